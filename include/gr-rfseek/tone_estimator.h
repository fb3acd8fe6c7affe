/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * tone_estimator: frequency, SNR and power of the strongest tone in a window of N complex
 * samples (the paper's Sec. III): window, zero padding to N_FFT, FFT (FFTW), peak search
 * (VOLK), then interpolation: the paper's eq. 3 or a maximum-likelihood refinement.
 * Plain C++ (no GNU Radio types).
 */

#ifndef INCLUDED_RFSEEK_TONE_ESTIMATOR_H
#define INCLUDED_RFSEEK_TONE_ESTIMATOR_H

#include <gr-rfseek/api.h>
#include <complex>
#include <memory>
#include <string>
#include <vector>

namespace gr {
namespace rfseek {

//! One window's estimate. When valid is false the numbers are finite placeholders.
struct RFSEEK_API tone_estimate {
    double freq_hz = 0.0;   //!< tone frequency in (-fs/2, fs/2]
    double snr_db = -100.0; //!< per-sample SNR of the tone against the rest of the window
    double power_db = -300.0; //!< tone power per sample (10 log10 |a|^2)
    double noise_power_db =
        -300.0;        //!< noise power per sample (window energy not in the tone)
    int peak_bin = -1; //!< FFT bin of the coarse peak
    //! false on zero, NaN or Inf input, an empty band, or an estimate outside the band
    bool valid = false;
};

class RFSEEK_API tone_estimator
{
public:
    /*!
     * \param samp_rate_hz sample rate (> 0)
     * \param window_len N samples per window (3 <= N <= fft_len)
     * \param fft_len N_FFT (>= 4), zero padding N -> N_FFT
     * \param window "rectangular" (the paper), "hann" or "blackman_harris"
     * \param interpolator "parabolic" (eq. 3), "newton" (maximum likelihood) or
     *        "log_parabolic" (parabola on log |X|)
     * \param min_freq_hz, max_freq_hz search band; equal values (default 0, 0) search the
     *        whole band (-fs/2, fs/2)
     * Bad values throw std::invalid_argument naming the parameter and its range.
     */
    tone_estimator(double samp_rate_hz,
                   int window_len,
                   int fft_len,
                   const std::string& window = "rectangular",
                   const std::string& interpolator = "parabolic",
                   double min_freq_hz = 0.0,
                   double max_freq_hz = 0.0);
    ~tone_estimator();
    tone_estimator(const tone_estimator&) = delete;
    tone_estimator& operator=(const tone_estimator&) = delete;

    //! Estimate from window_len() samples at x.
    tone_estimate estimate(const std::complex<float>* x);

    /*!
     * The FFT input: window_len() samples written here and passed to estimate() are
     * not copied again with the rectangular window (the zero padding after them is never
     * written); other windows leave the windowed samples there. C++ only.
     */
    std::complex<float>* input_buffer();
    tone_estimate estimate(const std::vector<std::complex<float>>& x);

    double samp_rate_hz() const { return d_fs; }
    int window_len() const { return d_n; }
    int fft_len() const { return d_nfft; }
    std::string window() const { return d_window_name; }
    std::string interpolator() const { return d_interp_name; }
    double min_freq_hz() const { return d_fmin; }
    double max_freq_hz() const { return d_fmax; }

    void set_window(const std::string& window);
    void set_interpolator(const std::string& interpolator);
    void set_band(double min_freq_hz, double max_freq_hz);
    //! A new sample rate (> 0; the search band in Hz is kept and must still fit).
    //! On a bad value nothing changes and std::invalid_argument names it.
    void set_samp_rate(double samp_rate_hz);

    static std::vector<std::string> windows();
    static std::vector<std::string> interpolators();

    //! Cramer-Rao bound on the frequency's standard deviation (Hz) for a tone of
    //! per-sample SNR snr_linear in N samples: var = 6 / ((2 pi)^2 SNR N (N^2 - 1) Ts^2).
    static double crb_std_hz(double snr_linear, int window_len, double samp_rate_hz);

private:
    struct impl;
    std::unique_ptr<impl> d_impl;
    double d_fs;
    int d_n;
    int d_nfft;
    std::string d_window_name;
    std::string d_interp_name;
    double d_fmin = 0.0;
    double d_fmax = 0.0;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_TONE_ESTIMATOR_H */
