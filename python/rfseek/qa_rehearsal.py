#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Rehearsals of the real receive chain without hardware: the simulated world's beacon
as an RTL-SDR delivers it (1.2 MS/s, 8 bits, LO offset 250 kHz, DC leak, IQ imbalance)
through the receive chain of a live radio, timing acquired, heading from the vehicle's
reports; in one process, and split into a beacon process and a receiver process that
talk over GNU Radio's ZeroMQ blocks. Both fly to the arrival radius."""

import os
import re
import socket
import subprocess
import sys

from gnuradio import gr_unittest

BUILD = os.environ.get("RFSEEK_BUILD_DIR", "")
LIVE = os.path.join(BUILD, "apps", "rfseek-live") if BUILD else "rfseek-live"
# 300 m out, flying toward the emitter: the paper's Stage 2 alone reaches 200 m quickly.
WORLD = ["--set", "carrier_hz=915e6", "--set", "initial_distance_m=320",
         "--set", "start_angle_rad=0", "--set", "start_heading_rad=3.14159",
         "--strategy", "paper_no_circle", "--seed", "5", "--speedup", "5"]


def live(*args, timeout=300):
    return subprocess.Popen([sys.executable, LIVE] + list(args), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def free_port():
    # Three consecutive free ports for the samples, the reports and the commands.
    for base in range(47000, 48000, 3):
        ok = True
        for p in range(base, base + 3):
            with socket.socket() as s:
                try:
                    s.bind(("127.0.0.1", p))
                except OSError:
                    ok = False
        if ok:
            return base
    raise RuntimeError("no free ports")


class qa_rehearsal(gr_unittest.TestCase):

    def test_one_process_rehearsal_arrives(self):
        p = live("--source", "sim", "--radio", "rtlsdr", *WORLD)
        out, err = p.communicate(timeout=300)
        self.assertEqual(p.returncode, 0, err)
        self.assertIn("acquire windows", err)
        m = re.search(r"rfseek-live: (\d+) measurements, \d+ Stage-2 updates, (\d+) invalid",
                      err)
        self.assertIsNotNone(m, err)
        self.assertLess(int(m.group(2)), 0.1 * int(m.group(1)))
        self.assertRegex(err, r"rfseek-live: arrived, \d+ m flown")

    def test_the_gain_loop_keeps_a_loud_radio_from_clipping(self):
        # The 8-bit radio 15 dB louder than its noise level asks for (set for a far
        # beacon): near the emitter the beacon clips. Without the gain loop most windows
        # are clipped, so invalid, and the flight wanders; with it (the default) few are.
        flight = ("--source", "sim", "--radio", "rtlsdr", "--set", "carrier_hz=915e6",
                  "--seed", "3", "--set", "initial_distance_m=400", "--speedup", "5",
                  "--strategy", "adaptive", "--gain", "15", "--duration", "120")
        runs = {}
        for agc in ("off", "on"):
            p = live(*flight, "--agc", agc)
            out, err = p.communicate(timeout=300)
            self.assertEqual(p.returncode, 0, err)
            m = re.search(r"rfseek-live: (\d+) measurements, \d+ Stage-2 updates, "
                          r"(\d+) invalid", err)
            self.assertIsNotNone(m, err)
            runs[agc] = int(m.group(2)) / int(m.group(1))
            if agc == "on":
                self.assertRegex(err, r"rfseek-live: arrived, \d+ m flown")
        self.assertGreater(runs["off"], 0.5)
        self.assertLess(runs["on"], 0.05)

    def test_two_processes_over_zeromq_arrive(self):
        addr = "tcp://127.0.0.1:%d" % free_port()
        beacon = live("--source", "sim", "--radio", "rtlsdr", "--zmq-serve", addr,
                      "--duration", "240", *WORLD)
        receiver = live("--source", "zmq", "--zmq", addr, "--radio", "rtlsdr",
                        "--freq", "915e6", "--strategy", "paper_no_circle",
                        "--duration", "240")
        try:
            b_out, b_err = beacon.communicate(timeout=300)
            r_out, r_err = receiver.communicate(timeout=60)
        finally:
            for proc in (beacon, receiver):
                if proc.poll() is None:
                    proc.kill()
        self.assertEqual(beacon.returncode, 0, b_err)
        self.assertEqual(receiver.returncode, 0, r_err)
        self.assertRegex(b_err, r"rfseek-live: arrived, \d+ m flown",
                         "beacon:\n%s\nreceiver:\n%s" % (b_err, r_err))
        self.assertRegex(b_err, r"\((\d+) commands late")
        self.assertGreater(int(re.search(r"\((\d+) commands late", b_err).group(1)), 100)
        m = re.search(r"rfseek-live: (\d+) measurements", r_err)
        self.assertIsNotNone(m, r_err)
        self.assertGreater(int(m.group(1)), 100)

    def test_radio_flags_the_server_ignores_are_refused(self):
        addr = "tcp://127.0.0.1:%d" % free_port()
        p = live("--source", "sim", "--radio", "rtlsdr", "--zmq-serve", addr, "--gain", "30",
                 "--freq", "2.4e9", "--duration", "1", *WORLD)
        out, err = p.communicate(timeout=60)
        self.assertEqual(p.returncode, 2, err)
        self.assertIn("--freq, --gain: not used by --zmq-serve", err)
        self.assertNotIn("Traceback", err)

    def test_bad_rehearsal_settings_are_clean_errors(self):
        p = live("--source", "sim", "--radio", "rtlsdr", "--duration", "1")
        out, err = p.communicate(timeout=60)
        self.assertEqual(p.returncode, 2, err)
        self.assertIn("carrier_hz", err)
        self.assertNotIn("Traceback", err)
        p = live("--source", "zmq", "--duration", "1")
        out, err = p.communicate(timeout=60)
        self.assertEqual(p.returncode, 2, err)
        self.assertIn("--zmq", err)
        # From Python: a plan asked for something that is not a scenario is named.
        from gnuradio.rfseek import rehearsal
        with self.assertRaisesRegex(ValueError, "^sc = None: must be an rfseek.scenario"):
            rehearsal.rehearsal_plan(None, "rtlsdr")

    def test_no_beacon_process_is_said_and_fails(self):
        # Nobody serves the address: the receiver says so while it waits, and a run that
        # measured nothing ends with status 1, not as a success.
        addr = "tcp://127.0.0.1:%d" % free_port()
        p = live("--source", "zmq", "--zmq", addr, "--radio", "rtlsdr", "--freq", "915e6",
                 "--duration", "11")
        out, err = p.communicate(timeout=120)
        self.assertEqual(p.returncode, 1, err)
        self.assertIn("nothing measured from %s after 10 s" % addr, err)
        self.assertIn("0 measurements", err)
        self.assertIn("nothing measured", err)
        self.assertNotIn("Traceback", err)


if __name__ == "__main__":
    gr_unittest.run(qa_rehearsal)
