#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""vehicle_bridge: the seeking controller's link to a vehicle's autopilot over UDP.

Datagrams are UTF-8 JSON objects, one per datagram:

  to the vehicle   {"type": "cmd", "seq": 17, "slot": 1234, "heading_deg": 271.5,
                    "stage": 2, "time": 61.7}
  from the vehicle {"type": "nav", "heading_deg": 270.9, "time": 61.72}

heading_deg is a compass heading: degrees clockwise from north, in [0, 360). The module
works in radians counter-clockwise from east; the bridge converts at this boundary:
theta = pi/2 - radians(heading_deg), heading_deg = (90 - degrees(theta)) mod 360.

The bridge binds to a local address (loopback by default), sends commands to the
configured peer and accepts reports only from that peer; foreign, oversized (more than
max_datagram bytes), too frequent (more than max_rate_hz reports per second, beyond a
burst of one second's worth), malformed or out-of-range datagrams are logged (once per
kind), counted and dropped. When reports stop
for nav_timeout seconds it logs it once and repeats the last command every second, so the
vehicle holds its course.
"""

import json
import math
import socket
import threading
import time

import pmt
from gnuradio import gr


def compass_deg_from_theta(theta):
    """Module angle (rad, CCW from east) -> compass heading (deg, CW from north)."""
    return (90.0 - math.degrees(theta)) % 360.0


def theta_from_compass_deg(heading_deg):
    """Compass heading (deg, CW from north) -> module angle (rad, CCW from east), (-pi, pi]."""
    t = math.pi / 2 - math.radians(heading_deg)
    return math.pi - ((math.pi - t) % (2.0 * math.pi))


def parse_nav(data):
    """(heading_deg, time) of a nav datagram (bytes, or str) {"type": "nav",
    "heading_deg": compass degrees in [0, 360), "time": optional}; ValueError saying
    what is wrong."""
    try:
        d = json.loads(data.decode("utf-8") if isinstance(data, (bytes, bytearray))
                       else data)
    except (UnicodeDecodeError, TypeError, ValueError):
        raise ValueError("not JSON")
    if not isinstance(d, dict) or d.get("type") != "nav":
        raise ValueError("not a nav object")
    h = d.get("heading_deg")
    if isinstance(h, bool) or not isinstance(h, (int, float)):
        raise ValueError("no numeric heading_deg")
    if not math.isfinite(h) or not 0.0 <= h < 360.0:
        raise ValueError("heading_deg out of [0, 360)")
    return float(h), d.get("time")


class vehicle_bridge(gr.basic_block):
    """Message block: "cmd" in (from seeking_controller) -> UDP to the vehicle; the
    vehicle's reports -> "nav" out (to seeking_controller), as {heading, time}."""

    def __init__(self, local_addr="127.0.0.1", local_port=14650, peer_addr="127.0.0.1",
                 peer_port=14651, nav_timeout=2.0, max_datagram=1024, max_rate_hz=50.0):
        gr.basic_block.__init__(self, name="vehicle_bridge", in_sig=None, out_sig=None)
        for name, port in (("local_port", local_port), ("peer_port", peer_port)):
            if not isinstance(port, int) or not 0 <= port <= 65535:
                raise ValueError("vehicle_bridge: %s = %r: must be an integer in [0, 65535]"
                                 % (name, port))
        if not nav_timeout > 0:
            raise ValueError("vehicle_bridge: nav_timeout = %r: must be > 0 s" % nav_timeout)
        if not isinstance(max_datagram, int) or not 64 <= max_datagram <= 65507:
            raise ValueError("vehicle_bridge: max_datagram = %r: must be an integer in "
                             "[64, 65507] bytes" % (max_datagram,))
        if not (isinstance(max_rate_hz, (int, float)) and 0 < max_rate_hz <= 10000):
            raise ValueError("vehicle_bridge: max_rate_hz = %r: must be in (0, 10000] "
                             "reports per second" % (max_rate_hz,))
        self.max_datagram = max_datagram
        self.max_rate_hz = float(max_rate_hz)
        self._tokens = self.max_rate_hz  # token bucket: a burst of one second's worth
        self.peer = (socket.gethostbyname(peer_addr), peer_port)
        self.nav_timeout = float(nav_timeout)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind((local_addr, local_port))
        self.sock.settimeout(0.05)
        self.local = self.sock.getsockname()
        self.message_port_register_in(pmt.intern("cmd"))
        self.message_port_register_out(pmt.intern("nav"))
        self.set_msg_handler(pmt.intern("cmd"), self.handle_cmd)
        self.sent = 0
        self.received = 0
        self.dropped = {"foreign": 0, "oversize": 0, "rate": 0, "malformed": 0, "cmd": 0}
        self._logged = set()
        self._seq = 0
        self._last_cmd = None
        self._last_nav = time.monotonic()
        self._stale = False
        self._lock = threading.Lock()
        self._running = True
        self._thread = threading.Thread(target=self._receive, daemon=True)
        self._thread.start()

    def _log_once(self, kind, text):
        if kind not in self._logged:
            self._logged.add(kind)
            self.logger.warn("%s (further ones are counted silently)" % text)

    def handle_cmd(self, msg):
        try:
            d = pmt.to_python(msg)
            theta = float(d["heading"])
            if not math.isfinite(theta):
                raise ValueError
        except (KeyError, TypeError, ValueError, AttributeError):
            self.dropped["cmd"] += 1
            self._log_once("cmd", "cmd message dropped: %s" % pmt.write_string(msg))
            return
        with self._lock:
            self._seq += 1
            out = {"type": "cmd", "seq": self._seq, "heading_deg": compass_deg_from_theta(theta)}
            for key in ("slot", "stage", "status", "time"):
                if isinstance(d.get(key), (int, float)) and not isinstance(d.get(key), bool):
                    out[key] = d[key]
            if isinstance(d.get("done"), bool):  # self arrival: the mission's end
                out["done"] = d["done"]
            self._last_cmd = json.dumps(out).encode("utf-8")
        self._send(self._last_cmd)

    def _send(self, data):
        try:
            self.sock.sendto(data, self.peer)
            self.sent += 1
        except OSError as e:
            self._log_once("send", "cannot send to %s:%d: %s" % (self.peer[0], self.peer[1], e))

    def _receive(self):
        last_repeat = 0.0
        last_refill = time.monotonic()
        while self._running:
            try:
                data, addr = self.sock.recvfrom(65536)
            except socket.timeout:
                data = None
            except OSError:
                break
            now = time.monotonic()
            self._tokens = min(self.max_rate_hz,
                               self._tokens + (now - last_refill) * self.max_rate_hz)
            last_refill = now
            if data is not None:
                if addr != self.peer:
                    self.dropped["foreign"] += 1
                    self._log_once("foreign", "datagram from %s:%d dropped: only %s:%d is "
                                   "accepted" % (addr[0], addr[1], self.peer[0], self.peer[1]))
                elif len(data) > self.max_datagram:
                    self.dropped["oversize"] += 1
                    self._log_once("oversize", "datagram of %d bytes dropped: at most %d are "
                                   "accepted" % (len(data), self.max_datagram))
                elif self._tokens < 1.0:
                    self.dropped["rate"] += 1
                    self._log_once("rate", "reports faster than %g per second: the excess "
                                   "is dropped" % self.max_rate_hz)
                else:
                    self._tokens -= 1.0
                    try:
                        heading_deg, t = parse_nav(data)
                    except ValueError as e:
                        self.dropped["malformed"] += 1
                        self._log_once("malformed", "nav datagram dropped (%s): %r" % (e, data[:80]))
                    else:
                        self.received += 1
                        self._last_nav = now
                        if self._stale:
                            self._stale = False
                            self.logger.info("vehicle reports resumed")
                        nav = {"heading": theta_from_compass_deg(heading_deg)}
                        if isinstance(t, (int, float)) and not isinstance(t, bool):
                            nav["time"] = float(t)
                        self.message_port_pub(pmt.intern("nav"), pmt.to_pmt(nav))
            if now - self._last_nav > self.nav_timeout:
                if not self._stale:
                    self._stale = True
                    self.logger.warn("no vehicle report for %.1f s: repeating the last command "
                                     "so the vehicle holds its course" % self.nav_timeout)
                with self._lock:
                    last = self._last_cmd
                if last is not None and now - last_repeat >= 1.0:
                    last_repeat = now
                    self._send(last)

    def stop(self):
        self._running = False
        self._thread.join(timeout=1.0)
        self.sock.close()
        return True


