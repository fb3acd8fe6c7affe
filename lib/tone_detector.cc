/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * tone_detector: Fisher's g over the in-band bins of a 2N-point transform, the threshold
 * from the exact uniform-spacings law (tone_detector.h).
 */

#include "samp_rate.h"
#include <gnuradio/fft/fft.h>
#include <fftw3.h>
#include <gr-rfseek/tone_detector.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace gr {
namespace rfseek {

struct tone_detector::impl {
    int nfft;
    fftwf_complex* in = nullptr;
    fftwf_complex* out = nullptr;
    fftwf_plan plan = nullptr;
    std::vector<int> bins; // in-band bins of the 2N-point transform

    explicit impl(int nfft_) : nfft(nfft_)
    {
        std::lock_guard<std::mutex> lock(gr::fft::planner::mutex());
        in = fftwf_alloc_complex(nfft);
        out = fftwf_alloc_complex(nfft);
        if (!in || !out) {
            fftwf_free(in);
            fftwf_free(out);
            throw std::bad_alloc();
        }
        plan = fftwf_plan_dft_1d(nfft, in, out, FFTW_FORWARD, FFTW_ESTIMATE);
        if (!plan) {
            fftwf_free(in);
            fftwf_free(out);
            throw std::runtime_error("tone_detector: FFTW could not plan the FFT");
        }
        std::memset(in, 0, sizeof(fftwf_complex) * nfft);
    }
    ~impl()
    {
        std::lock_guard<std::mutex> lock(gr::fft::planner::mutex());
        fftwf_destroy_plan(plan);
        fftwf_free(in);
        fftwf_free(out);
    }
    impl(const impl&) = delete;
    impl& operator=(const impl&) = delete;
};

tone_detector::tone_detector(double samp_rate_hz,
                             int window_len,
                             double pfa,
                             double min_freq_hz,
                             double max_freq_hz)
    : d_fs(samp_rate_hz), d_n(window_len)
{
    check_samp_rate("tone_detector", samp_rate_hz);
    if (window_len < 16 || window_len > (1 << 22))
        throw std::invalid_argument(
            "tone_detector: window_len = " + std::to_string(window_len) +
            ": must be in [16, 4194304]");
    d_impl = std::make_unique<impl>(2 * window_len);
    if (!(pfa >= 1e-12 && pfa <= 0.5))
        throw std::invalid_argument("tone_detector: pfa = " + std::to_string(pfa) +
                                    ": must be in [1e-12, 0.5]");
    d_pfa = pfa;
    set_band(min_freq_hz, max_freq_hz);
}

tone_detector::~tone_detector() = default;

void tone_detector::set_pfa(double pfa)
{
    if (!(pfa >= 1e-12 && pfa <= 0.5))
        throw std::invalid_argument("tone_detector: pfa = " + std::to_string(pfa) +
                                    ": must be in [1e-12, 0.5]");
    d_pfa = pfa;
    update_threshold();
}

void tone_detector::set_band(double min_freq_hz, double max_freq_hz)
{
    if (!std::isfinite(min_freq_hz) || !std::isfinite(max_freq_hz))
        throw std::invalid_argument("tone_detector: min_freq/max_freq must be finite");
    const double nyq = 0.5 * d_fs;
    const bool whole = min_freq_hz == max_freq_hz;
    if (!whole && (min_freq_hz < -nyq || max_freq_hz > nyq || min_freq_hz > max_freq_hz))
        throw std::invalid_argument(
            "tone_detector: search band [min_freq, max_freq] = [" +
            std::to_string(min_freq_hz) + ", " + std::to_string(max_freq_hz) +
            "] Hz: must satisfy -samp_rate/2 <= min_freq < max_freq <= samp_rate/2 "
            "(equal values search the whole band)");
    const int nfft = d_impl->nfft;
    std::vector<int> bins;
    int even = 0, odd = 0;
    for (int pass = 0; pass < 2; ++pass) {
        // The second pass, only if the exclusions left too little, ignores them.
        const bool exclude = pass == 0 && !d_excl.empty();
        bins.clear();
        even = odd = 0;
        for (int m = 0; m < nfft; ++m) {
            const int k = m <= nfft / 2 ? m : m - nfft; // signed index, f = k fs / nfft
            const double f = k * d_fs / nfft;
            if (!whole && (f < min_freq_hz || f > max_freq_hz))
                continue;
            if (exclude && std::any_of(d_excl.begin(), d_excl.end(), [&](double e) {
                    return std::abs(std::remainder(f - e, d_fs)) <= d_excl_hw;
                }))
                continue;
            bins.push_back(m);
            (m % 2 == 0 ? even : odd) += 1;
        }
        if (std::max(even, odd) >= 2 || d_excl.empty())
            break;
    }
    if (std::max(even, odd) < 2)
        throw std::invalid_argument("tone_detector: search band [min_freq, max_freq] "
                                    "must span at least 2 bins of the N-point DFT (" +
                                    std::to_string(2.0 * d_fs / d_n) + " Hz)");
    d_impl->bins = std::move(bins);
    d_bins = std::max(even, odd);
    d_fmin = min_freq_hz;
    d_fmax = max_freq_hz;
    update_threshold();
}

void tone_detector::set_exclusions(const std::vector<double>& freqs_hz,
                                   double half_width_hz)
{
    std::vector<double> keep;
    for (const double f : freqs_hz)
        if (std::isfinite(f))
            keep.push_back(f);
    if (keep == d_excl && half_width_hz == d_excl_hw)
        return;
    d_excl = std::move(keep);
    d_excl_hw = std::isfinite(half_width_hz) ? std::max(half_width_hz, 0.0) : 0.0;
    set_band(d_fmin, d_fmax);
}

void tone_detector::set_samp_rate(double samp_rate_hz)
{
    change_samp_rate(
        "tone_detector", d_fs, samp_rate_hz, [this] { set_band(d_fmin, d_fmax); });
}

void tone_detector::update_threshold()
{
    d_threshold = threshold_for(d_pfa, d_n, d_bins);
}

double tone_detector::set_false_alarm(double x, int window_len, int band_bins)
{
    if (!(x > 0.0))
        return 1.0;
    if (x >= 1.0 || band_bins < 1 || window_len < 2)
        return 0.0;
    // Alternating inclusion-exclusion in long double; each term is at most t1^j / j!.
    const long double lb = std::lgamma(band_bins + 1.0L);
    long double sum = 0.0L;
    for (int j = 1; j <= band_bins && j * x < 1.0; ++j) {
        const long double lt =
            lb - std::lgamma(j + 1.0L) - std::lgamma(band_bins - j + 1.0L) +
            (window_len - 1.0L) * std::log1p(-static_cast<long double>(j) * x);
        const long double t = std::exp(lt);
        sum += (j % 2 == 1) ? t : -t;
        if (j > 2 && t < 1e-30L)
            break;
    }
    return std::clamp(static_cast<double>(sum), 0.0, 1.0);
}

double tone_detector::threshold_for(double pfa, int window_len, int band_bins)
{
    // Bracket by the first term t1(x) = B (1 - x)^(N-1): P1 <= t1 and P1 >= t1 - t1^2/2,
    // so the root of 2 P1 = pfa lies between t1 = pfa/2 and t1 = pfa.
    const auto x_at = [&](double t1) {
        const double r = std::log(t1 / band_bins) / (window_len - 1.0);
        return std::clamp(-std::expm1(r), 0.0, 1.0);
    };
    double hi = x_at(0.5 * pfa), lo = x_at(pfa);
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (2.0 * set_false_alarm(mid, window_len, band_bins) > pfa)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

tone_detection tone_detector::test(const std::complex<float>* x)
{
    tone_detection r;
    r.threshold = d_threshold;
    auto* in = reinterpret_cast<std::complex<float>*>(d_impl->in);
    double energy = 0.0;
    for (int i = 0; i < d_n; ++i) {
        in[i] = x[i];
        energy += std::norm(std::complex<double>(x[i]));
    }
    if (!(energy > 0.0) || !std::isfinite(energy))
        return r;
    fftwf_execute(d_impl->plan);
    const auto* out = reinterpret_cast<const std::complex<float>*>(d_impl->out);
    const int nfft = d_impl->nfft;
    double best = -1.0;
    int best_m = 0;
    for (const int m : d_impl->bins) {
        const double p = std::norm(std::complex<double>(out[m]));
        if (p > best) {
            best = p;
            best_m = m;
        }
    }
    r.g = best / (d_n * energy);
    if (!std::isfinite(r.g))
        return tone_detection{ 0.0, d_threshold, -100.0, 0.0, false };
    // Coarse frequency: the vertex of the parabola through |X| around the peak.
    const double ym = std::abs(out[(best_m + nfft - 1) % nfft]);
    const double y0 = std::abs(out[best_m]);
    const double yp = std::abs(out[(best_m + 1) % nfft]);
    const double den = ym + yp - 2.0 * y0;
    const double delta = den < 0.0 ? std::clamp(0.5 * (ym - yp) / den, -0.5, 0.5) : 0.0;
    const int k = best_m <= nfft / 2 ? best_m : best_m - nfft;
    r.freq_hz = (k + delta) * d_fs / nfft;
    r.margin_db =
        r.g > 0.0 ? std::max(10.0 * std::log10(r.g / d_threshold), -100.0) : -100.0;
    r.detected = r.g > d_threshold;
    return r;
}

} // namespace rfseek
} // namespace gr
