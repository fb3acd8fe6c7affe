/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The overflight detector and the far-field Doppler amplitude (arrival.h,
 * docs/seeker.md "Arrival without truth").
 */

#include "angle.h"
#include "arrival_math.h"
#include <gr-rfseek/arrival.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {

//! True if the headings (rad) go all round: no gap of 120 deg or more between them.
bool goes_all_round(std::vector<double> h)
{
    if (h.empty())
        return false;
    for (double& a : h)
        a = wrap_remainder(a);
    std::sort(h.begin(), h.end());
    double gap = h.front() + 2.0 * M_PI - h.back();
    for (std::size_t i = 1; i < h.size(); ++i)
        gap = std::max(gap, h[i] - h[i - 1]);
    return gap < 2.0 * M_PI / 3.0;
}

/*
 * Least squares of the far-field model F = c + d u + p cos(psi) + q sin(psi), u = (t -
 * t_ref) / 60 s, over samples (t, psi, F) with use set; ridge * (samples used) is added
 * to the p and q diagonal (0: none). x = (c, d, p, q); a is the normal matrix (ridge
 * included), kept for standard errors.
 */
struct harmonic_fit {
    Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
    Eigen::Vector4d x = Eigen::Vector4d::Zero();
    double t_ref = 0.0;
    int used = 0;

    Eigen::Vector4d row(const std::array<double, 3>& q) const
    {
        return { 1.0, (q[0] - t_ref) / 60.0, std::cos(q[1]), std::sin(q[1]) };
    }
    double model(const std::array<double, 3>& q) const { return x.dot(row(q)); }
    bool solve(const std::vector<std::array<double, 3>>& s,
               const std::vector<char>& use,
               double t_reference,
               double ridge)
    {
        t_ref = t_reference;
        a.setZero();
        x.setZero();
        used = 0;
        for (std::size_t k = 0; k < s.size(); ++k) {
            if (!use[k])
                continue;
            const Eigen::Vector4d r = row(s[k]);
            a.noalias() += r * r.transpose();
            x += r * s[k][2];
            ++used;
        }
        a(2, 2) += ridge * used;
        a(3, 3) += ridge * used;
        return lu_solve(a, x);
    }
};
} // namespace

// ---------------------------------------------------------------- doppler_amplitude

void doppler_amplitude::add(double time_s, double heading_rad, double freq_hz)
{
    if (std::isfinite(time_s) && std::isfinite(heading_rad) && std::isfinite(freq_hz) &&
        d_m.size() < 20000)
        d_m.push_back({ time_s, heading_rad, freq_hz });
}

double doppler_amplitude::amplitude() const
{
    const std::size_t n = d_m.size();
    if (n < 8)
        return NAN;
    // The headings must go all round, as for the detector's amplitude: a part of a
    // turn leaves p and q tied to c.
    std::vector<double> h;
    for (const auto& q : d_m)
        h.push_back(q[1]);
    if (!goes_all_round(h))
        return NAN;
    const double t0 = d_m.front()[0];
    std::vector<char> use(n, 1);
    std::vector<double> res(n), in;
    double amp = NAN;
    for (int round = 0; round < 3; ++round) {
        harmonic_fit fit;
        if (!fit.solve(d_m, use, t0, 0.0))
            return NAN;
        amp = std::hypot(fit.x(2), fit.x(3));
        in.clear();
        for (std::size_t k = 0; k < n; ++k) {
            res[k] = std::abs(d_m[k][2] - fit.model(d_m[k]));
            if (use[k])
                in.push_back(res[k]);
        }
        const double lim = std::max(4.0 * 1.4826 * median(in), 5.0);
        for (std::size_t k = 0; k < n; ++k)
            use[k] = res[k] <= lim;
    }
    return amp;
}

// ---------------------------------------------------------------- overflight_detector

