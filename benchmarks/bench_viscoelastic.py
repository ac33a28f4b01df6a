"""What a viscoelastic layer costs (issue 28): a Zener layer's warm solve
against the same layer elastic, and a resistance curve of 100 speeds.

* Warm solve (kernel table cached; the load varied by 1e-3 per repeat so no
  result is reused), median over --repeat: the quasi-static Zener layer
  (ratio 2, deborah 0.1, kw 1, R/h 100, P/(mu_0 h) 0.002) against the elastic
  layer of mu_0 on the paper's path (``mp.solve``, the symmetric solver) and
  on the asymmetric solver (the same layer with friction 1e-12, the path the
  viscoelastic layer takes), and against the plain NumPy baseline's cylinder
  solve (benchmarks/baseline_numpy.py) run in the same process.
* A resistance curve: drag against the speed of one material, 100 deborah
  numbers log-spaced over 1e-3 ... 10 (quasi-static: the speed enters through
  deborah alone; each speed is a new medium, so a new kernel table), run
  twice: the first run, and the second (the process warm; the tables are
  kept only for the 16 most recent media).
* With the layer's inertia: the Zener layer and a three-branch Prony layer
  moving at vstar 0.1 (warm), against the elastic layer at vstar 0.1 on the
  asymmetric solver and on the symmetric one. And the warm Zener solve with
  its stress error estimate read (computed on first read).
* Viscoelastic sublayers in stacks moving at vstar 0.1 (a Zener course on
  an elastic base on springs; a Zener soil under an elastic top on a
  half-space), against the same stacks with their relaxed elastic moduli.
* Beyond the relaxed critical speed: the moving Zener layer at 100 speeds
  across V*_cr up to near V*_R; a warm train of two punches on a stack over
  a half-space (trains there measure their displacements from x = 100 h); a
  flat punch on the Zener layer at rest and moving (warm).
* The same as a user sweeps one material: ``Zener(ratio, tau=...)`` with
  ``inertia=False`` over 100 speeds vstar (deborah = sqrt(vstar) tau), the
  same material moving with its inertia over 100 speeds 1e-4 ... 0.5, and
  the bundled scene ``viscoelastic-bell`` (41 speeds) run with one and two
  worker processes.

Prints the machine's load average; never asserts a time.

    .venv/bin/python benchmarks/bench_viscoelastic.py [--repeat 7]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import statistics
import time
from collections.abc import Callable

import numpy as np
from bench_profiles import LOAD, peer_cylinder_ms

import movingpunch as mp

RADIUS, KW, NU = 100.0, 1.0, 0.2


def _median_ms(run: Callable[[float], object], repeat: int) -> float:
    run(LOAD)  # warm: the kernel table
    times = []
    for k in range(repeat):
        t0 = time.perf_counter()
        run(LOAD * (1.0 + 1e-3 * (k + 1)))
        times.append(1e3 * (time.perf_counter() - t0))
    return statistics.median(times)


PRONY = mp.Prony((1.0, 3.0, 0.5), (0.01, 1.0, 30.0))


def zener(
    load: float, deborah: float = 0.1, ratio: float = 2.0, vstar: float = 0.0
) -> mp.AsymmetricSolution:
    layer = mp.Layer(nu=NU, viscoelastic=mp.Zener(ratio, deborah))
    s = mp.solve(
        vstar=vstar, load=load, radius=RADIUS, layers=[layer], base=mp.Winkler(KW)
    )
    assert isinstance(s, mp.AsymmetricSolution)
    return s


def _sweep_seconds(material: mp.Zener, speeds: np.ndarray, inertia: bool) -> float:
    """Seconds to solve the layer of ``material`` at every speed (vstar)."""
    layer = mp.Layer(nu=NU, viscoelastic=material)
    t0 = time.perf_counter()
    for v in speeds:
        mp.solve(
            vstar=float(v),
            load=LOAD,
            radius=RADIUS,
            layers=[layer],
            base=mp.Winkler(KW),
            inertia=inertia,
        )
    return time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--speeds", type=int, default=100)
    args = parser.parse_args()
    print(f"load average: {os.getloadavg()[0]:.2f} ({os.cpu_count()} cores)")
    peer_ms = peer_cylinder_ms(args.repeat)
    visco = _median_ms(zener, args.repeat)
    elastic = _median_ms(
        lambda load: mp.solve(vstar=0.0, load=load, radius=RADIUS, kw=KW, nu=NU),
        args.repeat,
    )
    asym = _median_ms(
        lambda load: mp.solve(
            vstar=0.0, load=load, radius=RADIUS, kw=KW, nu=NU, friction=1e-12
        ),
        args.repeat,
    )
    # With the layer's inertia: the same layer moving at vstar 0.1, against
    # the elastic layer at vstar 0.1 on the asymmetric solver.
    moving = _median_ms(lambda load: zener(load, vstar=0.1), args.repeat)
    prony = _median_ms(
        lambda load: mp.solve(
            vstar=0.1,
            load=load,
            radius=RADIUS,
            layers=[mp.Layer(nu=NU, viscoelastic=PRONY)],
            base=mp.Winkler(KW),
        ),
        args.repeat,
    )
    sym_moving = _median_ms(
        lambda load: mp.solve(vstar=0.1, load=load, radius=RADIUS, kw=KW, nu=NU),
        args.repeat,
    )
    # The same warm Zener solve with its stress error estimate read (computed
    # on first read: the pressure's transform at the fine Fourier nodes).
    with_estimate = _median_ms(
        lambda load: zener(load).stress_error_estimate, args.repeat
    )
    sym_estimate = _median_ms(
        lambda load: (
            mp.solve(
                vstar=0.0, load=load, radius=RADIUS, kw=KW, nu=NU
            ).stress_error_estimate
        ),
        args.repeat,
    )
    asym_moving = _median_ms(
        lambda load: mp.solve(
            vstar=0.1, load=load, radius=RADIUS, kw=KW, nu=NU, friction=1e-12
        ),
        args.repeat,
    )
    # Viscoelastic sublayers in a stack (the complex propagation) against
    # the same stacks elastic (the relaxed moduli): an asphalt course on a
    # granular base on springs, and a lossy soil under an elastic top on a
    # half-space, moving at vstar 0.1.
    stacks = []
    for name, layers, base in (
        (
            "Zener course on a base, springs",
            [
                mp.Layer(0.4, nu=NU, viscoelastic=mp.Zener(3.0, 0.5)),
                mp.Layer(0.6, mu=2.0, nu=0.3, rho=1.2),
            ],
            mp.Winkler(KW),
        ),
        (
            "Zener soil under a top, half-space",
            [
                mp.Layer(0.3, nu=NU),
                mp.Layer(0.7, mu=0.5, nu=0.3, rho=0.8, viscoelastic=mp.Zener(4.0, 0.3)),
            ],
            mp.HalfSpace(mu=3.0, nu=0.25, rho=1.5),
        ),
    ):
        relaxed = [dataclasses.replace(sub, viscoelastic=None) for sub in layers]
        stacks.append(
            (
                name,
                *(
                    _median_ms(
                        lambda load, ls=ls, b=base: mp.solve(
                            vstar=0.1, load=load, radius=RADIUS, layers=ls, base=b
                        ),
                        args.repeat,
                    )
                    for ls in (layers, relaxed)
                ),
            )
        )
    print(f"{'warm solve':44} {'ms':>8} {'visco/it':>9}")
    for name, ms in (
        ("Zener layer (ratio 2, deborah 0.1)", visco),
        ("elastic layer, symmetric solver", elastic),
        ("elastic layer, asymmetric solver", asym),
        ("NumPy baseline cylinder (N = 24)", peer_ms),
    ):
        print(f"{name:44} {ms:8.2f} {visco / ms:9.1f}")
    print(f"{'warm solve at vstar 0.1 (inertia)':44} {'ms':>8} {'/elastic':>9}")
    for name, ms in (
        ("Zener layer moving (ratio 2, deborah 0.1)", moving),
        ("Prony layer moving (3 branches)", prony),
        ("elastic layer moving, asymmetric solver", asym_moving),
    ):
        print(f"{name:44} {ms:8.2f} {ms / asym_moving:9.1f}")
    print(
        f"{'elastic layer moving, symmetric solver':44} {sym_moving:8.2f} "
        f"(Zener moving / it: {moving / sym_moving:.1f})"
    )
    print(
        f"{'Zener layer, its stress estimate read too':44} {with_estimate:8.2f} "
        f"(/ the symmetric elastic's, {sym_estimate:.2f} ms: "
        f"{with_estimate / sym_estimate:.1f})"
    )
    print(f"{'stack moving at vstar 0.1':44} {'ms':>8} {'/elastic':>9}")
    for name, ms, elastic_ms in stacks:
        print(f"{name:44} {ms:8.2f} {ms / elastic_ms:9.1f}")
    deborahs = np.geomspace(1e-3, 10.0, args.speeds)
    for run in ("first", "second"):
        t0 = time.perf_counter()
        drags = [zener(LOAD, float(d)).drag for d in deborahs]
        total = time.perf_counter() - t0
        k = int(np.argmax(drags))
        print(
            f"resistance curve, {args.speeds} speeds ({run} run): {total:.2f} s "
            f"({1e3 * total / args.speeds:.1f} ms a speed); largest drag "
            f"{drags[k]:.4g} at deborah {deborahs[k]:.3g}"
        )
    # One material (tau = 100 h/c_T0) swept by its speed, quasi-statically.
    total = _sweep_seconds(mp.Zener(2.0, tau=100.0), (deborahs / 100.0) ** 2, False)
    print(
        f"one material by its speed (tau, inertia=False), {args.speeds} speeds: "
        f"{total:.2f} s ({1e3 * total / args.speeds:.1f} ms a speed)"
    )
    # The same material moving with its inertia (speeds below the relaxed
    # layer's V*_cr): each speed a new medium (its memory of a pole and a cut).
    total = _sweep_seconds(
        mp.Zener(2.0, tau=1.0), np.geomspace(1e-4, 0.5, args.speeds), True
    )
    print(
        f"one material moving (tau = 1, inertia), {args.speeds} speeds 1e-4 ... "
        f"0.5: {total:.2f} s ({1e3 * total / args.speeds:.1f} ms a speed)"
    )
    # Across the relaxed critical speed (0.572) to near the relaxed Rayleigh
    # speed (0.830): the Zener layer's own steady states there (each speed a
    # new medium; the load-curve scan runs where Re M1 < 0).
    total = _sweep_seconds(
        mp.Zener(2.0, 0.1), np.linspace(0.5, 0.82, args.speeds), True
    )
    print(
        f"Zener layer across V*_cr (0.5 ... 0.82, inertia), {args.speeds} speeds: "
        f"{total:.2f} s ({1e3 * total / args.speeds:.1f} ms a speed)"
    )
    # A train of two punches on a stack over a half-space (warm: the kernel
    # table cached; the load varied as above).
    stack = [mp.Layer(0.3, nu=NU), mp.Layer(0.7, mu=0.5, nu=0.3, rho=0.8)]
    half_space = mp.HalfSpace(mu=3.0, nu=0.25, rho=1.5)
    train_ms = _median_ms(
        lambda load: mp.solve_punches(
            [
                mp.Punch(5.0, load=25.0 * load, at=0.0),
                mp.Punch(5.0, load=40.0 * load, at=1.2),
            ],
            vstar=0.2,
            layers=stack,
            base=half_space,
        ),
        args.repeat,
    )
    print(f"train of two punches on a stack over a half-space, warm: {train_ms:.1f} ms")
    # A flat punch (b/h 0.5) on the Zener layer, at rest and moving (warm),
    # against the elastic flat punch (the symmetric solver).
    for vstar in (0.0, 0.1):
        flat_ms = _median_ms(
            lambda load, v=vstar: mp.solve(
                vstar=v,
                load=load,
                profile=mp.Flat(0.5),
                layers=[mp.Layer(nu=NU, viscoelastic=mp.Zener(2.0, 0.1))],
                base=mp.Winkler(KW),
            ),
            args.repeat,
        )
        flat_elastic = _median_ms(
            lambda load, v=vstar: mp.solve(
                vstar=v, load=load, profile=mp.Flat(0.5), kw=KW, nu=NU
            ),
            args.repeat,
        )
        print(
            f"flat punch on the Zener layer at vstar {vstar}, warm: {flat_ms:.2f} ms "
            f"(elastic flat, symmetric solver: {flat_elastic:.2f} ms)"
        )
    for jobs in (1, 2):
        scene = mp.Scene.bundled("viscoelastic-bell")
        t0 = time.perf_counter()
        result = scene.run(jobs=jobs)
        total = time.perf_counter() - t0
        assert result.sweep is not None
        print(
            f"scene viscoelastic-bell ({len(result.sweep.values)} speeds), "
            f"jobs {jobs}: {total:.2f} s"
        )


if __name__ == "__main__":
    main()
