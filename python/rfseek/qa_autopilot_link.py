#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""autopilot_link against sim_autopilot over loopback UDP (real MAVLink datagrams):
the plane's command path end to end, mode and arming gating, link loss and resumption
within a second, foreign systems, the .tlog, the copter setpoint stream, parameter
errors, and the rehearsal of a whole flight (rfseek-live --vehicle mavlink). Waits poll
a condition with a deadline (live sockets and threads); no timing is asserted beyond the
link's own one-second rule."""

import json
import math
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time

import pmt
from gnuradio import blocks, gr, gr_unittest
from gnuradio import rfseek
from gnuradio.rfseek import mavlink
from gnuradio.rfseek.autopilot_link import read_tlog


def wait_until(cond, timeout=8.0):
    ev = threading.Event()
    for _ in range(int(timeout / 0.01)):
        if cond():
            return True
        ev.wait(0.01)
    return cond()


class pair:
    """A link (udpin, ephemeral port) and a simulated autopilot sending to it, running,
    with the link's nav and status and the autopilot's cmd stored."""

    def __init__(self, family="ardupilot_plane", armed=True, tlog="", compass_dec=0.0,
                 **kw):
        kw.setdefault("command_timeout_s", 60.0)  # the tests command once, not every slot
        self.link = rfseek.autopilot_link("udpin:127.0.0.1:0", family=family, tlog=tlog, **kw)
        self.sim = rfseek.sim_autopilot("udpout:127.0.0.1:%d" % self.link.local_address()[1],
                                        family=family, armed=armed,
                                        declination_deg=compass_dec)
        self.nav, self.status, self.cmd = (blocks.message_debug() for _ in range(3))
        self.tb = gr.top_block()
        self.tb.msg_connect(self.link, "nav", self.nav, "store")
        self.tb.msg_connect(self.link, "status", self.status, "store")
        self.tb.msg_connect(self.sim, "cmd", self.cmd, "store")
        self.tb.start()
        self.state(0.3)

    def state(self, measured_heading):
        self.sim._on_state(pmt.to_pmt({"measured_heading": measured_heading, "x": 100.0,
                                       "y": -50.0}))

    def command(self, heading):
        self.link.handle_cmd(pmt.to_pmt({"heading": heading}))

    def sim_commands(self):
        return [pmt.to_python(self.cmd.get_message(i))["heading"]
                for i in range(self.cmd.num_messages())]

    def statuses(self):
        return [pmt.to_python(self.status.get_message(i))
                for i in range(self.status.num_messages())]

    def close(self):
        self.tb.stop()
        self.tb.wait()
        self.link.close()
        self.sim.close()


