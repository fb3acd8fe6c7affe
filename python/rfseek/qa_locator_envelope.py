#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""scripts/locator_envelope.py without flying: its design covers every factor's
extremes, its settings are what the Monte Carlo reads, and --calibrate --from-json
turns synthetic fixes of known errors into the factors their quantiles give (rows by
the rule of lib/emitter_locator.cc: a low fit in the wind whatever its gust level;
the wandering loiters' fixes sized apart)."""

import importlib.util
import io
import json
import math
import os
import re
import tempfile
from contextlib import redirect_stdout

from gnuradio import gr_unittest

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
spec = importlib.util.spec_from_file_location(
    "locator_envelope", os.path.join(SOURCE, "scripts", "locator_envelope.py"))
env = importlib.util.module_from_spec(spec)
spec.loader.exec_module(env)

CHI95, CHI50 = 5.991464547107979, 1.3862943611198906


def fix(nees, gust=0.3, wind=0.1, alt=100.0, wandered=False, wdist=None):
    return {"cell": "synthetic", "nees95": nees, "gust_rms": gust, "wind": wind,
            "alt": alt, "wandered": wandered, "wdist": wdist, "in95": nees <= 1.0}


class qa_locator_envelope(gr_unittest.TestCase):

    def test_design_covers_every_factors_extremes(self):
        cells = [c for _, c in env.DESIGN if isinstance(c, dict)]
        seen = lambda k, d: {c.get(k, d) for c in cells}
        # realistic's own values where a cell leaves a factor alone
        self.assertTrue({0, 1, 2.5} <= seen("wind_gust_mps", 1))
        self.assertTrue({2, 10, 30, 60} <= seen("wind_gust_tau_s", 5))
        self.assertTrue({0, -30, 30} <= seen("altimeter_error_m", 0))
        self.assertTrue({-5, 0, 5} <= seen("compass_bias", 3))
        self.assertTrue({0, 3, 6} <= seen("compass_noise", 2))
        self.assertTrue({0, 7} <= seen("wind_speed_mps", 4))
        self.assertTrue({50, 150} <= seen("altitude_m", 100))
        self.assertIn("windy", [c for _, c in env.DESIGN])

    def test_settings_are_the_monte_carlos_in_radians(self):
        s = env.settings({"compass_bias": 5, "wind_gust_mps": 2.5})
        self.assertEqual(s[1], "wind_gust_mps=2.5")
        k, v = s[0].split("=")
        self.assertEqual(k, "compass_bias_rad")
        self.assertAlmostEqual(float(v), math.radians(5), places=15)
        self.assertEqual(env.settings("windy"), [])
        self.assertEqual(env.preset("windy"), "windy")
        self.assertEqual(env.preset({"altitude_m": 50}), "realistic")

    def calibrate(self, fixes):
        tmp = tempfile.TemporaryDirectory(prefix="locator_envelope_")
        self.addCleanup(tmp.cleanup)
        path = os.path.join(tmp.name, "fixes.json")
        with open(path, "w") as f:
            json.dump(fixes, f)
        out = io.StringIO()
        with redirect_stdout(out):
            rc = env.main(["--calibrate", "--from-json", path])
        self.assertEqual(rc, 0)
        text = out.getvalue()
        m = re.search(r"f95 = (\[\[.*?\]\]), f50 = (\[\[.*?\]\])", text)
        self.assertIsNotNone(m, text)
        return json.loads(m.group(1)), json.loads(m.group(2)), text

    def test_factors_put_the_quantiles_on_the_contours(self):
        # 100 light-wind calm fixes whose errors, in units of the unscaled 95 %
        # contour, are 0.04, 0.08, ... 4.0: the 94th percentile (the 95th value) is 3.8
        # and the median (the 51st) 2.04.
        calm = [fix(4.0 * (i + 1) / 100) for i in range(100)]
        # 20 low fits in the wind that found little gust (under 0.55 m/s), each 9 x
        # the unscaled contour: the low row, not the light-wind one.
        low = [fix(9.0, gust=0.3, wind=0.3, alt=50.0) for _ in range(20)]
        # Wandering loiters' fixes are sized apart and stay out of the bins.
        wand = [fix(1e6, wandered=True, wdist=float(i + 1)) for i in range(50)]
        f95, f50, text = self.calibrate(calm + low + wand)
        self.assertAlmostEqual(f95[0][0], round(math.sqrt(3.8), 2))
        self.assertAlmostEqual(f50[0][0], round(math.sqrt(2.04 * CHI95 / CHI50), 2))
        self.assertAlmostEqual(f95[2][0], 3.0)
        self.assertAlmostEqual(f50[2][0], round(math.sqrt(9.0 * CHI95 / CHI50), 2))
        # Never smaller in stronger gusts (empty bins borrow their calmer neighbour).
        for row in f95 + f50:
            self.assertEqual(row, sorted(row))
        # The wandering fixes: quantiles 0.94 and 0.5 of their distances 1..50 m.
        m = re.search(r"wandering loiters' fixes: (\d+).*?\[([\d.]+), ([\d.]+)\]", text)
        self.assertIsNotNone(m, text)
        self.assertEqual(int(m.group(1)), 50)
        self.assertEqual((float(m.group(2)), float(m.group(3))), (48.0, 26.0))

    def test_a_safe_height_or_still_air_is_not_low(self):
        fixes = [fix(1.0, gust=0.3, wind=0.3, alt=70.0) for _ in range(12)] + \
                [fix(1.0, gust=0.3, wind=0.19, alt=50.0) for _ in range(12)]
        f95, _, _ = self.calibrate(fixes)
        self.assertAlmostEqual(f95[0][0], 1.0)
        # No low fit: the low row's bin is the largest of the rows above it.
        self.assertAlmostEqual(f95[2][0], 1.0)

    def test_bad_arguments_are_refused(self):
        for args in (["--cells", "("], ["--cells", "no such cell"], ["--runs", "0"]):
            with self.assertRaises(SystemExit):
                with redirect_stdout(io.StringIO()):
                    env.main(args)


if __name__ == "__main__":
    gr_unittest.run(qa_locator_envelope)
