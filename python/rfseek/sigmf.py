#
# Copyright 2026 gr-rfseek authors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
"""SigMF recording and replay of a seek: the received IQ (cf32_le) with its beacon tags,
the vehicle's heading reports and the measurements made live, so a flight can be replayed
through the estimator and controller without hardware.

Metadata (BASE.sigmf-meta, SigMF 1.0.0): global core:datatype / core:sample_rate /
core:version / core:description / core:recorder, plus "rfseek:estimator" (the estimator
settings used live); one capture at sample 0 with core:frequency; annotations, each with
core:sample_start and core:label:
  "beacon"  rfseek:slot, rfseek:time, rfseek:heading   (from rfseek_beacon tags)
  "nav"     rfseek:heading                             (a heading report, radians CCW from
                                                        east, at the sample it arrived)
  "meas"    rfseek:slot, rfseek:freq_hz, rfseek:snr_db, rfseek:power_db, rfseek:valid
            (the live measurement of the window starting there)
"""

import json
import math
import numbers
import os

import numpy as np
import pmt
from gnuradio import blocks, gr

SIGMF_VERSION = "1.0.0"


class sigmf_recorder(gr.sync_block):
    """Sink: writes BASE.sigmf-data while running and BASE.sigmf-meta on stop.
    Message inputs: nav (heading reports), meas (doppler_estimator's measurements)."""

    def __init__(self, base, samp_rate, center_freq=0.0, description="gr-rfseek recording",
                 estimator=None):
        gr.sync_block.__init__(self, name="sigmf_recorder", in_sig=[np.complex64],
                               out_sig=None)
        if not isinstance(samp_rate, numbers.Real) or not 0 < samp_rate < math.inf:
            raise ValueError("sigmf_recorder: samp_rate = %r: must be > 0 and finite"
                             % (samp_rate,))
        if not isinstance(center_freq, numbers.Real) or not math.isfinite(center_freq):
            raise ValueError("sigmf_recorder: center_freq = %r: must be a finite "
                             "frequency in Hz (SigMF's core:frequency)" % (center_freq,))
        self.base = base
        self.samp_rate = float(samp_rate)
        self.center_freq = float(center_freq)
        self.description = description
        self.estimator = estimator or {}
        self.annotations = []
        self._written = 0
        if not isinstance(base, str) or not base or base.endswith(os.sep):
            raise ValueError("sigmf_recorder: base = %r: must be a path and file name "
                             "without extension (BASE.sigmf-data, BASE.sigmf-meta)"
                             % (base,))
        d = os.path.dirname(os.path.abspath(base))
        if not os.path.isdir(d):
            # Never created here: a typo in the path would record somewhere unexpected.
            raise ValueError("sigmf_recorder: base = %r: the directory %s does not exist; "
                             "create it first" % (base, d))
        self._data = open(base + ".sigmf-data", "wb")
        self.message_port_register_in(pmt.intern("nav"))
        self.set_msg_handler(pmt.intern("nav"), self.on_nav)
        self.message_port_register_in(pmt.intern("meas"))
        self.set_msg_handler(pmt.intern("meas"), self.on_meas)

    def on_nav(self, msg):
        try:
            h = float(pmt.to_python(msg)["heading"])
        except (KeyError, TypeError, ValueError, AttributeError):
            return
        if math.isfinite(h):
            self.annotations.append({"core:sample_start": int(self._written),
                                     "core:label": "nav", "rfseek:heading": h})

    def on_meas(self, msg):
        try:
            m = pmt.to_python(msg)
            a = {"core:sample_start": int(m["offset"]), "core:label": "meas",
                 "rfseek:slot": int(m["slot"]), "rfseek:freq_hz": float(m["freq_hz"]),
                 "rfseek:snr_db": float(m["snr_db"]), "rfseek:power_db": float(m["power_db"]),
                 "rfseek:valid": bool(m["valid"])}
        except (KeyError, TypeError, ValueError, AttributeError):
            return
        self.annotations.append(a)

    def work(self, input_items, output_items):
        x = input_items[0]
        for t in self.get_tags_in_window(0, 0, len(x)):
            if pmt.symbol_to_string(t.key) == "rfseek_beacon":
                v = pmt.to_python(t.value)
                if isinstance(v, dict):
                    a = {"core:sample_start": int(t.offset), "core:label": "beacon"}
                    for k in ("slot", "time", "heading"):
                        if k in v:
                            a["rfseek:" + k] = v[k]
                    self.annotations.append(a)
            elif pmt.symbol_to_string(t.key) == "rx_freq" and t.offset == 0:
                self.center_freq = float(pmt.to_double(t.value))
        self._data.write(np.ascontiguousarray(x, dtype=np.complex64).tobytes())
        self._written += len(x)
        return len(x)

    def stop(self):
        self._data.close()
        last = max(self._written - 1, 0)
        for a in self.annotations:  # a report after the last sample belongs to it
            a["core:sample_start"] = min(a["core:sample_start"], last)
        meta = {
            "global": {"core:datatype": "cf32_le", "core:sample_rate": self.samp_rate,
                       "core:version": SIGMF_VERSION, "core:description": self.description,
                       "core:recorder": "gr-rfseek",
                       "core:extensions": [{"name": "rfseek", "version": "0.1.0",
                                            "optional": True}],
                       "rfseek:estimator": self.estimator},
            "captures": [{"core:sample_start": 0, "core:frequency": self.center_freq}],
            "annotations": sorted(self.annotations, key=lambda a: a["core:sample_start"]),
        }
        with open(self.base + ".sigmf-meta", "w") as f:
            json.dump(meta, f, indent=1)
        return True


