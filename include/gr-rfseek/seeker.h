/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * seeker: the steering strategies behind one interface (paper Sec. III). A seeker takes
 * one frequency measurement per slot and returns the heading to fly next. It never sees
 * the truth. Plain C++ (no GNU Radio types).
 */

#ifndef INCLUDED_RFSEEK_SEEKER_H
#define INCLUDED_RFSEEK_SEEKER_H

#include <gr-rfseek/api.h>
#include <gr-rfseek/arrival.h>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace gr {
namespace rfseek {

//! Every constant of the seeking strategies (angles in radians).
struct RFSEEK_API seeker_config {
    //! "paper", "paper_no_circle", "rss_baseline" or "adaptive" (ours, not the paper's)
    std::string strategy = "paper";
    double speed_mps = 10.0;                //!< v
    double carrier_hz = 2.0e9;              //!< f_c (for f_d,max = v f_c / c)
    double slot_period_s = 0.05;            //!< T_slot
    double delta_rad = 0.17453292519943295; //!< Stage-2 perturbation delta (10 deg)
    int m_slots = 20;                       //!< M: slots per half step
    //! `paper`'s Stage-2 perturbation delta_k (eq. 5 writes delta_k; docs/seeker.md
    //! "Stage 2 in the wind"): after Stage 1, once delta_after_steps steps in a row have
    //! measured an error beyond delta on the same side, delta_k grows toward the measured
    //! error by at most delta_step_rad per step, up to delta_max_rad, never beyond the
    //! error just measured, and is delta again as soon as a step measures less (or after
    //! an outage). Stage 2 then follows a bearing that keeps turning (wind near the
    //! emitter). delta_max_rad <= delta_rad (0): delta fixed, as the paper analyses it.
    //! paper_no_circle keeps delta fixed.
    double delta_max_rad = 0.3490658503988659;    //!< 20 deg
    double delta_step_rad = 0.017453292519943295; //!< 1 deg per step
    int delta_after_steps = 3;                    //!< steps in a row before delta_k grows
    double circle_radius_m = 100.0;               //!< R_c of the Stage-1 circle
    int moving_average_len = 15;                  //!< Stage-1 moving average (slots)
    double outlier_threshold_hz =
        0.0;                  //!< eq. 4 threshold; 0 = 2 f_d,max (4 pi v f_c / c rad/s)
    bool literal_eq4 = false; //!< eq. 4 as printed (compare with the previous raw value)
    int relock_count = 5;     //!< re-lock after this many agreeing rejections
    //! eq. 4 locks only once this many consecutive candidates agree (no unconditional
    //! first value; literal_eq4 takes the first value).
    int lock_count = 3;
    //! Measurements whose estimated SNR is below this are not eq. 4 candidates (dB).
    double min_snr_db = -20.0;
    //! Stage 1 (paper): least-squares fit of the circle's frequencies with a linear CFO
    //! trend; false = the paper's argmax of the moving average.
    bool stage1_fit = true;
    double turn_rate_rad_per_s = 0.0; //!< the vehicle's limit; 0 = instantaneous
    //! Bank limit of coordinated turns (turn rate g tan(bank) / v); 0 = none.
    double bank_limit_rad = 0.0;
    //! Roll-rate limit with bank_limit_rad (a heading change waits for the roll);
    //! 0 = instantaneous roll. The strategies plan their turns with these limits.
    double roll_rate_rad_per_s = 0.0;
    int hold_after_missing =
        10; //!< slots without valid measurements before holding course
    std::optional<double> initial_heading_rad; //!< Stage-2 start for paper_no_circle
                                               //!< (None: the first measured heading)
    std::uint64_t seed = 1;                    //!< circle turning sense, RSS tumbles
    // rss_baseline (multi-phase RSS seeking, after Wadhwa et al. 2011): a circle finds
    // the direction, a straight run goes on while its long-term average power rises.
    //! Length over which a run's power is averaged into one block (m).
    double rss_block_m = 200.0;
    //! Blocks per long-term average: a run ends when the mean of the last window of
    //! blocks falls below the mean of the window before by more than rss_fall_db.
    int rss_window_blocks = 4;
    //! Fall of the long-term average that ends a run (dB).
    double rss_fall_db = 0.0;
    // adaptive (ours, docs/seeker.md): acquisition on three headings, then probe cycles
    // (+delta, -delta, -delta, +delta) inverted by a least-squares fit.
    int adaptive_acquire_slots = 3; //!< slots per acquisition heading (120 deg apart)
    //! Slots flown straight on before an acquisition is retried (out of a fade).
    int adaptive_relocate_slots = 20;
    int adaptive_track_slots = 20; //!< slots per probe segment (4 segments per cycle)
    //! With a turn limit, segments are lengthened so that the reversals take at most
    //! this share of a probe cycle (in (0, 1]).
    double adaptive_turn_share = 0.75;
    double adaptive_gain = 0.5; //!< fraction of the estimated error removed per cycle
    double adaptive_delta_min_rad = 0.03490658503988659; //!< 2 deg
    double adaptive_delta_max_rad = 0.3490658503988659;  //!< 20 deg
    //! Estimated errors beyond this (or flying away) start a new acquisition.
    double adaptive_reacquire_rad = 1.0471975511965976; //!< 60 deg
    bool adaptive_drift = true; //!< fit (and so cancel) a linear CFO drift per cycle
    //! Size delta for the bearing scatter the cycles show when it exceeds the fit's
    //! white-noise figure (gusts); false: the white-noise figure only.
    bool adaptive_scatter_delta = true;
    // Guidance over the ground (docs/seeker.md "Guidance over the ground"): fly the
    // bearing plus a crab, adapted as in proportional navigation (crab change =
    // ground_track_gain x bearing change) until the bearing stops turning: a straight
    // ground track in any wind below the airspeed, without knowing the wind or the range.
    bool adaptive_ground_track = true; //!< `adaptive` crabs into the wind
    double ground_track_gain = 1.0;    //!< `adaptive`'s K (navigation constant N = K + 1)
    double ground_track_max_crab_rad = 0.8726646259971648; //!< |crab| limit (50 deg)
    //! The crab moves while the estimated bearing rate exceeds this many std.
    double ground_track_gate = 1.0;
    //! Random walk of the bearing rate in its Kalman filter (rad/s per sqrt(s)).
    double ground_track_rate_walk = 5.0e-5;
    //! An optional wind forecast for the ground track (m/s toward east and north in the
    //! compass frame; the operator's, e.g. an anemometer at launch; both 0: none). The
    //! crab starts from the forecast's wind triangle at the bearing and the law learns
    //! what the forecast missed. Its speed must be below speed_mps.
    double wind_forecast_east_mps = 0.0;
    double wind_forecast_north_mps = 0.0;
    //! `paper` and `paper_no_circle`: fly Stage 2's probes around theta plus the same
    //! crab (eq. 5 then measures the bearing around the heading flown); false: the
    //! paper's Stage 2, an air heading at theta.
    bool paper_ground_track = false;
    //! K of the paper's Stage 2 over the ground (paper_ground_track).
    double paper_ground_track_gain = 2.0;
    // Arrival without truth (docs/seeker.md "Arrival and location"), any strategy.
    //! Detect the overflight, loiter on an orbit and locate the emitter; false: fly the
    //! strategy only (the paper's runs end at the simulator's d_v).
    bool self_arrival = false;
    double arrival_swing = 0.8;     //!< drop beyond turns and drift, x f_d,max (>= 0.5)
    double arrival_window_s = 90.0; //!< the drop must happen within this time
    double arrival_heading_band_rad = 1.0471975511965976; //!< 60 deg spread allowed
    double arrival_power_rise_db = 2.0; //!< power peak over the drop's lower end
    //! Near the emitter (the power arrival_near_power_db above the start's) a drop of
    //! arrival_near_swing x f_d,max suffices (0: off; else in [0.5, arrival_swing]):
    //! a pass into a headwind swings by the ground speed's Doppler only.
    double arrival_near_swing = 0.5;
    double arrival_near_power_db = 25.0; //!< dB above the beacon's power at the start
    int arrival_block_slots = 40;        //!< slots per median block
    int arrival_confirm_blocks = 2;      //!< consecutive blocks with the signature
    //! Encircling signature: headings all round over 120 s with the far-field Doppler
    //! amplitude below this x f_d,max (0: off; docs/seeker.md).
    double arrival_encircle = 0.35;
    //! A loiter whose first orbit shows a Doppler amplitude of at least this x
    //! f_d,max is a false overflight (the emitter is far): seek on at once (0: off;
    //! checked only with locate_altitude_m >= 50 m, docs/seeker.md).
    double arrival_far_amplitude = 0.9;
    double loiter_radius_m = 25.0; //!< orbit radius (turn rate v / R, to the left)
    //! The loiter dead-reckons, and the locator models the air velocity, with the
    //! heading read smoothed by an alpha-beta filter (heading and turn rate) of this
    //! gain, in (0, 1]; 1: the read itself (an autopilot's already filtered heading).
    double loiter_heading_gain = 0.3;
    //! Arrival is declared when a location fit falls within this distance of the
    //! estimate the vehicle orbits (m), lies by the vehicle and, with
    //! locate_nuisance, its honest 95 % semi-major axis is at most 600 m. A loiter held
    //! back by that rule arrives when the orbits allowed run out if, with
    //! locate_altitude_m >= 50 m, its last two orbits around the estimate swing the
    //! Doppler by less than 2/3 of the far check's threshold (far_amplitude()), as over
    //! the emitter; its fix is then published unsure. So does a loiter none of whose
    //! fits agree (in gusts), if the last lay within 4 x this of the estimate: a fit of
    //! all the data, within 600 m, is published unsure. 0: declared on the overflight
    //! alone.
    double arrival_confirm_m = 30.0;
    //! Orbits of data before the first location fit (then every quarter orbit).
    double locate_orbits = 1.0;
    //! No fix after this many orbits (extended by each move of the estimate and by the
    //! arrival): seek again (locate_retry) or give up (done).
    double locate_max_orbits = 3.0;
    bool locate_retry = true; //!< seek again after locate_max_orbits without a fix
    //! A fix is published (located) when its 95 % ellipse's semi-major axis is below.
    double locate_max_axis_m = 100.0;
    //! Gust prior of the location fit: std per axis (m/s; 0: a constant wind only) and
    //! correlation time (s) of a first-order Gauss-Markov gust. The defaults are wide
    //! on purpose: they keep the 95 % ellipse honest for gusts from 0 to 2.5 m/s and
    //! 2 to 30 s (docs/seeker.md, "The locator across the envelope").
    double locate_gust_mps = 1.5;
    double locate_gust_tau_s = 4.0;
    //! The fix's split check (emitter_locator::check_split): the halves of its data in
    //! time fitted apart; where their disagreement T (chi-square, 2 degrees of freedom
    //! for a right ellipse) exceeds this gate, the published ellipse grows by
    //! sqrt(T / 2). 5.99: the 95 % point; 0: off.
    double locate_split_gate = 5.99;
    //! The fix carries what the flight does not know (locator_nuisance): it is refitted
    //! under wide gust models and altimeter readings off by +- locate_altimeter_range_m
    //! and its ellipse is theirs, mixed by evidence and calibrated
    //! (docs/seeker.md, "How honest the ellipse is"); false: the prior's fit alone.
    bool locate_nuisance = true;
    double locate_altimeter_range_m = 30.0; //!< altimeter error carried (m, 0..1000)
    //! The user's own factors on the radii of the honest 95 % and 50 % ellipses
    //! (locator_nuisance::scale95, scale50; 0.1..10), on top of the calibrated ones:
    //! above 1 for a day known to be rougher than the calibration's envelope (slow
    //! strong gusts with the altimeter off: docs/seeker.md, "How honest the ellipse
    //! is"). The wider ellipse also decides sure or unsure (locate_max_axis_m).
    double locate_scale95 = 1.0;
    double locate_scale50 = 1.0;
    //! The vehicle's height above the ground the emitter stands on, as its altimeter /
    //! autopilot holds it (m; NaN: unknown): the location fit's prior on the height,
    //! with std locate_altitude_sigma_m, the altimeter's stated accuracy (m; 0: the
    //! height is fitted freely). A fit whose height is more than 2.5 x that above
    //! locate_altitude_m, or below both the band and twice the height at which an
    //! orbit centred on the emitter swings as far as far_amplitude(), is not used (a
    //! far orbit read as a near, low emitter); with 0 or no altitude that check is off
    //! too. The simulation gives it the scenario's
    //! altitude_m plus its altimeter_error_m.
    double locate_altitude_m = std::numeric_limits<double>::quiet_NaN();
    double locate_altitude_sigma_m = 20.0;

