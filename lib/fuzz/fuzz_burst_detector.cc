/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * libFuzzer harness: burst_detector on arbitrary sample streams in arbitrary chunks. The
 * starts it reports must be inside what was pushed (or the average_len - 1 samples
 * before, where the change point looks back) and at least holdoff apart, and its noise
 * floor must not become NaN.
 */

#include <fuzzer/FuzzedDataProvider.h>
#include <gr-rfseek/burst_detector.h>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    FuzzedDataProvider fdp(data, size);
    const std::uint64_t holdoff = fdp.ConsumeIntegralInRange<std::uint64_t>(1, 300);
    gr::rfseek::burst_detector det(
        fdp.ConsumeFloatingPointInRange<double>(0.1, 30.0), holdoff, 8, 16, 2);
    std::vector<std::uint64_t> starts;
    std::uint64_t offset = 0;
    while (fdp.remaining_bytes() > 0) {
        const std::size_t n = fdp.ConsumeIntegralInRange<std::size_t>(0, 200);
        std::vector<std::complex<float>> x(n);
        const std::vector<std::uint8_t> raw =
            fdp.ConsumeBytes<std::uint8_t>(n * sizeof(std::complex<float>));
        if (!raw.empty())
            std::memcpy(x.data(), raw.data(), raw.size());
        const std::size_t before = starts.size();
        det.push(x.data(), n, offset, starts);
        for (std::size_t i = before; i < starts.size(); ++i) {
            // The change point looks back up to average_len - 1 = 7 samples.
            if (starts[i] + 7 < offset || starts[i] >= offset + n) {
                std::fprintf(stderr,
                             "start %llu outside [%llu - 7, %llu)\n",
                             (unsigned long long)starts[i],
                             (unsigned long long)offset,
                             (unsigned long long)(offset + n));
                std::abort();
            }
            if (i > 0 && starts[i] < starts[i - 1] + holdoff) {
                std::fprintf(stderr,
                             "start %llu within the holdoff %llu of %llu\n",
                             (unsigned long long)starts[i],
                             (unsigned long long)holdoff,
                             (unsigned long long)starts[i - 1]);
                std::abort();
            }
        }
        offset += n;
        if (std::isnan(det.noise_floor()))
            std::abort();
    }
    return 0;
}
