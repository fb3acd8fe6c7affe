/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * burst_detector: energy gating of a pulsed beacon (noise floor, threshold, change
 * point).
 */

#include <gr-rfseek/burst_detector.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gr {
namespace rfseek {

burst_detector::burst_detector(double threshold_db,
                               std::uint64_t holdoff,
                               int average_len,
                               int floor_block,
                               int floor_blocks)
    : d_holdoff(holdoff), d_m(average_len), d_block(floor_block), d_blocks(floor_blocks)
{
    set_threshold_db(threshold_db);
    if (holdoff < 1)
        throw std::invalid_argument("burst_detector: holdoff = 0: must be >= 1 sample");
    if (average_len < 8 || average_len > (1 << 20))
        throw std::invalid_argument(
            "burst_detector: average_len = " + std::to_string(average_len) +
            ": must be in [8, 1048576]");
    if (floor_block < 16 || floor_blocks < 2)
        throw std::invalid_argument("burst_detector: floor_block must be >= 16 and "
                                    "floor_blocks >= 2");
    d_ring.assign(d_m, 0.0);
}

void burst_detector::set_threshold_db(double threshold_db)
{
    if (!(threshold_db > 0.0 && threshold_db <= 60.0))
        throw std::invalid_argument(
            "burst_detector: threshold_db = " + std::to_string(threshold_db) +
            ": must be in (0, 60]");
    d_threshold_db = threshold_db;
    d_thr_lin = std::pow(10.0, threshold_db / 10.0);
    d_rearm_lin = std::pow(10.0, threshold_db / 20.0);
}

void burst_detector::push(const std::complex<float>* x,
                          std::size_t n,
                          std::uint64_t offset,
                          std::vector<std::uint64_t>& starts)
{
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint64_t k = offset + i;
        double p = std::norm(std::complex<double>(x[i]));
        if (!std::isfinite(p))
            p = 0.0; // a bad sample neither triggers nor poisons the floor
        d_sum += p - d_ring[d_ring_pos];
        d_ring[d_ring_pos] = p;
        d_ring_pos = (d_ring_pos + 1) % d_m;
        ++d_seen;

        d_block_acc += p;
        if (++d_block_fill == d_block) {
            d_block_means.push_back(d_block_acc / d_block);
            if (static_cast<int>(d_block_means.size()) > d_blocks)
                d_block_means.erase(d_block_means.begin());
            d_floor = *std::min_element(d_block_means.begin(), d_block_means.end());
            d_block_acc = 0.0;
            d_block_fill = 0;
        }
        // Armed once the floor rests on a few blocks and the average is full.
        if (d_block_means.size() < 2 || d_seen < static_cast<std::uint64_t>(d_m) ||
            !(d_floor > 0.0))
            continue;
        if (k < d_rest_until)
            continue;
        const bool above = d_sum / d_m > d_thr_lin * d_floor;
        if (d_need_quiet) {
            // Re-arm only once the last burst has left the average (below the level
            // halfway, in dB, to the threshold: hysteresis against re-triggering on the
            // burst's tail), and only after the rest.
            d_need_quiet = d_sum / d_m > d_rearm_lin * d_floor;
            continue;
        }
        if (!above)
            continue;
        // Change point over the last d_m powers: the start maximises the excess over tau.
        const double tau = d_thr_lin * d_floor;
        double acc = 0.0, best = -1e300;
        std::size_t best_back = 0;
        for (int b = 0; b < d_m; ++b) {
            const std::size_t idx = (d_ring_pos + d_m - 1 - b) % d_m;
            acc += d_ring[idx] - tau;
            if (acc > best) {
                best = acc;
                best_back = b;
            }
        }
        // Not back into the rest of the previous burst: starts increase by >= holdoff
        // (found by fuzzing: with holdoff < average_len a start could repeat or go back).
        const std::uint64_t start = std::max(k - best_back, d_rest_until);
        starts.push_back(start);
        d_rest_until = start + d_holdoff;
        d_need_quiet = true;
    }
}

} // namespace rfseek
} // namespace gr
