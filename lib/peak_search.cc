/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include "peak_search.h"
#include <cstring>

namespace gr {
namespace rfseek {
namespace detail {

namespace {
typedef float v8f __attribute__((vector_size(32)));
typedef int v8i __attribute__((vector_size(32)));
} // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
peak peak_search(const std::complex<float>* x, std::uint32_t n)
{
    const float* f = reinterpret_cast<const float*>(x);
    const std::uint32_t blocks = n / 8;
    v8f best = { -1, -1, -1, -1, -1, -1, -1, -1 };
    v8i best_block = { 0, 0, 0, 0, 0, 0, 0, 0 };
    v8f sum = { 0, 0, 0, 0, 0, 0, 0, 0 };
    // Squares, pair sums within 128-bit lanes, then a blend: lane l holds the power of
    // complex element LANE_ELEMENT[l] of the block of 8.
    const v8i swap_pairs = { 1, 0, 3, 2, 5, 4, 7, 6 };
    const v8i take_odd_from_hi = { 0, 9, 2, 11, 4, 13, 6, 15 };
    static const std::uint32_t LANE_ELEMENT[8] = { 0, 4, 1, 5, 2, 6, 3, 7 };
    for (std::uint32_t b = 0; b < blocks; ++b) {
        v8f lo, hi;
        std::memcpy(&lo, f + 16 * b, sizeof(lo));
        std::memcpy(&hi, f + 16 * b + 8, sizeof(hi));
        lo *= lo;
        hi *= hi;
        lo += __builtin_shuffle(lo, swap_pairs);
        hi += __builtin_shuffle(hi, swap_pairs);
        const v8f p = __builtin_shuffle(lo, hi, take_odd_from_hi);
        sum += p;
        const v8i gt = p > best;
        best = gt ? p : best;
        const v8i bb = { static_cast<int>(b), static_cast<int>(b), static_cast<int>(b),
                         static_cast<int>(b), static_cast<int>(b), static_cast<int>(b),
                         static_cast<int>(b), static_cast<int>(b) };
        best_block = gt ? bb : best_block;
    }
    peak r{ 0, -1.0f, 0.0 };
    for (int lane = 0; lane < 8; ++lane) {
        r.total += sum[lane];
        if (blocks == 0)
            continue;
        const std::uint32_t idx =
            static_cast<std::uint32_t>(best_block[lane]) * 8 + LANE_ELEMENT[lane];
        if (best[lane] > r.value || (best[lane] == r.value && idx < r.index)) {
            r.value = best[lane];
            r.index = idx;
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
__attribute__((target_clones("avx2", "default")))
#endif
std::complex<double>
demod_dot(const std::complex<float>* x,
          std::uint32_t n,
          const float* a,
          const float* br,
          const float* bi)
{
    const float* f = reinterpret_cast<const float*>(x);
    const v8i even = { 0, 2, 4, 6, 8, 10, 12, 14 };
    const v8i odd = { 1, 3, 5, 7, 9, 11, 13, 15 };
    double tr = 0.0, ti = 0.0;
    const std::uint32_t full = n / 64;
    for (std::uint32_t blk = 0; blk < full; ++blk) {
        const float ar = a[2 * blk], ai = a[2 * blk + 1];
        v8f sr = { 0, 0, 0, 0, 0, 0, 0, 0 }, si = sr;
        for (int j = 0; j < 8; ++j) {
            v8f lo, hi, vbr, vbi;
            std::memcpy(&lo, f + 128 * blk + 16 * j, sizeof(lo));
            std::memcpy(&hi, f + 128 * blk + 16 * j + 8, sizeof(hi));
            std::memcpy(&vbr, br + 8 * j, sizeof(vbr));
            std::memcpy(&vbi, bi + 8 * j, sizeof(vbi));
            const v8f xr = __builtin_shuffle(lo, hi, even);
            const v8f xi = __builtin_shuffle(lo, hi, odd);
            const v8f pr = ar * vbr - ai * vbi;
            const v8f pi = ar * vbi + ai * vbr;
            sr += xr * pr - xi * pi;
            si += xr * pi + xi * pr;
        }
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
