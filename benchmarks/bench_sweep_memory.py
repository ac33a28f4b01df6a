"""Memory of a sweep against its number of points.

Each run is a fresh Python process that builds a sweep scene, runs it (one
process: ``jobs=1``, or ``--jobs N``) and, with ``--out``, writes its CSV
table; it reports its resident set size (VmRSS) before and after the run and
at its peak (VmHWM, the whole process's). The growth per point is
(RSS(n2) - RSS(n1)) / (n2 - n1) between two sizes of the same sweep (by
default 2 000 and 22 000 points), after the run, with the result still
held; and the same for the peak. A sweep that kept a solution a point grew
by about 7 kB a point (issue 27); the table itself takes 8 bytes a quantity
and one for ``valid``, and the scene's grid 32.

    .venv/bin/python benchmarks/bench_sweep_memory.py [--param load vstar]
        [--points 2000 22000] [--jobs 1] [--out DIR]

A million-point load sweep (about 7 minutes on one core):

    .venv/bin/python benchmarks/bench_sweep_memory.py --param load \\
        --points 2000 1000000 --jobs 2 --out /tmp/sweep-out

Never asserts anything; prints the machine's load average before and after.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys

PARAMS = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2}
RANGES = {"load": (1e-4, 4e-3), "vstar": (0.0, 0.5), "kw": (0.5, 50.0)}

_CHILD = """
import json, sys, time
from pathlib import Path
from movingpunch.scene import Scene, Sweep
from movingpunch.scene._export import write_outputs

def status(field):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024
    return 0

spec = json.loads(sys.argv[1])
params = spec["params"]  # the swept one is overridden by the sweep
lo, hi = spec["range"]
scene = Scene(params=params, sweep=Sweep.range(spec["param"], lo, hi, spec["points"]))
before = status("VmRSS")
t0 = time.perf_counter()
result = scene.run(jobs=spec["jobs"])
seconds = time.perf_counter() - t0
after = status("VmRSS")
written = 0.0
if spec["out"]:
    t0 = time.perf_counter()
    (path,) = write_outputs(result, Path(spec["out"]), "csv")
    written = time.perf_counter() - t0
print(json.dumps({
    "before": before, "after": after, "peak": status("VmHWM"),
    "seconds": seconds, "write": written, "jobs": result.jobs,
    "valid": int(result.sweep.valid.sum()),
}))
"""


def measure(param: str, points: int, jobs: int, out: str | None) -> dict[str, float]:
    spec = {
        "params": PARAMS,
        "param": param,
        "range": RANGES[param],
        "points": points,
        "jobs": jobs,
        "out": out,
    }
    run = subprocess.run(
        [sys.executable, "-c", _CHILD, json.dumps(spec)],
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(run.stdout.splitlines()[-1])  # type: ignore[no-any-return]


def load_average() -> str:
    one, five, _ = os.getloadavg()
    return f"load average {one:.2f} (1 min), {five:.2f} (5 min)"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--param", nargs="+", default=["load", "vstar"])
    parser.add_argument("--points", nargs=2, type=int, default=[2000, 22000])
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--out", default=None, help="also write the CSV here")
    args = parser.parse_args()
    print(load_average())
    n1, n2 = args.points
    for param in args.param:
        if param not in RANGES:
            parser.error(f"--param: one of {', '.join(RANGES)}, got {param!r}")
        small = measure(param, n1, args.jobs, args.out)
        large = measure(param, n2, args.jobs, args.out)
        for n, m in ((n1, small), (n2, large)):
            print(
                f"{param} sweep, {n:>8d} points, jobs {m['jobs']}: "
                f"{m['seconds']:7.2f} s (+ CSV {m['write']:.2f} s), "
                f"RSS {m['before'] / 2**20:6.1f} -> {m['after'] / 2**20:6.1f} MiB, "
                f"peak {m['peak'] / 2**20:6.1f} MiB, {m['valid']} valid"
            )
        grow = (large["after"] - small["after"]) / (n2 - n1)
        peak = (large["peak"] - small["peak"]) / (n2 - n1)
        print(
            f"  growth per point: {grow:.0f} B after the run, {peak:.0f} B at the peak"
        )
    print(load_average())


if __name__ == "__main__":
    main()
