#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""How the firmware flies the link's heading commands, beside the module's model of the
same vehicle (docs/sitl.md "How the firmware flies the link's commands").

The SITL firmware takes off with the GPS off and is handed over as for a seek; then
autopilot_link, with the flight's settings for the vehicle (sitl_rehearsal.PROFILES),
is given a fixed sequence of heading steps relative to where the vehicle points at the
hand-over (SCHEDULE: hold, 90 deg right, 90 deg left, 10 deg right, 160 deg right, 45
deg left), and the firmware's true state is recorded. The same sequence is flown by
the module's world for the vehicle's scenario (its preset: the turn model that the
Monte Carlo, rfseek-sim and sim_autopilot fly). Both are reduced to the same figures
per step:

  rate      the steady turn rate: the heading change from a quarter to three
            quarters of the step over its time (steps of 90 deg or more)
  bank      the steady bank: the median over that part (smaller steps: the largest)
  roll-in   time from the command until the bank first reaches 90 % of it
  settle    time until the heading stays within 5 deg of the command
  speed     speed over the ground lost in the turn (the mean in the 3 s before the
            command less the least until settled)
  height    height lost in the turn (the same, for the height)

and, on the straight legs, the speed and how far the track is from the yaw. The
firmware's times count from the link's first frame after the command (its clock): the
host's latency is not the firmware's. compare() checks them against TOLERANCES.
Program: scripts/sitl_response.py.
"""

import argparse
import json
import math
import statistics
import sys
import time

#: (seconds, heading relative to the hand-over's, compass degrees: + is right).
SCHEDULE = ((12.0, 0.0), (30.0, 90.0), (30.0, 0.0), (15.0, 10.0), (35.0, 170.0),
            (25.0, 125.0))

#: How closely the model must match the firmware: (figure, relative, absolute): within
#: the larger of that fraction of the firmware's figure and that much.
TOLERANCES = (("rate_deg_s", 0.08, 0.0), ("roll_in_s", 0.0, 0.3), ("settle_s", 0.15, 0.5),
              ("leg_speed_mps", 0.05, 0.0))
#: What the model leaves out (it flies level, at a constant speed, its track its
#: heading): the firmware's figure must stay within these.
UNMODELLED = (("speed_lost_mps", 1.5), ("height_lost_m", 5.0), ("track_off_yaw_deg", 15.0))


def wrap_deg(a):
    return math.remainder(a, 360.0)


def reduce_steps(samples, starts):
    """Per step of the schedule (from the second on): the figures above. samples:
    time-ordered dicts {t, compass (deg, the frame of the commands), track (true
    heading, deg), speed, up, bank (deg)}; starts: (time, target compass) per step."""
    rows = []
    for k in range(1, len(starts)):
        t0, target = starts[k]
        t1 = starts[k + 1][0] if k + 1 < len(starts) else samples[-1]["t"]
        step = wrap_deg(target - starts[k - 1][1])
        idx = [i for i, s in enumerate(samples) if t0 <= s["t"] < t1]
        before = [s for s in samples if t0 - 3.0 <= s["t"] < t0]
        if not idx or not before:
            continue
        last_out = None  # the last sample 5 deg or more off the command
        for i in idx:
            if abs(wrap_deg(samples[i]["compass"] - target)) >= 5.0:
                last_out = i
        settle = (0.0 if last_out is None else None if last_out == idx[-1]
                  else samples[last_out + 1]["t"] - t0)
        end = t0 + settle if settle is not None else t1
        during = [samples[i] for i in idx if samples[i]["t"] <= end]
        row = {"step_deg": step, "settle_s": settle,
               "bank_deg": max(abs(s["bank"]) for s in during),
               "speed_lost_mps": statistics.mean(s["speed"] for s in before)
               - min(s["speed"] for s in during),
               "height_lost_m": statistics.mean(s["up"] for s in before)
               - min(s["up"] for s in during)}
        if abs(step) >= 89.5:
            # The steady turn: from a quarter to three quarters of the change.
            h0 = before[-1]["track"]
            turned = [(samples[i]["t"], abs(wrap_deg(samples[i]["track"] - h0)), i)
                      for i in idx]
            a = next((x for x in turned if x[1] >= 0.25 * abs(step)), None)
            b = next((x for x in turned if x[1] >= 0.75 * abs(step)), None)
            if a is not None and b is not None and b[0] > a[0]:
                mid = [abs(samples[i]["bank"]) for i in range(a[2], b[2] + 1)]
                bank = statistics.median(mid)
                first = next(samples[i]["t"] for i in idx
                             if abs(samples[i]["bank"]) >= 0.9 * bank)
                row.update(rate_deg_s=(b[1] - a[1]) / (b[0] - a[0]), bank_deg=bank,
                           roll_in_s=first - t0)
        rows.append(row)
    return rows


def legs(samples, starts):
    """The straight legs (the last 8 s of every step): mean speed over the ground and
    the median angle between the track (the velocity) and the yaw (deg)."""
    v, off = [], []
    for k, (t0, _) in enumerate(starts):
        t1 = starts[k + 1][0] if k + 1 < len(starts) else samples[-1]["t"]
        for s in samples:
            if t1 - 8.0 <= s["t"] < t1:
                v.append(s["speed"])
                if "course" in s and s["speed"] > 1.0:
                    off.append(abs(wrap_deg(s["course"] - s["track"])))
    return {"leg_speed_mps": statistics.mean(v) if v else float("nan"),
            "track_off_yaw_deg": statistics.median(off) if off else 0.0}


def fly_model(sc):
    """The schedule flown by the module's world (its turn model) for scenario sc."""
    from gnuradio import rfseek
    sc.initial_distance_m = 20000.0
    w = rfseek.world(sc)
    h0 = w.heading_rad
    compass0 = 90.0 - math.degrees(h0)
    samples, starts = [], []
    t = 0.0
    for dur, rel in SCHEDULE:
        target = compass0 + rel
        starts.append((t, target))
        end = t + dur
        while w.time_s < end - 1e-9:
            head = math.radians(90.0 - target)
            w.advance(head)
            c = 90.0 - math.degrees(w.heading_rad)
            samples.append({"t": w.time_s, "compass": c, "track": c, "speed": sc.speed_mps,
                            "up": sc.altitude_m, "bank": math.degrees(w.bank_rad)})
        t = end
    return samples, starts


