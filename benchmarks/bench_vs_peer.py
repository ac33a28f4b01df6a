"""Time movingpunch against the plain NumPy baseline, side by side in one process.

The baseline is the project's own plain NumPy implementation of the paper's
method (benchmarks/baseline_numpy.py: a 4 x 4 layer system per wavenumber,
composite Gauss-Legendre for the kernel, N = 24 Gauss-Chebyshev collocation, a
secant on a); ``--peer PATH`` times any other module with the same
``solve(nu, vstar, kw, R, mu_over_P)`` instead (a second yardstick). Both sides
aim at 1e-8 on a/h or better (ours: tol = 1e-8; the baseline agrees with ours
to 1e-13 on these cases, tests/python/test_baseline_numpy.py). Reports
medians and ratios (peer time / our time) measured in the same run, and the a/h
each gives; never asserts a time. Stages:

- cold:   a new (vstar, kw, nu): our critical speed and kernel are not cached;
- warm:   a new load only (our kernel table is reused; the peer recomputes all);
- sweep:  1000 loads at fixed (vstar, kw, nu), per point (the peer is timed on
          a subset of the points: it has no state to reuse);
- curves: the three curves the TUI draws after a parameter change (p(x) and
          sigma_x(x, 0) at 241 points, sigma_x(0, y) at 121 depths), with the
          solve: the redraw budget is 50 ms (the peer computes no stresses).

Ours includes the validity checks and the indentation in every solve.

Usage:

    .venv/bin/python benchmarks/bench_vs_peer.py [--repeat 7] [--peer PATH]

    .venv/bin/python benchmarks/bench_vs_peer.py --instructions   # callgrind

``--instructions`` counts instructions with ``valgrind --tool=callgrind``
(per cold solve, and per warm solve at a new load on a cached table)
(figures that survive a noisy machine; several minutes).
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

import movingpunch as mp

HERE = Path(__file__).resolve().parent
DEFAULT_PEER = HERE / "baseline_numpy.py"

# The peer's cases: (nu, vstar, kw, R/h, mu/(P/h)).
CASES = [
    (0.2, 0.001, 1.0, 100.0, 500.0),
    (0.2, 0.2, 1.0, 100.0, 500.0),
    (0.2, 0.2, 0.1, 100.0, 500.0),
]
TOL = 1e-8


def load_peer(path: Path) -> ModuleType:
    if not path.is_file():
        raise SystemExit(
            f"--peer: no such file {path} "
            "(a module with solve(nu, vstar, kw, R, mu_over_P))"
        )
    spec = importlib.util.spec_from_file_location("peer_numpy", path)
    if spec is None or spec.loader is None:
        raise SystemExit(f"cannot load the peer from {path}")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def median_time(fn: Callable[[int], Any], repeat: int) -> tuple[float, Any]:
    """Median wall time of fn(i) over ``repeat`` calls, and its last value."""
    times, value = [], None
    for i in range(repeat):
        t0 = time.perf_counter()
        value = fn(i)
        times.append(time.perf_counter() - t0)
    return statistics.median(times), value


def row(label: str, a_peer: float, a_ours: float, t_peer: float, t_ours: float) -> str:
    peer_a = f"{a_peer:12.8f}" if math.isfinite(a_peer) else f"{'-':>12s}"
    ratio = f"{t_peer / t_ours:8.0f}x" if math.isfinite(t_peer) else f"{'-':>9s}"
    peer_ms = f"{t_peer * 1e3:10.3f}" if math.isfinite(t_peer) else f"{'-':>10s}"
    return f"{label:34s} {peer_a} {a_ours:12.8f} {peer_ms} {t_ours * 1e3:10.3f} {ratio}"


def bench_case(
    peer: ModuleType, case_no: int, case: tuple[float, ...], repeat: int
) -> dict[str, float]:
    """Cold, warm and sweep ratios for one case; prints a row for each."""
    nu, vs, kw, radius, mu_p = case
    tag = f"{case}"

    def ours(load: float, k: float = kw) -> float:
        return mp.solve(vstar=vs, kw=k, radius=radius, load=load, nu=nu, tol=TOL).a

    t_peer, a_peer = median_time(lambda i: peer.solve(nu, vs, kw, radius, mu_p), repeat)
    # Cold: every call a foundation stiffness never seen before (1e-12 apart:
    # the same physics to 1e-12, but nothing cached).
    t_cold, a_cold = median_time(
        lambda i: ours(1 / mu_p, kw * (1.0 + 1e-12 * (1000 * case_no + i + 1))), repeat
    )
    print(row(f"cold  {tag}", a_peer, a_cold, t_peer, t_cold))
    # Warm: a new load each call (a wider contact first, so its table serves).
    ours(1.2 / mu_p)
    t_warm, a_warm = median_time(
        lambda i: ours((1.0 - 1e-3 * (i % 2)) / mu_p), max(repeat, 21)
    )
    print(row(f"warm  {tag}", a_peer, a_warm, t_peer, t_warm))
    # Sweep: 1000 loads from 2 mu/P down to mu/P / 2 (descending contact).
    loads = np.geomspace(2.0 / mu_p, 0.5 / mu_p, 1000)
    mp.clear_kernel_cache()
    t0 = time.perf_counter()
    widths = [ours(float(p)) for p in loads]
    t_sweep = (time.perf_counter() - t0) / len(loads)
    subset = loads[:: len(loads) // 5]
    t0 = time.perf_counter()
    for p in subset:
        peer.solve(nu, vs, kw, radius, 1.0 / float(p))
    t_peer_pt = (time.perf_counter() - t0) / len(subset)
    print(row(f"sweep {tag} /pt", math.nan, widths[-1], t_peer_pt, t_sweep))
    return {
        "cold": t_peer / t_cold,
        "warm": t_peer / t_warm,
        "sweep": t_peer_pt / t_sweep,
    }


def redraw_time(repeat: int) -> tuple[float, float]:
    """Median time of the TUI's redraw after a parameter change: a warm solve
    and the three curves it draws."""
    nu, vs, kw, radius, mu_p = CASES[1]

    def redraw(i: int) -> float:
        s = mp.solve(
            vstar=vs, kw=kw, radius=radius, load=(1.0 + 1e-3 * i) / mu_p, nu=nu, tol=TOL
        )
        s.pressure(np.linspace(-1.2 * s.a, 1.2 * s.a, 241))
        s.surface_stress(np.linspace(-3 * s.a, 3 * s.a, 241))
        s.depth_stress(np.linspace(0.0, -1.0, 121))
        return s.a

    return median_time(redraw, max(repeat, 21))


def run(peer: ModuleType, repeat: int) -> dict[str, list[float]]:
    print(
        f"{'stage, case (nu, vstar, kw, R, mu/P)':34s} {'peer a/h':>12s} "
        f"{'ours a/h':>12s} {'peer ms':>10s} {'ours ms':>10s} {'ratio':>9s}"
    )
    ratios: dict[str, list[float]] = {"cold": [], "warm": [], "sweep": []}
    for case_no, case in enumerate(CASES):
        for stage, value in bench_case(peer, case_no, case, repeat).items():
            ratios[stage].append(value)
    t_redraw, a_redraw = redraw_time(repeat)
    print(row("curves (solve + 3 curves)", math.nan, a_redraw, math.nan, t_redraw))
    print()
    for stage, values in ratios.items():
        mean = statistics.geometric_mean(values)
        print(
            f"{stage:6s} speed-up: geometric mean {mean:.0f}x "
            f"(min {min(values):.0f}x) over {len(values)} cases"
        )
    print(f"redraw: median {t_redraw * 1e3:.1f} ms (budget 50 ms)")
    return ratios


INSTRUCTION_SCRIPT = """
import importlib.util, sys
import movingpunch as mp
spec = importlib.util.spec_from_file_location("peer", {peer!r})
peer = importlib.util.module_from_spec(spec); spec.loader.exec_module(peer)
what = sys.argv[1]
if what == "ours":
    for i in range(20):
        mp.solve(vstar=0.2, kw=1.0 + 1e-9 * i, radius=100.0, load=0.002)
