/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * doppler_estimator: one frequency measurement per beacon window, as a message. A thin
 * adapter over gr::rfseek::tone_estimator.
 */

#ifndef INCLUDED_RFSEEK_DOPPLER_ESTIMATOR_H
#define INCLUDED_RFSEEK_DOPPLER_ESTIMATOR_H

#include <gnuradio/sync_block.h>
#include <gr-rfseek/api.h>
#include <cstdint>
#include <string>
#include <vector>

namespace gr {
namespace rfseek {

/*!
 * \brief Windowed, zero-padded FFT frequency estimator with a "meas" message per window.
 * \ingroup rfseek
 *
 * \details
 * Input: complex64. Windows of window_len samples are taken either on each tag whose key
 * is tag_key and whose value is not False (alignment "tag": the beacons of
 * channel_source or any tagged burst; gr-blocks' burst_tagger's start tags), every
 * period samples starting at offset (alignment "periodic": a continuous beacon), or at
 * each burst found by its power over the noise floor (alignment "energy"; see
 * burst_detector), or where a timing loop locked to the bursts' period puts them
 * (alignment "acquire": a pulsed beacon of window_len samples every period samples,
 * timing unknown, found by narrowband detection at the estimator's own sensitivity;
 * continuous carriers such as an interferer are found, removed and never reported;
 * locked, the search follows the beacon's tone, +-10 bins around it; see
 * burst_acquirer).
 * Each window gives one message on "meas": {slot, time, offset, freq_hz, snr_db,
 * power_db, noise_power_db, valid} plus every field of the aligning tag's dict (heading,
 * ...). time is the sample clock at the window's first sample, from the rx_time/rx_rate
 * tags in force there when present, else offset / samp_rate. An rx_rate tag also sets
 * the rate frequencies are measured at (the rate a radio actually granted;
 * set_samp_rate does the same by hand): a chain that decimates must scale it
 * (radio_source does). An rx_time tag that disagrees with the sample count by half a
 * sample or more is a discontinuity (an overflow: UHD tags the first sample after it):
 * a window straddling it is invalid, "periodic" windows and "acquire"'s timing loop go
 * on in time across it (discontinuity_count counts them). slot comes from the tag;
 * under "periodic" and "acquire" it is the beacon period's number from the stream's
 * start, following time across a gap (a lost burst leaves a gap or an invalid window;
 * "acquire" messages also carry lock, the acquisition's number); else it counts
 * windows. A window cut short by the next tag, or of
 * zero/NaN/Inf samples, gives valid = false with finite placeholders. With pfa > 0
 * (always under "acquire") every window is also tested for a tone at that false-alarm
 * probability (tone_detector): a window of noise alone gives valid = false, and the
 * message carries detect_margin_db (the statistic over its threshold, dB); under
 * "acquire" also timing_error (samples, the loop's prediction against the matched
 * filter).
 */
class RFSEEK_API doppler_estimator : virtual public gr::sync_block
{
public:
    typedef std::shared_ptr<doppler_estimator> sptr;

    /*!
     * \param samp_rate sample rate (Hz, > 0)
     * \param window_len N samples per window (3 <= N <= fft_len)
     * \param fft_len N_FFT (>= 4)
     * \param window "rectangular", "hann" or "blackman_harris"
     * \param interpolator "parabolic" (paper eq. 3), "newton" (ML) or "log_parabolic"
     * \param alignment "tag", "periodic", "energy" or "acquire"
     * \param tag_key key of the aligning tags (alignment "tag")
     * \param period samples between window starts (alignment "periodic", >= window_len;
     *        "acquire": the beacon's nominal period, > window_len)
     * \param offset first window start (alignment "periodic", >= 0)
     * \param min_freq, max_freq search band in Hz; equal values search the whole band
     * \param threshold_db burst detection level over the noise floor (alignment
     *        "energy", > 0 dB)
     * \param pfa false-alarm probability of the per-window detection test: 0 (no test)
     *        or in [1e-12, 0.5]; "acquire" always tests (0 means 1e-3)
     */
    static sptr make(double samp_rate,
                     int window_len,
                     int fft_len,
                     const std::string& window = "rectangular",
                     const std::string& interpolator = "parabolic",
                     const std::string& alignment = "tag",
                     const std::string& tag_key = "rfseek_beacon",
                     std::uint64_t period = 0,
                     std::uint64_t offset = 0,
                     double min_freq = 0.0,
                     double max_freq = 0.0,
                     double threshold_db = 2.0,
                     double pfa = 0.0);

    virtual std::string window() const = 0;
    virtual std::string interpolator() const = 0;
    virtual std::string alignment() const = 0;
    virtual double min_freq() const = 0;
    virtual double max_freq() const = 0;
    //! Windows measured / of them invalid / of them cut short by the next tag.
    virtual std::uint64_t window_count() const = 0;
    virtual std::uint64_t invalid_count() const = 0;
    virtual std::uint64_t truncated_count() const = 0;

    virtual void set_window(const std::string& window) = 0;
    virtual void set_interpolator(const std::string& interpolator) = 0;
    virtual void set_band(double min_freq, double max_freq) = 0;
    virtual void set_threshold_db(double threshold_db) = 0;
    virtual double threshold_db() const = 0;
    //! The sample rate frequencies are measured at (Hz): samp_rate, or the latest
    //! rx_rate tag's or set_samp_rate's.
    virtual double samp_rate() const = 0;
    //! A new sample rate (> 0; the search band must still fit within +-rate/2): e.g. the
    //! rate a device granted. Times go on from the samples already seen at the new rate.
    virtual void set_samp_rate(double samp_rate) = 0;
    //! Detection test's false-alarm probability (0: no test).
    virtual double pfa() const = 0;
    //! 0 turns the test off (not under "acquire"); else in [1e-12, 0.5].
    virtual void set_pfa(double pfa) = 0;
    //! "acquire": "search", "confirm" or "locked"; other alignments: "".
    virtual std::string acquire_state() const = 0;
    //! "acquire": the burst period the timing loop tracks (samples); else period.
    virtual double period_estimate() const = 0;
    //! rx_time tags that disagreed with the sample count (samples lost, or the clock
    //! set back).
    virtual std::uint64_t discontinuity_count() const = 0;
    //! "acquire": the continuous carriers (interferers) found and removed, Hz.
    virtual std::vector<double> carriers() const = 0;
    /*!
     * The receiver's full scale in the input's units (1.0 for UHD, osmosdr and Soapy
     * complex64; 0: unknown, no clipping check, the default). With it, each message
     * carries peak_dbfs (the window's largest |I| or |Q| against full scale) and
     * clipped: a window whose peak reaches -0.45 dBFS (95 % of full scale) was clipped
     * or nearly so, and is never valid. GRC callback; a negative or non-finite value is
     * a ValueError.
     */
    virtual void set_full_scale(double full_scale) = 0;
    virtual double full_scale() const = 0;
    //! Windows found clipped (full_scale > 0).
    virtual std::uint64_t clipped_count() const = 0;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_DOPPLER_ESTIMATOR_H */
