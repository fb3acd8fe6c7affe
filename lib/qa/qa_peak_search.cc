/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The vectorised kernels against plain loops: argmax of |X|^2 (first index on ties) with
 * Parseval's total, and the table-phasor demodulating dot product.
 */

#include "peak_search.h"
#include <gr-rfseek/rng.h>
#include <gtest/gtest.h>
#include <cmath>
#include <vector>

using namespace gr::rfseek;

TEST(peak_search, matches_a_plain_loop)
{
    rng g(21);
    for (std::uint32_t n : { 1u, 7u, 8u, 9u, 64u, 1000u, 4096u }) {
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
            const auto p = detail::peak_search(x.data(), n);
            ASSERT_EQ(p.index, best) << "n " << n << " trial " << trial;
            EXPECT_EQ(p.value, std::norm(x[best]));
            EXPECT_NEAR(p.total, total, 1e-5 * total);
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
    }
}
