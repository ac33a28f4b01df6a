"""Error estimates that mean what they say, warnings where tol is not met,
continuity down to subnormal speeds, and the pressure margin (issue 12).

Honesty of ``error_estimate`` is measured against a reference solved
independently: fixed N = 256 at tol 1e-14, whose own uncertainty ``u`` is its
difference from a second reference at N = 192 and tol 1e-12 (another N and
another k1 kernel table, so the kernel's round-off differs too).

The comparison (docs/performance.md, "Error estimates"):

* the estimate bounds the error: ``error_estimate >= |a - a_ref| - u``;
* it exceeds it by at most ``FACTOR`` = 100 unless the result carries a
  warning: ``error_estimate <= FACTOR * max(|a - a_ref|, u, 64 eps a)``. The
  floor ``64 eps a`` is the round-off scale of a/h (a ratio of two round-off
  numbers means nothing), and an error below the reference's own uncertainty
  cannot be resolved.
"""

from __future__ import annotations

import functools
import json
import math
import subprocess
from collections.abc import Callable

import numpy as np
import numpy.typing as npt
import pytest

import movingpunch as mp
from movingpunch.scene import Scene

EPS = float(np.finfo(np.float64).eps)
FACTOR = 100.0
INF = math.inf

# Loads with a valid single contact up to V*_cr (kw = 0.1 separates at the
# paper's load near V*_cr: a larger R P keeps the contact closed).
CASES = {0.1: {"radius": 100.0, "load": 0.02}, 1.0: {}, 10.0: {}}
PAPER = {"radius": 100.0, "load": 0.002}


def _params(kw: float) -> dict[str, float]:
    return {**PAPER, **CASES.get(kw, {})}


def _vstar(kw: float, eps: float) -> float:
    return mp.critical_vstar(kw) * (1.0 - eps)


@functools.cache
def reference_solutions(kw: float, eps: float) -> tuple[mp.Solution, mp.Solution]:
    """The N = 256, tol 1e-14 reference near V*_cr(1 - eps) and the N = 192,
    tol 1e-12 one that measures its uncertainty, cached for the module."""
    v = _vstar(kw, eps)
    fine = mp.solve(
        vstar=v, kw=kw, n=256, tol=1e-14, allow_unphysical=True, **_params(kw)
    )
    other = mp.solve(
        vstar=v, kw=kw, n=192, tol=1e-12, allow_unphysical=True, **_params(kw)
    )
    return fine, other


def reference(kw: float, eps: float) -> tuple[float, float]:
    """(a/h, its uncertainty) near V*_cr(1 - eps)."""
    fine, other = reference_solutions(kw, eps)
    return fine.a, abs(fine.a - other.a)


def check_honest(s: mp.Solution, ref: float, u: float, resolution: float = 0.0) -> None:
    """``resolution``: what the reference can resolve beyond ``u`` (its own
    error bound, where that exceeds the single-sample ``u``); it only raises
    the floor of the factor-100 check, never the bound check."""
    actual = abs(s.a - ref)
    where = (s.kw, s.vstar, s.tol, s.a, actual, u, s.error_estimate, s.warnings)
    assert s.error_estimate >= actual - u, where
    if not s.warnings:
        floor = max(actual, u, resolution, 64.0 * EPS * s.a)
        assert s.error_estimate <= FACTOR * floor, where
        assert s.error_estimate <= s.tol * s.a, where


NEAR = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-13, 1e-14]
FAST = {(1.0, 1e-4), (1.0, 1e-8), (1.0, 1e-12), (1.0, 1e-14)}


def near_group(kw: float, eps: float) -> pytest.MarkDecorator:
    """The tests of one near-critical reference run on one pytest-xdist
    worker (``--dist loadgroup``, scripts/test.sh): the reference (an
    N = 256 solve near V*_cr and its stress peaks, up to ~25 s of CPU) is
    then computed once, not once per worker that draws one of its tests."""
    return pytest.mark.xdist_group(f"estimates-near-{kw:g}-{eps:g}")


