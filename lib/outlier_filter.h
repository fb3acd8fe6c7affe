/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * outlier_filter: the paper's eq. 4 (outlier rejection of the measured frequency), shared
 * by every strategy that uses frequencies. Internal to the library.
 *
 * Default (docs/design.md item 5, sturdier form of issue 9): a value is accepted when it
 * is within the threshold of the last *accepted* value. There is no unconditional first
 * value: the filter locks only once lock_count consecutive candidates agree (their spread
 * is below the threshold), and it re-locks the same way (relock_count) when the accepted
 * value has gone stale, e.g. after a CFO jump. Measurements whose estimated SNR is below
 * min_snr_db are not candidates at all. literal = true keeps eq. 4 as printed (compare
 * with the previous raw value, first value accepted, substitute the reference).
 */

#ifndef INCLUDED_RFSEEK_OUTLIER_FILTER_H
#define INCLUDED_RFSEEK_OUTLIER_FILTER_H

#include <gr-rfseek/api.h>
#include <deque>

namespace gr {
namespace rfseek {

class RFSEEK_API outlier_filter
{
public:
    struct result {
        bool accepted = false; //!< this value was let through
        bool locked = false;   //!< the filter has a reference value
        double value = 0.0;    //!< eq. 4 output: the value, or the reference it replaces
    };

    outlier_filter(double threshold_hz,
                   bool literal,
                   int lock_count,
                   int relock_count,
                   double min_snr_db);

    //! One valid measurement (frequency and the estimator's SNR) in.
    result push(double freq_hz, double snr_db);
    bool locked() const { return d_locked; }
    double reference_hz() const { return d_last; }

private:
    bool agree(int count) const; // the last `count` candidates lie within the threshold

    double d_thr;
    bool d_literal;
    int d_lock, d_relock;
    double d_min_snr;
    bool d_locked = false;
    double d_last = 0.0;
    std::deque<double> d_candidates;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_OUTLIER_FILTER_H */
