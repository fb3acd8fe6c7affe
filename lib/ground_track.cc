/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * ground_track: the crab that nulls the bearing's rotation (ground_track.h).
 */

#include "angle.h"
#include "ground_track.h"
#include <algorithm>
#include <cmath>

namespace gr {
namespace rfseek {

namespace {
constexpr double MIN_SIGMA = 0.005;  // rad: floor of a measurement's standard error
constexpr double RATE_PRIOR = 0.002; // rad/s: std of the bearing rate before data
// The scatter of the bearings about the filter's prediction, before data: gusts make
// it far larger than a fit's white-noise standard error (8 deg).
constexpr double SCATTER_PRIOR = 0.14;
constexpr double SCATTER_GAIN = 0.1;    // per measurement
constexpr double INNOVATION_CLIP = 3.0; // standard deviations
// Bearings further apart than this start the filter anew (a loiter, a long outage):
// the rate seen across the gap is not the one to steer by. The crab is kept.
constexpr double MAX_GAP_S = 30.0;
// Beyond this bearing rate the vehicle is close to the emitter (|v_perp| / r: 1 deg/s is
// 5 m/s across at 290 m), where every small track error turns the bearing fast and the
// filter's lag would make the crab swing: the crab holds.
constexpr double NEAR_RATE = 0.0175;
} // namespace

ground_track_guidance::ground_track_guidance(const ground_track_config& cfg) : d_cfg(cfg)
{
}

void ground_track_guidance::reset()
{
    d_started = false;
    d_crab = 0.0;
    d_scatter = SCATTER_PRIOR * SCATTER_PRIOR;
}

double ground_track_guidance::forecast_crab_rad(double bearing_rad) const
{
    if (!(d_cfg.speed_mps > 0.0) || !std::isfinite(bearing_rad))
        return 0.0;
    // sin c = -w_perp / v, w_perp the forecast across the line of sight (left +).
    const double w_perp = -d_cfg.forecast_east_mps * std::sin(bearing_rad) +
                          d_cfg.forecast_north_mps * std::cos(bearing_rad);
    return std::asin(std::clamp(-w_perp / d_cfg.speed_mps, -1.0, 1.0));
}

double ground_track_guidance::total(double bearing_rad) const
{
    // (Without a forecast this is d_crab itself: it is kept within the limit.)
    return std::clamp(
        forecast_crab_rad(bearing_rad) + d_crab, -d_cfg.max_crab_rad, d_cfg.max_crab_rad);
}

void ground_track_guidance::set_forecast(double east_mps,
                                         double north_mps,
                                         double speed_mps)
{
    const bool none = east_mps == 0.0 && north_mps == 0.0;
    const double e = none ? 0.0 : east_mps, n = none ? 0.0 : north_mps;
    if (e == d_cfg.forecast_east_mps && n == d_cfg.forecast_north_mps)
        return;
    d_cfg.forecast_east_mps = e;
    d_cfg.forecast_north_mps = n;
    d_cfg.speed_mps = none ? 0.0 : speed_mps;
    // What the law learned corrected the old forecast; the new one replaces it (kept,
    // it would count the correction twice once the new forecast holds it).
    d_crab = 0.0;
}

double ground_track_guidance::bearing_rate_std() const
{
    return d_started ? std::sqrt(std::max(d_prr, 0.0)) : RATE_PRIOR;
}

double ground_track_guidance::update(double t_s, double bearing_rad, double sigma_rad)
{
    if (!std::isfinite(t_s) || !std::isfinite(bearing_rad))
        return crab_rad();
    const double sigma =
        std::isfinite(sigma_rad) ? std::max(sigma_rad, MIN_SIGMA) : 10.0 * MIN_SIGMA;
    if (d_started && t_s - d_t > MAX_GAP_S)
        d_started = false;
    if (!d_started || !(t_s > d_t)) {
        if (!d_started) {
            d_started = true;
            d_b = bearing_rad;
            d_r = 0.0;
            d_pbb = std::max(sigma * sigma, d_scatter);
            d_pbr = 0.0;
            d_prr = RATE_PRIOR * RATE_PRIOR;
            d_t = t_s;
        }
        return crab_rad();
    }
    // Predict: the rate is a random walk, the bearing its integral.
    const double dt = t_s - d_t;
    d_t = t_s;
    const double q = d_cfg.rate_walk * d_cfg.rate_walk;
    d_b += d_r * dt;
    const double pbb =
        d_pbb + 2.0 * dt * d_pbr + dt * dt * d_prr + q * dt * dt * dt / 3.0;
    const double pbr = d_pbr + dt * d_prr + q * dt * dt / 2.0;
    const double prr = d_prr + q * dt;
    // Update with the bearing, its variance the larger of the fit's and the scatter the
    // innovations have shown.
    const double r_meas = std::max(sigma * sigma, d_scatter);
    const double y_raw = wrap_remainder(bearing_rad - d_b);
    const double s = pbb + r_meas;
    const double lim = INNOVATION_CLIP * std::sqrt(s);
    const double y = std::clamp(y_raw, -lim, lim);
    const double kb = pbb / s, kr = pbr / s;
    d_b = wrap_remainder(d_b + kb * y);
    d_r += kr * y;
    d_pbb = (1.0 - kb) * pbb;
    d_pbr = (1.0 - kb) * pbr;
    d_prr = prr - kr * pbr;
    const double seen = std::min(y_raw * y_raw, 9.0 * s) - pbb;
    d_scatter = std::max((1.0 - SCATTER_GAIN) * d_scatter + SCATTER_GAIN * seen,
                         MIN_SIGMA * MIN_SIGMA);

    // Proportional navigation on a rate known to differ from zero.
    if (std::abs(d_r) > d_cfg.gate * std::sqrt(std::max(d_prr, 0.0)) &&
        std::abs(d_r) < NEAR_RATE) {
        const double step = std::clamp(
            d_cfg.gain * d_r * dt, -d_cfg.max_crab_rate * dt, d_cfg.max_crab_rate * dt);
        d_crab += step;
    }
    // The limit holds for the crab flown (forecast's + learned), at every bearing: a
    // learned crab beyond it would wind up unseen (without a forecast, |d_crab| <= max
    // as before).
    const double cf = forecast_crab_rad(d_b);
    d_crab = std::clamp(d_crab, -d_cfg.max_crab_rad - cf, d_cfg.max_crab_rad - cf);
    return crab_rad();
}

} // namespace rfseek
} // namespace gr
