/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * heading_filter: the heading read, smoothed for dead reckoning (the homing seeker's
 * loiter, seeker_config::loiter_heading_gain). An alpha-beta filter on the heading and
 * its rate: a turn at a constant rate is followed without lag, white read noise of std
 * sigma leaves sigma sqrt(noise_ratio(gain)). Internal to the library.
 */

#ifndef INCLUDED_RFSEEK_HEADING_FILTER_H
#define INCLUDED_RFSEEK_HEADING_FILTER_H

#include "angle.h"
#include <cmath>

namespace gr {
namespace rfseek {

class heading_filter
{
public:
    //! gain: alpha in (0, 1]; beta = alpha^2 / (2 - alpha) (Benedict-Bordner). 1: the
    //! read itself.
    explicit heading_filter(double gain) : d_alpha(gain), d_beta(beta_of(gain)) {}

    //! The rate gain that goes with alpha (Benedict-Bordner).
    static double beta_of(double alpha) { return alpha * alpha / (2.0 - alpha); }

    //! Starts over at a read (the rate taken as 0).
    void reset(double heading_rad)
    {
        d_heading = heading_rad;
        d_rate = 0.0;
        d_started = std::isfinite(heading_rad);
    }

    /*!
     * The filtered heading after a read dt_s after the previous one. A read that is not
     * finite is skipped (the prediction is returned; before any read, that read); before
     * any read, or after a gap of more than MAX_GAP_S, the filter starts over at the
     * read.
     */
    double update(double heading_rad, double dt_s)
    {
        if (!std::isfinite(heading_rad))
            return d_started ? predict(dt_s) : heading_rad;
        if (d_alpha >= 1.0) // the read itself, bit for bit
            return heading_rad;
        if (!d_started || !(dt_s > 0.0) || dt_s > MAX_GAP_S) {
            reset(heading_rad);
            return d_heading;
        }
        const double predicted = d_heading + d_rate * dt_s;
        const double r = wrap_remainder(heading_rad - predicted);
        d_heading = wrap_remainder(predicted + d_alpha * r);
        d_rate += d_beta * r / dt_s;
        return d_heading;
    }

    //! Steady-state variance of the filtered heading over that of white read noise.
    static double noise_ratio(double gain)
    {
        const double a = gain, b = beta_of(gain);
        return (2.0 * a * a + 2.0 * b - 3.0 * a * b) / (a * (4.0 - 2.0 * a - b));
    }

    static constexpr double MAX_GAP_S = 1.0;

private:
    double predict(double dt_s)
    {
        if (dt_s > 0.0 && dt_s <= MAX_GAP_S)
            d_heading = wrap_remainder(d_heading + d_rate * dt_s);
        return d_heading;
    }

    double d_alpha, d_beta;
    double d_heading = 0.0, d_rate = 0.0;
    bool d_started = false;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_HEADING_FILTER_H */
