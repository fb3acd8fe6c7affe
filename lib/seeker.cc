/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * seeker: the paper's two-stage seeker (Sec. III), with the resolutions of DESIGN.md.
 *
 * Timing: the measurement of slot j is taken at the heading commanded after slot j-1, so
 * each measurement is credited to the command that was in force when it was taken (its
 * "tag"). A Stage-2 step is a list of commands: S_plus settling slots then M slots at
 * theta + delta, S_minus settling slots then M slots at theta - delta. Settling slots
 * (the vehicle still turning at its finite rate) are flown but not averaged; with
 * instantaneous turns there are none. The update (eq. 5) is applied when the measurement
 * of the step's last command arrives, before the next command is issued.
 *
 * Eq. 4 (outlier rejection): by default compared with, and substituted by, the last
 * accepted value, with re-lock after relock_count consecutive rejected values that agree
 * with each other (DESIGN.md item 5); literal_eq4 keeps the printed form.
 */

#include <gr-rfseek/rng.h>
#include <gr-rfseek/scenario.h>
#include <gr-rfseek/seeker.h>
#include <gr-rfseek/world.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {

[[noreturn]] void bad(const std::string& field, double v, const std::string& range)
{
    throw std::invalid_argument("seeker_config." + field + " = " + std::to_string(v) +
                                ": must be " + range);
}

class outlier_filter
{
public:
    outlier_filter(double threshold, bool literal, int relock)
        : d_thr(threshold), d_literal(literal), d_relock(relock)
    {
    }

    // Returns the filtered value; *accepted tells whether f itself was let through.
    double push(double f, bool* accepted)
    {
        if (!d_have) {
            d_have = true;
            d_last = d_prev_raw = f;
            *accepted = true;
            return f;
        }
        if (d_literal) {
            const double ref = d_prev_raw;
            d_prev_raw = f;
            *accepted = std::abs(f - ref) < d_thr;
            return *accepted ? f : ref;
        }
        if (std::abs(f - d_last) < d_thr) {
            d_last = f;
            d_rejected.clear();
            *accepted = true;
            return f;
        }
        d_rejected.push_back(f);
        if (static_cast<int>(d_rejected.size()) > d_relock)
            d_rejected.erase(d_rejected.begin());
        if (static_cast<int>(d_rejected.size()) >= d_relock) {
            const auto mm = std::minmax_element(d_rejected.begin(), d_rejected.end());
            if (*mm.second - *mm.first < d_thr) { // they agree: the old value was wrong
                d_last = f;
                d_rejected.clear();
                *accepted = true;
                return f;
            }
        }
        *accepted = false;
        return d_last;
    }

private:
    double d_thr;
    bool d_literal;
    int d_relock;
    bool d_have = false;
    double d_last = 0.0, d_prev_raw = 0.0;
    std::vector<double> d_rejected;
};

