#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""pulsed_beacon: the paper's beacon (a tone burst of N samples every period) received
in white noise, made only of GNU Radio's own blocks, with known truth: the input of
benchmarks and tests of burst timing.

    sig_source_c (tone) x gate (N ones, period - N zeros, from `skip` samples in)
        -> channels.channel_model (noise, clock offset epsilon)

The tone has unit power, so the per-sample SNR is snr_db and the noise voltage
10^(-snr_db / 20). A burst's start in the output is (k period - skip) / epsilon, k >= 1
(k = 0 when skip = 0).
"""

import math

from gnuradio import analog, blocks, channels, gr


class pulsed_beacon(gr.hier_block2):
    """Pulsed tone in white noise: N of every `period` samples, the first burst `skip`
    samples into the pattern, the beacon's clock (1 + ppm 1e-6) times the receiver's.
    A tone_on of False sends no bursts (noise alone)."""

    def __init__(self, samp_rate=100e3, freq=5000.0, window_len=1000, period=5000,
                 snr_db=-12.0, skip=0, ppm=0.0, seed=1, tone_on=True):
        gr.hier_block2.__init__(self, "pulsed_beacon", gr.io_signature(0, 0, 0),
                                gr.io_signature(1, 1, gr.sizeof_gr_complex))
        if not (0 < window_len < period):
            raise ValueError("pulsed_beacon: window_len = %r: must be in (0, period = %r)"
                             % (window_len, period))
        if not (0 <= skip < period):
            raise ValueError("pulsed_beacon: skip = %r: must be in [0, period)" % skip)
        if not (abs(ppm) <= 1000.0):
            raise ValueError("pulsed_beacon: ppm = %r: must be in [-1000, 1000]" % ppm)
        self.samp_rate, self.freq, self.window_len = samp_rate, freq, window_len
        self.period, self.skip = period, skip
        # The beacon's samples come epsilon times as fast as its nominal rate: a
        # beacon clock ppm fast shortens its period in receiver samples.
        self.epsilon = 1.0 + ppm * 1e-6
        self.tone = analog.sig_source_c(samp_rate, analog.GR_COS_WAVE, freq,
                                        1.0 if tone_on else 0.0, 0)
        pattern = [1.0] * window_len + [0.0] * (period - window_len)
        self.gate = blocks.vector_source_f(pattern[skip:] + pattern[:skip], True)
        self.to_c = blocks.float_to_complex()
        self.mult = blocks.multiply_cc()
        self.channel = channels.channel_model(10.0 ** (-snr_db / 20.0), 0.0,
                                              self.epsilon, [1.0 + 0j], seed)
        self.connect(self.gate, self.to_c, (self.mult, 1))
        self.connect(self.tone, (self.mult, 0))
        self.connect(self.mult, self.channel, self)

    def burst_starts(self, count):
        """The first `count` burst starts in the output (fractional samples)."""
        first = 0 if self.skip == 0 else 1
        return [(k * self.period - self.skip) / self.epsilon
                for k in range(first, first + count)]

    def crb_std_hz(self, snr_db):
        """Cramer-Rao bound of one burst's frequency (Hz) at per-sample SNR snr_db."""
        n, ts = self.window_len, 1.0 / self.samp_rate
        snr = 10.0 ** (snr_db / 10.0)
        return math.sqrt(6.0 / ((2 * math.pi) ** 2 * snr * n * (n * n - 1) * ts * ts))
