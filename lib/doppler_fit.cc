/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * doppler_fit: least-squares bearing from frequencies at known headings (doppler_fit.h).
 */

#include "doppler_fit.h"
#include <gr-rfseek/world.h>
#include <algorithm>
#include <array>
#include <cmath>

namespace gr {
namespace rfseek {

namespace {

constexpr int MAXP = 4;
using vec = std::array<double, MAXP>;
using mat = std::array<vec, MAXP>;

// Inverts the p x p symmetric matrix a (Gauss-Jordan with partial pivoting).
bool invert(mat a, int p, mat& inv)
{
    for (int i = 0; i < p; ++i)
        for (int j = 0; j < p; ++j)
            inv[i][j] = i == j ? 1.0 : 0.0;
    double scale = 0.0;
    for (int i = 0; i < p; ++i)
        scale = std::max(scale, std::abs(a[i][i]));
    if (!(scale > 0.0))
        return false;
    for (int c = 0; c < p; ++c) {
        int piv = c;
        for (int r = c + 1; r < p; ++r)
            if (std::abs(a[r][c]) > std::abs(a[piv][c]))
                piv = r;
        if (!(std::abs(a[piv][c]) > 1e-12 * scale))
            return false;
        std::swap(a[c], a[piv]);
        std::swap(inv[c], inv[piv]);
        const double d = a[c][c];
        for (int j = 0; j < p; ++j) {
            a[c][j] /= d;
            inv[c][j] /= d;
        }
        for (int r = 0; r < p; ++r) {
            if (r == c)
                continue;
            const double f = a[r][c];
            for (int j = 0; j < p; ++j) {
                a[r][j] -= f * a[c][j];
                inv[r][j] -= f * inv[c][j];
            }
        }
    }
    return true;
}

struct ls_result {
    bool ok = false;
    vec x{};
    mat cov{}; // (X'X)^-1
    double rms = 0.0;
    int used = 0;
};

// Least squares y = X x over the kept rows; row(i, xrow) fills one row and returns y.
template <typename Row>
ls_result solve(int n, int p, const std::vector<char>& keep, Row row)
{
    ls_result r;
    mat xtx{};
    vec xty{};
    vec xr{};
    for (int i = 0; i < n; ++i) {
        if (!keep[i])
            continue;
        const double y = row(i, xr);
        for (int a = 0; a < p; ++a) {
            xty[a] += xr[a] * y;
            for (int b = 0; b < p; ++b)
                xtx[a][b] += xr[a] * xr[b];
        }
        ++r.used;
    }
    if (r.used < p + 1 || !invert(xtx, p, r.cov))
        return r;
    for (int a = 0; a < p; ++a) {
        r.x[a] = 0.0;
        for (int b = 0; b < p; ++b)
            r.x[a] += r.cov[a][b] * xty[b];
    }
    double ss = 0.0;
    for (int i = 0; i < n; ++i) {
        if (!keep[i])
            continue;
        double e = row(i, xr);
        for (int a = 0; a < p; ++a)
            e -= xr[a] * r.x[a];
        ss += e * e;
    }
    r.rms = std::sqrt(ss / std::max(1, r.used - p));
    r.ok = std::isfinite(r.rms);
    return r;
}

// Fit, drop the samples whose residual is beyond max(trim_sigma rms, floor), fit again.
template <typename Row>
ls_result trimmed(int n, int p, double trim_sigma, double floor_hz, Row row)
{
    std::vector<char> keep(n, 1);
    ls_result r = solve(n, p, keep, row);
    if (!r.ok || trim_sigma <= 0.0)
        return r;
    const double lim = std::max(trim_sigma * r.rms, floor_hz);
    bool dropped = false;
    vec xr{};
    for (int i = 0; i < n; ++i) {
        double e = row(i, xr);
        for (int a = 0; a < p; ++a)
            e -= xr[a] * r.x[a];
        if (std::abs(e) > lim) {
            keep[i] = 0;
            dropped = true;
        }
    }
    if (!dropped)
        return r;
    const ls_result again = solve(n, p, keep, row);
    return again.ok ? again : r;
}

double mean_time(const std::vector<doppler_sample>& s)
{
    double t = 0.0;
    for (const auto& x : s)
        t += x.time_s;
    return s.empty() ? 0.0 : t / s.size();
}

} // namespace

doppler_fit_result fit_doppler_full(const std::vector<doppler_sample>& s,
                                    bool with_drift,
                                    double trim_sigma,
                                    double trim_floor_hz)
{
    doppler_fit_result out;
    const int n = static_cast<int>(s.size());
    const int p = with_drift ? 4 : 3;
    const double tbar = mean_time(s);
    const auto row = [&](int i, vec& x) {
        x[0] = std::cos(s[i].heading_rad);
        x[1] = std::sin(s[i].heading_rad);
        x[2] = 1.0;
        x[3] = s[i].time_s - tbar;
        return s[i].freq_hz;
    };
    const ls_result r = trimmed(n, p, trim_sigma, trim_floor_hz, row);
    if (!r.ok)
        return out;
    const double a = r.x[0], b = r.x[1];
    const double amp2 = a * a + b * b;
    out.ok = amp2 > 0.0;
    out.bearing_rad = std::atan2(b, a);
    out.amplitude_hz = std::sqrt(amp2);
    out.offset_hz = r.x[2];
    out.drift_hz_per_s = with_drift ? r.x[3] : 0.0;
    out.residual_rms_hz = r.rms;
    out.used = r.used;
    // var(beta) from the gradient of atan2(b, a).
    const double var =
        r.rms * r.rms *
        (b * b * r.cov[0][0] + a * a * r.cov[1][1] - 2 * a * b * r.cov[0][1]) /
        std::max(amp2 * amp2, 1e-300);
    out.bearing_std_rad = std::sqrt(std::max(var, 0.0));
    return out;
}

doppler_fit_result fit_doppler_narrow(const std::vector<doppler_sample>& s,
                                      double theta_rad,
                                      double amplitude_hz,
                                      bool with_drift,
                                      double trim_sigma,
                                      double trim_floor_hz)
{
    doppler_fit_result out;
    const int n = static_cast<int>(s.size());
    const int p = with_drift ? 3 : 2;
    const double tbar = mean_time(s);
    const double A = amplitude_hz;
    const auto row = [&](int i, vec& x) {
        const double u = world::wrap(s[i].heading_rad - theta_rad);
        x[0] = A * std::sin(u);
        x[1] = 1.0;
        x[2] = s[i].time_s - tbar;
        return s[i].freq_hz - A * std::cos(u);
    };
    const ls_result r = trimmed(n, p, trim_sigma, trim_floor_hz, row);
    if (!r.ok || !(A > 0.0))
        return out;
    out.ok = true;
    out.sin_error = r.x[0];
    const double q = std::clamp(r.x[0], -1.0, 1.0);
    out.bearing_rad = world::wrap(theta_rad + std::asin(q));
    out.amplitude_hz = A;
    out.offset_hz = r.x[1];
    out.drift_hz_per_s = with_drift ? r.x[2] : 0.0;
    out.residual_rms_hz = r.rms;
    out.used = r.used;
    out.bearing_std_rad = r.rms * std::sqrt(std::max(r.cov[0][0], 0.0)) /
                          std::sqrt(std::max(1e-12, 1 - q * q));
    return out;
}

doppler_side_result doppler_side(const std::vector<doppler_sample>& s,
                                 double heading_rad,
                                 double amplitude_hz,
                                 int grid,
                                 double floor_hz)
{
    doppler_side_result out;
    const int n = static_cast<int>(s.size());
    if (n < 3 || grid < 4 || !(amplitude_hz > 0.0))
        return out;
    double best = INFINITY, best_left = INFINITY, best_right = INFINITY, best_beta = 0.0;
    for (int k = 0; k < grid; ++k) {
        const double beta = world::wrap(heading_rad + 2.0 * M_PI * (k + 0.5) / grid);
        double sum = 0.0, sum2 = 0.0;
        for (const auto& x : s) {
            const double r = x.freq_hz - amplitude_hz * std::cos(x.heading_rad - beta);
            sum += r;
            sum2 += r * r;
        }
        const double ss = sum2 - sum * sum / n; // c at its least-squares value
        double& side_best =
            world::wrap(beta - heading_rad) > 0.0 ? best_left : best_right;
        side_best = std::min(side_best, ss);
        if (ss < best) {
            best = ss;
            best_beta = beta;
        }
    }
    if (!std::isfinite(best))
        return out;
    const double var = std::max(best / (n - 2), floor_hz * floor_hz);
    out.ok = true;
    out.bearing_rad = best_beta;
    out.side = world::wrap(best_beta - heading_rad) > 0.0 ? 1 : -1;
    out.statistic =
        (out.side > 0 ? best_right - best_left : best_left - best_right) / var;
    out.residual_rms_hz = std::sqrt(std::max(best, 0.0) / (n - 2));
    return out;
}

double invert_probe_difference(double f_plus_hz,
                               double f_minus_hz,
                               double delta_rad,
                               double amplitude_hz)
{
    const double s =
        -(f_plus_hz - f_minus_hz) / (2.0 * amplitude_hz * std::sin(delta_rad));
    return std::asin(std::clamp(s, -1.0, 1.0));
}

double resolve_probe_error(double f_nominal_hz,
                           double f_plus_hz,
                           double f_minus_hz,
                           double delta_rad)
{
    const double sin_part = (f_minus_hz - f_plus_hz) / (2.0 * std::sin(delta_rad));
    const double cos_part =
        (f_nominal_hz - 0.5 * (f_plus_hz + f_minus_hz)) / (1.0 - std::cos(delta_rad));
    return std::atan2(sin_part, cos_part);
}

} // namespace rfseek
} // namespace gr
