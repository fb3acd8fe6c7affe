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
import numbers

import pmt
from gnuradio import gr


def _real(name, v, lo=None, closed=True):
    """v as a float: a finite real (not a bool), and >= lo (closed) or > lo."""
    if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(v):
        raise ValueError("gain_loop: %s = %r: must be a finite number" % (name, v))
    if lo is not None and not (v >= lo if closed else v > lo):
        raise ValueError("gain_loop: %s = %g: must be %s %g" % (
            name, v, ">=" if closed else ">", lo))
    return float(v)


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
    the start, or the gain a user last set with set_gain_db, the GRC callback). The
    steps are taken as applied exactly, from the triggering window's time plus
    settle_s: a radio that rounds the gain (HackRF's 8 dB steps) or applies it later
    than that leaves power_db off by the difference."""

    def __init__(self, set_gain, gain_db, min_db, high_dbfs=-6.0, low_dbfs=-30.0,
                 step_down_db=10.0, step_up_db=5.0, settle_s=0.2, hold=20):
        gr.basic_block.__init__(self, name="rfseek_gain_loop", in_sig=None, out_sig=None)
        gain_db, min_db = _real("gain_db", gain_db), _real("min_db", min_db)
        high_dbfs, low_dbfs = _real("high_dbfs", high_dbfs), _real("low_dbfs", low_dbfs)
        if set_gain is not None and not callable(set_gain):
            raise ValueError("gain_loop: set_gain = %r: must be callable (the radio's "
                             "set_gain) or None (commands on the port only)" % (set_gain,))
        if not min_db <= gain_db:
            raise ValueError("gain_loop: min_db = %g: must be <= gain_db (%g)"
                             % (min_db, gain_db))
        if not low_dbfs < high_dbfs <= 0.0:
            raise ValueError("gain_loop: high_dbfs = %g, low_dbfs = %g: need low_dbfs < "
                             "high_dbfs <= 0 dBFS" % (high_dbfs, low_dbfs))
        self.down = _real("step_down_db", step_down_db, 0.0, False)
        self.up = _real("step_up_db", step_up_db, 0.0, False)
        self.settle = _real("settle_s", settle_s, 0.0, True)
        if isinstance(hold, bool) or not isinstance(hold, numbers.Integral) or hold < 1:
            raise ValueError("gain_loop: hold = %r: must be an integer >= 1 (windows)"
                             % (hold,))
        self.set_gain, self.min_db = set_gain, min_db
        # ref_db: the power's reference (the first start); start_db: the highest gain
        # the loop goes back up to (the user's setting: set_gain_db moves it).
        self.ref_db = self.start_db = self.gain_db = gain_db
        self.high, self.low, self.hold = high_dbfs, low_dbfs, int(hold)
        self.changes = []      # (window time of the change, gain before, gain after)
        self._quiet = 0
        self._last_t = -math.inf
        self.dropped = 0
        self.clipped = self.clipped_valid = 0  # windows clipped; of them passed as valid
        self.message_port_register_in(pmt.intern("meas"))
        self.message_port_register_out(pmt.intern("meas"))
        self.message_port_register_out(pmt.intern("command"))
        self.set_msg_handler(pmt.intern("meas"), self.on_meas)

    def gain_at(self, t):
        """(gain in force for a window at time t, settling): the gain before a change
        for windows up to its time, after it from settle_s later, unknown between."""
        g = self.ref_db
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
            if not math.isfinite(t):
                raise ValueError("time %r" % t)
        except (KeyError, TypeError, ValueError, AttributeError) as e:
            self.dropped += 1
            if self.dropped == 1:
                gr.log.warn("gain_loop: a meas without a finite time dropped (%s); the "
                            "rest are counted (dropped)" % e)
            return
        self._last_t = max(self._last_t, t)
        gain, settling = self.gain_at(t)
        shift = gain - self.ref_db
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

    def set_gain_db(self, gain_db):
        """GRC callback: the user set the radio's gain (a slider): the loop takes it as
        the gain in force from the latest window on, and as the highest it steps back
        up to. The radio is not commanded (the user's setter has done that)."""
        g = _real("gain_db", gain_db)
        if not g >= self.min_db:
            raise ValueError("gain_loop: gain_db = %g: must be >= min_db (%g)"
                             % (g, self.min_db))
        if g != self.gain_db:
            self.changes.append((self._last_t, self.gain_db, g))
            self.gain_db = g
        self.start_db = g
        self._quiet = 0

    def summary(self):
        """One line for a run's end: the steps, the gain's range, the clipped windows."""
        gains = [self.ref_db] + [after for _, _, after in self.changes]
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
