/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * arrival_math: the robust statistics and linear solves of the overflight detector and
 * the emitter locator (Eigen), and the sizes of a fix's ellipses. Internal to the
 * library.
 */

#ifndef INCLUDED_RFSEEK_ARRIVAL_MATH_H
#define INCLUDED_RFSEEK_ARRIVAL_MATH_H

#include <Eigen/Dense>
#include <gr-rfseek/arrival.h>
#include <gr-rfseek/seeker.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <vector>

namespace gr {
namespace rfseek {

//! The median of v (the mean of the middle two for an even count); v not empty.
inline double median(std::vector<double> v)
{
    const std::size_t n = v.size();
    std::nth_element(v.begin(), v.begin() + n / 2, v.end());
    const double hi = v[n / 2];
    if (n % 2)
        return hi;
    return 0.5 * (hi + *std::max_element(v.begin(), v.begin() + n / 2));
}

/*!
 * Solves A X = B in place of B (LU with partial pivoting) for square A. False if A is
 * singular (a zero pivot) or the solution is not finite.
 */
template <typename MatA, typename MatB>
bool lu_solve(const MatA& a, MatB& b)
{
    const Eigen::PartialPivLU<typename MatA::PlainObject> lu(a);
    if ((lu.matrixLU().diagonal().array() == 0.0).any())
        return false;
    b = lu.solve(b);
    return b.allFinite();
}

/*!
 * N^-1 B in place of B, N (symmetric) with a tiny ridge (1e-9 x its largest diagonal)
 * that keeps a zero height (no height prior) invertible. False if singular.
 */
inline bool solve_ridged(Eigen::MatrixXd n, Eigen::MatrixXd& b)
{
    const double scale = std::max(n.diagonal().maxCoeff(), 0.0);
    n.diagonal().array() += 1e-9 * scale + 1e-12;
    return lu_solve(n, b);
}

//! An ellipse's semi-axes scaled, direction and aspect kept, to the geometric mean
//! size_m if larger (non-finite or degenerate axes are left as they are).
inline void cap_ellipse_size(double& major_m, double& minor_m, double size_m)
{
    const double g = std::sqrt(major_m * minor_m);
    if (g > size_m && std::isfinite(g)) {
        major_m *= size_m / g;
        minor_m *= size_m / g;
    }
}

/*!
 * A fit of all a loiter's data, published unsure (c: the seeker's settings). Spanning
 * several orbits over the emitter it errs by tens of metres whatever its covariance
 * says (often kilometres): its ellipses keep their direction and aspect and take the
 * calibrated size of such fits (locator_nuisance::whole_loiter_radii, larger low in the
 * wind), in proportion to a wider orbit, times the user's factors, unless their own are
 * smaller.
 */
inline void size_whole_loiter_fix(emitter_location& l, const seeker_config& c)
{
    const double k = std::max(1.0, c.loiter_radius_m / seeker_config().loiter_radius_m);
    const auto r = locator_nuisance::whole_loiter_radii(
        l.altitude_m, std::hypot(l.wind_east_mps, l.wind_north_mps) / c.speed_mps);
    cap_ellipse_size(l.major_m, l.minor_m, r[0] * k * c.locate_scale95);
    cap_ellipse_size(l.major50_m, l.minor50_m, r[1] * k * c.locate_scale50);
    l.unsure = true;
}

/*!
 * The Doppler's amplitude in the heading (doppler_amplitude, Hz) over the measurements
 * m (time, heading, frequency; oldest first) of the last `orbits` orbits of orbit_s,
 * widened an orbit at a time, to max_orbits at most, while their headings do not go all
 * round (NaN if they never do). Where the wind drags the orbit, an orbit's time of data
 * often holds a transit to a moved estimate and not every heading.
 */
inline double recent_amplitude(const std::deque<std::array<double, 3>>& m,
                               double orbit_s,
                               double orbits,
                               double max_orbits)
{
    double amp = NAN;
    for (double k = orbits; k <= max_orbits && !std::isfinite(amp) && !m.empty(); ++k) {
        doppler_amplitude a;
        for (const auto& r : m)
            if (r[0] >= m.back()[0] - k * orbit_s)
                a.add(r[0], r[1], r[2]);
        amp = a.amplitude();
    }
    return amp;
}

//! Both of l's ellipses (95 % and 50 %) scaled by k, direction and aspect kept.
inline void scale_ellipses(emitter_location& l, double k)
{
    l.major_m *= k;
    l.minor_m *= k;
    l.major50_m *= k;
    l.minor50_m *= k;
}

/*!
 * An unsure fix l whose 95 % ellipse must reach where another fit w of the same data
 * places the emitter (both in the dead-reckoned frame, from the vehicle at their own
 * times): both of l's ellipses scaled, direction and aspect kept, to put that point on
 * the 95 % contour if it lies outside.
 */
inline void reach_fit(emitter_location& l, const emitter_location& w)
{
    const double dx = w.east_m + w.dr_x_m - l.east_m - l.dr_x_m;
    const double dy = w.north_m + w.dr_y_m - l.north_m - l.dr_y_m;
    const double c = std::cos(l.major_angle_rad), s = std::sin(l.major_angle_rad);
    const double u = (dx * c + dy * s) / l.major_m, v = (dy * c - dx * s) / l.minor_m;
    const double k = std::sqrt(u * u + v * v);
    if (k > 1.0 && std::isfinite(k))
        scale_ellipses(l, k);
}

//! An earlier fix l carried to time t, unsure: in the dead-reckoned (air) frame the
//! emitter drifts with minus the wind, whose uncertainty grows the ellipses.
inline emitter_location carried_fix(emitter_location l, double t)
{
    const double dt = std::max(t - l.time_s, 0.0);
    l.east_m -= l.wind_east_mps * dt;
    l.north_m -= l.wind_north_mps * dt;
    const double s2 = std::pow(l.wind_sigma_mps * dt, 2);
    const double chi2_95 = 5.991464547107979, chi2_50 = 1.3862943611198906;
    l.major_m = std::sqrt(l.major_m * l.major_m + chi2_95 * s2);
    l.minor_m = std::sqrt(l.minor_m * l.minor_m + chi2_95 * s2);
    l.major50_m = std::sqrt(l.major50_m * l.major50_m + chi2_50 * s2);
    l.minor50_m = std::sqrt(l.minor50_m * l.minor50_m + chi2_50 * s2);
    l.time_s = t;
    l.unsure = true;
    return l;
}

/*!
 * Whether a fit's height contradicts the altimeter (c: the seeker's settings): beyond
 * HEIGHT_SIGMAS x its stated accuracy above it. An orbit far from the emitter swings its
 * Doppler by about f_d,max, which a near emitter only explains with the height run down
 * to a few metres, so below the altimeter only a height that low is refused: under
 * twice the height h at which an orbit centred on the emitter swings as far as the far
 * check's amplitude a, R sqrt(1 / a^2 - 1) (12 m for the default 25 m orbit). Strong
 * fast gusts, which the gust prior underrates, pull a fit over the emitter down to
 * 25-50 m from 100 m. Without a height prior every fit passes.
 */
inline bool height_agrees(const emitter_location& l, const seeker_config& c)
{
    constexpr double HEIGHT_SIGMAS = 2.5;
    const double s = c.locate_altitude_sigma_m;
    const double h0 = c.locate_altitude_m;
    if (!(s > 0.0 && std::isfinite(h0)))
        return true;
    const double a = std::clamp(c.far_amplitude(), 0.1, 0.999);
    const double swing_h = c.loiter_radius_m * std::sqrt(1.0 / (a * a) - 1.0);
    const double floor = std::min(h0 - HEIGHT_SIGMAS * s, 2.0 * swing_h);
    return l.altitude_m >= floor && l.altitude_m <= h0 + HEIGHT_SIGMAS * s;
}

//! A confirming fit's far excess under which a plane wave counts as plausible.
constexpr double PLANE_WAVE_EXCESS = 25.0;

/*!
 * Whether an emitter far away explains the honest fit l's data almost as well as l: a
 * plane wave from the best bearing, under the same gust prior, costs less than
 * PLANE_WAVE_EXCESS more (emitter_location::far_excess, in units of the noise
 * variance; unknown: no). Around the emitter the line of sight turns with the orbit and
 * no plane wave follows it; 1-3 km off, where slow strong gusts can give fits by the
 * vehicle that confirm each other, a plane wave does as well or better.
 */
inline bool far_is_plausible(const emitter_location& l)
{
    return l.far_excess < PLANE_WAVE_EXCESS;
}

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_ARRIVAL_MATH_H */
