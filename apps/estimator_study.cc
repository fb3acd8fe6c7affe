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

#include <CLI/CLI.hpp>
#include <gr-rfseek/rng.h>
#include <gr-rfseek/tone_estimator.h>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

using namespace gr::rfseek;

namespace {

const double FS = 1e5;
const int N = 1000, NFFT = 4096;

struct options {
    int trials = 2000;
    std::uint64_t seed = 1;
    std::string window = "rectangular", out;
    double snr_min = -20.0, snr_max = 30.0, snr_step = 2.0;
};

// One point of the study: the estimator's errors over the trials at one SNR.
struct point {
    double rmse = NAN, bias = NAN, outlier_rate = 0.0, mean_snr_est = 0.0;
};

point measure(tone_estimator& est, const options& o, double snr_db)
{
    // Same seed for every interpolator: they see the same tones and noise.
    rng g(o.seed, 7, static_cast<std::uint64_t>(std::lround((snr_db + 1000) * 100)));
    const double sigma = std::sqrt(0.5 / std::pow(10.0, snr_db / 10.0));
    std::vector<std::complex<float>> x(N);
    double se = 0.0, bias = 0.0, snr_acc = 0.0;
    int in = 0, outl = 0;
    for (int t = 0; t < o.trials; ++t) {
        const double f = g.uniform(-45000.0, 45000.0);
        const double ph = g.uniform(0.0, 2 * M_PI);
        for (int k = 0; k < N; ++k) {
            const double p = 2 * M_PI * f * k / FS + ph;
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
    point p;
    if (in) {
        p.rmse = std::sqrt(se / in);
        p.bias = bias / in;
    }
    p.outlier_rate = double(outl) / o.trials;
    p.mean_snr_est = snr_acc / o.trials;
    return p;
}

} // namespace

int main(int argc, char** argv)
{
    options o;
    CLI::App app("Accuracy of the tone estimator versus per-sample SNR, against the "
                 "Cramer-Rao bound, for each interpolator (N = 1000, Ts = 10 us, "
                 "N_FFT = 4096).",
                 "rfseek-estimator-study");
    app.add_option("--trials", o.trials, "trials per point")
        ->check(CLI::Range(1, 100000000))
        ->capture_default_str();
    app.add_option("--seed", o.seed, "seed")
        ->check(CLI::Range(std::uint64_t(0), std::uint64_t(9000000000000000000ULL)))
        ->capture_default_str();
    app.add_option("--window", o.window, "window")
        ->check(CLI::IsMember(tone_estimator::windows()))
        ->capture_default_str();
    app.add_option("--out", o.out, "CSV for scripts/plot_estimator.py");
    app.add_option("--snr-min", o.snr_min, "lowest SNR (dB, in [-100, 100])")
        ->check(CLI::Range(-100.0, 100.0))
        ->capture_default_str();
    app.add_option("--snr-max", o.snr_max, "highest SNR (dB, in [--snr-min, 100])")
        ->check(CLI::Range(-100.0, 100.0))
        ->capture_default_str();
    app.add_option("--snr-step", o.snr_step, "SNR step (dB, in [0.01, 200])")
        ->check(CLI::Range(0.01, 200.0))
        ->capture_default_str();
    try {
        app.parse(argc, argv);
        for (const auto& [name, v] :
             { std::pair<const char*, double>{ "--snr-min", o.snr_min },
               std::pair<const char*, double>{ "--snr-max", o.snr_max },
               std::pair<const char*, double>{ "--snr-step", o.snr_step } })
            if (!std::isfinite(v))
                throw CLI::ValidationError(name, "must be a finite number of dB");
        if (!(o.snr_min <= o.snr_max))
            throw CLI::ValidationError(
                "--snr-max", "must be >= --snr-min (" + std::to_string(o.snr_min) + ")");
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0)
            return app.exit(e);
        std::fprintf(stderr, "rfseek-estimator-study: error: %s\n", e.what());
        return 2;
    }

    FILE* csv = nullptr;
    if (!o.out.empty()) {
        csv = std::fopen(o.out.c_str(), "w");
        if (!csv) {
            std::perror(o.out.c_str());
            return 1;
        }
        std::fprintf(csv,
                     "interpolator,window,snr_db,trials,crb_hz,rmse_hz,bias_hz,"
                     "outlier_rate,mean_snr_est_db\n");
    }
    std::printf(
        "N = %d, Ts = 10 us, N_FFT = %d, window %s, %d trials per point, seed %llu\n",
        N,
        NFFT,
        o.window.c_str(),
        o.trials,
        static_cast<unsigned long long>(o.seed));
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
        tone_estimator est(FS, N, NFFT, o.window, interp);
        for (double snr_db = o.snr_min; snr_db <= o.snr_max + 1e-9;
             snr_db += o.snr_step) {
            const point p = measure(est, o, snr_db);
            const double crb =
                tone_estimator::crb_std_hz(std::pow(10.0, snr_db / 10.0), N, FS);
            std::printf("%-14s %7.1f %10.4f %10.4f %8.3f %10.4f %9.4f %9.2f\n",
                        interp.c_str(),
                        snr_db,
                        crb,
                        p.rmse,
                        p.rmse / crb,
                        p.bias,
                        p.outlier_rate,
                        p.mean_snr_est);
            if (csv)
                std::fprintf(csv,
                             "%s,%s,%.2f,%d,%.6g,%.6g,%.6g,%.6g,%.4f\n",
                             interp.c_str(),
                             o.window.c_str(),
                             snr_db,
                             o.trials,
                             crb,
                             p.rmse,
                             p.bias,
                             p.outlier_rate,
                             p.mean_snr_est);
        }
    }
    if (csv)
        std::fclose(csv);
    return 0;
}