def fly_sitl(vehicle, speedup, sitl_dir, log):
    """The schedule flown by the SITL firmware through autopilot_link."""
    import pmt
    from gnuradio import blocks, gr, rfseek
    from gnuradio.rfseek import sitl, sitl_rehearsal
    from gnuradio.rfseek.sitl_pilot import pilot
    p = sitl_rehearsal.PROFILES[vehicle]
    speedup = min(speedup, p.get("max_speedup", speedup))
    proc = sitl.sitl_process(vehicle, sitl_dir, speedup, None, params=p.get("params"))
    samples, starts = [], []
    with proc:
        pl = pilot(proc, p["altitude_m"], log=log)
        reader = tb = link = None
        try:
            pl.take_off()
            reader = sitl.truth_reader(proc.truth_link, proc.spec["kind"], proc.home)
            reader.start_streams(since_s=pl.clock())
            settings = sitl_rehearsal._link_settings(proc, p, speedup, "", 0.0)
            link = rfseek.autopilot_link(**settings)
            tb = gr.top_block()
            dbg = blocks.message_debug()
            tb.msg_connect(link, "nav", dbg, "store")
            tb.start()
            first = None
            while first is None:
                got = reader.read(0.1)
                first = next((t for t in got if "reported_heading" in t), None)
            compass0 = 90.0 - math.degrees(first["reported_heading"])
            t = first["time"]
            if proc.spec["kind"] == "px4":
                link.handle_cmd(pmt.to_pmt({"heading": first["reported_heading"]}))
                pl.keep_streaming(lambda: link.status()["state"] == "commanding")
            for dur, rel in SCHEDULE:
                target = compass0 + rel
                starts.append((t, target))
                end = t + dur
                head = math.radians(90.0 - target)
                last_cmd = -1.0
                sent_before, delivered = link.control_sent_s(), False
                while t < end:
                    if not proc.alive():
                        raise sitl.SitlError("the SITL stopped: %s" % proc.log_tail(1))
                    if t - last_cmd >= 0.2:  # the controller's pace: a command a slot
                        link.handle_cmd(pmt.to_pmt({"heading": head}))
                        last_cmd = t
                    sent = link.control_sent_s()
                    if not delivered and sent is not None and sent != sent_before:
                        # The step starts when the link first sends the new heading (the
                        # autopilot's clock): the host's latency (the setpoint's phase,
                        # a loaded machine) is not the firmware's response.
                        delivered = True
                        starts[-1] = (max(starts[-1][0], sent), target)
                    for tr in reader.read(0.02):
                        t = tr["time"]
                        samples.append({
                            "t": t, "compass": 90.0 - math.degrees(tr.get(
                                "reported_heading", tr["heading"])),
                            "track": 90.0 - math.degrees(tr["heading"]),
                            "speed": math.hypot(tr["v_east"], tr["v_north"]),
                            "course": 90.0 - math.degrees(math.atan2(tr["v_north"],
                                                                     tr["v_east"])),
                            "up": tr["up"], "bank": math.degrees(tr["bank"])})
                    pl.watch()
            log("schedule flown: %d truths over %.0f s" % (len(samples), t - starts[0][0]))
        finally:
            if tb is not None:
                tb.stop()
                tb.wait()
            if link is not None:
                link.close()
            if reader is not None:
                reader.close()
            pl.close()
    return samples, starts


