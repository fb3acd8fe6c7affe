#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""The seek flown by the real firmware: ArduCopter, ArduPlane and PX4 (SIH quad) SITL,
GPS off, about 800 m, each must arrive; the firmware's response to the link's heading
steps matches the module's model of it (the arduplane and arducopter presets) within
sitl_response.TOLERANCES; and the rehearsal's bad inputs, each one line,
with every process it started stopped. Runs whenever SITL builds are found (--sitl,
$RFSEEK_SITL, or ../shared/sitl beside the source tree); otherwise each test says it is
skipped and why."""

import math
import os
import shutil
import socket
import stat
import sys
import tempfile
import time
import unittest

from gnuradio import gr_unittest
from gnuradio import rfseek
from gnuradio.rfseek import sitl, sitl_pilot, sitl_rehearsal, sitl_response

# Under the sanitizers (scripts/sanitize.sh) the receive chain runs several times
# slower; the main test job flies every vehicle, this job the copter's seek.
SANITIZED = os.environ.get("RFSEEK_SANITIZE") == "1"

try:
    SITL = sitl.find_sitl()
    WHY = ""
except sitl.SitlError as e:
    SITL, WHY = None, "no SITL builds here (%s)" % e


def gone(proc, within_s=3.0):
    """Nothing of the SITL's process group is left (its killed children may take a
    moment to be reaped)."""
    deadline = time.monotonic() + within_s
    while time.monotonic() < deadline:
        try:
            os.killpg(proc.proc.pid, 0)
        except ProcessLookupError:
            return True
        time.sleep(0.05)
    return False


def own_sitl_processes():
    """This test's SITL processes still running: its children (and their process
    groups' members) running a binary of the SITL folder or a scratch copy."""
    rows = []
    for pid in filter(str.isdigit, os.listdir("/proc")):  # not ps: read /proc itself
        try:
            with open("/proc/%s/stat" % pid) as f:
                stat = f.read()
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                args = f.read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue  # gone meanwhile
        fields = stat[stat.rindex(")") + 2:].split()  # after "pid (comm) "
        if fields[0] == "Z":
            continue  # exited, not yet reaped
        rows.append((pid, fields[1], fields[2], args))
    mine = {pid for pid, ppid, pgid, args in rows if int(ppid) == os.getpid()}
    return [args for pid, ppid, pgid, args in rows
            if (pid in mine or pgid in mine) and "sitl" in args]


class qa_sitl_profiles(gr_unittest.TestCase):
    """What the rehearsal believes of each vehicle (no SITL needed)."""

    def test_a_steeper_copter_is_a_faster_one(self):
        for pitch, speed in sitl_rehearsal.COPTER_SPEED_AT_PITCH.items():
            sc = sitl_rehearsal.scenario_for("arducopter", 1000.0, 1, pitch_deg=pitch)
            self.assertEqual(sc.speed_mps, speed)
            self.assertEqual(sitl_rehearsal.profile("arducopter", pitch)["pitch_deg"], pitch)
        # The speed rises with the pitch, as measured.
        speeds = [v for _, v in sorted(sitl_rehearsal.COPTER_SPEED_AT_PITCH.items())]
        self.assertEqual(speeds, sorted(speeds))
        for vehicle, pitch in (("arducopter", 20.0), ("arduplane", 15.0)):
            with self.assertRaises(ValueError) as cm:
                sitl_rehearsal.profile(vehicle, pitch)
            self.assertIn("pitch_deg", str(cm.exception))
        with self.assertRaises(ValueError) as cm:
            sitl_rehearsal.profile("glider")
        self.assertIn("vehicle", str(cm.exception))

    def test_the_forecast_is_the_wind_the_simulation_hands_over(self):
        # A wind from a compass direction (SITL's SIM_WIND_DIR, weather reports) is the
        # forecast the simulation hands its seeker for the same wind (--set
        # wind_forecast=true), whose direction is counter-clockwise from east, toward.
        for speed, frm in ((5.0, 0.0), (5.0, 90.0), (3.0, 225.0), (4.0, 301.0)):
            sc = sitl_rehearsal.scenario_for("arducopter", 1000.0, 1, pitch_deg=30.0)
            sc.wind_speed_mps = speed
            sc.wind_to_rad = math.remainder(math.radians(90.0 - (frm + 180.0)), 2 * math.pi)
            sc.wind_forecast = True
            cfg = rfseek.simulation.seeker_for(sc, "adaptive")
            east, north = sitl_rehearsal.forecast_vector((speed, frm))
            self.assertAlmostEqual(east, cfg.wind_forecast_east_mps, places=9)
            self.assertAlmostEqual(north, cfg.wind_forecast_north_mps, places=9)
        # From the north blows toward the south.
        east, north = sitl_rehearsal.forecast_vector((5.0, 0.0))
        self.assertAlmostEqual(east, 0.0)
        self.assertAlmostEqual(north, -5.0)
        self.assertEqual(sitl_rehearsal.forecast_vector(None), (0.0, 0.0))
        for bad in ((-1.0, 0.0), (float("nan"), 10.0), (5.0, float("inf"))):
            with self.assertRaises(ValueError) as cm:
                sitl_rehearsal.forecast_vector(bad)
            self.assertIn("forecast", str(cm.exception))


