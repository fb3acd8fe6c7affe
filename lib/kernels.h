/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * kernels: the hot loops of the core (spectral peak search, demodulating dot product,
 * sum of tones, Gaussian noise). Written with GCC vector extensions and compiled for AVX2
 * and for the baseline (the one-pass synthesis also for AVX-512), picked at run time
 * (target_clones), so a distribution build runs everywhere and still uses AVX2 where it
 * exists. No fused multiply-adds (-ffp-contract=off): every clone gives the same floats.
 */

#ifndef INCLUDED_RFSEEK_KERNELS_H
#define INCLUDED_RFSEEK_KERNELS_H

#include <cmath>
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

//! The CPU has AVX-512 (the kernels' 16-lane paths pay only there).
bool have_avx512f();

/*!
 * First index of the maximum of |x[k]|^2 over k < n (n >= 1), and the total power.
 * width: 16 (16-lane vectors, where the CPU has AVX-512; else as 8), 8 (8-lane vectors)
 * or 0 (16 where AVX-512 is available); the same result and floats at any width.
 */
peak peak_search(const std::complex<float>* x, std::uint32_t n, int width = 0);

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

/*!
 * out[n] += sum_p amp[p] exp(j 2 pi cyc[p] n), n < len: a sum of tones (cycles per
 * sample), each phasor the product of a per-64-sample block term and an in-block term
 * built by recurrences in double, so the phase error stays at float rounding at any
 * length.
 */
void add_tones(std::complex<float>* out,
               std::uint32_t len,
               const std::complex<double>* amp,
               const double* cyc,
               std::uint32_t paths);

/*!
 * out[n] += sigma (g1 + j g2), n < len, with g1, g2 independent standard normals from a
 * generator seeded by key (Box-Muller on xoshiro128+ streams, 8 lanes). The same key
 * gives the same noise on every run of the same build.
 */
void add_gaussian_noise(std::complex<float>* out,
                        std::uint32_t len,
                        float sigma,
                        std::uint64_t key);

/*!
 * std::fmod(x, y) for finite x and y > 0, bit for bit (fmod is exact), without its slow
 * loop: n = trunc(|x| / y) is the true quotient or one more (the division rounds
 * monotonically and integers below 2^52 are exact), |x| - n y is then fmod's result or
 * that minus y, both representable, so one fma computes it exactly, and a negative
 * remainder takes y back exactly. Falls back to std::fmod when |x| / y >= 2^52.
 */
inline double fmod_exact(double x, double y)
{
    const double ax = std::fabs(x);
    if (ax < y)
        return x; // also keeps subnormal x exact where denormals are flushed
    const double q = ax / y;
    if (!(q < 4503599627370496.0)) // 2^52, or NaN
        return std::fmod(x, y);
    const double n = std::trunc(q);
    double r = std::fma(-n, y, ax);
    if (r < 0.0)
        r += y;
    return std::copysign(r, x);
}

/*!
 * std::polar(rho, theta) with one sincos call instead of cos and sin: glibc's sincos
 * returns the very doubles of its cos and sin (checked on 5e8 arguments, and by a test).
 */
inline std::complex<double> polar(double rho, double theta)
{
    double s, c;
    ::sincos(theta, &s, &c);
    return { rho * c, rho * s };
}

/*!
 * out[n] = sum_p amp[p] exp(j 2 pi cyc[p] n) (n < tone_len, zero after) plus, when noise,
 * the noise add_gaussian_noise(out, len, sigma, key) would add; n < len. The same floats
 * as zeroing out, add_tones over tone_len and add_gaussian_noise over len, in one pass
 * (the tones of each 64-sample block are summed in registers, then the noise is added
 * before the block is stored). width: floats per vector in the tone sums, 16 or 8 (0: 16
 * where AVX-512 is available); the same floats either way.
 */
void tones_and_noise(std::complex<float>* out,
                     std::uint32_t len,
                     std::uint32_t tone_len,
                     const std::complex<double>* amp,
                     const double* cyc,
                     std::uint32_t paths,
                     bool noise,
                     float sigma,
                     std::uint64_t key,
                     int width = 0);

} // namespace detail
} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_KERNELS_H */
