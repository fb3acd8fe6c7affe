/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include "arrival_math.h"
#include "location_model.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gr {
namespace rfseek {
namespace location {

double problem::doppler(const params& p, std::size_t k) const
{
    const double dt = t[k] - tf;
    const double rx = p[0] - p[2] * dt - x[k];
    const double ry = p[1] - p[3] * dt - y[k];
    const double s = std::sqrt(rx * rx + ry * ry + p[4] * p[4]);
    return s > 0.0 ? ((vx[k] + p[2]) * rx + (vy[k] + p[3]) * ry) / (lambda * s) : 0.0;
}

double
problem::residuals(const params& p, std::vector<double>& r, double* c, double* d) const
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
    const double cc = det > 1e-9 ? (stt * sy - st * sty) / det : sy / std::max(s1, 1.0);
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

std::size_t problem::inliers() const
{
    return static_cast<std::size_t>(std::count(use.begin(), use.end(), 1));
}

std::array<double, 2> problem::centroid() const
{
    double cx = 0.0, cy = 0.0;
    for (std::size_t k = 0; k < t.size(); ++k) {
        cx += x[k];
        cy += y[k];
    }
    return { cx / t.size(), cy / t.size() };
}

gust_fit::gust_fit(
    const problem& p, double sigma_g, double tau, double h0, double sigma_h)
    : d_pr(p), d_sigma_g(sigma_g), d_tau(tau), d_h0(h0), d_sigma_h(sigma_h)
{
    const std::size_t n = d_pr.t.size();
    const double t0 = d_pr.t.front();
    // Knots every min(tau, 5 s), at most 41 of them (a bounded cost however long the
    // loiter).
    d_spacing = std::max({ std::min(0.5 * tau, 5.0), (d_pr.tf - t0) / 40.0, 1e-3 });
    d_K =
        sigma_g > 0.0
            ? std::max<std::size_t>(
                  2, static_cast<std::size_t>(std::ceil((d_pr.tf - t0) / d_spacing)) + 1)
            : 0;
    d_m = 5 + 2 * d_K;
    if (d_K == 0)
        return;
    d_j0.resize(n);
    d_u.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double x = std::max(0.0, (d_pr.t[k] - t0) / d_spacing);
        const std::size_t j = std::min(static_cast<std::size_t>(x), d_K - 2);
        d_j0[k] = j;
        d_u[k] = std::clamp(x - j, 0.0, 1.0);
    }
    // B_kj = F_j(t_f) - F_j(t_k), F_j the integral of knot j's hat function
    // max(0, 1 - |t - tau_j| / spacing) from -infinity (exact across any gap).
    auto F = [&](std::size_t j, double t) {
        const double x = (t - (t0 + j * d_spacing)) / d_spacing;
        if (x <= -1.0)
            return 0.0;
        if (x <= 0.0)
            return 0.5 * d_spacing * (x + 1.0) * (x + 1.0);
        if (x <= 1.0)
            return d_spacing * (1.0 - 0.5 * (1.0 - x) * (1.0 - x));
        return d_spacing;
    };
    d_B.resize(n, d_K);
    for (std::size_t k = 0; k < n; ++k)
        for (std::size_t j = 0; j < d_K; ++j)
            d_B(k, j) = F(j, d_pr.tf) - F(j, d_pr.t[k]);
}

// The model D_k and, if J, its gradient (m entries) at th.
double gust_fit::model(const Eigen::VectorXd& th, std::size_t k, double* J) const
{
    const std::size_t K = d_K;
    double Gx = 0.0, Gy = 0.0, gxk = 0.0, gyk = 0.0, uk = 0.0;
    std::size_t j = 0;
    if (K) {
        Gx = d_B.row(k).dot(th.segment(5, K));
        Gy = d_B.row(k).dot(th.segment(5 + K, K));
        j = d_j0[k];
        uk = d_u[k];
        gxk = (1.0 - uk) * th(5 + j) + uk * th(5 + j + 1);
        gyk = (1.0 - uk) * th(5 + K + j) + uk * th(5 + K + j + 1);
    }
    const double dt = d_pr.t[k] - d_pr.tf;
    const double rx = th(0) - th(2) * dt + Gx - d_pr.x[k];
    const double ry = th(1) - th(3) * dt + Gy - d_pr.y[k];
    const double h = th(4);
    const double s = std::sqrt(rx * rx + ry * ry + h * h);
    if (!(s > 0.0)) {
        if (J)
            std::fill(J, J + d_m, 0.0);
        return 0.0;
    }
    const double vx = d_pr.vx[k] + th(2) + gxk, vy = d_pr.vy[k] + th(3) + gyk;
    const double num = vx * rx + vy * ry;
    const double ls = d_pr.lambda * s;
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
            J[5 + q] = d_B(k, q) * drx;
            J[5 + K + q] = d_B(k, q) * dry;
        }
        if (K) {
            J[5 + j] += (1.0 - uk) * dvx;
            J[5 + j + 1] += uk * dvx;
            J[5 + K + j] += (1.0 - uk) * dvy;
            J[5 + K + j + 1] += uk * dvy;
        }
    }
    return num / ls;
}

