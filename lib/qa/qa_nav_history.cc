/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * nav_history: a window takes the heading of the report nearest its time (interpolated
 * between two around it), reports late or out of order go where they belong, a link
 * silent for 2 s leaves the windows in its middle without a heading, a foreign clock's
 * offset is learned from the fastest reports, and reports without a time are timed by
 * their arrival.
 */

#include "nav_history.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

using namespace gr::rfseek;

TEST(nav_history, the_report_nearest_in_time_interpolated_and_in_order)
{
    nav_history h;
    h.measured(10.5);
    // Reports every 0.1 s of a turn at 0.5 rad/s, the one at 10.3 s arriving last.
    for (const double t : { 10.0, 10.1, 10.2, 10.4, 10.5, 10.3 })
        h.report(0.5 * (t - 10.0), true, t);
    auto p = h.at(10.25);
    ASSERT_TRUE(p.found);
    EXPECT_NEAR(p.heading_rad, 0.125, 1e-12);
    EXPECT_NEAR(p.offset_s, 0.05, 1e-12);
    p = h.at(10.3);
    EXPECT_NEAR(p.heading_rad, 0.15, 1e-12);
    // Past the last report (within a second): carried on at the turn rate of the last
    // two, for at most half a second.
    p = h.at(10.6);
    ASSERT_TRUE(p.found);
    EXPECT_NEAR(p.heading_rad, 0.3, 1e-12);
    p = h.at(11.2);
    ASSERT_TRUE(p.found);
    EXPECT_NEAR(p.heading_rad, 0.25 + 0.5 * 0.5, 1e-12);
    EXPECT_NEAR(p.offset_s, -0.7, 1e-12);
    EXPECT_FALSE(h.at(11.6).found);
    EXPECT_FALSE(h.foreign_clock());
    // Reports 6 s behind the latest window: one is a late packet, five in a row are on
    // another clock.
    h.measured(16.6);
    h.report(0.0, true, 10.6);
    EXPECT_FALSE(h.foreign_clock());
    for (int k = 1; k < 5; ++k)
        h.report(0.0, true, 10.6 + 0.01 * k);
    EXPECT_TRUE(h.foreign_clock());
}

TEST(nav_history, a_silent_link_leaves_windows_without_a_heading)
{
    nav_history h;
    for (int k = 0; k <= 60; ++k) {
        h.measured(0.1 * k);
        if (k <= 20 || k >= 41) // silent from 2.0 to 4.1 s
            h.report(k <= 20 ? 1.0 : 2.0, true, 0.1 * k);
    }
    EXPECT_FALSE(h.foreign_clock());
    EXPECT_EQ(h.at(2.5).heading_rad, 1.0);
    EXPECT_TRUE(h.at(2.9).found);          // 0.9 s after the last report
    EXPECT_FALSE(h.at(3.05).found);        // over 1 s from both
    EXPECT_EQ(h.at(3.5).heading_rad, 2.0); // 0.6 s before the next
}

TEST(nav_history, a_foreign_clock_and_late_reports)
{
    // Windows every 0.05 s; reports every 0.1 s on a clock 1000 s ahead, each arriving
    // 0.05-0.4 s late (so out of order); heading = the report's own time.
    const double lag[] = { 0.3, 0.05, 0.4, 0.2, 0.1, 0.35, 0.05, 0.25 };
    std::vector<std::pair<double, int>> events; // (arrival, -1: window, k: report)
    for (int j = 0; j < 100; ++j)
        events.emplace_back(0.05 * j + 0.001, -1);
    for (int k = 0; k < 40; ++k)
        events.emplace_back(0.1 * k + lag[k % 8], k);
    std::sort(events.begin(), events.end());
    nav_history h;
    for (const auto& [at, k] : events) {
        if (k < 0)
            h.measured(at - 0.001);
        else
            h.report(0.1 * k, true, 1000.0 + 0.1 * k);
    }
    EXPECT_TRUE(h.foreign_clock());
    // The fastest reports (0.05 s late, up to a window's 0.05 s) set the offset: a
    // window at 2 s gets the heading of 1.9-2.0 s, not of the report that arrived last.
    const auto p = h.at(2.0);
    ASSERT_TRUE(p.found);
    EXPECT_GE(p.heading_rad, 1.9 - 1e-9);
    EXPECT_LE(p.heading_rad, 2.0 + 1e-9);
}

TEST(nav_history, reports_without_a_time_are_timed_by_their_arrival)
{
    nav_history h;
    h.report(0.7, false, 0.0); // before any window: timed by the first
    EXPECT_TRUE(h.any());
    h.measured(5.0);
    EXPECT_NEAR(h.at(5.0).heading_rad, 0.7, 1e-12);
    h.report(0.8, false, 0.0);
    h.report(0.9, false, 0.0); // the later of two at the same time wins
    h.measured(5.05);
    EXPECT_NEAR(h.at(5.05).heading_rad, 0.9, 1e-12);
    h.report(std::nan(""), false, 0.0); // ignored
    h.measured(6.5);
    EXPECT_FALSE(h.at(6.5).found); // 1.45 s since the last report
}

TEST(nav_history, timed_reports_before_the_first_window_on_another_clock)
{
    // A vehicle's reports on the epoch (1.7e9 s) arrive before the first window (0.05 s).
    nav_history h;
    h.report(0.1, true, 1.7e9 + 0.0);
    h.report(0.2, true, 1.7e9 + 0.1);
    h.measured(0.05);
    EXPECT_TRUE(h.foreign_clock());
    const auto p = h.at(0.05);
    ASSERT_TRUE(p.found);
    EXPECT_NEAR(p.heading_rad, 0.2, 1e-6); // (the epoch's float precision)
    h.measured(0.15);
    h.report(0.3, true, 1.7e9 + 0.2); // arrives with the window at 0.15: the same offset
    EXPECT_NEAR(h.at(0.15).heading_rad, 0.3, 1e-6);
}
