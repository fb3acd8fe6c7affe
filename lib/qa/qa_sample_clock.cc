/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * sample_clock: each sample's time from the rx_time / rx_rate tag in force at it, at an
 * epoch of 1.7e9 s to the microsecond; an overflow's tag is a discontinuity of the
 * samples lost, a consistent tag is not, and a clock set back is a negative one.
 */

#include "sample_clock.h"
#include <gtest/gtest.h>
#include <cmath>

using namespace gr::rfseek;

TEST(sample_clock, each_sample_keeps_the_time_of_the_tag_in_force)
{
    sample_clock c(1e5);
    EXPECT_DOUBLE_EQ(c.time_of(250000), 2.5); // no tag: offset / rate
    EXPECT_FALSE(c.on_time(1000, 1700000000.0, 0.25).discontinuity); // the first
    // 3000 samples lost before sample 500000: the tag there says so (0.25 + 502000 /
    // 1e5 = 5.27 s after the epoch).
    const auto j = c.on_time(500000, 1700000005.0, 0.27);
    EXPECT_TRUE(j.discontinuity);
    EXPECT_NEAR(j.samples, 3000.0, 1e-3);
    EXPECT_NEAR(j.seconds, 0.03, 1e-8);
    EXPECT_EQ(c.discontinuities(), 1u);
    // A window before the tag keeps the earlier anchor's time; after it, the new one's.
    EXPECT_NEAR(c.time_of(499000) - 1700000000.0, 0.25 + 498000 / 1e5, 1e-6);
    EXPECT_NEAR(c.time_of(500100) - 1700000000.0, 0.25 + 502100 / 1e5, 1e-6);
    EXPECT_DOUBLE_EQ(c.time_of(500), 500 / 1e5); // before the first tag: offset / rate
    // A consistent tag (a re-tag) is no discontinuity.
    EXPECT_FALSE(c.on_time(600000, 1700000006.0, 0.27).discontinuity);
    // The clock set back by 2 s: a negative discontinuity.
    const auto back = c.on_time(700000, 1700000005.0, 0.27);
    EXPECT_TRUE(back.discontinuity);
    EXPECT_NEAR(back.seconds, -2.0, 1e-6);
    EXPECT_EQ(c.discontinuities(), 2u);
}

TEST(sample_clock, a_new_rate_continues_the_time)
{
    sample_clock c(1e5);
    c.on_time(0, 10.0, 0.5);
    EXPECT_TRUE(c.on_rate(200000, 2e5)); // from 12.5 s on at 200 kS/s
    EXPECT_NEAR(c.time_of(100000), 11.5, 1e-12);
    EXPECT_NEAR(c.time_of(400000), 13.5, 1e-12);
    EXPECT_DOUBLE_EQ(c.rate_at(100000), 1e5);
    EXPECT_DOUBLE_EQ(c.rate_at(400000), 2e5);
    // At the new rate the count agrees with a later tag.
    EXPECT_FALSE(c.on_time(600000, 14.0, 0.5).discontinuity);
    EXPECT_FALSE(c.on_rate(800000, -1.0));
    EXPECT_FALSE(c.on_rate(800000, std::nan("")));
    bool ok = true;
    c.on_time(900000, std::nan(""), 0.0, &ok);
    EXPECT_FALSE(ok);
    c.on_time(10, 1.0, 0.0, &ok); // before the last anchor
    EXPECT_FALSE(ok);
    c.forget_before(650000);
    EXPECT_EQ(c.anchors(), 1u);
    EXPECT_NEAR(c.time_of(700000), 15.0, 1e-12);
}
