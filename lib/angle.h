/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * angle: the angle wrap of the arrival code (overflight detector, homing seeker).
 * Internal to the library.
 */

#ifndef INCLUDED_RFSEEK_ANGLE_H
#define INCLUDED_RFSEEK_ANGLE_H

#include <cmath>

namespace gr {
namespace rfseek {

//! a wrapped to (-pi, pi] by the IEEE remainder (exact).
inline double wrap_remainder(double a)
{
    a = std::remainder(a, 2.0 * M_PI);
    return a <= -M_PI ? a + 2.0 * M_PI : a;
}

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_ANGLE_H */
