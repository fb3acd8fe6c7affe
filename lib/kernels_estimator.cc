/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The estimator's kernels: the FFT peak search and the demodulated dot product
 * (kernels.h).
 */

#include "kernels.h"
#include "kernels_vec.h"
#include <cmath>
#include <cstring>

namespace gr {
namespace rfseek {
namespace detail {

namespace {

// The element of its block of 8 that lane l (mod 8) of the running maxima holds.
const std::uint32_t LANE_ELEMENT[8] = { 0, 4, 1, 5, 2, 6, 3, 7 };

// The reduction shared by both widths: per parity (even, odd blocks) and lane, the
// running maximum, its block and the float sum; then the tail. Returns the peak.
peak reduce_lanes(const float (&best)[2][8],
                  const float (&sum)[2][8],
                  const int (&best_block)[2][8],
                  const std::complex<float>* x,
                  std::uint32_t blocks,
                  std::uint32_t n)
{
    peak r{ 0, -1.0f, 0.0 };
    for (int s = 0; s < 2; ++s) {
        for (int lane = 0; lane < 8; ++lane) {
            r.total += sum[s][lane];
            if (best[s][lane] < 0.0f)
                continue; // no block of this parity
            const std::uint32_t idx =
                static_cast<std::uint32_t>(best_block[s][lane]) * 8 + LANE_ELEMENT[lane];
            if (best[s][lane] > r.value || (best[s][lane] == r.value && idx < r.index)) {
                r.value = best[s][lane];
                r.index = idx;
            }
        }
    }
    for (std::uint32_t k = blocks * 8; k < n; ++k) {
        const float p = std::norm(x[k]);
        r.total += p;
        if (p > r.value) {
            r.value = p;
            r.index = k;
        }
    }
    return r;
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define RFSEEK_WIDE_PEAK_SEARCH 1
// AVX-512: both parities in one 16-lane vector, a pair of blocks per step.
__attribute__((target("avx512f"))) peak peak_search_wide(const std::complex<float>* x,
                                                         std::uint32_t n)
{
    const float* f = reinterpret_cast<const float*>(x);
    const std::uint32_t blocks = n / 8;
    // Two independent sets of running maxima and sums (even and odd blocks), so the
    // compare-and-select chains overlap instead of waiting on each other; both sets in
    // one 16-lane vector (lanes 0-7 even blocks, 8-15 odd), a pair of blocks per step.
    v16f best16 = { -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1 };
    v16i block16 = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    v16f sum16 = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    // Squares, pair sums within pairs of floats, then a blend: lane l (mod 8) holds the
    // power of complex element LANE_ELEMENT[l % 8] of its block of 8.
    const v16i swap_pairs = { 1, 0, 3, 2, 5, 4, 7, 6, 9, 8, 11, 10, 13, 12, 15, 14 };
    const v16i take_odd_from_hi = { 0,  9,  2,  11, 4,  13, 6,  15,
                                    16, 25, 18, 27, 20, 29, 22, 31 };
    auto step = [&](std::uint32_t blk, v16f a, v16f b) {
        a *= a;
        b *= b;
        a += __builtin_shuffle(a, swap_pairs);
        b += __builtin_shuffle(b, swap_pairs);
        const v16f p = __builtin_shuffle(a, b, take_odd_from_hi);
        sum16 += p;
        const v16i gt = p > best16;
        best16 = gt ? p : best16;
        const int e = static_cast<int>(blk), o = e + 1;
        const v16i bb = { e, e, e, e, e, e, e, e, o, o, o, o, o, o, o, o };
        block16 = gt ? bb : block16;
    };
    std::uint32_t b = 0;
    for (; b + 2 <= blocks; b += 2) {
        v16f a, c;
        std::memcpy(&a, f + 16 * b, sizeof(a));
        std::memcpy(&c, f + 16 * b + 16, sizeof(c));
        step(b, a, c);
    }
    if (b < blocks) {
        // The last (even) block alone: the odd half keeps its state.
        v16f a = {}, c = {};
        std::memcpy(&a, f + 16 * b, 16 * sizeof(float));
        const v16f best_keep = best16, sum_keep = sum16;
        const v16i block_keep = block16;
        step(b, a, c);
        const v16i even = { -1, -1, -1, -1, -1, -1, -1, -1, 0, 0, 0, 0, 0, 0, 0, 0 };
        best16 = even ? best16 : best_keep;
        sum16 = even ? sum16 : sum_keep;
        block16 = even ? block16 : block_keep;
    }
    // Out through memory in one go (indexing the vectors would keep them in memory
    // during the loop).
    float best[2][8], sum[2][8];
    int best_block[2][8];
    std::memcpy(best, &best16, sizeof(best));
    std::memcpy(sum, &sum16, sizeof(sum));
    std::memcpy(best_block, &block16, sizeof(best_block));
    return reduce_lanes(best, sum, best_block, x, blocks, n);
}
#endif

// AVX2 and the baseline: the same lanes, the same float operations in the same order,
// as two 8-lane vectors per quantity (the 16-lane form splits into halves that GCC
// shuffled through memory, ten times slower without AVX-512).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
peak peak_search_narrow(const std::complex<float>* x, std::uint32_t n)
{
    const float* f = reinterpret_cast<const float*>(x);
    const std::uint32_t blocks = n / 8;
    v8f best_e = { -1, -1, -1, -1, -1, -1, -1, -1 }, best_o = best_e;
    v8i block_e = { 0, 0, 0, 0, 0, 0, 0, 0 }, block_o = block_e;
    v8f sum_e = { 0, 0, 0, 0, 0, 0, 0, 0 }, sum_o = sum_e;
    const v8i swap_pairs = { 1, 0, 3, 2, 5, 4, 7, 6 };
    const v8i take_odd_from_hi = { 0, 9, 2, 11, 4, 13, 6, 15 };
    // Named accumulators per parity (an indexed array of vectors would live in memory).
    auto step = [&](std::uint32_t blk, v8f& best, v8f& sum, v8i& block) {
        v8f lo, hi;
        std::memcpy(&lo, f + 16 * blk, sizeof(lo));
        std::memcpy(&hi, f + 16 * blk + 8, sizeof(hi));
        lo *= lo;
        hi *= hi;
        lo += __builtin_shuffle(lo, swap_pairs);
        hi += __builtin_shuffle(hi, swap_pairs);
        const v8f p = __builtin_shuffle(lo, hi, take_odd_from_hi);
        sum += p;
        const v8i gt = p > best;
        best = gt ? p : best;
        const int e = static_cast<int>(blk);
        const v8i bb = { e, e, e, e, e, e, e, e };
        block = gt ? bb : block;
    };
    std::uint32_t b = 0;
    for (; b + 2 <= blocks; b += 2) {
        step(b, best_e, sum_e, block_e);
        step(b + 1, best_o, sum_o, block_o);
    }
    if (b < blocks)
        step(b, best_e, sum_e, block_e);
    float best_out[2][8], sum_out[2][8];
    int block_out[2][8];
    std::memcpy(best_out[0], &best_e, sizeof(best_out[0]));
    std::memcpy(best_out[1], &best_o, sizeof(best_out[1]));
    std::memcpy(sum_out[0], &sum_e, sizeof(sum_out[0]));
    std::memcpy(sum_out[1], &sum_o, sizeof(sum_out[1]));
    std::memcpy(block_out[0], &block_e, sizeof(block_out[0]));
    std::memcpy(block_out[1], &block_o, sizeof(block_out[1]));
    return reduce_lanes(best_out, sum_out, block_out, x, blocks, n);
}

} // namespace

peak peak_search(const std::complex<float>* x, std::uint32_t n, int width)
{
#ifdef RFSEEK_WIDE_PEAK_SEARCH
    static const bool wide = have_avx512f();
    if (width != 8 && wide)
        return peak_search_wide(x, n);
#else
    (void)width;
#endif
    return peak_search_narrow(x, n);
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
std::complex<double>
demod_dot(const std::complex<float>* x,
          std::uint32_t n,
          const float* a,
          const float* br,
          const float* bi)
{
    const float* f = reinterpret_cast<const float*>(x);
    // Vector j of 8 complex: lanes 0-7 from the first operand; j + 1: lanes 8-15.
    const v16i even16 = { 0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30 };
    const v16i odd16 = { 1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31 };
    double tr = 0.0, ti = 0.0;
    const std::uint32_t full = n / 64;
    for (std::uint32_t blk = 0; blk < full; ++blk) {
        const float ar = a[2 * blk], ai = a[2 * blk + 1];
        // Two accumulator pairs (even and odd vectors of 8) so the adds overlap, held
        // together in 16-lane vectors: lanes 0-7 the even vector, 8-15 the odd one.
        v16f s16r = {}, s16i = {};
        for (int j = 0; j < 8; j += 2) {
            v16f a, b, vbr, vbi;
            std::memcpy(&a, f + 128 * blk + 16 * j, sizeof(a));
            std::memcpy(&b, f + 128 * blk + 16 * j + 16, sizeof(b));
            std::memcpy(&vbr, br + 8 * j, sizeof(vbr));
            std::memcpy(&vbi, bi + 8 * j, sizeof(vbi));
            const v16f xr = __builtin_shuffle(a, b, even16);
            const v16f xi = __builtin_shuffle(a, b, odd16);
            const v16f pr = ar * vbr - ai * vbi;
            const v16f pi = ar * vbi + ai * vbr;
            s16r += xr * pr - xi * pi;
            s16i += xr * pi + xi * pr;
        }
        const v8f sr0 = __builtin_shufflevector(s16r, s16r, 0, 1, 2, 3, 4, 5, 6, 7);
        const v8f sr1 = __builtin_shufflevector(s16r, s16r, 8, 9, 10, 11, 12, 13, 14, 15);
        const v8f si0 = __builtin_shufflevector(s16i, s16i, 0, 1, 2, 3, 4, 5, 6, 7);
        const v8f si1 = __builtin_shufflevector(s16i, s16i, 8, 9, 10, 11, 12, 13, 14, 15);
        const v8f sr = sr0 + sr1, si = si0 + si1;
        for (int lane = 0; lane < 8; ++lane) {
            tr += sr[lane];
            ti += si[lane];
        }
    }
    if (full * 64 < n) {
        const float ar = a[2 * full], ai = a[2 * full + 1];
        for (std::uint32_t k = full * 64; k < n; ++k) {
            const std::uint32_t b = k - full * 64;
            const float pr = ar * br[b] - ai * bi[b];
            const float pi = ar * bi[b] + ai * br[b];
            tr += x[k].real() * pr - x[k].imag() * pi;
            ti += x[k].real() * pi + x[k].imag() * pr;
        }
    }
    return { tr, ti };
}

} // namespace detail
} // namespace rfseek
} // namespace gr
