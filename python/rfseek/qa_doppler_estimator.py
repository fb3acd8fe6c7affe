#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""doppler_estimator in flowgraphs: one meas per tag with slot, time, frequency and the
tag's fields; periodic windows; the sample clock from rx_time; the Doppler plus CFO of
channel_source; degenerate windows; parameter errors."""

import math

import numpy as np
import pmt
from gnuradio import blocks, gr, gr_unittest
from gnuradio import rfseek

FS = 1e5
N = 1000
NFFT = 4096


def tag(offset, key, value):
    t = gr.tag_t()
    t.offset = offset
    t.key = pmt.intern(key)
    t.value = pmt.to_pmt(value)
    return t


def run(samples, tags, **kw):
    tb = gr.top_block()
    src = blocks.vector_source_c(list(samples), False, 1, tags)
    est = rfseek.doppler_estimator(FS, N, NFFT, **kw)
    dbg = blocks.message_debug()
    tb.connect(src, est)
    tb.msg_connect(est, "meas", dbg, "store")
    tb.run()
    return est, [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())]


def burst(f, n=N, amp=1.0):
    return amp * np.exp(2j * np.pi * f * np.arange(n) / FS)


class qa_doppler_estimator(gr_unittest.TestCase):

    def test_one_meas_per_tag_with_forwarded_fields(self):
        freqs = [123.4, -987.6, 40000.25, -33.3]
        gap = 300
        samples, tags = [], []
        for k, f in enumerate(freqs):
            tags.append(tag(len(samples) + gap, "rfseek_beacon",
                            {"slot": 10 + k, "heading": 0.1 * k, "label": "b%d" % k}))
            samples.extend(np.zeros(gap))
            samples.extend(burst(f))
        est, meas = run(samples, tags, interpolator="newton")
        self.assertEqual(len(meas), len(freqs))
        for k, (m, f) in enumerate(zip(meas, freqs)):
            self.assertEqual(m["slot"], 10 + k)
            self.assertAlmostEqual(m["heading"], 0.1 * k)
            self.assertEqual(m["label"], "b%d" % k)
            self.assertTrue(m["valid"])
            self.assertAlmostEqual(m["freq_hz"], f, delta=0.01)
            self.assertEqual(m["offset"], tags[k].offset)
            self.assertAlmostEqual(m["time"], tags[k].offset / FS, places=12)
            for key in ("snr_db", "power_db", "noise_power_db"):
                self.assertTrue(math.isfinite(m[key]))
        self.assertEqual(est.window_count(), 4)
        self.assertEqual(est.invalid_count(), 0)

    def test_burst_tagger_start_tags_only(self):
        # gr-blocks' burst_tagger tags each burst's start (True) and end (False) with the
        # same key: one window per burst, at its start, none at its end.
        freqs = [250.0, -1200.5, 3000.0]
        gap = 700
        samples, trigger, starts = [], [], []
        for f in freqs:
            samples.extend(np.zeros(gap))
            trigger.extend([0] * gap)
            starts.append(len(samples))
            samples.extend(burst(f))
            trigger.extend([1] * N)
        samples.extend(np.zeros(gap))
        trigger.extend([0] * gap)
        tb = gr.top_block()
        src = blocks.vector_source_c(list(samples), False)
        trig = blocks.vector_source_s(trigger, False)
        tagger = blocks.burst_tagger(gr.sizeof_gr_complex)
        est = rfseek.doppler_estimator(FS, N, NFFT, tag_key="burst", interpolator="newton")
        dbg = blocks.message_debug()
        tb.connect(src, (tagger, 0))
        tb.connect(trig, (tagger, 1))
        tb.connect(tagger, est)
        tb.msg_connect(est, "meas", dbg, "store")
        tb.run()
        meas = [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())]
        self.assertEqual([m["offset"] for m in meas], starts)
        for m, f in zip(meas, freqs):
            self.assertTrue(m["valid"])
            self.assertAlmostEqual(m["freq_hz"], f, delta=0.01)

    def test_periodic_windows_and_rx_time_clock(self):
        period, offset = 1500, 200
        f = 777.7
        x = burst(f, 20000)
        tags = [tag(0, "rx_time", (5, 0.25)), tag(0, "rx_rate", FS)]
        est, meas = run(x, tags, alignment="periodic", period=period, offset=offset,
                        window="hann", interpolator="parabolic")
        starts = list(range(offset, 20000 - N + 1, period))
        self.assertEqual([m["offset"] for m in meas], starts)
        self.assertEqual([m["slot"] for m in meas], list(range(len(starts))))
        for m, s in zip(meas, starts):
            self.assertAlmostEqual(m["time"], 5.25 + s / FS, places=9)
            self.assertAlmostEqual(m["freq_hz"], f, delta=0.2)

    def test_every_sample_in_a_window(self):
        x = burst(-2500.0, 10 * N)
        est, meas = run(x, [], alignment="periodic", period=N)
        self.assertEqual(len(meas), 10)

    def test_channel_source_doppler_plus_cfo(self):
        sc = rfseek.scenario(initial_distance_m=230.0, num_scatterers=0, add_noise=False,
                             cfo_hz=-432.1, cfo_drift_hz_per_s=0.0,
                             cfo_walk_hz_per_sqrt_s=0.0, start_angle_rad=0.3,
                             start_heading_rad=2.0, heading_noise_rad=0.0)
        tb = gr.top_block()
        src = rfseek.channel_source(sc, lockstep=False)
        est = rfseek.doppler_estimator(sc.samp_rate_hz, sc.window_len, sc.fft_len,
                                       interpolator="newton")
        states, meas = blocks.message_debug(), blocks.message_debug()
        tb.connect(src, est)
        tb.msg_connect(src, "state", states, "store")
        tb.msg_connect(est, "meas", meas, "store")
        tb.run()
        n = meas.num_messages()
        self.assertGreater(n, 100)
        for i in range(n):
            m = pmt.to_python(meas.get_message(i))
            s = pmt.to_python(states.get_message(i))
            self.assertEqual(m["slot"], s["slot"])
            self.assertAlmostEqual(m["time"], s["time"], places=9)
            self.assertAlmostEqual(m["heading"], s["measured_heading"])
            self.assertAlmostEqual(m["freq_hz"], s["doppler_hz"] + s["cfo_hz"], delta=0.01)

    def test_energy_gating_on_a_continuous_stream(self):
        # A pulsed beacon received continuously: windows start at the detected bursts.
        for snr, expect_windows in ((0.0, True), (-100.0, False)):
            sc = rfseek.scenario(initial_distance_m=230.0, num_scatterers=0, snr_db=snr,
                                 cfo_hz=150.0, cfo_drift_hz_per_s=0.0,
                                 cfo_walk_hz_per_sqrt_s=0.0, start_angle_rad=0.0,
                                 start_heading_rad=math.pi, seed=6)
            tb = gr.top_block()
            src = rfseek.channel_source(sc, mode="continuous", lockstep=False)
            est = rfseek.doppler_estimator(sc.samp_rate_hz, sc.window_len, sc.fft_len,
                                           alignment="energy", interpolator="newton")
            meas, states = blocks.message_debug(), blocks.message_debug()
            tb.connect(src, est)
            tb.msg_connect(est, "meas", meas, "store")
            tb.msg_connect(src, "state", states, "store")
            tb.run()
            m = [pmt.to_python(meas.get_message(i)) for i in range(meas.num_messages())]
            if not expect_windows:
                self.assertEqual(m, [])
                continue
            slots = states.num_messages() - 1
            self.assertGreaterEqual(len(m), 0.97 * slots)
            self.assertLessEqual(len(m), slots)
            for x in m:
                k = round(x["offset"] / sc.slot_samples)
                self.assertLessEqual(abs(x["offset"] - k * sc.slot_samples), 50)
                self.assertTrue(x["valid"])
                # 0 dB per sample: the Cramer-Rao bound is 1.2 Hz; 5 sigma.
                self.assertAlmostEqual(x["freq_hz"], 150.0 + sc.max_doppler_hz, delta=6.2)
        with self.assertRaisesRegex(ValueError, "threshold_db"):
            rfseek.doppler_estimator(FS, N, NFFT, alignment="energy", threshold_db=0.0)

    def test_degenerate_windows_are_invalid_without_nan(self):
        x = np.concatenate([np.zeros(N), np.full(N, np.nan), burst(100.0, 600), burst(50.0)])
        tags = [tag(0, "rfseek_beacon", {"slot": 0}),
                tag(N, "rfseek_beacon", {"slot": 1}),
                tag(2 * N, "rfseek_beacon", {"slot": 2}),        # cut short by the next
                tag(2 * N + 600, "rfseek_beacon", {"slot": 3})]
        est, meas = run(x.astype(np.complex64), tags)
        self.assertEqual([m["valid"] for m in meas], [False, False, False, True])
        for m in meas:
            for v in m.values():
                if isinstance(v, float):
                    self.assertTrue(math.isfinite(v))
        self.assertEqual(est.truncated_count(), 1)
        self.assertEqual(est.invalid_count(), 3)

    def test_bad_parameters_raise_value_error(self):
        cases = [
            (dict(samp_rate=FS, window_len=2, fft_len=NFFT), "window_len"),
            (dict(samp_rate=FS, window_len=5000, fft_len=NFFT), "window_len"),
            (dict(samp_rate=FS, window_len=3, fft_len=3), "fft_len"),
            (dict(samp_rate=0.0, window_len=N, fft_len=NFFT), "samp_rate"),
            (dict(samp_rate=FS, window_len=N, fft_len=NFFT, window="kaiser"), "window"),
            (dict(samp_rate=FS, window_len=N, fft_len=NFFT, interpolator="spline"),
             "interpolator"),
            (dict(samp_rate=FS, window_len=N, fft_len=NFFT, alignment="pulse"),
             "alignment"),
            (dict(samp_rate=FS, window_len=N, fft_len=NFFT, alignment="periodic",
                  period=10), "period"),
            (dict(samp_rate=FS, window_len=N, fft_len=NFFT, alignment="periodic",
                  period=-1), "period = -1: must be >= 0"),
            (dict(samp_rate=FS, window_len=N, fft_len=NFFT, alignment="periodic",
                  period=2 * N, offset=-1), "offset = -1: must be >= 0"),
        ]
        for kw, name in cases:
            with self.assertRaisesRegex(ValueError, name):
                rfseek.doppler_estimator(**kw)
        est = rfseek.doppler_estimator(FS, N, NFFT)
        with self.assertRaisesRegex(ValueError, "interpolator"):
            est.set_interpolator("cubic")
        est.set_interpolator("newton")
        est.set_window("blackman_harris")
        est.set_band(-1000.0, 1000.0)
        self.assertEqual((est.interpolator(), est.window(), est.min_freq(), est.max_freq()),
                         ("newton", "blackman_harris", -1000.0, 1000.0))


if __name__ == "__main__":
    gr_unittest.run(qa_doppler_estimator)