NEAR_CASES = [
    pytest.param(
        kw,
        eps,
        marks=(near_group(kw, eps),)
        + (() if (kw, eps) in FAST else (pytest.mark.slow,)),
    )
    for kw in CASES
    for eps in NEAR
]
"""(kw, eps) of the near-critical tests, grouped by reference; all but the
FAST cases slow-marked."""


@pytest.mark.parametrize(("kw", "eps"), NEAR_CASES)
@pytest.mark.parametrize("tol", [1e-8, 1e-10])
def test_error_estimate_is_honest_near_critical(
    kw: float, eps: float, tol: float
) -> None:
    """Bounds the error, and at most 100 times it unless a warning says tol
    was not met (the acceptance of issue 12). As at a loose tol, an error
    below the reference's own bound is not resolved: that bound is in the
    floor of the factor-100 check (kw 1 at 1e-13: an error of 9.7e-12 against
    a sample u of 9.3e-12 is round-off of both)."""
    fine, other = reference_solutions(kw, eps)
    s = mp.solve(vstar=_vstar(kw, eps), kw=kw, tol=tol, **_params(kw))
    assert s.valid
    check_honest(s, fine.a, abs(fine.a - other.a), resolution=fine.error_estimate)


@pytest.mark.parametrize(("kw", "eps"), NEAR_CASES)
@pytest.mark.parametrize("tol", [1e-4, 1e-6])
def test_error_estimate_is_honest_near_critical_at_loose_tol(
    kw: float, eps: float, tol: float
) -> None:
    """The same at a loose tol, down to 1e-14 of V*_cr. (a/h is never
    solved looser than 1e-8: a ladder stopped at N = 16 or 24 there gave
    estimates 100 ... 230 times a lucky error, the kernel's round-off moving
    a/h by 1e-9 ... 5e-8 from one table to the next.) An error measured below
    the reference's own bound (its round-off, ~5e-10 at eps <= 1e-12, where
    the sample ``u`` between the two references can be 1e-10) is not
    resolved: the factor-100 check's floor includes that bound."""
    fine, other = reference_solutions(kw, eps)
    s = mp.solve(vstar=_vstar(kw, eps), kw=kw, tol=tol, **_params(kw))
    assert s.valid
    check_honest(s, fine.a, abs(fine.a - other.a), resolution=fine.error_estimate)


@near_group(1.0, 1e-12)
def test_estimate_at_the_issues_case_is_no_longer_absurd() -> None:
    """kw = 1 within 1e-12 of V*_cr: the estimate was 4.8e2 (a/h ~ 1.23)."""
    s = mp.solve(vstar=_vstar(1.0, 1e-12), kw=1.0, **PAPER)
    ref, u = reference(1.0, 1e-12)
    assert abs(s.a - ref) < 1e-9
    assert s.error_estimate < 1e-8 * s.a
    assert s.stress_error_estimate < 1e-4
    assert s.warnings == ()
    check_honest(s, ref, u)


AWAY = [
    {"vstar": 0.0, "kw": INF},
    {"vstar": 0.2, "kw": 1.0},  # the paper's Fig. 4
    {"vstar": 0.5, "kw": 10.0},
    {"vstar": 0.7, "kw": INF, "nu": 0.3},
]


@functools.cache
def away_reference(key: tuple[tuple[str, float], ...]) -> tuple[mp.Solution, ...]:
    """As reference_solutions, for a case away from V*_cr given as items."""
    case = dict(key)
    params = {**PAPER, **case}
    fine = mp.solve(**params, n=256, tol=1e-14)
    other = mp.solve(**params, n=192, tol=1e-12)
    return fine, other


@pytest.mark.parametrize("case", AWAY)
def test_error_estimate_is_honest_away_from_critical(case: dict[str, float]) -> None:
    fine, other = away_reference(tuple(case.items()))
    u = abs(fine.a - other.a)
    for tol in (1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12):
        check_honest(mp.solve(**case, **PAPER, tol=tol), fine.a, u)


