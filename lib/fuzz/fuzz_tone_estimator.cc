/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * libFuzzer harness: tone_estimator on arbitrary sample windows (the bytes are the
 * samples: NaN, inf, denormals, huge values all occur). A valid estimate must be finite
 * and inside the search band; an invalid one must not carry NaN either.
 */

#include <fuzzer/FuzzedDataProvider.h>
#include <gr-rfseek/tone_estimator.h>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    FuzzedDataProvider fdp(data, size);
    static const char* windows[] = { "rectangular", "hann", "blackman_harris" };
    static const char* interps[] = { "parabolic", "newton", "log_parabolic" };
    const int n = 1 << fdp.ConsumeIntegralInRange<int>(2, 7);    // 4..128 samples
    const int nfft = n << fdp.ConsumeIntegralInRange<int>(0, 3); // zero padding
    const double fs = 1e5;
    const bool band = fdp.ConsumeBool();
    const char* window = windows[fdp.ConsumeIntegralInRange<int>(0, 2)];
    const char* interp = interps[fdp.ConsumeIntegralInRange<int>(0, 2)];
    // Constructor arguments are checked elsewhere (qa_tone_estimator: a band narrower
    // than three bins is refused); only accepted configurations are fuzzed here.
    std::unique_ptr<gr::rfseek::tone_estimator> made;
    try {
        made = std::make_unique<gr::rfseek::tone_estimator>(
            fs, n, nfft, window, interp, band ? -2000.0 : 0.0, band ? 2000.0 : 0.0);
    } catch (const std::invalid_argument&) {
        return 0;
    }
    gr::rfseek::tone_estimator& est = *made;
    std::vector<std::complex<float>> x(n);
    const std::vector<std::uint8_t> raw = fdp.ConsumeRemainingBytes<std::uint8_t>();
    if (!raw.empty())
        std::memcpy(x.data(), raw.data(), std::min(raw.size(), x.size() * sizeof(x[0])));
    const gr::rfseek::tone_estimate e = est.estimate(x);
    if (!std::isfinite(e.freq_hz) || std::isnan(e.snr_db) || std::isnan(e.power_db)) {
        std::fprintf(stderr,
                     "valid %d freq %g snr %g power %g\n",
                     e.valid,
                     e.freq_hz,
                     e.snr_db,
                     e.power_db);
        std::abort();
    }
    if (e.valid &&
        (std::abs(e.freq_hz) > fs / 2 || (band && std::abs(e.freq_hz) > 2000.0))) {
        std::fprintf(stderr,
                     "valid estimate %g Hz outside the band (n %d, nfft %d, %s, %s)\n",
                     e.freq_hz,
                     n,
                     nfft,
                     window,
                     interp);
        std::abort();
    }
    return 0;
}
