#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""The rehearsal's pilot: what a ground station and its pilot do before a seek against
SITL (docs/sitl.md): the take-off without GPS and the
hand-over to the link in the GPS-free mode."""

import math
import threading
import time

from . import rfseek_python as _core
from .sitl import SitlError, _ACK_RESULTS, mav_client


#: The plane is handed over once its airspeed has varied by at most SETTLED_MPS over
#: SETTLED_S s of the autopilot's clock.
SETTLED_MPS, SETTLED_S = 0.5, 3.0
#: ArduCopter is flown forward at the seek's pitch this long (autopilot's clock) before
#: the hand-over.
COPTER_SPEED_UP_S = 4.0


class pilot:
    """What a ground station and its pilot do before the seek: take off without GPS,
    climb to `altitude_m` above home, and hand the vehicle over to the link in its
    GPS-free mode. Then it stays on the line to watch (altitude, mode) and, at the end,
    to land or disarm. Every wait is on the autopilot's clock (time_boot_ms), so a
    speed-up changes nothing; `wall_timeout_s` bounds each step in host time.

    ArduCopter: ALT_HOLD, an ordinary arm (EKF3 runs without GPS), throttle 1800 by
    RC_CHANNELS_OVERRIDE until the height, 1500 (hold), GUIDED_NOGPS, the override
    released. ArduPlane: FBWA (FLY_BY_WIRE_A), a forced arm (ordinary arming is refused without GPS),
    full throttle by override until the height, GUIDED (it holds the height it was
    entered at), released. PX4: a level SET_ATTITUDE_TARGET stream at take-off thrust,
    OFFBOARD, arm, climb, hover thrust until the link's own stream takes over."""

    def __init__(self, proc, altitude_m=50.0, wall_timeout_s=120.0, log=None,
                 cruise_pitch_deg=None):
        if not (10.0 <= altitude_m <= 500.0):
            raise ValueError("altitude_m = %r: must be in [10, 500] m" % (altitude_m,))
        self.proc = proc
        self.kind = proc.spec["kind"]
        self.vehicle = proc.vehicle
        self.altitude_m = float(altitude_m)
        self.wall_timeout_s = float(wall_timeout_s)
        self.log = log or (lambda text: None)
        self.client = mav_client(proc.pilot_link, connect_timeout=min(30.0, wall_timeout_s))
        self.hover_thrust = 0.5
        # ArduCopter: handed over in forward flight at this pitch (None: from a hover).
        self.cruise_pitch_deg = cruise_pitch_deg
        self._q = (1.0, 0.0, 0.0, 0.0)  # the attitude the streaming thread holds
        self.ground_alt = None
        self._hovering = False
        self._hover_thread = None

    # --- helpers on the autopilot's clock ---
    def clock(self):
        """The autopilot's clock (s since its boot), or None before it spoke."""
        return self._clock()

    def _clock(self):
        return None if self.client.time_boot_ms is None else self.client.time_boot_ms / 1e3

    def _until(self, what, done, every_s=0.1, action=None, sim_timeout_s=300.0):
        """Poll until done() holds; action() every every_s of the autopilot's clock."""
        wall_end = time.monotonic() + self.wall_timeout_s
        start, last = None, None
        while True:
            if not self.proc.alive():
                raise SitlError("the SITL stopped while %s: %s" % (what, self.proc.log_tail(1)))
            self.client.poll(0.02)
            now = self._clock()
            if now is not None:
                start = now if start is None else start
                if action is not None and (last is None or now - last >= every_s):
                    last = now
                    action()
                if done():
                    return
                if now - start > sim_timeout_s:
                    raise SitlError("%s: not done after %.0f s of the autopilot's clock%s"
                                    % (what, sim_timeout_s, self._why()))
            if time.monotonic() > wall_end:
                raise SitlError("%s: the SITL did not answer within %.0f s%s"
                                % (what, self.wall_timeout_s, self._why()))

    def _why(self):
        return (" (it said: %s)" % self.client.text[-1]) if self.client.text else ""

    def _set_mode(self, name):
        number = _core.autopilot_mode_number(self.proc.spec["family"], name)
        if self.kind == "px4":
            result = self.client.command(176, (1, (number >> 16) & 0xFF, (number >> 24) & 0xFF))
        else:
            result = self.client.command(176, (1, number))
        if result != 0:
            raise SitlError("mode %s refused (%s)%s" % (
                name, _ACK_RESULTS.get(result, "no answer") if result is not None
                else "no answer", self._why()))
        self.log("mode %s" % name)

    def _arm(self, force=False):
        result = [None]

        def attempt():
            result[0] = self.client.command(400, (1, 21196 if force else 0), timeout=1.0, tries=1)

        self._until("arming", lambda: result[0] == 0, every_s=2.0, action=attempt,
                    sim_timeout_s=90.0)
        self.log("armed%s at %.1f s" % (" (forced: no GPS)" if force else "", self._clock()))

    def _rc(self, throttle):
        self.client.send("RC_CHANNELS_OVERRIDE", target_system=1, target_component=1,
                         chan1_raw=1500, chan2_raw=1500, chan3_raw=throttle, chan4_raw=1500)

    def _release_rc(self):
        self.client.send("RC_CHANNELS_OVERRIDE", target_system=1, target_component=1)

    def height(self):
        """The autopilot's own height above home (barometric), or None: ArduPilot's
        GLOBAL_POSITION_INT relative_alt; PX4 sends none without GPS, so its VFR_HUD
        altitude less the one read on the ground."""
        if self.kind == "px4":
            v = self.client.last.get("VFR_HUD")
            if v is None:
                return None
            if self.ground_alt is None:
                self.ground_alt = v.get("alt")
            return v.get("alt") - self.ground_alt
        g = self.client.last.get("GLOBAL_POSITION_INT")
        return None if g is None else g.get("relative_alt") / 1000.0

    def _attitude_target(self, thrust, yaw=None, q=None):
        if q is None:
            q = (1.0, 0.0, 0.0, 0.0) if yaw is None else (
                math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))
        self.client.send("SET_ATTITUDE_TARGET", target_system=1, target_component=1,
                         type_mask=7, q=q, thrust=thrust)

    # --- the flight ---
    def take_off(self):
        c = self.client
        if c.wait("HEARTBEAT", self.wall_timeout_s) is None:
            raise SitlError("the SITL never sent a heartbeat in %.0f s" % self.wall_timeout_s)
        for msgid, hz in ((30, 10), (33, 4), (74, 4)):  # ATTITUDE, GLOBAL_POSITION_INT, VFR_HUD
            c.set_interval(msgid, hz)
        above = lambda: (self.height() or 0.0) >= self.altitude_m - 1.0
        if self.vehicle == "arducopter":
            self._set_mode("ALT_HOLD")
            self._arm()
            self._until("climbing to %.0f m" % self.altitude_m, above,
                        action=lambda: self._rc(1800), sim_timeout_s=180.0)
            self._rc(1500)
            self._set_mode("GUIDED_NOGPS")
            self._release_rc()
            if self.cruise_pitch_deg:
                self._copter_to_speed()
        elif self.vehicle == "arduplane":
            # Forced at once, the plane took off before its attitude had settled and
            # flew into the ground: 20 s on the autopilot's clock first.
            self._until("letting the attitude settle", lambda: self._clock() >= 20.0)
            self._set_mode("FLY_BY_WIRE_A")
            self._arm(force=True)
            self._until("climbing to %.0f m" % self.altitude_m, above,
                        action=lambda: self._rc(2000), sim_timeout_s=240.0)
            self._set_mode("GUIDED")
            self._release_rc()
            self._settle_plane()
        else:
            hold = lambda: self._attitude_target(0.75)
            # PX4 enters OFFBOARD only once a setpoint stream runs: stream for 1 s first.
            self._until("waiting for the clock and the barometer",
                        lambda: self._clock() is not None and self.height() is not None)
            t0 = self._clock()
            self._until("starting the setpoint stream", lambda: self._clock() - t0 >= 1.0,
                        action=hold)
            self._set_mode("OFFBOARD")
            self._arm(force=True)
            self._until("climbing to %.0f m" % self.altitude_m, above, action=hold,
                        sim_timeout_s=120.0)
            # Until the link's own stream runs, PX4 must not miss its setpoints (or its
            # offboard-loss failsafe lands it): a thread streams hover thrust.
            self._hovering = True
            self._hover_thread = threading.Thread(target=self._hover, daemon=True)
            self._hover_thread.start()
        self.log("at %.1f m, handed over in %s at %.1f s" % (
            self.height() or 0.0, self.proc.spec["mode"], self._clock()))

    def _settle_plane(self):
        """Out of its full-throttle climb the plane is some 8 m/s over its cruise, and
        in GUIDED alone it would circle. Hand it over as a pilot would, from steady
        cruise: hold the heading it has until its airspeed has settled (within
        SETTLED_MPS over SETTLED_S of the autopilot's clock)."""
        hud = self.client.last.get("VFR_HUD")
        heading = float(hud.get("heading")) if hud is not None else 0.0
        self.client.send("COMMAND_INT", target_system=1, target_component=1, frame=0,
                         command=43002, param1=1.0, param2=heading, param3=6.0)
        speeds = []

        def settled():
            v = self.client.last.get("VFR_HUD")
            if v is None or self._clock() is None:
                return False
            speeds.append((self._clock(), float(v.get("airspeed"))))
            while speeds and speeds[0][0] < speeds[-1][0] - SETTLED_S:
                speeds.pop(0)
            recent = [a for _, a in speeds]
            return (speeds[-1][0] - speeds[0][0] >= 0.9 * SETTLED_S
                    and max(recent) - min(recent) <= SETTLED_MPS)

        t0 = self._clock()
        self._until("settling to cruise", settled, sim_timeout_s=90.0)
        self.log("at cruise, %.1f m/s, after %.1f s" % (speeds[-1][1], self._clock() - t0))

    def _copter_to_speed(self):
        """A hover drifts with the wind and a seek would begin at no airspeed: hand over
        as from the seek's own flight, pitched forward on the current yaw for
        COPTER_SPEED_UP_S of the autopilot's clock (the streaming thread holds it until
        the link streams its own)."""
        att = self.client.last.get("ATTITUDE")
        yaw = float(att.get("yaw")) if att is not None else 0.0
        pitch = -math.radians(self.cruise_pitch_deg)  # nose down
        cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
        cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
        self._q = (cp * cy, -sp * sy, sp * cy, cp * sy)
        self._hovering = True
        self._hover_thread = threading.Thread(target=self._hover, daemon=True)
        self._hover_thread.start()
        t0 = self._clock()
        self._until("getting up to speed", lambda: self._clock() - t0 >= COPTER_SPEED_UP_S)

    def _hover(self):
        while self._hovering and self.proc.alive():
            try:
                self._attitude_target(self.hover_thrust, q=self._q)
            except (OSError, SitlError):
                return
            time.sleep(0.05 / self.proc.speedup)

    def keep_streaming(self, until):
        """The pilot's setpoints (PX4's hover, ArduCopter's forward flight) go on until
        until() (the link streams its own); nothing to do if none are streamed."""
        if not self._hovering:
            return
        try:
            self._until("handing over to the link", until, sim_timeout_s=30.0)
        finally:
            self.stop_hovering()

    def stop_hovering(self):
        self._hovering = False
        if self._hover_thread is not None:
            self._hover_thread.join(timeout=1.0)
            self._hover_thread = None

    def watch(self):
        """Read what the autopilot sent (keeps its buffers drained); the latest height."""
        self.client.poll(0.0)
        return self.height()

    def close(self):
        self.stop_hovering()
        self.client.close()
