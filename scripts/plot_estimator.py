#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Plot rfseek-estimator-study's CSV: RMSE versus per-sample SNR against the Cramer-Rao
bound for each interpolator, and the outlier rate near threshold.

    rfseek-estimator-study --out est.csv && scripts/plot_estimator.py est.csv est.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) == 2 and argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        with open(argv[1]) as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        print("plot_estimator: error: %s: %s" % (argv[1], e.strerror), file=sys.stderr)
        return 2
    if not rows:
        print("plot_estimator: no rows in %s" % argv[1], file=sys.stderr)
        return 1
    need = {"interpolator", "window", "snr_db", "crb_hz", "rmse_hz", "outlier_rate"}
    if not need <= set(rows[0]):
        print("plot_estimator: error: %s lacks the columns %s: not an "
              "rfseek-estimator-study CSV" % (argv[1], ", ".join(sorted(need - set(rows[0])))),
              file=sys.stderr)
        return 2
    interps = sorted({r["interpolator"] for r in rows})
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 8), sharex=True,
                                   gridspec_kw={"height_ratios": [3, 1]})
    crb = sorted({(float(r["snr_db"]), float(r["crb_hz"])) for r in rows})
    ax1.semilogy([c[0] for c in crb], [c[1] for c in crb], "k--", label="Cramer-Rao bound")
    for name in interps:
        rs = [r for r in rows if r["interpolator"] == name]
        snr = [float(r["snr_db"]) for r in rs]
        ax1.semilogy(snr, [float(r["rmse_hz"]) for r in rs], "o-", ms=3, label=name)
        ax2.semilogy(snr, [max(float(r["outlier_rate"]), 1e-4) for r in rs], "o-", ms=3,
                     label=name)
    ax1.set_ylabel("RMSE of inliers (Hz)")
    ax1.set_title("Tone frequency estimation, N = 1000, Ts = 10 us, N_FFT = 4096 (%s)"
                  % rows[0]["window"], fontsize=10)
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend()
    ax2.set_xlabel("per-sample SNR (dB)")
    ax2.set_ylabel("outliers (|err| > 100 Hz)")
    ax2.set_ylim(8e-5, 1.2)
    ax2.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(argv[2], dpi=110)
    print("wrote %s" % argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
