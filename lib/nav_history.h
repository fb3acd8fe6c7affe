/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * nav_history: the vehicle's heading reports, timed on the measurements' clock, and the
 * heading at a window's time (internal header; plain C++, used by seeking_controller).
 */

#ifndef INCLUDED_RFSEEK_NAV_HISTORY_H
#define INCLUDED_RFSEEK_NAV_HISTORY_H

#include <gr-rfseek/api.h>
#include <cmath>
#include <cstdint>
#include <deque>

namespace gr {
namespace rfseek {

/*!
 * A report's time on the measurements' clock:
 *  - its "time", when that is the measurements' clock: within 5 s of the latest
 *    measurement's time when it arrives (a simulated or rehearsed world, a radio and a
 *    link on one host clock); 5 reports in a row further off make the clock foreign;
 *  - its "time" moved by the clocks' offset otherwise, learned as the least difference
 *    (latest measurement's time at arrival - report's time) over the last 64 reports:
 *    the fastest report sets the offset, and a late or out-of-order one is put back
 *    where it belongs. (A delay common to every report cannot be told from the offset.)
 *  - without a "time", the latest measurement's time when it arrives (its arrival).
 * A window at t takes the heading of the report nearest in time, interpolated between
 * the two that bracket t when both are within max_gap, carried on at the turn rate of
 * the two latest (at most 1 rad/s, for at most 0.5 s) when t is after the latest; with
 * none within max_gap of t it has none.
 */
class RFSEEK_API nav_history
{
public:
    explicit nav_history(double max_gap_s = 1.0) : d_max_gap(max_gap_s) {}

    //! A report; has_time says whether time is its own "time" field.
    void report(double heading_rad, bool has_time, double time);
    //! A measurement's window time (call for each, before at()).
    void measured(double time);

    struct pick {
        bool found = false;
        double heading_rad = 0.0;
        double offset_s = 0.0; //!< report time - window time (the nearest report used)
    };
    pick at(double time) const;

    bool any() const { return !d_reports.empty() || d_have_pending; }
    //! The latest report to arrive had a time of its own (a late one can be waited for).
    bool timed() const { return d_timed_last; }
    //! The latest report's time (-inf: none).
    double newest() const { return d_reports.empty() ? -HUGE_VAL : d_reports.back().t; }
    //! The latest measurement's time (-inf: none).
    double latest_measured() const { return d_have_meas ? d_latest : -HUGE_VAL; }
    //! The reports' clock is not the measurements' (their offset is learned).
    bool foreign_clock() const { return d_foreign; }
    double max_gap_s() const { return d_max_gap; }

private:
    struct entry {
        double t, heading;
        std::uint64_t order; // arrival
    };
    void insert(double t, double heading);

    double d_max_gap;
    std::deque<entry> d_reports; // by time
    std::deque<double> d_diffs;  // (latest meas - report time), foreign clock
    bool d_have_meas = false, d_foreign = false, d_have_pending = false;
    bool d_timed_last = false;
    int d_out_of_range = 0; // timed reports in a row off the measurements' clock
    double d_latest = 0.0;
    double d_pending_heading = 0.0; // a report before any measurement, without a time
    std::uint64_t d_order = 0;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_NAV_HISTORY_H */