    double max_doppler_hz() const;
    double effective_outlier_threshold_hz() const;
    /*!
     * The first orbit's Doppler amplitude, in units of f_d,max, from which the emitter
     * is far (a false overflight): arrival_far_amplitude, or what an emitter 4 orbit
     * radii from the orbit's centre swings at locate_altitude_m if that is more (a
     * plane's 150 m orbit at 100 m: 0.978; begun late, it can swing over 0.9 with the
     * emitter a few hundred metres outside it). At the defaults (25 m orbit, 50 m up or
     * more) it is arrival_far_amplitude.
     */
    double far_amplitude() const;

    //! Names settable by set() (the fields, plus *_deg aliases of the angles in degrees).
    static std::vector<std::string> keys();
    /*!
     * Set a field by name from text (numbers, true/false, none for initial_heading_rad).
     * Throws std::invalid_argument for an unknown key or unparsable value; validate()
     * checks ranges.
     */
    void set(const std::string& key, const std::string& value);
    //! Throws std::invalid_argument naming the field and its range.
    void validate() const;
};

//! One slot's measurement as the seeker sees it.
struct RFSEEK_API measurement {
    std::uint64_t slot = 0;
    double time_s = 0.0;
    double freq_hz = 0.0;
    double snr_db = 0.0;
    double power_db = 0.0;
    bool valid = false;
    bool has_heading = false;
    double heading_rad = 0.0; //!< measured heading at the beacon
};

//! The seeker's answer to one measurement.
struct RFSEEK_API command {
    std::uint64_t slot = 0;   //!< slot of the measurement answered
    double heading_rad = 0.0; //!< heading to fly from now on
    int stage = 0; //!< 1 (circle, acquisition), 2 (perturbations, probes), 3 (loiter)
    double theta_est_rad = 0.0; //!< current estimate of the direction to the emitter
    bool update = false;  //!< a Stage-2 update (eq. 5) or the Stage-1 decision happened
    bool holding = false; //!< holding course for lack of measurements
    double filtered_freq_hz = 0.0; //!< the eq. 4 output for this measurement
    bool accepted = false;         //!< eq. 4 accepted this measurement
    //! Mission status (self_arrival): 0 seeking, 1 arrived (loitering), 2 located.
    int status = 0;
    //! self_arrival: the mission is over (located, or gave up after locate_max_orbits).
    bool done = false;
    emitter_location location; //!< the latest fix (valid once located)
};

class RFSEEK_API seeker
{
public:
    virtual ~seeker() = default;
    //! Build a strategy by name (seeker_config::strategy). Throws on bad configuration.
    static std::unique_ptr<seeker> make(const seeker_config& cfg);
    static std::vector<std::string> strategies();

    //! One measurement in (valid or not), one command out.
    virtual command update(const measurement& m) = 0;
    virtual const seeker_config& config() const = 0;
    virtual int stage() const = 0;
    virtual double theta_est_rad() const = 0;
    virtual std::uint64_t updates() const = 0; //!< Stage-2 updates applied
    /*!
     * A new wind forecast for the ground track, mid-flight (seeker_config::
     * wind_forecast_east_mps / _north_mps; both 0: none). A changed forecast replaces
     * what the law had learned (the crab is the new forecast's triangle from the next
     * update on). Returns false, changing nothing, for a strategy that flies no ground
     * track. The caller checks the values (seeking_controller::set_wind_forecast does).
     */
    virtual bool set_wind_forecast(double east_mps, double north_mps)
    {
        (void)east_mps;
        (void)north_mps;
        return false;
    }
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_SEEKER_H */
