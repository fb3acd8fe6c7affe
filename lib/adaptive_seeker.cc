/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * adaptive_seeker: strategy `adaptive`. Ours, not the paper's: it keeps the paper's idea
 * (Stage-2 probing around the estimated bearing) and drops its circle and its small eq. 5
 * gain. docs/seeker.md has the analysis behind each constant.
 *
 * - Acquisition: fly three headings 120 deg apart twice round (adaptive_acquire_slots
 *   each; with a turn limit, a turn at the maximum rate, see below) and fit
 *   f = a cos psi + b sin psi + c + d t (doppler_fit): the whole circle of bearings,
 *   "flying away" included, and a linear CFO drift, in a few slots. An implausible fit
 *   (few samples, wrong amplitude, loose bearing) is retried after
 *   adaptive_relocate_slots straight on, out of the fade, keeping recent samples.
 * - Tracking: probe cycles +delta, -delta, -delta, +delta (adaptive_track_slots each).
 * The palindromic order makes a linear CFO drift orthogonal to the probe difference, and
 *   the fit has a drift term too. The fit inverts the model (asin of the normalised
 *   difference), so one cycle measures the whole error; theta moves by adaptive_gain of
 *   it. delta follows the measured noise (delta* = (G/N)^(1/4) sqrt(sigma/A), the
 *   minimum of zig-zag plus pointing cost) and the last error, within [delta_min,
 *   delta_max].
 * - Away check: the probe mean is the CFO plus A cos(theta~). The CFO is tracked from
 *   cycle to cycle; a mean below it by more than A says |theta~| > 90 deg, and an error
 *   beyond adaptive_reacquire_rad also starts a new acquisition.
 * - Turns planned for the airframe (any turn limit: a turn rate, or a bank and a roll
 *   rate): the acquisition turn leads the heading by ACQ_LEAD, reverses once the side
 *   test says the emitter is the other way, and ends on the first arc (>= ARC_MIN)
 *   whose fit is sure; probe segments are lengthened so that turns take at most
 *   adaptive_turn_share of a cycle, and delta is capped where they could not.
 * - Turn awareness: every measurement enters the fits at its own heading (the commanded
 *   heading once the vehicle has turned to it, the measured one while it turns), never
 *   averaged as if flown straight at the probe heading.
 * - Eq. 4 (outlier_filter) vets every frequency; rejected values are simply left out.
 * - Over the ground (adaptive_ground_track): the probes are flown around theta + crab,
 *   the crab from ground_track_guidance fed with each cycle's measured bearing, so that
 *   a crosswind does not bend the ground track into a pursuit curve. theta stays the
 *   bearing estimate; the fit is centred on the heading flown.
 */

#include "doppler_fit.h"
#include "strategies.h"
#include <gr-rfseek/world.h>
#include <algorithm>
#include <cmath>
#include <vector>