def _number(where, v, lo, hi):
    """v as a float in [lo, hi], or ValueError naming where it came from."""
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not lo <= v <= hi:
        raise ValueError("%s = %r: must be a number in [%g, %g]" % (where, v, lo, hi))
    return float(v)


def load(base):
    """(samples as complex64, metadata dict) of BASE.sigmf-{data,meta}; BASE may also be
    either file's path. ValueError naming the field if the recording is not one this
    module can replay (a recording comes from outside: every field used is checked,
    python/rfseek/fuzz_python.py tries the rest)."""
    for ext in (".sigmf-meta", ".sigmf-data"):
        if base.endswith(ext):
            base = base[:-len(ext)]
    try:
        with open(base + ".sigmf-meta", "rb") as f:
            meta = json.loads(f.read().decode("utf-8"))
    except (UnicodeDecodeError, ValueError) as e:
        raise ValueError("%s.sigmf-meta: not JSON (%s)" % (base, e))
    if not isinstance(meta, dict) or not isinstance(meta.get("global"), dict):
        raise ValueError("%s.sigmf-meta: no 'global' object" % base)
    g = meta["global"]
    if g.get("core:datatype") != "cf32_le":
        raise ValueError("%s: core:datatype %r: only cf32_le is supported" % (
            base, g.get("core:datatype")))
    v = g.get("core:sample_rate")
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not 0 < v < 1e12:
        raise ValueError("%s: no positive core:sample_rate (got %r)" % (base, v))
    caps = meta.get("captures", [])
    if not isinstance(caps, list) or not all(isinstance(c, dict) for c in caps):
        raise ValueError("%s: captures: must be a list of objects" % base)
    if caps and "core:frequency" in caps[0]:
        _number("%s: captures[0].core:frequency" % base, caps[0]["core:frequency"], -1e12, 1e12)
    anns = meta.get("annotations", [])
    if not isinstance(anns, list) or not all(isinstance(a, dict) for a in anns):
        raise ValueError("%s: annotations: must be a list of objects" % base)
    data = np.fromfile(base + ".sigmf-data", dtype=np.uint8)
    if data.size % 8:
        raise ValueError("%s.sigmf-data: %d bytes, not a whole number of cf32_le samples"
                         % (base, data.size))
    data = data.view(np.complex64)
    for i, a in enumerate(anns):
        if a.get("core:label") != "beacon":
            continue
        where = "%s: annotations[%d]" % (base, i)
        start = a.get("core:sample_start")
        if isinstance(start, bool) or not isinstance(start, int) or not 0 <= start < max(data.size, 1):
            raise ValueError("%s.core:sample_start = %r: must be a sample index in [0, %d)"
                             % (where, start, data.size))
        if "rfseek:slot" in a:
            slot = a["rfseek:slot"]
            if isinstance(slot, bool) or not isinstance(slot, int) or not 0 <= slot < 2**63:
                raise ValueError("%s.rfseek:slot = %r: must be an integer >= 0" % (where, slot))
        for k in ("time", "heading"):
            if "rfseek:" + k in a:
                _number("%s.rfseek:%s" % (where, k), a["rfseek:" + k], -1e12, 1e12)
    return data, meta


def replay_source(base, repeat=False):
    """A vector_source_c playing the recording with its beacon tags (rfseek_beacon
    {slot, time, heading}) and rx_rate / rx_freq at sample 0, and the metadata."""
    data, meta = load(base)
    tags = []

    def tag(offset, key, value):
        t = gr.tag_t()
        t.offset = offset
        t.key = pmt.intern(key)
        t.value = value
        tags.append(t)

    tag(0, "rx_rate", pmt.from_double(meta["global"]["core:sample_rate"]))
    caps = meta.get("captures") or [{}]
    tag(0, "rx_freq", pmt.from_double(float(caps[0].get("core:frequency", 0.0))))
    for a in meta.get("annotations", []):
        if a.get("core:label") != "beacon":
            continue
        d = pmt.make_dict()
        if "rfseek:slot" in a:
            d = pmt.dict_add(d, pmt.intern("slot"), pmt.from_uint64(int(a["rfseek:slot"])))
        for k in ("time", "heading"):
            if "rfseek:" + k in a:
                d = pmt.dict_add(d, pmt.intern(k), pmt.from_double(float(a["rfseek:" + k])))
        tag(int(a["core:sample_start"]), "rfseek_beacon", d)
    return blocks.vector_source_c(data.tolist(), repeat, 1, tags), meta
