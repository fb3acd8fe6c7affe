#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""doppler_estimator's "acquire" alignment and detection test in flowgraphs: a pulsed
beacon made by GNU Radio's own blocks found at -12 dB per-sample SNR with its timing
unknown and its clock 20 ppm off; a faded burst as an invalid window in its slot; the
detection test's false alarms on noise against its bound; parameter errors."""

import numpy as np
import pmt
from gnuradio import blocks, gr, gr_unittest
from gnuradio import rfseek

FS, N, NFFT, P = 1e5, 1000, 4096, 5000


def collect(src, est, nsamples=None):
    tb = gr.top_block()
    dbg = blocks.message_debug()
    if nsamples is not None:
        head = blocks.head(gr.sizeof_gr_complex, int(nsamples))
        tb.connect(src, head, est)
    else:
        tb.connect(src, est)
    tb.msg_connect(est, "meas", dbg, "store")
    tb.run()
    return [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())]


def acquire(**kw):
    return rfseek.doppler_estimator(FS, N, NFFT, "rectangular", "newton", "acquire",
                                    "rfseek_beacon", P, **kw)


class qa_acquire(gr_unittest.TestCase):

    def test_finds_a_pulsed_beacon_at_minus_12_db(self):
        snr, freq = -12.0, -7321.0
        beacon = rfseek.pulsed_beacon(FS, freq, N, P, snr, skip=3217, ppm=20.0, seed=4)
        est = acquire()
        meas = collect(beacon, est, 8 * FS)
        truth = np.array(beacon.burst_starts(170))
        valid = [m for m in meas if m["valid"]]
        self.assertGreaterEqual(len(valid), 2)
        # Acquired (the second burst measured) within 2 s.
        self.assertLess((valid[1]["offset"] + N) / FS, 2.0)
        k0 = int(np.argmin(np.abs(truth - meas[0]["offset"])))
        sent = [k for k in range(k0, len(truth)) if truth[k] + N <= 8 * FS]
        self.assertEqual(len(meas), len(sent))
        errs = []
        for m, k in zip(meas, sent):
            # On the true burst (the channel model's interpolator shifts by a few
            # samples), numbered by the beacon's period.
            self.assertLess(abs(m["offset"] - truth[k]), 30)
            self.assertEqual(m["slot"] - meas[0]["slot"], k - k0)
            self.assertTrue(np.isfinite(m["timing_error"]))
            self.assertTrue(np.isfinite(m["detect_margin_db"]))
            if m["valid"]:
                errs.append(m["freq_hz"] - freq)
        self.assertGreaterEqual(len(errs), 0.99 * len(sent))
        rms = np.sqrt(np.mean(np.square(errs)))
        self.assertLess(rms, 1.3 * beacon.crb_std_hz(snr))
        self.assertEqual(est.acquire_state(), "locked")
        # The loop follows the beacon's clock: 20 ppm fast is a period 0.1 sample short.
        self.assertAlmostEqual(est.period_estimate(), P / 1.00002, delta=0.3)

    def test_a_faded_burst_is_an_invalid_window_in_its_slot(self):
        rng = np.random.default_rng(8)
        n_periods, start, freq = 40, 1800, 2500.0
        x = (rng.standard_normal(n_periods * P) +
             1j * rng.standard_normal(n_periods * P)) * np.sqrt(0.5 * 0.1)
        t = np.arange(N)
        faded = {12, 25}
        for k in range(n_periods - 1):
            if k not in faded:
                s = start + k * P
                x[s:s + N] += np.exp(2j * np.pi * freq * (s + t) / FS)
        est = acquire(pfa=1e-4)
        meas = collect(blocks.vector_source_c(x.astype(np.complex64).tolist()), est)
        by_slot = {m["slot"]: m for m in meas}
        self.assertEqual(len(by_slot), len(meas))
        # Slot = period number from the stream's start: burst k is in slot k.
        for k in range(2, n_periods - 1):
            self.assertIn(k, by_slot)
            m = by_slot[k]
            self.assertEqual(m["offset"], start + k * P)
            self.assertEqual(m["valid"], k not in faded, "slot %d" % k)
            if m["valid"]:
                self.assertAlmostEqual(m["freq_hz"], freq, delta=2.0)
            else:
                self.assertLess(m["detect_margin_db"], 0.0)
        self.assertAlmostEqual(est.pfa(), 1e-4)

    def test_detection_test_on_noise_windows(self):
        # Periodic windows of noise: without the test every one is "valid" (the
        # estimator alone cannot tell); with it, between pfa / 2 and pfa of them.
        rng = np.random.default_rng(2)
        windows = 3000
        x = ((rng.standard_normal(windows * N) + 1j * rng.standard_normal(windows * N))
             * 0.3).astype(np.complex64)
        for pfa in (0.0, 0.02):
            est = rfseek.doppler_estimator(FS, N, NFFT, alignment="periodic", period=N,
                                           pfa=pfa)
            meas = collect(blocks.vector_source_c(x.tolist()), est)
            self.assertEqual(len(meas), windows)
            rate = sum(m["valid"] for m in meas) / windows
            if pfa == 0.0:
                self.assertEqual(rate, 1.0)
                self.assertNotIn("detect_margin_db", meas[0])
            else:
                sd = np.sqrt(pfa * (1 - pfa) / windows)
                self.assertLessEqual(rate, pfa + 4 * sd)
                self.assertGreaterEqual(rate, pfa / 2 - 4 * sd)
        est.set_pfa(0.0)
        self.assertEqual(est.pfa(), 0.0)
        est.set_pfa(1e-3)
        self.assertEqual(est.pfa(), 1e-3)

    def test_bad_parameters_raise_value_error(self):
        with self.assertRaisesRegex(ValueError, "period"):
            rfseek.doppler_estimator(FS, N, NFFT, alignment="acquire", period=N)
        with self.assertRaisesRegex(ValueError, "pfa"):
            rfseek.doppler_estimator(FS, N, NFFT, alignment="periodic", period=N, pfa=0.7)
        est = acquire()
        with self.assertRaisesRegex(ValueError, "pfa"):
            est.set_pfa(-1.0)
        self.assertEqual(est.alignment(), "acquire")
        self.assertEqual(est.acquire_state(), "search")
        self.assertEqual(est.pfa(), 1e-3)
        with self.assertRaisesRegex(ValueError, "skip"):
            rfseek.pulsed_beacon(skip=10 ** 6)


if __name__ == "__main__":
    gr_unittest.run(qa_acquire)
