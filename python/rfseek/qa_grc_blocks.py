#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""The GRC block files (grc/*.block.yml) as a user meets them: the controller's first tab
holds what a flight needs (at most 12 parameters); no two parameters of a block share a
label; every option has its own label; every numeric parameter is checked by an assert;
and, through GRC's own platform loading the source blocks, every block is valid at its
defaults while a value out of range fails an assert that names that parameter (a
negative controller speed fails on the speed alone). The example flowgraphs type each
physical quantity (airspeed, carrier, slot period, sample rate) once: blocks that share
one take the same variable."""

import glob
import os
import re
import unittest

import yaml
from gnuradio import gr

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
GRC = os.path.abspath(os.path.join(SOURCE, "grc"))
NUMERIC = ("real", "int", "float")
# The parameters of rfseek blocks that are one physical quantity of a flight; "0" (the
# link's "use the controller's") is not a value.
QUANTITIES = {
    "airspeed": ("speed", "airspeed_mps", "turn_speed_mps"),
    "carrier": ("carrier", "center_freq"),
    "slot period": ("slot_period",),
    "sample rate": ("samp_rate",),
}


def load_blocks():
    blocks = {}
    for path in sorted(glob.glob(os.path.join(GRC, "*.block.yml"))):
        with open(path) as f:
            d = yaml.safe_load(f)
        blocks[d["id"]] = d
    return blocks


class qa_grc_blocks(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.blocks = load_blocks()

    def test_controller_first_tab(self):
        d = self.blocks["rfseek_seeking_controller"]
        first = [p["id"] for p in d["parameters"] if p.get("category", "General") == "General"]
        self.assertLessEqual(len(first), 12, first)
        for pid in ("strategy", "speed", "carrier", "slot_period", "arrival",
                    "wind_forecast_east", "wind_forecast_north"):
            self.assertIn(pid, first)
        doc = d["documentation"]
        self.assertLessEqual(len(doc.splitlines()), 30)
        for cb in d["templates"]["callbacks"]:
            self.assertIn(cb.split("(")[0], doc)

    def test_labels_and_option_labels(self):
        for bid, d in self.blocks.items():
            labels = [p.get("label", p["id"]).strip().lower() for p in d.get("parameters", [])]
            dup = sorted({x for x in labels if labels.count(x) > 1})
            self.assertEqual(dup, [], bid)
            for p in d.get("parameters", []):
                if "options" in p and "option_labels" in p:
                    # A comma in an unquoted flow list splits a label in two.
                    self.assertEqual(len(p["option_labels"]), len(p["options"]),
                                     (bid, p["id"]))

    def test_numeric_parameters_have_asserts(self):
        for bid, d in self.blocks.items():
            asserts = d.get("asserts") or []
            named = set(re.findall(r"[A-Za-z_]\w*", " ".join(asserts)))
            ids = {p["id"] for p in d.get("parameters", [])}
            unchecked = [p["id"] for p in d.get("parameters", [])
                         if p.get("dtype") in NUMERIC and p["id"] not in named]
            self.assertEqual(unchecked, [], bid)
            for a in asserts:
                self.assertTrue(ids & set(re.findall(r"[A-Za-z_]\w*", a)), (bid, a))

    def test_examples_type_each_quantity_once(self):
        examples = sorted(glob.glob(os.path.join(SOURCE, "examples", "*.grc")))
        self.assertGreaterEqual(len(examples), 9)
        shared = 0
        for path in examples:
            with open(path) as f:
                fg = yaml.safe_load(f)
            for quantity, keys in QUANTITIES.items():
                uses = [(b["name"], str(b["parameters"][k])) for b in fg["blocks"]
                        if b["id"].startswith("rfseek_") for k in keys
                        if k in b["parameters"] and str(b["parameters"][k]) != "0"]
                if len(uses) < 2:
                    continue
                shared += 1
                values = {v for _, v in uses}
                name = os.path.basename(path)
                self.assertEqual(len(values), 1, "%s: %s set apart: %s"
                                 % (name, quantity, uses))
                value = values.pop()
                self.assertIsNone(re.fullmatch(r"[-+0-9.eE]+", value),
                                  "%s: %s typed as a literal in %d blocks"
                                  % (name, quantity, len(uses)))
        self.assertGreater(shared, 10)  # the examples do share quantities

    def test_grc_validates_defaults_and_names_bad_values(self):
        from gnuradio.grc.core.platform import Platform
        platform = Platform(name="qa_grc_blocks", prefs=gr.prefs(), version=gr.version(),
                            version_parts=(gr.major_version(), gr.api_version(),
                                           gr.minor_version()))
        core = os.path.join(gr.prefix(), "share", "gnuradio", "grc", "blocks")
        platform.build_library([core, GRC])
        fg = platform.make_flow_graph()
        var = fg.new_block("variable")
        var.params["id"].set_value("samp_rate")
        var.params["value"].set_value("100e3")
        blocks = {}
        for bid in self.blocks:
            self.assertTrue(os.path.abspath(platform.blocks[bid].loaded_from).startswith(GRC))
            blocks[bid] = fg.new_block(bid)

        def failed(block):
            fg.rewrite()
            fg.validate()
            return [e for e in block.get_error_messages() if e.startswith("Assertion")]

        for bid, block in blocks.items():
            self.assertEqual(failed(block), [], bid)
        bad = [("rfseek_seeking_controller", "speed", "-10"),
               ("rfseek_seeking_controller", "carrier", "0"),
               ("rfseek_seeking_controller", "slot_period", "0"),
               ("rfseek_seeking_controller", "m_slots", "0"),
               ("rfseek_channel_source", "speed", "-10"),
               ("rfseek_channel_source", "distance", "0"),
               ("rfseek_channel_source", "slot_period", "0.001"),
               ("rfseek_radio_source", "out_rate", "0"),
               ("rfseek_sigmf_recorder", "samp_rate", "0"),
               ("rfseek_vehicle_bridge", "local_port", "70000"),
               ("rfseek_seek_view", "update_ms", "1")]
        for bid, pid, value in bad:
            param = blocks[bid].params[pid]
            default = param.get_value()
            param.set_value(value)
            errors = failed(blocks[bid])
            self.assertTrue(errors, (bid, pid, value))
            for e in errors:
                self.assertIn(pid, e, (bid, pid, value))
            param.set_value(default)
        blocks["rfseek_seeking_controller"].params["speed"].set_value("-10")
        self.assertEqual(failed(blocks["rfseek_seeking_controller"]),
                         ['Assertion "speed > 0" failed.'])


if __name__ == "__main__":
    unittest.main()
