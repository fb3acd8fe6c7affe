#!/usr/bin/env python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""The emitter locator across gusts and altimeter errors it was not told about.

Runs rfseek-montecarlo --arrival self on `realistic` (adaptive) for every cell of
gust std x gust correlation time x altimeter error, with the locator's defaults (or the
--set values given), and prints a Markdown table: located, declared within 300 m, false
arrivals, location error median / p90 and how often the 95 % ellipse holds the emitter.
Gust 0 has no correlation time: it is run once per altimeter error.

  scripts/locator_envelope.py --mc build/apps/rfseek-montecarlo --runs 200 \\
      --seed 1 --out /tmp/envelope [--set locate_gust_mps=1 ...]
"""

import argparse
import json
import os
import statistics
import subprocess
import sys


def percentile(v, q):
    v = sorted(v)
    return v[min(len(v) - 1, int(q * len(v)))] if v else float("nan")


def cell_summary(rows):
    n = len(rows)
    if n == 0:
        raise ValueError("no usable rows (every run raised)")
    located = [r for r in rows if r.get("located")]
    err = [r["location_error_m"] for r in located]
    return {
        "runs": n,
        "success": sum(bool(r["success"]) for r in rows) / n,
        "line": statistics.mean(r["straight_ratio"] for r in rows),
        "declared_300": sum(bool(r["declared"]) and r["arrival_detect_distance_m"] <= 300.0
                            for r in rows) / n,
        "false": sum(bool(r["false_arrival"]) for r in rows) / n,
        "located": len(located) / n,
        "err_median": statistics.median(err) if err else float("nan"),
        "err_p90": percentile(err, 0.9),
        "in_ellipse": (sum(bool(r["location_in_ellipse"]) for r in located) / len(located)
                       if located else float("nan")),
    }


def main(argv):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mc", default="rfseek-montecarlo", help="rfseek-montecarlo to run")
    p.add_argument("--runs", type=int, default=200)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--preset", default="realistic")
    p.add_argument("--strategy", default="adaptive")
    p.add_argument("--gusts", default="0,1,2.5", help="wind_gust_mps values")
    p.add_argument("--taus", default="2,5,30", help="wind_gust_tau_s values")
    p.add_argument("--altimeter", default="0,-30,30", help="altimeter_error_m values")
    p.add_argument("--set", action="append", default=[], help="KEY=VALUE, as the Monte "
                   "Carlo's (e.g. locate_gust_mps=1)")
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--out", default="locator_envelope", help="folder for the JSON files")
    p.add_argument("--reuse", action="store_true",
                   help="tabulate the JSON files already in --out instead of running "
                        "the cells again")
    a = p.parse_args(argv)
    if a.runs < 1:
        p.error("--runs must be >= 1")
    os.makedirs(a.out, exist_ok=True)
    cells = []
    for alt in a.altimeter.split(","):
        for g in a.gusts.split(","):
            for tau in (a.taus.split(",") if float(g) > 0 else ["-"]):
                cells.append((g, tau, alt))
    print("| gusts (std, tau) | altimeter error | success | line ratio | located "
          "| declared within 300 m | false | error median / p90 | in 95 % ellipse |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for g, tau, alt in cells:
        name = "g%s_t%s_a%s" % (g, tau, alt)
        out = os.path.join(a.out, name + ".json")
        cmd = [a.mc, "--runs", str(a.runs), "--seed", str(a.seed), "--preset", a.preset,
               "--strategy", a.strategy, "--arrival", "self", "--quiet", "--out", out,
               "--set", "wind_gust_mps=" + g, "--set", "altimeter_error_m=" + alt]
        if tau != "-":
            cmd += ["--set", "wind_gust_tau_s=" + tau]
        if a.threads:
            cmd += ["--threads", str(a.threads)]
        for s in a.set:
            cmd += ["--set", s]
        if not (a.reuse and os.path.exists(out)):
            r = subprocess.run(cmd, capture_output=True, text=True)
            if r.returncode != 0:
                print("locator_envelope: %s failed: %s" % (name, r.stderr.strip()),
                      file=sys.stderr)
                return 1
        with open(out) as f:
            rows = [x for x in json.load(f)["rows"] if not x.get("error")]
        try:
            s = cell_summary(rows)
        except ValueError as e:
            print("locator_envelope: %s: %s" % (name, e), file=sys.stderr)
            return 1
        gust = "none" if tau == "-" else "%s m/s, %s s" % (g, tau)
        print("| %s | %+d m | %.1f %% | %.3f | %.1f %% | %.1f %% | %.1f %% | %.1f / %.0f m "
              "| %.1f %% |" % (
            gust, int(float(alt)), 100 * s["success"], s["line"], 100 * s["located"],
            100 * s["declared_300"],
            100 * s["false"], s["err_median"], s["err_p90"], 100 * s["in_ellipse"]),
            flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
