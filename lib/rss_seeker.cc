/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rss_seeker: strategy `rss_baseline`, the received-signal-strength method the paper
 * compares against. It uses only power_db (no frequency, no eq. 4).
 */

#include "strategies.h"
#include <gr-rfseek/rng.h>
#include <gr-rfseek/world.h>
#include <algorithm>
#include <cmath>
#include <vector>

namespace gr {
namespace rfseek {

namespace {

// rss_baseline: the received-signal-strength method the paper compares against
// (Wadhwa, Madhow, Hespanha, Sadler, "Following an RF trail to its source", Allerton
// 2011), reconstructed from its description (docs/seeker.md). It uses only power_db.
//
// Moving along the line of sight, the paths from the scatterers around the emitter keep
// their phase differences and the power fades slowly; across it they fade fast (at 5 km
// the slow cone is only a few degrees wide). So:
// - scan: fly a circle of circle_radius_m (as Stage 1) and take the heading where the
//   power changes least (median |p[k+3] - p[k]| over a 15-slot window, smallest) as the
//   line-of-sight axis; which way along it is unknown: pick one at random;
// - run: fly straight runs of rss_run_slots slots; a run's fading rate is the median
//   |p[k+10] - p[k]|; the trend of the run-mean power over the runs tells toward (rising)
//   from away (falling by rss_reverse_db: turn back);
// - tumble: two runs in a row fading faster than rss_good_ratio of the scan's typical
// rate
//   mean the heading has left the cone: scan again from where the UAV is.
// Slots flown while turning are not judged, so the moves stay feasible at a finite rate.
class rss_seeker : public seeker
{
public:
    explicit rss_seeker(const seeker_config& cfg)
        : d_cfg(cfg), d_rng(cfg.seed, 12), d_radius(cfg.circle_radius_m)
    {
    }

    const seeker_config& config() const override { return d_cfg; }
    int stage() const override { return d_scanning ? 1 : 2; }
    double theta_est_rad() const override { return d_axis; }
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
        const double h_meas = d_have_heading ? d_meas_heading : d_heading;
        if (d_scanning) {
            d_scan_p.push_back(valid ? m.power_db : NAN);
            d_scan_h.push_back(h_meas);
            if (d_scan_next >= d_circle_cmds) {
                finish_scan();
                c.update = true;
            } else {
                d_heading = d_scan_base + d_sense * (++d_scan_next) * d_circle_step;
            }
        } else {
            if (d_settle > 0)
                --d_settle;
            else if (valid)
                d_power.push_back(m.power_db);
            if (++d_in_run >= d_cfg.rss_run_slots) {
                c.update = judge_run();
                d_in_run = 0;
                d_power.clear();
            }
        }
        c.stage = stage();
        c.heading_rad = world::wrap(d_heading);
        c.theta_est_rad = d_axis;
        c.holding = d_missing >= d_cfg.hold_after_missing;
        c.filtered_freq_hz = m.freq_hz;
        c.accepted = valid;
        return c;
    }

private:
    static double median_abs_lag(const std::vector<double>& p,
                                 std::size_t a,
                                 std::size_t b,
                                 std::size_t lag)
    {
        std::vector<double> v;
        for (std::size_t i = a + lag; i < b; ++i)
            if (std::isfinite(p[i]) && std::isfinite(p[i - lag]))
                v.push_back(std::abs(p[i] - p[i - lag]));
        if (v.empty())
            return NAN;
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v[v.size() / 2];
    }

    void start_scan()
    {
        d_circle_step = d_cfg.speed_mps * d_cfg.slot_period_s / d_radius;
        d_circle_cmds = std::max(1L, std::lround(2.0 * M_PI / d_circle_step));
        d_scanning = true;
        d_scan_base = d_heading;
        d_sense = d_rng.uniform() < 0.5 ? 1.0 : -1.0;
        d_scan_next = 0;
        d_scan_p.clear();
        d_scan_h.clear();
        d_heading = d_scan_base + d_sense * (++d_scan_next) * d_circle_step;
    }

