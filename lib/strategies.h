/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * strategies: the constructors behind seeker::make, one strategy per file:
 *   two_stage_seeker.cc   paper, paper_no_circle (the paper's Stage 1 circle, Stage 2 eq.
 * 5) rss_seeker.cc         rss_baseline (received power only, after Wadhwa et al.)
 *   adaptive_seeker.cc    adaptive (ours: model-inverting probes, not in the paper)
 * Internal to the library.
 */

#ifndef INCLUDED_RFSEEK_STRATEGIES_H
#define INCLUDED_RFSEEK_STRATEGIES_H

#include "ground_track.h"
#include "outlier_filter.h"
#include "turn_model.h"
#include <gr-rfseek/seeker.h>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace gr {
namespace rfseek {

//! std::invalid_argument "<what> = '<name>': must be one of ..." unless name is one of
//! seeker::strategies().
inline void require_strategy(const std::string& name, const std::string& what)
{
    const auto names = seeker::strategies();
    if (std::find(names.begin(), names.end(), name) != names.end())
        return;
    std::string all;
    for (const auto& s : names)
        all += (all.empty() ? "" : ", ") + s;
    throw std::invalid_argument(what + " = '" + name + "': must be one of " + all);
}

std::unique_ptr<seeker> make_two_stage_seeker(const seeker_config& cfg);
std::unique_ptr<seeker> make_rss_seeker(const seeker_config& cfg);
std::unique_ptr<seeker> make_adaptive_seeker(const seeker_config& cfg);
//! Any strategy with arrival detection, loiter and location (homing_seeker.cc).
std::unique_ptr<seeker> make_homing_seeker(const seeker_config& cfg,
                                           std::unique_ptr<seeker> strategy);

//! The eq. 4 filter as a strategy's configuration asks for it.
inline outlier_filter make_outlier_filter(const seeker_config& cfg)
{
    return outlier_filter(cfg.effective_outlier_threshold_hz(),
                          cfg.literal_eq4,
                          cfg.lock_count,
                          cfg.relock_count,
                          cfg.min_snr_db);
}

//! The ground-track guidance as a strategy's configuration asks for it, with the
//! strategy's own gain K (ground_track_gain or paper_ground_track_gain).
inline ground_track_guidance make_ground_track(const seeker_config& cfg, double gain)
{
    ground_track_config g;
    g.gain = gain;
    g.max_crab_rad = cfg.ground_track_max_crab_rad;
    g.gate = cfg.ground_track_gate;
    g.rate_walk = cfg.ground_track_rate_walk;
    ground_track_guidance t(g);
    t.set_forecast(
        cfg.wind_forecast_east_mps, cfg.wind_forecast_north_mps, cfg.speed_mps);
    return t;
}

//! seeker::set_wind_forecast for a strategy whose ground track is `track` (on: the
//! strategy flies it): the configuration and the guidance take the new forecast.
inline bool set_track_forecast(seeker_config& cfg,
                               ground_track_guidance& track,
                               bool on,
                               double east_mps,
                               double north_mps)
{
    if (!on)
        return false;
    cfg.wind_forecast_east_mps = east_mps;
    cfg.wind_forecast_north_mps = north_mps;
    track.set_forecast(east_mps, north_mps, cfg.speed_mps);
    return true;
}

//! The turn limits the strategies plan with (the vehicle's, as the configuration says).
inline turn_limits turn_limits_of(const seeker_config& cfg)
{
    return turn_limits{ cfg.turn_rate_rad_per_s,
                        cfg.bank_limit_rad,
                        cfg.roll_rate_rad_per_s,
                        cfg.speed_mps };
}

//! Slots until a heading change of |turn| is flown (0 without a turn limit): the
//! ceiling of the turn's time in slots less `slack`.
inline int settle_slots(const seeker_config& cfg, double turn, double slack = 1e-9)
{
    const turn_limits lim = turn_limits_of(cfg);
    if (!lim.limited())
        return 0;
    const double slots = lim.rolls()
                             ? lim.change_time_s(turn) / cfg.slot_period_s
                             : std::abs(turn) / (lim.max_rate() * cfg.slot_period_s);
    return static_cast<int>(std::ceil(slots - slack));
}

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_STRATEGIES_H */
