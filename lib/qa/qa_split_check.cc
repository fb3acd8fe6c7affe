/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The fix's split check (emitter_locator::check_split, seeker_config::locate_split_gate):
 * the halves of the data in time fitted apart. Where the model holds, their disagreement
 * T follows the chi-square law with 2 degrees of freedom (mean 2, 5 % beyond 5.99); a
 * wind that changes half-way, which a constant-wind fit cannot follow, gives a large T
 * and an ellipse grown by exactly sqrt(T / 2); too little data, an invalid fit or a bad
 * gate leave the fix alone; in the closed loop the published fix is the unchecked one
 * with only its ellipse scaled.
 */

#include "arrival_fixtures.h"
#include <gr-rfseek/arrival.h>
#include <gr-rfseek/rng.h>
#include <gr-rfseek/scenario.h>
#include <gr-rfseek/seeker.h>
#include <gr-rfseek/simulation.h>
#include <gtest/gtest.h>
#include <cmath>
#include <stdexcept>
#include <string>

using namespace gr::rfseek;
using namespace gr::rfseek::qa;

namespace {

/*
 * Two orbits of 25 m flown in the air frame around (15, 10) m from the emitter, 100 m
 * up: the locator gets the air-frame positions and velocities, the frequencies the
 * ground geometry makes (+ CFO 500 Hz + 0.2 Hz/s + white noise of 1 Hz). The wind is
 * (wx, wy) until half-way and (wx2, wy2) from there. Returns the locator and the fix.
 */
struct flown {
    emitter_locator loc;
    emitter_location fix;
};

flown fly(
    std::uint64_t seed, double wx, double wy, double wx2, double wy2, int orbits = 2)
{
    constexpr double R = 25.0, H = 100.0, OX = 15.0, OY = 10.0;
    flown f{ emitter_locator(LAMBDA, 600.0, 0.0, 5.0, H, 10.0), emitter_location() };
    rng g(seed, 12, 0);
    const double w = V / R;
    const int n = static_cast<int>(orbits * 2.0 * M_PI / w / T);
    double gx = OX, gy = OY - R; // ground position, emitter at the origin
    double qx = 0.0, qy = 0.0;   // dead-reckoned (air frame)
    for (int k = 0; k <= n; ++k) {
        const double t = k * T, a = w * t;
        const bool second = 2 * k > n;
        const double ux = second ? wx2 : wx, uy = second ? wy2 : wy;
        const double vx = V * std::cos(a), vy = V * std::sin(a);
        const double s = std::sqrt(gx * gx + gy * gy + H * H);
        const double dop = ((vx + ux) * -gx + (vy + uy) * -gy) / (LAMBDA * s);
        f.loc.add(t, qx, qy, vx, vy, 500.0 + 0.2 * t + dop + g.normal());
        if (k < n) {
            qx += vx * T;
            qy += vy * T;
            gx += (vx + ux) * T;
            gy += (vy + uy) * T;
        }
    }
    f.fix = f.loc.fit(qx, qy);
    return f;
}

} // namespace

TEST(split_check, honest_ellipses_give_chi_square_with_two_degrees_of_freedom)
{
    // Constant wind, white noise: the model holds. Over 40 seeds the mean of T is near
    // 2 and few exceed the 95 % point; the ellipse is then left as it was.
    const int seeds = 40;
    double sum = 0.0;
    int beyond = 0, checked = 0;
    for (int seed = 0; seed < seeds; ++seed) {
        flown f = fly(seed, 3.0, -2.0, 3.0, -2.0);
        ASSERT_TRUE(f.fix.valid) << seed;
        emitter_location l = f.fix;
        ASSERT_TRUE(f.loc.check_split(l, 5.99)) << seed;
        ++checked;
        sum += l.consistency;
        if (l.consistency > 5.99) {
            ++beyond;
        } else {
            EXPECT_EQ(l.major_m, f.fix.major_m);
            EXPECT_EQ(l.minor_m, f.fix.minor_m);
        }
        EXPECT_EQ(l.east_m, f.fix.east_m); // the position is never moved
        EXPECT_EQ(l.north_m, f.fix.north_m);
    }
    const double mean = sum / checked;
    // chi-square(2): mean 2, std of the mean 2 / sqrt(40) = 0.32.
    EXPECT_GT(mean, 1.0);
    EXPECT_LT(mean, 3.3);
    EXPECT_LE(beyond, 6); // 5 % expected: 2 of 40
}