class loopback_vehicle:
    """A tiny simulated vehicle for tests and demos: listens for cmd datagrams and
    answers each with a nav report of its (instantly turned) compass heading, plus
    periodic reports every `period` seconds."""

    def __init__(self, addr="127.0.0.1", port=14651, bridge=("127.0.0.1", 14650),
                 heading_deg=0.0, period=0.1):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind((addr, port))
        self.sock.settimeout(0.02)
        self.bridge = bridge
        self.heading_deg = heading_deg
        self.period = period
        self.commands = []
        self.reporting = True
        self._running = True
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def report(self, payload=None):
        data = payload if payload is not None else json.dumps(
            {"type": "nav", "heading_deg": self.heading_deg, "time": time.time()}).encode()
        self.sock.sendto(data, self.bridge)

    def _run(self):
        last = 0.0
        while self._running:
            try:
                data, _ = self.sock.recvfrom(65536)
                d = json.loads(data.decode())
                if d.get("type") == "cmd":
                    self.commands.append(d)
                    self.heading_deg = float(d["heading_deg"]) % 360.0
                    if self.reporting:
                        self.report()
            except socket.timeout:
                pass
            except (OSError, ValueError, KeyError):
                if not self._running:
                    break
            now = time.monotonic()
            if self.reporting and now - last >= self.period:
                last = now
                try:
                    self.report()
                except OSError:
                    pass

    def close(self):
        self._running = False
        self._thread.join(timeout=1.0)
        self.sock.close()