namespace gr {
namespace rfseek {

namespace {

constexpr double ACQ_STEP = 2.0 * M_PI / 3.0; // 120 deg between acquisition headings
constexpr int ACQ_HEADINGS = 6;               // twice round
constexpr int ACQ_ROUNDS = 4;                 // rounds whose samples a retry keeps
constexpr int ACQ_MIN_SAMPLES = 8;            // accepted samples for a 4-term fit
constexpr double ACQ_MAX_STD = 0.25;          // rad (14 deg): the fit's bearing std
// A turn-limited acquisition ends early once the arc flown holds a sure fit:
constexpr double ARC_MIN = 1.0471975511965976;  // rad (60 deg) of the model's heading
constexpr double ARC_DRIFT = 5.235987755982988; // rad (300 deg): fit the drift from here
constexpr double ARC_MAX_STD = 0.07; //           // rad (4 deg): the fit's bearing std
constexpr double ARC_AMP_TOL = 0.25; // |A fitted / f_d,max - 1|
constexpr int TURN_MAX_SEGMENTS = 4; // probe segments up to 4 x adaptive_track_slots
// The turn-limited acquisition's side test (doppler_side): from SIDE_MIN of arc, the
// Doppler along the arc, the amplitude known, says on which side the emitter lies; once
// the likelihood ratio of the sides passes SIDE_Z^2 the turn goes on that way (reversed
// if need be). Undecided at SIDE_MAX (the emitter near ahead or behind), it goes on as
// it is. SIDE_Z chosen on seeds 990001-990300 (2 to 4 alike).
constexpr double SIDE_MIN = 0.05235987755982988; // rad (3 deg)
constexpr double SIDE_MAX = 0.5235987755982988;  // rad (30 deg)
constexpr double SIDE_Z = 3.0;
// Planned turns lead the heading by ACQ_LEAD: the roll begins at once at its full rate,
// and the way of the turn does not depend on the compass noise of the start heading.
constexpr double ACQ_LEAD = 0.3490658503988659; // rad (20 deg)

class adaptive_seeker : public seeker
{
public:
    explicit adaptive_seeker(const seeker_config& cfg)
        : d_cfg(cfg),
          d_filter(make_outlier_filter(cfg)),
          d_track(make_ground_track(cfg, cfg.ground_track_gain)),
          d_amp(cfg.max_doppler_hz()),
          d_lim(turn_limits_of(cfg)),
          d_plan_turns(d_lim.limited()),
          d_turn(d_lim, 0.0)
    {
        d_delta_max = turn_delta_max();
        d_delta = cfg.adaptive_delta_max_rad;
    }

    const seeker_config& config() const override { return d_cfg; }
    bool set_wind_forecast(double east_mps, double north_mps) override
    {
        return set_track_forecast(
            d_cfg, d_track, d_cfg.adaptive_ground_track, east_mps, north_mps);
    }
    int stage() const override { return d_acquiring ? 1 : 2; }
    double theta_est_rad() const override { return d_theta; }
    std::uint64_t updates() const override { return d_updates; }

