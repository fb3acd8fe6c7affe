/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * burst_acquirer: search, confirm, lock (burst_acquirer.h).
 */

#include "carrier_notch.h"
#include <gr-rfseek/burst_acquirer.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gr {
namespace rfseek {

namespace {
burst_acquirer_config checked(burst_acquirer_config c)
{
    const auto bad = [](const std::string& what) {
        throw std::invalid_argument("burst_acquirer: " + what);
    };
    if (c.window_len < 16 || c.window_len > (1 << 22))
        bad("window_len = " + std::to_string(c.window_len) +
            ": must be in [16, 4194304]");
    if (!(c.period > c.window_len) || !std::isfinite(c.period) || c.period > 1e12)
        bad("period = " + std::to_string(c.period) + ": must be > window_len (" +
            std::to_string(c.window_len) + ") samples and finite");
    if (c.hop < 0 || c.hop > c.window_len)
        bad("hop = " + std::to_string(c.hop) + ": must be in [0, window_len] (0: N / 4)");
    if (c.margin < 0 || c.margin > c.window_len)
        bad("margin = " + std::to_string(c.margin) +
            ": must be in [0, window_len] (0: automatic)");
    if (c.max_misses < 1)
        bad("max_misses = " + std::to_string(c.max_misses) + ": must be >= 1");
    if (!(c.loop_alpha > 0.0 && c.loop_alpha <= 1.0))
        bad("loop_alpha = " + std::to_string(c.loop_alpha) + ": must be in (0, 1]");
    if (!(c.loop_beta >= 0.0 && c.loop_beta <= c.loop_alpha))
        bad("loop_beta = " + std::to_string(c.loop_beta) +
            ": must be in [0, loop_alpha]");
    if (c.track_bins < 0 || c.track_bins > c.window_len / 2)
        bad("track_bins = " + std::to_string(c.track_bins) +
            ": must be in [0, window_len / 2] (0: the whole band)");
    if (c.max_carriers < 0 || c.max_carriers > 16)
        bad("max_carriers = " + std::to_string(c.max_carriers) + ": must be in [0, 16]");
    return c;
}
} // namespace

burst_acquirer::burst_acquirer(double samp_rate_hz, const burst_acquirer_config& cfg)
    : d_fs(samp_rate_hz),
      d_cfg(checked(cfg)),
      d_det(samp_rate_hz, cfg.window_len, cfg.pfa, cfg.min_freq_hz, cfg.max_freq_hz),
      d_hop(cfg.hop > 0 ? cfg.hop : std::max(1, cfg.window_len / 4)),
      d_margin(cfg.margin > 0 ? cfg.margin
                              : static_cast<int>(std::min(
                                    0.25 * cfg.window_len,
                                    std::floor(0.5 * (cfg.period - cfg.window_len))))),
      d_period(cfg.period),
      d_notch(std::make_shared<carrier_notch>(
          samp_rate_hz, static_cast<std::size_t>(std::max(cfg.max_carriers, 1)))),
      d_scratch(static_cast<std::size_t>(cfg.window_len))
{
}

std::vector<double> burst_acquirer::carriers() const { return d_notch->freqs(); }

bool burst_acquirer::tracking() const
{
    return d_state == state::locked && d_cfg.track_bins > 0 && d_have_track &&
           d_track_misses < 3;
}

double burst_acquirer::tracked_freq() const
{
    return tracking() ? d_track_freq : std::nan("");
}

tone_detection burst_acquirer::test_at(std::uint64_t start, bool track)
{
    const auto* x = at(start);
    std::copy(x, x + d_cfg.window_len, d_scratch.begin());
    std::vector<double> share;
    d_notch->apply(d_scratch.data(), d_scratch.size(), &share, d_state == state::search);
    equalize_blocks(d_scratch.data(),
                    d_scratch.size(),
                    std::max<std::size_t>(8, d_scratch.size() / 20));
    d_scratch_start = start;
    d_scratch_lo = d_scratch_hi = 0.0;
    if (d_state == state::search) {
        ++d_span_windows;
        d_carrier_seen.resize(share.size(), 0);
        for (std::size_t c = 0; c < share.size(); ++c)
            d_carrier_seen[c] += share[c] > d_det.threshold() ? 1 : 0;
    }
    if (!track)
        return d_det.test(d_scratch.data());
    // Around the tracked tone, within the configured band.
    const double bin = d_fs / d_cfg.window_len;
    const bool whole = d_cfg.min_freq_hz == d_cfg.max_freq_hz;
    const double lo = std::max(d_track_freq - d_cfg.track_bins * bin,
                               whole ? -0.5 * d_fs : d_cfg.min_freq_hz);
    const double hi = std::min(d_track_freq + d_cfg.track_bins * bin,
                               whole ? 0.5 * d_fs : d_cfg.max_freq_hz);
    if (hi - lo < 4.0 * bin)
        return d_det.test(d_scratch.data());
    if (!d_track) {
        d_track =
            std::make_unique<tone_detector>(d_fs, d_cfg.window_len, d_cfg.pfa, lo, hi);
        d_track->set_exclusions(d_notch->freqs(), 2.0 * bin);
    } else if (std::abs(lo - d_track_lo) > 0.25 * bin ||
               std::abs(hi - d_track_hi) > 0.25 * bin) {
        d_track->set_band(lo, hi);
    } else {
        d_scratch_lo = lo;
        d_scratch_hi = hi;
        return d_track->test(d_scratch.data());
    }
    d_track_lo = lo;
    d_track_hi = hi;
    d_scratch_lo = lo;
    d_scratch_hi = hi;
    return d_track->test(d_scratch.data());
}

void burst_acquirer::learn_carriers(const trial* best)
{
    if (d_cfg.max_carriers <= 0)
        return;
    const double bin = d_fs / d_cfg.window_len;
    bool changed = false;
    // Forget the carriers present in fewer than half of this period's windows.
    for (std::size_t c = d_notch->freqs().size(); c-- > 0;)
        if (c < d_carrier_seen.size() && 2 * d_carrier_seen[c] < d_span_windows) {
            d_notch->remove(c);
            changed = true;
        }
    // The strongest detection was continuous: a carrier, removed from now on.
    if (best && d_notch->add(best->det.freq_hz, 2.0 * bin))
        changed = true;
    d_carrier_seen.assign(d_notch->freqs().size(), 0);
    d_span_windows = 0;
    if (changed) {
        d_det.set_exclusions(d_notch->freqs(), 2.0 * bin);
        if (d_track)
            d_track->set_exclusions(d_notch->freqs(), 2.0 * bin);
    }
}

std::string burst_acquirer::state_name() const
{
    switch (d_state) {
    case state::search:
        return "search";
    case state::confirm:
        return "confirm";
    default:
        return "locked";
    }
}

void burst_acquirer::set_pfa(double pfa)
{
    d_det.set_pfa(pfa);
    d_cfg.pfa = pfa;
    d_track.reset();
}

void burst_acquirer::set_band(double min_freq_hz, double max_freq_hz)
{
    d_det.set_band(min_freq_hz, max_freq_hz);
    d_cfg.min_freq_hz = min_freq_hz;
    d_cfg.max_freq_hz = max_freq_hz;
}

void burst_acquirer::set_samp_rate(double samp_rate_hz)
{
    d_det.set_samp_rate(samp_rate_hz);
    d_fs = samp_rate_hz;
    d_notch->set_samp_rate(samp_rate_hz);
    d_track.reset();
}

bool burst_acquirer::have(std::uint64_t from, std::uint64_t to) const
{
    return from >= d_base && to <= d_end;
}

const std::complex<float>* burst_acquirer::at(std::uint64_t abs) const
{
    return d_buf.data() + (abs - d_base);
}

std::vector<double> burst_acquirer::matched(std::uint64_t around, double freq_hz) const
{
    // |sum_{n=s}^{s+N-1} x_n exp(-j w n)|^2 for s = around - margin .. around + margin
    // (entries outside the samples held stay -1).
    const std::uint64_t n = d_cfg.window_len;
    std::vector<double> out(2 * static_cast<std::size_t>(d_margin) + 1, -1.0);
    const std::int64_t first = static_cast<std::int64_t>(around) - d_margin;
    const std::uint64_t lo = std::max<std::uint64_t>(
        first > 0 ? static_cast<std::uint64_t>(first) : 0, d_base);
    if (d_end < n + lo)
        return out;
    const std::uint64_t hi = std::min<std::uint64_t>(around + d_margin, d_end - n);
    if (hi < lo)
        return out;
    const double w = -2.0 * M_PI * freq_hz / d_fs;
    const std::size_t len = hi - lo + n;
    std::vector<std::complex<double>> y(len);
    // The carriers removed from the stretch first (their sidelobes would ripple the
    // matched filter).
    std::vector<std::complex<float>> x(at(lo), at(lo) + len);
    d_notch->apply(x.data(), x.size());
    for (std::size_t i = 0; i < len; ++i) {
        const std::complex<double> v(x[i]);
        y[i] = std::isfinite(v.real()) && std::isfinite(v.imag())
                   ? v * std::polar(1.0, w * static_cast<double>(i))
                   : 0.0;
    }
    std::complex<double> s = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        s += y[i];
    for (std::uint64_t k = lo;; ++k) {
        out[static_cast<std::size_t>(static_cast<std::int64_t>(k) - first)] =
            std::norm(s);
        if (k == hi)
            break;
        s += y[k - lo + n] - y[k - lo];
    }
    return out;
}

double burst_acquirer::refine(std::uint64_t around, double freq_hz) const
{
    const auto c = matched(around, freq_hz);
    const auto best = std::max_element(c.begin(), c.end()) - c.begin();
    if (c[static_cast<std::size_t>(best)] < 0.0)
        return static_cast<double>(around);
    return static_cast<double>(around) + static_cast<double>(best - d_margin);
}

acquired_window burst_acquirer::make_window(std::uint64_t start,
                                            const tone_detection& d,
                                            double err,
                                            std::uint64_t slot) const
{
    acquired_window w;
    w.start = start;
    w.slot = slot;
    w.detection = d;
    w.timing_error = err;
    w.lock = d_acquisitions;
    w.peak = 0.0;
    for (const auto* x = at(start); x != at(start) + d_cfg.window_len; ++x)
        w.peak = std::max({ w.peak,
                            static_cast<double>(std::abs(x->real())),
                            static_cast<double>(std::abs(x->imag())) });
    if (!std::isfinite(w.peak))
        w.peak = 0.0;
    if (d_scratch_start == start) {
        w.samples = d_scratch;
        w.min_freq_hz = d_scratch_lo;
        w.max_freq_hz = d_scratch_hi;
    } else {
        const auto* x = at(start);
        w.samples.assign(x, x + d_cfg.window_len);
        d_notch->apply(w.samples.data(), w.samples.size());
        equalize_blocks(w.samples.data(),
                        w.samples.size(),
                        std::max<std::size_t>(8, w.samples.size() / 20));
    }
    return w;
}

bool burst_acquirer::pulsed(const trial& cand) const
{
    const double n = d_cfg.window_len;
    const double df = 2.0 * d_fs / n;
    int off = 0, same = 0;
    for (const auto& t : d_span) {
        double d = std::fmod(static_cast<double>(t.pos) - static_cast<double>(cand.pos),
                             d_cfg.period);
        if (d < 0.0)
            d += d_cfg.period;
        if (d < n + d_hop || d_cfg.period - d < n + d_hop)
            continue; // this window may hold part of a burst
        ++off;
        if (t.det.detected && std::abs(t.det.freq_hz - cand.det.freq_hz) <= df)
            ++same;
    }
    return !(off > 0 && 2 * same > off);
}

bool burst_acquirer::step_search()
{
    const std::uint64_t n = d_cfg.window_len;
    if (d_pos < d_base)
        d_pos = d_span_start = d_base;
    if (!have(d_pos, d_pos + n))
        return false;
    d_span.push_back({ d_pos, test_at(d_pos, false) });
    d_pos += d_hop;
    if (static_cast<double>(d_pos - d_span_start) < d_cfg.period)
        return true;
    const trial* best = nullptr;
    for (const auto& t : d_span)
        if (t.det.detected && (!best || t.det.g > best->det.g))
            best = &t;
    learn_carriers(best && !pulsed(*best) ? best : nullptr);
    if (best && pulsed(*best)) {
        d_state = state::confirm;
        d_cand = best->pos;
        d_cand_det = best->det;
        d_tries = 0;
        d_refined = false;
    }
    d_span.clear();
    d_span_start = d_pos;
    return true;
}

bool burst_acquirer::step_confirm(std::vector<acquired_window>& out)
{
    const std::uint64_t n = d_cfg.window_len;
    const std::uint64_t m = d_margin;
    if (!d_refined) {
        if (!have(std::max(d_base, d_cand >= m ? d_cand - m : 0), d_cand + n + m))
            return false;
        d_cand = static_cast<std::uint64_t>(refine(d_cand, d_cand_det.freq_hz));
        d_cand_det = test_at(d_cand, false);
        d_pred = static_cast<double>(d_cand) + d_period;
        d_refined = true;
        return true;
    }
    const auto p = static_cast<std::uint64_t>(std::llround(d_pred));
    if (!have(p - m, p + n + m))
        return false;
    const tone_detection det = test_at(p, false);
    if (!det.detected) {
        if (++d_tries >= 2) { // not confirmed: search on from here
            d_state = state::search;
            d_pos = d_span_start = p + n;
            d_span.clear();
        } else {
            d_pred += d_period;
        }
        return true;
    }
    // The two bursts' matched filters together (their spacing known), for a start
    // twice as sure as one burst's.
    const auto c1 = matched(d_cand, d_cand_det.freq_hz);
    const auto c2 = matched(p, det.freq_hz);
    std::size_t best = static_cast<std::size_t>(d_margin);
    for (std::size_t i = 0; i < c1.size(); ++i)
        if (c1[i] >= 0.0 && c2[i] >= 0.0 && c1[i] + c2[i] > c1[best] + c2[best])
            best = i;
    const std::int64_t shift = static_cast<std::int64_t>(best) - d_margin;
    d_cand = static_cast<std::uint64_t>(static_cast<std::int64_t>(d_cand) + shift);
    const auto p2 = static_cast<std::uint64_t>(static_cast<std::int64_t>(p) + shift);
    const double err = static_cast<double>(p2) - d_pred;
    // Slots: the period number from the stream's start; after a lost lock, counted on
    // from the last predicted slot so that the gap shows.
    std::uint64_t slot0;
    const double first = static_cast<double>(d_cand);
    if (!d_have_slot) {
        slot0 = static_cast<std::uint64_t>(std::floor((first + d_shift) / d_cfg.period));
        d_have_slot = true;
    } else {
        const double k = std::llround((first - d_last_next) / d_period);
        slot0 = d_slot + static_cast<std::uint64_t>(std::max(0.0, k));
    }
    const std::uint64_t slot1 = slot0 + 1 + static_cast<std::uint64_t>(d_tries);
    ++d_acquisitions;
    d_have_track = false; // (the first two are measured over the whole band)
    const tone_detection d1 = test_at(d_cand, false);
    out.push_back(make_window(d_cand, d1, 0.0, slot0));
    const tone_detection d2 = test_at(p2, false);
    out.push_back(make_window(p2, d2, err, slot1));
    d_have_track = d2.detected || d1.detected;
    d_track_freq = d2.detected ? d2.freq_hz : d1.freq_hz;
    d_track_misses = 0;
    d_state = state::locked;
    d_hits = 2;
    d_misses = 0;
    d_slot = slot1 + 1;
    d_next = static_cast<double>(p2) + d_period;
    return true;
}

bool burst_acquirer::step_locked(std::vector<acquired_window>& out)
{
    const std::uint64_t n = d_cfg.window_len;
    const std::uint64_t m = d_margin;
    const auto p = static_cast<std::uint64_t>(std::llround(std::max(d_next, 0.0)));
    if (!have(p >= m ? p - m : 0, p + n + m) || p < d_base)
        return false;
    const tone_detection det = test_at(p, tracking());
    double err = 0.0;
    if (det.detected) {
        err = refine(p, det.freq_hz) - d_next;
        ++d_hits;
        d_misses = 0;
        const double a = std::max(d_cfg.loop_alpha, 1.0 / static_cast<double>(d_hits));
        // A clock offset is parts per million: the period is held within 1 % of the
        // nominal, whatever a burst of garbage makes the errors say (found by fuzzing:
        // the period went negative).
        d_period = std::clamp(
            d_period + d_cfg.loop_beta * err, 0.99 * d_cfg.period, 1.01 * d_cfg.period);
        d_next += a * err + d_period;
        d_recheck = 0;
    } else {
        ++d_misses;
        d_next += d_period;
    }
    out.push_back(make_window(p, det, err, d_slot++));
    // Follow the tone; after 3 misses in a row search the whole band again.
    if (det.detected) {
        d_have_track = true;
        d_track_freq = det.freq_hz;
        d_track_misses = 0;
    } else {
        ++d_track_misses;
    }
    // After a gap the phase comes from the receiver's clock: unless one of the next two
    // bursts is where it says, the count was wrong and the beacon must be found again.
    const bool lost_at_gap = d_recheck > 0 && !det.detected && --d_recheck == 0;
    if (d_misses >= d_cfg.max_misses || lost_at_gap) {
        ++d_losses;
        d_last_next = d_next;
        d_state = state::search;
        d_pos = d_span_start = p + n;
        d_span.clear();
    }
    return true;
}

void burst_acquirer::gap(double samples)
{
    ++d_gaps;
    d_buf.clear();
    d_base = d_end;
    d_span.clear();
    const bool plausible =
        std::isfinite(samples) && samples > 0.0 && samples < 1e6 * d_cfg.period;
    if (plausible) {
        d_shift += samples;
        d_last_next -= samples; // (in the coordinates of the samples after the gap)
    }
    const double end = static_cast<double>(d_end);
    if (d_state == state::locked && plausible) {
        // Before the gap, sample d_end would have been at d_end + samples: the next
        // burst whose window and timing margin lie wholly after the gap, on the same
        // phase; the slots in between are missing.
        const double after = end + samples;
        const double lead = d_next - d_margin;
        const double k = lead < after ? std::ceil((after - lead) / d_period) : 0.0;
        d_next += k * d_period - samples;
        d_slot += static_cast<std::uint64_t>(k);
        d_recheck = 2;
        return;
    }
    if (d_state == state::locked) {
        ++d_losses;
        d_last_next = end; // slots go on from the last one
    }
    d_state = state::search;
    d_pos = d_span_start = d_end;
}

bool burst_acquirer::step(std::vector<acquired_window>& out)
{
    switch (d_state) {
    case state::search:
        return step_search();
    case state::confirm:
        return step_confirm(out);
    default:
        return step_locked(out);
    }
}

void burst_acquirer::trim()
{
    const auto keep = static_cast<std::size_t>(
        3.0 * d_cfg.period + 2.0 * d_cfg.window_len + 2.0 * d_margin + d_hop);
    if (d_buf.size() <= 2 * keep)
        return;
    const std::size_t drop = d_buf.size() - keep;
    d_buf.erase(d_buf.begin(), d_buf.begin() + static_cast<std::ptrdiff_t>(drop));
    d_base += drop;
}

void burst_acquirer::push(const std::complex<float>* x,
                          std::size_t n,
                          std::vector<acquired_window>& out)
{
    d_buf.insert(d_buf.end(), x, x + n);
    d_end += n;
    while (step(out)) {
    }
    trim();
}

} // namespace rfseek
} // namespace gr