elif what.startswith("warm"):
    # One solve at a wider contact builds the table the others reuse.
    mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.0024)
    for i in range(20 if what == "warm" else 0):
        mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002 * (1.0 + 1e-3 * i))
elif what == "peer":
    peer.solve(0.2, 0.2, 1.0, 100.0, 500.0)
"""


def instructions(peer_path: Path) -> None:
    """Instructions per solve with callgrind: (run - baseline) / solves."""
    if shutil.which("valgrind") is None:
        raise SystemExit("--instructions needs valgrind (apt-get install valgrind)")
    with tempfile.TemporaryDirectory() as tmp:
        script = Path(tmp) / "count.py"
        script.write_text(INSTRUCTION_SCRIPT.format(peer=str(peer_path)))

        def count(what: str) -> int:
            out = Path(tmp) / f"cg.{what}"
            subprocess.run(
                [
                    "valgrind",
                    "--tool=callgrind",
                    f"--callgrind-out-file={out}",
                    sys.executable,
                    str(script),
                    what,
                ],
                check=True,
                capture_output=True,
            )
            for line in out.read_text().splitlines():
                if line.startswith("summary:") or line.startswith("totals:"):
                    return int(line.split()[1])
            raise SystemExit(f"no totals in {out}")

        base = count("none")
        ours = (count("ours") - base) / 20
        warm = (count("warm") - count("warm_base")) / 20
        theirs = count("peer") - base
        print(
            f"instructions per cold solve (paper case): ours {ours:.3e}, "
            f"peer {theirs:.3e}, ratio {theirs / ours:.0f}x"
        )
        print(
            f"instructions per warm solve (paper case, a new load): ours {warm:.3e}, "
            f"peer {theirs:.3e}, ratio {theirs / warm:.0f}x"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument(
        "--peer",
        type=Path,
        default=DEFAULT_PEER,
        help="a module with solve(nu, vstar, kw, R, mu_over_P) -> a/h "
        "(default: the project's NumPy baseline)",
    )
    parser.add_argument(
        "--instructions", action="store_true", help="count instructions (callgrind)"
    )
    args = parser.parse_args()
    peer = load_peer(args.peer)
    if args.instructions:
        instructions(args.peer)
        return
    run(peer, args.repeat)


if __name__ == "__main__":
    main()
