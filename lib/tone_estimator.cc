/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * tone_estimator: coarse peak of the zero-padded FFT, then
 *  - parabolic: the paper's eq. 3 read as docs/design.md item 4, the vertex of the
 * parabola through |X| at bins i-1, i, i+1: offset (y- - y+) / (2 (y- + y+ - 2 y0)) bins;
 *  - log_parabolic: the same on ln |X| (exact for a Gaussian-shaped peak);
 *  - newton: maximum-likelihood frequency, the maximum of the periodogram
 *    |sum_n x_n exp(-j w n)|^2 of the unwindowed samples, found by Newton steps from the
 *    parabolic estimate. The periodogram and its derivatives near w0 come from moments
 *    M_k = sum_m u_m^k y_m of y_m = x_m exp(-j w0 m) (m centred, u = m / h), so the
 *    iterations cost no pass over the data.
 * SNR and power: the tone's amplitude is the least-squares fit at the estimated
 * frequency; the noise is the window energy the tone does not explain.
 */

#include "kernels.h"
#include "samp_rate.h"
#include <gnuradio/fft/fft.h>
#include <fftw3.h>
#include <gr-rfseek/tone_estimator.h>
#include <volk/volk.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <stdexcept>

// How the FFT is planned (CMake RFSEEK_FFT_PLANNER): FFTW_ESTIMATE (the default) chooses
// without timing, so every process on every machine with the same FFTW computes the same
// floats and a seeded run flies the same slots; FFTW_MEASURE times the candidate
// algorithms and keeps the fastest, which under load may differ from process to process.
#ifndef RFSEEK_FFTW_PLANNER
#define RFSEEK_FFTW_PLANNER FFTW_ESTIMATE
#endif

namespace gr {
namespace rfseek {

namespace {

constexpr double TWO_PI = 2.0 * M_PI;
constexpr int MOMENTS = 8;         // Taylor terms of the periodogram around w0
constexpr double MAX_SHIFT = 0.15; // |D| (rad per unit u) before re-centring
constexpr int BLOCK = 64;          // phasor table length

template <typename T>
struct volk_deleter {
    void operator()(T* p) const { volk_free(p); }
};
template <typename T>
using volk_ptr = std::unique_ptr<T[], volk_deleter<T>>;
template <typename T>
volk_ptr<T> volk_alloc(std::size_t n)
{
    auto* p = static_cast<T*>(volk_malloc(n * sizeof(T), volk_get_alignment()));
    if (!p)
        throw std::bad_alloc();
    std::memset(static_cast<void*>(p), 0, n * sizeof(T));
    return volk_ptr<T>(p);
}

enum class win_kind { rectangular, hann, blackman_harris };
enum class interp_kind { parabolic, newton, log_parabolic };

win_kind parse_window(const std::string& w)
{
    if (w == "rectangular")
        return win_kind::rectangular;
    if (w == "hann")
        return win_kind::hann;
    if (w == "blackman_harris")
        return win_kind::blackman_harris;
    throw std::invalid_argument("tone_estimator: window = '" + w +
                                "': must be one of rectangular, hann, blackman_harris");
}

interp_kind parse_interp(const std::string& i)
{
    if (i == "parabolic")
        return interp_kind::parabolic;
    if (i == "newton")
        return interp_kind::newton;
    if (i == "log_parabolic")
        return interp_kind::log_parabolic;
    throw std::invalid_argument("tone_estimator: interpolator = '" + i +
                                "': must be one of parabolic, newton, log_parabolic");
}

double db(double p, double floor_db)
{
    return p > 0.0 ? std::max(10.0 * std::log10(p), floor_db) : floor_db;
}

} // namespace

struct tone_estimator::impl {
    int n, nfft;
    double c, h; // centre index (N-1)/2 and scale of u = (n - c) / h
    fftwf_complex* in = nullptr;
    fftwf_complex* out = nullptr;
    fftwf_plan plan = nullptr;
    win_kind wk = win_kind::rectangular;
    interp_kind ik = interp_kind::parabolic;
    volk_ptr<float> win;
    volk_ptr<std::complex<float>> y, phasor, xcopy;
    std::vector<float> atab, btab_re, btab_im;
    std::vector<volk_ptr<float>> upow; // u^k, k < MOMENTS
    // search band as bins [kmin, kmax] in signed FFT indexing; full band when !banded
    bool banded = false;
    long kmin = 0, kmax = 0;