enum class phase { none, circle, plus, minus };

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
          d_filter(
              cfg.effective_outlier_threshold_hz(), cfg.literal_eq4, cfg.relock_count),
          d_circle(cfg.strategy == "paper")
    {
        rng g(cfg.seed, 11);
        d_sense = g.uniform() < 0.5 ? 1.0 : -1.0;
        const double step = cfg.speed_mps * cfg.slot_period_s / cfg.circle_radius_m;
        d_circle_step = step;
        d_circle_cmds = std::max(1L, std::lround(2.0 * M_PI / step));
    }

    const seeker_config& config() const override { return d_cfg; }
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
                // stale, start a new one.
                start_step();
                d_prev = cmd_tag{};
            }
        }
        d_last_slot = m.slot;

        double f = 0.0;
        if (valid) {
            f = d_filter.push(m.freq_hz, &c.accepted);
            c.filtered_freq_hz = f;
        }

        // Holding course after a run of missing or invalid measurements.
        d_missing = valid ? 0 : d_missing + 1;
        if (!d_hold && d_missing >= d_cfg.hold_after_missing) {
            d_hold = true;
            d_hold_heading = d_stage == 2 ? d_theta : d_last_cmd;
        }
        if (d_hold) {
            if (!valid)
                return issue(c, d_hold_heading, cmd_tag{}, true);
            d_hold = false; // measurements are back: resume
            if (d_stage == 2)
                start_step();
            d_prev = cmd_tag{};
        }

        // Credit this measurement to the command in force when it was taken.
        if (valid) {
            if (d_prev.ph == phase::circle) {
                d_samples_f.push_back(f);
                d_samples_h.push_back(d_have_heading ? d_heading : d_last_cmd);
            } else if ((d_prev.ph == phase::plus || d_prev.ph == phase::minus) &&
                       !d_prev.settle && d_prev.step == d_step) {
                (d_prev.ph == phase::plus ? d_sum_plus : d_sum_minus) += f;
                ++(d_prev.ph == phase::plus ? d_n_plus : d_n_minus);
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

    int settle_slots(double turn) const
    {
        if (d_cfg.turn_rate_rad_per_s <= 0.0)
            return 0;
        return static_cast<int>(std::ceil(
            std::abs(turn) / (d_cfg.turn_rate_rad_per_s * d_cfg.slot_period_s) - 1e-9));
    }

    void start_step()
    {
        ++d_step;
        d_pos = 0;
        d_sum_plus = d_sum_minus = 0.0;
        d_n_plus = d_n_minus = 0;
        d_settle_plus = settle_slots(world::wrap(d_theta + d_cfg.delta_rad - d_last_cmd));
        d_settle_minus = settle_slots(2.0 * d_cfg.delta_rad);
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
        const double h =
            d_theta + (tag.ph == phase::plus ? d_cfg.delta_rad : -d_cfg.delta_rad);
        return issue(c, h, tag, false);
    }

    // Stage 1: the heading of the maximum of the (outlier-rejected, moving-averaged)
    // frequency around the circle (eq. 4, then theta_0 = heading at argmax). The moving
    // average is centred and circular: the circle is closed, and a trailing average would
    // lag the heading by half its length.
    void decide_initial_heading()
    {
        const int n = static_cast<int>(d_samples_f.size());
        double theta0 = d_last_cmd;
        if (n > 0) {
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
        start_step();
    }

    // Stage 2, eq. 5 in Hz: theta += (mean f+ - mean f-) delta / f_d,max.
    bool apply_eq5()
    {
        const int need = std::max(1, d_cfg.m_slots / 2);
        if (d_n_plus < need || d_n_minus < need)
            return false; // too few measurements in a half: keep theta
        const double diff = d_sum_plus / d_n_plus - d_sum_minus / d_n_minus;
        d_theta = world::wrap(d_theta + diff * d_cfg.delta_rad / d_cfg.max_doppler_hz());
        ++d_updates;
        return true;
    }

    seeker_config d_cfg;
    outlier_filter d_filter;
    const bool d_circle;
    double d_sense = 1.0, d_circle_step = 0.0;
    long d_circle_cmds = 0, d_circle_next = 0;
    double d_circle_base = 0.0;
    std::vector<double> d_samples_f, d_samples_h;

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
    int d_n_plus = 0, d_n_minus = 0;
    std::uint64_t d_updates = 0;
};

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
        if (d_cfg.turn_rate_rad_per_s > 0.0)
            d_settle = static_cast<int>(
                std::ceil(std::abs(world::wrap(h - d_heading)) /
                          (d_cfg.turn_rate_rad_per_s * d_cfg.slot_period_s)));
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

double seeker_config::max_doppler_hz() const
{
    return speed_mps * carrier_hz / SPEED_OF_LIGHT;
}

double seeker_config::effective_outlier_threshold_hz() const
{
    return outlier_threshold_hz > 0.0 ? outlier_threshold_hz : 2.0 * max_doppler_hz();
}

void seeker_config::validate() const
{
    const auto names = seeker::strategies();
    if (std::find(names.begin(), names.end(), strategy) == names.end()) {
        std::string all;
        for (const auto& s : names)
            all += (all.empty() ? "" : ", ") + s;
        throw std::invalid_argument("seeker_config.strategy = '" + strategy +
                                    "': must be one of " + all);
    }
    if (!(speed_mps > 0.0) || !std::isfinite(speed_mps))
        bad("speed_mps", speed_mps, "> 0");
    if (!(carrier_hz > 0.0) || !std::isfinite(carrier_hz))
        bad("carrier_hz", carrier_hz, "> 0");
    if (!(slot_period_s > 0.0) || !std::isfinite(slot_period_s))
        bad("slot_period_s", slot_period_s, "> 0");
    if (!(delta_rad > 0.0 && delta_rad < M_PI / 2))
        bad("delta_rad", delta_rad, "in (0, pi/2)");
    if (m_slots < 1 || m_slots > 100000)
        bad("m_slots", m_slots, "in [1, 100000]");
    if (!(circle_radius_m > 0.0) || !std::isfinite(circle_radius_m))
        bad("circle_radius_m", circle_radius_m, "> 0");
    if (circle_radius_m < speed_mps * slot_period_s / M_PI)
        bad("circle_radius_m",
            circle_radius_m,
            ">= v T_slot / pi (at least 2 slots per turn)");
    if (moving_average_len < 1 || moving_average_len > 100000)
        bad("moving_average_len", moving_average_len, "in [1, 100000]");
    if (!(outlier_threshold_hz >= 0.0) || !std::isfinite(outlier_threshold_hz))
        bad("outlier_threshold_hz", outlier_threshold_hz, ">= 0 (0 = 2 f_d,max)");
    if (relock_count < 1 || relock_count > 1000)
        bad("relock_count", relock_count, "in [1, 1000]");
    if (!(turn_rate_rad_per_s >= 0.0) || !std::isfinite(turn_rate_rad_per_s))
        bad("turn_rate_rad_per_s", turn_rate_rad_per_s, ">= 0 (0 = instantaneous)");
    if (hold_after_missing < 1)
        bad("hold_after_missing", hold_after_missing, ">= 1");
    if (rss_run_slots < 4 || rss_run_slots > 100000)
        bad("rss_run_slots", rss_run_slots, "in [4, 100000]");
    if (!(rss_good_ratio > 0.0 && rss_good_ratio <= 1.0))
        bad("rss_good_ratio", rss_good_ratio, "in (0, 1]");
    if (!(rss_reverse_db > 0.0) || !std::isfinite(rss_reverse_db))
        bad("rss_reverse_db", rss_reverse_db, "> 0");
    if (rss_min_runs < 2 || rss_min_runs > 100000)
        bad("rss_min_runs", rss_min_runs, "in [2, 100000]");
    if (initial_heading_rad && !std::isfinite(*initial_heading_rad))
        bad("initial_heading_rad", *initial_heading_rad, "finite");
}

std::vector<std::string> seeker_config::keys()
{
    return { "strategy",
             "speed_mps",
             "carrier_hz",
             "slot_period_s",
             "delta_rad",
             "delta_deg",
             "m_slots",
             "circle_radius_m",
             "moving_average_len",
             "outlier_threshold_hz",
             "literal_eq4",
             "relock_count",
             "turn_rate_rad_per_s",
             "hold_after_missing",
             "initial_heading_rad",
             "seed",
             "rss_run_slots",
             "rss_good_ratio",
             "rss_reverse_db",
             "rss_min_runs" };
}

void seeker_config::set(const std::string& key, const std::string& value)
{
    auto number = [&]() {
        char* end = nullptr;
        const double v = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0')
            throw std::invalid_argument("seeker_config." + key + ": cannot parse '" +
                                        value + "' as a number");
        return v;
    };
    auto integer = [&]() {
        const double v = number();
        if (v != std::floor(v) || std::abs(v) > 2e9)
            throw std::invalid_argument("seeker_config." + key + ": '" + value +
                                        "' is not an integer");
        return static_cast<int>(v);
    };
    if (key == "strategy")
        strategy = value;
    else if (key == "speed_mps")
        speed_mps = number();
    else if (key == "carrier_hz")
        carrier_hz = number();
    else if (key == "slot_period_s")
        slot_period_s = number();
    else if (key == "delta_rad")
        delta_rad = number();
    else if (key == "delta_deg")
        delta_rad = number() * M_PI / 180.0;
    else if (key == "m_slots")
        m_slots = integer();
    else if (key == "circle_radius_m")
        circle_radius_m = number();
    else if (key == "moving_average_len")
        moving_average_len = integer();
    else if (key == "outlier_threshold_hz")
        outlier_threshold_hz = number();
    else if (key == "literal_eq4")
        literal_eq4 = value == "true" || value == "1" || value == "True";
    else if (key == "relock_count")
        relock_count = integer();
    else if (key == "turn_rate_rad_per_s")
        turn_rate_rad_per_s = number();
    else if (key == "hold_after_missing")
        hold_after_missing = integer();
    else if (key == "initial_heading_rad") {
        if (value == "none" || value == "None" || value.empty())
            initial_heading_rad.reset();
        else
            initial_heading_rad = number();
    } else if (key == "seed")
        seed = static_cast<std::uint64_t>(std::strtoull(value.c_str(), nullptr, 10));
    else if (key == "rss_run_slots")
        rss_run_slots = integer();
    else if (key == "rss_good_ratio")
        rss_good_ratio = number();
    else if (key == "rss_reverse_db")
        rss_reverse_db = number();
    else if (key == "rss_min_runs")
        rss_min_runs = integer();
    else
        throw std::invalid_argument("seeker_config: unknown parameter '" + key + "'");
}

std::vector<std::string> seeker::strategies()
{
    return { "paper", "paper_no_circle", "rss_baseline" };
}

std::unique_ptr<seeker> seeker::make(const seeker_config& cfg)
{
    cfg.validate();
    if (cfg.strategy == "rss_baseline")
        return std::make_unique<rss_seeker>(cfg);
    return std::make_unique<two_stage_seeker>(cfg);
}

} // namespace rfseek
} // namespace gr
