/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * simulation: the closed loop of channel_source -> doppler_estimator ->
 * seeking_controller, slot by slot, without a scheduler. The flowgraph and this loop
 * exchange the same numbers: burst samples, the measured heading of the beacon tag, the
 * estimate, the command.
 */

#include "strategies.h"
#include <gr-rfseek/simulation.h>
#include <gr-rfseek/tone_estimator.h>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace gr {
namespace rfseek {

namespace {
std::unique_ptr<tone_estimator> make_estimator(const scenario& sc,
                                               const estimator_config& e)
{
    return std::make_unique<tone_estimator>(sc.samp_rate_hz,
                                            sc.window_len,
                                            sc.fft_len,
                                            e.window,
                                            e.interpolator,
                                            e.min_freq_hz,
                                            e.max_freq_hz);
}
} // namespace

simulation::simulation(const scenario& sc,
                       const seeker_config& cfg,
                       const estimator_config& est)
    : d_sc(sc), d_cfg(cfg), d_est(est)
{
    d_sc.validate();
    d_cfg.validate();
    if (d_sc.self_arrival != d_cfg.self_arrival)
        throw std::invalid_argument(
            std::string("scenario.self_arrival = ") +
            (d_sc.self_arrival ? "true" : "false") +
            " but seeker_config.self_arrival = " +
            (d_cfg.self_arrival ? "true" : "false") +
            ": they must agree (the world ends the run at the seeker's done, or at d_v); "
            "simulation.seeker_for(scenario, strategy) copies it");
    make_estimator(d_sc, d_est); // fail early on bad estimator settings
}

seeker_config simulation::seeker_for(const scenario& sc, const std::string& strategy)
{
    // A strategy name is checked here, where it is given (the rest of the configuration
    // is validated by its user, after any settings of its own).
    require_strategy(strategy, "simulation.seeker_for: strategy");
    seeker_config c;
    c.strategy = strategy;
    // What the vehicle believes of itself: the truth plus the scenario's sensor errors.
    c.speed_mps = sc.speed_mps + sc.airspeed_error_mps;
    c.carrier_hz = sc.carrier_hz;
    c.slot_period_s = sc.slot_period_s;
    c.turn_rate_rad_per_s = sc.turn_rate_rad_per_s;
    c.bank_limit_rad = sc.bank_limit_rad;
    c.roll_rate_rad_per_s = sc.roll_rate_rad_per_s;
    c.locate_altitude_m = sc.altitude_m + sc.altimeter_error_m; // the altimeter's
    c.seed = sc.seed;
    c.self_arrival = sc.self_arrival;
    if (sc.wind_forecast) {
        // The run's mean wind at the start (its direction drawn from the seed when not
        // given), as a forecast off by the scenario's errors.
        // (scenario::validate keeps the forecast's speed in [0, the believed airspeed).)
        const world w(sc);
        const double speed = sc.wind_speed_mps + sc.wind_forecast_speed_error_mps;
        const double to = w.start_wind_to_rad() + sc.wind_forecast_direction_error_rad;
        c.wind_forecast_east_mps = speed * std::cos(to);
        c.wind_forecast_north_mps = speed * std::sin(to);
    }
    return c;
}

run_result simulation::run(bool keep_records) const
{
    run_result r;
    world w(d_sc);
    const auto est = make_estimator(d_sc, d_est);
    auto sk = seeker::make(d_cfg);
    // The beacon is synthesised straight into the estimator's FFT input.
    std::complex<float>* buf = est->input_buffer();
    const std::size_t n = static_cast<std::size_t>(d_sc.window_len);
    r.scatterers = w.scatterers();
    int prev_stage = 0;

    while (!w.finished()) {
        w.synthesize(buf, n);
        const tone_estimate e = est->estimate(buf);
        measurement m;
        m.slot = w.slot();
        m.time_s = w.time_s();
        m.freq_hz = e.freq_hz;
        m.snr_db = e.snr_db;
        m.power_db = e.power_db;
        m.valid = e.valid;
        m.has_heading = true;
        m.heading_rad = w.measured_heading_rad();
        const command c = sk->update(m);
        if (prev_stage == 1 && c.stage == 2 && !r.summary.has_stage1) {
            r.summary.has_stage1 = true;
            r.summary.stage1_heading_error_rad =
                world::wrap(c.theta_est_rad - w.bearing_to_emitter_rad());
        }
        prev_stage = c.stage;
        run_summary& sm = r.summary;
        if (c.stage == 3 && d_sc.self_arrival && !sm.overflight) {
            sm.overflight = true;
            sm.overflight_distance_m = w.distance_m();
        }
        if (c.status >= 1 && !sm.declared) {
            sm.declared = true;
            sm.arrival_time_s = w.time_s();
            sm.arrival_detect_distance_m = w.distance_m();
            sm.false_arrival = sm.arrival_detect_distance_m > 1000.0;
        }
        if (c.status == 2 && !sm.located && c.location.valid) {
            sm.located = true;
            r.location = c.location;
            r.location_vehicle_x_m = w.x_m();
            r.location_vehicle_y_m = w.y_m();
            // The emitter is at the origin: its true offset from the vehicle is -x, -y.
            const double ex = c.location.east_m + w.x_m();
            const double ey = c.location.north_m + w.y_m();
            sm.location_error_m = std::hypot(ex, ey);
            sm.location_major_m = c.location.major_m;
            sm.location_minor_m = c.location.minor_m;
            const double ca = std::cos(c.location.major_angle_rad);
            const double sa = std::sin(c.location.major_angle_rad);
            const double u = (ex * ca + ey * sa) / std::max(c.location.major_m, 1e-9);
            const double v = (-ex * sa + ey * ca) / std::max(c.location.minor_m, 1e-9);
            sm.location_in_ellipse = u * u + v * v <= 1.0;
            const double u5 =
                u * c.location.major_m / std::max(c.location.major50_m, 1e-9);
            const double v5 =
                v * c.location.minor_m / std::max(c.location.minor50_m, 1e-9);
            sm.location_in_ellipse50 = u5 * u5 + v5 * v5 <= 1.0;
            sm.location_unsure = c.location.unsure;
        }
        if (keep_records) {
            slot_record s;
            s.slot = w.slot();
            s.time_s = w.time_s();
            s.x_m = w.x_m();
            s.y_m = w.y_m();
            s.heading_rad = w.heading_rad();
            s.measured_heading_rad = w.measured_heading_rad();
            s.distance_m = w.distance_m();
            s.distance_flown_m = w.distance_flown_m();
            s.cfo_hz = w.cfo_hz();
            s.doppler_hz = w.los_doppler_hz();
            s.true_snr_db = w.snr_db();
            s.freq_hz = e.freq_hz;
            s.snr_db = e.snr_db;
            s.power_db = e.power_db;
            s.valid = e.valid;
            s.stage = c.stage;
            s.theta_est_rad = c.theta_est_rad;
            s.cmd_heading_rad = c.heading_rad;
            s.update = c.update;
            s.status = c.status;
            r.records.push_back(s);
        }
        if (d_sc.self_arrival && c.done) {
            w.end_run();
            break;
        }
        w.advance(c.heading_rad);
    }

    run_summary& s = r.summary;
    s.strategy = d_cfg.strategy;
    s.seed = d_sc.seed;
    s.self_arrival = d_sc.self_arrival;
    s.total_distance_m = w.distance_flown_m();
    s.distance_m =
        d_sc.self_arrival && w.reached() ? w.reached_flown_m() : w.distance_flown_m();
    s.shortest_path_m = d_sc.shortest_path_m();
    s.ratio = s.shortest_path_m > 0.0 ? s.distance_m / s.shortest_path_m : 0.0;
    s.straight_air_m = w.straight_air_m();
    s.straight_ratio = s.straight_air_m > 0.0 && std::isfinite(s.straight_air_m)
                           ? s.distance_m / s.straight_air_m
                           : 0.0;
    s.time_s = w.time_s();
    s.success = d_sc.self_arrival ? w.reached() : w.arrived();
    s.slots = w.slot();
    s.updates = sk->updates();
    return r;
}

} // namespace rfseek
} // namespace gr
