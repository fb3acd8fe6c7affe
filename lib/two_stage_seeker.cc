/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * two_stage_seeker: the paper's two-stage seeker (Sec. III), strategies `paper` (Stage 1
 * circle, then Stage 2) and `paper_no_circle` (Stage 2 from the initial heading), with
 * the resolutions of docs/design.md.
 *
 * Timing: the measurement of slot j is taken at the heading commanded after slot j-1, so
 * each measurement is credited to the command that was in force when it was taken (its
 * "tag"). A Stage-2 step is a list of commands: S_plus settling slots then M slots at
 * theta + delta_k, S_minus settling slots then M slots at theta - delta_k (delta_k =
 * delta, or larger while a bearing keeps turning: apply_eq5). Settling slots
 * (the vehicle still turning at its finite rate) are flown but not averaged; with
 * instantaneous turns there are none. The update (eq. 5) is applied when the measurement
 * of the step's last command arrives, before the next command is issued.
 *
 * Eq. 4 is the shared outlier_filter. Values it does not accept never enter the Stage-1
 * record nor the Stage-2 means (literal_eq4 keeps the paper's substitution instead).
 * Stage 1 decides theta_0 by a least-squares fit of the circle's frequencies with a
 * linear CFO trend (doppler_fit); stage1_fit = false keeps the paper's argmax of the
 * moving average.
 *
 * paper_ground_track (off by default, the paper's): Stage 2's probes are flown around
 * theta + crab, the crab from ground_track_guidance fed with each step's bearing, so
 * that a crosswind no longer bends the ground track (step_over_the_ground).
 */

#include "doppler_fit.h"
#include "ground_track.h"
#include "strategies.h"
#include <gr-rfseek/rng.h>
#include <gr-rfseek/world.h>
#include <algorithm>
#include <cmath>
#include <vector>

namespace gr {
namespace rfseek {

namespace {

enum class phase { none, circle, plus, minus };

// paper_ground_track: beyond this error of theta the crab starts again (chosen on seeds
// 990001-990100 of `realistic` at 4 and 7 m/s: 0.5 rad reset it on the gusts' noise).
constexpr double CRAB_RESET_RAD = 1.0;

struct cmd_tag {
    phase ph = phase::none;
    bool settle = false;
    long step = -1;
    bool last = false; // last command of the circle or of the step
};

class two_stage_seeker : public seeker
{
public:
    explicit two_stage_seeker(const seeker_config& cfg)
        : d_cfg(cfg),
          d_filter(make_outlier_filter(cfg)),
          d_delta(cfg.delta_rad),
          d_circle(cfg.strategy == "paper"),
          d_grow_delta(d_circle && cfg.delta_max_rad > cfg.delta_rad),
          d_ground_track(cfg.paper_ground_track),
          d_track(make_ground_track(cfg, cfg.paper_ground_track_gain))
    {
        rng g(cfg.seed, 11);
        d_sense = g.uniform() < 0.5 ? 1.0 : -1.0;
        // The circle at circle_radius_m, or at the turn limit where the radius needs it.
        const turn_limits lim = turn_limits_of(cfg);
        double step = cfg.speed_mps * cfg.slot_period_s / cfg.circle_radius_m;
        if (lim.limited() && step > lim.max_rate() * cfg.slot_period_s)
            step = lim.max_rate() * cfg.slot_period_s;
        d_circle_step = step;
        d_circle_cmds = std::max(1L, std::lround(2.0 * M_PI / step));
    }

    const seeker_config& config() const override { return d_cfg; }
    bool set_wind_forecast(double east_mps, double north_mps) override
    {
        return set_track_forecast(
            d_cfg, d_track, d_cfg.paper_ground_track, east_mps, north_mps);
    }
    int stage() const override { return d_stage; }
    double theta_est_rad() const override { return d_theta; }
    std::uint64_t updates() const override { return d_updates; }

    command update(const measurement& m) override
    {
        command c;
        c.slot = m.slot;
        if (m.has_heading && std::isfinite(m.heading_rad)) {
            d_heading = m.heading_rad;
            d_have_heading = true;
        }
        const bool valid = m.valid && std::isfinite(m.freq_hz);

        if (!d_started) {
            d_started = true;
            const double h0 =
                d_have_heading ? d_heading : d_cfg.initial_heading_rad.value_or(0.0);
            d_last_cmd = h0;
            if (d_circle) {
                d_stage = 1;
                d_circle_base = h0;
                d_theta = h0;
                d_prev = cmd_tag{ phase::circle, false, -1, false };
            } else {
                d_stage = 2;
                d_theta = world::wrap(d_cfg.initial_heading_rad.value_or(h0));
                start_step();
                d_prev = cmd_tag{};
            }
        } else if (m.slot > d_last_slot + 1) {
            const int gap = static_cast<int>(
                std::min<std::uint64_t>(m.slot - d_last_slot - 1, 1 << 20));
            d_missing += gap;
            if (gap >= d_cfg.hold_after_missing && d_stage == 2 && !d_hold) {
                // The vehicle held its course through the gap: the step in progress is
                // stale, start a new one (and delta_k anew).
                reset_delta_k();
                start_step();
                d_prev = cmd_tag{};
            }
        }
        d_last_slot = m.slot;

        double f = 0.0;
        bool use = false; // enters the Stage-1 record or the Stage-2 means
        if (valid) {
            const auto r = d_filter.push(m.freq_hz, m.snr_db);
            c.accepted = r.accepted;
            f = c.filtered_freq_hz = r.value;
            use = r.accepted || (d_cfg.literal_eq4 && r.locked);
        }

        // Holding course after a run of missing or invalid measurements.
        d_missing = valid ? 0 : d_missing + 1;
        if (!d_hold && d_missing >= d_cfg.hold_after_missing) {
            d_hold = true;
            d_hold_heading = d_stage == 2 ? d_theta + d_crab : d_last_cmd;
        }
        if (d_hold) {
            if (!valid)
                return issue(c, d_hold_heading, cmd_tag{}, true);
            d_hold = false; // measurements are back: resume
            if (d_stage == 2) {
                reset_delta_k();
                start_step();
            }
            d_prev = cmd_tag{};
        }

        // Credit this measurement to the command in force when it was taken.
        if (use) {
            if (d_prev.ph == phase::circle) {
                d_samples_f.push_back(f);
                d_samples_h.push_back(d_have_heading ? d_heading : d_last_cmd);
                d_samples_t.push_back(m.time_s);
            } else if ((d_prev.ph == phase::plus || d_prev.ph == phase::minus) &&
                       !d_prev.settle && d_prev.step == d_step) {
                (d_prev.ph == phase::plus ? d_sum_plus : d_sum_minus) += f;
                ++(d_prev.ph == phase::plus ? d_n_plus : d_n_minus);
                d_step_t_sum += m.time_s;
            }
        }

        if (d_stage == 1 && d_prev.ph == phase::circle && d_prev.last) {
            decide_initial_heading();
            c.update = true;
        } else if (d_stage == 2 && d_prev.last && d_prev.step == d_step) {
            c.update = apply_eq5();
            start_step();
        }
        return next_command(c);
    }

private:
    // paper_ground_track (docs/seeker.md "Guidance over the ground"): eq. 5's step moves
    // theta toward the bearing the probes measured around theta + crab (the paper's
    // step when the crab is 0 and the difference within its range; capped beyond), and
    // each step's bearing feeds the crab's filter.
    // A probe difference beyond its range (|sin| > 1: noise or a bearing far off) says
    // nothing of the bearing's rotation and is left out; an error of theta beyond
    // CRAB_RESET_RAD (the emitter passed or lost) makes the crab, measured on the old
    // line of sight, wrong for the new one: it starts again from 0.
    void step_over_the_ground(double diff_hz, double centre_err, double theta_err)
    {
        const double a = d_cfg.max_doppler_hz();
        const double bearing = world::wrap(d_theta + d_crab - centre_err);
        const bool in_range = std::abs(diff_hz) < 2.0 * a * std::sin(d_delta);
        d_theta = world::wrap(d_theta + 2.0 * d_delta * std::sin(d_delta) *
                                            std::sin(world::wrap(bearing - d_theta)));
        if (std::abs(theta_err) > CRAB_RESET_RAD) {
            d_track.reset();
            d_crab = d_track.forecast_crab_rad(bearing); // 0 without a forecast
        } else if (in_range) {
            // No standard error is passed (the filter's floor): the scatter its own
            // innovations show sets the bearing's variance, as gusts dominate it.
            d_crab = d_track.update(d_step_t_sum / (d_n_plus + d_n_minus), bearing, 0.0);
        }
    }

    command issue(command& c, double heading, const cmd_tag& tag, bool holding)
    {
        d_prev = tag;
        d_last_cmd = world::wrap(heading);
        c.heading_rad = d_last_cmd;
        c.stage = d_stage;
        c.theta_est_rad = d_theta;
        c.holding = holding;
        return c;
    }

    int settle_slots(double turn) const { return rfseek::settle_slots(d_cfg, turn); }

    // After an outage the errors measured before it say nothing of the bearing now.
    void reset_delta_k()
    {
        d_run = 0;
        d_delta = d_cfg.delta_rad;
    }

    void start_step()
    {
        ++d_step;
        d_pos = 0;
        d_sum_plus = d_sum_minus = 0.0;
        d_n_plus = d_n_minus = 0;
        d_step_t_sum = 0.0;
        d_settle_plus =
            settle_slots(world::wrap(d_theta + d_crab + d_delta - d_last_cmd));
        d_settle_minus = settle_slots(2.0 * d_delta);
    }

    command next_command(command& c)
    {
        if (d_stage == 1) {
            const long i = d_circle_next++;
            const double h = d_circle_base + d_sense * (i + 1) * d_circle_step;
            return issue(
                c, h, cmd_tag{ phase::circle, false, -1, i == d_circle_cmds - 1 }, false);
        }
        const int half_plus = d_settle_plus + d_cfg.m_slots;
        const int half_minus = d_settle_minus + d_cfg.m_slots;
        const int pos = d_pos++;
        cmd_tag tag;
        tag.step = d_step;
        if (pos < half_plus) {
            tag.ph = phase::plus;
            tag.settle = pos < d_settle_plus;
        } else {
            tag.ph = phase::minus;
            tag.settle = pos - half_plus < d_settle_minus;
            tag.last = pos == half_plus + half_minus - 1;
        }
        const double h = d_theta + d_crab + (tag.ph == phase::plus ? d_delta : -d_delta);
        return issue(c, h, tag, false);
    }

    // Stage 1 decision. Default: least squares of the circle's frequencies against
    // f = A cos(psi - beta) + c + a t (doppler_fit), theta_0 = beta, so a linear CFO
    // drift over the circle does not move the decision. stage1_fit = false: the paper's
    // heading of the maximum of the moving-averaged frequency (eq. 4, then argmax); the
    // moving average is centred and circular (the circle is closed; a trailing average
    // would lag the heading by half its length).
    void decide_initial_heading()
    {
        const int n = static_cast<int>(d_samples_f.size());
        double theta0 = d_last_cmd;
        bool decided = false;
        if (d_cfg.stage1_fit && n > 0) {
            std::vector<doppler_sample> s(n);
            for (int i = 0; i < n; ++i)
                s[i] = doppler_sample{ d_samples_h[i], d_samples_t[i], d_samples_f[i] };
            const doppler_fit_result r = fit_doppler_full(s, true);
            if (r.ok) {
                theta0 = r.bearing_rad;
                decided = true;
            }
        }
        if (!decided && n > 0) {
            const int L = std::min(d_cfg.moving_average_len, n);
            const int back = (L - 1) / 2;
            double best = -1e300;
            int arg = 0;
            for (int i = 0; i < n; ++i) {
                double s = 0.0;
                for (int k = 0; k < L; ++k)
                    s += d_samples_f[((i - back + k) % n + n) % n];
                if (s > best) {
                    best = s;
                    arg = i;
                }
            }
            theta0 = d_samples_h[arg];
        }
        d_stage = 2;
        d_theta = world::wrap(theta0);
        d_samples_f.clear();
        d_samples_h.clear();
        d_samples_t.clear();
        start_step();
    }

    // Stage 2, eq. 5 in Hz: theta += (mean f+ - mean f-) delta_k / f_d,max.
    bool apply_eq5()
    {
        const int need = std::max(1, d_cfg.m_slots / 2);
        if (d_n_plus < need || d_n_minus < need) {
            reset_delta_k(); // too few measurements in a half: keep theta, delta anew
            return false;
        }
        const double mean_plus = d_sum_plus / d_n_plus;
        const double mean_minus = d_sum_minus / d_n_minus;
        const double a = d_cfg.max_doppler_hz();
        // The error of the probes' centre (centre - bearing), the difference inverted;
        // theta's error is that less the crab flown.
        const double centre_err =
            invert_probe_difference(mean_plus, mean_minus, d_delta, a);
        const double theta_err = centre_err - d_crab;
        if (d_ground_track)
            step_over_the_ground(mean_plus - mean_minus, centre_err, theta_err);
        else
            d_theta = world::wrap(d_theta + (mean_plus - mean_minus) * d_delta / a);
        ++d_updates;
        if (d_grow_delta) {
            // delta_k (docs/seeker.md "Stage 2 in the wind"). The error this step
            // measured (the probe difference inverted, folded into [-90, 90] deg); once
            // delta_after_steps steps in a row measured more than delta on the same side
            // (a bearing that keeps turning, not the seconds of a pass), the probe grows
            // toward it by at most delta_step_rad per step, up to delta_max_rad, and
            // never beyond the error just measured; it is delta again as soon as a step
            // measures less than delta.
            const double err = theta_err;
            const double e = std::abs(err);
            const int side = err > 0.0 ? 1 : -1;
            if (e <= d_cfg.delta_rad)
                d_run = 0;
            else
                d_run = (d_run > 0 && side == d_side) ? d_run + 1 : 1;
            d_side = side;
            d_delta = d_run >= d_cfg.delta_after_steps
                          ? std::min(std::min(e, d_cfg.delta_max_rad),
                                     d_delta + d_cfg.delta_step_rad)
                          : d_cfg.delta_rad;
        }
        return true;
    }

    seeker_config d_cfg;
    outlier_filter d_filter;
    double d_delta; // delta_k of the step in progress
    const bool d_circle;
    // delta_k follows the measured error only in `paper`, whose Stage 2 starts after
    // Stage 1 facing the emitter (from an arbitrary heading eq. 5 cannot tell theta~
    // from pi - theta~), and only with delta_max_rad > delta_rad.
    const bool d_grow_delta;
    double d_sense = 1.0, d_circle_step = 0.0;
    long d_circle_cmds = 0, d_circle_next = 0;
    double d_circle_base = 0.0;
    std::vector<double> d_samples_f, d_samples_h, d_samples_t;

    bool d_started = false;
    int d_stage = 1;
    double d_theta = 0.0;
    double d_heading = 0.0;
    bool d_have_heading = false;
    double d_last_cmd = 0.0;
    std::uint64_t d_last_slot = 0;
    int d_missing = 0;
    bool d_hold = false;
    double d_hold_heading = 0.0;
    cmd_tag d_prev;

    long d_step = -1;
    int d_pos = 0;
    int d_settle_plus = 0, d_settle_minus = 0;
    double d_sum_plus = 0.0, d_sum_minus = 0.0;
    int d_run = 0;  // consecutive steps that measured more than delta, on one side
    int d_side = 0; // that side (the sign of the measured error)
    int d_n_plus = 0, d_n_minus = 0;
    std::uint64_t d_updates = 0;
    // paper_ground_track: the crab flown around theta (ground_track), and the sum of the
    // times of the step's averaged measurements (the bearing's time for its filter)
    const bool d_ground_track;
    ground_track_guidance d_track;
    double d_crab = 0.0;
    double d_step_t_sum = 0.0; // over the step's d_n_plus + d_n_minus measurements
};


} // namespace

std::unique_ptr<seeker> make_two_stage_seeker(const seeker_config& cfg)
{
    return std::make_unique<two_stage_seeker>(cfg);
}

} // namespace rfseek
} // namespace gr
