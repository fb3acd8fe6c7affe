/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * turn_model and the world's coordinated turn against closed forms: the time to
 * change the heading by 2 delta (roll in, hold the bank, roll out), the radius at the
 * bank limit (v^2 / (g tan(bank))), no overshoot, and the scenario's limits checked.
 */

#include "turn_model.h"
#include <gr-rfseek/simulation.h>
#include <gr-rfseek/world.h>
#include <gtest/gtest.h>
#include <cmath>
#include <stdexcept>
#include <vector>

using gr::rfseek::coordinated_turn;
using gr::rfseek::scenario;
using gr::rfseek::turn_limits;
using gr::rfseek::world;

namespace {

constexpr double DEG = M_PI / 180.0;
constexpr double G = 9.80665;

turn_limits fixed_wing(double v)
{
    turn_limits l;
    l.bank_rad = 30.0 * DEG;
    l.roll_rate_rad_per_s = 60.0 * DEG;
    l.speed_mps = v;
    return l;
}

// Steps of dt toward `target` from heading 0 until aligned and level; returns the time.
double stepped_time(const turn_limits& lim, double target, double dt, double* overshoot)
{
    coordinated_turn t(lim, 0.0);
    double worst = 0.0;
    for (int i = 1; i < 100000; ++i) {
        t.step(target, dt);
        // Beyond the target, in the turn's direction: how far it overshot.
        worst = std::max(worst, std::copysign(1.0, target) * (t.heading_rad() - target));
        if (!t.turning()) {
            if (overshoot)
                *overshoot = worst;
            return i * dt;
        }
    }
    return -1.0;
}

} // namespace

TEST(TurnModel, SteadyLimitsAreTheBankAndRateFormulas)
{
    turn_limits l = fixed_wing(25.0);
    EXPECT_NEAR(l.max_rate(), G * std::tan(30.0 * DEG) / 25.0, 1e-12);
    EXPECT_NEAR(l.min_radius_m(), 25.0 * 25.0 / (G * std::tan(30.0 * DEG)), 1e-9);
    l.rate_rad_per_s = 0.1; // the tighter limit wins
    EXPECT_DOUBLE_EQ(l.max_rate(), 0.1);
    EXPECT_NEAR(l.max_bank(), std::atan(0.1 * 25.0 / G), 1e-12);
    turn_limits r; // a plain rate limit: the arc's time
    r.rate_rad_per_s = 0.5;
    EXPECT_FALSE(r.rolls());
    EXPECT_DOUBLE_EQ(r.change_time_s(1.0), 2.0);
    EXPECT_DOUBLE_EQ(turn_limits().change_time_s(1.0), 0.0);
    // The stepped model is the coordinated turn only (the world flies the plain arc).
    coordinated_turn plain(r, 0.0);
    EXPECT_THROW(plain.step(1.0, 0.05), std::logic_error);
}

TEST(TurnModel, ReversalTimeMatchesTheClosedForm)
{
    // Reversals of 2 delta, short (the bank limit is never reached) and long, at the
    // speeds of the fixed-wing presets; the stepped model ends within a slot of the
    // closed form and never overshoots the command.
    const double dt = 0.05;
    for (double v : { 10.0, 15.0, 25.0 }) {
        const turn_limits l = fixed_wing(v);
        for (double delta_deg : { 1.0, 3.0, 10.0, 20.0, 60.0 }) {
            const double a = 2.0 * delta_deg * DEG;
            double over = 1.0;
            const double t = stepped_time(l, a, dt, &over);
            // t counts whole slots; the stepped law decides per eighth of a slot.
            EXPECT_GE(t, l.change_time_s(a) - dt / 8.0)
                << "v " << v << " d " << delta_deg;
            EXPECT_LE(t, l.change_time_s(a) + dt + dt / 4.0)
                << "v " << v << " delta " << delta_deg;
            EXPECT_LT(over, 1e-6) << "v " << v << " delta " << delta_deg;
            double over_neg = 1.0;
            EXPECT_DOUBLE_EQ(stepped_time(l, -a, dt, &over_neg), t); // symmetric
        }
    }
    // Independently of the model's own formula: a short reversal is two rolls of
    // duration tau = T / 2 each, turning 2 (g / (v p)) (-ln cos(p tau)).
    const turn_limits l = fixed_wing(25.0);
    const double a = 4.0 * DEG, T = l.change_time_s(a);
    const double p = 60.0 * DEG;
    EXPECT_LT(p * T / 2.0, 30.0 * DEG); // the bank limit is not reached
    EXPECT_NEAR(2.0 * G / (25.0 * p) * -std::log(std::cos(p * T / 2.0)), a, 1e-12);
}

