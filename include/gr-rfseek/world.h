/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * world: the simulated physics of one run, slot by slot. Emitter at the origin,
 * scatterers in an annulus around it, the UAV flying at constant speed, the drifting
 * carrier offset, and the complex baseband beacon the UAV receives (paper eq. 1-2, with
 * the resolutions of docs/design.md: physical Doppler sign, CFO phase as the integral of
 * f_o, amplitudes and phases from eq. 2). Plain C++ (no GNU Radio types).
 */

#ifndef INCLUDED_RFSEEK_WORLD_H
#define INCLUDED_RFSEEK_WORLD_H

#include <gr-rfseek/api.h>
#include <gr-rfseek/rng.h>
#include <gr-rfseek/scenario.h>
#include <complex>
#include <cstdint>
#include <functional>
#include <vector>

namespace gr {
namespace rfseek {

//! One point scatterer: position and complex reflection coefficient Gamma_i.
struct RFSEEK_API scatterer {
    double x_m;
    double y_m;
    std::complex<double> gamma;
};

//! One propagation path as seen from the UAV at the start of a slot.
struct RFSEEK_API path_state {
    std::complex<double> amplitude; //!< complex amplitude of the received path (sqrt W)
    double doppler_hz;              //!< +f_d,max cos(heading - direction to source point)
    double length_m;                //!< emitter -> (scatterer ->) UAV
};

/*!
 * One true state of a vehicle flown by something else (a flight simulator such as
 * ArduPilot's or PX4's SITL), in a local level frame of its own: east, north, up (m)
 * from any fixed point whose height is the emitter's ground, velocity over the ground
 * (m/s), the true heading (rad, counter-clockwise from east), and the time on the
 * simulator's clock (s).
 */
struct RFSEEK_API vehicle_truth {
    double time_s = 0.0;
    double east_m = 0.0, north_m = 0.0, up_m = 0.0;
    double v_east_mps = 0.0, v_north_mps = 0.0, v_up_mps = 0.0;
    double heading_rad = 0.0;
};

class RFSEEK_API world
{
public:
    //! Validates the scenario and draws the geometry, start and CFO from its seed.
    explicit world(const scenario& sc);

    const scenario& config() const { return d_sc; }
    const std::vector<scatterer>& scatterers() const { return d_scatterers; }

    // State at the start of the current slot
    std::uint64_t slot() const { return d_slot; }
    double time_s() const { return d_slot * d_sc.slot_period_s; }
    double x_m() const { return d_x; }
    double y_m() const { return d_y; }
    double heading_rad() const { return d_heading; }
    //! Bank angle (rad, + turning counter-clockwise); 0 unless the turns are coordinated.
    double bank_rad() const { return d_bank; }
    //! Heading the UAV's sensors report for this slot: the true heading minus the
    //! compass error it flies with, plus sigma_phi noise.
    double measured_heading_rad() const { return d_measured_heading; }
    //! Horizontal distance to the emitter (what d_v is judged on).
    double distance_m() const;
    //! Straight-line (3-D) distance to the emitter, altitude included.
    double slant_range_m() const;
    //! Height above the emitter's ground (the scenario's, or the truth followed).
    double altitude_m() const { return d_alt; }
    //! Vertical speed (m/s, up); 0 unless the world follows a truth.
    double up_mps() const { return d_vz; }
    //! Velocity over the ground (air velocity + wind), m/s.
    double ground_vx_mps() const;
    double ground_vy_mps() const;
    //! Compass error of the heading flown in this slot (flown - commanded).
    double compass_error_rad() const { return d_compass_err; }
    //! Distance flown through the air (what the battery pays); following a truth, the
    //! length of the true track over the ground.
    double distance_flown_m() const { return d_flown; }
    /*!
     * What the straight ground line costs: the air distance a vehicle pays flying the
     * straight ground track from the start to d_v, crabbed into the mean wind at the
     * start (d - d_v in calm air; infinity when that wind blows it back).
     */
    double straight_air_m() const { return d_straight_air; }
    /*!
     * The distance flown through the air at which the run is capped (a failure):
     * flight_cap_m if set, else 4 x straight_air_m() where that is longer than d - d_v
     * (into a headwind the straight line itself costs more air distance), else
     * 4 (d - d_v) (calm air, a tailwind, or a wind that blows the vehicle back).
     */
    double flight_cap_m() const { return d_cap; }
    //! The mean wind now (without gusts), m/s.
    double wind_east_mps() const { return d_wind_x; }
    double wind_north_mps() const { return d_wind_y; }
    //! Where the mean wind blew toward at the start (rad; drawn from the seed when the
    //! scenario gives none, even at 0 m/s; 0 when neither wind nor gusts are set).
    double start_wind_to_rad() const { return d_wind_to0; }
    //! Bearing from the UAV toward the emitter.
    double bearing_to_emitter_rad() const;
    //! Carrier offset f_o at the start of this slot, and its linear drift rate a.
    double cfo_hz() const { return d_cfo_hz; }
    double cfo_drift_hz_per_s() const { return d_cfo_drift; }
    //! Doppler of the line-of-sight path (+ when approaching).
    double los_doppler_hz() const;
    //! Electric field of eq. 2 at the UAV (1/m, unit transmit amplitude).
    std::complex<double> field() const;
    //! Every path (LOS first, then scatterers) at the UAV.
    std::vector<path_state> paths() const;
    //! Signal amplitude scale A (sqrt W * m) set from snr_db at the initial distance.
    double amplitude_scale() const { return d_amp; }
    //! Received beacon power A^2 |EF|^2 at the UAV (W, per sample).
    double received_power() const;
    //! Mean received power at distance d over positions and fading (no cross terms).
    double mean_power_at(double distance_m) const;
    double noise_power() const { return d_noise_power; }
    //! Instantaneous per-sample SNR of this slot's beacon (dB).
    double snr_db() const;

