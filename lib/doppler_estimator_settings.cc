/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * doppler_estimator: its settings, setters (GRC callbacks) and counters, each under the
 * block's lock (the stream's handling is in doppler_estimator_impl.cc).
 */

#include "doppler_estimator_impl.h"
#include <cmath>
#include <stdexcept>
#include <string>

namespace gr {
namespace rfseek {

std::string doppler_estimator_impl::window() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_est.window();
}

std::string doppler_estimator_impl::interpolator() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_est.interpolator();
}

double doppler_estimator_impl::min_freq() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_est.min_freq_hz();
}

double doppler_estimator_impl::max_freq() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_est.max_freq_hz();
}

std::uint64_t doppler_estimator_impl::window_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_windows;
}

std::uint64_t doppler_estimator_impl::invalid_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_invalid;
}

std::uint64_t doppler_estimator_impl::truncated_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_truncated;
}

void doppler_estimator_impl::set_window(const std::string& window)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_est.set_window(window);
}

void doppler_estimator_impl::set_interpolator(const std::string& interpolator)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_est.set_interpolator(interpolator);
}

void doppler_estimator_impl::set_threshold_db(double threshold_db)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_detector.set_threshold_db(threshold_db);
}

double doppler_estimator_impl::threshold_db() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_detector.threshold_db();
}

void doppler_estimator_impl::set_band(double min_freq, double max_freq)
{
    gr::thread::scoped_lock lock(d_setlock);
    d_est.set_band(min_freq, max_freq);
    if (d_acq)
        d_acq->set_band(min_freq, max_freq);
    if (d_detect)
        d_detect->set_band(min_freq, max_freq);
}

void doppler_estimator_impl::apply_rate(double rate)
{
    const double old = d_est.samp_rate_hz();
    d_est.set_samp_rate(rate); // throws with nothing changed
    try {
        if (d_acq)
            d_acq->set_samp_rate(rate);
        if (d_detect)
            d_detect->set_samp_rate(rate);
    } catch (...) {
        d_est.set_samp_rate(old);
        throw;
    }
}

double doppler_estimator_impl::samp_rate() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_est.samp_rate_hz();
}

void doppler_estimator_impl::set_samp_rate(double samp_rate)
{
    gr::thread::scoped_lock lock(d_setlock);
    try {
        apply_rate(samp_rate);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string("doppler_estimator: ") + e.what());
    }
    d_clock.on_rate(d_seen, samp_rate);
}

double doppler_estimator_impl::pfa() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_acq ? d_acq->config().pfa : (d_detect ? d_detect->pfa() : 0.0);
}

void doppler_estimator_impl::set_pfa(double pfa)
{
    check_pfa(pfa);
    gr::thread::scoped_lock lock(d_setlock);
    if (d_acq) {
        d_acq->set_pfa(pfa > 0.0 ? pfa : 1e-3);
    } else if (pfa == 0.0) {
        d_detect.reset();
    } else if (d_detect) {
        d_detect->set_pfa(pfa);
    } else {
        d_detect = std::make_unique<tone_detector>(d_est.samp_rate_hz(),
                                                   d_est.window_len(),
                                                   pfa,
                                                   d_est.min_freq_hz(),
                                                   d_est.max_freq_hz());
    }
}

std::string doppler_estimator_impl::acquire_state() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_acq ? d_acq->state_name() : std::string();
}

std::uint64_t doppler_estimator_impl::discontinuity_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_clock.discontinuities();
}

void doppler_estimator_impl::set_full_scale(double full_scale)
{
    if (!(full_scale >= 0.0) || !std::isfinite(full_scale))
        throw std::invalid_argument(
            "doppler_estimator: full_scale = " + std::to_string(full_scale) +
            ": must be >= 0 and finite (0: no clipping check)");
    gr::thread::scoped_lock lock(d_setlock);
    d_full_scale = full_scale;
}

double doppler_estimator_impl::full_scale() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_full_scale;
}

std::uint64_t doppler_estimator_impl::clipped_count() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_clipped;
}

std::vector<double> doppler_estimator_impl::carriers() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_acq ? d_acq->carriers() : std::vector<double>();
}

double doppler_estimator_impl::period_estimate() const
{
    gr::thread::scoped_lock lock(setlock());
    return d_acq ? d_acq->period_estimate() : static_cast<double>(d_period);
}

} // namespace rfseek
} // namespace gr
