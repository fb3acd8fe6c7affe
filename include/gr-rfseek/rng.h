/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rng: the run-owned random source. xoshiro256** seeded through splitmix64 from
 * (seed, stream, index), so every draw of a run is reproducible from its seed, streams
 * are independent (geometry, noise of slot k, heading noise of slot k, ...) and results
 * do not depend on thread count or on the order in which streams are consumed.
 */

#ifndef INCLUDED_RFSEEK_RNG_H
#define INCLUDED_RFSEEK_RNG_H

#include <gr-rfseek/api.h>
#include <cmath>
#include <cstdint>

namespace gr {
namespace rfseek {

class RFSEEK_API rng
{
public:
    rng(std::uint64_t seed, std::uint64_t stream = 0, std::uint64_t index = 0)
    {
        reseed(seed, stream, index);
    }

    void reseed(std::uint64_t seed, std::uint64_t stream = 0, std::uint64_t index = 0)
    {
        std::uint64_t x = seed ^
                          mix(stream * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL) ^
                          mix(index + 0x8CB92BA72F3D8DD7ULL);
        for (auto& si : d_s)
            si = splitmix(x);
        d_have_spare = false;
    }

    std::uint64_t next()
    {
        const std::uint64_t result = rotl(d_s[1] * 5, 7) * 9;
        const std::uint64_t t = d_s[1] << 17;
        d_s[2] ^= d_s[0];
        d_s[3] ^= d_s[1];
        d_s[1] ^= d_s[2];
        d_s[0] ^= d_s[3];
        d_s[2] ^= t;
        d_s[3] = rotl(d_s[3], 45);
        return result;
    }

    //! Uniform in [0, 1).
    double uniform() { return (next() >> 11) * 0x1.0p-53; }
    //! Uniform in [a, b).
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
    //! Standard normal (Marsaglia polar method).
    double normal()
    {
        if (d_have_spare) {
            d_have_spare = false;
            return d_spare;
        }
        double u, v, s;
        do {
            u = 2.0 * uniform() - 1.0;
            v = 2.0 * uniform() - 1.0;
            s = u * u + v * v;
        } while (s >= 1.0 || s == 0.0);
        const double m = std::sqrt(-2.0 * std::log(s) / s);
        d_spare = v * m;
        d_have_spare = true;
        return u * m;
    }

private:
    static std::uint64_t rotl(std::uint64_t x, int k)
    {
        return (x << k) | (x >> (64 - k));
    }
    static std::uint64_t mix(std::uint64_t z)
    {
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    static std::uint64_t splitmix(std::uint64_t& x)
    {
        x += 0x9E3779B97F4A7C15ULL;
        return mix(x);
    }

    std::uint64_t d_s[4];
    double d_spare = 0.0;
    bool d_have_spare = false;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_RNG_H */
