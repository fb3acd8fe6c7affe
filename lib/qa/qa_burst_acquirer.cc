/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * burst_acquirer: locks to a pulsed beacon whose clock is 20 ppm off the receiver's,
 * numbers slots from time (a missed burst is an undetected window in its own slot, a
 * lost lock a gap), rejects a continuous carrier, and stays quiet on noise.
 */

#include <gr-rfseek/burst_acquirer.h>
#include <gr-rfseek/rng.h>
#include <gtest/gtest.h>
#include <cmath>
#include <complex>
#include <set>
#include <stdexcept>
#include <vector>

using namespace gr::rfseek;

namespace {
struct beacon {
    int n = 256;
    double period = 1280.0; // the beacon's own period, in receiver samples
    double t0 = 517.3;      // first burst start
    double snr_db = -3.0;
    double freq = 0.1234; // cycles per sample
    std::set<int> silent; // bursts not sent
    double carrier = 0.0; // amplitude of a continuous carrier at carrier_freq
    double carrier_freq = 0.0;
    std::uint64_t drop_at = 0, drop_len = 0; // samples lost (not pushed) from drop_at
    bool lie = false; // tell the acquirer `told` instead of the true gap (drop_len)
    double told = 0.0;
    double start(int k) const { return t0 + k * period; }
};

// Runs `total` samples of the beacon plus unit-power noise through the acquirer in
// chunks of 4096; returns its windows.
std::vector<acquired_window>
run(const beacon& b, burst_acquirer& acq, std::uint64_t total, std::uint64_t seed)
{
    rng r(seed);
    const double a = std::sqrt(std::pow(10.0, b.snr_db / 10.0));
    const double s = std::sqrt(0.5);
    std::vector<acquired_window> out;
    std::vector<std::complex<float>> x;
    int k = 0;
    double phase = 0.0;
    for (std::uint64_t base = 0; base < total; base += x.size()) {
        x.assign(std::min<std::uint64_t>(4096, total - base), 0.0f);
        for (std::size_t i = 0; i < x.size(); ++i) {
            const double t = static_cast<double>(base + i);
            while (b.start(k) + b.n <= t) {
                ++k;
                phase = r.uniform(0.0, 2.0 * M_PI);
            }
            std::complex<double> v(s * r.normal(), s * r.normal());
            const double st = std::ceil(b.start(k));
            if (t >= st && t < st + b.n && !b.silent.count(k))
                v += std::polar(a, phase + 2.0 * M_PI * b.freq * t);
            if (b.carrier > 0.0)
                v += std::polar(b.carrier, 2.0 * M_PI * b.carrier_freq * t);
            x[i] = std::complex<float>(v);
        }
        // An overflow: the samples of [drop_at, drop_at + drop_len) never arrive, and
        // the acquirer is told of the gap before the next sample.
        const std::uint64_t end = base + x.size();
        const std::uint64_t g0 = b.drop_at, g1 = b.drop_at + b.drop_len;
        for (std::uint64_t i = base; i < end;) {
            if (b.drop_len > 0 && i >= g0 && i < g1) {
                if (i == g0)
                    acq.gap(b.lie ? b.told : static_cast<double>(b.drop_len));
                i = std::min(end, g1);
                continue;
            }
            const std::uint64_t stop = b.drop_len > 0 && i < g0 ? std::min(end, g0) : end;
            acq.push(x.data() + (i - base), stop - i, out);
            i = stop;
        }
    }
    return out;
}

// A window's start in the samples generated (the pushed index plus the gap before it).
double generated(const beacon& b, const acquired_window& w)
{
    return static_cast<double>(w.start) + (b.drop_len > 0 && w.start >= b.drop_at
                                               ? static_cast<double>(b.drop_len)
                                               : 0.0);
}

burst_acquirer_config config(const beacon& b, double nominal_period)
{
    burst_acquirer_config c;
    c.window_len = b.n;
    c.period = nominal_period;
    c.pfa = 1e-3;
    return c;
}

// Index of the true burst nearest to a window start.
int nearest(const beacon& b, std::uint64_t start)
{
    return static_cast<int>(std::lround((static_cast<double>(start) - b.t0) / b.period));
}
} // namespace

