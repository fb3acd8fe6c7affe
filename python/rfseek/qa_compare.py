#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""The paired comparison of two rfseek-montecarlo results (gnuradio.rfseek.compare and
rfseek-plot-montecarlo --against): against a hand computation of the per-seed
differences, groups kept apart, bad input, and two studies flown from the build tree."""

import json
import math
import os
import random
import subprocess
import sys
import tempfile

from gnuradio import gr_unittest
from gnuradio.rfseek import compare

BUILD = os.environ.get("RFSEEK_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
SOURCE = os.environ.get("RFSEEK_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
MC = os.path.join(BUILD, "apps", "rfseek-montecarlo")
PLOT = os.path.join(SOURCE, "apps", "rfseek-plot-montecarlo")


def result(rows):
    return {"rows": rows, "summary": {}, "strategies": ["adaptive"], "runs": len(rows)}


def row(seed, ratio, success=True, preset="", sweep=""):
    r = {"seed": seed, "strategy": "adaptive", "ratio": ratio, "success": success}
    if preset:
        r["preset"] = preset
    if sweep:
        r["sweep_value"] = sweep
    return r


class qa_compare(gr_unittest.TestCase):

    def test_paired_difference_against_a_hand_computation(self):
        rng = random.Random(7)
        base, variant, d = [], [], []
        for seed in range(100, 160):
            r = 1.0 + rng.random() * 0.2           # the worlds' spread, common to both
            shift = rng.gauss(-0.003, 0.002)       # what the variant changes
            base.append(row(seed, r, success=seed % 7 != 0))
            variant.append(row(seed, r + shift, success=seed % 5 != 0))
            d.append((r + shift) - r)
        # Seeds only one side flew, and a run without a value, are not paired.
        base.append(row(200, 1.1))
        variant.append(row(300, 1.2))
        variant[3]["ratio"] = None
        del d[3]
        out = compare.paired(result(variant), result(base))
        self.assertEqual(len(out), 1)
        o = out[0]
        n = len(d)
        self.assertEqual(o["n"], 59)
        mean = sum(d) / n
        sd = math.sqrt(sum((x - mean) ** 2 for x in d) / (n - 1))
        self.assertAlmostEqual(o["diff"], mean, places=12)
        self.assertAlmostEqual(o["se"], sd / math.sqrt(n), places=12)
        self.assertEqual(o["changed"], 59)
        seeds = [s for s in range(100, 160) if s != 103]
        self.assertAlmostEqual(o["success_base"], sum(s % 7 != 0 for s in seeds) / n)
        self.assertAlmostEqual(o["success_variant"], sum(s % 5 != 0 for s in seeds) / n)
        # Pairing sees a shift that the two means' spread hides.
        spread = math.sqrt(sum((r["ratio"] - o["mean_base"]) ** 2 for r in base[:60]) / 59)
        self.assertLess(o["se"], 0.2 * spread / math.sqrt(n))
        table = compare.paired_table(out)
        self.assertIn("| adaptive | — | — | 59 |", table)
        self.assertIn("%+.5f (+- %.5f)" % (mean, sd / math.sqrt(n)), table)

    def test_groups_are_kept_apart_and_a_constant_shift_is_exact(self):
        base, variant = [], []
        for seed in range(1, 9):
            for preset, sweep, shift in (("reference", "10", 0.125), ("reference", "25", 0.0),
                                         ("windy", "10", -0.25)):
                r = 1.0 + seed / 8.0                 # exact binary fractions
                base.append(row(seed, r, preset=preset, sweep=sweep))
                variant.append(row(seed, r + shift, preset=preset, sweep=sweep))
        out = {(o["preset"], o["sweep_value"]): o
               for o in compare.paired(result(variant), result(base))}
        self.assertEqual(set(out), {("reference", "10"), ("reference", "25"), ("windy", "10")})
        self.assertEqual(out[("reference", "10")]["diff"], 0.125)
        self.assertEqual(out[("reference", "10")]["se"], 0.0)
        self.assertEqual(out[("reference", "25")]["changed"], 0)
        self.assertEqual(out[("windy", "10")]["diff"], -0.25)
        self.assertEqual(out[("windy", "10")]["n"], 8)

    def test_bad_input_names_the_problem(self):
        good = result([row(1, 1.0)])
        with self.assertRaisesRegex(ValueError, "column must be one of"):
            compare.paired(good, good, "success")
        with self.assertRaisesRegex(ValueError, "the base is not an rfseek-montecarlo"):
            compare.paired(good, {"summary": {}})
        with self.assertRaisesRegex(ValueError, "share no seed"):
            compare.paired(result([row(2, 1.0)]), good)
        one = compare.paired(good, good)
        self.assertIsNone(one[0]["se"])
        self.assertIn("(one pair)", compare.paired_table(one))

    def test_two_studies_from_the_build_tree(self):
        tmp = tempfile.mkdtemp(prefix="rfseek_compare_")
        common = ["--runs", "6", "--seed", "41", "--strategy", "adaptive", "--quiet",
                  "--set", "initial_distance_m=2000"]
        paths = {}
        for name, extra in (("one", ["--threads", "1"]), ("two", ["--threads", "2"]),
                            ("long", ["--threads", "2", "--set", "adaptive_track_slots=30"])):
            paths[name] = os.path.join(tmp, name + ".json")
            p = subprocess.run([MC, "--out", paths[name]] + common + extra,
                               capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stderr)

        def cli(*args):
            return subprocess.run([sys.executable, PLOT] + list(args),
                                  capture_output=True, text=True)
        # The thread count does not change a row: nothing differs.
        p = cli(paths["two"], "--against", paths["one"])
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("| adaptive | — | — | 6 |", p.stdout)
        self.assertIn("+0.00000 (+- 0.00000) | [0.00000, 0.00000] | 0 |", p.stdout)
        # Longer probe segments change the flights: the printed difference is the mean
        # of the per-seed differences of the two JSON files.
        p = cli(paths["long"], "--against", paths["one"])
        self.assertEqual(p.returncode, 0, p.stderr)
        a = {r["seed"]: r["ratio"] for r in json.load(open(paths["long"]))["rows"]}
        b = {r["seed"]: r["ratio"] for r in json.load(open(paths["one"]))["rows"]}
        d = [a[s] - b[s] for s in b]
        self.assertEqual(len(d), 6)
        self.assertGreater(sum(1 for x in d if x != 0.0), 0)
        self.assertIn("%+.5f (+- " % (sum(d) / 6), p.stdout)
        self.assertIn("| %d |" % sum(1 for x in d if x != 0.0), p.stdout)
        # Not a result, or nothing in common: exit 2 with the reason.
        bad = os.path.join(tmp, "bad.json")
        with open(bad, "w") as f:
            f.write("{}")
        p = cli(paths["one"], "--against", bad)
        self.assertEqual(p.returncode, 2)
        self.assertIn("not an rfseek-montecarlo result", p.stderr)
        p = cli(paths["one"], "--against", paths["two"], "--column", "slots")
        self.assertEqual(p.returncode, 2)
        self.assertIn("column must be one of", p.stderr)


if __name__ == "__main__":
    gr_unittest.run(qa_compare)
