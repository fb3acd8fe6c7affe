#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Figures of a seek, as the paper draws them: the trajectory (Fig. 5) and the frequency
measurements with the received power along the route (Fig. 6). Inputs are "columns":
dicts of equal-length numpy arrays, made from a flowgraph's collected messages
(columns_from_messages) or from a core simulation (columns_from_result)."""

import math

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


def trajectory_figure(col, scatterers_xy=None, title=None, path=None, arrival=None):
    """Fig. 5: emitter, scatterers, start, path with the stages marked. arrival (from
    flowgraphs.arrival_summary, a self_arrival flight): the loiter from the overflight,
    where arrival was declared, the estimated emitter and its 95 % ellipse."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    zoom = bool(arrival and arrival.get("declared"))
    if zoom:  # the whole flight, and the last few hundred metres around the emitter
        fig, (ax, az) = plt.subplots(1, 2, figsize=(13, 6.5))
    else:
        fig, ax = plt.subplots(figsize=(7, 6.5))

    def draw(ax, legend):
        ax.plot(0, 0, "r*", ms=14, label="emitter", zorder=5)
        if scatterers_xy is not None and len(scatterers_xy):
            sc = np.asarray(scatterers_xy, float).reshape(-1, 2)
            ax.plot(sc[:, 0], sc[:, 1], "k^", ms=4, label="scatterers")
        x, y, stage = col["x_m"], col["y_m"], col["stage"]
        for st, colour, label in ((1, "tab:orange", "stage 1 (circle)"),
                                  (2, "tab:blue", "stage 2 (perturbations)"),
                                  (3, "tab:green", "loiter (from the overflight)")):
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
        if arrival and (stage == 3).any():
            k = int(np.argmax(stage == 3))
            ax.plot(x[k], y[k], "c^", ms=8, label="overflight seen (%.0f m)"
                    % np.hypot(x[k], y[k]))
        if arrival and arrival.get("declared"):
            k = min(int(arrival["arrival_slot"]), len(x) - 1)
            ax.plot(x[k], y[k], "mv", ms=8, label="arrival declared (%.0f m)"
                    % arrival["arrival_detect_distance_m"])
        if arrival and arrival.get("located"):
            ex, ey = arrival["estimated_emitter_xy"]
            loc = arrival["location"]
            ax.plot(ex, ey, "mx", ms=10, mew=2, label="estimated emitter (error %.1f m)"
                    % arrival["location_error_m"])
            ax.add_patch(matplotlib.patches.Ellipse(
                (ex, ey), 2 * loc["major_m"], 2 * loc["minor_m"],
                angle=np.degrees(loc["major_angle_rad"]), fill=False, color="m",
                label="95 % ellipse"))
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.grid(alpha=0.3)
        if legend:
            ax.legend(fontsize=8, loc="best")

    draw(ax, True)
    if zoom:
        draw(az, False)
        half = 300.0
        if arrival.get("located"):
            ex, ey = arrival["estimated_emitter_xy"]
            half = max(half, 1.3 * math.hypot(ex, ey))
        az.set_aspect("equal", adjustable="box")
        az.set_xlim(-half, half)
        az.set_ylim(-half, half)
        az.set_title("around the emitter: loiter, fix and its 95 % ellipse", fontsize=10)
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


# ---------------------------------------------------------------------------------------
# Monte Carlo figures (rfseek-montecarlo's JSON)

def _study(result, need=None):
    """`result` checked to be rfseek-montecarlo's JSON (the dict json.load gives of its
    --out file), with the key `need` when given: ValueError naming what is wrong
    otherwise (a single run's run_result, a path, a study without --sweep)."""
    if not (isinstance(result, dict) and "rows" in result and "strategies" in result):
        raise ValueError(
            "result = %s: must be rfseek-montecarlo's JSON, the dict json.load gives of "
            "its --out file (one run's run_result goes to trajectory_figure("
            "columns_from_result(r)))" % type(result).__name__)
    if need == "sweep" and "sweep" not in result:
        raise ValueError("result: a study without --sweep; this figure needs one made "
                         "with --sweep KEY=V1,V2,...")
    if need and need not in result:
        raise ValueError("result: no %r in this JSON; made by an older "
                         "rfseek-montecarlo? Run the study again" % need)
    return result


def _rows_by_strategy(result, sweep_value=None):
    out = {}
    for r in result["rows"]:
        if sweep_value is not None and r.get("sweep_value") != sweep_value:
            continue
        if "error" in r:  # a run that raised: counted in the summary, not drawn
            continue
        out.setdefault(r["strategy"], []).append(r)
    return out