@pytest.mark.parametrize("kw", [0.1, 1.0, 10.0])
@pytest.mark.parametrize("fraction", [0.0, 0.3, 0.7, 0.95])
@pytest.mark.parametrize("tol", [1e-3, 1e-4, 1e-6])
def test_error_estimate_is_honest_at_loose_tol(
    kw: float, fraction: float, tol: float
) -> None:
    """At a loose tol the estimate once exceeded the error 1e2 ... 1e4 times
    (a kernel built to 1e-2 tol, whose QUADPACK and Chebyshev-tail estimates
    overstate what it delivers; an N error read from two sizes only). The
    kernel is now never looser than 1e-10, and N is refined over three sizes
    unless the change is at round-off."""
    v = mp.critical_vstar(kw) * fraction
    fine, other = away_reference((("vstar", v), ("kw", kw), *_loads(kw)))
    s = mp.solve(vstar=v, kw=kw, tol=tol, **_params(kw))
    check_honest(s, fine.a, abs(fine.a - other.a))


def _loads(kw: float) -> tuple[tuple[str, float], ...]:
    """CASES' load overrides for kw as items (away_reference adds PAPER)."""
    return tuple(CASES.get(kw, {}).items())


def test_budget_parts_add_up_to_the_estimate() -> None:
    s = mp.solve(vstar=0.2, kw=1.0, **PAPER)
    parts = s._impl.error_budget
    assert set(parts) == {"collocation", "root", "kernel", "roundoff"}
    assert sum(parts.values()) == pytest.approx(s.error_estimate, rel=1e-15)
    assert all(v >= 0.0 for v in parts.values())


# ----------------------------------------------------------------------------
# The stress error estimate
# ----------------------------------------------------------------------------

# Surface points in units of the reference's a: on and off the contact, down
# to 1e-3 a from its edge (sigma_x has a square-root cusp at the edge).
SURFACE = np.array([0.0, 0.25, 0.5, 0.75, 0.9, 0.99, 0.999])
SURFACE = np.concatenate([SURFACE, [1.001, 1.01, 1.1, 1.5, 2.0, 3.0, 5.0]])


_STRESS_VALUES: dict[tuple[object, ...], npt.NDArray[np.float64]] = {}


def stress_values(s: mp.Solution, ref: mp.Solution) -> npt.NDArray[np.float64]:
    """stress_values_of, computed once per solution content: a/h is never
    solved looser than 1e-8, so the solutions at tol 1e-3 ... 1e-8 of a case
    are bit for bit one solution, and its peak search (seconds near V*_cr)
    need not run four times. The key is everything the values depend on:
    the inputs, N, a/h, the coefficients (bit for bit) and the stress
    estimate (the peak search's tolerance); the reference is kept alive by
    its cache, so its id is not reused."""
    key = (
        id(ref),
        s.kw,
        s.vstar,
        s.nu,
        s.kp,
        s.radius,
        s.load,
        s.collocation_n,
        s.a,
        np.asarray(s.g_coefficients, dtype=np.float64).tobytes(),
        s.stress_error_estimate,
    )
    if key not in _STRESS_VALUES:
        _STRESS_VALUES[key] = stress_values_of(s, ref)
    return _STRESS_VALUES[key].copy()


def stress_values_of(s: mp.Solution, ref: mp.Solution) -> npt.NDArray[np.float64]:
    """The stress_peaks values of ``s`` (most compressive and most tensile on
    the top, most tensile on the bottom, at (0, 0) and (0, -h)) and its
    surface sigma_x/(P/h) at SURFACE times the reference's a.

    (The peak search's own miss is in the reference's uncertainty: at
    kw = 0.1 within 1e-4 of V*_cr a grid step moves the top tensile peak and
    its value by 1e-3 between the N = 256 and N = 192 references, which leaves
    those cases only the bound to check.)
    """
    p = s.stress_peaks()
    peaks = [p.top_compressive, p.top_tensile, p.bottom_tensile]
    peaks += [p.centre_top, p.centre_bottom]
    surface = np.asarray(s.surface_stress(ref.a * SURFACE))
    return np.concatenate([peaks, surface])


