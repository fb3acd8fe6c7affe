#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""The seek flown by the real firmware: SITL (sitl.sitl_process) flies the vehicle, the
world follows its truth, and the receive chain, the controller and autopilot_link are
the very blocks of a flight (docs/sitl.md).

    SITL ──true state──▶ truth_source ──truth──▶ channel_source(follow_truth) ──▶
        doppler_estimator ──meas──▶ seeking_controller ──cmd──▶ autopilot_link ──▶ SITL
                                               ▲─────────────nav (ATTITUDE)───────┘

Only channel_source and the scoring read the truth.
"""

import math
import threading
import time

import pmt
from gnuradio import gr

from . import rfseek_python as _core
from .autopilot_link import autopilot_link
from .flowgraphs import collector
from .sitl import HOME, HOME_DECLINATION_DEG, SitlError, sitl_process, truth_reader
from .sitl_pilot import pilot


class truth_source(gr.basic_block):
    """Message source: the simulator's true state ("truth" out) from a truth_reader, read
    on a thread of its own; every truth is kept (truths) for the scoring and the
    figure."""

    def __init__(self, reader):
        gr.basic_block.__init__(self, name="rfseek_truth_source", in_sig=None, out_sig=None)
        self.reader = reader
        self.truths = []
        self.error = None
        self.message_port_register_out(pmt.intern("truth"))
        self._running = False
        self._thread = None

    def start(self):
        self._running = True
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()
        return True

    def _run(self):
        last = None
        while self._running:
            try:
                got = self.reader.read(0.02)
            except OSError as e:
                self.error = str(e)
                break
            for t in got:
                if last is not None and t["time"] <= last:
                    continue  # the same tick's clock: one truth per tick
                last = t["time"]
                self.truths.append(t)
                self.message_port_pub(pmt.intern("truth"), pmt.to_pmt(t))

    def stop(self):
        self._running = False
        if self._thread is not None:
            self._thread.join(timeout=1.0)
        return True


class sitl_truth(truth_source):
    """The truth of a SITL already flying (GRC "RF-Seek SITL Truth"): a truth_source
    on `link` for a firmware of `kind` ("ardupilot" or "px4") whose home is `home` (lat,
    lon in deg, altitude in m above sea level). Its streams are asked for when the
    flowgraph starts; truths from then on are published."""

    def __init__(self, link="tcp:127.0.0.1:5762", kind="ardupilot", home=HOME):
        try:
            reader = truth_reader(link, kind, home, connect_timeout=5.0)
        except SitlError as e:
            raise ConnectionError("sitl_truth: %s" % e) from None
        truth_source.__init__(self, reader)

    def start(self):
        self.reader.start_streams()
        return truth_source.start(self)


class sitl_loop(gr.top_block):
    """The closed loop around a running SITL: truth -> world -> estimator -> controller
    -> autopilot_link -> SITL. `cfg` is the controller's seeker_config; `link` the
    autopilot_link keyword arguments."""

    def __init__(self, sc, cfg, reader, link, progress_every=0):
        gr.top_block.__init__(self, "rfseek SITL rehearsal", catch_exceptions=False)
        self.truth = truth_source(reader)
        self.world = _core.channel_source(sc, mode="burst", lockstep=False,
                                          follow_truth=True)
        self.estimator = _core.doppler_estimator(sc.samp_rate_hz, sc.window_len,
                                                 sc.fft_len, interpolator="parabolic")
        self.controller = _core.seeking_controller(cfg)
        # The beacon's tags carry no heading here: the first one comes from the link's
        # nav. Seeking before it would start from an assumed heading, and the first
        # commands would send the vehicle off the way the strategy never meant.
        self.controller.set_wait_for_heading(True)
        self.link = autopilot_link(**link)
        self.collector = collector(progress_every)
        self.connect(self.world, self.estimator)
        self.msg_connect(self.truth, "truth", self.world, "truth")
        self.msg_connect(self.estimator, "meas", self.controller, "meas")
        self.msg_connect(self.controller, "cmd", self.link, "cmd")
        self.msg_connect(self.controller, "cmd", self.world, "cmd")  # its "done" only
        self.msg_connect(self.link, "nav", self.controller, "nav")
        self.msg_connect(self.world, "state", self.collector, "state")
        self.msg_connect(self.estimator, "meas", self.collector, "meas")
        self.msg_connect(self.controller, "telemetry", self.collector, "telemetry")
        self.msg_connect(self.controller, "status", self.collector, "status")

    def finished(self):
        s = self.collector.states
        if not s:
            return False
        d = s[-1]
        return bool((d["arrived"] and "reached" not in d) or d["capped"] or d.get("ended"))


#: How each vehicle flies the seek: the link's settings, and what the seeker and the
#: in-process simulation believe of the vehicle (its speed over still air at those
#: settings, its turns): for ArduPilot the scenario presets fitted to the firmware's
#: own response (sitl_response; docs/sitl.md "How the firmware flies the link's
#: commands"), whose speed, bank and roll rate are repeated here for the link.
PROFILES = {
    # GUIDED_NOGPS at 15 deg of pitch, the link's coordinated turns at 15 deg of bank.
    "arducopter": {"preset": "arducopter", "altitude_m": 50.0, "speed_mps": 6.1,
                   "pitch_deg": 15.0, "thrust": 0.5, "bank_deg": 15.0,
                   "roll_rate_deg_s": 30.0},
    # ArduPlane's GUIDED heading loop at its default gain (GUIDED_P 5000) settles a 10
    # deg step in about 10 s; at 15000 in about 1 s. The link asks for 6 m/s^2 (a 31
    # deg bank, which it flies); the plane then turns at 11.0 deg/s, as a coordinated
    # turn at 24.8 deg would.
    "arduplane": {"preset": "arduplane", "altitude_m": 100.0, "speed_mps": 23.6,
                  "bank_deg": 24.8, "roll_rate_deg_s": 40.0, "heading_accel_mps2": 6.0,
                  "params": {"GUIDED_P": 15000}},
    # PX4 SIH's quad flies 2.7 m/s at 15 deg of pitch; its lockstep simulator kept up
    # with about 4 x real time here (at 10 x its truth and telemetry came late).
    "px4_quad": {"altitude_m": 50.0, "speed_mps": 2.7, "pitch_deg": 15.0, "thrust": 0.5,
                 "bank_deg": 15.0, "roll_rate_deg_s": 90.0, "max_speedup": 4.0},
}


#: ArduCopter SITL's speed over the ground (m/s) in GUIDED_NOGPS by the link's forward
#: pitch (deg), still air (sitl_response; docs/sitl.md). A steeper pitch flies faster:
#: for wind near the 15 deg speed.
COPTER_SPEED_AT_PITCH = {5.0: 2.6, 15.0: 6.1, 25.0: 8.7, 30.0: 10.0}


def profile(vehicle, pitch_deg=None):
    """PROFILES[vehicle], with ArduCopter at another measured forward pitch (one of
    COPTER_SPEED_AT_PITCH): its speed, and the link's coordinated turns at it."""
    if vehicle not in PROFILES:
        raise ValueError("vehicle = %r: must be one of %s" % (vehicle, ", ".join(PROFILES)))
    p = dict(PROFILES[vehicle])
    if pitch_deg is None:
        return p
    if vehicle != "arducopter" or float(pitch_deg) not in COPTER_SPEED_AT_PITCH:
        raise ValueError("pitch_deg = %r: ArduCopter only, one of %s (the pitches whose "
                         "speed was measured)" % (pitch_deg, ", ".join(
                             "%g" % k for k in sorted(COPTER_SPEED_AT_PITCH))))
    p.update(pitch_deg=float(pitch_deg), speed_mps=COPTER_SPEED_AT_PITCH[float(pitch_deg)])
    return p


