/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * sample_clock: anchors from rx_time / rx_rate tags (sample_clock.h).
 */

#include "sample_clock.h"
#include <cmath>

namespace gr {
namespace rfseek {

namespace {
// Samples from anchor offset a to b, signed, in double.
double samples_between(std::uint64_t a, std::uint64_t b)
{
    return b >= a ? static_cast<double>(b - a) : -static_cast<double>(a - b);
}
} // namespace

sample_clock::sample_clock(double rate_hz)
{
    d_anchors.push_back(
        { 0, 0.0, 0.0, rate_hz > 0.0 && std::isfinite(rate_hz) ? rate_hz : 1.0 });
}

const sample_clock::anchor& sample_clock::in_force(std::uint64_t abs) const
{
    for (auto it = d_anchors.rbegin(); it != d_anchors.rend(); ++it)
        if (it->offset <= abs)
            return *it;
    return d_anchors.front(); // before the oldest anchor kept: extrapolated back
}

double sample_clock::time_of(std::uint64_t abs) const
{
    const anchor& a = in_force(abs);
    return a.secs + (a.frac + samples_between(a.offset, abs) / a.rate);
}

double sample_clock::rate_at(std::uint64_t abs) const { return in_force(abs).rate; }

sample_clock::jump
sample_clock::on_time(std::uint64_t offset, double secs, double frac, bool* accepted)
{
    jump j;
    const anchor& last = d_anchors.back();
    const bool ok = std::isfinite(secs) && std::isfinite(frac) &&
                    std::isfinite(secs + frac) && offset >= last.offset;
    if (accepted)
        *accepted = ok;
    if (!ok)
        return j;
    if (d_timed) {
        // The tag's time less the time the count gives it, computed in differences
        // (exact for whole seconds) so that an epoch of 1.7e9 s keeps sub-sample
        // precision.
        const double dt = (secs - last.secs) + (frac - last.frac) -
                          samples_between(last.offset, offset) / last.rate;
        j.samples = dt * last.rate;
        j.seconds = dt;
        j.discontinuity = !(std::abs(j.samples) < 0.5);
        if (j.discontinuity)
            ++d_jumps;
    }
    const double rate = last.rate;
    if (offset == last.offset)
        d_anchors.pop_back(); // the newer tag at the same sample wins
    d_anchors.push_back({ offset, secs, frac, rate });
    d_timed = true;
    return j;
}

bool sample_clock::on_rate(std::uint64_t offset, double rate_hz)
{
    const anchor last = d_anchors.back();
    if (!(rate_hz > 0.0) || !std::isfinite(rate_hz) || offset < last.offset)
        return false;
    const double frac = last.frac + samples_between(last.offset, offset) / last.rate;
    if (offset == last.offset)
        d_anchors.pop_back();
    d_anchors.push_back({ offset, last.secs, frac, rate_hz });
    return true;
}

void sample_clock::forget_before(std::uint64_t abs)
{
    while (d_anchors.size() > 1 && d_anchors[1].offset <= abs)
        d_anchors.pop_front();
}

} // namespace rfseek
} // namespace gr
