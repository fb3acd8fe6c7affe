/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * tone_estimator against closed forms: exact tones, the Cramer-Rao bound
 * var(f) = 6 / ((2 pi)^2 SNR N (N^2 - 1) Ts^2), the outlier rate near threshold, the SNR
 * of the synthetic window, and degenerate input.
 */

#include <gr-rfseek/rng.h>
#include <gr-rfseek/tone_estimator.h>
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <vector>

using gr::rfseek::rng;
using gr::rfseek::tone_estimate;
using gr::rfseek::tone_estimator;
using cvec = std::vector<std::complex<float>>;

namespace {

constexpr double FS = 1e5;
constexpr int N = 1000;
constexpr int NFFT = 4096;

// Unit tone at f with phase ph plus complex white noise of power 1 / snr (snr <= 0:
// none).
cvec tone(double f, double ph, double snr, rng& g)
{
    cvec x(N);
    const double sigma = snr > 0 ? std::sqrt(0.5 / snr) : 0.0;
    for (int n = 0; n < N; ++n) {
        const double p = 2.0 * M_PI * f * n / FS + ph;
        x[n] = std::complex<float>(std::cos(p) + sigma * g.normal(),
                                   std::sin(p) + sigma * g.normal());
    }
    return x;
}

struct stats {
    double rmse_inliers;
    double outlier_rate;
    double mean_snr_db;
};

stats run(const std::string& interp, double snr_db, int trials, std::uint64_t seed)
{
    tone_estimator est(FS, N, NFFT, "rectangular", interp);
    rng g(seed);
    const double snr = std::pow(10.0, snr_db / 10.0);
    double se = 0.0, snr_acc = 0.0;
    int in = 0, out = 0;
    for (int t = 0; t < trials; ++t) {
        const double f = g.uniform(-45000.0, 45000.0);
        const auto x = tone(f, g.uniform(0.0, 2 * M_PI), snr, g);
        const tone_estimate e = est.estimate(x);
        EXPECT_TRUE(e.valid);
        const double err = e.freq_hz - f;
        if (std::abs(err) > 100.0) {
            ++out;
        } else {
            se += err * err;
            ++in;
        }
        snr_acc += e.snr_db;
    }
    return { std::sqrt(se / std::max(in, 1)), double(out) / trials, snr_acc / trials };
}

} // namespace

TEST(tone_estimator, crb_closed_form)
{
    // N = 1000, Ts = 10 us, SNR = 1: var = 6 / (4 pi^2 * 1000 * 999999 * 1e-10)
    const double v = 6.0 / (4.0 * M_PI * M_PI * 1000.0 * 999999.0 * 1e-10);
    EXPECT_NEAR(tone_estimator::crb_std_hz(1.0, N, FS), std::sqrt(v), 1e-12);
    EXPECT_NEAR(tone_estimator::crb_std_hz(1.0, N, FS), 1.2328, 1e-3);
}

TEST(tone_estimator, noise_free_tones_across_the_band)
{
    rng g(11);
    const struct {
        const char* interp;
        const char* window;
        double tol;
    } cases[] = {
        { "parabolic", "rectangular", 0.2 },     { "parabolic", "hann", 0.2 },
        { "parabolic", "blackman_harris", 0.2 }, { "newton", "rectangular", 0.01 },
        { "newton", "blackman_harris", 0.01 },   { "log_parabolic", "rectangular", 0.15 },
    };
    for (const auto& c : cases) {
        tone_estimator est(FS, N, NFFT, c.window, c.interp);
        double worst = 0.0;
        for (int t = 0; t < 400; ++t) {
            const double f = g.uniform(-49900.0, 49900.0);
            const auto e = est.estimate(tone(f, g.uniform(0.0, 6.28), 0.0, g));
            ASSERT_TRUE(e.valid);
            worst = std::max(worst, std::abs(e.freq_hz - f));
        }
        EXPECT_LE(worst, c.tol) << c.interp << "/" << c.window;
    }
}

