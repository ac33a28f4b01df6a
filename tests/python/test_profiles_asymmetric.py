"""Punch profiles on the asymmetric solver (issue 14): a rounded flat or a
table with damping and/or Coulomb friction, and asymmetric tables
(docs/theory.md section 13, "Profiles on the asymmetric solver").

Every anchor is independent of the code path under test:

* translation invariance: a tabulated parabola shifted by x0 is the cylinder
  of the undamped (symmetric, separately written) solver moved by x0;
* the damping -> 0 limit: the undamped solver's rounded flat and table;
* a tabulated parabola with damping and/or friction is the cylinder on the
  asymmetric solver's own cylinder path (no projection, no centre root);
* the energy balance: the drag of a damped profile equals the dashpots'
  dissipation (Parseval on the bottom face's response: a conservation law);
* the rigid punch: the surface follows the profile on the contact (the
  displacement machinery against the profile's own heights);
* a frictional, damped asymmetric case against a Gauss-Jacobi collocation
  written from scratch (SciPy's roots_jacobi, CubicSpline and brentq, the
  layer from numpy eigenvectors: tests/python/test_friction.py).
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

import movingpunch as mp
from movingpunch import _core
from movingpunch.asymmetric import AsymmetricSolution
from movingpunch.errors import InvalidParameterError
from test_friction import _independent_rule

BASE = {"vstar": 0.2, "kw": 1.0, "load": 0.002}
R = 100.0


def _parabola(x0: float = 0.0, lo: float = -1.5, hi: float = 2.5) -> mp.Profile:
    xs = np.linspace(lo, hi, 801)
    return mp.Profile(tuple(xs), tuple((xs - x0) ** 2 / (2 * R)))


# ---------------------------------------------------------------------------
# Asymmetric tables


def test_an_asymmetric_table_is_accepted_and_routed_to_the_asymmetric_solver() -> None:
    prof = _parabola(0.3)
    assert not prof.symmetric
    assert "asymmetric" in prof.describe()
    s = mp.solve(**BASE, profile=prof)
    assert isinstance(s, AsymmetricSolution)
    assert s.damping == 0.0
    assert s.friction == 0.0
    assert s.profile == prof
    assert math.isinf(s.radius)  # a table has no radius
    # The undamped (symmetric) solver itself refuses it, naming the table.
    with pytest.raises(InvalidParameterError) as info:
        _core.solve_contact(
            **BASE, radius=1.0, nu=0.2, tol=1e-8, allow_unphysical=False,
            **{k: v for k, v in prof.core_args().items() if k != "radius"},
        )  # fmt: skip
    assert info.value.parameter in ("profile.x", "profile.y")
    assert "asymmetric solver" in str(info.value)


@pytest.mark.parametrize("x0", [0.3, -0.45])
def test_a_shifted_parabola_is_the_undamped_cylinder_moved(x0: float) -> None:
    """Translation invariance: f = (x - x0)^2/2R on the asymmetric solver
    equals the undamped solver's cylinder shifted by x0: ends, pressure,
    surface stress and indentation (delta_cyl - x0^2/2R: heights count from
    x = 0)."""
    u = mp.solve(**BASE, radius=R)
    s = mp.solve(**BASE, profile=_parabola(x0))
    assert s.contact_interval == pytest.approx((x0 - u.a, x0 + u.a), abs=1e-12)
    assert s.error_estimate >= 0.0
    x = x0 + np.linspace(-0.95, 0.95, 9) * u.a
    np.testing.assert_allclose(s.pressure(x), u.pressure(x - x0), rtol=0, atol=1e-10)
    np.testing.assert_allclose(
        s.surface_stress(x), u.surface_stress(x - x0), rtol=0, atol=1e-9
    )
    assert s.indentation == pytest.approx(u.indentation - x0 * x0 / (2 * R), rel=1e-10)
    assert abs(s.drag) < 1e-14
    assert s.valid


# ---------------------------------------------------------------------------
# The damping -> 0 limit: the undamped solver's profiles


@pytest.mark.parametrize(
    "prof",
    [
        mp.RoundedFlat(0.3, 100.0),
        mp.RoundedFlat(0.05, 5.0),
        mp.Profile.from_function(lambda x: x**4 / 4 + x**2 / 300, 1.2, 1201),
    ],
    ids=["rounded-flat", "rounded-flat-sharp", "table-quartic"],
)
def test_vanishing_damping_gives_the_undamped_profile(prof: mp.PunchProfile) -> None:
    """damping 1e-9: the asymmetric solver's ends, pressure and indentation
    equal the undamped (symmetric) solver's to the first-order change
    (~1e-9 relative), which is odd in x."""
    u = mp.solve(**BASE, profile=prof)
    d = mp.solve(**BASE, profile=prof, damping=1e-9)
    assert d.contact_interval == pytest.approx((-u.a, u.a), rel=1e-8)
    x = np.linspace(-0.95, 0.95, 11) * u.a
    scale = u.p0
    # Both pressures carry their own series truncation near the corners.
    tol = 1e-7 * scale + 2.0 * (d._impl.series_truncation + u._impl.series_truncation)
    assert np.max(np.abs(d.pressure(x) - u.pressure(x))) < tol
    assert d.indentation == pytest.approx(u.indentation, rel=1e-8)
    assert abs(d.drag) < 1e-8 * u.a / R + 1e-12


# ---------------------------------------------------------------------------
# A tabulated parabola is the cylinder, with damping and/or friction


@pytest.mark.parametrize(
    "extra",
    [{"damping": 0.5}, {"friction": 0.3}, {"friction": 0.3, "damping": 0.5}],
    ids=["damped", "friction", "both"],
)
def test_a_tabulated_parabola_is_the_asymmetric_cylinder(
    extra: dict[str, float],
) -> None:
    """The table path (projected slope, the centre by its own root) against
    the cylinder's path (the centre absorbed by the constant unknown)."""
    c = mp.solve(**BASE, radius=R, **extra)
    t = mp.solve(**BASE, profile=_parabola(), **extra)
    assert t.contact_interval == pytest.approx(c.contact_interval, abs=1e-11)
    assert t.drag == pytest.approx(c.drag, rel=1e-8, abs=1e-15)
    assert t.end_exponents == c.end_exponents
    x = np.linspace(*c.contact_interval, 9)[1:-1]
    np.testing.assert_allclose(t.pressure(x), c.pressure(x), rtol=0, atol=1e-9)
    assert t.indentation == pytest.approx(c.indentation, rel=1e-9)
    # Shifted by x0, everything moves with it (friction and damping too).
    x0 = 0.2
    s = mp.solve(**BASE, profile=_parabola(x0), **extra)
    assert s.contact_interval == pytest.approx(
        (c.contact_interval[0] + x0, c.contact_interval[1] + x0), abs=1e-11
    )


