/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * tone_detector: is there a tone in this window, or only noise? Fisher's g test at a set
 * false-alarm probability. Plain C++ (no GNU Radio types).
 */

#ifndef INCLUDED_RFSEEK_TONE_DETECTOR_H
#define INCLUDED_RFSEEK_TONE_DETECTOR_H

#include <gr-rfseek/api.h>
#include <complex>
#include <memory>
#include <vector>

namespace gr {
namespace rfseek {

//! One window's detection.
struct RFSEEK_API tone_detection {
    double g = 0.0;            //!< statistic: largest in-band periodogram share (0..1)
    double threshold = 1.0;    //!< g above which the window holds a tone
    double margin_db = -100.0; //!< 10 log10(g / threshold): > 0 when detected
    double freq_hz = 0.0;      //!< frequency of the largest in-band bin (coarse)
    bool detected = false;
};

/*!
 * \brief Detection of a tone of unknown frequency, phase and amplitude in white noise of
 * unknown power, at a set false-alarm probability.
 *
 * \details
 * The window of N samples is transformed at 2N points (rectangular window, zero padded).
 * The even bins are the N-point DFT, the odd bins the DFT shifted by half a bin; each
 * set holds N periodogram values that are independent under white Gaussian noise, and
 * each set sums to N times the window energy. The statistic is Fisher's
 *   g = max over the search band of |X_m|^2 / (N sum |x_n|^2),
 * the largest share of the energy one bin takes; it needs no noise estimate. Over B
 * in-band bins of one set, g exceeds x with the exact probability
 *   P1(x) = sum_{j >= 1, j x < 1} (-1)^(j-1) C(B, j) (1 - j x)^(N-1)
 * (uniform spacings), so with both sets P1(x) <= P(g > x) <= 2 P1(x). The threshold
 * solves 2 P1(x) = pfa: the false-alarm probability is at most pfa (and at least pfa /
 * 2). The half-bin set keeps the loss of a tone between bins below 0.9 dB (3.9 dB with
 * the N-point DFT alone).
 */
class RFSEEK_API tone_detector
{
public:
    /*!
     * \param samp_rate_hz sample rate (> 0)
     * \param window_len N (16 <= N <= 2^22)
     * \param pfa false-alarm probability per window (1e-12 <= pfa <= 0.5)
     * \param min_freq_hz, max_freq_hz search band; equal values search the whole band
     * Bad values throw std::invalid_argument naming the parameter and its range.
     */
    tone_detector(double samp_rate_hz,
                  int window_len,
                  double pfa = 1e-3,
                  double min_freq_hz = 0.0,
                  double max_freq_hz = 0.0);
    ~tone_detector();
    tone_detector(const tone_detector&) = delete;
    tone_detector& operator=(const tone_detector&) = delete;

    //! Test window_len() samples at x. Zero, NaN or Inf input is never detected.
    tone_detection test(const std::complex<float>* x);

    double samp_rate_hz() const { return d_fs; }
    int window_len() const { return d_n; }
    double pfa() const { return d_pfa; }
    double min_freq_hz() const { return d_fmin; }
    double max_freq_hz() const { return d_fmax; }
    //! Bins of one set (N-point DFT) in the search band: B above.
    int band_bins() const { return d_bins; }
    //! The g threshold (solves 2 P1 = pfa).
    double threshold() const { return d_threshold; }

    void set_pfa(double pfa);
    void set_band(double min_freq_hz, double max_freq_hz);
    //! A new sample rate (> 0; the band in Hz is kept and must still fit). On a bad
    //! value nothing changes and std::invalid_argument names it.
    void set_samp_rate(double samp_rate_hz);
    /*!
     * Bins within half_width_hz of any of freqs_hz are left out of the search (B and
     * the threshold follow): the places of carriers removed before the test. If they
     * would leave fewer than 2 bins, the band is searched whole.
     */
    void set_exclusions(const std::vector<double>& freqs_hz, double half_width_hz);

    //! P1(x): the exact probability that the largest of B of N uniform-spacing shares
    //! exceeds x (one set of bins; noise only).
    static double set_false_alarm(double x, int window_len, int band_bins);
    //! The x that solves 2 P1(x) = pfa.
    static double threshold_for(double pfa, int window_len, int band_bins);

private:
    void update_threshold();
    struct impl;
    std::unique_ptr<impl> d_impl;
    double d_fs;
    int d_n;
    double d_pfa = 1e-3;
    double d_fmin = 0.0, d_fmax = 0.0;
    std::vector<double> d_excl;
    double d_excl_hw = 0.0;
    int d_bins = 0;
    double d_threshold = 1.0;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_TONE_DETECTOR_H */
