#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Ready-made flowgraphs: the closed-loop seek of channel_source -> doppler_estimator ->
seeking_controller -> channel_source, with the truth and telemetry collected."""

import heapq
import math
import random
import sys

import pmt
from gnuradio import gr

from .rfseek_python import (channel_source, doppler_estimator, estimator_config,
                            seeking_controller, simulation)


class collector(gr.basic_block):
    """Keeps every message of its inputs 'state', 'meas', 'telemetry' and 'status' as
    Python dicts; optionally prints a progress line every `every` slots."""

    def __init__(self, progress_every=0, stream=sys.stderr):
        gr.basic_block.__init__(self, name="rfseek_collector", in_sig=None, out_sig=None)
        self.states, self.meas, self.telemetry, self.status = [], [], [], []
        self._every = progress_every
        self._stream = stream
        # GNU Radio's Python gateway finds handlers by method name: one method per port.
        self.message_port_register_in(pmt.intern("state"))
        self.set_msg_handler(pmt.intern("state"), self.on_state)
        self.message_port_register_in(pmt.intern("meas"))
        self.set_msg_handler(pmt.intern("meas"), self.on_meas)
        self.message_port_register_in(pmt.intern("telemetry"))
        self.set_msg_handler(pmt.intern("telemetry"), self.on_telemetry)
        self.message_port_register_in(pmt.intern("status"))
        self.set_msg_handler(pmt.intern("status"), self.on_status)

    def on_status(self, msg):
        d = pmt.to_python(msg)
        self.status.append(d)
        if self._every and d["status"] != "seeking":
            self._stream.write("\n  %s at slot %d%s\n" % (
                d["status"].upper(), d["slot"],
                ", emitter %.0f m away at %.0f deg CCW from east (95 %% ellipse %.0f x "
                "%.0f m)" % (
                    d["range_m"], math.degrees(d["bearing_rad"]), d["major_m"],
                    d["minor_m"]) if "range_m" in d else ""))
            self._stream.flush()

    def on_meas(self, msg):
        self.meas.append(pmt.to_python(msg))

    def on_telemetry(self, msg):
        self.telemetry.append(pmt.to_python(msg))

    def on_state(self, msg):
        d = pmt.to_python(msg)
        self.states.append(d)
        end = (d["arrived"] and "reached" not in d) or d["capped"] or d.get("ended", False)
        tty = hasattr(self._stream, "isatty") and self._stream.isatty()
        every = self._every if tty else 10 * self._every  # a log gets fewer lines
        if self._every and (d["slot"] % every == 0 or end):
            stage = self.telemetry[-1]["stage"] if self.telemetry else 0
            line = "  slot %6d  t %7.1f s  flown %7.1f m  to go %7.1f m  stage %d" % (
                d["slot"], d["time"], d["distance_flown"], d["distance"], stage)
            self._stream.write(("\r" + line + ("\n" if end else "")) if tty else line + "\n")
            self._stream.flush()


class closed_loop(gr.top_block):
    """The seek through GNU Radio, in lockstep (reproducible from the scenario's seed).

    scenario: rfseek.scenario; strategy: seeker strategy name or a seeker_config;
    estimator: rfseek.estimator_config (window, interpolator, band)."""

    def __init__(self, scenario, strategy="paper", estimator=None, progress_every=0):
        gr.top_block.__init__(self, "rfseek closed loop", catch_exceptions=False)
        est_cfg = estimator or estimator_config()
        cfg = (simulation.seeker_for(scenario, strategy) if isinstance(strategy, str)
               else strategy)
        self.source = channel_source(scenario, mode="burst", lockstep=True, realtime=False)
        self.estimator = doppler_estimator(scenario.samp_rate_hz, scenario.window_len,
                                           scenario.fft_len, window=est_cfg.window,
                                           interpolator=est_cfg.interpolator,
                                           min_freq=est_cfg.min_freq_hz,
                                           max_freq=est_cfg.max_freq_hz)
        self.controller = seeking_controller(cfg)
        self.collector = collector(progress_every)
        self.connect(self.source, self.estimator)
        self.msg_connect(self.estimator, "meas", self.controller, "meas")
        self.msg_connect(self.controller, "cmd", self.source, "cmd")
        self.msg_connect(self.source, "state", self.collector, "state")
        self.msg_connect(self.estimator, "meas", self.collector, "meas")
        self.msg_connect(self.controller, "telemetry", self.collector, "telemetry")
        self.msg_connect(self.controller, "status", self.collector, "status")


class state_to_nav(gr.basic_block):
    """Turns channel_source's per-slot truth into the heading reports a vehicle would
    send ({heading, time}: the measured heading at the world's time), for recordings,
    demos and rehearsals of the nav path. A link's faults, in the world's time:
    delay_s (every report that late), jitter_s (each a further 0 to jitter_s late,
    drawn from `seed`: reports then arrive out of order), and dropouts (no report for
    dropout_s seconds, every dropout_every_s seconds from the first period on)."""

    def __init__(self, delay_s=0.0, jitter_s=0.0, dropout_s=0.0, dropout_every_s=20.0,
                 seed=0):
        gr.basic_block.__init__(self, name="rfseek_state_to_nav", in_sig=None, out_sig=None)
        for name, v, lo in (("delay_s", delay_s, 0.0), ("jitter_s", jitter_s, 0.0),
                            ("dropout_s", dropout_s, 0.0),
                            ("dropout_every_s", dropout_every_s, 1e-3)):
            if not (isinstance(v, (int, float)) and math.isfinite(v) and lo <= v <= 3600):
                raise ValueError("state_to_nav: %s = %r: must be in [%g, 3600] s"
                                 % (name, v, lo))
        if dropout_s >= dropout_every_s:
            raise ValueError("state_to_nav: dropout_s = %r: must be below dropout_every_s "
                             "= %r" % (dropout_s, dropout_every_s))
        self.delay_s, self.jitter_s = float(delay_s), float(jitter_s)
        self.dropout_s, self.dropout_every_s = float(dropout_s), float(dropout_every_s)
        self._rng = random.Random(seed)
        self._held = []  # (release time, arrival order, report)
        self._order = 0
        self.sent = self.dropped = 0
        self.message_port_register_in(pmt.intern("state"))
        self.message_port_register_out(pmt.intern("nav"))
        self.set_msg_handler(pmt.intern("state"), self.on_state)

    def on_state(self, msg):
        try:
            d = pmt.to_python(msg)
            h = float(d["measured_heading"])
            t = float(d.get("time", math.nan))
        except (KeyError, TypeError, ValueError, AttributeError):
            return
        report = {"heading": h}
        if math.isfinite(t):
            report["time"] = t
        faulty = self.delay_s > 0 or self.jitter_s > 0 or self.dropout_s > 0
        if not faulty or not math.isfinite(t):
            self.sent += 1
            self.message_port_pub(pmt.intern("nav"), pmt.to_pmt(report))
            return
        phase = t % self.dropout_every_s
        if t >= self.dropout_every_s and phase < self.dropout_s:
            self.dropped += 1
        else:
            late = self.delay_s + self._rng.uniform(0.0, self.jitter_s)
            heapq.heappush(self._held, (t + late, self._order, report))
            self._order += 1
        # Released when the world's time has passed theirs.
        while self._held and self._held[0][0] <= t:
            self.sent += 1
            self.message_port_pub(pmt.intern("nav"), pmt.to_pmt(heapq.heappop(self._held)[2]))


def arrival_summary(states, status, telemetry=None):
    """The arrival and location figures of a self_arrival flight from closed_loop's
    collected 'state' (truth) and 'status' messages, as rfseek.simulation's run_summary
    computes them: declared, arrival_detect_distance_m (true horizontal distance at the
    declaration), false_arrival (> 1 km), located, location (the first fix: east_m,
    north_m relative to the vehicle, major_m, minor_m, major_angle_rad), the vehicle's
    true position then, location_error_m, location_in_ellipse (95 %),
    location_in_ellipse50 and location_unsure. With the
    'telemetry' messages: overflight and overflight_distance_m (where the loiter, stage
    3, first began)."""
    by_slot = {int(s["slot"]): s for s in states}
    out = {"declared": False, "located": False}
    if telemetry is not None:
        loiter = next((t for t in telemetry if t["stage"] == 3), None)
        out["overflight"] = loiter is not None and int(loiter["slot"]) in by_slot
        if out["overflight"]:
            out["overflight_distance_m"] = by_slot[int(loiter["slot"])]["distance"]
    arrived = next((m for m in status if m["status"] in ("arrived", "located")), None)
    if arrived is not None and int(arrived["slot"]) in by_slot:
        st = by_slot[int(arrived["slot"])]
        out.update(declared=True, arrival_slot=int(arrived["slot"]),
                   arrival_time_s=st["time"], arrival_detect_distance_m=st["distance"],
                   false_arrival=st["distance"] > 1000.0)
    fix = next((m for m in status if m["status"] == "located" and "east_m" in m), None)
    if fix is not None and int(fix["slot"]) in by_slot:
        st = by_slot[int(fix["slot"])]
        ex, ey = fix["east_m"] + st["x"], fix["north_m"] + st["y"]  # emitter: origin
        ca, sa = math.cos(fix["major_angle_rad"]), math.sin(fix["major_angle_rad"])
        u = (ex * ca + ey * sa) / max(fix["major_m"], 1e-9)
        v = (-ex * sa + ey * ca) / max(fix["minor_m"], 1e-9)
        u5 = (ex * ca + ey * sa) / max(fix.get("major50_m", 0.0), 1e-9)
        v5 = (-ex * sa + ey * ca) / max(fix.get("minor50_m", 0.0), 1e-9)
        out.update(located=True, location_slot=int(fix["slot"]),
                   location={k: fix[k] for k in (
                       "east_m", "north_m", "range_m", "bearing_rad", "major_m", "minor_m",
                       "major_angle_rad", "wind_east_mps", "wind_north_mps", "altitude_m",
                       "rms_hz", "consistency", "major50_m", "minor50_m", "unsure")},
                   vehicle_xy_at_fix=(st["x"], st["y"]),
                   estimated_emitter_xy=(st["x"] + fix["east_m"], st["y"] + fix["north_m"]),
                   location_error_m=math.hypot(ex, ey),
                   location_in_ellipse=u * u + v * v <= 1.0,
                   location_in_ellipse50=u5 * u5 + v5 * v5 <= 1.0,
                   location_unsure=bool(fix["unsure"]))
    return out