# ---------------------------------------------------------------------------
# Conservation laws and the rigid punch


@pytest.mark.parametrize(
    "prof",
    [mp.RoundedFlat(0.3, 100.0), _parabola(0.25), mp.RoundedFlat(0.5, 2.0)],
    ids=["rounded-flat", "shifted-table", "rounded-flat-tight"],
)
def test_a_damped_profiles_drag_is_its_dissipation(prof: mp.PunchProfile) -> None:
    """Energy balance: drag P V (from the pressure and the profile's slope)
    equals the dashpots' power (Parseval on the bottom face's response,
    computed independently of the drag)."""
    s = mp.solve(**BASE, profile=prof, damping=0.5)
    assert s.drag > 0
    assert s.dissipation == pytest.approx(s.drag, rel=1e-8)


@pytest.mark.parametrize(
    "extra",
    [{"damping": 0.5}, {"friction": 0.3}, {"friction": 0.5, "damping": 0.2}],
    ids=["damped", "friction", "both"],
)
def test_the_surface_follows_the_rounded_flat_on_the_contact(
    extra: dict[str, float],
) -> None:
    """The punch is rigid: v(x, 0) = f(x) - delta on the contact (f the
    profile's height), equilibrium int p = P, no penetration beside it."""
    prof = mp.RoundedFlat(0.3, 20.0)
    s = mp.solve(**BASE, profile=prof, **extra)
    lo, hi = s.contact_interval
    assert lo < -0.3  # both corners carry load
    assert hi > 0.3
    x = np.linspace(lo, hi, 41)[1:-1]
    gap = prof.height(x) - s.indentation - s.surface_displacement(x)
    assert np.max(np.abs(gap)) < 1e-7 * s.indentation
    # int p dx with x = (lo + hi)/2 - (hi - lo) cos(th)/2 (the ends' cusps
    # smoothed), by the midpoint rule on 200000 angles (the kinks: O(h^2)).
    th = (np.arange(200000) + 0.5) * math.pi / 200000
    xm = 0.5 * (lo + hi) - 0.5 * (hi - lo) * np.cos(th)
    total = (
        float(np.sum(s.pressure(xm) * np.sin(th))) * 0.5 * (hi - lo) * math.pi / 200000
    )
    assert total == pytest.approx(1.0, abs=1e-8)
    assert s.valid
    assert s.min_gap >= 0.0
    assert s.tangential_force == extra.get("friction", 0.0)


