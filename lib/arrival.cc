/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * arrival: the overflight detector and the emitter locator (arrival.h, docs/seeker.md).
 */

#include "angle.h"
#include <gr-rfseek/arrival.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {

double median(std::vector<double> v)
{
    const std::size_t n = v.size();
    std::nth_element(v.begin(), v.begin() + n / 2, v.end());
    const double hi = v[n / 2];
    if (n % 2)
        return hi;
    return 0.5 * (hi + *std::max_element(v.begin(), v.begin() + n / 2));
}

//! Solve the n x n system a x = b in place (Gauss-Jordan, partial pivoting).
template <std::size_t N>
bool solve(std::array<std::array<double, N>, N> a, std::array<double, N>& b)
{
    for (std::size_t c = 0; c < N; ++c) {
        std::size_t p = c;
        for (std::size_t r = c + 1; r < N; ++r)
            if (std::abs(a[r][c]) > std::abs(a[p][c]))
                p = r;
        if (!(std::abs(a[p][c]) > 0.0))
            return false;
        std::swap(a[p], a[c]);
        std::swap(b[p], b[c]);
        for (std::size_t r = 0; r < N; ++r) {
            if (r == c)
                continue;
            const double f = a[r][c] / a[c][c];
            for (std::size_t k = c; k < N; ++k)
                a[r][k] -= f * a[c][k];
            b[r] -= f * b[c];
        }
    }
    for (std::size_t c = 0; c < N; ++c)
        b[c] /= a[c][c];
    return true;
}

} // namespace

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
    d_detected = false;
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
 * The CFO drift up to block b: least squares over the usable blocks of the last drift_s
 * (b included) of F = c + d t + p cos(psi) + q sin(psi), the far-field model (every path
 * from one bearing beta: p = f_d,max cos beta, q = f_d,max sin beta). Turns make p and q
 * identifiable; in steady flight they are collinear with c, and a small ridge keeps the
 * system solvable (the drift is then the plain trend). NaN with fewer than 10 blocks.
 */
double overflight_detector::drift_before(const block& b) const
{
    std::vector<const block*> w{ &b };
    for (std::size_t i = d_blocks.size(); i-- > 0;) {
        if (b.time_s - d_blocks[i].time_s > d_cfg.drift_s)
            break;
        w.push_back(&d_blocks[i]);
    }
    auto row = [&](const block* q, double r[4]) {
        r[0] = 1.0;
        r[1] = (q->time_s - b.time_s) / 60.0;
        r[2] = std::cos(q->heading_rad);
        r[3] = std::sin(q->heading_rad);
    };
    std::array<std::array<double, 4>, 4> a{};
    std::array<double, 4> y{};
    int used = 0;
    for (const block* q : w) {
        if (!q->usable)
            continue;
        double r[4];
        row(q, r);
        for (int i = 0; i < 4; ++i) {
            y[i] += r[i] * q->freq_hz;
            for (int k = 0; k < 4; ++k)
                a[i][k] += r[i] * r[k];
        }
        ++used;
    }
    // At least half of drift_s of usable blocks: a short history (the start of a
    // flight, its first manoeuvres) gives no trustworthy drift.
    const double block_s = d_cfg.block_slots * d_cfg.slot_period_s;
    if (used < std::max(10.0, 0.5 * d_cfg.drift_s / block_s))
        return NAN;
    for (int i = 2; i < 4; ++i)
        a[i][i] += 1e-3 * used;
    std::array<double, 4> x = y, e1{ 0.0, 1.0, 0.0, 0.0 };
    if (!solve(a, x) || !solve(a, e1))
        return NAN;
    double ss = 0.0;
    for (const block* q : w) {
        if (!q->usable)
            continue;
        double r[4];
        row(q, r);
        const double e = q->freq_hz - (x[0] + x[1] * r[1] + x[2] * r[2] + x[3] * r[3]);
        ss += e * e;
    }
    // Shrunk toward zero by two standard errors: an uncertain drift corrects nothing.
    const double se = std::sqrt(std::max(ss / std::max(used - 4, 1), 0.0) * e1[1]);
    const double d = x[1], mag = std::max(std::abs(d) - 2.0 * se, 0.0);
    return (d < 0.0 ? -mag : mag) / 60.0;
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
    b.drift = b.usable ? drift_before(b) : NAN;
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
        return;
    }
    const double a = d_cfg.max_doppler_hz;
    double lo = b.heading_lo, hi = b.heading_hi, pmax = b.power_db;
    double best = -std::numeric_limits<double>::infinity();
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
        best = std::max(best,
                        j.freq_hz - b.freq_hz - a * (1.0 - std::cos(dpsi)) +
                            j.drift * (b.time_s - j.time_s));
    }
    d_last_drop = std::isfinite(best) ? best : 0.0;
    d_hits = best >= d_cfg.swing * a ? d_hits + 1 : 0;
    if (d_hits >= d_cfg.confirm_blocks)
        d_detected = true;
}

