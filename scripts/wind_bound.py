#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""What the wind costs a flight that knows the bearing from the first slot.

For each run seed the world (its start, wind, gusts and turn limits) is flown twice
with the true bearing to the emitter at every slot, compass error removed:

  pursuit   the air heading at the bearing: what any strategy that steers its air
            heading at a perfect bearing flies (a crosswind bends the ground track
            into a pursuit curve that meets the emitter from downwind);
  triangle  the air heading that cancels the mean wind across the line of sight
            (sin c = -w_perp / v, the wind triangle): the straight ground line, with
            only the gusts and the turns left to pay.

Printed per wind speed: mean / p90 of the straight-line ratio (air distance flown to d_v
over the straight ground line's, world.straight_air_m) for both. A strategy that must
measure its bearing (`adaptive`, results.md "Wind") cannot on average beat the triangle;
against the pursuit it shows what its guidance over the ground recovers.

  scripts/wind_bound.py --preset realistic --winds 0,4,7 --runs 300 --seed 1
  scripts/wind_bound.py --preset windy --runs 300
"""

import argparse
import math
import sys

import numpy as np
from gnuradio import rfseek

MODES = ("pursuit", "triangle")


def triangle_heading(w, v):
    """The air heading whose ground velocity points at the emitter in the mean wind
    (the bearing itself where the wind across the line of sight exceeds the airspeed)."""
    b = w.bearing_to_emitter_rad
    across = -w.wind_east_mps * math.sin(b) + w.wind_north_mps * math.cos(b)
    s = -across / v
    return b + math.asin(s) if abs(s) < 1.0 else b


def fly(sc, mode):
    """The world `sc` flown with the true bearing (`mode`: pursuit or triangle); returns
    the finished world (arrived() tells whether it reached d_v)."""
    w = rfseek.world(sc)
    v = sc.speed_mps
    while not w.finished:
        h = w.bearing_to_emitter_rad if mode == "pursuit" else triangle_heading(w, v)
        w.advance(rfseek.world.wrap(h - w.compass_error_rad))
    return w


def flight_ratio(sc, mode):
    """Straight-line ratio of the world `sc` flown the `mode` way (NaN: not arrived)."""
    w = fly(sc, mode)
    if not w.arrived:
        return float("nan")
    return w.reached_flown_m / w.straight_air_m


def bound(preset, sets, wind, runs, seed):
    """{mode: (mean, p90, runs not arrived)} over `runs` seeds from `seed`."""
    ratios = {m: [] for m in MODES}
    for i in range(runs):
        sc = rfseek.scenario()
        if preset:
            sc.apply_preset(preset)
        for kv in sets:
            key, _, value = kv.partition("=")
            sc.set(key, value)
        if wind is not None:
            sc.set("wind_speed_mps", repr(wind))
        sc.set("seed", str(seed + i))
        for m in MODES:
            ratios[m].append(flight_ratio(sc, m))
    out = {}
    for m in MODES:
        r = np.array(ratios[m])
        ok = r[~np.isnan(r)]
        mean = float(ok.mean()) if ok.size else float("nan")
        p90 = float(np.percentile(ok, 90)) if ok.size else float("nan")
        out[m] = (mean, p90, int(np.isnan(r).sum()))
    return out


def main(argv):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--preset", default="realistic",
                   help="scenario preset (default: realistic)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="scenario field, repeatable")
    p.add_argument("--winds", default="",
                   help="mean wind speeds to sweep, m/s (V1,V2,...; default: the preset's)")
    p.add_argument("--runs", type=int, default=300)
    p.add_argument("--seed", type=int, default=1, help="run i uses seed S + i")
    a = p.parse_args(argv)
    if a.runs < 1:
        p.error("--runs must be >= 1")
    try:
        winds = [float(v) for v in a.winds.split(",")] if a.winds else [None]
    except ValueError:
        p.error("--winds must be numbers separated by commas")
    rows = []
    for wind in winds:
        try:
            rows.append((wind, bound(a.preset, a.set, wind, a.runs, a.seed)))
        except ValueError as e:
            print("wind_bound.py: %s" % e, file=sys.stderr)
            return 2
    print("| wind_speed_mps | pursuit mean / p90 | triangle mean / p90 | not arrived |")
    print("| --- | --- | --- | --- |")
    for wind, b in rows:
        lost = "%d / %d" % (b["pursuit"][2], b["triangle"][2])
        print("| %s | %.3f / %.3f | %.3f / %.3f | %s |" %
              ("-" if wind is None else "%g" % wind, b["pursuit"][0], b["pursuit"][1],
               b["triangle"][0], b["triangle"][1], lost))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
