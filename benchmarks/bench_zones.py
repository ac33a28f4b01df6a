"""What several contact zones cost: a two-punch train against one punch.

For each case (a layer, a speed, the punches' spacing) the warm solve (kernel
table cached; the loads varied by 1e-3 per repeat so no result is reused) of
one punch (``mp.solve``, the single contact) and of a two-punch train
(``mp.solve_punches``, each punch as the single one), medians over --repeat
solves, their ratio (the issue asks at most 4x), and both against the plain
NumPy baseline's cylinder solve (benchmarks/baseline_numpy.py, N = 24, the
paper's problem) run in the same process. Also the separated contact of one
punch (the paper's soft foundation at 0.99 V*_cr: two zones) against the
single contact it replaces, and a train of 8 rounded flats against one.
Prints the machine's load average; never asserts a time.

    .venv/bin/python benchmarks/bench_zones.py [--repeat 7]
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Callable

from bench_profiles import LOAD, _median_ms, peer_cylinder_ms

import movingpunch as mp

CASES: dict[str, dict[str, float]] = {
    "stiff, 100 h apart": {"vstar": 0.5, "kw": 1.0, "spacing": 100.0},
    "kw 1, 3 h apart": {"vstar": 0.5, "kw": 1.0, "spacing": 3.0},
    "kw 1 damped 0.3, 3 h": {"vstar": 0.5, "kw": 1.0, "spacing": 3.0, "damping": 0.3},
    "kw 0.1 at 0.9 V*cr, 4 h": {
        "vstar": 0.9 * mp.critical_vstar(0.1),
        "kw": 0.1,
        "spacing": 4.0,
    },
}


def _warm_median_ms(run: Callable[[float], object], repeat: int) -> float:
    run(LOAD)  # warm: the kernel table
    return _median_ms(run, repeat, cold=False)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    print(f"load average: {os.getloadavg()[0]:.2f} ({os.cpu_count()} cores)")
    peer_ms = peer_cylinder_ms(args.repeat)
    header = f"{'case':26} {'one ms':>8} {'two ms':>8} {'two/one':>8} {'two/peer':>9}"
    print(header)
    print("-" * len(header))
    for name, case in CASES.items():
        layer = {k: v for k, v in case.items() if k != "spacing"}
        half = 0.5 * case["spacing"]

        def one(load: float, layer: dict[str, float] = layer) -> object:
            return mp.solve(**layer, radius=100.0, load=load)

        def two(
            load: float, layer: dict[str, float] = layer, half: float = half
        ) -> object:
            punches = [mp.Punch(100.0, load, at=-half), mp.Punch(100.0, load, at=half)]
            return mp.solve_punches(punches, **layer)

        a = _warm_median_ms(one, args.repeat)
        b = _warm_median_ms(two, args.repeat)
        print(f"{name:26} {a:8.2f} {b:8.2f} {b / a:8.1f} {b / peer_ms:9.3f}")
    v99 = 0.99 * mp.critical_vstar(0.1)

    def single(load: float) -> object:
        return mp.solve(
            vstar=v99,
            kw=0.1,
            radius=100.0,
            load=load,
            contact="single",
            allow_unphysical=True,
        )

    def separated(load: float) -> object:
        return mp.solve(vstar=v99, kw=0.1, radius=100.0, load=load)

    a = _warm_median_ms(single, args.repeat)
    b = _warm_median_ms(separated, args.repeat)
    print(
        f"separated (kw 0.1, 0.99 V*cr): single contact {a:.2f} ms, "
        f"two zones {b:.2f} ms ({b / a:.1f}x; {b / peer_ms:.3f} of the peer)"
    )
    # Issue 27: a train of 8 rounded flats (0.3/100, 3 h apart, kw 1) against
    # one rounded flat; the train must converge without a warning.
    flat = mp.RoundedFlat(0.3, 100.0)

    def one_flat(load: float) -> object:
        return mp.solve(vstar=0.2, kw=1.0, profile=flat, load=load)

    def eight_flats(load: float) -> object:
        punches = [mp.Punch(flat, load, at=3.0 * (i - 3.5)) for i in range(8)]
        s = mp.solve_punches(punches, vstar=0.2, kw=1.0)
        if s.warnings:
            raise SystemExit(f"the train of 8 rounded flats warned: {s.warnings}")
        return s

    a = _warm_median_ms(one_flat, args.repeat)
    b = _warm_median_ms(eight_flats, args.repeat)
    print(
        f"8 rounded flats 0.3/100, 3 h apart (V* 0.2, kw 1): one {a:.2f} ms, "
        f"train {b:.1f} ms ({b / a:.1f}x one; issue 27 asks at most 30x)"
    )


if __name__ == "__main__":
    main()
