/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * doppler_estimator: window alignment (tags or periodic), the sample clock (rx_time), and
 * the "meas" message around a gr::rfseek::tone_estimator. No estimation logic here.
 */

#include "doppler_estimator_impl.h"
#include <gnuradio/io_signature.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {
int parse_alignment(const std::string& a)
{
    if (a == "tag")
        return 0;
    if (a == "periodic")
        return 1;
    if (a == "energy")
        return 2;
    if (a == "acquire")
        return 3;
    throw std::invalid_argument("doppler_estimator: alignment = '" + a +
                                "': must be 'tag', 'periodic', 'energy' or 'acquire'");
}

std::uint64_t check_period(bool periodic, std::uint64_t period, int window_len)
{
    if (periodic && period < static_cast<std::uint64_t>(std::max(window_len, 1)))
        throw std::invalid_argument(
            "doppler_estimator: period = " + std::to_string(period) +
            ": must be >= window_len (" + std::to_string(window_len) +
            ") for periodic alignment");
    return period;
}
} // namespace

doppler_estimator::sptr doppler_estimator::make(double samp_rate,
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
                                                double pfa)
{
    return gnuradio::make_block_sptr<doppler_estimator_impl>(samp_rate,
                                                             window_len,
                                                             fft_len,
                                                             window,
                                                             interpolator,
                                                             alignment,
                                                             tag_key,
                                                             period,
                                                             offset,
                                                             min_freq,
                                                             max_freq,
                                                             threshold_db,
                                                             pfa);
}

doppler_estimator_impl::doppler_estimator_impl(double samp_rate,
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
                                               double pfa)
    : gr::sync_block("doppler_estimator",
                     gr::io_signature::make(1, 1, sizeof(gr_complex)),
                     gr::io_signature::make(0, 0, 0)),
      d_est(samp_rate, window_len, fft_len, window, interpolator, min_freq, max_freq),
      d_periodic(parse_alignment(alignment) == 1),
      d_energy(parse_alignment(alignment) == 2),
      d_detector(threshold_db, static_cast<std::uint64_t>(std::max(window_len, 1)) + 1),
      d_tag_key(pmt::mp(tag_key)),
      d_period(check_period(d_periodic, period, window_len)),
      d_offset(offset),
      d_buf(window_len),
      d_fields(pmt::PMT_NIL),
      d_clock(samp_rate),
      d_port_meas(pmt::mp("meas")),
      d_key_rx_time(pmt::mp("rx_time")),
      d_key_rx_rate(pmt::mp("rx_rate"))
{
    const bool acquire = parse_alignment(alignment) == 3;
    if (!d_periodic && !d_energy && !acquire && tag_key.empty())
        throw std::invalid_argument("doppler_estimator: tag_key must not be empty for "
                                    "tag alignment");
    check_pfa(pfa);
    if (acquire) {
        if (!(static_cast<double>(period) > window_len))
            throw std::invalid_argument(
                "doppler_estimator: period = " + std::to_string(period) +
                ": must be > window_len (" + std::to_string(window_len) +
                ") for acquire alignment (the beacon's samples from burst to burst)");
        burst_acquirer_config c;
        c.window_len = window_len;
        c.period = static_cast<double>(period);
        c.pfa = pfa > 0.0 ? pfa : 1e-3;
        c.min_freq_hz = min_freq;
        c.max_freq_hz = max_freq;
        d_acq = std::make_unique<burst_acquirer>(samp_rate, c);
    } else if (pfa > 0.0) {
        d_detect = std::make_unique<tone_detector>(
            samp_rate, window_len, pfa, min_freq, max_freq);
    }
    message_port_register_out(d_port_meas);
}

void doppler_estimator_impl::start_window(std::uint64_t abs, const pmt::pmt_t& fields)
{
    d_collecting = true;
    d_fill = 0;
    d_start = abs;
    d_fields = fields;
}

