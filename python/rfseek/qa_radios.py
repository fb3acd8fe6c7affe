#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Radios: the table's plans against the devices' documented ranges, the example
flowgraphs' device settings inside them, the receive chain at each family's device rate
with its impairments (the beacon found at -12 dB, the DC spike out of the band), a
coerced device rate followed by the estimator, the docs table, and clean errors."""

import math
import os
import re

import numpy as np
import pmt
import yaml
from gnuradio import analog, blocks, gr, gr_unittest
from gnuradio import rfseek
from gnuradio.rfseek import radios

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
FS, N, NFFT, P = 1e5, 1000, 4096, 5000


def run(src, est, nsamples):
    tb = gr.top_block()
    dbg = blocks.message_debug()
    tb.connect(src, blocks.head(gr.sizeof_gr_complex, int(nsamples)), est)
    tb.msg_connect(est, "meas", dbg, "store")
    tb.run()
    return [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())]


def grc_values(path):
    """The flowgraph's blocks and its variables evaluated as GRC evaluates them."""
    with open(path) as f:
        d = yaml.safe_load(f)
    env = {"rfseek": rfseek, "math": math}
    pending = {b["name"]: b["parameters"]["value"] for b in d["blocks"]
               if b["id"] in ("variable", "variable_qtgui_range")}
    for _ in range(len(pending) + 1):
        for name, expr in list(pending.items()):
            try:
                env[name] = eval(str(expr), env)
                del pending[name]
            except NameError:
                pass
    if pending:
        raise AssertionError("%s: unresolved variables %s" % (path, sorted(pending)))
    return d["blocks"], env