def scenario_for(vehicle, distance_m=800.0, seed=1, altitude_m=None, sets=(),
                 pitch_deg=None):
    """The world of a rehearsal: the reference scenario (with the vehicle's preset, if
    it has one) from `distance_m`, the emitter placed at a bearing drawn from `seed`
    relative to where the seek starts, the vehicle's speed and turns as the seeker
    believes them, then `sets` (KEY=VALUE)."""
    p = profile(vehicle, pitch_deg)
    sc = _core.scenario()
    if "preset" in p:
        sc.apply_preset(p["preset"])
    sc.seed = int(seed)
    sc.initial_distance_m = float(distance_m)
    sc.speed_mps = p["speed_mps"]
    sc.altitude_m = float(altitude_m if altitude_m is not None else p["altitude_m"])
    sc.bank_limit_rad = math.radians(p["bank_deg"])
    sc.roll_rate_rad_per_s = math.radians(p["roll_rate_deg_s"])
    for kv in sets:
        key, _, value = kv.partition("=")
        sc.set(key, value)
    sc.validate()
    return sc


def forecast_vector(wind):
    """A wind given as (speed m/s, compass direction it blows from in deg, true) as the
    seeker's forecast: (toward east, toward north) in m/s. None: no wind, (0, 0)."""
    if wind is None:
        return 0.0, 0.0
    speed, frm = (float(v) for v in wind)
    if not (math.isfinite(speed) and math.isfinite(frm) and speed >= 0.0):
        raise ValueError("forecast = %r: must be (speed >= 0 m/s, from in deg), finite"
                         % (wind,))
    toward = math.radians(frm + 180.0)  # compass: clockwise from north
    return speed * math.sin(toward), speed * math.cos(toward)


