#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""channel_source(follow_truth=True): the world follows a recorded sequence of true
states (as a SITL's) on the simulator's clock. The beacon's measured frequency is the
Doppler of that motion plus the carrier offset; slots wait for the truth; the tags carry
no heading; malformed truths are counted and dropped. And the SITL helpers that need no
SITL: the frame conversion and the truth messages' conversion."""

import math
import time

import numpy as np
import pmt
from gnuradio import blocks, gr, gr_unittest
from gnuradio import rfseek
from gnuradio.rfseek import sitl

C = 299792458.0


def truths(n, t0=1000.0, dt=0.02):
    """A climbing, turning, speeding-up track in a frame offset from the world's."""
    out = []
    e, nn = 500.0, -300.0
    for k in range(n):
        t = t0 + dt * k
        speed, track = 6.0 + 0.002 * k, 0.3 + 0.0015 * k
        ve, vn = speed * math.cos(track), speed * math.sin(track)
        e += ve * dt
        nn += vn * dt
        out.append({"time": t, "east": e, "north": nn, "up": 40.0 + 0.01 * k,
                    "v_east": ve, "v_north": vn, "v_up": 0.5, "heading": track + 0.1})
    return out


def scenario():
    sc = rfseek.scenario(initial_distance_m=700.0, start_angle_rad=1.0, seed=5,
                         num_scatterers=0, add_noise=False, cfo_hz=40.0,
                         cfo_drift_hz_per_s=0.0, cfo_walk_hz_per_sqrt_s=0.0)
    sc.fft_len = 16384
    return sc


def beacon_tags(sink):
    return [t for t in sink.tags() if pmt.symbol_to_string(t.key) == "rfseek_beacon"]


def wait_until(condition, timeout_s=10.0):
    deadline = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.005)
    return True