    command update(const measurement& m) override
    {
        command c;
        c.slot = m.slot;
        const bool has_heading = m.has_heading && std::isfinite(m.heading_rad);
        const bool valid = m.valid && std::isfinite(m.freq_hz) && std::isfinite(m.time_s);

        if (!d_started) {
            d_started = true;
            d_model =
                has_heading ? m.heading_rad : d_cfg.initial_heading_rad.value_or(0.0);
            d_theta = world::wrap(d_cfg.initial_heading_rad.value_or(d_model));
            d_last_cmd = d_model;
            d_turn.set_heading(d_model);
            start_acquisition();
        } else if (m.slot > d_last_slot + 1) {
            d_missing += static_cast<int>(
                std::min<std::uint64_t>(m.slot - d_last_slot - 1, 1 << 20));
        }
        d_last_slot = m.slot;
        if (std::isfinite(m.time_s))
            d_last_time = m.time_s;

        // Heading at this beacon: the turn model's, unless the vehicle says otherwise.
        double psi = d_model;
        if (has_heading && (d_turning || std::abs(world::wrap(m.heading_rad - d_model)) >
                                             20.0 * M_PI / 180.0))
            psi = m.heading_rad;

        if (valid) {
            const auto r = d_filter.push(m.freq_hz, m.snr_db);
            c.accepted = r.accepted;
            c.filtered_freq_hz = r.value;
            if (r.accepted && d_tag_cycle == d_cycle) {
                d_samples.push_back(doppler_sample{ psi, m.time_s, m.freq_hz });
                if (d_acquiring && !d_side_known) // the model's heading: no noise
                    d_side_samples.push_back(
                        doppler_sample{ d_model, m.time_s, m.freq_hz });
            }
        }
        if (d_acquiring && d_tag_cycle == d_cycle)
            d_arc += std::abs(world::wrap(d_model - d_arc_last)); // the model: no noise
        d_arc_last = d_model;

        d_missing = valid ? 0 : d_missing + 1;
        if (d_missing >= d_cfg.hold_after_missing) {
            // Hold course; the cycle in progress is stale.
            if (!d_hold) {
                d_hold = true;
                d_hold_heading = d_acquiring ? d_last_cmd : d_theta + d_crab;
            }
            return issue(c, d_hold_heading, -1, true);
        }
        if (d_hold) {
            d_hold = false;
            d_acquiring ? start_acquisition() : start_cycle();
        }

        if (d_acquiring && d_plan_turns && !d_side_known && d_arc >= SIDE_MIN)
            choose_side();
        if (d_acquiring && d_plan_turns && d_arc >= ARC_MIN && d_arc < ARC_DRIFT &&
            finish_acquisition(true)) {
            c.update = true; // the arc flown so far already holds a sure bearing
            start_cycle();
        } else if (d_pos >= static_cast<int>(d_plan.size())) {
            const bool was_acquiring = d_acquiring;
            c.update = d_acquiring ? finish_acquisition() : finish_cycle();
            if (!d_acquiring)
                start_cycle();
            else
                start_acquisition(was_acquiring && !c.update);
        }
        const double h = d_plan[d_pos++];
        return issue(c, h, d_cycle, false);
    }

private:
    command issue(command& c, double heading, long tag, bool holding)
    {
        d_tag_cycle = tag;
        d_last_cmd = world::wrap(heading);
        // The vehicle's heading at the next beacon (the turn model the world flies).
        if (d_lim.rolls()) {
            d_turn.step(d_last_cmd, d_cfg.slot_period_s);
            d_turning = d_turn.turning();
            d_model = d_turn.heading_rad();
        } else {
            const double rate = d_lim.max_rate() * d_cfg.slot_period_s;
            const double turn = world::wrap(d_last_cmd - d_model);
            d_turning = rate > 0.0 && std::abs(turn) > rate;
            d_model =
                world::wrap(d_turning ? d_model + std::copysign(rate, turn) : d_last_cmd);
        }
        c.heading_rad = d_last_cmd;
        c.stage = stage();
        c.theta_est_rad = d_theta;
        c.holding = holding;
        return c;
    }

    void new_plan(bool keep_samples = false)
    {
        ++d_cycle;
        d_pos = 0;
        d_plan.clear();
        if (!keep_samples) {
            d_samples.clear();
            d_rounds.clear();
        }
    }

    // Three headings 120 deg apart, twice round; with a turn-rate limit, one turn at the
    // maximum rate (its measurements all enter the fit at their own headings). A retry
    // (the last round gave no plausible fit: deep fade, low SNR) first flies
    // adaptive_relocate_slots straight on, on the first round's heading, so the pattern
    // is not flown again in the same fade, and keeps the samples of the last ACQ_ROUNDS
    // rounds.
    void start_acquisition(bool retry = false)
    {
        d_acquiring = true;
        new_plan(retry);
        if (retry) {
            d_rounds.push_back(d_last_time);
            while (static_cast<int>(d_rounds.size()) > ACQ_ROUNDS) {
                const double oldest = d_rounds.front();
                d_rounds.erase(d_rounds.begin());
                d_samples.erase(std::remove_if(d_samples.begin(),
                                               d_samples.end(),
                                               [&](const doppler_sample& s) {
                                                   return s.time_s < oldest;
                                               }),
                                d_samples.end());
            }
            // Always the same way (the heading the first round started on): legs on the
            // pattern's last heading would close a triangle back into the same fade.
            for (int i = 0; i < d_cfg.adaptive_relocate_slots; ++i)
                d_plan.push_back(d_acq_origin);
        } else {
            d_acq_origin = d_model;
            d_side_known = false;
            d_side_samples.clear();
        }
        d_acq_start = retry ? d_acq_origin : d_model;
        d_arc = 0.0;
        d_arc_last = d_model;
        const double rate = d_lim.max_rate() * d_cfg.slot_period_s;
        if (rate > 0.0 && rate < ACQ_STEP) {
            plan_turn(d_acq_start);
        } else {
            for (int k = 0; k < ACQ_HEADINGS; ++k)
                for (int i = 0; i < d_cfg.adaptive_acquire_slots; ++i)
                    d_plan.push_back(d_acq_start + k * ACQ_STEP);
        }
    }

