/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * channel_source in a flowgraph: the samples are the core world's, slot by slot, with the
 * documented tags; the stream ends at d_v.
 */

#include <gnuradio/blocks/vector_sink.h>
#include <gnuradio/top_block.h>
#include <gr-rfseek/channel_source.h>
#include <gr-rfseek/world.h>
#include <gtest/gtest.h>
#include <cmath>
#include <cstring>

using namespace gr::rfseek;

namespace {
scenario short_run()
{
    scenario s;
    s.seed = 9;
    s.initial_distance_m = 210.0;
    s.start_angle_rad = 0.5;
    s.start_heading_rad = 0.5 + M_PI; // straight at the emitter: 20 slots to d_v
    return s;
}
} // namespace

TEST(channel_source, free_running_burst_matches_core_world)
{
    const scenario s = short_run();
    auto tb = gr::make_top_block("qa");
    auto src = channel_source::make(s, "burst", false, false);
    auto snk = gr::blocks::vector_sink_c::make();
    tb->connect(src, 0, snk, 0);
    tb->run();

    const auto& data = snk->data();
    ASSERT_EQ(data.size(), 20u * s.window_len);
    world w(s);
    for (int k = 0; k < 20; ++k) {
        const auto x = w.synthesize(s.window_len);
        EXPECT_EQ(0,
                  std::memcmp(
                      x.data(), data.data() + k * s.window_len, x.size() * sizeof(x[0])))
            << "slot " << k;
        w.advance(w.heading_rad());
    }
    EXPECT_TRUE(w.arrived());

    int beacons = 0, rx_time = 0, rx_rate = 0, rx_freq = 0;
    for (const auto& t : snk->tags()) {
        const std::string key = pmt::symbol_to_string(t.key);
        if (key == "rfseek_beacon") {
            const auto slot =
                pmt::to_uint64(pmt::dict_ref(t.value, pmt::mp("slot"), pmt::PMT_NIL));
            EXPECT_EQ(t.offset, slot * s.window_len);
            EXPECT_DOUBLE_EQ(
                pmt::to_double(pmt::dict_ref(t.value, pmt::mp("time"), pmt::PMT_NIL)),
                slot * s.slot_period_s);
            EXPECT_TRUE(
                pmt::is_real(pmt::dict_ref(t.value, pmt::mp("heading"), pmt::PMT_NIL)));
            ++beacons;
        } else if (key == "rx_time") {
            ++rx_time;
        } else if (key == "rx_rate") {
            EXPECT_EQ(t.offset, 0u);
            EXPECT_EQ(pmt::to_double(t.value), s.samp_rate_hz);
            ++rx_rate;
        } else if (key == "rx_freq") {
            EXPECT_EQ(t.offset, 0u);
            EXPECT_EQ(pmt::to_double(t.value), s.carrier_hz);
            ++rx_freq;
        }
    }
    EXPECT_EQ(beacons, 20);
    EXPECT_EQ(rx_time, 20); // burst mode: every burst is timed
    EXPECT_EQ(rx_rate, 1);
    EXPECT_EQ(rx_freq, 1);
}

TEST(channel_source, continuous_mode_emits_whole_slots)
{
    const scenario s = short_run();
    auto tb = gr::make_top_block("qa");
    auto src = channel_source::make(s, "continuous", false, false);
    auto snk = gr::blocks::vector_sink_c::make();
    tb->connect(src, 0, snk, 0);
    tb->run();
    ASSERT_EQ(snk->data().size(), 20u * s.slot_samples());
    int beacons = 0, rx_time = 0;
    for (const auto& t : snk->tags()) {
        const std::string key = pmt::symbol_to_string(t.key);
        if (key == "rfseek_beacon") {
            EXPECT_EQ(t.offset % s.slot_samples(), 0u);
            ++beacons;
        } else if (key == "rx_time") {
            EXPECT_EQ(t.offset, 0u);
            ++rx_time;
        }
    }
    EXPECT_EQ(beacons, 20);
    EXPECT_EQ(rx_time, 1);
}

TEST(channel_source, bad_parameters_throw)
{
    EXPECT_THROW(channel_source::make(short_run(), "bursty"), std::invalid_argument);
    scenario s = short_run();
    s.fft_len = 2;
    EXPECT_THROW(channel_source::make(s), std::invalid_argument);
}
