#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""autopilot_link: the seeking controller's link to an ArduPilot or PX4 autopilot over
MAVLink 2 (docs/live.md "Autopilot"). A drop-in for vehicle_bridge: "cmd" in (from
seeking_controller), "nav" out ({heading, time, airspeed}), plus a "status" port.

The rules are the C++ core's (rfseek.autopilot_session): heartbeats both ways; commands
only while the autopilot is armed and in the named mode; the documented command path of
each family (ArduPlane: MAV_CMD_GUIDED_CHANGE_HEADING and MAV_CMD_DO_CHANGE_SPEED,
acknowledged and retried; ArduCopter GUIDED_NOGPS and PX4 OFFBOARD: attitude setpoints
streamed); no command once the link falls silent (link_timeout_s, 0.5 s by default);
reports of any other system or component dropped; position never passed on. This file
adds the transports and the telemetry log.

Transports (the `link` argument), as MAVLink tools name them:
  udpin:HOST:PORT      listen (a ground station or router sends to this port; replies go
                       to the last sender)
  udpout:HOST:PORT     send to HOST:PORT (the autopilot's or router's UDP port)
  tcp:HOST:PORT        connect to a TCP server (ArduPilot SITL's serial ports, 5760 +
                       10 x instance and up; MAVProxy's and mavlink-router's TCP ports)
  serial:DEVICE:BAUD   a telemetry radio or the autopilot's UART (raw 8N1)

