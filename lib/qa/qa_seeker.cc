/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * seeker and simulation against the paper's analysis (Sec. III-B) and its reference
 * scenario: the Stage-2 error recursion, Stage-1 accuracy, convergence from any heading,
 * robustness to invalid and missing measurements, and eq. 4.
 */

#include "model_loop.h"
#include <gr-rfseek/rng.h>
#include <gr-rfseek/seeker.h>
#include <gr-rfseek/simulation.h>
#include <gr-rfseek/tone_estimator.h>
#include <gr-rfseek/world.h>
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <vector>

using namespace gr::rfseek;

namespace {

constexpr double DEG = M_PI / 180.0;

scenario clean()
{
    scenario s;
    s.num_scatterers = 0;
    s.add_noise = false;
    s.cfo_hz = 250.0;
    s.cfo_drift_hz_per_s = 0.0;
    s.cfo_walk_hz_per_sqrt_s = 0.0;
    s.heading_noise_rad = 0.0;
    s.start_angle_rad = 0.3;
    return s;
}

measurement
measure(const world& w, tone_estimator& est, std::vector<std::complex<float>>& buf)
{
    w.synthesize(buf.data(), buf.size());
    const auto e = est.estimate(buf.data());
    measurement m;
    m.slot = w.slot();
    m.time_s = w.time_s();
    m.freq_hz = e.freq_hz;
    m.valid = e.valid;
    m.has_heading = true;
    m.heading_rad = w.measured_heading_rad();
    return m;
}

// Runs the loop until the seeker reports Stage 2 (the Stage-1 decision); returns
// theta_0 minus the true bearing at that moment.
double stage1_error(const scenario& sc)
{
    world w(sc);
    tone_estimator est(sc.samp_rate_hz, sc.window_len, sc.fft_len);
    auto sk = seeker::make(simulation::seeker_for(sc, "paper"));
    std::vector<std::complex<float>> buf(sc.window_len);
    for (int k = 0; k < 5000; ++k) {
        const command c = sk->update(measure(w, est, buf));
        if (c.stage == 2)
            return world::wrap(c.theta_est_rad - w.bearing_to_emitter_rad());
        w.advance(c.heading_rad);
    }
    ADD_FAILURE() << "no Stage-1 decision";
    return M_PI;
}

} // namespace

TEST(seeker, stage2_step_follows_the_error_recursion)
{
    // theta~_{k+1} = theta~_k - 2 sin(theta~_k) sin(delta) delta  (Sec. III-B, eq. 6)
    const double delta = 10.0 * DEG;
    for (double err_deg : { 5.0, 20.0, 45.0, 90.0, 120.0, 150.0, 170.0, -30.0, -100.0 }) {
        scenario sc = clean();
        sc.initial_distance_m = 50000.0; // far field: the bearing barely moves in a step
        sc.success_radius_m = 200.0;
        world w(sc);
        const double bearing = w.bearing_to_emitter_rad();
        seeker_config cfg = simulation::seeker_for(sc, "paper_no_circle");
        cfg.initial_heading_rad = bearing + err_deg * DEG;
        auto sk = seeker::make(cfg);
        tone_estimator est(
            sc.samp_rate_hz, sc.window_len, sc.fft_len, "rectangular", "newton");
        std::vector<std::complex<float>> buf(sc.window_len);
        const double theta0 = world::wrap(*cfg.initial_heading_rad);
        double theta1 = theta0, bearing1 = bearing;
        for (int k = 0; k < 100; ++k) {
            const command c = sk->update(measure(w, est, buf));
            if (c.update) {
                theta1 = c.theta_est_rad;
                bearing1 = w.bearing_to_emitter_rad();
                break;
            }
            w.advance(c.heading_rad);
        }
        const double e0 = world::wrap(theta0 - bearing);
        const double predicted = -2.0 * std::sin(e0) * std::sin(delta) * delta;
        const double change = world::wrap(theta1 - theta0);
        EXPECT_NEAR(change, predicted, 0.05 * std::abs(predicted)) << "error " << err_deg;
        const double e1 = world::wrap(theta1 - bearing1);
        EXPECT_NEAR(e1, e0 + predicted, 0.05 * std::abs(predicted) + 1e-3)
            << "error " << err_deg;
    }
}

