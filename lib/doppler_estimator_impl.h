/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#ifndef INCLUDED_RFSEEK_DOPPLER_ESTIMATOR_IMPL_H
#define INCLUDED_RFSEEK_DOPPLER_ESTIMATOR_IMPL_H

#include "sample_clock.h"
#include <gr-rfseek/burst_acquirer.h>
#include <gr-rfseek/burst_detector.h>
#include <gr-rfseek/doppler_estimator.h>
#include <gr-rfseek/tone_estimator.h>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace gr {
namespace rfseek {

//! std::invalid_argument naming pfa unless 0 (no test) or in [1e-12, 0.5].
inline void check_pfa(double pfa)
{
    if (!(pfa == 0.0 || (pfa >= 1e-12 && pfa <= 0.5)))
        throw std::invalid_argument("doppler_estimator: pfa = " + std::to_string(pfa) +
                                    ": must be 0 (no detection test) or in [1e-12, 0.5]");
}

class doppler_estimator_impl : public doppler_estimator
{
public:
    doppler_estimator_impl(double samp_rate,
                           int window_len,
                           int fft_len,
                           const std::string& window,
                           const std::string& interpolator,
                           const std::string& alignment,
                           const std::string& tag_key,
                           std::uint64_t period,
                           std::uint64_t offset,
                           double min_freq,
                           double max_freq,
                           double threshold_db,
                           double pfa);

    int work(int noutput_items,
             gr_vector_const_void_star& input_items,
             gr_vector_void_star& output_items) override;

    std::string window() const override;
    std::string interpolator() const override;
    std::string alignment() const override
    {
        return d_acq      ? "acquire"
               : d_energy ? "energy"
                          : (d_periodic ? "periodic" : "tag");
    }
    double min_freq() const override;
    double max_freq() const override;
    std::uint64_t window_count() const override;
    std::uint64_t invalid_count() const override;
    std::uint64_t truncated_count() const override;

    void set_window(const std::string& window) override;
    void set_interpolator(const std::string& interpolator) override;
    void set_band(double min_freq, double max_freq) override;
    void set_threshold_db(double threshold_db) override;
    double threshold_db() const override;
    double samp_rate() const override;
    void set_samp_rate(double samp_rate) override;
    double pfa() const override;
    void set_pfa(double pfa) override;
    std::string acquire_state() const override;
    double period_estimate() const override;
    std::uint64_t discontinuity_count() const override;
    std::vector<double> carriers() const override;
    void set_full_scale(double full_scale) override;
    double full_scale() const override;
    std::uint64_t clipped_count() const override;

private:
    gr::thread::mutex& setlock() const
    {
        return const_cast<gr::thread::mutex&>(d_setlock);
    }
    void feed(const gr_complex* in, std::uint64_t abs, std::uint64_t count);
    void start_window(std::uint64_t abs, const pmt::pmt_t& fields);
    void finish_window(bool truncated);
    void publish(std::uint64_t start,
                 tone_estimate e,
                 const pmt::pmt_t& fields,
                 std::uint64_t slot,
                 const tone_detection* det,
                 const acquired_window* acq,
                 double peak);
    void apply_rate(double rate);
    void on_rate_tag(std::uint64_t offset, const pmt::pmt_t& value);
    void on_time_tag(std::uint64_t offset, const pmt::pmt_t& value);
    void acquire(const gr_complex* in, std::uint64_t count);
    void forget_old_anchors();

    tone_estimator d_est;
    const bool d_periodic;
    const bool d_energy;
    burst_detector d_detector;
    std::vector<gr_complex> d_hist; // the last samples before the current chunk
    std::uint64_t d_hist_end = 0;   // absolute index one past d_hist's last sample
    const pmt::pmt_t d_tag_key;
    const std::uint64_t d_period;
    const std::uint64_t d_offset;

    std::vector<gr_complex> d_buf;
    bool d_collecting = false;
    std::size_t d_fill = 0;
    std::uint64_t d_start = 0;
    pmt::pmt_t d_fields;
    sample_clock d_clock;      // times from the rx_time / rx_rate tag in force
    std::uint64_t d_shift = 0; // samples lost in the stream's gaps (periodic windows
                               // and their slots follow time across them)
    std::uint64_t d_windows = 0, d_invalid = 0, d_truncated = 0, d_clipped = 0;
    double d_full_scale = 0.0;               // 0: no clipping check
    std::unique_ptr<burst_acquirer> d_acq;   // alignment "acquire"
    std::unique_ptr<tone_detector> d_detect; // the per-window test (pfa > 0), others

    const pmt::pmt_t d_port_meas;
    const pmt::pmt_t d_key_rx_time;
    const pmt::pmt_t d_key_rx_rate;
    std::uint64_t d_seen = 0; // samples seen
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_DOPPLER_ESTIMATOR_IMPL_H */
