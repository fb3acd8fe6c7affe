#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""scripts/check_docs.py on small synthetic trees: a good tree passes, and each kind of
fault (a page too long, a link that holds in the source tree but not installed, a block
missing from a list) gives one line naming it."""

import importlib.util
import os
import tempfile

from gnuradio import gr_unittest

SOURCE = os.environ.get("RFSEEK_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
spec = importlib.util.spec_from_file_location(
    "check_docs", os.path.join(SOURCE, "scripts", "check_docs.py"))
check_docs = importlib.util.module_from_spec(spec)
spec.loader.exec_module(check_docs)

CMAKE = """project(x)
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
"""
README = "# x\n\n| block |\n| --- |\n| `alpha` |\n\n[map](docs/index.md#pages)\n"
INDEX = "# Map\n\n## Pages\n\n[README](../README.md), [blocks](blocks.md), " \
        "[a note](notes/history.md)\n"
BLOCKS = "# Blocks\n\n## alpha\n\nIt does things.\n"
NOTE = "# History\n\nBack to the [map](../index.md).\n"
MANIFEST = "title: x\n---\nBlocks: `alpha`.\n"


class qa_check_docs(gr_unittest.TestCase):

    def tree(self, over=None):
        """A small module tree; `over` replaces files by relative path."""
        tmp = tempfile.TemporaryDirectory(prefix="check_docs_")
        self.addCleanup(tmp.cleanup)
        root = tmp.name
        files = {"CMakeLists.txt": CMAKE, "README.md": README, "MANIFEST.md": MANIFEST,
                 "docs/index.md": INDEX, "docs/blocks.md": BLOCKS,
                 "docs/notes/history.md": NOTE,
                 "grc/x_alpha.block.yml": "id: rfseek_alpha\nlabel: Alpha\n"}
        files.update(over or {})
        for rel, text in files.items():
            path = os.path.join(root, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        return root

    def test_good_tree_passes(self):
        root = self.tree()
        self.assertEqual(check_docs.check(root), [])
        inst = check_docs.installed_docs(root)
        self.assertEqual(inst["README.md"], "README.md")
        self.assertEqual(inst["docs/notes/history.md"], "docs/notes/history.md")

    def test_sizes(self):
        root = self.tree({"README.md": README + "x\n" * 150,
                          "docs/notes/history.md": NOTE + "x\n" * 1000})
        bad = check_docs.check(root)
        self.assertEqual(len(bad), 1, bad)
        self.assertIn("README.md: 157 lines", bad[0])
        root = self.tree({"docs/blocks.md": BLOCKS + "x\n" * 400})
        bad = check_docs.check(root)
        self.assertEqual(len(bad), 1, bad)
        self.assertIn("docs/blocks.md: 405 lines", bad[0])

    def test_flat_install_breaks_links(self):
        """docs/ installed flat beside README: README's docs/... and index's ../README.md
        resolve in the source tree only."""
        root = self.tree({"CMakeLists.txt": CMAKE.replace("${CMAKE_INSTALL_DOCDIR}/docs",
                                                        "${CMAKE_INSTALL_DOCDIR}")})
        bad = check_docs.check(root)
        self.assertEqual(len(bad), 2, bad)
        self.assertTrue(bad[0].startswith("README.md:7: docs/index.md#pages (not in the "
                                          "installed docs"), bad)
        self.assertIn("docs/index.md:5: ../README.md (outside the installed doc", bad[1])

    def test_uninstalled_page_and_bad_links(self):
        root = self.tree({"CMakeLists.txt": "project(x)\n"})
        bad = check_docs.check(root)
        self.assertEqual(len([b for b in bad if "not installed" in b]), 4, bad)
        root = self.tree({"docs/blocks.md": BLOCKS + "[a](index.md#nowhere) "
                          "[b](gone.md) [c](https://example.org)\n"})
        bad = check_docs.check(root)
        self.assertEqual(len(bad), 3, bad)
        self.assertIn("(no such heading)", bad[0])
        self.assertIn("(no such file)", bad[1])
        self.assertIn("(points outside the repository)", bad[2])

    def test_block_lists(self):
        root = self.tree({"grc/x_beta.block.yml": "id: rfseek_beta\n"})
        bad = check_docs.check(root)
        self.assertEqual(bad, [
            "docs/blocks.md: block beta has no section (a heading naming it)",
            "README.md: block beta is not listed (as `beta`)",
            "MANIFEST.md: block beta is not listed (as `beta`)"])

    def test_every_example_is_pictured(self):
        root = self.tree({"examples/seek.grc": "options: {}\n"})
        self.assertEqual(check_docs.check(root), [
            "docs/examples.md: example seek is not pictured (figures/flowgraph_seek.png, "
            "scripts/draw_flowgraphs.py)"])
        page = "# Examples\n\n![seek](figures/flowgraph_seek.png)\n"
        root = self.tree({"examples/seek.grc": "options: {}\n", "docs/examples.md": page,
                          "docs/figures/flowgraph_seek.png": "png"})
        self.assertEqual(check_docs.check(root), [])


if __name__ == "__main__":
    gr_unittest.run(qa_check_docs)
