"""Damped against undamped stress evaluations (issue 13: the damped field at
every depth, the surface layer included).

For each case (V*, kw, damping; the paper's radius 100, load 0.002, nu 0.2)
the damped solution's ``depth_stress`` on 101 and 200 depths from -1 to 0
(the TUI's sigma_x(0, y) tab uses 101) and ``stress_field`` on 41 x 41 and
97 x 41 (the TUI's field tab) points, against the undamped solution's at the
same V* and kw (at V* above the undamped V*_cr: V* = 0.55, the nearest
subcritical speed tried). Each evaluation runs on a fresh solution (the
damped one prepares its node data on first use: counted), interleaved
damped/undamped, --repeat times; prints the medians in ms, the ratios
damped / undamped and the machine's load average. Never asserts a time.

    .venv/bin/python benchmarks/bench_damped_field.py [--repeat 7]
"""

from __future__ import annotations

import argparse
import functools
import os
import statistics
import time
from collections.abc import Callable

import numpy as np

import movingpunch as mp

PAPER = {"radius": 100.0, "load": 0.002, "nu": 0.2}
CASES = [(0.2, 1.0, 0.1), (0.65, 1.0, 0.1), (0.8, 1.0, 0.01), (0.65, 10.0, 1.0)]
X41, X97 = np.linspace(-3.0, 3.0, 41), np.linspace(-3.0, 3.0, 97)
Y41 = np.linspace(-1.0, 0.0, 41)
TASKS: dict[str, Callable[[object], object]] = {
    "depth 101": lambda s: s.depth_stress(np.linspace(-1.0, 0.0, 101)),  # type: ignore[attr-defined]
    "depth 200": lambda s: s.depth_stress(np.linspace(-1.0, 0.0, 200)),  # type: ignore[attr-defined]
    "field 41x41": lambda s: s.stress_field(X41, Y41),  # type: ignore[attr-defined]
    "field 97x41": lambda s: s.stress_field(X97, Y41),  # type: ignore[attr-defined]
}


def _ms(make: Callable[[], object], task: Callable[[object], object]) -> float:
    s = make()
    t0 = time.perf_counter()
    task(s)
    return 1e3 * (time.perf_counter() - t0)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}")
    for vstar, kw, damping in CASES:
        ref = min(vstar, 0.55) if kw == 1.0 else vstar

        make_damped = functools.partial(
            mp.solve, vstar=vstar, kw=kw, damping=damping, **PAPER
        )
        make_undamped = functools.partial(mp.solve, vstar=ref, kw=kw, **PAPER)
        for name, task in TASKS.items():
            d, u = [], []
            for _ in range(args.repeat):
                d.append(_ms(make_damped, task))
                u.append(_ms(make_undamped, task))
            md, mu = statistics.median(d), statistics.median(u)
            print(
                f"V* {vstar} kw {kw} D {damping} (undamped V* {ref}) {name}: "
                f"damped {md:.1f} ms, undamped {mu:.1f} ms, ratio {md / mu:.2f}"
            )


if __name__ == "__main__":
    main()
