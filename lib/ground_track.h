/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * ground_track: guidance over the ground (docs/seeker.md "Guidance over the ground").
 * A strategy that points its air heading at the measured bearing beta flies a pursuit
 * curve in a crosswind: the ground velocity v u(psi) + w has a component across the
 * line of sight, and the bearing turns at
 *     beta' = -(v sin(psi - beta) + w_perp) / r.
 * The straight ground line is the course psi = beta + c* with sin c* = -w_perp / v (the
 * wind triangle), on which beta stops turning. Neither w_perp nor r is known, but the
 * sign and size of beta' are: the crab c is adapted as in proportional navigation,
 *     c' = K beta'   (heading rate (K + 1) beta', navigation constant N = K + 1),
 * which drives beta' to zero whatever r: linearised, c - c* decays with the time
 * constant r / (K v cos c*), from the first bearing change on. The bearing rate is
 * estimated by a Kalman filter (bearing, bearing rate; the rate a random walk) from the
 * strategy's per-step bearing measurements, whose noise scale the filter learns from
 * its own innovations (gusts make it larger than a fit's white-noise standard error).
 * The crab moves only while the rate differs from zero by more than `gate` standard
 * deviations, so calm air leaves it at zero, and holds where the bearing turns faster
 * than 1 deg/s (a few hundred metres from the emitter, where the filter's lag would make
 * it swing). Bearings more than 30 s apart (a loiter, an outage) restart the filter.
 * With a wind forecast (the operator's, optional) the crab starts from the forecast's
 * wind triangle at the filtered bearing and the law learns only what the forecast
 * missed.
 * Internal to the library; unit-tested against the wind triangle in
 * lib/qa/qa_ground_track.cc.
 */

#ifndef INCLUDED_RFSEEK_GROUND_TRACK_H
#define INCLUDED_RFSEEK_GROUND_TRACK_H

#include <gr-rfseek/api.h>

namespace gr {
namespace rfseek {

struct ground_track_config {
    double gain = 1.0;             //!< K: crab change per bearing change (N - 1)
    double max_crab_rad = 0.87;    //!< |c| limit (50 deg: winds up to 0.77 v across)
    double gate = 1.0;             //!< rate / std beyond which the crab moves
    double rate_walk = 5.0e-5;     //!< bearing-rate random walk (rad/s per sqrt(s))
    double max_crab_rate = 0.0175; //!< |c'| limit (rad/s; 1 deg/s)
    //! A wind forecast (m/s toward east and north in the bearing's frame) and the
    //! airspeed it is flown at: the crab starts from the forecast's wind triangle at
    //! the filtered bearing, and the law adapts only the remainder. speed_mps 0: none.
    double forecast_east_mps = 0.0;
    double forecast_north_mps = 0.0;
    double speed_mps = 0.0;
};

class RFSEEK_API ground_track_guidance
{
public:
    explicit ground_track_guidance(
        const ground_track_config& cfg = ground_track_config());

    /*!
     * One bearing measurement (rad, the strategy's compass frame) at time t_s with the
     * measurement's standard error sigma_rad; returns the crab to fly (heading = bearing
     * + crab). Non-finite input is ignored.
     */
    double update(double t_s, double bearing_rad, double sigma_rad);

    //! The crab to fly now: the forecast's at the filtered bearing plus the learned one.
    double crab_rad() const { return d_started ? total(d_b) : d_crab; }
    //! The crab the law has learned (the whole crab without a forecast).
    double learned_crab_rad() const { return d_crab; }
    //! The wind triangle's crab for the forecast at bearing b (0 without a forecast).
    double forecast_crab_rad(double bearing_rad) const;
    double bearing_rad() const { return d_b; }
    double bearing_rate_rad_per_s() const { return d_r; }
    double bearing_rate_std() const;
    bool started() const { return d_started; }

    //! Forget everything, crab included.
    void reset();

    //! A new forecast (both 0: none) at airspeed speed_mps; the learned crab is kept.
    void set_forecast(double east_mps, double north_mps, double speed_mps);

private:
    double total(double bearing_rad) const;

    ground_track_config d_cfg;
    bool d_started = false;
    double d_t = 0.0, d_b = 0.0, d_r = 0.0;
    double d_pbb = 0.0, d_pbr = 0.0, d_prr = 0.0;
    double d_scatter = 0.0196; // bearing variance about the prediction, from the data
    double d_crab = 0.0;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_GROUND_TRACK_H */
