/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * doppler_fit (the fits behind the adaptive strategy and the paper's least-squares Stage
 * 1) against noise-free frequencies from the model f = A cos(psi - beta) + f_o + d t: the
 * model-inverting gain, the away resolution and the cancellation of a linear CFO drift.
 */

#include "doppler_fit.h"
#include <gr-rfseek/world.h>
#include <gtest/gtest.h>
#include <cmath>
#include <random>
#include <vector>

using namespace gr::rfseek;

namespace {

constexpr double DEG = M_PI / 180.0;
constexpr double A = 66.7128190396304; // f_d,max at 10 m/s, 2 GHz

double model(double psi, double beta, double t, double cfo = 250.0, double drift = 0.0)
{
    return A * std::cos(psi - beta) + cfo + drift * t;
}

// One probe cycle of segments at theta + sign * delta, m slots each, 0.05 s apart.
std::vector<doppler_sample> cycle(double theta,
                                  double delta,
                                  double beta,
                                  std::vector<double> signs,
                                  double drift,
                                  int m = 10,
                                  double t0 = 100.0)
{
    std::vector<doppler_sample> s;
    double t = t0;
    for (double sign : signs)
        for (int i = 0; i < m; ++i, t += 0.05) {
            const double psi = theta + sign * delta;
            s.push_back(doppler_sample{ psi, t, model(psi, beta, t, 250.0, drift) });
        }
    return s;
}

} // namespace

TEST(doppler_fit, probe_difference_inverts_the_model_in_one_step)
{
    const double delta = 10.0 * DEG;
    for (double err_deg : { -89.0, -60.0, -20.0, -3.0, 0.0, 0.5, 7.0, 45.0, 80.0 }) {
        const double theta = 0.4;
        const double beta = theta - err_deg * DEG; // theta~ = theta - beta
        const double fp = model(theta + delta, beta, 0.0);
        const double fm = model(theta - delta, beta, 0.0);
        EXPECT_NEAR(invert_probe_difference(fp, fm, delta, A), err_deg * DEG, 1e-9)
            << err_deg;
        // Eq. 5's step 2 delta sin(delta) sin(theta~) removes only ~6 % of it at 10 deg.
        const double eq5 = 2.0 * delta * std::sin(delta) * std::sin(err_deg * DEG);
        EXPECT_LE(std::abs(eq5), 0.065 * std::abs(err_deg * DEG) + 1e-12);
    }
    // Beyond the model's range (noise): clamped to +-90 deg, never NaN.
    EXPECT_NEAR(invert_probe_difference(0.0, 3.0 * A, 10.0 * DEG, A), M_PI / 2, 1e-12);
    EXPECT_NEAR(invert_probe_difference(3.0 * A, 0.0, 10.0 * DEG, A), -M_PI / 2, 1e-12);
}

TEST(doppler_fit, narrow_fit_recovers_the_error_with_a_cfo_drift)
{
    const double theta = -2.0, delta = 8.0 * DEG;
    for (double err_deg : { -70.0, -12.0, 0.0, 4.0, 33.0 }) {
        const double beta = theta - err_deg * DEG;
        const auto s = cycle(theta, delta, beta, { 1, -1, -1, 1 }, 10.0);
        const auto r = fit_doppler_narrow(s, theta, A, true);
        ASSERT_TRUE(r.ok);
        EXPECT_NEAR(world::wrap(r.bearing_rad - beta), 0.0, 1e-9) << err_deg;
        EXPECT_NEAR(r.drift_hz_per_s, 10.0, 1e-6);
        EXPECT_NEAR(r.residual_rms_hz, 0.0, 1e-6);
    }
}

