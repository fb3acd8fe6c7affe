#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""scripts/turn_bound.py, the floor that turn limits set on the distance ratio, against
the closed form of a turn onto the emitter at the limit followed by a straight line."""

import importlib.util
import math
import os

from gnuradio import gr_unittest
from gnuradio import rfseek

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
spec = importlib.util.spec_from_file_location(
    "turn_bound", os.path.join(SOURCE, "scripts", "turn_bound.py"))
turn_bound = importlib.util.module_from_spec(spec)
spec.loader.exec_module(turn_bound)


def scenario(rel, rate=0.0):
    """The reference world, its emitter `rel` rad off the start heading (+: left)."""
    sc = rfseek.scenario()
    sc.set("seed", "3")
    sc.set("start_angle_rad", "0")
    sc.set("turn_rate_rad_per_s", repr(rate))
    bearing = rfseek.world(sc).bearing_to_emitter_rad
    sc.set("start_heading_rad", repr(rfseek.world.wrap(bearing - rel)))
    return sc


class qa_turn_bound(gr_unittest.TestCase):

    def test_without_a_turn_limit_the_floor_is_the_straight_line(self):
        for rel in (0.0, 1.0, math.pi):
            self.assertAlmostEqual(turn_bound.flight_ratio(scenario(rel)), 1.0, delta=2e-4)

    def test_a_turn_at_the_limit_costs_r_times_phi_less_sin_phi(self):
        # Far from the emitter (R << d) turning phi onto it at radius R = v / omega and
        # flying straight costs R (phi - sin phi) over the straight line, to first order
        # in R / d: 0.571 R at 90 deg, pi R behind.
        omega = math.radians(10.0)
        r = 10.0 / omega
        for phi in (math.pi / 2, -math.pi / 2, 0.999 * math.pi):
            sc = scenario(phi, omega)
            extra = (turn_bound.flight_ratio(sc) - 1.0) * sc.shortest_path_m
            expect = r * (abs(phi) - math.sin(abs(phi)))
            self.assertAlmostEqual(extra, expect, delta=2.0 + 0.02 * expect, msg=phi)

    def test_the_script_prints_a_row_per_speed_and_names_bad_fields(self):
        import contextlib
        import io
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = turn_bound.main(["--preset", "fixedwing15", "--speeds", "10,25",
                                  "--runs", "3"])
        self.assertEqual(rc, 0)
        rows = [l for l in out.getvalue().splitlines() if l.startswith("| 1")
                or l.startswith("| 2")]
        self.assertEqual(len(rows), 2)
        # Slower turns at 25 m/s (10.4 deg/s, radius 138 m) cost more than at 10 m/s.
        self.assertGreater(float(rows[1].split("|")[2]), float(rows[0].split("|")[2]))
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            self.assertEqual(turn_bound.main(["--set", "bogus=1", "--runs", "1"]), 2)
        self.assertIn("bogus", err.getvalue())

    def test_a_speed_where_no_run_arrives_reads_as_a_dash(self):
        # Every run capped: no mean to print, the row says "-" and counts them all.
        import contextlib
        import io
        import unittest.mock
        out = io.StringIO()
        with unittest.mock.patch.object(turn_bound, "flight_ratio",
                                        lambda sc: float("nan")), \
                contextlib.redirect_stdout(out):
            self.assertEqual(turn_bound.main(["--speeds", "10", "--runs", "2"]), 0)
        self.assertIn("| 10 | - | - | 2 |", out.getvalue())
        self.assertNotIn("nan", out.getvalue())


if __name__ == "__main__":
    gr_unittest.run(qa_turn_bound)
