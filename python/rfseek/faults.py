#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""faults: the faults a real receiver brings, on a pulsed beacon made by GNU Radio's own
blocks with known truth: the input of rfseek-bench-faults and of the tests of
doppler_estimator's "acquire" alignment under them.

    beacon_stream(...)   the beacon in noise (pulsed_beacon), optionally with a
                         continuous carrier and wideband noise bursts added by
                         sig_source_c / noise_source_c, as a numpy array
    overflow(...)        samples dropped mid-stream, the next one tagged with the true
                         rx_time, as UHD does after an overflow ("O")
    measure(...)         doppler_estimator on those samples and tags: its messages
    score(...)           each message against the truth
"""

import math

import numpy as np
import pmt
from gnuradio import analog, blocks, gr

from .pulsed_beacon import pulsed_beacon
from .rfseek_python import doppler_estimator

FS, N, NFFT, PERIOD = 100e3, 1000, 4096, 5000


class stream:
    """Samples and their truth: the beacon's frequency, each burst's start in the
    samples (fractional; NaN for a burst lost in a gap) and in receiver time."""

    def __init__(self, samples, starts, times, freq, crb, tags=(), cw_freq=None,
                 t0=0.0, gaps=()):
        self.samples, self.starts, self.times = samples, starts, times
        self.freq, self.crb, self.tags, self.cw_freq = freq, crb, list(tags), cw_freq
        self.t0, self.gaps = t0, list(gaps)

    def time_of(self, offset):
        """The true receiver time of sample `offset` (after the gaps cut so far)."""
        lost = sum(n for at, n in self.gaps if at <= offset)
        return self.t0 + (offset + lost) / FS


def beacon_stream(seed, snr_db=-10.0, seconds=20.0, ppm=20.0, cw_db=None, cw_offset=None,
                  wideband_db=None, wideband_s=0.01, wideband_rate=2.0, t0=1.7e9 + 0.25):
    """The beacon at a random frequency in +-20 kHz and a random phase of its period,
    its clock ppm off the receiver's, at per-sample SNR snr_db. cw_db: a continuous
    carrier that many dB above the beacon, cw_offset Hz from it (random outside +-1 kHz
    and inside the band when None). wideband_db: noise bursts of wideband_s seconds at
    random times (wideband_rate per second on average), that many dB above the noise."""
    rng = np.random.default_rng(seed)
    skip = int(rng.integers(0, PERIOD))
    freq = float(rng.uniform(-20e3, 20e3))
    total = int(seconds * FS)
    tb = gr.top_block()
    src = pulsed_beacon(FS, freq, N, PERIOD, snr_db, skip, ppm, seed)
    head = blocks.head(gr.sizeof_gr_complex, total)
    sink = blocks.vector_sink_c()
    add = blocks.add_cc()
    tb.connect(src, (add, 0))
    inputs = 1
    cw_freq = None
    if cw_db is not None:
        while cw_offset is None or not (-FS / 2 + 200 < freq + cw_offset < FS / 2 - 200):
            cw_offset = float(rng.choice([-1, 1]) * rng.uniform(1000.0, FS / 2))
        cw_freq = freq + cw_offset
        cw = analog.sig_source_c(FS, analog.GR_COS_WAVE, cw_freq, 10.0 ** (cw_db / 20.0),
                                 0, float(rng.uniform(0, 2 * np.pi)))
        tb.connect(cw, (add, inputs))
        inputs += 1
    if wideband_db is not None:
        sigma = 10.0 ** (-snr_db / 20.0)
        noise = analog.noise_source_c(analog.GR_GAUSSIAN,
                                      sigma * 10.0 ** (wideband_db / 20.0), seed + 17)
        gate = np.zeros(total, dtype=np.float32)
        count = rng.poisson(wideband_rate * seconds)
        length = int(wideband_s * FS)
        for s in rng.integers(0, max(total - length, 1), size=count):
            gate[s:s + length] = 1.0
        g = blocks.vector_source_f(gate.tolist(), False)
        to_c = blocks.float_to_complex()
        mult = blocks.multiply_cc()
        tb.connect(g, to_c, (mult, 1))
        tb.connect(noise, (mult, 0))
        tb.connect(mult, (add, inputs))
        inputs += 1
    tb.connect(add, head, sink)
    tb.run()
    x = np.array(sink.data(), dtype=np.complex64)
    starts = np.array(src.burst_starts(int(total / PERIOD) + 2))
    starts = starts[starts + N <= total]
    tags = [(0, "rx_time", (int(t0), t0 - int(t0))), (0, "rx_rate", FS)]
    return stream(x, starts, t0 + starts / FS, freq, src.crb_std_hz(snr_db), tags, cw_freq,
                  t0)


def overflow(s, at, lost):
    """Drop samples [at, at + lost) of stream s and tag the next one with its true
    rx_time. Bursts touching the gap lose their start (NaN); later ones move back."""
    x = np.concatenate([s.samples[:at], s.samples[at + lost:]])
    starts = s.starts.copy()
    inside = (starts + N > at) & (starts < at + lost)
    later = starts >= at + lost
    starts[later] -= lost
    starts[inside] = np.nan
    t = s.time_of(at) + lost / FS
    tags = s.tags + [(at, "rx_time", (int(t), t - int(t)))]
    return stream(x, starts, s.times, s.freq, s.crb, tags, s.cw_freq, s.t0,
                  s.gaps + [(at, lost)])


def _tag(offset, key, value):
    t = gr.tag_t()
    t.offset = offset
    t.key = pmt.intern(key)
    if key == "rx_time":
        t.value = pmt.make_tuple(pmt.from_uint64(value[0]), pmt.from_double(value[1]))
    else:
        t.value = pmt.to_pmt(value)
    return t


def measure(s, band=0.0, alignment="acquire", chunk=None):
    """doppler_estimator (acquire, newton, N_FFT 4096) on s's samples and tags; band > 0
    searches only +-band Hz around the beacon. chunk: items per call (None: GNU Radio's
    own)."""
    tb = gr.top_block()
    src = blocks.vector_source_c(s.samples.tolist(), False, 1,
                                 [_tag(o, k, v) for o, k, v in s.tags])
    lo, hi = (s.freq - band, s.freq + band) if band > 0 else (0.0, 0.0)
    est = doppler_estimator(FS, N, NFFT, "rectangular", "newton", alignment,
                            "rfseek_beacon", PERIOD, 0, lo, hi, 2.0, 0.0)
    if chunk:
        est.set_max_noutput_items(chunk)
    dbg = blocks.message_debug()
    tb.connect(src, est)
    tb.msg_connect(est, "meas", dbg, "store")
    tb.run()
    return est, [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())]


def score(meas, s, skip_first=2):
    """Each valid window against the truth. A valid window within N/10 of a burst's true
    start measures that burst; any other valid window is false (on noise, across a gap,
    or on the interferer). found counts the bursts after the first skip_first measured
    (the acquisition) out of those sent after them, outside any gap."""
    known = ~np.isnan(s.starts)
    starts = np.where(known, s.starts, -1e18)
    errs, timing, false, on_cw, hit = [], [], 0, 0, set()
    # Each window's time against the true time of its first sample (every window).
    clock_err = max((abs(m["time"] - s.time_of(m["offset"])) for m in meas), default=0.0)
    for m in meas:
        if not m["valid"]:
            continue
        if m["offset"] < N:
            continue  # (the stream may begin inside a burst: a partial one at 0)
        k = int(np.argmin(np.abs(starts - m["offset"])))
        if abs(starts[k] - m["offset"]) <= N / 10:
            hit.add(k)
            errs.append(m["freq_hz"] - s.freq)
            timing.append(m["offset"] - starts[k])
        else:
            false += 1
        if s.cw_freq is not None and abs(m["freq_hz"] - s.cw_freq) < 2 * FS / N:
            on_cw += 1
    last_acq = sorted(hit)[skip_first - 1] if len(hit) >= skip_first else len(starts)
    sent = [k for k in range(len(starts)) if known[k] and k > last_acq]
    found = sum(1 for k in sent if k in hit)
    e = np.array(errs)
    inl = e[np.abs(e) <= 10 * s.crb] if len(e) else e
    return dict(found=found, sent=len(sent), false=false, on_interferer=on_cw,
                rms_over_crb=float(np.sqrt(np.mean(inl ** 2)) / s.crb) if len(inl) else math.nan,
                outliers=int(len(e) - len(inl)), inliers=[float(v) for v in inl],
                max_clock_err_s=float(clock_err),
                timing_rms=float(np.sqrt(np.mean(np.square(timing)))) if timing else math.nan,
                hit=hit)
