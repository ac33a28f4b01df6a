"""Worker processes on cold sweeps: --jobs 1 against --jobs N, and validation.

1. A 2000-point vstar sweep and a 2000-point kw sweep (every point its own
   kernel: cold) run in this process (jobs=1) and on N spawned workers
   (jobs=N, worker start-up included), and with the automatic choice
   (jobs=None). The speed-up jobs=1 / jobs=N is printed.
2. A 20 000-point one-group load sweep (one kernel, cheap points): the
   chunked pool against this process.
3. Loading and validating a 20 000-point kw sweep (O(1) critical speeds).

Each case is the best of --repeat runs, the kernel cache of this process
cleared before each. Beside the wall-clock time, the CPU time of this
process and its (reaped) workers: CPU(jobs=N) / CPU(jobs=1) is the pool's
overhead, which the load of other processes barely changes, while the
wall-clock speed-up needs idle cores. The machine's load average is printed
before and after. Never asserts a time.

    .venv/bin/python benchmarks/bench_jobs.py [--repeat 3] [--jobs 2]
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable

import movingpunch as mp
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


def timed(fn: Callable[[], object], repeat: int) -> tuple[float, float]:
    """(best wall-clock seconds, best CPU seconds) of ``repeat`` cold runs."""
    wall = cpu = float("inf")
    for _ in range(repeat):
        mp.clear_kernel_cache()
        c0, t0 = cpu_seconds(), time.perf_counter()
        fn()
        wall = min(wall, time.perf_counter() - t0)
        cpu = min(cpu, cpu_seconds() - c0)
    return wall, cpu


def best_of(fn: Callable[[], object], repeat: int) -> float:
    return timed(fn, repeat)[0]


def load_average() -> str:
    one, five, _ = os.getloadavg()
    return f"load average {one:.2f} (1 min), {five:.2f} (5 min)"


def compare(name: str, scene: Scene, jobs: int, repeat: int) -> None:
    serial, serial_cpu = timed(lambda: scene.run(jobs=1), repeat)
    pooled, pooled_cpu = timed(lambda: scene.run(jobs=jobs), repeat)
    auto_result = scene.run(jobs=None)
    auto, _ = timed(lambda: scene.run(jobs=None), repeat)
    print(f"{name}")
    print(f"  jobs=1       {serial:8.3f} s   CPU {serial_cpu:7.3f} s")
    print(
        f"  jobs={jobs:<7d} {pooled:8.3f} s   CPU {pooled_cpu:7.3f} s   "
        f"speed-up {serial / pooled:.2f}x, CPU overhead {pooled_cpu / serial_cpu:.2f}x"
    )
    print(f"  jobs=None    {auto:8.3f} s   (chose {auto_result.jobs} process(es))")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    print(load_average())

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
