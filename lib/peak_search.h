/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * peak_search: index of the largest |X_k|^2 of a complex spectrum, and the sum of all
 * |X_k|^2 (Parseval), in one pass. Written with GCC vector extensions and compiled for
 * AVX2 and for the baseline, picked at run time (target_clones), so a distribution build
 * runs everywhere and still uses AVX2 where it exists.
 */

#ifndef INCLUDED_RFSEEK_PEAK_SEARCH_H
#define INCLUDED_RFSEEK_PEAK_SEARCH_H

#include <complex>
#include <cstdint>

namespace gr {
namespace rfseek {
namespace detail {

struct peak {
    std::uint32_t index;
    float value;  //!< |X_index|^2
    double total; //!< sum of |X_k|^2
};

//! First index of the maximum of |x[k]|^2 over k < n (n >= 1), and the total power.
peak peak_search(const std::complex<float>* x, std::uint32_t n);

/*!
 * sum_k x[k] A_{k / 64} B_{k % 64}: a demodulating dot product whose phasor is the
 * product of a block term a[] (interleaved re, im; ceil(n / 64) entries) and an in-block
 * term given as separate real and imaginary tables br[64], bi[64].
 */
std::complex<double> demod_dot(const std::complex<float>* x,
                               std::uint32_t n,
                               const float* a,
                               const float* br,
                               const float* bi);

} // namespace detail
} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_PEAK_SEARCH_H */
