"""What each punch profile costs, on the symmetric and the asymmetric solver.

For the paper's layer (V* 0.2, kw 1, nu 0.2, P/(mu h) 0.002) and each profile
(the cylinder R/h 100, a rounded flat b/h 0.3 with R/h 100, a symmetric
tabulated parabola, the same parabola shifted by 0.2 h (asymmetric), a flat
punch b/h 0.5), each with no damping or friction, damping 0.5, friction 0.3
and both: the cold solve (kernel cache cleared first) and the warm one (the
table cached, another load), medians over --repeat solves, and their ratio to
the plain NumPy baseline's cylinder solve (benchmarks/baseline_numpy.py, the
project's own implementation of the paper's method, N = 24) run in the same
process. Prints the machine's
load average; never asserts a time.

    .venv/bin/python benchmarks/bench_profiles.py [--repeat 5] [--maps]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

import movingpunch as mp

sys.path.insert(0, str(Path(__file__).resolve().parent))
import baseline_numpy

BASE = {"vstar": 0.2, "kw": 1.0, "nu": 0.2}
LOAD = 0.002


def _table(x0: float) -> mp.Profile:
    xs = np.linspace(-1.5, 2.5, 801) if x0 else np.linspace(-2.0, 2.0, 801)
    return mp.Profile(tuple(xs), tuple((xs - x0) ** 2 / 200.0))


PROFILES: dict[str, mp.PunchProfile] = {
    "cylinder": mp.Cylinder(100.0),
    "rounded flat": mp.RoundedFlat(0.3, 100.0),
    "table": _table(0.0),
    "asymmetric table": _table(0.2),
    "flat": mp.Flat(0.5),
}
EXTRAS: dict[str, dict[str, float]] = {
    "-": {},
    "damping 0.5": {"damping": 0.5},
    "friction 0.3": {"friction": 0.3},
    "both": {"damping": 0.5, "friction": 0.3},
}


def peer_cylinder_ms(repeat: int) -> float:
    """Median ms of the NumPy baseline's cylinder solve (the paper's problem,
    N = 24), printed."""
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        baseline_numpy.solve(0.2, 0.2, 1.0, 100.0, 500.0)
        t.append(1e3 * (time.perf_counter() - t0))
    ms = statistics.median(t)
    print(f"NumPy baseline (cylinder, N = 24): {ms:.1f} ms")
    return ms


def _median_ms(run: Any, repeat: int, cold: bool) -> float:
    times = []
    for k in range(repeat):
        if cold:
            mp.clear_kernel_cache()
        t0 = time.perf_counter()
        run(LOAD * (1.0 + 1e-3 * (k + 1)))
        times.append(1e3 * (time.perf_counter() - t0))
    return statistics.median(times)


def _map_ms(run: Any, repeat: int) -> float:
    """Best ms of the TUI's stress map (97 x over +-3 h, 41 depths) of a
    fresh solution (nothing of a previous map reused)."""
    x, y = np.linspace(-3.0, 3.0, 97), np.linspace(-1.0, 0.0, 41)
    best = float("inf")
    for k in range(repeat):
        s: Any = run(LOAD * (1.0 + 1e-3 * (k + 1)))
        t0 = time.perf_counter()
        s.stress_field(x, y)
        best = min(best, 1e3 * (time.perf_counter() - t0))
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument(
        "--maps",
        action="store_true",
        help="also the TUI's 97x41 stress map of each solution (its best of "
        "--repeat, each on a fresh solution) and its ratio to the cylinder's",
    )
    args = parser.parse_args()
    print(f"load average: {os.getloadavg()[0]:.2f} ({os.cpu_count()} cores)")
    peer_ms = peer_cylinder_ms(args.repeat)
    header = (
        f"{'profile':18} {'options':13} {'cold ms':>9} {'warm ms':>9} {'warm/peer':>9}"
    )
    if args.maps:
        header += f" {'map ms':>9} {'map/cyl':>8}"
    map_base: list[float] = []
    print(header)
    print("-" * len(header))
    for name, prof in PROFILES.items():
        for label, extra in EXTRAS.items():

            def run(load: float, prof: Any = prof, extra: Any = extra) -> object:
                return mp.solve(**BASE, load=load, profile=prof, **extra)

            try:
                cold = _median_ms(run, args.repeat, cold=True)
                run(LOAD)
                warm = _median_ms(run, args.repeat, cold=False)
            except mp.MovingPunchError as exc:
                print(f"{name:18} {label:13} {type(exc).__name__}")
                continue
            line = f"{name:18} {label:13} {cold:9.1f} {warm:9.1f} {warm / peer_ms:9.3f}"
            if args.maps:
                ms = _map_ms(run, args.repeat)
                map_base = map_base or [ms]  # the first row: the cylinder's
                line += f" {ms:9.1f} {ms / map_base[0]:8.1f}"
            print(line)


if __name__ == "__main__":
    main()