void doppler_estimator_impl::finish_window(bool truncated)
{
    d_collecting = false;
    tone_estimate e;
    tone_detection det;
    if (!truncated) {
        e = d_est.estimate(d_buf.data());
        if (d_detect)
            det = d_detect->test(d_buf.data());
    }
    if (truncated)
        ++d_truncated;
    // Periodic windows are numbered by the period they start in, counted in time.
    const std::uint64_t slot =
        d_periodic ? (d_start + d_shift - d_offset) / d_period : d_windows;
    double peak = 0.0;
    for (std::size_t i = 0; i < d_fill; ++i)
        peak = std::max({ peak,
                          static_cast<double>(std::abs(d_buf[i].real())),
                          static_cast<double>(std::abs(d_buf[i].imag())) });
    publish(d_start,
            e,
            d_fields,
            slot,
            d_detect ? &det : nullptr,
            nullptr,
            std::isfinite(peak) ? peak : 0.0);
}

void doppler_estimator_impl::publish(std::uint64_t start,
                                     tone_estimate e,
                                     const pmt::pmt_t& fields,
                                     std::uint64_t slot,
                                     const tone_detection* det,
                                     const acquired_window* acq,
                                     double peak)
{
    if (det && !det->detected)
        e.valid = false; // noise alone, at the set false-alarm probability
    // A clipped window's frequency and power are not the beacon's alone.
    const bool clipped = d_full_scale > 0.0 && peak >= 0.95 * d_full_scale;
    if (clipped) {
        e.valid = false;
        ++d_clipped;
    }
    ++d_windows;
    if (!e.valid)
        ++d_invalid;

    pmt::pmt_t m = pmt::make_dict();
    // Forward the aligning tag's fields (finite numbers and everything non-numeric).
    if (pmt::is_dict(fields) && !pmt::is_null(fields)) {
        pmt::pmt_t items = pmt::dict_items(fields);
        for (std::size_t i = 0; i < pmt::length(items); ++i) {
            const pmt::pmt_t kv = pmt::nth(i, items);
            const pmt::pmt_t v = pmt::cdr(kv);
            if (pmt::is_real(v) && !std::isfinite(pmt::to_double(v)))
                continue;
            m = pmt::dict_add(m, pmt::car(kv), v);
        }
    } else if (!pmt::is_null(fields)) {
        m = pmt::dict_add(m, pmt::mp("tag_value"), fields);
    }
    if (!pmt::dict_has_key(m, pmt::mp("slot")))
        m = pmt::dict_add(m, pmt::mp("slot"), pmt::from_uint64(slot));
    m = pmt::dict_add(m, pmt::mp("time"), pmt::from_double(d_clock.time_of(start)));
    m = pmt::dict_add(m, pmt::mp("offset"), pmt::from_uint64(start));
    m = pmt::dict_add(m, pmt::mp("freq_hz"), pmt::from_double(e.freq_hz));
    m = pmt::dict_add(m, pmt::mp("snr_db"), pmt::from_double(e.snr_db));
    m = pmt::dict_add(m, pmt::mp("power_db"), pmt::from_double(e.power_db));
    m = pmt::dict_add(m, pmt::mp("noise_power_db"), pmt::from_double(e.noise_power_db));
    if (det)
        m = pmt::dict_add(
            m, pmt::mp("detect_margin_db"), pmt::from_double(det->margin_db));
    if (acq) {
        m = pmt::dict_add(
            m, pmt::mp("timing_error"), pmt::from_double(acq->timing_error));
        m = pmt::dict_add(m, pmt::mp("lock"), pmt::from_uint64(acq->lock));
    }
    if (d_full_scale > 0.0) {
        m = pmt::dict_add(
            m,
            pmt::mp("peak_dbfs"),
            pmt::from_double(std::max(20.0 * std::log10(peak / d_full_scale), -200.0)));
        m = pmt::dict_add(m, pmt::mp("clipped"), pmt::from_bool(clipped));
    }
    m = pmt::dict_add(m, pmt::mp("valid"), pmt::from_bool(e.valid));
    message_port_pub(d_port_meas, m);
}

