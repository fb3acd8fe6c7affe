/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * libFuzzer harness: channel_source's "cmd" handler on messages built from fuzz bytes,
 * in lockstep and free-running mode, and its "truth" handler when it follows an
 * autopilot's truth (truth dicts with every key, values fuzzed, keys sometimes missing):
 * no exception, no crash, every message applied or counted. (Flying the slot needs a
 * flowgraph's buffers: the non-finite headings that could reach it are refused by the
 * handler, checked in qa_channel_source.)
 */

#include "../channel_source_impl.h"
#include "fuzz_common.h"

namespace {

// The most derived class constructs the virtual base (gr::sync_block), as the impl does.
struct probe : gr::rfseek::channel_source_impl {
    probe(const gr::rfseek::scenario& sc, bool lockstep, bool follow)
        : gr::sync_block("channel_source",
                         gr::io_signature::make(0, 0, 0),
                         gr::io_signature::make(1, 1, sizeof(gr_complex))),
          channel_source_impl(sc, "burst", lockstep, false, 1.0, follow)
    {
    }
    void deliver(const pmt::pmt_t& msg) { dispatch_msg(pmt::mp("cmd"), msg); }
    void deliver_truth(const pmt::pmt_t& msg) { dispatch_msg(pmt::mp("truth"), msg); }
};

// A truth as the SITL readers publish it, every value fuzzed, a key now and then left
// out.
pmt::pmt_t fuzz_truth(FuzzedDataProvider& fdp)
{
    static const char* keys[] = { "time",   "east",    "north", "up",
                                  "v_east", "v_north", "v_up",  "heading" };
    pmt::pmt_t d = pmt::make_dict();
    for (const char* k : keys) {
        switch (fdp.ConsumeIntegralInRange<int>(0, 7)) {
        case 0: // left out
            break;
        case 1:
            d = pmt::dict_add(d, pmt::mp(k), rfseek_fuzz::fuzz_pmt(fdp, 2));
            break;
        default:
            d = pmt::dict_add(
                d, pmt::mp(k), pmt::from_double(rfseek_fuzz::fuzz_double(fdp)));
        }
    }
    return d;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    FuzzedDataProvider fdp(data, size);
    gr::rfseek::scenario sc;
    sc.seed = 1;
    sc.num_scatterers = 2;
    sc.window_len = 64;
    sc.fft_len = 64;
    const bool lockstep = fdp.ConsumeBool();
    const bool follow = fdp.ConsumeBool();
    auto src = std::make_shared<probe>(sc, lockstep, follow);
    std::uint64_t delivered = 0, truths = 0;
    while (fdp.remaining_bytes() > 0 && delivered + truths < 16) {
        switch (fdp.ConsumeIntegralInRange<int>(0, 2)) {
        case 0:
            src->deliver(rfseek_fuzz::fuzz_pmt(fdp));
            ++delivered;
            break;
        case 1:
            src->deliver_truth(fuzz_truth(fdp));
            ++truths;
            break;
        default:
            src->deliver_truth(rfseek_fuzz::fuzz_pmt(fdp));
            ++truths;
        }
    }
    // Every message was either applied or counted as dropped or stale: none threw.
    if (src->malformed_count() + src->stale_count() > delivered)
        std::abort();
    // Every truth was kept or counted as dropped, and none is kept by a source that
    // does not follow one.
    if (src->truth_count() + src->truth_dropped_count() != truths ||
        (!follow && src->truth_count() != 0))
        std::abort();
    return 0;
}
