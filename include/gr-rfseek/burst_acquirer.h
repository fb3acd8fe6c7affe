/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * burst_acquirer: finds a pulsed beacon (N samples every period, timing unknown) by
 * narrowband detection, locks a timing loop to its period and keeps measuring from the
 * predicted times through fades. Plain C++ (no GNU Radio types).
 */

#ifndef INCLUDED_RFSEEK_BURST_ACQUIRER_H
#define INCLUDED_RFSEEK_BURST_ACQUIRER_H

#include <gr-rfseek/api.h>
#include <gr-rfseek/tone_detector.h>
#include <complex>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gr {
namespace rfseek {

class carrier_notch;

struct RFSEEK_API burst_acquirer_config {
    int window_len = 1000;  //!< N, the burst length in samples (>= 16)
    double period = 5000.0; //!< nominal samples from burst to burst (> window_len)
    double pfa = 1e-3;      //!< false-alarm probability of each window's test
    double min_freq_hz = 0.0, max_freq_hz = 0.0; //!< search band (equal: whole band)
    int hop = 0;          //!< search step in samples (0: window_len / 4)
    int margin = 0;       //!< timing search +- samples (0: min(N / 4, (period - N) / 2))
    int max_misses = 100; //!< undetected bursts in a row before searching again
    double loop_alpha = 0.1;  //!< timing loop: steady-state phase gain (0, 1]
    double loop_beta = 0.005; //!< timing loop: period gain (0, loop_alpha]
    int track_bins = 10;      //!< locked: search +- this many bins (fs / N) around the
                              //!< tracked tone (0: the whole band, always)
    int max_carriers = 4;     //!< continuous carriers removed (0: none, only rejected)
};

//! One beacon window, measured where the timing loop puts the burst.
struct RFSEEK_API acquired_window {
    std::uint64_t start = 0;   //!< absolute index of the window's first sample
    std::uint64_t slot = 0;    //!< period number counted from the stream's first sample
    tone_detection detection;  //!< the detection test of this window
    double timing_error = 0.0; //!< matched-filter start - predicted start (samples)
    std::uint64_t lock = 0;    //!< the acquisition it belongs to (1, 2, ...)
    //! The band its test searched when narrowed around the tracked tone (Hz; equal
    //! values: the configured band).
    double min_freq_hz = 0.0, max_freq_hz = 0.0;
    //! The largest |I| or |Q| of the window's samples as received (before any carrier
    //! is removed): the receiver's clipping shows here.
    double peak = 0.0;
    //! the window_len samples from start, continuous carriers removed and wideband
    //! bursts weighted down (equalize_blocks; power and SNR are those of the weighted
    //! window)
    std::vector<std::complex<float>> samples;
};

/*!
 * \brief Burst timing for a pulsed beacon at the detector's sensitivity.
 *
 * \details
 * Search: windows every hop samples are tested with tone_detector (narrowband: one FFT
 * bin's share of the energy, not wideband power) over one period; the strongest
 * detection is a candidate unless the same frequency is also detected in the windows
 * clear of it (a continuous carrier, e.g. the receiver's DC leak, is not a burst).
 * Carriers: a frequency detected in most windows of a search period is a continuous
 * carrier (an interferer); up to max_carriers of them are removed from every window and
 * every matched filter before they are used (carrier_notch: refined on the samples and
 * projected out) and their bins are left out of the tests, so that a carrier 20 dB
 * above the beacon neither captures the search nor buries the beacon. A carrier that is
 * no longer there in half a search period's windows is forgotten.
 * Timing: the burst start is the maximum over +-margin samples of the matched filter
 * |sum_{n=s}^{s+N-1} x_n exp(-j 2 pi f n / fs)| at the detected frequency (the maximum-
 * likelihood start of a tone burst of known length). Confirm: the candidate is locked
 * when one of the next two predicted bursts is detected too; both are then placed by
 * their matched filters together (their spacing known) and emitted.
 * Locked: each predicted window is tested and measured where predicted; a detected
 * burst's timing error drives an alpha-beta loop on the start and the period (gains
 * 1/n at first, then loop_alpha / loop_beta), which follows a clock offset between
 * beacon and receiver; the period is held within 1 % of the nominal. Undetected
 * bursts are emitted too (detection.detected false) and the loop coasts; after
 * max_misses in a row it searches again. Locked, the test searches only +-track_bins
 * bins around the tone it last detected (the beacon's frequency moves slowly) and the
 * whole band again after 3 misses in a row. slot is the period number from the stream's
 * start, so a burst lost in a fade or a search leaves a gap.
 * Discontinuity: gap() says that samples were lost between the samples pushed so far
 * and the next (an overflow, told by the receiver's rx_time). The bursts go on in time:
 * a lock carries its phase across the gap (the bursts inside it are missing slots, never
 * a renumbering) and must find one of the next two predicted bursts, or it searches
 * again; no window straddles the gap.
 */
class RFSEEK_API burst_acquirer
{
public:
    enum class state { search, confirm, locked };