    //! Within d_v of the emitter (horizontal). Ends the run unless self_arrival.
    bool arrived() const { return d_arrived; }
    //! Has been within d_v at some slot (the same as arrived() without self_arrival).
    bool reached() const { return d_reached; }
    //! Distance flown when d_v was first reached (0 if not reached).
    double reached_flown_m() const { return d_reached_flown; }
    bool capped() const { return d_capped; }
    //! self_arrival: the vehicle declared the run over (end_run()).
    bool ended() const { return d_ended; }
    bool finished() const
    {
        return (d_arrived && !d_sc.self_arrival) || d_capped || d_ended;
    }
    //! End the run now (the vehicle declared it is done); finished() from then on.
    void end_run() { d_ended = true; }

    /*!
     * Synthesise n samples of the current slot: the beacon in the first
     * min(n, window_len) samples, noise (if enabled) in all n. A pure function of the
     * slot's state: calling it twice gives the same samples.
     */
    void synthesize(std::complex<float>* out, std::size_t n) const;
    std::vector<std::complex<float>> synthesize(std::size_t n) const;

    /*!
     * Fly one slot toward commanded_heading_rad (turning at most at the turn rate),
     * advance the CFO, then draw the next slot's measured heading. Throws
     * std::invalid_argument on a non-finite heading, std::logic_error once finished.
     */
    void advance(double commanded_heading_rad);

    /*!
     * Follow a vehicle flown by something else: this slot's state is the truth `s`
     * (its position, height, ground velocity and heading; the Doppler of every path is
     * that velocity along the direction to the path's source, climbs included). The
     * first call places the emitter: the scene turns about the emitter by the truth's
     * heading less the scenario's start heading, and the truth's frame is moved onto
     * the vehicle's start, so that the vehicle starts initial_distance_m from the
     * emitter with it (and the scatterers) where the scenario's start heading sees
     * them. Each later call is the next slot, at a time not before the last one's;
     * the carrier offset advances by the time between them, and distance_flown_m()
     * by the track's length. advance() is refused from the first call on.
     * std::invalid_argument for a non-finite field or a time that goes back,
     * std::logic_error once finished.
     */
    void follow(const vehicle_truth& s);
    //! follow() has been called: the world follows a truth.
    bool following() const { return d_follow; }

    // Run-time changes (take effect from the current slot)
    void set_snr_db(double snr_db);
    void set_heading_noise_rad(double sigma);
    void set_turn_rate_rad_per_s(double rate);

    //! Wrap an angle to (-pi, pi].
    static double wrap(double a);

private:
    enum stream : std::uint64_t {
        STREAM_GEOMETRY = 1,
        STREAM_NOISE = 2,
        STREAM_HEADING = 3,
        STREAM_CFO_WALK = 4,
        STREAM_WIND = 5,
        STREAM_COMPASS = 6,
    };
    //! Altitude and wind absent: the paper's flat, windless world, computed as before.
    bool flat_and_calm() const;
    void draw_compass_error(std::uint64_t index);

    void draw_measured_heading();
    void advance_cfo(double dt, std::uint64_t index);
    void update_amplitude();
    void fill_paths(std::vector<path_state>& out) const;
    void reconfigure(const std::function<void(scenario&)>& change);
    double mean_field_power(double distance_m) const;

    scenario d_sc;
    std::vector<scatterer> d_scatterers;
    std::vector<double> d_scatterer_range; // emitter to scatterer i
    std::uint64_t d_slot = 0;
    double d_x = 0.0, d_y = 0.0, d_heading = 0.0, d_measured_heading = 0.0;
    double d_bank = 0.0;
    double d_flown = 0.0;
    double d_cfo_hz = 0.0, d_cfo_drift = 0.0, d_cfo_phase = 0.0;
    double d_amp = 0.0, d_noise_power = 0.0;
    double d_wind_x = 0.0, d_wind_y = 0.0; // mean wind
    double d_wind_to0 = 0.0;               // its direction at the start
    double d_straight_air = 0.0;
    double d_cap = 0.0;
    double d_gust_x = 0.0, d_gust_y = 0.0;     // gusts (Gauss-Markov), this slot
    double d_compass_err = 0.0;                // flown - commanded, this slot
    double d_alt = 0.0;                        // height above the emitter's ground
    bool d_follow = false;                     // follow(): the state is a truth's
    double d_vx = 0.0, d_vy = 0.0, d_vz = 0.0; // following: the ground velocity
    double d_anchor_x = 0.0, d_anchor_y = 0.0; // following: world minus truth frame
    double d_follow_time = 0.0;                // following: the last truth's time
    bool d_arrived = false, d_capped = false, d_reached = false, d_ended = false;
    double d_reached_flown = 0.0;
    void update_arrival();
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_WORLD_H */
