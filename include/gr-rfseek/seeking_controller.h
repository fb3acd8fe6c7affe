/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * seeking_controller: the seeker as a message block (meas, nav in; cmd, telemetry out).
 * A thin adapter over gr::rfseek::seeker.
 */

#ifndef INCLUDED_RFSEEK_SEEKING_CONTROLLER_H
#define INCLUDED_RFSEEK_SEEKING_CONTROLLER_H

#include <gnuradio/block.h>
#include <gr-rfseek/api.h>
#include <gr-rfseek/seeker.h>
#include <cstdint>

namespace gr {
namespace rfseek {

/*!
 * \brief Steers the UAV from frequency measurements (paper Sec. III).
 * \ingroup rfseek
 *
 * \details
 * In "meas": dicts from doppler_estimator {slot, freq_hz, valid, heading?, snr_db?,
 * power_db?, time?}. In "nav": dicts {heading, time?} from the vehicle; the heading of a
 * meas is used when present, else the nav report nearest the window's time (reports
 * late, out of order or on another clock are timed as nav_history says: a "time" on
 * the measurements' clock is used as it is, one on another clock is moved by an
 * offset learned from the fastest reports, none is the arrival), interpolated between
 * the two around it; with no report within 1 s the window has no heading (counted,
 * unpaired_count; telemetry nav_paired false) and the strategy flies on its own
 * heading model. Every meas with a usable slot is
 * answered (but while waiting for the first heading: set_wait_for_heading below)
 * by one "cmd" {slot, heading, stage} and one "telemetry" {slot, stage,
 * theta_est, update, holding, accepted, filtered_freq_hz, freq_hz, valid, and
 * flown_heading, nav_paired, nav_offset_s when from nav}. Invalid
 * measurements are ignored by the strategy (a cmd is still sent so a lockstep source
 * keeps going); after a run of them the course is held. Malformed messages are logged
 * once per kind, counted and dropped.
 *
 * With cfg.self_arrival (docs/seeker.md, "Arrival and location") the strategy is wrapped
 * by the overflight detector, the loiter orbit and the emitter locator; the cmd then also
 * carries {status (0 seeking, 1 arrived, 2 located), done} (a channel_source whose
 * scenario has self_arrival ends the run at `done`), telemetry carries status, and the
 * "status" port publishes {status: 'seeking' | 'arrived' | 'located', slot, time, done}
 * at every change of status or done, plus for every new fix {east_m, north_m, range_m,
 * bearing_rad (emitter relative to the vehicle: x east, y north by its compass; the
 * angle counter-clockwise from east), dr_x_m, dr_y_m, major_m, minor_m,
 * major_angle_rad (95 % ellipse), wind_east_mps, wind_north_mps, altitude_m, fix_time,
 * rms_hz}. Without self_arrival "status" says 'seeking' once.
 */
class RFSEEK_API seeking_controller : virtual public gr::block
{
public:
    typedef std::shared_ptr<seeking_controller> sptr;

    //! \param cfg strategy and constants (validated; bad fields raise ValueError)
    static sptr make(const seeker_config& cfg);

    virtual seeker_config config() const = 0;
    virtual int stage() const = 0;
    virtual double theta_est() const = 0;
    virtual std::uint64_t updates() const = 0;
    virtual std::uint64_t meas_count() const = 0;
    virtual std::uint64_t invalid_count() const = 0;
    virtual std::uint64_t malformed_count() const = 0;
    //! 0 seeking, 1 arrived (loitering), 2 located (always 0 without self_arrival).
    virtual int status() const = 0;
    //! The latest fix (valid once located).
    virtual emitter_location location() const = 0;
    //! self_arrival: the mission is over (located, or given up without a fix).
    virtual bool done() const = 0;

    /*!
     * Wait for the vehicle's first heading before seeking (default false). Until a meas
     * carries a heading or a nav report has come, each meas is counted (waiting_count)
     * and answered by no cmd, telemetry or status: the vehicle keeps the course it
     * flies, and the strategy starts from its true heading, not from one it would have
     * to assume. It applies only before the strategy has started: switched on later, it
     * changes nothing. For flows whose headings come on "nav" (a live radio, two
     * processes, a recording); a lockstep source without heading tags would wait for
     * ever.
     */
    virtual void set_wait_for_heading(bool wait) = 0;
    virtual bool wait_for_heading() const = 0;
    //! meas messages set aside while waiting for the first heading.
    virtual std::uint64_t waiting_count() const = 0;
    //! Windows with no nav report within 1 s of their time (measured without a
    //! heading).
    virtual std::uint64_t unpaired_count() const = 0;
    /*!
     * A new wind forecast for the ground track, mid-flight (m/s toward east and north in
     * the compass frame; both 0: none; docs/seeker.md "A wind forecast"); it replaces
     * what the law had learned, from the next probe cycle or Stage-2 step. config()
     * shows the values in use. Returns false, changing nothing, for a non-finite value
     * or a speed not below the airspeed (logged as an error: a callback in a running
     * flight must not stop the controller) and for a strategy that flies no ground
     * track (a warning, once, unless the forecast is 0, 0).
     */
    virtual bool set_wind_forecast(double east_mps, double north_mps) = 0;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_SEEKING_CONTROLLER_H */
