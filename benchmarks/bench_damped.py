"""Damped against undamped solves, and widening against narrowing sweeps.

1. In one process, side by side: the undamped solve (``mp.solve``) and the
   damped one (``solve_asymmetric``, damping 0.1) on the paper's case (kw 1,
   radius 100, load 0.002, nu 0.2), cold (kernel cache cleared before each
   solve) and warm (the same vstar, kw, nu, damping and tol, another load),
   at V* = 0.2 and 0.65. The undamped problem has no steady solution at
   V* = 0.65 > V*_cr = 0.5717, so the undamped reference there is V* = 0.55
   (the fastest subcritical speed tried). Prints the medians and the ratios
   damped / undamped.
2. A 1000-point load sweep (undamped, V* 0.2, kw 1; load 0.001 ... 0.01) in
   the widening order (load rising: every point a slightly wider contact)
   and in the narrowing order, each from an empty kernel cache: time per
   point, kernel tables built, and the ratio widening / narrowing.

Times are medians and bests (minimum: the least disturbed by other
processes on a shared machine) over --repeat solves (cold, warm), and whole
sweeps (best of --repeat). The machine's load average is printed; never
asserts a time.

    .venv/bin/python benchmarks/bench_damped.py [--repeat 9] [--points 1000]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from collections.abc import Callable

import numpy as np

import movingpunch as mp
from movingpunch.asymmetric import solve_asymmetric

CASE = {"kw": 1.0, "radius": 100.0, "nu": 0.2}
LOAD = 0.002
DAMPING = 0.1


def _times_ms(
    run: Callable[[float], object], loads: list[float], cold: bool
) -> list[float]:
    times = []
    for load in loads:
        if cold:
            mp.clear_kernel_cache()
        t0 = time.perf_counter()
        run(load)
        times.append(1e3 * (time.perf_counter() - t0))
    return times


def solve_times(
    vstar: float, damped: bool, repeat: int
) -> tuple[list[float], list[float]]:
    """(cold, warm) times in ms for one speed."""

    def run(load: float) -> object:
        if damped:
            return solve_asymmetric(vstar=vstar, load=load, damping=DAMPING, **CASE)
        return mp.solve(vstar=vstar, load=load, **CASE)

    loads = [LOAD * (1.0 + 1e-3 * k) for k in range(repeat)]
    cold = _times_ms(run, loads, cold=True)
    run(LOAD)  # the table the warm solves reuse
    warm = _times_ms(run, [*loads[1:], LOAD * 1.01], cold=False)
    return cold, warm


def sweep(loads: np.ndarray) -> tuple[float, int]:
    """Seconds per point and kernel tables built over one sweep."""
    mp.clear_kernel_cache()
    builds = 0
    t0 = time.perf_counter()
    for load in loads:
        builds += mp.solve(vstar=0.2, load=float(load), **CASE).kernel_builds
    return (time.perf_counter() - t0) / len(loads), builds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=9)
    parser.add_argument("--points", type=int, default=1000)
    args = parser.parse_args()
    print(f"load average before: {os.getloadavg()[0]:.2f}")

    heads = ("cold ms", "warm ms", "best cold", "best warm")
    print(f"{'case':34s} " + " ".join(f"{h:>10s}" for h in heads))
    rows = {}
    for label, vstar, damped in (
        ("undamped V*=0.2", 0.2, False),
        ("damped   V*=0.2  (damping 0.1)", 0.2, True),
        ("undamped V*=0.55", 0.55, False),
        ("damped   V*=0.65 (damping 0.1)", 0.65, True),
    ):
        cold, warm = solve_times(vstar, damped, args.repeat)
        rows[label] = (
            statistics.median(cold),
            statistics.median(warm),
            min(cold),
            min(warm),
        )
        print(f"{label:34s} " + " ".join(f"{t:9.3f} " for t in rows[label]))
    for damped_label, ref in (
        ("damped   V*=0.2  (damping 0.1)", "undamped V*=0.2"),
        ("damped   V*=0.65 (damping 0.1)", "undamped V*=0.2"),
        ("damped   V*=0.65 (damping 0.1)", "undamped V*=0.55"),
    ):
        d, u = rows[damped_label], rows[ref]
        print(
            f"{damped_label.split('(')[0].strip():16s} / {ref:17s}: "
            f"cold {d[0] / u[0]:6.1f}x (target <= 20x)  "
            f"warm {d[1] / u[1]:6.1f}x (target <= 10x)  "
            f"best: cold {d[2] / u[2]:5.1f}x, warm {d[3] / u[3]:5.1f}x"
        )

    loads = np.geomspace(0.001, 0.01, args.points)
    best_w, best_n = (np.inf, 0), (np.inf, 0)
    for _ in range(max(1, args.repeat // 3)):
        w = sweep(loads)
        n = sweep(loads[::-1])
        best_w = min(best_w, w)
        best_n = min(best_n, n)
    print(
        f"{args.points}-point load sweep (undamped, V* 0.2, kw 1, load 0.001..0.01): "
        f"widening {1e3 * best_w[0]:.3f} ms/pt ({best_w[1]} tables), "
        f"narrowing {1e3 * best_n[0]:.3f} ms/pt ({best_n[1]} tables), "
        f"ratio {best_w[0] / best_n[0]:.2f} (target <= 1.2)"
    )
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
