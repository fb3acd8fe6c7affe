/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The beacon synthesis kernels: tones over the paths, Gaussian noise, both in one pass
 * (kernels.h). The estimator's are in kernels_estimator.cc.
 */

#include "kernels.h"
#include "kernels_rng.h"
#include "kernels_vec.h"
#include <cmath>
#include <cstring>

namespace gr {
namespace rfseek {
namespace detail {

namespace {

constexpr std::uint32_t BLOCK = 64;
constexpr std::uint32_t MAX_PATHS = 256;

} // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
void add_tones(std::complex<float>* out,
               std::uint32_t len,
               const std::complex<double>* amp,
               const double* cyc,
               std::uint32_t paths)
{
    if (len == 0 || paths == 0)
        return;
    // In-block tables B_p[b] = exp(j 2 pi f_p b), b < 64, as separate re/im rows, and the
    // block steps exp(j 2 pi f_p 64), all from recurrences in double.
    alignas(32) float bre[MAX_PATHS][BLOCK];
    alignas(32) float bim[MAX_PATHS][BLOCK];
    double ar[MAX_PATHS], ai[MAX_PATHS], sr[MAX_PATHS], si[MAX_PATHS];
    const std::uint32_t np = paths < MAX_PATHS ? paths : MAX_PATHS;
    for (std::uint32_t p = 0; p < np; ++p) {
        const double w = 2.0 * M_PI * cyc[p];
        const double cr = std::cos(w), ci = std::sin(w);
        double pr = 1.0, pi = 0.0;
        for (std::uint32_t b = 0; b < BLOCK; ++b) {
            bre[p][b] = static_cast<float>(pr);
            bim[p][b] = static_cast<float>(pi);
            const double t = pr * cr - pi * ci;
            pi = pr * ci + pi * cr;
            pr = t;
        }
        // exp(j w BLOCK) by repeated squaring of exp(j w) (BLOCK = 2^6), in double.
        double qr = cr, qi = ci;
        for (std::uint32_t k = 1; k < BLOCK; k *= 2) {
            const double t = qr * qr - qi * qi;
            qi = 2.0 * qr * qi;
            qr = t;
        }
        sr[p] = qr;
        si[p] = qi;
        ar[p] = amp[p].real();
        ai[p] = amp[p].imag();
    }
    float* o = reinterpret_cast<float*>(out);
    const v8i lo_idx = { 0, 8, 1, 9, 2, 10, 3, 11 };
    const v8i hi_idx = { 4, 12, 5, 13, 6, 14, 7, 15 };
    for (std::uint32_t base = 0; base < len; base += BLOCK) {
        v8f accr[BLOCK / 8], acci[BLOCK / 8];
        for (std::uint32_t j = 0; j < BLOCK / 8; ++j) {
            accr[j] = v8f{ 0, 0, 0, 0, 0, 0, 0, 0 };
            acci[j] = accr[j];
        }
        for (std::uint32_t p = 0; p < np; ++p) {
            const float cr = static_cast<float>(ar[p]), ci = static_cast<float>(ai[p]);
            for (std::uint32_t j = 0; j < BLOCK / 8; ++j) {
                v8f br, bi;
                std::memcpy(&br, &bre[p][8 * j], sizeof(br));
                std::memcpy(&bi, &bim[p][8 * j], sizeof(bi));
                accr[j] += cr * br - ci * bi;
                acci[j] += cr * bi + ci * br;
            }
            const double t = ar[p] * sr[p] - ai[p] * si[p];
            ai[p] = ar[p] * si[p] + ai[p] * sr[p];
            ar[p] = t;
        }
        const std::uint32_t n = len - base < BLOCK ? len - base : BLOCK;
        if (n == BLOCK) {
            for (std::uint32_t j = 0; j < BLOCK / 8; ++j) {
                v8f a, b;
                std::memcpy(&a, o + 2 * (base + 8 * j), sizeof(a));
                std::memcpy(&b, o + 2 * (base + 8 * j) + 8, sizeof(b));
                a += __builtin_shuffle(accr[j], acci[j], lo_idx);
                b += __builtin_shuffle(accr[j], acci[j], hi_idx);
                std::memcpy(o + 2 * (base + 8 * j), &a, sizeof(a));
                std::memcpy(o + 2 * (base + 8 * j) + 8, &b, sizeof(b));
            }
        } else {
            for (std::uint32_t k = 0; k < n; ++k) {
                o[2 * (base + k)] += accr[k / 8][k % 8];
                o[2 * (base + k) + 1] += acci[k / 8][k % 8];
            }
        }
    }
}


#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
void add_gaussian_noise(std::complex<float>* out,
                        std::uint32_t len,
                        float sigma,
                        std::uint64_t key)
{
    lanes g = seed_lanes(key);
    float* o = reinterpret_cast<float*>(out);
    const v8i lo_idx = { 0, 8, 1, 9, 2, 10, 3, 11 };
    const v8i hi_idx = { 4, 12, 5, 13, 6, 14, 7, 15 };
    for (std::uint32_t base = 0; base < len; base += 8) {
        v8f re, im;
        g.normals(sigma, re, im);
        const std::uint32_t n = len - base < 8 ? len - base : 8;
        if (n == 8) {
            v8f a, b;
            std::memcpy(&a, o + 2 * base, sizeof(a));
            std::memcpy(&b, o + 2 * base + 8, sizeof(b));
            a += __builtin_shuffle(re, im, lo_idx);
            b += __builtin_shuffle(re, im, hi_idx);
            std::memcpy(o + 2 * base, &a, sizeof(a));
            std::memcpy(o + 2 * base + 8, &b, sizeof(b));
        } else {
            for (std::uint32_t k = 0; k < n; ++k) {
                o[2 * (base + k)] += re[k];
                o[2 * (base + k) + 1] += im[k];
            }
        }
    }
}

namespace {
typedef double v4d __attribute__((vector_size(32)));
typedef float v4f __attribute__((vector_size(16)));

// add_tones' tables for paths [0, np), four paths per vector: the same double
// recurrences, element by element, as add_tones' scalar loops (so the same floats),
// with four independent chains in flight instead of one.
__attribute__((always_inline)) inline void tone_tables(const std::complex<double>* amp,
                                                       const double* cyc,
                                                       std::uint32_t np,
                                                       float (*bre)[BLOCK],
                                                       float (*bim)[BLOCK],
                                                       double* ar,
                                                       double* ai,
                                                       double* sr,
                                                       double* si)
{
    for (std::uint32_t p0 = 0; p0 < np; p0 += 4) {
        const std::uint32_t cnt = np - p0 < 4 ? np - p0 : 4;
        v4d cr = { 1, 1, 1, 1 }, ci = { 0, 0, 0, 0 };
        for (std::uint32_t i = 0; i < cnt; ++i) {
            const double w = 2.0 * M_PI * cyc[p0 + i];
            cr[i] = std::cos(w);
            ci[i] = std::sin(w);
        }
        v4d pr = { 1, 1, 1, 1 }, pi = { 0, 0, 0, 0 };
        for (std::uint32_t b = 0; b < BLOCK; ++b) {
            const v4f fr = __builtin_convertvector(pr, v4f);
            const v4f fi = __builtin_convertvector(pi, v4f);
            for (std::uint32_t i = 0; i < cnt; ++i) {
                bre[p0 + i][b] = fr[i];
                bim[p0 + i][b] = fi[i];
            }
            const v4d t = pr * cr - pi * ci;
            pi = pr * ci + pi * cr;
            pr = t;
        }
        v4d qr = cr, qi = ci;
        for (std::uint32_t k = 1; k < BLOCK; k *= 2) {
            const v4d t = qr * qr - qi * qi;
            qi = 2.0 * qr * qi;
            qr = t;
        }
        for (std::uint32_t i = 0; i < 4; ++i) { // padding lanes: zero amplitude
            sr[p0 + i] = qr[i];
            si[p0 + i] = qi[i];
            ar[p0 + i] = i < cnt ? amp[p0 + i].real() : 0.0;
            ai[p0 + i] = i < cnt ? amp[p0 + i].imag() : 0.0;
        }
    }
}

typedef double v8d __attribute__((vector_size(64)));

// v[k][i] -> v[i][k] for eight vectors of eight floats (values only move).
__attribute__((always_inline)) inline void
transpose8(v8f& r0, v8f& r1, v8f& r2, v8f& r3, v8f& r4, v8f& r5, v8f& r6, v8f& r7)
{
    const v8i lo = { 0, 8, 1, 9, 4, 12, 5, 13 }, hi = { 2, 10, 3, 11, 6, 14, 7, 15 };
    const v8i lo2 = { 0, 1, 8, 9, 4, 5, 12, 13 }, hi2 = { 2, 3, 10, 11, 6, 7, 14, 15 };
    const v8i lo4 = { 0, 1, 2, 3, 8, 9, 10, 11 }, hi4 = { 4, 5, 6, 7, 12, 13, 14, 15 };
    const v8f t0 = __builtin_shuffle(r0, r1, lo), t1 = __builtin_shuffle(r0, r1, hi);
    const v8f t2 = __builtin_shuffle(r2, r3, lo), t3 = __builtin_shuffle(r2, r3, hi);
    const v8f t4 = __builtin_shuffle(r4, r5, lo), t5 = __builtin_shuffle(r4, r5, hi);
    const v8f t6 = __builtin_shuffle(r6, r7, lo), t7 = __builtin_shuffle(r6, r7, hi);
    const v8f u0 = __builtin_shuffle(t0, t2, lo2), u1 = __builtin_shuffle(t0, t2, hi2);
    const v8f u2 = __builtin_shuffle(t1, t3, lo2), u3 = __builtin_shuffle(t1, t3, hi2);
    const v8f u4 = __builtin_shuffle(t4, t6, lo2), u5 = __builtin_shuffle(t4, t6, hi2);
    const v8f u6 = __builtin_shuffle(t5, t7, lo2), u7 = __builtin_shuffle(t5, t7, hi2);
    r0 = __builtin_shuffle(u0, u4, lo4);
    r4 = __builtin_shuffle(u0, u4, hi4);
    r1 = __builtin_shuffle(u1, u5, lo4);
    r5 = __builtin_shuffle(u1, u5, hi4);
    r2 = __builtin_shuffle(u2, u6, lo4);
    r6 = __builtin_shuffle(u2, u6, hi4);
    r3 = __builtin_shuffle(u3, u7, lo4);
    r7 = __builtin_shuffle(u3, u7, hi4);
}

// tone_tables with eight paths per vector (AVX-512): eight steps of the recurrences are
// kept in registers and transposed, so each path's row is written eight floats at a time.
__attribute__((always_inline)) inline void
tone_tables_wide(const std::complex<double>* amp,
                 const double* cyc,
                 std::uint32_t np,
                 float (*bre)[BLOCK],
                 float (*bim)[BLOCK],
                 double* ar,
                 double* ai,
                 double* sr,
                 double* si)
{
    for (std::uint32_t p0 = 0; p0 < np; p0 += 8) {
        const std::uint32_t cnt = np - p0 < 8 ? np - p0 : 8;
        v8d cr = { 1, 1, 1, 1, 1, 1, 1, 1 }, ci = { 0, 0, 0, 0, 0, 0, 0, 0 };
        for (std::uint32_t i = 0; i < cnt; ++i) {
            const double w = 2.0 * M_PI * cyc[p0 + i];
            cr[i] = std::cos(w);
            ci[i] = std::sin(w);
        }
        v8d pr = { 1, 1, 1, 1, 1, 1, 1, 1 }, pi = { 0, 0, 0, 0, 0, 0, 0, 0 };
        auto step = [&](v8f& fr, v8f& fi) {
            fr = __builtin_convertvector(pr, v8f);
            fi = __builtin_convertvector(pi, v8f);
            const v8d t = pr * cr - pi * ci;
            pi = pr * ci + pi * cr;
            pr = t;
        };
        for (std::uint32_t b = 0; b < BLOCK; b += 8) {
            v8f r0, r1, r2, r3, r4, r5, r6, r7, i0, i1, i2, i3, i4, i5, i6, i7;
            step(r0, i0);
            step(r1, i1);
            step(r2, i2);
            step(r3, i3);
            step(r4, i4);
            step(r5, i5);
            step(r6, i6);
            step(r7, i7);
            transpose8(r0, r1, r2, r3, r4, r5, r6, r7);
            transpose8(i0, i1, i2, i3, i4, i5, i6, i7);
            const v8f* rows_r[8] = { &r0, &r1, &r2, &r3, &r4, &r5, &r6, &r7 };
            const v8f* rows_i[8] = { &i0, &i1, &i2, &i3, &i4, &i5, &i6, &i7 };
            for (std::uint32_t i = 0; i < cnt; ++i) {
                std::memcpy(&bre[p0 + i][b], rows_r[i], sizeof(v8f));
                std::memcpy(&bim[p0 + i][b], rows_i[i], sizeof(v8f));
            }
        }
        v8d qr = cr, qi = ci;
        for (std::uint32_t k = 1; k < BLOCK; k *= 2) {
            const v8d t = qr * qr - qi * qi;
            qi = 2.0 * qr * qi;
            qr = t;
        }
        for (std::uint32_t i = 0; i < 8; ++i) { // padding lanes: zero amplitude
            sr[p0 + i] = qr[i];
            si[p0 + i] = qi[i];
            ar[p0 + i] = i < cnt ? amp[p0 + i].real() : 0.0;
            ai[p0 + i] = i < cnt ? amp[p0 + i].imag() : 0.0;
        }
    }
}

// tr[k], ti[k] (k < BLOCK) = sum over paths, in path order, of (cf + j sf)_p B_p[k]: the
// per-sample arithmetic of add_tones. GROUP samples at a time in four vectors of VF per
// part, the accumulators named so they stay in registers.
template <typename VF, std::uint32_t GROUP>
__attribute__((always_inline)) inline void sum_tones(const float (*bre)[BLOCK],
                                                     const float (*bim)[BLOCK],
                                                     const float* cf,
                                                     const float* sf,
                                                     std::uint32_t np,
                                                     float* tr,
                                                     float* ti)
{
    constexpr std::uint32_t W = sizeof(VF) / sizeof(float);
    static_assert(GROUP == 4 * W && BLOCK % GROUP == 0, "four vectors per group");
    for (std::uint32_t h = 0; h < BLOCK; h += GROUP) {
        const VF zero{};
        VF r0 = zero, r1 = zero, r2 = zero, r3 = zero;
        VF i0 = zero, i1 = zero, i2 = zero, i3 = zero;
        for (std::uint32_t p = 0; p < np; ++p) {
            const float cr = cf[p], ci = sf[p];
            auto mac = [&](std::uint32_t j, VF& accr, VF& acci) {
                VF br, bi;
                std::memcpy(&br, &bre[p][h + W * j], sizeof(br));
                std::memcpy(&bi, &bim[p][h + W * j], sizeof(bi));
                accr += cr * br - ci * bi;
                acci += cr * bi + ci * br;
            };
            mac(0, r0, i0);
            mac(1, r1, i1);
            mac(2, r2, i2);
            mac(3, r3, i3);
        }
        std::memcpy(tr + h, &r0, sizeof(VF));
        std::memcpy(tr + h + W, &r1, sizeof(VF));
        std::memcpy(tr + h + 2 * W, &r2, sizeof(VF));
        std::memcpy(tr + h + 3 * W, &r3, sizeof(VF));
        std::memcpy(ti + h, &i0, sizeof(VF));
        std::memcpy(ti + h + W, &i1, sizeof(VF));
        std::memcpy(ti + h + 2 * W, &i2, sizeof(VF));
        std::memcpy(ti + h + 3 * W, &i3, sizeof(VF));
    }
}

// One block out, eight samples per step: the draws and sums of tones_and_noise's
// 16-sample loop (normals2 = two normals) in 8-lane vectors (16 went through memory).
__attribute__((always_inline)) inline void write_samples8(const float* tr,
                                                          const float* ti,
                                                          std::uint32_t nblk,
                                                          bool noise,
                                                          float sigma,
                                                          lanes& g,
                                                          float* q)
{
    const v8i lo_idx = { 0, 8, 1, 9, 2, 10, 3, 11 },
              hi_idx = { 4, 12, 5, 13, 6, 14, 7, 15 };
    for (std::uint32_t c = 0; c < nblk; c += 8) {
        v8f re, im;
        std::memcpy(&re, tr + c, sizeof(re));
        std::memcpy(&im, ti + c, sizeof(im));
        if (noise) {
            v8f nr, ni;
            g.normals(sigma, nr, ni);
            re += nr;
            im += ni;
        }
        const v8f a = __builtin_shuffle(re, im, lo_idx);
        const v8f b = __builtin_shuffle(re, im, hi_idx);
        if (nblk - c >= 8) {
            std::memcpy(q + 2 * c, &a, sizeof(a));
            std::memcpy(q + 2 * c + 8, &b, sizeof(b));
        } else {
            float ab[16];
            std::memcpy(ab, &a, sizeof(a));
            std::memcpy(ab + 8, &b, sizeof(b));
            std::memcpy(q + 2 * c, ab, 2 * (nblk - c) * sizeof(float));
        }
    }
}

// 512-bit vectors pay only with AVX-512 (32 registers); elsewhere 16 ymm accumulators
// would spill. (The clones' resolvers pick the AVX-512 one by the same test; either
// width gives the same floats.)
const bool HAVE_AVX512F = have_avx512f();
} // namespace

bool have_avx512f()
{
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    __builtin_cpu_init(); // may run before libgcc's own initialisation
    return __builtin_cpu_supports("avx512f");
#else
    return false;
#endif
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void tones_and_noise(std::complex<float>* out,
                     std::uint32_t len,
                     std::uint32_t tone_len,
                     const std::complex<double>* amp,
                     const double* cyc,
                     std::uint32_t paths,
                     bool noise,
                     float sigma,
                     std::uint64_t key,
                     int width)
{
    if (len == 0)
        return;
    if (tone_len > len)
        tone_len = len;
    if (paths == 0)
        tone_len = 0;
    alignas(32) float bre[MAX_PATHS][BLOCK];
    alignas(32) float bim[MAX_PATHS][BLOCK];
    alignas(32) double ar[MAX_PATHS], ai[MAX_PATHS], sr[MAX_PATHS], si[MAX_PATHS];
    const std::uint32_t np = paths < MAX_PATHS ? paths : MAX_PATHS;
    const bool wide = width == 0 ? HAVE_AVX512F : width == 16;
    if (tone_len > 0) {
        if (wide)
            tone_tables_wide(amp, cyc, np, bre, bim, ar, ai, sr, si);
        else
            tone_tables(amp, cyc, np, bre, bim, ar, ai, sr, si);
    }
    lanes g = noise ? seed_lanes(key) : lanes{};
    float* o = reinterpret_cast<float*>(out);
    // This block's tones, zero past tone_len.
    alignas(64) float tr[BLOCK], ti[BLOCK];
    bool tr_zero = false;
    for (std::uint32_t base = 0; base < len; base += BLOCK) {
        if (base < tone_len) {
            alignas(32) float cf[MAX_PATHS], sf[MAX_PATHS];
            for (std::uint32_t p = 0; p < np; ++p) {
                cf[p] = static_cast<float>(ar[p]);
                sf[p] = static_cast<float>(ai[p]);
            }
            for (std::uint32_t p0 = 0; p0 < np; p0 += 4) {
                v4d vr, vi, vsr, vsi;
                std::memcpy(&vr, ar + p0, sizeof(vr));
                std::memcpy(&vi, ai + p0, sizeof(vi));
                std::memcpy(&vsr, sr + p0, sizeof(vsr));
                std::memcpy(&vsi, si + p0, sizeof(vsi));
                const v4d t = vr * vsr - vi * vsi;
                vi = vr * vsi + vi * vsr;
                std::memcpy(ar + p0, &t, sizeof(t));
                std::memcpy(ai + p0, &vi, sizeof(vi));
            }
            // All paths summed per sample in path order (as add_tones), four vectors
            // of eight samples at a time so the accumulators stay in registers.
            if (wide)
                sum_tones<v16f, BLOCK>(bre, bim, cf, sf, np, tr, ti);
            else
                sum_tones<v8f, 32>(bre, bim, cf, sf, np, tr, ti);
            for (std::uint32_t k = tone_len - base; k < BLOCK; ++k)
                tr[k] = ti[k] = 0.0f;
            tr_zero = false;
        } else if (!tr_zero) {
            std::memset(tr, 0, sizeof(tr));
            std::memset(ti, 0, sizeof(ti));
            tr_zero = true;
        }
        const std::uint32_t nblk = len - base < BLOCK ? len - base : BLOCK;
        if (!wide) {
            write_samples8(tr, ti, nblk, noise, sigma, g, o + 2 * base);
            continue;
        }
        // With AVX-512, sixteen samples per step: two draws of the noise generator at
        // once, loaded as the tone sums were stored (whole vectors, so the loads are
        // forwarded).
        const v16i lo16 = { 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23 };
        const v16i hi16 = {
            8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31
        };
        for (std::uint32_t c = 0; c < nblk; c += 16) {
            v16f re, im;
            std::memcpy(&re, tr + c, sizeof(re));
            std::memcpy(&im, ti + c, sizeof(im));
            if (noise) {
                // As add_gaussian_noise on a buffer holding the tones (or zeros).
                v16f nr, ni;
                if (nblk - c > 8) {
                    g.normals2(sigma, nr, ni);
                } else {
                    v8f r8, i8;
                    g.normals(sigma, r8, i8);
                    nr = __builtin_shufflevector(
                        r8, r8, 0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7);
                    ni = __builtin_shufflevector(
                        i8, i8, 0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7);
                }
                re += nr;
                im += ni;
            }
            const v16f a = __builtin_shuffle(re, im, lo16);
            const v16f b = __builtin_shuffle(re, im, hi16);
            float* q = o + 2 * (base + c);
            if (nblk - c >= 16) {
                std::memcpy(q, &a, sizeof(a));
                std::memcpy(q + 16, &b, sizeof(b));
            } else {
                float ab[32];
                std::memcpy(ab, &a, sizeof(a));
                std::memcpy(ab + 16, &b, sizeof(b));
                std::memcpy(q, ab, 2 * (nblk - c) * sizeof(float));
            }
        }
    }
}

} // namespace detail
} // namespace rfseek
} // namespace gr
