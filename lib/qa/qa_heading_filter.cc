/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * heading_filter (the loiter's smoothed heading read) against closed forms: no lag on a
 * turn at a constant rate, across the +-pi wrap; the noise left from white read noise
 * against the alpha-beta filter's steady-state variance ratio; gain 1 is the read; gaps
 * and non-finite reads; seeker_config::loiter_heading_gain checked.
 */

#include "angle.h"
#include "heading_filter.h"
#include <gr-rfseek/seeker.h>
#include <gtest/gtest.h>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

using gr::rfseek::heading_filter;
using gr::rfseek::seeker_config;
using gr::rfseek::wrap_remainder;

namespace {

constexpr double DEG = M_PI / 180.0;
constexpr double DT = 0.05;         // s per slot
constexpr double RATE = 23.0 * DEG; // rad/s: a 25 m orbit at 10 m/s

} // namespace

TEST(heading_filter, follows_a_constant_turn_without_lag_across_the_wrap)
{
    for (double gain : { 0.1, 0.3, 0.7 }) {
        heading_filter f(gain);
        double truth = 3.0; // near +pi: the turn crosses the wrap many times
        f.reset(truth);
        double worst = 0.0;
        for (int k = 1; k <= 4000; ++k) {
            truth = wrap_remainder(truth + RATE * DT);
            const double h = f.update(truth, DT);
            ASSERT_TRUE(std::isfinite(h));
            ASSERT_GT(h, -M_PI);
            ASSERT_LE(h, M_PI);
            if (k > 2000)
                worst = std::max(worst, std::abs(wrap_remainder(h - truth)));
        }
        // The rate state converges to the turn rate: no steady-state lag.
        EXPECT_LT(worst, 1e-9) << "gain " << gain;
    }
}

TEST(heading_filter, white_read_noise_against_the_closed_form)
{
    const double sigma = 3.0 * DEG;
    for (double gain : { 0.1, 0.2, 0.3, 0.5 }) {
        std::mt19937 g(1234);
        std::normal_distribution<double> n(0.0, sigma);
        heading_filter f(gain);
        double truth = -1.0;
        f.reset(truth);
        double sum = 0.0, sum2 = 0.0;
        int count = 0;
        for (int k = 1; k <= 200000; ++k) {
            truth = wrap_remainder(truth - RATE * DT); // a right turn this time
            const double e =
                wrap_remainder(f.update(wrap_remainder(truth + n(g)), DT) - truth);
            if (k > 1000) {
                sum += e;
                sum2 += e * e;
                ++count;
            }
        }
        const double mean = sum / count;
        const double std = std::sqrt(sum2 / count - mean * mean);
        const double expected = sigma * std::sqrt(heading_filter::noise_ratio(gain));
        EXPECT_LT(std::abs(mean), 0.02 * sigma) << "gain " << gain;
        EXPECT_NEAR(std / expected, 1.0, 0.04) << "gain " << gain;
    }
    // The ratio itself: 1 at gain 1 (the read), smaller as the gain falls.
    EXPECT_NEAR(heading_filter::noise_ratio(1.0), 1.0, 1e-12);
    EXPECT_LT(heading_filter::noise_ratio(0.3), 0.25);
    EXPECT_LT(heading_filter::noise_ratio(0.1), heading_filter::noise_ratio(0.3));
}

TEST(heading_filter, gain_one_is_the_read_and_gaps_restart)
{
    heading_filter raw(1.0);
    raw.reset(0.0);
    for (double h : { 0.1, -3.1, 3.1, 0.7 })
        EXPECT_EQ(raw.update(h, DT), h); // bit for bit

    heading_filter f(0.3);
    f.reset(0.0);
    for (int k = 0; k < 100; ++k)
        f.update(0.0, DT);
    // A gap longer than MAX_GAP_S: the filter starts over at the read.
    EXPECT_EQ(f.update(2.0, heading_filter::MAX_GAP_S + DT), 2.0);
    // A read that is not finite is skipped: the prediction (still 2.0, no rate).
    EXPECT_NEAR(f.update(std::nan(""), DT), 2.0, 1e-12);
    // Before any read a non-finite read has nothing to predict from.
    heading_filter fresh(0.3);
    EXPECT_TRUE(std::isnan(fresh.update(std::nan(""), DT)));
    EXPECT_EQ(fresh.update(-1.0, DT), -1.0); // the first read starts it
}

TEST(heading_filter, seeker_config_gain_is_checked)
{
    for (double bad : { 0.0, -0.1, 1.5, std::nan("") }) {
        seeker_config c;
        c.loiter_heading_gain = bad;
        try {
            c.validate();
            ADD_FAILURE() << bad << " accepted";
        } catch (const std::invalid_argument& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("seeker_config.loiter_heading_gain"), std::string::npos)
                << what;
            EXPECT_NE(what.find("(0, 1]"), std::string::npos) << what;
        }
    }
    seeker_config c;
    c.loiter_heading_gain = 1.0;
    EXPECT_NO_THROW(c.validate());
    EXPECT_NO_THROW(c.set("loiter_heading_gain", "0.5"));
    EXPECT_DOUBLE_EQ(c.loiter_heading_gain, 0.5);
}
