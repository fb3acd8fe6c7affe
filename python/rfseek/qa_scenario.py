#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""scenario and world from Python: readable attributes, keyword construction, None for
seed-drawn fields, ValueError naming the field, numpy samples."""

import json
import math

import numpy as np
from gnuradio import gr_unittest
from gnuradio import rfseek


class qa_scenario(gr_unittest.TestCase):

    def test_version_is_the_cmake_projects(self):
        import os
        import re
        src = os.environ.get("RFSEEK_SOURCE_DIR",
                             os.path.join(os.path.dirname(__file__), "..", ".."))
        with open(os.path.join(src, "CMakeLists.txt")) as f:
            m = re.search(r"project\(gr-rfseek VERSION ([0-9.]+)", f.read())
        self.assertIsNotNone(m)
        self.assertEqual(rfseek.__version__, m.group(1))

    def test_defaults_and_keywords(self):
        sc = rfseek.scenario()
        self.assertEqual(sc.initial_distance_m, 5000.0)
        self.assertIsNone(sc.cfo_hz)
        self.assertIsNone(sc.start_heading_rad)
        sc2 = rfseek.scenario(snr_db=-5.0, cfo_hz=10.0, num_scatterers=0)
        self.assertEqual((sc2.snr_db, sc2.cfo_hz, sc2.num_scatterers), (-5.0, 10.0, 0))
        with self.assertRaises(TypeError):
            rfseek.scenario(snr=3)
        self.assertAlmostEqual(sc.max_doppler_hz, 10 * 2e9 / rfseek.SPEED_OF_LIGHT)
        self.assertEqual(set(json.loads(sc.to_json()).keys()), set(rfseek.scenario.keys()))

    def test_split_sets_sorts_keys_and_lists_them_all_when_unknown(self):
        scen, seek = rfseek.split_sets(["snr_db=-3", "adaptive_gain=0.7", "speed_mps=12"])
        self.assertEqual(scen, ["snr_db=-3", "speed_mps=12"])  # shared keys: the scenario's
        self.assertEqual(seek, ["adaptive_gain=0.7"])
        with self.assertRaises(ValueError) as cm:
            rfseek.split_sets(["adaptive_gian=0.7"])
        text = str(cm.exception)
        self.assertIn("adaptive_gian", text)
        for key in list(rfseek.scenario.keys()) + list(rfseek.seeker_config.keys()):
            self.assertIn(key, text)
        for bad in (["snr_db"], "snr_db=1"):
            with self.assertRaises(ValueError):
                rfseek.split_sets(bad)

    def test_value_error_names_field(self):
        for key, bad in (("initial_distance_m", -1.0), ("fft_len", 2), ("gamma_max", 2.0),
                         ("samp_rate_hz", 0.0), ("cfo_hz", 1e6)):
            sc = rfseek.scenario()
            setattr(sc, key, bad)
            with self.assertRaisesRegex(ValueError, "scenario." + key):
                sc.validate()

    def test_world_from_python(self):
        sc = rfseek.scenario(num_scatterers=0, add_noise=False, cfo_hz=0.0,
                             cfo_drift_hz_per_s=0.0, cfo_walk_hz_per_sqrt_s=0.0,
                             start_angle_rad=math.pi / 2, start_heading_rad=-math.pi / 2)
        w = rfseek.world(sc)
        x = w.synthesize(sc.window_len)
        self.assertEqual(x.dtype, np.complex64)
        f = np.angle(np.vdot(x[:-1], x[1:])) / (2 * np.pi) * sc.samp_rate_hz
        self.assertAlmostEqual(f, sc.max_doppler_hz, delta=0.05)
        self.assertEqual(len(w.paths()), 1)
        self.assertAlmostEqual(abs(w.field()), 1.0 / 5000.0)
        w.advance(-math.pi / 2)
        self.assertAlmostEqual(w.distance_m, 5000.0 - 0.5)
        with self.assertRaises(ValueError):
            w.advance(float("nan"))

    def test_copies_and_pickles_are_independent_and_whole(self):
        import copy
        import pickle
        sc = rfseek.scenario(seed=3, wind_speed_mps=4.0, start_angle_rad=0.5)
        for twin in (copy.copy(sc), copy.deepcopy(sc), pickle.loads(pickle.dumps(sc))):
            self.assertEqual(twin.to_json(), sc.to_json())
            twin.snr_db = -3.0
            self.assertEqual(sc.snr_db, 0.0)
        cfg = rfseek.seeker_config(strategy="adaptive", adaptive_gain=0.6)
        back = pickle.loads(pickle.dumps(cfg))
        for key in cfg.keys():
            if hasattr(cfg, key):
                a, b = getattr(cfg, key), getattr(back, key)
                self.assertTrue(a == b or (a != a and b != b), key)  # NaN == NaN here
        self.assertIn("strategy='adaptive'", repr(cfg))
        self.assertIn("window='hann'", repr(rfseek.estimator_config(window="hann")))
        # A run's summary prints its fields.
        r = rfseek.simulation(rfseek.scenario(seed=2, initial_distance_m=400.0),
                              rfseek.simulation.seeker_for(
                                  rfseek.scenario(seed=2, initial_distance_m=400.0),
                                  "paper")).run()
        self.assertIn("ratio=%r" % r.summary.ratio, repr(r.summary))

    def test_helpers_name_what_is_wrong(self):
        with self.assertRaisesRegex(ValueError, "seeker_for: strategy = 'nope'"):
            rfseek.simulation.seeker_for(rfseek.scenario(), "nope")
        with self.assertRaisesRegex(ValueError, "a list of 'KEY=VALUE' strings"):
            rfseek.apply_sets(rfseek.scenario(), "snr_db=3")


if __name__ == "__main__":
    gr_unittest.run(qa_scenario)