// ---------------------------------------------------------------- emitter_locator

emitter_locator::emitter_locator(double wavelength_m, double search_radius_m)
    : d_lambda(wavelength_m), d_search(search_radius_m)
{
    if (!(wavelength_m > 0.0) || !std::isfinite(wavelength_m))
        throw std::invalid_argument("emitter_locator: wavelength_m must be > 0");
    if (!(search_radius_m > 0.0) || !std::isfinite(search_radius_m))
        throw std::invalid_argument("emitter_locator: search_radius_m must be > 0");
}

void emitter_locator::clear()
{
    d_t.clear();
    d_x.clear();
    d_y.clear();
    d_vx.clear();
    d_vy.clear();
    d_f.clear();
}

void emitter_locator::add(
    double time_s, double x_m, double y_m, double vx_mps, double vy_mps, double freq_hz)
{
    if (!(std::isfinite(time_s) && std::isfinite(x_m) && std::isfinite(y_m) &&
          std::isfinite(vx_mps) && std::isfinite(vy_mps) && std::isfinite(freq_hz)))
        return;
    d_t.push_back(time_s);
    d_x.push_back(x_m);
    d_y.push_back(y_m);
    d_vx.push_back(vx_mps);
    d_vy.push_back(vy_mps);
    d_f.push_back(freq_hz);
}

namespace {

// The nonlinear parameters: emitter (x, y) at t_f, wind (x, y), height.
using params = std::array<double, 5>;

struct problem {
    const std::vector<double>&t, &x, &y, &vx, &vy, &f;
    double lambda, tf;
    std::vector<char> use; // inliers
    std::size_t step = 1;  // decimation (the grid search)

    double doppler(const params& p, std::size_t k) const
    {
        const double dt = t[k] - tf;
        const double rx = p[0] - p[2] * dt - x[k];
        const double ry = p[1] - p[3] * dt - y[k];
        const double s = std::sqrt(rx * rx + ry * ry + p[4] * p[4]);
        return s > 0.0 ? ((vx[k] + p[2]) * rx + (vy[k] + p[3]) * ry) / (lambda * s) : 0.0;
    }

    // Residuals after the best c + d (t - tf) (variable projection); returns the sum of
    // squares over the inliers, writes every residual.
    double residuals(const params& p,
                     std::vector<double>& r,
                     double* c = nullptr,
                     double* d = nullptr) const
    {
        const std::size_t n = t.size();
        r.assign(n, 0.0);
        double s1 = 0, st = 0, stt = 0, sy = 0, sty = 0;
        for (std::size_t k = 0; k < n; k += step) {
            r[k] = f[k] - doppler(p, k);
            if (!use[k])
                continue;
            const double dt = t[k] - tf;
            s1 += 1;
            st += dt;
            stt += dt * dt;
            sy += r[k];
            sty += dt * r[k];
        }
        const double det = s1 * stt - st * st;
        const double cc =
            det > 1e-9 ? (stt * sy - st * sty) / det : sy / std::max(s1, 1.0);
        const double dd = det > 1e-9 ? (s1 * sty - st * sy) / det : 0.0;
        double ss = 0.0;
        for (std::size_t k = 0; k < n; k += step) {
            r[k] -= cc + dd * (t[k] - tf);
            if (use[k])
                ss += r[k] * r[k];
        }
        if (c)
            *c = cc;
        if (d)
            *d = dd;
        return ss;
    }
};

} // namespace