    // One full turn at the maximum rate from `from`, ACQ_LEAD ahead, the way d_acq_dir
    // says, then adaptive_acquire_slots on its last heading.
    void plan_turn(double from)
    {
        const double rate = d_acq_dir * d_lim.max_rate() * d_cfg.slot_period_s;
        const double lead = d_acq_dir * ACQ_LEAD;
        const int n = static_cast<int>(std::ceil(2.0 * M_PI / std::abs(rate)));
        for (int i = 1; i <= n; ++i)
            d_plan.push_back(from + lead + i * rate * (1.0 - 1e-9));
        for (int i = 0; i < d_cfg.adaptive_acquire_slots; ++i)
            d_plan.push_back(from + lead + n * rate * (1.0 - 1e-9));
    }

    // The side test (SIDE_MIN .. SIDE_MAX of arc, doppler_side): which side of the
    // heading now flown the emitter lies on, the amplitude known; a sure answer the other
    // way than the turn reverses it from here. The arc and the samples go on (both ways
    // add headings to the fit).
    void choose_side()
    {
        const bool enough = static_cast<int>(d_side_samples.size()) >= ACQ_MIN_SAMPLES;
        const doppler_side_result r =
            enough ? doppler_side(d_side_samples, d_model, d_amp) : doppler_side_result{};
        if (!r.ok || !(r.statistic > SIDE_Z * SIDE_Z)) {
            d_side_known = d_arc >= SIDE_MAX;
            return;
        }
        d_side_known = true;
        if ((r.side > 0) == (d_acq_dir > 0.0))
            return;
        d_acq_dir = -d_acq_dir;
        d_plan.resize(d_pos);
        plan_turn(d_model);
    }

    // arc: the turn-limited acquisition's early end (an arc short of the full turn, no
    // drift term below ARC_DRIFT): only a sure fit ends it, anything else turns on.
    bool finish_acquisition(bool arc = false)
    {
        const doppler_fit_result r =
            fit_doppler_full(d_samples, d_cfg.adaptive_drift && !arc);
        // A plausible fit: enough samples, the amplitude is the known f_d,max within a
        // third and the bearing is known to within ACQ_MAX_STD.
        if (!r.ok || r.used < ACQ_MIN_SAMPLES || r.amplitude_hz < 0.67 * d_amp ||
            r.amplitude_hz > 1.5 * d_amp || !(r.bearing_std_rad < ACQ_MAX_STD))
            return false; // acquire again
        if (arc && (std::abs(r.amplitude_hz / d_amp - 1.0) > ARC_AMP_TOL ||
                    !(r.bearing_std_rad < ARC_MAX_STD)))
            return false; // not sure yet: turn on
        d_theta = world::wrap(r.bearing_rad);
        // The bearing goes on as one more measurement of the ground track, but not an
        // arc's: fitted without the drift, it can be off by several degrees, which the
        // first cycles would read as the bearing turning (a crab in calm air).
        if (d_cfg.adaptive_ground_track && !arc)
            d_crab = d_track.update(mean_time(), d_theta, r.bearing_std_rad);
        d_sigma = std::max(r.residual_rms_hz, 1e-3);
        d_cfo = r.offset_hz;
        d_cfo_time = mean_time();
        d_drift = r.drift_hz_per_s;
        // The first probes: as wide as delta_max, or (a turn-limited airframe) as wide as
        // the fit's own uncertainty says.
        d_err = d_plan_turns ? 2.0 * r.bearing_std_rad : d_cfg.adaptive_delta_max_rad;
        d_acquiring = false;
        ++d_updates;
        return true;
    }

