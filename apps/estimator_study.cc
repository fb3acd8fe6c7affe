/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-estimator-study: accuracy of the tone estimator versus per-sample SNR, against
 * the Cramer-Rao bound, for each interpolator (N = 1000, Ts = 10 us, N_FFT = 4096 unless
 * told otherwise). Prints a table; --out FILE.csv writes it for
 * scripts/plot_estimator.py.
 *
 *   rfseek-estimator-study [--trials T] [--seed S] [--window W] [--out FILE.csv]
 *                          [--snr-min DB] [--snr-max DB] [--snr-step DB]
 */

#include <gr-rfseek/rng.h>
#include <gr-rfseek/tone_estimator.h>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace gr::rfseek;

int main(int argc, char** argv)
{
    int trials = 2000;
    std::uint64_t seed = 1;
    std::string window = "rectangular", out;
    double snr_min = -20.0, snr_max = 30.0, snr_step = 2.0;
    const double fs = 1e5;
    const int n = 1000, nfft = 4096;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> const char* {
            if (i + 1 >= argc) {
                std::fprintf(
                    stderr, "rfseek-estimator-study: %s needs a value\n", a.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--trials")
            trials = std::atoi(next());
        else if (a == "--seed")
            seed = std::strtoull(next(), nullptr, 10);
        else if (a == "--window")
            window = next();
        else if (a == "--out")
            out = next();
        else if (a == "--snr-min")
            snr_min = std::atof(next());
        else if (a == "--snr-max")
            snr_max = std::atof(next());
        else if (a == "--snr-step")
            snr_step = std::atof(next());
        else {
            std::fprintf(
                stderr,
                "usage: rfseek-estimator-study [--trials T] [--seed S] [--window W] "
                "[--out FILE.csv] [--snr-min DB] [--snr-max DB] [--snr-step DB]\n");
            return a == "--help" || a == "-h" ? 0 : 2;
        }
    }
    if (trials < 1 || !(snr_step > 0.0)) {
        std::fprintf(stderr,
                     "rfseek-estimator-study: --trials >= 1 and --snr-step > 0\n");
        return 2;
    }

    FILE* csv = nullptr;
    if (!out.empty()) {
        csv = std::fopen(out.c_str(), "w");
        if (!csv) {
            std::perror(out.c_str());
            return 1;
        }
        std::fprintf(csv,
                     "interpolator,window,snr_db,trials,crb_hz,rmse_hz,bias_hz,"
                     "outlier_rate,mean_snr_est_db\n");
    }
    std::printf(
        "N = %d, Ts = 10 us, N_FFT = %d, window %s, %d trials per point, seed %llu\n",
        n,
        nfft,
        window.c_str(),
        trials,
        static_cast<unsigned long long>(seed));
    std::printf("outliers: |error| > 100 Hz (excluded from RMSE and bias)\n");
    std::printf("%-14s %7s %10s %10s %8s %10s %9s %9s\n",
                "interpolator",
                "snr_db",
                "crb_hz",
                "rmse_hz",
                "rmse/crb",
                "bias_hz",
                "outliers",
                "snr_est");
    for (const auto& interp : tone_estimator::interpolators()) {
        tone_estimator est(fs, n, nfft, window, interp);
        std::vector<std::complex<float>> x(n);
        for (double snr_db = snr_min; snr_db <= snr_max + 1e-9; snr_db += snr_step) {
            // Same seed for every interpolator: they see the same tones and noise.
            rng g(
                seed, 7, static_cast<std::uint64_t>(std::lround((snr_db + 1000) * 100)));
            const double snr = std::pow(10.0, snr_db / 10.0);
            const double sigma = std::sqrt(0.5 / snr);
            double se = 0.0, bias = 0.0, snr_acc = 0.0;
            int in = 0, outl = 0;
            for (int t = 0; t < trials; ++t) {
                const double f = g.uniform(-45000.0, 45000.0);
                const double ph = g.uniform(0.0, 2 * M_PI);
                for (int k = 0; k < n; ++k) {
                    const double p = 2 * M_PI * f * k / fs + ph;
                    x[k] = std::complex<float>(std::cos(p) + sigma * g.normal(),
                                               std::sin(p) + sigma * g.normal());
                }
                const auto e = est.estimate(x.data());
                const double err = e.freq_hz - f;
                if (!e.valid || std::abs(err) > 100.0) {
                    ++outl;
                } else {
                    se += err * err;
                    bias += err;
                    ++in;
                }
                snr_acc += e.snr_db;
            }
            const double crb = tone_estimator::crb_std_hz(snr, n, fs);
            const double rmse = in ? std::sqrt(se / in) : NAN;
            std::printf("%-14s %7.1f %10.4f %10.4f %8.3f %10.4f %9.4f %9.2f\n",
                        interp.c_str(),
                        snr_db,
                        crb,
                        rmse,
                        rmse / crb,
                        in ? bias / in : NAN,
                        double(outl) / trials,
                        snr_acc / trials);
            if (csv)
                std::fprintf(csv,
                             "%s,%s,%.2f,%d,%.6g,%.6g,%.6g,%.6g,%.4f\n",
                             interp.c_str(),
                             window.c_str(),
                             snr_db,
                             trials,
                             crb,
                             rmse,
                             in ? bias / in : NAN,
                             double(outl) / trials,
                             snr_acc / trials);
        }
    }
    if (csv)
        std::fclose(csv);
    return 0;
}
