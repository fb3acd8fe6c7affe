/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-bench-estimator: microseconds per window for each interpolator next to one bare
 * FFTW execute of size N_FFT in the same run, and the doppler_estimator block's
 * throughput in periodic mode with every sample inside a window. Prints figures; not a
 * test.  Usage: rfseek-bench-estimator [windows]
 */

#include "bench_args.h"
#include <gnuradio/blocks/head.h>
#include <gnuradio/blocks/vector_source.h>
#include <gnuradio/top_block.h>
#include <fftw3.h>
#include <gr-rfseek/doppler_estimator.h>
#include <gr-rfseek/rng.h>
#include <gr-rfseek/tone_estimator.h>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace gr::rfseek;
using clk = std::chrono::steady_clock;

int main(int argc, char** argv)
{
    const int reps = bench_count(
        argc,
        argv,
        "windows",
        20000,
        100000000,
        "Microseconds per window for each interpolator next to one FFTW execute, and "
        "the doppler_estimator block's throughput.");
    const double fs = 1e5;
    const int n = 1000, nfft = 4096;

    // A noisy tone at 0 dB per-sample SNR, typical of the reference scenario at 5 km.
    std::vector<std::complex<float>> x(n);
    rng g(1);
    for (int k = 0; k < n; ++k) {
        const double p = 2 * M_PI * 1234.5 * k / fs;
        x[k] = std::complex<float>(std::cos(p) + std::sqrt(0.5) * g.normal(),
                                   std::sin(p) + std::sqrt(0.5) * g.normal());
    }

    auto* in = fftwf_alloc_complex(nfft);
    auto* out = fftwf_alloc_complex(nfft);
    fftwf_plan plan = fftwf_plan_dft_1d(nfft, in, out, FFTW_FORWARD, FFTW_MEASURE);
    for (int i = 0; i < nfft; ++i) {
        in[i][0] = i < n ? x[i].real() : 0.0f;
        in[i][1] = i < n ? x[i].imag() : 0.0f;
    }
    auto time_us = [reps](auto&& f) {
        f();
        const auto t0 = clk::now();
        for (int i = 0; i < reps; ++i)
            f();
        return std::chrono::duration<double, std::micro>(clk::now() - t0).count() / reps;
    };
    const double t_fft = time_us([&] { fftwf_execute(plan); });
    std::printf("rfseek-bench-estimator: N = %d, N_FFT = %d, %d windows per figure\n",
                n,
                nfft,
                reps);
    std::printf("  %-30s %8.2f us\n", "FFTW execute (floor)", t_fft);
    double sink = 0.0;
    for (const char* window : { "rectangular", "blackman_harris" }) {
        for (const auto& interp : tone_estimator::interpolators()) {
            tone_estimator est(fs, n, nfft, window, interp);
            const double t = time_us([&] { sink += est.estimate(x.data()).freq_hz; });
            std::printf("  %-14s %-15s %8.2f us  (%.2f x FFT)\n",
                        interp.c_str(),
                        window,
                        t,
                        t / t_fft);
        }
    }
    fftwf_destroy_plan(plan);
    fftwf_free(in);
    fftwf_free(out);

    // Block throughput: every sample inside a window (periodic, period = N).
    for (const char* interp : { "parabolic", "newton" }) {
        const std::uint64_t total = static_cast<std::uint64_t>(reps) * n;
        auto tb = gr::make_top_block("bench");
        auto src = gr::blocks::vector_source_c::make(x, true);
        auto head = gr::blocks::head::make(sizeof(gr_complex), total);
        auto est = doppler_estimator::make(
            fs, n, nfft, "rectangular", interp, "periodic", "", n);
        tb->connect(src, 0, head, 0);
        tb->connect(head, 0, est, 0);
        const auto t0 = clk::now();
        tb->run();
        const double s = std::chrono::duration<double>(clk::now() - t0).count();
        std::printf("  doppler_estimator block, periodic, %-9s %8.2f Msamples/s "
                    "(%llu windows, %.0f x the reference beacon rate)\n",
                    interp,
                    total / s / 1e6,
                    static_cast<unsigned long long>(est->window_count()),
                    (total / s) / (n / 0.05));
    }
    return sink == 12345.0;
}
