/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * sample_clock: the receiver's clock from rx_time / rx_rate tags, the time of any sample
 * from the tag in force at it, and the stream's discontinuities (internal header; plain
 * C++, shared by doppler_estimator and its fuzz harness).
 */

#ifndef INCLUDED_RFSEEK_SAMPLE_CLOCK_H
#define INCLUDED_RFSEEK_SAMPLE_CLOCK_H

#include <gr-rfseek/api.h>
#include <cstdint>
#include <deque>

namespace gr {
namespace rfseek {

/*!
 * The time of sample k is t_a + (k - k_a) / r_a for the last anchor a at or before k.
 * Anchors come from rx_time tags (a time at a sample) and rx_rate tags (a new rate from a
 * sample on, the time there continued). An rx_time tag after the first that disagrees
 * with the sample count by half a sample or more is a discontinuity: samples were lost
 * (an overflow: the tag is later than the count says) or the clock was set back. UHD
 * tags the first sample after an overflow this way.
 */
class RFSEEK_API sample_clock
{
public:
    //! What an rx_time tag said about the stream.
    struct jump {
        bool discontinuity = false; //!< the tag disagrees with the sample count
        double samples = 0.0;       //!< samples missing (< 0: the clock went back)
        double seconds = 0.0;       //!< the same in seconds
    };

    explicit sample_clock(double rate_hz);

    //! rx_time (whole seconds, fraction) at sample `offset`. A tag before the last
    //! anchor, or with a non-finite time, is ignored (returns false in `accepted`).
    jump
    on_time(std::uint64_t offset, double secs, double frac, bool* accepted = nullptr);
    //! rx_rate from sample `offset` on; earlier samples keep their times. A rate that
    //! is not positive and finite, or a tag before the last anchor, is ignored.
    bool on_rate(std::uint64_t offset, double rate_hz);

    double time_of(std::uint64_t abs) const;
    double rate_at(std::uint64_t abs) const;
    //! Anchors are kept only for samples at or after `abs`.
    void forget_before(std::uint64_t abs);

    bool timed() const { return d_timed; }
    std::uint64_t discontinuities() const { return d_jumps; }
    std::size_t anchors() const { return d_anchors.size(); }

private:
    struct anchor {
        std::uint64_t offset;
        double secs, frac; // time = secs + frac (kept apart for precision)
        double rate;
    };
    const anchor& in_force(std::uint64_t abs) const;

    std::deque<anchor> d_anchors;
    bool d_timed = false;
    std::uint64_t d_jumps = 0;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_SAMPLE_CLOCK_H */
