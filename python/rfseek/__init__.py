#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""gr-rfseek: RF source seeking using frequency measurements (GNU Radio OOT module).

Blocks: channel_source (simulated emitter, scatterers, UAV, CFO), doppler_estimator
(zero-padded FFT frequency estimator), seeking_controller (the paper's seeker), and in
Python vehicle_bridge (UDP JSON link to the autopilot; loopback_vehicle for tests),
sigmf_recorder (SigMF recording; replay_source plays one back) and seek_view (QT GUI
trajectory and frequency plots).
Core classes: scenario, world, rng, tone_estimator, seeker, simulation, study_point.
Helpers: flowgraphs.closed_loop, plots.
"""

from .rfseek_python import *  # noqa: F401,F403
from ._version import __version__  # noqa: F401

import math as _math

# The Python blocks, importable from the package as the README lists them. As in
# gr_modtool's modules, rfseek.vehicle_bridge and rfseek.seek_view are then the blocks,
# which shadow the modules of the same name as attributes of the package: take their
# helpers with `from gnuradio.rfseek.vehicle_bridge import parse_nav` (`import
# gnuradio.rfseek.vehicle_bridge as m` gives the block). rfseek.sigmf stays the module.
from .vehicle_bridge import loopback_vehicle, vehicle_bridge  # noqa: E402,F401
from .sigmf import replay_source, sigmf_recorder  # noqa: E402,F401
from .autopilot_link import autopilot_link  # noqa: E402,F401
from .sim_autopilot import sim_autopilot  # noqa: E402,F401
from .pulsed_beacon import pulsed_beacon  # noqa: E402,F401
from .meas_streams import meas_streams  # noqa: E402,F401
from .radios import (RADIOS, radio_for, radio_rx_chain, radio_source,  # noqa: E402,F401
                     rx_plan, sim_radio)

try:
    from .seek_view import seek_view  # noqa: E402,F401
except Exception:  # no (or a broken) Qt or matplotlib: every other block works
    pass


def deg(x):
    """Degrees to radians (the module's angles are radians, CCW from +x)."""
    return _math.radians(x)


def deg_or_none(x):
    """Degrees to radians, keeping None (= drawn from the seed). For GRC parameters."""
    return None if x is None else _math.radians(x)


def arrival_is_self(mode):
    """An "oracle" / "self" arrival setting (GRC's Arrival parameter, a --arrival option)
    as a bool: True for "self"; ValueError for anything else."""
    if mode not in ("oracle", "self"):
        raise ValueError("arrival = %r: must be 'oracle' (the simulator ends the run at "
                         "d_v) or 'self' (the vehicle decides its arrival)" % (mode,))
    return mode == "self"


def scenario_from(**fields):
    """A scenario with the given fields set; None values mean "drawn from the seed"."""
    sc = scenario()
    for key, value in fields.items():
        if key not in scenario.keys():
            raise TypeError("unknown scenario field '%s'" % key)
        setattr(sc, key, value)
    return sc


def apply_sets(sc, sets):
    """Apply "KEY=VALUE" strings (command-line --set options) to a scenario; ValueError
    names a malformed item or a bad field."""
    for kv in sets:
        key, sep, value = kv.partition("=")
        if not sep:
            raise ValueError("--set expects KEY=VALUE, got '%s'" % kv)
        sc.set(key.strip(), value.strip())
    return sc
