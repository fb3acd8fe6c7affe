#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Checks the user docs (README.md, CHANGELOG.md, MANIFEST.md, docs/*.md): every link
points inside the repository, to a file that exists and, with a #fragment, to a heading
of that file (GitHub's anchors: lower case, punctuation dropped, spaces to hyphens).
Exits 1 listing each bad link.

  scripts/check_docs.py [SOURCE_DIR]
"""

import glob
import os
import re
import sys

LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$")


def anchor(title):
    """GitHub's anchor of a heading."""
    t = title.strip().lower()
    t = re.sub(r"[^\w\- ]", "", t)
    return t.replace(" ", "-")


def headings(path):
    out, fenced = set(), False
    counts = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("```"):
                fenced = not fenced
                continue
            m = None if fenced else HEADING.match(line)
            if m:
                a = anchor(m.group(1))
                n = counts.get(a, 0)
                counts[a] = n + 1
                out.add(a if n == 0 else "%s-%d" % (a, n))
    return out


def check(root):
    files = [os.path.join(root, f) for f in ("README.md", "CHANGELOG.md", "MANIFEST.md")]
    files += sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    bad = []
    for path in files:
        if not os.path.exists(path):
            continue
        fenced = False
        with open(path, encoding="utf-8") as f:
            for no, line in enumerate(f, 1):
                if line.startswith("```"):
                    fenced = not fenced
                if fenced:
                    continue
                for m in LINK.finditer(line):
                    target = m.group(1) or m.group(2)
                    where = "%s:%d: %s" % (os.path.relpath(path, root), no, target)
                    if re.match(r"^[a-z][a-z0-9+.-]*:", target):
                        bad.append(where + " (points outside the repository)")
                        continue
                    file_part, _, frag = target.partition("#")
                    dest = (os.path.normpath(os.path.join(os.path.dirname(path), file_part))
                            if file_part else path)
                    real, top = os.path.realpath(dest), os.path.realpath(root)
                    if os.path.commonpath([real, top]) != top:
                        bad.append(where + " (outside the repository)")
                    elif not os.path.exists(dest):
                        bad.append(where + " (no such file)")
                    elif frag and dest.endswith(".md") and frag not in headings(dest):
                        bad.append(where + " (no such heading)")
    return bad


def main(argv):
    root = os.path.abspath(argv[0] if argv else
                           os.path.join(os.path.dirname(__file__), ".."))
    bad = check(root)
    for b in bad:
        print("check_docs: " + b, file=sys.stderr)
    if not bad:
        print("check_docs: every link resolves inside the repository")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
