#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""The blocks' GRC C++ templates: examples/seek_sim_cpp.grc is generated as C++ by grcc,
built by the CMakeLists.txt GRC writes (no flags: find_package finds the module installed
from the build tree) and run; it must end its flight on the
slot the core simulation ends on, with the scenario and seeker its Python twin (the same
.grc generated as Python) builds. A variant sets every optional field the C++ templates
handle (start angle and heading, CFO, overrides, initial heading, arrival self), and
another eq. 4 as printed."""

import os
import re
import shutil
import subprocess
import sys
import tempfile
import importlib.util

import yaml
from gnuradio import gr_unittest
from gnuradio import rfseek

# GRC's compiler: the one CMake found, else the one on PATH.
GRCC = os.environ.get("RFSEEK_GRCC") or shutil.which("grcc") or "grcc"

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
BUILD = os.environ.get("RFSEEK_BUILD_DIR", os.path.join(SOURCE, "build"))
# The module installed from the build tree (ctest's install_staged).
STAGE = os.environ.get("RFSEEK_STAGE", os.path.join(BUILD, "stage"))


class qa_grc_cpp(gr_unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="rfseek_grc_cpp_")
        with open(os.path.join(SOURCE, "examples", "seek_sim_cpp.grc")) as f:
            self.grc = yaml.safe_load(f)

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def block(self, grc, name):
        return next(b for b in grc["blocks"] if b["name"] == name)

    def grcc(self, grc, language, name):
        g = yaml.safe_load(yaml.safe_dump(grc))
        g["options"]["parameters"]["output_language"] = language
        g["options"]["parameters"]["id"] = name
        path = os.path.join(self.tmp, name + ".grc")
        with open(path, "w") as f:
            yaml.safe_dump(g, f)
        out = os.path.join(self.tmp, "out")
        p = subprocess.run([sys.executable, GRCC, "-o", out, path],
                           capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        return out

    def core_slots(self, grc, name):
        # The same flowgraph generated as Python: its blocks' configurations, flown by
        # the core simulation.
        out = self.grcc(grc, "python", name + "_py")
        spec = importlib.util.spec_from_file_location(
            name + "_py", os.path.join(out, name + "_py.py"))
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        tb = getattr(mod, name + "_py")()
        sc, cfg = tb.channel.config(), tb.controller.config()
        del tb
        return rfseek.simulation(sc, cfg).run(False).summary, cfg

    def cpp_end(self, grc, name):
        # GRC's own CMakeLists.txt, with no flags: the module is found by
        # find_package(gnuradio-rfseek) in the installed (staged) tree.
        out = os.path.join(self.grcc(grc, "cpp", name), name)
        build = os.path.join(out, "build")
        env = dict(os.environ)
        env["CMAKE_PREFIX_PATH"] = STAGE
        if os.environ.get("RFSEEK_SANITIZE"):
            # Sanitizer build: the flowgraph is instrumented like the library; CMake and
            # the compiler run without the ASan runtime the Python QA preloads.
            env["CXXFLAGS"] = env["LDFLAGS"] = "-fsanitize=address,undefined"
            env.pop("LD_PRELOAD", None)
        for cmd in (["cmake", "-S", out, "-B", build], ["cmake", "--build", build]):
            p = subprocess.run(cmd, capture_output=True, text=True, env=env)
            self.assertEqual(p.returncode, 0, (p.stdout + p.stderr)[-4000:])
        exe = os.path.join(build, name)
        p = subprocess.run([exe], capture_output=True, text=True, env=env, timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr[-4000:])
        m = re.search(r"(arrived|flight cap reached|declared its mission done) at slot (\d+)",
                      p.stdout + p.stderr)
        self.assertIsNotNone(m, p.stderr[-4000:])
        return m.group(1), int(m.group(2))

    def test_example_flies_the_core_trajectory(self):
        core, cfg = self.core_slots(self.grc, "seek_sim_cpp")
        self.assertEqual(cfg.strategy, "paper")
        self.assertTrue(core.success)
        how, slot = self.cpp_end(self.grc, "seek_sim_cpp")
        self.assertEqual(how, "arrived")
        self.assertEqual(slot, core.slots)

    def test_every_optional_field_reaches_the_cpp_flowgraph(self):
        g = yaml.safe_load(yaml.safe_dump(self.grc))
        self.block(g, "strategy")["parameters"]["value"] = '"paper_no_circle"'
        self.block(g, "arrival")["parameters"]["value"] = '"self"'
        self.block(g, "seed")["parameters"]["value"] = "7"
        ch = self.block(g, "channel")["parameters"]
        ch.update({"start_angle_deg": "40", "start_heading_deg": "-120", "cfo_hz": "750.0",
                   "cfo_drift": "0.2", "distance": "2000", "self_arrival": "arrival == 'self'",
                   "overrides": "dict(altitude_m=100, wind_speed_mps=4, wind_gust_mps=1, "
                                "compass_bias_rad=0.05, compass_noise_rad=0.03, "
                                "add_noise=True)"})
        co = self.block(g, "controller")["parameters"]
        co.update({"initial_heading_deg": "-60", "altitude": "100",
                   "arrival": "arrival == 'self'"})
        core, cfg = self.core_slots(g, "seek_sim_cpp_all")
        self.assertEqual(cfg.strategy, "paper_no_circle")
        self.assertTrue(cfg.self_arrival)
        self.assertAlmostEqual(cfg.initial_heading_rad, -60 * 3.141592653589793 / 180, 12)
        self.assertTrue(core.located)
        how, slot = self.cpp_end(g, "seek_sim_cpp_all")
        self.assertEqual(how, "declared its mission done")
        self.assertEqual(slot, core.slots)

    def test_literal_eq4_reaches_the_cpp_flowgraph(self):
        # Eq. 4 as printed flies another (longer) trajectory on the example's seed.
        g = yaml.safe_load(yaml.safe_dump(self.grc))
        self.block(g, "controller")["parameters"]["literal_eq4"] = "True"
        core, cfg = self.core_slots(g, "seek_sim_cpp_eq4")
        plain, _ = self.core_slots(self.grc, "seek_sim_cpp")
        self.assertTrue(cfg.literal_eq4)
        self.assertTrue(core.success)
        self.assertNotEqual(core.slots, plain.slots)
        how, slot = self.cpp_end(g, "seek_sim_cpp_eq4")
        self.assertEqual(how, "arrived")
        self.assertEqual(slot, core.slots)


if __name__ == "__main__":
    gr_unittest.run(qa_grc_cpp)
