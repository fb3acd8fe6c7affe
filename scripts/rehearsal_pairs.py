#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Paced rehearsals against the plain simulation, seed by seed.

For each seed, rfseek-live --source sim flies the same scenario twice, paced to
--speedup times real time:
  direct   the beacon's windows on the simulator's tags at 100 kS/s, the controller's
           commands straight to the simulated world;
  --via mavlink (default)
           the commands cross autopilot_link -> real MAVLink datagrams on loopback ->
           sim_autopilot -> the world, and the headings come back as ATTITUDE;
  --via radio:FAMILY
           the beacon as FAMILY's radio delivers it (its device rate, LO offset, DC leak,
           IQ imbalance, quantisation) through the receive chain of a live radio, its
           timing acquired (alignment acquire), the heading from the vehicle's reports.
With --fault "ARGS" both flights go --via, the second with rfseek-live's ARGS added (a
fault: --fault "--fault nav:0.3,0,2"), so the pair is the fault's cost; --base "ARGS"
adds options to the first only, --both "ARGS" to both (a clipping study: --both "--gain
10" --base "--fault adc:unclipped" --fault "", the same radio with a converter that does
not saturate as the reference).
It prints the distance flown (as a ratio to the start distance) of each and the paired
difference, with its mean and standard error.

  /usr/bin/python3 scripts/rehearsal_pairs.py [--seeds 20] [--first 1]
      [--distance 1000] [--speedup 10] [--strategy paper] [--via mavlink|radio:FAMILY]
      [--autopilot ardupilot_plane] [--set KEY=VALUE ...] [--fault "ARGS"]
      [--base "ARGS"] [--both "ARGS"]

