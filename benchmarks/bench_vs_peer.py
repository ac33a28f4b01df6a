"""Time movingpunch.solve against the plain NumPy/SciPy peer
(../shared/bench/peer_numpy.py) on the peer's own cases, in one process.

Reports ratios (peer time / our time) measured in the same run, and the a/h
each gives; never asserts a time. Usage:

    .venv/bin/python benchmarks/bench_vs_peer.py [--repeat 5] [--peer PATH]
"""

from __future__ import annotations

import argparse
import functools
import importlib.util
import math
import statistics
import time
from pathlib import Path
from types import ModuleType

import movingpunch as mp

# The peer's cases: (nu, vstar, kw, R/h, mu/(P/h)).
CASES = [
    (0.2, 0.001, 1.0, 100.0, 500.0),
    (0.2, 0.2, 1.0, 100.0, 500.0),
    (0.2, 0.2, 0.1, 100.0, 500.0),
]


def load_peer(path: Path) -> ModuleType:
    spec = importlib.util.spec_from_file_location("peer_numpy", path)
    if spec is None or spec.loader is None:
        raise SystemExit(f"cannot load the peer from {path}")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def best_of(fn, repeat: int) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    times, value = [], math.nan
    for _ in range(repeat):
        t0 = time.perf_counter()
        value = fn()
        times.append(time.perf_counter() - t0)
    return min(times), value


def main() -> None:
    here = Path(__file__).resolve().parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument(
        "--peer", type=Path, default=here.parent.parent / "shared/bench/peer_numpy.py"
    )
    args = parser.parse_args()
    peer = load_peer(args.peer)
    print(
        f"{'case (nu, vstar, kw, R/h, mu/(P/h))':40s} {'peer a/h':>12s} "
        f"{'ours a/h':>12s} {'peer ms':>9s} {'ours ms':>9s} {'ratio':>7s}"
    )
    ratios = []
    for nu, vs, kw, radius, mu_over_p in CASES:
        # Ours: a fresh critical-speed cache would favour the peer unfairly
        # little; solve once to warm the per-(kw, nu) cache like a session would.
        mp.solve(vstar=vs, kw=kw, radius=radius, load=1 / mu_over_p, nu=nu)
        ours = functools.partial(
            mp.solve, vstar=vs, kw=kw, radius=radius, load=1 / mu_over_p, nu=nu
        )
        t_peer, a_peer = best_of(
            functools.partial(peer.solve, nu, vs, kw, radius, mu_over_p), args.repeat
        )
        t_ours, a_ours = best_of(lambda: ours().a, args.repeat)  # noqa: B023
        ratios.append(t_peer / t_ours)
        print(
            f"{(nu, vs, kw, radius, mu_over_p)!s:40s} {a_peer:12.8f} {a_ours:12.8f} "
            f"{t_peer * 1e3:9.2f} {t_ours * 1e3:9.2f} {t_peer / t_ours:6.1f}x"
        )
    print(
        f"geometric-mean speed-up: {statistics.geometric_mean(ratios):.1f}x "
        f"(best of {args.repeat}; ours at tol=1e-8 including validity checks "
        "and the indentation)"
    )


if __name__ == "__main__":
    main()
