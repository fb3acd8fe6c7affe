/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rss_seeker: strategy `rss_baseline`, the received-signal-strength method the paper
 * compares against. It uses only power_db (no frequency, no eq. 4).
 */

#include "rss_phases.h"
#include "strategies.h"
#include <gr-rfseek/rng.h>
#include <gr-rfseek/world.h>
#include <algorithm>
#include <cmath>
#include <vector>

namespace gr {
namespace rfseek {

namespace {

// rss_baseline: the multi-phase RSS method of Wadhwa, Madhow, Hespanha and Sadler
// ("Following an RF trail to its source", Allerton 2011) as we reconstruct it from its
// abstract (docs/seeker.md lists each choice):
// 1. direction: fly a circle of circle_radius_m, hearing the power in every direction;
//    the line-of-sight axis is where it fades slowest (the paths through the scatterers
//    around the emitter keep their phases along it), the way along the axis is the one
//    the circle's power trend rises toward (rss::estimate_direction);
// 2. run: fly straight that way; the power is averaged over blocks of rss_block_m, and
//    the run goes on while the mean of the last rss_window_blocks blocks has not fallen
//    more than rss_fall_db below the mean of the window before (rss::run_monitor);
// 3. re-estimation: when it has, fly a new circle from where the vehicle is.
// Slots flown while turning onto a run are not averaged, so the moves stay feasible at a
// finite turn rate.
class rss_seeker : public seeker
{
public:
    explicit rss_seeker(const seeker_config& cfg)
        : d_cfg(cfg),
          d_rng(cfg.seed, 12),
          d_monitor(block_slots(cfg), cfg.rss_window_blocks, cfg.rss_fall_db),
          d_circle_step(cfg.speed_mps * cfg.slot_period_s / cfg.circle_radius_m),
          d_circle_cmds(std::max(1L, std::lround(2.0 * M_PI / d_circle_step)))
    {
    }

    const seeker_config& config() const override { return d_cfg; }
    int stage() const override { return d_scanning ? 1 : 2; }
    double theta_est_rad() const override { return d_way; }
    std::uint64_t updates() const override { return d_updates; }

    command update(const measurement& m) override
    {
        command c;
        c.slot = m.slot;
        const bool valid = m.valid && std::isfinite(m.power_db);
        if (m.has_heading && std::isfinite(m.heading_rad)) {
            d_meas_heading = m.heading_rad;
            d_have_heading = true;
        }
        if (!d_started) {
            d_started = true;
            d_heading =
                d_have_heading ? d_meas_heading : d_cfg.initial_heading_rad.value_or(0.0);
            start_scan();
        }
        d_missing = valid ? 0 : d_missing + 1;
        if (d_scanning) {
            d_scan_p.push_back(valid ? m.power_db : NAN);
            d_scan_h.push_back(d_have_heading ? d_meas_heading : d_heading);
            if (d_scan_next >= d_circle_cmds) {
                c.update = finish_scan();
            } else {
                d_heading = d_scan_base + d_sense * (++d_scan_next) * d_circle_step;
            }
        } else if (d_settle > 0) {
            --d_settle;
        } else if (d_monitor.add(valid ? m.power_db : NAN)) {
            start_scan(); // the long-term average fell: estimate the direction again
        }
        c.stage = stage();
        c.heading_rad = world::wrap(d_heading);
        c.theta_est_rad = d_way;
        c.holding = d_missing >= d_cfg.hold_after_missing;
        c.filtered_freq_hz = m.freq_hz;
        c.accepted = valid;
        return c;
    }

private:
    static int block_slots(const seeker_config& cfg)
    {
        const double slots = cfg.rss_block_m / (cfg.speed_mps * cfg.slot_period_s);
        return static_cast<int>(std::clamp(std::round(slots), 4.0, 100000.0));
    }

    void start_scan()
    {
        d_scanning = true;
        d_scan_base = d_heading;
        d_sense = d_rng.uniform() < 0.5 ? 1.0 : -1.0;
        d_scan_next = 0;
        d_scan_p.clear();
        d_scan_h.clear();
        d_heading = d_scan_base + d_sense * (++d_scan_next) * d_circle_step;
    }

    // The circle is complete: run the way it found, or fly another one when it found
    // nothing (every power missing).
    bool finish_scan()
    {
        const rss::direction_estimate e =
            rss::estimate_direction(d_scan_p, d_scan_h, d_sense, d_cfg.circle_radius_m);
        if (!e.valid) {
            start_scan();
            return false;
        }
        d_scanning = false;
        d_way = e.way_rad;
        ++d_updates;
        const double to = world::wrap(d_way);
        d_settle = settle_slots(d_cfg, world::wrap(to - d_heading), 0.0);
        d_heading = to;
        d_monitor.reset();
        return true;
    }

    seeker_config d_cfg;
    rng d_rng;
    rss::run_monitor d_monitor;
    const double d_circle_step; // heading step of a circle of circle_radius_m (rad/slot)
    const long d_circle_cmds;   // commands per full circle
    bool d_started = false, d_scanning = false, d_have_heading = false;
    double d_heading = 0.0, d_meas_heading = 0.0, d_way = 0.0;
    double d_scan_base = 0.0, d_sense = 1.0;
    long d_scan_next = 0;
    int d_settle = 0, d_missing = 0;
    std::vector<double> d_scan_p, d_scan_h;
    std::uint64_t d_updates = 0;
};

} // namespace

std::unique_ptr<seeker> make_rss_seeker(const seeker_config& cfg)
{
    return std::make_unique<rss_seeker>(cfg);
}

} // namespace rfseek
} // namespace gr
