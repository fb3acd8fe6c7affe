/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * tone_detector against closed forms: the exact law of Fisher's g on one set of DFT
 * bins (checked with an independent DFT), the detector's false-alarm rate between the
 * bounds it promises, and its detection rate against the Rice (Marcum Q) law.
 */

#include <gr-rfseek/rng.h>
#include <gr-rfseek/tone_detector.h>
#include <gr-rfseek/tone_estimator.h>
#include <gtest/gtest.h>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <vector>

using namespace gr::rfseek;

namespace {
std::vector<std::complex<float>> noise(rng& r, int n, double sigma2 = 1.0)
{
    std::vector<std::complex<float>> x(n);
    const double s = std::sqrt(0.5 * sigma2);
    for (auto& v : x)
        v = std::complex<float>(s * r.normal(), s * r.normal());
    return x;
}

// Q1(a, b) = P(|z| > b) for z complex Gaussian of mean a and variance 1 per component:
// the integral of the Rice density from b, by Simpson's rule.
double marcum_q1(double a, double b)
{
    const double hi = a + b + 12.0;
    const int steps = 20000;
    const double h = (hi - b) / steps;
    double sum = 0.0;
    for (int i = 0; i <= steps; ++i) {
        const double x = b + i * h;
        // x exp(-(x^2 + a^2) / 2) I0(a x), with I0 scaled to avoid overflow
        const double f =
            x * std::exp(-0.5 * (x - a) * (x - a)) *
            (a * x > 0 ? std::cyl_bessel_i(0.0, a * x) * std::exp(-a * x) : 1.0);
        sum += f * ((i == 0 || i == steps) ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return sum * h / 3.0;
}
} // namespace

TEST(tone_detector, set_law_matches_an_independent_dft)
{
    // Fisher's g over B of the N bins of a plain N-point DFT, computed here by hand,
    // exceeds x with the closed-form probability P1(x).
    const int n = 64, trials = 20000, band = 20;
    rng r(11);
    const double x1 = 0.09, x2 = 0.12;
    int over1 = 0, over2 = 0;
    for (int t = 0; t < trials; ++t) {
        const auto x = noise(r, n);
        double energy = 0.0, best = 0.0;
        for (const auto& v : x)
            energy += std::norm(std::complex<double>(v));
        for (int k = 0; k < band; ++k) {
            std::complex<double> s = 0.0;
            for (int i = 0; i < n; ++i)
                s +=
                    std::complex<double>(x[i]) * std::polar(1.0, -2.0 * M_PI * k * i / n);
            best = std::max(best, std::norm(s));
        }
        const double g = best / (n * energy);
        over1 += g > x1;
        over2 += g > x2;
    }
    for (const auto& [x, over] : { std::pair{ x1, over1 }, std::pair{ x2, over2 } }) {
        const double p = tone_detector::set_false_alarm(x, n, band);
        const double sd = std::sqrt(p * (1 - p) / trials);
        EXPECT_GT(p, 0.005);
        EXPECT_NEAR(static_cast<double>(over) / trials, p, 4.0 * sd + 1e-4)
            << "x = " << x;
    }
    // The first terms and the limits.
    EXPECT_NEAR(tone_detector::set_false_alarm(0.3, n, band),
                band * std::pow(0.7, n - 1) -
                    0.5 * band * (band - 1) * std::pow(0.4, n - 1) +
                    band * (band - 1) * (band - 2) / 6.0 * std::pow(0.1, n - 1),
                1e-15);
    EXPECT_EQ(tone_detector::set_false_alarm(1.0, n, band), 0.0);
    EXPECT_EQ(tone_detector::set_false_alarm(0.0, n, band), 1.0);
}

TEST(tone_detector, false_alarms_lie_between_the_promised_bounds)
{
    const int n = 256, trials = 20000;
    for (const double pfa : { 0.05, 0.01 }) {
        tone_detector d(100e3, n, pfa);
        EXPECT_EQ(d.band_bins(), n);
        const double p1 = tone_detector::set_false_alarm(d.threshold(), n, n);
        EXPECT_NEAR(2.0 * p1, pfa, 1e-9 * pfa);
        rng r(23);
        int hits = 0;
        for (int t = 0; t < trials; ++t) {
            const auto x = noise(r, n, 3.7); // the noise power is not needed
            hits += d.test(x.data()).detected;
        }
        const double rate = static_cast<double>(hits) / trials;
        const double sd = std::sqrt(pfa * (1 - pfa) / trials);
        EXPECT_LE(rate, pfa + 4.0 * sd) << "pfa " << pfa;
        EXPECT_GE(rate, 0.5 * pfa - 4.0 * sd) << "pfa " << pfa;
    }
}

TEST(tone_detector, detection_rate_follows_the_rice_law)
{
    // A tone on a bin of the N-point DFT: the bin's periodogram over N sigma^2 is
    // noncentral chi-square with 2 degrees of freedom and noncentrality 2 N SNR, so
    // P_D = Q1(sqrt(2 N SNR), sqrt(2 gamma)) with gamma = threshold * N * (1 + SNR) (the
    // window's mean energy per sample is sigma^2 (1 + SNR)).
    const int n = 256, trials = 6000;
    const double fs = 100e3;
    tone_detector d(fs, n, 1e-3);
    for (const double snr_db : { -13.0, -12.0 }) {
        const double snr = std::pow(10.0, snr_db / 10.0);
        rng r(31);
        int hits = 0, elsewhere = 0;
        const int k = 37;
        for (int t = 0; t < trials; ++t) {
            auto x = noise(r, n);
            const double ph = r.uniform(0.0, 2.0 * M_PI);
            for (int i = 0; i < n; ++i)
                x[i] += std::complex<float>(
                    std::polar(std::sqrt(snr), ph + 2.0 * M_PI * k * i / n));
            const auto det = d.test(x.data());
            hits += det.detected;
            elsewhere += det.detected && std::abs(det.freq_hz - k * fs / n) > fs / n;
        }
        const double gamma = d.threshold() * n * (1.0 + snr);
        const double pd = marcum_q1(std::sqrt(2.0 * n * snr), std::sqrt(2.0 * gamma));
        EXPECT_GT(pd, 0.2);
        EXPECT_LT(pd, 0.95);
        EXPECT_NEAR(static_cast<double>(hits) / trials, pd, 0.03) << "SNR " << snr_db;
        // Detections on a noise bin: about pfa of the windows.
        EXPECT_LE(elsewhere, 0.005 * trials) << "SNR " << snr_db;
    }
}

TEST(tone_detector, band_and_bad_input)
{
    tone_detector d(100e3, 100, 1e-3, 1000.0, 5000.0);
    // 1000..5000 Hz at 1 kHz per DFT bin: 5 even bins, 4 odd ones.
    EXPECT_EQ(d.band_bins(), 5);
    std::vector<std::complex<float>> x(100);
    for (int i = 0; i < 100; ++i) // a strong tone outside the band
        x[i] = std::polar(1.0f, static_cast<float>(2.0 * M_PI * 20e3 * i / 100e3));
    EXPECT_FALSE(d.test(x.data()).detected);
    for (int i = 0; i < 100; ++i) // inside
        x[i] = std::polar(1.0f, static_cast<float>(2.0 * M_PI * 3e3 * i / 100e3));
    const auto in = d.test(x.data());
    EXPECT_TRUE(in.detected);
    EXPECT_NEAR(in.freq_hz, 3000.0, 100.0);
    std::fill(x.begin(), x.end(), std::complex<float>(0.0f));
    EXPECT_FALSE(d.test(x.data()).detected);
    x[5] = std::numeric_limits<float>::quiet_NaN();
    const auto nan = d.test(x.data());
    EXPECT_FALSE(nan.detected);
    EXPECT_TRUE(std::isfinite(nan.g) && std::isfinite(nan.margin_db));
    EXPECT_THROW(tone_detector(100e3, 8), std::invalid_argument);
    EXPECT_THROW(tone_detector(100e3, 100, 0.9), std::invalid_argument);
    EXPECT_THROW(tone_detector(100e3, 100, 1e-3, 0.0, 60e3), std::invalid_argument);
    EXPECT_THROW(tone_detector(100e3, 100, 1e-3, 0.0, 500.0), std::invalid_argument);
}

// A new sample rate: the same samples read as a tone of f x the rate's ratio (the
// digital frequency is the samples' own), the band in Hz kept; a rate the band cannot
// fit is refused with nothing changed.
TEST(ToneDetector, set_samp_rate_rescales_frequencies_and_keeps_the_band)
{
    const int n = 1000;
    std::vector<std::complex<float>> x(n);
    for (int i = 0; i < n; ++i)
        x[i] = std::polar(1.0f, static_cast<float>(2.0 * M_PI * 0.123 * i));
    tone_detector d(100e3, n, 1e-3, -20e3, 20e3);
    auto r = d.test(x.data());
    ASSERT_TRUE(r.detected);
    EXPECT_NEAR(r.freq_hz, 12.3e3, 60.0);
    const int bins = d.band_bins();
    d.set_samp_rate(150e3);
    r = d.test(x.data());
    EXPECT_TRUE(r.detected);
    EXPECT_NEAR(r.freq_hz, 0.123 * 150e3, 90.0);
    EXPECT_EQ(d.min_freq_hz(), -20e3);
    EXPECT_LT(d.band_bins(), bins); // the same Hz are fewer bins at a higher rate
    EXPECT_THROW(d.set_samp_rate(30e3), std::invalid_argument);
    EXPECT_THROW(d.set_samp_rate(-1.0), std::invalid_argument);
    EXPECT_EQ(d.samp_rate_hz(), 150e3);

    tone_estimator e(100e3, n, 4096, "rectangular", "newton", -20e3, 20e3);
    const double f1 = e.estimate(x).freq_hz;
    EXPECT_NEAR(f1, 12.3e3, 0.5);
    e.set_samp_rate(150e3);
    EXPECT_NEAR(e.estimate(x).freq_hz, f1 * 1.5, 0.5);
    EXPECT_THROW(e.set_samp_rate(30e3), std::invalid_argument);
    EXPECT_EQ(e.samp_rate_hz(), 150e3);
}
