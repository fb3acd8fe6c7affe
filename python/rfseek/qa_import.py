#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""`from gnuradio import rfseek` loads no GUI toolkit: Qt and matplotlib come with
seek_view or a plot, when first used; every block is still reachable by its name."""

import subprocess
import sys

from gnuradio import gr_unittest


def loaded_after(statement):
    """The GUI modules loaded by `statement` in a fresh interpreter."""
    code = "import sys\n%s\nprint(sorted(m for m in ('PyQt5', 'matplotlib') " \
           "if m in sys.modules))" % statement
    out = subprocess.run([sys.executable, "-c", code], check=True,
                         stdout=subprocess.PIPE, text=True).stdout
    return out.strip().splitlines()[-1]


class qa_import(gr_unittest.TestCase):

    def test_the_module_loads_no_gui_toolkit(self):
        self.assertEqual(loaded_after("from gnuradio import rfseek"), "[]")
        # Blocks that need neither stay so when used.
        self.assertEqual(loaded_after(
            "from gnuradio import rfseek\n"
            "rfseek.radio_source, rfseek.sigmf_recorder, rfseek.pulsed_beacon"), "[]")

    def test_seek_view_brings_its_toolkit_when_used(self):
        self.assertEqual(loaded_after("from gnuradio import rfseek\nrfseek.seek_view"),
                         "['PyQt5', 'matplotlib']")

    def test_every_lazy_name_is_the_submodules_own(self):
        from gnuradio import rfseek
        from gnuradio.rfseek import radios, sigmf
        import gnuradio.rfseek.pulsed_beacon  # noqa: F401  (the submodule of that name)
        pulsed_beacon = sys.modules["gnuradio.rfseek.pulsed_beacon"]
        self.assertIs(rfseek.radio_source, radios.radio_source)
        self.assertIs(rfseek.RADIOS, radios.RADIOS)
        self.assertIs(rfseek.replay_source, sigmf.replay_source)
        self.assertIs(rfseek.pulsed_beacon, pulsed_beacon.pulsed_beacon)
        for name in ("seek_view", "sim_radio", "rx_plan", "radio_for", "radio_rx_chain"):
            self.assertIn(name, dir(rfseek))
        with self.assertRaises(AttributeError):
            rfseek.no_such_block

    def test_a_block_keeps_its_name_when_its_submodule_is_imported(self):
        # Python sets a package's attribute to a submodule imported by its full name;
        # seek_view and pulsed_beacon share their submodules' names.
        out = subprocess.run([sys.executable, "-c", "\n".join([
            "import gnuradio.rfseek.pulsed_beacon",
            "from gnuradio.rfseek.seek_view import seek_view",
            "from gnuradio import rfseek",
            "print(isinstance(rfseek.pulsed_beacon, type), rfseek.seek_view is seek_view)"])],
            check=True, stdout=subprocess.PIPE, text=True).stdout
        self.assertEqual(out.strip().splitlines()[-1], "True True")


if __name__ == "__main__":
    gr_unittest.run(qa_import)
