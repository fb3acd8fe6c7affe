#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""help() is useful: every public method, property and constructor of the C++ bindings
carries a docstring beyond its signature, and the Python blocks and helpers document
themselves."""

import inspect
import re

from gnuradio import gr_unittest
from gnuradio import rfseek
from gnuradio.rfseek import rfseek_python


def prose(doc, name):
    """The docstring's text without pybind11's signature lines."""
    lines = [l.strip() for l in (doc or "").splitlines() if l.strip()]
    return [l for l in lines
            if not l.startswith(name + "(") and l != "Overloaded function."
            and not re.match(r"\d+\. " + re.escape(name) + r"\(", l)]


class qa_docstrings(gr_unittest.TestCase):

    def test_every_binding_member_is_documented(self):
        undocumented = []
        classes = [c for c in vars(rfseek_python).values() if inspect.isclass(c)]
        self.assertGreater(len(classes), 20)
        for cls in classes:
            self.assertTrue(prose(cls.__doc__, cls.__name__) or cls.__doc__,
                            cls.__name__ + " has no class docstring")
            for attr, v in vars(cls).items():
                if attr.startswith("_") and attr != "__init__":
                    continue
                if not prose(getattr(v, "__doc__", None), attr):
                    undocumented.append("%s.%s" % (cls.__name__, attr))
        self.assertEqual(undocumented, [], "without a docstring")

    def test_help_names_the_units_and_errors(self):
        # Spot checks that the text is the member's own, not a placeholder.
        self.assertIn("f_d,max", rfseek.scenario.max_doppler_hz.__doc__)
        self.assertIn("ValueError", rfseek.world.advance.__doc__)
        self.assertIn("Hz", rfseek.measurement.freq_hz.__doc__)
        self.assertIn("window_len", rfseek.tone_estimator.__init__.__doc__)

    def test_python_blocks_document_themselves(self):
        for obj in (rfseek.vehicle_bridge, rfseek.sigmf_recorder, rfseek.replay_source,
                    rfseek.loopback_vehicle):
            self.assertTrue(obj.__doc__ and len(obj.__doc__.strip()) > 40, obj)


if __name__ == "__main__":
    gr_unittest.run(qa_docstrings)
