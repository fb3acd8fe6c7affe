/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * arrival_fixtures: what the overflight detector's tests share (the synthetic
 * vehicle's speed, slot and carrier, the detector's settings for it, a pass's result).
 */

#ifndef INCLUDED_RFSEEK_QA_ARRIVAL_FIXTURES_H
#define INCLUDED_RFSEEK_QA_ARRIVAL_FIXTURES_H

#include <gr-rfseek/arrival.h>
#include <gr-rfseek/rng.h>
#include <gr-rfseek/scenario.h>
#include <gr-rfseek/seeker.h>
#include <gr-rfseek/simulation.h>
#include <cmath>
#include <utility>

namespace gr {
namespace rfseek {
namespace qa {

constexpr double V = 10.0, T = 0.05, FC = 2.0e9;
const double LAMBDA = SPEED_OF_LIGHT / FC;
const double A = V / LAMBDA; // f_d,max

inline overflight_config detector_cfg()
{
    overflight_config c;
    c.max_doppler_hz = A;
    c.slot_period_s = T;
    return c;
}

struct pass_result {
    bool detected = false;
    double along_m = 0.0; // along-track position at detection (0: closest approach)
    double range_m = 0.0; // horizontal distance then
};

/*!
 * A straight track along +x from x0 at the ground speed vg, the emitter at (0, offset),
 * until x_end or the detection. signal(t, x, r) gives the slot's (frequency, power), r
 * the horizontal distance (it draws its own noise from g first); the heading read has
 * 2 deg of noise.
 */
template <typename Signal>
pass_result fly_pass(overflight_detector& d,
                     rng& g,
                     double x0,
                     double vg,
                     double x_end,
                     double offset_m,
                     Signal signal)
{
    pass_result out;
    for (int k = 0;; ++k) {
        const double t = k * T;
        const double x = x0 + vg * t;
        if (x >= x_end)
            break;
        const double r = std::hypot(x, offset_m);
        const std::pair<double, double> fp = signal(t, x, r);
        const double h = 0.035 * g.normal();
        if (d.update(t, fp.first, fp.second, 10.0, true, h)) {
            out.detected = true;
            out.along_m = x;
            out.range_m = r;
            break;
        }
    }
    return out;
}

// A `realistic` flight of `adaptive` that arrives and locates by itself, with no limit
// on the ellipse: a wider ellipse then changes nothing but itself (the fix is sure, the
// flight the same). Run it with simulation(f.first, f.second).run(false).
inline std::pair<scenario, seeker_config> unlimited_fix_flight(std::uint64_t seed)
{
    scenario sc;
    sc.apply_preset("realistic");
    sc.seed = seed;
    sc.self_arrival = true;
    seeker_config cfg = simulation::seeker_for(sc, "adaptive");
    cfg.locate_max_axis_m = 1e6;
    return { sc, cfg };
}

} // namespace qa
} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_QA_ARRIVAL_FIXTURES_H */