void doppler_estimator_impl::feed(const gr_complex* in,
                                  std::uint64_t abs,
                                  std::uint64_t count)
{
    while (count > 0) {
        if (!d_collecting) {
            if (!d_periodic)
                return; // between tagged or detected windows: nothing to measure
            // Window starts are offset + k period in the stream's time, which runs
            // d_shift samples ahead of the sample index after gaps.
            const std::uint64_t now = abs + d_shift;
            std::uint64_t next = d_offset;
            if (now > d_offset)
                next = d_offset + ((now - d_offset + d_period - 1) / d_period) * d_period;
            next -= d_shift;
            if (next >= abs + count)
                return;
            in += next - abs;
            count -= next - abs;
            abs = next;
            start_window(abs, pmt::PMT_NIL);
        }
        const std::uint64_t take = std::min<std::uint64_t>(count, d_buf.size() - d_fill);
        std::copy_n(in, take, d_buf.data() + d_fill);
        d_fill += take;
        in += take;
        abs += take;
        count -= take;
        if (d_fill == d_buf.size())
            finish_window(false);
    }
}

void doppler_estimator_impl::on_rate_tag(std::uint64_t offset, const pmt::pmt_t& value)
{
    const double rate = pmt::is_real(value) ? pmt::to_double(value) : -1.0;
    if (!(rate > 0.0) || !std::isfinite(rate)) {
        d_logger->warn("rx_rate tag dropped: not a positive finite number");
        return;
    }
    // The rate the samples really come at is also the one frequencies are measured at
    // (a device that coerced the rate it was asked for).
    const double now = d_est.samp_rate_hz();
    if (std::abs(rate - now) > 1e-9 * now) {
        try {
            apply_rate(rate);
            d_logger->info("rx_rate tag: measuring at {} Hz", rate);
        } catch (const std::invalid_argument& e) {
            d_logger->warn("rx_rate tag {} Hz not followed: {}", rate, e.what());
            return; // neither frequencies nor times take a rate that cannot be used
        }
    }
    d_clock.on_rate(offset, rate); // earlier samples keep their times
}

void doppler_estimator_impl::on_time_tag(std::uint64_t offset, const pmt::pmt_t& value)
{
    if (!(pmt::is_tuple(value) && pmt::length(value) == 2)) {
        d_logger->warn("rx_time tag dropped: not a (seconds, fraction) tuple");
        return;
    }
    const pmt::pmt_t s = pmt::tuple_ref(value, 0);
    const pmt::pmt_t f = pmt::tuple_ref(value, 1);
    if (!((pmt::is_uint64(s) || pmt::is_integer(s)) && pmt::is_real(f))) {
        d_logger->warn("rx_time tag dropped: not a (seconds, fraction) tuple");
        return;
    }
    const double secs = pmt::is_uint64(s) ? static_cast<double>(pmt::to_uint64(s))
                                          : static_cast<double>(pmt::to_long(s));
    bool accepted = false;
    const sample_clock::jump j =
        d_clock.on_time(offset, secs, pmt::to_double(f), &accepted);
    if (!accepted) {
        d_logger->warn("rx_time tag dropped: not a finite time");
        return;
    }
    if (!j.discontinuity)
        return;
    // Samples were lost (or the clock set back): nothing measured straddles the gap.
    if (d_clock.discontinuities() <= 10)
        d_logger->warn("rx_time at sample {} is {:.6f} s off the sample count ({:.0f} "
                       "samples lost): the timing goes on from the new time{}",
                       offset,
                       j.seconds,
                       j.samples,
                       d_clock.discontinuities() == 10
                           ? " (further discontinuities are counted silently; see "
                             "discontinuity_count())"
                           : "");
    if (d_collecting && d_start < offset)
        finish_window(true);
    if (d_acq)
        d_acq->gap(j.samples);
    if (std::isfinite(j.samples) && j.samples >= 0.5 && j.samples < 1e15)
        d_shift += static_cast<std::uint64_t>(std::llround(j.samples));
}

void doppler_estimator_impl::acquire(const gr_complex* in, std::uint64_t count)
{
    if (!d_acq || count == 0)
        return;
    std::vector<acquired_window> done;
    d_acq->push(in, static_cast<std::size_t>(count), done);
    for (const auto& w : done) {
        // Measured in the band the window was found in (around the tracked tone).
        const bool narrowed = w.min_freq_hz != w.max_freq_hz;
        const double lo = d_est.min_freq_hz(), hi = d_est.max_freq_hz();
        bool banded = false;
        if (narrowed) {
            try {
                d_est.set_band(w.min_freq_hz, w.max_freq_hz);
                banded = true;
            } catch (const std::invalid_argument&) {
                // (too narrow for the FFT: measured over the configured band)
            }
        }
        const tone_estimate e = d_est.estimate(w.samples.data());
        if (banded)
            d_est.set_band(lo, hi);
        publish(w.start, e, pmt::PMT_NIL, w.slot, &w.detection, &w, w.peak);
    }
}