def compare(firmware, model):
    """The checks of TOLERANCES: a list of (figure, step or "legs", firmware's, model's,
    within). firmware and model: {"steps": reduce_steps rows, "legs": legs()}."""
    out = []
    pairs = [(a["step_deg"], a, b) for a, b in zip(firmware["steps"], model["steps"])]
    pairs.append(("legs", firmware["legs"], model["legs"]))
    for key, rel, tol in TOLERANCES:
        for where, a, b in pairs:
            if a.get(key) is not None and b.get(key) is not None:
                x, y = a[key], b[key]
                out.append((key, where, x, y, abs(y - x) <= max(rel * abs(x), tol)))
    for key, bound in UNMODELLED:
        for where, a, b in pairs:
            if a.get(key) is not None:
                out.append((key, where, a[key], b.get(key, 0.0), a[key] <= bound))
    return out


def table(vehicle, firmware, model):
    """The comparison as a Markdown table (firmware first, the model in brackets)."""
    def f(row, key, fmt):
        v = row.get(key)
        return "-" if v is None else fmt % v
    a, b = firmware["legs"], model["legs"]
    out = ["%s: straight legs %.1f m/s (model %.1f), track %.1f deg off the yaw (model "
           "%.1f)" % (vehicle, a["leg_speed_mps"], b["leg_speed_mps"],
                      a["track_off_yaw_deg"], b["track_off_yaw_deg"]),
           "", "| step | rate deg/s | bank deg | roll-in s | settle s | speed lost m/s | "
           "height lost m |", "| --- | --- | --- | --- | --- | --- | --- |"]
    for x, y in zip(firmware["steps"], model["steps"]):
        out.append("| %+.0f deg | %s |" % (y["step_deg"], " | ".join(
            "%s (%s)" % (f(x, k, fmt), f(y, k, fmt)) for k, fmt in (
                ("rate_deg_s", "%.1f"), ("bank_deg", "%.0f"), ("roll_in_s", "%.1f"),
                ("settle_s", "%.1f"), ("speed_lost_mps", "%.1f"),
                ("height_lost_m", "%.1f")))))
    return "\n".join(out)


def main(argv):
    p = argparse.ArgumentParser(
        prog="sitl_response.py", formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__ + """
Usage (from a build tree: PYTHONPATH=build/python LD_LIBRARY_PATH=build/lib):

    /usr/bin/python3 scripts/sitl_response.py --vehicle arduplane [--speedup 10]
        [--sitl DIR] [--preset NAME] [--set KEY=VALUE] [--json FILE] [--model-only]

Exit status 0 when every figure is within its tolerance, 1 otherwise, 3 when the SITL
could not be flown.""")
    p.add_argument("--vehicle", required=True, choices=["arducopter", "arduplane", "px4_quad"])
    p.add_argument("--speedup", type=float, default=10.0)
    p.add_argument("--sitl", default=None)
    p.add_argument("--preset", default=None, help="fly the model with this scenario "
                   "preset instead of the vehicle's")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="a scenario field of the model")
    p.add_argument("--json", default=None, help="write the figures (and the samples)")
    p.add_argument("--model-only", action="store_true", help="skip the SITL flight")
    a = p.parse_args(argv)
    from gnuradio.rfseek import sitl, sitl_rehearsal
    sc = sitl_rehearsal.scenario_for(a.vehicle, 1000.0, 1)
    if a.preset:
        sc.apply_preset(a.preset)
    for kv in a.set:
        key, _, value = kv.partition("=")
        sc.set(key, value)
    m_samples, m_starts = fly_model(sc)
    model = {"steps": reduce_steps(m_samples, m_starts), "legs": legs(m_samples, m_starts)}
    firmware = {"steps": [{} for _ in model["steps"]],
                "legs": {"leg_speed_mps": float("nan"), "track_off_yaw_deg": float("nan")}}
    s_samples, checks = [], []
    if not a.model_only:
        log = lambda text: print("sitl_response: " + text, file=sys.stderr, flush=True)  # noqa
        t = time.monotonic()
        try:
            s_samples, s_starts = fly_sitl(a.vehicle, a.speedup, a.sitl, log)
        except (sitl.SitlError, OSError) as e:
            print("sitl_response: %s" % e, file=sys.stderr)
            return 3
        firmware = {"steps": reduce_steps(s_samples, s_starts),
                    "legs": legs(s_samples, s_starts)}
        log("wall time %.0f s" % (time.monotonic() - t))
        checks = compare(firmware, model)
    print(table(a.vehicle, firmware, model))
    bad = [c for c in checks if not c[4]]
    for key, where, x, y, _ in bad:
        print("outside the tolerance: %s at %s: firmware %.2f, model %.2f" % (
            key, where, x, y))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"vehicle": a.vehicle, "firmware": firmware, "model": model,
                       "checks": checks, "samples": s_samples}, f, indent=1)
    return 1 if bad else 0
