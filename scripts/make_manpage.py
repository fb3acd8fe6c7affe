#!/usr/bin/python3
#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""A man page (section 1) from a program's own --help, at build time, so that the two
never disagree: NAME with the program's one-line summary, then the help text as it
prints (options, defaults, examples), then where the documentation is installed.

  make_manpage.py NAME VERSION OUTPUT -- COMMAND [ARGS...]

COMMAND --help is run (its stdout, or stderr if stdout is empty); a non-zero exit or an
empty help is an error (exit 1), so a broken program fails the build, not the page.
"""

import re
import subprocess
import sys
import textwrap

#: The NAME line of each program (man's one-line summary); others take the first
#: sentence of their help, cut at a word.
SUMMARIES = {
    "rfseek-sim": "one closed-loop seek through GNU Radio, with its figures",
    "rfseek-live": "the seek with a radio or a recording, a vehicle link, or rehearsed",
    "rfseek-sitl": "the seek flown by ArduPilot's or PX4's SITL firmware, GPS off",
    "rfseek-montecarlo": "Monte Carlo studies of the closed loop (threads or Dask)",
    "rfseek-plot-montecarlo": "figures and tables of rfseek-montecarlo results",
    "rfseek-soak": "memory of many flowgraphs and of a long study",
    "rfseek-bench-acquire": "benchmark: burst timing acquisition on a pulsed beacon",
    "rfseek-bench-faults": "benchmark: the acquire alignment through receiver faults",
    "rfseek-bench-import": "benchmark: the time to import the module",
    "rfseek-bench-world": "benchmark: the cost of synthesising a beacon slot",
    "rfseek-bench-estimator": "benchmark: the cost of one frequency estimate",
    "rfseek-bench-loop": "benchmark: the cost of the closed loop per slot",
    "rfseek-estimator-study": "the estimator's accuracy against the Cramer-Rao bound",
}


def roff_escape(line):
    """A line of help text as literal roff: backslashes doubled, and a leading dot or
    quote (a roff request) escaped."""
    line = line.replace("\\", "\\e")
    if line.startswith((".", "'")):
        line = "\\&" + line
    return line


def summary(name, text):
    """The program's one-line summary: SUMMARIES', else the first sentence of the
    description (the text after the usage block) cut to 70 characters at a word."""
    if name in SUMMARIES:
        return SUMMARIES[name]
    lines = text.splitlines()
    i = 0
    if lines and lines[0].lower().startswith("usage:"):
        while i < len(lines) and lines[i].strip():  # the usage block
            i += 1
    for line in lines[i:]:
        line = line.strip()
        if line and not line.lower().startswith("usage"):
            line = re.sub(r"^%s:\s*" % re.escape(name), "", line)
            return textwrap.shorten(line.split(". ")[0].rstrip(".:"), 70, placeholder="...")
    return "a program of gr-rfseek"


def page(name, version, text):
    # The program may print its own path as argv[0]: the page names it.
    text = re.sub(r"(?m)(usage:\s*)\S*%s\b" % re.escape(name), r"\g<1>%s" % name, text)
    out = [".TH %s 1 \"\" \"gr-rfseek %s\" \"User Commands\"" % (name.upper(), version),
           ".SH NAME", "%s \\- %s" % (name, roff_escape(summary(name, text))),
           ".SH DESCRIPTION", ".nf"]
    for line in text.rstrip("\n").splitlines():  # long lines wrapped, indent kept
        indent = line[:len(line) - len(line.lstrip())]
        for part in (textwrap.wrap(line, 88, subsequent_indent=indent) or [""]):
            out.append(roff_escape(part))
    out += [".fi", ".SH SEE ALSO",
            "The gr-rfseek user guide, installed in share/doc/gr-rfseek (README.md and "
            "docs/index.md)."]
    return "\n".join(out) + "\n"


def main(argv):
    if len(argv) < 5 or argv[3] != "--":
        print(__doc__, file=sys.stderr)
        return 2
    name, version, output, command = argv[0], argv[1], argv[2], argv[4:]
    try:
        p = subprocess.run(command + ["--help"], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, timeout=120)
    except (OSError, subprocess.TimeoutExpired) as e:
        print("make_manpage: %s --help: %s" % (name, e), file=sys.stderr)
        return 1
    text = p.stdout if p.stdout.strip() else p.stderr
    if p.returncode != 0 or not text.strip():
        print("make_manpage: %s --help exited %d: %s" % (name, p.returncode,
                                                         p.stderr.strip()[-300:]),
              file=sys.stderr)
        return 1
    with open(output, "w", encoding="utf-8") as f:
        f.write(page(name, version, text))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
