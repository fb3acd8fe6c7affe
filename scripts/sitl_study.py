#!/usr/bin/python3
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Seeks flown by the SITL firmware, seed after seed, beside the in-process simulation
of the same scenario (the module's own world and turn model): one table row per
vehicle and strategy (docs/results.md "Flown by the real firmware").

Usage (from a build tree: PYTHONPATH=build/python LD_LIBRARY_PATH=build/lib, or with
the module installed):

    /usr/bin/python3 scripts/sitl_study.py --vehicle arducopter --distance 1000 \\
        --seeds 1-5 [--strategy adaptive] [--speedup 10] [--wind-from DEG,M_S] [--sitl DIR]
        [--arrival self] [--declination DEG] [--wind-speed M_S] [--pitch DEG] [--forecast]
        [--out DIR]

With --wind-speed the SITL wind blows at that speed from a direction drawn from each
seed (or --wind-from's), and the simulated column flies the same mean wind; both
ratios are then the track over the ground. With --forecast the seeker (SITL and
simulated alike) is handed that wind as its forecast, as rfseek-live --wind-from does.

Prints one line per seed (arrived, ratio, flight time, wall time, lowest and highest
height; with --arrival self where it declared and the fix's error against the true
emitter) and the summary: arrivals, mean ratio, and the paired difference SITL minus
simulation with its standard error. The ratio is the true distance flown over the
straight line to the 200 m arrival radius.
"""

import argparse
import json
import math
import os
import random
import statistics
import sys


def seeds(text):
    a, _, b = text.partition("-")
    lo, hi = int(a), int(b or a)
    if not 0 < lo <= hi:
        raise argparse.ArgumentTypeError("--seeds %r: must be N or N-M, 0 < N <= M" % text)
    return list(range(lo, hi + 1))


def wind(text):
    frm, speed = (float(v) for v in text.split(","))
    return speed, frm


def main(argv):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--vehicle", required=True, choices=["arducopter", "arduplane", "px4_quad"])
    p.add_argument("--distance", type=float, default=1000.0)
    p.add_argument("--seeds", type=seeds, default=seeds("1-5"))
    p.add_argument("--strategy", default="adaptive")
    p.add_argument("--speedup", type=float, default=10.0)
    p.add_argument("--wind-from", type=wind, default=None)
    p.add_argument("--pitch", type=float, default=None,
                   help="ArduCopter's forward pitch (deg; 5, 15, 25 or 30; default 15)")
    p.add_argument("--wind-speed", type=float, default=None,
                   help="wind of this speed (m/s) from a direction drawn from the seed")
    p.add_argument("--forecast", action="store_true",
                   help="hand the seeker the wind as its forecast (exact)")
    p.add_argument("--out", default=None, metavar="DIR",
                   help="write each seed's summary (seed_N.json) and true track "
                        "(seed_N.png) into DIR")
    p.add_argument("--sitl", default=None)
    p.add_argument("--arrival", default="oracle", choices=("oracle", "self"))
    p.add_argument("--declination", type=float, default=None,
                   help="told to the link (default: the home's)")
    a = p.parse_args(argv)
    if a.forecast and a.wind_from is None and a.wind_speed is None:
        p.error("--forecast: give the wind (--wind-speed or --wind-from)")
    from gnuradio import rfseek
    from gnuradio.rfseek import sitl_rehearsal
    rows = []
    for seed in a.seeds:
        wind_ = a.wind_from
        if a.wind_speed is not None:
            wind_ = (a.wind_speed, random.Random(seed).uniform(0.0, 360.0))
        kw = {} if a.declination is None else {"declination_deg": a.declination}
        s, rec = sitl_rehearsal.rehearse(a.vehicle, a.distance, a.strategy, seed, a.speedup,
                                       wind_, sitl_dir=a.sitl,
                                       self_arrival=a.arrival == "self",
                                       pitch_deg=a.pitch,
                                       forecast="sitl" if a.forecast else None, **kw)
        # The simulation of the same scenario: the SITL's scene was turned from the
        # scenario's start heading to the hand-over's; its wind is turned back for the
        # simulation, so that both fly the same geometry in the same wind.
        sc = sitl_rehearsal.scenario_for(a.vehicle, a.distance, seed, pitch_deg=a.pitch)
        if wind_ is not None:  # (speed, from)
            turn = s["start_heading_rad"] - rfseek.world(sc).heading_rad
            sc.wind_speed_mps = wind_[0]
            sc.wind_to_rad = math.remainder(math.radians(90.0 - (wind_[1] + 180.0)) - turn,
                                            2 * math.pi)
            sc.wind_forecast = a.forecast
        sim = rfseek.simulation(sc, rfseek.simulation.seeker_for(sc, a.strategy)).run(True)
        # The SITL's ratio is the true track over the ground (in wind too): so is the
        # simulation's, from its positions (its own ratio is through the air).
        c = sim.columns()
        ground = sum(math.hypot(x1 - x0, y1 - y0) for x0, y0, x1, y1 in zip(
            c["x_m"], c["y_m"], c["x_m"][1:], c["y_m"][1:]))
        sim_ratio = (ground / sim.summary.shortest_path_m if wind_ is not None
                     else sim.summary.ratio)
        rows.append((s, sim, sim_ratio))
        if a.out:
            os.makedirs(a.out, exist_ok=True)
            with open(os.path.join(a.out, "seed_%d.json" % seed), "w") as f:
                json.dump(dict(s, simulated_ratio=sim_ratio), f, indent=1, default=str)
            sitl_rehearsal.trajectory(s, rec, os.path.join(a.out, "seed_%d.png" % seed))
        arr = s.get("arrival", {})
        print("seed %3d  %s  ratio %.3f (simulated %.3f)  flight %6.1f s  wall %5.1f s  "
              "height %.1f-%.1f m  compass %.1f deg east%s%s%s" % (
                  seed, "arrived" if s["success"] else "FAILED ", s["ratio"],
                  sim_ratio, s["time_s"], s["wall_s"],
                  s["height_min_m"], s["height_max_m"], s["compass_declination_deg"] or 0.0,
                  ("  declared %s at %.0f m, fix error %s" % (
                      arr["declared"], arr.get("arrival_detect_distance_m", float("nan")),
                      "%.1f m (in ellipse: %s)" % (arr["location_error_m"],
                                                   arr["location_in_ellipse"])
                      if arr.get("located") else "none")) if arr else "",
                  "  wind %.1f m/s from %.0f deg" % wind_ if wind_ else "",
                  " (forecast)" if a.forecast else ""), flush=True)
    ok = [(s, r) for s, sim, r in rows if s["success"] and sim.summary.success]
    arrived = sum(s["success"] for s, _, _ in rows)
    diffs = [s["ratio"] - r for s, r in ok]
    mean = statistics.mean(s["ratio"] for s, _ in ok) if ok else float("nan")
    sim_mean = statistics.mean(r for _, r in ok) if ok else float("nan")
    se = statistics.stdev(diffs) / math.sqrt(len(diffs)) if len(diffs) > 1 else float("nan")
    print("%s %s from %.0f m, %d seeds: arrived %d/%d; mean ratio %.3f (simulated %.3f); "
          "paired difference %+.3f +- %.3f" % (
              a.vehicle, a.strategy, a.distance, len(rows), arrived, len(rows), mean,
              sim_mean, statistics.mean(diffs) if diffs else float("nan"), se))
    return 0 if arrived == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
