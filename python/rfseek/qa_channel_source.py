#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""channel_source in closed loop from Python: lockstep, reproducibility from the seed,
malformed commands, termination at d_v, and parameter errors as ValueError."""

import math
import subprocess
import sys
import threading
import time

import numpy as np
import pmt
from gnuradio import blocks, gr, gr_unittest
from gnuradio import rfseek


def console(lines, until=None, timeout=300, stamps=None):
    """Runs a script (its lines) in a fresh interpreter: (exit status, its console
    output, GNU Radio's log included). With `until`, a line goes to the script's stdin
    once a line of its output holds `until` (the script reads it to end); `stamps` (a
    list) then gets (time.monotonic(), line) for each line read before it."""
    p = subprocess.Popen([sys.executable, "-c", "\n".join(lines)], stdin=subprocess.PIPE,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seen = []
    if until is not None:
        for line in p.stdout:  # ends at the script's end too
            seen.append(line)
            if stamps is not None:
                stamps.append((time.monotonic(), line))
            if until in line:
                break
        p.stdin.write("stop\n")
        p.stdin.flush()
    out, _ = p.communicate(timeout=timeout)
    return p.returncode, "".join(seen) + out


class pilot(gr.basic_block):
    """Answers every state message with a cmd (the controller's role in a closed loop);
    optionally sends a malformed message first on chosen slots."""

    def __init__(self, heading_of_slot, junk=None):
        gr.basic_block.__init__(self, "pilot", [], [])
        self.message_port_register_in(pmt.intern("state"))
        self.message_port_register_out(pmt.intern("cmd"))
        self.set_msg_handler(pmt.intern("state"), self.handle)
        self.heading_of_slot = heading_of_slot
        self.junk = junk or {}
        self.states = []

    def handle(self, msg):
        state = pmt.to_python(msg)
        self.states.append(state)
        if state["arrived"] or state["capped"]:
            return
        slot = state["slot"]
        if slot in self.junk:
            self.message_port_pub(pmt.intern("cmd"), self.junk[slot])
        cmd = pmt.make_dict()
        cmd = pmt.dict_add(cmd, pmt.intern("heading"),
                           pmt.from_double(self.heading_of_slot(slot)))
        cmd = pmt.dict_add(cmd, pmt.intern("slot"), pmt.from_uint64(slot))
        self.message_port_pub(pmt.intern("cmd"), cmd)


def wait_until(condition, timeout_s):
    """Polls condition until it holds (True) or timeout_s passes (False)."""
    deadline = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.005)
    return True


def scenario(**kw):
    sc = rfseek.scenario(initial_distance_m=230.0, start_angle_rad=0.0,
                         start_heading_rad=math.pi, seed=3)
    for k, v in kw.items():
        setattr(sc, k, v)
    return sc


def run_loop(sc, heading_of_slot, mode="burst", junk=None):
    tb = gr.top_block()
    src = rfseek.channel_source(sc, mode=mode, lockstep=True, realtime=False)
    snk = blocks.vector_sink_c()
    p = pilot(heading_of_slot, junk)
    tb.connect(src, snk)
    tb.msg_connect(src, "state", p, "state")
    tb.msg_connect(p, "cmd", src, "cmd")
    tb.run()
    return src, snk, p


class qa_channel_source(gr_unittest.TestCase):

    def test_lockstep_loop_flies_the_commands_and_ends_at_dv(self):
        # Zig-zag toward the emitter: heading pi +- 0.3 alternating every 5 slots.
        def heading(k):
            return math.pi + (0.3 if (k // 5) % 2 else -0.3)
        sc = scenario()
        src, snk, p = run_loop(sc, heading)
        # Replay the same commands on the core world: same samples, same path.
        w = rfseek.world(sc)
        chunks = []
        while not w.finished:
            chunks.append(w.synthesize(sc.window_len))
            w.advance(heading(w.slot))
        ref = np.concatenate(chunks)
        data = np.array(snk.data(), dtype=np.complex64)
        self.assertEqual(len(data), len(ref))
        self.assertTrue(np.array_equal(data, ref))
        self.assertTrue(p.states[-1]["arrived"])
        self.assertLessEqual(p.states[-1]["distance"], sc.success_radius_m)
        self.assertEqual(p.states[-1]["slot"], w.slot)
        self.assertAlmostEqual(p.states[-1]["x"], w.x_m, places=9)
        # One beacon tag per slot, on its first sample, with slot and time.
        tags = [t for t in snk.tags() if pmt.symbol_to_string(t.key) == "rfseek_beacon"]
        self.assertEqual(len(tags), w.slot)
        for k, t in enumerate(tags):
            v = pmt.to_python(t.value)
            self.assertEqual(t.offset, k * sc.window_len)
            self.assertEqual(v["slot"], k)
            self.assertAlmostEqual(v["time"], k * sc.slot_period_s, places=12)
        # The truth says the UAV turned as commanded (instantaneous turns).
        for s in p.states[1:-1]:
            self.assertAlmostEqual(rfseek.world.wrap(s["heading"] - heading(s["slot"] - 1)),
                                   0.0, places=9)

    def test_same_seed_same_stream_other_seed_differs(self):
        h = lambda k: math.pi + 0.1
        a = np.array(run_loop(scenario(), h)[1].data())
        b = np.array(run_loop(scenario(), h)[1].data())
        c = np.array(run_loop(scenario(seed=4), h)[1].data())
        self.assertTrue(np.array_equal(a, b))
        self.assertFalse(np.array_equal(a[:len(c)], c[:len(a)]))

    def test_malformed_cmds_are_dropped_and_counted(self):
        junk = {
            2: pmt.intern("turn left"),                                     # not a dict
            4: pmt.dict_add(pmt.make_dict(), pmt.intern("hdg"), pmt.from_double(1.0)),
            6: pmt.dict_add(pmt.make_dict(), pmt.intern("heading"), pmt.intern("north")),
            8: pmt.dict_add(pmt.make_dict(), pmt.intern("heading"), pmt.from_double(float("nan"))),
            10: pmt.dict_add(pmt.dict_add(pmt.make_dict(), pmt.intern("heading"),
                                          pmt.from_double(0.0)),
                             pmt.intern("slot"), pmt.from_double(1.5)),
        }
        sc = scenario()
        src, snk, p = run_loop(sc, lambda k: math.pi, junk=junk)
        self.assertEqual(src.malformed_count(), len(junk))
        self.assertTrue(p.states[-1]["arrived"])
        # Nothing malformed moved the UAV: straight in, 60 slots for 30 m.
        self.assertEqual(p.states[-1]["slot"], 60)

    def test_stale_cmd_is_ignored(self):
        # A cmd for an earlier slot (here: slot - 1, heading away) must not be applied.
        stale = {k: pmt.dict_add(pmt.dict_add(pmt.make_dict(), pmt.intern("heading"),
                                              pmt.from_double(0.0)),
                                 pmt.intern("slot"), pmt.from_uint64(k - 1))
                 for k in range(1, 50)}
        src, snk, p = run_loop(scenario(), lambda k: math.pi, junk=stale)
        self.assertEqual(src.stale_count(), 49)
        self.assertEqual(p.states[-1]["slot"], 60)

    def test_continuous_mode_slot_length(self):
        sc = scenario(initial_distance_m=205.0)
        src, snk, p = run_loop(sc, lambda k: math.pi, mode="continuous")
        self.assertEqual(len(snk.data()), 10 * sc.slot_samples)

    def test_state_message_truth(self):
        sc = scenario(initial_distance_m=205.0, cfo_hz=123.0, cfo_drift_hz_per_s=0.0,
                      cfo_walk_hz_per_sqrt_s=0.0)
        src, snk, p = run_loop(sc, lambda k: math.pi)
        s0 = p.states[0]
        for key in ("slot", "time", "x", "y", "heading", "measured_heading", "distance",
                    "distance_flown", "cfo_hz", "doppler_hz", "snr_db", "power_db",
                    "arrived", "capped"):
            self.assertIn(key, s0)
        self.assertAlmostEqual(s0["distance"], 205.0)
        self.assertAlmostEqual(s0["cfo_hz"], 123.0)
        self.assertAlmostEqual(s0["doppler_hz"], sc.max_doppler_hz)
        self.assertEqual(len(p.states), 11)

    def test_free_running_realtime_emits_every_slot_once(self):
        # Pacing must not skip or repeat slots (10 slots = 0.5 s of real time).
        sc = scenario(initial_distance_m=205.0)
        tb = gr.top_block()
        src = rfseek.channel_source(sc, mode="continuous", lockstep=False, realtime=True)
        snk = blocks.vector_sink_c()
        states = blocks.message_debug()
        tb.connect(src, snk)
        tb.msg_connect(src, "state", states, "store")
        tb.run()
        slots = [pmt.to_python(states.get_message(i))["slot"]
                 for i in range(states.num_messages())]
        self.assertEqual(slots, list(range(11)))
        self.assertEqual(len(snk.data()), 10 * sc.slot_samples)

    def test_paced_source_goes_on_at_once_after_a_restart(self):
        # Pacing is a matter of wall time, so this test waits on conditions (no fixed
        # sleeps). Paced at 2 x real time (a slot every 25 ms), the first run flies 120
        # slots (3 s). Started again, the world's present slot must be due at once: 20
        # more slots take 0.5 s. Before the fix every slot waited as long again as the
        # first run had lasted (3 s), so the limit of half that has a wide margin both
        # ways.
        src = rfseek.channel_source(scenario(initial_distance_m=5000.0), mode="burst",
                                    lockstep=False, realtime=True, speedup=2.0)
        tb = gr.top_block()
        tb.connect(src, blocks.null_sink(gr.sizeof_gr_complex))
        tb.start()
        self.assertTrue(wait_until(lambda: src.slot() >= 120, 60.0))
        tb.stop()
        tb.wait()
        first = src.slot()
        stall = first * 0.05 / 2.0  # s: the first run's length, what the bug waited
        t0 = time.monotonic()
        tb.start()
        self.assertTrue(wait_until(lambda: src.slot() >= first + 20, 60.0))
        elapsed = time.monotonic() - t0
        tb.stop()
        tb.wait()
        self.assertLess(elapsed, 0.5 * stall)

    def test_stop_does_not_wait_for_a_slow_pace(self):
        # At 0.001 x real time the next slot is 50 s away: stop() must interrupt the wait
        # (it used to sleep it out). Once the first slot is out the source is waiting;
        # stop() runs in another thread, given a generous limit.
        src = rfseek.channel_source(scenario(), mode="continuous", lockstep=False,
                                    realtime=True, speedup=0.001)
        tb = gr.top_block()
        tb.connect(src, blocks.null_sink(gr.sizeof_gr_complex))
        tb.start()
        self.assertTrue(wait_until(lambda: src.slot() >= 1, 20.0))
        done = threading.Event()
        stopper = threading.Thread(target=lambda: (tb.stop(), tb.wait(), done.set()),
                                   daemon=True)
        stopper.start()
        self.assertTrue(done.wait(20.0), "stop() waited for the 50 s slot")

    def test_bad_parameters_raise_value_error(self):
        with self.assertRaisesRegex(ValueError, "scenario.snr_db"):
            rfseek.channel_source(scenario(snr_db=float("nan")))
        with self.assertRaisesRegex(ValueError, "scenario.window_len"):
            rfseek.channel_source(scenario(window_len=1))
        with self.assertRaisesRegex(ValueError, "mode"):
            rfseek.channel_source(scenario(), mode="pulsed")
        with self.assertRaisesRegex(ValueError, "scenario.speed_mps"):
            rfseek.world(scenario(speed_mps=-1.0))
        src = rfseek.channel_source(scenario())
        with self.assertRaisesRegex(ValueError, "scenario.heading_noise_rad"):
            src.set_heading_noise_rad(-1.0)

    def test_setters_take_effect(self):
        src = rfseek.channel_source(scenario(), lockstep=True)
        src.set_snr_db(12.0)
        self.assertEqual(src.config().snr_db, 12.0)
        src.set_turn_rate_rad_per_s(0.5)
        self.assertEqual(src.config().turn_rate_rad_per_s, 0.5)
        src.set_lockstep(False)
        self.assertFalse(src.lockstep())
        src.set_realtime(True)
        self.assertTrue(src.realtime())
        self.assertEqual(src.mode(), "burst")

    def test_lockstep_without_a_controller_says_what_it_waits_for(self):
        # The first flowgraph a user builds: source -> estimator -> message_debug with
        # the defaults (lockstep). The world waits for a cmd that never comes; it must
        # say so, once, and what would end the wait, within 2 s of the start (it is due
        # after 1.5 s of waiting; the bound allows a loaded machine 1 s more). In a
        # process of its own (GNU Radio's logger writes to that process's console),
        # stopped once the warning has come.
        stamps = []
        rc, out = console([
            "import select, sys",
            "from gnuradio import blocks, gr, rfseek",
            "tb = gr.top_block()",
            "sc = rfseek.scenario()",
            "src = rfseek.channel_source(sc)",
            "est = rfseek.doppler_estimator(sc.samp_rate_hz, sc.window_len, sc.fft_len)",
            "dbg = blocks.message_debug()",
            "tb.connect(src, est)",
            "tb.msg_connect(est, 'meas', dbg, 'store')",
            "tb.start()",
            "print('started', flush=True)",
            "select.select([sys.stdin], [], [], 120.0)",
            "print('measurements', dbg.num_messages(), flush=True)",
            "tb.stop()",
            "tb.wait()"], until="waits for a cmd", stamps=stamps)
        self.assertEqual(rc, 0, out)
        started = [t for t, line in stamps if line.startswith("started")]
        self.assertEqual(len(started), 1, out)
        waited = stamps[-1][0] - started[0]
        self.assertGreater(waited, 1.0, out)  # it waited before warning
        self.assertLess(waited, 3.0, out)
        warnings = [l for l in out.splitlines() if "waits for a cmd" in l]
        self.assertEqual(len(warnings), 1, out)
        self.assertIn("lockstep=False", warnings[0])
        self.assertIn("measurements 1", out)  # slot 0 only: it did wait

    def test_a_closed_loop_does_not_warn_of_waiting(self):
        # In lockstep with a controller every wait is short: the timer starts again at
        # every slot, so a whole flight (thousands of short waits) says nothing.
        rc, out = console([
            "from gnuradio import rfseek",
            "from gnuradio.rfseek.flowgraphs import closed_loop",
            "sc = rfseek.scenario(seed=3, initial_distance_m=600.0)",
            "tb = closed_loop(sc, 'adaptive')",
            "tb.run()",
            "print('slots', tb.collector.states[-1]['slot'], flush=True)"])
        self.assertEqual(rc, 0, out)
        self.assertGreater(int(out.split()[-1]), 500)  # "slots N"
        self.assertNotIn("waits for", out)
        self.assertNotIn("controller was told", out)  # one scenario for both

    def test_a_controller_told_another_world_warns_once_per_quantity(self):
        # A world at 25 m/s on 2.4 GHz, a controller told 10 m/s and 2.0 GHz: each
        # quantity is named once, with both values; the slot period agrees, unnamed.
        rc, out = console([
            "from gnuradio import rfseek",
            "from gnuradio.rfseek.flowgraphs import closed_loop",
            "sc = rfseek.scenario(seed=3, initial_distance_m=600.0, speed_mps=25.0,",
            "                     carrier_hz=2.4e9)",
            "cfg = rfseek.simulation.seeker_for(sc, 'adaptive')",
            "cfg.speed_mps, cfg.carrier_hz = 10.0, 2.0e9",
            "tb = closed_loop(sc, cfg)",
            "tb.run()"])
        self.assertEqual(rc, 0, out)
        told = [l for l in out.splitlines() if "controller was told" in l]
        self.assertEqual(len(told), 2, out)
        self.assertIn("speed_mps", told[0] + told[1])
        self.assertIn("has 25 m/s but this controller was told 10 m/s", out)
        self.assertIn("has 2.4e+09 Hz but this controller was told 2e+09 Hz", out)
        self.assertNotIn("slot_period_s:", out)


if __name__ == "__main__":
    gr_unittest.run(qa_channel_source)