def test_a_vanishing_face_tends_to_the_cylinder_with_friction() -> None:
    """RoundedFlat(b -> 0, R) -> Cylinder(R), linearly in b (damped and
    frictional)."""
    extra = {"friction": 0.3, "damping": 0.2}
    c = np.array(mp.solve(**BASE, radius=R, **extra).contact_interval)
    diffs = []
    for b in (1e-4, 1e-5, 1e-6):
        s = mp.solve(**BASE, profile=mp.RoundedFlat(b, R), **extra)
        diffs.append(np.max(np.abs(np.array(s.contact_interval) - c)))
    assert diffs[2] < 1e-5
    assert diffs[0] / diffs[1] == pytest.approx(10.0, rel=0.2)
    assert diffs[1] / diffs[2] == pytest.approx(10.0, rel=0.2)


# ---------------------------------------------------------------------------
# An independent collocation of a frictional, damped, asymmetric profile


def _independent_profile_ends(
    s: float,
    kw: float,
    nu: float,
    damping: float,
    f: float,
    slope: object,
    load: float,
    n: int,
) -> tuple[float, float]:
    """(-b, a) of a plain Gauss-Jacobi collocation (point values of the
    slope, no projection) of
    f Phi p + (1/pi) int p/(xi - x) - int p Lr(x - xi)/phi1 = -f'(x)/(P phi1),
    the centre from the consistency condition (brentq) per width and the
    width from equilibrium (brentq)."""
    phi1, _, _, r, w, sk, alpha, weight, g = _independent_rule(s, kw, nu, damping, f, n)

    def solve_at(width: float) -> tuple[float, float]:
        u = width * (sk[:, None] - r[None, :])
        kern = (np.exp(1j * np.multiply.outer(u, alpha)) @ (weight * g)).real / phi1
        m = np.zeros((n + 1, n + 1))
        m[:, :n] = (w / math.pi)[None, :] * (
            1 / (r[None, :] - sk[:, None]) - width * kern
        )
        m[:, n] = 1

        def gamma(c: float) -> float:
            return float(np.linalg.solve(m, slope(c + width * sk))[n])  # type: ignore[operator]

        c = brentq(gamma, -1.0, 1.0, xtol=1e-16, rtol=1e-15)
        sol = np.linalg.solve(m, slope(c + width * sk))  # type: ignore[operator]
        return -width * float(w @ sol[:n]) / phi1, c

    lw = brentq(
        lambda v: math.log(solve_at(math.exp(v))[0] / load),
        math.log(0.1),
        math.log(1.5),
        xtol=1e-15,
        rtol=1e-15,
    )
    width = math.exp(lw)
    centre = solve_at(width)[1]
    return centre - width, centre + width


def test_frictional_damped_asymmetric_profile_matches_independent_collocation() -> None:
    """A non-parabolic asymmetric table, f = (cosh(k (x - x0)) - 1)/(k^2 R),
    with friction and damping: the contact ends to 1e-8 against a collocation
    written from scratch (same not-a-knot spline through the table, by
    SciPy's CubicSpline)."""
    k, x0, radius = 2.0, 0.15, 40.0
    xs = np.linspace(-1.6, 2.0, 2001)
    ys = (np.cosh(k * (xs - x0)) - 1) / (k * k * radius)
    prof = mp.Profile(tuple(xs), tuple(ys))
    spline = CubicSpline(xs, ys, bc_type="not-a-knot").derivative()
    extra = {"friction": 0.4, "damping": 0.3}
    s = mp.solve(vstar=0.3, kw=1.0, load=0.004, nu=0.2, profile=prof, **extra)
    ends = _independent_profile_ends(0.3, 1.0, 0.2, 0.3, 0.4, spline, 0.004, 48)
    assert s.contact_interval == pytest.approx(ends, abs=1e-8)
    assert s.error_estimate < 1e-8


