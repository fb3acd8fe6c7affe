/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rss_baseline's two phases on synthetic power tracks with known answers:
 * - direction: a scan circle whose power fades slowly only within a few degrees of the
 *   line of sight (both ways along it) and fast across it, plus a mean-power trend
 *   across the circle toward the emitter: the axis and the way along it come back;
 * - run: long-term averages along a run that rises and then falls (a tent) end the run
 *   when the later window's mean drops below the earlier's, at the block the closed
 *   form gives, and not while the power rises under fast fading.
 */

#include "rss_phases.h"
#include <gr-rfseek/rng.h>
#include <gr-rfseek/world.h>
#include <gtest/gtest.h>
#include <cmath>
#include <stdexcept>
#include <vector>

using gr::rfseek::rng;
using gr::rfseek::world;
namespace rss = gr::rfseek::rss;

namespace {

constexpr double DEG = M_PI / 180.0;

// A scan circle of radius_m flown from heading base with turning sense `sense`, one
// slot per 0.5 m. The emitter lies at bearing `los` from the circle's centre: within
// 4 deg of the line of sight (either way) the power follows a slow random walk (0.02 dB
// per slot), elsewhere it fades fast (i.i.d. 4 dB); on top, the mean power rises by
// gradient_db_per_m toward the emitter across the circle.
struct circle {
    std::vector<double> power_db, heading_rad;
};

circle scan_circle(
    double los, double sense, double base, double gradient_db_per_m, std::uint64_t seed)
{
    const double radius = 100.0;
    const double step = 0.5 / radius;
    const int n = static_cast<int>(std::lround(2.0 * M_PI / step));
    rng g(seed);
    circle c;
    double slow = 0.0;
    for (int k = 1; k <= n; ++k) {
        const double h = base + sense * k * step;
        const double off = std::abs(world::wrap(2.0 * (h - los))) / 2.0; // mod pi
        slow += 0.02 * g.normal();
        const double fading = off < 4.0 * DEG ? slow : 4.0 * g.normal();
        const double psi = h - sense * M_PI / 2.0; // position angle on the circle
        const double trend = gradient_db_per_m * radius * std::cos(psi - los);
        c.power_db.push_back(-60.0 + trend + fading);
        c.heading_rad.push_back(world::wrap(h + 2.0 * DEG * g.normal()));
    }
    return c;
}

// A run's powers, one per slot: blocks of `block` slots whose mean rises by `slope` dB
// per block up to block `peak` and falls as fast after it, with i.i.d. fading of
// `fading_db` per slot.
std::vector<double> tent(int block, int peak, int blocks, double slope, double fading_db)
{
    rng g(77);
    std::vector<double> p;
    for (int b = 0; b < blocks; ++b)
        for (int k = 0; k < block; ++k) {
            const double x = b + (k + 0.5) / block;
            const double mean = slope * (x < peak + 0.5 ? x : 2.0 * (peak + 0.5) - x);
            p.push_back(-60.0 + mean + fading_db * g.normal());
        }
    return p;
}

// The block whose comparison ends the run (-1: it never ends).
int ending_block(rss::run_monitor& m, const std::vector<double>& p, int block)
{
    for (std::size_t i = 0; i < p.size(); ++i)
        if (m.add(p[i]))
            return static_cast<int>(i) / block;
    return -1;
}

} // namespace