void doppler_estimator_impl::forget_old_anchors()
{
    // The oldest sample a window still to be published can start at.
    std::uint64_t oldest = d_seen;
    if (d_collecting)
        oldest = std::min(oldest, d_start);
    if (d_acq)
        oldest = std::min(oldest, d_acq->oldest_held());
    if (d_energy)
        oldest = std::min<std::uint64_t>(oldest, d_hist_end - d_hist.size());
    d_clock.forget_before(oldest);
}

int doppler_estimator_impl::work(int noutput_items,
                                 gr_vector_const_void_star& input_items,
                                 gr_vector_void_star& output_items)
{
    auto in = static_cast<const gr_complex*>(input_items[0]);
    gr::thread::scoped_lock lock(d_setlock);
    const std::uint64_t base = nitems_read(0);
    const std::uint64_t end = base + noutput_items;

    std::vector<gr::tag_t> tags;
    get_tags_in_range(tags, 0, base, end);
    if (d_energy) {
        // Burst starts found from the power; a start may lie in the samples kept from the
        // previous call (at most the detector's averaging length back).
        std::vector<std::uint64_t> starts;
        d_detector.push(in, noutput_items, base, starts);
        for (const auto s : starts) {
            if (s < base) {
                if (d_collecting)
                    finish_window(true);
                start_window(s, pmt::PMT_NIL);
                const std::uint64_t from = d_hist_end - d_hist.size();
                for (std::uint64_t k = std::max(s, from);
                     k < base && d_fill < d_buf.size();
                     ++k)
                    d_buf[d_fill++] = d_hist[k - from];
            } else {
                gr::tag_t t;
                t.offset = s;
                t.key = d_tag_key;
                t.value = pmt::PMT_NIL;
                tags.push_back(t);
            }
        }
    }
    // Clock tags before window tags at the same offset.
    std::stable_sort(
        tags.begin(), tags.end(), [this](const gr::tag_t& a, const gr::tag_t& b) {
            if (a.offset != b.offset)
                return a.offset < b.offset;
            return !pmt::eqv(a.key, d_tag_key) && pmt::eqv(b.key, d_tag_key);
        });

    std::uint64_t pos = base;
    for (const auto& t : tags) {
        const bool is_time = pmt::eqv(t.key, d_key_rx_time);
        const bool is_rate = pmt::eqv(t.key, d_key_rx_rate);
        // A tag whose value is False ends a burst (gr-blocks' burst_tagger marks both
        // ends with the same key): only the others open a window.
        const bool end_tag = pmt::is_bool(t.value) && !pmt::to_bool(t.value);
        const bool is_window = !d_periodic && !d_acq && pmt::eqv(t.key, d_tag_key) &&
                               !end_tag && (!d_energy || pmt::is_null(t.value));
        if (!is_time && !is_rate && !is_window)
            continue;
        feed(in + (pos - base), pos, t.offset - pos);
        acquire(in + (pos - base), t.offset - pos);
        pos = t.offset;
        if (is_time) {
            on_time_tag(t.offset, t.value);
        } else if (is_rate) {
            on_rate_tag(t.offset, t.value);
        } else {
            if (d_collecting)
                finish_window(true);
            start_window(t.offset, t.value);
        }
    }
    feed(in + (pos - base), pos, end - pos);
    acquire(in + (pos - base), end - pos);
    d_seen = end;
    if (d_energy) {
        // Keep the last samples for a burst whose start is found later in them.
        const std::size_t keep = 1024;
        const std::size_t n = static_cast<std::size_t>(noutput_items);
        if (n >= keep) {
            d_hist.assign(in + n - keep, in + n);
        } else {
            d_hist.insert(d_hist.end(), in, in + n);
            if (d_hist.size() > keep)
                d_hist.erase(d_hist.begin(), d_hist.end() - keep);
        }
        d_hist_end = end;
    }
    forget_old_anchors();
    return noutput_items;
}

} // namespace rfseek
} // namespace gr