TEST(tone_estimator, newton_reaches_the_crb)
{
    for (double snr_db : { -14.0, -10.0, 0.0, 10.0, 20.0, 30.0 }) {
        const stats s = run("newton", snr_db, 2000, 100 + static_cast<int>(snr_db));
        const double crb =
            tone_estimator::crb_std_hz(std::pow(10.0, snr_db / 10.0), N, FS);
        EXPECT_LE(s.rmse_inliers, 1.1 * crb) << "snr " << snr_db;
        EXPECT_LE(s.outlier_rate, 0.001) << "snr " << snr_db;
    }
}

TEST(tone_estimator, parabolic_reaches_the_crb_up_to_10_db)
{
    for (double snr_db : { -14.0, -10.0, 0.0, 10.0 }) {
        const stats s = run("parabolic", snr_db, 2000, 200 + static_cast<int>(snr_db));
        const double crb =
            tone_estimator::crb_std_hz(std::pow(10.0, snr_db / 10.0), N, FS);
        EXPECT_LE(s.rmse_inliers, 1.1 * crb) << "snr " << snr_db;
    }
    // Above that its bias (up to 0.14 Hz) dominates: it must not be mistaken for
    // efficient.
    const stats hi = run("parabolic", 30.0, 500, 230);
    EXPECT_GT(hi.rmse_inliers, 1.5 * tone_estimator::crb_std_hz(1000.0, N, FS));
}

TEST(tone_estimator, few_outliers_near_threshold)
{
    for (const char* interp : { "parabolic", "newton" }) {
        const stats s = run(interp, -16.0, 3000, 316);
        EXPECT_LE(s.outlier_rate, 0.01) << interp;
    }
}

TEST(tone_estimator, snr_estimate_within_1_db)
{
    for (double snr_db : { -10.0, -5.0, 0.0, 10.0, 20.0, 30.0 }) {
        for (const char* interp : { "parabolic", "newton" }) {
            const stats s = run(interp, snr_db, 300, 400 + static_cast<int>(snr_db));
            EXPECT_NEAR(s.mean_snr_db, snr_db, 1.0) << interp << " snr " << snr_db;
        }
    }
}

TEST(tone_estimator, power_is_the_tone_power)
{
    tone_estimator est(FS, N, NFFT, "hann", "newton");
    rng g(3);
    cvec x = tone(1234.5, 0.3, 0.0, g);
    for (auto& v : x)
        v *= 0.01f; // -40 dB
    const auto e = est.estimate(x);
    EXPECT_NEAR(e.power_db, -40.0, 0.01);
    EXPECT_GT(e.snr_db, 60.0);
}

TEST(tone_estimator, search_band_ignores_stronger_tones_outside)
{
    rng g(5);
    cvec a = tone(20000.0, 0.0, 0.0, g);
    const cvec b = tone(-310.0, 1.0, 0.0, g);
    for (int n = 0; n < N; ++n)
        a[n] = a[n] * 3.0f + b[n];
    tone_estimator est(FS, N, NFFT, "blackman_harris", "newton", -1000.0, 1000.0);
    EXPECT_NEAR(est.estimate(a).freq_hz, -310.0, 0.5);
    est.set_band(0.0, 0.0);
    EXPECT_NEAR(est.estimate(a).freq_hz, 20000.0, 0.5);
    est.set_band(19000.0, 21000.0);
    EXPECT_NEAR(est.estimate(a).freq_hz, 20000.0, 0.5);
}

// Found by fuzzing (lib/fuzz/fuzz_tone_estimator.cc): the skirt of a tone just outside
// the band makes the band's edge bin its largest, and the interpolation carried the
// estimate outside the band (or left it biased at the edge).
TEST(tone_estimator, a_tone_outside_the_band_is_not_a_valid_estimate)
{
    rng g(3);
    tone_estimator est(FS, N, NFFT, "rectangular", "parabolic", -1000.0, 1000.0);
    const double bin = FS / NFFT; // 24.4 Hz
    // Within a bin or two outside the edge (further out, a rectangular window's sidelobes
    // are local peaks inside the band: the band is a search range, not a filter).
    for (double f : { 1000.0 + 0.4 * bin, -1000.0 - 0.4 * bin, 1030.0, -1000.0 - bin }) {
        const tone_estimate e = est.estimate(tone(f, 0.3, 0.0, g));
        EXPECT_FALSE(e.valid) << f << " gave " << e.freq_hz;
        EXPECT_TRUE(std::isfinite(e.freq_hz));
    }
    // Inside by more than half a bin (within half a bin of the edge, the peak bin may lie
    // outside, and the tone is refused).
    for (double f : { 1000.0 - 2.0 * bin, -1000.0 + bin, 0.0, 512.3 }) {
        const tone_estimate e = est.estimate(tone(f, 0.3, 0.0, g));
        EXPECT_TRUE(e.valid) << f << " gave " << e.freq_hz;
        EXPECT_NEAR(e.freq_hz, f, 1.0);
    }
}

