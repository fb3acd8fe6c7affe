#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""rfseek-montecarlo from the build tree: the JSON's schema, the summary recomputed from
the rows, identical rows with 1 and 2 threads, the CSV, the plots, and bad options."""

import csv
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import unittest

from gnuradio import gr_unittest

BUILD = os.environ.get("RFSEEK_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
SOURCE = os.environ.get("RFSEEK_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
MC = os.path.join(BUILD, "apps", "rfseek-montecarlo")
# A shorter flight than the reference (2 km) keeps the test quick; the code is the same.
SHORT = ["--set", "initial_distance_m=2000", "--quiet"]
# Under AddressSanitizer (scripts/sanitize.sh) the studies of 20-60 runs would take most
# of the job: they are statistics, which the main test job checks; the sanitizer job
# runs every code path they use in the short tests (arrival and location included).
SANITIZED = os.environ.get("RFSEEK_SANITIZE") == "1"
STUDY = "a statistical study: run by the main test job, too slow under the sanitizers"


def run_mc(tmp, name, *args):
    out = os.path.join(tmp, name + ".json")
    p = subprocess.run([MC, "--out", out] + list(args), capture_output=True, text=True)
    return p, out


def percentile(v, q):
    v = sorted(v)
    pos = q * (len(v) - 1)
    i = int(pos)
    f = pos - i
    return v[i] * (1 - f) + v[i + 1] * f if i + 1 < len(v) else v[i]


class qa_montecarlo(gr_unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="rfseek_mc_")

    def test_schema_and_summary_match_rows(self):
        p, out = run_mc(self.tmp, "mc", "--runs", "20", "--seed", "5",
                        "--strategy", "paper,paper_no_circle", "--threads", "2", *SHORT)
        self.assertEqual(p.returncode, 0, p.stderr)
        res = json.load(open(out))
        for key in ("scenario", "rows", "summary", "strategies", "runs", "seed", "timing"):
            self.assertIn(key, res)
        self.assertEqual(res["scenario"]["initial_distance_m"], 2000)
        self.assertEqual(len(res["rows"]), 40)
        for r in res["rows"]:
            for key in ("seed", "strategy", "distance_m", "ratio", "time_s", "success",
                        "stage1_heading_error_deg"):
                self.assertIn(key, r)
        # Both strategies on the same seeds 5..24.
        for s in ("paper", "paper_no_circle"):
            rows = [r for r in res["rows"] if r["strategy"] == s]
            self.assertEqual(sorted(r["seed"] for r in rows), list(range(5, 25)))
            summ = res["summary"][s]
            d = [r["distance_m"] for r in rows]
            ratio = [r["ratio"] for r in rows]
            shortest = 2000 - 200
            self.assertEqual(summ["runs"], 20)
            self.assertAlmostEqual(summ["success_rate"], sum(r["success"] for r in rows) / 20)
            self.assertAlmostEqual(summ["mean_distance_m"], statistics.mean(d), places=4)
            self.assertAlmostEqual(summ["median_distance_m"], statistics.median(d), places=4)
            self.assertAlmostEqual(summ["p90_distance_m"], percentile(d, 0.9), places=4)
            self.assertAlmostEqual(summ["mean_ratio"], statistics.mean(ratio), places=6)
            self.assertAlmostEqual(summ["median_ratio"], statistics.median(ratio), places=6)
            self.assertAlmostEqual(summ["p90_ratio"], percentile(ratio, 0.9), places=6)
            self.assertEqual(summ["shortest_path_m"], shortest)
            for r in rows:
                self.assertAlmostEqual(r["ratio"], r["distance_m"] / shortest, places=6)
                self.assertAlmostEqual(r["time_s"], r["distance_m"] / 10.0, places=6)
        # The CSV holds the same rows.
        rows_csv = list(csv.DictReader(open(out[:-5] + ".csv")))
        self.assertEqual(len(rows_csv), 40)
        self.assertAlmostEqual(float(rows_csv[3]["distance_m"]), res["rows"][3]["distance_m"],
                               places=3)
        # And the figures can be drawn from it.
        plot = subprocess.run([sys.executable, os.path.join(SOURCE, "apps",
                                                            "rfseek-plot-montecarlo"), out],
                              capture_output=True, text=True)
        self.assertEqual(plot.returncode, 0, plot.stderr)
        self.assertTrue(os.path.getsize(os.path.join(self.tmp, "mc_histograms.png")) > 1000)
        self.assertTrue(os.path.getsize(os.path.join(self.tmp, "mc_comparison.png")) > 1000)

    @unittest.skipIf(SANITIZED, STUDY)
    def test_arrival_self(self):
        # The acceptance study at relaxed bounds: 30 reference runs, the vehicle
        # deciding its arrival and locating the emitter without truth.
        p, out = run_mc(self.tmp, "self", "--runs", "30", "--strategy", "paper",
                        "--arrival", "self", "--threads", "2", "--quiet")
        self.assertEqual(p.returncode, 0, p.stderr)
        res = json.load(open(out))
        rows = res["rows"]
        self.assertEqual(len(rows), 30)
        detect = [r["arrival_detect_distance_m"] for r in rows if r["declared"]]
        errors = [r["location_error_m"] for r in rows if r["located"]]
        self.assertGreaterEqual(sum(d <= 300.0 for d in detect), 29)  # >= 95 %
        self.assertEqual(sum(r["false_arrival"] for r in rows), 0)
        self.assertGreaterEqual(len(errors), 28)
        self.assertLessEqual(statistics.median(errors), 30.0)
        self.assertLessEqual(percentile(errors, 0.9), 80.0)
        summ = res["summary"]["paper"]
        self.assertAlmostEqual(summ["location_error_m_median"], statistics.median(errors))
        self.assertAlmostEqual(summ["declared_within_300m_rate"],
                               sum(d <= 300.0 for d in detect) / 30)
        # The seeking figures are those of the oracle runs (distance to d_v): the path
        # up to d_v does not depend on what happens after it.
        p2, out2 = run_mc(self.tmp, "oracle", "--runs", "30", "--strategy", "paper",
                          "--threads", "2", "--quiet")
        self.assertEqual(p2.returncode, 0, p2.stderr)
        oracle = json.load(open(out2))["rows"]
        # The loiter begins at the overflight (arrival is declared later, once a fit
        # confirms it): a run whose overflight came within d_v flew the oracle's path.
        for a, b in zip(rows, oracle):
            if a["declared"]:
                self.assertIsNotNone(a["overflight_distance_m"])
            if a["overflight_distance_m"] is not None and a["overflight_distance_m"] < 200.0:
                # The same path: both processes plan their FFTs without timing
                # (RFSEEK_FFT_PLANNER=ESTIMATE), so the floats are the same too.
                self.assertEqual(a["distance_m"], b["distance_m"])
        # The CSV has the arrival columns and --resume reads them back.
        head = open(out[:-5] + ".csv").readline().strip().split(",")
        for col in ("declared", "arrival_detect_distance_m", "false_arrival", "located",
                    "location_error_m", "location_major_m", "location_in_ellipse",
                    "overflight_distance_m"):
            self.assertIn(col, head)
        p3 = subprocess.run([MC, "--out", out, "--runs", "30", "--strategy", "paper",
                             "--arrival", "self", "--resume", "--quiet"],
                            capture_output=True, text=True)
        self.assertEqual(p3.returncode, 0, p3.stderr)
        self.assertEqual(json.load(open(out))["rows"], rows)
        bad = subprocess.run([MC, "--arrival", "maybe"], capture_output=True, text=True)
        self.assertEqual(bad.returncode, 2)
        self.assertIn("--arrival", bad.stderr)

    @unittest.skipIf(SANITIZED, STUDY)
    def test_arrival_self_realistic(self):
        # Under realistic (100 m up, 4 m/s wind with 1 m/s gusts, compass error), 30
        # adaptive runs: the location fit with gust states and the height prior meets the
        # issue's targets at relaxed bounds, and its 95 % ellipse is honest where the
        # constant-wind fit without priors (which reads the integrated gust as position)
        # is overconfident, on the same seeds (200 runs: 87 % against 28 %), its own
        # ellipse measured without the split check. The split check, which fits the
        # halves of each fix's data apart, sees the constant-wind fit fail and grows its
        # ellipse: the same fixes are covered more often.
        errs, inside = {}, {}
        # The constant-wind fits are the prior's ellipse alone (locate_nuisance=false:
        # the honest ellipse would widen theirs too), and no limit on it decides when a
        # fix is published (the split check's grown ellipse would otherwise keep some
        # flights orbiting: different fixes).
        const = ["--set", "locate_gust_mps=0", "--set", "locate_altitude_sigma_m=0",
                 "--set", "locate_nuisance=false", "--set", "locate_max_axis_m=1e6"]
        for name, extra in (("map", []),
                            ("const", const + ["--set", "locate_split_gate=0"]),
                            ("const_checked", const)):
            p, out = run_mc(self.tmp, "real_" + name, "--runs", "30", "--strategy",
                            "adaptive", "--preset", "realistic", "--arrival", "self",
                            "--threads", "2", "--quiet", *extra)
            self.assertEqual(p.returncode, 0, p.stderr)
            rows = json.load(open(out))["rows"]
            self.assertEqual(len(rows), 30)
            self.assertEqual(sum(r["false_arrival"] for r in rows), 0)
            errs[name] = [r["location_error_m"] for r in rows if r["located"]]
            inside[name] = sum(r["location_in_ellipse"] for r in rows if r["located"])
            if name == "map":
                # Arrival is declared by the emitter, confirmed by the fit.
                near = [r for r in rows
                        if r["declared"] and r["arrival_detect_distance_m"] <= 300.0]
                self.assertGreaterEqual(len(near), 29)
        e = errs["map"]
        self.assertGreaterEqual(len(e), 27)
        self.assertLessEqual(statistics.median(e), 30.0)
        self.assertLessEqual(percentile(e, 0.9), 80.0)
        self.assertGreaterEqual(inside["map"], 0.7 * len(e))
        self.assertLessEqual(inside["const"], 0.5 * len(errs["const"]))
        self.assertEqual(errs["const_checked"], errs["const"])  # the same fixes
        self.assertGreater(inside["const_checked"], inside["const"])

    @unittest.skipIf(SANITIZED, STUDY)
    def test_arrival_self_windy(self):
        # The windy preset (6 m/s wind, 2 m/s gusts of 15 s, compass, altimeter and
        # airspeed errors) with the locator's defaults, 20 adaptive runs at relaxed
        # bounds. Gusts there drop the Doppler like an overflight kilometres out; the
        # first orbit's far-field amplitude (arrival_far_amplitude) sends the vehicle on
        # at once, where without it each such loiter costs minutes of flight.
        rows = {}
        for name, extra in (("check", []),
                            ("nocheck", ["--set", "arrival_far_amplitude=0"])):
            p, out = run_mc(self.tmp, "windy_" + name, "--runs", "20", "--strategy",
                            "adaptive", "--preset", "windy", "--arrival", "self",
                            "--threads", "2", "--quiet", *extra)
            self.assertEqual(p.returncode, 0, p.stderr)
            rows[name] = json.load(open(out))["rows"]
            self.assertEqual(len(rows[name]), 20)
        r = rows["check"]
        self.assertGreaterEqual(sum(x["success"] for x in r), 18)
        self.assertLessEqual(sum(x["false_arrival"] for x in r), 2)
        near = [x for x in r if x["declared"] and x["arrival_detect_distance_m"] <= 300.0]
        self.assertGreaterEqual(len(near), 10)
        # Seed by seed (the same flights up to the first false overflight): the check
        # shortens more flights than it lengthens (20 seeds: 6 shorter, none longer; 30
        # seeds: 10 and none). The mean is not compared: in these gusts one chaotic
        # flight can move it by 5 % either way.
        pairs = list(zip(sorted(rows["check"], key=lambda x: x["seed"]),
                         sorted(rows["nocheck"], key=lambda x: x["seed"])))
        shorter = sum(a["straight_ratio"] < b["straight_ratio"] - 0.02 for a, b in pairs)
        longer = sum(a["straight_ratio"] > b["straight_ratio"] + 0.02 for a, b in pairs)
        self.assertGreater(shorter, longer + 2)

    @unittest.skipIf(SANITIZED, STUDY)
    def test_locator_is_honest_in_gusts_unlike_its_prior(self):
        # The locator's gust prior (1.5 m/s, 4 s by default) is not the air's: realistic
        # with 1 m/s gusts of 30 s, 30 adaptive runs. The 95 % ellipse must still hold
        # the emitter in most located runs (the envelope table in docs/seeker.md: 91.9 %
        # of 100 runs for these gusts), while staying small enough to mean something.
        p, out = run_mc(self.tmp, "honest", "--runs", "30", "--strategy", "adaptive",
                        "--preset", "realistic", "--arrival", "self", "--threads", "2",
                        "--set", "wind_gust_mps=1", "--set", "wind_gust_tau_s=30",
                        "--quiet")
        self.assertEqual(p.returncode, 0, p.stderr)
        rows = [r for r in json.load(open(out))["rows"] if r["located"]]
        self.assertGreaterEqual(len(rows), 28)
        inside = sum(r["location_in_ellipse"] for r in rows)
        self.assertGreaterEqual(inside, 0.8 * len(rows))
        self.assertLessEqual(statistics.median(r["location_error_m"] for r in rows), 25.0)
        self.assertLessEqual(statistics.median(r["location_major_m"] for r in rows), 60.0)

    def test_ellipse_stays_honest_where_gusts_and_altimeter_are_unlike_the_priors(self):
        # A mismatched cell: 2.5 m/s gusts of 30 s (the prior: 1.5 m/s of 4 s) and the
        # altimeter 30 m low (the prior: its reading +- 20 m), 30 adaptive runs on seeds
        # no table uses. The fixes, sure and unsure alike, carry the nuisance: the 95 %
        # ellipse holds the emitter in at least 75 % of them (docs/seeker.md, "How honest
        # the ellipse is"); the prior's own ellipse (locate_nuisance=false) held it in
        # 45 % of 100 such runs. The summary's new rates agree with the rows. Under the
        # sanitizers 6 runs take the same paths (sure and unsure fixes), without the rate.
        runs = 6 if SANITIZED else 30
        p, out = run_mc(self.tmp, "mismatch", "--runs", str(runs), "--seed", "6000001",
                        "--strategy", "adaptive", "--preset", "realistic", "--arrival",
                        "self", "--threads", "2", "--set", "wind_gust_mps=2.5",
                        "--set", "wind_gust_tau_s=30", "--set", "altimeter_error_m=-30",
                        "--quiet")
        self.assertEqual(p.returncode, 0, p.stderr)
        res = json.load(open(out))
        rows = res["rows"]
        fixes = [r for r in rows if r["located"]]
        self.assertGreaterEqual(len(fixes), 0.9 * runs)
        inside = sum(r["location_in_ellipse"] for r in fixes)
        if not SANITIZED:
            self.assertGreaterEqual(inside, 0.75 * len(fixes))
        # A 50 % ellipse inside the 95 % one holds fewer.
        self.assertLessEqual(sum(r["location_in_ellipse50"] for r in fixes), inside)
        s = res["summary"]["adaptive"]
        unsure = sum(r["location_unsure"] for r in fixes)
        self.assertAlmostEqual(s["located_unsure_rate"], unsure / len(rows))
        self.assertAlmostEqual(s["located_sure_rate"], (len(fixes) - unsure) / len(rows))
        self.assertAlmostEqual(s["location_in_ellipse50_rate"],
                               sum(r["location_in_ellipse50"] for r in fixes) / len(fixes))
        # Unsure fixes are those whose 95 % ellipse exceeds the limit (100 m), or a
        # wandering loiter's, never confirmed: sized as such fixes err, its semi-axes'
        # geometric mean 63 m (locator_nuisance.wander_radii_m()), so its semi-major
        # axis at least that.
        for r in fixes:
            if r["location_unsure"]:
                self.assertGreaterEqual(r["location_major_m"], 63.0)

    def test_rows_do_not_depend_on_thread_count(self):
        args = ["--runs", "6", "--seed", "11", "--strategy", "paper,rss_baseline",
                "--set", "flight_cap_m=4000"] + SHORT
        p1, o1 = run_mc(self.tmp, "t1", "--threads", "1", *args)
        p2, o2 = run_mc(self.tmp, "t2", "--threads", "2", *args)
        self.assertEqual(p1.returncode, 0, p1.stderr)
        self.assertEqual(p2.returncode, 0, p2.stderr)
        r1, r2 = json.load(open(o1)), json.load(open(o2))
        self.assertEqual(r1["rows"], r2["rows"])
        self.assertEqual(r1["summary"], r2["summary"])

    def test_sweep(self):
        p, out = run_mc(self.tmp, "sw", "--runs", "3", "--strategy", "paper_no_circle",
                        "--sweep", "snr_db=-5,5", *SHORT)
        self.assertEqual(p.returncode, 0, p.stderr)
        res = json.load(open(out))
        self.assertEqual(res["sweep"]["key"], "snr_db")
        self.assertEqual([e["value"] for e in res["sweep"]["summary"]], ["-5", "5"])
        self.assertEqual(len(res["rows"]), 6)
        plot = subprocess.run([sys.executable, os.path.join(SOURCE, "apps",
                                                            "rfseek-plot-montecarlo"), out],
                              capture_output=True, text=True)
        self.assertEqual(plot.returncode, 0, plot.stderr)

    def test_sweep_over_several_presets_plots_a_column_each(self):
        # --preset A,B --sweep: each preset's column shows its own points (the figure
        # once mixed them and failed on mismatched lengths).
        from gnuradio.rfseek import plots
        p, out = run_mc(self.tmp, "psw", "--runs", "1", "--strategy", "paper",
                        "--preset", "reference,drift10", "--sweep", "snr_db=-5,5", *SHORT)
        self.assertEqual(p.returncode, 0, p.stderr)
        res = json.load(open(out))
        fig = plots.sweep_plot(res)
        top = [a for a in fig.axes if a.get_title()]
        self.assertEqual([a.get_title().split(":")[0] for a in top], ["reference", "drift10"])
        for a, preset in zip(top, ("reference", "drift10")):
            want = [e["paper"]["mean_ratio"] for e in res["sweep"]["summary"]
                    if e["preset"] == preset]
            self.assertEqual(list(a.get_lines()[0].get_ydata()), want)
            self.assertEqual(list(a.get_lines()[0].get_xdata()), [-5.0, 5.0])
        plot = subprocess.run([sys.executable, os.path.join(SOURCE, "apps",
                                                            "rfseek-plot-montecarlo"), out,
                               "--table"], capture_output=True, text=True)
        self.assertEqual(plot.returncode, 0, plot.stderr)
        self.assertIn("| drift10: snr_db", plot.stdout)

    def test_wind_sweep_uses_the_straight_line_ratio(self):
        # In calm air the straight-line ratio is the plain ratio; in wind the sweep's
        # figure and table use it (the air distance of the straight ground line is not
        # the shortest path's).
        from gnuradio.rfseek import plots
        p, out = run_mc(self.tmp, "wsw", "--runs", "2", "--strategy", "adaptive",
                        "--sweep", "wind_speed_mps=0,5", *SHORT)
        self.assertEqual(p.returncode, 0, p.stderr)
        res = json.load(open(out))
        calm = [r for r in res["rows"] if r["sweep_value"] == "0"]
        windy = [r for r in res["rows"] if r["sweep_value"] == "5"]
        for r in calm:
            self.assertEqual(r["straight_ratio"], r["ratio"])
        for r in windy:
            self.assertNotEqual(r["straight_ratio"], r["ratio"])
        self.assertEqual(plots.sweep_metric(res)[0], "straight_ratio")
        self.assertEqual(plots.sweep_metric(res, "ratio")[0], "ratio")
        with self.assertRaises(ValueError):
            plots.sweep_metric(res, "speed")
        # What is not a study's JSON is named, not a KeyError or TypeError: one run's
        # result, a path, a study made without --sweep given to a sweep figure.
        from gnuradio import rfseek
        sc = rfseek.scenario(seed=1, initial_distance_m=300.0)
        one = rfseek.simulation(sc, rfseek.simulation.seeker_for(sc, "paper")).run()
        for bad in (one, out, None):
            with self.assertRaisesRegex(ValueError, "rfseek-montecarlo's JSON"):
                plots.sweep_plot(bad)
            with self.assertRaisesRegex(ValueError, "rfseek-montecarlo's JSON"):
                plots.distance_histograms(bad)
        flat = dict(res)
        del flat["sweep"]
        for fig in (plots.sweep_plot, plots.sweep_table):
            with self.assertRaisesRegex(ValueError, "without --sweep"):
                fig(flat)
        plot = subprocess.run([sys.executable, os.path.join(SOURCE, "apps",
                                                            "rfseek-plot-montecarlo"), out,
                               "--table"], capture_output=True, text=True)
        self.assertEqual(plot.returncode, 0, plot.stderr)
        rows = [l for l in plot.stdout.splitlines() if l.startswith("| `adaptive`")]
        self.assertEqual(len(rows), 1)
        mean5 = res["sweep"]["summary"][1]["adaptive"]["mean_straight_ratio"]
        self.assertIn("%.3f" % mean5, rows[0].split("|")[3])

    def test_presets(self):
        from gnuradio import rfseek
        p = subprocess.run([MC, "--preset", "list"], capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stderr)
        for name in rfseek.scenario.presets():
            self.assertIn(name, p.stdout)
        # Each preset's overrides reach the runs; --set applies on top of them.
        p, out = run_mc(self.tmp, "pr", "--runs", "2", "--strategy", "adaptive,paper",
                        "--preset", "drift10,speed20", "--set", "snr_db=3", *SHORT)
        self.assertEqual(p.returncode, 0, p.stderr)
        res = json.load(open(out))
        self.assertEqual(res["presets"]["names"], ["drift10", "speed20"])
        sc = res["presets"]["scenarios"]
        self.assertEqual(sc["drift10"]["cfo_drift_hz_per_s"], 10)
        self.assertEqual(sc["speed20"]["speed_mps"], 20)
        for name in ("drift10", "speed20"):
            self.assertEqual(sc[name]["snr_db"], 3)
            self.assertEqual(sc[name]["initial_distance_m"], 2000)
        self.assertEqual([q["preset"] for q in res["points"]], ["drift10", "speed20"])
        self.assertEqual(len(res["rows"]), 2 * 2 * 2)
        for q in res["points"]:
            for strategy in ("adaptive", "paper"):
                rows = [r for r in res["rows"]
                        if r["preset"] == q["preset"] and r["strategy"] == strategy]
                self.assertEqual(sorted(r["seed"] for r in rows), [1, 2])
                self.assertAlmostEqual(q[strategy]["mean_ratio"],
                                       statistics.mean(r["ratio"] for r in rows), places=6)
        # At 20 m/s the flight takes half the time of 10 m/s for the same distance.
        r20 = [r for r in res["rows"] if r["preset"] == "speed20"]
        for r in r20:
            self.assertAlmostEqual(r["time_s"], r["distance_m"] / 20.0, places=6)
        rows_csv = list(csv.DictReader(open(out[:-5] + ".csv")))
        self.assertEqual(sorted(set(r["preset"] for r in rows_csv)), ["drift10", "speed20"])
        plot = subprocess.run([sys.executable, os.path.join(SOURCE, "apps",
                                                            "rfseek-plot-montecarlo"),
                               out, "--table"], capture_output=True, text=True)
        self.assertEqual(plot.returncode, 0, plot.stderr)
        self.assertTrue(os.path.getsize(os.path.join(self.tmp, "pr_presets.png")) > 1000)
        self.assertIn("| drift10 |", plot.stdout)
        # An unknown preset is refused by name.
        p, _ = run_mc(self.tmp, "bad", "--preset", "reference,stormy")
        self.assertEqual(p.returncode, 2)
        self.assertIn("stormy", p.stderr)

    @unittest.skipIf(SANITIZED, STUDY)
    def test_fixedwing25(self):
        # A fixed wing at 25 m/s turning as ArduPlane does (an effective 24.8 deg bank,
        # 10.4 deg/s after a 0.6 s roll): 30 runs at relaxed bounds. adaptive's acquisition ends on the arc that holds a sure
        # bearing and its probes are timed for the roll; before it planned its turns for
        # the airframe it flew 1.17 x here. paper flies its circle at the bank limit.
        p, out = run_mc(self.tmp, "fw25", "--runs", "30", "--strategy", "adaptive,paper",
                        "--preset", "fixedwing25", "--threads", "2", "--quiet")
        self.assertEqual(p.returncode, 0, p.stderr)
        res = json.load(open(out))
        sc = res["presets"]["scenarios"]["fixedwing25"]
        self.assertEqual(sc["speed_mps"], 25)
        self.assertAlmostEqual(math.degrees(sc["bank_limit_rad"]), 24.8)
        self.assertAlmostEqual(math.degrees(sc["roll_rate_rad_per_s"]), 40.0)
        for strategy, bound in (("adaptive", 1.10), ("paper", 1.25)):
            rows = [r for r in res["rows"] if r["strategy"] == strategy]
            self.assertEqual(len(rows), 30)
            self.assertGreaterEqual(sum(r["success"] for r in rows), 29, strategy)
            self.assertLessEqual(statistics.mean(r["ratio"] for r in rows), bound, strategy)

    @unittest.skipIf(SANITIZED, STUDY)
    def test_rss_baseline(self):
        # The RSS method (received power only) from 5 km, 30 runs at relaxed bounds on
        # seeds no table uses: a circle finds the line-of-sight axis and the way along
        # it, runs go on while the long-term average power rises. Wadhwa et al. report
        # about 3 x; with a 10 x flight cap at least 80 % arrive at a mean <= 4 x.
        p, out = run_mc(self.tmp, "rss", "--runs", "30", "--seed", "424242",
                        "--strategy", "rss_baseline", "--set", "flight_cap_m=48000",
                        "--threads", "2", "--quiet")
        self.assertEqual(p.returncode, 0, p.stderr)
        rows = json.load(open(out))["rows"]
        self.assertEqual(len(rows), 30)
        self.assertGreaterEqual(sum(r["success"] for r in rows), 24)
        self.assertLessEqual(statistics.mean(r["ratio"] for r in rows), 4.0)
        # A failed run counts with the cap it flew: 10 x the shortest path.
        self.assertTrue(all(r["ratio"] <= 10.001 for r in rows))

    def test_bad_options_exit_2_with_a_message(self):
        for args, word in ((["--runs", "0"], "--runs"),
                           (["--strategy", "gradient"], "gradient"),
                           (["--set", "snr=3"], "snr"),
                           (["--set", "snr_db=loud"], "snr_db"),
                           (["--set", "window_len=2"], "window_len"),
                           (["--set", "delta_deg=95"], "delta_rad"),
                           (["--set", "snr_db=nan"], "snr_db"),
                           (["--set", "snr_db=inf"], "snr_db"),
                           (["--runs", "2.5"], "--runs"),
                           (["--threads", "0"], "--threads"),
                           (["--seed", "abc"], "--seed"),
                           (["--dask-local", "0"], "--dask-local"),
                           (["--scheduler", "tcp://h:1", "--dask-local", "2"], "exclude"),
                           (["--csv", os.path.join(self.tmp, "no", "such", "dir.csv")],
                            "cannot write"),
                           (["--bogus"], "--bogus")):
            p, out = run_mc(self.tmp, "bad", *args)
            self.assertEqual(p.returncode, 2, args)
            self.assertIn(word, p.stderr)
            self.assertNotIn("Traceback", p.stderr)
            self.assertEqual(len(p.stderr.strip().splitlines()), 1, p.stderr)
            # nothing written: no partial output file
            self.assertEqual([f for f in os.listdir(self.tmp) if f.startswith("bad")], [])
        # An unknown --set key lists every key --set takes: the scenario's fields and
        # the seeker's constants alike.
        from gnuradio import rfseek
        p, _ = run_mc(self.tmp, "bad", "--set", "bogus=1")
        self.assertEqual(p.returncode, 2)
        listed = set(p.stderr.replace(":", ",").replace(".", ",").replace(" ", "")
                     .split(","))
        for key in list(rfseek.scenario.keys()) + list(rfseek.seeker_config.keys()):
            self.assertIn(key, listed)


if __name__ == "__main__":
    gr_unittest.run(qa_montecarlo)
