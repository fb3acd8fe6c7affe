/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * carrier_notch: refine and project out continuous carriers (carrier_notch.h).
 */

#include "carrier_notch.h"
#include <algorithm>
#include <cmath>

namespace gr {
namespace rfseek {

namespace {
using cd = std::complex<double>;

// sum x_n exp(-j w n), by a rotating phasor renormalised every 256 samples.
cd project(const std::complex<float>* x, std::size_t n, double w)
{
    cd s = 0.0, r = 1.0;
    const cd step = std::polar(1.0, -w);
    for (std::size_t i = 0; i < n; ++i) {
        if ((i & 255) == 0)
            r = std::polar(1.0, -w * static_cast<double>(i));
        s += cd(x[i]) * r;
        r *= step;
    }
    return s;
}
} // namespace

carrier_notch::carrier_notch(double samp_rate_hz, std::size_t max_carriers)
    : d_fs(samp_rate_hz), d_max(std::max<std::size_t>(max_carriers, 1))
{
}

void carrier_notch::set_samp_rate(double samp_rate_hz) { d_fs = samp_rate_hz; }

bool carrier_notch::add(double freq_hz, double min_sep_hz)
{
    if (!std::isfinite(freq_hz))
        return false;
    for (const double f : d_freqs)
        if (std::abs(std::remainder(f - freq_hz, d_fs)) < min_sep_hz)
            return false;
    if (d_freqs.size() >= d_max) {
        d_freqs.erase(d_freqs.begin());
        d_home.erase(d_home.begin());
    }
    d_freqs.push_back(freq_hz);
    d_home.push_back(freq_hz);
    return true;
}

void carrier_notch::remove(std::size_t i)
{
    if (i < d_freqs.size()) {
        d_freqs.erase(d_freqs.begin() + static_cast<std::ptrdiff_t>(i));
        d_home.erase(d_home.begin() + static_cast<std::ptrdiff_t>(i));
    }
}

void carrier_notch::apply(std::complex<float>* x,
                          std::size_t n,
                          std::vector<double>* share,
                          bool follow)
{
    if (share)
        share->assign(d_freqs.size(), 0.0);
    if (d_freqs.empty() || n < 4)
        return;
    double energy = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        energy += std::norm(cd(x[i]));
    if (!(energy > 0.0) || !std::isfinite(energy))
        return;
    const double len = static_cast<double>(n);
    for (std::size_t c = 0; c < d_freqs.size(); ++c) {
        // Two parabolic steps on the periodogram: within half a bin, then an eighth.
        double w = 2.0 * M_PI * d_freqs[c] / d_fs;
        double delta = M_PI / len; // half a bin
        for (int it = 0; it < 2; ++it) {
            const double pm = std::norm(project(x, n, w - delta));
            const double p0 = std::norm(project(x, n, w));
            const double pp = std::norm(project(x, n, w + delta));
            const double den = pm + pp - 2.0 * p0;
            if (den < 0.0)
                w += std::clamp(0.5 * (pm - pp) / den, -1.0, 1.0) * delta;
            delta *= 0.25;
        }
        const cd a = project(x, n, w) / len;
        if (share)
            (*share)[c] = len * std::norm(a) / energy;
        cd r = a;
        const cd step = std::polar(1.0, w);
        for (std::size_t i = 0; i < n; ++i) {
            if ((i & 255) == 0)
                r = a * std::polar(1.0, w * static_cast<double>(i));
            x[i] -= std::complex<float>(r);
            r *= step;
        }
        // Follow a drifting carrier while it clearly dominates, within a bin of home.
        if (follow && len * std::norm(a) > 0.3 * energy) {
            const double bin = d_fs / len;
            const double f = std::remainder(w * d_fs / (2.0 * M_PI), d_fs);
            const double off = std::remainder(f - d_home[c], d_fs);
            d_freqs[c] = std::remainder(d_home[c] + std::clamp(off, -bin, bin), d_fs);
        }
    }
}

int equalize_blocks(std::complex<float>* x, std::size_t n, std::size_t block)
{
    if (block < 1 || n < 4 * block)
        return 0;
    const std::size_t nb = n / block;
    std::vector<double> p(nb, 0.0);
    for (std::size_t b = 0; b < nb; ++b) {
        const std::size_t end = b + 1 == nb ? n : (b + 1) * block;
        for (std::size_t i = b * block; i < end; ++i)
            p[b] += std::norm(cd(x[i]));
        p[b] /= static_cast<double>(end - b * block);
    }
    std::vector<double> sorted(p);
    std::nth_element(sorted.begin(), sorted.begin() + nb / 2, sorted.end());
    const double med = sorted[nb / 2];
    if (!(med > 0.0) || !std::isfinite(med))
        return 0;
    int weighted = 0;
    for (std::size_t b = 0; b < nb; ++b) {
        if (!(p[b] > 3.0 * med) || !std::isfinite(p[b]))
            continue;
        const float w = static_cast<float>(med / p[b]);
        const std::size_t end = b + 1 == nb ? n : (b + 1) * block;
        for (std::size_t i = b * block; i < end; ++i)
            x[i] *= w;
        ++weighted;
    }
    return weighted;
}

} // namespace rfseek
} // namespace gr
