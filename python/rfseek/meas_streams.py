#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""meas_streams: doppler_estimator's measurements as float streams for QT GUI number and
time sinks (the measure-only flowgraph's display)."""

import collections
import math
import queue
import time

import numpy
import pmt
from gnuradio import gr


class meas_streams(gr.sync_block):
    """Message in "meas" (doppler_estimator's dicts); three float outputs, one item per
    valid measurement: freq_hz, snr_db, and the rate of valid measurements over the last
    `window_s` seconds of sample time (per second: the beacon's burst rate when all are
    heard). Invalid windows and malformed messages give no item (the latter are counted
    in dropped())."""

    def __init__(self, window_s=1.0):
        gr.sync_block.__init__(self, "rfseek_meas_streams", None,
                               [numpy.float32, numpy.float32, numpy.float32])
        if not (window_s > 0 and math.isfinite(window_s)):
            raise ValueError("window_s = %r: must be > 0" % window_s)
        self.window_s = float(window_s)
        self.message_port_register_in(pmt.intern("meas"))
        self.set_msg_handler(pmt.intern("meas"), self._on_meas)
        self._q = queue.Queue()
        self._times = collections.deque()
        self._dropped = 0
        self._stop = False

    def dropped(self):
        return self._dropped

    def _on_meas(self, msg):
        try:
            d = pmt.to_python(msg)
            f, snr, t = float(d["freq_hz"]), float(d["snr_db"]), float(d["time"])
            valid = bool(d["valid"])
        except (KeyError, TypeError, ValueError, AttributeError):
            self._dropped += 1
            return
        if valid and all(map(math.isfinite, (f, snr, t))):
            self._q.put((f, snr, t))

    def stop(self):
        self._stop = True
        return True

    def work(self, input_items, output_items):
        n = 0
        limit = len(output_items[0])
        while n < limit and not self._stop:
            try:
                f, snr, t = self._q.get_nowait()
            except queue.Empty:
                break
            self._times.append(t)
            while self._times and self._times[0] < t - self.window_s:
                self._times.popleft()
            output_items[0][n] = f
            output_items[1][n] = snr
            output_items[2][n] = len(self._times) / self.window_s
            n += 1
        if self._stop and n == 0:
            return -1  # WORK_DONE
        if n == 0:
            # The message handler runs on this block's thread between calls: give it the
            # turn without spinning.
            time.sleep(0.01)
        return n
