/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-bench-world: cost of synthesising one beacon slot (reference scenario, L = 10)
 * next to one FFTW execute of size N_FFT, measured in the same run. Prints figures;
 * not a test.  Usage: rfseek-bench-world [slots]
 */

#include "bench_args.h"
#include <fftw3.h>
#include <gr-rfseek/world.h>
#include <chrono>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace gr::rfseek;
using clk = std::chrono::steady_clock;

namespace {

template <typename F>
double us_per_call(int reps, F&& f)
{
    f(); // warm-up
    const auto t0 = clk::now();
    for (int i = 0; i < reps; ++i)
        f();
    return std::chrono::duration<double, std::micro>(clk::now() - t0).count() / reps;
}

} // namespace

int main(int argc, char** argv)
{
    const int reps = bench_count(
        argc,
        argv,
        "slots",
        20000,
        100000000,
        "Cost of synthesising one beacon slot (reference scenario) next to one FFTW "
        "execute of size N_FFT, measured in the same run.");
    scenario sc;
    sc.seed = 1;

    // One FFTW execute of size N_FFT (complex float, out of place, FFTW_MEASURE plan).
    const int nfft = sc.fft_len;
    auto* in = fftwf_alloc_complex(nfft);
    auto* out = fftwf_alloc_complex(nfft);
    fftwf_plan plan = fftwf_plan_dft_1d(nfft, in, out, FFTW_FORWARD, FFTW_MEASURE);
    for (int i = 0; i < nfft; ++i) {
        in[i][0] = static_cast<float>(i % 7) - 3.0f;
        in[i][1] = static_cast<float>(i % 5) - 2.0f;
    }
    const double t_fft = us_per_call(reps, [&] { fftwf_execute(plan); });

    std::vector<std::complex<float>> buf(sc.slot_samples());
    world w(sc);
    const double t_burst =
        us_per_call(reps, [&] { w.synthesize(buf.data(), sc.window_len); });
    scenario quiet = sc;
    quiet.add_noise = false;
    world wq(quiet);
    const double t_clean =
        us_per_call(reps, [&] { wq.synthesize(buf.data(), sc.window_len); });
    const double t_cont =
        us_per_call(reps / 5 + 1, [&] { w.synthesize(buf.data(), sc.slot_samples()); });
    world wa(sc);
    const double t_adv = us_per_call(reps, [&] {
        if (wa.finished())
            wa = world(sc);
        wa.advance(wa.heading_rad() + 0.001);
    });

    std::printf("rfseek-bench-world: reference scenario, L = %d scatterers, N = %d, "
                "N_FFT = %d, %d repetitions\n",
                sc.num_scatterers,
                sc.window_len,
                nfft,
                reps);
    std::printf("  FFTW execute, size %d (floor)          %8.2f us\n", nfft, t_fft);
    std::printf("  beacon slot, burst (N samples, noise)   %8.2f us  (%.2f x FFT)\n",
                t_burst,
                t_burst / t_fft);
    std::printf("  beacon slot, burst, noise-free          %8.2f us  (%.2f x FFT)\n",
                t_clean,
                t_clean / t_fft);
    std::printf("  whole slot, continuous (%d samples)   %8.2f us  (%.2f x FFT)\n",
                sc.slot_samples(),
                t_cont,
                t_cont / t_fft);
    std::printf("  world.advance (kinematics, CFO)         %8.3f us\n", t_adv);

    fftwf_destroy_plan(plan);
    fftwf_free(in);
    fftwf_free(out);
    return 0;
}
