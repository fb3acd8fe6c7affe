/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * channel_source: the simulated world as a GNU Radio source (emitter, scatterers, UAV,
 * CFO). A thin adapter over gr::rfseek::world.
 */

#ifndef INCLUDED_RFSEEK_CHANNEL_SOURCE_H
#define INCLUDED_RFSEEK_CHANNEL_SOURCE_H

#include <gnuradio/sync_block.h>
#include <gr-rfseek/api.h>
#include <gr-rfseek/scenario.h>
#include <cstdint>
#include <string>

namespace gr {
namespace rfseek {

/*!
 * \brief Simulated beacon as received by the UAV, one slot at a time.
 * \ingroup rfseek
 *
 * \details
 * Output: complex64 at scenario.samp_rate_hz. Mode "burst" emits the N-sample beacon of
 * each slot; mode "continuous" emits the whole slot (T_slot * fs samples, beacon first,
 * noise after). The beacon's first sample carries tag "rfseek_beacon" = {slot, time,
 * heading (measured)}; like uhd.usrp_source, sample 0 carries rx_time, rx_rate and
 * rx_freq (in burst mode every burst carries rx_time).
 *
 * Message in "cmd": dict {heading (rad), optional slot}: the heading to fly; the UAV
 * turns toward it at most at the turn rate. Message out "state": per-slot truth {slot,
 * time, x, y, heading, measured_heading, distance, distance_flown, cfo_hz, doppler_hz,
 * snr_db, power_db, arrived, capped} for logs and plots (never for the controller).
 *
 * lockstep (default): slot k+1 is produced only after the cmd for slot k arrived, so a
 * run is reproducible from its seed. Otherwise the source runs free and applies the
 * newest cmd it has at each slot boundary (the receive chain lags by a few slots, so a
 * cmd for a past slot is flown late rather than dropped); realtime paces the output to
 * the sample clock, speedup times faster (a sped-up rehearsal of a live run). The stream
 * ends (WORK_DONE) when the UAV is within success_radius_m or has flown the flight cap.
 * Malformed cmd messages are logged once per kind, counted and dropped.
 *
 * follow_truth: the vehicle is flown by something else (ArduPilot's or PX4's SITL) and
 * the world follows its true state, given on message port "truth" as dicts {time (s,
 * the simulator's clock), east, north, up (m, any local level frame whose height is the
 * emitter's ground), v_east, v_north, v_up (m/s over the ground), heading (rad, true,
 * counter-clockwise from east)}, in time order. Slot k is the truth at t0 + k T_slot, t0
 * the first truth's time (interpolated between the two truths around it), and is
 * produced only once a truth at or after that time has arrived: the samples, their
 * times and the Doppler follow the simulator's clock, whatever its pace (realtime and
 * speedup do not apply). The first truth places the emitter (world::follow). Headings
 * on "cmd" are not flown (the autopilot flies them); a cmd's "done" still ends a
 * self-arrival run. The beacon tags carry no heading: the vehicle's heading reaches
 * the controller from the autopilot, as in flight. Truths that are malformed or go
 * back in time are logged once per kind, counted and dropped.
 */
class RFSEEK_API channel_source : virtual public gr::sync_block
{
public:
    typedef std::shared_ptr<channel_source> sptr;

    /*!
     * \param sc the run's scenario (validated; bad fields raise std::invalid_argument)
     * \param mode "burst" or "continuous"
     * \param lockstep wait for the cmd of each slot before producing the next
     * \param realtime pace output to real time (for live-looking demos)
     * \param speedup pacing speed-up over real time, in (0, 1e6] (1: real time)
     * \param follow_truth follow the true state on "truth" (a vehicle flown by SITL)
     */
    static sptr make(const scenario& sc,
                     const std::string& mode = "burst",
                     bool lockstep = true,
                     bool realtime = false,
                     double speedup = 1.0,
                     bool follow_truth = false);

    virtual scenario config() const = 0;
    virtual std::string mode() const = 0;
    //! Current slot index (the slot being, or last, produced).
    virtual std::uint64_t slot() const = 0;
    //! cmd messages dropped as malformed.
    virtual std::uint64_t malformed_count() const = 0;
    /*!
     * cmd messages ignored as stale. In lockstep: a slot other than the current one.
     * Free-running: a slot older than the newest command applied, or one not flown yet.
     */
    virtual std::uint64_t stale_count() const = 0;
    //! Free-running: commands applied after their slot had passed (the latest one wins).
    virtual std::uint64_t late_count() const = 0;
    virtual bool lockstep() const = 0;
    //! The world follows the truth on "truth".
    virtual bool follow_truth() const = 0;
    //! follow_truth: truths received and kept (in time order, well formed).
    virtual std::uint64_t truth_count() const = 0;
    //! follow_truth: truths dropped (malformed, or before the last one).
    virtual std::uint64_t truth_dropped_count() const = 0;
    virtual bool realtime() const = 0;
    virtual double speedup() const = 0;

    virtual void set_snr_db(double snr_db) = 0;
    virtual void set_heading_noise_rad(double sigma) = 0;
    virtual void set_turn_rate_rad_per_s(double rate) = 0;
    virtual void set_lockstep(bool lockstep) = 0;
    virtual void set_realtime(bool realtime) = 0;
    //! Throws std::invalid_argument outside (0, 1e6].
    virtual void set_speedup(double speedup) = 0;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_CHANNEL_SOURCE_H */