_REFERENCE_STRESSES: dict[int, tuple[npt.NDArray[np.float64], float]] = {}


def reference_stresses(
    fine: mp.Solution, other: mp.Solution
) -> tuple[npt.NDArray[np.float64], float]:
    """stress_values of the reference and their uncertainty (its difference
    from the other reference), computed once per reference: the peak search
    on an N = 256 solution near V*_cr takes seconds."""
    key = id(fine)
    if key not in _REFERENCE_STRESSES:
        ref = stress_values(fine, fine)
        u = float(np.max(np.abs(stress_values(other, fine) - ref)))
        _REFERENCE_STRESSES[key] = (ref, u)
    return _REFERENCE_STRESSES[key]


def check_stress_honest(s: mp.Solution, fine: mp.Solution, other: mp.Solution) -> None:
    """As check_honest, for stress_error_estimate; the floor is 64 eps
    times the largest |sigma_x|, the round-off scale of the stresses."""
    ref, u = reference_stresses(fine, other)
    actual = float(np.max(np.abs(stress_values(s, fine) - ref)))
    est = s.stress_error_estimate
    where = (s.kw, s.vstar, s.tol, s.collocation_n, actual, u, est, s.warnings)
    assert est >= actual - u, where
    if not s.warnings:
        floor = max(actual, u, 64.0 * EPS * float(np.max(np.abs(ref))))
        assert est <= FACTOR * floor, where


@pytest.mark.parametrize(("kw", "eps"), NEAR_CASES)
@pytest.mark.parametrize("tol", [1e-8, 1e-10])
def test_stress_error_estimate_is_honest_near_critical(
    kw: float, eps: float, tol: float
) -> None:
    """sigma_x's estimate bounds its error against the N = 256 reference and
    is at most 100 times it (or the reference's uncertainty) unless a warning
    says tol was not met (issue 12)."""
    fine, other = reference_solutions(kw, eps)
    s = mp.solve(vstar=_vstar(kw, eps), kw=kw, tol=tol, **_params(kw))
    assert s.valid
    check_stress_honest(s, fine, other)


@pytest.mark.parametrize(("kw", "eps"), NEAR_CASES)
@pytest.mark.parametrize("tol", [1e-3, 1e-4, 1e-6])
def test_stress_error_estimate_is_honest_near_critical_at_loose_tol(
    kw: float, eps: float, tol: float
) -> None:
    """The same at a loose tol (an a-priori kernel term once made it up to
    6e7 times the actual error there)."""
    fine, other = reference_solutions(kw, eps)
    s = mp.solve(vstar=_vstar(kw, eps), kw=kw, tol=tol, **_params(kw))
    assert s.valid
    check_stress_honest(s, fine, other)


@pytest.mark.parametrize("case", AWAY)
def test_stress_error_estimate_is_honest_away_from_critical(
    case: dict[str, float],
) -> None:
    """The same at tol 1e-3 ... 1e-12 away from V*_cr (it was 1400 times the
    actual error at the paper's Fig. 4 case, and up to 6e7 times at tol 1e-3
    with the a-priori kernel term once kept above tol 1e-7)."""
    fine, other = away_reference(tuple(case.items()))
    for tol in (1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12):
        check_stress_honest(mp.solve(**case, **PAPER, tol=tol), fine, other)


# ----------------------------------------------------------------------------
# Warnings
# ----------------------------------------------------------------------------


def test_no_warning_when_tol_is_met() -> None:
    s = mp.solve(vstar=0.2, kw=1.0, **PAPER)
    assert s.warnings == ()
    assert s.to_dict()["warnings"] == []