namespace {

// `paper` in the noise-free model loop (far-field Doppler f = c + A cos(psi - beta)
// exactly, A = f_d,max, psi the heading flown, turns instantaneous), with the bearing
// fixed through Stage 1 and beta0 + turn(tau) from then on (tau: seconds into Stage 2),
// as when the wind carries the vehicle sideways near the emitter. Returns, at every
// Stage-2 update, theta_est - beta and the probe half-angle delta_k of the step it
// starts.
struct turning_run {
    std::vector<double> errors;
    std::vector<double> deltas;
};

template <typename Turn>
turning_run fly_turning_bearing(Turn turn, double delta_max_rad, int updates)
{
    seeker_config cfg;
    cfg.strategy = "paper";
    cfg.delta_max_rad = delta_max_rad;
    qa::model_loop loop(cfg, 0.0);
    loop.cfo = 300.0;
    const double beta0 = 0.7;
    double t_stage2 = -1.0;
    turning_run out;
    while (loop.slot < 200000 && static_cast<int>(out.errors.size()) < updates) {
        const double t = loop.slot * cfg.slot_period_s;
        loop.beta = beta0 + (t_stage2 < 0.0 ? 0.0 : turn(t - t_stage2));
        const command c = loop.step();
        if (c.stage == 2 && t_stage2 < 0.0)
            t_stage2 = t;
        if (c.stage == 2 && c.update && t > t_stage2) {
            out.errors.push_back(world::wrap(c.theta_est_rad - loop.beta));
            out.deltas.push_back(std::abs(world::wrap(c.heading_rad - c.theta_est_rad)));
        }
    }
    return out;
}

} // namespace

TEST(seeker, paper_delta_k_follows_a_bearing_that_turns)
{
    // A bearing turning by w = omega * 2 M T_slot per step. With a fixed delta, eq. 5
    // turns at most 2 delta sin(delta) = 0.061 rad per step (10 deg): at w = 0.08 it
    // cannot follow and slips. With delta_k up to 20 deg it turns up to 0.24 rad per
    // step and follows with a steady error of about 16 deg.
    const double step_s = 2 * 20 * 0.05;
    const double w = 0.08, omega = w / step_s;
    const auto turn = [omega](double tau) { return omega * tau; };
    const auto fixed = fly_turning_bearing(turn, 0.0, 300);
    const auto tracked = fly_turning_bearing(turn, 20.0 * DEG, 300);
    ASSERT_EQ(tracked.errors.size(), 300u);
    double worst_fixed = 0.0;
    for (double e : fixed.errors)
        worst_fixed = std::max(worst_fixed, std::abs(e));
    EXPECT_GT(worst_fixed, 90.0 * DEG) << "fixed delta should slip";

    // The fixed point of eq. 5 with delta_k = clamp(|measured error|, 10, 20 deg),
    // computed slot by slot: the + half is M slots at theta + delta_k while the bearing
    // turns on, then M at theta - delta_k; the error is taken at the step's last
    // measurement. (The seeker's growth limits shape the way in, not the fixed point.)
    const double a = seeker_config().max_doppler_hz(), T = 0.05;
    const int M = 20;
    double theta = 0.0, d = 10.0 * DEG, t = 0.0, steady = 0.0;
    for (int k = 0; k < 400; ++k) {
        double fp = 0.0, fm = 0.0;
        for (int j = 0; j < 2 * M; ++j, t += T)
            (j < M ? fp : fm) += a * std::cos(theta + (j < M ? d : -d) - omega * t) / M;
        theta += (fp - fm) * d / a;
        d = std::clamp(
            std::asin(std::min(1.0, std::abs(fp - fm) / (2 * a * std::sin(d)))),
            10.0 * DEG,
            20.0 * DEG);
        if (k >= 300)
            steady += (omega * (t - T) - theta) / 100.0;
    }
    double mean = 0.0;
    for (int k = 200; k < 300; ++k) {
        // lagging behind the turning bearing: theta_est - beta < 0 for omega > 0
        EXPECT_LT(std::abs(tracked.errors[k]), 30.0 * DEG) << "update " << k;
        mean += tracked.errors[k] / 100.0;
    }
    EXPECT_NEAR(-mean, steady, 0.5 * DEG) << "steady error " << steady / DEG << " deg";
}