    impl(int n_, int nfft_) : n(n_), nfft(nfft_)
    {
        c = 0.5 * (n - 1);
        h = std::max(1.0, c);
        {
            std::lock_guard<std::mutex> lock(gr::fft::planner::mutex());
            in = fftwf_alloc_complex(nfft);
            out = fftwf_alloc_complex(nfft);
            if (!in || !out)
                throw std::bad_alloc();
            plan = fftwf_plan_dft_1d(nfft, in, out, FFTW_FORWARD, RFSEEK_FFTW_PLANNER);
        }
        if (!plan)
            throw std::runtime_error("tone_estimator: FFTW could not plan the FFT");
        std::memset(in, 0, sizeof(fftwf_complex) * nfft);
        win = volk_alloc<float>(n);
        y = volk_alloc<std::complex<float>>(n);
        phasor = volk_alloc<std::complex<float>>(n);
        atab.assign(2 * ((n + BLOCK - 1) / BLOCK), 0.0f);
        btab_re.assign(BLOCK, 0.0f);
        btab_im.assign(BLOCK, 0.0f);
        for (int k = 0; k < MOMENTS; ++k) {
            upow.push_back(volk_alloc<float>(n));
            for (int i = 0; i < n; ++i)
                upow[k][i] = static_cast<float>(std::pow((i - c) / h, k));
        }
    }

    ~impl()
    {
        std::lock_guard<std::mutex> lock(gr::fft::planner::mutex());
        if (plan)
            fftwf_destroy_plan(plan);
        fftwf_free(in);
        fftwf_free(out);
    }

    void make_window(win_kind k)
    {
        wk = k;
        const double L = std::max(1, n - 1);
        for (int i = 0; i < n; ++i) {
            const double t = TWO_PI * i / L;
            double w = 1.0;
            if (k == win_kind::hann)
                w = 0.5 - 0.5 * std::cos(t);
            else if (k == win_kind::blackman_harris)
                w = 0.35875 - 0.48829 * std::cos(t) + 0.14128 * std::cos(2 * t) -
                    0.01168 * std::cos(3 * t);
            win[i] = static_cast<float>(w);
        }
    }

    // y_m = x_m exp(-j w0 (m - c)), returning sum_m y_m (= M_0). The phasor is the
    // product A_a B_b of two short tables (m = BLOCK a + b) built by recurrences in
    // double, so its phase error stays at float rounding and does not walk off.
    std::complex<double> demodulate(const std::complex<float>* x, double w0, bool keep_y)
    {
        const double br = std::cos(w0), bi = -std::sin(w0);
        double pr = 1.0, pi = 0.0;
        for (int b = 0; b < BLOCK; ++b) {
            btab_re[b] = static_cast<float>(pr);
            btab_im[b] = static_cast<float>(pi);
            const double t = pr * br - pi * bi;
            pi = pr * bi + pi * br;
            pr = t;
        }
        const double ar = std::cos(BLOCK * w0), ai = -std::sin(BLOCK * w0);
        pr = std::cos(w0 * c); // A_0 = exp(+j w0 c)
        pi = std::sin(w0 * c);
        const int blocks = (n + BLOCK - 1) / BLOCK;
        for (int i = 0; i < blocks; ++i) {
            atab[2 * i] = static_cast<float>(pr);
            atab[2 * i + 1] = static_cast<float>(pi);
            const double t = pr * ar - pi * ai;
            pi = pr * ai + pi * ar;
            pr = t;
        }
        if (!keep_y)
            return detail::demod_dot(x, n, atab.data(), btab_re.data(), btab_im.data());
        float* ph = reinterpret_cast<float*>(phasor.get());
        for (int i = 0, blk = 0; i < n; i += BLOCK, ++blk) {
            const float fr = atab[2 * blk], fi = atab[2 * blk + 1];
            const int len = std::min(BLOCK, n - i);
            float* o = ph + 2 * i;
            for (int b = 0; b < len; ++b) {
                o[2 * b] = fr * btab_re[b] - fi * btab_im[b];
                o[2 * b + 1] = fr * btab_im[b] + fi * btab_re[b];
            }
        }
        volk_32fc_x2_multiply_32fc(y.get(), x, phasor.get(), n);
        lv_32fc_t m0;
        volk_32fc_accumulator_s32fc(&m0, y.get(), n);
        return std::complex<double>(m0);
    }

