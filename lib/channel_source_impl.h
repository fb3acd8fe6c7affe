/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#ifndef INCLUDED_RFSEEK_CHANNEL_SOURCE_IMPL_H
#define INCLUDED_RFSEEK_CHANNEL_SOURCE_IMPL_H

#include <gr-rfseek/channel_source.h>
#include <gr-rfseek/world.h>
#include <array>
#include <chrono>
#include <deque>
#include <set>
#include <vector>

namespace gr {
namespace rfseek {

class channel_source_impl : public channel_source
{
public:
    channel_source_impl(const scenario& sc,
                        const std::string& mode,
                        bool lockstep,
                        bool realtime,
                        double speedup,
                        bool follow_truth);

    int work(int noutput_items,
             gr_vector_const_void_star& input_items,
             gr_vector_void_star& output_items) override;
    bool start() override;

    scenario config() const override;
    std::string mode() const override { return d_continuous ? "continuous" : "burst"; }
    std::uint64_t slot() const override;
    std::uint64_t malformed_count() const override;
    std::uint64_t stale_count() const override;
    std::uint64_t late_count() const override;
    bool lockstep() const override;
    bool follow_truth() const override { return d_follow; }
    std::uint64_t truth_count() const override;
    std::uint64_t truth_dropped_count() const override;
    bool realtime() const override;

    void set_snr_db(double snr_db) override;
    void set_heading_noise_rad(double sigma) override;
    void set_turn_rate_rad_per_s(double rate) override;
    void set_lockstep(bool lockstep) override;
    void set_realtime(bool realtime) override;
    double speedup() const override;
    void set_speedup(double speedup) override;

private:
    gr::thread::mutex& setlock() const
    {
        return const_cast<gr::thread::mutex&>(d_setlock);
    }
    void handle_cmd(const pmt::pmt_t& msg);
    void handle_truth(const pmt::pmt_t& msg);
    // follow_truth: the truth at slot k's time, if one at or after it has arrived.
    bool truth_at(std::uint64_t k, vehicle_truth& out);
    void end_run_now();
    void drop(const std::string& kind, const pmt::pmt_t& msg);
    // work() found nothing to emit until a message arrives: after PARKED_WARN_S of
    // wall time, says once what it waits for (a flowgraph without a controller).
    void parked(const char* what);
    static constexpr double PARKED_WARN_S = 1.5;
    void begin_slot(std::uint64_t offset);
    void publish_state();
    void reanchor(); // d_t0 such that the world's time is due now
    // The world's present time on the pace's clock (d_setlock held).
    std::chrono::steady_clock::duration paced_time() const;
    // Until the world's present slot is due (zero or less: due, or not paced).
    std::chrono::steady_clock::duration time_to_due() const;
    static constexpr long long MAX_NAP_US = 20000; // longest pacing sleep (20 ms)

    world d_world;
    const bool d_continuous;
    const bool d_follow;
    std::deque<vehicle_truth> d_truth; // follow_truth: received, in time order
    double d_truth_t0 = 0.0;           // the first truth's time: slot 0
    std::uint64_t d_truth_count = 0, d_truth_dropped = 0;
    bool d_lockstep;
    bool d_realtime;
    double d_speedup = 1.0;
    std::vector<gr_complex> d_buf;
    std::size_t d_pos = 0;
    bool d_started = false;
    bool d_next_ready = false; // advanced to a slot not yet begun
    bool d_done = false;
    bool d_have_cmd = false;
    bool d_end_requested = false; // self_arrival: the controller declared it done
    bool d_warned_no_done = false;
    double d_cmd_heading = 0.0;
    std::uint64_t d_malformed = 0;
    std::uint64_t d_stale = 0;
    std::uint64_t d_late = 0;
    long long d_cmd_slot = -1; // slot of the newest command applied
    std::set<std::string> d_logged;
    std::chrono::steady_clock::time_point d_t0;
    bool d_parked = false, d_warned_parked = false;
    std::chrono::steady_clock::time_point d_parked_since;

    const pmt::pmt_t d_port_cmd;
    const pmt::pmt_t d_port_truth;
    // The truth's keys, in the order of vehicle_truth's fields.
    static constexpr std::size_t TRUTH_FIELDS = 8;
    const std::array<pmt::pmt_t, TRUTH_FIELDS> d_truth_keys;
    const pmt::pmt_t d_port_state;
    const pmt::pmt_t d_key_beacon;
    const pmt::pmt_t d_key_slot;
    const pmt::pmt_t d_key_time;
    const pmt::pmt_t d_key_heading;
    const pmt::pmt_t d_key_rx_time;
    const pmt::pmt_t d_key_rx_rate;
    const pmt::pmt_t d_key_rx_freq;
    const pmt::pmt_t d_key_world;
    const pmt::pmt_t d_world_info; // the beacon tag's "world" (world_info)
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_CHANNEL_SOURCE_IMPL_H */