TEST(seeker, paper_delta_k_stays_delta_while_the_error_is_small)
{
    // A bearing that does not turn: after Stage 1 (exact here) every measured error is
    // below delta, so every probe is the paper's delta: the reference flights are the
    // paper's Stage 2.
    const auto r = fly_turning_bearing([](double) { return 0.0; }, 20.0 * DEG, 100);
    ASSERT_EQ(r.deltas.size(), 100u);
    for (double d : r.deltas)
        EXPECT_NEAR(d, 10.0 * DEG, 1e-9);
    for (double e : r.errors)
        EXPECT_LT(std::abs(e), 2.0 * DEG);
}

TEST(seeker, paper_delta_k_grows_slowly_and_returns_to_delta)
{
    // The bearing jumps 60 deg as Stage 2 begins. The probe stays delta until
    // delta_after_steps (3) updates in a row have measured an error beyond delta; then
    // delta_k grows by at most delta_step (1 deg) per step, never beyond delta_max (20
    // deg), never beyond the error just measured, and is delta again once a step
    // measures less than delta.
    const auto r = fly_turning_bearing(
        [](double tau) { return tau > 0.0 ? 60.0 * DEG : 0.0; }, 20.0 * DEG, 200);
    ASSERT_EQ(r.deltas.size(), 200u);
    for (int k = 0; k < 2; ++k)
        EXPECT_NEAR(r.deltas[k], 10.0 * DEG, 1e-9) << "update " << k;
    EXPECT_NEAR(r.deltas[2], 11.0 * DEG, 1e-9); // the third in a row: one step up
    double largest = 0.0;
    for (std::size_t k = 1; k < r.deltas.size(); ++k) {
        EXPECT_LE(r.deltas[k] - r.deltas[k - 1], 1.0 * DEG + 1e-9) << "update " << k;
        EXPECT_LE(r.deltas[k], 20.0 * DEG + 1e-9);
        // never beyond the error: the error before update k is the one after update k-1
        // (the bearing no longer moves), so delta_k <= max(delta, |that error|)
        EXPECT_LE(r.deltas[k], std::max(10.0 * DEG, std::abs(r.errors[k - 1])) + 1e-6)
            << "update " << k;
        largest = std::max(largest, r.deltas[k]);
    }
    EXPECT_GT(largest, 15.0 * DEG);
    // Converged: the error and the probe are the paper's again.
    EXPECT_LT(std::abs(r.errors.back()), 1.0 * DEG);
    EXPECT_NEAR(r.deltas.back(), 10.0 * DEG, 1e-9);
    // It converges faster than with delta fixed: the error after 20 steps.
    const auto fixed = fly_turning_bearing(
        [](double tau) { return tau > 0.0 ? 60.0 * DEG : 0.0; }, 0.0, 200);
    EXPECT_LT(std::abs(r.errors[20]), std::abs(fixed.errors[20]));
}

TEST(seeker, reaches_dv_from_any_initial_heading)
{
    for (double err_deg : { 0.0, 60.0, -90.0, 135.0, 170.0, -175.0 }) {
        scenario sc = clean();
        sc.initial_distance_m = 2000.0;
        world w0(sc);
        seeker_config cfg = simulation::seeker_for(sc, "paper_no_circle");
        cfg.initial_heading_rad = w0.bearing_to_emitter_rad() + err_deg * DEG;
        const auto r = simulation(sc, cfg).run(false);
        EXPECT_TRUE(r.summary.success) << "initial error " << err_deg;
    }
}

TEST(seeker, stage1_line_of_sight_within_3_degrees)
{
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        scenario sc = clean();
        sc.seed = seed;
        sc.start_angle_rad.reset();
        const double e = stage1_error(sc);
        EXPECT_LE(std::abs(e), 3.0 * DEG) << "seed " << seed << ": " << e / DEG << " deg";
    }
}

