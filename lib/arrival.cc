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
#include <memory>
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

//! Solve the n x n system a X = b in place (Gauss-Jordan, partial pivoting) for the k
//! columns of b (n x k, row-major; k = 1: a vector of n); a is row-major. False if a is
//! singular.
bool solve_dense(std::vector<double>& a, std::vector<double>& b, std::size_t k = 1)
{
    const std::size_t n = b.size() / k;
    for (std::size_t c = 0; c < n; ++c) {
        std::size_t p = c;
        for (std::size_t r = c + 1; r < n; ++r)
            if (std::abs(a[r * n + c]) > std::abs(a[p * n + c]))
                p = r;
        if (!(std::abs(a[p * n + c]) > 0.0))
            return false;
        if (p != c) {
            std::swap_ranges(
                a.begin() + p * n, a.begin() + (p + 1) * n, a.begin() + c * n);
            std::swap_ranges(
                b.begin() + p * k, b.begin() + (p + 1) * k, b.begin() + c * k);
        }
        for (std::size_t r = 0; r < n; ++r) {
            if (r == c)
                continue;
            const double f = a[r * n + c] / a[c * n + c];
            for (std::size_t q = c; q < n; ++q)
                a[r * n + q] -= f * a[c * n + q];
            for (std::size_t j = 0; j < k; ++j)
                b[r * k + j] -= f * b[c * k + j];
        }
    }
    for (std::size_t c = 0; c < n; ++c)
        for (std::size_t j = 0; j < k; ++j)
            b[c * k + j] /= a[c * n + c];
    return true;
}

//! N^-1 B for the k columns of B (m x k, row-major, overwritten), N (m x m) with a tiny
//! ridge (1e-9 x its largest diagonal) that keeps a zero height (no height prior)
//! invertible. False if singular.
bool solve_ridged(std::vector<double> N,
                  std::size_t m,
                  std::vector<double>& B,
                  std::size_t k)
{
    double scale = 0.0;
    for (std::size_t q = 0; q < m; ++q)
        scale = std::max(scale, N[q * m + q]);
    for (std::size_t q = 0; q < m; ++q)
        N[q * m + q] += 1e-9 * scale + 1e-12;
    return solve_dense(N, B, k);
}

