/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * location_model: the emitter locator's measurement model and its fits (Eigen).
 *   problem   the samples, the Doppler of a candidate (emitter, wind, height), and the
 *             residuals with the carrier offset and its drift projected out (the grid
 *             search's cost);
 *   gust_fit  the model with the gusts as states under a Gauss-Markov prior, solved by
 *             Levenberg-Marquardt (maximum a posteriori), with the Gauss-Newton matrix
 *             that gives the fix's covariance.
 *   far_excess the plane-wave test: an emitter far away fitted to the same data.
 * Internal to the library (emitter_locator, docs/seeker.md).
 */

#ifndef INCLUDED_RFSEEK_LOCATION_MODEL_H
#define INCLUDED_RFSEEK_LOCATION_MODEL_H

#include <Eigen/Dense>
#include <array>
#include <cstddef>
#include <vector>

namespace gr {
namespace rfseek {
namespace location {

//! The nonlinear parameters: emitter (x, y) at t_f, wind (x, y), height.
using params = std::array<double, 5>;
using row_matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct problem {
    const std::vector<double>&t, &x, &y, &vx, &vy, &f;
    double lambda, tf;
    std::vector<char> use; //!< inliers
    std::size_t step = 1;  //!< decimation (the grid search)

    //! The line-of-sight Doppler of sample k for the candidate p (no gusts).
    double doppler(const params& p, std::size_t k) const;
    /*!
     * Residuals after the best c + d (t - tf) (variable projection) over every step-th
     * sample; returns the sum of squares over the inliers, writes every residual.
     */
    double residuals(const params& p,
                     std::vector<double>& r,
                     double* c = nullptr,
                     double* d = nullptr) const;
    std::size_t inliers() const;
    //! The mean of the path's positions (x, y); the path not empty.
    std::array<double, 2> centroid() const;
};

/*
 * The location model with gusts: the wind is w + g(t), g piecewise linear between knots
 * every min(tau, 5 s) (at most 41 knots) with a first-order Gauss-Markov prior (std
 * sigma_g per axis, correlation time tau; sigma_g 0: no gust states), so
 *   r_k = p - w (t_k - t_f) + integral_{t_k}^{t_f} g - q_k,
 *   f_k = c + d (t_k - t_f) + (v_k + w + g(t_k)) . r_k / (lambda |(r_k, h)|),
 * with priors on the mean wind (0 +- 15 m/s per axis) and the height (h0 +- sigma_h,
 * sigma_h 0: none). run() finds the maximum a posteriori theta = (p, w, h, g) by
 * Gauss-Newton with Levenberg damping and an analytic Jacobian, c and d projected out,
 * the priors weighted by the measurement noise variance s2; build() gives the
 * Gauss-Newton matrix J^T J + s2 E^T E whose inverse times s2 is the covariance.
 */
class gust_fit
{
public:
    gust_fit(const problem& p, double sigma_g, double tau, double h0, double sigma_h);

    std::size_t knots() const { return d_K; }
    //! Parameters: 5 + 2 knots.
    std::size_t size() const { return d_m; }

    //! Projected residuals and the data part of the cost; the carrier offset c if asked.
    double residuals(const Eigen::VectorXd& th,
                     Eigen::VectorXd& r,
                     row_matrix* J = nullptr,
                     double* c_out = nullptr) const;
    //! The priors' cost s2 |e|^2; with N and g, adds s2 E^T E to N (upper triangle)
    //! and -s2 E^T e to g.
    double priors(const Eigen::VectorXd& th,
                  double s2,
                  Eigen::MatrixXd* N = nullptr,
                  Eigen::VectorXd* g = nullptr) const;
    //! N = J^T J + s2 E^T E, g = J^T r - s2 E^T e and r at th; returns the cost.
    double build(const Eigen::VectorXd& th,
                 double s2,
                 Eigen::MatrixXd& N,
                 Eigen::VectorXd& g,
                 Eigen::VectorXd& r) const;
    //! trace((J^T J + s2 E^T E)^-1 J^T J): the parameters the data fit (gust states the
    //! prior holds near zero count for little).
    double effective_params(const Eigen::VectorXd& th, double s2) const;
    //! Holds the emitter's position (th 0, 1) where it is in run() (a far emitter).
    void fix_position(bool fix) { d_fix_p = fix; }
    //! Minimises the data cost + s2 |e|^2 from th (Levenberg-Marquardt).
    void run(Eigen::VectorXd& th, double s2, int max_it) const;

private:
    double model(const Eigen::VectorXd& th, std::size_t k, double* J) const;

    const problem& d_pr;
    double d_sigma_g, d_tau;
    double d_h0, d_sigma_h;
    bool d_fix_p = false;
    static constexpr double wind_sigma = 15.0; //!< mean wind prior, m/s per axis
    std::size_t d_K = 0, d_m = 0;
    double d_spacing = 0.0;
    std::vector<std::size_t> d_j0; //!< knot below t_k
    std::vector<double> d_u;       //!< position between knots j0, j0 + 1
    row_matrix d_B; //!< n x K: integral of the hat functions from t_k to t_f
};

/*!
 * How much worse than the fit th (gust model gust_mps, tau_s; height prior h0 +-
 * sigma_h; noise variance var) an emitter far away explains pr's data: a plane wave
 * (the emitter 20 km from the path's centroid at the bearing of least constant-wind
 * cost), refitted with its position held under the same priors. The difference of the
 * two MAP costs over var (emitter_location::far_excess); NaN if th is not that model's.
 */
double far_excess(const problem& pr,
                  double gust_mps,
                  double tau_s,
                  double h0,
                  double sigma_h,
                  const Eigen::VectorXd& th,
                  double var);

} // namespace location
} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_LOCATION_MODEL_H */