TEST(burst_acquirer, timing_loop_locks_across_20_ppm)
{
    for (const double ppm : { 20.0, -20.0 }) {
        beacon b;
        b.period = 20000.0 * (1.0 + ppm * 1e-6); // 0.4 samples a period off nominal
        const int periods = 600;
        double mean_err[2];
        for (const double beta : { 0.005, 0.0 }) {
            auto c = config(b, 20000.0);
            c.loop_beta = beta;
            burst_acquirer acq(100e3, c);
            const auto w = run(b, acq, static_cast<std::uint64_t>(periods * 20000.0), 5);
            ASSERT_GT(w.size(), periods - 5u);
            EXPECT_EQ(acq.acquisitions(), 1u);
            double sum = 0.0;
            int cnt = 0;
            for (std::size_t i = 0; i < w.size(); ++i) {
                const int k = nearest(b, w[i].start);
                EXPECT_EQ(w[i].slot, static_cast<std::uint64_t>(k));
                const double err =
                    static_cast<double>(w[i].start) - std::ceil(b.start(k));
                if (beta > 0.0) {
                    EXPECT_LT(std::abs(err), 12.0) << "window " << i;
                }
                if (i >= w.size() - 200) {
                    sum += err;
                    ++cnt;
                }
            }
            mean_err[beta > 0.0 ? 0 : 1] = sum / cnt;
            if (beta > 0.0) {
                EXPECT_NEAR(acq.period_estimate(), b.period, 0.2);
            }
        }
        // The period term removes the lag a phase-only loop keeps (0.4 / alpha = 4
        // samples behind the drift: early when the beacon's period is the longer).
        EXPECT_LT(std::abs(mean_err[0]), 1.0) << ppm << " ppm";
        EXPECT_GT(std::abs(mean_err[1]), 2.5) << ppm << " ppm, phase-only loop";
        EXPECT_LT(mean_err[1] * ppm, 0.0) << "the lag trails the drift";
    }
}

TEST(burst_acquirer, slots_count_periods_so_missed_bursts_show)
{
    beacon b;
    b.snr_db = 0.0;
    for (int k : { 20, 21, 30 }) // fades
        b.silent.insert(k);
    for (int k = 60; k < 200; ++k) // the beacon off long enough to lose the lock
        b.silent.insert(k);
    burst_acquirer acq(100e3, config(b, b.period));
    const auto w = run(b, acq, static_cast<std::uint64_t>(260 * b.period), 9);
    EXPECT_EQ(acq.acquisitions(), 2u);
    EXPECT_EQ(acq.losses(), 1u);
    std::set<std::uint64_t> slots;
    for (const auto& win : w) {
        const int k = nearest(b, win.start);
        EXPECT_EQ(win.slot, static_cast<std::uint64_t>(k)) << "start " << win.start;
        EXPECT_EQ(win.detection.detected, !b.silent.count(k)) << "burst " << k;
        EXPECT_TRUE(slots.insert(win.slot).second) << "slot " << win.slot << " twice";
        ASSERT_EQ(win.samples.size(), static_cast<std::size_t>(b.n));
    }
    // The fades are measured (undetected windows in their slots); the long silence
    // is coasted for max_misses periods, then a gap until the beacon is found again.
    EXPECT_TRUE(slots.count(20) && slots.count(21) && slots.count(30));
    EXPECT_TRUE(slots.count(159));
    EXPECT_FALSE(slots.count(160));
    EXPECT_FALSE(slots.count(199));
    EXPECT_TRUE(slots.count(205));
}

TEST(burst_acquirer, a_continuous_carrier_is_not_a_burst)
{
    beacon b;
    b.silent = {};
    for (int k = 0; k < 400; ++k)
        b.silent.insert(k);
    b.carrier = 0.5; // -6 dB per sample, continuous (a receiver's DC leak at 0 Hz)
    burst_acquirer acq(100e3, config(b, b.period));
    auto w = run(b, acq, static_cast<std::uint64_t>(300 * b.period), 3);
    EXPECT_EQ(acq.acquisitions(), 0u);
    EXPECT_TRUE(w.empty());
    // With the beacon on (stronger than the carrier) it locks to the beacon.
    b.silent = {};
    b.carrier = 0.2;
    burst_acquirer acq2(100e3, config(b, b.period));
    w = run(b, acq2, static_cast<std::uint64_t>(100 * b.period), 3);
    EXPECT_EQ(acq2.acquisitions(), 1u);
    ASSERT_GT(w.size(), 90u);
    for (const auto& win : w)
        EXPECT_NEAR(win.detection.freq_hz, b.freq * 100e3, 200.0);
}