emitter_location emitter_locator::fit(double vehicle_x_m, double vehicle_y_m) const
{
    emitter_location out;
    const std::size_t n = d_t.size();
    if (n < 50)
        return out;
    problem pr{ d_t, d_x, d_y, d_vx, d_vy, d_f, d_lambda, d_t.back(), {}, 1 };
    pr.use.assign(n, 1);
    out.time_s = pr.tf;
    out.dr_x_m = vehicle_x_m;
    out.dr_y_m = vehicle_y_m;

    // Grid search (decimated, bounded cost) around the path's centroid, no wind.
    double cx = 0, cy = 0;
    for (std::size_t k = 0; k < n; ++k) {
        cx += d_x[k];
        cy += d_y[k];
    }
    cx /= n;
    cy /= n;
    pr.step = std::max<std::size_t>(1, n / 120);
    std::vector<double> r;
    params best{ cx, cy, 0.0, 0.0, 0.0 };
    double best_cost = std::numeric_limits<double>::infinity();
    const double spacing = 30.0;
    const int m = static_cast<int>(std::ceil(d_search / spacing));
    const double tau2 = 100.0; // (10 Hz)^2: a robust cost for the grid
    // Wind candidates: calm, and 3 and 6 m/s from 8 directions (a strong wind moves the
    // emitter by hundreds of metres in the air frame over an orbit: the fit must start
    // near it).
    std::vector<std::pair<double, double>> winds{ { 0.0, 0.0 } };
    for (double ws : { 3.0, 6.0 })
        for (int q = 0; q < 8; ++q)
            winds.emplace_back(ws * std::cos(q * M_PI / 4), ws * std::sin(q * M_PI / 4));
    for (const auto& wv : winds)
        for (double h : { 10.0, 100.0 })
            for (int i = -m; i <= m; ++i)
                for (int j = -m; j <= m; ++j) {
                    if (i * i + j * j > m * m)
                        continue;
                    const params p{
                        cx + i * spacing, cy + j * spacing, wv.first, wv.second, h
                    };
                    pr.residuals(p, r);
                    double cost = 0.0;
                    for (std::size_t k = 0; k < n; k += pr.step)
                        cost += std::min(r[k] * r[k], tau2);
                    if (cost < best_cost) {
                        best_cost = cost;
                        best = p;
                    }
                }
    pr.step = 1;

    // Levenberg-Marquardt on the projected residuals, two rounds of outlier rejection.
    const std::array<double, 5> eps{ 0.05, 0.05, 0.005, 0.005, 0.05 };
    params p = best;
    std::vector<double> rj;
    std::array<std::array<double, 5>, 5> jtj{};
    std::vector<std::array<double, 5>> jac(n);
    auto jacobian = [&](const params& at, const std::vector<double>& r0) {
        for (std::size_t q = 0; q < 5; ++q) {
            params pp = at;
            pp[q] += eps[q];
            pr.residuals(pp, rj);
            for (std::size_t k = 0; k < n; ++k)
                jac[k][q] = (rj[k] - r0[k]) / eps[q];
        }
        for (auto& row : jtj)
            row.fill(0.0);
        for (std::size_t k = 0; k < n; ++k)
            if (pr.use[k])
                for (std::size_t a = 0; a < 5; ++a)
                    for (std::size_t b = 0; b < 5; ++b)
                        jtj[a][b] += jac[k][a] * jac[k][b];
    };
    double cost = 0.0;
    for (int round = 0; round < 3; ++round) {
        double mu = 1e-3;
        cost = pr.residuals(p, r);
        for (int it = 0; it < 60; ++it) {
            jacobian(p, r);
            std::array<double, 5> g{};
            for (std::size_t k = 0; k < n; ++k)
                if (pr.use[k])
                    for (std::size_t a = 0; a < 5; ++a)
                        g[a] -= jac[k][a] * r[k];
            bool improved = false;
            for (int tries = 0; tries < 10 && !improved; ++tries) {
                auto a = jtj;
                for (std::size_t q = 0; q < 5; ++q)
                    a[q][q] += mu * (jtj[q][q] + 1e-9);
                std::array<double, 5> step = g;
                if (!solve(a, step)) {
                    mu *= 10;
                    continue;
                }
                params pn = p;
                for (std::size_t q = 0; q < 5; ++q)
                    pn[q] += step[q];
                std::vector<double> rn;
                const double cn = pr.residuals(pn, rn);
                if (cn < cost) {
                    const double gain = (cost - cn) / std::max(cost, 1e-12);
                    p = pn;
                    r.swap(rn);
                    cost = cn;
                    mu = std::max(mu / 3.0, 1e-9);
                    improved = true;
                    if (gain < 1e-9)
                        it = 1000;
                } else
                    mu *= 4.0;
            }
            if (!improved)
                break;
        }
        if (round == 2)
            break;
        // Robust sigma of the inliers; reject beyond 4 sigma (at least 1 Hz).
        std::vector<double> a;
        for (std::size_t k = 0; k < n; ++k)
            if (pr.use[k])
                a.push_back(std::abs(r[k]));
        const double sigma = std::max(1.4826 * median(a), 0.25);
        for (std::size_t k = 0; k < n; ++k)
            pr.use[k] = std::abs(r[k]) <= std::max(4.0 * sigma, 1.0);
    }

    // Covariance of (p_x, p_y) from the final Jacobian, inflated for correlated
    // residuals.
    double c0 = 0.0, d0 = 0.0;
    cost = pr.residuals(p, r, &c0, &d0);
    jacobian(p, r);
    int used = 0;
    double r1 = 0.0, r0 = 0.0, prev = 0.0;
    bool have_prev = false;
    for (std::size_t k = 0; k < n; ++k) {
        if (!pr.use[k])
            continue;
        ++used;
        r0 += r[k] * r[k];
        if (have_prev)
            r1 += prev * r[k];
        prev = r[k];
        have_prev = true;
    }
    if (used < 50)
        return out;
    // Correlated residuals (multipath along the path, gusts) carry less information than
    // their number says: inflate by the larger of the AR(1) factor and the variance
    // ratio of 1 s block means (B var(mean) / var, 1 for white residuals).
    const double rho = std::clamp(r0 > 0.0 ? r1 / r0 : 0.0, 0.0, 0.98);
    double inflation = (1.0 + rho) / (1.0 - rho);
    {
        const std::size_t B = 20;
        double sum = 0.0, bm2 = 0.0;
        std::size_t in_block = 0, blocks = 0;
        for (std::size_t k = 0; k < n; ++k) {
            if (!pr.use[k])
                continue;
            sum += r[k];
            if (++in_block == B) {
                bm2 += (sum / B) * (sum / B);
                sum = 0.0;
                in_block = 0;
                ++blocks;
            }
        }
        if (blocks >= 5 && r0 > 0.0)
            inflation = std::max(inflation, B * (bm2 / blocks) / (r0 / used));
    }
    const double s2 = cost / std::max(used - 7, 1);
    // Invert J^T J column by column (a tiny ridge keeps h = 0 invertible).
    double scale = 0.0;
    for (std::size_t q = 0; q < 5; ++q)
        scale = std::max(scale, jtj[q][q]);
    auto a = jtj;
    for (std::size_t q = 0; q < 5; ++q)
        a[q][q] += 1e-9 * scale + 1e-12;
    std::array<double, 5> e0{ 1, 0, 0, 0, 0 }, e1{ 0, 1, 0, 0, 0 };
    std::array<double, 5> e2{ 0, 0, 1, 0, 0 }, e3{ 0, 0, 0, 1, 0 };
    if (!solve(a, e0) || !solve(a, e1) || !solve(a, e2) || !solve(a, e3))
        return out;
    const double sxx = s2 * inflation * e0[0], syy = s2 * inflation * e1[1];
    const double sxy = s2 * inflation * 0.5 * (e0[1] + e1[0]);
    const double tr = 0.5 * (sxx + syy);
    const double disc = std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
    const double chi2_95 = 5.991464547107979; // 2 degrees of freedom
    out.major_m = std::sqrt(chi2_95 * std::max(tr + disc, 0.0));
    out.minor_m = std::sqrt(chi2_95 * std::max(tr - disc, 0.0));
    out.major_angle_rad = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
    out.east_m = p[0] - vehicle_x_m;
    out.north_m = p[1] - vehicle_y_m;
    out.wind_east_mps = p[2];
    out.wind_north_mps = p[3];
    out.wind_sigma_mps = std::sqrt(std::max(0.5 * s2 * inflation * (e2[2] + e3[3]), 0.0));
    out.altitude_m = std::abs(p[4]);
    out.cfo_hz = c0;
    out.rms_hz = std::sqrt(r0 / used);
    out.used = used;
    out.inflation = inflation;
    out.valid = std::isfinite(out.east_m) && std::isfinite(out.north_m) &&
                std::isfinite(out.major_m) && std::isfinite(out.minor_m);
    return out;
}

} // namespace rfseek
} // namespace gr
