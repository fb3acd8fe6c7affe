#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Pictures for the user guide, drawn without a display: each example flowgraph as GRC
lays it out (its blocks at their canvas coordinates, with their labels and the
parameters GRC shows, stream connections solid, message connections dashed), and the
Seeking Controller's options dialog, tab by tab, from its block file.

  scripts/draw_flowgraphs.py [OUT_DIR]       (default docs/figures)

Writes OUT_DIR/flowgraph_<example>.png and OUT_DIR/controller_dialog.png. GRC itself
needs GTK and a display, which a build machine lacks; the drawing reads the same .grc
and .block.yml files GRC reads.
"""

import glob
import os
import sys

import yaml

SOURCE = os.path.normpath(os.path.join(os.path.dirname(__file__), ".."))
GR_BLOCKS = ("/usr/share/gnuradio/grc/blocks", "/usr/local/share/gnuradio/grc/blocks")


def block_files():
    """{block id: its parsed .block.yml}, GNU Radio's and the module's."""
    out = {}
    for d in GR_BLOCKS + (os.path.join(SOURCE, "grc"),):
        for path in glob.glob(os.path.join(d, "*.block.yml")):
            with open(path) as f:
                y = yaml.safe_load(f)
            if isinstance(y, dict) and "id" in y:
                out[y["id"]] = y
    return out


def shown_params(block, spec, limit=6):
    """(label, value) of the parameters a block shows on its first tab, in the block
    file's order, hidden ones left out, at most `limit`."""
    values = block.get("parameters") or {}
    rows = []
    for p in (spec or {}).get("parameters", []):
        if p.get("category", "General") not in ("General", "") or p["id"] not in values:
            continue
        if str(p.get("hide", "none")).strip() in ("all", "part") or p["id"] in (
                "alias", "affinity", "minoutbuf", "maxoutbuf", "comment"):
            continue
        text = str(values[p["id"]]).replace("\n", " ")
        if text == "":
            continue
        label = str(p.get("label", p["id"]))
        rows.append((label if len(label) <= 26 else label[:23] + "...",
                     text if len(text) <= 22 else text[:19] + "..."))
    return rows[:limit]


def draw_flowgraph(path, specs, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import FancyBboxPatch

    with open(path) as f:
        fg = yaml.safe_load(f)
    boxes = {}
    for b in fg["blocks"]:
        if b.get("states", {}).get("state") == "disabled":
            continue
        spec = specs.get(b["id"])
        title = spec.get("label", b["id"]) if spec else b["id"]
        rows = shown_params(b, spec)
        if b["id"] in ("variable", "parameter"):
            v = (b.get("parameters") or {}).get("value", "")
            rows = [("Id", b["name"]), ("Value", str(v)[:22])]
        x, y = b["states"]["coordinate"]
        w = 4.6 * max([len(title) * 1.1] + [len(a) + len(v) + 2 for a, v in rows]) + 12
        h = 15 + 10 * len(rows)
        boxes[b["name"]] = (x, y, w, h, title, rows, b["id"] in ("variable", "parameter"))
    width = max(x + w for x, y, w, h, *_ in boxes.values()) + 20
    height = max(y + h for x, y, w, h, *_ in boxes.values()) + 20
    fig = plt.figure(figsize=(width / 72.0, height / 72.0))
    ax = fig.add_axes([0, 0, 1, 1])
    ax.set_xlim(0, width)
    ax.set_ylim(height, 0)
    ax.axis("off")
    for name, (x, y, w, h, title, rows, var) in boxes.items():
        ax.add_patch(FancyBboxPatch((x, y), w, h, boxstyle="round,pad=0,rounding_size=4",
                                    fc="#eeeeee" if var else "#dde8f8", ec="#333333", lw=0.8))
        ax.text(x + w / 2, y + 8, title, ha="center", va="center", fontsize=5.5,
                fontweight="bold")
        for i, (a, v) in enumerate(rows):
            ax.text(x + 5, y + 19 + 10 * i, "%s: %s" % (a, v), fontsize=4.8, va="center")
    for src, sport, dst, dport in fg.get("connections", []):
        if src not in boxes or dst not in boxes:
            continue
        x0, y0, w0, h0 = boxes[src][:4]
        x1, y1, w1, h1 = boxes[dst][:4]
        stream = str(sport).isdigit() and str(dport).isdigit()
        ax.annotate("", xy=(x1, y1 + h1 / 2), xytext=(x0 + w0, y0 + h0 / 2),
                    arrowprops=dict(arrowstyle="->", lw=0.9 if stream else 0.7,
                                    ls="-" if stream else "--",
                                    color="#1f4e9c" if stream else "#555555",
                                    connectionstyle="arc3,rad=0.08"))
        if not stream:
            ax.text((x0 + w0 + x1) / 2, (y0 + h0 / 2 + y1 + h1 / 2) / 2 - 4,
                    "%s -> %s" % (sport, dport), fontsize=4.5, color="#555555", ha="center")
    fig.savefig(out, dpi=120)
    plt.close(fig)


def draw_dialog(spec, out):
    """The controller's options dialog: one column per tab, label and default value."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tabs = {}
    for p in spec["parameters"]:
        default = str(p.get("default", ""))
        if p.get("options") and p.get("option_labels"):  # an enum shows its label
            for value, label in zip(p["options"], p["option_labels"]):
                if str(value) == default:
                    default = str(label)
        label = str(p.get("label", p["id"]))
        tabs.setdefault(p.get("category", "General"), []).append(
            (label if len(label) <= 40 else label[:37] + "...", default))
    n = max(len(v) for v in tabs.values())
    fig, axes = plt.subplots(1, len(tabs), figsize=(5.6 * len(tabs), 0.26 * n + 0.9))
    for ax, (tab, rows) in zip(axes, tabs.items()):
        ax.axis("off")
        ax.set_title("%s (%d)" % (tab, len(rows)), fontsize=9, fontweight="bold", loc="left")
        for i, (label, default) in enumerate(rows):
            d = default if len(default) <= 18 else default[:15] + "..."
            ax.text(0.0, 1 - (i + 0.5) / n, label, fontsize=7, va="center",
                    transform=ax.transAxes)
            ax.text(0.68, 1 - (i + 0.5) / n, d, fontsize=7, va="center", family="monospace",
                    transform=ax.transAxes,
                    bbox=dict(fc="white", ec="#999999", lw=0.5, pad=1.5))
    fig.suptitle("%s: properties" % spec.get("label", spec["id"]), fontsize=10, x=0.01,
                 ha="left")
    fig.savefig(out, dpi=110, bbox_inches="tight")
    plt.close(fig)


def main(argv):
    out_dir = argv[0] if argv else os.path.join(SOURCE, "docs", "figures")
    specs = block_files()
    written = []
    for path in sorted(glob.glob(os.path.join(SOURCE, "examples", "*.grc"))):
        name = os.path.splitext(os.path.basename(path))[0]
        out = os.path.join(out_dir, "flowgraph_%s.png" % name)
        draw_flowgraph(path, specs, out)
        written.append(out)
    out = os.path.join(out_dir, "controller_dialog.png")
    draw_dialog(specs["rfseek_seeking_controller"], out)
    written.append(out)
    print("\n".join(written))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
