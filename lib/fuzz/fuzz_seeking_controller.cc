/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * libFuzzer harness: seeking_controller's "meas" and "nav" handlers on sequences of
 * messages built from fuzz bytes, for each strategy; every cmd and telemetry message it
 * publishes must be finite (a NaN heading would steer the vehicle nowhere).
 */

#include "../seeking_controller_impl.h"
#include "fuzz_common.h"

namespace {

// The most derived class constructs the virtual base (gr::block), as the impl does.
struct probe : gr::rfseek::seeking_controller_impl {
    explicit probe(const gr::rfseek::seeker_config& cfg)
        : gr::block("seeking_controller",
                    gr::io_signature::make(0, 0, 0),
                    gr::io_signature::make(0, 0, 0)),
          seeking_controller_impl(cfg)
    {
    }
    void deliver(const char* port, const pmt::pmt_t& msg)
    {
        dispatch_msg(pmt::mp(port), msg);
    }
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    FuzzedDataProvider fdp(data, size);
    static const char* strategies[] = {
        "paper", "paper_no_circle", "rss_baseline", "adaptive"
    };
    gr::rfseek::seeker_config cfg;
    cfg.strategy = strategies[fdp.ConsumeIntegralInRange<int>(0, 3)];
    auto ctl = std::make_shared<probe>(cfg);
    auto out = std::make_shared<rfseek_fuzz::sink>();
    for (const char* port : { "cmd", "telemetry" })
        ctl->message_port_sub(pmt::mp(port), pmt::cons(out->alias_pmt(), pmt::mp("in")));
    std::uint64_t slot = 0;
    while (fdp.remaining_bytes() > 0) {
        const int what = fdp.ConsumeIntegralInRange<int>(0, 3);
        if (what == 0) {
            ctl->deliver("nav", rfseek_fuzz::fuzz_pmt(fdp));
        } else if (what == 1) {
            ctl->deliver("meas", rfseek_fuzz::fuzz_pmt(fdp));
        } else { // a well-formed meas whose values are fuzzed: reaches the seekers
            pmt::pmt_t d = pmt::make_dict();
            d = pmt::dict_add(d, pmt::mp("slot"), pmt::from_uint64(slot++));
            d = pmt::dict_add(
                d, pmt::mp("freq_hz"), pmt::from_double(rfseek_fuzz::fuzz_double(fdp)));
            d = pmt::dict_add(d, pmt::mp("valid"), pmt::from_bool(fdp.ConsumeBool()));
            d = pmt::dict_add(
                d, pmt::mp("snr_db"), pmt::from_double(rfseek_fuzz::fuzz_double(fdp)));
            d = pmt::dict_add(
                d, pmt::mp("power_db"), pmt::from_double(rfseek_fuzz::fuzz_double(fdp)));
            d = pmt::dict_add(
                d, pmt::mp("time"), pmt::from_double(rfseek_fuzz::fuzz_double(fdp)));
            if (fdp.ConsumeBool())
                d = pmt::dict_add(d,
                                  pmt::mp("heading"),
                                  pmt::from_double(rfseek_fuzz::fuzz_double(fdp)));
            ctl->deliver("meas", d);
        }
        out->drain("seeking_controller cmd/telemetry");
        if (!std::isfinite(ctl->theta_est()))
            std::abort();
    }
    return 0;
}
