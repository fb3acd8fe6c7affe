/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * outlier_filter: eq. 4 with lock, re-lock and an SNR gate (see outlier_filter.h).
 */

#include "outlier_filter.h"
#include <algorithm>
#include <cmath>

namespace gr {
namespace rfseek {

outlier_filter::outlier_filter(double threshold_hz,
                               bool literal,
                               int lock_count,
                               int relock_count,
                               double min_snr_db)
    : d_thr(threshold_hz),
      d_literal(literal),
      d_lock(std::max(1, lock_count)),
      d_relock(std::max(1, relock_count)),
      d_min_snr(min_snr_db)
{
}

bool outlier_filter::agree(int count) const
{
    if (static_cast<int>(d_candidates.size()) < count)
        return false;
    const auto first = d_candidates.end() - count;
    const auto mm = std::minmax_element(first, d_candidates.end());
    return *mm.second - *mm.first < d_thr;
}

outlier_filter::result outlier_filter::push(double f, double snr_db)
{
    result r;
    if (d_literal) {
        // As printed: the first value is taken, each value is compared with the previous
        // raw one and replaced by it when they differ by the threshold or more.
        if (!d_locked) {
            d_locked = true;
            d_last = f;
            r.accepted = r.locked = true;
            r.value = f;
            return r;
        }
        const double ref = d_last;
        d_last = f;
        r.locked = true;
        r.accepted = std::abs(f - ref) < d_thr;
        r.value = r.accepted ? f : ref;
        return r;
    }
    const bool gated = !(snr_db >= d_min_snr); // NaN SNR is gated too
    if (d_locked && !gated && std::abs(f - d_last) < d_thr) {
        d_last = f;
        d_candidates.clear();
        r.accepted = r.locked = true;
        r.value = f;
        return r;
    }
    if (!gated) {
        d_candidates.push_back(f);
        const int keep = std::max(d_lock, d_relock);
        while (static_cast<int>(d_candidates.size()) > keep)
            d_candidates.pop_front();
        if (agree(d_locked ? d_relock : d_lock)) {
            // Agreeing candidates: (re-)lock on the newest of them.
            d_locked = true;
            d_last = f;
            d_candidates.clear();
            r.accepted = r.locked = true;
            r.value = f;
            return r;
        }
    }
    r.locked = d_locked;
    r.value = d_last;
    return r;
}

} // namespace rfseek
} // namespace gr