# ---------------------------------------------------------------------------
# Error estimates, refusals


@pytest.mark.parametrize(
    ("prof", "extra"),
    [
        (mp.RoundedFlat(0.3, 50.0), {"damping": 0.5}),
        (_parabola(0.2), {"friction": 0.3}),
        (mp.RoundedFlat(0.2, 20.0), {"friction": 0.3, "damping": 0.3}),
    ],
    ids=["rounded-flat-damped", "table-friction", "rounded-flat-both"],
)
@pytest.mark.parametrize("n", [8, 12])
def test_the_ends_estimate_bounds_the_error(
    prof: mp.PunchProfile, extra: dict[str, float], n: int
) -> None:
    """At a fixed small n the estimate bounds the ends' actual error against
    an n = 96 reference."""
    ref = np.array(mp.solve(**BASE, profile=prof, n=96, **extra).contact_interval)
    s = mp.solve(**BASE, profile=prof, n=n, allow_unphysical=True, **extra)
    err = np.max(np.abs(np.array(s.contact_interval) - ref))
    assert s.error_estimate >= err
    auto = mp.solve(**BASE, profile=prof, **extra)
    assert np.max(np.abs(np.array(auto.contact_interval) - ref)) <= max(
        auto.error_estimate, 1e-13
    )


def test_a_contact_wider_than_an_asymmetric_table_is_refused() -> None:
    xs = np.linspace(-0.2, 0.4, 61)
    prof = mp.Profile(tuple(xs), tuple((xs - 0.1) ** 2 / 2))
    with pytest.raises(InvalidParameterError) as info:
        mp.solve(vstar=0.2, kw=1.0, load=1.0, profile=prof, damping=0.5)
    assert "table" in str(info.value)


# ---------------------------------------------------------------------------
# Everywhere: the CLI and scenes


def test_the_issues_cli_command_solves_a_frictional_flat_punch_on_pasternak(
    run_cli: Any,
) -> None:
    """`solve --profile flat --half-width 0.5 --friction 0.3 --kp 0.2`: the
    numbers are the API's (JSON), both end coefficients shown."""
    args = ["solve", "--vstar", "0.2", "--kw", "1", "--load", "0.002"]
    args += ["--profile", "flat", "--half-width", "0.5", "--friction", "0.3"]
    args += ["--kp", "0.2"]
    out = run_cli(*args, "--json")
    assert out.returncode == 0, out.stderr
    got = json.loads(out.stdout)
    s = mp.solve(
        vstar=0.2, kw=1.0, load=0.002, kp=0.2, friction=0.3, profile=mp.Flat(0.5)
    )
    assert got["end_coefficients"] == pytest.approx(list(s.end_coefficients), rel=1e-12)
    assert got["contact_interval"] == pytest.approx([-0.5, 0.5], abs=0)
    text = run_cli(*args)
    assert text.returncode == 0, text.stderr
    assert "K_back, K_front" in text.stdout
    # The stress section's search range is |x| <= extent on the asymmetric
    # solver (both sides searched).
    base = ["solve", "--vstar", "0.2", "--kw", "1", "--load", "0.002"]
    stress = run_cli(*base, "--profile", "rounded_flat", "--half-width", "0.3",
                     "--radius", "100", "--damping", "0.5", "--stress")  # fmt: skip
    assert stress.returncode == 0, stress.stderr
    assert "searched on |x|/h <=" in stress.stdout