TEST(TurnModel, WorldFliesTheBankLimitedCircle)
{
    // A command always 90 deg ahead: after the roll the world flies a circle of radius
    // v^2 / (g tan(bank)), at the preset's bank (ArduPlane's effective 24.8 deg).
    scenario sc;
    sc.apply_preset("fixedwing25");
    const double bank = sc.bank_limit_rad;
    EXPECT_NEAR(bank, 24.8 * DEG, 1e-12);
    sc.add_noise = false;
    sc.heading_noise_rad = 0.0;
    sc.initial_distance_m = 100000.0;
    sc.flight_cap_m = 1e6;
    world w(sc);
    std::vector<double> xs, ys;
    for (int i = 0; i < 2000; ++i) {
        w.advance(w.heading_rad() + M_PI / 2.0);
        if (i >= 200) { // rolled in long ago
            xs.push_back(w.x_m());
            ys.push_back(w.y_m());
            EXPECT_NEAR(w.bank_rad(), bank, 1e-9);
        }
    }
    // Centre from the mean of the points over whole turns; radius from each point.
    const double radius = 25.0 * 25.0 / (G * std::tan(bank));
    const double period = 2.0 * M_PI * radius / 25.0 / sc.slot_period_s; // slots
    const std::size_t n = static_cast<std::size_t>(std::floor(2.0 * period));
    double cx = 0.0, cy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        cx += xs[i] / n;
        cy += ys[i] / n;
    }
    for (std::size_t i = 0; i < n; ++i)
        EXPECT_NEAR(std::hypot(xs[i] - cx, ys[i] - cy), radius, 0.01 * radius);
}

TEST(TurnModel, WorldRollsBeforeItTurns)
{
    // From wings level, the first slot of a turn rolls to p dt only: the heading moves
    // by the integral of g tan(p t) / v, far less than the steady rate would.
    scenario sc;
    sc.apply_preset("fixedwing15");
    sc.heading_noise_rad = 0.0;
    sc.start_heading_rad = 0.0;
    world w(sc);
    const double h0 = w.heading_rad();
    w.advance(h0 + 1.0);
    const double dt = sc.slot_period_s, p = sc.roll_rate_rad_per_s;
    const double exact = G / (15.0 * p) * -std::log(std::cos(p * dt));
    EXPECT_NEAR(w.heading_rad() - h0, exact, 0.02 * exact);
    EXPECT_NEAR(w.bank_rad(), p * dt, 1e-12);
    EXPECT_LT(w.heading_rad() - h0, 0.1 * G * std::tan(sc.bank_limit_rad) / 15.0 * dt);
}

TEST(TurnModel, LimitsAreChecked)
{
    scenario sc;
    sc.roll_rate_rad_per_s = 1.0; // a roll limit without a bank limit
    EXPECT_THROW(sc.validate(), std::invalid_argument);
    try {
        sc.validate();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("roll_rate_rad_per_s"), std::string::npos);
    }
    sc.roll_rate_rad_per_s = 0.0;
    sc.bank_limit_rad = 85.0 * DEG;
    EXPECT_THROW(sc.validate(), std::invalid_argument);
    sc.bank_limit_rad = 30.0 * DEG;
    EXPECT_NO_THROW(sc.validate());
    gr::rfseek::seeker_config c;
    c.bank_limit_rad = -0.1;
    EXPECT_THROW(c.validate(), std::invalid_argument);
    c.bank_limit_rad = 0.5;
    c.adaptive_turn_share = 0.0;
    EXPECT_THROW(c.validate(), std::invalid_argument);
    // The seeker is told the scenario's airframe.
    scenario f;
    f.apply_preset("fixedwing25");
    const auto k = gr::rfseek::simulation::seeker_for(f, "adaptive");
    EXPECT_DOUBLE_EQ(k.bank_limit_rad, f.bank_limit_rad);
    EXPECT_DOUBLE_EQ(k.roll_rate_rad_per_s, f.roll_rate_rad_per_s);
}
