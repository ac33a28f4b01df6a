"""The process-wide k1 kernel cache and the per-stage times of a solve."""

from __future__ import annotations

import math

import pytest

import movingpunch as mp


@pytest.fixture(autouse=True)
def _empty_cache() -> None:
    mp.clear_kernel_cache()


def test_load_sweep_builds_the_kernel_once() -> None:
    # Largest contact first; the rest reuse its table.
    loads = [0.004 * 0.9**i for i in range(12)]
    sols = [mp.solve(vstar=0.3, kw=1.0, radius=100.0, load=p) for p in loads]
    assert sols[0].kernel_builds >= 1
    assert [s.kernel_builds for s in sols[1:]] == [0] * (len(loads) - 1)
    info = mp.kernel_cache_info()
    assert info["hits"] >= len(loads) - 1
    assert info["misses"] == sum(s.kernel_builds for s in sols)
    # Reuse changes nothing beyond the root finder's tolerance: a fresh solve
    # of the last point agrees, and a/h still falls with the load.
    widths = [s.a for s in sols]
    assert widths == sorted(widths, reverse=True)
    mp.clear_kernel_cache()
    fresh = mp.solve(vstar=0.3, kw=1.0, radius=100.0, load=loads[-1])
    assert fresh.kernel_builds >= 1
    assert fresh.a == pytest.approx(sols[-1].a, rel=1e-11)


def test_the_asymmetric_solvers_tables_are_counted_apart() -> None:
    """A damped or frictional solve builds (then reuses) a table of the
    asymmetric solver's cache, counted under damped_*, not under k1's."""
    args = {"vstar": 0.3, "kw": 1.0, "radius": 100.0, "load": 0.002}
    first = mp.solve(**args, damping=0.1)
    info = mp.kernel_cache_info()
    assert first.kernel_builds >= 1
    assert info["asymmetric_misses"] == first.kernel_builds
    assert info["asymmetric_size"] >= 1
    assert (info["size"], info["misses"]) == (0, 0)
    again = mp.solve(**args, damping=0.1)
    assert again.kernel_builds == 0
    assert mp.kernel_cache_info()["asymmetric_hits"] > info["asymmetric_hits"]
    frictional = mp.solve(**args, friction=0.3)  # its own key: (.., friction)
    assert frictional.kernel_builds >= 1
    assert mp.kernel_cache_info()["asymmetric_misses"] == (
        first.kernel_builds + frictional.kernel_builds
    )
    mp.clear_kernel_cache()
    assert mp.kernel_cache_info()["asymmetric_size"] == 0


def test_a_different_material_or_tolerance_builds_its_own() -> None:
    mp.solve(vstar=0.3, kw=1.0, radius=100.0, load=0.002)
    for change in ({"vstar": 0.31}, {"kw": 2.0}, {"nu": 0.3}, {"tol": 1e-9}):
        args = {"vstar": 0.3, "kw": 1.0, "radius": 100.0, "load": 0.002} | change
        assert mp.solve(**args).kernel_builds >= 1, change
    # The same material again, another radius with the same contact scale: a hit.
    assert mp.solve(vstar=0.3, kw=1.0, radius=50.0, load=0.004).kernel_builds == 0


def test_radius_and_load_enter_through_their_product() -> None:
    # a/h and p/(P/h) depend on R and P only through R P (the equation for g
    # has R P as its only load parameter): an independent check of the kernel
    # reuse as well, since the second solve reuses the first one's table.
    a = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
    b = mp.solve(vstar=0.2, kw=1.0, radius=20.0, load=0.01)
    assert b.kernel_builds == 0
    assert b.a == pytest.approx(a.a, rel=1e-12)
    assert b.p0 == pytest.approx(a.p0, rel=1e-10)


def test_stage_times_sum_to_elapsed() -> None:
    s = mp.solve(vstar=0.5, kw=10.0, radius=100.0, load=0.002)
    assert set(s.stage_times) == {"critical_speed", "kernel", "width", "checks"}
    assert all(t >= 0.0 and math.isfinite(t) for t in s.stage_times.values())
    total = sum(s.stage_times.values())
    assert total <= s.elapsed * (1 + 1e-9)
    assert total >= 0.9 * s.elapsed - 1e-5
    assert s.to_dict()["stage_times"] == dict(s.stage_times)
    with pytest.raises(TypeError):
        s.stage_times["kernel"] = 0.0  # type: ignore[index]