TEST(doppler_fit, palindromic_probe_order_cancels_a_linear_drift)
{
    // +delta, -delta, -delta, +delta: the drift regressor is orthogonal to the probe
    // difference, so even a fit without a drift term is exact. The plain alternation
    // +delta, -delta of the paper is biased by drift * (segment time) / (2 A sin delta).
    const double theta = 1.0, delta = 5.0 * DEG, beta = theta - 3.0 * DEG;
    const double drift = 10.0; // Hz/s
    const auto pal = fit_doppler_narrow(
        cycle(theta, delta, beta, { 1, -1, -1, 1 }, drift), theta, A, false);
    ASSERT_TRUE(pal.ok);
    EXPECT_NEAR(world::wrap(pal.bearing_rad - beta), 0.0, 1e-9);

    const auto alt = fit_doppler_narrow(
        cycle(theta, delta, beta, { 1, -1 }, drift, 20), theta, A, false);
    ASSERT_TRUE(alt.ok);
    // Segment centres 1 s apart: the drift adds 10 Hz to f- - f+, i.e. sin(theta~) is off
    // by 10 / (2 A sin delta) = 0.86: tens of degrees.
    const double bias = std::abs(world::wrap(alt.bearing_rad - beta));
    EXPECT_GT(bias, 20.0 * DEG);
    // With a drift term the plain alternation is exact again.
    const auto alt_d = fit_doppler_narrow(
        cycle(theta, delta, beta, { 1, -1 }, drift, 20), theta, A, true);
    EXPECT_NEAR(world::wrap(alt_d.bearing_rad - beta), 0.0, 1e-9);
}

TEST(doppler_fit, full_fit_finds_any_bearing_including_behind)
{
    for (double beta_deg : { -179.0, -120.0, -30.0, 0.0, 75.0, 150.0, 180.0 }) {
        std::vector<doppler_sample> s;
        double t = 3.0;
        for (int k = 0; k < 6; ++k)
            for (int i = 0; i < 3; ++i, t += 0.05) {
                const double psi = 0.2 + k * 120.0 * DEG;
                s.push_back(
                    doppler_sample{ psi, t, model(psi, beta_deg * DEG, t, -400, 7) });
            }
        const auto r = fit_doppler_full(s, true);
        ASSERT_TRUE(r.ok);
        EXPECT_NEAR(world::wrap(r.bearing_rad - beta_deg * DEG), 0.0, 1e-9) << beta_deg;
        EXPECT_NEAR(r.amplitude_hz, A, 1e-9);
        EXPECT_NEAR(r.drift_hz_per_s, 7.0, 1e-6);
    }
    // Too few samples, or one heading only: not ok, no NaN.
    std::vector<doppler_sample> one{ { 0.0, 0.0, 10.0 }, { 0.0, 0.1, 11.0 } };
    EXPECT_FALSE(fit_doppler_full(one, true).ok);
    std::vector<doppler_sample> same;
    for (int i = 0; i < 20; ++i)
        same.push_back(doppler_sample{ 0.3, 0.05 * i, 100.0 });
    const auto r = fit_doppler_full(same, true);
    EXPECT_FALSE(r.ok);
    EXPECT_FALSE(std::isnan(r.bearing_rad));
}

TEST(doppler_fit, full_fit_trims_an_outlier)
{
    std::vector<doppler_sample> s;
    double t = 0.0;
    const double beta = 2.0;
    for (int k = 0; k < 6; ++k)
        for (int i = 0; i < 4; ++i, t += 0.05) {
            const double psi = k * 120.0 * DEG;
            s.push_back(
                doppler_sample{ psi, t, model(psi, beta, t) + 0.5 * ((i % 2) - 0.5) });
        }
    s[5].freq_hz += 120.0; // within eq. 4's threshold, far outside the noise
    const auto r = fit_doppler_full(s, false);
    ASSERT_TRUE(r.ok);
    EXPECT_EQ(r.used, static_cast<int>(s.size()) - 1);
    EXPECT_NEAR(world::wrap(r.bearing_rad - beta), 0.0, 0.5 * DEG);
}

