#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Figures of a seek, as the paper draws them: the trajectory (Fig. 5) and the frequency
measurements with the received power along the route (Fig. 6). Inputs are "columns":
dicts of equal-length numpy arrays, made from a flowgraph's collected messages
(columns_from_messages) or from a core simulation (columns_from_result)."""

import numpy as np


def columns_from_messages(states, meas, telemetry):
    """Columns from closed_loop's collector (one state, meas and telemetry per slot)."""
    n = min(len(meas), len(telemetry), len(states))
    st = states[:n]
    me = meas[:n]
    te = telemetry[:n]
    col = {
        "time_s": np.array([s["time"] for s in st]),
        "x_m": np.array([s["x"] for s in st]),
        "y_m": np.array([s["y"] for s in st]),
        "distance_m": np.array([s["distance"] for s in st]),
        "truth_f_hz": np.array([s["doppler_hz"] + s["cfo_hz"] for s in st]),
        "true_power_db": np.array([s["power_db"] for s in st]),
        "freq_hz": np.array([m["freq_hz"] for m in me]),
        "valid": np.array([bool(m["valid"]) for m in me]),
        "power_db": np.array([m["power_db"] for m in me]),
        "stage": np.array([t["stage"] for t in te]),
        "filtered_freq_hz": np.array([t["filtered_freq_hz"] for t in te]),
    }
    if states:  # the final position (arrival), which has no measurement
        col["end_xy"] = (states[-1]["x"], states[-1]["y"])
    return col


def columns_from_result(result, world_power_db=None):
    """Columns from rfseek.simulation(...).run()."""
    c = result.columns()
    return {
        "time_s": c["time_s"], "x_m": c["x_m"], "y_m": c["y_m"],
        "distance_m": c["distance_m"], "truth_f_hz": c["doppler_hz"] + c["cfo_hz"],
        "true_power_db": (c["true_snr_db"] if world_power_db is None else world_power_db),
        "freq_hz": c["freq_hz"], "valid": c["valid"].astype(bool),
        "power_db": c["power_db"], "stage": c["stage"].astype(int),
    }


def trajectory_figure(col, scatterers_xy=None, title=None, path=None):
    """Fig. 5: emitter, scatterers, start, path with the stages marked."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 6.5))
    ax.plot(0, 0, "r*", ms=14, label="emitter", zorder=5)
    if scatterers_xy is not None and len(scatterers_xy):
        sc = np.asarray(scatterers_xy, float).reshape(-1, 2)
        ax.plot(sc[:, 0], sc[:, 1], "k^", ms=4, label="scatterers")
    x, y, stage = col["x_m"], col["y_m"], col["stage"]
    for st, colour, label in ((1, "tab:orange", "stage 1 (circle)"),
                              (2, "tab:blue", "stage 2 (perturbations)")):
        sel = stage == st
        if sel.any():
            xs, ys = x.astype(float).copy(), y.astype(float).copy()
            xs[~sel] = np.nan  # break the line outside the stage
            ys[~sel] = np.nan
            ax.plot(xs, ys, "-", lw=1.2, color=colour, label=label)
    ax.plot(x[0], y[0], "go", ms=8, label="start")
    if "end_xy" in col:
        ax.plot(*col["end_xy"], "bs", ms=6, label="end")
    ax.add_patch(matplotlib.patches.Circle((0, 0), 200, fill=False, ls="--", color="r",
                                           label="d_v"))
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    ax.set_title(title or "trajectory", fontsize=10)
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=110)
    return fig


def frequency_power_figure(col, title=None, path=None):
    """Fig. 6: frequency measurements and received power along the route."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    t, v = col["time_s"], col["valid"]
    a1.plot(t[v], col["freq_hz"][v], ".", ms=1.5, color="tab:blue", label="measured")
    if "filtered_freq_hz" in col:
        a1.plot(t[v], col["filtered_freq_hz"][v], "-", lw=0.6, color="tab:green",
                label="after eq. 4")
    a1.plot(t, col["truth_f_hz"], "-", lw=1, color="tab:red", label="LOS Doppler + CFO (truth)")
    lo, hi = np.percentile(col["truth_f_hz"], [0, 100])
    a1.set_ylim(lo - 150, hi + 150)
    a1.set_ylabel("frequency (Hz)")
    a1.legend(fontsize=8, loc="best", markerscale=3)
    a1.grid(alpha=0.3)
    a1.set_title(title or "frequency measurements and received power", fontsize=10)
    a2.plot(t[v], col["power_db"][v], ".", ms=1.5, color="tab:blue", label="estimated tone power")
    a2.plot(t, col["true_power_db"], "-", lw=0.6, color="tab:red", label="received power (truth)")
    a2.set_xlabel("time (s)")
    a2.set_ylabel("power (dB)")
    a2.legend(fontsize=8, loc="best", markerscale=3)
    a2.grid(alpha=0.3)
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=110)
    return fig
