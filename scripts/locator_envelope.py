#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""How honest the emitter locator's ellipse is across an envelope it was not told about.

The design (DESIGN below, a fractional design that covers every factor's extremes):
gusts 0 / 1 / 2.5 m/s x correlation time 2 / 10 / 30 / 60 s, altimeter error 0 / -30 /
+30 m, compass bias 0 / +-5 deg x noise 0 / 3 / 6 deg, mean wind 0-7 m/s, heights
50-150 m, and the `windy` preset. Every other cell of a row is `realistic`'s, and the
locator keeps its defaults (or the --set values given).

Study (the default): runs rfseek-montecarlo --arrival self (adaptive) per cell and prints
a Markdown table: located (sure / unsure), false arrivals, located within 300 m, how
often the 95 % and 50 % ellipses hold the emitter (a run without a fix reports "no
fix" itself and is not counted), the median semi-major axis and the location error.

  scripts/locator_envelope.py --runs 100 --seed 5000001 --out /tmp/envelope

Calibration (--calibrate): runs the cells through the Python bindings on other seeds
and prints, per bin of the fit's gust level (emitter_location.gust_rms_mps), the radius
factors that would make the 95 % and 50 % ellipses hold the emitter at their rate (the
constants of lib/emitter_locator.cc, ellipse_scale()).

  PYTHONPATH=build/python LD_LIBRARY_PATH=build/lib \\
      scripts/locator_envelope.py --calibrate --runs 40 --seed 4000001
"""

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys

# name: the scenario settings on top of `realistic` (angles in degrees here), or a
# preset's name.
DESIGN = [
    ("calm", {"wind_gust_mps": 0}),
    ("gust 1 m/s, 2 s", {"wind_gust_mps": 1, "wind_gust_tau_s": 2}),
    ("gust 1 m/s, 10 s", {"wind_gust_mps": 1, "wind_gust_tau_s": 10}),
    ("gust 1 m/s, 30 s", {"wind_gust_mps": 1, "wind_gust_tau_s": 30}),
    ("gust 1 m/s, 60 s", {"wind_gust_mps": 1, "wind_gust_tau_s": 60}),
    ("gust 2.5 m/s, 2 s", {"wind_gust_mps": 2.5, "wind_gust_tau_s": 2}),
    ("gust 2.5 m/s, 10 s", {"wind_gust_mps": 2.5, "wind_gust_tau_s": 10}),
    ("gust 2.5 m/s, 30 s", {"wind_gust_mps": 2.5, "wind_gust_tau_s": 30}),
    ("gust 2.5 m/s, 60 s", {"wind_gust_mps": 2.5, "wind_gust_tau_s": 60}),
    ("altimeter -30 m", {"wind_gust_mps": 0, "altimeter_error_m": -30}),
    ("altimeter +30 m", {"wind_gust_mps": 0, "altimeter_error_m": 30}),
    ("gust 1/10, altimeter -30", {"wind_gust_mps": 1, "wind_gust_tau_s": 10,
                                  "altimeter_error_m": -30}),
    ("gust 1/10, altimeter +30", {"wind_gust_mps": 1, "wind_gust_tau_s": 10,
                                  "altimeter_error_m": 30}),
    ("gust 2.5/30, altimeter -30", {"wind_gust_mps": 2.5, "wind_gust_tau_s": 30,
                                    "altimeter_error_m": -30}),
    ("gust 2.5/10, altimeter +30", {"wind_gust_mps": 2.5, "wind_gust_tau_s": 10,
                                    "altimeter_error_m": 30}),
    ("compass -5 deg, noise 0", {"wind_gust_mps": 1, "wind_gust_tau_s": 10,
                                 "compass_bias": -5, "compass_noise": 0}),
    ("compass +5 deg, noise 6", {"wind_gust_mps": 1, "wind_gust_tau_s": 10,
                                 "compass_bias": 5, "compass_noise": 6}),
    ("compass 0 deg, noise 3", {"wind_gust_mps": 1, "wind_gust_tau_s": 10,
                                "compass_bias": 0, "compass_noise": 3}),
    ("compass -5 deg, noise 6, calm", {"wind_gust_mps": 0, "compass_bias": -5,
                                       "compass_noise": 6}),
    ("wind 0, 50 m up", {"wind_gust_mps": 1, "wind_gust_tau_s": 10, "wind_speed_mps": 0,
                         "altitude_m": 50}),
    ("wind 7, 150 m up", {"wind_gust_mps": 1, "wind_gust_tau_s": 10, "wind_speed_mps": 7,
                          "altitude_m": 150}),
    ("wind 7, 50 m up, gust 2.5/30", {"wind_gust_mps": 2.5, "wind_gust_tau_s": 30,
                                      "wind_speed_mps": 7, "altitude_m": 50}),
    ("wind 0, 150 m up, calm", {"wind_gust_mps": 0, "wind_speed_mps": 0,
                                "altitude_m": 150}),
    ("all high: 2.5/60, -30 m, +5/6 deg, 7 m/s, 50 m", {
        "wind_gust_mps": 2.5, "wind_gust_tau_s": 60, "altimeter_error_m": -30,
        "compass_bias": 5, "compass_noise": 6, "wind_speed_mps": 7, "altitude_m": 50}),
    ("mixed: 2.5/2, +30 m, -5/0 deg, 0 m/s, 150 m", {
        "wind_gust_mps": 2.5, "wind_gust_tau_s": 2, "altimeter_error_m": 30,
        "compass_bias": -5, "compass_noise": 0, "wind_speed_mps": 0, "altitude_m": 150}),
    ("mixed: 1/60, -30 m, -5/6 deg, 7 m/s, 150 m", {
        "wind_gust_mps": 1, "wind_gust_tau_s": 60, "altimeter_error_m": -30,
        "compass_bias": -5, "compass_noise": 6, "wind_speed_mps": 7, "altitude_m": 150}),
    ("windy preset", "windy"),
]

# Calm cells (no gusts or 1 m/s, altimeter right, compass as `realistic`).
CALM = {"calm", "gust 1 m/s, 2 s", "gust 1 m/s, 10 s", "gust 1 m/s, 30 s",
        "gust 1 m/s, 60 s"}


def settings(cell):
    """The cell's KEY=VALUE scenario settings (on top of its preset)."""
    if isinstance(cell, str):
        return []
    out = []
    for k, v in cell.items():
        if k in ("compass_bias", "compass_noise"):
            out.append("%s_rad=%r" % (k, math.radians(v)))
        else:
            out.append("%s=%r" % (k, v))
    return out


def preset(cell):
    return cell if isinstance(cell, str) else "realistic"


def study(a):
    if a.mc is None:
        here = os.path.dirname(os.path.abspath(__file__))
        built = os.path.join(here, "..", "build", "apps", "rfseek-montecarlo")
        a.mc = built if os.access(built, os.X_OK) else shutil.which("rfseek-montecarlo")
    if not a.mc or not os.access(a.mc, os.X_OK):
        print("locator_envelope: rfseek-montecarlo not found (give --mc PATH)",
              file=sys.stderr)
        return 2
    os.makedirs(a.out, exist_ok=True)
    print("| cell | located: sure / unsure | false | within 300 m | in 95 % ellipse "
          "| in 50 % ellipse | semi-major median | error median / p90 |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    rows = []
    for i, (name, cell) in enumerate(DESIGN):
        if not re.search(a.cells, name):
            continue
        out = os.path.join(a.out, "cell%02d.json" % i)
        cmd = [a.mc, "--runs", str(a.runs), "--seed", str(a.seed), "--preset",
               preset(cell), "--strategy", "adaptive", "--arrival", "self", "--quiet",
               "--out", out]
        for s in settings(cell) + a.set:
            cmd += ["--set", s]
        if a.threads:
            cmd += ["--threads", str(a.threads)]
        if not (a.reuse and os.path.exists(out)):
            r = subprocess.run(cmd, capture_output=True, text=True)
            if r.returncode != 0:
                print("locator_envelope: %s failed: %s" % (name, r.stderr.strip()),
                      file=sys.stderr)
                return 1
        with open(out) as f:
            s = json.load(f)["summary"]["adaptive"]  # rfseek-montecarlo's own summary
        if s["runs"] == s.get("errors", 0):
            print("locator_envelope: %s: every run raised" % name, file=sys.stderr)
            return 1
        rows.append((name, s))
        print("| %s | %.0f %% / %.0f %% | %.1f %% | %.0f %% | %.0f %% | %.0f %% | %.0f m "
              "| %.1f / %.0f m |" % (
                  name, 100 * s["located_sure_rate"], 100 * s["located_unsure_rate"],
                  100 * s["false_arrival_rate"], 100 * s["located_within_300m_rate"],
                  100 * s["location_in_ellipse_rate"],
                  100 * s["location_in_ellipse50_rate"], s["location_major_m_median"],
                  s["location_error_m_median"], s["location_error_m_p90"]), flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump([{"cell": n, "summary": s} for n, s in rows], f, indent=1)
    if a.figure:
        figure(rows, a.figure)
    return 0


def figure(rows, path):
    """Coverage of the 95 % and 50 % ellipses per cell, with the target bands."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = [n for n, _ in rows]
    y = list(range(len(rows)))[::-1]
    fig, ax = plt.subplots(1, 2, figsize=(11, 0.28 * len(rows) + 1.6), sharey=True)
    for k, (key, band, label) in enumerate((
            ("location_in_ellipse_rate", (88, 98), "95 % ellipse"),
            ("location_in_ellipse50_rate", (40, 60), "50 % ellipse"))):
        ax[k].axvspan(*band, color="tab:green", alpha=0.15, label="target")
        ax[k].barh(y, [100 * s[key] for _, s in rows], color="tab:blue", height=0.6)
        ax[k].set_xlim(0, 100)
        ax[k].set_xlabel("runs whose emitter lies in the %s (%%)" % label)
        ax[k].grid(axis="x", alpha=0.3)
    ax[0].set_yticks(y)
    ax[0].set_yticklabels(names, fontsize=7)
    ax[0].legend(loc="lower left", fontsize=7)
    fig.suptitle("How honest the ellipse is: `adaptive`, --arrival self, %d runs per "
                 "cell" % rows[0][1]["runs"], fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


# Calibration: one run through the bindings, its fix's normalised error.
def _calibration_run(job):
    from gnuradio import rfseek
    name, cell, seed, sets = job
    sc = rfseek.scenario.preset(preset(cell))
    for kv in settings(cell) + sets:
        k, v = kv.split("=", 1)
        sc.set(k, v)
    sc.seed = seed
    sc.self_arrival = True
    cfg = rfseek.simulation.seeker_for(sc, "adaptive")
    r = rfseek.simulation(sc, cfg).run()
    loc = r.location
    if not r.summary.located:
        return None
    ex = loc.east_m + r.location_vehicle_x_m  # the emitter is at the origin
    ey = loc.north_m + r.location_vehicle_y_m
    ca, sa = math.cos(loc.major_angle_rad), math.sin(loc.major_angle_rad)
    u = (ex * ca + ey * sa) / loc.major_m
    v = (-ex * sa + ey * ca) / loc.minor_m
    # In units of the 95 % contour without the calibrated factors (divided out; the
    # user's scale95 is 1 here): u^2 + v^2 <= 1 inside.
    wind = math.hypot(loc.wind_east_mps, loc.wind_north_mps) / sc.speed_mps
    k95 = rfseek.locator_nuisance.factors(loc.gust_rms_mps, wind, loc.altitude_m)[0]
    # A wandering loiter's fix: its error in the metric of an ellipse of its
    # direction and aspect whose semi-axes' geometric mean is 1 m, over the orbit's
    # scale (locator_nuisance::WANDER_RADII_M).
    wdist = None
    if loc.wandered:
        radius = cfg.loiter_radius_m
        aspect = math.sqrt(loc.minor_m / loc.major_m)
        wdist = math.hypot((ex * ca + ey * sa) * aspect, (-ex * sa + ey * ca) / aspect) \
            / max(1.0, radius / rfseek.seeker_config().loiter_radius_m)
    return {"cell": name, "nees95": (u * u + v * v) * k95 * k95,
            "wandered": loc.wandered, "wdist": wdist, "in95": u * u + v * v <= 1.0,
            "gust_rms": loc.gust_rms_mps, "wind": wind,
            "major": loc.major_m, "minor": loc.minor_m, "T": loc.consistency,
            "spread": loc.model_spread_m, "rms": loc.rms_hz, "alt": loc.altitude_m,
            "range": math.hypot(loc.east_m, loc.north_m), "seed": seed,
            "error": math.hypot(ex, ey), "unsure": loc.unsure,
            "wide": loc.wide_gust_weight, "offh": loc.off_height_weight}


def calibrate(a):
    import multiprocessing
    if a.from_json:
        with open(a.from_json) as f:
            res = json.load(f)
    else:
        jobs = [(n, c, a.seed + 1000 * i + k, a.set)
                for i, (n, c) in enumerate(DESIGN) if re.search(a.cells, n)
                for k in range(a.runs)]
        with multiprocessing.Pool(a.threads or os.cpu_count()) as p:
            res = [r for r in p.map(_calibration_run, jobs, chunksize=4) if r]
    if a.json and not a.from_json:
        with open(a.json, "w") as f:
            json.dump(res, f)
    gust_edges = [float(e) for e in a.bins.split(",")]
    wind_edges = [float(e) for e in a.wind_bins.split(",")]
    chi95, chi50 = 5.991464547107979, 1.3862943611198906

    def factors(q):
        # The radius factors that put quantiles 0.94 and 0.5 of the errors (in units
        # of the unscaled 95 % contour) on the 95 % and 50 % contours.
        q = sorted(q)
        at = lambda p: q[min(len(q) - 1, int(p * len(q)))]
        return math.sqrt(at(0.94)), math.sqrt(at(0.5) * chi95 / chi50)

    print("| fits | wind / airspeed | gust level (m/s) | fixes | in 95 % | in 50 % "
          "| factor 95 % | factor 50 % |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    # Rows: one per wind bin for the fits that are not low; then one for the low fits
    # (under --low-height, wind from --low-wind, whatever the gust level).
    # The fixes of loiters whose estimate wandered take sizes of their own
    # (locator_nuisance::WANDER_RADII_M); the bins leave them out.
    wand = [r for r in res if r.get("wandered")]
    res = [r for r in res if not r.get("wandered")]

    def low(r):
        return r["alt"] < a.low_height and r["wind"] >= a.low_wind

    rows = [("not low", wlo, whi,
             lambda r, wlo=wlo, whi=whi: not low(r) and wlo <= r["wind"] < whi)
            for wlo, whi in zip([0.0] + wind_edges, wind_edges + [1e9])]
    rows.append(("under %g m" % a.low_height, a.low_wind, 1e9, low))
    table95, table50 = [], []
    for label, wlo, whi, member in rows:
        row95, row50 = [], []
        for lo, hi in zip([0.0] + gust_edges, gust_edges + [1e9]):
            q = [r["nees95"] for r in res if lo <= r["gust_rms"] < hi and member(r)]
            f95, f50 = factors(q) if len(q) >= 10 else (float("nan"),) * 2
            row95.append(f95)
            row50.append(f50)
            print("| %s | %.2f-%s | %.2f-%s | %d | %s | %s | %.2f | %.2f |" % (
                label, wlo, "%.2f" % whi if whi < 1e9 else "", lo,
                "%.2f" % hi if hi < 1e9 else "", len(q),
                "%.1f %%" % (100.0 * sum(x <= 1.0 for x in q) / len(q)) if q else "-",
                "%.1f %%" % (100.0 * sum(x * chi95 <= chi50 for x in q) / len(q))
                if q else "-", f95, f50))
        table95.append(row95)
        table50.append(row50)
    # Never smaller in stronger gusts or wind, or lower down (a sparse bin borrows its
    # neighbour's; the low row is at least every wind row).
    for t in (table95, table50):
        for j, row in enumerate(t):
            for i in range(len(row)):
                prev = [row[i - 1]] if i else []
                below = [t[k][i] for k in range(j)] if j == len(t) - 1 else \
                    ([t[j - 1][i]] if j else [])
                cand = [v for v in [row[i]] + prev + below if v == v]
                row[i] = max(cand) if cand else 1.0
    print("\nfor ellipse_scale(): f95 = %s, f50 = %s (rows: %s)" % (
        [[round(v, 2) for v in r] for r in table95],
        [[round(v, 2) for v in r] for r in table50],
        ", ".join(label + (" wind %.2f-" % wlo) for label, wlo, _, _ in rows)))
    if wand:
        q = sorted(r["wdist"] for r in wand)
        at = lambda p: q[min(len(q) - 1, int(p * len(q)))]
        print("\nwandering loiters' fixes: %d, in their 95 %% ellipse %.1f %%; "
              "WANDER_RADII_M (C++) = [%.1f, %.1f] (quantiles 0.94 and 0.5)" % (
                  len(wand), 100.0 * sum(r["in95"] for r in wand) / len(wand),
                  at(0.94), at(0.5)))
    print("(lib/emitter_locator.cc keeps the strong-wind row's earlier factors, which "
          "rest on more fixes; docs/notes/seeker.md, \"Low in the wind\")")
    return 0


def main(argv):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mc", default=None,
                   help="rfseek-montecarlo to run (default: build/apps/ beside this "
                        "script's source tree if built there, else on PATH)")
    p.add_argument("--runs", type=int, default=100, help="runs per cell")
    p.add_argument("--seed", type=int, default=5000001, help="first seed")
    p.add_argument("--set", action="append", default=[], help="KEY=VALUE, as the Monte "
                   "Carlo's (e.g. locate_nuisance=false)")
    p.add_argument("--cells", default="",
                   help="only the cells whose name matches this regular expression "
                        "(e.g. 'gust 2.5|windy'; seeds as with all cells)")
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--out", default="locator_envelope", help="folder for the JSON files")
    p.add_argument("--json", default=None, help="also write the results to this file")
    p.add_argument("--figure", default=None, help="study: draw the coverage per cell "
                   "to this PNG")
    p.add_argument("--reuse", action="store_true",
                   help="tabulate the JSON files already in --out instead of running "
                        "the cells again")
    p.add_argument("--calibrate", action="store_true",
                   help="the calibration through the Python bindings (see above)")
    p.add_argument("--bins", default="0.55,0.9,1.2",
                   help="--calibrate: gust level bin edges (m/s)")
    p.add_argument("--wind-bins", default="0.52",
                   help="--calibrate: bin edges of the fitted wind over the airspeed")
    p.add_argument("--low-height", type=float, default=70.0,
                   help="--calibrate: fits under this height (m) get a row of their "
                   "own (LOW_HEIGHT_M in C++, 70)")
    p.add_argument("--low-wind", type=float, default=0.2,
                   help="--calibrate: ... and a wind of at least this fraction of the "
                   "airspeed (LOW_WIND_FRACTION in C++, 0.2)")
    p.add_argument("--from-json", default=None,
                   help="--calibrate: tabulate the runs of an earlier --json file")
    a = p.parse_args(argv)
    try:
        re.compile(a.cells)
    except re.error as e:
        p.error("--cells: not a regular expression (%s)" % e)
    if not any(re.search(a.cells, n) for n, _ in DESIGN):
        p.error("--cells %r matches no cell" % a.cells)
    if a.runs < 1:
        p.error("--runs must be >= 1")
    for s in a.set:
        if "=" not in s:
            p.error("--set takes KEY=VALUE, got %r" % s)
    return calibrate(a) if a.calibrate else study(a)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
