"""Time scenes: only-what-is-asked and work sharing, in one process.

1. A contact-width-only scene against a full scene (every output) on the same
   parameters: the ratio shows what asking for less saves.
2. A 200-point load sweep at fixed (vstar, kw, nu): one kernel for all points
   (the scene) against a cold kernel per point (cache cleared before each).
3. The same multi-group sweep (fig2: 4 speeds x 20 radii) in this process and
   on worker processes.

Every case is timed cold (kernel cache cleared first) and reported as the best
of --repeat runs; ratios are measured in this run. Never asserts a time.

    .venv/bin/python benchmarks/bench_scenes.py [--repeat 5] [--jobs N]
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable

import movingpunch as mp
from movingpunch.scene import OutputSpec, Scene, Sweep

PARAMS = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2}
ALL_OUTPUTS = (
    "contact_width",
    "pressure",
    "surface_stress",
    "depth_stress",
    "stress_field",
    "displacement",
    "critical_speed",
)


def best_of(fn: Callable[[], object], repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        mp.clear_kernel_cache()
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args()

    width_only = Scene(
        params=PARAMS, outputs={"contact_width": OutputSpec("contact_width")}
    )
    full = Scene(params=PARAMS, outputs={k: OutputSpec(k) for k in ALL_OUTPUTS})
    t_width = best_of(width_only.run, args.repeat)
    t_full = best_of(full.run, args.repeat)
    stages = full.run().stages
    print("1. Only what is asked (V* = 0.2, kw = 1, R/h = 100, P/(mu h) = 0.002)")
    print(f"   contact width only   {t_width * 1e3:9.2f} ms")
    print(f"   every output         {t_full * 1e3:9.2f} ms")
    print(f"   ratio full / width   {t_full / t_width:9.1f} x")
    print(
        "   full scene stages: "
        + ", ".join(f"{s.name} {s.seconds * 1e3:.1f} ms" for s in stages)
    )

    sweep = Scene(
        params=PARAMS, sweep=Sweep.range("load", 1e-4, 4e-3, 200, quantities=("a",))
    )
    loads = sweep.sweep.values if sweep.sweep is not None else ()

    failures: set[float] = set()

    def cold_each() -> None:
        for load in loads:
            mp.clear_kernel_cache()
            try:
                mp.solve(**{**PARAMS, "load": load})
            except mp.MovingPunchError:
                failures.add(load)

    t_shared = best_of(lambda: sweep.run(jobs=1), args.repeat)
    t_cold = best_of(cold_each, max(1, args.repeat // 2))
    print()
    print("2. 200-point load sweep at fixed (V*, kw, nu)")
    print(f"   scene (one kernel)    {t_shared * 1e3:9.1f} ms")
    print(f"   cold kernel per point {t_cold * 1e3:9.1f} ms")
    print(f"   ratio                 {t_cold / t_shared:9.1f} x")
    for load in sorted(failures):
        print(f"   (cold solve failed at load = {load!r})")

    fig2 = Scene.bundled("fig2")
    t_one = best_of(lambda: fig2.run(jobs=1), args.repeat)
    t_many = best_of(lambda: fig2.run(jobs=args.jobs), max(1, args.repeat // 2))
    print()
    print(f"3. fig2 (80 points, 4 kernel groups), {args.jobs} worker processes")
    print(f"   this process          {t_one * 1e3:9.1f} ms")
    print(f"   worker processes      {t_many * 1e3:9.1f} ms (includes starting them)")


if __name__ == "__main__":
    main()