def distance_histograms(result, path=None, bins=40):
    """Figs. 7-8: histogram of the distance flown per strategy (failed runs, which stop
    at the flight cap, are drawn in grey)."""
    _study(result, "summary")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    by = _rows_by_strategy(result)
    names = [s for s in result["strategies"] if s in by]
    fig, axes = plt.subplots(len(names), 1, figsize=(7, 2.6 * len(names) + 0.6), squeeze=False)
    shortest = next(iter(result["summary"].values()))["shortest_path_m"]
    for ax, name in zip(axes[:, 0], names):
        rows = by[name]
        ok = np.array([r["distance_m"] for r in rows if r["success"]]) / 1000.0
        bad = np.array([r["distance_m"] for r in rows if not r["success"]]) / 1000.0
        s = result["summary"][name]
        hi = max([1e-9] + list(ok) + list(bad))
        edges = np.linspace(shortest / 1000.0 * 0.98, hi * 1.02, bins + 1)
        ax.hist(ok, bins=edges, color="tab:blue", label="arrived")
        if len(bad):
            ax.hist(bad, bins=edges, color="tab:gray", label="flight cap (failed)")
        ax.axvline(shortest / 1000.0, color="k", ls="--", lw=1, label="shortest path")
        ax.axvline(s["mean_distance_m"] / 1000.0, color="tab:red", lw=1.5,
                   label="mean %.2f km (%.2f x)" % (s["mean_distance_m"] / 1000.0,
                                                   s["mean_ratio"]))
        ax.set_title("%s: %d runs, success %.1f %%" % (name, s["runs"],
                                                       100 * s["success_rate"]), fontsize=10)
        ax.set_ylabel("runs")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("distance flown to reach d_v (km)")
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=110)
    return fig


def comparison_chart(result, paper=None, path=None):
    """Mean, median and p90 of the distance ratio per strategy, with the paper's means."""
    _study(result, "summary")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = [s for s in result["strategies"] if s in result["summary"]]
    fig, ax = plt.subplots(figsize=(7, 4))
    x = np.arange(len(names))
    w = 0.25
    for k, (key, label) in enumerate((("mean_ratio", "mean"), ("median_ratio", "median"),
                                      ("p90_ratio", "90th percentile"))):
        ax.bar(x + (k - 1) * w, [result["summary"][n][key] for n in names], w, label=label)
    if paper:
        for i, n in enumerate(names):
            if n in paper:
                ax.plot([i - 1.5 * w, i + 1.5 * w], [paper[n]] * 2, "k--", lw=1.5,
                        label="paper (mean)" if i == 0 else None)
    for i, n in enumerate(names):
        ax.text(i, 0.05, "%.0f %% ok" % (100 * result["summary"][n]["success_rate"]),
                ha="center", fontsize=8, color="white")
    ax.set_xticks(x)
    ax.set_xticklabels(names)
    ax.set_ylabel("distance / shortest path")
    ax.set_title("distance ratio, %d runs per strategy" % result["runs"], fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=110)
    return fig


def in_wind(result):
    """True if the result's rows flew in wind (their straight-line ratio differs from the
    plain ratio): then the fair measure is the straight-line ratio, the air distance
    over the air distance of the straight ground line in the same wind (1 for a straight
    ground track, whatever the wind)."""
    _study(result)
    return any("straight_ratio" in r and "error" not in r
               and r["straight_ratio"] != r["ratio"] for r in result["rows"])


def sweep_metric(result, metric="auto"):
    """(JSON key prefix, axis label) of the ratio a sweep is drawn and tabled with:
    metric "ratio" (distance over the shortest path), "straight_ratio" or "auto"
    (straight_ratio when the rows flew in wind)."""
    _study(result)
    if metric not in ("auto", "ratio", "straight_ratio"):
        raise ValueError("metric must be auto, ratio or straight_ratio, not %r" % metric)
    if metric == "auto":
        metric = "straight_ratio" if in_wind(result) else "ratio"
    if metric == "straight_ratio":
        return "straight_ratio", "air distance / straight ground line's"
    return "ratio", "distance / shortest path"