class qa_radios(gr_unittest.TestCase):

    def test_every_plan_lies_in_the_devices_ranges(self):
        for family, r in radios.RADIOS.items():
            freq = 915e6 if family == "rtlsdr" else 2.4e9
            s = rfseek.rx_plan(family, freq)
            self.assertTrue(r.accepts_rate(s.device_rate), family)
            self.assertEqual(s.decimation * s.out_rate, s.device_rate)
            self.assertAlmostEqual(s.out_rate, 100e3)
            self.assertTrue(r.tunes(s.center_hz), family)
            # The DC spike (at the tuned centre) is outside the output band, past the
            # filter's transition.
            self.assertGreaterEqual(abs(s.lo_offset_hz), 0.5 * s.out_rate + 0.1 * s.out_rate)
            if r.tx_rates:
                self.assertTrue(r.accepts_rate(r.tx_rate, tx=True), family)
            lo, hi = s.band_hz
            self.assertTrue((lo, hi) == (0.0, 0.0) or (lo < 0 < hi and hi < 0.45 * FS))
            # The low-pass: unit gain in the band, >= 80 dB down from 0.6 x out_rate and
            # at the DC spike.
            taps = np.array(s.taps)
            resp = lambda f: abs(np.sum(taps * np.exp(-2j * np.pi * f / s.device_rate *
                                                      np.arange(len(taps)))))
            self.assertAlmostEqual(resp(0.0), 1.0, delta=0.01)
            self.assertAlmostEqual(resp(0.44 * s.out_rate), 1.0, delta=0.01)
            for f in (0.6 * s.out_rate, s.out_rate, s.lo_offset_hz):
                self.assertLess(20 * math.log10(resp(f) + 1e-12), -80.0, (family, f))

    def test_examples_ask_only_what_their_radios_accept(self):
        checked = 0
        for name in sorted(os.listdir(os.path.join(SOURCE, "examples"))):
            if not name.endswith(".grc"):
                continue
            blks, env = grc_values(os.path.join(SOURCE, "examples", name))
            for b in blks:
                p = b["parameters"]
                ev = lambda k: eval(str(p[k]), env)
                if b["id"] == "rfseek_radio_source":
                    s = rfseek.rx_plan(ev("family"), ev("freq"), ev("out_rate"))
                    lo, hi = radios.radio_for(s.family).gain_db
                    self.assertTrue(lo <= ev("gain") <= hi, name)
                    checked += 1
                elif b["id"] in ("uhd_usrp_source", "osmosdr_source", "soapy_source"):
                    self.fail("%s: a receiver outside the table (%s)" % (name, b["id"]))
                elif b["id"] in ("uhd_usrp_sink", "osmosdr_sink"):
                    r = radios.radio_for(env["family"])
                    rate = ev("samp_rate" if b["id"] == "uhd_usrp_sink" else "sample_rate")
                    freq = ev("center_freq0" if b["id"] == "uhd_usrp_sink" else "freq0")
                    self.assertTrue(r.accepts_rate(rate, tx=True), "%s: %g" % (name, rate))
                    self.assertTrue(r.tunes(freq), name)
                    self.assertTrue(r.tx_gain_db[0] <= ev("gain0") <= r.tx_gain_db[1])
                    # The burst is window_len samples at the receiver's rate.
                    self.assertAlmostEqual(
                        env["window_len"] * env["samp_rate"] / env["rx_rate"] /
                        env["samp_rate"], 0.01)
                    checked += 1
        self.assertGreaterEqual(checked, 4)

    def test_generated_examples_open_the_radio_they_name(self):
        # What GRC generates, not only what the .grc says: a parameter that refused the
        # family variable would fall back to its default radio.
        import shutil
        import subprocess
        import sys
        import tempfile
        grcc = shutil.which("grcc")
        self.assertIsNotNone(grcc, "grcc not found")
        with tempfile.TemporaryDirectory() as out:
            for name, family in (("seek_usrp", "usrp_b2xx"), ("seek_osmosdr", "rtlsdr"),
                                 ("measure_radio", "rtlsdr")):
                p = subprocess.run([sys.executable, grcc, "-o", out,
                                    os.path.join(SOURCE, "examples", name + ".grc")],
                                   capture_output=True, text=True, timeout=120)
                self.assertEqual(p.returncode, 0, p.stderr)
                with open(os.path.join(out, name + ".py")) as f:
                    code = f.read()
                self.assertIn("rfseek.radio_source(family, freq, gain", code, name)
                self.assertIn('self.family = family = "%s"' % family, code, name)

    def check_chain(self, family, snr_db=-12.0, seconds=4.0):
        s = rfseek.rx_plan(family, 915e6 if family == "rtlsdr" else 2.4e9)
        freq = 3217.0
        beacon = rfseek.pulsed_beacon(FS, freq, N, P, snr_db, skip=1234, seed=3)
        tb_src = gr.hier_block2("src", gr.io_signature(0, 0, 0),
                                gr.io_signature(1, 1, gr.sizeof_gr_complex))
        radio = rfseek.sim_radio(s, FS, 10 ** (-snr_db / 20))
        chain = rfseek.radio_rx_chain(s, None, radios.radio_for(family).ddc)
        tb_src.connect(beacon, radio, chain, tb_src)
        est = rfseek.doppler_estimator(FS, N, NFFT, "rectangular", "newton", "acquire",
                                       "x", P, 0, s.band_hz[0], s.band_hz[1], 2.0, 1e-3)
        meas = run(tb_src, est, seconds * FS)
        return meas, freq, beacon.crb_std_hz(snr_db)

    def test_the_chain_at_each_device_rate_finds_the_beacon_at_minus_12_db(self):
        for family in radios.RADIOS:
            meas, freq, crb = self.check_chain(family)
            valid = [m for m in meas if m["valid"]]
            self.assertGreaterEqual(len(meas), 75, family)
            self.assertGreaterEqual(len(valid), 0.99 * len(meas), family)
            err = np.array([m["freq_hz"] - freq for m in valid])
            self.assertLess(np.sqrt(np.mean(err ** 2)), 1.3 * crb, family)
            # A window every period, one slot each (the timing loop moves a few samples
            # a burst at this SNR).
            starts = np.array([m["offset"] for m in meas])
            self.assertTrue(np.all(np.abs(np.diff(starts) - P) <= 20), family)
            self.assertEqual([m["slot"] - meas[0]["slot"] for m in meas],
                             list(range(len(meas))))

    def test_the_dc_spike_stays_out_of_the_band(self):
        # Noise (white at the device rate, as a receiver's own) and a strong DC offset
        # (the radio's LO leak), no beacon: with the table's LO offset no window holds a
        # tone (a radio without DSP, and a USRP whose DSP shifts the leak to +lo_offset);
        # tuned on the beacon (no offset), the spike sits in the band and the detection
        # test finds it in every window.
        for family, lo, expect_tone in (("rtlsdr", None, False), ("usrp_b2xx", None, False),
                                        ("rtlsdr", 0.0, True)):
            s = rfseek.rx_plan(family, 915e6, lo_offset_hz=lo)
            src = gr.hier_block2("src", gr.io_signature(0, 0, 0),
                                 gr.io_signature(1, 1, gr.sizeof_gr_complex))
            noise = analog.noise_source_c(analog.GR_GAUSSIAN, 1.0, 5)
            radio = rfseek.sim_radio(s, in_rate=s.device_rate, noise_rms=1.0, dc=0.1)
            # kept: it holds a Python block
            chain = rfseek.radio_rx_chain(s, None, radios.radio_for(family).ddc)
            src.connect(noise, radio, chain, src)
            est = rfseek.doppler_estimator(FS, N, NFFT, alignment="periodic", period=N,
                                           pfa=1e-3)
            meas = run(src, est, 300 * N)
            rate = sum(m["valid"] for m in meas) / len(meas)
            if expect_tone:
                self.assertGreater(rate, 0.99)
                self.assertLess(abs(np.median([m["freq_hz"] for m in meas])), 30.0)
            else:
                self.assertLessEqual(rate, 0.01)  # pfa 1e-3: 0.3 expected of 300

    def test_a_strong_beacon_clips_and_the_estimator_says_so(self):
        # A tone 30 dB over the noise through an 8-bit radio (the noise 8 steps above
        # zero, so full scale 24 dB above it) at gain 0 and at -20 dB: the first clips at
        # the converter, and the estimator told the full scale finds every window
        # clipped; 20 dB less gain leaves it clean and valid. A 12-bit radio (full scale
        # 48 dB above the noise) clips the same tone at +20 dB, not at 0 dB; with
        # clip=False neither saturates: the samples exceed the converter's full scale
        # (2x and 1.26x), within the radio's lifted one.
        for family, gain_db, clip, clipped in (
                ("rtlsdr", 0.0, True, True), ("rtlsdr", -20.0, True, False),
                ("usrp_b2xx", 20.0, True, True), ("usrp_b2xx", 0.0, True, False),
                ("rtlsdr", 0.0, False, False), ("usrp_b2xx", 20.0, False, False)):
            s = rfseek.rx_plan(family, 915e6)
            src = gr.hier_block2("src", gr.io_signature(0, 0, 0),
                                 gr.io_signature(1, 1, gr.sizeof_gr_complex))
            tone = analog.sig_source_c(s.device_rate, analog.GR_COS_WAVE,
                                       1234.0, 10 ** (30 / 20), 0)
            noise = analog.noise_source_c(analog.GR_GAUSSIAN, 1.0, 6)
            add = blocks.add_cc()
            radio = rfseek.sim_radio(s, in_rate=s.device_rate, noise_rms=1.0, dc=0.0,
                                     clip=clip)
            radio.set_gain(gain_db)
            chain = rfseek.radio_rx_chain(s, None, rfseek.radio_for(family).ddc)
            src.connect(tone, (add, 0))
            src.connect(noise, (add, 1))
            src.connect(add, radio, chain, src)
            est = rfseek.doppler_estimator(FS, N, NFFT, alignment="periodic", period=N,
                                           pfa=1e-3)
            est.set_full_scale(radio.full_scale)
            meas = run(src, est, 50 * N)[2:]  # (after the filter's start)
            case = (family, gain_db, clip)
            self.assertEqual(all(m["clipped"] for m in meas), clipped, case)
            self.assertEqual(any(m["clipped"] for m in meas), clipped, case)
            self.assertEqual(any(m["valid"] for m in meas), not clipped, case)
            # The largest sample against the converter's full scale (8 steps of noise).
            fs = (2 ** (rfseek.radio_for(family).adc_bits - 1) - 1) / 8.0
            peak = max(10 ** (m["peak_dbfs"] / 20) for m in meas) * radio.full_scale / fs
            if clipped:  # held at full scale (I and Q at most at their largest codes)
                self.assertLess(peak, 1.45, case)
            elif not clip:
                self.assertGreater(peak, 1.5 if family == "rtlsdr" else 1.1, case)
        with self.assertRaisesRegex(ValueError, "gain_db"):
            radio.set_gain(float("nan"))

    def test_a_coerced_device_rate_is_followed(self):
        # An X3xx at 184.32 MHz asked for 1 MS/s gives 184.32e6 / 184; UHD tags the
        # stream's start with that rate. A tone 12 kHz off the beacon's nominal centre
        # must measure 12 kHz (the nominal rate would read 11 979 Hz) and time must run
        # at the granted rate.
        s = rfseek.rx_plan("usrp_n2xx_x3xx", 2.4e9)
        granted = 184.32e6 / 184
        t = np.arange(int(0.4 * granted))
        rng = np.random.default_rng(1)
        x = np.exp(2j * np.pi * 12e3 * t / granted) + 0.3 * (
            rng.standard_normal(len(t)) + 1j * rng.standard_normal(len(t)))
        tag = gr.tag_utils.python_to_tag((0, pmt.intern("rx_rate"),
                                          pmt.from_double(granted), pmt.PMT_NIL))
        src = blocks.vector_source_c(x.astype(np.complex64).tolist(), False, 1, [tag])
        chain = rfseek.radio_rx_chain(s, granted, True)
        self.assertAlmostEqual(chain.out_rate(), granted / 10)
        est = rfseek.doppler_estimator(FS, N, NFFT, "rectangular", "newton", "periodic",
                                       "x", N, 0, 0.0, 0.0, 2.0, 1e-3)
        tb = gr.top_block()
        dbg = blocks.message_debug()
        tb.connect(src, chain, est)
        tb.msg_connect(est, "meas", dbg, "store")
        tb.run()
        meas = [pmt.to_python(dbg.get_message(i)) for i in range(dbg.num_messages())]
        self.assertGreater(len(meas), 30)
        self.assertAlmostEqual(est.samp_rate(), granted / 10, delta=1e-6)
        for m in meas[2:]:
            self.assertTrue(m["valid"])
            self.assertAlmostEqual(m["freq_hz"], 12e3, delta=1.0)
            self.assertAlmostEqual(m["time"], m["offset"] / (granted / 10), delta=1e-9)
        # By hand: set_samp_rate does the same, and refuses a rate the band cannot fit.
        est2 = rfseek.doppler_estimator(FS, N, NFFT, min_freq=-45e3, max_freq=45e3)
        est2.set_samp_rate(granted / 10)
        self.assertAlmostEqual(est2.samp_rate(), granted / 10)
        with self.assertRaisesRegex(ValueError, "samp_rate|band"):
            est2.set_samp_rate(50e3)
        self.assertAlmostEqual(est2.samp_rate(), granted / 10)

    def test_meas_streams_shows_frequency_snr_and_burst_rate(self):
        # The measure-only flowgraph's display: a -6 dB beacon of 20 bursts a second.
        # The estimator's flowgraph runs to completion; its messages then go through the
        # block's handler and work() directly (it is a source that waits for messages).
        freq = -4321.0
        beacon = rfseek.pulsed_beacon(FS, freq, N, P, -6.0, skip=700, seed=9)
        est = rfseek.doppler_estimator(FS, N, NFFT, "rectangular", "newton", "acquire",
                                       "x", P)
        tb = gr.top_block()
        dbg = blocks.message_debug()
        tb.connect(beacon, blocks.head(gr.sizeof_gr_complex, int(5 * FS)), est)
        tb.msg_connect(est, "meas", dbg, "store")
        tb.run()
        streams = rfseek.meas_streams(1.0)
        for i in range(dbg.num_messages()):
            streams._on_meas(dbg.get_message(i))
        out = [np.zeros(1000, dtype=np.float32) for _ in range(3)]
        n = streams.work([], out)
        f, snr, rate = (o[:n] for o in out)
        self.assertGreaterEqual(n, 95)  # 98 bursts after the acquisition
        self.assertLess(np.sqrt(np.mean((f - freq) ** 2)), 1.3 * beacon.crb_std_hz(-6.0))
        self.assertAlmostEqual(np.median(snr), -6.0, delta=1.5)
        # One second of sample time holds 20 bursts (21 counting both ends).
        self.assertTrue(np.all(np.abs(rate[25:] - 20.0) <= 1.0), rate[25:])
        streams._on_meas(pmt.intern("junk"))
        self.assertEqual(streams.dropped(), 1)
        with self.assertRaisesRegex(ValueError, "window_s"):
            rfseek.meas_streams(0.0)

    def test_bad_rate_tags_are_not_followed(self):
        # NaN, zero, a string, and a rate the search band cannot fit: measuring goes on
        # at the last good rate.
        t = np.arange(40 * N)
        x = np.exp(2j * np.pi * 12e3 * t / FS).astype(np.complex64)
        tags = [gr.tag_utils.python_to_tag((k * 5 * N, pmt.intern("rx_rate"), v,
                                            pmt.PMT_NIL))
                for k, v in enumerate((pmt.from_double(float("nan")), pmt.from_double(0.0),
                                       pmt.intern("fast"), pmt.from_double(50e3)))]
        est = rfseek.doppler_estimator(FS, N, NFFT, "rectangular", "newton", "periodic",
                                       "x", N, 0, -45e3, 45e3, 2.0, 1e-3)
        meas = run(blocks.vector_source_c(x.tolist(), False, 1, tags), est, len(x))
        self.assertEqual(len(meas), 40)
        for m in meas:
            self.assertTrue(m["valid"])
            self.assertAlmostEqual(m["freq_hz"], 12e3, delta=0.5)
            self.assertAlmostEqual(m["time"], m["offset"] / FS, delta=1e-9)
        self.assertEqual(est.samp_rate(), FS)

    def test_docs_table_matches_the_radios(self):
        with open(os.path.join(SOURCE, "docs", "live.md")) as f:
            text = f.read()
        m = re.search(r"<!-- radios table -->\n(.*?)<!-- end radios table -->", text, re.S)
        self.assertIsNotNone(m, "docs/live.md has no radios table")
        self.assertEqual(m.group(1).strip(), radios.markdown_table().strip())

    def test_bad_settings_and_missing_devices(self):
        with self.assertRaisesRegex(ValueError, "family"):
            rfseek.rx_plan("usrp_x999")
        with self.assertRaisesRegex(ValueError, "freq"):
            rfseek.rx_plan("rtlsdr", 2e9)
        with self.assertRaisesRegex(ValueError, "device_rate"):
            rfseek.rx_plan("usrp_n2xx_x3xx", 2.4e9, device_rate=100e3)
        with self.assertRaisesRegex(ValueError, "out_rate"):
            rfseek.rx_plan("hackrf", 2.4e9, out_rate=300e3)
        with self.assertRaisesRegex(ValueError, "lo_offset"):
            rfseek.rx_plan("rtlsdr", 915e6, lo_offset_hz=500e3)
        # Not a number at all (None, a string, NaN): named, before any arithmetic.
        for kw, name in (({"out_rate": None}, "out_rate"), ({"freq_hz": "2.4G"}, "freq"),
                         ({"device_rate": float("nan")}, "device_rate"),
                         ({"lo_offset_hz": "x"}, "lo_offset"),
                         ({"beacon_ppm": float("inf")}, "beacon_ppm"),
                         ({"max_speed_mps": None}, "max_speed_mps")):
            with self.assertRaisesRegex(ValueError, "^%s = " % name):
                rfseek.rx_plan("usrp_b2xx", **kw)
        # A gain that is not a number is refused before any device is looked for.
        for gain in (float("nan"), float("inf"), "loud"):
            with self.assertRaisesRegex(ValueError, "gain = .*RTL-SDR"):
                rfseek.radio_source("rtlsdr", 915e6, gain)
        for family, what in (("rtlsdr", "osmosdr"), ("plutosdr", "SoapySDR")):
            with self.assertRaisesRegex(LookupError, "no %s device found" % what):
                rfseek.radio_source(family, 915e6)


if __name__ == "__main__":
    gr_unittest.run(qa_radios)
