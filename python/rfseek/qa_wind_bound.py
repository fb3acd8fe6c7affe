#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""scripts/wind_bound.py, the flights that know the bearing in the wind, against closed
forms: the pursuit's conservation law and the wind triangle's straight ground line."""

import contextlib
import importlib.util
import io
import math
import os

from gnuradio import gr_unittest
from gnuradio import rfseek

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
spec = importlib.util.spec_from_file_location(
    "wind_bound", os.path.join(SOURCE, "scripts", "wind_bound.py"))
wind_bound = importlib.util.module_from_spec(spec)
spec.loader.exec_module(wind_bound)

V = 10.0


def windy_world(wind, to_rad, seed=3):
    """The reference world (no turn limit, no compass noise) in a steady wind of `wind`
    m/s blowing toward `to_rad`, without gusts."""
    sc = rfseek.scenario()
    sc.set("seed", str(seed))
    sc.set("heading_noise_rad", "0")
    sc.set("wind_speed_mps", repr(wind))
    sc.set("wind_to_rad", repr(to_rad))
    return sc


class qa_wind_bound(gr_unittest.TestCase):

    def test_calm_air_both_flights_are_the_straight_line(self):
        sc = windy_world(0.0, 0.0)
        for mode in wind_bound.MODES:
            self.assertAlmostEqual(wind_bound.flight_ratio(sc, mode), 1.0, delta=2e-4)

    def test_the_pursuit_obeys_its_conservation_law(self):
        # Flying at the emitter (p: position from it, r = |p|) in a steady wind w,
        # p' = -v p / r + w, so d/dt (v r + w . p) = -(v^2 - w^2): the air distance to
        # any end state is v (v r0 + w . p0 - v r1 - w . p1) / (v^2 - w^2), whatever
        # the wind's direction (the classic boat aimed at a point across a current).
        for wind, to in ((6.0, 0.3), (6.0, 2.0), (7.0, -1.4), (4.0, math.pi)):
            sc = windy_world(wind, to)
            w0 = rfseek.world(sc)
            wx, wy = w0.wind_east_mps, w0.wind_north_mps
            start = V * math.hypot(w0.x_m, w0.y_m) + wx * w0.x_m + wy * w0.y_m
            w = wind_bound.fly(sc, "pursuit")
            self.assertTrue(w.arrived)
            end = V * math.hypot(w.x_m, w.y_m) + wx * w.x_m + wy * w.y_m
            expect = V * (start - end) / (V * V - wind * wind)
            self.assertAlmostEqual(w.distance_flown_m, expect, delta=2e-3 * expect,
                                   msg=(wind, to))

    def test_the_wind_triangle_flies_the_straight_ground_line(self):
        # Across, quartering or along the line of sight: the ground track is straight,
        # so the air distance is the straight line's; into a pure head- or tailwind
        # there is no crab and the pursuit is the same flight.
        for to in (0.3, 2.0, -1.4):
            sc = windy_world(6.0, to)
            triangle = wind_bound.flight_ratio(sc, "triangle")
            self.assertAlmostEqual(triangle, 1.0, delta=2e-3, msg=to)
            self.assertGreater(wind_bound.flight_ratio(sc, "pursuit"), triangle + 2e-3,
                               msg=to)
        sc = windy_world(6.0, 0.0)
        bearing = rfseek.world(sc).bearing_to_emitter_rad
        for to in (bearing, bearing + math.pi):
            sc = windy_world(6.0, to)
            a = wind_bound.flight_ratio(sc, "pursuit")
            self.assertAlmostEqual(a, wind_bound.flight_ratio(sc, "triangle"), delta=1e-9)
            self.assertAlmostEqual(a, 1.0, delta=2e-3)

    def test_the_script_prints_a_row_per_wind_and_names_bad_fields(self):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = wind_bound.main(["--winds", "0,7", "--runs", "4"])
        self.assertEqual(rc, 0)
        rows = [l.split("|") for l in out.getvalue().splitlines()
                if l.startswith("| 0") or l.startswith("| 7")]
        self.assertEqual(len(rows), 2)
        # In 7 m/s the pursuit pays for its curve, the triangle does not.
        pursuit7 = float(rows[1][2].split("/")[0])
        triangle7 = float(rows[1][3].split("/")[0])
        self.assertGreater(pursuit7, triangle7 + 0.02)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            self.assertEqual(wind_bound.main(["--set", "bogus=1", "--runs", "1"]), 2)
        self.assertIn("bogus", err.getvalue())


if __name__ == "__main__":
    gr_unittest.run(qa_wind_bound)
