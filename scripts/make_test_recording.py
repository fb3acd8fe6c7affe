#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Make the committed SigMF test vector examples/data/sim_beacons.sigmf-{data,meta}: 60
beacon slots of the reference scenario (seed 7) received in burst mode, flown in closed
loop, with the beacon tags, heading reports and the live measurements.

    scripts/make_test_recording.py [BASE]     (run from a build tree or an install)

Without BASE it rewrites the committed recording in the source tree.
"""
import argparse
import os
import sys

from gnuradio import gr, rfseek
from gnuradio.rfseek import flowgraphs
from gnuradio.rfseek.sigmf import sigmf_recorder


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(prog="make_test_recording.py", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("base", nargs="?", default=None,
                   help="write BASE.sigmf-data and BASE.sigmf-meta (default: the committed "
                        "examples/data/sim_beacons)")
    base = p.parse_args(argv).base or os.path.join(here, "..", "examples", "data",
                                                   "sim_beacons")
    sc = rfseek.scenario(seed=7)
    sc.flight_cap_m = 60 * sc.speed_mps * sc.slot_period_s  # 60 slots
    tb = flowgraphs.closed_loop(sc, "paper")
    est = {"window": "rectangular", "interpolator": "parabolic", "window_len": sc.window_len,
           "fft_len": sc.fft_len, "alignment": "tag"}
    rec = sigmf_recorder(base, sc.samp_rate_hz, sc.carrier_hz,
                         "gr-rfseek simulator: reference scenario, seed 7, 60 slots, burst "
                         "mode, closed loop (strategy paper)", est)
    nav = flowgraphs.state_to_nav()
    tb.connect(tb.source, rec)
    tb.msg_connect(tb.estimator, "meas", rec, "meas")
    tb.msg_connect(tb.source, "state", nav, "state")
    tb.msg_connect(nav, "nav", rec, "nav")
    tb.run()
    print("wrote %s.sigmf-data and %s.sigmf-meta (%d annotations)" % (
        base, base, len(rec.annotations)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