Run from a build tree (PYTHONPATH and LD_LIBRARY_PATH as in rfseek-env.sh) or with the
module installed.
"""

import argparse
import math
import os
import re
import subprocess
import sys


def fly(live, seed, args, via, extra=()):
    cmd = [sys.executable, live, "--source", "sim", "--seed", str(seed),
           "--set", "initial_distance_m=%g" % args.distance, "--speedup", str(args.speedup),
           "--strategy", args.strategy, "--duration", str(args.timeout)]
    for kv in args.set:
        cmd += ["--set", kv]
    if via == "mavlink":
        cmd += ["--vehicle", "mavlink", "--autopilot", args.autopilot]
    elif via:
        cmd += ["--radio", via.split(":", 1)[1]]
    cmd += list(extra)
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout + 120)
    m = re.search(r"rfseek-live: (arrived|stopped), (\d+) m flown", r.stderr)
    if r.returncode != 0 or not m:
        errors = [l for l in r.stderr.splitlines() if "error" in l]
        raise RunFailed("seed %d (%s): %s" % (
            seed, via or "direct", errors[-1] if errors else
            "rfseek-live exited %d:\n%s" % (r.returncode, r.stderr[-1500:])))
    late = re.search(r"simulator: (\d+) commands applied late", r.stderr)
    clip = re.search(r"gain loop: (\d+) gain steps .*, (\d+) windows clipped, (\d+) of them "
                     r"valid", r.stderr)
    return (m.group(1) == "arrived", float(m.group(2)), int(late.group(1)) if late else 0,
            tuple(int(x) for x in clip.groups()) if clip else (0, 0, 0))


class RunFailed(Exception):
    """A flight that rfseek-live refused or could not finish."""


def main(argv):
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--seeds", type=int, default=20)
    p.add_argument("--first", type=int, default=1)
    p.add_argument("--distance", type=float, default=1000.0)
    p.add_argument("--speedup", type=float, default=10.0)
    p.add_argument("--strategy", default="paper")
    p.add_argument("--autopilot", default="ardupilot_plane",
                   choices=["ardupilot_plane", "ardupilot_copter", "px4"])
    p.add_argument("--via", default="mavlink",
                   help="mavlink, or radio:FAMILY (a radio of rfseek.RADIOS)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="scenario settings for both runs (e.g. carrier_hz=915e6 for a "
                        "radio that does not tune 2 GHz)")
    p.add_argument("--fault", default=None, metavar="ARGS",
                   help="both flights --via, the second with these rfseek-live options")
    p.add_argument("--base", default="", metavar="ARGS",
                   help="with --fault: rfseek-live options of the first flight only")
    p.add_argument("--both", default="", metavar="ARGS",
                   help="rfseek-live options of both flights")
    p.add_argument("--timeout", type=float, default=600.0,
                   help="wall seconds per run before it is stopped")
    args = p.parse_args(argv)
    if args.seeds < 1 or args.first < 0:
        p.error("--seeds must be >= 1 and --first >= 0")
    if not (math.isfinite(args.speedup) and args.speedup > 0 and
            math.isfinite(args.timeout) and args.timeout > 0):
        p.error("--speedup and --timeout must be finite and > 0")
    from gnuradio import rfseek
    probe = rfseek.scenario()
    try:
        rfseek.apply_sets(probe, ["initial_distance_m=%r" % args.distance] + args.set)
        probe.validate()
    except ValueError as e:
        p.error(str(e))
    if not args.distance > probe.success_radius_m:
        p.error("--distance %g: must be beyond the arrival radius success_radius_m (%g m)"
                % (args.distance, probe.success_radius_m))
    here = os.path.dirname(os.path.abspath(__file__))
    live = os.path.join(here, "..", "apps", "rfseek-live")

    rows = []
    if args.via != "mavlink" and not args.via.startswith("radio:"):
        p.error("--via: mavlink or radio:FAMILY")
    name = args.via.split(":")[0]
    base, extra = (args.via, args.fault.split()) if args.fault is not None else (None, ())
    if args.base and args.fault is None:
        p.error("--base: only with --fault (the second flight's options)")
    if args.fault is not None:
        name = "fault"
    first = "clean" if args.fault is not None else "direct"
    print("seed  %6s ratio  %7s ratio  difference" % (first, name))
    late, clips = 0, [[0, 0, 0], [0, 0, 0]]
    both = args.both.split()
    for seed in range(args.first, args.first + args.seeds):
        try:
            a_ok, a, late_a, clip_a = fly(live, seed, args, base, both + args.base.split())
            b_ok, b, late_b, clip_b = fly(live, seed, args, args.via, both + list(extra))
        except RunFailed as e:
            print("rehearsal_pairs.py: error: %s" % e, file=sys.stderr)
            return 1
        late += late_a + late_b
        for total, c in zip(clips, (clip_a, clip_b)):
            total[:] = [x + y for x, y in zip(total, c)]
        # rfseek-live reports the flight to the arrival radius; the ratio is to the
        # straight line from the start to that radius, as the study's.
        line = args.distance - probe.success_radius_m
        rows.append((a / line, b / line, a_ok, b_ok))
        print("%4d  %12.3f%s  %13.3f%s  %+10.3f" % (seed, a / line, "" if a_ok else "*",
                                                   b / line, "" if b_ok else "*",
                                                   (b - a) / line), flush=True)
    d = [r[1] - r[0] for r in rows]
    n = len(d)
    mean = sum(d) / n
    se = math.sqrt(sum((x - mean) ** 2 for x in d) / (n - 1) / n) if n > 1 else float("nan")
    print("%s:  mean ratio %.3f, %d/%d arrived" % (first,
        sum(r[0] for r in rows) / n, sum(r[2] for r in rows), n))
    print("%s: mean ratio %.3f, %d/%d arrived" % (
        name, sum(r[1] for r in rows) / n, sum(r[3] for r in rows), n))
    print("paired difference (%s - %s): %+.4f +- %.4f (standard error)"
          % (name, first, mean, se))
    print("commands the simulator flew late (free-running, over all runs): %d" % late)
    for label, (steps, clipped, valid) in zip((first, name), clips):
        if steps or clipped:
            print("%s: %d gain steps, %d windows clipped, %d of them valid (all runs)"
                  % (label, steps, clipped, valid))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
