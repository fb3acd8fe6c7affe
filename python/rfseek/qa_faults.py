#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""doppler_estimator under the faults a real receiver brings, on a pulsed beacon made by
GNU Radio's own blocks at -10 dB per-sample SNR, timing unknown (rfseek.faults):
an overflow's lost samples and the rx_time tag after them, a clock that jumps (windows
timed by the tag in force at their first sample, slots that follow time across the gap,
no window valid across it); a continuous carrier 20 dB above the beacon and wideband
noise bursts (the beacon found and measured, the interferer never reported)."""

import time

import numpy as np
import pmt
from gnuradio import blocks, gr, gr_unittest
from gnuradio import rfseek
from gnuradio.rfseek import faults

FS, N, PERIOD = faults.FS, faults.N, faults.PERIOD


def by_offset(meas, at):
    return [m for m in meas if m["offset"] < at], [m for m in meas if m["offset"] >= at]


class qa_faults(gr_unittest.TestCase):

    def check_overflow(self, seed, at, lost, chunk=None):
        s = faults.overflow(faults.beacon_stream(seed, -10.0, 8.0, 20.0), at, lost)
        est, meas = faults.measure(s, chunk=chunk)
        r = faults.score(meas, s)
        self.assertEqual(est.discontinuity_count(), 1)
        # Every window timed by the tag in force at its first sample (the target is
        # 0.1 ms; the clock itself is exact to the float).
        self.assertLess(r["max_clock_err_s"], 1e-6)
        # One lock throughout; no window valid off a burst or across the gap.
        self.assertEqual({m["lock"] for m in meas}, {1})
        self.assertEqual(r["false"], 0)
        self.assertGreaterEqual(r["found"], 0.99 * r["sent"])
        self.assertLessEqual(r["rms_over_crb"], 1.2)
        before, after = by_offset(meas, at)
        self.assertTrue(all(m["offset"] + N <= at for m in before))
        # Locked again at once: one of the first two bursts after the gap is measured.
        after_gap = [k for k in range(len(s.starts)) if s.starts[k] >= at]
        first = min(k for k in r["hit"] if k in after_gap)
        self.assertLessEqual(first - after_gap[0], 1)
        # Slots follow time: the beacon periods between two windows, whatever was lost.
        a, b = before[-1], after[0]
        self.assertEqual(b["slot"] - a["slot"], round((b["time"] - a["time"]) * FS / PERIOD))
        return r

    def test_an_overflow_of_a_few_thousand_samples(self):
        for seed, at, lost in ((31, 400_123, 3000), (32, 351_000, 4999)):
            self.check_overflow(seed, at, lost)

    def test_an_overflow_in_small_chunks(self):
        # The tag in force is found whatever the work() calls' boundaries.
        self.check_overflow(33, 300_007, 2500, chunk=997)

    def test_a_clock_that_jumps_by_7_s(self):
        # Before the fix, the windows before the jump read 7 s late.
        s = faults.overflow(faults.beacon_stream(34, -10.0, 12.0, 20.0), 300_000, 700_000)
        est, meas = faults.measure(s)
        r = faults.score(meas, s)
        self.assertLess(r["max_clock_err_s"], 1e-6)
        self.assertEqual(r["false"], 0)
        self.assertGreaterEqual(r["found"], 0.99 * r["sent"])
        before, after = by_offset(meas, 300_000)
        self.assertEqual(after[0]["slot"] - before[-1]["slot"],
                         round((after[0]["time"] - before[-1]["time"]) * FS / PERIOD))

    def check_interferer(self, seed, **kw):
        s = faults.beacon_stream(seed, -10.0, 10.0, 20.0, **kw)
        est, meas = faults.measure(s)
        r = faults.score(meas, s)
        self.assertEqual(r["false"], 0)
        self.assertEqual(r["on_interferer"], 0)
        self.assertGreaterEqual(r["found"], 0.97 * r["sent"])
        self.assertGreater(r["sent"], 190)
        self.assertLessEqual(r["rms_over_crb"], 1.2)
        if s.cw_freq is not None:  # found, and removed from every window
            self.assertTrue(any(abs(f - s.cw_freq) < 5.0 for f in est.carriers()),
                            (est.carriers(), s.cw_freq))
        return r

    def test_a_carrier_20_dB_above_the_beacon(self):
        # Anywhere in the band outside +-1 kHz of the beacon: here 1.3 kHz and 31 kHz.
        for seed, offset in ((41, 1300.0), (42, -31000.0)):
            self.check_interferer(seed, cw_db=20.0, cw_offset=offset)

    def test_wideband_noise_bursts(self):
        # 10 ms bursts 10 dB over the noise, two a second at random times.
        self.check_interferer(43, wideband_db=10.0)

    def run_tagged(self, x, tags, **kw):
        tb = gr.top_block()
        src = blocks.vector_source_c(x.tolist(), False, 1, tags)
        est = rfseek.doppler_estimator(FS, N, 4096, **kw)
        dbg = blocks.message_debug()
        tb.connect(src, est)
        tb.msg_connect(est, "meas", dbg, "store")
        tb.run()
        return est, [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())]

    def test_periodic_windows_follow_time_across_a_gap(self):
        # A continuous tone, windows every 1500 samples; 2600 samples lost at 9500.
        x = np.exp(2j * np.pi * 1234.5 * np.arange(30_000) / FS).astype(np.complex64)
        cut = np.concatenate([x[:9500], x[12_100:]])
        tags = [faults._tag(0, "rx_time", (100, 0.5)),
                faults._tag(9500, "rx_time", (100, 0.5 + 12_100 / FS))]
        est, meas = self.run_tagged(cut, tags, alignment="periodic", period=1500)
        self.assertEqual(est.discontinuity_count(), 1)
        for m in meas:
            t = m["time"] - 100.5
            # Windows start on the period in the stream's time, numbered by it.
            self.assertAlmostEqual(t * FS, round(t * FS / 1500) * 1500, places=3)
            self.assertEqual(m["slot"], round(t * FS / 1500))
            straddles = m["offset"] < 9500 < m["offset"] + N
            self.assertEqual(m["valid"], not straddles)
        self.assertEqual(sum(not m["valid"] for m in meas), 1)  # the one at 9000
        self.assertEqual([m["slot"] for m in meas if m["valid"]][6:8], [9, 10])

    def test_a_tagged_window_straddling_a_gap_is_invalid(self):
        x = np.exp(2j * np.pi * 500.0 * np.arange(5000) / FS).astype(np.complex64)
        tags = [faults._tag(0, "rx_time", (7, 0.0)),
                faults._tag(100, "rfseek_beacon", {"slot": 1}),
                faults._tag(600, "rx_time", (7, 0.5)),  # 0.494 s lost
                faults._tag(2000, "rfseek_beacon", {"slot": 2})]
        est, meas = self.run_tagged(x, tags)
        self.assertEqual([(m["slot"], m["valid"]) for m in meas], [(1, False), (2, True)])
        self.assertAlmostEqual(meas[0]["time"], 7.001, places=9)
        self.assertAlmostEqual(meas[1]["time"], 7.514, places=9)
        self.assertEqual(est.truncated_count(), 1)

    def test_a_clipped_window_is_never_valid(self):
        # A tone at half of full scale, then one at 1.3 clipped by the ADC at 1.0 per
        # component (I and Q, as a radio's converter does), in periodic windows; and the
        # same under acquire, where the check reads the samples as received.
        n = 20 * N
        t = np.arange(n)
        amp = np.where(t < n // 2, 0.5, 1.3)
        x = amp * np.exp(2j * np.pi * 1500.0 * t / FS)
        x = (np.clip(x.real, -1, 1) + 1j * np.clip(x.imag, -1, 1)).astype(np.complex64)
        est, meas = self.run_tagged(x, [], alignment="periodic", period=N)
        self.assertEqual(len(meas), 20)
        self.assertNotIn("clipped", meas[0])  # full scale unknown: no check
        self.assertTrue(all(m["valid"] for m in meas))
        pulsed = np.where(t % (2 * N) < N, x, 0).astype(np.complex64)
        for alignment, period, y in (("periodic", N, x), ("acquire", 2 * N, pulsed)):
            tb = gr.top_block()
            src = blocks.vector_source_c(y.tolist(), False)
            est = rfseek.doppler_estimator(FS, N, 4096, alignment=alignment, period=period)
            est.set_full_scale(1.0)
            dbg = blocks.message_debug()
            tb.connect(src, est)
            tb.msg_connect(est, "meas", dbg, "store")
            tb.run()
            meas = [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())]
            self.assertGreater(len(meas), 5, alignment)
            for m in meas:
                clipped = m["offset"] + N > n // 2
                self.assertEqual(m["clipped"], clipped, (alignment, m["offset"]))
                if clipped:
                    self.assertFalse(m["valid"])
                    self.assertGreater(m["peak_dbfs"], -0.01)
                else:
                    self.assertAlmostEqual(m["peak_dbfs"], 20 * np.log10(0.5), delta=0.01)
            self.assertEqual(est.clipped_count(), sum(m["clipped"] for m in meas))
        for bad in (-1.0, float("nan"), float("inf")):
            with self.assertRaisesRegex(ValueError, "full_scale"):
                est.set_full_scale(bad)

    def test_the_rehearsals_overflow_injector(self):
        # A ramp through the injector: 3000 samples lost every 20 s (at 1 kS/s), each
        # gap's next sample tagged with its true time; the estimator counts each one.
        # rx_rate tags every 1000 samples: those in a gap go out with the next time.
        from gnuradio.rfseek.rehearsal import overflow_injector
        from gnuradio.rfseek.live_options import fault
        x = np.arange(100_000).astype(np.complex64)
        tb = gr.top_block()
        rate_tags = [gr.python_to_tag((p, pmt.intern("rx_rate"), pmt.from_double(1000.0),
                                       pmt.PMT_F)) for p in range(500, 100_000, 1000)]
        src = blocks.vector_source_c(x.tolist(), False, 1, rate_tags)
        inj = overflow_injector(1000.0, **fault("overflow:20,3000")[1], seed=3)
        snk = blocks.vector_sink_c()
        est = rfseek.doppler_estimator(1000.0, 64, 64, alignment="periodic", period=100)
        tb.connect(src, inj, snk)
        tb.connect(inj, est)
        tb.run()
        y = np.array(snk.data()).real
        self.assertEqual(inj.overflows, 4)
        self.assertEqual(len(y), 100_000 - 4 * 3000)
        jumps = np.nonzero(np.diff(y) != 1)[0] + 1
        self.assertTrue(np.all(np.diff(y)[jumps - 1] == 3001))
        times = {t.offset: pmt.to_python(t.value) for t in snk.tags()
                 if pmt.symbol_to_string(t.key) == "rx_time"}
        self.assertEqual(sorted(times), [0] + list(jumps))
        for k, (secs, frac) in times.items():
            self.assertAlmostEqual(secs + frac, y[k] / 1000.0, places=9)
        where = {int(v): k for k, v in enumerate(y)}  # input sample -> output index
        expected = set()
        for p in range(500, 100_000, 1000):
            # kept: at its own sample; dropped: at the first sample after its gap
            expected.add(where.get(p, next((k for k in jumps if y[k] > p), None)))
        rates = [t.offset for t in snk.tags() if pmt.symbol_to_string(t.key) == "rx_rate"]
        self.assertEqual(len(rates), len(set(rates)))
        self.assertEqual(set(rates), expected)
        self.assertEqual(len(rates), 100 - 4 * 3 + 4)  # 3 in each gap, one carried
        self.assertEqual(est.discontinuity_count(), 4)
        with self.assertRaises(Exception):
            fault("overflow:0")

    def test_the_gain_loop_keeps_the_beacon_below_full_scale(self):
        # A beacon whose peak rises from -40 to +5 dBFS at the start gain over 45 s (the
        # last kilometres: it would clip from 39.5 s on), then falls back; a radio whose
        # gain moves the peak and the power dB for dB, applied 0.1 s after it is set.
        from gnuradio.rfseek.gain_loop import gain_loop
        radio = {"gain": 30.0, "pending": []}
        now = [0.0]
        out, commands = [], []

        class probe(gain_loop):
            def message_port_pub(self, port, msg):
                (out if pmt.symbol_to_string(port) == "meas" else commands).append(
                    pmt.to_python(msg))

        loop = probe(lambda g: radio["pending"].append((now[0] + 0.1, g)), 30.0, 0.0)
        for k in range(2000):
            t = now[0] = 0.05 * k
            while radio["pending"] and radio["pending"][0][0] <= t:
                radio["gain"] = radio["pending"].pop(0)[1]
            level = -40.0 + min(t, 45.0) - max(0.0, t - 50.0)  # dBFS at gain 30
            peak = level + radio["gain"] - 30.0
            msg = {"time": t, "valid": True, "peak_dbfs": min(peak, 0.0), "clipped": peak >= -0.45,
                   "power_db": level - 3.0 + radio["gain"] - 30.0, "noise_power_db": -50.0}
            loop.on_meas(pmt.to_pmt(msg))
        # Down as it rises, up as it falls.
        self.assertTrue(any(b > a for _, b, a in loop.changes))
        self.assertTrue(any(b < a for _, b, a in loop.changes))
        for m in out:
            if m["valid"]:
                self.assertFalse(m["clipped"])
                # The power referred to the start gain: the beacon's own, whatever the gain.
                level = -40.0 + min(m["time"], 45.0) - max(0.0, m["time"] - 50.0)
                self.assertAlmostEqual(m["power_db"], level - 3.0, places=9)
        clipped = [m for m in out if m["clipped"]]
        self.assertLessEqual(len(clipped), 3)
        self.assertGreater(sum(m["valid"] for m in out), 0.95 * len(out))
        self.assertEqual(loop.gain_db, 30.0)  # back at the start once it has fallen
        # Every change also went out as a radio's command, in order.
        self.assertEqual(commands, [{"gain": after} for _, _, after in loop.changes])
        with self.assertRaisesRegex(ValueError, "set_gain"):
            gain_loop("radio", 30.0, 0.0)

    def test_the_gain_loop_follows_the_users_gain_and_refuses_bad_settings(self):
        # A slider moves the radio to 20 dB (set_gain_db, the GRC callback): windows
        # from the latest one on are referred to it, and the loop steps up to 20 only.
        from gnuradio.rfseek.gain_loop import gain_loop
        out = []

        class probe(gain_loop):
            def message_port_pub(self, port, msg):
                if pmt.symbol_to_string(port) == "meas":
                    out.append(pmt.to_python(msg))

        loop = probe(None, np.float32(30.0), 0, hold=np.int64(2))
        meas = lambda t, peak: loop.on_meas(pmt.to_pmt(
            {"time": t, "valid": True, "peak_dbfs": peak, "power_db": -50.0}))
        meas(1.0, -20.0)
        loop.set_gain_db(20.0)
        meas(1.5, -40.0)
        for t in (2.0, 2.05, 2.1, 2.15):
            meas(t, -40.0)
        self.assertEqual(loop.gain_db, 20.0)  # quiet, but not above the user's gain
        self.assertEqual([m["gain_db"] for m in out], [30.0] + [20.0] * 5)
        self.assertEqual(out[1]["power_db"], -40.0)  # referred to the first 30 dB
        loop.on_meas(pmt.to_pmt({"time": float("nan"), "valid": True}))
        self.assertEqual((loop.dropped, len(out)), (1, 6))
        for bad, name in (({"gain_db": True}, "gain_db"), ({"min_db": 40.0}, "min_db"),
                          ({"high_dbfs": -40.0}, "high_dbfs"),
                          ({"step_down_db": 0.0}, "step_down_db"),
                          ({"settle_s": -1.0}, "settle_s"), ({"hold": 0}, "hold"),
                          ({"hold": 2.5}, "hold")):
            kw = dict({"set_gain": None, "gain_db": 30.0, "min_db": 0.0}, **bad)
            with self.assertRaisesRegex(ValueError, name):
                gain_loop(**kw)
        with self.assertRaisesRegex(ValueError, "gain_db"):
            loop.set_gain_db(-1.0)

    def test_a_radio_takes_the_gain_loops_commands(self):
        # gain_loop (no setter: the GRC block) -> a radio_source's command port: each
        # {"gain": dB} reaches the radio's setter; other messages are counted and dropped
        # while it keeps going.
        from gnuradio.rfseek.gain_loop import gain_loop
        from gnuradio.rfseek.radios import _commands
        got = []
        radio = _commands({"gain": got.append, "freq": got.append})
        loop = gain_loop(None, 30.0, 0.0)
        tb = gr.top_block()
        tb.msg_connect(loop, "command", radio, "command")
        tb.start()
        try:
            for k, peak in enumerate((-20.0, 0.0, -20.0, 1.0)):
                loop.to_basic_block()._post(pmt.intern("meas"), pmt.to_pmt(
                    {"time": 1.0 * k, "valid": True, "peak_dbfs": peak,
                     "clipped": peak >= 0.0}))
            for bad in (pmt.intern("gain"), pmt.to_pmt({"gain": "high"}),
                        pmt.to_pmt({"volume": 3.0}), pmt.to_pmt({"gain": float("nan")})):
                radio.to_basic_block()._post(pmt.intern("command"), bad)
            deadline = time.time() + 5.0
            while (len(got) < 2 or radio.dropped < 4) and time.time() < deadline:
                time.sleep(0.01)
        finally:
            tb.stop()
            tb.wait()
        self.assertEqual(got, [20.0, 10.0])  # two clipped windows, 10 dB each
        self.assertEqual(radio.dropped, 4)

    def test_rfseek_live_puts_the_gain_loop_on_radios_and_rehearsals(self):
        import argparse
        from gnuradio.rfseek import live_options
        from gnuradio.rfseek.gain_loop import gain_loop
        from gnuradio.rfseek.rehearsal import rehearsal_source
        sc = rfseek.scenario(carrier_hz=915e6)
        src = rehearsal_source(sc, "rtlsdr", realtime=False)
        on = argparse.Namespace(agc="on", gain=None)
        loop = live_options.gain_control(on, src)
        self.assertIsInstance(loop, gain_loop)
        loop.set_gain(-10.0)  # the simulated radio's own setter
        self.assertEqual(src.radio.gain_db, -10.0)
        self.assertIsNone(live_options.gain_control(argparse.Namespace(agc="off"), src))
        plain = rfseek.channel_source(sc, lockstep=False)
        self.assertIsNone(live_options.gain_control(on, plain))

    def _controller_with_reports(self, reports):
        """A running controller (telemetry into a message_debug) that has handled the
        nav `reports` ((heading, time) pairs): windows within them are sent until one
        comes back paired (nav and meas are separate queues). Returns (top block,
        controller, message_debug, post, the telemetry messages so far)."""
        ctl = rfseek.seeking_controller(rfseek.seeker_config())
        dbg = blocks.message_debug()
        tb = gr.top_block()
        tb.msg_connect(ctl, "telemetry", dbg, "store")
        tb.start()
        post = lambda port, d: ctl.to_basic_block()._post(pmt.intern(port), pmt.to_pmt(d))
        for heading, t in reports:
            post("nav", {"heading": heading, "time": t})
        first = min(t for _, t in reports)
        deadline = time.monotonic() + 10.0
        paired, k = False, 0
        while not paired and time.monotonic() < deadline:
            k = min(k + 1, 10)
            post("meas", {"slot": k, "time": first + 0.01 * k, "freq_hz": 10.0,
                          "valid": True})
            time.sleep(0.01)
            paired = any(pmt.to_python(dbg.get_message(i)).get("nav_paired")
                         for i in range(dbg.num_messages()))
        self.assertTrue(paired)
        return tb, ctl, dbg, post, dbg.num_messages()

    def test_a_window_waiting_for_its_report_is_answered_at_stop(self):
        # Reports up to 1 s, then a window at 2.5 s that waits for the report of its
        # time: stopping the flowgraph at once (well before the 0.5 s watchdog) answers
        # it, without a heading (none within 1 s), rather than losing it.
        tb, ctl, dbg, post, _ = self._controller_with_reports(
            [(0.0, 0.1 * k) for k in range(11)])
        n = ctl.meas_count()
        post("meas", {"slot": 50, "time": 2.5, "freq_hz": 10.0, "valid": True})
        deadline = time.monotonic() + 10.0
        while ctl.meas_count() < n + 1 and time.monotonic() < deadline:
            time.sleep(0.002)
        tb.stop()
        tb.wait()
        self.assertEqual(ctl.meas_count(), n + 1)
        self.assertEqual(ctl.unpaired_count(), 1)

    def test_the_controller_pairs_each_window_with_the_report_nearest_in_time(self):
        # Heading reports every 0.1 s of a turn at 0.5 rad/s, posted out of order, then
        # windows: at 0.53 s the heading is the reports' around it; at 2.5 s no report is
        # within 1 s: no heading, and the telemetry says so.
        tb, ctl, dbg, post, n = self._controller_with_reports(
            [(0.05 * k, 0.1 * k) for k in (0, 3, 1, 2, 5, 4, 7, 6, 9, 8, 10)])
        try:
            # (The window at 2.5 s waits for a report of its time until a window 0.5 s
            # later has come, or 0.5 s of host time: then the last one is answered too.)
            for slot, t in ((11, 0.53), (12, 1.02), (50, 2.5), (62, 3.1)):
                post("meas", {"slot": slot, "time": t, "freq_hz": 10.0, "valid": True})
            deadline = time.monotonic() + 10.0
            while dbg.num_messages() < n + 4 and time.monotonic() < deadline:
                time.sleep(0.01)
        finally:
            tb.stop()
            tb.wait()
        tel = [pmt.to_python(dbg.get_message(i)) for i in range(n, dbg.num_messages())]
        # Every window answered: a lockstep source waits for each cmd.
        self.assertEqual(len(tel), 4)
        self.assertAlmostEqual(tel[0]["flown_heading"], 0.265, places=12)
        self.assertAlmostEqual(tel[0]["nav_offset_s"], -0.03, places=12)
        # 0.02 s after the last report: carried on at the turn rate of the last two.
        self.assertAlmostEqual(tel[1]["flown_heading"], 0.51, places=12)
        self.assertTrue(tel[0]["nav_paired"] and tel[1]["nav_paired"])
        self.assertFalse(tel[2]["nav_paired"])
        self.assertNotIn("flown_heading", tel[2])
        self.assertFalse(tel[3]["nav_paired"])
        self.assertEqual(ctl.unpaired_count(), 2)


if __name__ == "__main__":
    gr_unittest.run(qa_faults)
