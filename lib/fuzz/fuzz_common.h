/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * Shared by the libFuzzer harnesses (scripts/fuzz.sh): a PMT built from fuzz bytes and a
 * message sink that checks what a block publishes.
 *
 * The PMT is built by a small grammar over the bytes (dicts, pairs, vectors, symbols,
 * integers, uint64, reals including NaN, inf, denormals and huge values, bools, nil),
 * not by pmt::deserialize: that one trusts the length fields of its input and allocates
 * gigabytes for a few bytes (found by the first run of these harnesses), so it is no
 * parser of outside data, and no block here uses it.
 */

#ifndef INCLUDED_RFSEEK_FUZZ_COMMON_H
#define INCLUDED_RFSEEK_FUZZ_COMMON_H

#include <gnuradio/block.h>
#include <gnuradio/io_signature.h>
#include <fuzzer/FuzzedDataProvider.h>
#include <pmt/pmt.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

namespace rfseek_fuzz {

inline double fuzz_double(FuzzedDataProvider& fdp)
{
    switch (fdp.ConsumeIntegralInRange<int>(0, 9)) {
    case 0:
        return std::numeric_limits<double>::quiet_NaN();
    case 1:
        return fdp.ConsumeBool() ? INFINITY : -INFINITY;
    case 2:
        return std::numeric_limits<double>::denorm_min();
    case 3:
        return fdp.ConsumeBool() ? 1e300 : -1e300;
    case 4:
        return 0.0;
    default:
        return fdp.ConsumeFloatingPoint<double>();
    }
}

// Keys the blocks look for, and a few they do not.
inline pmt::pmt_t fuzz_key(FuzzedDataProvider& fdp)
{
    static const char* keys[] = { "heading",  "slot",    "freq_hz", "valid",    "snr_db",
                                  "power_db", "time",    "stage",   "x",        "",
                                  "Heading",  "slot\0x", "nav",     "theta_est" };
    if (fdp.ConsumeIntegralInRange<int>(0, 7) == 0)
        return pmt::intern(fdp.ConsumeRandomLengthString(16));
    return pmt::intern(keys[fdp.ConsumeIntegralInRange<int>(0, 13)]);
}

inline pmt::pmt_t fuzz_pmt(FuzzedDataProvider& fdp, int depth = 0)
{
    const int kind = fdp.ConsumeIntegralInRange<int>(0, depth < 3 ? 11 : 7);
    switch (kind) {
    case 0:
        return pmt::PMT_NIL;
    case 1:
        return pmt::from_bool(fdp.ConsumeBool());
    case 2:
        return pmt::from_long(fdp.ConsumeIntegral<long>());
    case 3:
        return pmt::from_uint64(fdp.ConsumeIntegral<std::uint64_t>());
    case 4:
    case 5:
        return pmt::from_double(fuzz_double(fdp));
    case 6:
        return pmt::intern(fdp.ConsumeRandomLengthString(32));
    case 7:
        return pmt::from_complex(fuzz_double(fdp), fuzz_double(fdp));
    case 8:
    case 9: { // a dict, the usual message
        pmt::pmt_t d = pmt::make_dict();
        const int n = fdp.ConsumeIntegralInRange<int>(0, 8);
        for (int i = 0; i < n && fdp.remaining_bytes() > 0; ++i)
            d = pmt::dict_add(d, fuzz_key(fdp), fuzz_pmt(fdp, depth + 1));
        return d;
    }
    case 10:
        return pmt::cons(fuzz_pmt(fdp, depth + 1), fuzz_pmt(fdp, depth + 1));
    default: {
        const int n = fdp.ConsumeIntegralInRange<int>(0, 4);
        pmt::pmt_t v = pmt::make_vector(n, pmt::PMT_NIL);
        for (int i = 0; i < n; ++i)
            pmt::vector_set(v, i, fuzz_pmt(fdp, depth + 1));
        return v;
    }
    }
}

// Aborts (a finding) if a published message holds a non-finite real anywhere.
inline void require_finite(const pmt::pmt_t& m, const char* where)
{
    if (pmt::is_real(m) && !std::isfinite(pmt::to_double(m))) {
        std::fprintf(stderr, "%s: non-finite value in a published message\n", where);
        std::abort();
    }
    if (pmt::is_dict(m) && !pmt::is_null(m)) {
        pmt::pmt_t items = pmt::dict_items(m);
        for (std::size_t i = 0; i < pmt::length(items); ++i)
            require_finite(pmt::cdr(pmt::nth(i, items)), where);
    }
}

// A message sink: subscribe it to a block's output port, then drain() after each input.
class sink : public gr::block
{
public:
    sink()
        : gr::block("fuzz_sink",
                    gr::io_signature::make(0, 0, 0),
                    gr::io_signature::make(0, 0, 0))
    {
        message_port_register_in(pmt::mp("in"));
    }
    std::size_t drain(const char* where)
    {
        std::size_t n = 0;
        for (pmt::pmt_t m = delete_head_nowait(pmt::mp("in")); m.get();
             m = delete_head_nowait(pmt::mp("in"))) {
            require_finite(m, where);
            ++n;
        }
        return n;
    }
};

} // namespace rfseek_fuzz

#endif