@unittest.skipIf(SITL is None, WHY)
class qa_sitl(gr_unittest.TestCase):

    def tearDown(self):
        # No orphan: whatever the test did, no SITL it started is left running.
        self.assertEqual(own_sitl_processes(), [])
        self.assertEqual(len(sitl._LIVE), 0)

    def fly(self, vehicle, seed):
        summary, rec = sitl_rehearsal.rehearse(vehicle, 800.0, "adaptive", seed,
                                               speedup=10.0, sitl_dir=SITL,
                                               wall_cap_s=400.0)
        sys.stderr.write("%s seed %d: %s\n" % (vehicle, seed, {
            k: summary[k] for k in ("success", "ratio", "time_s", "wall_s",
                                    "height_min_m", "height_max_m",
                                    "compass_declination_deg")}))
        self.assertTrue(summary["success"], summary)
        # The world followed the firmware: its track is the truth's, whose speed is
        # the vehicle's, not the scenario's.
        self.assertGreater(summary["truths"], 100)
        self.assertGreater(summary["distance_flown_m"], 590.0)
        # Without GPS the firmware's headings are magnetic: over the seek they pointed
        # the home's declination east of true (the link was told it).
        self.assertEqual(summary["declination_deg"], sitl.HOME_DECLINATION_DEG)
        self.assertAlmostEqual(summary["compass_declination_deg"],
                               sitl.HOME_DECLINATION_DEG, delta=3.0)
        return summary, rec

    def test_arducopter_gps_off_arrives(self):
        self.fly("arducopter", 11)

    @unittest.skipIf(SANITIZED, "flown by the main test job; the sanitizer job flies the "
                     "copter's seek only")
    def test_arduplane_gps_off_arrives(self):
        s, rec = self.fly("arduplane", 12)
        self.assertGreater(s["height_min_m"], s["altitude_m"] - 20.0)

    @unittest.skipIf(SANITIZED, "flown by the main test job; the sanitizer job flies the "
                     "copter's seek only")
    def test_px4_quad_gps_off_arrives(self):
        self.fly("px4_quad", 13)

    def respond(self, vehicle, preset):
        # The rehearsal's profile is the preset's airframe.
        sc, ref = sitl_rehearsal.scenario_for(vehicle), rfseek.scenario()
        ref.apply_preset(preset)
        for key in ("speed_mps", "bank_limit_rad", "roll_rate_rad_per_s"):
            self.assertAlmostEqual(getattr(sc, key), getattr(ref, key), places=9, msg=key)
        samples, starts = sitl_response.fly_sitl(vehicle, 10.0, SITL, lambda text: None)
        firmware = {"steps": sitl_response.reduce_steps(samples, starts),
                    "legs": sitl_response.legs(samples, starts)}
        m_samples, m_starts = sitl_response.fly_model(ref)
        model = {"steps": sitl_response.reduce_steps(m_samples, m_starts),
                 "legs": sitl_response.legs(m_samples, m_starts)}
        sys.stderr.write(sitl_response.table(vehicle, firmware, model) + "\n")
        checks = sitl_response.compare(firmware, model)
        self.assertEqual(len(firmware["steps"]), len(sitl_response.SCHEDULE) - 1)
        # Every figure compared: the rate, bank and roll-in of the three long turns,
        # the settling of all five, the legs.
        self.assertGreaterEqual(len(checks), 3 * 2 + 5 + 1)
        self.assertEqual([c for c in checks if not c[4]], [])

    @unittest.skipIf(SANITIZED, "flown by the main test job")
    def test_arduplane_turns_as_the_model(self):
        self.respond("arduplane", "arduplane")

    @unittest.skipIf(SANITIZED, "flown by the main test job")
    def test_arducopter_turns_as_the_model(self):
        self.respond("arducopter", "arducopter")

    def test_bad_inputs_are_one_line_and_leave_nothing_behind(self):
        with self.assertRaises(sitl.SitlError) as cm:
            sitl.sitl_process("arducopter", "/nonexistent/rfseek-sitl")
        self.assertIn("/nonexistent/rfseek-sitl", str(cm.exception))
        scratch = tempfile.mkdtemp(prefix="rfseek-fake-sitl-")
        try:
            # A SITL folder whose binary is not executable.
            open(os.path.join(scratch, "arducopter"), "w").close()
            with self.assertRaises(sitl.SitlError) as cm:
                sitl.sitl_process("arducopter", scratch)
            self.assertIn("not executable", str(cm.exception))
            # A SITL that never answers: the pilot gives up in one line, all stopped.
            fake = os.path.join(scratch, "arducopter")
            with open(fake, "w") as f:
                f.write("#!/bin/sh\nsleep 600\n")
            os.chmod(fake, stat.S_IRWXU)
            p = sitl.sitl_process("arducopter", scratch, instance=7)
            with self.assertRaises(sitl.SitlError) as cm:
                with p:
                    self.assertNotEqual(own_sitl_processes(), [])  # the check sees it
                    sitl_pilot.pilot(p, wall_timeout_s=2.0)
            self.assertIn("never accepted a connection", str(cm.exception))
            self.assertTrue(gone(p))
        finally:
            shutil.rmtree(scratch)
        # An arming refused by the real firmware (ArduPlane without GPS refuses the
        # ordinary one): one line naming the step and what the autopilot said;
        # nothing left running.
        p = sitl.sitl_process("arduplane", SITL, 10.0)
        with self.assertRaises(sitl.SitlError) as cm:
            with p:
                pl = sitl_pilot.pilot(p, wall_timeout_s=60.0)
                try:
                    self.assertIsNotNone(pl.client.wait("HEARTBEAT", 30.0))
                    pl._arm(force=False)  # ordinary arming: refused without GPS
                finally:
                    pl.close()
        self.assertIn("arming: not done", str(cm.exception))
        self.assertNotIn("\n", str(cm.exception))
        self.assertTrue(gone(p))
        # A port already in use, on the instance asked for.
        s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        s.bind(("127.0.0.1", 5760 + 10 * 9))
        s.listen(1)
        try:
            p = sitl.sitl_process("arducopter", SITL, instance=9)
            with self.assertRaises(sitl.SitlError) as cm:
                p.start()
            self.assertIn("port 5850 already in use", str(cm.exception))
            self.assertIsNone(p.proc)
        finally:
            s.close()


if __name__ == "__main__":
    unittest.main()