TEST(seeker, stage1_reference_scenario_within_20_degrees_in_90_percent)
{
    int within = 0;
    const int seeds = 40;
    for (int seed = 1; seed <= seeds; ++seed) {
        scenario sc;
        sc.seed = seed;
        if (std::abs(stage1_error(sc)) <= 20.0 * DEG)
            ++within;
    }
    EXPECT_GE(within, 0.9 * seeds);
}

TEST(seeker, reference_scenario_20_seeds)
{
    double sum = 0.0;
    for (int seed = 1; seed <= 20; ++seed) {
        scenario sc;
        sc.seed = seed;
        const auto r = simulation(sc, simulation::seeker_for(sc, "paper")).run(false);
        EXPECT_TRUE(r.summary.success) << "seed " << seed;
        // Never shorter than the straight line plus the Stage-1 circle (2 pi 100 m).
        EXPECT_GE(r.summary.distance_m, sc.shortest_path_m() + 2 * M_PI * 100.0 - 1.0);
        sum += r.summary.ratio;
    }
    EXPECT_LT(sum / 20.0, 1.25);
}

TEST(seeker, invalid_measurements_and_a_gap_do_not_derail_it)
{
    scenario sc;
    sc.seed = 4;
    world w(sc);
    tone_estimator est(sc.samp_rate_hz, sc.window_len, sc.fft_len);
    auto sk = seeker::make(simulation::seeker_for(sc, "paper"));
    std::vector<std::complex<float>> buf(sc.window_len);
    double heading = w.heading_rad();
    int held = 0;
    while (!w.finished()) {
        const std::uint64_t k = w.slot();
        const bool gap = k >= 3000 && k < 3040;            // 2 s without measurements
        const bool invalid_run = k >= 5000 && k < 5060;    // 3 s of invalid ones
        const bool sporadic = (k * 2654435761u) % 100 < 5; // 5 % invalid
        if (!gap) {
            measurement m = measure(w, est, buf);
            if (invalid_run || sporadic) {
                m.valid = false;
                m.freq_hz = std::nan("");
            }
            const command c = sk->update(m);
            ASSERT_TRUE(std::isfinite(c.heading_rad));
            if (c.holding) {
                ++held;
                EXPECT_NEAR(world::wrap(c.heading_rad - c.theta_est_rad), 0.0, 1e-12);
            }
            heading = c.heading_rad;
        }
        w.advance(heading); // through the gap the vehicle holds its last command
    }
    EXPECT_TRUE(w.arrived());
    EXPECT_GE(held, 60 - 10); // held course through most of the invalid run
    EXPECT_LT(w.distance_flown_m(), 1.3 * sc.shortest_path_m());
}