TEST(rss_direction, slow_fading_marks_the_axis_and_the_trend_the_way)
{
    int n = 0;
    for (double los : { -170.0, -95.0, -20.0, 0.0, 45.0, 120.0 })
        for (double sense : { 1.0, -1.0 })
            for (double toward : { 1.0, -1.0 }) {
                // toward = -1: the emitter lies the other way along the same axis.
                const double bearing = (toward > 0 ? los : los + 180.0) * DEG;
                const circle c = scan_circle(los * DEG, sense, 0.3, 0.03 * toward, ++n);
                const auto e =
                    rss::estimate_direction(c.power_db, c.heading_rad, sense, 100.0);
                ASSERT_TRUE(e.valid);
                const double axis_err =
                    std::abs(world::wrap(2.0 * (e.axis_rad - los * DEG)));
                EXPECT_LE(axis_err / 2.0, 6.0 * DEG) << los << " " << sense;
                EXPECT_LE(std::abs(world::wrap(e.way_rad - bearing)), 6.0 * DEG)
                    << los << " " << sense << " " << toward;
                // The slope across the circle, 0.03 dB/m, within 20 % (the fast fading
                // leaves a standard error of 4 dB sqrt(2 / 1257) / 100 m = 0.0016 dB/m).
                EXPECT_NEAR(e.trend_db_per_m, 0.03, 0.006);
                EXPECT_LT(e.slow_rate_db, 0.25 * e.typical_rate_db);
            }
}

TEST(rss_direction, too_little_power_is_no_estimate)
{
    circle c = scan_circle(0.0, 1.0, 0.0, 0.01, 3);
    for (std::size_t k = 20; k < c.power_db.size(); ++k)
        c.power_db[k] = NAN;
    EXPECT_FALSE(rss::estimate_direction(c.power_db, c.heading_rad, 1.0, 100.0).valid);
    EXPECT_FALSE(rss::estimate_direction({}, {}, 1.0, 100.0).valid);
}

TEST(rss_run, ends_when_the_long_term_average_turns)
{
    // Without fading a tent peaking at block K ends the run at block K + w: the first
    // block whose window of w blocks averages below the window before (the two are
    // symmetric about the peak at K + w - 1/2).
    const int block = 200, peak = 12;
    for (int w : { 2, 3, 5 }) {
        rss::run_monitor m(block, w, 0.0);
        EXPECT_EQ(ending_block(m, tent(block, peak, 40, 0.3, 0.0), block), peak + w) << w;
        EXPECT_LT(m.last_change_db(), 0.0);
    }
    // With 5 dB of fast fading per slot (a block's mean: 0.35 dB) and a 0.3 dB rise per
    // block, the run goes on over the whole rise and ends at most one block late.
    rss::run_monitor m(block, 5, 0.0);
    const int end = ending_block(m, tent(block, peak, 40, 0.3, 5.0), block);
    EXPECT_GE(end, peak + 4);
    EXPECT_LE(end, peak + 6);
    // A fall margin keeps the run going until the average fell by that much: with
    // w = 5 the windows differ by 1.5 dB on the fall, by more than 1 dB from block
    // K + 4 + 1 on (the difference falls by 0.6 dB per block from K + 2).
    rss::run_monitor late(block, 5, 1.0);
    const int margin_end = ending_block(late, tent(block, peak, 40, 0.3, 0.0), block);
    EXPECT_GT(margin_end, peak + 5);
    EXPECT_LE(margin_end, peak + 10);
}

TEST(rss_run, missing_powers_are_skipped_and_bad_settings_named)
{
    rss::run_monitor m(10, 1, 0.0);
    for (int k = 0; k < 100; ++k)
        EXPECT_FALSE(m.add(NAN));
    EXPECT_EQ(m.blocks(), 0u);
    EXPECT_TRUE(std::isnan(m.last_change_db()));
    for (int k = 0; k < 10; ++k)
        m.add(k < 3 ? -50.0 : NAN); // 3 of 10: counted (at least a quarter)
    EXPECT_EQ(m.blocks(), 1u);
    for (int k = 0; k < 10; ++k)
        m.add(-53.0); // 3 dB lower: the run ends
    EXPECT_NEAR(m.last_change_db(), -3.0, 1e-12);
    m.reset();
    EXPECT_EQ(m.blocks(), 0u);
    auto names = [](int block, int w, double fall, const char* word) {
        try {
            rss::run_monitor bad(block, w, fall);
            ADD_FAILURE() << word;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
        }
    };
    names(2, 5, 0.0, "block_slots");
    names(200, 0, 0.0, "window");
    names(200, 5, NAN, "fall_db");
    names(200, 5, -1.0, "fall_db");
}
