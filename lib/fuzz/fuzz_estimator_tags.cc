/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * libFuzzer harness: doppler_estimator's handling of the receiver's clock tags, in a
 * running flowgraph. A pulsed tone in noise (so that "acquire" locks) carries rx_time
 * and rx_rate tags with any value (tuples of any numbers, NaN, junk PMTs), in any order
 * and at any offset, plus the aligning key; the stream is cut in chunks of any size.
 * Nothing may crash, every number in every message must be finite, and within one lock
 * (the "lock" field) the times must never go backwards.
 */

#include "fuzz_common.h"
#include <gnuradio/blocks/message_debug.h>
#include <gnuradio/blocks/vector_source.h>
#include <gnuradio/logger.h>
#include <gnuradio/top_block.h>
#include <gr-rfseek/doppler_estimator.h>
#include <complex>
#include <map>
#include <random>
#include <vector>

namespace {

pmt::pmt_t fuzz_time_value(FuzzedDataProvider& fdp)
{
    switch (fdp.ConsumeIntegralInRange<int>(0, 4)) {
    case 0: // UHD's form: (uint64 seconds, double fraction)
        return pmt::make_tuple(pmt::from_uint64(fdp.ConsumeIntegral<std::uint64_t>()),
                               pmt::from_double(rfseek_fuzz::fuzz_double(fdp)));
    case 1: // a plausible clock near the last one
        return pmt::make_tuple(
            pmt::from_uint64(1700000000 + fdp.ConsumeIntegralInRange<int>(-3, 10)),
            pmt::from_double(fdp.ConsumeFloatingPointInRange<double>(-0.5, 1.5)));
    case 2:
        return pmt::make_tuple(pmt::from_long(fdp.ConsumeIntegral<long>()),
                               pmt::from_double(rfseek_fuzz::fuzz_double(fdp)));
    case 3:
        return pmt::from_double(rfseek_fuzz::fuzz_double(fdp));
    default:
        return rfseek_fuzz::fuzz_pmt(fdp);
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const bool quiet = [] {
        gr::logging::singleton().set_default_level(gr::log_level::off);
        return true;
    }();
    (void)quiet;
    FuzzedDataProvider fdp(data, size);
    static const char* alignments[] = { "acquire", "acquire", "periodic", "tag" };
    const std::string alignment = alignments[fdp.ConsumeIntegralInRange<int>(0, 3)];
    const double fs = fdp.ConsumeBool() ? 1e5 : 48e3;
    const int n = fdp.ConsumeIntegralInRange<int>(16, 64);
    const int period = n + fdp.ConsumeIntegralInRange<int>(1, 3 * n);
    const std::size_t len = fdp.ConsumeIntegralInRange<std::size_t>(1, 40 * period);

    // A tone burst of n samples every period in noise, SNR and frequency from the input.
    std::mt19937 gen(fdp.ConsumeIntegral<std::uint32_t>());
    std::normal_distribution<float> noise(0.0f, 0.7f);
    const double f = fdp.ConsumeFloatingPointInRange<double>(-0.4, 0.4);
    const double amp = fdp.ConsumeFloatingPointInRange<double>(0.0, 3.0);
    const int skip = fdp.ConsumeIntegralInRange<int>(0, period - 1);
    std::vector<gr_complex> x(len);
    for (std::size_t i = 0; i < len; ++i) {
        const bool on = (i + skip) % period < static_cast<std::size_t>(n);
        x[i] = gr_complex(noise(gen), noise(gen)) +
               (on ? std::polar(static_cast<float>(amp),
                                static_cast<float>(2 * M_PI * f * i))
                   : gr_complex(0.0f, 0.0f));
    }
    std::vector<gr::tag_t> tags;
    const int ntags = fdp.ConsumeIntegralInRange<int>(0, 24);
    for (int i = 0; i < ntags && fdp.remaining_bytes() > 0; ++i) {
        gr::tag_t t;
        t.offset = fdp.ConsumeIntegralInRange<std::uint64_t>(0, len + 8);
        switch (fdp.ConsumeIntegralInRange<int>(0, 3)) {
        case 0:
        case 1:
            t.key = pmt::mp("rx_time");
            t.value = fuzz_time_value(fdp);
            break;
        case 2:
            t.key = pmt::mp("rx_rate");
            t.value = fdp.ConsumeBool()
                          ? pmt::from_double(rfseek_fuzz::fuzz_double(fdp))
                          : pmt::from_double(
                                fs * fdp.ConsumeFloatingPointInRange<double>(0.5, 2.0));
            break;
        default:
            t.key = pmt::mp("rfseek_beacon");
            t.value = rfseek_fuzz::fuzz_pmt(fdp);
        }
        tags.push_back(t);
    }
    const int chunk = fdp.ConsumeIntegralInRange<int>(1, 4 * period);

    gr::rfseek::doppler_estimator::sptr est;
    try {
        est = gr::rfseek::doppler_estimator::make(
            fs, n, 4 * n, "rectangular", "newton", alignment, "rfseek_beacon", period);
    } catch (const std::invalid_argument&) {
        return 0;
    }
    if (fdp.ConsumeBool()) // the clipping check, at a full scale the tone may reach
        est->set_full_scale(fdp.ConsumeFloatingPointInRange<double>(0.0, 4.0));
    auto tb = gr::make_top_block("fuzz_estimator_tags");
    auto src = gr::blocks::vector_source_c::make(x, false, 1, tags);
    auto dbg = gr::blocks::message_debug::make();
    est->set_max_noutput_items(chunk);
    tb->connect(src, 0, est, 0);
    tb->msg_connect(est, "meas", dbg, "store");
    tb->run();

    std::map<std::uint64_t, double> last_time; // per lock
    for (int i = 0; i < dbg->num_messages(); ++i) {
        const pmt::pmt_t m = dbg->get_message(i);
        rfseek_fuzz::require_finite(m, "doppler_estimator meas");
        const pmt::pmt_t lock = pmt::dict_ref(m, pmt::mp("lock"), pmt::PMT_NIL);
        if (pmt::is_null(lock))
            continue;
        const double t = pmt::to_double(pmt::dict_ref(m, pmt::mp("time"), pmt::PMT_NIL));
        const std::uint64_t k = pmt::to_uint64(lock);
        auto it = last_time.find(k);
        if (it != last_time.end() && t < it->second) {
            std::fprintf(stderr,
                         "time went back within lock %llu: %.9f after %.9f\n",
                         static_cast<unsigned long long>(k),
                         t,
                         it->second);
            std::abort();
        }
        last_time[k] = t;
    }
    return 0;
}
