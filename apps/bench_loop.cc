/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-bench-loop: cost of the closed loop on the reference scenario (strategy paper):
 * the core simulation's microseconds per slot next to one FFTW execute of size N_FFT, and
 * the GNU Radio flowgraph (channel_source -> doppler_estimator -> seeking_controller, in
 * lockstep) against real time. Prints figures; not a test.
 *   Usage: rfseek-bench-loop [runs]
 */

#include "bench_args.h"
#include <gnuradio/top_block.h>
#include <fftw3.h>
#include <gr-rfseek/channel_source.h>
#include <gr-rfseek/doppler_estimator.h>
#include <gr-rfseek/seeking_controller.h>
#include <gr-rfseek/simulation.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>

using namespace gr::rfseek;
using clk = std::chrono::steady_clock;

int main(int argc, char** argv)
{
    const int runs = bench_count(
        argc,
        argv,
        "runs",
        3,
        100000,
        "Cost of the closed loop on the reference scenario: the core simulation per "
        "slot next to one FFTW execute, and the GNU Radio flowgraph against real time.");
    scenario base;

    auto* in = fftwf_alloc_complex(base.fft_len);
    auto* out = fftwf_alloc_complex(base.fft_len);
    fftwf_plan plan =
        fftwf_plan_dft_1d(base.fft_len, in, out, FFTW_FORWARD, FFTW_MEASURE);
    for (int i = 0; i < base.fft_len; ++i)
        in[i][0] = in[i][1] = static_cast<float>(i % 7);
    fftwf_execute(plan);
    const int reps = 20000;
    auto t0 = clk::now();
    for (int i = 0; i < reps; ++i)
        fftwf_execute(plan);
    const double t_fft =
        std::chrono::duration<double, std::micro>(clk::now() - t0).count() / reps;

    double core_s = 0.0, flight_s = 0.0;
    std::uint64_t slots = 0;
    for (int r = 1; r <= runs; ++r) {
        scenario sc = base;
        sc.seed = r;
        simulation sim(sc, simulation::seeker_for(sc, "paper"));
        t0 = clk::now();
        const auto res = sim.run(false);
        core_s += std::chrono::duration<double>(clk::now() - t0).count();
        slots += res.summary.slots;
        flight_s += res.summary.time_s;
    }
    std::printf(
        "rfseek-bench-loop: reference scenario, strategy paper, %d runs, %llu slots\n",
        runs,
        static_cast<unsigned long long>(slots));
    std::printf("  FFTW execute, size %d (floor)        %8.2f us\n", base.fft_len, t_fft);
    std::printf("  core simulation, per slot            %8.2f us  (%.1f x FFT)\n",
                1e6 * core_s / slots,
                1e6 * core_s / slots / t_fft);
    std::printf("  core simulation, per run             %8.3f s   (%.0f x real time)\n",
                core_s / runs,
                flight_s / core_s);

    double fg_s = 0.0;
    for (int r = 1; r <= runs; ++r) {
        scenario sc = base;
        sc.seed = r;
        auto tb = gr::make_top_block("bench");
        auto src = channel_source::make(sc, "burst", true, false);
        auto est = doppler_estimator::make(sc.samp_rate_hz, sc.window_len, sc.fft_len);
        auto ctl = seeking_controller::make(simulation::seeker_for(sc, "paper"));
        tb->connect(src, 0, est, 0);
        tb->msg_connect(est, "meas", ctl, "meas");
        tb->msg_connect(ctl, "cmd", src, "cmd");
        t0 = clk::now();
        tb->run();
        fg_s += std::chrono::duration<double>(clk::now() - t0).count();
    }
    std::printf("  GNU Radio flowgraph (lockstep), per run %6.3f s   (%.0f x real time, "
                "%.1f us per slot)\n",
                fg_s / runs,
                flight_s / fg_s,
                1e6 * fg_s / slots);
    fftwf_destroy_plan(plan);
    fftwf_free(in);
    fftwf_free(out);
    return 0;
}
