/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * libFuzzer harness: burst_acquirer (doppler_estimator's "acquire" alignment) on
 * arbitrary sample streams (NaN, inf and huge values included) in arbitrary chunks, with
 * arbitrary valid settings, and gaps of any size (NaN, negative, huge) told between
 * chunks. Every window it returns must lie inside what was pushed and
 * hold window_len samples, slots must increase, and its numbers (timing error, detection
 * statistic and margin, the tracked period) must stay finite.
 */

#include <fuzzer/FuzzedDataProvider.h>
#include <gr-rfseek/burst_acquirer.h>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {
[[noreturn]] void fail(const char* what, double a, double b)
{
    std::fprintf(stderr, "%s: %g %g\n", what, a, b);
    std::abort();
}
double rfseek_gap(FuzzedDataProvider& fdp)
{
    switch (fdp.ConsumeIntegralInRange<int>(0, 3)) {
    case 0:
        return std::nan("");
    case 1:
        return fdp.ConsumeFloatingPointInRange<double>(-1e6, 1e6);
    case 2:
        return fdp.ConsumeFloatingPoint<double>();
    default:
        return fdp.ConsumeFloatingPointInRange<double>(0.0, 5000.0);
    }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    FuzzedDataProvider fdp(data, size);
    gr::rfseek::burst_acquirer_config c;
    c.window_len = fdp.ConsumeIntegralInRange<int>(16, 64);
    c.period = c.window_len + fdp.ConsumeIntegralInRange<int>(1, 3 * c.window_len);
    c.pfa = fdp.ConsumeFloatingPointInRange<double>(1e-6, 0.5);
    if (fdp.ConsumeBool()) {
        const double lo = fdp.ConsumeFloatingPointInRange<double>(-0.5, 0.3);
        c.min_freq_hz = lo;
        c.max_freq_hz = lo + fdp.ConsumeFloatingPointInRange<double>(0.1, 0.2);
    }
    c.hop = fdp.ConsumeIntegralInRange<int>(0, c.window_len);
    c.margin = fdp.ConsumeIntegralInRange<int>(0, c.window_len);
    c.max_misses = fdp.ConsumeIntegralInRange<int>(1, 5);
    c.loop_alpha = fdp.ConsumeFloatingPointInRange<double>(0.01, 1.0);
    c.loop_beta = fdp.ConsumeFloatingPointInRange<double>(0.0, c.loop_alpha);
    c.track_bins = fdp.ConsumeIntegralInRange<int>(0, c.window_len / 2);
    c.max_carriers = fdp.ConsumeIntegralInRange<int>(0, 16);
    std::unique_ptr<gr::rfseek::burst_acquirer> made;
    try {
        made = std::make_unique<gr::rfseek::burst_acquirer>(1.0, c); // cycles per sample
    } catch (const std::invalid_argument&) {
        return 0; // a band narrower than 2 bins: refused, as it must be
    }
    auto& acq = *made;
    std::vector<gr::rfseek::acquired_window> out;
    std::uint64_t pushed = 0;
    bool have_slot = false;
    std::uint64_t last_slot = 0;
    while (fdp.remaining_bytes() > 0) {
        if (fdp.ConsumeIntegralInRange<int>(0, 15) == 0) // an overflow's gap, any size
            acq.gap(fdp.ConsumeBool() ? rfseek_gap(fdp) : 0.0);
        const std::size_t n = fdp.ConsumeIntegralInRange<std::size_t>(0, 300);
        std::vector<std::complex<float>> x(n);
        const std::vector<std::uint8_t> raw =
            fdp.ConsumeBytes<std::uint8_t>(n * sizeof(std::complex<float>));
        if (!raw.empty())
            std::memcpy(x.data(), raw.data(), raw.size());
        out.clear();
        acq.push(x.data(), n, out);
        pushed += n;
        for (const auto& w : out) {
            if (w.samples.size() != static_cast<std::size_t>(c.window_len))
                fail("window size", w.samples.size(), c.window_len);
            if (w.start + c.window_len > pushed)
                fail("window beyond the samples pushed", w.start, pushed);
            if (have_slot && w.slot <= last_slot)
                fail("slot not increasing", w.slot, last_slot);
            have_slot = true;
            last_slot = w.slot;
            if (!std::isfinite(w.timing_error) || !std::isfinite(w.detection.g) ||
                !std::isfinite(w.detection.margin_db) ||
                !std::isfinite(w.detection.freq_hz))
                fail("non-finite window figure", w.timing_error, w.detection.g);
        }
        if (!(acq.period_estimate() > 0.0) || !std::isfinite(acq.period_estimate()))
            fail("period estimate", acq.period_estimate(), c.period);
    }
    return 0;
}
