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
import sys as _sys
import types as _types

# The Python blocks, importable from the package as the README lists them. As in
# gr_modtool's modules, rfseek.vehicle_bridge and rfseek.seek_view are then the blocks,
# which shadow the modules of the same name as attributes of the package: take their
# helpers with `from gnuradio.rfseek.vehicle_bridge import parse_nav` (`import
# gnuradio.rfseek.vehicle_bridge as m` gives the block). rfseek.sigmf stays the module.
from .vehicle_bridge import loopback_vehicle, vehicle_bridge  # noqa: E402,F401
from .autopilot_link import autopilot_link  # noqa: E402,F401
from .sim_autopilot import sim_autopilot  # noqa: E402,F401
from .meas_streams import meas_streams  # noqa: E402,F401


#: Imported when first used, not with the module (`rfseek.seek_view` works as before):
#: seek_view's Qt and matplotlib, and the blocks built of GNU Radio's analog, filter and
#: channels blocks. A headless companion computer never loads a GUI toolkit, and
#: `from gnuradio import rfseek` stays fast (docs/benchmarks.md "Import time").
_LAZY = {"seek_view": "seek_view", "replay_source": "sigmf", "sigmf_recorder": "sigmf",
         "pulsed_beacon": "pulsed_beacon", "RADIOS": "radios", "radio_for": "radios",
         "radio_rx_chain": "radios", "radio_source": "radios", "rx_plan": "radios",
         "sim_radio": "radios", "gain_loop": "gain_loop"}


def __getattr__(name):
    if name in _LAZY:
        import importlib
        value = getattr(importlib.import_module("." + _LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError("module %r has no attribute %r" % (__name__, name))


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


class _package(_types.ModuleType):
    """This package's module type: importing a submodule that shares its block's name
    (gnuradio.rfseek.seek_view, .pulsed_beacon) makes Python set the package's
    attribute to the submodule; the block's name must stay the block."""

    def __setattr__(self, name, value):
        if _LAZY.get(name) == name and isinstance(value, _types.ModuleType):
            value = getattr(value, name)
        super().__setattr__(name, value)


_sys.modules[__name__].__class__ = _package


def _fields(obj):
    """The data fields of a bound parameter or result struct (its settable attributes
    that are not methods), in a stable order."""
    cls = type(obj)
    names = [k for k in cls.keys() if hasattr(obj, k)] if hasattr(cls, "keys") else sorted(
        k for k in dir(obj) if not k.startswith("_") and not callable(getattr(obj, k)))
    return names


def _rebuild(cls, state):
    obj = cls()
    for key, value in state.items():
        setattr(obj, key, value)
    return obj


def _give_values(cls, copyable=True, readable=True):
    """Copying and pickling (multiprocessing, Dask) and a readable repr for a bound
    struct whose fields are plain values: state is {field: value}, restored field by
    field (so a copy is independent and an out-of-range object pickles as it is)."""
    def state(self):
        return {k: getattr(self, k) for k in _fields(self)}
    if copyable:
        cls.__reduce__ = lambda self: (_rebuild, (type(self), state(self)))
        cls.__copy__ = lambda self: _rebuild(type(self), state(self))
        cls.__deepcopy__ = lambda self, memo: _rebuild(type(self), state(self))
    if readable:
        cls.__repr__ = lambda self: "%s(%s)" % (type(self).__name__, ", ".join(
            "%s=%r" % (k, getattr(self, k)) for k in _fields(self)))


_give_values(scenario, readable=False)  # noqa: F405 (it has its own repr)
_give_values(seeker_config)  # noqa: F405
_give_values(estimator_config)  # noqa: F405
_give_values(run_summary, copyable=False)  # noqa: F405 (made by a run only)


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


def split_sets(sets):
    """Command-line --set items ("KEY=VALUE") as (scenario items, seeker items): a key
    of both (speed_mps, self_arrival, ...) is the scenario's, which seeker_for copies
    into the seeker configuration. ValueError for a malformed item, and for an unknown
    key, listing every key taken."""
    if isinstance(sets, (str, bytes)) or not hasattr(sets, "__iter__"):
        raise ValueError("sets: a list of 'KEY=VALUE' strings, got %r" % (sets,))
    scen_keys = list(scenario.keys())
    seek_keys = [k for k in seeker_config.keys() if k not in set(scen_keys)]
    scen, seek = [], []
    for kv in sets:
        key, sep, _ = kv.partition("=")
        if not sep:
            raise ValueError("--set expects KEY=VALUE, got '%s'" % kv)
        key = key.strip()
        if key in scen_keys:
            scen.append(kv)
        elif key in seek_keys:
            seek.append(kv)
        else:
            raise ValueError("--set %s: unknown key. Scenario fields: %s. Seeker constants: "
                             "%s" % (key, ", ".join(scen_keys), ", ".join(seek_keys)))
    return scen, seek


def apply_sets(sc, sets):
    """Apply "KEY=VALUE" strings (command-line --set options) to a scenario; ValueError
    names a malformed item or a bad field."""
    if isinstance(sets, (str, bytes)) or not hasattr(sets, "__iter__"):
        raise ValueError("sets: a list of 'KEY=VALUE' strings, got %r" % (sets,))
    for kv in sets:
        key, sep, value = kv.partition("=")
        if not sep:
            raise ValueError("--set expects KEY=VALUE, got '%s'" % kv)
        sc.set(key.strip(), value.strip())
    return sc
