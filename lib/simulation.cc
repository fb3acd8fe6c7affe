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

#include <gr-rfseek/simulation.h>
#include <gr-rfseek/tone_estimator.h>
#include <cmath>
#include <memory>

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
    make_estimator(d_sc, d_est); // fail early on bad estimator settings
}

seeker_config simulation::seeker_for(const scenario& sc, const std::string& strategy)
{
    seeker_config c;
    c.strategy = strategy;
    c.speed_mps = sc.speed_mps;
    c.carrier_hz = sc.carrier_hz;
    c.slot_period_s = sc.slot_period_s;
    c.turn_rate_rad_per_s = sc.turn_rate_rad_per_s;
    c.seed = sc.seed;
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
            r.records.push_back(s);
        }
        w.advance(c.heading_rad);
    }

    run_summary& s = r.summary;
    s.strategy = d_cfg.strategy;
    s.seed = d_sc.seed;
    s.distance_m = w.distance_flown_m();
    s.shortest_path_m = d_sc.shortest_path_m();
    s.ratio = s.shortest_path_m > 0.0 ? s.distance_m / s.shortest_path_m : 0.0;
    s.time_s = w.time_s();
    s.success = w.arrived();
    s.slots = w.slot();
    s.updates = sk->updates();
    return r;
}

} // namespace rfseek
} // namespace gr
