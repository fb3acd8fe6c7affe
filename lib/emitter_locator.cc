/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The emitter locator (arrival.h, docs/seeker.md "The location fit"): a grid search for
 * a start, a constant-wind fit with outlier rejection, the fit with gusts, and the 95 %
 * ellipse from the covariance inflated for correlated residuals. The model and its
 * solver are in location_model.
 */

#include "arrival_math.h"
#include "location_model.h"
#include <gr-rfseek/arrival.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace gr {
namespace rfseek {

using location::far_excess;
using location::gust_fit;
using location::params;
using location::problem;

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

// Grid search (decimated, bounded cost) around the path's centroid: emitter candidates
// every 30 m within the search radius, for calm air and 3 and 6 m/s from 8 directions (a
// strong wind moves the emitter by hundreds of metres in the air frame over an orbit:
// the fit must start near it), at the height prior (at least 10 m: at zero the cost is
// spiky where the path passes over a candidate), else low and high.
params
grid_start(problem& pr, double search_m, double altitude_m, double altitude_sigma_m)
{
    const std::size_t n = pr.t.size();
    const std::array<double, 2> mid = pr.centroid();
    const double cx = mid[0], cy = mid[1];
    pr.step = std::max<std::size_t>(1, n / 120);
    std::vector<double> r;
    params best{ cx, cy, 0.0, 0.0, 0.0 };
    double best_cost = std::numeric_limits<double>::infinity();
    const double spacing = 30.0;
    const int gm = static_cast<int>(std::ceil(search_m / spacing));
    const double tau2 = 100.0; // (10 Hz)^2: a robust cost for the grid
    std::vector<std::pair<double, double>> winds{ { 0.0, 0.0 } };
    for (double ws : { 3.0, 6.0 })
        for (int q = 0; q < 8; ++q)
            winds.emplace_back(ws * std::cos(q * M_PI / 4), ws * std::sin(q * M_PI / 4));
    const std::vector<double> heights =
        altitude_sigma_m > 0.0 ? std::vector<double>{ std::max(altitude_m, 10.0) }
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
    return best;
}

// The constant-wind fit (maximum a posteriori with the wind and height priors) from th,
// with two rounds of outlier rejection (beyond 4 robust sigma, at least 1 Hz); s2 starts
// at the grid's residual scale and ends at the fit's residual variance. Returns the
// inliers.
int constant_wind_fit(problem& pr, const gust_fit& base, Eigen::VectorXd& th, double& s2)
{
    const std::size_t n = pr.t.size();
    Eigen::VectorXd r;
    int used = 0;
    for (int round = 0; round < 3; ++round) {
        base.run(th, s2, 60);
        const double ss = base.residuals(th, r);
        used = static_cast<int>(pr.inliers());
        s2 = std::max(ss / std::max(used - 7, 1), 0.0625); // at least (0.25 Hz)^2
        if (round == 2)
            break;
        std::vector<double> a;
        for (std::size_t k = 0; k < n; ++k)
            if (pr.use[k])
                a.push_back(std::abs(r(k)));
        const double sigma = std::max(1.4826 * median(a), 0.25);
        for (std::size_t k = 0; k < n; ++k)
            pr.use[k] = std::abs(r(k)) <= std::max(4.0 * sigma, 1.0);
    }
    return used;
}

// Correlated residuals (multipath along the path, gusts) carry less information than
// their number says: the covariance is inflated by the larger of the AR(1) factor and
// the variance ratio of 1 s block means (B var(mean) / var, 1 for white residuals).
// r0 is set to the inliers' sum of squares.
double inflation_of(const problem& pr, const Eigen::VectorXd& r, int used, double& r0)
{
    double r1 = 0.0, prev = 0.0;
    bool have_prev = false;
    r0 = 0.0;
    for (std::size_t k = 0; k < pr.t.size(); ++k) {
        if (!pr.use[k])
            continue;
        r0 += r(k) * r(k);
        if (have_prev)
            r1 += prev * r(k);
        prev = r(k);
        have_prev = true;
    }
    const double rho = std::clamp(r0 > 0.0 ? r1 / r0 : 0.0, 0.0, 0.98);
    double inflation = (1.0 + rho) / (1.0 - rho);
    const std::size_t B = 20;
    double sum = 0.0, bm2 = 0.0;
    std::size_t in_block = 0, blocks = 0;
    for (std::size_t k = 0; k < pr.t.size(); ++k) {
        if (!pr.use[k])
            continue;
        sum += r(k);
        if (++in_block == B) {
            bm2 += (sum / B) * (sum / B);
            sum = 0.0;
            in_block = 0;
            ++blocks;
        }
    }
    if (blocks >= 5 && r0 > 0.0)
        inflation = std::max(inflation, B * (bm2 / blocks) / (r0 / used));
    return inflation;
}

// The 95 % and 50 % ellipses of the position covariance c (m^2), their radii scaled by
// k95 and k50.
void set_axes(const Eigen::Matrix2d& c, double k95, double k50, emitter_location& out)
{
    const double sxx = c(0, 0), syy = c(1, 1), sxy = 0.5 * (c(0, 1) + c(1, 0));
    const double tr = 0.5 * (sxx + syy);
    const double disc = std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
    const double chi2_95 = 5.991464547107979; // 2 degrees of freedom
    const double chi2_50 = 1.3862943611198906;
    const double a2 = std::max(tr + disc, 0.0), b2 = std::max(tr - disc, 0.0);
    out.major_m = k95 * std::sqrt(chi2_95 * a2);
    out.minor_m = k95 * std::sqrt(chi2_95 * b2);
    out.major50_m = k50 * std::sqrt(chi2_50 * a2);
    out.minor50_m = k50 * std::sqrt(chi2_50 * b2);
    out.major_angle_rad = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
}

// The ellipses and the wind's standard deviation from the covariance
// (J^T J / (s2 inflation) + priors)^-1 = s2 inflation N^-1, N the Gauss-Newton matrix
// with the priors weighted by s2 inflation: the inflation is the data's, not the
// priors'. False if N is singular.
bool ellipse(const gust_fit& fit,
             const Eigen::VectorXd& th,
             double var,
             emitter_location& out,
             Eigen::Matrix4d* cov4 = nullptr)
{
    Eigen::MatrixXd N;
    Eigen::VectorXd g, r;
    fit.build(th, var, N, g, r);
    Eigen::MatrixXd cov = Eigen::MatrixXd::Identity(fit.size(), 4);
    if (!solve_ridged(N, cov)) // the (p_x, p_y, w_x, w_y) columns of N^-1
        return false;
    const Eigen::Matrix4d c = var * cov.topRows(4);
    set_axes(c.topLeftCorner<2, 2>(), 1.0, 1.0, out);
    out.wind_sigma_mps = std::sqrt(std::max(0.5 * (c(2, 2) + c(3, 3)), 0.0));
    if (cov4)
        *cov4 = 0.5 * (c + c.transpose());
    return true;
}

// One nuisance model refitted from th0 on the first model's inliers and noise variance
// var: its parameters, covariance (p, w) and log Laplace evidence (up to a constant
// shared by every model: the flat prior on p, the data's normalisation).
struct model_fit {
    Eigen::VectorXd th;
    Eigen::Matrix4d cov;
    double log_evidence = -std::numeric_limits<double>::infinity();
};

model_fit fit_model(const problem& pr,
                    const Eigen::VectorXd& th0,
                    double var,
                    double gust,
                    double tau,
                    double h0,
                    double sigma_h)
{
    model_fit m;
    const gust_fit f(pr, gust, tau, h0, sigma_h);
    m.th = Eigen::VectorXd::Zero(f.size());
    m.th.head(5) = th0.head(5);
    if (sigma_h > 0.0)
        m.th(4) = h0;
    f.run(m.th, var, 40);
    Eigen::MatrixXd N, P = Eigen::MatrixXd::Zero(f.size(), f.size());
    Eigen::VectorXd g, r, gp = Eigen::VectorXd::Zero(f.size());
    const double cost = f.build(m.th, var, N, g, r);
    f.priors(m.th, 1.0, &P, &gp);
    P.triangularView<Eigen::StrictlyLower>() = P.transpose();
    // The prior's precision over the parameters it covers: wind, gusts, the height.
    std::vector<Eigen::Index> idx{ 2, 3 };
    if (sigma_h > 0.0)
        idx.push_back(4);
    for (Eigen::Index q = 5; q < static_cast<Eigen::Index>(f.size()); ++q)
        idx.push_back(q);
    Eigen::MatrixXd Ps(idx.size(), idx.size());
    for (std::size_t a = 0; a < idx.size(); ++a)
        for (std::size_t b = 0; b < idx.size(); ++b)
            Ps(a, b) = P(idx[a], idx[b]);
    const Eigen::LDLT<Eigen::MatrixXd> ln(N / var), lp(Ps);
    if (ln.info() != Eigen::Success || lp.info() != Eigen::Success ||
        !(ln.vectorD().array() > 0.0).all() || !(lp.vectorD().array() > 0.0).all())
        return m;
    Eigen::MatrixXd cov = Eigen::MatrixXd::Identity(f.size(), 4);
    if (!solve_ridged(N, cov))
        return m;
    const Eigen::Matrix4d c = var * cov.topRows(4);
    m.cov = 0.5 * (c + c.transpose());
    m.log_evidence = -0.5 * cost / var - 0.5 * ln.vectorD().array().log().sum() +
                     0.5 * lp.vectorD().array().log().sum();
    if (!std::isfinite(m.log_evidence) || !m.th.allFinite())
        m.log_evidence = -std::numeric_limits<double>::infinity();
    return m;
}

// The calibrated radius factors of the 95 % and 50 % ellipses, by the gust level the fit
// found (emitter_location::gust_rms_mps: below 0.55, 0.9, 1.2 m/s, or above), its mean
// wind over the airspeed (below 0.52, or above) and whether it is low in the wind
// (locator_nuisance::LOW_HEIGHT_M, LOW_WIND_FRACTION: one row for any wind). Measured
// by scripts/locator_envelope.py --calibrate --runs 40 --seed 4000001 (27 cells x 40
// runs, seeds no table uses; docs/seeker.md, "How honest the ellipse is"): per bin, the
// factors that put the 94th and the 50th percentile of the fixes' errors, in the metric
// of the mixture's covariance, on the 95 % and 50 % contours. The light-wind and the
// low rows are the calibration of the build with the arrival rules (docs/notes/
// seeker.md, "Low in the wind"); the strong-wind row (few fixes) keeps its earlier
// factors (95 %: the first calibration's; 50 %: the recalibration with the arrival
// that needs the honest ellipse). Gusty or strong air leaves a few fixes far off (the
// gusts' drift, which the Doppler of one orbit cannot tell from a moved emitter), low
// fits in the wind most of all: the 95 % factor grows far more than the 50 %. Each entry
// is at least its neighbours' toward calmer air.
struct radius_factors {
    double k95, k50;
};
radius_factors ellipse_scale(double gust_rms_mps, double wind_fraction, double height_m)
{
    static constexpr std::array<double, 3> gust_edge{ { 0.55, 0.9, 1.2 } };
    static constexpr double wind_edge = 0.52;
    // Rows: light wind, strong wind, low in the wind (its first bin the strong
    // wind's, as few fixes fall there).
    static constexpr double f95[3][4] = { { 0.80, 1.13, 2.08, 11.82 },
                                          { 3.35, 3.65, 6.07, 39.04 },
                                          { 3.35, 12.26, 12.26, 57.76 } };
    static constexpr double f50[3][4] = { { 0.79, 0.86, 1.21, 2.99 },
                                          { 1.08, 1.87, 5.27, 5.27 },
                                          { 1.08, 5.76, 5.76, 8.27 } };
    const std::size_t i = static_cast<std::size_t>(
        std::upper_bound(gust_edge.begin(), gust_edge.end(), gust_rms_mps) -
        gust_edge.begin());
    // Unknown (NaN) counts as the worst: strong wind, low (a NaN gust level already
    // falls in the top bin).
    std::size_t j = !(wind_fraction < wind_edge) ? 1 : 0;
    // Low in the wind whatever gusts the fit found: there a fit that found little
    // (under 0.55 m/s) in 2.5 m/s gusts erred by up to 3 x its light-wind radius.
    if (!(height_m >= locator_nuisance::LOW_HEIGHT_M) &&
        !(wind_fraction < locator_nuisance::LOW_WIND_FRACTION))
        j = 2;
    return { f95[j][i], f50[j][i] };
}

} // namespace

