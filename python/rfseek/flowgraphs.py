#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Ready-made flowgraphs: the closed-loop seek of channel_source -> doppler_estimator ->
seeking_controller -> channel_source, with the truth and telemetry collected."""

import sys

import pmt
from gnuradio import gr

from .rfseek_python import (channel_source, doppler_estimator, estimator_config,
                            seeking_controller, simulation)


class collector(gr.basic_block):
    """Keeps every message of its inputs 'state', 'meas' and 'telemetry' as Python dicts;
    optionally prints a progress line every `every` slots."""

    def __init__(self, progress_every=0, stream=sys.stderr):
        gr.basic_block.__init__(self, name="rfseek_collector", in_sig=None, out_sig=None)
        self.states, self.meas, self.telemetry = [], [], []
        self._every = progress_every
        self._stream = stream
        # GNU Radio's Python gateway finds handlers by method name: one method per port.
        self.message_port_register_in(pmt.intern("state"))
        self.set_msg_handler(pmt.intern("state"), self.on_state)
        self.message_port_register_in(pmt.intern("meas"))
        self.set_msg_handler(pmt.intern("meas"), self.on_meas)
        self.message_port_register_in(pmt.intern("telemetry"))
        self.set_msg_handler(pmt.intern("telemetry"), self.on_telemetry)

    def on_meas(self, msg):
        self.meas.append(pmt.to_python(msg))

    def on_telemetry(self, msg):
        self.telemetry.append(pmt.to_python(msg))

    def on_state(self, msg):
        d = pmt.to_python(msg)
        self.states.append(d)
        end = d["arrived"] or d["capped"]
        tty = hasattr(self._stream, "isatty") and self._stream.isatty()
        every = self._every if tty else 10 * self._every  # a log gets fewer lines
        if self._every and (d["slot"] % every == 0 or end):
            stage = self.telemetry[-1]["stage"] if self.telemetry else 0
            line = "  slot %6d  t %7.1f s  flown %7.1f m  to go %7.1f m  stage %d" % (
                d["slot"], d["time"], d["distance_flown"], d["distance"], stage)
            self._stream.write(("\r" + line + ("\n" if end else "")) if tty else line + "\n")
            self._stream.flush()


class closed_loop(gr.top_block):
    """The seek through GNU Radio, in lockstep (reproducible from the scenario's seed).

    scenario: rfseek.scenario; strategy: seeker strategy name or a seeker_config;
    estimator: rfseek.estimator_config (window, interpolator, band)."""

    def __init__(self, scenario, strategy="paper", estimator=None, progress_every=0):
        gr.top_block.__init__(self, "rfseek closed loop", catch_exceptions=False)
        est_cfg = estimator or estimator_config()
        cfg = (simulation.seeker_for(scenario, strategy) if isinstance(strategy, str)
               else strategy)
        self.source = channel_source(scenario, mode="burst", lockstep=True, realtime=False)
        self.estimator = doppler_estimator(scenario.samp_rate_hz, scenario.window_len,
                                           scenario.fft_len, window=est_cfg.window,
                                           interpolator=est_cfg.interpolator,
                                           min_freq=est_cfg.min_freq_hz,
                                           max_freq=est_cfg.max_freq_hz)
        self.controller = seeking_controller(cfg)
        self.collector = collector(progress_every)
        self.connect(self.source, self.estimator)
        self.msg_connect(self.estimator, "meas", self.controller, "meas")
        self.msg_connect(self.controller, "cmd", self.source, "cmd")
        self.msg_connect(self.source, "state", self.collector, "state")
        self.msg_connect(self.estimator, "meas", self.collector, "meas")
        self.msg_connect(self.controller, "telemetry", self.collector, "telemetry")


class state_to_nav(gr.basic_block):
    """Turns channel_source's per-slot truth into the heading reports a vehicle would
    send ({heading} = the measured heading), for recordings and demos of the nav path."""

    def __init__(self):
        gr.basic_block.__init__(self, name="rfseek_state_to_nav", in_sig=None, out_sig=None)
        self.message_port_register_in(pmt.intern("state"))
        self.message_port_register_out(pmt.intern("nav"))
        self.set_msg_handler(pmt.intern("state"), self.on_state)

    def on_state(self, msg):
        try:
            h = float(pmt.to_python(msg)["measured_heading"])
        except (KeyError, TypeError, ValueError, AttributeError):
            return
        self.message_port_pub(pmt.intern("nav"), pmt.to_pmt({"heading": h}))
