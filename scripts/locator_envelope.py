#!/usr/bin/python3
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
import shutil
import subprocess
import sys


def main(argv):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mc", default=None,
                   help="rfseek-montecarlo to run (default: build/apps/ beside this "
                        "script's source tree if built there, else on PATH)")
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
    if a.mc is None:
        here = os.path.dirname(os.path.abspath(__file__))
        built = os.path.join(here, "..", "build", "apps", "rfseek-montecarlo")
        a.mc = built if os.access(built, os.X_OK) else shutil.which("rfseek-montecarlo")
    if not a.mc or not os.access(a.mc, os.X_OK):
        p.error("rfseek-montecarlo not found (give --mc PATH)")
    try:
        for g in a.gusts.split(","):
            float(g)
        [float(v) for v in a.taus.split(",") + a.altimeter.split(",")]
    except ValueError:
        p.error("--gusts, --taus and --altimeter must be comma-separated numbers")
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
            s = json.load(f)["summary"][a.strategy]  # rfseek-montecarlo's own summary
        if s["runs"] == s.get("errors", 0):
            print("locator_envelope: %s: every run raised" % name, file=sys.stderr)
            return 1
        gust = "none" if tau == "-" else "%s m/s, %s s" % (g, tau)
        print("| %s | %+d m | %.1f %% | %.3f | %.1f %% | %.1f %% | %.1f %% | %.1f / %.0f m "
              "| %.1f %% |" % (
            gust, int(float(alt)), 100 * s["success_rate"], s["mean_straight_ratio"],
            100 * s["located_rate"], 100 * s["declared_within_300m_rate"],
            100 * s["false_arrival_rate"], s["location_error_m_median"],
            s["location_error_m_p90"], 100 * s["location_in_ellipse_rate"]),
            flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
