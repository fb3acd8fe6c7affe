#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""The closed loop through GNU Radio against the core simulation (slot by slot, same
seed), and seeking_controller's handling of invalid and malformed messages."""

import importlib.util
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import pmt
from gnuradio import blocks, gr, gr_unittest
from gnuradio import rfseek
from gnuradio.rfseek import flowgraphs


def meas(slot, freq, valid=True, heading=None):
    d = {"slot": slot, "freq_hz": freq, "valid": valid, "snr_db": 0.0}
    if heading is not None:
        d["heading"] = heading
    return pmt.to_pmt(d)


class qa_closed_loop(gr_unittest.TestCase):

    def test_flowgraph_equals_core_simulation(self):
        for seed, strategy in ((3, "paper"), (8, "paper"), (3, "adaptive"), (5, "adaptive")):
            sc = rfseek.scenario(seed=seed)
            tb = flowgraphs.closed_loop(sc, strategy)
            tb.run()
            core = rfseek.simulation(sc, rfseek.simulation.seeker_for(sc, strategy)).run()
            c = core.columns()
            states = tb.collector.states
            tel = tb.collector.telemetry
            n = len(c["x_m"])
            self.assertEqual(len(tel), n)
            self.assertEqual(len(states), n + 1)  # plus the arrival state
            x = np.array([s["x"] for s in states[:n]])
            y = np.array([s["y"] for s in states[:n]])
            h = np.array([t["heading"] for t in tel])
            what = "%s seed %d" % (strategy, seed)
            self.assertTrue(np.array_equal(x, c["x_m"]), what + ": x differs")
            self.assertTrue(np.array_equal(y, c["y_m"]), what + ": y differs")
            self.assertTrue(np.array_equal(h, c["cmd_heading_rad"]))
            self.assertEqual([t["stage"] for t in tel], list(c["stage"].astype(int)))
            self.assertTrue(states[-1]["arrived"])
            self.assertTrue(core.summary.success)
            self.assertAlmostEqual(states[-1]["distance_flown"], core.summary.distance_m)

    def test_grc_example_flies_the_core_trajectory(self):
        # examples/seek_sim.grc, compiled by grcc and run headless (offscreen Qt), gives the
        # core simulation's trajectory for its seed, for the default strategy and for the
        # one given by its "strategy" parameter (as --strategy on its command line).
        source = os.environ.get("RFSEEK_SOURCE_DIR",
                                os.path.join(os.path.dirname(__file__), "..", ".."))
        out = tempfile.mkdtemp(prefix="rfseek_grc_")
        p = subprocess.run([sys.executable, "/usr/bin/grcc", "-o", out,
                            os.path.join(source, "examples", "seek_sim.grc")],
                           capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stderr)
        spec = importlib.util.spec_from_file_location("seek_sim", os.path.join(out, "seek_sim.py"))
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
        from PyQt5 import Qt
        app = Qt.QApplication.instance() or Qt.QApplication([])
        for strategy in (None, "adaptive"):
            tb = mod.seek_sim() if strategy is None else mod.seek_sim(strategy=strategy)
            self.assertEqual(tb.controller.config().strategy, strategy or "paper")
            col = flowgraphs.collector()
            tb.msg_connect(tb.channel, "state", col, "state")
            tb.start()
            tb.wait()
            sc = tb.channel.config()
            core = rfseek.simulation(
                sc, rfseek.simulation.seeker_for(sc, strategy or "paper")).run()
            c = core.columns()
            n = len(c["x_m"])
            self.assertEqual(len(col.states), n + 1)
            self.assertTrue(np.array_equal(np.array([s["x"] for s in col.states[:n]]),
                                           c["x_m"]))
            self.assertTrue(np.array_equal(np.array([s["y"] for s in col.states[:n]]),
                                           c["y_m"]))
            self.assertTrue(col.states[-1]["arrived"])
            del tb
        del app

    def test_invalid_and_malformed_messages(self):
        cfg = rfseek.seeker_config(strategy="paper_no_circle", initial_heading_rad=0.5)
        ctl = rfseek.seeking_controller(cfg)
        cmds = blocks.message_debug()
        tel = blocks.message_debug()
        tb = gr.top_block()
        tb.msg_connect(ctl, "cmd", cmds, "store")
        tb.msg_connect(ctl, "telemetry", tel, "store")
        port = pmt.intern("meas")
        msgs = [
            meas(0, 100.0, heading=0.5),
            meas(1, 0.0, valid=False),                        # invalid: still answered
            pmt.intern("garbage"),                            # not a dict: dropped
            pmt.to_pmt({"freq_hz": 3.0, "valid": True}),      # no slot: dropped
            pmt.to_pmt({"slot": 2, "valid": True}),           # no freq: answered as invalid
            pmt.to_pmt({"slot": 3, "freq_hz": float("nan"), "valid": True}),  # NaN: invalid
            meas(4, 101.0),
        ]
        for m in msgs:
            ctl._post(port, m)
        ctl._post(pmt.intern("nav"), pmt.to_pmt({"heading": "north"}))  # malformed nav
        ctl._post(pmt.intern("system"), pmt.cons(pmt.intern("done"), pmt.from_long(1)))
        tb.start()
        tb.wait()
        answered = [pmt.to_python(cmds.get_message(i)) for i in range(cmds.num_messages())]
        self.assertEqual([a["slot"] for a in answered], [0, 1, 2, 3, 4])
        for a in answered:
            self.assertTrue(math.isfinite(a["heading"]))
            self.assertEqual(a["stage"], 2)
        # Stage 2 from the initial heading: theta + delta for the first M slots.
        self.assertAlmostEqual(answered[0]["heading"], 0.5 + cfg.delta_rad)
        self.assertEqual(ctl.malformed_count(), 4)  # garbage, no slot, no freq, bad nav
        self.assertEqual(ctl.invalid_count(), 3)    # invalid, no freq, NaN
        self.assertEqual(ctl.meas_count(), 5)
        t = [pmt.to_python(tel.get_message(i)) for i in range(tel.num_messages())]
        for entry in t:
            for v in entry.values():
                if isinstance(v, float):
                    self.assertTrue(math.isfinite(v))

    def test_bad_configuration_raises_value_error(self):
        with self.assertRaisesRegex(ValueError, "seeker_config.strategy"):
            rfseek.seeking_controller(rfseek.seeker_config(strategy="gradient"))
        with self.assertRaisesRegex(ValueError, "seeker_config.m_slots"):
            rfseek.seeking_controller(rfseek.seeker_config(m_slots=0))
        with self.assertRaises(TypeError):
            rfseek.seeker_config(delta=0.1)


if __name__ == "__main__":
    gr_unittest.run(qa_closed_loop)
