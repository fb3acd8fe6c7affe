#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""gr-rfseek: RF source seeking using frequency measurements (GNU Radio OOT module).

Blocks: channel_source (simulated emitter, scatterers, UAV, CFO).
Core classes: scenario, world, rng.
"""

from .rfseek_python import *  # noqa: F401,F403

import math as _math


def deg(x):
    """Degrees to radians (the module's angles are radians, CCW from +x)."""
    return _math.radians(x)