overflight_detector::overflight_detector(const overflight_config& cfg) : d_cfg(cfg)
{
    auto bad = [](const char* f, const char* range) {
        throw std::invalid_argument(std::string("overflight_config.") + f + ": must be " +
                                    range);
    };
    if (!(cfg.max_doppler_hz > 0.0) || !std::isfinite(cfg.max_doppler_hz))
        bad("max_doppler_hz", "> 0");
    if (!(cfg.slot_period_s > 0.0) || !std::isfinite(cfg.slot_period_s))
        bad("slot_period_s", "> 0");
    if (!(cfg.swing >= 0.5 && cfg.swing <= 2.0))
        bad("swing", "in [0.5, 2]");
    if (!(cfg.window_s > 0.0) || !std::isfinite(cfg.window_s))
        bad("window_s", "> 0");
    if (!(cfg.heading_band_rad > 0.0 && cfg.heading_band_rad <= M_PI))
        bad("heading_band_rad", "in (0, pi]");
    if (!(cfg.drift_s > 0.0) || !std::isfinite(cfg.drift_s))
        bad("drift_s", "> 0");
    if (!(cfg.power_rise_db >= 0.0) || !std::isfinite(cfg.power_rise_db))
        bad("power_rise_db", ">= 0");
    if (cfg.block_slots < 1 || cfg.block_slots > 100000)
        bad("block_slots", "in [1, 100000]");
    if (cfg.confirm_blocks < 1 || cfg.confirm_blocks > 1000)
        bad("confirm_blocks", "in [1, 1000]");
    if (!(cfg.encircle_amplitude >= 0.0 && cfg.encircle_amplitude <= 1.0))
        bad("encircle_amplitude", "in [0, 1] (0: off)");
    if (!(cfg.near_swing == 0.0 ||
          (cfg.near_swing >= 0.5 && cfg.near_swing <= cfg.swing)))
        bad("near_swing", "0 (off) or in [0.5, swing]");
    if (!(cfg.near_power_db >= 0.0 && cfg.near_power_db <= 100.0))
        bad("near_power_db", "in [0, 100] dB");
    if (std::isnan(cfg.min_snr_db))
        bad("min_snr_db", "a number");
    reset();
}

void overflight_detector::reset()
{
    d_f.clear();
    d_p.clear();
    d_h.clear();
    d_in_block = 0;
    d_blocks.clear();
    d_hits = 0;
    d_near_hits = 0;
    d_circle_hits = 0;
    d_detected = false;
    d_encircled = false;
    d_last_amplitude = NAN;
    d_detect_time = 0.0;
    d_last_drop = 0.0;
}

bool overflight_detector::update(double time_s,
                                 double freq_hz,
                                 double power_db,
                                 double snr_db,
                                 bool valid,
                                 double heading_rad)
{
    if (d_detected)
        return true;
    if (d_in_block == 0)
        d_block_start = time_s;
    if (valid && snr_db >= d_cfg.min_snr_db && std::isfinite(freq_hz) &&
        std::isfinite(power_db)) {
        d_f.push_back(freq_hz);
        d_p.push_back(power_db);
    }
    if (std::isfinite(heading_rad))
        d_h.push_back(heading_rad);
    if (++d_in_block >= d_cfg.block_slots) {
        close_block();
        if (d_detected)
            d_detect_time = time_s;
    }
    return d_detected;
}

/*
 * The far-field fit up to block b: least squares over the usable blocks of the last
 * drift_s (b included) of F = c + d t + p cos(psi) + q sin(psi), the far-field model
 * (every path from one bearing beta: p = f_d,max cos beta, q = f_d,max sin beta). Turns
 * make p and q identifiable; in steady flight they are collinear with c, and a small
 * ridge keeps the system solvable (the drift is then the plain trend). The drift is
 * shrunk toward zero by two standard errors; NaN with fewer than 10 blocks (or half of
 * drift_s). The amplitude hypot(p, q) is reported when the blocks' headings go all
 * round (no gap of 120 deg between them), else NaN.
 */
overflight_detector::far_field overflight_detector::fit_far_field(const block& b) const
{
    far_field out{ NAN, NAN };
    std::vector<std::array<double, 3>> s; // the usable blocks of the last drift_s
    for (std::size_t i = d_blocks.size() + 1; i-- > 0;) {
        const block& q = i == d_blocks.size() ? b : d_blocks[i];
        if (b.time_s - q.time_s > d_cfg.drift_s)
            break;
        if (q.usable)
            s.push_back({ q.time_s, q.heading_rad, q.freq_hz });
    }
    // At least half of drift_s of usable blocks: a short history (the start of a
    // flight, its first manoeuvres) gives no trustworthy drift.
    const double block_s = d_cfg.block_slots * d_cfg.slot_period_s;
    if (s.size() < std::max(10.0, 0.5 * d_cfg.drift_s / block_s))
        return out;
    harmonic_fit fit;
    const std::vector<char> use(s.size(), 1);
    Eigen::Vector4d e1 = Eigen::Vector4d::UnitY(); // becomes the drift's row of a^-1
    if (!fit.solve(s, use, b.time_s, 1e-3) || !lu_solve(fit.a, e1))
        return out;
    double ss = 0.0;
    for (const auto& q : s) {
        const double e = q[2] - fit.model(q);
        ss += e * e;
    }
    // Shrunk toward zero by two standard errors: an uncertain drift corrects nothing.
    const int used = fit.used;
    const double se = std::sqrt(std::max(ss / std::max(used - 4, 1), 0.0) * e1(1));
    const double d = fit.x(1), mag = std::max(std::abs(d) - 2.0 * se, 0.0);
    out.drift = (d < 0.0 ? -mag : mag) / 60.0;
    std::vector<double> headings;
    for (const auto& q : s)
        headings.push_back(q[1]);
    if (goes_all_round(headings))
        out.amplitude = std::hypot(fit.x(2), fit.x(3));
    return out;
}

