#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""seek_view: a QT GUI widget block that draws a seek live: the trajectory (emitter,
scatterers, path coloured by stage) from channel_source's "state" truth, and the frequency
measurements against the true Doppler + CFO from doppler_estimator's "meas"."""

import numbers
import threading

import numpy as np
import pmt
from gnuradio import gr
from matplotlib.backends.backend_qt5agg import FigureCanvasQTAgg as FigureCanvas
from matplotlib.figure import Figure
from PyQt5 import QtCore


class seek_view(gr.basic_block, FigureCanvas):
    """Live trajectory and frequency plots. Message inputs: state (channel_source), meas
    (doppler_estimator), telemetry (seeking_controller, optional: stage colouring)."""

    def __init__(self, title="gr-rfseek", update_ms=200, parent=None):
        if not (isinstance(update_ms, numbers.Real) and 10 <= update_ms <= 60000):
            raise ValueError("seek_view: update_ms = %r: must be in [10, 60000] ms"
                             % (update_ms,))
        gr.basic_block.__init__(self, name="seek_view", in_sig=None, out_sig=None)
        self.fig = Figure(figsize=(10, 4.5), dpi=90)
        FigureCanvas.__init__(self, self.fig)
        if parent is not None:
            self.setParent(parent)
        self._lock = threading.Lock()
        self._state = {k: [] for k in ("t", "x", "y", "truth_f")}
        self._meas = {k: [] for k in ("t", "f", "valid")}
        self._stage_by_slot = {}
        self._scatterers = np.zeros((0, 2))
        self._title = title
        for port, handler in (("state", self._on_state), ("meas", self._on_meas),
                              ("telemetry", self._on_telemetry)):
            self.message_port_register_in(pmt.intern(port))
            self.set_msg_handler(pmt.intern(port), handler)
        self.ax_xy = self.fig.add_subplot(1, 2, 1)
        self.ax_f = self.fig.add_subplot(1, 2, 2)
        self.fig.tight_layout()
        self._timer = QtCore.QTimer()
        self._timer.timeout.connect(self._redraw)
        self._timer.start(int(update_ms))

    # Message handlers run in GNU Radio threads: they only store numbers.
    def _on_state(self, msg):
        try:
            s = pmt.to_python(msg)
            with self._lock:
                self._state["t"].append(float(s["time"]))
                self._state["x"].append(float(s["x"]))
                self._state["y"].append(float(s["y"]))
                self._state["truth_f"].append(float(s["doppler_hz"]) + float(s["cfo_hz"]))
                if "scatterers" in s:
                    self._scatterers = np.asarray(s["scatterers"], float).reshape(-1, 2)
        except (KeyError, TypeError, ValueError, AttributeError):
            pass

    def _on_meas(self, msg):
        try:
            m = pmt.to_python(msg)
            with self._lock:
                self._meas["t"].append(float(m["time"]))
                self._meas["f"].append(float(m["freq_hz"]))
                self._meas["valid"].append(bool(m["valid"]))
        except (KeyError, TypeError, ValueError, AttributeError):
            pass

    def _on_telemetry(self, msg):
        try:
            t = pmt.to_python(msg)
            with self._lock:
                self._stage_by_slot[int(t["slot"])] = int(t["stage"])
        except (KeyError, TypeError, ValueError, AttributeError):
            pass

    def _redraw(self):
        with self._lock:
            x = np.array(self._state["x"])
            y = np.array(self._state["y"])
            ts = np.array(self._state["t"])
            truth = np.array(self._state["truth_f"])
            tm = np.array(self._meas["t"])
            fm = np.array(self._meas["f"])
            vm = np.array(self._meas["valid"], bool)
            stages = dict(self._stage_by_slot)
            sc = self._scatterers.copy()
        if len(x) == 0:
            return
        ax = self.ax_xy
        ax.clear()
        ax.plot(0, 0, "r*", ms=12, label="emitter")
        if len(sc):
            ax.plot(sc[:, 0], sc[:, 1], "k.", ms=3, label="scatterers")
        stage = np.array([stages.get(k, 0) for k in range(len(x))])
        for st, colour, label in ((1, "tab:orange", "stage 1"), (2, "tab:blue", "stage 2"),
                                  (0, "tab:gray", "path")):
            sel = stage == st
            if sel.sum() > 1:
                ax.plot(x[sel], y[sel], ".", ms=1, color=colour, label=label)
        ax.plot(x[0], y[0], "go", label="start")
        ax.plot(x[-1], y[-1], "b^")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_title("%s: trajectory, %.0f m from the emitter" % (self._title,
                                                                   np.hypot(x[-1], y[-1])),
                     fontsize=9)
        ax.legend(fontsize=7, loc="best")
        ax.grid(alpha=0.3)
        ax = self.ax_f
        ax.clear()
        if len(tm):
            ax.plot(tm[vm], fm[vm], ".", ms=1, color="tab:blue", label="measured")
        ax.plot(ts, truth, "-", lw=1, color="tab:red", label="LOS Doppler + CFO (truth)")
        if len(truth):  # outliers (deep fades) would hide the structure
            ax.set_ylim(truth.min() - 150.0, truth.max() + 150.0)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("frequency (Hz)")
        ax.set_title("frequency measurements", fontsize=9)
        ax.legend(fontsize=7, loc="best")
        ax.grid(alpha=0.3)
        self.draw_idle()
