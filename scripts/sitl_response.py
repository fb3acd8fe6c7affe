#!/usr/bin/python3
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""How the SITL firmware flies the link's heading commands, beside the module's model
(gnuradio.rfseek.sitl_response; docs/sitl.md). --help for the options."""
import sys

from gnuradio.rfseek.sitl_response import main

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