class qa_autopilot_link(gr_unittest.TestCase):

    def test_plane_commands_reach_the_autopilot_and_headings_come_back(self):
        p = pair(airspeed_mps=12.0)
        try:
            self.assertTrue(wait_until(lambda: p.link.status()["heartbeats"] >= 1))
            p.command(-2.0)  # compass 90 + 114.6 = 204.6 deg
            self.assertTrue(wait_until(lambda: len(p.sim_commands()) >= 1))
            self.assertAlmostEqual(p.sim_commands()[-1], -2.0, places=5)  # float32 deg
            self.assertTrue(wait_until(lambda: p.link.status()["commands_acked"] >= 2))
            self.assertAlmostEqual(p.sim.airspeed, 12.0, places=5)
            names = [r[1] for r in p.sim.received]
            self.assertIn("HEARTBEAT", names)  # ours, as the companion computer
            cmds = {(r[1], r[2]["command"]) for r in p.sim.received
                    if r[1] in ("COMMAND_LONG", "COMMAND_INT")}
            # The streams asked for, the speed, the heading (COMMAND_INT, as ArduPlane
            # handles it in every version).
            self.assertEqual(cmds, {("COMMAND_LONG", 511), ("COMMAND_LONG", 178),
                                    ("COMMAND_INT", 43002)})
            # ATTITUDE yaw -> nav heading in the module's convention, position never.
            def last_nav():
                k = p.nav.num_messages()
                return pmt.to_python(p.nav.get_message(k - 1)) if k else {}
            # VFR_HUD (4 Hz) brings the airspeed into the reports (on a loaded machine
            # one sent before the speed change may arrive first: wait for the new one).
            self.assertTrue(wait_until(
                lambda: abs(last_nav().get("airspeed", 0.0) - 12.0) < 1e-5))
            n = last_nav()
            self.assertAlmostEqual(n["airspeed"], 12.0, places=5)
            self.assertAlmostEqual(n["heading"], 0.3, places=5)
            self.assertEqual(sorted(n), ["airspeed", "heading", "time"])
            self.assertEqual(p.statuses()[-1]["state"], "commanding")
        finally:
            p.close()

    def test_a_magnetic_compass_and_the_declination(self):
        # An autopilot without GPS whose compass is magnetic (declination 12.8 deg east):
        # a link told the declination reports and commands true headings, and what
        # crosses the link is magnetic; a link not told stays in the magnetic frame.
        dec = 12.8
        for told in (dec, 0.0):
            p = pair(airspeed_mps=12.0, compass_dec=dec, declination_deg=told)
            try:
                p.state(0.3)  # the true heading, counter-clockwise from east
                self.assertTrue(wait_until(lambda: p.nav.num_messages() >= 1))
                self.assertTrue(wait_until(lambda: abs(pmt.to_python(
                    p.nav.get_message(p.nav.num_messages() - 1))["heading"]
                    - (0.3 + math.radians(dec - told))) < 1e-5))
                p.command(-2.0)  # true compass 204.6 deg
                self.assertTrue(wait_until(lambda: len(p.sim_commands()) >= 1))
                # The world flies the command turned by what the link was not told.
                self.assertAlmostEqual(p.sim_commands()[-1], -2.0 + math.radians(told - dec),
                                       places=5)
                sent = [r[2] for r in p.sim.received
                        if r[1] == "COMMAND_INT" and r[2]["command"] == 43002]
                compass = (90.0 - math.degrees(-2.0)) % 360.0
                self.assertAlmostEqual(sent[-1]["param2"], compass - told, places=3)
            finally:
                p.close()

    def test_disarmed_or_out_of_mode_holds_commands(self):
        p = pair(armed=False)
        try:
            p.command(1.0)
            self.assertTrue(wait_until(lambda: p.link.status()["state"] == "holding"))
            self.assertEqual(p.link.status()["reason"], "not armed")
            p.sim.set_armed(True)
            p.sim.set_mode("FLY_BY_WIRE_A")
            self.assertTrue(wait_until(lambda: "not GUIDED" in p.link.status()["reason"]))
            p.command(1.1)
            p.sim.set_mode("GUIDED")
            self.assertTrue(wait_until(lambda: p.link.status()["state"] == "commanding"))
            self.assertTrue(wait_until(lambda: len(p.sim_commands()) >= 1))
            # Nothing reached the autopilot before it was armed in GUIDED.
            self.assertEqual(len(p.sim_commands()), 1)
            self.assertAlmostEqual(p.sim_commands()[0], 1.1, places=5)
            reasons = [s["reason"] for s in p.statuses() if s["state"] == "holding"]
            self.assertIn("not armed", reasons)
        finally:
            p.close()

    def test_link_loss_stops_commands_within_a_second(self):
        p = pair(family="ardupilot_copter")
        try:
            p.command(0.7)
            self.assertTrue(wait_until(lambda: p.link.status()["state"] == "commanding"))
            self.assertTrue(wait_until(lambda: len(p.sim_commands()) >= 5))  # 10 Hz stream
            p.sim.set_silent(True)  # the autopilot falls silent
            silent_at = time.monotonic()
            self.assertTrue(wait_until(lambda: p.link.status()["state"] == "lost"))
            wait_until(lambda: False, timeout=1.5)
            setpoints = [t for t, name in p.sim.arrivals if name == "SET_ATTITUDE_TARGET"]
            # The autopilot's last frame was before silent_at: commands stopped within
            # a second of it (link_timeout_s 0.5 s), while our heartbeats go on.
            self.assertLess(max(setpoints), silent_at + 1.0)
            self.assertTrue(any(t > silent_at + 1.0 for t, name in p.sim.arrivals
                                if name == "HEARTBEAT"))
            lost = [s for s in p.statuses() if s["state"] == "lost"]
            self.assertEqual(len(lost), 1)
            self.assertIn("link_timeout_s", lost[0]["reason"])
            # It resumes cleanly when the autopilot speaks again.
            n = len(p.sim_commands())
            p.sim.set_silent(False)
            self.assertTrue(wait_until(lambda: p.link.status()["state"] == "commanding"))
            self.assertTrue(wait_until(lambda: len(p.sim_commands()) > n))
        finally:
            p.close()

    def test_foreign_system_is_dropped_and_never_answered(self):
        p = pair()
        try:
            self.assertTrue(wait_until(lambda: p.link.status()["heartbeats"] >= 1))
            intruder = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            hb = mavlink.message("HEARTBEAT")
            hb.set("base_mode", 129)
            hb.set("custom_mode", 15)
            att = mavlink.message("ATTITUDE")
            att.set("yaw", 2.0)
            before = p.link.status()["foreign"]
            for seq in range(5):
                for m in (hb, att):
                    intruder.sendto(mavlink.encode(m, mavlink.header(seq, 2, 1)),
                                    p.link.local_address())
            self.assertTrue(wait_until(lambda: p.link.status()["foreign"] >= before + 10))
            navs = [pmt.to_python(p.nav.get_message(i))["heading"]
                    for i in range(p.nav.num_messages())]
            self.assertNotIn(True, [abs(h - (math.pi / 2 - 2.0)) < 1e-4 for h in navs])
            intruder.settimeout(0.5)
            with self.assertRaises(socket.timeout):  # the link never answers it
                intruder.recvfrom(1024)
            intruder.close()
        finally:
            p.close()

    def test_tlog_holds_both_directions(self):
        path = os.path.join(tempfile.mkdtemp(), "flight.tlog")
        p = pair(tlog=path)
        try:
            p.command(0.2)
            self.assertTrue(wait_until(lambda: p.link.status()["commands_acked"] >= 1))
            self.assertTrue(wait_until(lambda: p.link.status()["heartbeats"] >= 2))
        finally:
            p.close()
        entries = read_tlog(path)
        parser = mavlink.parser()
        frames = [f for _, raw in entries for f in parser.push(raw)]
        self.assertEqual(len(frames), len(entries))  # every entry one whole, valid frame
        stamps = [t for t, _ in entries]
        self.assertEqual(stamps, sorted(stamps))
        names = {(f.sysid, f.compid, f.decode().name) for f in frames if f.known()}
        for expected in ((1, 1, "HEARTBEAT"), (1, 1, "ATTITUDE"), (1, 1, "COMMAND_ACK"),
                         (1, 1, "GLOBAL_POSITION_INT"), (1, 191, "COMMAND_LONG"),
                         (1, 191, "HEARTBEAT")):
            self.assertIn(expected, names)
        self.check_tlog_with_node_mavlink(path, entries)

    def check_tlog_with_node_mavlink(self, path, entries):
        """Each entry of the log, time stamp and frame, read by node-mavlink's splitter
        (which takes the 8 bytes before a frame as a .tlog time stamp), where node and
        node-mavlink are installed. Entry by entry, and only entries whose time stamp
        holds no magic byte (0xFD, 0xFE): node-mavlink's splitter looks for magic bytes
        and takes one inside a stamp for a frame start; log readers that walk the
        entries by their lengths (read_tlog, ground stations) do not."""
        modules = os.path.join(os.environ.get("RFSEEK_BUILD_DIR", "build"), "node",
                               "node_modules")
        if shutil.which("node") is None or not os.path.isdir(
                os.path.join(modules, "node-mavlink")):
            print("node-mavlink not installed: the .tlog is not read by it here")
            return
        with open(path, "rb") as f:
            data = f.read()
        chunks, i = [], 0
        for _, raw in entries:
            chunks.append(data[i:i + 8 + len(raw)].hex())
            i += 8 + len(raw)
        self.assertEqual(i, len(data))
        script = """
const mav = require('node-mavlink');
const chunks = JSON.parse(require('fs').readFileSync(0, 'utf8'));
const out = [];
(async () => {
  for (const c of chunks) {
    const s = new mav.MavLinkPacketSplitter();
    const got = await new Promise(res => {
      const ps = []; s.on('data', p => ps.push(p));
      s.on('end', () => res(ps)); s.end(Buffer.from(c, 'hex')); s.resume(); });
    out.push(got.map(p => [Number(p.timestamp), p.buffer.toString('hex')]));
  }
  console.log(JSON.stringify(out));
})();
"""
        # node is not built with the sanitizers: no preloaded runtime for it.
        env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
        env["NODE_PATH"] = modules
        r = subprocess.run(["node", "-e", script], input=json.dumps(chunks),
                           capture_output=True, text=True, env=env, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        got = json.loads(r.stdout)
        checked = 0
        for found, chunk, (t, raw) in zip(got, chunks, entries):
            stamp = bytes.fromhex(chunk[:16])
            if 0xFD in stamp or 0xFE in stamp:
                continue  # node-mavlink takes a magic byte in the stamp for a frame start
            checked += 1
            self.assertEqual(len(found), 1, "entry not read as one frame")
            self.assertEqual(found[0][1], raw.hex())
            self.assertEqual(found[0][0], int(t * 1e6) // 1000)  # node-mavlink: ms
        self.assertGreater(checked, len(entries) // 2)

    def test_serial_transport_on_a_pseudo_terminal(self):
        # A pty stands in for a telemetry radio: the link opens its slave side as a
        # serial device; the "autopilot" reads and writes the master side.
        import pty
        master, slave = pty.openpty()
        link = rfseek.autopilot_link("serial:%s:57600" % os.ttyname(slave))
        tb = gr.top_block()
        store = blocks.message_debug()
        tb.msg_connect(link, "nav", store, "store")
        tb.start()
        try:
            hb = mavlink.message("HEARTBEAT")
            hb.set("base_mode", 129)
            hb.set("custom_mode", 15)
            att = mavlink.message("ATTITUDE")
            att.set("yaw", 0.0)
            parser = mavlink.parser()
            ours = []
            os.set_blocking(master, False)
            for k in range(30):
                os.write(master, mavlink.encode(hb if k % 10 == 0 else att,
                                                mavlink.header(k, 1, 1)))
                wait_until(lambda: False, timeout=0.05)
                try:
                    ours += parser.push(os.read(master, 4096))
                except BlockingIOError:
                    pass
            self.assertGreaterEqual(link.status()["heartbeats"], 3)
            self.assertTrue(wait_until(lambda: store.num_messages() >= 20))
            self.assertAlmostEqual(pmt.to_python(store.get_message(0))["heading"],
                                   math.pi / 2, places=6)
            self.assertIn("HEARTBEAT", [f.decode().name for f in ours if f.known()])
        finally:
            tb.stop()
            tb.wait()
            link.close()
            os.close(master)
            os.close(slave)

    def test_when_a_setpoint_last_went_out(self):
        # control_sent_s(): the link's clock when it last sent a frame other than a
        # heartbeat (the SITL rehearsal times the firmware's response from it). A
        # copter's setpoint stream on the host clock: it moves with the setpoints,
        # stays put while only heartbeats go out, and is never after their arrival.
        mav = rfseek.mavlink
        from gnuradio.rfseek.autopilot_link import _msgid
        hb = mav.encode(mav.message("HEARTBEAT"), mav.header(0, 1, 1))
        att = mav.encode(mav.message("ATTITUDE"), mav.header(1, 1, 1))
        self.assertEqual((_msgid(hb), _msgid(att)), (0, 30))
        self.assertEqual(_msgid(bytes([0xFE, 9, 0, 1, 1, 0]) + bytes(11)), 0)  # version 1
        self.assertIsNone(_msgid(b""))
        p = pair(family="ardupilot_copter", command_timeout_s=0.5)
        try:
            p.command(0.7)
            self.assertTrue(wait_until(lambda: len(p.sim_commands()) >= 3))
            self.assertTrue(wait_until(
                lambda: "command_timeout_s" in p.link.status()["reason"]))
            sent = p.link.control_sent_s()  # holding: no setpoint goes out any more
            # Our heartbeats go on (1 Hz); once one sent well after it has arrived, so
            # has every setpoint.
            self.assertTrue(wait_until(lambda: any(
                t > sent + 0.5 for t, name in p.sim.arrivals if name == "HEARTBEAT")))
            self.assertEqual(p.link.control_sent_s(), sent)  # heartbeats only since
            setpoints = [t for t, name in p.sim.arrivals if name == "SET_ATTITUDE_TARGET"]
            self.assertLessEqual(sent, max(setpoints) + 1e-6)
            self.assertGreater(sent, max(setpoints) - 0.1)
        finally:
            p.close()

    def test_the_autopilot_clock(self):
        # clock "autopilot" (a rehearsal against a simulator): the link's time goes on
        # from where it was at the first ATTITUDE, then moves as the autopilot's
        # time_boot_ms does, whatever the host clock does, and never goes back.
        link = rfseek.autopilot_link("udpin:127.0.0.1:0", clock="autopilot")
        try:
            mav = rfseek.mavlink

            def attitude(ms, seq):
                m = mav.message("ATTITUDE")
                m.set("time_boot_ms", ms)
                return mav.encode(m, mav.header(seq, 1, 1))
            t1 = link._now()
            link.session.receive(attitude(1000000, 0), t1)
            t2 = link._now()
            self.assertLess(t2 - t1, 0.5)
            link.session.receive(attitude(1005000, 1), t2)
            t3 = link._now()
            self.assertAlmostEqual(t3 - t1, 5.0, delta=0.5)
            link.session.receive(attitude(1004000, 2), t3)  # older: never back
            self.assertGreaterEqual(link._now(), t3)
        finally:
            link.close()

    def test_bad_parameters(self):
        for kw, word in (({"link": "tcpin:1.2.3.4:5"}, "link"),
                         ({"link": "tcp:127.0.0.1:x"}, "port"),
                         ({"turn_bank_deg": 40}, "turn_bank_deg"),
                         ({"turn_bank_deg": 10}, "turn_speed_mps"),
                         ({"clock": "gps"}, "clock"),
                         ({"link": "udpin:127.0.0.1:70000"}, "port"),
                         ({"link": "serial:/dev/ttyS0:12345"}, "baud"),
                         ({"family": "inav"}, "family"),
                         ({"mode": "OFFBOARD"}, "mode"),
                         ({"target_system": 0}, "target_system"),
                         ({"link_timeout_s": 0}, "link_timeout_s"),
                         ({"retries": 11}, "retries"),
                         ({"signing_key": "abcd"}, "signing_key"),
                         ({"heading_accel_mps2": 0}, "heading_accel_mps2"),
                         ({"thrust": 1.5}, "thrust"),
                         ({"declination_deg": 190.0}, "declination_deg"),
                         ({"declination_deg": float("nan")}, "declination_deg"),
                         ({"signing_key": "ab" * 32, "time_scale": 10}, "time_scale")):
            with self.assertRaises(ValueError) as cm:
                rfseek.autopilot_link(**kw)
            self.assertIn(word, str(cm.exception))
        # The simulated autopilot checks what it is given the same way.
        for kw, word in (({"airspeed_mps": -1.0}, "airspeed_mps"),
                         ({"airspeed_mps": float("nan")}, "airspeed_mps"),
                         ({"ref_lat_deg": 100.0}, "ref_lat_deg"),
                         ({"ref_lon_deg": 200.0}, "ref_lon_deg"),
                         ({"time_scale": 0.5}, "time_scale"),
                         ({"declination_deg": -200.0}, "declination_deg")):
            with self.assertRaises(ValueError) as cm:
                rfseek.sim_autopilot(**kw)
            self.assertIn(word, str(cm.exception))
        with self.assertRaises(OSError) as cm:
            rfseek.autopilot_link("serial:/dev/rfseek-no-such-device:57600")
        self.assertIn("/dev/rfseek-no-such-device", str(cm.exception))
        # A TCP server that is not there: refused at once, the cause named.
        s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
        s.close()
        with self.assertRaises(ConnectionError) as cm:
            rfseek.autopilot_link("tcp:127.0.0.1:%d" % port)
        self.assertIn("cannot connect", str(cm.exception))

    def test_done_and_a_silent_controller_stop_commands(self):
        p = pair(family="ardupilot_copter", command_timeout_s=0.5)
        try:
            p.command(0.7)
            self.assertTrue(wait_until(lambda: p.link.status()["state"] == "commanding"))
            # The controller falls silent: the link holds after command_timeout_s.
            self.assertTrue(wait_until(
                lambda: "command_timeout_s" in p.link.status()["reason"]))
            n = len(p.sim_commands())
            wait_until(lambda: False, timeout=0.5)
            self.assertEqual(len(p.sim_commands()), n)
            p.command(0.8)
            self.assertTrue(wait_until(lambda: len(p.sim_commands()) > n))
            # done: no more commands, even with headings after it.
            p.link.handle_cmd(pmt.to_pmt({"heading": 0.9, "done": True}))
            self.assertTrue(wait_until(
                lambda: p.link.status()["reason"] == "the controller is done"))
            p.command(1.0)
            n = len(p.sim_commands())
            wait_until(lambda: False, timeout=0.5)
            self.assertEqual(len(p.sim_commands()), n)
        finally:
            p.close()

    def test_malformed_commands_are_counted_and_dropped(self):
        p = pair()
        try:
            for bad in (pmt.intern("x"), pmt.to_pmt({"heading": float("nan")}),
                        pmt.to_pmt({"speed": 3.0})):
                p.link.handle_cmd(bad)
            self.assertEqual(p.link.dropped["cmd"], 3)
            p.command(0.4)
            self.assertTrue(wait_until(lambda: len(p.sim_commands()) >= 1))
        finally:
            p.close()

    def test_rehearsal_over_mavlink_arrives(self):
        live = os.path.join(os.environ.get("RFSEEK_SOURCE_DIR", "."), "apps", "rfseek-live")
        r = subprocess.run([sys.executable, live, "--source", "sim", "--vehicle", "mavlink",
                            "--set", "initial_distance_m=800", "--speedup", "8",
                            "--seed", "3", "--duration", "240",
                            # its compass magnetic, the link told the declination
                            "--declination", "15"],
                           capture_output=True, text=True, timeout=400)
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        self.assertIn("rfseek-live: arrived", r.stderr)
        self.assertRegex(r.stderr, r"MAVLink link commanding: \d+ frames")
        self.assertIn("0 failed", r.stderr)


if __name__ == "__main__":
    gr_unittest.run(qa_autopilot_link)