// The priors at th, each weighted by s2: the gusts' (Gauss-Markov: e_0 = g_0 / sigma_g,
// e_j = (g_j - a g_{j-1}) / (sigma_g sqrt(1 - a^2)), a = exp(-spacing / tau), per axis),
// the mean wind's (0 +- wind_sigma per axis: keeps a far-field fit from running off to
// kilometres and tens of m/s) and the height's (h0 +- sigma_h).
double gust_fit::priors(const Eigen::VectorXd& th,
                        double s2,
                        Eigen::MatrixXd* N,
                        Eigen::VectorXd* g) const
{
    double cost = 0.0;
    // One whitened residual e = c0 th[q0] + c1 th[q1] - mean (q1 unused if c1 0).
    auto add = [&](std::size_t q0, double c0, std::size_t q1, double c1, double mean) {
        const double e = c0 * th(q0) + c1 * th(q1) - mean;
        cost += s2 * e * e;
        if (!N)
            return;
        (*N)(q0, q0) += s2 * c0 * c0;
        (*g)(q0) -= s2 * c0 * e;
        if (c1 != 0.0) {
            (*N)(q1, q1) += s2 * c1 * c1;
            (*N)(std::min(q0, q1), std::max(q0, q1)) += s2 * c0 * c1;
            (*g)(q1) -= s2 * c1 * e;
        }
    };
    if (d_K) {
        const double a = std::exp(-d_spacing / d_tau);
        const double sd = d_sigma_g * std::sqrt(1.0 - a * a);
        for (std::size_t ax = 0; ax < 2; ++ax)
            for (std::size_t j = 0; j < d_K; ++j) {
                const std::size_t q = 5 + ax * d_K + j;
                if (j == 0)
                    add(q, 1.0 / d_sigma_g, q, 0.0, 0.0);
                else
                    add(q, 1.0 / sd, q - 1, -a / sd, 0.0);
            }
    }
    add(2, 1.0 / wind_sigma, 2, 0.0, 0.0);
    add(3, 1.0 / wind_sigma, 3, 0.0, 0.0);
    if (d_sigma_h > 0.0)
        add(4, 1.0 / d_sigma_h, 4, 0.0, d_h0 / d_sigma_h);
    return cost;
}

// Projected residuals (c + d (t - t_f) over the inliers removed) and, if J, the projected
// Jacobian of the model (n x m; outlier rows are not used).
double gust_fit::residuals(const Eigen::VectorXd& th,
                           Eigen::VectorXd& r,
                           row_matrix* J,
                           double* c_out) const
{
    const std::size_t n = d_pr.t.size();
    r.setZero(n);
    if (J)
        J->setZero(n, d_m);
    Eigen::VectorXd w(n), dt(n); // inlier weight, t - t_f
    for (std::size_t k = 0; k < n; ++k) {
        r(k) = d_pr.f[k] - model(th, k, J && d_pr.use[k] ? J->row(k).data() : nullptr);
        w(k) = d_pr.use[k] ? 1.0 : 0.0;
        dt(k) = d_pr.t[k] - d_pr.tf;
    }
    const double s1 = w.sum(), st = w.dot(dt), stt = w.dot(dt.cwiseProduct(dt));
    const double det = s1 * stt - st * st;
    // The inliers' best line c + d dt, from its sums sy = w . v, sty = (w dt) . v.
    auto line = [&](double sy, double sty, double& c, double& d) {
        c = det > 1e-9 ? (stt * sy - st * sty) / det : sy / std::max(s1, 1.0);
        d = det > 1e-9 ? (s1 * sty - st * sy) / det : 0.0;
    };
    const Eigen::VectorXd wdt = w.cwiseProduct(dt);
    double cc, dd;
    line(w.dot(r), wdt.dot(r), cc, dd);
    r.array() -= cc + dd * dt.array();
    if (c_out)
        *c_out = cc;
    if (J) {
        const Eigen::RowVectorXd sy = w.transpose() * *J, sty = wdt.transpose() * *J;
        for (std::size_t q = 0; q < d_m; ++q) {
            double c, d;
            line(sy(q), sty(q), c, d);
            J->col(q).array() -= c + d * dt.array();
        }
        if (d_fix_p)
            J->leftCols(2).setZero();
    }
    return r.cwiseProduct(w).squaredNorm();
}