def test_a_scene_with_a_rounded_flat_damping_and_friction(tmp_path: Any) -> None:
    """A scene file's [params.profile] with damping and friction runs on the
    asymmetric solver and writes the API's pressure."""
    from movingpunch.scene import load_scene
    from movingpunch.scene._run import run_scene

    path = tmp_path / "rf.toml"
    path.write_text(
        'name = "rf"\n[params]\nvstar = 0.2\nkw = 1.0\nload = 0.002\n'
        "damping = 0.5\nfriction = 0.3\n"
        '[params.profile]\nkind = "rounded_flat"\nhalf_width = 0.3\nradius = 100.0\n'
        "[outputs]\ncontact_width = true\npressure = { x = [-0.7, 0.7], points = 15 }\n"
    )
    scene = load_scene(path)
    assert scene.profile == mp.RoundedFlat(0.3, 100.0)
    result = run_scene(scene)
    s = mp.solve(
        vstar=0.2, kw=1.0, load=0.002, damping=0.5, friction=0.3,
        profile=mp.RoundedFlat(0.3, 100.0),
    )  # fmt: skip
    (curve,) = result.outputs["pressure"].curves
    np.testing.assert_allclose(curve.y, s.pressure(curve.x), rtol=0, atol=1e-12)
    assert isinstance(result.solutions[0], AsymmetricSolution)
    assert result.solutions[0].contact_interval == s.contact_interval


@pytest.mark.parametrize(
    ("prof", "extra"),
    [
        (mp.RoundedFlat(0.3, 100.0), {"damping": 0.5}),
        (_parabola(0.2), {"friction": 0.3}),
    ],
    ids=["rounded-flat-damped", "asymmetric-table-friction"],
)
def test_a_load_sweep_gives_the_same_contacts_in_both_directions(
    prof: mp.PunchProfile, extra: dict[str, float]
) -> None:
    """Rising and falling loads (each from an empty kernel cache: the tables
    and first guesses differ) give the same contacts to round-off."""
    loads = np.geomspace(1e-3, 4e-3, 5)

    def sweep(order: np.ndarray) -> dict[float, tuple[float, float]]:
        mp.clear_kernel_cache()
        return {
            float(x): mp.solve(
                **BASE | {"load": float(x)}, profile=prof, **extra
            ).contact_interval
            for x in order
        }

    up, down = sweep(loads), sweep(loads[::-1])
    for x in up:
        assert up[x] == pytest.approx(down[x], abs=1e-13)


@pytest.mark.parametrize(
    "extra", [{"damping": 0.5}, {"friction": 0.3}], ids=["damped", "friction"]
)
def test_max_pressure_is_the_pressures_largest_value(extra: dict[str, float]) -> None:
    """A rounded flat's max_pressure is the largest value of its (4096- or
    1024-term) pressure, sampled independently on 200001 points (it once
    added the tail's sum |b_n|: 0.7 % high)."""
    s = mp.solve(**BASE, profile=mp.RoundedFlat(0.3, 100.0), **extra)
    x = np.linspace(*s.contact_interval, 200001)[1:-1]
    assert s.max_pressure == pytest.approx(float(np.max(s.pressure(x))), rel=1e-7)


def test_the_load_curve_scan_is_kept_per_shape() -> None:
    """Above V*_cr a load can be carried by several contacts; the scan of the
    load curve lambda(w) that finds them is kept per kernel table and shape
    (it does not depend on the load). Kept values must give what a fresh
    scan gives, and one shape's values must never answer for another's."""
    soft = {"vstar": 0.65, "kw": 1.0, "damping": 0.01, "nu": 0.2}
    several = {"profile": mp.RoundedFlat(0.1, 50.0), "load": 0.003}

    def fresh(**kw: Any) -> Any:
        mp.clear_kernel_cache()  # the kept scans go with their tables
        return mp.solve(**soft, **kw)

    a = fresh(**several)
    assert len(a.other_half_widths) == 2  # measured: 0.776, 0.890
    b = mp.solve(**soft, **several)  # the kept scan
    assert b.other_half_widths == pytest.approx(a.other_half_widths, rel=1e-12)
    # Other shapes on the same table after it: as fresh.
    for other in (
        {"profile": mp.RoundedFlat(0.1, 100.0), "load": 0.002},
        {"profile": mp.RoundedFlat(0.2, 50.0), "load": 0.003},
        {"radius": 50.0, "load": 0.003},
    ):
        mp.solve(**soft, **several)
        kept = mp.solve(**soft, **other)
        new = fresh(**other)
        assert len(kept.other_half_widths) == len(new.other_half_widths), other
        assert kept.other_half_widths == pytest.approx(new.other_half_widths, rel=1e-9)
