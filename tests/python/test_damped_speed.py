"""Kernel reuse: the damped kernel table is cached across solves, and kernel
tables grow with headroom so a widening sweep builds a few tables (issue 13).

Counts, never times: the times are in benchmarks/bench_damped.py."""

from __future__ import annotations

import math

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.asymmetric import solve_asymmetric

PAPER = {"kw": 1.0, "radius": 100.0, "nu": 0.2}


@pytest.mark.parametrize("vstar", [0.2, 0.65])
def test_second_damped_solve_reuses_the_kernel(vstar: float) -> None:
    mp.clear_kernel_cache()
    first = solve_asymmetric(vstar=vstar, load=0.002, damping=0.1, **PAPER)
    assert first.kernel_builds >= 1
    warm = solve_asymmetric(vstar=vstar, load=0.0021, damping=0.1, **PAPER)
    assert warm.kernel_builds == 0
    assert warm.iterations > 0
    assert set(warm.stage_times) == {"critical_speed", "kernel", "width", "checks"}
    assert math.isclose(sum(warm.stage_times.values()), warm.elapsed, rel_tol=1e-2)
    # The reused table gives the contact a fresh one gives.
    mp.clear_kernel_cache()
    fresh = solve_asymmetric(vstar=vstar, load=0.0021, damping=0.1, **PAPER)
    assert fresh.kernel_builds >= 1
    for w, f in zip(warm.contact_interval, fresh.contact_interval, strict=True):
        assert abs(w - f) <= 1e-13
    assert math.isclose(warm.drag, fresh.drag, rel_tol=1e-11)


def test_stage_times_are_nonnegative_when_the_checks_fetch_a_wider_kernel() -> None:
    """A wide asymmetric contact on a soft foundation: the checks (the scan
    for other steady states, the gap) fetch a wider kernel table after the
    width is found; its time is the kernel's, never subtracted from the
    width (the width stage came out -12 ... -21 ms)."""
    mp.clear_kernel_cache()
    s = solve_asymmetric(vstar=0.3, kw=0.1, radius=100.0, load=0.006, damping=0.1)
    assert s.kernel_builds >= 2, s.kernel_builds
    assert all(t >= 0.0 for t in s.stage_times.values()), s.stage_times
    assert math.isclose(sum(s.stage_times.values()), s.elapsed, rel_tol=1e-2)


def test_cached_damped_solve_matches_the_direct_kernel_values() -> None:
    # docs/damped.md section 5 (measured before the table, with the kernel
    # summed directly per matrix entry): V* 0.2 -> (-0.3674248, 0.3781579),
    # drag 5.717036e-5; V* 0.65 -> (0.2736640, 1.1858265), drag 8.292463e-3.
    mp.clear_kernel_cache()
    for vstar, ends, drag in (
        (0.2, (-0.3674248, 0.3781579), 5.717036e-5),
        (0.65, (0.2736640, 1.1858265), 8.292463e-3),
    ):
        for load in (0.0019, 0.002):  # the second on the first's table
            s = solve_asymmetric(vstar=vstar, load=load, damping=0.1, **PAPER)
        assert s.kernel_builds == 0
        assert s.contact_interval == pytest.approx(ends, abs=1e-7)
        assert s.drag == pytest.approx(drag, rel=1e-6)
        # The energy balance, independent of the drag's evaluation.
        assert s.dissipation == pytest.approx(s.drag, rel=1e-9)


def _sweep_builds(loads: np.ndarray) -> int:
    mp.clear_kernel_cache()
    return sum(
        mp.solve(vstar=0.2, load=float(load), **PAPER).kernel_builds for load in loads
    )


def test_widening_load_sweep_builds_a_few_tables() -> None:
    loads = np.geomspace(0.001, 0.01, 200)
    widening = _sweep_builds(loads)
    narrowing = _sweep_builds(loads[::-1])
    # Before issue 13 the widening order built a table at nearly every point.
    assert 1 <= widening <= 4
    assert 1 <= narrowing <= 4


def test_random_order_sweep_builds_a_few_tables() -> None:
    loads = np.random.default_rng(13).permutation(np.geomspace(0.001, 0.01, 200))
    assert 1 <= _sweep_builds(loads) <= 6


def test_damped_depth_stress_includes_the_surface() -> None:
    # Anchor: the undamped solver's field evaluator (closed-form half-plane
    # part, an independent computation) at damping -> 0.
    s = solve_asymmetric(vstar=0.2, load=0.002, damping=1e-9, **PAPER)
    u = mp.solve(vstar=0.2, load=0.002, **PAPER)
    for x in (0.0, 0.2):
        assert s.depth_stress(0.0, x=x) == s.surface_stress(x)
    assert s.depth_stress(0.0) == pytest.approx(u.depth_stress(0.0), abs=1e-7)
    values = s.depth_stress([0.0, -0.01, -0.5])
    assert values == pytest.approx(u.depth_stress([0.0, -0.01, -0.5]), abs=1e-7)
    near = s.depth_stress([-1e-6, -1e-4])  # the surface layer too (issue 13)
    assert near == pytest.approx(u.depth_stress([-1e-6, -1e-4]), abs=1e-7)
    with pytest.raises(mp.InvalidParameterError, match="y must satisfy"):
        s.depth_stress(1e-4)
