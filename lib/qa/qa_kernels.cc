/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The vectorised kernels against plain loops: argmax of |X|^2 (first index on ties) with
 * Parseval's total, the table-phasor demodulating dot product, the sum of tones, the
 * noise, and the fused one-pass synthesis against the two-pass one (bit for bit).
 */

#include "kernels.h"
#include <gr-rfseek/rng.h>
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

using namespace gr::rfseek;

TEST(peak_search, matches_a_plain_loop)
{
    rng g(21);
    for (std::uint32_t n : { 1u, 7u, 8u, 9u, 16u, 24u, 64u, 1000u, 4096u, 4104u }) {
        for (int trial = 0; trial < 50; ++trial) {
            std::vector<std::complex<float>> x(n);
            for (auto& v : x)
                v = { static_cast<float>(g.normal()), static_cast<float>(g.normal()) };
            if (trial % 5 == 0 && n > 3) // exact ties: the first index wins
                x[n - 1] = x[n / 2] = x[1] = { 9.0f, 9.0f };
            std::uint32_t best = 0;
            double total = 0.0;
            for (std::uint32_t k = 0; k < n; ++k) {
                total += std::norm(x[k]);
                if (std::norm(x[k]) > std::norm(x[best]))
                    best = k;
            }
            // Every width (16 runs as 8 on a CPU without AVX-512): the same result.
            const auto p = detail::peak_search(x.data(), n);
            for (int width : { 8, 16 }) {
                const auto q = detail::peak_search(x.data(), n, width);
                ASSERT_EQ(q.index, p.index) << "n " << n << " width " << width;
                ASSERT_EQ(q.value, p.value) << "n " << n << " width " << width;
                ASSERT_EQ(q.total, p.total) << "n " << n << " width " << width;
            }
            ASSERT_EQ(p.index, best) << "n " << n << " trial " << trial;
            EXPECT_EQ(p.value, std::norm(x[best]));
            EXPECT_NEAR(p.total, total, 1e-5 * total);
            // The documented summation order, exactly: per parity of the block of 8 and
            // element (in the order 0, 4, 1, 5, 2, 6, 3, 7), a float sum over the blocks,
            // then the tail.
            static const std::uint32_t order[8] = { 0, 4, 1, 5, 2, 6, 3, 7 };
            double exact = 0.0;
            for (std::uint32_t par = 0; par < 2; ++par)
                for (std::uint32_t e : order) {
                    float acc = 0.0f;
                    for (std::uint32_t b = par; b < n / 8; b += 2)
                        acc += std::norm(x[8 * b + e]);
                    exact += acc;
                }
            for (std::uint32_t k = n / 8 * 8; k < n; ++k)
                exact += std::norm(x[k]);
            EXPECT_EQ(p.total, exact) << "n " << n;
        }
    }
}

TEST(peak_search, demod_dot_matches_direct_sum)
{
    rng g(22);
    for (std::uint32_t n : { 3u, 64u, 100u, 1000u }) {
        std::vector<std::complex<float>> x(n);
        for (auto& v : x)
            v = { static_cast<float>(g.normal()), static_cast<float>(g.normal()) };
        const double w = 0.0123;
        std::vector<float> a(2 * ((n + 63) / 64)), br(64), bi(64);
        for (std::size_t i = 0; i < a.size() / 2; ++i) {
            a[2 * i] = static_cast<float>(std::cos(-w * 64.0 * i));
            a[2 * i + 1] = static_cast<float>(std::sin(-w * 64.0 * i));
        }
        for (int b = 0; b < 64; ++b) {
            br[b] = static_cast<float>(std::cos(-w * b));
            bi[b] = static_cast<float>(std::sin(-w * b));
        }
        std::complex<double> ref = 0.0;
        for (std::uint32_t k = 0; k < n; ++k)
            ref += std::complex<double>(x[k]) * std::polar(1.0, -w * k);
        const auto got = detail::demod_dot(x.data(), n, a.data(), br.data(), bi.data());
        EXPECT_NEAR(std::abs(got - ref), 0.0, 1e-4 * std::sqrt(double(n))) << "n " << n;
        // The documented order, exactly: per block of 64, float sums per lane over the
        // even and the odd vectors of 8, their sum, lanes added in double; then the tail.
        double er = 0.0, ei = 0.0;
        for (std::uint32_t blk = 0; blk < n / 64; ++blk) {
            const float ar = a[2 * blk], ai = a[2 * blk + 1];
            for (int lane = 0; lane < 8; ++lane) {
                float sr[2] = { 0.0f, 0.0f }, si[2] = { 0.0f, 0.0f };
                for (int j = 0; j < 8; ++j) {
                    const int b = 8 * j + lane;
                    const float pr = ar * br[b] - ai * bi[b];
                    const float pi = ar * bi[b] + ai * br[b];
                    const std::complex<float> v = x[64 * blk + b];
                    sr[j % 2] += v.real() * pr - v.imag() * pi;
                    si[j % 2] += v.real() * pi + v.imag() * pr;
                }
                er += sr[0] + sr[1];
                ei += si[0] + si[1];
            }
        }
        const std::uint32_t full = n / 64;
        for (std::uint32_t k = full * 64; k < n; ++k) {
            const std::uint32_t b = k - full * 64;
            const float pr = a[2 * full] * br[b] - a[2 * full + 1] * bi[b];
            const float pi = a[2 * full] * bi[b] + a[2 * full + 1] * br[b];
            er += x[k].real() * pr - x[k].imag() * pi;
            ei += x[k].real() * pi + x[k].imag() * pr;
        }
        EXPECT_EQ(got.real(), er) << "n " << n;
        EXPECT_EQ(got.imag(), ei) << "n " << n;
    }
}

