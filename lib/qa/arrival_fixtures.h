/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * arrival_fixtures: what the overflight detector's tests share (the synthetic
 * vehicle's speed, slot and carrier, the detector's settings for it, a pass's result)
 * and the locator's (gusty orbits).
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

/*!
 * Three orbits of radius_m flown in the air frame for the emitter locator loc, height_m
 * above the emitter's ground, in a (3.2, -2.4) m/s wind with first-order Gauss-Markov
 * gusts (std gust_mps per axis, correlation time tau_s) and 3 Hz of white noise on the
 * frequency (CFO 500 Hz + 0.1 Hz/s). The orbit starts at ground position (gx, gy), the
 * emitter at the origin; on return (gx, gy) is where it ended and (qx, qy) the
 * dead-reckoned (air-frame) end.
 */
inline void fly_gusty_orbits(emitter_locator& loc,
                             rng& g,
                             double height_m,
                             double radius_m,
                             double gust_mps,
                             double tau_s,
                             double& gx,
                             double& gy,
                             double& qx,
                             double& qy)
{
    const double w = V / radius_m, wx = 3.2, wy = -2.4;
    const int n = static_cast<int>(3.0 * 2.0 * M_PI / w / T);
    const double a = std::exp(-T / tau_s), s = gust_mps * std::sqrt(1.0 - a * a);
    qx = qy = 0.0;
    double ux = gust_mps * g.normal(), uy = gust_mps * g.normal();
    for (int k = 0; k <= n; ++k) {
        const double t = k * T, ang = w * t;
        const double vx = V * std::cos(ang), vy = V * std::sin(ang);
        const double r = std::sqrt(gx * gx + gy * gy + height_m * height_m);
        const double dop = ((vx + wx + ux) * -gx + (vy + wy + uy) * -gy) / (LAMBDA * r);
        loc.add(t, qx, qy, vx, vy, 500.0 + 0.1 * t + dop + 3.0 * g.normal());
        if (k < n) {
            qx += vx * T;
            qy += vy * T;
            gx += (vx + wx + ux) * T;
            gy += (vy + wy + uy) * T;
            ux = a * ux + s * g.normal();
            uy = a * uy + s * g.normal();
        }
    }
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
