/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * carrier_notch: continuous carriers (an interferer, a receiver's DC leak) removed from a
 * stretch of samples before a pulsed beacon is looked for in it, and wideband bursts
 * weighted down (internal header; plain C++, used by burst_acquirer).
 */

#ifndef INCLUDED_RFSEEK_CARRIER_NOTCH_H
#define INCLUDED_RFSEEK_CARRIER_NOTCH_H

#include <gr-rfseek/api.h>
#include <complex>
#include <cstddef>
#include <vector>

namespace gr {
namespace rfseek {

/*!
 * Each carrier's frequency is refined on the stretch itself (the maximum of its
 * periodogram within half a bin of the frequency held, by two parabolic steps) and its
 * complex exponential projected out: x_n -= a exp(j w n), a = (1/L) sum x_n exp(-j w n).
 * A carrier 40 dB above the noise in its bin leaves a residue near the noise: its
 * sidelobes, which would bury a beacon 20 dB weaker ten bins away, are gone. With
 * follow (the search's windows, which hold no beacon it has found), the frequency held
 * follows a carrier that holds over 30 % of the stretch's energy (a drifting
 * interferer), within a bin of where it was first held: a notch never walks onto a
 * beacon.
 */
class RFSEEK_API carrier_notch
{
public:
    explicit carrier_notch(double samp_rate_hz, std::size_t max_carriers = 4);

    //! A carrier at freq_hz; false (nothing added) when one is held within min_sep_hz.
    //! When max_carriers are held, the oldest goes.
    bool add(double freq_hz, double min_sep_hz);
    void remove(std::size_t i);
    void clear() { d_freqs.clear(); }
    const std::vector<double>& freqs() const { return d_freqs; }
    std::size_t max_carriers() const { return d_max; }
    void set_samp_rate(double samp_rate_hz);

    /*!
     * Removes the carriers from x[0..n). share, when given, receives per carrier the
     * fraction of the stretch's energy it held (L |a|^2 / sum |x|^2, before removal).
     * Non-finite samples are left alone (the stretch is not touched).
     */
    void apply(std::complex<float>* x,
               std::size_t n,
               std::vector<double>* share = nullptr,
               bool follow = false);

private:
    double d_fs;
    std::size_t d_max;
    std::vector<double> d_freqs;
    std::vector<double> d_home; // where each was first held
};

/*!
 * Wideband bursts (another transmitter's noise-like burst, a spark) in a window: the
 * window is cut in blocks of `block` samples and a block whose power is over 3 times
 * the blocks' median is weighted by median / power (the matched filter's weight of a
 * stretch whose noise is that much stronger). A tone keeps its frequency (positive
 * weights do not move a periodogram's peak) and the noise is left about white.
 * Returns the blocks weighted. A burst over half the window or more leaves the median
 * itself high, and the window as it is.
 */
RFSEEK_API int equalize_blocks(std::complex<float>* x, std::size_t n, std::size_t block);

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_CARRIER_NOTCH_H */
