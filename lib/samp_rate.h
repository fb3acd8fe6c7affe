/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * A sample rate's check, and its change with the band rebuilt at the new rate or
 * nothing changed: shared by tone_estimator and tone_detector (internal header).
 */

#ifndef INCLUDED_RFSEEK_SAMP_RATE_H
#define INCLUDED_RFSEEK_SAMP_RATE_H

#include <cmath>
#include <stdexcept>
#include <string>

namespace gr {
namespace rfseek {

//! std::invalid_argument "<who>: samp_rate = x: must be > 0" unless positive and finite.
inline void check_samp_rate(const char* who, double samp_rate_hz)
{
    if (!(samp_rate_hz > 0.0) || !std::isfinite(samp_rate_hz))
        throw std::invalid_argument(std::string(who) + ": samp_rate = " +
                                    std::to_string(samp_rate_hz) + ": must be > 0");
}

//! fs = samp_rate_hz, then rebuild() (what depends on it); if either throws, fs is left
//! as it was and the exception goes on.
template <typename Rebuild>
void change_samp_rate(const char* who, double& fs, double samp_rate_hz, Rebuild&& rebuild)
{
    check_samp_rate(who, samp_rate_hz);
    const double old = fs;
    fs = samp_rate_hz;
    try {
        rebuild();
    } catch (...) {
        fs = old;
        throw;
    }
}

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_SAMP_RATE_H */
