/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * kernels_rng: the synthesis's vectorised Gaussian noise (xoshiro128+ on 8 lanes,
 * Box-Muller with a vectorised log), inlined into each clone of lib/kernels.cc.
 * Internal.
 */

#ifndef INCLUDED_RFSEEK_KERNELS_RNG_H
#define INCLUDED_RFSEEK_KERNELS_RNG_H

#include "kernels_vec.h"
#include <cmath>
#include <cstdint>
#include <cstring>

namespace gr {
namespace rfseek {
namespace detail {

inline std::uint64_t splitmix(std::uint64_t& x)
{
    x += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = x;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

// Natural log for x in (0, 1], vectorised: x = m 2^e with m in [sqrt(1/2), sqrt(2)),
// ln m = 2 atanh(t), t = (m - 1) / (m + 1), |t| <= 0.172 (error < 1e-9 before rounding).
template <typename VF, typename VI>
__attribute__((always_inline)) inline VF vlog(VF x)
{
    VI bits;
    std::memcpy(&bits, &x, sizeof(bits));
    VI e = ((bits >> 23) & 0xff) - 127;
    VI mb = (bits & 0x007fffff) | 0x3f800000; // m in [1, 2)
    VF m;
    std::memcpy(&m, &mb, sizeof(m));
    const VI big = m > 1.41421356f;
    m = big ? m * 0.5f : m;
    e = big ? e + 1 : e;
    const VF t = (m - 1.0f) / (m + 1.0f);
    const VF t2 = t * t;
    const VF poly =
        2.0f * t *
        (1.0f + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7 + t2 * (1.0f / 9)))));
    return __builtin_convertvector(e, VF) * 0.69314718056f + poly;
}

// Box-Muller on two draws of uniform bits per lane: sigma (g1 + j g2) per lane.
template <typename VF, typename VI, typename VU>
__attribute__((always_inline)) inline void
box_muller(VU r1, VU r2, float sigma, VF& re, VF& im)
{
    const float pi4 = 0.78539816340f;
    // u1 in (0, 1]: 24 bits plus half a step; psi in [-pi/4, pi/4); quadrant from 2
    // bits.
    const VF u1 =
        __builtin_convertvector((VI)(r1 >> 8), VF) * 5.9604645e-08f + 2.9802322e-08f;
    const VF psi =
        (__builtin_convertvector((VI)(r2 >> 8), VF) * 5.9604645e-08f - 0.5f) * 2.0f * pi4;
    const VU q = r2 & 3u;
    VF rad = -2.0f * vlog<VF, VI>(u1);
    for (unsigned i = 0; i < sizeof(VF) / sizeof(float); ++i) // sqrtps (-fno-math-errno)
        rad[i] = sigma * std::sqrt(rad[i]);
    const VF p2 = psi * psi;
    const VF s = psi * (1.0f - p2 * (1.0f / 6 - p2 * (1.0f / 120 - p2 * (1.0f / 5040))));
    const VF c =
        1.0f - p2 * (0.5f - p2 * (1.0f / 24 - p2 * (1.0f / 720 - p2 * (1.0f / 40320))));
    // Rotate (c, s) by q quarter turns: a uniform angle on the whole circle.
    const VI q1 = (VI)(q == 1u), q2 = (VI)(q == 2u), q3 = (VI)(q == 3u);
    VF cr = q1 ? -s : (q2 ? -c : (q3 ? s : c));
    VF sr = q1 ? c : (q2 ? -s : (q3 ? -c : s));
    re = rad * cr;
    im = rad * sr;
}

struct lanes {
    v8u s0, s1, s2, s3;
    // xoshiro128+ on 8 independent lanes.
    __attribute__((always_inline)) v8u next()
    {
        const v8u r = s0 + s3;
        const v8u t = s1 << 9;
        s2 ^= s0;
        s3 ^= s1;
        s1 ^= s2;
        s0 ^= s3;
        s2 ^= t;
        s3 = (s3 << 11) | (s3 >> 21);
        return r;
    }
    // Eight complex normals sigma (g1 + j g2): Box-Muller, one draw of two steps.
    __attribute__((always_inline)) void normals(float sigma, v8f& re, v8f& im)
    {
        const v8u r1 = next(), r2 = next();
        box_muller<v8f, v8i, v8u>(r1, r2, sigma, re, im);
    }
    // Two consecutive draws of normals() at once, in 16-lane vectors (the same numbers:
    // the lanes' arithmetic is unchanged).
    __attribute__((always_inline)) void normals2(float sigma, v16f& re, v16f& im)
    {
        const v8u a1 = next(), a2 = next(), b1 = next(), b2 = next();
        box_muller<v16f, v16i, v16u>(
            __builtin_shufflevector(
                a1, b1, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
            __builtin_shufflevector(
                a2, b2, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
            sigma,
            re,
            im);
    }
};

__attribute__((always_inline)) inline lanes seed_lanes(std::uint64_t key)
{
    lanes g;
    std::uint64_t x = key;
    for (int i = 0; i < 8; ++i) {
        const std::uint64_t a = splitmix(x), b = splitmix(x);
        g.s0[i] = static_cast<unsigned>(a);
        g.s1[i] = static_cast<unsigned>(a >> 32);
        g.s2[i] = static_cast<unsigned>(b);
        g.s3[i] = static_cast<unsigned>(b >> 32) | 1u; // never all zero
    }
    return g;
}

} // namespace detail
} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_KERNELS_RNG_H */
