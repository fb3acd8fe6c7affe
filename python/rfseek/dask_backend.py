"""The Dask backend of rfseek-montecarlo (``--scheduler ADDR`` / ``--dask-local N``).

rfseek-montecarlo writes the study's jobs (points, strategies, job index and seed of
every run still to do) to a JSON file and starts::

    /usr/bin/python3 -m gnuradio.rfseek.dask_backend JOBS.json (--scheduler ADDR | --local N)

This program connects to the Dask scheduler (or starts a LocalCluster of N worker
processes), prints ``READY <workers>``, sends chunks of runs (one study point, one
strategy, a range of seeds) to the workers and prints one line per run as chunks finish:

    ROW <job> <distance_m> <ratio> <straight_ratio> <time_s> <success> <slots> <has_stage1> <stage1_rad>
        <self_arrival> <declared> <detect_m> <false_arrival> <located> <loc_error_m>
        <loc_major_m> <in_ellipse> <overflight> <overflight_distance_m>
        <in_ellipse50> <unsure>
    ERR <job> <message>

Each worker runs ``study_point.run(strategy, seed)``, the C++ core through the bindings,
the very call rfseek-montecarlo's threads make: rows agree per seed whatever the backend.
A chunk whose worker dies is retried by Dask (``retries``); a run that raises is an ERR
row; a chunk that still fails gives ERR rows for its runs. Nothing is dropped silently.
An unreachable scheduler is one line on stderr and exit status 2.
"""

import argparse
import json
import logging
import math
import sys

_POINTS = {}


def _point(spec):
    """The study_point of a spec, built once per worker process."""
    key = json.dumps(spec, sort_keys=True)
    p = _POINTS.get(key)
    if p is None:
        from gnuradio import rfseek

        p = rfseek.study_point(spec["preset"], [tuple(kv) for kv in spec["given"]],
                               spec["sweep_key"], spec["sweep_value"])
        _POINTS[key] = p
    return p


def run_chunk(spec, strategy, jobs):
    """Runs [(job, seed), ...] of one point and strategy; returns the output lines."""
    p = _point(spec)
    out = []
    for job, seed in jobs:
        try:
            s = p.run(strategy, int(seed))
            out.append("ROW %d %r %r %r %r %d %d %d %r %d %d %r %d %d %r %r %d %d %r %d %d" % (
                job, s.distance_m, s.ratio, s.straight_ratio, s.time_s, int(s.success), s.slots,
                int(s.has_stage1), s.stage1_heading_error_rad, int(s.self_arrival),
                int(s.declared), s.arrival_detect_distance_m, int(s.false_arrival),
                int(s.located), s.location_error_m, s.location_major_m,
                int(s.location_in_ellipse), int(s.overflight), s.overflight_distance_m,
                int(s.location_in_ellipse50), int(s.location_unsure)))
        except Exception as e:  # a run that raises is a row with its error
            out.append("ERR %d %s: %s" % (job, type(e).__name__, " ".join(str(e).split())))
    return out


def chunks(study, size):
    """Consecutive jobs of the same point and strategy, at most size per chunk."""
    cur, key = [], None
    for job, point, strategy, seed in study["jobs"]:
        if cur and ((point, strategy) != key or len(cur) >= size):
            yield key, cur
            cur = []
        key = (point, strategy)
        cur.append((job, seed))
    if cur:
        yield key, cur


def fail(msg):
    print("rfseek-montecarlo: error: " + msg, file=sys.stderr, flush=True)
    sys.exit(2)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="gnuradio.rfseek.dask_backend",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("jobs", help="jobs file written by rfseek-montecarlo")
    where = ap.add_mutually_exclusive_group(required=True)
    where.add_argument("--scheduler", help="address of a running Dask scheduler")
    where.add_argument("--local", type=int, help="start a LocalCluster of N workers")
    ap.add_argument("--timeout", type=float, default=10.0,
                    help="seconds to reach the scheduler (default 10)")
    ap.add_argument("--retries", type=int, default=3,
                    help="retries of a chunk whose worker died (default 3)")
    args = ap.parse_args(argv)
    with open(args.jobs) as f:
        study = json.load(f)
    for name in ("distributed", "distributed.worker", "distributed.nanny",
                 "distributed.scheduler", "distributed.core", "distributed.comm"):
        logging.getLogger(name).setLevel(logging.ERROR)
    try:
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError as e:
        fail("the Dask backend needs Dask distributed (Debian: apt-get install "
             "python3-distributed): %s" % e)
    cluster = None
    try:
        if args.scheduler:
            client = Client(args.scheduler, timeout=args.timeout)
        else:
            if args.local < 1:
                fail("--dask-local must be >= 1")
            cluster = LocalCluster(n_workers=args.local, threads_per_worker=1,
                                   processes=True, dashboard_address=None)
            client = Client(cluster, timeout=args.timeout)
    except (OSError, TimeoutError) as e:
        fail("cannot reach the Dask scheduler at %s: %s"
             % (args.scheduler or "the local cluster", " ".join(str(e).split())))
    workers = len(client.scheduler_info().get("workers", {}))
    print("READY %d" % max(workers, 1), flush=True)
    if workers == 0:
        print("rfseek-montecarlo: the scheduler has no workers yet; waiting for them",
              file=sys.stderr, flush=True)

    njobs = len(study["jobs"])
    size = study.get("chunk") or 0
    if size < 1:  # about 4 tasks per worker, at most 50 runs each
        size = max(1, min(50, math.ceil(njobs / (4 * max(workers, 1)))))
    points, strategies = study["points"], study["strategies"]
    pending = {}
    for (point, strategy), jobs in chunks(study, size):
        fut = client.submit(run_chunk, points[point], strategies[strategy], jobs,
                            retries=args.retries, pure=False)
        pending[fut] = jobs
    try:
        for fut in as_completed(list(pending)):
            try:
                lines = fut.result()
            except Exception as e:  # the chunk failed on every try
                msg = "%s: %s" % (type(e).__name__, " ".join(str(e).split()))
                lines = ["ERR %d chunk failed: %s" % (job, msg) for job, _ in pending[fut]]
            sys.stdout.write("".join(line + "\n" for line in lines))
            sys.stdout.flush()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