void overflight_detector::close_block()
{
    block b{};
    b.time_s = d_block_start;
    b.usable = 2 * static_cast<int>(d_f.size()) >= d_cfg.block_slots && !d_h.empty();
    if (b.usable) {
        b.freq_hz = median(d_f);
        b.power_db = median(d_p);
        double s = 0.0, c = 0.0;
        for (double h : d_h) {
            s += std::sin(h);
            c += std::cos(h);
        }
        b.heading_rad = std::atan2(s, c);
        b.heading_lo = b.heading_hi = 0.0;
        for (double h : d_h) {
            const double dev = wrap_remainder(h - b.heading_rad);
            b.heading_lo = std::min(b.heading_lo, dev);
            b.heading_hi = std::max(b.heading_hi, dev);
        }
    }
    d_f.clear();
    d_p.clear();
    d_h.clear();
    d_in_block = 0;
    const far_field ff = b.usable ? fit_far_field(b) : far_field{ NAN, NAN };
    b.drift = ff.drift;
    d_blocks.push_back(b);
    // Keep the window (and one block more).
    const double keep =
        d_cfg.window_s + d_cfg.drift_s + d_cfg.block_slots * d_cfg.slot_period_s;
    std::size_t old = 0;
    while (old < d_blocks.size() && b.time_s - d_blocks[old].time_s > keep)
        ++old;
    d_blocks.erase(d_blocks.begin(), d_blocks.begin() + old);

    d_last_drop = 0.0;
    if (!b.usable) {
        d_hits = 0;
        d_circle_hits = 0;
        d_last_amplitude = NAN;
        return;
    }
    if (static_cast<int>(d_start_powers.size()) < START_BLOCKS &&
        std::isfinite(b.power_db)) {
        d_start_powers.push_back(b.power_db);
        if (static_cast<int>(d_start_powers.size()) == START_BLOCKS)
            d_start_power = median(d_start_powers); // fixed from here on
    }
    const double a = d_cfg.max_doppler_hz;
    // Near the emitter (the power well above the start's) a smaller drop suffices.
    const double near_level = d_cfg.near_swing > 0.0
                                  ? d_start_power + d_cfg.near_power_db
                                  : std::numeric_limits<double>::quiet_NaN();
    double lo = b.heading_lo, hi = b.heading_hi, pmax = b.power_db;
    double best = -std::numeric_limits<double>::infinity(), best_near = best;
    for (std::size_t i = d_blocks.size() - 1; i-- > 0;) {
        const block& j = d_blocks[i];
        if (b.time_s - j.time_s > d_cfg.window_s)
            break;
        if (!j.usable)
            continue;
        const double dpsi = wrap_remainder(j.heading_rad - b.heading_rad);
        lo = std::min(lo, dpsi + j.heading_lo);
        hi = std::max(hi, dpsi + j.heading_hi);
        if (hi - lo > d_cfg.heading_band_rad)
            break; // a turn: the frequency before it is not comparable
        pmax = std::max(pmax, j.power_db);
        if (pmax < std::min(j.power_db, b.power_db) + d_cfg.power_rise_db)
            continue;
        if (std::isnan(j.drift))
            continue; // the CFO drift before j is not known yet
        const double drop = j.freq_hz - b.freq_hz - a * (1.0 - std::cos(dpsi)) +
                            j.drift * (b.time_s - j.time_s);
        best = std::max(best, drop);
        if (pmax >= near_level) // false while the start's power is not known
            best_near = std::max(best_near, drop);
    }
    d_last_drop = std::isfinite(best) ? best : 0.0;
    d_hits = best >= d_cfg.swing * a ? d_hits + 1 : 0;
    d_near_hits =
        d_cfg.near_swing > 0.0 && best_near >= d_cfg.near_swing * a ? d_near_hits + 1 : 0;
    if (d_near_hits >= d_cfg.confirm_blocks)
        d_hits = std::max(d_hits, d_near_hits);
    // Encircling: headings all round while the far-field Doppler amplitude has
    // collapsed (the bearing to the emitter turns with the vehicle).
    d_last_amplitude = ff.amplitude;
    d_circle_hits =
        d_cfg.encircle_amplitude > 0.0 && ff.amplitude < d_cfg.encircle_amplitude * a
            ? d_circle_hits + 1
            : 0;
    if (d_hits >= d_cfg.confirm_blocks) {
        d_detected = true;
        d_encircled = false;
    } else if (d_circle_hits >= d_cfg.confirm_blocks) {
        d_detected = true;
        d_encircled = true;
    }
}

} // namespace rfseek
} // namespace gr
