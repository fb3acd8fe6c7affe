#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Every bad input answered (issue 12): the table of docs/robustness.md, one check per row.

Each row is an input tried and the answer the module gives. The check either tries it
here or runs the QA test named in the row (which tries it with more detail). The test
also checks that docs/robustness.md lists every row, so the table and the checks stay
one: `qa_robustness.py --markdown` prints the table.
"""

import importlib
import math
import os
import subprocess
import sys
import unittest

import numpy as np
import pmt
from gnuradio import blocks, gr, gr_unittest, rfseek
from gnuradio.rfseek.vehicle_bridge import vehicle_bridge

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BUILD = os.environ.get("RFSEEK_BUILD_DIR", os.path.join(SOURCE, "build"))
NAN, INF = float("nan"), float("inf")


def _config(**kw):
    c = rfseek.burst_acquirer_config()
    for k, v in kw.items():
        setattr(c, k, v)
    return c


def raises(fn, word):
    """fn() raises ValueError whose text names word."""
    def check(tc):
        with tc.assertRaisesRegex(ValueError, word):
            fn()
    return check


def qa(module, test):
    """Runs test `module.test` (another QA file) and requires it to pass."""
    def check(tc):
        mod = importlib.import_module("qa_" + module)
        cls = getattr(mod, "qa_" + module)
        result = unittest.TestResult()
        cls(test).run(result)
        tc.assertTrue(result.wasSuccessful() and not result.skipped,
                      "%s.%s: %s" % (module, test, result.errors + result.failures +
                                     result.skipped))
    return check


def program(args, word):
    """A program answers args with one line naming word, exit status 2, nothing written."""
    def check(tc):
        p = subprocess.run(args, capture_output=True, text=True, timeout=120, cwd=BUILD)
        tc.assertEqual(p.returncode, 2, p.stderr)
        lines = [line for line in p.stderr.splitlines() if line.strip()]
        tc.assertEqual(len(lines), 1, p.stderr)
        tc.assertIn(word, lines[0])
        tc.assertNotIn("Traceback", p.stderr)
    return check


def estimator_windows(tc):
    est = rfseek.tone_estimator(1e5, 256, 1024)
    tiny = np.full(256, 1e-45, dtype=np.complex64)  # denormals
    huge = np.full(256, 3e38, dtype=np.complex64)
    for x in (np.zeros(256), np.full(256, np.nan), np.full(256, np.inf), tiny, huge,
              np.r_[np.ones(255), np.nan]):
        e = est.estimate(np.asarray(x, dtype=np.complex64))
        tc.assertTrue(math.isfinite(e.freq_hz))
        tc.assertFalse(math.isnan(e.snr_db) or math.isnan(e.power_db))
        if not np.all(np.isfinite(x)) or not np.any(x):
            tc.assertFalse(e.valid)


def controller_answers(posts):
    """A seeking_controller's cmd and telemetry messages for the (port, PMT) posts, run to
    completion: the posts, then the system port's done, are queued before the start, and
    the flowgraph ends once the controller has handled them all."""
    ctl = rfseek.seeking_controller(rfseek.seeker_config())
    dbg = blocks.message_debug()
    tb = gr.top_block()
    tb.msg_connect(ctl, "telemetry", dbg, "store")
    tb.msg_connect(ctl, "cmd", dbg, "store")
    for port, msg in posts:
        ctl._post(pmt.intern(port), msg)
    ctl._post(pmt.intern("system"), pmt.cons(pmt.intern("done"), pmt.from_long(1)))
    tb.start()
    tb.wait()
    return ctl, [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())]


def controller_nan_fields(tc):
    posts = []
    for i, (k, v) in enumerate((("time", NAN), ("snr_db", INF), ("power_db", NAN),
                                ("freq_hz", INF), ("heading", NAN))):
        d = {"slot": i, "freq_hz": 100.0, "valid": True, "snr_db": 10.0,
             "power_db": -10.0, "time": 0.05 * i}
        d[k] = v
        posts.append(("meas", pmt.to_pmt(d)))
    ctl, out = controller_answers(posts)
    tc.assertEqual(len(out), 10)
    for m in out:
        for v in m.values():
            if isinstance(v, float):
                tc.assertTrue(math.isfinite(v))
    tc.assertEqual(ctl.invalid_count(), 4)  # all but the NaN heading (then not used)


def uint64_numbers(tc):
    """uint64 PMTs where a number is expected (pmt.to_double throws for them)."""
    def dict_of(**kv):
        d = pmt.make_dict()
        for k, v in kv.items():
            d = pmt.dict_add(d, pmt.intern(k), v)
        return d
    u = pmt.from_uint64
    ctl, out = controller_answers(
        [("nav", dict_of(heading=u(2))),
         ("meas", dict_of(slot=u(0), freq_hz=u(100), valid=pmt.PMT_T, time=u(1),
                          heading=u(1), snr_db=u(20)))])
    tc.assertEqual(len(out), 2)  # one cmd, one telemetry
    tc.assertEqual(ctl.malformed_count(), 0)
    tc.assertEqual(ctl.meas_count(), 1)
    # channel_source, free-running, run to completion: a uint64 heading (3 rad, toward
    # the emitter from where it starts) is flown, so the run arrives instead of flying
    # away at heading 0 to the cap.
    sc = rfseek.scenario(initial_distance_m=300, start_angle_rad=0.0, start_heading_rad=0.0,
                         num_scatterers=0, window_len=64, fft_len=64, heading_noise_rad=0.0)
    src = rfseek.channel_source(sc, lockstep=False)
    states = blocks.message_debug()
    tb = gr.top_block()
    tb.connect(src, blocks.null_sink(gr.sizeof_gr_complex))
    tb.msg_connect(src, "state", states, "store")
    src._post(pmt.intern("cmd"), dict_of(heading=u(3)))
    tb.run()
    last = pmt.to_python(states.get_message(states.num_messages() - 1))
    tc.assertEqual(src.malformed_count(), 0)
    tc.assertTrue(last["arrived"])
    tc.assertAlmostEqual(last["heading"], 3.0)


def acquirer_config(**kw):
    c = rfseek.burst_acquirer_config()
    c.window_len, c.period = 1000, 5000.0
    for k, v in kw.items():
        setattr(c, k, v)
    return c


MC = os.path.join(BUILD, "apps", "rfseek-montecarlo")
SIM = [sys.executable, os.path.join(SOURCE, "apps", "rfseek-sim"), "--no-figures"]
LIVE = [sys.executable, os.path.join(SOURCE, "apps", "rfseek-live")]

# (area, input, answer, check)
def resume_narrower(tc):
    """A finished 2-run study resumed as a 1-run one is refused; its CSV stays whole."""
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.json")
        base = [MC, "--out", out, "--quiet", "--set", "initial_distance_m=300"]
        tc.assertEqual(subprocess.run(base + ["--runs", "2"], capture_output=True,
                                      timeout=120).returncode, 0)
        with open(out[:-5] + ".csv") as f:
            before = f.read()
        program(base + ["--runs", "1", "--resume"], "would delete")(tc)
        with open(out[:-5] + ".csv") as f:
            tc.assertEqual(f.read(), before)


ROWS = [
    # --- parameters
    ("parameters", "`scenario(snr_db=nan)` / `inf`; `sc.snr_db = nan`, then any block or `validate()`",
     "ValueError `scenario.snr_db = nan: must be in [-100, 100]` (keyword arguments are validated as the scenario is made)",
     lambda tc: [raises(lambda: rfseek.scenario(snr_db=v), "snr_db")(tc) for v in (NAN, INF)]
     + [raises(lambda: (lambda s: (setattr(s, "snr_db", NAN), s.validate()))(rfseek.scenario()),
               "snr_db")(tc)]),
    ("parameters", "`scenario(initial_distance_m=-5)`, `0`, `1e30`; `scenario(speed_mps=-1)`",
     "ValueError naming the field, range [1, 1e7] m; speed_mps",
     lambda tc: [raises(lambda: rfseek.scenario(initial_distance_m=v),
                        "initial_distance_m")(tc) for v in (-5.0, 0.0, 1e30)]
     + [raises(lambda: rfseek.scenario(speed_mps=-1.0), "speed_mps")(tc)]),
    ("parameters", "`scenario(fft_len=100)` (smaller than `window_len` 1000)",
     "ValueError `scenario.window_len = 1000: must be in [3, 100]`",
     raises(lambda: rfseek.scenario(fft_len=100), "window_len")),
    ("parameters", "`scenario(seed=-1)`, `snr_db='loud'`, `num_scatterers=2.5`, `add_noise='yes'` (wrong types)",
     "ValueError naming the field and the type expected",
     lambda tc: [raises(lambda: rfseek.scenario(**{k: v}), k)(tc) for k, v in
                 (("seed", -1), ("snr_db", "loud"), ("num_scatterers", 2.5),
                  ("add_noise", "yes"))]),
    ("parameters", "`scenario.set('snr_db', 'nan')`, `set('nope', '1')`",
     "ValueError naming the field (range, or the known keys)",
     lambda tc: [raises(lambda: (lambda s: (s.set("snr_db", "nan"), s.validate()))(rfseek.scenario()), "snr_db")(tc),
                 raises(lambda: rfseek.scenario().set("nope", "1"), "nope")(tc)]),
    ("parameters", "`tone_estimator(1e5, 1000, 512)` (fft_len < window_len), `samp_rate=nan`, `window='kaiser'`",
     "ValueError naming window_len / samp_rate / window and the allowed values",
     lambda tc: [raises(lambda: rfseek.tone_estimator(1e5, 1000, 512), "window_len")(tc),
                 raises(lambda: rfseek.tone_estimator(NAN, 100, 512), "samp_rate")(tc),
                 raises(lambda: rfseek.tone_estimator(1e5, 100, 512, "kaiser"), "window")(tc)]),
    ("parameters", "`doppler_estimator` window_len 2 or > fft_len, samp_rate 0, unknown window, interpolator or alignment, period < window",
     "ValueError naming the parameter", qa("doppler_estimator", "test_bad_parameters_raise_value_error")),
    ("parameters", "`seeker_config(delta_rad=nan)`, `strategy='bogus'`, `m_slots=0`, `m_slots='x'`",
     "ValueError `seeker_config.delta_rad = nan: must be in (0, pi/2)` etc.",
     lambda tc: [raises(lambda: rfseek.seeking_controller(rfseek.seeker_config(**kw)), word)(tc)
                 for kw, word in ((dict(delta_rad=NAN), "delta_rad"),
                                  (dict(strategy="bogus"), "strategy"),
                                  (dict(m_slots=0), "m_slots"), (dict(m_slots="x"), "m_slots"))]),
    ("parameters", "`channel_source(mode='bogus')`, `speedup=0` / `nan` / `1e7`, a bad scenario",
     "ValueError naming mode / speedup / the scenario field",
     lambda tc: [raises(lambda: rfseek.channel_source(rfseek.scenario(), mode="bogus"), "mode")(tc),
                 raises(lambda: rfseek.channel_source(rfseek.scenario(), speedup=NAN), "speedup")(tc),
                 raises(lambda: rfseek.channel_source(rfseek.scenario(window_len=2)), "window_len")(tc)]),
    ("parameters", "`doppler_estimator.set_full_scale(-1)`, `state_to_nav(delay_s=nan)`, `overflow_injector(lost=0)`, `burst_acquirer_config(track_bins=-1)`",
     "ValueError naming the parameter and its range",
     lambda tc: [raises(lambda: rfseek.doppler_estimator(1e5, 100, 128).set_full_scale(-1),
                        "full_scale")(tc),
                 raises(lambda: __import__("gnuradio.rfseek.flowgraphs", fromlist=["x"])
                        .state_to_nav(delay_s=NAN), "delay_s")(tc),
                 raises(lambda: __import__("gnuradio.rfseek.rehearsal", fromlist=["x"])
                        .overflow_injector(1e5, lost=0), "lost")(tc),
                 raises(lambda: rfseek.burst_acquirer(
                     1e5, _config(track_bins=-1)), "track_bins")(tc)]),
    ("parameters", "`burst_detector(threshold_db=nan)`, `average_len=1`",
     "ValueError naming the parameter and its range",
     lambda tc: [raises(lambda: rfseek.burst_detector(NAN), "threshold_db")(tc),
                 raises(lambda: rfseek.burst_detector(2.0, 1000, 1), "average_len")(tc)]),
    ("parameters", "`doppler_estimator(pfa=0.7)`, `set_pfa(-1)`, alignment `acquire` with period <= window_len; `set_samp_rate(50e3)` with a +-45 kHz band",
     "ValueError naming pfa / period / the band, nothing changed (`qa_acquire`, `qa_radios`)",
     lambda tc: [qa("acquire", "test_bad_parameters_raise_value_error")(tc),
                 qa("radios", "test_a_coerced_device_rate_is_followed")(tc)]),
    ("parameters", "`tone_detector(window_len=8)`, `pfa=0`, a band narrower than 2 bins; `burst_acquirer` hop, margin, loop gains out of range",
     "ValueError naming the parameter and its range (`qa_tone_detector`, `qa_burst_acquirer`)",
     lambda tc: [raises(lambda: rfseek.tone_detector(1e5, 8), "window_len")(tc),
                 raises(lambda: rfseek.tone_detector(1e5, 1000, 0.0), "pfa")(tc),
                 raises(lambda: rfseek.tone_detector(1e5, 1000, 1e-3, 0.0, 60.0), "band")(tc)]
     + [raises(lambda k=k, v=v: rfseek.burst_acquirer(1e5, acquirer_config(**{k: v})), k)(tc)
        for k, v in (("hop", -1), ("margin", 5000), ("loop_alpha", 0.0),
                     ("loop_beta", 0.5))]),
    ("parameters", "`rx_plan('usrp_x999')`, an RTL-SDR at 2 GHz, an N210 at 100 kS/s, an out_rate that does not divide the device rate, an LO offset beyond the band; `radio_source` gain out of range, or NaN",
     "ValueError naming family / freq / device_rate / out_rate / lo_offset (with the radio's range); the gain is clamped with a warning, a NaN one refused (ValueError naming gain) (`qa_radios`)",
     qa("radios", "test_bad_settings_and_missing_devices")),
    ("parameters", "`radio_source` with no radio attached",
     "LookupError `no UHD / osmosdr / SoapySDR device found ...`; `rfseek-live` exits with status 3",
     qa("radios", "test_bad_settings_and_missing_devices")),
    ("parameters", "`vehicle_bridge(peer_port=70000)`, `nav_timeout=0`, `max_datagram=10`, `max_rate_hz=nan`",
     "ValueError naming the parameter and its range", qa("vehicle_bridge", "test_bad_parameters")),
    ("parameters", "`sim_autopilot(airspeed_mps=-1)`, `ref_lat_deg=100`, `time_scale=0.5`; `seek_view(update_ms=0)`",
     "ValueError naming the parameter and its range, before any socket or widget is made",
     lambda tc: [raises(lambda k=k, v=v: rfseek.sim_autopilot(**{k: v}), k)(tc)
                 for k, v in (("airspeed_mps", -1.0), ("ref_lat_deg", 100.0),
                              ("time_scale", 0.5))]
     + ([raises(lambda: rfseek.seek_view("view", 0), "update_ms")(tc)]
        if hasattr(rfseek, "seek_view") else [])),
    # --- messages
    ("messages", "`channel_source` cmd: not a dict, no numeric heading, NaN heading, non-integer slot",
     "logged once per kind, counted (`malformed_count()`), dropped; the UAV flies on",
     qa("channel_source", "test_malformed_cmds_are_dropped_and_counted")),
    ("messages", "`channel_source` cmd for another slot (lockstep)",
     "ignored, counted (`stale_count()`)", qa("channel_source", "test_stale_cmd_is_ignored")),
    ("messages", "`seeking_controller` meas: garbage, no slot, no freq; nav: heading 'north'",
     "logged once, counted (`malformed_count()`), dropped; the block keeps running",
     qa("closed_loop", "test_invalid_and_malformed_messages")),
    ("messages", "`seeking_controller` meas with NaN/inf `time`, `snr_db`, `power_db`, `freq_hz` or `heading`",
     "answered as an invalid measurement (`invalid_count()`); no NaN in cmd or telemetry",
     controller_nan_fields),
    ("messages", "cmd / meas / nav whose heading, freq_hz, time or snr_db is a uint64 PMT",
     "taken as the number (`pmt::to_double` throws for a uint64: found by fuzzing, was an exception out of the handler)",
     uint64_numbers),
    ("messages", "any PMT built from fuzz bytes into cmd / meas / nav",
     "no crash, no NaN published (libFuzzer, `scripts/fuzz.sh`: see Fuzzing below)",
     lambda tc: tc.assertTrue(os.path.exists(os.path.join(SOURCE, "lib", "fuzz", "fuzz_seeking_controller.cc")))),
    ("messages", "vehicle datagrams: not JSON, wrong type, heading 'north', 400, NaN; from a stranger",
     "logged once per kind, counted (`dropped[...]`), dropped", qa("vehicle_bridge", "test_round_trip_and_bad_datagrams")),
    ("messages", "vehicle datagram > 1024 bytes; a flood of 100 reports at once",
     "dropped (`oversize`); beyond 50/s after a 1 s burst dropped (`rate`)", qa("vehicle_bridge", "test_size_and_rate_bounds")),
    # --- samples
    ("samples", "`tone_estimator` windows: all zero, all NaN, all inf, denormals, 3e38, one NaN",
     "`valid = False` where not finite or empty, frequency always finite, no NaN", estimator_windows),
    ("samples", "`doppler_estimator` windows: zero, NaN, cut short by the next beacon",
     "`valid = False`, counted, no NaN in meas", qa("doppler_estimator", "test_degenerate_windows_are_invalid_without_nan")),
    ("samples", "`doppler_estimator` windows of noise alone, with `pfa` or under `acquire`",
     "`valid = False` but for the false-alarm probability (`detect_margin_db` < 0)",
     lambda tc: [qa("acquire", "test_detection_test_on_noise_windows")(tc),
                 qa("radios", "test_the_dc_spike_stays_out_of_the_band")(tc)]),
    ("samples", "`rx_rate` tag: not a number, NaN, 0, or a rate the search band cannot fit",
     "logged, not followed; measuring goes on at the last good rate",
     qa("radios", "test_bad_rate_tags_are_not_followed")),
    ("samples", "SigMF recordings: wrong datatype, no sample rate, mutated metadata and data; `sigmf_recorder` with a NaN `center_freq` or an infinite `samp_rate`",
     "ValueError naming the field (scripts/fuzz_python.py: 0 other exceptions)",
     qa("sigmf", "test_bad_recording_is_refused")),
    # --- programs
    ("programs", "`rfseek-montecarlo --runs 0`, `--runs 2.5`, `--threads 0`, `--seed abc`, `--set snr=3`, `--set snr_db=nan`, unwritable `--csv`",
     "one line naming the option, exit 2, no output file", qa("montecarlo", "test_bad_options_exit_2_with_a_message")),
    ("programs", "`rfseek-montecarlo --scheduler tcp://127.0.0.1:9` (nothing there)",
     "one line `cannot reach the Dask scheduler at ...`, exit 2", qa("study_backends", "test_unreachable_scheduler_is_one_line_and_exit_2")),
    ("programs", "`rfseek-sim --set snr_db=nan`",
     "one line naming snr_db, exit 2", program(SIM + ["--set", "snr_db=nan"], "snr_db")),
    ("programs", "`rfseek-sim --set unknown=1`, `--strategy bogus`, `--seed -1`",
     "one line naming it (an unknown key: every scenario field and seeker constant), exit 2",
     lambda tc: [program(SIM + a, w)(tc) for a, w in ((["--set", "unknown=1"], "unknown"),
                                                    (["--set", "unknown=1"],
                                                     "Seeker constants: strategy, "),
                                                    (["--strategy", "bogus"], "bogus"),
                                                    (["--seed", "-1"], "--seed"))]),
    ("programs", "`rfseek-sim --out /etc/passwd/x` (not writable)",
     "one line, exit 2, before the flight", program(SIM + ["--out", "/etc/passwd/x"], "--out")),
    ("programs", "`rfseek-live --source bogus`, `--source file` without `--file`, `--window-len 2`",
     "one line, exit 2", lambda tc: [program(LIVE + ["--source", "bogus"], "bogus")(tc),
                                     qa("live", "test_bad_arguments")(tc)]),
    ("programs", "`rfseek-live --source uhd` / `osmosdr` / `soapy` with no radio attached",
     "one line `no UHD device found` (osmosdr, SoapySDR), exit 3",
     qa("live", "test_no_device_is_a_clean_error")),
    ("programs", "`rfseek-live --source osmosdr --freq 2e9` (beyond the RTL-SDR), `--device-rate 50e3` on a USRP, `--source sim --radio rtlsdr` at the world's 2 GHz, `--source zmq` without `--zmq`",
     "one line naming the setting and the radio's range, exit 2",
     lambda tc: [program(LIVE + a, w)(tc) for a, w in (
         (["--source", "osmosdr", "--freq", "2e9"], "freq"),
         (["--source", "uhd", "--device-rate", "50e3"], "device_rate"),
         (["--source", "sim", "--radio", "rtlsdr", "--duration", "1"], "carrier_hz"),
         (["--source", "zmq"], "--zmq"))]),
    ("programs", "`rfseek-live --source sim --freq 915e6` / `--gain nan` / `--rate 0`; `--lo-offset` without `--radio`; radio flags to `--zmq-serve` (settings that would be ignored)",
     "one line naming them and saying where the world's carrier and rate are set, exit 2",
     lambda tc: [program(LIVE + ["--source", "sim", "--fast"] + a, w)(tc) for a, w in (
         (["--freq", "915e6"], "--freq: not used with --source sim"),
         (["--gain", "nan"], "--gain: not used"),
         (["--rate", "0"], "--rate: not used"),
         (["--lo-offset", "1000"], "need --radio FAMILY"))]
     + [qa("rehearsal", "test_radio_flags_the_server_ignores_are_refused")(tc)]),
    ("programs", "`rfseek-live --source zmq --zmq ADDR` with no beacon process serving ADDR",
     "says so every 10 s while nothing is measured; a run that measured nothing ends with `nothing measured`, exit 1",
     qa("rehearsal", "test_no_beacon_process_is_said_and_fails")),
    ("programs", "`rfseek-montecarlo --resume` with fewer `--runs` or without a strategy the CSV holds",
     "one line naming how many finished rows it would delete, exit 2, the CSV untouched (`qa_study_backends`)",
     lambda tc: resume_narrower(tc)),
    ("programs", "`rfseek-bench-world abc`, `rfseek-bench-estimator -5`, `rfseek-bench-loop 0`",
     "one line naming the count and its range, exit 2 (`--help`: the usage, exit 0)",
     lambda tc: [program([os.path.join(BUILD, "apps", b), v], w)(tc) for b, v, w in (
         ("rfseek-bench-world", "abc", "slots = 'abc'"),
         ("rfseek-bench-estimator", "-5", "windows = '-5'"),
         ("rfseek-bench-loop", "0", "runs = '0'"))]),
    ("programs", "`rfseek-plot-montecarlo R.json --column straight_ratio` without `--against`",
     "one line saying --column needs --against, exit 2",
     program([sys.executable, os.path.join(SOURCE, "apps", "rfseek-plot-montecarlo"),
              "r.json", "--column", "straight_ratio"], "--against")),
    ("programs", "`rfseek-soak --strategy nosuch`, `rfseek-bench-acquire --seeds 0`, `rfseek-bench-faults --faults nosuch`",
     "one line naming the option, exit 2",
     lambda tc: [program([sys.executable, os.path.join(SOURCE, "apps", a)] + args, w)(tc)
                 for a, args, w in (("rfseek-soak", ["--strategy", "nosuch"], "--strategy"),
                                    ("rfseek-bench-acquire", ["--seeds", "0"], "--seeds"),
                                    ("rfseek-bench-faults", ["--faults", "nosuch"], "--faults"))]),
    ("programs", "`rfseek-estimator-study --seed -1`, `--snr-min nan`, `--snr-min 5 --snr-max 0`",
     "one line naming the option, exit 2",
     lambda tc: [program([os.path.join(BUILD, "apps", "rfseek-estimator-study")] + args, w)(tc)
                 for args, w in ((["--seed", "-1"], "--seed"), (["--snr-min", "nan"], "--snr-min"),
                                 (["--snr-min", "5", "--snr-max", "0"], "--snr-max"))]),
    ("parameters", "`seeker_config(wind_forecast_east_mps=10)` for a 10 m/s vehicle, `wind_forecast_north_mps=nan`; `scenario(wind_forecast=True, wind_forecast_speed_error_mps=9)`",
     "ValueError naming the field: the forecast's speed must be below the airspeed",
     lambda tc: [raises(lambda: rfseek.seeker_config(wind_forecast_east_mps=10.0),
                        "wind_forecast_east_mps.*below speed_mps")(tc),
                 raises(lambda: rfseek.seeker_config(wind_forecast_north_mps=float("nan")),
                        "wind_forecast_north_mps")(tc),
                 raises(lambda: rfseek.scenario(wind_forecast=True, wind_speed_mps=4.0,
                                                wind_forecast_speed_error_mps=9.0),
                        "wind_forecast_speed_error_mps")(tc)]),
    ("parameters", "`rx_plan` / `rehearsal_plan` given None, a string or NaN where a number or a scenario goes",
     "ValueError naming the argument (`qa_radios`, `qa_rehearsal`)",
     lambda tc: [raises(lambda: rfseek.rx_plan("usrp_b2xx", out_rate=None), "^out_rate = None")(tc),
                 raises(lambda: rfseek.rx_plan("usrp_b2xx", "2.4G"), "^freq = ")(tc),
                 raises(lambda: __import__("gnuradio.rfseek.rehearsal", fromlist=["x"])
                        .rehearsal_plan(None, "rtlsdr"), "^sc = None")(tc)]),
    ("parameters", "`plots.sweep_plot` and the other study figures given one run's result, a path, or a study without `--sweep`",
     "ValueError saying what they take (`qa_montecarlo`)",
     lambda tc: [raises(lambda: __import__("gnuradio.rfseek.plots", fromlist=["x"])
                        .sweep_plot(bad), "rfseek-montecarlo's JSON")(tc)
                 for bad in ("study.json", None, {"rows": []})]),
]


class qa_robustness(gr_unittest.TestCase):
    pass


def _make(i, row):
    def test(self):
        row[3](self)
    test.__doc__ = row[1]
    return test


for _i, _row in enumerate(ROWS):
    setattr(qa_robustness, "test_%02d_%s" % (_i, _row[0]), _make(_i, _row))


def _table_test(self):
    doc = open(os.path.join(SOURCE, "docs", "robustness.md")).read()
    for area, what, answer, _ in ROWS:
        self.assertIn("| %s | %s |" % (what, answer), doc, "docs/robustness.md lacks: " + what)


qa_robustness.test_table_in_docs = _table_test


def markdown():
    out = []
    for area in ("parameters", "messages", "samples", "programs"):
        out.append("\n### %s\n\n| input | answer |\n| --- | --- |" % area.capitalize())
        out += ["| %s | %s |" % (w, a) for ar, w, a, _ in ROWS if ar == area]
    return "\n".join(out)


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    if "--markdown" in sys.argv:
        print(markdown())
    else:
        gr_unittest.run(qa_robustness)
