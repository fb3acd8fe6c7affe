/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * doppler_fit: the bearing of the emitter from frequencies measured at known headings.
 * With the physical sign of eq. 1 (docs/design.md item 1) a measurement flown at heading
 * psi is f = A cos(psi - beta) + f_o(t),   A = f_d,max,  f_o(t) ~ c + a (t - t0), beta
 * the bearing to the emitter. Internal to the library (Stage 1 of `paper`, and the
 * `adaptive` strategy); unit-tested against the model in lib/qa/qa_doppler_fit.cc.
 */

#ifndef INCLUDED_RFSEEK_DOPPLER_FIT_H
#define INCLUDED_RFSEEK_DOPPLER_FIT_H

#include <gr-rfseek/api.h>
#include <vector>

namespace gr {
namespace rfseek {

//! One accepted frequency measurement at a known heading.
struct doppler_sample {
    double heading_rad = 0.0;
    double time_s = 0.0;
    double freq_hz = 0.0;
};

struct doppler_fit_result {
    bool ok = false;             //!< enough samples and a solvable system
    double bearing_rad = 0.0;    //!< beta
    double amplitude_hz = 0.0;   //!< fitted A (full fit) or the given one (narrow fit)
    double offset_hz = 0.0;      //!< c: CFO at the samples' mean time (narrow: see below)
    double drift_hz_per_s = 0.0; //!< a (0 without the drift term)
    double sin_error = 0.0;      //!< narrow fit: sin(beta - theta) before clamping
    double residual_rms_hz = 0.0;
    double bearing_std_rad = 0.0; //!< from the LS covariance and the residual
    int used = 0;                 //!< samples kept after trimming outliers
};

/*!
 * Full fit, any heading spread (three or more headings; resolves "flying away"):
 * f = a cos psi + b sin psi + c [+ d (t - tbar)], beta = atan2(b, a), A = hypot(a, b).
 * Samples whose residual exceeds trim_sigma residual RMS (and trim_floor_hz) are dropped
 * once and the fit repeated.
 */
RFSEEK_API doppler_fit_result fit_doppler_full(const std::vector<doppler_sample>& s,
                                               bool with_drift,
                                               double trim_sigma = 4.0,
                                               double trim_floor_hz = 10.0);

/*!
 * Narrow fit around a heading theta with the amplitude A known (Stage-2 probing): with
 * u = psi - theta, f - A cos u = A sin(u) s + c [+ d (t - tbar)] and beta = theta +
 * asin(clamp(s)) (the model-inverting gain: one step removes the whole error, rather than
 * eq. 5's small-angle step). Assumes |beta - theta| < 90 deg; offset_hz is then
 * c = f_o - A (1 - cos(beta - theta)) approximately.
 */
RFSEEK_API doppler_fit_result fit_doppler_narrow(const std::vector<doppler_sample>& s,
                                                 double theta_rad,
                                                 double amplitude_hz,
                                                 bool with_drift,
                                                 double trim_sigma = 4.0,
                                                 double trim_floor_hz = 10.0);

//! Which way the emitter lies from a heading (doppler_side).
struct doppler_side_result {
    bool ok = false;          //!< enough samples (3) and a finite fit
    double bearing_rad = 0.0; //!< the best bearing on the grid
    int side = 0;             //!< +1: left of the heading (counterclockwise), -1: right
    double statistic = 0.0;   //!< (SS of the best bearing on the other side - SS) / s^2
    double residual_rms_hz = 0.0;
};

/*!
 * Side test for a short arc, the amplitude A known: f = A cos(psi - beta) + c with c
 * free, beta on a grid of `grid` bearings (least squares for c at each). The best
 * bearing's side of `heading_rad`, and the generalised likelihood ratio of that side
 * against the other: the least residual sum of squares with beta on the other side less
 * the best, over the best fit's residual variance (floored at floor_hz^2). Unlike a fit
 * linear in sin(psi - theta), it keeps the curvature A cos(psi - beta) has over an arc
 * when the emitter is behind. Near ahead or behind both sides fit alike (statistic ~0).
 */
RFSEEK_API doppler_side_result doppler_side(const std::vector<doppler_sample>& s,
                                            double heading_rad,
                                            double amplitude_hz,
                                            int grid = 720,
                                            double floor_hz = 0.5);

/*!
 * The probe difference inverted in closed form: with f+ and f- the mean frequencies at
 * theta + delta and theta - delta, f+ - f- = -2 A sin(delta) sin(theta~), theta~ = theta
 * - beta, so theta~ = asin(clamp(-(f+ - f-) / (2 A sin delta))), |theta~| <= 90 deg.
 */
RFSEEK_API double invert_probe_difference(double f_plus_hz,
                                          double f_minus_hz,
                                          double delta_rad,
                                          double amplitude_hz);

/*!
 * Three probes (theta, theta + delta, theta - delta) resolve the whole circle, flying
 * away included, without knowing A or the CFO: theta~ = atan2((f- - f+) / (2 sin delta),
 * (f0 - (f+ + f-) / 2) / (1 - cos delta)).
 */
RFSEEK_API double resolve_probe_error(double f_nominal_hz,
                                      double f_plus_hz,
                                      double f_minus_hz,
                                      double delta_rad);

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_DOPPLER_FIT_H */
