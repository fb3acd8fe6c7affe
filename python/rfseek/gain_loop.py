#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""gain_loop: an automatic gain loop for a radio, driven by the estimator's measurements.

The received power rises by about 30 dB from 5 km to 100 m: a radio set for the far
beacon clips close in, and a clipped window is never valid (doppler_estimator with
set_full_scale). The loop steps the radio's gain down when a window clips or peaks near
full scale, and back up when the windows stay far below it, and passes the measurements
on with their power referred to the gain it started at, so that what follows sees one
power scale whatever the gain.
"""

import math

import pmt
from gnuradio import gr


class gain_loop(gr.basic_block):
    """Message in `meas` (doppler_estimator's, with peak_dbfs: set its full scale), out
    `meas` (forwarded; power_db and noise_power_db minus the gain change since the start,
    gain_db added; windows in the settle_s after a change are invalid, since the gain
    they were measured at is not known). set_gain: a callable taking the radio's gain in
    dB (radio_source.set_gain, sim_radio.set_gain), or None: every change is also
    published on the message port `command` as {"gain": dB}, the command of UHD's
    sources and of radio_source (GRC: connect it to the radio's command port). A window
    that clips or peaks above high_dbfs steps the gain down by step_down_db (not below
    min_db); hold windows in a row below low_dbfs step it up by step_up_db (not above
    the start)."""

    def __init__(self, set_gain, gain_db, min_db, high_dbfs=-6.0, low_dbfs=-30.0,
                 step_down_db=10.0, step_up_db=5.0, settle_s=0.2, hold=20):
        gr.basic_block.__init__(self, name="rfseek_gain_loop", in_sig=None, out_sig=None)
        checks = (("gain_db", gain_db), ("min_db", min_db), ("high_dbfs", high_dbfs),
                  ("low_dbfs", low_dbfs), ("step_down_db", step_down_db),
                  ("step_up_db", step_up_db), ("settle_s", settle_s))
        for name, v in checks:
            if not (isinstance(v, (int, float)) and math.isfinite(v)):
                raise ValueError("gain_loop: %s = %r: must be a finite number" % (name, v))
        if set_gain is not None and not callable(set_gain):
            raise ValueError("gain_loop: set_gain = %r: must be callable (the radio's "
                             "set_gain) or None (commands on the port only)" % (set_gain,))
        if not (min_db <= gain_db and low_dbfs < high_dbfs <= 0.0 and step_down_db > 0 and
                step_up_db > 0 and settle_s >= 0 and isinstance(hold, int) and hold >= 1):
            raise ValueError("gain_loop: need min_db <= gain_db, low_dbfs < high_dbfs <= 0, "
                             "steps > 0, settle_s >= 0, hold >= 1")
        self.set_gain, self.start_db, self.min_db = set_gain, float(gain_db), float(min_db)
        self.high, self.low = float(high_dbfs), float(low_dbfs)
        self.down, self.up = float(step_down_db), float(step_up_db)
        self.settle, self.hold = float(settle_s), hold
        self.gain_db = self.start_db
        self.changes = []      # (window time of the change, gain before, gain after)
        self._quiet = 0
        self.dropped = 0
        self.clipped = self.clipped_valid = 0  # windows clipped; of them passed as valid
        self.message_port_register_in(pmt.intern("meas"))
        self.message_port_register_out(pmt.intern("meas"))
        self.message_port_register_out(pmt.intern("command"))
        self.set_msg_handler(pmt.intern("meas"), self.on_meas)

    def gain_at(self, t):
        """(gain in force for a window at time t, settling): the gain before a change
        for windows up to its time, after it from settle_s later, unknown between."""
        g = self.start_db
        for when, before, after in self.changes:
            if t < when:
                return before, False
            if t < when + self.settle:
                return after, True
            g = after
        return g, False

    def on_meas(self, msg):
        try:
            d = pmt.to_python(msg)
            t = float(d["time"])
        except (KeyError, TypeError, ValueError, AttributeError):
            self.dropped += 1
            return
        gain, settling = self.gain_at(t)
        shift = gain - self.start_db
        for key in ("power_db", "noise_power_db"):
            if isinstance(d.get(key), (int, float)):
                d[key] = float(d[key]) - shift
        d["gain_db"] = gain
        if settling:
            d["valid"] = False
        if d.get("clipped"):
            self.clipped += 1
            self.clipped_valid += bool(d.get("valid"))
        self._step(t, d)
        self.message_port_pub(pmt.intern("meas"), pmt.to_pmt(d))

    def summary(self):
        """One line for a run's end: the steps, the gain's range, the clipped windows."""
        gains = [self.start_db] + [after for _, _, after in self.changes]
        return "%d gain steps (%.0f to %.0f dB), %d windows clipped, %d of them valid" % (
            len(self.changes), min(gains), max(gains), self.clipped, self.clipped_valid)

    def _step(self, t, d):
        peak = d.get("peak_dbfs")
        if not isinstance(peak, (int, float)) or not math.isfinite(peak):
            return
        if self.changes and t < self.changes[-1][0] + self.settle:
            return  # the last change has not reached the windows yet
        new = self.gain_db
        if d.get("clipped") or peak > self.high:
            new = max(self.min_db, self.gain_db - self.down)
            self._quiet = 0
        elif peak < self.low:
            self._quiet += 1
            if self._quiet >= self.hold:
                new = min(self.start_db, self.gain_db + self.up)
                self._quiet = 0
        else:
            self._quiet = 0
        if new != self.gain_db:
            self.changes.append((t, self.gain_db, new))
            self.gain_db = new
            if self.set_gain is not None:
                self.set_gain(new)
            self.message_port_pub(pmt.intern("command"), pmt.to_pmt({"gain": new}))