TEST(kernels, add_tones_matches_a_direct_sum)
{
    rng g(23);
    for (std::uint32_t n : { 1u, 63u, 64u, 1000u, 5000u }) {
        const std::uint32_t paths = 11;
        std::vector<std::complex<double>> amp(paths);
        std::vector<double> cyc(paths);
        for (std::uint32_t p = 0; p < paths; ++p) {
            amp[p] = std::polar(g.uniform(0.1, 1.0), g.uniform(-M_PI, M_PI));
            cyc[p] = g.uniform(-0.02, 0.02); // up to +-2 kHz at 100 kHz
        }
        std::vector<std::complex<float>> x(n, { 0.25f, -0.5f });
        detail::add_tones(x.data(), n, amp.data(), cyc.data(), paths);
        double worst = 0.0;
        for (std::uint32_t k = 0; k < n; ++k) {
            std::complex<double> ref(0.25, -0.5);
            for (std::uint32_t p = 0; p < paths; ++p)
                ref += amp[p] * std::polar(1.0, 2.0 * M_PI * cyc[p] * k);
            worst = std::max(worst, std::abs(std::complex<double>(x[k]) - ref));
        }
        EXPECT_LT(worst, 2e-5) << "n " << n; // float rounding, no phase walk
    }
}

TEST(kernels, tones_and_noise_equals_tones_then_noise_bit_for_bit)
{
    // The fused one-pass synthesis must give the very floats of the two-pass reference
    // (zero, add_tones over tone_len, add_gaussian_noise over len): the Monte Carlo
    // studies depend on them.
    rng g(24);
    for (std::uint32_t paths : { 0u, 1u, 4u, 11u, 13u }) {
        for (std::uint32_t len : { 1u, 7u, 63u, 64u, 65u, 1000u, 5000u }) {
            for (std::uint32_t tone_len : { 0u, 1u, 9u, 64u, 1000u, 5000u }) {
                if (tone_len > len)
                    continue;
                std::vector<std::complex<double>> amp(paths);
                std::vector<double> cyc(paths);
                for (std::uint32_t p = 0; p < paths; ++p) {
                    amp[p] = std::polar(g.uniform(1e-4, 1.0), g.uniform(-M_PI, M_PI));
                    cyc[p] = g.uniform(-0.02, 0.02);
                }
                for (int width : { 8, 16, 0 }) {
                    for (bool noise : { false, true }) {
                        const float sigma = 0.3f;
                        const std::uint64_t key = g.next();
                        std::vector<std::complex<float>> ref(len),
                            got(len, { 7.0f, 7.0f });
                        detail::add_tones(
                            ref.data(), tone_len, amp.data(), cyc.data(), paths);
                        if (noise)
                            detail::add_gaussian_noise(ref.data(), len, sigma, key);
                        detail::tones_and_noise(got.data(),
                                                len,
                                                tone_len,
                                                amp.data(),
                                                cyc.data(),
                                                paths,
                                                noise,
                                                sigma,
                                                key,
                                                width);
                        for (std::uint32_t k = 0; k < len; ++k) {
                            ASSERT_EQ(std::memcmp(&got[k], &ref[k], sizeof(got[k])), 0)
                                << "paths " << paths << " len " << len << " tone_len "
                                << tone_len << " noise " << noise << " width " << width
                                << " k " << k << ": " << got[k] << " vs " << ref[k];
                        }
                    }
                }
            }
        }
    }
}