class qa_follow_truth(gr_unittest.TestCase):

    def run_truths(self, sequence, junk=(), late=()):
        sc = scenario()
        tb = gr.top_block(catch_exceptions=False)
        src = rfseek.channel_source(sc, mode="burst", lockstep=False, follow_truth=True)
        est = rfseek.doppler_estimator(sc.samp_rate_hz, sc.window_len, sc.fft_len,
                                       interpolator="newton")
        meas = blocks.message_debug()
        states = blocks.message_debug()
        samples = blocks.vector_sink_c()
        tb.connect(src, est)
        tb.connect(src, samples)
        tb.msg_connect(est, "meas", meas, "store")
        tb.msg_connect(src, "state", states, "store")
        tb.start()
        try:
            for j in junk:
                src.to_basic_block()._post(pmt.intern("truth"), j)
            for t in sequence:
                src.to_basic_block()._post(pmt.intern("truth"), pmt.to_pmt(t))
            for t in late:  # before the last one: dropped
                src.to_basic_block()._post(pmt.intern("truth"), pmt.to_pmt(t))
            span = sequence[-1]["time"] - sequence[0]["time"]
            expected = int(span / sc.slot_period_s + 1e-9) + 1
            # The estimator and the sample sink run in their own threads: wait for both,
            # and for the source to have handled every message posted (the late one
            # can come after the last beacon it makes).
            posted = len(junk) + len(sequence) + len(late)
            self.assertTrue(wait_until(lambda: meas.num_messages() >= expected
                                       and len(beacon_tags(samples)) >= expected
                                       and src.truth_count() + src.truth_dropped_count()
                                       >= posted))
        finally:
            tb.stop()
            tb.wait()
        ms = [pmt.to_python(meas.get_message(i)) for i in range(meas.num_messages())]
        ss = [pmt.to_python(states.get_message(i)) for i in range(states.num_messages())]
        return sc, src, ms, ss, beacon_tags(samples), expected

    def test_the_beacon_is_the_doppler_of_the_true_motion(self):
        seq = truths(60)  # 1.18 s of truth at 50 Hz: slots 0..23
        sc, src, ms, ss, tags, expected = self.run_truths(seq)
        self.assertEqual(len(ms), expected)
        self.assertEqual(src.truth_count(), len(seq))
        lam = C / sc.carrier_hz
        # The scene turned so that the first heading is the scenario's start heading.
        turn = seq[0]["heading"] - rfseek.world(sc).heading_rad
        x0, y0 = 700.0 * math.cos(1.0 + turn), 700.0 * math.sin(1.0 + turn)
        for m, s in zip(ms, ss):
            k = int(m["slot"])
            t = seq[0]["time"] + k * sc.slot_period_s
            # The truth at the slot's time, interpolated here independently.
            i = int((t - seq[0]["time"]) / 0.02 + 1e-9)
            j = min(i + 1, len(seq) - 1)
            u = (t - seq[i]["time"]) / 0.02 if j > i else 0.0
            at = {key: seq[i][key] + u * (seq[j][key] - seq[i][key]) for key in seq[i]}
            x = x0 + at["east"] - seq[0]["east"]
            y = y0 + at["north"] - seq[0]["north"]
            h = at["up"]
            d3 = math.sqrt(x * x + y * y + h * h)
            doppler = (at["v_east"] * -x + at["v_north"] * -y + at["v_up"] * -h) / d3 / lam
            self.assertAlmostEqual(s["x"], x, delta=1e-6)
            self.assertAlmostEqual(s["y"], y, delta=1e-6)
            self.assertAlmostEqual(s["doppler_hz"], doppler, delta=1e-6)
            self.assertAlmostEqual(m["time"], k * sc.slot_period_s, delta=1e-9)
            # A noise-free tone: the estimator reads Doppler + carrier offset.
            self.assertAlmostEqual(m["freq_hz"], doppler + 40.0, delta=0.05)
        # Every beacon's tag, and none carries a heading (the autopilot's comes on nav).
        self.assertEqual(len(tags), expected)
        self.assertTrue(all("heading" not in pmt.to_python(t.value) for t in tags))
        self.assertTrue(all("slot" in pmt.to_python(t.value) for t in tags))

    def test_bad_truths_are_counted_and_dropped(self):
        seq = truths(30)
        junk = [pmt.intern("junk"), pmt.to_pmt({"time": 1.0}),
                pmt.to_pmt(dict(seq[0], up=float("nan")))]
        sc, src, ms, ss, tags, expected = self.run_truths(seq, junk, late=[seq[3]])
        # Three malformed, and one before the last truth.
        self.assertEqual(src.truth_dropped_count(), 4)
        self.assertEqual(src.truth_count(), len(seq))
        self.assertEqual(len(ms), expected)
        self.assertTrue(all(np.isfinite(m["freq_hz"]) for m in ms))

    def test_frames_and_truth_messages(self):
        home = sitl.HOME
        e, n, u = sitl.lla_to_local(home[0] + 0.001, home[1] + 0.001, home[2] + 12.5, home)
        self.assertAlmostEqual(n, math.radians(0.001) * sitl.EARTH_RADIUS_M, delta=1e-6)
        self.assertAlmostEqual(e, math.radians(0.001) * sitl.EARTH_RADIUS_M *
                               math.cos(math.radians(home[0])), delta=1e-6)
        self.assertAlmostEqual(u, 12.5, delta=1e-9)

        reader = sitl.truth_reader.__new__(sitl.truth_reader)  # no connection
        reader.kind, reader.home = "px4", home
        att = rfseek.mavlink.message("ATTITUDE")  # the autopilot's own: compass 42 deg
        att.set("yaw", math.radians(42.0))
        reader.client = type("client", (), {"time_boot_ms": 5000,
                                            "last": {"ATTITUDE": att}})()
        m = rfseek.mavlink.message("HIL_STATE_QUATERNION")
        m.set_int("time_usec", 12345678)
        yaw = math.radians(30.0)  # 30 deg clockwise from north: 60 deg CCW from east
        for i, q in enumerate((math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))):
            m.set("attitude_quaternion", q, i)
        m.set_int("lat", int(round(home[0] * 1e7)))
        m.set_int("lon", int(round(home[1] * 1e7)))
        m.set_int("alt", int(round((home[2] + 30.0) * 1e3)))
        m.set("vx", 300)   # north, cm/s
        m.set("vy", -400)  # east
        m.set("vz", -50)   # down: climbing
        t = reader.convert(m)
        self.assertAlmostEqual(t["time"], 12.345678)
        self.assertAlmostEqual(t["heading"], math.radians(60.0), delta=1e-6)
        self.assertAlmostEqual(t["reported_heading"], math.radians(48.0), delta=1e-6)
        self.assertAlmostEqual(t["bank"], 0.0, delta=1e-9)  # a yaw alone: wings level
        roll = math.radians(20.0)  # then rolled 20 deg right about the body's x axis
        qr = (math.cos(roll / 2), math.sin(roll / 2), 0.0, 0.0)
        qy = [m.get("attitude_quaternion", i) for i in range(4)]
        w1, x1, y1, z1 = qy
        w2, x2, y2, z2 = qr
        for i, q in enumerate((w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
                               w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                               w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                               w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)):
            m.set("attitude_quaternion", q, i)
        t = reader.convert(m)
        self.assertAlmostEqual(t["bank"], roll, delta=1e-6)
        self.assertAlmostEqual(t["heading"], math.radians(60.0), delta=1e-6)
        self.assertAlmostEqual(t["v_north"], 3.0)
        self.assertAlmostEqual(t["v_east"], -4.0)
        self.assertAlmostEqual(t["v_up"], 0.5)
        self.assertAlmostEqual(t["up"], 30.0, delta=1e-3)
        s = rfseek.mavlink.message("SIM_STATE")
        s.set("yaw", math.radians(-90.0))  # west
        s.set("roll", 0.3)
        s.set_int("lat_int", int(round((home[0] + 0.0001) * 1e7)))
        s.set_int("lon_int", int(round(home[1] * 1e7)))
        s.set("alt", home[2] + 50.0)
        s.set("vn", 1.0)
        s.set("ve", 2.0)
        s.set("vd", 0.5)
        t = reader.convert(s)
        self.assertAlmostEqual(t["time"], 5.0)  # the clock of the ATTITUDE with it
        self.assertAlmostEqual(t["bank"], 0.3, delta=1e-6)
        self.assertAlmostEqual(math.remainder(t["heading"] - math.pi, 2 * math.pi), 0.0,
                               delta=1e-6)
        self.assertAlmostEqual(t["north"], math.radians(0.0001) * sitl.EARTH_RADIUS_M,
                               delta=0.02)
        self.assertAlmostEqual(t["v_up"], -0.5)

    def test_missing_sitl_is_one_clear_error(self):
        with self.assertRaises(sitl.SitlError) as cm:
            sitl.find_sitl("/nonexistent/rfseek-sitl")
        self.assertIn("/nonexistent/rfseek-sitl", str(cm.exception))
        with self.assertRaises(ValueError) as cm:
            sitl.sitl_process("inav")
        self.assertIn("vehicle", str(cm.exception))


if __name__ == "__main__":
    gr_unittest.run(qa_follow_truth)