TEST(seeker, eq4_rejects_an_outlier_and_relocks)
{
    seeker_config cfg;
    cfg.strategy = "paper_no_circle";
    cfg.initial_heading_rad = 0.0;
    auto sk = seeker::make(cfg);
    auto feed = [&](std::uint64_t slot, double f, double snr_db = 0.0) {
        measurement m;
        m.slot = slot;
        m.freq_hz = f;
        m.snr_db = snr_db;
        m.valid = true;
        return sk->update(m);
    };
    ASSERT_EQ(cfg.lock_count, 3);
    // Initialisation (issue 9): an outlier first measurement does not set the filter, nor
    // does any single value; it locks once lock_count consecutive values agree.
    EXPECT_FALSE(feed(0, 40000.0).accepted);
    EXPECT_FALSE(feed(1, 100.0).accepted);
    EXPECT_FALSE(feed(2, 105.0).accepted);
    const command lock = feed(3, 110.0);
    EXPECT_TRUE(lock.accepted);
    EXPECT_EQ(lock.filtered_freq_hz, 110.0);
    const command out = feed(4, 900.0); // outlier: replaced by the last accepted value
    EXPECT_FALSE(out.accepted);
    EXPECT_EQ(out.filtered_freq_hz, 110.0);
    // The sample after the outlier is compared with the last accepted value, not with
    // the outlier (the literal eq. 4 would let the outlier through here).
    const command next = feed(5, 115.0);
    EXPECT_TRUE(next.accepted);
    EXPECT_EQ(next.filtered_freq_hz, 115.0);
    // A value whose estimated SNR is below min_snr_db is no candidate, even when it
    // agrees with the reference.
    const command weak = feed(6, 116.0, cfg.min_snr_db - 1.0);
    EXPECT_FALSE(weak.accepted);
    EXPECT_EQ(weak.filtered_freq_hz, 115.0);
    // A lasting jump (e.g. the CFO re-tuned) is re-acquired after relock_count samples.
    int k = 7;
    command c;
    for (int i = 0; i < cfg.relock_count; ++i) {
        c = feed(k++, 600.0 + i);
        if (i + 1 < cfg.relock_count) {
            EXPECT_FALSE(c.accepted);
        }
    }
    EXPECT_TRUE(c.accepted);
    EXPECT_EQ(c.filtered_freq_hz, 600.0 + cfg.relock_count - 1);

    // Weak values never lock the filter.
    sk = seeker::make(cfg);
    for (int i = 0; i < 10; ++i)
        EXPECT_FALSE(feed(i, 100.0, cfg.min_snr_db - 0.5).accepted);

    cfg.literal_eq4 = true;
    sk = seeker::make(cfg);
    EXPECT_TRUE(feed(0, 40000.0).accepted); // as printed: the first value sets the filter
    EXPECT_FALSE(feed(1, 100.0).accepted);
    sk = seeker::make(cfg);
    feed(0, 100.0);
    EXPECT_FALSE(feed(1, 900.0).accepted);
    const command lit = feed(2, 105.0); // compared with 900: rejected, 900 substituted
    EXPECT_FALSE(lit.accepted);
    EXPECT_EQ(lit.filtered_freq_hz, 900.0);
}

TEST(seeker, finite_turn_rate_excludes_turning_slots_and_succeeds)
{
    scenario sc;
    sc.seed = 2;
    sc.turn_rate_rad_per_s = 30.0 * DEG;
    const auto r = simulation(sc, simulation::seeker_for(sc, "paper")).run(true);
    EXPECT_TRUE(r.summary.success);
    // The vehicle never turned faster than its limit.
    for (std::size_t i = 1; i < r.records.size(); ++i)
        EXPECT_LE(std::abs(world::wrap(r.records[i].heading_rad -
                                       r.records[i - 1].heading_rad)),
                  sc.turn_rate_rad_per_s * sc.slot_period_s + 1e-9);
}

TEST(seeker, bad_configuration_names_the_field)
{
    seeker_config c;
    c.strategy = "gradient";
    EXPECT_THROW(seeker::make(c), std::invalid_argument);
    for (auto mutate : std::vector<void (*)(seeker_config&)>{
             [](seeker_config& s) { s.delta_rad = 0.0; },
             [](seeker_config& s) { s.m_slots = 0; },
             [](seeker_config& s) { s.circle_radius_m = -1.0; },
             [](seeker_config& s) { s.speed_mps = 0.0; },
             [](seeker_config& s) { s.moving_average_len = 0; },
             [](seeker_config& s) { s.turn_rate_rad_per_s = -1.0; },
             [](seeker_config& s) { s.delta_max_rad = 2.0; } }) {
        seeker_config s;
        mutate(s);
        try {
            s.validate();
            ADD_FAILURE() << "accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("seeker_config."), std::string::npos);
        }
    }
}

TEST(seeker, bad_delta_k_configuration_names_the_field_and_range)
{
    const std::vector<std::pair<std::string, void (*)(seeker_config&)>> cases = {
        { "delta_max_rad", [](seeker_config& s) { s.delta_max_rad = 2.0; } },
        { "delta_max_rad", [](seeker_config& s) { s.delta_max_rad = std::nan(""); } },
        { "delta_step_rad", [](seeker_config& s) { s.delta_step_rad = 0.0; } },
        { "delta_after_steps", [](seeker_config& s) { s.delta_after_steps = 0; } },
    };
    for (const auto& [name, mutate] : cases) {
        seeker_config s;
        mutate(s);
        try {
            s.validate();
            ADD_FAILURE() << name << " accepted";
        } catch (const std::invalid_argument& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("seeker_config." + name), std::string::npos) << what;
            EXPECT_NE(what.find("in "), std::string::npos) << what; // the range
        }
    }
    seeker_config fixed; // at or below delta: delta fixed, valid
    fixed.delta_max_rad = 0.0;
    EXPECT_NO_THROW(fixed.validate());
}