    //! Bad values throw std::invalid_argument naming the parameter and its range.
    burst_acquirer(double samp_rate_hz, const burst_acquirer_config& cfg);

    //! Feed the next n samples of the stream; appends the windows completed.
    void
    push(const std::complex<float>* x, std::size_t n, std::vector<acquired_window>& out);

    state current_state() const { return d_state; }
    std::string state_name() const;
    //! The period the loop tracks (samples; the nominal one before the first lock).
    double period_estimate() const { return d_period; }
    std::uint64_t acquisitions() const { return d_acquisitions; }
    std::uint64_t losses() const { return d_losses; }
    std::uint64_t samples_seen() const { return d_end; }
    //! The oldest sample a window still to come can start at (windows are emitted late).
    std::uint64_t oldest_held() const { return d_base; }
    std::uint64_t gaps() const { return d_gaps; }

    /*!
     * \brief Samples were lost after those pushed so far: `samples` of them (the
     * receiver's count; fractional). A negative, non-finite or implausibly long gap
     * (over 10^6 periods) ends a lock and searches again. Windows not yet emitted that
     * need samples from before the gap are dropped.
     */
    void gap(double samples);
    const burst_acquirer_config& config() const { return d_cfg; }
    const tone_detector& detector() const { return d_det; }
    //! The continuous carriers removed (Hz).
    std::vector<double> carriers() const;
    //! Locked and searching around the tracked tone: its frequency (Hz); else NaN.
    double tracked_freq() const;

    void set_pfa(double pfa);
    void set_band(double min_freq_hz, double max_freq_hz);
    //! A new sample rate (tone_detector::set_samp_rate); the timing is in samples and
    //! is kept.
    void set_samp_rate(double samp_rate_hz);

private:
    struct trial {
        std::uint64_t pos;
        tone_detection det;
    };
    bool have(std::uint64_t from, std::uint64_t to) const;
    const std::complex<float>* at(std::uint64_t abs) const;
    std::vector<double> matched(std::uint64_t around, double freq_hz) const;
    double refine(std::uint64_t around, double freq_hz) const;
    bool step(std::vector<acquired_window>& out);
    bool step_search();
    bool step_confirm(std::vector<acquired_window>& out);
    bool step_locked(std::vector<acquired_window>& out);
    bool pulsed(const trial& cand) const;
    tone_detection test_at(std::uint64_t start, bool track);
    void learn_carriers(const trial* best);
    bool tracking() const;
    acquired_window make_window(std::uint64_t start,
                                const tone_detection& d,
                                double err,
                                std::uint64_t slot) const;
    void trim();

    double d_fs;
    burst_acquirer_config d_cfg;
    tone_detector d_det;
    int d_hop, d_margin;
    state d_state = state::search;

    std::vector<std::complex<float>> d_buf; // samples [d_base, d_end)
    std::uint64_t d_base = 0, d_end = 0;

    // search
    std::uint64_t d_pos = 0, d_span_start = 0;
    std::vector<trial> d_span;
    // confirm
    std::uint64_t d_cand = 0;
    tone_detection d_cand_det;
    int d_tries = 0;
    // locked: alpha-beta loop on the predicted start
    double d_next = 0.0, d_period;
    std::uint64_t d_slot = 0, d_hits = 0;
    int d_misses = 0;
    bool d_have_slot = false; // a lock has numbered the slots
    double d_last_next = 0.0; // predicted start of slot d_slot when the lock was lost
    bool d_refined = false;   // the candidate's start has been refined
    double d_pred = 0.0;      // confirm: predicted start of the next burst
    std::uint64_t d_acquisitions = 0, d_losses = 0, d_gaps = 0;
    double d_shift = 0.0; // samples lost in gaps so far (the stream's time in samples
                          // is the sample index + d_shift)
    int d_recheck = 0;    // after a gap: predicted bursts left to find one of
    // continuous carriers (carrier_notch, internal), and their presence in the windows
    // of the current search period
    std::shared_ptr<carrier_notch> d_notch;
    std::vector<int> d_carrier_seen;
    int d_span_windows = 0;
    // the window prepared last (carriers removed) and its start
    std::vector<std::complex<float>> d_scratch;
    std::uint64_t d_scratch_start = ~std::uint64_t(0);
    double d_scratch_lo = 0.0, d_scratch_hi = 0.0; // the band it was tested in
    // locked: the test around the tracked tone
    std::unique_ptr<tone_detector> d_track;
    double d_track_freq = 0.0, d_track_lo = 0.0, d_track_hi = 0.0;
    bool d_have_track = false;
    int d_track_misses = 0;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_BURST_ACQUIRER_H */
