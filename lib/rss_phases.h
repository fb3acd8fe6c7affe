/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rss_phases: the two measurements behind `rss_baseline` (docs/seeker.md), our
 * reconstruction of the multi-phase RSS method of Wadhwa, Madhow, Hespanha and Sadler
 * ("Following an RF trail to its source", Allerton 2011). Both use received power only.
 * - estimate_direction: from the powers of a scan circle (RSS in every direction), the
 *   line-of-sight axis (where the power fades slowest) and the way along it (the
 *   circle's power trend across its diameter);
 * - run_monitor: along a run, long-term averages of the power over blocks; the run ends
 *   when the last window's average falls below the window before it.
 * Internal to the library; tested on synthetic power tracks in lib/qa/qa_rss.cc.
 */

#ifndef INCLUDED_RFSEEK_RSS_PHASES_H
#define INCLUDED_RFSEEK_RSS_PHASES_H

#include <gr-rfseek/api.h>
#include <cstddef>
#include <vector>

namespace gr {
namespace rfseek {
namespace rss {

//! What one scan circle says about the emitter's direction.
struct RFSEEK_API direction_estimate {
    bool valid = false;
    double axis_rad = 0.0; //!< heading where the power fades slowest (the LOS, mod pi)
    double way_rad = 0.0;  //!< axis_rad or axis_rad + pi: the one the power rises along
    double slow_rate_db = 0.0;    //!< the fading rate at axis_rad (median |p[k+3]-p[k]|)
    double typical_rate_db = 0.0; //!< the median fading rate around the circle
    double trend_db_per_m = 0.0;  //!< the power's slope across the circle, toward way_rad
};

//! The direction from a scan circle. power_db[k] (NaN: missing) was received at
//! measured heading heading_rad[k] on a circle of radius_m flown with turning sense
//! `sense` (+1 counter-clockwise, -1 clockwise), so the vehicle sat at position angle
//! heading - sense pi/2 from the circle's centre. The axis is the heading whose 15-slot
//! window fades least (median |p[k+3] - p[k]|); the way along it follows the first
//! harmonic of the power over the position angle (the mean-power gradient across the
//! circle's diameter). Needs at least 30 finite powers, else valid = false.
RFSEEK_API direction_estimate estimate_direction(const std::vector<double>& power_db,
                                                 const std::vector<double>& heading_rad,
                                                 double sense,
                                                 double radius_m);

//! Long-term averages of the power along a straight run. Each block of block_slots
//! measurements is averaged (in dB; missing ones skipped, a block with fewer than a
//! quarter of them valid is not counted); once 2 x window blocks are in, the run should
//! end when the mean of the last `window` blocks is more than fall_db below the mean of
//! the `window` blocks before.
class RFSEEK_API run_monitor
{
public:
    //! Throws std::invalid_argument naming the parameter when out of range.
    run_monitor(int block_slots, int window, double fall_db);
    void reset();
    //! Add one slot's power (NaN: missing). True when the run should end.
    bool add(double power_db);
    //! Blocks averaged since the last reset.
    std::size_t blocks() const { return d_means.size(); }
    //! The last comparison: later window's mean minus the earlier's (dB; NaN: none yet).
    double last_change_db() const { return d_change; }

private:
    int d_block, d_window;
    double d_fall;
    int d_in_block = 0, d_valid = 0;
    double d_sum = 0.0;
    double d_change;
    std::vector<double> d_means;
};

} // namespace rss
} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_RSS_PHASES_H */