@near_group(1.0, 1e-4)
def test_a_fixed_size_too_small_for_tol_warns_by_how_much() -> None:
    ref, _ = reference(1.0, 1e-4)
    s = mp.solve(vstar=_vstar(1.0, 1e-4), kw=1.0, **PAPER, n=8, tol=1e-10)
    actual = abs(s.a - ref)
    assert actual > 1e-10 * s.a  # tol is truly not met at N = 8
    assert s.error_estimate >= actual
    (line,) = s.warnings
    assert "tol not met" in line
    assert "N = 8" in line
    assert "1e-10" in line
    assert "\n" not in line
    assert s.to_dict()["warnings"] == [line]


@near_group(1.0, 1e-14)
def test_tight_tol_within_1e_14_of_critical_warns() -> None:
    """Round-off of the resonance limits a/h to ~1e-9 there: tol = 1e-12 is
    not met, and the result says so (and its estimate still bounds the error)."""
    ref, u = reference(1.0, 1e-14)
    s = mp.solve(vstar=_vstar(1.0, 1e-14), kw=1.0, **PAPER, tol=1e-12)
    assert s.warnings
    assert "kernel" in s.warnings[0]
    assert s.error_estimate >= abs(s.a - ref) - u


BASE_ARGS = ["--radius", "100", "--load", "0.002"]
WARN_ARGS = ["--vstar", repr(_vstar(1.0, 1e-14)), "--kw", "1", "--tol", "1e-12"]
WARN_ARGS += BASE_ARGS


def test_cli_solve_shows_every_warning(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    expected = mp.solve(vstar=_vstar(1.0, 1e-14), kw=1.0, **PAPER, tol=1e-12).warnings
    assert expected
    table = run_cli("solve", *WARN_ARGS)
    assert table.returncode == 0, table.stderr
    shown = [ln for ln in table.stderr.splitlines() if ln.startswith("warning: ")]
    assert shown == [f"warning: {w}" for w in expected]
    assert "pressure margin" in table.stdout
    doc = run_cli("solve", *WARN_ARGS, "--json")
    assert doc.returncode == 0, doc.stderr
    data = json.loads(doc.stdout)
    assert data["warnings"] == list(expected)
    assert data["pressure_margin"] > 0.0
    quiet = run_cli("solve", "--vstar", "0.2", "--kw", "1", *BASE_ARGS)
    assert quiet.returncode == 0
    assert "warning" not in quiet.stderr


SCENE = f"""
name = "warned"
[params]
vstar = {_vstar(1.0, 1e-14)!r}
kw = 1.0
radius = 100.0
load = 0.002
nu = 0.2
[accuracy]
tol = 1e-12
[outputs]
contact_width = true
"""


def test_scene_records_and_prints_every_warning(tmp_path: object) -> None:
    from pathlib import Path

    from movingpunch.scene import format_summary, read_csv, write_outputs

    scene = Scene.from_toml(SCENE, "test")
    result = scene.run()
    assert len(result.warnings) == 1
    assert result.warnings[0].startswith("vstar=")
    assert "tol not met" in result.warnings[0]
    text = format_summary(result)
    assert f"warning: {result.warnings[0]}" in text
    (path,) = write_outputs(result, Path(str(tmp_path)), "csv")
    meta, _ = read_csv(path)
    assert meta["warnings"] == result.warnings[0]
    quiet = Scene.bundled("fig4").run()
    assert quiet.warnings == ()
    assert "Warnings" not in format_summary(quiet)


# ----------------------------------------------------------------------------
# Continuity down to subnormal speeds
# ----------------------------------------------------------------------------

TINY = [5e-324, 1e-323, 1e-320, 1e-310, 2.2250738585072014e-308, 1e-300]
TINY += [10.0**k for k in range(-290, -9, 20)] + [1e-10]


@pytest.mark.parametrize("kw", [0.1, 1.0, INF])
def test_width_is_continuous_down_to_subnormal_speeds(kw: float) -> None:
    """|a(vstar) - a(0)| <= tol a for 0 <= vstar <= 1e-10 (a moves by about
    1e-11 relative per 1e-10 of vstar, so tol = 1e-8 covers the slope)."""
    tol = 1e-8
    a0 = mp.solve(vstar=0.0, kw=kw, **PAPER, tol=tol).a
    for v in TINY:
        s = mp.solve(vstar=v, kw=kw, **PAPER, tol=tol)
        assert abs(s.a - a0) <= tol * a0, (v, s.a, a0)
        assert s.warnings == ()
    # Below 1e-300 every vstar-dependent term is far below round-off: a/h is
    # the static one to the last bits (it was 1e-6 off at 1e-320).
    for v in TINY[:6]:
        assert mp.solve(vstar=v, kw=kw, **PAPER, tol=tol).a == pytest.approx(
            a0, rel=4 * EPS
        )


# ----------------------------------------------------------------------------
# Pressure margin
# ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "case",
    [
        {"vstar": 0.2, "kw": 1.0, **PAPER},
        {"vstar": 0.0, "kw": INF, **PAPER},
        {"vstar": 0.2, "kw": 0.1, **PAPER},
        {"vstar": _vstar(0.1, 1e-8), "kw": 0.1, "radius": 100.0, "load": 0.02},
    ],
)
def test_pressure_margin_matches_a_dense_evaluation(case: dict[str, float]) -> None:
    """Against p(x)/sqrt(1 - (x/a)^2) through the public pressure(), on
    200001 points of the open contact, cosine-spaced to within 5e-7 of its
    ends (an independent evaluation; the minimum can sit at an end, where
    x = a r rounds (1 - r) by ~1e-16/(1 - r) relative)."""
    s = mp.solve(**case)
    r = np.cos(np.linspace(1e-3, math.pi - 1e-3, 200001))
    dense = np.asarray(s.pressure(s.a * r)) / np.sqrt((1.0 - r) * (1.0 + r))
    assert s.pressure_margin <= dense.min() + 1e-9 * abs(dense.min())
    assert s.pressure_margin == pytest.approx(dense.min(), rel=1e-5, abs=1e-12)
    assert s.to_dict()["pressure_margin"] == s.pressure_margin
    # min_pressure, at the ends, says nothing: the margin is what is left.
    assert s.min_pressure == pytest.approx(0.0, abs=1e-12)