//! solve_dense for small fixed-size systems.
template <std::size_t N>
bool solve(const std::array<std::array<double, N>, N>& a, std::array<double, N>& b)
{
    std::vector<double> m(N * N), x(b.begin(), b.end());
    for (std::size_t r = 0; r < N; ++r)
        std::copy(a[r].begin(), a[r].end(), m.begin() + r * N);
    if (!solve_dense(m, x))
        return false;
    std::copy(x.begin(), x.end(), b.begin());
    return true;
}

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
    std::array<std::array<double, 4>, 4> a{};
    std::array<double, 4> x{};
    double t_ref = 0.0;
    int used = 0;

    void row(const std::array<double, 3>& q, double r[4]) const
    {
        r[0] = 1.0;
        r[1] = (q[0] - t_ref) / 60.0;
        r[2] = std::cos(q[1]);
        r[3] = std::sin(q[1]);
    }
    double model(const std::array<double, 3>& q) const
    {
        double r[4];
        row(q, r);
        return x[0] + x[1] * r[1] + x[2] * r[2] + x[3] * r[3];
    }
    bool solve(const std::vector<std::array<double, 3>>& s,
               const std::vector<char>& use,
               double t_reference,
               double ridge)
    {
        t_ref = t_reference;
        a = {};
        std::array<double, 4> y{};
        used = 0;
        for (std::size_t k = 0; k < s.size(); ++k) {
            if (!use[k])
                continue;
            double r[4];
            row(s[k], r);
            for (int i = 0; i < 4; ++i) {
                y[i] += r[i] * s[k][2];
                for (int j = 0; j < 4; ++j)
                    a[i][j] += r[i] * r[j];
            }
            ++used;
        }
        for (int i = 2; i < 4; ++i)
            a[i][i] += ridge * used;
        x = y;
        return rfseek::solve(a, x);
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
        amp = std::hypot(fit.x[2], fit.x[3]);
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
    std::array<double, 4> e1{ 0.0, 1.0, 0.0, 0.0 };
    if (!fit.solve(s, use, b.time_s, 1e-3) || !solve(fit.a, e1))
        return out;
    double ss = 0.0;
    for (const auto& q : s) {
        const double e = q[2] - fit.model(q);
        ss += e * e;
    }
    // Shrunk toward zero by two standard errors: an uncertain drift corrects nothing.
    const int used = fit.used;
    const double se = std::sqrt(std::max(ss / std::max(used - 4, 1), 0.0) * e1[1]);
    const double d = fit.x[1], mag = std::max(std::abs(d) - 2.0 * se, 0.0);
    out.drift = (d < 0.0 ? -mag : mag) / 60.0;
    std::vector<double> headings;
    for (const auto& q : s)
        headings.push_back(q[1]);
    if (goes_all_round(headings))
        out.amplitude = std::hypot(fit.x[2], fit.x[3]);
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

// ---------------------------------------------------------------- emitter_locator

emitter_locator::emitter_locator(double wavelength_m,
                                 double search_radius_m,
                                 double gust_mps,
                                 double gust_tau_s,
                                 double altitude_m,
                                 double altitude_sigma_m)
    : d_lambda(wavelength_m),
      d_search(search_radius_m),
      d_gust(gust_mps),
      d_gust_tau(gust_tau_s),
      d_alt(altitude_m),
      d_alt_sigma(altitude_sigma_m)
{
    if (!(altitude_sigma_m >= 0.0 && altitude_sigma_m <= 1e4))
        throw std::invalid_argument(
            "emitter_locator: altitude_sigma_m must be in [0, 1e4] (0: no prior)");
    if (altitude_sigma_m > 0.0 && !(altitude_m >= 0.0 && altitude_m <= 1e4))
        throw std::invalid_argument(
            "emitter_locator: altitude_m must be in [0, 1e4] with a height prior");
    if (!(gust_mps >= 0.0 && gust_mps <= 50.0))
        throw std::invalid_argument("emitter_locator: gust_mps must be in [0, 50]");
    if (!(gust_tau_s >= 0.1 && gust_tau_s <= 3600.0))
        throw std::invalid_argument("emitter_locator: gust_tau_s must be in [0.1, 3600]");
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

/*
 * The location model with gusts: the wind is w + g(t), g piecewise linear between knots
 * every min(tau, 5 s) (at most 41 knots) with a first-order Gauss-Markov prior (std
 * sigma_g per axis, correlation time tau; sigma_g 0: no gust states), so
 *   r_k = p - w (t_k - t_f) + integral_{t_k}^{t_f} g - q_k,
 *   f_k = c + d (t_k - t_f) + (v_k + w + g(t_k)) . r_k / (lambda |(r_k, h)|),
 * with priors on the mean wind (0 +- 15 m/s per axis) and the height (h0 +- sigma_h,
 * sigma_h 0: none). run() finds the maximum a posteriori (p, w, h, g) by Gauss-Newton
 * with Levenberg damping and an analytic Jacobian, c and d projected out (variable
 * projection), the priors weighted by the measurement noise variance s2; build() gives
 * the Gauss-Newton matrix J^T J + s2 E^T E whose inverse times s2 is the covariance.
 */
struct gust_fit {
    const problem& pr;
    double sigma_g, tau;
    double h0, sigma_h;                        // height prior (sigma_h 0: none)
    static constexpr double wind_sigma = 15.0; // mean wind prior, m/s per axis
    std::size_t K = 0, m = 0;
    double spacing = 0.0;
    std::vector<std::size_t> j0; // knot below t_k
    std::vector<double> u;       // position between knots j0, j0 + 1
    std::vector<double> B;       // n x K: integral of the hat functions from t_k to t_f

    gust_fit(const problem& p, double sg, double tg, double h, double sh)
        : pr(p), sigma_g(sg), tau(tg), h0(h), sigma_h(sh)
    {
        const std::size_t n = pr.t.size();
        const double t0 = pr.t.front();
        // Knots every min(tau, 5 s), at most 41 of them (a bounded cost however long
        // the loiter).
        spacing = std::max({ std::min(0.5 * tau, 5.0), (pr.tf - t0) / 40.0, 1e-3 });
        K = sigma_g > 0.0
                ? std::max<std::size_t>(
                      2, static_cast<std::size_t>(std::ceil((pr.tf - t0) / spacing)) + 1)
                : 0;
        m = 5 + 2 * K;
        if (K == 0)
            return;
        j0.resize(n);
        u.resize(n);
        for (std::size_t k = 0; k < n; ++k) {
            const double x = std::max(0.0, (pr.t[k] - t0) / spacing);
            const std::size_t j = std::min(static_cast<std::size_t>(x), K - 2);
            j0[k] = j;
            u[k] = std::clamp(x - j, 0.0, 1.0);
        }
        // B_kj = F_j(t_f) - F_j(t_k), F_j the integral of knot j's hat function
        // max(0, 1 - |t - tau_j| / spacing) from -infinity (exact across any gap).
        auto F = [&](std::size_t j, double t) {
            const double x = (t - (t0 + j * spacing)) / spacing;
            if (x <= -1.0)
                return 0.0;
            if (x <= 0.0)
                return 0.5 * spacing * (x + 1.0) * (x + 1.0);
            if (x <= 1.0)
                return spacing * (1.0 - 0.5 * (1.0 - x) * (1.0 - x));
            return spacing;
        };
        B.assign(n * K, 0.0);
        for (std::size_t k = 0; k < n; ++k)
            for (std::size_t j = 0; j < K; ++j)
                B[k * K + j] = F(j, pr.tf) - F(j, pr.t[k]);
    }

    // The model D_k and, if J, its gradient (m entries) at theta.
    double model(const std::vector<double>& th, std::size_t k, double* J) const
    {
        const double* gx = th.data() + 5;
        const double* gy = gx + K;
        const double* b = K ? B.data() + k * K : nullptr;
        double Gx = 0.0, Gy = 0.0;
        for (std::size_t j = 0; j < K; ++j) {
            Gx += b[j] * gx[j];
            Gy += b[j] * gy[j];
        }
        const std::size_t j = K ? j0[k] : 0;
        const double gxk = K ? (1.0 - u[k]) * gx[j] + u[k] * gx[j + 1] : 0.0;
        const double gyk = K ? (1.0 - u[k]) * gy[j] + u[k] * gy[j + 1] : 0.0;
        const double dt = pr.t[k] - pr.tf;
        const double rx = th[0] - th[2] * dt + Gx - pr.x[k];
        const double ry = th[1] - th[3] * dt + Gy - pr.y[k];
        const double h = th[4];
        const double s = std::sqrt(rx * rx + ry * ry + h * h);
        if (!(s > 0.0)) {
            if (J)
                std::fill(J, J + m, 0.0);
            return 0.0;
        }
        const double vx = pr.vx[k] + th[2] + gxk, vy = pr.vy[k] + th[3] + gyk;
        const double num = vx * rx + vy * ry;
        const double ls = pr.lambda * s;
        if (J) {
            const double s2 = s * s;
            const double drx = (vx - num * rx / s2) / ls, dry = (vy - num * ry / s2) / ls;
            const double dvx = rx / ls, dvy = ry / ls;
            J[0] = drx;
            J[1] = dry;
            J[2] = -dt * drx + dvx;
            J[3] = -dt * dry + dvy;
            J[4] = -num * h / (ls * s2);
            for (std::size_t q = 0; q < K; ++q) {
                J[5 + q] = b[q] * drx;
                J[5 + K + q] = b[q] * dry;
            }
            if (K) {
                J[5 + j] += (1.0 - u[k]) * dvx;
                J[5 + j + 1] += u[k] * dvx;
                J[5 + K + j] += (1.0 - u[k]) * dvy;
                J[5 + K + j + 1] += u[k] * dvy;
            }
        }
        return num / ls;
    }

    // The priors at th, each weighted by s2: the gusts' (Gauss-Markov: e_0 = g_0 /
    // sigma_g, e_j = (g_j - a g_{j-1}) / (sigma_g sqrt(1 - a^2)), a = exp(-spacing /
    // tau), per axis), the mean wind's (0 +- wind_sigma per axis: keeps a far-field
    // fit from running off to kilometres and tens of m/s) and the height's (h0 +-
    // sigma_h). Returns s2 |e|^2; with N and g, adds s2 E^T E to N (upper triangle)
    // and -s2 E^T e to g.
    double priors(const std::vector<double>& th,
                  double s2,
                  std::vector<double>* N = nullptr,
                  std::vector<double>* g = nullptr) const
    {
        double cost = 0.0;
        // One whitened residual e = c0 th[q0] + c1 th[q1] - mean (q1 unused if c1 0).
        auto add =
            [&](std::size_t q0, double c0, std::size_t q1, double c1, double mean) {
                const double e = c0 * th[q0] + c1 * th[q1] - mean;
                cost += s2 * e * e;
                if (!N)
                    return;
                (*N)[q0 * m + q0] += s2 * c0 * c0;
                (*g)[q0] -= s2 * c0 * e;
                if (c1 != 0.0) {
                    (*N)[q1 * m + q1] += s2 * c1 * c1;
                    (*N)[std::min(q0, q1) * m + std::max(q0, q1)] += s2 * c0 * c1;
                    (*g)[q1] -= s2 * c1 * e;
                }
            };
        if (K) {
            const double a = std::exp(-spacing / tau);
            const double sd = sigma_g * std::sqrt(1.0 - a * a);
            for (std::size_t ax = 0; ax < 2; ++ax)
                for (std::size_t j = 0; j < K; ++j) {
                    const std::size_t q = 5 + ax * K + j;
                    if (j == 0)
                        add(q, 1.0 / sigma_g, q, 0.0, 0.0);
                    else
                        add(q, 1.0 / sd, q - 1, -a / sd, 0.0);
                }
        }
        add(2, 1.0 / wind_sigma, 2, 0.0, 0.0);
        add(3, 1.0 / wind_sigma, 3, 0.0, 0.0);
        if (sigma_h > 0.0)
            add(4, 1.0 / sigma_h, 4, 0.0, h0 / sigma_h);
        return cost;
    }

    // Projected residuals (c + d (t - t_f) over the inliers removed) and, if Jt, the
    // projected Jacobian of the model (n x m, inlier rows only filled). Returns the
    // data part of the cost.
    double residuals(const std::vector<double>& th,
                     std::vector<double>& r,
                     std::vector<double>* Jt = nullptr,
                     double* c_out = nullptr) const
    {
        const std::size_t n = pr.t.size();
        r.assign(n, 0.0);
        if (Jt)
            Jt->assign(n * m, 0.0);
        double s1 = 0, st = 0, stt = 0;
        for (std::size_t k = 0; k < n; ++k) {
            r[k] = pr.f[k] - model(th, k, Jt && pr.use[k] ? Jt->data() + k * m : nullptr);
            if (!pr.use[k])
                continue;
            const double dt = pr.t[k] - pr.tf;
            s1 += 1;
            st += dt;
            stt += dt * dt;
        }
        const double det = s1 * stt - st * st;
        // Removes the inliers' best line a + b dt from column v (stride, offset).
        auto project = [&](double* v, std::size_t stride) -> double {
            double sy = 0, sty = 0;
            for (std::size_t k = 0; k < n; ++k)
                if (pr.use[k]) {
                    sy += v[k * stride];
                    sty += (pr.t[k] - pr.tf) * v[k * stride];
                }
            const double cc =
                det > 1e-9 ? (stt * sy - st * sty) / det : sy / std::max(s1, 1.0);
            const double dd = det > 1e-9 ? (s1 * sty - st * sy) / det : 0.0;
            for (std::size_t k = 0; k < n; ++k)
                v[k * stride] -= cc + dd * (pr.t[k] - pr.tf);
            return cc;
        };
        const double cc = project(r.data(), 1);
        if (c_out)
            *c_out = cc;
        if (Jt)
            for (std::size_t q = 0; q < m; ++q)
                project(Jt->data() + q, m);
        double ss = 0.0;
        for (std::size_t k = 0; k < n; ++k)
            if (pr.use[k])
                ss += r[k] * r[k];
        return ss;
    }

    // The Gauss-Newton matrix N = J^T J + s2 E^T E (m x m), the step's right-hand side
    // g = J^T r - s2 E^T e and the residuals r at th; returns the cost.
    double build(const std::vector<double>& th,
                 double s2,
                 std::vector<double>& N,
                 std::vector<double>& g,
                 std::vector<double>& r) const
    {
        const std::size_t n = pr.t.size();
        std::vector<double> Jt, e;
        double cost = residuals(th, r, &Jt);
        N.assign(m * m, 0.0);
        g.assign(m, 0.0);
        for (std::size_t k = 0; k < n; ++k) {
            if (!pr.use[k])
                continue;
            const double* row = Jt.data() + k * m;
            for (std::size_t p = 0; p < m; ++p) {
                if (row[p] == 0.0)
                    continue;
                g[p] += row[p] * r[k];
                double* Np = N.data() + p * m;
                for (std::size_t q = p; q < m; ++q)
                    Np[q] += row[p] * row[q];
            }
        }
        cost += priors(th, s2, &N, &g);
        for (std::size_t p = 0; p < m; ++p)
            for (std::size_t q = 0; q < p; ++q)
                N[p * m + q] = N[q * m + p];
        return cost;
    }

    // The number of parameters the data fit at th, trace((J^T J + s2 E^T E)^-1 J^T J):
    // m for free parameters, less as the priors hold them (gust states the prior
    // keeps near zero count for little). The residual variance is SS / (n - this - 2).
    double effective_params(const std::vector<double>& th, double s2) const
    {
        std::vector<double> N0, N, g, r;
        build(th, 0.0, N0, g, r); // J^T J
        build(th, s2, N, g, r);
        if (!solve_ridged(N, m, N0, m)) // N0 becomes N^-1 J^T J
            return static_cast<double>(m);
        double tr = 0.0;
        for (std::size_t q = 0; q < m; ++q)
            tr += N0[q * m + q];
        return std::clamp(tr, 0.0, static_cast<double>(m));
    }

    // Minimises the data cost + s2 |e|^2 from th (Levenberg-Marquardt).
    void run(std::vector<double>& th, double s2, int max_it) const
    {
        std::vector<double> N, g, r, rn;
        double mu = 1e-3;
        for (int it = 0; it < max_it; ++it) {
            const double cost = build(th, s2, N, g, r);
            bool improved = false;
            for (int tries = 0; tries < 8 && !improved; ++tries) {
                std::vector<double> A = N, step = g;
                for (std::size_t q = 0; q < m; ++q)
                    A[q * m + q] += mu * (N[q * m + q] + 1e-9);
                if (!solve_dense(A, step)) {
                    mu *= 10.0;
                    continue;
                }
                std::vector<double> tn = th;
                for (std::size_t q = 0; q < m; ++q)
                    tn[q] += step[q];
                const double cn = residuals(tn, rn) + priors(tn, s2);
                if (std::isfinite(cn) && cn < cost) {
                    const double gain = (cost - cn) / std::max(cost, 1e-12);
                    th.swap(tn);
                    mu = std::max(mu / 3.0, 1e-9);
                    improved = true;
                    if (gain < 1e-7)
                        return;
                } else
                    mu *= 4.0;
            }
            if (!improved)
                return;
        }
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
    const int gm = static_cast<int>(std::ceil(d_search / spacing));
    const double tau2 = 100.0; // (10 Hz)^2: a robust cost for the grid
    // Wind candidates: calm, and 3 and 6 m/s from 8 directions (a strong wind moves the
    // emitter by hundreds of metres in the air frame over an orbit: the fit must start
    // near it).
    std::vector<std::pair<double, double>> winds{ { 0.0, 0.0 } };
    for (double ws : { 3.0, 6.0 })
        for (int q = 0; q < 8; ++q)
            winds.emplace_back(ws * std::cos(q * M_PI / 4), ws * std::sin(q * M_PI / 4));
    // Heights: the prior's (at least 10 m: at zero the cost is spiky where the path
    // passes over a candidate), else low and high.
    const std::vector<double> heights = d_alt_sigma > 0.0
                                            ? std::vector<double>{ std::max(d_alt, 10.0) }
                                            : std::vector<double>{ 10.0, 100.0 };
    for (const auto& wv : winds)
        for (double h : heights)
            for (int i = -gm; i <= gm; ++i)
                for (int j = -gm; j <= gm; ++j) {
                    if (i * i + j * j > gm * gm)
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

    // The grid's residual scale weights the priors until a fit gives a better one.
    pr.residuals(best, r);
    double s2 = 0.0;
    {
        std::vector<double> a;
        for (std::size_t k = 0; k < n; ++k)
            a.push_back(std::abs(r[k]));
        s2 = std::pow(std::max(1.4826 * median(a), 0.25), 2);
    }

    // Constant wind first (maximum a posteriori with the wind and height priors), two
    // rounds of outlier rejection; then, with a gust prior, the fit with gusts from
    // there.
    gust_fit base(pr, 0.0, d_gust_tau, d_alt, d_alt_sigma);
    std::vector<double> th(best.begin(), best.end());
    int used = 0;
    for (int round = 0; round < 3; ++round) {
        base.run(th, s2, 60);
        const double ss = base.residuals(th, r);
        used = 0;
        for (std::size_t k = 0; k < n; ++k)
            used += pr.use[k] ? 1 : 0;
        s2 = std::max(ss / std::max(used - 7, 1), 0.0625); // at least (0.25 Hz)^2
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
    if (used < 50)
        return out;
    double c0 = 0.0;
    std::unique_ptr<gust_fit> gf;
    const gust_fit* fin = &base;
    if (d_gust > 0.0) {
        // Gusts: weight the prior by the constant-wind fit's residual variance, then
        // once more by the gust fit's own, which also weighs the final covariance.
        gf = std::make_unique<gust_fit>(pr, d_gust, d_gust_tau, d_alt, d_alt_sigma);
        th.resize(gf->m, 0.0);
        // The residual variance counts the parameters the gust states took from the
        // data (effective_params): the gusts can absorb noise and multipath, and the
        // raw residual variance would then weaken the prior and shrink the ellipse.
        auto variance = [&]() {
            const double dof = used - 2.0 - gf->effective_params(th, s2);
            return std::max(gf->residuals(th, r) / std::max(dof, 1.0), 0.0625);
        };
        gf->run(th, s2, 30);
        s2 = variance();
        gf->run(th, s2, 30);
        s2 = variance();
        out.gust_knots = static_cast<int>(gf->K);
        fin = gf.get();
    }
    fin->residuals(th, r, nullptr, &c0);
    const params p{ th[0], th[1], th[2], th[3], th[4] };
    double r1 = 0.0, r0 = 0.0, prev = 0.0;
    bool have_prev = false;
    for (std::size_t k = 0; k < n; ++k) {
        if (!pr.use[k])
            continue;
        r0 += r[k] * r[k];
        if (have_prev)
            r1 += prev * r[k];
        prev = r[k];
        have_prev = true;
    }
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
    // The covariance (J^T J / (s2 inflation) + priors)^-1 = s2 inflation N^-1, N the
    // Gauss-Newton matrix with the priors weighted by s2 inflation: the inflation is
    // the data's, not the priors' (solve_ridged keeps a zero height invertible).
    std::vector<double> N, g, rr;
    fin->build(th, s2 * inflation, N, g, rr);
    const std::size_t m = fin->m;
    std::vector<double> E(m * 4, 0.0); // the first 4 unit columns -> N^-1's
    for (std::size_t q = 0; q < 4; ++q)
        E[q * 4 + q] = 1.0;
    if (!solve_ridged(N, m, E, 4))
        return out;
    std::array<double, 16> cov{}; // (p_x, p_y, w_x, w_y) block of N^-1
    for (std::size_t w = 0; w < 4; ++w)
        for (std::size_t q = 0; q < 4; ++q)
            cov[w * 4 + q] = E[w * 4 + q];
    const double sxx = s2 * inflation * cov[0], syy = s2 * inflation * cov[5];
    const double sxy = s2 * inflation * 0.5 * (cov[1] + cov[4]);
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
    out.wind_sigma_mps =
        std::sqrt(std::max(0.5 * s2 * inflation * (cov[10] + cov[15]), 0.0));
    out.altitude_m = std::abs(p[4]);
    out.cfo_hz = c0;
    out.rms_hz = std::sqrt(r0 / used);
    out.used = used;
    out.inflation = inflation;
    out.valid = std::isfinite(out.east_m) && std::isfinite(out.north_m) &&
                std::isfinite(out.major_m) && std::isfinite(out.minor_m) &&
                std::isfinite(out.wind_sigma_mps) && std::isfinite(out.altitude_m) &&
                std::isfinite(out.cfo_hz);
    return out;
}

} // namespace rfseek
} // namespace gr
