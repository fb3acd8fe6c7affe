#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""rfseek-live without hardware: a clean "no device found" (status 3, no traceback) for
the USRP and osmosdr sources, replay of the committed recording, a short simulated run,
and argument errors."""

import os
import re
import subprocess
import sys
import tempfile

from gnuradio import gr_unittest

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
LIVE = os.path.join(SOURCE, "apps", "rfseek-live")


def live(*args):
    return subprocess.run([sys.executable, LIVE] + list(args), capture_output=True,
                          text=True, timeout=300)


class qa_live(gr_unittest.TestCase):

    def test_no_device_is_a_clean_error(self):
        for source, name in (("uhd", "UHD"), ("osmosdr", "osmosdr"), ("soapy", "SoapySDR")):
            p = live("--source", source, "--duration", "1")
            self.assertEqual(p.returncode, 3, p.stderr)
            self.assertIn("no %s device found" % name, p.stderr)
            self.assertNotIn("Traceback", p.stderr)

    def test_replay_of_the_committed_recording(self):
        p = live("--source", "file", "--file", os.path.join(SOURCE, "examples", "data",
                                                            "sim_beacons"))
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("60 measurements", p.stderr)

    def test_simulated_source(self):
        p = live("--source", "sim", "--fast", "--set", "initial_distance_m=205",
                 "--set", "start_angle_rad=0", "--set", "start_heading_rad=3.14159",
                 "--strategy", "paper_no_circle")
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("arrived", p.stderr)

    def test_simulated_source_arrival_self(self):
        # Free-running and paced (5 x real time: commands a slot or so late, timing not
        # reproducible): the controller declares arrival, loiters and ends the simulated
        # flight by itself, near the emitter. At 20 x on a loaded machine a controller
        # busy for a second of wall time leaves the vehicle 20 s on one heading, and
        # the orbits that locate the emitter go astray (seen once in CI: capped at
        # 2400 m without a fix); at 5 x such a stall is 5 s of flight.
        p = live("--source", "sim", "--speedup", "5", "--set", "initial_distance_m=800",
                 "--set", "start_angle_rad=0", "--set", "start_heading_rad=3.14159",
                 "--strategy", "paper_no_circle", "--arrival", "self", "--duration", "120")
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("mission done (self arrival)", p.stderr)
        self.assertRegex(p.stderr, r"final status located: emitter \d+ m")
        end = float(re.search(r"mission done \(self arrival\), \d+ m flown, (\d+) m from",
                              p.stderr).group(1))
        self.assertLess(end, 300.0)

    def test_free_running_paced_run_flies_the_late_commands(self):
        # Paced to (20 x) real time, free-running: each command reaches the simulator after
        # its slot has passed. Flown late, they turn the UAV, which starts flying away,
        # back to the emitter; dropped (as before issue 12) it would fly away to the cap.
        p = live("--source", "sim", "--speedup", "20", "--set", "initial_distance_m=800",
                 "--set", "start_angle_rad=0", "--set", "start_heading_rad=0",
                 "--strategy", "adaptive", "--duration", "120")
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("rfseek-live: arrived", p.stderr)
        m = re.search(r"simulator: (\d+) commands applied late, (\d+) stale", p.stderr)
        self.assertIsNotNone(m, p.stderr)
        self.assertGreater(int(m.group(1)), 100)
        flown = float(re.search(r"arrived, (\d+) m flown", p.stderr).group(1))
        self.assertLess(flown, 1.25 * 600)  # shortest path 800 - 200 m
        # The progress line gives the flight's time (the sample clock, 20 x the wall
        # clock's pace here) and compass bearings in [0, 360).
        lines = re.findall(r"flight +([\d.]+) s +\(wall +([\d.]+) s\).*heading (\d+\.\d) deg",
                           p.stderr)
        self.assertGreater(len(lines), 3, p.stderr)
        flight, wall, _ = (float(v) for v in lines[-1])
        self.assertGreater(flight, 2.0 * wall)
        for _, _, heading in lines:
            self.assertTrue(0.0 <= float(heading) < 360.0, heading)

    def test_speedup_out_of_range_is_a_value_error(self):
        from gnuradio import rfseek
        for bad in (0.0, -1.0, float("nan"), 1e7):
            with self.assertRaisesRegex(ValueError, "speedup"):
                rfseek.channel_source(rfseek.scenario(), speedup=bad)
        src = rfseek.channel_source(rfseek.scenario(), lockstep=False, realtime=True,
                                    speedup=5.0)
        self.assertEqual(src.speedup(), 5.0)
        with self.assertRaisesRegex(ValueError, "speedup"):
            src.set_speedup(0.0)
        self.assertEqual(src.speedup(), 5.0)

    def test_bad_arguments(self):
        self.assertEqual(live("--source", "file").returncode, 2)
        self.assertEqual(live("--source", "radio").returncode, 2)
        # A recording into a folder that does not exist (a typo) is refused, not made.
        p = live("--source", "sim", "--fast", "--duration", "1", "--record",
                 os.path.join(tempfile.gettempdir(), "rfseek-no-such-dir", "x"))
        self.assertEqual(p.returncode, 2, p.stderr)
        self.assertIn("does not exist", p.stderr)
        self.assertFalse(os.path.exists(os.path.join(tempfile.gettempdir(),
                                                     "rfseek-no-such-dir")))
        p = live("--source", "sim", "--fast", "--window-len", "2")
        self.assertEqual(p.returncode, 2)
        self.assertIn("window_len", p.stderr)
        self.assertNotIn("Traceback", p.stderr)
        # --set takes seeker constants with any source (scenario fields only with a
        # simulated world) and refuses what it cannot place.
        rec = os.path.join(os.environ.get("RFSEEK_SOURCE_DIR", "."), "examples", "data",
                           "sim_beacons")
        p = live("--source", "file", "--file", rec, "--set", "locate_max_orbits=5",
                 "--set", "adaptive_gain=0.6", "--strategy", "adaptive")
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("seeker constants set: locate_max_orbits=5, adaptive_gain=0.6",
                      p.stderr)
        for bad, word in (("bogus=3", "--set bogus: unknown"),
                          ("snr_db=3", "--set snr_db: a field of the simulated world")):
            p = live("--source", "file", "--file", rec, "--set", bad)
            self.assertEqual(p.returncode, 2, p.stderr)
            self.assertIn(word, p.stderr)
        # --wind-from: the direction the wind blows from (compass, as weather reports
        # give it) and its speed become the ground track's forecast in the module's
        # frame (from 270 deg, the west: toward +east); bad text or a wind as fast as
        # the airspeed is one line, exit 2.
        p = live("--source", "file", "--file", rec, "--strategy", "adaptive",
                 "--wind-from", "270,6")
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("wind forecast: 6.0 m/s toward east, 0.0 m/s toward north", p.stderr)
        for arg, want in (("0,4", "0.0 m/s toward east, -4.0 m/s toward north"),
                          ("90,4", "-4.0 m/s toward east, 0.0 m/s toward north")):
            p = live("--source", "file", "--file", rec, "--strategy", "adaptive",
                     "--wind-from", arg)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertIn("wind forecast: " + want, p.stderr)
        # Refused: not a direction and speed; a wind as fast as --speed (before any
        # device); a strategy that flies no ground track (the default `paper`).
        for args, word in ((["--wind-from", "west"], "--wind-from"),
                           (["--wind-from", "90,12"], "--wind-from: a wind of 12"),
                           (["--wind-from", "90,4", "--strategy", "paper"],
                            "--wind-from: used by the ground track only")):
            p = live("--source", "file", "--file", rec, *args)
            self.assertEqual(p.returncode, 2, p.stderr)
            self.assertIn(word, p.stderr)
            self.assertNotIn("Traceback", p.stderr)
        # Radio settings the simulator would ignore are refused, naming them.
        p = live("--source", "sim", "--fast", "--freq", "915e6", "--gain", "nan")
        self.assertEqual(p.returncode, 2, p.stderr)
        self.assertIn("--freq, --gain: not used with --source sim", p.stderr)
        self.assertIn("carrier_hz", p.stderr)
        self.assertNotIn("Traceback", p.stderr)


if __name__ == "__main__":
    gr_unittest.run(qa_live)
