/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * carrier_notch and equalize_blocks: a carrier 40 dB above the noise in its bin is
 * removed to the noise while a tone ten bins away keeps its power; a wideband burst in
 * a window is weighted down and white noise or a strong tone is left alone; the tone
 * detector leaves the bins of removed carriers out of its search.
 */

#include "carrier_notch.h"
#include <gr-rfseek/rng.h>
#include <gr-rfseek/tone_detector.h>
#include <gtest/gtest.h>
#include <cmath>
#include <complex>
#include <vector>

using namespace gr::rfseek;
using cf = std::complex<float>;

namespace {
std::vector<cf> noise(std::size_t n, std::uint64_t seed, double power = 1.0)
{
    rng r(seed);
    std::vector<cf> x(n);
    const double s = std::sqrt(0.5 * power);
    for (auto& v : x)
        v = cf(static_cast<float>(s * r.normal()), static_cast<float>(s * r.normal()));
    return x;
}

// |sum x_n exp(-j 2 pi f n)|^2 / N: the periodogram at f (cycles per sample).
double periodogram(const std::vector<cf>& x, double f)
{
    std::complex<double> s = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i)
        s += std::complex<double>(x[i]) * std::polar(1.0, -2.0 * M_PI * f * i);
    return std::norm(s) / x.size();
}
} // namespace

TEST(carrier_notch, a_strong_carrier_goes_and_a_tone_ten_bins_away_stays)
{
    const std::size_t n = 1000;
    const double fc = 0.1234567, ft = fc + 10.4 / n; // between bins
    double residual = 0.0, kept = 0.0;
    const int trials = 20;
    for (int t = 0; t < trials; ++t) {
        auto x = noise(n, 100 + t);
        for (std::size_t i = 0; i < n; ++i) {
            x[i] += cf(std::polar(std::sqrt(10.0), 2.0 * M_PI * fc * i + t)); // +10 dB
            x[i] += cf(std::polar(std::sqrt(0.1), 2.0 * M_PI * ft * i));      // -10 dB
        }
        carrier_notch notch(1.0);
        notch.add(fc + 0.3 / n, 2.0 / n); // held a third of a bin off
        std::vector<double> share;
        notch.apply(x.data(), n, &share);
        EXPECT_NEAR(share[0], 10.0 / 11.1, 0.02);
        residual += periodogram(x, fc) / trials;
        kept += periodogram(x, ft) / trials;
    }
    // The carrier's bin held 10 N = 40 dB over the noise's 1; the tone's N / 10 = 100.
    EXPECT_LT(residual, 3.0);
    EXPECT_NEAR(10.0 * std::log10(kept / 100.0), 0.0, 1.0);
}

TEST(carrier_notch, it_holds_at_most_max_carriers_apart)
{
    carrier_notch notch(1e5, 2);
    EXPECT_TRUE(notch.add(1000.0, 200.0));
    EXPECT_FALSE(notch.add(1100.0, 200.0)); // the same carrier
    EXPECT_TRUE(notch.add(-3000.0, 200.0));
    EXPECT_TRUE(notch.add(7000.0, 200.0)); // the oldest goes
    EXPECT_EQ(notch.freqs(), (std::vector<double>{ -3000.0, 7000.0 }));
    EXPECT_FALSE(notch.add(std::nan(""), 1.0));
}

TEST(equalize_blocks, a_wideband_burst_is_weighted_down_and_noise_left_alone)
{
    auto x = noise(1000, 7);
    auto y = x;
    EXPECT_EQ(equalize_blocks(y.data(), y.size(), 50), 0);
    EXPECT_EQ(x, y);
    // A burst 10 dB over the noise across 300 samples (6 blocks).
    auto burst = noise(1000, 8, 10.0);
    for (std::size_t i = 400; i < 700; ++i)
        x[i] += burst[i];
    EXPECT_EQ(equalize_blocks(x.data(), x.size(), 50), 6);
    double p = 0.0;
    for (std::size_t i = 400; i < 700; ++i)
        p += std::norm(x[i]) / 300.0;
    EXPECT_LT(p, 1.5); // back near the noise's power
    // A strong tone is no burst.
    std::vector<cf> tone(1000);
    for (std::size_t i = 0; i < tone.size(); ++i)
        tone[i] = cf(std::polar(30.0, 0.3 * i));
    EXPECT_EQ(equalize_blocks(tone.data(), tone.size(), 50), 0);
}

TEST(tone_detector, bins_of_removed_carriers_are_left_out)
{
    tone_detector d(1e5, 1000, 1e-3);
    const int all = d.band_bins();
    const double t0 = d.threshold();
    d.set_exclusions({ 5000.0, -20000.0 }, 600.0);
    // 25 bins of the 2N-point transform (50 Hz apart) per carrier, 12 or 13 of a set.
    EXPECT_GE(d.band_bins(), all - 26);
    EXPECT_LE(d.band_bins(), all - 24);
    EXPECT_LT(d.threshold(), t0);
    std::vector<cf> x(1000);
    for (std::size_t i = 0; i < x.size(); ++i)
        x[i] = cf(std::polar(1.0, 2.0 * M_PI * 5000.0 * i / 1e5));
    EXPECT_FALSE(d.test(x.data()).detected);
    d.set_exclusions({}, 0.0);
    EXPECT_EQ(d.band_bins(), all);
    EXPECT_TRUE(d.test(x.data()).detected);
}