    std::complex<double> moment(int k) const
    {
        lv_32fc_t r;
        volk_32fc_32f_dot_prod_32fc(&r, y.get(), upow[k].get(), n);
        return std::complex<double>(r);
    }

    // Newton's method on P(D) = |X(D)|^2, X(D) = sum_m y_m exp(-j D u_m), from D = 0.
    // Returns D; X at D in *xd.
    double newton(std::complex<double>* xd) const
    {
        std::complex<double> M[MOMENTS];
        for (int k = 0; k < MOMENTS; ++k)
            M[k] = moment(k);
        double fact[MOMENTS];
        fact[0] = 1.0;
        for (int k = 1; k < MOMENTS; ++k)
            fact[k] = fact[k - 1] * k;
        const std::complex<double> mj(0.0, -1.0);
        auto eval = [&](double D,
                        std::complex<double>& X,
                        std::complex<double>& X1,
                        std::complex<double>& X2) {
            X = X1 = X2 = 0.0;
            std::complex<double> pk = 1.0; // (-j)^k
            for (int k = 0; k < MOMENTS; ++k) {
                const std::complex<double> t = pk * M[k];
                X += t * std::pow(D, k) / fact[k];
                if (k >= 1)
                    X1 += t * std::pow(D, k - 1) / fact[k - 1];
                if (k >= 2)
                    X2 += t * std::pow(D, k - 2) / fact[k - 2];
                pk *= mj;
            }
        };
        double D = 0.0;
        std::complex<double> X, X1, X2;
        for (int it = 0; it < 20; ++it) {
            eval(D, X, X1, X2);
            const double p1 = 2.0 * std::real(std::conj(X) * X1);
            const double p2 = 2.0 * (std::norm(X1) + std::real(std::conj(X) * X2));
            if (!(p2 < 0.0))
                break; // not at a maximum: keep the current point
            const double step = -p1 / p2;
            D += step;
            if (std::abs(D) > 2.0 * MAX_SHIFT)
                break; // the caller re-centres
            if (std::abs(step) < 1e-12)
                break;
        }
        eval(D, X, X1, X2);
        *xd = X;
        return D;
    }
};

tone_estimator::tone_estimator(double samp_rate_hz,
                               int window_len,
                               int fft_len,
                               const std::string& window,
                               const std::string& interpolator,
                               double min_freq_hz,
                               double max_freq_hz)
    : d_fs(samp_rate_hz), d_n(window_len), d_nfft(fft_len)
{
    check_samp_rate("tone_estimator", samp_rate_hz);
    if (fft_len < 4 || fft_len > (1 << 24))
        throw std::invalid_argument(
            "tone_estimator: fft_len = " + std::to_string(fft_len) +
            ": must be in [4, 16777216]");
    if (window_len < 3 || window_len > fft_len)
        throw std::invalid_argument(
            "tone_estimator: window_len = " + std::to_string(window_len) +
            ": must be in [3, fft_len=" + std::to_string(fft_len) + "]");
    const win_kind wk = parse_window(window);
    const interp_kind ik = parse_interp(interpolator);
    d_impl = std::make_unique<impl>(window_len, fft_len);
    d_impl->make_window(wk);
    d_impl->ik = ik;
    d_window_name = window;
    d_interp_name = interpolator;
    set_band(min_freq_hz, max_freq_hz);
}

tone_estimator::~tone_estimator() = default;

void tone_estimator::set_window(const std::string& window)
{
    d_impl->make_window(parse_window(window));
    d_window_name = window;
}

void tone_estimator::set_interpolator(const std::string& interpolator)
{
    d_impl->ik = parse_interp(interpolator);
    d_interp_name = interpolator;
}

void tone_estimator::set_band(double min_freq_hz, double max_freq_hz)
{
    if (!std::isfinite(min_freq_hz) || !std::isfinite(max_freq_hz))
        throw std::invalid_argument("tone_estimator: min_freq/max_freq must be finite");
    if (min_freq_hz == max_freq_hz) {
        d_impl->banded = false;
        d_fmin = d_fmax = min_freq_hz;
        return;
    }
    const double nyq = 0.5 * d_fs;
    if (min_freq_hz < -nyq || max_freq_hz > nyq || min_freq_hz > max_freq_hz)
        throw std::invalid_argument(
            "tone_estimator: search band [min_freq, max_freq] = [" +
            std::to_string(min_freq_hz) + ", " + std::to_string(max_freq_hz) +
            "] Hz: must satisfy -samp_rate/2 <= min_freq < max_freq <= samp_rate/2 "
            "(equal values search the whole band)");
    const long kmin = static_cast<long>(std::ceil(min_freq_hz * d_nfft / d_fs));
    const long kmax = static_cast<long>(std::floor(max_freq_hz * d_nfft / d_fs));
    if (kmax - kmin < 2)
        throw std::invalid_argument(
            "tone_estimator: search band [min_freq, max_freq] = [" +
            std::to_string(min_freq_hz) + ", " + std::to_string(max_freq_hz) +
            "] Hz: must hold at least 3 FFT bin centres, which are samp_rate / fft_len "
            "= " +
            std::to_string(d_fs / d_nfft) +
            " Hz apart (a band 2 bins wide holds 3 when it starts on one)");
    d_impl->banded = true;
    d_impl->kmin = kmin;
    d_impl->kmax = std::min(kmax, kmin + d_nfft - 1);
    d_fmin = min_freq_hz;
    d_fmax = max_freq_hz;
}

void tone_estimator::set_samp_rate(double samp_rate_hz)
{
    change_samp_rate(
        "tone_estimator", d_fs, samp_rate_hz, [this] { set_band(d_fmin, d_fmax); });
}

std::vector<std::string> tone_estimator::windows()
{
    return { "rectangular", "hann", "blackman_harris" };
}

std::vector<std::string> tone_estimator::interpolators()
{
    return { "parabolic", "newton", "log_parabolic" };
}

double tone_estimator::crb_std_hz(double snr_linear, int window_len, double samp_rate_hz)
{
    const double N = window_len;
    const double ts = 1.0 / samp_rate_hz;
    return std::sqrt(6.0 / (TWO_PI * TWO_PI * snr_linear * N * (N * N - 1.0) * ts * ts));
}

std::complex<float>* tone_estimator::input_buffer()
{
    return reinterpret_cast<std::complex<float>*>(d_impl->in);
}

tone_estimate tone_estimator::estimate(const std::vector<std::complex<float>>& x)
{
    if (x.size() < static_cast<std::size_t>(d_n))
        throw std::invalid_argument(
            "tone_estimator: need window_len = " + std::to_string(d_n) +
            " samples, got " + std::to_string(x.size()));
    return estimate(x.data());
}

tone_estimate tone_estimator::estimate(const std::complex<float>* x)
{
    impl& m = *d_impl;
    tone_estimate r;
    const int n = m.n, nfft = m.nfft;

    auto* in = reinterpret_cast<std::complex<float>*>(m.in);
    auto* out = reinterpret_cast<lv_32fc_t*>(m.out);
    double energy = 0.0; // sum |x|^2, from Parseval when the window is rectangular
    if (m.wk == win_kind::rectangular) {
        if (x != in)
            std::memcpy(in, x, sizeof(std::complex<float>) * n);
    } else {
        if (x == in) { // windowing in place would lose the samples demodulate() needs
            if (!m.xcopy)
                m.xcopy = volk_alloc<std::complex<float>>(n);
            std::memcpy(m.xcopy.get(), x, sizeof(std::complex<float>) * n);
            x = m.xcopy.get();
        }
        lv_32fc_t e32;
        volk_32fc_x2_conjugate_dot_prod_32fc(&e32, x, x, n);
        energy = std::real(std::complex<double>(e32));
        volk_32fc_32f_multiply_32fc(in, x, m.win.get(), n);
    }
    fftwf_execute(m.plan);

    // Coarse peak: the largest |X|^2 over the band.
    const auto* spec = reinterpret_cast<const std::complex<float>*>(out);
    uint32_t peak = 0;
    if (!m.banded || m.wk == win_kind::rectangular) {
        const auto all = detail::peak_search(spec, nfft);
        peak = all.index;
        if (m.wk == win_kind::rectangular)
            energy = all.total / nfft;
    }
    if (!std::isfinite(energy) || !(energy > 0.0))
        return r; // zero, NaN or Inf input
    if (m.banded) {
        const long a = ((m.kmin % nfft) + nfft) % nfft;
        const long len = m.kmax - m.kmin + 1;
        const long first = std::min<long>(len, nfft - a);
        const auto p1 = detail::peak_search(spec + a, first);
        peak = static_cast<uint32_t>(a + p1.index);
        if (len > first) {
            const auto p2 = detail::peak_search(spec, len - first);
            if (p2.value > p1.value)
                peak = p2.index;
        }
    }
    const double y0 = std::abs(out[peak]);
    if (!(y0 > 0.0) || !std::isfinite(y0))
        return r;
    const double ym = std::abs(out[(peak + nfft - 1) % nfft]);
    const double yp = std::abs(out[(peak + 1) % nfft]);
    // The largest bin of the band but not a peak of the spectrum: it is the skirt of a
    // tone outside the band (at the band's edge; found by fuzzing), not a measurement.
    if (d_fmax > d_fmin && (ym > y0 || yp > y0))
        return r;

    double delta = 0.0; // bins
    if (m.ik == interp_kind::log_parabolic && ym > 0.0 && yp > 0.0) {
        const double lm = std::log(ym), l0 = std::log(y0), lp = std::log(yp);
        const double den = lm + lp - 2.0 * l0;
        if (den < 0.0)
            delta = 0.5 * (lm - lp) / den;
    } else {
        const double den = ym + yp - 2.0 * y0;
        if (den < 0.0)
            delta = 0.5 * (ym - yp) / den;
    }
    delta = std::clamp(delta, -0.5, 0.5);
    double w = TWO_PI * (peak + delta) / nfft; // rad/sample
    if (w > M_PI)
        w -= TWO_PI;

    // Tone amplitude at the estimate: X(w) of the unwindowed samples.
    const bool newton = m.ik == interp_kind::newton;
    std::complex<double> X = m.demodulate(x, w, newton);
    if (newton) {
        for (int round = 0; round < 4; ++round) {
            const double D = m.newton(&X);
            if (std::abs(D) <= MAX_SHIFT) {
                w += D / m.h;
                break;
            }
            // Far from the start point: re-centre the expansion on the new estimate,
            // within one FFT bin of the coarse peak.
            const double bin = TWO_PI / nfft;
            w += std::clamp(D / m.h, -bin, bin);
            X = m.demodulate(x, w, true);
        }
    }
    if (w > M_PI)
        w -= TWO_PI;
    else if (w <= -M_PI)
        w += TWO_PI;

    const double Y = std::norm(X);
    const double noise = std::max(energy - Y / n, 0.0) / (n - 1);
    const double tone = std::max(Y / (double(n) * n) - noise / n, 0.0);
    r.freq_hz = w * d_fs / TWO_PI;
    r.power_db = db(tone, -300.0);
    r.noise_power_db = db(noise, -300.0);
    if (noise > 0.0)
        r.snr_db = std::clamp(db(tone / noise, -100.0), -100.0, 200.0);
    else
        r.snr_db = 200.0;
    r.peak_bin = static_cast<int>(peak);
    r.valid = std::isfinite(r.freq_hz);
    // Interpolation from a peak in the band's edge bin can land up to half a bin outside
    // the band (found by fuzzing): a tone outside the band asked for is not a
    // measurement.
    if (d_fmax > d_fmin && (r.freq_hz < d_fmin || r.freq_hz > d_fmax))
        r.valid = false;
    if (!r.valid)
        r = tone_estimate();
    return r;
}

} // namespace rfseek
} // namespace gr
