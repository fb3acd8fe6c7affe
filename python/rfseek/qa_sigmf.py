#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""SigMF record and replay: the committed simulator recording replays through the
estimator to the very measurements made live, and a fresh record -> replay round trip
keeps the samples and the beacon tags."""

import json
import os
import tempfile

import numpy as np
import pmt
from gnuradio import blocks, gr, gr_unittest
from gnuradio import rfseek
from gnuradio.rfseek import flowgraphs, sigmf

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
RECORDING = os.path.join(SOURCE, "examples", "data", "sim_beacons")


def replay_meas(base):
    src, meta = sigmf.replay_source(base)
    e = meta["global"]["rfseek:estimator"]
    est = rfseek.doppler_estimator(meta["global"]["core:sample_rate"], e["window_len"],
                                   e["fft_len"], window=e["window"],
                                   interpolator=e["interpolator"], alignment=e["alignment"])
    dbg = blocks.message_debug()
    tb = gr.top_block()
    tb.connect(src, est)
    tb.msg_connect(est, "meas", dbg, "store")
    tb.run()
    return [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())], meta


class qa_sigmf(gr_unittest.TestCase):

    def test_python_blocks_are_importable_from_the_package(self):
        # As the README lists them: rfseek.<block> is the class its module defines.
        import sys
        from gnuradio.rfseek.vehicle_bridge import parse_nav  # noqa: F401 (GRC's way)
        vehicle_bridge = sys.modules["gnuradio.rfseek.vehicle_bridge"]
        self.assertIs(rfseek.sigmf_recorder, sigmf.sigmf_recorder)
        self.assertIs(rfseek.replay_source, sigmf.replay_source)
        self.assertIs(rfseek.vehicle_bridge, vehicle_bridge.vehicle_bridge)
        self.assertIs(rfseek.loopback_vehicle, vehicle_bridge.loopback_vehicle)
        try:
            from gnuradio.rfseek.seek_view import seek_view  # noqa: F401
        except ImportError:
            self.skipTest("no Qt or matplotlib: seek_view is optional")
        self.assertIs(rfseek.seek_view, sys.modules["gnuradio.rfseek.seek_view"].seek_view)
        # A refresh interval Qt cannot run is refused before any widget is made.
        for bad in (0, -5, float("nan"), "fast"):
            with self.assertRaisesRegex(ValueError, "update_ms"):
                rfseek.seek_view("view", bad)

    def test_committed_recording_is_valid_sigmf(self):
        # Named by its base or by either file, it is the same recording.
        data, m = sigmf.load(RECORDING)
        for name in (RECORDING + ".sigmf-meta", RECORDING + ".sigmf-data"):
            d2, m2 = sigmf.load(name)
            self.assertEqual(m2, m)
            self.assertTrue(np.array_equal(d2, data))
        meta = json.load(open(RECORDING + ".sigmf-meta"))
        g = meta["global"]
        self.assertEqual(g["core:datatype"], "cf32_le")
        self.assertEqual(g["core:version"], "1.0.0")
        self.assertEqual(g["core:sample_rate"], 100000.0)
        self.assertEqual(meta["captures"][0]["core:sample_start"], 0)
        starts = [a["core:sample_start"] for a in meta["annotations"]]
        self.assertEqual(starts, sorted(starts))
        labels = {a["core:label"] for a in meta["annotations"]}
        self.assertEqual(labels, {"beacon", "nav", "meas"})
        n = os.path.getsize(RECORDING + ".sigmf-data") // 8
        self.assertEqual(n, 60 * 1000)
        self.assertTrue(all(0 <= s < n for s in starts))

    def test_replay_reproduces_the_recorded_measurements(self):
        meas, meta = replay_meas(RECORDING)
        live = [a for a in meta["annotations"] if a["core:label"] == "meas"]
        self.assertEqual(len(meas), len(live))
        self.assertEqual(len(meas), 60)
        for m, a in zip(meas, live):
            self.assertEqual(m["slot"], a["rfseek:slot"])
            self.assertEqual(m["offset"], a["core:sample_start"])
            self.assertEqual(m["valid"], a["rfseek:valid"])
            # The recording's FFT may have been planned otherwise (FFTW's algorithm choice):
            # the same float32 spectrum to rounding moves the interpolated peak of these
            # windows at 0-5 dB by up to 2e-5 Hz (1e-6 of a 24.4 Hz bin), far below the
            # estimator's own scatter.
            self.assertAlmostEqual(m["freq_hz"], a["rfseek:freq_hz"], delta=1e-4)
            # The SNR sums float products: a change of summation order in the vector
            # kernels moves it in the 7th digit, nothing more.
            self.assertAlmostEqual(m["snr_db"], a["rfseek:snr_db"], delta=1e-4)

    def test_record_then_replay_round_trip(self):
        base = os.path.join(tempfile.mkdtemp(prefix="rfseek_sigmf_"), "rt")
        sc = rfseek.scenario(seed=12, initial_distance_m=210.0, start_angle_rad=0.0,
                             start_heading_rad=3.14159)
        tb = gr.top_block()
        src = rfseek.channel_source(sc, mode="burst", lockstep=False)
        rec = sigmf.sigmf_recorder(base, sc.samp_rate_hz, sc.carrier_hz, "round trip")
        snk = blocks.vector_sink_c()
        tb.connect(src, rec)
        tb.connect(src, snk)
        tb.run()
        data, meta = sigmf.load(base)
        self.assertTrue(np.array_equal(data, np.array(snk.data(), dtype=np.complex64)))
        self.assertEqual(meta["captures"][0]["core:frequency"], sc.carrier_hz)
        beacons = [a for a in meta["annotations"] if a["core:label"] == "beacon"]
        self.assertEqual([a["core:sample_start"] for a in beacons],
                         [k * sc.window_len for k in range(len(beacons))])
        self.assertEqual([a["rfseek:slot"] for a in beacons], list(range(len(beacons))))
        # And the replayed stream carries the same beacon tags.
        rsrc, _ = sigmf.replay_source(base)
        snk2 = blocks.vector_sink_c()
        tb2 = gr.top_block()
        tb2.connect(rsrc, snk2)
        tb2.run()
        tags = [t for t in snk2.tags() if pmt.symbol_to_string(t.key) == "rfseek_beacon"]
        self.assertEqual(len(tags), len(beacons))
        self.assertEqual(pmt.to_python(tags[3].value)["slot"], 3)

    def test_bad_recording_is_refused(self):
        base = os.path.join(tempfile.mkdtemp(prefix="rfseek_sigmf_"), "bad")
        json.dump({"global": {"core:datatype": "ri16_le", "core:sample_rate": 1.0}},
                  open(base + ".sigmf-meta", "w"))
        open(base + ".sigmf-data", "wb").close()
        with self.assertRaisesRegex(ValueError, "cf32_le"):
            sigmf.load(base)
        # A recorder that would write a frequency strict JSON cannot hold is refused.
        for rate, freq, word in ((1e5, float("nan"), "center_freq"),
                                 (1e5, "2.4 GHz", "center_freq"),
                                 (float("inf"), 2.4e9, "samp_rate"),
                                 (0.0, 2.4e9, "samp_rate")):
            with self.assertRaisesRegex(ValueError, word):
                sigmf.sigmf_recorder(base + "_rec", rate, freq)
        # A directory that does not exist is refused, not created: a typo in the path
        # would otherwise record somewhere unexpected.
        missing = os.path.join(os.path.dirname(base), "no_such_dir", "rec")
        with self.assertRaisesRegex(ValueError, "base.*no_such_dir.*does not exist"):
            sigmf.sigmf_recorder(missing, 1e5, 2.4e9)
        self.assertFalse(os.path.exists(os.path.dirname(missing)))
        for bad in ("", os.path.dirname(base) + os.sep, None):
            with self.assertRaisesRegex(ValueError, "base"):
                sigmf.sigmf_recorder(bad, 1e5, 2.4e9)


if __name__ == "__main__":
    gr_unittest.run(qa_sigmf)