TEST(rss_baseline, uses_only_power_and_is_deterministic)
{
    // Same powers, different frequencies: the same commands.
    auto run = [](double freq_scale) {
        seeker_config cfg;
        cfg.strategy = "rss_baseline";
        cfg.seed = 5;
        auto sk = seeker::make(cfg);
        rng g(9);
        std::vector<double> out;
        for (std::uint64_t k = 0; k < 4000; ++k) {
            measurement m;
            m.slot = k;
            m.valid = true;
            m.power_db = -70.0 + 3.0 * g.normal();
            m.freq_hz = freq_scale * g.normal();
            m.has_heading = true;
            m.heading_rad = 0.3;
            out.push_back(sk->update(m).heading_rad);
        }
        return out;
    };
    EXPECT_EQ(run(1.0), run(1000.0));
}

TEST(rss_baseline, scan_finds_the_line_of_sight_axis)
{
    // The fading rate is smallest along the line of sight: the first scan circle's axis
    // (direction mod pi) points at the emitter.
    int within = 0;
    const int seeds = 10;
    for (int seed = 1; seed <= seeds; ++seed) {
        scenario sc;
        sc.seed = seed;
        world w(sc);
        tone_estimator est(sc.samp_rate_hz, sc.window_len, sc.fft_len);
        auto sk = seeker::make(simulation::seeker_for(sc, "rss_baseline"));
        std::vector<std::complex<float>> buf(sc.window_len);
        for (int k = 0; k < 3000; ++k) {
            w.synthesize(buf.data(), buf.size());
            const auto e = est.estimate(buf.data());
            measurement m;
            m.slot = w.slot();
            m.valid = e.valid;
            m.power_db = e.power_db;
            m.has_heading = true;
            m.heading_rad = w.measured_heading_rad();
            const command c = sk->update(m);
            if (c.update) {
                const double err =
                    world::wrap(c.theta_est_rad - w.bearing_to_emitter_rad());
                const double axis_err = std::abs(world::wrap(2.0 * err)) / 2.0; // mod pi
                if (axis_err <= 10.0 * DEG)
                    ++within;
                break;
            }
            w.advance(c.heading_rad);
        }
    }
    EXPECT_GE(within, 8);
}

TEST(seeker, config_set_by_name)
{
    seeker_config c;
    c.set("delta_deg", "15");
    EXPECT_NEAR(c.delta_rad, 15.0 * DEG, 1e-15);
    c.set("m_slots", "30");
    EXPECT_EQ(c.m_slots, 30);
    c.set("delta_max_deg", "25");
    EXPECT_NEAR(c.delta_max_rad, 25.0 * DEG, 1e-15);
    c.set("delta_step_deg", "2");
    EXPECT_NEAR(c.delta_step_rad, 2.0 * DEG, 1e-15);
    c.set("delta_after_steps", "4");
    EXPECT_EQ(c.delta_after_steps, 4);
    c.set("strategy", "rss_baseline");
    EXPECT_EQ(c.strategy, "rss_baseline");
    c.set("literal_eq4", "true");
    EXPECT_TRUE(c.literal_eq4);
    c.set("initial_heading_rad", "0.5");
    ASSERT_TRUE(c.initial_heading_rad.has_value());
    c.set("initial_heading_rad", "none");
    EXPECT_FALSE(c.initial_heading_rad.has_value());
    EXPECT_NO_THROW(c.validate());
    EXPECT_THROW(c.set("m_slots", "2.5"), std::invalid_argument);
    EXPECT_THROW(c.set("delta_deg", "wide"), std::invalid_argument);
    EXPECT_THROW(c.set("gain", "1"), std::invalid_argument);
    for (const auto& k : seeker_config::keys())
        EXPECT_NO_THROW(seeker_config().set(k, k == "strategy" ? "paper" : "1")) << k;
}