TEST(burst_acquirer, noise_alone_is_rarely_valid)
{
    beacon b;
    for (int k = 0; k < 6000; ++k)
        b.silent.insert(k);
    burst_acquirer acq(100e3, config(b, b.period));
    const auto w = run(b, acq, static_cast<std::uint64_t>(5000 * b.period), 17);
    int detected = 0;
    for (const auto& win : w)
        detected += win.detection.detected;
    // A false lock needs two detections a period apart (pfa 1e-3 each, 20 candidate
    // positions a period): well under one in 5000 periods.
    EXPECT_LE(acq.acquisitions(), 1u);
    EXPECT_LE(detected, 5) << "of 5000 beacon periods";
}

TEST(burst_acquirer, bad_settings_name_the_parameter)
{
    burst_acquirer_config c;
    c.period = 1000.0;
    try {
        burst_acquirer a(100e3, c);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("period"), std::string::npos);
    }
    c = burst_acquirer_config();
    c.loop_alpha = 0.0;
    EXPECT_THROW(burst_acquirer(100e3, c), std::invalid_argument);
    c = burst_acquirer_config();
    c.pfa = 0.0;
    EXPECT_THROW(burst_acquirer(100e3, c), std::invalid_argument);
    c = burst_acquirer_config();
    c.hop = 5000;
    EXPECT_THROW(burst_acquirer(100e3, c), std::invalid_argument);
}

// Bursts whose starts jump by up to +-15 samples from period to period (garbage timing)
// with the loop's gains at their largest: the tracked period stays within 1 % of the
// nominal (found by fuzzing: it went negative) and the loop keeps measuring.
TEST(BurstAcquirer, the_period_stays_within_one_percent_whatever_the_timing_errors)
{
    const int n = 64;
    const double period = 80.0;
    burst_acquirer_config c;
    c.window_len = n;
    c.period = period;
    c.margin = 16;
    c.loop_alpha = 1.0;
    c.loop_beta = 1.0;
    burst_acquirer acq(1.0, c);
    rng r(11);
    std::vector<std::complex<float>> x(static_cast<std::size_t>(period * 400), 0.0f);
    for (int k = 0; k < 398; ++k) {
        const int s =
            static_cast<int>(k * period) + 20 + static_cast<int>(r.uniform(-15, 15));
        for (int i = 0; i < n; ++i)
            x[s + i] = std::polar(1.0f, static_cast<float>(2.0 * M_PI * 0.2 * (s + i)));
    }
    for (auto& v : x)
        v += std::complex<float>(0.05f * r.normal(), 0.05f * r.normal());
    std::vector<acquired_window> out;
    double lo = period, hi = period;
    for (std::size_t i = 0; i < x.size(); i += 37) {
        acq.push(x.data() + i, std::min<std::size_t>(37, x.size() - i), out);
        lo = std::min(lo, acq.period_estimate());
        hi = std::max(hi, acq.period_estimate());
    }
    EXPECT_GE(lo, 0.99 * period);
    EXPECT_LE(hi, 1.01 * period);
    EXPECT_GT(out.size(), 300u);
}

TEST(burst_acquirer, a_gap_keeps_the_phase_and_slots_follow_time)
{
    // 4321 samples lost mid-lock (an overflow, 3.4 periods): the bursts inside it are
    // missing slots, the next burst is measured where it is, and nothing straddles it.
    beacon b;
    b.drop_at = 40 * 1280 + 900;
    b.drop_len = 4321;
    burst_acquirer acq(100e3, config(b, 1280.0));
    const auto w = run(b, acq, 120 * 1280, 3);
    EXPECT_EQ(acq.acquisitions(), 1u);
    EXPECT_EQ(acq.losses(), 0u);
    EXPECT_EQ(acq.gaps(), 1u);
    int after = 0;
    for (const auto& x : w) {
        const double g = generated(b, x);
        const int k = static_cast<int>(std::lround((g - b.t0) / b.period));
        EXPECT_EQ(x.slot, static_cast<std::uint64_t>(k)) << "at " << g;
        EXPECT_LT(std::abs(g - std::ceil(b.start(k))), 12.0) << "slot " << x.slot;
        // Nothing before the gap reaches into it; nothing after starts inside it.
        if (x.start < b.drop_at)
            EXPECT_LE(x.start + b.n, b.drop_at);
        if (x.start >= b.drop_at && after++ == 0) {
            EXPECT_TRUE(x.detection.detected) << "the first burst after the gap";
            EXPECT_EQ(x.slot,
                      static_cast<std::uint64_t>(
                          std::ceil((b.drop_at + b.drop_len - b.t0) / b.period)));
        }
    }
    EXPECT_GT(after, 70);
}

