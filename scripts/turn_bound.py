#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""What the turns alone cost: a flight that knows the bearing from the first slot.

For each run seed, the world (its start, its heading, its turn limits) is flown with the
true bearing to the emitter commanded at every slot, compass error removed: the vehicle
turns onto the emitter at its limits and flies straight in. No strategy that must first
measure the bearing can do better on average, so this is the floor of the distance ratio
(d flown to d_v over d - d_v) that turn limits set. Prints mean / p90 per speed.

  scripts/turn_bound.py --preset fixedwing15 --speeds 10,15,20,25 --runs 1000 --seed 1
  scripts/turn_bound.py --set turn_rate_rad_per_s=0.17453292519943295 --runs 1000
"""

import argparse
import sys

import numpy as np
from gnuradio import rfseek


def flight_ratio(sc):
    """Distance ratio of the world `sc` flown on the true bearing."""
    w = rfseek.world(sc)
    while not w.finished and not w.arrived:
        w.advance(w.bearing_to_emitter_rad - w.compass_error_rad)
    if not w.arrived:
        return float("nan")
    return w.reached_flown_m / sc.shortest_path_m


def bound(preset, sets, speed, runs, seed):
    ratios = []
    for i in range(runs):
        sc = rfseek.scenario()
        if preset:
            sc.apply_preset(preset)
        for kv in sets:
            key, _, value = kv.partition("=")
            sc.set(key, value)
        if speed is not None:
            sc.set("speed_mps", str(speed))
        sc.set("seed", str(seed + i))
        ratios.append(flight_ratio(sc))
    r = np.array(ratios)
    lost = int(np.isnan(r).sum())
    if lost == len(r):  # nothing to average: said as "-" in the table, not NaN
        return None, None, lost
    return float(np.nanmean(r)), float(np.nanpercentile(r, 90)), lost


def main(argv):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--preset", default="", help="scenario preset (default: reference)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="scenario field, repeatable")
    p.add_argument("--speeds", default="", help="speeds to sweep, m/s (V1,V2,...)")
    p.add_argument("--runs", type=int, default=300)
    p.add_argument("--seed", type=int, default=1, help="run i uses seed S + i")
    a = p.parse_args(argv)
    if a.runs < 1:
        p.error("--runs must be >= 1")
    try:
        speeds = [float(v) for v in a.speeds.split(",")] if a.speeds else [None]
    except ValueError:
        p.error("--speeds must be numbers separated by commas")
    rows = []
    for v in speeds:
        try:
            rows.append((v,) + bound(a.preset, a.set, v, a.runs, a.seed))
        except ValueError as e:
            print("turn_bound.py: %s" % e, file=sys.stderr)
            return 2
    print("| speed_mps | mean | p90 | not arrived |")
    print("| --- | --- | --- | --- |")
    def cell(x):
        return "-" if x is None else "%.3f" % x
    for v, mean, p90, lost in rows:
        print("| %s | %s | %s | %d |" % ("-" if v is None else "%g" % v, cell(mean),
                                        cell(p90), lost))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
