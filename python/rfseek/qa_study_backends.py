#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""rfseek-montecarlo's backends and resumption (issue 11): study_point from Python equals
the program's rows; a Dask LocalCluster of 2 worker processes gives the rows of
--threads 2; a study killed after some rows and resumed gives the uninterrupted summary
without re-running its finished rows; an unreachable scheduler is one line and exit 2."""

import csv
import io
import json
import os
import signal
import subprocess
import tempfile
import time

from gnuradio import gr_unittest
from gnuradio import rfseek

BUILD = os.environ.get("RFSEEK_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
MC = os.path.join(BUILD, "apps", "rfseek-montecarlo")
# A 2 km flight keeps the test quick; the code is the same as the reference's.
SHORT = ["--set", "initial_distance_m=2000", "--quiet"]


def read_text(path):
    with open(path) as f:
        return f.read()


def load_json(path):
    return json.loads(read_text(path))


def run_mc(tmp, name, *args, timeout=300):
    out = os.path.join(tmp, name + ".json")
    p = subprocess.run([MC, "--out", out] + list(args), capture_output=True, text=True,
                       timeout=timeout)
    return p, out


def have_dask():
    try:
        import distributed  # noqa: F401
        return True
    except ImportError:
        return False


class qa_study_backends(gr_unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="rfseek_study_")

    def test_study_point_from_python_equals_the_program(self):
        p, out = run_mc(self.tmp, "one", "--runs", "3", "--seed", "7", "--strategy",
                        "adaptive", "--preset", "drift2", "--threads", "1", *SHORT)
        self.assertEqual(p.returncode, 0, p.stderr)
        rows = load_json((out))["rows"]
        pt = rfseek.study_point("drift2", [("initial_distance_m", "2000")])
        self.assertEqual(pt.scenario.initial_distance_m, 2000)
        self.assertEqual(pt.scenario.cfo_drift_hz_per_s, 2.0)  # the preset, then --set
        for r in rows:
            s = pt.run("adaptive", r["seed"])
            self.assertEqual(s.slots, r["slots"])
            self.assertAlmostEqual(s.distance_m, r["distance_m"], places=6)
        with self.assertRaises(ValueError):
            rfseek.study_point("", [("no_such_key", "1")])
        with self.assertRaises(ValueError):
            rfseek.study_point("no_such_preset")
        with self.assertRaises(ValueError):
            rfseek.study_point("", [("snr_db", "loud")])

    def test_dask_local_cluster_rows_equal_threads(self):
        if not have_dask():
            self.skipTest("python3-distributed is not installed (scripts/setup.sh installs it)")
        args = ["--runs", "20", "--seed", "3", "--strategy", "paper,adaptive"] + SHORT
        pt, ot = run_mc(self.tmp, "threads", "--threads", "2", *args)
        pd, od = run_mc(self.tmp, "dask", "--dask-local", "2", "--dask-chunk", "3", *args)
        self.assertEqual(pt.returncode, 0, pt.stderr)
        self.assertEqual(pd.returncode, 0, pd.stderr)
        rt, rd = load_json((ot)), load_json((od))
        self.assertEqual(len(rd["rows"]), 40)
        self.assertEqual(rt["rows"], rd["rows"])
        self.assertEqual(rt["summary"], rd["summary"])
        self.assertEqual(rd["timing"]["backend"], "dask-local")
        self.assertEqual(rd["timing"]["threads"], 2)
        self.assertEqual(read_text(ot[:-5] + ".csv"), read_text(od[:-5] + ".csv"))

    def test_killed_study_resumes_to_the_same_summary(self):
        args = ["--runs", "12", "--seed", "1", "--strategy", "paper,adaptive",
                "--preset", "reference,drift10", "--threads", "2"] + SHORT
        out = os.path.join(self.tmp, "cut.json")
        csv_path = out[:-5] + ".csv"
        proc = subprocess.Popen([MC, "--out", out] + args, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        deadline = time.time() + 120
        rows_before = 0
        while time.time() < deadline and proc.poll() is None:
            if os.path.exists(csv_path):
                rows_before = read_text(csv_path).count("\n") - 1
                if rows_before >= 10:
                    break
            time.sleep(0.02)
        self.assertIsNone(proc.poll(), "the study ended before it could be interrupted")
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        self.assertFalse(os.path.exists(out))  # killed: no JSON yet
        kept = list(csv.DictReader(io.StringIO(read_text(csv_path))))
        kept = [r for r in kept if r["error"] is not None]  # complete lines only
        self.assertGreaterEqual(len(kept), 10)
        self.assertLess(len(kept), 48)
        with open(csv_path, "a") as f:  # and a line cut in the middle, as a kill leaves
            f.write("5,paper,refer")

        p, _ = run_mc(self.tmp, "cut", "--resume", *args)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("resuming: %d of 48 rows" % len(kept), p.stderr)
        resumed = load_json((out))
        self.assertEqual(resumed["timing"]["runs_resumed"], len(kept))
        # Only the missing runs ran: the slots flown now are those of the missing rows.
        done = {(r["strategy"], r["preset"], int(r["seed"])) for r in kept}
        missing_slots = sum(r["slots"] for r in resumed["rows"]
                            if (r["strategy"], r["preset"], r["seed"]) not in done)
        self.assertEqual(resumed["timing"]["slots"], missing_slots)

        p, whole = run_mc(self.tmp, "whole", *args)
        self.assertEqual(p.returncode, 0, p.stderr)
        whole = load_json((whole))
        self.assertEqual(resumed["rows"], whole["rows"])
        self.assertEqual(resumed["points"], whole["points"])
        self.assertEqual(resumed["summary"], whole["summary"])
        self.assertEqual(read_text(csv_path),
                         read_text(os.path.join(self.tmp, "whole.csv")))

        # A finished study resumed runs nothing; other settings are refused.
        p, _ = run_mc(self.tmp, "cut", "--resume", *args)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(load_json((out))["timing"]["slots"], 0)
        p, _ = run_mc(self.tmp, "cut", "--resume", *args, "--set", "snr_db=-5")
        self.assertEqual(p.returncode, 2)
        self.assertIn("other settings", p.stderr)
        # A narrower study would rewrite the CSV without the rows it leaves out: refused,
        # the CSV untouched (fewer runs, or one strategy of two).
        before = read_text(csv_path)
        fewer = ["6" if a == "12" else a for a in args]
        one = ["paper" if a == "paper,adaptive" else a for a in args]
        for narrower, outside in ((fewer, 24), (one, 24)):
            p, _ = run_mc(self.tmp, "cut", "--resume", *narrower)
            self.assertEqual(p.returncode, 2, p.stderr)
            self.assertIn("holds %d finished row(s)" % outside, p.stderr)
            self.assertIn("would delete", p.stderr)
            self.assertEqual(read_text(csv_path), before)

    def test_unreachable_scheduler_is_one_line_and_exit_2(self):
        if not have_dask():
            self.skipTest("python3-distributed is not installed (scripts/setup.sh installs it)")
        p, out = run_mc(self.tmp, "nowhere", "--runs", "2", "--scheduler",
                        "tcp://127.0.0.1:9", "--dask-timeout", "2", *SHORT, timeout=120)
        self.assertEqual(p.returncode, 2)
        lines = [line for line in p.stderr.splitlines() if line.strip()]
        self.assertEqual(len(lines), 1, p.stderr)
        self.assertIn("cannot reach the Dask scheduler at tcp://127.0.0.1:9", lines[0])
        self.assertFalse(os.path.exists(out))
        self.assertFalse(os.path.exists(out[:-5] + ".csv"))


if __name__ == "__main__":
    gr_unittest.run(qa_study_backends)