std::array<double, 2>
locator_nuisance::factors(double gust_rms_mps, double wind_fraction, double height_m)
{
    const radius_factors k = ellipse_scale(gust_rms_mps, wind_fraction, height_m);
    return { k.k95, k.k50 };
}

std::array<double, 2> locator_nuisance::whole_loiter_radii(double height_m,
                                                           double wind_fraction)
{
    const bool low = !(height_m >= LOW_HEIGHT_M) && !(wind_fraction < LOW_WIND_FRACTION);
    return low ? LOW_WANDER_RADII_M : WANDER_RADII_M;
}

namespace {

// The fix under every nuisance model (locator_nuisance), weighted by evidence: the mean
// and the covariance of the mixture replace out's fix and ellipses. The first model is
// the locator's own prior (gust std and time, height h0 +- sigma_h).
void carry_nuisance(const problem& pr,
                    const Eigen::VectorXd& th0,
                    double var,
                    const std::array<double, 4>& model,
                    const locator_nuisance& nu,
                    emitter_location& out)
{
    const double gust = model[0], gust_tau = model[1], h0 = model[2], sigma_h = model[3];
    std::vector<std::pair<double, double>> gusts{ { gust, gust_tau } };
    for (double tau : locator_nuisance::GUST_TAUS_S)
        gusts.emplace_back(locator_nuisance::GUST_WIDE_MPS, tau);
    std::vector<double> heights{ h0 };
    const bool prior = sigma_h > 0.0;
    if (prior && nu.altimeter_m > 0.0) {
        heights.push_back(std::max(h0 - nu.altimeter_m, 5.0));
        heights.push_back(h0 + nu.altimeter_m);
    }
    std::vector<model_fit> fits;
    std::vector<char> wide, off; // the model's gusts are wide; its height is off h0
    double best = -std::numeric_limits<double>::infinity();
    for (const auto& gu : gusts)
        for (double h : heights) {
            fits.push_back(fit_model(pr, th0, var, gu.first, gu.second, h, sigma_h));
            wide.push_back(&gu != &gusts.front());
            off.push_back(h != h0);
            best = std::max(best, fits.back().log_evidence);
        }
    if (!std::isfinite(best))
        return;
    double wsum = 0.0;
    Eigen::Vector4d mean = Eigen::Vector4d::Zero();
    double height = 0.0;
    std::vector<double> w;
    for (const model_fit& m : fits) {
        w.push_back(std::exp(m.log_evidence - best));
        wsum += w.back();
        mean += w.back() * m.th.head(4);
        height += w.back() * std::abs(m.th(4));
    }
    mean /= wsum;
    Eigen::Matrix4d cov = Eigen::Matrix4d::Zero();
    double spread = 0.0, wide_w = 0.0, off_w = 0.0;
    for (std::size_t j = 0; j < fits.size(); ++j) {
        if (w[j] == 0.0)
            continue;
        wide_w += wide[j] ? w[j] / wsum : 0.0;
        off_w += off[j] ? w[j] / wsum : 0.0;
        const Eigen::Vector4d d = fits[j].th.head(4) - mean;
        cov += (w[j] / wsum) * (fits[j].cov + d * d.transpose());
        spread += (w[j] / wsum) * d.head(2).squaredNorm();
    }
    const radius_factors k =
        nu.calibrated ? ellipse_scale(out.gust_rms_mps,
                                      std::hypot(mean(2), mean(3)) / nu.airspeed_mps,
                                      height / wsum)
                      : radius_factors{ 1.0, 1.0 };
    set_axes(cov.topLeftCorner<2, 2>(), k.k95 * nu.scale95, k.k50 * nu.scale50, out);
    out.wind_sigma_mps = std::sqrt(std::max(0.5 * (cov(2, 2) + cov(3, 3)), 0.0));
    out.east_m = mean(0) - out.dr_x_m;
    out.north_m = mean(1) - out.dr_y_m;
    out.wind_east_mps = mean(2);
    out.wind_north_mps = mean(3);
    out.altitude_m = height / wsum;
    out.hypotheses = static_cast<int>(fits.size());
    out.model_spread_m = std::sqrt(spread);
    out.wide_gust_weight = wide_w;
    out.off_height_weight = off_w;
}

} // namespace