def test_pressure_margin_is_negative_where_the_contact_separates() -> None:
    kw = 0.1
    s = mp.solve(vstar=_vstar(kw, 1e-8), kw=kw, **PAPER, allow_unphysical=True)
    assert not s.valid
    assert s.pressure_margin < 0.0


def test_pressure_margin_in_the_half_plane_limit() -> None:
    """Hertz: p = (2P/(pi a^2)) sqrt(a^2 - x^2), so p/sqrt(1 - r^2) = 2/(pi a)
    in units of P/h with a in units of h."""
    s = mp.solve(vstar=0.3, kw=INF, radius=1.0, load=1e-7)
    assert s.a < 1e-3
    assert s.pressure_margin == pytest.approx(2.0 / (math.pi * s.a), rel=2e-3)


# ----------------------------------------------------------------------------
# The terminal UI's status line
# ----------------------------------------------------------------------------


def test_tui_status_line_shows_every_warning() -> None:
    from movingpunch.tui.app import create_app
    from tui_pilot import settle, status_text, sync, type_into

    @sync
    async def run() -> None:
        app = create_app()
        async with app.run_test(size=(100, 32)) as pilot:
            await settle(pilot)
            assert "warning" not in status_text(app)
            await type_into(pilot, "tol", "1e-12", paste=True)
            await type_into(pilot, "vstar", repr(_vstar(1.0, 1e-14)), paste=True)
            expected = mp.solve(
                vstar=_vstar(1.0, 1e-14), kw=1.0, **PAPER, tol=1e-12
            ).warnings
            assert expected
            text = status_text(app)
            for line in expected:
                assert f"warning: {line}" in text
            await type_into(pilot, "vstar", "0.2", paste=True)
            assert "warning" not in status_text(app)

    run()