TEST(tone_estimator, degenerate_input_is_invalid_and_finite)
{
    tone_estimator est(FS, N, NFFT, "rectangular", "newton");
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    cvec zeros(N), with_nan(N, { 1.0f, 0.0f }), with_inf(N, { 1.0f, 0.0f });
    with_nan[17] = { nan, 0.0f };
    with_inf[900] = { 0.0f, inf };
    for (const cvec* x : { &zeros, &with_nan, &with_inf }) {
        const auto e = est.estimate(*x);
        EXPECT_FALSE(e.valid);
        EXPECT_TRUE(std::isfinite(e.freq_hz) && std::isfinite(e.snr_db) &&
                    std::isfinite(e.power_db) && std::isfinite(e.noise_power_db));
    }
    // A pure DC window is a valid tone at 0 Hz.
    const cvec dc(N, { 0.5f, 0.5f });
    const auto e = est.estimate(dc);
    EXPECT_TRUE(e.valid);
    EXPECT_NEAR(e.freq_hz, 0.0, 1e-6);
}

TEST(tone_estimator, bad_parameters_name_themselves)
{
    auto msg = [](auto&& f) {
        try {
            f();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no exception");
    };
    EXPECT_NE(msg([] { tone_estimator(FS, 2, NFFT); }).find("window_len"),
              std::string::npos);
    EXPECT_NE(msg([] { tone_estimator(FS, 5000, NFFT); }).find("window_len"),
              std::string::npos);
    EXPECT_NE(msg([] { tone_estimator(FS, 3, 3); }).find("fft_len"), std::string::npos);
    EXPECT_NE(msg([] { tone_estimator(0.0, N, NFFT); }).find("samp_rate"),
              std::string::npos);
    EXPECT_NE(msg([] { tone_estimator(FS, N, NFFT, "kaiser"); }).find("window"),
              std::string::npos);
    EXPECT_NE(
        msg([] { tone_estimator(FS, N, NFFT, "hann", "cubic"); }).find("interpolator"),
        std::string::npos);
    EXPECT_NE(msg([] {
                  tone_estimator(FS, N, NFFT, "hann", "newton", 10.0, 20.0);
              }).find("band"),
              std::string::npos);
    EXPECT_NE(msg([] {
                  tone_estimator(FS, N, NFFT, "hann", "newton", -6e4, 0.0);
              }).find("band"),
              std::string::npos);
}

TEST(tone_estimator, input_buffer_in_place_gives_the_same_estimate)
{
    rng g(31);
    for (const char* window : { "rectangular", "hann", "blackman_harris" }) {
        for (const char* interp : { "parabolic", "newton" }) {
            tone_estimator est(FS, N, NFFT, window, interp);
            for (int t = 0; t < 20; ++t) {
                const auto x = tone(g.uniform(-40000.0, 40000.0), 1.0, 3.0, g);
                const tone_estimate a = est.estimate(x);
                std::copy(x.begin(), x.end(), est.input_buffer());
                const tone_estimate b = est.estimate(est.input_buffer());
                EXPECT_EQ(a.freq_hz, b.freq_hz) << window << "/" << interp;
                EXPECT_EQ(a.snr_db, b.snr_db) << window << "/" << interp;
                EXPECT_EQ(a.power_db, b.power_db) << window << "/" << interp;
                if (std::string(window) == "rectangular") { // untouched: no window
                    EXPECT_TRUE(std::equal(x.begin(), x.end(), est.input_buffer()));
                }
            }
        }
    }
}
