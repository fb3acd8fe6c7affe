#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Rehearsals against the real flight firmware: ArduPilot's (ArduCopter, ArduPlane) or
PX4's (SIH quad) software-in-the-loop build flies the vehicle, with the GPS off, and the
simulated world follows its true state (docs/sitl.md).

    find_sitl(path)      where the SITL builds are: the option, $RFSEEK_SITL, or the
                         source tree's ../shared/sitl
    sitl_process         one SITL binary in a scratch folder, on free ports, stopped on
                         exit, on errors and on Ctrl-C (with everything it started)
    mav_client           a small MAVLink client (the rehearsal's "pilot" and truth taps)
    truth_reader         the simulator's true state (SIM_STATE / HIL_STATE_QUATERNION),
                         for the world alone

Truth flows one way: the truth_reader's messages go to channel_source(follow_truth=True)
and to the scoring; the estimator, the controller and autopilot_link never see them.
"""

import atexit
import math
import os
import select
import shutil
import signal
import socket
import subprocess
import tempfile
import time

from . import rfseek_python as _core
from .autopilot_link import mavlink_transport

_mav = _core.mavlink

#: Where the firmware starts (ArduPilot's test site, CMAC): lat, lon (deg), altitude
#: (m above sea level), heading (deg). The emitter's ground is the home's height.
HOME = (-35.363261, 149.165230, 584.0, 353.0)
#: The magnetic declination at HOME (deg east of true north), as ArduPilot's own table
#: gives it there with GPS (COMPASS_DEC 0.2234 rad). Without GPS the firmware flies and
#: reports magnetic headings; the rehearsal tells the link this declination.
HOME_DECLINATION_DEG = 12.8
EARTH_RADIUS_M = 6378137.0

#: The vehicles: binary (relative to the SITL folder), how to start it, the link's
#: family and GPS-free mode.
VEHICLES = {
    "arducopter": {"kind": "ardupilot", "binary": "arducopter", "model": "quad",
                   "defaults": "copter.parm", "family": "ardupilot_copter",
                   "mode": "GUIDED_NOGPS"},
    "arduplane": {"kind": "ardupilot", "binary": "arduplane", "model": "plane",
                  "defaults": "plane.parm", "family": "ardupilot_plane", "mode": "GUIDED"},
    "px4_quad": {"kind": "px4", "binary": os.path.join("px4", "bin", "px4"),
                 "etc": os.path.join("px4", "etc"), "autostart": 10040,
                 "model": "sihsim_quadx", "family": "px4", "mode": "OFFBOARD"},
}

_ACK_RESULTS = {0: "accepted", 1: "temporarily rejected", 2: "denied", 3: "unsupported",
                4: "failed", 5: "in progress", 6: "cancelled"}


class SitlError(RuntimeError):
    """A rehearsal that cannot go on; its message is one line naming the cause."""


def find_sitl(path=None):
    """The folder of the SITL builds: `path`, else $RFSEEK_SITL, else ../shared/sitl
    beside the source tree this module was built from. SitlError if none is there."""
    tried = []
    for where, what in ((path, "the option"), (os.environ.get("RFSEEK_SITL"), "RFSEEK_SITL"),
                        (_source_tree_sitl(), "the source tree's ../shared/sitl")):
        if not where:
            continue
        tried.append("%s (%s)" % (where, what))
        if os.path.isdir(where):
            return os.path.abspath(where)
        if path:
            break  # an explicit folder that is not there is an error, not a fallback
    raise SitlError("no SITL folder: tried %s; give --sitl DIR or set RFSEEK_SITL"
                    % (", ".join(tried) or "nothing (no option, no RFSEEK_SITL, not run "
                       "from a source tree)"))


def _source_tree_sitl():
    try:
        from ._version import source_dir
    except ImportError:
        return None
    return os.path.join(os.path.dirname(source_dir), "shared", "sitl") if source_dir else None


def _port_free(port, kind):
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM if kind == "tcp" else socket.SOCK_DGRAM)
    if kind == "tcp":  # as a server binds: a port in TIME_WAIT is free to it
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        s.bind(("127.0.0.1", port))
        return True
    except OSError:
        return False
    finally:
        s.close()


try:  # loaded here: nothing is imported in a forked child
    import ctypes
    _LIBC = ctypes.CDLL(None, use_errno=True)
except OSError:
    _LIBC = None


def _child_of(parent):
    """preexec_fn: in the child, the kernel kills it when the thread that started it
    dies, even by SIGKILL (a test runner's timeout), so that no SITL is ever left
    behind. Start SITLs from the main thread."""
    def setup():
        if _LIBC is not None:
            _LIBC.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        if os.getppid() != parent:  # the parent died before prctl took effect
            os._exit(1)
    return setup


# Processes started by this interpreter and not yet stopped: stopped at exit.
_LIVE = set()


@atexit.register
def _stop_all():
    for p in list(_LIVE):
        p.stop()


class sitl_process:
    """One SITL binary of `vehicle` (a key of VEHICLES) from the folder `sitl_dir`, run in
    a scratch folder with the GPS off, `speedup` times faster than real time, with an
    optional SITL wind (speed m/s, the compass direction it blows from in degrees).

    ArduPilot: instance `instance` (None: the first whose ports are free) serves
    MAVLink on TCP 5760 + 10 i (the pilot), 5762 + 10 i (the truth) and 5763 + 10 i (the
    link). PX4 SIH: UDP, the pilot on 14550, the link on 14540, the truth on 19410
    (instance 0 only). stop() ends it and its children; so do exit, errors and Ctrl-C
    in the program that started it (use it as a context manager)."""

    def __init__(self, vehicle, sitl_dir=None, speedup=1.0, wind=None, instance=None,
                 home=HOME, keep=False, params=None):
        if vehicle not in VEHICLES:
            raise ValueError("vehicle = %r: must be one of %s" % (vehicle, ", ".join(VEHICLES)))
        self.vehicle = vehicle
        self.spec = VEHICLES[vehicle]
        self.dir = find_sitl(sitl_dir)
        if not (isinstance(speedup, (int, float)) and 1.0 <= speedup <= 100.0):
            raise ValueError("speedup = %r: must be in [1, 100]" % (speedup,))
        self.speedup = float(speedup)
        if wind is not None:
            speed, frm = wind
            if not (0.0 <= speed <= 30.0 and math.isfinite(frm)):
                raise ValueError("wind = %r: the speed must be in [0, 30] m/s and the "
                                 "direction finite (deg, where it blows from)" % (wind,))
        if wind is not None and self.spec["kind"] == "px4":
            raise ValueError("wind: not supported for %s (SITL wind is ArduPilot's "
                             "SIM_WIND_*)" % vehicle)
        self.wind = wind
        self.home = home
        self.keep = keep
        self.params = dict(params or {})
        self.instance = instance
        self.proc = None
        self.workdir = None
        binary = os.path.join(self.dir, self.spec["binary"])
        if not os.path.isfile(binary):
            raise SitlError("SITL binary %s: not found" % binary)
        if not os.access(binary, os.X_OK):
            raise SitlError("SITL binary %s: not executable" % binary)
        self.binary = binary

    # --- ports ---
    def _ports(self, i):
        if self.spec["kind"] == "ardupilot":
            return [("tcp", 5760 + 10 * i), ("tcp", 5762 + 10 * i), ("tcp", 5763 + 10 * i)]
        return [("udp", 14550), ("udp", 14540), ("udp", 19410), ("udp", 18570),
                ("udp", 14580), ("udp", 19450)]

    def _choose_instance(self):
        if self.spec["kind"] == "px4":
            if self.instance not in (None, 0):
                raise ValueError("instance = %r: PX4 SIH runs as instance 0 only"
                                 % (self.instance,))
            candidates = [0]
        else:
            candidates = [self.instance] if self.instance is not None else range(0, 20)
        for i in candidates:
            busy = [p for kind, p in self._ports(i) if not _port_free(p, kind)]
            if not busy:
                return i
            if self.instance is not None or self.spec["kind"] == "px4":
                raise SitlError("port %d already in use (another SITL or ground station?); "
                                "stop it%s" % (busy[0], "" if self.spec["kind"] == "px4"
                                                else " or choose another --instance"))
        raise SitlError("no free SITL instance: ports 5760-5953 are all in use")

    @property
    def pilot_link(self):
        if self.spec["kind"] == "ardupilot":
            return "tcp:127.0.0.1:%d" % (5760 + 10 * self.instance)
        return "udpin:127.0.0.1:14550"

    @property
    def truth_link(self):
        if self.spec["kind"] == "ardupilot":
            return "tcp:127.0.0.1:%d" % (5762 + 10 * self.instance)
        return "udpin:127.0.0.1:19410"

    @property
    def link(self):
        """The link for autopilot_link (a port of its own, as a companion computer's)."""
        if self.spec["kind"] == "ardupilot":
            return "tcp:127.0.0.1:%d" % (5763 + 10 * self.instance)
        return "udpin:127.0.0.1:14540"

    # --- life ---
    def start(self):
        self.instance = self._choose_instance()
        self.workdir = tempfile.mkdtemp(prefix="rfseek-sitl-%s-" % self.vehicle)
        try:
            self._launch()
        except BaseException:
            self.stop()  # the scratch folder too
            raise
        _LIVE.add(self)
        return self

    def _launch(self):
        env = dict(os.environ)
        # The firmware is not ours to sanitize: no ASan runtime preloaded into it (the
        # test suite's sanitizer job preloads one into Python).
        for k in ("LD_PRELOAD", "ASAN_OPTIONS", "UBSAN_OPTIONS"):
            env.pop(k, None)
        if self.spec["kind"] == "ardupilot":
            extra = os.path.join(self.workdir, "rfseek.parm")
            # The truth and the link on SERIAL1 and SERIAL2 at 921600 baud: ArduPilot
            # fits its streams to a port's baud rate (57600 by default), which would
            # thin SIM_STATE to about 12 Hz.
            params = {"SIM_GPS1_ENABLE": 0, "SERIAL1_BAUD": 921, "SERIAL2_BAUD": 921}
            if self.wind is not None:
                params.update(SIM_WIND_SPD=self.wind[0], SIM_WIND_DIR=self.wind[1] % 360.0)
            params.update(self.params)
            with open(extra, "w") as f:
                for k, v in params.items():
                    f.write("%s %s\n" % (k, v))
            lat, lon, alt, hdg = self.home
            cmd = [self.binary, "--model", self.spec["model"],
                   "--defaults", "%s,%s" % (os.path.join(self.dir, self.spec["defaults"]), extra),
                   "--home", "%.7f,%.7f,%.1f,%.0f" % (lat, lon, alt, hdg),
                   "--speedup", "%g" % self.speedup, "-I%d" % self.instance, "--wipe"]
        else:
            env.update(PX4_SYS_AUTOSTART=str(self.spec["autostart"]),
                       PX4_SIM_MODEL=self.spec["model"], PX4_PARAM_SENS_EN_GPSSIM="0",
                       PX4_PARAM_SYS_HAS_GPS="0", PX4_SIM_SPEED_FACTOR="%g" % self.speedup)
            lat, lon, alt, _ = self.home
            # SIH's own origin is its home: the truth's heights are above it.
            env.update(PX4_HOME_LAT="%.7f" % lat, PX4_HOME_LON="%.7f" % lon,
                       PX4_HOME_ALT="%.1f" % alt, PX4_PARAM_SIH_LOC_LAT0="%.7f" % lat,
                       PX4_PARAM_SIH_LOC_LON0="%.7f" % lon, PX4_PARAM_SIH_LOC_H0="%.1f" % alt)
            for k, v in self.params.items():
                env["PX4_PARAM_%s" % k] = str(v)
            # PX4's start-up scripts run its modules as px4-NAME, links to the px4
            # binary found on PATH. A copied build may hold them as small files naming
            # the target instead of links: the scratch folder gets links of its own.
            bin_dir = os.path.join(self.workdir, "bin")
            os.mkdir(bin_dir)
            src = os.path.dirname(self.binary)
            for name in os.listdir(src):
                path = os.path.join(src, name)
                if name == "px4" or (name.startswith("px4-") and os.path.getsize(path) <= 8):
                    os.symlink(self.binary, os.path.join(bin_dir, name))
                elif os.path.isfile(path):
                    shutil.copy(path, bin_dir)
            env["PATH"] = bin_dir + os.pathsep + env.get("PATH", "")
            cmd = [os.path.join(bin_dir, "px4"), "-d", os.path.join(self.dir, self.spec["etc"])]
        self.log_path = os.path.join(self.workdir, "sitl.log")
        log = open(self.log_path, "wb")
        try:
            self.proc = subprocess.Popen(cmd, cwd=self.workdir, env=env, stdout=log,
                                         stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                         start_new_session=True,
                                         preexec_fn=_child_of(os.getpid()))
        except OSError as e:
            raise SitlError("cannot start %s: %s" % (self.binary, e.strerror)) from None
        finally:
            log.close()

    def alive(self):
        return self.proc is not None and self.proc.poll() is None

    def log_tail(self, lines=5):
        try:
            with open(self.log_path, "rb") as f:
                return b"\n".join(f.read().splitlines()[-lines:]).decode(errors="replace")
        except OSError:
            return ""

    def stop(self):
        """Stop the firmware and every process of its session; remove the scratch folder
        (unless keep)."""
        if self.proc is not None and self.proc.poll() is None:
            for sig, wait in ((signal.SIGTERM, 3.0), (signal.SIGKILL, 3.0)):
                try:
                    os.killpg(self.proc.pid, sig)
                except ProcessLookupError:
                    break
                try:
                    self.proc.wait(wait)
                    break
                except subprocess.TimeoutExpired:
                    continue
        if self.proc is not None:
            try:  # anything left in its process group
                os.killpg(self.proc.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        _LIVE.discard(self)
        if self.workdir and not self.keep:
            shutil.rmtree(self.workdir, ignore_errors=True)
            self.workdir = None

    def __enter__(self):
        return self.start() if self.proc is None else self

    def __exit__(self, *exc):
        self.stop()
        return False


def lla_to_local(lat, lon, alt, home=HOME):
    """(east, north, up) in m of a point relative to `home` (a flat earth about it: the
    rehearsal's few km)."""
    lat0, lon0, alt0 = math.radians(home[0]), math.radians(home[1]), home[2]
    north = (math.radians(lat) - lat0) * EARTH_RADIUS_M
    east = (math.radians(lon) - lon0) * EARTH_RADIUS_M * math.cos(lat0)
    return east, north, alt - alt0


class mav_client:
    """A MAVLink client on `spec` (see autopilot_link's transports), speaking as a ground
    station (system 255, component 190) to the autopilot (system 1, component 1).
    Frames of any other system or component are ignored (the autopilot forwards the
    companion's heartbeat to its other ports)."""

    def __init__(self, spec, connect_timeout=10.0, sysid=255, compid=190):
        deadline = time.monotonic() + connect_timeout
        while True:
            try:
                self.transport = mavlink_transport(spec, "sitl", connect_timeout=1.0)
                break
            except ConnectionError:
                if time.monotonic() > deadline:
                    raise SitlError("%s: the SITL never accepted a connection in %.0f s"
                                    % (spec, connect_timeout)) from None
                time.sleep(0.1)
        self.parser = _mav.parser()
        self.hdr = (sysid, compid)
        self.seq = 0
        self.last = {}       # message name -> the latest message
        self.time_boot_ms = None
        self.text = []       # STATUSTEXT lines

    def send(self, name, **fields):
        m = _mav.message(name)
        for k, v in fields.items():
            if isinstance(v, (list, tuple)):
                for i, x in enumerate(v):
                    m.set(k, x, i)
            elif isinstance(v, str):
                m.set_text(k, v)
            else:
                m.set(k, v)
        try:
            self.transport.send(_mav.encode(m, _mav.header(self.seq % 256, *self.hdr)))
        except OSError as e:
            raise SitlError("%s: the SITL closed the connection (%s)" % (
                self.transport.spec, e)) from None
        self.seq += 1

    def poll(self, timeout=0.05):
        """Messages from the autopilot within `timeout` s (a list)."""
        out = []
        try:
            ready, _, _ = select.select([self.transport.fileno()], [], [], timeout)
            while ready:  # everything waiting (UDP: one datagram a read), not to lag
                data, addr = self.transport.recv()
                if not data:
                    break
                self._take(data, addr, out)
                ready, _, _ = select.select([self.transport.fileno()], [], [], 0)
        except (OSError, ValueError) as e:
            raise SitlError("%s: the SITL closed the connection (%s)%s" % (
                self.transport.spec, e, (" (it said: %s)" % self.text[-1])
                if self.text else "")) from None
        return out

    def _take(self, data, addr, out):
        for f in self.parser.push(data):
            if not f.known() or (f.sysid, f.compid) != (1, 1):
                continue
            self.transport.answer(addr)
            m = f.decode()
            self.last[m.name] = m
            if m.name == "ATTITUDE":
                # The simulated clock. (PX4's SYSTEM_TIME counts host time since boot,
                # not its lockstep clock: at a speed-up the two part.)
                self.time_boot_ms = int(m.get("time_boot_ms"))
            if m.name == "STATUSTEXT":
                self.text.append(m.get_text("text"))
            out.append(m)

    def wait(self, name, timeout, pred=None):
        """The next `name` (for which pred holds) within `timeout` s of wall time, or
        None."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            for m in self.poll(min(0.05, max(0.0, deadline - time.monotonic()))):
                if m.name == name and (pred is None or pred(m)):
                    return m
        return None

    def command(self, command, params=(), timeout=2.0, tries=3):
        """COMMAND_LONG; its COMMAND_ACK result (0: accepted), or None without an ack."""
        p = list(params) + [0.0] * (7 - len(params))
        for _ in range(tries):
            self.send("COMMAND_LONG", target_system=1, target_component=1, command=command,
                      **{"param%d" % (i + 1): p[i] for i in range(7)})
            ack = self.wait("COMMAND_ACK", timeout, lambda m: int(m.get("command")) == command)
            if ack is not None:
                return int(ack.get("result"))
        return None

    def set_interval(self, msgid, hz):
        return self.command(511, (msgid, 1e6 / hz))

    def close(self):
        self.transport.close()


def _quat_yaw(w, x, y, z):
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def _quat_roll(w, x, y, z):
    return math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))


class truth_reader:
    """The simulator's true state on its own MAVLink connection, as "truth" dicts for
    channel_source(follow_truth=True): ArduPilot's SIM_STATE (kind "ardupilot"), PX4
    SIH's HIL_STATE_QUATERNION ("px4"), each with the autopilot's clock from the
    ATTITUDE sent in the same stream. `link` is the truth's port (sitl_process's
    truth_link: ArduPilot tcp:127.0.0.1:5762 + 10 x instance, PX4 udpin:127.0.0.1:19410).
    Positions are east/north/up from `home` (the emitter's ground is the home's height);
    the heading is true, counter-clockwise from east; "reported_heading" is the
    autopilot's own (its ATTITUDE yaw: magnetic without GPS) and "bank" the true roll
    (rad, right wing down positive), for the scoring.

    Read by the world and the scoring only: never connect it to the estimator, the
    controller or the link."""

    def __init__(self, link, kind, home=HOME, rate_hz=50.0, connect_timeout=30.0):
        if kind not in ("ardupilot", "px4"):
            raise ValueError("kind = %r: must be 'ardupilot' or 'px4'" % (kind,))
        self.link = link
        self.kind = kind
        self.home = tuple(home)
        self.client = mav_client(link, connect_timeout=connect_timeout)
        self.rate_hz = float(rate_hz)
        self.since_s = None

    def start_streams(self, since_s=None):
        """Ask for the truth's streams; truths before `since_s` (the autopilot's clock,
        e.g. the hand-over) and whatever was buffered before are dropped."""
        self.since_s = since_s
        # The truth and ATTITUDE at the same rate: each truth takes the clock of the
        # ATTITUDE sent with it (SIM_STATE has no time; PX4 SIH's HIL_STATE_QUATERNION
        # leaves time_usec 0). ArduPlane (a 50 Hz main loop) refuses 50 Hz: the rate
        # halves until one is accepted.
        rate = self.rate_hz
        ids = (108, 30) if self.kind == "ardupilot" else (115, 30)
        while not all(self.client.set_interval(m, rate) == 0 for m in ids):
            rate /= 2.0
            if rate < 5.0:
                raise SitlError("the SITL refuses to stream its truth at 5 Hz or more "
                                "on %s%s" % (self.link, (
                                    " (it said: %s)" % self.client.text[-1])
                                    if self.client.text else ""))
        self.rate_hz = rate

    def read(self, timeout=0.02):
        """The truths that arrived within `timeout` s (a list of dicts, in time order)."""
        out = []
        for m in self.client.poll(timeout):
            t = self.convert(m)
            if t is not None and (self.since_s is None or t["time"] >= self.since_s):
                out.append(t)
        return out

    def convert(self, m):
        if m.name == "SIM_STATE" and self.client.time_boot_ms is not None:
            lat = m.get("lat_int") / 1e7 if m.get("lat_int") else m.get("lat")
            lon = m.get("lon_int") / 1e7 if m.get("lon_int") else m.get("lon")
            e, n, u = lla_to_local(lat, lon, m.get("alt"), self.home)
            return self._with_report({
                "time": self.client.time_boot_ms / 1e3, "east": e, "north": n, "up": u,
                "v_east": m.get("ve"), "v_north": m.get("vn"), "v_up": -m.get("vd"),
                "heading": math.pi / 2 - m.get("yaw"), "bank": m.get("roll")})
        if m.name == "HIL_STATE_QUATERNION":
            usec = m.get_int("time_usec")
            if usec <= 0 and self.client.time_boot_ms is None:
                return None
            e, n, u = lla_to_local(m.get("lat") / 1e7, m.get("lon") / 1e7,
                                   m.get("alt") / 1e3, self.home)
            q = [m.get("attitude_quaternion", i) for i in range(4)]
            return self._with_report({
                "time": usec / 1e6 if usec > 0 else self.client.time_boot_ms / 1e3,
                "east": e, "north": n, "up": u,
                "v_east": m.get("vy") / 100.0, "v_north": m.get("vx") / 100.0,
                "v_up": -m.get("vz") / 100.0, "heading": math.pi / 2 - _quat_yaw(*q),
                "bank": _quat_roll(*q)})
        return None

    def _with_report(self, truth):
        att = self.client.last.get("ATTITUDE")
        if att is not None:
            truth["reported_heading"] = math.pi / 2 - att.get("yaw")
        return truth

    def close(self):
        self.client.close()