double gust_fit::build(const Eigen::VectorXd& th,
                       double s2,
                       Eigen::MatrixXd& N,
                       Eigen::VectorXd& g,
                       Eigen::VectorXd& r) const
{
    row_matrix J;
    double cost = residuals(th, r, &J);
    for (std::size_t k = 0; k < d_pr.t.size(); ++k)
        if (!d_pr.use[k])
            J.row(k).setZero();
    N.setZero(d_m, d_m);
    N.selfadjointView<Eigen::Upper>().rankUpdate(J.transpose());
    g = J.transpose() * r;
    cost += priors(th, s2, &N, &g);
    N.triangularView<Eigen::StrictlyLower>() = N.transpose();
    return cost;
}

// The residual variance is SS / (n - this - 2).
double gust_fit::effective_params(const Eigen::VectorXd& th, double s2) const
{
    Eigen::MatrixXd N0, N;
    Eigen::VectorXd g, r;
    build(th, 0.0, N0, g, r); // J^T J
    build(th, s2, N, g, r);
    if (!solve_ridged(N, N0)) // N0 becomes N^-1 J^T J
        return static_cast<double>(d_m);
    return std::clamp(N0.trace(), 0.0, static_cast<double>(d_m));
}

void gust_fit::run(Eigen::VectorXd& th, double s2, int max_it) const
{
    Eigen::MatrixXd N;
    Eigen::VectorXd g, r, rn;
    double mu = 1e-3;
    for (int it = 0; it < max_it; ++it) {
        const double cost = build(th, s2, N, g, r);
        bool improved = false;
        for (int tries = 0; tries < 8 && !improved; ++tries) {
            Eigen::MatrixXd A = N;
            A.diagonal().array() += mu * (N.diagonal().array() + 1e-9);
            Eigen::VectorXd step = g;
            if (!lu_solve(A, step)) {
                mu *= 10.0;
                continue;
            }
            const Eigen::VectorXd tn = th + step;
            const double cn = residuals(tn, rn) + priors(tn, s2);
            if (std::isfinite(cn) && cn < cost) {
                const double gain = (cost - cn) / std::max(cost, 1e-12);
                th = tn;
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

// The plane wave (location_model.h): its bearing every 10 deg, then every 1 deg around
// the best, by the constant-wind cost.
double far_excess(const problem& pr,
                  double gust,
                  double tau,
                  double h0,
                  double sigma_h,
                  const Eigen::VectorXd& th,
                  double var)
{
    constexpr double FAR_RANGE_M = 20000.0;
    const gust_fit fit(pr, gust, tau, h0, sigma_h);
    if (th.size() != static_cast<Eigen::Index>(fit.size()))
        return std::numeric_limits<double>::quiet_NaN();
    const std::array<double, 2> mid = pr.centroid();
    const double cx = mid[0], cy = mid[1];
    auto at = [&](double a) {
        return params{ cx + FAR_RANGE_M * std::cos(a),
                       cy + FAR_RANGE_M * std::sin(a),
                       th(2),
                       th(3),
                       th(4) };
    };
    std::vector<double> r;
    double best_a = 0.0, best_cost = std::numeric_limits<double>::infinity();
    auto try_bearing = [&](double a) {
        const double c = pr.residuals(at(a), r);
        if (c < best_cost) {
            best_cost = c;
            best_a = a;
        }
    };
    for (int q = 0; q < 36; ++q)
        try_bearing(q * M_PI / 18.0);
    const double coarse = best_a;
    for (int q = -10; q <= 10; ++q)
        try_bearing(coarse + q * M_PI / 180.0);
    gust_fit far(pr, gust, tau, h0, sigma_h);
    far.fix_position(true);
    Eigen::VectorXd tf = Eigen::VectorXd::Zero(far.size());
    const params b = at(best_a);
    for (int i = 0; i < 5; ++i)
        tf(i) = b[i];
    far.run(tf, var, 40);
    Eigen::MatrixXd N;
    Eigen::VectorXd g, rr;
    const double near_cost = fit.build(th, var, N, g, rr);
    const double far_cost = far.build(tf, var, N, g, rr);
    return (far_cost - near_cost) / var;
}

} // namespace location
} // namespace rfseek
} // namespace gr