    // Probe half-angle: the minimum of zig-zag plus pointing cost for the measured noise,
    // and larger while the last error was large.
    double choose_delta() const
    {
        const double g = d_cfg.adaptive_gain;
        const double n = 4.0 * d_cfg.adaptive_track_slots;
        // The probe noise in units of sin(error) x sin(delta): the fit's white-noise
        // figure sigma / (A sqrt(n)), or the scatter the cycles' bearings have shown if
        // larger (gusts move the frequency coherently over a cycle).
        const double noise = std::max(d_sigma / (d_amp * std::sqrt(n)), d_scatter);
        const double optimum = std::pow(g / (2.0 - g), 0.25) * std::sqrt(noise);
        return std::clamp(std::max(optimum, std::abs(d_err)),
                          d_cfg.adaptive_delta_min_rad,
                          d_delta_max);
    }

    // delta_max, or less where slow turns would stretch a probe segment beyond
    // TURN_MAX_SEGMENTS x adaptive_track_slots (the largest delta whose reversals fit).
    double turn_delta_max() const
    {
        double lo = d_cfg.adaptive_delta_min_rad, hi = d_cfg.adaptive_delta_max_rad;
        const int cap = TURN_MAX_SEGMENTS * d_cfg.adaptive_track_slots;
        if (!d_plan_turns || segment_slots(hi) <= cap)
            return hi;
        if (segment_slots(lo) > cap)
            return lo;
        for (int i = 0; i < 40; ++i) {
            const double mid = 0.5 * (lo + hi);
            (segment_slots(mid) <= cap ? lo : hi) = mid;
        }
        return lo;
    }

    // Slots per probe segment: adaptive_track_slots, or more where the airframe's turns
    // are slow, so that the cycle's turns (onto its first probe, first_turn rad away,
    // then two reversals of 2 delta) take at most adaptive_turn_share of its 4 segments.
    int segment_slots(double delta, double first_turn = 0.0) const
    {
        const int m = d_cfg.adaptive_track_slots;
        if (!d_plan_turns)
            return m;
        const double turn_s =
            d_lim.change_time_s(first_turn) + 2.0 * d_lim.change_time_s(2.0 * delta);
        const double need =
            turn_s / (4.0 * d_cfg.adaptive_turn_share * d_cfg.slot_period_s);
        return std::max(m, static_cast<int>(std::ceil(need - 1e-9)));
    }

    void start_cycle()
    {
        d_acquiring = false;
        new_plan();
        d_delta = choose_delta();
        d_centre = d_theta + d_crab;
        const int m =
            segment_slots(d_delta, std::abs(world::wrap(d_centre + d_delta - d_model)));
        for (double s : { 1.0, -1.0, -1.0, 1.0 })
            for (int i = 0; i < m; ++i)
                d_plan.push_back(d_centre + s * d_delta);
    }

