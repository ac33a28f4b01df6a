"""Worker processes on cold sweeps: --jobs 1 against --jobs N, and validation.

1. A 2000-point vstar sweep and a 2000-point kw sweep (every point its own
   kernel: cold) run with jobs=1 (one process) and jobs=N (it and N-1
   spawned workers, their start-up included), and with the automatic choice
   (jobs=None). The speed-up jobs=1 / jobs=N is printed.
   A 20 000-point vstar sweep the same way, and on a local Dask cluster
   of --jobs single-threaded workers (started, and warmed by a 40-point
   sweep that imports movingpunch in its workers, before the timing: a
   cluster in use).
2. A 20 000-point one-group load sweep (one kernel, cheap points): the
   chunked pool against this process.
3. Loading and validating a 20 000-point kw sweep (O(1) critical speeds).

Cold means cold: each run is a fresh Python process (timed from just before
``Scene.run`` to just after, so the interpreter's start-up is not counted),
as a user's ``movingpunch run`` is. Clearing the caches of one long-lived
process is not enough: it keeps per-(kw, nu) critical speeds that spawned
workers would have to compute, which made --jobs look slower than it is.
Each case is the best of --repeat runs. Beside the wall-clock time, the CPU time of this
process and its (reaped) workers: CPU(jobs=N) / CPU(jobs=1) is the pool's
overhead, which the load of other processes barely changes, while the
wall-clock speed-up needs idle cores. The machine's load average is printed
before and after. Never asserts a time.

    .venv/bin/python benchmarks/bench_jobs.py [--repeat 3] [--jobs 2] [--only vstar20k]
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import json
import os
import subprocess
import sys
import time
from collections.abc import Callable, Iterator

from movingpunch.scene import Scene, Sweep

PARAMS = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2}

KW_SWEEP_20K = """\
[params]
vstar = 0.05
radius = 100
load = 0.002

[sweep]
param = "kw"
start = 0.5
stop = 50
points = 20000
spacing = "log"
"""


def cpu_seconds() -> float:
    """CPU time of this process and of its reaped children."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


# Runs one scene in a fresh interpreter; prints {"wall": s, "cpu": s, "jobs": n}.
_CHILD = """
import json, os, sys, time
from movingpunch.scene import Scene

def cpu():
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system

if __name__ == "__main__":
    spec = json.loads(sys.argv[1])
    scene = Scene.from_toml(spec["scene"])
    c0, t0 = cpu(), time.perf_counter()
    result = scene.run(jobs=spec["jobs"], dask=spec.get("dask"))
    wall, used = time.perf_counter() - t0, cpu() - c0
    print(json.dumps({"wall": wall, "cpu": used, "jobs": result.jobs}))
"""


def run_cold(scene: str, jobs: int | None, dask: str | None = None) -> dict[str, float]:
    """One run of ``scene`` (TOML text) in a fresh Python process (on the
    Dask scheduler at ``dask`` if given)."""
    spec = {"scene": scene, "jobs": jobs, "dask": dask}
    out = subprocess.run(
        [sys.executable, "-c", _CHILD, json.dumps(spec)],
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(out.stdout.splitlines()[-1])  # type: ignore[no-any-return]


def timed(
    scene: str, jobs: int | None, repeat: int, dask: str | None = None
) -> tuple[float, float, int]:
    """(best wall-clock seconds, best CPU seconds, processes used) of
    ``repeat`` cold runs."""
    runs = [run_cold(scene, jobs, dask) for _ in range(repeat)]
    return (
        min(r["wall"] for r in runs),
        min(r["cpu"] for r in runs),
        int(runs[0]["jobs"]),
    )


def best_of(fn: Callable[[], object], repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def load_average() -> str:
    one, five, _ = os.getloadavg()
    return f"load average {one:.2f} (1 min), {five:.2f} (5 min)"


def compare(
    name: str, scene: Scene, jobs: int, repeat: int, dask: str | None = None
) -> None:
    text = scene.to_toml()
    serial, serial_cpu, _ = timed(text, 1, repeat)
    pooled, pooled_cpu, _ = timed(text, jobs, repeat)
    auto, _, auto_jobs = timed(text, None, repeat)
    print(f"{name}")
    print(f"  jobs=1       {serial:8.3f} s   CPU {serial_cpu:7.3f} s")
    print(
        f"  jobs={jobs:<7d} {pooled:8.3f} s   CPU {pooled_cpu:7.3f} s   "
        f"speed-up {serial / pooled:.2f}x, CPU overhead {pooled_cpu / serial_cpu:.2f}x"
    )
    print(f"  jobs=None    {auto:8.3f} s   (chose {auto_jobs} process(es))")
    if dask is not None:  # the workers' CPU is not this process's: wall only
        on_dask, _, _ = timed(text, 1, repeat, dask)
        print(f"  dask         {on_dask:8.3f} s   speed-up {serial / on_dask:.2f}x")


@contextlib.contextmanager
def local_cluster(workers: int) -> Iterator[str | None]:
    """The address of a local Dask cluster of ``workers`` single-threaded
    worker processes (None without Dask), started and warmed before and
    closed after the timings: a user's cluster is already running."""
    try:
        distributed = importlib.import_module("distributed")
    except ImportError:
        print("dask: not installed (pip install 'movingpunch[dask]'): skipped")
        yield None
        return
    with distributed.LocalCluster(
        n_workers=workers,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
    ) as cluster:
        # A cluster in use: its workers have imported movingpunch (a first
        # task's 0.4 s of imports is theirs once, not every sweep's).
        warm_up = Scene(params=PARAMS, sweep=Sweep.range("vstar", 0.0, 0.5, 40))
        warm_up.run(dask=cluster.scheduler_address)
        yield cluster.scheduler_address


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument(
        "--only",
        choices=["vstar20k"],
        help="only the 20 000-point vstar sweep (jobs, automatic, Dask)",
    )
    args = parser.parse_args()
    print(load_average())

    with local_cluster(args.jobs) as address:
        compare(
            "20 000-point vstar sweep, cold (a kernel per point)",
            Scene(params=PARAMS, sweep=Sweep.range("vstar", 0.0, 0.5, 20_000)),
            args.jobs,
            args.repeat,
            address,
        )
    if args.only is not None:
        print(load_average())
        return
    compare(
        "2000-point vstar sweep, cold (a kernel per point)",
        Scene(params=PARAMS, sweep=Sweep.range("vstar", 0.0, 0.5, 2000)),
        args.jobs,
        args.repeat,
    )
    compare(
        "2000-point kw sweep, cold (a kernel per point)",
        Scene(
            params={**PARAMS, "vstar": 0.05},
            sweep=Sweep.range("kw", 0.5, 50.0, 2000, spacing="log"),
        ),
        args.jobs,
        args.repeat,
    )
    compare(
        "20 000-point load sweep, one group (one kernel)",
        Scene(params=PARAMS, sweep=Sweep.range("load", 1e-4, 4e-3, 20_000)),
        args.jobs,
        args.repeat,
    )
    validate = best_of(lambda: Scene.from_toml(KW_SWEEP_20K), args.repeat)
    print(f"validate a 20 000-point kw sweep: {validate * 1e3:.1f} ms")
    print(load_average())


if __name__ == "__main__":
    main()