def _link_settings(proc, p, speedup, tlog, declination_deg):
    """autopilot_link's settings for a vehicle of profile p behind the SITL proc."""
    link = {"link": proc.link, "family": proc.spec["family"], "time_scale": speedup,
            "link_timeout_s": 2.0, "tlog": tlog or "", "clock": "autopilot",
            "declination_deg": declination_deg}
    for k in ("pitch_deg", "thrust", "heading_accel_mps2"):
        if k in p:
            link[k] = p[k]
    if "thrust" in p:  # multirotors: coordinated turns, as the seeker's turn model
        link.update(turn_bank_deg=p["bank_deg"], turn_speed_mps=p["speed_mps"])
    if proc.spec["kind"] == "px4":  # raw thrust: the link holds the height
        link["hold_altitude"] = True
    return link


def rehearse(vehicle, distance_m=800.0, strategy="adaptive", seed=1, speedup=10.0,
             wind=None, altitude_m=None, sitl_dir=None, tlog=None, self_arrival=False,
             sets=(), progress_every=0, log=None, wall_cap_s=600.0,
             declination_deg=HOME_DECLINATION_DEG, pitch_deg=None, forecast=None):
    """One seek flown by the SITL firmware of `vehicle` from `distance_m`; returns the
    summary dict and the run's records (truths, states, statuses). Raises SitlError
    (one line) when the SITL cannot be started, answers not, or refuses a step; every
    process started is stopped whatever happens. declination_deg: what the link is
    told of the home's declination (0: the seek and its fix in the compass's frame).
    pitch_deg: ArduCopter's forward pitch, one of COPTER_SPEED_AT_PITCH (default 15).
    wind: the SITL's wind, (speed m/s, compass direction it blows from in deg).
    forecast: the wind as the operator knows it, handed to the seeker (`adaptive`'s
    wind forecast, as rfseek-live --wind-from): "sitl" for the SITL's own wind, or
    (speed, from) like `wind`; None (default): the seeker learns the wind alone."""
    if not (isinstance(declination_deg, (int, float)) and -180 <= declination_deg <= 180):
        raise ValueError("declination_deg = %r: must be in [-180, 180] (deg east of true "
                         "north)" % (declination_deg,))
    log = log or (lambda text: None)
    p = profile(vehicle, pitch_deg)
    from . import split_sets
    scenario_sets, seeker_sets = split_sets(sets)
    sc = scenario_for(vehicle, distance_m, seed, altitude_m, scenario_sets, pitch_deg)
    sc.self_arrival = bool(self_arrival)
    cfg = _core.simulation.seeker_for(sc, strategy)
    for kv in seeker_sets:
        key, _, value = kv.partition("=")
        cfg.set(key.strip(), value.strip())
    if forecast is not None:
        cfg.wind_forecast_east_mps, cfg.wind_forecast_north_mps = forecast_vector(
            wind if forecast == "sitl" else forecast)
    if sc.self_arrival and sc.bank_limit_rad > 0:
        # The loiter over the emitter must be an orbit the vehicle can fly: 20 % wider
        # than its tightest turn at the profile's bank (a plane's is about 93 m).
        tightest = sc.speed_mps ** 2 / (9.80665 * math.tan(sc.bank_limit_rad))
        cfg.loiter_radius_m = max(cfg.loiter_radius_m, 1.2 * tightest)
    cfg.validate()
    speedup = min(speedup, p.get("max_speedup", speedup))
    t_wall = time.monotonic()
    proc = sitl_process(vehicle, sitl_dir, speedup, wind, params=p.get("params"))
    with proc:
        log("started %s (instance %d) in %s" % (proc.binary, proc.instance, proc.workdir))
        pl = pilot(proc, sc.altitude_m, log=log,
                   cruise_pitch_deg=p.get("pitch_deg") if vehicle == "arducopter" else None)
        reader = loop = None
        try:
            pl.take_off()
            # Connected at the hand-over: nothing buffered during the take-off is read.
            reader = truth_reader(proc.truth_link, proc.spec["kind"], proc.home)
            reader.start_streams(since_s=pl.clock())
            t_seek = time.monotonic()
            try:
                loop = sitl_loop(sc, cfg, reader,
                                 _link_settings(proc, p, speedup, tlog, declination_deg),
                                 progress_every)
            except OSError as e:
                raise SitlError("the link to %s: %s" % (proc.link, e)) from None
            loop.start()
            pl.keep_streaming(lambda: loop.link.status()["state"] == "commanding")
            while not loop.finished():
                if not proc.alive():
                    raise SitlError("the SITL stopped during the seek: %s" % proc.log_tail(1))
                if loop.truth.error:
                    raise SitlError("the truth link failed: %s" % loop.truth.error)
                if time.monotonic() - t_seek > wall_cap_s:
                    raise SitlError("the seek took over %.0f s of wall time" % wall_cap_s)
                pl.watch()
                time.sleep(0.05)
        finally:  # whatever happened: the flowgraph, the sockets, the pilot's thread
            if loop is not None:
                loop.stop()
                loop.wait()
                loop.link.close()
            if reader is not None:
                reader.close()
            pl.close()
    states = loop.collector.states
    last = states[-1]
    straight = sc.initial_distance_m - sc.success_radius_m
    summary = {
        "vehicle": vehicle, "strategy": strategy, "seed": seed, "speedup": speedup,
        "distance_m": sc.initial_distance_m, "altitude_m": sc.altitude_m,
        "wind": list(wind) if wind else None,
        "forecast": [cfg.wind_forecast_east_mps, cfg.wind_forecast_north_mps]
        if forecast is not None else None, "pitch_deg": p.get("pitch_deg"),
        "speed_mps": sc.speed_mps,
        "success": bool(last["arrived"] or last.get("reached", False)),
        "capped": bool(last["capped"]),
        "distance_flown_m": last["distance_flown"], "ratio": last["distance_flown"] / straight,
        "time_s": last["time"], "slots": int(last["slot"]),
        "wall_s": time.monotonic() - t_wall, "seek_wall_s": time.monotonic() - t_seek,
        "truths": len(loop.truth.truths),
        "height_min_m": min(t["up"] for t in loop.truth.truths),
        "height_max_m": max(t["up"] for t in loop.truth.truths),
        "link": loop.link.status(),
        "declination_deg": declination_deg,
        # The heading at the hand-over (true): the scene turned from the scenario's
        # start heading to it (world.follow).
        "start_heading_rad": loop.truth.truths[0]["heading"],
        "compass_declination_deg": _compass_declination(loop.truth.truths),
    }
    if sc.self_arrival:  # declared where, and the fix against the true emitter
        from .flowgraphs import arrival_summary
        summary["arrival"] = arrival_summary(states, loop.collector.status,
                                             loop.collector.telemetry)
    return summary, {"truths": loop.truth.truths, "states": states,
                     "status": loop.collector.status, "telemetry": loop.collector.telemetry,
                     "meas": loop.collector.meas}