def sweep_plot(result, path=None, metric="auto"):
    """Ratio (mean, p90) and success rate versus the swept parameter, per strategy; one
    column of panels per preset when the study swept several (--preset A,B --sweep). In
    wind (metric "auto") the ratio is the straight-line ratio (sweep_metric)."""
    _study(result, "sweep")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    key, label = sweep_metric(result, metric)
    sw = result["sweep"]
    presets = []
    for e in sw["summary"]:
        if e.get("preset") not in presets:
            presets.append(e.get("preset"))
    fig, axes = plt.subplots(2, len(presets), figsize=(7 * len(presets), 6), sharex=True,
                             squeeze=False)
    for col, preset in enumerate(presets):
        entries = [e for e in sw["summary"] if e.get("preset") == preset]
        xs = [float(e["value"]) for e in entries]
        a1, a2 = axes[0][col], axes[1][col]
        for name in result["strategies"]:
            mean = [e[name]["mean_" + key] for e in entries]
            p90 = [e[name]["p90_" + key] for e in entries]
            ok = [100 * e[name]["success_rate"] for e in entries]
            line, = a1.plot(xs, mean, "o-", label="%s mean" % name)
            a1.plot(xs, p90, "s--", color=line.get_color(), alpha=0.6,
                    label="%s p90" % name)
            a2.plot(xs, ok, "o-", color=line.get_color(), label=name)
        a1.set_ylabel(label)
        a1.grid(alpha=0.3)
        a1.legend(fontsize=8)
        a1.set_title("%ssweep of %s, %d runs per point" % (
            "%s: " % preset if len(presets) > 1 else "", sw["key"], result["runs"]),
            fontsize=10)
        a2.set_ylabel("success (%)")
        a2.set_xlabel(sw["key"])
        a2.grid(alpha=0.3)
        a2.legend(fontsize=8)
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=110)
    return fig


def sweep_table(result, metric="auto"):
    """The sweep as Markdown: a row per strategy, a column per swept value, cells
    "mean / p90 (success)" of the ratio sweep_metric picks."""
    _study(result, "sweep")
    key, label = sweep_metric(result, metric)
    sw = result["sweep"]
    presets = []
    for e in sw["summary"]:
        if e.get("preset") not in presets:
            presets.append(e.get("preset"))
    lines = []
    for preset in presets:  # one table per preset (--preset A,B with --sweep)
        entries = [e for e in sw["summary"] if e.get("preset") == preset]
        if lines:
            lines.append("")
        head = "%s (%s)" % (sw["key"], label)
        if len(presets) > 1:
            head = "%s: %s" % (preset, head)
        lines += ["| %s | " % head + " | ".join(str(e["value"]) for e in entries) + " |",
                  "| --- |" + " --- |" * len(entries)]
        for name in result["strategies"]:
            cells = []
            for e in entries:
                s = e[name]
                ok = ("%.1f" % (100 * s["success_rate"])).replace("100.0", "100")
                cells.append("%.3f / %.3f (%s %%)" % (s["mean_" + key], s["p90_" + key],
                                                       ok))
            lines.append("| `%s` mean / p90 (success) | " % name + " | ".join(cells) +
                         " |")
    return "\n".join(lines)


def preset_plot(result, path=None, ymax=1.6):
    """Strategies compared across presets (rfseek-montecarlo --preset A,B,...): mean ratio
    (bars) and p90 (ticks) above, success rate below. Bars beyond ymax are cut and
    labelled with their value."""
    _study(result, "points")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    presets = [p["preset"] for p in result["points"]]
    names = [s for s in result["strategies"]]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(max(7, 1.1 * len(presets) + 2), 6.5),
                                 sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    x = np.arange(len(presets))
    w = 0.8 / max(1, len(names))
    for k, name in enumerate(names):
        xs = x + (k - (len(names) - 1) / 2) * w
        mean = np.array([p[name]["mean_ratio"] for p in result["points"]])
        p90 = np.array([p[name]["p90_ratio"] for p in result["points"]])
        ok = np.array([100 * p[name]["success_rate"] for p in result["points"]])
        bars = a1.bar(xs, np.minimum(mean, ymax) - 1.0, w, bottom=1.0, label=name)
        color = bars.patches[0].get_facecolor()
        a1.plot(xs, np.minimum(p90, ymax), "_", color="k", ms=8,
                label="p90" if k == len(names) - 1 else None)
        for xi, m in zip(xs, mean):
            if m > ymax:
                a1.text(xi, ymax - 0.02, "%.2f" % m, rotation=90, ha="center", va="top",
                        fontsize=7, color="white")
        a2.bar(xs, ok, w, color=color)
    a1.set_ylim(1.0, ymax)
    a1.set_ylabel("distance / shortest path")
    a1.set_title("strategies across presets, %d runs each (mean: bar, p90: tick)"
                 % result["runs"], fontsize=10, pad=24)
    # above the axes: inside, it would hide the labels of bars cut at the top
    a1.legend(fontsize=8, ncol=len(names) + 1, loc="lower center",
              bbox_to_anchor=(0.5, 1.0), frameon=False)
    a1.grid(axis="y", alpha=0.3)
    a2.set_ylabel("success (%)")
    a2.set_ylim(0, 105)
    a2.grid(axis="y", alpha=0.3)
    a2.set_xticks(x)
    a2.set_xticklabels(presets, rotation=20)
    fig.tight_layout()
    if path:
        fig.savefig(path, dpi=110)
    return fig