TEST(doppler_fit, three_probes_resolve_flying_away)
{
    // The probe difference alone cannot tell theta~ from 180 deg - theta~; the nominal
    // probe f0 can, without knowing A or the CFO.
    const double delta = 15.0 * DEG;
    for (double err_deg :
         { -179.0, -150.0, -95.0, -30.0, 0.0, 20.0, 91.0, 135.0, 178.0 }) {
        const double theta = -0.7, beta = theta - err_deg * DEG;
        const double f0 = model(theta, beta, 0.0, 321.0);
        const double fp = model(theta + delta, beta, 0.0, 321.0);
        const double fm = model(theta - delta, beta, 0.0, 321.0);
        EXPECT_NEAR(world::wrap(resolve_probe_error(f0, fp, fm, delta) - err_deg * DEG),
                    0.0,
                    1e-9)
            << err_deg;
        // The difference alone folds |theta~| > 90 deg onto the front.
        const double folded = invert_probe_difference(fp, fm, delta, A);
        if (std::abs(err_deg) > 90.0) {
            EXPECT_NEAR(
                folded, std::copysign(M_PI - std::abs(err_deg * DEG), err_deg), 1e-9)
                << err_deg;
        }
    }
}

namespace {

// An arc turned at 13 deg/s from heading 0 to `arc` (left), a sample per 0.05 s, with
// white frequency noise of sigma Hz (seeded).
std::vector<doppler_sample>
arc_samples(double arc, double beta, double sigma, unsigned seed)
{
    std::mt19937 g(seed);
    std::normal_distribution<double> n(0.0, sigma);
    std::vector<doppler_sample> s;
    const double step = 13.0 * DEG * 0.05;
    for (int i = 0; i * step <= arc; ++i)
        s.push_back({ i * step, 0.05 * i, model(i * step, beta, 0.05 * i) + n(g) });
    return s;
}

} // namespace

TEST(doppler_fit, side_test_says_which_way_to_turn_from_a_short_arc)
{
    // 20 deg of arc at 10 m/s (A = 67 Hz), 1 Hz of noise: the side of the heading flown
    // at the end of the arc, for emitters anywhere but near ahead or behind, past the
    // seeker's threshold (SIDE_Z^2 = 9).
    const double arc = 20.0 * DEG;
    for (double rel_deg : { -150.0, -120.0, -90.0, -45.0, 45.0, 90.0, 120.0, 150.0 })
        for (unsigned seed : { 1u, 2u, 3u }) {
            const double beta = world::wrap(arc + rel_deg * DEG);
            const doppler_side_result r =
                doppler_side(arc_samples(arc, beta, 1.0, seed), arc, A);
            ASSERT_TRUE(r.ok);
            EXPECT_EQ(r.side, rel_deg > 0 ? 1 : -1) << rel_deg << " seed " << seed;
            EXPECT_GT(r.statistic, 9.0) << rel_deg << " seed " << seed;
        }
    // Without noise the grid's best bearing is the emitter's (within the grid's step).
    const double beta = world::wrap(arc - 150.0 * DEG);
    const doppler_side_result r = doppler_side(arc_samples(arc, beta, 0.0, 1), arc, A);
    EXPECT_LT(std::abs(world::wrap(r.bearing_rad - beta)), 0.5 * DEG);
    EXPECT_LT(r.residual_rms_hz, 0.2);
}

TEST(doppler_fit, side_test_is_undecided_ahead_and_behind_and_needs_samples)
{
    // Straight ahead or behind the heading, both sides fit alike: no decision.
    const double arc = 15.0 * DEG;
    for (double rel_deg : { 0.0, 180.0 })
        for (unsigned seed : { 1u, 2u, 3u }) {
            const doppler_side_result r = doppler_side(
                arc_samples(arc, world::wrap(arc + rel_deg * DEG), 1.0, seed), arc, A);
            ASSERT_TRUE(r.ok);
            EXPECT_LT(r.statistic, 9.0) << rel_deg << " seed " << seed;
        }
    EXPECT_FALSE(doppler_side({ { 0.0, 0.0, 1.0 }, { 0.1, 0.05, 2.0 } }, 0.0, A).ok);
    EXPECT_FALSE(doppler_side(arc_samples(arc, 1.0, 0.0, 1), 0.0, 0.0).ok);
}
