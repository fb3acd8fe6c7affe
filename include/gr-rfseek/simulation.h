/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * simulation: world + tone_estimator + seeker in a closed loop without the GNU Radio
 * scheduler: the very code the blocks run, for tests and Monte Carlo. Plain C++.
 */

#ifndef INCLUDED_RFSEEK_SIMULATION_H
#define INCLUDED_RFSEEK_SIMULATION_H

#include <gr-rfseek/api.h>
#include <gr-rfseek/scenario.h>
#include <gr-rfseek/seeker.h>
#include <gr-rfseek/world.h>
#include <cstdint>
#include <string>
#include <vector>

namespace gr {
namespace rfseek {

//! How the beacon's frequency is measured in the loop (tone_estimator settings).
struct RFSEEK_API estimator_config {
    std::string window = "rectangular";
    std::string interpolator = "parabolic";
    double min_freq_hz = 0.0;
    double max_freq_hz = 0.0;
};

//! Truth, measurement and decision of one slot.
struct RFSEEK_API slot_record {
    std::uint64_t slot = 0;
    double time_s = 0.0;
    double x_m = 0.0, y_m = 0.0;
    double heading_rad = 0.0;          //!< true heading at the beacon
    double measured_heading_rad = 0.0; //!< what the seeker was told
    double distance_m = 0.0;           //!< to the emitter
    double distance_flown_m = 0.0;
    double cfo_hz = 0.0;      //!< truth
    double doppler_hz = 0.0;  //!< LOS Doppler (truth)
    double true_snr_db = 0.0; //!< instantaneous SNR (truth)
    double freq_hz = 0.0;     //!< measured
    double snr_db = 0.0;      //!< estimated
    double power_db = 0.0;    //!< estimated tone power
    bool valid = false;
    int stage = 0;
    double theta_est_rad = 0.0;
    double cmd_heading_rad = 0.0;
    bool update = false;
    int status = 0; //!< 0 seeking, 1 arrived (loitering), 2 located (self_arrival)
};

struct RFSEEK_API run_summary {
    std::string strategy;
    std::uint64_t seed = 0;
    double distance_m = 0.0;      //!< flown, Stage-1 circle included
    double shortest_path_m = 0.0; //!< d - d_v
    double ratio = 0.0;           //!< distance_m / shortest_path_m
    //! Air distance of the straight ground line to d_v in the mean wind at the start
    //! (world::straight_air_m; shortest_path_m in calm air).
    double straight_air_m = 0.0;
    //! distance_m / straight_air_m: 1 for the straight ground track whatever the wind
    //! (ratio in calm air; 0 when the wind blows faster than the airspeed against it).
    double straight_ratio = 0.0;
    double time_s = 0.0;
    bool success = false; //!< arrived within d_v before the flight cap
    std::uint64_t slots = 0;
    bool has_stage1 = false;
    double stage1_heading_error_rad =
        0.0;                   //!< theta_0 minus the true bearing, at the decision
    std::uint64_t updates = 0; //!< Stage-2 updates applied
    // Arrival without truth (scenario::self_arrival; docs/seeker.md). In that mode
    // distance_m, ratio and success are taken when d_v was first reached.
    bool self_arrival = false;
    //! The overflight (or encircling) signature was first seen (the loiter began).
    bool overflight = false;
    double overflight_distance_m = 0.0; //!< true horizontal distance then
    //! The vehicle declared its arrival (seeker_config::arrival_confirm_m: when a
    //! location fit confirmed it; 0: at the overflight).
    bool declared = false;
    double arrival_time_s = 0.0;
    double arrival_detect_distance_m = 0.0; //!< true horizontal distance then
    bool false_arrival = false;             //!< declared more than 1 km away
    bool located = false;                   //!< a location fix was published
    double location_error_m = 0.0; //!< |estimated - true| emitter offset at the fix
    double location_major_m = 0.0; //!< 95 % ellipse semi-axes of the fix
    double location_minor_m = 0.0;
    bool location_in_ellipse = false;   //!< the truth lies inside the 95 % ellipse
    bool location_in_ellipse50 = false; //!< the truth lies inside the 50 % ellipse
    bool location_unsure = false;  //!< the fix was published unsure (emitter_location)
    double total_distance_m = 0.0; //!< flown until the run ended (loiter included)
};

struct RFSEEK_API run_result {
    run_summary summary;
    std::vector<slot_record> records;
    std::vector<scatterer> scatterers;
    double emitter_x_m = 0.0, emitter_y_m = 0.0;
    //! self_arrival: the first fix and where the vehicle truly was then.
    emitter_location location;
    double location_vehicle_x_m = 0.0, location_vehicle_y_m = 0.0;
};

class RFSEEK_API simulation
{
public:
    simulation(const scenario& sc,
               const seeker_config& cfg,
               const estimator_config& est = estimator_config());

    //! Run to arrival or the flight cap; records every slot when keep_records.
    run_result run(bool keep_records = true) const;

    const scenario& scenario_config() const { return d_sc; }
    const seeker_config& seeker_cfg() const { return d_cfg; }
    const estimator_config& estimator_cfg() const { return d_est; }

    //! A seeker configuration for a scenario: its speed, carrier, slot period, turn rate
    //! and seed, the paper's constants (delta 10 deg, M 20, R_c 100 m, MA 15) otherwise.
    static seeker_config seeker_for(const scenario& sc, const std::string& strategy);

private:
    scenario d_sc;
    seeker_config d_cfg;
    estimator_config d_est;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_SIMULATION_H */