TEST(burst_acquirer, a_gap_told_wrong_is_searched_again)
{
    // The count says half a period less than was lost: the phase is wrong, the next two
    // predicted bursts are not there, and the beacon is found again.
    beacon b;
    b.drop_at = 30 * 1280 + 100;
    b.drop_len = 3000;
    b.lie = true;
    b.told = 3000 - 640;
    burst_acquirer acq(100e3, config(b, 1280.0));
    const auto w = run(b, acq, 90 * 1280, 4);
    EXPECT_EQ(acq.losses(), 1u);
    EXPECT_EQ(acq.acquisitions(), 2u);
    std::size_t second = 0;
    for (const auto& x : w) {
        if (x.lock != 2)
            continue;
        ++second;
        const double g = generated(b, x);
        const int k = static_cast<int>(std::lround((g - b.t0) / b.period));
        EXPECT_LT(std::abs(g - std::ceil(b.start(k))), 12.0);
    }
    EXPECT_GT(second, 40u);
}

TEST(burst_acquirer, a_clock_set_back_or_absurd_gap_ends_the_lock)
{
    for (const double told : { -500.0, std::nan(""), 1e30 }) {
        beacon b;
        b.drop_at = 20 * 1280;
        b.drop_len = 1; // (one sample lost; the acquirer is told otherwise)
        b.lie = true;
        b.told = told;
        burst_acquirer acq(100e3, config(b, 1280.0));
        const auto w = run(b, acq, 60 * 1280, 6);
        EXPECT_EQ(acq.losses(), 1u) << told;
        EXPECT_EQ(acq.acquisitions(), 2u) << told;
        for (std::size_t i = 1; i < w.size(); ++i)
            EXPECT_GT(w[i].slot, w[i - 1].slot);
    }
}

TEST(burst_acquirer, a_carrier_20_dB_above_the_beacon_is_removed_and_the_beacon_found)
{
    // The carrier 20 dB above the beacon and 25 bins (of fs / N) away, continuous.
    // Without removal it takes every window's largest bin (and the test's energy); the
    // beacon is never found.
    for (const int max_carriers : { 4, 0 }) {
        beacon b;
        b.snr_db = -3.0;
        b.carrier = std::sqrt(std::pow(10.0, (b.snr_db + 20.0) / 10.0));
        b.carrier_freq = b.freq + 25.0 / b.n;
        auto c = config(b, b.period);
        c.max_carriers = max_carriers;
        burst_acquirer acq(100e3, c);
        const auto w = run(b, acq, static_cast<std::uint64_t>(150 * b.period), 8);
        if (max_carriers == 0) {
            EXPECT_EQ(acq.acquisitions(), 0u);
            continue;
        }
        EXPECT_EQ(acq.acquisitions(), 1u);
        ASSERT_EQ(acq.carriers().size(), 1u);
        EXPECT_NEAR(acq.carriers()[0], b.carrier_freq * 100e3, 1.0);
        int detected = 0;
        for (const auto& win : w) {
            if (!win.detection.detected)
                continue;
            ++detected;
            EXPECT_NEAR(win.detection.freq_hz, b.freq * 100e3, 200.0);
        }
        EXPECT_GE(detected, 0.97 * 145);
    }
}

TEST(burst_acquirer, locked_it_searches_around_the_tone_and_widens_when_lost)
{
    beacon b;
    for (int k = 60; k < 70; ++k)
        b.silent.insert(k); // a fade of 10 bursts
    burst_acquirer acq(100e3, config(b, b.period));
    const auto w = run(b, acq, static_cast<std::uint64_t>(100 * b.period), 9);
    EXPECT_EQ(acq.acquisitions(), 1u);
    const double bin = 100e3 / b.n, f = b.freq * 100e3;
    int narrowed = 0, whole = 0;
    for (const auto& win : w) {
        const int k = nearest(b, win.start);
        if (win.min_freq_hz != win.max_freq_hz) {
            ++narrowed;
            EXPECT_NEAR(0.5 * (win.min_freq_hz + win.max_freq_hz), f, 1.0 * bin);
            EXPECT_NEAR(win.max_freq_hz - win.min_freq_hz, 20.0 * bin, 0.5 * bin);
        } else if (k > 2) {
            ++whole;
            // Only after three misses in a row: the fade's 4th to 10th bursts.
            EXPECT_GE(k, 63) << "slot " << win.slot;
            EXPECT_LE(k, 70) << "slot " << win.slot;
        }
    }
    EXPECT_GT(narrowed, 80);
    EXPECT_EQ(whole, 8); // bursts 63-69 and the first found again (70)
}