TEST(kernels, fmod_exact_is_std_fmod_bit_for_bit)
{
    rng g(25);
    auto same = [](double x, double y) {
        const double a = detail::fmod_exact(x, y), b = std::fmod(x, y);
        return std::memcmp(&a, &b, sizeof(a)) == 0;
    };
    const double two_pi = 2.0 * M_PI;
    for (int i = 0; i < 2000000; ++i) {
        // Phases beta L of paths up to 10^7 m at 0.3 m, and random moduli.
        const double x =
            std::ldexp(g.uniform(-1.0, 1.0), static_cast<int>(g.uniform(-30, 60)));
        const double y =
            i % 2 ? two_pi
                  : std::ldexp(g.uniform(0.5, 1.0), static_cast<int>(g.uniform(-10, 20)));
        ASSERT_TRUE(same(x, y)) << x << " mod " << y;
    }
    // Multiples of the modulus and their neighbours, where the quotient rounds up.
    for (int k = 0; k < 100000; ++k) {
        const double m = k * two_pi;
        for (double x : { m, std::nextafter(m, 0.0), std::nextafter(m, 1e300), -m })
            ASSERT_TRUE(same(x, two_pi)) << x;
    }
    for (double x : { 0.0, -0.0, 1e-300, 1e16, -1e300, 4503599627370496.0 * two_pi })
        EXPECT_TRUE(same(x, two_pi)) << x;
}

TEST(kernels, polar_is_std_polar_bit_for_bit)
{
    // The path phases are in (-2 pi, 0]; a wider range for good measure.
    rng g(26);
    for (int i = 0; i < 1000000; ++i) {
        const double rho = g.uniform(1e-6, 1.0);
        const double theta =
            i % 2 ? g.uniform(-2.0 * M_PI, 0.0) : g.uniform(-100.0, 100.0);
        const std::complex<double> a = detail::polar(rho, theta),
                                   b = std::polar(rho, theta);
        ASSERT_EQ(std::memcmp(&a, &b, sizeof(a)), 0) << rho << " " << theta;
    }
}

TEST(kernels, gaussian_noise_is_gaussian)
{
    const std::uint32_t n = 1u << 20;
    const float sigma = 0.7f;
    std::vector<std::complex<float>> x(n);
    detail::add_gaussian_noise(x.data(), n, sigma, 12345);
    double m1 = 0, m2r = 0, m2i = 0, m4 = 0, cross = 0;
    std::uint32_t beyond3 = 0;
    std::vector<double> v;
    v.reserve(2 * n);
    for (const auto& c : x) {
        const double re = c.real() / sigma, im = c.imag() / sigma;
        m1 += re + im;
        m2r += re * re;
        m2i += im * im;
        m4 += re * re * re * re + im * im * im * im;
        cross += re * im;
        beyond3 += (std::abs(re) > 3.0) + (std::abs(im) > 3.0);
        v.push_back(re);
        v.push_back(im);
    }
    const double N = 2.0 * n;
    EXPECT_NEAR(m1 / N, 0.0, 0.003);
    EXPECT_NEAR(m2r / n, 1.0, 0.005);
    EXPECT_NEAR(m2i / n, 1.0, 0.005);
    EXPECT_NEAR(m4 / N, 3.0, 0.03);     // kurtosis of a normal
    EXPECT_NEAR(cross / n, 0.0, 0.005); // real and imaginary parts independent
    EXPECT_NEAR(beyond3 / N, 0.0026998, 0.0026998 * 0.08);
    // Kolmogorov-Smirnov distance to the normal CDF.
    std::sort(v.begin(), v.end());
    double ks = 0.0;
    for (std::size_t i = 0; i < v.size(); i += 97) {
        const double cdf = 0.5 * std::erfc(-v[i] / std::sqrt(2.0));
        ks = std::max(ks, std::abs(cdf - (i + 0.5) / v.size()));
    }
    EXPECT_LT(ks, 0.0015);
    // The same key gives the same noise; another key other noise.
    std::vector<std::complex<float>> a(100), b(100), c(100);
    detail::add_gaussian_noise(a.data(), 100, 1.0f, 7);
    detail::add_gaussian_noise(b.data(), 100, 1.0f, 7);
    detail::add_gaussian_noise(c.data(), 100, 1.0f, 8);
    EXPECT_EQ(a, b);
    EXPECT_NE(a, c);
}
