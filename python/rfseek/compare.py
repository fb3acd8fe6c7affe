#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Paired comparison of two rfseek-montecarlo results.

rfseek-montecarlo flies run i of every study on scenario seed S + i, so two studies
over the same seeds (a changed --set, another build) fly the same worlds: the same
start, emitter, scatterers, CFO, wind and noise draws. Their per-seed differences
cancel what the worlds have in common, and the mean difference is known far more
precisely than either mean (docs/results.md "Comparing two variants on the same
seeds"). `rfseek-plot-montecarlo VARIANT.json --against BASE.json` prints it.
"""

import math
import statistics

#: The columns a comparison may use (numbers in every row of rfseek-montecarlo).
COLUMNS = ("ratio", "straight_ratio", "distance_m", "time_s", "location_error_m")


def _group(row):
    return (row.get("strategy", ""), row.get("preset", ""), row.get("sweep_value", ""))


def _value(row, column):
    v = row.get(column)
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return None
    return float(v) if math.isfinite(v) else None


def paired(variant, base, column="ratio"):
    """Per (strategy, preset, sweep value) held by both results, over the seeds both
    flew: n, the two means, the mean of the per-seed differences variant - base, its
    standard error (stdev / sqrt(n); None below 2 pairs), the runs whose value changed,
    and the two success rates over those runs. Rows whose column is not a finite number
    (a run that failed with an error, a location never fixed) are left out of both."""
    if column not in COLUMNS:
        raise ValueError("column must be one of %s, not '%s'" % (", ".join(COLUMNS), column))
    for name, res in (("variant", variant), ("base", base)):
        if not isinstance(res, dict) or not isinstance(res.get("rows"), list):
            raise ValueError("the %s is not an rfseek-montecarlo result (no 'rows')" % name)
    base_rows = {}
    for r in base["rows"]:
        base_rows[_group(r) + (r.get("seed"),)] = r
    groups = {}
    for r in variant["rows"]:
        b = base_rows.get(_group(r) + (r.get("seed"),))
        if b is None:
            continue
        va, vb = _value(r, column), _value(b, column)
        if va is None or vb is None:
            continue
        groups.setdefault(_group(r), []).append((va, vb, bool(r.get("success")),
                                                 bool(b.get("success"))))
    if not groups:
        raise ValueError("the two results share no seed with a value of '%s' for the same "
                         "strategy, preset and sweep value" % column)
    out = []
    for key in sorted(groups):
        va, vb, sa, sb = zip(*groups[key])
        d = [a - b for a, b in zip(va, vb)]
        n = len(d)
        out.append({
            "strategy": key[0], "preset": key[1], "sweep_value": key[2], "n": n,
            "mean_variant": statistics.fmean(va), "mean_base": statistics.fmean(vb),
            "diff": statistics.fmean(d),
            "se": statistics.stdev(d) / math.sqrt(n) if n >= 2 else None,
            "changed": sum(1 for x in d if x != 0.0),
            "success_variant": sum(sa) / n, "success_base": sum(sb) / n,
        })
    return out


def paired_table(rows, column="ratio"):
    """The rows of paired() as a Markdown table: the difference with its standard error
    and a 95 % interval (+-1.96 standard errors: the normal approximation, for tens of
    pairs or more)."""
    digits = 5 if column in ("ratio", "straight_ratio") else 2
    f = "%%.%df" % digits
    lines = ["| strategy | preset | sweep | pairs | base | variant | variant - base (+- se) "
             "| 95 % interval | changed | success base / variant |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        if r["se"] is None:
            diff, interval = (f % r["diff"]) + " (one pair)", "—"
        else:
            diff = ("%+" + f[1:] + " (+- " + f + ")") % (r["diff"], r["se"])
            interval = ("[" + f + ", " + f + "]") % (r["diff"] - 1.96 * r["se"],
                                                     r["diff"] + 1.96 * r["se"])
        lines.append("| %s | %s | %s | %d | %s | %s | %s | %s | %d | %.1f / %.1f %% |" % (
            r["strategy"], r["preset"] or "—", r["sweep_value"] or "—", r["n"],
            f % r["mean_base"], f % r["mean_variant"], diff, interval, r["changed"],
            100 * r["success_base"], 100 * r["success_variant"]))
    return "\n".join(lines)