emitter_location
emitter_locator::fit(double vehicle_x_m, double vehicle_y_m, bool nuisance) const
{
    return fit_range(0, d_t.size(), vehicle_x_m, vehicle_y_m, nullptr, nuisance);
}

void emitter_locator::set_nuisance(const locator_nuisance& n)
{
    auto require = [](double v, double lo, double hi, const char* what) {
        if (!(v >= lo && v <= hi))
            throw std::invalid_argument(std::string("emitter_locator: nuisance ") + what);
    };
    require(n.altimeter_m, 0.0, 1000.0, "altimeter_m must be in [0, 1000] m");
    require(n.scale95, 0.1, 10.0, "scale95 must be in [0.1, 10]");
    require(n.scale50, 0.1, 10.0, "scale50 must be in [0.1, 10]");
    require(n.airspeed_mps, 0.1, 1000.0, "airspeed_mps must be in [0.1, 1000] m/s");
    d_nuisance = n;
}

emitter_location emitter_locator::fit_range(std::size_t begin,
                                            std::size_t end,
                                            double vehicle_x_m,
                                            double vehicle_y_m,
                                            std::array<double, 16>* cov_out,
                                            bool nuisance) const
{
    emitter_location out;
    if (end > d_t.size() || begin >= end || end - begin < 50)
        return out;
    const std::size_t n = end - begin;
    // A part of the data (the split check) is copied out; the whole is fitted in place.
    const bool whole = begin == 0 && end == d_t.size();
    std::vector<double> part[6];
    const std::vector<double>* src[6] = { &d_t, &d_x, &d_y, &d_vx, &d_vy, &d_f };
    if (!whole)
        for (int i = 0; i < 6; ++i) {
            part[i].assign(src[i]->begin() + begin, src[i]->begin() + end);
            src[i] = &part[i];
        }
    problem pr{ *src[0], *src[1],  *src[2],        *src[3], *src[4],
                *src[5], d_lambda, src[0]->back(), {},      1 };
    pr.use.assign(n, 1);
    out.time_s = pr.tf;
    out.dr_x_m = vehicle_x_m;
    out.dr_y_m = vehicle_y_m;

    const params best = grid_start(pr, d_search, d_alt, d_alt_sigma);
    // The grid's residual scale weights the priors until a fit gives a better one.
    std::vector<double> rg;
    pr.residuals(best, rg);
    for (double& v : rg)
        v = std::abs(v);
    double s2 = std::pow(std::max(1.4826 * median(rg), 0.25), 2);

    // Constant wind first; then, with a gust prior, the fit with gusts from there.
    gust_fit base(pr, 0.0, d_gust_tau, d_alt, d_alt_sigma);
    Eigen::VectorXd th = Eigen::Map<const Eigen::VectorXd>(best.data(), 5);
    const int used = constant_wind_fit(pr, base, th, s2);
    if (used < 50)
        return out;
    Eigen::VectorXd r;
    std::unique_ptr<gust_fit> gf;
    const gust_fit* fin = &base;
    if (d_gust > 0.0) {
        // Gusts: weight the prior by the constant-wind fit's residual variance, then
        // once more by the gust fit's own, which also weighs the final covariance. The
        // residual variance counts the parameters the gust states took from the data
        // (effective_params): the gusts can absorb noise and multipath, and the raw
        // residual variance would then weaken the prior and shrink the ellipse.
        gf = std::make_unique<gust_fit>(pr, d_gust, d_gust_tau, d_alt, d_alt_sigma);
        th.conservativeResize(gf->size());
        th.tail(gf->size() - 5).setZero();
        auto variance = [&]() {
            const double dof = used - 2.0 - gf->effective_params(th, s2);
            return std::max(gf->residuals(th, r) / std::max(dof, 1.0), 0.0625);
        };
        gf->run(th, s2, 30);
        s2 = variance();
        gf->run(th, s2, 30);
        s2 = variance();
        out.gust_knots = static_cast<int>(gf->knots());
        const Eigen::Index ng = th.size() - 5;
        out.gust_rms_mps = ng > 0 ? std::sqrt(th.tail(ng).squaredNorm() / ng) : 0.0;
        fin = gf.get();
    }
    double c0 = 0.0, r0 = 0.0;
    fin->residuals(th, r, nullptr, &c0);
    const double inflation = inflation_of(pr, r, used, r0);
    Eigen::Matrix4d c4;
    if (!ellipse(*fin, th, s2 * inflation, out, &c4))
        return out;
    if (cov_out)
        Eigen::Map<Eigen::Matrix4d>(cov_out->data()) = c4;
    out.east_m = th(0) - vehicle_x_m;
    out.north_m = th(1) - vehicle_y_m;
    out.wind_east_mps = th(2);
    out.wind_north_mps = th(3);
    out.altitude_m = std::abs(th(4));
    out.cfo_hz = c0;
    out.rms_hz = std::sqrt(r0 / used);
    out.used = used;
    out.inflation = inflation;
    if (nuisance) {
        out.far_excess =
            far_excess(pr, d_gust, d_gust_tau, d_alt, d_alt_sigma, th, s2 * inflation);
        carry_nuisance(pr,
                       th,
                       s2 * inflation,
                       { d_gust, d_gust_tau, d_alt, d_alt_sigma },
                       d_nuisance,
                       out);
    }
    out.valid = std::isfinite(out.east_m) && std::isfinite(out.north_m) &&
                std::isfinite(out.major_m) && std::isfinite(out.minor_m) &&
                std::isfinite(out.wind_sigma_mps) && std::isfinite(out.altitude_m) &&
                std::isfinite(out.cfo_hz);
    return out;
}