TEST(split_check, a_wind_change_the_fit_cannot_follow_grows_the_ellipse)
{
    // The wind turns from (3, -2) to (-2, 3) m/s half-way: the constant-wind fit
    // averages two winds, its halves disagree by tens of metres against ellipses of a
    // few. T is far beyond the gate, and the ellipse grows by exactly sqrt(T / 2).
    int caught = 0;
    for (int seed = 0; seed < 5; ++seed) {
        flown f = fly(seed, 3.0, -2.0, -2.0, 3.0);
        ASSERT_TRUE(f.fix.valid) << seed;
        emitter_location l = f.fix;
        ASSERT_TRUE(f.loc.check_split(l, 5.99)) << seed;
        caught += l.consistency > 5.99;
        const double k = l.consistency > 5.99 ? std::sqrt(0.5 * l.consistency) : 1.0;
        EXPECT_NEAR(l.major_m, k * f.fix.major_m, 1e-9 * l.major_m) << seed;
        EXPECT_NEAR(l.minor_m, k * f.fix.minor_m, 1e-9 * l.minor_m) << seed;
        EXPECT_NEAR(l.wind_sigma_mps, k * f.fix.wind_sigma_mps, 1e-9) << seed;
        // gate 0: measured, nothing grown; the same T.
        emitter_location m = f.fix;
        ASSERT_TRUE(f.loc.check_split(m, 0.0));
        EXPECT_EQ(m.consistency, l.consistency);
        EXPECT_EQ(m.major_m, f.fix.major_m);
        // A gate above T: measured, nothing grown.
        emitter_location h = f.fix;
        ASSERT_TRUE(f.loc.check_split(h, l.consistency + 1.0));
        EXPECT_EQ(h.major_m, f.fix.major_m);
    }
    EXPECT_EQ(caught, 5);
}

TEST(split_check, too_little_data_an_invalid_fix_or_a_bad_gate_change_nothing)
{
    // One orbit (314 measurements) is enough: two halves of 157.
    flown f = fly(1, 3.0, -2.0, 3.0, -2.0, 1);
    ASSERT_TRUE(f.fix.valid);
    emitter_location l = f.fix;
    EXPECT_TRUE(f.loc.check_split(l, 5.99));
    EXPECT_GE(l.consistency, 0.0);
    // 150 measurements: under 100 in a half.
    flown g = fly(1, 3.0, -2.0, 3.0, -2.0, 2);
    emitter_locator few(LAMBDA);
    for (int k = 0; k < 150; ++k)
        few.add(k * T, k, 0.0, V, 0.0, 100.0 + 0.1 * k);
    emitter_location any = g.fix;
    EXPECT_FALSE(few.check_split(any, 5.99));
    EXPECT_EQ(any.consistency, -1.0);
    EXPECT_EQ(any.major_m, g.fix.major_m);
    emitter_location invalid;
    EXPECT_FALSE(g.loc.check_split(invalid, 5.99));
    EXPECT_EQ(invalid.consistency, -1.0);
    for (double bad : { -1.0, double(NAN) }) {
        emitter_location b = g.fix;
        EXPECT_FALSE(g.loc.check_split(b, bad));
        EXPECT_EQ(b.consistency, -1.0);
        EXPECT_EQ(b.major_m, g.fix.major_m);
    }
    seeker_config c;
    EXPECT_EQ(c.locate_split_gate, 5.99);
    c.locate_split_gate = 0.0;
    EXPECT_NO_THROW(c.validate());
    for (double bad : { -0.5, double(NAN), 2e6 }) {
        c.locate_split_gate = bad;
        try {
            c.validate();
            ADD_FAILURE() << bad;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("locate_split_gate"), std::string::npos);
        }
    }
}

TEST(split_check, the_closed_loop_publishes_the_same_fix_with_only_its_ellipse_scaled)
{
    // The check changes the fix's ellipse only: with it off the very same fix is
    // published, and with it on the ellipse is that one's, grown by sqrt(T / 2) where T
    // passes the gate. (The grown ellipse also decides whether the fix is sure: with no
    // limit on the ellipse, the flights are the same.)
    for (std::uint64_t seed : { 3, 4 }) {
        auto [sc, cfg] = unlimited_fix_flight(seed);
        const run_result on = simulation(sc, cfg).run(false);
        cfg.locate_split_gate = 0.0;
        const run_result off = simulation(sc, cfg).run(false);
        ASSERT_TRUE(on.summary.located && off.summary.located) << seed;
        EXPECT_EQ(off.location.consistency, -1.0);
        ASSERT_GE(on.location.consistency, 0.0) << seed;
        EXPECT_EQ(on.location.east_m, off.location.east_m);
        EXPECT_EQ(on.summary.location_error_m, off.summary.location_error_m);
        EXPECT_EQ(on.summary.distance_m, off.summary.distance_m);
        const double T = on.location.consistency;
        const double k = T > 5.99 ? std::sqrt(0.5 * T) : 1.0;
        EXPECT_NEAR(on.location.major_m, k * off.location.major_m, 1e-9 * k) << seed;
    }
}
