#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Man pages made from the programs' own --help (scripts/make_manpage.py, at build
time): roff-safe, named after their program, one per installed program."""

import os
import subprocess
import sys
import tempfile

from gnuradio import gr_unittest

SOURCE = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))
MAKE = os.path.join(SOURCE, "scripts", "make_manpage.py")
BUILD = os.environ.get("RFSEEK_BUILD_DIR", os.getcwd())
PROGRAMS = ("rfseek-sim", "rfseek-live", "rfseek-sitl", "rfseek-montecarlo",
            "rfseek-plot-montecarlo", "rfseek-soak", "rfseek-bench-acquire",
            "rfseek-bench-faults", "rfseek-bench-import", "rfseek-bench-world", "rfseek-bench-estimator",
            "rfseek-bench-loop", "rfseek-estimator-study")


def make(name, program_text):
    """make_manpage.py on a program printing `program_text` for --help: (exit, page)."""
    d = tempfile.mkdtemp(prefix="rfseek_man_")
    prog = os.path.join(d, name)
    with open(prog, "w") as f:
        f.write("import sys\nsys.stdout.write(%r)\n" % program_text)
    out = os.path.join(d, name + ".1")
    p = subprocess.run([sys.executable, MAKE, name, "9.9", out, "--", sys.executable, prog],
                       stderr=subprocess.PIPE, text=True)
    return p.returncode, (open(out).read() if os.path.exists(out) else None), p.stderr


class qa_manpages(gr_unittest.TestCase):

    def test_help_text_becomes_literal_roff(self):
        rc, page, _ = make("demo", "usage: /x/y/demo [-h] [--gain DB]\n\ndemo: tunes a "
                           "radio. It does more.\n.not a request\n'nor this\nback\\slash\n")
        self.assertEqual(rc, 0)
        lines = page.splitlines()
        self.assertEqual(lines[0], '.TH DEMO 1 "" "gr-rfseek 9.9" "User Commands"')
        self.assertIn("demo \\- tunes a radio", lines)  # the summary, "demo:" dropped
        self.assertIn("usage: demo [-h] [--gain DB]", lines)  # its own path: the name
        self.assertIn("\\&.not a request", lines)
        self.assertIn("\\&'nor this", lines)
        self.assertIn("back\\eslash", lines)

    def test_a_failing_help_is_a_build_error(self):
        rc, page, err = make("broken", "")
        self.assertEqual(rc, 1)
        self.assertIsNone(page)
        self.assertIn("broken --help", err)

    def test_every_program_has_its_page(self):
        pages = os.path.join(BUILD, "apps")
        if not os.path.exists(os.path.join(pages, "rfseek-sim.1")):
            self.skipTest("no man pages in %s (RFSEEK_MANPAGES off)" % pages)
        for name in PROGRAMS:
            with open(os.path.join(pages, name + ".1")) as f:
                page = f.read()
            self.assertTrue(page.startswith(".TH %s 1 " % name.upper()), name)
            self.assertIn("\n%s \\- " % name, page)
            body = page.split("\n.nf\n", 1)[1].split("\n.fi\n", 1)[0]
            self.assertGreaterEqual(len(body.splitlines()), 3, name)  # its --help
        with open(os.path.join(pages, "rfseek-sitl.1")) as f:
            self.assertIn("--forecast", f.read())


if __name__ == "__main__":
    gr_unittest.run(qa_manpages)