def _compass_declination(truths):
    """How far east of true north the autopilot's own headings pointed: the median, over
    the seek, of the true heading less the reported one (deg, compass sense); None
    without reports."""
    d = sorted(math.degrees(math.remainder(t["reported_heading"] - t["heading"], 2 * math.pi))
               for t in truths if "reported_heading" in t)
    return d[len(d) // 2] if d else None


def trajectory(summary, rec, path):
    """The true track (the world followed the firmware's truth), as rfseek-sim draws a
    simulated one; with a self-declared arrival, its fix and ellipse."""
    from .flowgraphs import arrival_summary
    from .plots import columns_from_messages, trajectory_figure
    col = columns_from_messages(rec["states"], rec["meas"], rec["telemetry"])
    arrival = (arrival_summary(rec["states"], rec["status"], rec["telemetry"])
               if rec["status"] else None)
    title = "%s SITL, GPS off: %s, %.0f m flown (ratio %.3f)%s" % (
        summary["vehicle"], summary["strategy"], summary["distance_flown_m"],
        summary["ratio"], ", wind %.0f m/s from %.0f deg" % tuple(summary["wind"])
        if summary["wind"] else "")
    trajectory_figure(col, title=title, path=path, arrival=arrival)


def take_off_and_hold(vehicle, sitl_dir=None, speedup=10.0, wind=None, altitude_m=None,
                      log=None):
    """Start the SITL of an ArduPilot `vehicle`, take off and hand over in its GPS-free
    mode, then hold it there (the pilot watching) until the SITL stops or Ctrl-C, for a
    flowgraph of one's own (examples/seek_sitl.grc) to seek with. PX4 is refused: its
    hand-over needs the link's setpoint stream at once (use rehearse)."""
    log = log or (lambda text: None)
    if vehicle not in PROFILES:
        raise ValueError("vehicle = %r: must be one of %s" % (vehicle, ", ".join(PROFILES)))
    p = PROFILES[vehicle]
    if vehicle == "px4_quad":
        raise ValueError("takeoff-only: ArduPilot vehicles only (PX4 leaves OFFBOARD "
                         "unless the link streams at once; fly it with rfseek-sitl)")
    proc = sitl_process(vehicle, sitl_dir, speedup, wind, params=p.get("params"))
    with proc:
        pl = pilot(proc, altitude_m if altitude_m is not None else p["altitude_m"], log=log)
        pl.take_off()
        log("ready: truth on %s, link on %s, home %.6f, %.6f, %.0f m; Ctrl-C stops it"
            % (proc.truth_link, proc.link, *proc.home[:3]))
        while proc.alive():
            pl.watch()
            time.sleep(0.1)
        raise SitlError("the SITL stopped: %s" % proc.log_tail(1))
