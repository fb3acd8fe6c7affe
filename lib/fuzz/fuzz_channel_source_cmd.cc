/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * libFuzzer harness: channel_source's "cmd" handler on messages built from fuzz bytes,
 * in lockstep and free-running mode: no exception, no crash, every message applied or
 * counted. (Flying the slot needs a flowgraph's buffers: the non-finite headings that
 * could reach it are refused by the handler, checked in qa_channel_source.)
 */

#include "../channel_source_impl.h"
#include "fuzz_common.h"

namespace {

// The most derived class constructs the virtual base (gr::sync_block), as the impl does.
struct probe : gr::rfseek::channel_source_impl {
    probe(const gr::rfseek::scenario& sc, bool lockstep)
        : gr::sync_block("channel_source",
                         gr::io_signature::make(0, 0, 0),
                         gr::io_signature::make(1, 1, sizeof(gr_complex))),
          channel_source_impl(sc, "burst", lockstep, false, 1.0)
    {
    }
    void deliver(const pmt::pmt_t& msg) { dispatch_msg(pmt::mp("cmd"), msg); }
};

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
    auto src = std::make_shared<probe>(sc, lockstep);
    std::uint64_t delivered = 0;
    while (fdp.remaining_bytes() > 0 && delivered < 16) {
        src->deliver(rfseek_fuzz::fuzz_pmt(fdp));
        ++delivered;
    }
    // Every message was either applied or counted as dropped or stale: none threw.
    if (src->malformed_count() + src->stale_count() > delivered)
        std::abort();
    return 0;
}
