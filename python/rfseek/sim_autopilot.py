#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""sim_autopilot: the simulated world's vehicle behind a MAVLink endpoint, for rehearsing a
flight over real MAVLink datagrams (docs/live.md "Autopilot").

It speaks as an ArduPlane, ArduCopter or PX4 autopilot (system 1, component 1): HEARTBEAT
at 1 Hz with its mode and armed state, ATTITUDE at 20 Hz (the yaw of the world's measured
heading: the autopilot's compass; with declination_deg, a magnetic one that never learnt
the declination, as without GPS), VFR_HUD at 4 Hz, SYS_STATUS at 1 Hz and
GLOBAL_POSITION_INT at 2 Hz (the world's position about a reference point: a GPS the
seeker must never use). It obeys the same command paths the link uses: SET_MODE,
MAV_CMD_DO_SET_MODE (PX4: OFFBOARD only with a setpoint stream running),
MAV_CMD_COMPONENT_ARM_DISARM, MAV_CMD_SET_MESSAGE_INTERVAL (acknowledged; its rates are
fixed), MAV_CMD_GUIDED_CHANGE_HEADING as COMMAND_LONG or COMMAND_INT (denied unless armed
in GUIDED with a heading in [0, 360) and a positive acceleration; the acceleration does
not shape the simulated turn, which is the world's turn model) and
MAV_CMD_DO_CHANGE_SPEED for the plane, SET_ATTITUDE_TARGET in GUIDED_NOGPS / OFFBOARD
for the copters. Acks are addressed to the sender. A heading it accepts goes
out on "cmd" to channel_source, whose turn model flies it; "state" in is channel_source's.

For tests it can be disarmed, switched out of mode, silenced (a lost link) and told to
ignore commands (no acks).
"""

import math
import numbers
import select
import threading
import time

import pmt
from gnuradio import gr

from . import rfseek_python as _core
from .autopilot_link import mavlink_transport

_mav = _core.mavlink
_CUSTOM_MODE_ENABLED, _ARMED = 1, 128
_ACCEPTED, _DENIED, _UNSUPPORTED = 0, 2, 3
_TYPES = {"ardupilot_plane": (1, 3), "ardupilot_copter": (2, 3), "px4": (2, 12)}


class sim_autopilot(gr.basic_block):
    """Message block: "state" in (channel_source) and "cmd" out (to channel_source), with
    a MAVLink autopilot on `link` (see autopilot_link for the transport syntax).
    time_scale: its telemetry rates run that many times faster, for a rehearsal paced
    at that speed-up (give autopilot_link the same)."""

    def __init__(self, link="udpout:127.0.0.1:14550", family="ardupilot_plane", mode="",
                 armed=True, airspeed_mps=10.0, ref_lat_deg=47.0, ref_lon_deg=8.0,
                 time_scale=1.0, declination_deg=0.0):
        gr.basic_block.__init__(self, name="sim_autopilot", in_sig=None, out_sig=None)
        if family not in _TYPES:
            raise ValueError("sim_autopilot: family = %r: must be ardupilot_plane, "
                             "ardupilot_copter or px4" % (family,))
        if not (isinstance(time_scale, (int, float)) and 1.0 <= time_scale <= 100.0):
            raise ValueError("sim_autopilot: time_scale = %r: must be in [1, 100]"
                             % (time_scale,))
        for name, value, lo, hi, what in (
                ("airspeed_mps", airspeed_mps, 0.0, 100.0, "[0, 100] m/s"),
                ("ref_lat_deg", ref_lat_deg, -89.0, 89.0,
                 "[-89, 89] deg (the local frame's origin; not at a pole)"),
                ("ref_lon_deg", ref_lon_deg, -180.0, 180.0, "[-180, 180] deg"),
                ("declination_deg", declination_deg, -180.0, 180.0,
                 "[-180, 180] deg east of true north")):
            if not (isinstance(value, numbers.Real) and lo <= value <= hi):
                raise ValueError("sim_autopilot: %s = %r: must be in %s" % (name, value, what))
        self.time_scale = float(time_scale)
        self.family = family
        self.mode_name = mode or _core.autopilot_default_mode(family)
        self.custom_mode = _core.autopilot_mode_number(family, self.mode_name)
        self._guided = self.custom_mode
        self.armed = bool(armed)
        self.airspeed = float(airspeed_mps)
        self.ref = (math.radians(ref_lat_deg), math.radians(ref_lon_deg))
        # A compass that never learnt the declination (no GPS): it reads and flies
        # magnetic headings, true ones turned by -declination (counter-clockwise).
        self.declination = math.radians(declination_deg)
        self.transport = mavlink_transport(link, "sim_autopilot")
        self.parser = _mav.parser()
        self.silent = False
        self.ignore_commands = False
        self.received = []   # (monotonic time, message name, fields) of what it obeyed
        self.arrivals = []   # (monotonic time, message name) of every frame, even silent
        self.headings = []   # (monotonic time, heading rad) it passed to the world
        self._state = None
        self._last_setpoint = -1e300
        self._seq = 0
        self._lock = threading.Lock()
        self._running = False
        self._thread = None
        self._t0 = time.monotonic()
        self.message_port_register_in(pmt.intern("state"))
        self.message_port_register_out(pmt.intern("cmd"))
        self.set_msg_handler(pmt.intern("state"), self._on_state)

    # --- controls for rehearsals and tests ---
    def set_armed(self, armed):
        self.armed = bool(armed)

    def set_mode(self, mode):
        """Switch to a mode of the family by name ('': its seeking mode)."""
        mode = mode or _core.autopilot_default_mode(self.family)
        self.custom_mode = _core.autopilot_mode_number(self.family, mode)
        self.mode_name = mode

    def set_silent(self, silent):
        """Stop (True) or resume (False) sending and obeying anything: a lost link. What
        arrives meanwhile is still noted in `arrivals`."""
        self.silent = bool(silent)

    def local_address(self):
        return self.transport.local

    # --- the world ---
    def _on_state(self, msg):
        try:
            d = pmt.to_python(msg)
            if isinstance(d, dict) and "measured_heading" in d:
                with self._lock:
                    self._state = d
        except (TypeError, ValueError):
            pass

    def _fly(self, theta):
        theta = math.remainder(theta - self.declination, 2 * math.pi)  # magnetic -> true
        self.headings.append((time.monotonic(), theta))
        self.message_port_pub(pmt.intern("cmd"), pmt.to_pmt({"heading": float(theta)}))

    # --- MAVLink ---
    def _send(self, msg):
        if self.silent:
            return
        frame = _mav.encode(msg, _mav.header(self._seq % 256, 1, 1))
        self._seq += 1
        try:
            self.transport.send(frame)
        except OSError:
            pass

    def _ack(self, command, result, to=(0, 0)):
        m = _mav.message("COMMAND_ACK")
        m.set("command", command)
        m.set("result", result)
        m.set("target_system", to[0])
        m.set("target_component", to[1])
        self._send(m)

    def _may_enter(self, custom_mode):
        # PX4 enters OFFBOARD only with a setpoint stream already running.
        return not (self.family == "px4" and custom_mode == self._guided and
                    time.monotonic() - self._last_setpoint > 0.5 / self.time_scale)

    def _in_guided(self):
        return self.armed and self.custom_mode == self._guided

    def _handle(self, msg, sender):
        name = msg.name
        self.received.append((time.monotonic(), name, msg.fields()))
        if self.ignore_commands or name == "HEARTBEAT":
            return
        if name == "SET_MODE":
            if self._may_enter(int(msg.get("custom_mode"))):
                self.custom_mode = int(msg.get("custom_mode"))
        elif name in ("COMMAND_LONG", "COMMAND_INT"):
            cmd = int(msg.get("command"))
            p = [msg.get("param%d" % i) for i in range(1, 5)]
            if cmd == 176:  # MAV_CMD_DO_SET_MODE
                ok = self._may_enter(int(p[1]))
                if ok:
                    self.custom_mode = int(p[1])
                self._ack(cmd, _ACCEPTED if ok else _DENIED, sender)
            elif cmd == 400:  # MAV_CMD_COMPONENT_ARM_DISARM
                self.armed = p[0] > 0.5
                self._ack(cmd, _ACCEPTED, sender)
            elif cmd == 511:  # MAV_CMD_SET_MESSAGE_INTERVAL: its rates are fixed
                self._ack(cmd, _ACCEPTED, sender)
            elif cmd == 43002 and self.family == "ardupilot_plane":
                # As ArduPlane: param2 in [0, 360), param3 the centripetal acceleration.
                if not self._in_guided() or not 0 <= p[1] < 360 or not p[2] > 0:
                    self._ack(cmd, _DENIED, sender)
                else:
                    self._ack(cmd, _ACCEPTED, sender)
                    self._fly(math.pi / 2 - math.radians(p[1]))
            elif cmd == 178:  # MAV_CMD_DO_CHANGE_SPEED
                if p[1] > 0:
                    self.airspeed = p[1]
                self._ack(cmd, _ACCEPTED if self._in_guided() else _DENIED, sender)
            else:
                self._ack(cmd, _UNSUPPORTED, sender)
        elif name == "SET_ATTITUDE_TARGET" and self.family != "ardupilot_plane":
            self._last_setpoint = time.monotonic()
            if self._in_guided():
                w, x, y, z = (msg.get("q", i) for i in range(4))
                yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
                self._fly(math.pi / 2 - yaw)

    def _telemetry(self, k):
        """Messages due at tick k (100 Hz)."""
        now_ms = int((time.monotonic() - self._t0) * 1000 * self.time_scale) % 4294967296
        with self._lock:
            st = self._state
        vtype, autopilot = _TYPES[self.family]
        if k % 100 == 0:
            m = _mav.message("HEARTBEAT")
            m.set("type", vtype)
            m.set("autopilot", autopilot)
            m.set("base_mode", _CUSTOM_MODE_ENABLED | (_ARMED if self.armed else 0))
            m.set("custom_mode", self.custom_mode)
            m.set("system_status", 4)
            m.set("mavlink_version", 3)
            self._send(m)
            s = _mav.message("SYS_STATUS")
            s.set("voltage_battery", 12600)
            s.set("battery_remaining", 80)
            self._send(s)
        if st is None:
            return
        magnetic = float(st["measured_heading"]) + self.declination  # what its compass reads
        if k % 5 == 0:
            m = _mav.message("ATTITUDE")
            m.set("time_boot_ms", now_ms)
            m.set("yaw", math.remainder(math.pi / 2 - magnetic, 2 * math.pi))
            self._send(m)
        if k % 25 == 0:
            m = _mav.message("VFR_HUD")
            m.set("airspeed", self.airspeed)
            m.set("groundspeed", self.airspeed)
            compass = (90.0 - math.degrees(magnetic)) % 360.0
            m.set("heading", int(compass) % 360)
            m.set("throttle", 50)
            self._send(m)
        if k % 50 == 0:
            m = _mav.message("GLOBAL_POSITION_INT")
            lat = self.ref[0] + float(st["y"]) / 6371000.0
            lon = self.ref[1] + float(st["x"]) / (6371000.0 * math.cos(self.ref[0]))
            m.set("time_boot_ms", now_ms)
            m.set_int("lat", int(math.degrees(lat) * 1e7))
            m.set_int("lon", int(math.degrees(lon) * 1e7))
            self._send(m)

    def start(self):
        self._running = True
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()
        return True

    def _run(self):
        fd = self.transport.fileno()
        k = 0
        next_tick = time.monotonic()
        while self._running:
            timeout = max(0.0, next_tick - time.monotonic())
            try:
                ready, _, _ = select.select([fd], [], [], timeout)
            except (OSError, ValueError):
                break
            if ready:
                data, addr = self.transport.recv()
                self.transport.answer(addr)
                for f in self.parser.push(data):
                    if not f.known():
                        continue
                    msg = f.decode()
                    self.arrivals.append((time.monotonic(), msg.name))
                    if not self.silent:
                        self._handle(msg, (f.sysid, f.compid))
            if time.monotonic() >= next_tick:
                self._telemetry(k)
                k += 1
                next_tick += 0.01 / self.time_scale

    def stop(self):
        self._running = False
        if self._thread is not None:
            self._thread.join(timeout=1.0)
        return True

    def close(self):
        self.stop()
        self.transport.close()
