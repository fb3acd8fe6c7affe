/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * scenario: every parameter of one simulated run, in one place. The defaults are the
 * reference scenario of the paper's Table I plus the choices docs/design.md makes where
 * the paper is silent. Plain C++ (no GNU Radio types).
 */

#ifndef INCLUDED_RFSEEK_SCENARIO_H
#define INCLUDED_RFSEEK_SCENARIO_H

#include <gr-rfseek/api.h>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gr {
namespace rfseek {

//! Speed of light in m/s.
constexpr double SPEED_OF_LIGHT = 299792458.0;

/*!
 * \brief All parameters of a simulated run (angles in radians, CCW from +x).
 *
 * Fields left unset (std::optional, None in Python) are drawn from the run's seed.
 * validate() throws std::invalid_argument naming the offending field and its range.
 */
struct RFSEEK_API scenario {
    // Geometry
    double initial_distance_m = 5000.0;      //!< d: UAV to emitter at start
    std::optional<double> start_angle_rad;   //!< alpha: UAV polar angle around emitter
    std::optional<double> start_heading_rad; //!< phi at slot 0
    int num_scatterers = 10;                 //!< L
    double scatterer_inner_radius_m = 100.0; //!< R_in
    double scatterer_outer_radius_m = 200.0; //!< R
    double gamma_min = 0.3;                  //!< |Gamma_i| lower bound
    double gamma_max = 0.7;                  //!< |Gamma_i| upper bound
    // Radio
    double carrier_hz = 2.0e9;     //!< f_c
    double samp_rate_hz = 1.0e5;   //!< 1 / Ts
    int window_len = 1000;         //!< N: beacon samples
    double slot_period_s = 0.05;   //!< T_slot
    int fft_len = 4096;            //!< N_FFT
    double snr_db = 0.0;           //!< mean per-sample SNR at initial distance
    double noise_power_db = -70.0; //!< sigma_n^2 (complex noise power)
    bool add_noise = true;         //!< false: noise-free samples
    // Carrier frequency offset f_o(t) = f_o(0) + a t + random walk
    std::optional<double> cfo_hz; //!< f_o(0); drawn in +-cfo_range_hz
    double cfo_range_hz = 1000.0;
    std::optional<double> cfo_drift_hz_per_s; //!< a; drawn in +-cfo_drift_range
    double cfo_drift_range_hz_per_s = 0.5;
    double cfo_walk_hz_per_sqrt_s = 0.1; //!< random-walk strength q
    // Vehicle
    double speed_mps = 10.0; //!< v (constant)
    double heading_noise_rad =
        0.034906585039886591;         //!< sigma_phi (2 deg), white per slot
    double turn_rate_rad_per_s = 0.0; //!< 0 = instantaneous turns (paper)
    //! Coordinated turns (docs/world.md "Turns"): bank limit; turn rate g tan(bank) / v.
    double bank_limit_rad = 0.0; //!< 0 = no bank limit
    //! Roll-rate limit with bank_limit_rad: a heading change first waits for the roll.
    double roll_rate_rad_per_s = 0.0; //!< 0 = instantaneous roll
    // Real flight (docs/world.md); the zeros keep the paper's flat, windless world.
    double altitude_m = 0.0;     //!< UAV height above the emitter (scatterers: ground)
    double wind_speed_mps = 0.0; //!< mean wind
    std::optional<double>
        wind_to_rad;                //!< where the wind blows toward; drawn from the seed
    double wind_gust_mps = 0.0;     //!< gust std per axis (first-order Gauss-Markov)
    double wind_gust_tau_s = 5.0;   //!< gust correlation time
    double compass_bias_rad = 0.0;  //!< flown = commanded + bias + noise (reported: not)
    double compass_noise_rad = 0.0; //!< white per slot
    //! The mean wind's direction turns at this rate (rad/s, + counter-clockwise).
    double wind_veer_rad_per_s = 0.0;
    // What the vehicle believes of itself (docs/world.md "What the vehicle believes"):
    // simulation::seeker_for hands the seeker the truth plus these errors.
    double airspeed_error_mps = 0.0; //!< believed airspeed - speed_mps
    double altimeter_error_m = 0.0;  //!< believed altitude - altitude_m
    //! The seeker is handed a wind forecast (seeker_config::wind_forecast_*): the run's
    //! mean wind at the start, its speed off by wind_forecast_speed_error_mps and its
    //! direction by wind_forecast_direction_error_rad (false: no forecast).
    bool wind_forecast = false;
    double wind_forecast_speed_error_mps = 0.0;     //!< forecast speed - true (m/s)
    double wind_forecast_direction_error_rad = 0.0; //!< forecast direction - true (rad)
    // Run
    double success_radius_m = 200.0;    //!< d_v
    std::optional<double> flight_cap_m; //!< default: world::flight_cap_m()
    /*!
     * The run ends when the vehicle itself declares it is done (seeker_config::
     * self_arrival: located, or given up), not at d_v; d_v stays a study metric
     * (world::arrived()). False: the paper's runs, ended by the truth at d_v.
     */
    bool self_arrival = false;
    std::uint64_t seed = 1;

    //! Throws std::invalid_argument("scenario.<field> = <value>: must be ...").
    void validate() const;

    //! Derived quantities.
    double wavelength_m() const { return SPEED_OF_LIGHT / carrier_hz; }
    double max_doppler_hz() const { return speed_mps * carrier_hz / SPEED_OF_LIGHT; }
    int slot_samples() const; //!< round(T_slot * fs)
    double window_duration_s() const { return window_len / samp_rate_hz; }
    double shortest_path_m() const { return initial_distance_m - success_radius_m; }
    //! flight_cap_m, or 4 (d - d_v): the cap in calm air (world::flight_cap_m() is the
    //! one flown: into a headwind the default is 4 x the straight line's air distance).
    double effective_flight_cap_m() const;

    //! Names of the numeric fields settable by set() (CLI "--set key=value", GRC).
    static std::vector<std::string> keys();
    /*!
     * Set a field by name from text: numbers, "true"/"false" for add_noise,
     * "none"/"random" to unset an optional field. Throws std::invalid_argument for an
     * unknown key or unparsable value (validate() checks ranges).
     */
    void set(const std::string& key, const std::string& value);
    //! Field value as text ("none" for an unset optional).
    std::string get(const std::string& key) const;
    //! All fields as a JSON object (one line).
    std::string to_json() const;

    /*!
     * Named scenario variants, kept here for programs, tests and docs alike:
     * reference, turn30, start1km, start10km, speed20, drift2, drift10, snr-15, snr-22,
     * hard, realistic, windy. A preset is a list of set() overrides on the reference
     * scenario.
     */
    static std::vector<std::string> presets();
    //! The overrides of a preset, as (key, value) pairs for set().
    static std::vector<std::pair<std::string, std::string>>
    preset_overrides(const std::string& name);
    //! One line saying what the preset is.
    static std::string preset_description(const std::string& name);
    //! Apply a preset's overrides to this scenario (throws for an unknown name).
    void apply_preset(const std::string& name);
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_SCENARIO_H */
