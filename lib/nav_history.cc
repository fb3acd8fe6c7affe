/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * nav_history: heading reports on the measurements' clock (nav_history.h).
 */

#include "nav_history.h"
#include <gr-rfseek/world.h>
#include <algorithm>
#include <cmath>

namespace gr {
namespace rfseek {

namespace {
// A report on the measurements' clock is within 5 s of the latest window: behind it by a
// late link's delay, ahead of it by what a slow receiver has not yet processed.
bool on_our_clock(double behind_s) { return std::abs(behind_s) <= 5.0; }
} // namespace

void nav_history::insert(double t, double heading)
{
    const entry e{ t, heading, d_order++ };
    // Kept in time order (an out-of-order report goes where it belongs); ties by arrival.
    auto it = std::upper_bound(d_reports.begin(),
                               d_reports.end(),
                               t,
                               [](double v, const entry& x) { return v < x.t; });
    d_reports.insert(it, e);
    while (d_reports.size() > 256 ||
           (d_reports.size() > 2 && d_reports.back().t - d_reports.front().t > 30.0))
        d_reports.pop_front();
}

void nav_history::report(double heading_rad, bool has_time, double time)
{
    if (!std::isfinite(heading_rad))
        return;
    d_timed_last = has_time && std::isfinite(time);
    if (!d_timed_last) {
        if (!d_have_meas) {
            d_have_pending = true; // timed by the first measurement
            d_pending_heading = heading_rad;
            return;
        }
        insert(d_latest, heading_rad);
        return;
    }
    d_out_of_range =
        d_have_meas && !on_our_clock(d_latest - time) ? d_out_of_range + 1 : 0;
    if (!d_foreign && d_out_of_range >= 5) {
        d_foreign = true;
        d_reports.clear(); // (timed as if on the measurements' clock: they were not)
    }
    if (!d_foreign) {
        insert(time, heading_rad);
        return;
    }
    d_diffs.push_back(d_latest - time);
    if (d_diffs.size() > 64)
        d_diffs.pop_front();
    const double offset = *std::min_element(d_diffs.begin(), d_diffs.end());
    insert(time + offset, heading_rad);
}

void nav_history::measured(double time)
{
    if (!std::isfinite(time))
        return;
    const bool first = !d_have_meas;
    d_latest = d_have_meas ? std::max(d_latest, time) : time;
    d_have_meas = true;
    // Timed reports before the first window, on another clock: the newest is taken as
    // now, and the others keep their spacing from it.
    // (Reports before the first window can be ahead of it by the receiver's latency and
    // more: only a clock far off is foreign here.)
    if (first && !d_reports.empty() && std::abs(time - d_reports.back().t) > 5.0) {
        d_foreign = true;
        const double shift = time - d_reports.back().t;
        d_diffs.push_back(shift);
        for (auto& e : d_reports)
            e.t += shift;
    }
    if (d_have_pending) {
        d_have_pending = false;
        insert(d_latest, d_pending_heading);
    }
}

nav_history::pick nav_history::at(double time) const
{
    pick p;
    if (d_reports.empty() || !std::isfinite(time))
        return p;
    // The first report after t, and the one before it.
    auto after = std::upper_bound(d_reports.begin(),
                                  d_reports.end(),
                                  time,
                                  [](double v, const entry& x) { return v < x.t; });
    const entry* hi = after != d_reports.end() ? &*after : nullptr;
    const entry* lo = nullptr;
    if (after != d_reports.begin()) {
        // Of the reports at the same time before t, the latest to arrive.
        auto b = std::prev(after);
        lo = &*b;
        for (auto it = b; it->t == b->t; --it) {
            if (it->order > lo->order)
                lo = &*it;
            if (it == d_reports.begin())
                break;
        }
    }
    if (lo && hi && time - lo->t <= d_max_gap && hi->t - time <= d_max_gap &&
        hi->t > lo->t) {
        const double u = (time - lo->t) / (hi->t - lo->t);
        p.found = true;
        p.heading_rad =
            world::wrap(lo->heading + u * world::wrap(hi->heading - lo->heading));
        p.offset_s = u < 0.5 ? lo->t - time : hi->t - time;
        return p;
    }
    const entry* n = nullptr;
    if (lo && time - lo->t <= d_max_gap)
        n = lo;
    if (hi && hi->t - time <= d_max_gap && (!n || hi->t - time < time - n->t))
        n = hi;
    if (!n)
        return p;
    p.found = true;
    p.heading_rad = n->heading;
    p.offset_s = n->t - time;
    // After the latest report (a late link): carried on at the turn rate of the two
    // latest reports, for at most half a second.
    if (n == lo && !hi && after != d_reports.begin()) {
        auto b = std::prev(after);
        while (b != d_reports.begin() && std::prev(b)->t == lo->t)
            --b;
        if (b != d_reports.begin()) {
            const entry& prev = *std::prev(b);
            const double dt = lo->t - prev.t;
            if (dt > 0.0 && dt <= d_max_gap) {
                const double rate =
                    std::clamp(world::wrap(lo->heading - prev.heading) / dt, -1.0, 1.0);
                p.heading_rad =
                    world::wrap(lo->heading + rate * std::min(time - lo->t, 0.5));
            }
        }
    }
    return p;
}

} // namespace rfseek
} // namespace gr
