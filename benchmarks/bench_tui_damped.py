"""The terminal UI's redraw with and without damping (issue 13: every
damped TUI redraw under 100 ms).

A redraw is what the UI's worker computes after an edit: the summary (a
solve and its sigma_x peaks) and the open tab's data
(``movingpunch.tui.model.compute``). Here the edit changes the load by 1 %
(the kernel table stays warm, as while typing a load), on a fresh cache each
time; medians over --repeat edits per tab, undamped and damped (0.1) at
V* = 0.2, and at V* = 0.55 (undamped) / 0.65 (damped, above the undamped
V*_cr). Prints ms per tab and the ratio damped / undamped. Never asserts a
time.

    .venv/bin/python benchmarks/bench_tui_damped.py [--repeat 4]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

from movingpunch.tui import model
from movingpunch.tui.model import Cache, Params, Request, TabName

TABS: tuple[TabName, ...] = ("pressure", "surface", "depth", "field", "sweep")
CASES = ((0.2, 0.0), (0.2, 0.1), (0.55, 0.0), (0.65, 0.1))


def redraw_ms(vstar: float, damping: float, tab: TabName, repeat: int) -> float:
    """Median ms of ``repeat`` redraws of ``tab`` after a 1 % load change."""
    cache = Cache()
    first = Params(vstar=vstar, damping=damping, load=0.0019)
    model.compute(cache, Request(generation=1, params=first, tab=tab))
    times = []
    for k in range(repeat):
        params = Params(vstar=vstar, damping=damping, load=0.002 * (1 + 0.01 * k))
        t0 = time.perf_counter()
        model.compute(cache, Request(generation=2 + k, params=params, tab=tab))
        times.append(time.perf_counter() - t0)
    return 1e3 * statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=4)
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}; ms per redraw (median)")
    print(f"{'case':<22}" + "".join(f"{t:>10}" for t in TABS))
    rows = {}
    for vstar, damping in CASES:
        row = [redraw_ms(vstar, damping, tab, args.repeat) for tab in TABS]
        rows[(vstar, damping)] = row
        label = f"V*={vstar} damping={damping}"
        print(f"{label:<22}" + "".join(f"{v:>10.0f}" for v in row))
    for (vd, d), (vu, u) in (((0.2, 0.1), (0.2, 0.0)), ((0.65, 0.1), (0.55, 0.0))):
        ratios = [a / b for a, b in zip(rows[(vd, d)], rows[(vu, u)], strict=True)]
        label = f"ratio {vd}/{vu}"
        print(f"{label:<22}" + "".join(f"{r:>9.2f}x" for r in ratios))
    worst = max(max(rows[c]) for c in CASES if c[1] > 0)
    print(f"slowest damped redraw: {worst:.0f} ms (target < 100 ms)")


if __name__ == "__main__":
    main()
