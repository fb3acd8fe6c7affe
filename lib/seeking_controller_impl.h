/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#ifndef INCLUDED_RFSEEK_SEEKING_CONTROLLER_IMPL_H
#define INCLUDED_RFSEEK_SEEKING_CONTROLLER_IMPL_H

#include "nav_history.h"
#include <gr-rfseek/seeking_controller.h>
#include <atomic>
#include <chrono>
#include <deque>
#include <memory>
#include <set>
#include <thread>

namespace gr {
namespace rfseek {

class seeking_controller_impl : public seeking_controller
{
public:
    explicit seeking_controller_impl(const seeker_config& cfg);
    ~seeking_controller_impl() override
    {
        d_running = false;
        if (d_watchdog.joinable())
            d_watchdog.join();
    }

    seeker_config config() const override;
    int stage() const override;
    double theta_est() const override;
    std::uint64_t updates() const override;
    std::uint64_t meas_count() const override;
    std::uint64_t invalid_count() const override;
    std::uint64_t malformed_count() const override;
    int status() const override;
    bool done() const override;
    void set_wait_for_heading(bool wait) override;
    bool set_wind_forecast(double east_mps, double north_mps) override;
    bool wait_for_heading() const override;
    std::uint64_t waiting_count() const override;
    std::uint64_t unpaired_count() const override;
    bool start() override;
    bool stop() override;
    emitter_location location() const override;

private:
    gr::thread::mutex& setlock() const
    {
        return const_cast<gr::thread::mutex&>(d_setlock);
    }
    void handle_meas(const pmt::pmt_t& msg);
    void handle_nav(const pmt::pmt_t& msg);
    // Measurements waiting for the nav report of their time (in order), and their
    // processing once it has come or nav_wait_s of later windows have.
    void drain(bool watchdog = false, bool force = false);
    void process(measurement m);
    std::deque<measurement> d_pending;
    std::deque<std::chrono::steady_clock::time_point> d_pending_since;
    double d_nav_wait_s = 0.5;
    // A window never waits more than 0.5 s of host time: a lockstep source makes the
    // next window only after the cmd (a watchdog thread releases it).
    std::thread d_watchdog;
    std::atomic<bool> d_running{ false };
    bool d_logged_wait = false;
    void drop(const std::string& port, const std::string& kind, const pmt::pmt_t& msg);
    // A meas forwarded from channel_source's beacon tag carries the world's "world"
    // dict: warns once for each of speed, carrier and slot period told otherwise.
    void check_world(const pmt::pmt_t& world);
    bool d_world_checked = false;

    std::unique_ptr<seeker> d_seeker;
    nav_history d_nav;            // heading reports on the measurements' clock
    std::uint64_t d_unpaired = 0; // windows with no report near their time
    bool d_wait_heading = false;  // set_wait_for_heading
    bool d_seeking = false;       // a meas has reached the strategy
    std::uint64_t d_waiting = 0;
    std::uint64_t d_meas = 0, d_invalid = 0, d_malformed = 0;
    std::set<std::string> d_logged;

    void publish_status(const command& c, double time_s);
    void publish_telemetry(const command& c,
                           const measurement& m,
                           bool from_nav,
                           const nav_history::pick& nav);
    int d_status = -1; // last published status (-1: none yet)
    emitter_location d_location;
    bool d_done = false;
    double d_fix_time = -1.0; // time of the last published fix

    const pmt::pmt_t d_port_meas, d_port_nav, d_port_cmd, d_port_telemetry, d_port_status;
    const pmt::pmt_t d_key_slot, d_key_heading, d_key_freq, d_key_valid, d_key_snr,
        d_key_power, d_key_time, d_key_stage;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_SEEKING_CONTROLLER_IMPL_H */
