#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""scripts/gust_probe_bound.py, one probe cycle's bearing noise in gusts, against its
closed forms: white noise alone, a gust constant over the cycle, and the generalised
least squares fit never worse than the plain one."""

import importlib.util
import math
import os
import subprocess
import sys

from gnuradio import gr_unittest

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(SOURCE, "scripts", "gust_probe_bound.py")
spec = importlib.util.spec_from_file_location("gust_probe_bound", SCRIPT)
gpb = importlib.util.module_from_spec(spec)
spec.loader.exec_module(gpb)

A = 66.7  # f_d,max at 10 m/s and 2 GHz


class qa_gust_probe_bound(gr_unittest.TestCase):

    def test_white_noise_alone_is_the_closed_form(self):
        # Instant turns: A sin(u) = +-A sin(delta) over n = 4 slots beacons, orthogonal to
        # the offset and (+, -, -, + is symmetric in time) to the drift.
        for slots, deg in ((10, 5.0), (20, 10.0), (40, 20.0)):
            d = math.radians(deg)
            ols, gls = gpb.sin_error_std(A, d, slots, 0.05, 0.0, 0.0, 5.0, 2.5)
            expected = 2.5 / (A * math.sin(d) * math.sqrt(4 * slots))
            self.assertAlmostEqual(ols, expected, delta=1e-9)
            self.assertAlmostEqual(gls, expected, delta=1e-9)

    def test_a_gust_constant_over_the_cycle_is_the_offset(self):
        ols0, _ = gpb.sin_error_std(A, math.radians(10), 20, 0.05, 0.0, 0.0, 5.0, 2.5)
        ols, gls = gpb.sin_error_std(A, math.radians(10), 20, 0.05, 0.0, 13.3, 1e9, 2.5)
        self.assertAlmostEqual(ols, ols0, delta=1e-6)
        self.assertAlmostEqual(gls, ols0, delta=1e-6)

    def test_the_best_linear_fit_is_never_worse(self):
        prev = 0.0
        for tau in (30.0, 15.0, 5.0, 2.0):
            ols, gls = gpb.sin_error_std(A, math.radians(10), 20, 0.05, math.radians(30),
                                         13.3, tau, 2.5)
            self.assertLessEqual(gls, ols * (1 + 1e-9))
            self.assertGreater(gls, 0.0)
            # Faster gusts of the same size leave more in one cycle: the floor rises.
            self.assertGreater(gls, prev)
            prev = gls

    def test_the_best_fit_is_the_gls_covariance(self):
        # Independently: the generalised least squares covariance (X' S^-1 X)^-1, with
        # the gust (Gauss-Markov) and white-noise covariance S built here.
        import numpy as np
        for tau, rate in ((15.0, 30.0), (5.0, 0.0)):
            d, slots, dt = math.radians(10), 20, 0.05
            u = gpb.cycle_headings(d, slots, math.radians(rate), dt)
            t = np.arange(len(u)) * dt
            x = np.column_stack([A * np.sin(u), np.ones(len(u)), t - t.mean()])
            cov = 13.3 ** 2 * np.exp(-np.abs(np.subtract.outer(t, t)) / tau) + \
                2.5 ** 2 * np.eye(len(u))
            expected = math.sqrt(np.linalg.inv(x.T @ np.linalg.inv(cov) @ x)[0, 0])
            ols, gls = gpb.sin_error_std(A, d, slots, dt, math.radians(rate), 13.3, tau,
                                         2.5)
            self.assertAlmostEqual(gls, expected, delta=1e-9 * expected)
            self.assertGreater(ols, gls * 1.01)  # correlated gusts: the plain fit loses

    def test_turns_take_the_stated_time(self):
        h = gpb.cycle_headings(math.radians(10), 20, math.radians(30), 0.05)
        self.assertEqual(len(h), 80)
        # From +10 to -10 deg at 30 deg/s: 20 deg in 0.667 s, 14 beacons of 0.05 s.
        moving = sum(1 for a, b in zip(h[:40], h[1:41]) if abs(b - a) > 1e-12)
        self.assertEqual(moving, math.ceil(20.0 / (30.0 * 0.05)))
        self.assertAlmostEqual(h[39], math.radians(-10))

    def test_command_line(self):
        run = subprocess.run([sys.executable, SCRIPT, "--gust", "1", "--tau", "5",
                              "--slots", "20", "--deltas", "10"],
                             capture_output=True, text=True, timeout=60)
        self.assertEqual(run.returncode, 0, run.stderr)
        row = [line for line in run.stdout.splitlines() if line.startswith("| 20 | 10 |")]
        self.assertEqual(len(row), 1, run.stdout)
        ols, gls = gpb.sin_error_std(10.0 / (gpb.C / 2e9), math.radians(10), 20,
                                     0.05, math.radians(30), 1.0 / (gpb.C / 2e9), 5.0, 2.5)
        self.assertIn("| %.3f | %.3f |" % (ols, gls), row[0])
        for bad, name in ((["--gust", "-1"], "--gust"), (["--tau", "0"], "--tau"),
                          (["--deltas", "95"], "--deltas"), (["--slots", "1"], "--slots"),
                          (["--slots", "x"], "--slots")):
            run = subprocess.run([sys.executable, SCRIPT] + bad, capture_output=True,
                                 text=True, timeout=60)
            self.assertEqual(run.returncode, 2)
            self.assertIn(name, run.stderr)
            self.assertNotIn("Traceback", run.stderr)


if __name__ == "__main__":
    gr_unittest.run(qa_gust_probe_bound)
