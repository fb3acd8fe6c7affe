/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * burst_detector: finds the simulated beacon bursts (continuous reception, one N-sample
 * burst per slot) at the reference SNR, places their starts, and finds nothing in noise.
 */

#include <gr-rfseek/burst_detector.h>
#include <gr-rfseek/world.h>
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <stdexcept>
#include <vector>

using namespace gr::rfseek;

namespace {
// Continuous reception of `slots` slots; burst k starts at sample k * slot_samples.
std::vector<std::complex<float>> receive(scenario sc, int slots)
{
    world w(sc);
    std::vector<std::complex<float>> x;
    for (int k = 0; k < slots && !w.finished(); ++k) {
        const auto s = w.synthesize(sc.slot_samples());
        x.insert(x.end(), s.begin(), s.end());
        w.advance(w.heading_rad());
    }
    return x;
}
} // namespace

TEST(burst_detector, finds_99_percent_of_bursts_at_the_reference_snr)
{
    scenario sc;
    sc.num_scatterers = 0; // the burst at the reference mean SNR, 0 dB, without fades
    sc.snr_db = 0.0;
    sc.seed = 31;
    const int slots = 400;
    const auto x = receive(sc, slots);
    burst_detector det(2.0, sc.window_len + 1);
    std::vector<std::uint64_t> starts;
    // Fed in uneven chunks, as a scheduler would.
    std::size_t pos = 0, chunk = 777;
    while (pos < x.size()) {
        const std::size_t n = std::min(chunk, x.size() - pos);
        det.push(x.data() + pos, n, pos, starts);
        pos += n;
        chunk = chunk * 7 % 4093 + 100;
    }
    int found = 0;
    for (int k = 1; k < slots; ++k) { // the floor needs the first blocks
        const std::int64_t truth = static_cast<std::int64_t>(k) * sc.slot_samples();
        for (auto s : starts)
            if (std::llabs(static_cast<std::int64_t>(s) - truth) <= 50) {
                ++found;
                break;
            }
    }
    EXPECT_GE(found, 0.99 * (slots - 1));
    EXPECT_LE(starts.size(), static_cast<std::size_t>(slots)); // no extra windows
    EXPECT_NEAR(det.noise_floor() / 1e-7, 1.0, 0.15);
}

TEST(burst_detector, no_false_windows_in_noise_alone)
{
    scenario sc;
    sc.snr_db = -100.0; // the beacon is off: noise only
    sc.seed = 32;
    const auto x = receive(sc, 400); // 2 million samples
    burst_detector det(2.0, sc.window_len + 1);
    std::vector<std::uint64_t> starts;
    det.push(x.data(), x.size(), 0, starts);
    EXPECT_EQ(starts.size(), 0u);
}

TEST(burst_detector, bad_parameters_throw)
{
    EXPECT_THROW(burst_detector(0.0), std::invalid_argument);
    EXPECT_THROW(burst_detector(2.0, 0), std::invalid_argument);
    EXPECT_THROW(burst_detector(2.0, 100, 4), std::invalid_argument);
    EXPECT_THROW(burst_detector(2.0, 100, 256, 8), std::invalid_argument);
}

// Found by fuzzing (lib/fuzz/fuzz_burst_detector.cc): with a holdoff shorter than the
// average, a start was back-dated into the rest of the previous burst (a start could
// repeat or go back). Bursty streams of random on/off runs, pushed in random chunks.
TEST(burst_detector, starts_increase_by_the_holdoff_even_when_it_is_short)
{
    std::srand(7);
    int bursts = 0;
    for (int seed = 0; seed < 300; ++seed) {
        const std::uint64_t holdoff = 1 + std::rand() % 6;
        burst_detector det(3.0, holdoff, 8, 16, 2);
        std::vector<std::uint64_t> starts;
        std::uint64_t offset = 0;
        bool on = false;
        for (int chunk = 0; chunk < 60; ++chunk) {
            std::vector<std::complex<float>> x(1 + std::rand() % 40);
            for (auto& s : x) {
                if (std::rand() % 4 == 0)
                    on = !on;
                const float a = on ? 10.0f : 0.1f + 0.01f * (std::rand() % 10);
                s = { a, 0.0f };
            }
            const std::size_t before = starts.size();
            det.push(x.data(), x.size(), offset, starts);
            for (std::size_t i = before; i < starts.size(); ++i) {
                EXPECT_LT(starts[i], offset + x.size());
                EXPECT_GE(starts[i] + 7, offset); // the change point looks back < 8
                if (i > 0) {
                    EXPECT_GE(starts[i], starts[i - 1] + holdoff)
                        << "seed " << seed << " holdoff " << holdoff;
                }
            }
            offset += x.size();
        }
        bursts += static_cast<int>(starts.size());
    }
    EXPECT_GT(bursts, 300); // the streams did trigger
}
