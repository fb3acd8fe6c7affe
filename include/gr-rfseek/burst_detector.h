/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * burst_detector: finds the start of each beacon burst in a continuous received stream
 * from its power over the noise floor (energy gating), for a real pulsed beacon as in the
 * paper (N samples every T_slot). Plain C++ (no GNU Radio types).
 */

#ifndef INCLUDED_RFSEEK_BURST_DETECTOR_H
#define INCLUDED_RFSEEK_BURST_DETECTOR_H

#include <gr-rfseek/api.h>
#include <complex>
#include <cstdint>
#include <vector>

namespace gr {
namespace rfseek {

/*!
 * The noise floor is the smallest mean power of the last floor_blocks blocks of
 * floor_block samples (bursts raise some blocks, never all). A burst is detected when the
 * power averaged over average_len samples exceeds the floor by threshold_db; its start is
 * the change point of the power over the last average_len samples (the maximum of the
 * cumulative excess over the threshold level, summed back from the detection).
 * After a detection the detector rests for holdoff samples from the burst start and
 * until the average has fallen below the level halfway (in dB) to the threshold; a start
 * is never placed inside that rest, so starts increase by at least holdoff. A start may
 * lie up to average_len - 1 samples before the chunk in which it is detected.
 */
class RFSEEK_API burst_detector
{
public:
    /*!
     * \param threshold_db detection level over the noise floor (dB, > 0)
     * \param holdoff samples after a burst start before the next may be found (>= 1)
     * \param average_len samples in the detection average (>= 8)
     * \param floor_block, floor_blocks noise-floor blocks (>= 16 samples, >= 2 blocks)
     */
    burst_detector(double threshold_db = 2.0,
                   std::uint64_t holdoff = 1000,
                   int average_len = 256,
                   int floor_block = 512,
                   int floor_blocks = 16);

    //! Feed n samples whose first has absolute index offset; appends burst starts found.
    void push(const std::complex<float>* x,
              std::size_t n,
              std::uint64_t offset,
              std::vector<std::uint64_t>& starts);

    //! Current noise-floor estimate (mean power per sample; 0 before the first blocks).
    double noise_floor() const { return d_floor; }
    double threshold_db() const { return d_threshold_db; }
    void set_threshold_db(double threshold_db);

private:
    double d_threshold_db, d_thr_lin, d_rearm_lin;
    std::uint64_t d_holdoff;
    int d_m, d_block, d_blocks;
    std::vector<double> d_ring; // last d_m powers
    std::size_t d_ring_pos = 0;
    double d_sum = 0.0;
    std::uint64_t d_seen = 0;
    std::vector<double> d_block_means;
    double d_block_acc = 0.0;
    int d_block_fill = 0;
    double d_floor = 0.0;
    std::uint64_t d_rest_until = 0;
    bool d_need_quiet = false;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_BURST_DETECTOR_H */
