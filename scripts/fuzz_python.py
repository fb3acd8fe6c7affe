#!/usr/bin/python3
"""Mutation fuzzing of the Python parsers of outside data (scripts/fuzz.sh runs it):

  nav    vehicle_bridge.parse_nav on datagrams
  sigmf  sigmf.load and sigmf.replay_source on recordings (metadata and data file)

usage: fuzz_python.py [--seconds S | --inputs N] [--seed N] [--corpus DIR] [--out DIR]
       (PYTHONPATH must reach gnuradio.rfseek, e.g. build/python)

Inputs start from the seed corpus (lib/fuzz/corpus/nav/*, the committed recording's
metadata) and are mutated: bytes flipped, inserted, cut; JSON values replaced by other
types, NaN, inf, negative, huge or deleted. A parser may answer ValueError (the contract:
a clear error naming the field) and nothing else; any other exception is a finding,
written to the output folder and counted. Exit status 1 if anything was found.
libFuzzer does not reach Python (Debian has no atheris); this is its honest substitute:
random, not coverage-guided, seeded and reproducible.
"""

import argparse
import copy
import json
import math
import os
import random
import shutil
import sys
import tempfile
import time
import traceback

from gnuradio.rfseek import sigmf
from gnuradio.rfseek.vehicle_bridge import parse_nav

WEIRD = [None, True, False, 0, -1, 1, 2**64, -2**63, 1e308, -1e308, float("nan"),
         float("inf"), float("-inf"), 5e-324, "", "x", "0", [], {}, [1, 2], {"a": 1}]


def mutate_bytes(rng, b):
    b = bytearray(b)
    for _ in range(rng.randint(1, 8)):
        op = rng.randrange(4)
        if op == 0 and b:
            b[rng.randrange(len(b))] = rng.randrange(256)
        elif op == 1:
            b.insert(rng.randint(0, len(b)), rng.randrange(256))
        elif op == 2 and b:
            i = rng.randrange(len(b))
            del b[i:i + rng.randint(1, 8)]
        else:
            b += bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
    return bytes(b)


def mutate_json(rng, v, depth=0):
    """A copy of v with some values replaced by weird ones, keys deleted or added."""
    if rng.random() < 0.15 or depth > 6:
        return rng.choice(WEIRD)
    if isinstance(v, dict):
        out = {}
        for k, x in v.items():
            if rng.random() < 0.05:
                continue
            out[k] = mutate_json(rng, x, depth + 1) if rng.random() < 0.3 else x
        if rng.random() < 0.05:
            out[rng.choice(["core:sample_start", "rfseek:slot", "x"])] = rng.choice(WEIRD)
        return out
    if isinstance(v, list):
        out = [mutate_json(rng, x, depth + 1) if rng.random() < 0.3 else x for x in v]
        if out and rng.random() < 0.1:
            del out[rng.randrange(len(out))]
        return out
    return v


def dumps(v):
    return json.dumps(v, allow_nan=True).encode()


def check_nav(data):
    try:
        h, _ = parse_nav(data)
    except ValueError:
        return
    if not (math.isfinite(h) and 0.0 <= h < 360.0):
        raise AssertionError("parse_nav accepted heading %r" % h)


def check_sigmf(base):
    try:
        sigmf.load(base)
        sigmf.replay_source(base)
    except ValueError:
        return


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seconds", type=float, default=30.0, help="per target (default 30)")
    ap.add_argument("--inputs", type=int, default=0,
                    help="a fixed number of inputs per target instead (deterministic)")
    ap.add_argument("--seed", type=int, default=1)
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap.add_argument("--corpus", default=os.path.join(here, "lib", "fuzz", "corpus"))
    ap.add_argument("--out", default=None, help="where findings go (default: a temp dir)")
    args = ap.parse_args(argv)
    if not args.seconds > 0 or args.inputs < 0:
        ap.error("--seconds must be > 0 and --inputs >= 0")

    def more(count, t0):
        if args.inputs:
            return count < args.inputs
        return time.monotonic() - t0 < args.seconds
    rng = random.Random(args.seed)
    out = args.out or tempfile.mkdtemp(prefix="rfseek_fuzz_py_")
    os.makedirs(out, exist_ok=True)
    found = 0

    def finding(target, n, data, suffix=""):
        nonlocal found
        found += 1
        path = os.path.join(out, "%s-crash-%d%s" % (target, n, suffix))
        with open(path, "wb") as f:
            f.write(data)
        print("FINDING %s: %s (input in %s)" % (target, traceback.format_exc().strip()
                                                .splitlines()[-1], path), flush=True)

    # nav datagrams
    seeds = []
    d = os.path.join(args.corpus, "nav")
    for name in sorted(os.listdir(d)) if os.path.isdir(d) else []:
        seeds.append(open(os.path.join(d, name), "rb").read())
    seeds = seeds or [b'{"type": "nav", "heading_deg": 90.0, "time": 1.5}']
    n, t0 = 0, time.monotonic()
    while more(n, t0):
        s = rng.choice(seeds)
        if rng.random() < 0.5:
            try:
                data = dumps(mutate_json(rng, json.loads(s)))
            except ValueError:
                data = mutate_bytes(rng, s)
        else:
            data = mutate_bytes(rng, s)
        n += 1
        try:
            check_nav(data)
        except Exception:
            finding("nav", n, data)
    print("fuzz_python nav: %d inputs in %.1f s, %d findings"
          % (n, time.monotonic() - t0, found), flush=True)

    # SigMF recordings: the committed one's metadata, a short data file
    rec = os.path.join(here, "examples", "data", "sim_beacons")
    meta = json.load(open(rec + ".sigmf-meta"))
    meta["annotations"] = meta["annotations"][:5]
    raw = open(rec + ".sigmf-data", "rb").read()[:8 * 6000]
    work = tempfile.mkdtemp(prefix="rfseek_fuzz_sigmf_")
    base = os.path.join(work, "r")
    before = found
    m, t0 = 0, time.monotonic()
    while more(m, t0):
        m += 1
        mode = rng.randrange(3)
        mb = dumps(mutate_json(rng, copy.deepcopy(meta))) if mode != 1 else dumps(meta)
        if mode == 2 or rng.random() < 0.1:
            mb = mutate_bytes(rng, mb)
        db = raw if mode == 0 else raw[:rng.randrange(len(raw) + 1)]
        with open(base + ".sigmf-meta", "wb") as f:
            f.write(mb)
        with open(base + ".sigmf-data", "wb") as f:
            f.write(db)
        try:
            check_sigmf(base)
        except Exception:
            finding("sigmf", m, mb, ".sigmf-meta")
            shutil.copy(base + ".sigmf-data",
                        os.path.join(out, "sigmf-crash-%d.sigmf-data" % m))
    shutil.rmtree(work, ignore_errors=True)
    print("fuzz_python sigmf: %d recordings in %.1f s, %d findings"
          % (m, time.monotonic() - t0, found - before), flush=True)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