tlog: when `tlog` names a file, every frame received and sent is written to it as the
usual MAVLink telemetry log (each frame preceded by its time, microseconds since
1970-01-01 as a big-endian uint64), which ground-station tools open for flight review.
"""

import math
import os
import select
import socket
import struct
import threading
import time

import pmt
from gnuradio import gr

from . import rfseek_python as _core

_BAUDS = (9600, 19200, 38400, 57600, 115200, 230400, 460800, 500000, 921600, 1500000)


def _msgid(frame):
    """The message id of a MAVLink frame (version 2: bytes 7-9; version 1: byte 5)."""
    if len(frame) >= 10 and frame[0] == 0xFD:
        return frame[7] | frame[8] << 8 | frame[9] << 16
    return frame[5] if len(frame) >= 6 and frame[0] == 0xFE else None


def _port(text, host, owner, spec):
    try:
        port = int(text)
    except ValueError:
        port = -1
    if not 0 <= port <= 65535 or not host:
        raise ValueError("%s: link = %r: the port must be an integer in [0, 65535] "
                         "after a host" % (owner, spec))
    return port


class mavlink_transport:
    """A byte pipe to an autopilot: udpin / udpout / serial (see the module doc)."""

    def __init__(self, spec, owner="autopilot_link", connect_timeout=5.0):
        if not isinstance(spec, str) or spec.count(":") < 2:
            raise ValueError("%s: link = %r: must be udpin:HOST:PORT, udpout:HOST:PORT, "
                             "tcp:HOST:PORT or serial:DEVICE:BAUD" % (owner, spec))
        kind, rest = spec.split(":", 1)
        where, _, last = rest.rpartition(":")
        self.kind = kind
        self.spec = spec
        self.peer = None
        self.sock = None
        self.fd = None
        if kind == "tcp":
            port = _port(last, where, owner, spec)
            try:
                self.sock = socket.create_connection((where, port), timeout=connect_timeout)
            except OSError as e:
                raise ConnectionError("%s: link %s: cannot connect: %s (is the autopilot "
                                      "or its simulator running there?)"
                                      % (owner, spec, e.strerror or e)) from None
            self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            self.sock.settimeout(2.0)  # sends block at most this long; reads are selected
            self.peer = (where, port)
            self.local = self.sock.getsockname()
        elif kind in ("udpin", "udpout"):
            port = _port(last, where, owner, spec)
            self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            if kind == "udpin":
                self.sock.bind((where, port))
            else:
                self.peer = (socket.gethostbyname(where), port)
                self.sock.bind(("0.0.0.0" if where not in ("127.0.0.1", "localhost")
                                else "127.0.0.1", 0))
            self.sock.setblocking(False)
            self.local = self.sock.getsockname()
        elif kind == "serial":
            import termios
            try:
                baud = int(last)
            except ValueError:
                baud = -1
            if baud not in _BAUDS:
                raise ValueError("%s: link = %r: the baud rate must be one of %s"
                                 % (owner, spec, ", ".join(map(str, _BAUDS))))
            try:
                self.fd = os.open(where, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
            except OSError as e:
                raise OSError(e.errno, "%s: serial device %s: %s" % (owner, where, e.strerror))
            try:
                attrs = termios.tcgetattr(self.fd)
            except termios.error as e:
                os.close(self.fd)
                raise OSError("%s: %s is not a serial device (%s)" % (owner, where, e))
            speed = getattr(termios, "B%d" % baud)
            attrs[0] = 0                                            # iflag: raw
            attrs[1] = 0                                            # oflag: raw
            attrs[2] = termios.CS8 | termios.CREAD | termios.CLOCAL  # 8N1
            attrs[3] = 0                                            # lflag: raw
            attrs[4] = attrs[5] = speed
            termios.tcsetattr(self.fd, termios.TCSANOW, attrs)
            self.local = where
        else:
            raise ValueError("%s: link = %r: the kind must be udpin, udpout, tcp or serial"
                             % (owner, spec))

    def fileno(self):
        return self.sock.fileno() if self.sock is not None else self.fd

    def recv(self):
        """(bytes waiting or b'', the sender's address or None)."""
        try:
            if self.kind == "tcp":
                data = self.sock.recv(65536)
                if not data:
                    raise ConnectionError("%s: closed by the other end" % self.spec)
                return data, None
            if self.sock is not None:
                return self.sock.recvfrom(65536)
            return os.read(self.fd, 4096), None
        except (BlockingIOError, InterruptedError, socket.timeout):
            return b"", None

    def answer(self, addr):
        """udpin: reply to addr from now on (a sender the autopilot's frames came from)."""
        if self.kind == "udpin" and addr is not None:
            self.peer = addr

    def send(self, data):
        if self.kind == "tcp":
            self.sock.sendall(data)
        elif self.sock is not None:
            if self.peer is None:
                return False  # udpin: nobody has spoken yet
            self.sock.sendto(data, self.peer)
        else:
            os.write(self.fd, data)
        return True

    def close(self):
        if self.sock is not None:
            self.sock.close()
        elif self.fd is not None:
            os.close(self.fd)


class tlog_writer:
    """A MAVLink telemetry log: per frame, microseconds since 1970 (big-endian uint64),
    then the frame's bytes."""

    def __init__(self, path):
        self.f = open(path, "wb")
        self.frames = 0

    def write(self, unix_time, frame):
        self.f.write(struct.pack(">Q", int(unix_time * 1e6)) + frame)
        self.frames += 1

    def close(self):
        self.f.close()


def read_tlog(path):
    """The (unix time, frame bytes) entries of a .tlog (as tlog_writer writes it)."""
    with open(path, "rb") as f:
        data = f.read()
    out = []
    i = 0
    while i + 11 <= len(data):
        stamp = struct.unpack(">Q", data[i:i + 8])[0] / 1e6
        head = data[i + 8:i + 11]
        if head[0] == 0xFD:
            n = 10 + head[1] + 2 + (13 if head[2] & 1 else 0)
        elif head[0] == 0xFE:
            n = 6 + head[1] + 2
        else:
            raise ValueError("%s: not a MAVLink telemetry log (byte %d)" % (path, i + 8))
        out.append((stamp, data[i + 8:i + 8 + n]))
        i += 8 + n
    return out


class autopilot_link(gr.basic_block):
    """Message block: "cmd" in (seeking_controller's headings) -> MAVLink to the autopilot;
    its ATTITUDE -> "nav" out {heading, time, airspeed}; "status" out at every change
    {state, reason, armed, custom_mode, in_mode, heartbeats, commands_*, retries, foreign,
    link}. States: connecting, holding (linked but not commanding: not armed, another
    mode, no command yet), commanding, lost. time_scale > 1 runs the link's clock (rates,
    timeouts) that many times faster, for a rehearsal paced faster than real time
    against sim_autopilot with the same time_scale. declination_deg: the site's magnetic
    declination (deg east of true north): nav headings are turned from the autopilot's
    (magnetic, without GPS) to true north and commands back (0: the autopilot's frame)."""

    def __init__(self, link="udpin:127.0.0.1:14550", family="ardupilot_plane", mode="",
                 target_system=1, target_component=1, own_system=1, own_component=191,
                 airspeed_mps=0.0, link_timeout_s=0.5, ack_timeout_s=0.3, retries=3,
                 signing_key="", tlog="", time_scale=1.0, heading_accel_mps2=6.0,
                 pitch_deg=5.0, thrust=0.5, command_timeout_s=2.0, turn_bank_deg=0.0,
                 turn_speed_mps=0.0, hold_altitude=False, clock="host",
                 declination_deg=0.0):
        gr.basic_block.__init__(self, name="autopilot_link", in_sig=None, out_sig=None)
        cfg = _core.autopilot_config()
        try:
            cfg.family = family
        except ValueError as e:
            raise ValueError("autopilot_link: family = %r: %s" % (family, e))
        cfg.mode = mode
        for name, value in (("target_system", target_system),
                            ("target_component", target_component),
                            ("own_system", own_system), ("own_component", own_component)):
            if not isinstance(value, int) or not 1 <= value <= 255:
                raise ValueError("autopilot_link: %s = %r: must be an integer in [1, 255]"
                                 % (name, value))
            setattr(cfg, name, value)
        cfg.airspeed_mps = float(airspeed_mps)
        cfg.link_timeout_s = float(link_timeout_s)
        cfg.ack_timeout_s = float(ack_timeout_s)
        if not isinstance(retries, int):
            raise ValueError("autopilot_link: retries = %r: must be an integer in [0, 10]"
                             % (retries,))
        cfg.retries = retries
        cfg.heading_accel_mps2 = float(heading_accel_mps2)
        cfg.pitch_deg = float(pitch_deg)
        cfg.thrust = float(thrust)
        cfg.turn_bank_deg = float(turn_bank_deg)
        cfg.turn_speed_mps = float(turn_speed_mps)
        cfg.hold_altitude = bool(hold_altitude)
        cfg.declination_deg = float(declination_deg)
        cfg.command_timeout_s = float(command_timeout_s)
        if signing_key:
            try:
                key = bytes.fromhex(signing_key)
            except ValueError:
                key = b""
            if len(key) != 32:
                raise ValueError("autopilot_link: signing_key: must be 64 hex digits (a "
                                 "32-byte key), or empty for no signing")
            if time_scale != 1.0:
                raise ValueError("autopilot_link: signing_key with time_scale = %r: signing "
                                 "needs the real clock (time_scale 1)" % (time_scale,))
            cfg.signing_key = key
            cfg.signing_clock_offset_s = time.time() - 1420070400.0 - time.monotonic()
        cfg.validate()
        if not (isinstance(time_scale, (int, float)) and 1.0 <= time_scale <= 100.0):
            raise ValueError("autopilot_link: time_scale = %r: must be in [1, 100] (1 on a "
                             "real flight)" % (time_scale,))
        self.time_scale = float(time_scale)
        if clock not in ("host", "autopilot"):
            raise ValueError("autopilot_link: clock = %r: must be 'host' (a flight) or "
                             "'autopilot' (a rehearsal against a simulator)" % (clock,))
        self.clock = clock
        self._t = None           # the link's time so far (the autopilot clock)
        self._ap_offset = None   # autopilot clock minus the link's, at its first ATTITUDE
        self.config = cfg
        self.session = _core.autopilot_session(cfg)
        self.tlog = tlog_writer(tlog) if tlog else None
        try:
            self.transport = mavlink_transport(link)
        except (OSError, ValueError):
            if self.tlog is not None:
                self.tlog.close()
            raise
        self.message_port_register_in(pmt.intern("cmd"))
        self.message_port_register_out(pmt.intern("nav"))
        self.message_port_register_out(pmt.intern("status"))
        self.set_msg_handler(pmt.intern("cmd"), self.handle_cmd)
        self.dropped = {"cmd": 0}
        self.nav_count = 0
        self.statuses = []
        self._logged = set()
        self._control_sent_s = None  # see control_sent_s()
        self._lock = threading.Lock()
        self._running = False
        self._thread = None

    def _now(self):
        # The link's clock: real time, or faster in a rehearsal paced at time_scale x.
        host = time.monotonic() * self.time_scale
        if self.clock == "host":
            return host
        # clock "autopilot": host time until the autopilot's first ATTITUDE, then its
        # clock (time_boot_ms), carried on by host time at time_scale between its
        # frames and never going back: rates and timeouts keep their meaning on a
        # simulator that runs slower or faster than asked.
        ap = self.session.autopilot_time()
        t = host
        if ap is not None:
            if self._ap_offset is None:
                self._ap_offset = ap - (self._t if self._t is not None else host)
                self._ap_at = (ap, host)
            elif ap != self._ap_at[0]:
                self._ap_at = (ap, host)
            t = self._ap_at[0] - self._ap_offset + (host - self._ap_at[1])
        self._t = t if self._t is None else max(self._t, t)
        return self._t

    def handle_cmd(self, msg):
        try:
            d = pmt.to_python(msg)
            theta = float(d["heading"])
            if not math.isfinite(theta):
                raise ValueError
        except (KeyError, TypeError, ValueError, AttributeError):
            self.dropped["cmd"] += 1
            if "cmd" not in self._logged:
                self._logged.add("cmd")
                self.logger.warn("cmd message dropped (no finite 'heading'): %s (further "
                                 "ones are counted silently)" % pmt.write_string(msg))
            return
        with self._lock:
            if d.get("done") is True:
                # The controller is done (arrived and located, or gave up): the autopilot
                # keeps its last command; the link commands no more.
                self.session.finish(self._now())
            else:
                self.session.command(theta, self._now())

    def start(self):
        self._running = True
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()
        return True

    def _run(self):
        fd = self.transport.fileno()
        t_start, wall_start = self._now(), time.time()
        while self._running:
            try:
                ready, _, _ = select.select([fd], [], [], max(0.001, 0.01 / self.time_scale))
            except (OSError, ValueError):
                break
            try:
                data, addr = self.transport.recv() if ready else (b"", None)
            except OSError as e:
                # A serial device unplugged, a network gone: say so once, keep polling
                # (the link goes to "lost"), and do not spin.
                if "recv" not in self._logged:
                    self._logged.add("recv")
                    self.logger.error("cannot read %s: %s" % (self.transport.spec, e))
                data, addr = b"", None
                time.sleep(0.1)
            if ready and not data and self.transport.sock is None:
                time.sleep(0.01)  # a serial device at end of file: readable, empty
            with self._lock:
                t = self._now()
                if data:
                    before = self.session.status()["frames"]
                    self.session.receive(data, t)
                    # udpin: answer only a sender that the autopilot's frames came from.
                    if self.session.status()["frames"] > before:
                        self.transport.answer(addr)
                frames = self.session.poll(t)
                navs = self.session.take_nav()
                statuses = self.session.take_status()
                log = self.session.take_log()
            for f in frames:
                try:
                    self.transport.send(f)
                    if _msgid(f) != 0:  # not a HEARTBEAT: a setpoint or a command
                        self._control_sent_s = t + (self._ap_offset or 0.0)
                except OSError as e:
                    if "send" not in self._logged:
                        self._logged.add("send")
                        self.logger.warn("cannot send on %s: %s" % (self.transport.spec, e))
            for n in navs:
                self.nav_count += 1
                self.message_port_pub(pmt.intern("nav"), pmt.to_pmt(n))
            for s in statuses:
                s["link"] = self.transport.spec
                self.statuses.append(s)
                if s["reason"]:
                    self.logger.warn("autopilot link %s: %s" % (s["state"], s["reason"]))
                else:
                    self.logger.info("autopilot link: %s" % s["state"])
                self.message_port_pub(pmt.intern("status"), pmt.to_pmt(s))
            if self.tlog is not None:
                for when, frame in log:
                    self.tlog.write(wall_start + (when - t_start) / self.time_scale, frame)

    def set_airspeed(self, airspeed_mps):
        """A new commanded airspeed (m/s; 0: the autopilot's own), sent when commanding."""
        with self._lock:
            self.session.set_airspeed(float(airspeed_mps))

    def control_sent_s(self):
        """When the link last sent the autopilot a frame other than a heartbeat (a
        setpoint or a command), on the autopilot's clock (time_boot, s) with clock
        "autopilot", else the host's; None before the first. A rehearsal times the
        firmware's response to a command from it, not from when the command was given."""
        with self._lock:
            return self._control_sent_s

    def status(self):
        """The link's current status (a dict, as on the status port)."""
        with self._lock:
            return self.session.status()

    def parser_stats(self):
        with self._lock:
            return self.session.parser_stats()

    def local_address(self):
        """The transport's local (host, port), or the serial device."""
        return self.transport.local

    def stop(self):
        self._running = False
        if self._thread is not None:
            self._thread.join(timeout=1.0)
        if self.tlog is not None:
            self.tlog.f.flush()
        return True

    def close(self):
        """Release the socket or device and the log (after stop)."""
        self.stop()
        self.transport.close()
        if self.tlog is not None:
            self.tlog.close()
