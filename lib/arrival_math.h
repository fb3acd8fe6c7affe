/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * arrival_math: the robust statistics and linear solves of the overflight detector and
 * the emitter locator (Eigen). Internal to the library.
 */

#ifndef INCLUDED_RFSEEK_ARRIVAL_MATH_H
#define INCLUDED_RFSEEK_ARRIVAL_MATH_H

#include <Eigen/Dense>
#include <algorithm>
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

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_ARRIVAL_MATH_H */