    void finish_scan()
    {
        const std::size_t n = d_scan_p.size();
        const std::size_t half = 7;
        double best = 1e300;
        std::size_t arg = 0;
        std::vector<double> rates;
        for (std::size_t i = half + 3; i + half < n; ++i) {
            const double r = median_abs_lag(d_scan_p, i - half - 3, i + half + 1, 3);
            if (!std::isfinite(r))
                continue;
            rates.push_back(r);
            if (r < best) {
                best = r;
                arg = i;
            }
        }
        if (!rates.empty()) {
            std::sort(rates.begin(), rates.end());
            d_ref = rates[(3 * (rates.size() - 1)) / 4];
        }
        const double axis = d_scan_h[arg];
        if (d_follow) {
            // Keep going the way that was confirmed toward the emitter.
            d_axis = std::abs(world::wrap(axis - d_last_toward)) <= M_PI / 2
                         ? axis
                         : world::wrap(axis + M_PI);
        } else {
            d_axis = world::wrap(axis + (d_rng.uniform() < 0.5 ? 0.0 : M_PI));
        }
        d_follow = false;
        d_scanning = false;
        ++d_updates;
        turn_to(d_axis);
    }

    void turn_to(double h)
    {
        h = world::wrap(h);
        if (turn_limits_of(d_cfg).limited())
            d_settle = settle_slots(d_cfg, world::wrap(h - d_heading), 0.0);
        d_heading = h;
        d_run_means.clear();
        d_bad = 0;
        d_in_run = 0;
        d_power.clear();
    }

    // Least-squares change of the run means over the last n runs (dB).
    double trend(std::size_t n) const
    {
        const std::size_t k0 = d_run_means.size() - n;
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double y = d_run_means[k0 + i];
            sx += i;
            sy += y;
            sxx += double(i) * i;
            sxy += i * y;
        }
        return (n * sxy - sx * sy) / (n * sxx - sx * sx) * (n - 1);
    }

    void rescan(bool follow)
    {
        if (follow) {
            d_follow = true;
            d_last_toward = d_heading;
            d_radius = std::max(0.25 * d_cfg.circle_radius_m, 0.5 * d_radius);
        }
        d_confirmed = false;
        d_run_means.clear();
        d_bad = 0;
        start_scan();
    }

    bool judge_run()
    {
        if (d_power.size() < 20)
            return false; // too little to judge: keep flying
        const double rate = median_abs_lag(d_power, 0, d_power.size(), 10);
        double mean = 0.0;
        for (double p : d_power)
            mean += p;
        mean /= d_power.size();
        ++d_updates;
        d_run_means.push_back(mean);
        const std::size_t n = d_run_means.size();
        const std::size_t need = static_cast<std::size_t>(d_cfg.rss_min_runs);
        if (d_confirmed) {
            // Toward the emitter: keep going while the power does not fall.
            if (n >= need && trend(need) < -d_cfg.rss_reverse_db)
                rescan(true);
            return true;
        }
        if (std::isfinite(rate) && rate > d_cfg.rss_good_ratio * d_ref) {
            if (++d_bad >= 2)
                rescan(false); // left the slow-fading cone: scan again
            return true;
        }
        d_bad = 0;
        if (n >= need) {
            const double change = trend(n);
            if (change < -d_cfg.rss_reverse_db) {
                d_axis = world::wrap(d_axis + M_PI);
                turn_to(d_axis);
            } else if (change > d_cfg.rss_reverse_db) {
                d_confirmed = true;
            }
        }
        return true;
    }

    seeker_config d_cfg;
    rng d_rng;
    double d_radius;
    double d_circle_step = 0.0;
    long d_circle_cmds = 0;
    bool d_started = false, d_scanning = false, d_confirmed = false;
    bool d_have_heading = false, d_follow = false;
    double d_last_toward = 0.0;
    double d_heading = 0.0, d_meas_heading = 0.0, d_axis = 0.0, d_ref = 1.0;
    double d_scan_base = 0.0, d_sense = 1.0;
    long d_scan_next = 0;
    int d_settle = 0, d_in_run = 0, d_missing = 0, d_bad = 0;
    std::vector<double> d_scan_p, d_scan_h, d_power, d_run_means;
    std::uint64_t d_updates = 0;
};

} // namespace

std::unique_ptr<seeker> make_rss_seeker(const seeker_config& cfg)
{
    return std::make_unique<rss_seeker>(cfg);
}

} // namespace rfseek
} // namespace gr