    bool finish_cycle()
    {
        const int need = std::max(4, d_cfg.adaptive_track_slots);
        if (static_cast<int>(d_samples.size()) < need)
            return false; // too little: keep theta, probe again
        // The fit is centred on the heading flown (theta + crab); err is the bearing
        // seen from there, e the error of theta.
        const doppler_fit_result r =
            fit_doppler_narrow(d_samples, d_centre, d_amp, d_cfg.adaptive_drift);
        if (!r.ok)
            return false;
        const double t = mean_time();
        const double err = std::asin(std::clamp(r.sin_error, -1.0, 1.0));
        const double e = d_crab + err; // |crab| < 90 deg, |err| <= 90 deg
        // Away check: the probe mean is the CFO + A (cos(theta~) cos(delta) - 1)-ish; far
        // below the tracked CFO means the emitter is behind.
        const double cfo_pred = d_cfo + d_drift * (t - d_cfo_time);
        const double level = r.offset_hz + d_amp * (1.0 - std::cos(err));
        // Crabbed, the probe difference is already large: noise can carry it past
        // the asin's range with theta still close. Such a cycle is left out.
        if (d_crab != 0.0 && std::abs(r.sin_error) > 1.0 &&
            std::abs(e) <= d_cfg.adaptive_reacquire_rad)
            return false;
        if (level - cfo_pred < -d_amp || std::abs(e) > d_cfg.adaptive_reacquire_rad ||
            std::abs(r.sin_error) > 1.0) {
            d_acquiring = true;
            return false;
        }
        d_cfo = level;
        d_cfo_time = t;
        if (d_cfg.adaptive_drift)
            d_drift = 0.5 * d_drift + 0.5 * r.drift_hz_per_s;
        d_sigma = 0.7 * d_sigma + 0.3 * std::max(r.residual_rms_hz, 1e-3);
        // Scatter of successive bearings (each scaled by its probe's sin delta): the
        // bearing noise the probes actually see.
        const double bearing = world::wrap(d_centre + err);
        if (d_cfg.adaptive_scatter_delta && d_have_bearing) {
            const double diff =
                std::min(std::abs(world::wrap(bearing - d_last_bearing)), 0.5);
            const double v =
                0.5 * diff * diff * std::sin(d_delta) * std::sin(d_last_delta);
            d_scatter2 = d_scatter2 <= 0.0 ? v : 0.9 * d_scatter2 + 0.1 * v;
            d_scatter = std::sqrt(d_scatter2);
        }
        d_have_bearing = true;
        d_last_bearing = bearing;
        d_last_delta = d_delta;
        d_err = e;
        d_theta = world::wrap(d_theta + d_cfg.adaptive_gain * e);
        if (d_cfg.adaptive_ground_track)
            d_crab = d_track.update(t, world::wrap(d_centre + err), r.bearing_std_rad);
        ++d_updates;
        return true;
    }

    double mean_time() const
    {
        double t = 0.0;
        for (const auto& s : d_samples)
            t += s.time_s;
        return d_samples.empty() ? 0.0 : t / d_samples.size();
    }

    seeker_config d_cfg;
    outlier_filter d_filter;
    ground_track_guidance d_track;
    double d_crab = 0.0; // flown heading - bearing estimate (ground-track guidance)
    bool d_have_bearing = false;
    double d_last_bearing = 0.0, d_last_delta = 0.0, d_scatter2 = 0.0, d_scatter = 0.0;
    double d_centre = 0.0; // the heading the probes of this cycle are flown around
    const double d_amp;    // f_d,max
    const turn_limits d_lim;
    // Turns planned for the airframe (side test, arc acquisition, probe segments and
    // delta sized for the reversals): any turn limit.
    const bool d_plan_turns;
    coordinated_turn d_turn; // the heading model with rolls (d_model otherwise)
    double d_arc = 0.0, d_arc_last = 0.0; // heading flown in this acquisition
    double d_delta_max = 0.0;             // delta_max within the airframe's turns
    double d_acq_dir = 1.0;               // the acquisition turn's way (+1: left)
    bool d_side_known = false;            // the side test has decided it
    bool d_started = false, d_acquiring = true, d_hold = false, d_turning = false;
    double d_theta = 0.0, d_model = 0.0, d_last_cmd = 0.0, d_hold_heading = 0.0;
    double d_acq_start = 0.0, d_acq_origin = 0.0, d_delta = 0.0, d_err = 0.0;
    double d_sigma = 1.0, d_cfo = 0.0, d_cfo_time = 0.0, d_drift = 0.0, d_last_time = 0.0;
    std::vector<double> d_rounds; // start times of the kept acquisition rounds
    std::uint64_t d_last_slot = 0, d_updates = 0;
    int d_missing = 0, d_pos = 0;
    long d_cycle = 0, d_tag_cycle = -1;
    std::vector<double> d_plan;
    std::vector<doppler_sample> d_samples;
    std::vector<doppler_sample> d_side_samples; // the side test's, at the model's heading
};

} // namespace

std::unique_ptr<seeker> make_adaptive_seeker(const seeker_config& cfg)
{
    return std::make_unique<adaptive_seeker>(cfg);
}

} // namespace rfseek
} // namespace gr
