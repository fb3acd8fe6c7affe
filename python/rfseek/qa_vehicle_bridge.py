#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""vehicle_bridge over loopback UDP with the simulated vehicle: commands out as compass
headings, reports back as module headings, malformed and foreign datagrams dropped
without stopping, the angle conversion, and parameter errors. Waits poll a condition with
a deadline (no fixed sleeps)."""

import json
import math
import socket
import threading
import time

import pmt
from gnuradio import blocks, gr, gr_unittest
from gnuradio.rfseek.vehicle_bridge import (compass_deg_from_theta, loopback_vehicle,
                                            theta_from_compass_deg, vehicle_bridge)


def wait_until(cond, timeout=5.0):
    ev = threading.Event()
    for _ in range(int(timeout / 0.01)):
        if cond():
            return True
        ev.wait(0.01)
    return cond()


def linked(reporting=True, heading_deg=0.0, **bridge_kw):
    """A loopback vehicle and a bridge that know each other's ports, the bridge's nav in
    a running flowgraph: (vehicle, bridge, nav store, top block)."""
    vehicle = loopback_vehicle(port=0, bridge=("127.0.0.1", 0), heading_deg=heading_deg)
    vehicle.reporting = reporting
    bridge = vehicle_bridge(local_port=0, peer_port=vehicle.sock.getsockname()[1],
                            **bridge_kw)
    vehicle.bridge = bridge.local
    nav = blocks.message_debug()
    tb = gr.top_block()
    tb.msg_connect(bridge, "nav", nav, "store")
    tb.start()
    return vehicle, bridge, nav, tb


class qa_vehicle_bridge(gr_unittest.TestCase):

    def test_angle_conventions(self):
        # Compass: clockwise from north. Module: counter-clockwise from east.
        for compass, theta in ((0.0, math.pi / 2), (90.0, 0.0), (180.0, -math.pi / 2),
                               (270.0, math.pi), (45.0, math.pi / 4)):
            self.assertAlmostEqual(theta_from_compass_deg(compass), theta)
            self.assertAlmostEqual(compass_deg_from_theta(theta) % 360.0, compass % 360.0)
        for theta in (-3.0, -1.0, 0.3, 2.9):
            self.assertAlmostEqual(theta_from_compass_deg(compass_deg_from_theta(theta)), theta)

    def test_round_trip_and_bad_datagrams(self):
        vehicle, bridge, nav, tb = linked(heading_deg=10.0, nav_timeout=30.0)
        try:
            # A command goes out as a compass heading; the vehicle turns and reports.
            theta = 0.7
            bridge._post(pmt.intern("cmd"), pmt.to_pmt({"heading": theta, "slot": 5,
                                                        "stage": 2}))
            self.assertTrue(wait_until(lambda: len(vehicle.commands) >= 1))
            c = vehicle.commands[0]
            self.assertEqual(c["type"], "cmd")
            self.assertEqual(c["slot"], 5)
            self.assertAlmostEqual(c["heading_deg"], compass_deg_from_theta(theta))
            self.assertNotIn("done", c)
            # With self arrival the controller's status and done travel too.
            bridge._post(pmt.intern("cmd"), pmt.to_pmt({"heading": theta, "slot": 6,
                                                        "stage": 3, "status": 2,
                                                        "done": True}))
            self.assertTrue(wait_until(lambda: len(vehicle.commands) >= 2))
            c = vehicle.commands[1]
            self.assertEqual((c["slot"], c["stage"], c["status"], c["done"]),
                             (6, 3, 2, True))

            def latest_heading():
                n = nav.num_messages()
                return pmt.to_python(nav.get_message(n - 1))["heading"] if n else None
            self.assertTrue(wait_until(lambda: latest_heading() is not None and
                                       abs(latest_heading() - theta) < 1e-9))
            # Malformed datagrams from the peer, and any datagram from a stranger.
            vehicle.reporting = False
            for junk in (b"\xff\xfe", b"not json", b'{"type": "cmd"}',
                         b'{"type": "nav", "heading_deg": "north"}',
                         b'{"type": "nav", "heading_deg": 400}',
                         b'{"type": "nav", "heading_deg": NaN}'):
                vehicle.report(junk)
            stranger = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            stranger.sendto(json.dumps({"type": "nav", "heading_deg": 123.0}).encode(),
                            bridge.local)
            stranger.close()
            self.assertTrue(wait_until(lambda: bridge.dropped["malformed"] == 6 and
                                       bridge.dropped["foreign"] == 1))
            # Still running: a good report gets through.
            before = nav.num_messages()
            vehicle.report(json.dumps({"type": "nav", "heading_deg": 90.0}).encode())
            self.assertTrue(wait_until(lambda: nav.num_messages() > before))
            self.assertAlmostEqual(latest_heading(), 0.0)
            # A malformed cmd message is counted, not sent.
            bridge._post(pmt.intern("cmd"), pmt.intern("left"))
            self.assertTrue(wait_until(lambda: bridge.dropped["cmd"] == 1))
        finally:
            tb.stop()
            tb.wait()
            vehicle.close()

    def test_repeats_the_last_command_when_reports_stop(self):
        vehicle, bridge, _, tb = linked(reporting=False, nav_timeout=0.2)
        try:
            bridge._post(pmt.intern("cmd"), pmt.to_pmt({"heading": 1.0}))
            self.assertTrue(wait_until(lambda: len(vehicle.commands) >= 2, timeout=5.0))
            self.assertEqual(vehicle.commands[0]["seq"], vehicle.commands[1]["seq"])
        finally:
            tb.stop()
            tb.wait()
            vehicle.close()

    def test_size_and_rate_bounds(self):
        vehicle, bridge, nav, tb = linked(reporting=False, nav_timeout=30.0,
                                          max_datagram=256, max_rate_hz=20.0)
        try:
            good = json.dumps({"type": "nav", "heading_deg": 45.0}).encode()
            big = json.dumps({"type": "nav", "heading_deg": 45.0, "pad": "x" * 300}).encode()
            vehicle.report(big)
            self.assertTrue(wait_until(lambda: bridge.dropped["oversize"] == 1))
            # A flood of 100 good reports at once: a burst of 20 (one second's worth) passes,
            # the rest is dropped and counted; nothing else is lost.
            t0 = time.monotonic()
            for _ in range(100):
                vehicle.report(good)
            self.assertTrue(wait_until(lambda: bridge.received + bridge.dropped["rate"] == 100))
            elapsed = time.monotonic() - t0
            self.assertGreaterEqual(bridge.received, 20)
            # at most the burst plus what the bucket refilled (20/s) while they came in
            self.assertLessEqual(bridge.received, 20 + math.ceil(20 * elapsed) + 1)
            self.assertTrue(wait_until(lambda: nav.num_messages() == bridge.received))
            # Once the bucket has refilled, reports at the allowed rate pass again.
            self.assertTrue(wait_until(lambda: bridge._tokens >= 1.0))
            before = bridge.received
            vehicle.report(good)
            self.assertTrue(wait_until(lambda: bridge.received == before + 1))
        finally:
            tb.stop()
            tb.wait()
            vehicle.close()

    def test_bad_parameters(self):
        with self.assertRaisesRegex(ValueError, "peer_port"):
            vehicle_bridge(local_port=0, peer_port=70000)
        with self.assertRaisesRegex(ValueError, "nav_timeout"):
            vehicle_bridge(local_port=0, peer_port=1, nav_timeout=0)
        with self.assertRaisesRegex(ValueError, "max_datagram"):
            vehicle_bridge(local_port=0, peer_port=1, max_datagram=10)
        for bad in (0, -1.0, float("nan"), "fast"):
            with self.assertRaisesRegex(ValueError, "max_rate_hz"):
                vehicle_bridge(local_port=0, peer_port=1, max_rate_hz=bad)


if __name__ == "__main__":
    gr_unittest.run(qa_vehicle_bridge)
