#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""Checks the docs (README.md, CHANGELOG.md, MANIFEST.md, docs/*.md, docs/notes/*.md):

- sizes: README.md at most 150 lines, every user page docs/*.md at most 400 (the notes
  in docs/notes/ are the research record, without a limit);
- links: every link points inside the repository, to a file that exists and, with a
  #fragment, to a heading of that file (GitHub's anchors: lower case, punctuation
  dropped, spaces to hyphens); and the same link resolves in the installed docs, whose
  layout is read from the top-level CMakeLists.txt's install() rules into
  ${CMAKE_INSTALL_DOCDIR} (README.md and every page under docs/, notes included, must be installed);
- block lists: every GRC block (grc/*.block.yml, its id without the `rfseek_` prefix)
  has a heading in docs/blocks.md and is named, as `name`, in README.md and MANIFEST.md.

Prints one line per failure and exits 1 when there is any.

  scripts/check_docs.py [SOURCE_DIR]
"""

import glob
import os
import re
import sys

README_MAX_LINES = 150
PAGE_MAX_LINES = 400
DOCDIR = "${CMAKE_INSTALL_DOCDIR}"
# Checked in the source tree; they need not be installed.
NOT_INSTALLED = ("MANIFEST.md", "CHANGELOG.md")

LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$")
BLOCK_ID = re.compile(r"^id:\s*(\S+)\s*$", re.M)


def anchor(title):
    """GitHub's anchor of a heading."""
    t = title.strip().lower()
    t = re.sub(r"[^\w\- ]", "", t)
    return t.replace(" ", "-")


def heading_titles(path):
    """The headings of a Markdown file, outside code fences, in order."""
    out, fenced = [], False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("```"):
                fenced = not fenced
                continue
            m = None if fenced else HEADING.match(line)
            if m:
                out.append(m.group(1))
    return out


def headings(path):
    out, counts = set(), {}
    for title in heading_titles(path):
        a = anchor(title)
        n = counts.get(a, 0)
        counts[a] = n + 1
        out.add(a if n == 0 else "%s-%d" % (a, n))
    return out


def doc_files(root):
    """Relative paths of the checked Markdown files that exist."""
    files = [f for f in ("README.md", "CHANGELOG.md", "MANIFEST.md")
             if os.path.exists(os.path.join(root, f))]
    for pattern in ("docs/*.md", "docs/notes/*.md"):
        files += sorted(os.path.relpath(p, root)
                        for p in glob.glob(os.path.join(root, pattern)))
    return files


def user_pages(root):
    return sorted(os.path.relpath(p, root) for p in glob.glob(os.path.join(root, "docs", "*.md")))


def install_calls(text):
    """The argument lists of the install() calls in CMake text (comments removed)."""
    text = re.sub(r"#[^\n]*", "", text)
    out = []
    for m in re.finditer(r"\binstall\s*\(", text):
        depth, i = 1, m.end()
        while i < len(text) and depth:
            depth += {"(": 1, ")": -1}.get(text[i], 0)
            i += 1
        out.append(text[m.end():i - 1].split())
    return out


def installed_docs(root):
    """{source path: path under the doc directory} for every file the top-level
    CMakeLists.txt installs into ${CMAKE_INSTALL_DOCDIR} (FILES and DIRECTORY rules; a
    directory with a trailing slash installs its contents, without one itself)."""
    path = os.path.join(root, "CMakeLists.txt")
    if not os.path.exists(path):
        return {}
    with open(path, encoding="utf-8") as f:
        calls = install_calls(f.read())
    out = {}
    for args in calls:
        if len(args) < 3 or args[0] not in ("FILES", "DIRECTORY") or "DESTINATION" not in args:
            continue
        dest = args[args.index("DESTINATION") + 1]
        if dest != DOCDIR and not dest.startswith(DOCDIR + "/"):
            continue
        dest = dest[len(DOCDIR):].strip("/")
        for src in args[1:args.index("DESTINATION")]:
            if args[0] == "FILES":
                out[os.path.normpath(src)] = os.path.normpath(
                    os.path.join(dest, os.path.basename(src)))
                continue
            base = src if src.endswith("/") else os.path.dirname(src.rstrip("/"))
            for d, _, names in os.walk(os.path.join(root, src)):
                for n in names:
                    rel = os.path.relpath(os.path.join(d, n), root)
                    inst = os.path.relpath(os.path.join(root, rel), os.path.join(root, base))
                    out[os.path.normpath(rel)] = os.path.normpath(os.path.join(dest, inst))
    return out


def check_sizes(root):
    bad = []
    limits = [("README.md", README_MAX_LINES)] + [(p, PAGE_MAX_LINES) for p in user_pages(root)]
    for rel, limit in limits:
        path = os.path.join(root, rel)
        if not os.path.exists(path):
            bad.append("%s: missing" % rel)
            continue
        with open(path, encoding="utf-8") as f:
            n = sum(1 for _ in f)
        if n > limit:
            bad.append("%s: %d lines, over the %d a user page may have (research record: "
                       "docs/notes/)" % (rel, n, limit))
    return bad


def check_installed_target(rel, file_part, frag, installed, root):
    """Why the link `file_part#frag` of the source file rel fails in the installed docs,
    or None."""
    if rel not in installed:
        return None
    inst = installed[rel]
    if not file_part:
        return None
    dest = os.path.normpath(os.path.join(os.path.dirname(inst), file_part))
    if dest == ".." or dest.startswith("../"):
        return "outside the installed doc directory"
    back = {v: k for k, v in installed.items()}
    if dest in back:
        src = back[dest]
        if frag and src.endswith(".md") and frag not in headings(os.path.join(root, src)):
            return "no such heading in the installed docs"
        return None
    if any(v.startswith(dest + "/") for v in back):
        return None
    return "not in the installed docs (share/doc/gr-rfseek/%s)" % dest


def check_links(root):
    installed = installed_docs(root)
    bad = ["%s: not installed into the doc directory (CMakeLists.txt install())" % rel
           for rel in doc_files(root) if rel not in installed and rel not in NOT_INSTALLED]
    top = os.path.realpath(root)
    for rel in doc_files(root):
        path = os.path.join(root, rel)
        fenced = False
        with open(path, encoding="utf-8") as f:
            for no, line in enumerate(f, 1):
                if line.startswith("```"):
                    fenced = not fenced
                if fenced:
                    continue
                for m in LINK.finditer(line):
                    target = m.group(1) or m.group(2)
                    where = "%s:%d: %s" % (rel, no, target)
                    if re.match(r"^[a-z][a-z0-9+.-]*:", target):
                        bad.append(where + " (points outside the repository)")
                        continue
                    file_part, _, frag = target.partition("#")
                    dest = (os.path.normpath(os.path.join(os.path.dirname(path), file_part))
                            if file_part else path)
                    if os.path.commonpath([os.path.realpath(dest), top]) != top:
                        bad.append(where + " (outside the repository)")
                    elif not os.path.exists(dest):
                        bad.append(where + " (no such file)")
                    elif frag and dest.endswith(".md") and frag not in headings(dest):
                        bad.append(where + " (no such heading)")
                    else:
                        why = check_installed_target(rel, file_part, frag, installed, root)
                        if why:
                            bad.append(where + " (" + why + ")")
    return bad


def block_names(root):
    """The GRC blocks' ids without the module prefix, from grc/*.block.yml."""
    names = []
    for path in sorted(glob.glob(os.path.join(root, "grc", "*.block.yml"))):
        with open(path, encoding="utf-8") as f:
            m = BLOCK_ID.search(f.read())
        if m:
            names.append(re.sub(r"^rfseek_", "", m.group(1)))
    return names


def check_blocks(root):
    bad = []
    names = block_names(root)
    blocks_md = os.path.join(root, "docs", "blocks.md")
    titles = heading_titles(blocks_md) if os.path.exists(blocks_md) else []
    for name in names:
        if not any(re.search(r"\b%s\b" % re.escape(name), t) for t in titles):
            bad.append("docs/blocks.md: block %s has no section (a heading naming it)" % name)
    for rel in ("README.md", "MANIFEST.md"):
        path = os.path.join(root, rel)
        text = ""
        if os.path.exists(path):
            with open(path, encoding="utf-8") as f:
                text = f.read()
        for name in names:
            if "`%s`" % name not in text:
                bad.append("%s: block %s is not listed (as `%s`)" % (rel, name, name))
    return bad


def check_examples(root):
    """Every example flowgraph is pictured in docs/examples.md (its figure from
    scripts/draw_flowgraphs.py); the link check makes sure the figure exists."""
    bad = []
    page = os.path.join(root, "docs", "examples.md")
    text = ""
    if os.path.exists(page):
        with open(page, encoding="utf-8") as f:
            text = f.read()
    for path in sorted(glob.glob(os.path.join(root, "examples", "*.grc"))):
        name = os.path.splitext(os.path.basename(path))[0]
        if "(figures/flowgraph_%s.png)" % name not in text:
            bad.append("docs/examples.md: example %s is not pictured (figures/flowgraph_%s."
                       "png, scripts/draw_flowgraphs.py)" % (name, name))
    return bad


def check(root):
    """Every failure, one line each."""
    return check_sizes(root) + check_links(root) + check_blocks(root) + check_examples(root)


def main(argv):
    root = os.path.abspath(argv[0] if argv else
                           os.path.join(os.path.dirname(__file__), ".."))
    bad = check(root)
    for b in bad:
        print("check_docs: " + b, file=sys.stderr)
    if not bad:
        print("check_docs: README <= %d lines, user pages <= %d, every link resolves in the "
              "source tree and the installed docs, %d GRC blocks listed in blocks.md, "
              "README.md and MANIFEST.md, every example pictured"
              % (README_MAX_LINES, PAGE_MAX_LINES, len(block_names(root))))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