bool emitter_locator::check_split(emitter_location& l, double gate) const
{
    const std::size_t n = d_t.size();
    if (!l.valid || !(gate >= 0.0) || n < 2 * SPLIT_MIN)
        return false;
    // The halves in time: the gusts' drift and the geometry differ between them, which
    // is what an ellipse too narrow for the air of the day misses.
    const double ts = 0.5 * (d_t.front() + d_t.back());
    const std::size_t m = static_cast<std::size_t>(
        std::lower_bound(d_t.begin(), d_t.end(), ts) - d_t.begin());
    if (m < SPLIT_MIN || n - m < SPLIT_MIN)
        return false;
    std::array<double, 16> ca_raw, cb_raw;
    const emitter_location a = fit_range(0, m, 0.0, 0.0, &ca_raw);
    const emitter_location b = fit_range(m, n, 0.0, 0.0, &cb_raw);
    if (!a.valid || !b.valid)
        return false;
    const Eigen::Matrix4d ca = Eigen::Map<const Eigen::Matrix4d>(ca_raw.data());
    const Eigen::Matrix4d cb = Eigen::Map<const Eigen::Matrix4d>(cb_raw.data());
    // The first half's emitter carried to the second's time with its own wind (in the
    // air frame the emitter drifts by minus the wind), its covariance with it; the
    // halves share no data, so the covariances add.
    const double dt = b.time_s - a.time_s;
    Eigen::Matrix<double, 2, 4> J;
    J << 1.0, 0.0, -dt, 0.0, 0.0, 1.0, 0.0, -dt;
    const Eigen::Matrix2d c = J * ca * J.transpose() + cb.topLeftCorner<2, 2>();
    const Eigen::Vector2d d(a.east_m - a.wind_east_mps * dt - b.east_m,
                            a.north_m - a.wind_north_mps * dt - b.north_m);
    const Eigen::LDLT<Eigen::Matrix2d> ldlt(c);
    if (ldlt.info() != Eigen::Success || !(c.determinant() > 0.0))
        return false;
    const double T = d.dot(ldlt.solve(d));
    if (!std::isfinite(T) || T < 0.0)
        return false;
    l.consistency = T;
    if (gate > 0.0 && T > gate) {
        // The halves disagree beyond what their ellipses allow: the covariance is
        // scaled by T / 2, the factor by which the disagreement exceeds its mean.
        const double k = std::sqrt(0.5 * T);
        scale_ellipses(l, k);
        l.wind_sigma_mps *= k;
    }
    return true;
}

} // namespace rfseek
} // namespace gr
