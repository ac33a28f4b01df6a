"""Punch profiles (docs/theory.md section 13) against independent anchors:
closed forms (the flat punch and the rounded flat on a half-plane), limits
(R -> 0, b -> 0, a wide flat punch's long-wave indentation), a plain NumPy
index +1 solve written here, high-N references, and the cylinder itself."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

import movingpunch as mp
from movingpunch import _core

LOAD = 0.002


def flat_closed_form(b: float, x: np.ndarray) -> np.ndarray:
    """p/(P/h) of a flat punch on any frictionless half-plane."""
    return 1.0 / (math.pi * np.sqrt(b * b - x * x))


@pytest.mark.parametrize("kw", [0.1, 1.0, math.inf])
@pytest.mark.parametrize("fraction", [0.0, 0.5, 0.95])
def test_flat_half_plane_limit(kw: float, fraction: float) -> None:
    """b = 1e-4 h: p = P/(pi sqrt(b^2 - x^2)) to 1e-6 at interior points, at
    any speed below V*_cr; the layer's correction is O((b/h)^2) (measured:
    at most 1.9e-7 here, 100 times more at b = 1e-3)."""
    vstar = fraction * mp.critical_vstar(kw)
    gaps = []
    for b in (1e-4, 1e-3):
        s = mp.solve(vstar=vstar, kw=kw, load=LOAD, profile=mp.Flat(b))
        x = b * np.array([0.0, 0.3, -0.6, 0.9, 0.99])
        rel = np.abs(s.pressure(x) / flat_closed_form(b, x) - 1.0)
        gaps.append(float(np.max(rel)))
        # K = lim sqrt(2 pi (b - x)) p = 1/sqrt(pi b) on a half-plane.
        k_back, k_front = s.end_coefficients
        assert k_back == k_front
        assert k_front * math.sqrt(math.pi * b) == pytest.approx(1.0, rel=2e-5)
        assert s.a == b
        assert s.error_estimate == 0.0
        assert s.contact_interval == (-b, b)
        assert math.isinf(s.radius)
        assert s.profile == mp.Flat(b)
    assert gaps[0] < 1e-6
    assert gaps[1] / gaps[0] == pytest.approx(100.0, rel=0.05)  # O(b^2)


def numpy_flat_solve(
    b: float, vstar: float, kw: float, n: int
) -> tuple[np.ndarray, np.ndarray]:
    """An index +1 solve written independently of the core's folded one: the
    full N x N Gauss-Chebyshev (first kind) system, N - 1 collocation points
    and equilibrium, with k1 from the kernel's direct quadrature. Returns
    the Chebyshev-T coefficients of g = p sqrt(1 - r^2)/(P/h) and the nodes."""
    i = np.arange(1, n + 1)
    theta = (2 * i - 1) * math.pi / (2 * n)
    t = np.cos(theta)
    xk = np.cos(np.arange(1, n) * math.pi / n)
    u = b * (t[None, :] - xk[:, None])
    k1 = _core.kernel_k1(u.ravel(), vstar, kw, 0.2, 1e-12, 2.0 * b, True).reshape(
        u.shape
    )
    A = np.vstack(
        [(1.0 / (t[None, :] - xk[:, None]) + b * k1) / n, np.full(n, math.pi * b / n)]
    )
    rhs = np.zeros(n)
    rhs[-1] = 1.0
    g = np.linalg.solve(A, rhs)
    m = np.arange(n)
    c = 2.0 / n * np.cos(np.outer(m, theta)) @ g
    c[0] *= 0.5
    return c, t


@pytest.mark.parametrize(
    ("b", "vstar", "kw"), [(0.5, 0.2, 1.0), (1.5, 0.0, math.inf), (0.8, 0.05, 0.1)]
)
def test_flat_on_the_layer_against_a_numpy_solve(
    b: float, vstar: float, kw: float
) -> None:
    s = mp.solve(
        vstar=vstar,
        kw=kw,
        load=LOAD,
        profile=mp.Flat(b),
        tol=1e-10,
        allow_unphysical=True,  # kw = 0.1: p < 0 mid-face; the numerics hold
    )
    c, _ = numpy_flat_solve(b, vstar, kw, 48)
    g1 = float(np.polynomial.chebyshev.chebval(1.0, c))
    assert s.end_coefficients[1] == pytest.approx(g1 * math.sqrt(math.pi * b), rel=1e-9)
    x = b * np.array([0.0, 0.4, -0.8, 0.97])
    r = x / b
    p_np = np.polynomial.chebyshev.chebval(r, c) / np.sqrt(1.0 - r * r)
    np.testing.assert_allclose(s.pressure(x), p_np, rtol=1e-9)
    # The end coefficient's own estimate bounds its error (N = 48 numpy
    # reference, spectrally converged).
    assert abs(s.end_coefficients[1] - g1 * math.sqrt(math.pi * b)) <= max(
        s.end_coefficient_error, 1e-13
    )


@pytest.mark.parametrize("kw", [1.0, 0.1])
def test_wide_flat_punch_indentation_is_the_long_wave_compliance(kw: float) -> None:
    """b >> h: the face presses P/(2b) almost uniformly, and the layer answers
    long waves with v = -p h (1/kw + (1 - nu)/2)/mu (docs/theory.md §4),
    so delta -> (P/(2b)) (1/kw + (1 - nu)/2); the gap is O(h/b) (halves as
    b doubles: measured -2.1 %, -1.1 % at kw = 1, b = 20, 40)."""
    gaps = []
    for b in (20.0, 40.0):
        s = mp.solve(vstar=0.0, kw=kw, load=LOAD, profile=mp.Flat(b))
        gaps.append(s.indentation / (LOAD / (2 * b) * (1 / kw + 0.4)) - 1.0)
    assert abs(gaps[1]) < 0.03
    assert gaps[0] / gaps[1] == pytest.approx(2.0, rel=0.05)


@pytest.mark.parametrize("kp", [0.0, 0.5])
def test_flat_punch_surface_follows_the_face(kp: float) -> None:
    """The displacement integral (not the collocation's slope condition)
    gives v(x, 0) = -delta all over the face, and the field's displacement
    (a second, closed-form evaluation) agrees with it; on springs alone and
    with a Pasternak layer."""
    s = mp.solve(vstar=0.3, kw=1.0, kp=kp, load=LOAD, profile=mp.Flat(0.6))
    assert s.kp == kp
    x = 0.6 * np.linspace(-0.98, 0.98, 9)
    np.testing.assert_allclose(
        s.surface_displacement(x), -s.indentation, rtol=1e-8, atol=0.0
    )
    xs = np.array([-1.5, -0.6, 0.0, 0.3, 2.0])
    np.testing.assert_allclose(
        s.displacement(xs, 0.0), s.surface_displacement(xs), rtol=1e-9
    )
    # The top face: sigma_y = -p on the face, 0 beside it; the edges are
    # singular and say so.
    field = s.stress_field(np.array([0.0, 0.3, 0.9]), np.array([0.0]))
    np.testing.assert_allclose(
        field.sigma_y[0], [-s.pressure(0.0), -s.pressure(0.3), 0.0], atol=1e-10
    )
    assert s.pressure(0.6) == math.inf
    assert s.surface_stress(0.6) == -math.inf
    assert s.min_gap == math.inf


def test_flat_punch_separation_is_reported() -> None:
    """A wide flat punch on a soft foundation near V*_cr: the pressure goes
    negative on the face (docs/theory.md §8: the bounded solution needs
    int p cos(alpha_c x) ~ 0, which a positive p over a face with
    alpha_c b > pi/2 cannot meet)."""
    kw = 0.01
    vstar = 0.99 * mp.critical_vstar(kw)
    with pytest.raises(mp.UnphysicalContactError, match="negative"):
        mp.solve(vstar=vstar, kw=kw, load=LOAD, profile=mp.Flat(2.0))
    s = mp.solve(
        vstar=vstar, kw=kw, load=LOAD, profile=mp.Flat(2.0), allow_unphysical=True
    )
    assert not s.valid
    assert s.pressure_margin < 0.0
    stiff = mp.solve(vstar=0.0, kw=10.0, load=LOAD, profile=mp.Flat(2.0))
    assert stiff.valid
    assert stiff.pressure_margin > 0.0


def rounded_flat_half_plane(b: float, R: float, a: float, s: np.ndarray) -> np.ndarray:
    """p(a s)/(P/h) of the rounded flat on a half-plane (static, phi1 = 1 - nu):
    the bounded inversion q = sqrt(1 - s^2) (a/R) J(s)/(pi phi1 P),
    J = 2 acos(beta) + (s - beta) K(s) - (s + beta) K(-s),
    K(s) = PV int_beta^1 dt/(sqrt(1 - t^2)(t - s)) in closed form."""
    beta = b / a
    tb = math.acos(beta)

    def K(x: np.ndarray) -> np.ndarray:
        psi = np.arccos(x)
        return np.log(np.abs(np.sin((tb + psi) / 2) / np.sin((tb - psi) / 2))) / np.sin(
            psi
        )

    J = 2 * tb + (s - beta) * K(s) - (s + beta) * K(-s)
    return np.sqrt(1 - s * s) * (a / R) * J / (math.pi * 0.8 * LOAD)


def test_rounded_flat_half_plane_closed_form() -> None:
    """A tiny rounded flat (b = 1e-4 h): a from P = (a^2/(phi1 R))
    (pi/2 - phi0 - sin phi0 cos phi0), sin phi0 = b/a (the half-plane
    consistency condition, independent of the solver), and the pressure
    against the closed form, corners included, within the reported series
    truncation."""
    b, R = 1e-5, 1e-4
    s = mp.solve(vstar=0.0, kw=1.0, load=LOAD, profile=mp.RoundedFlat(b, R))

    def load_of(a: float) -> float:
        phi0 = math.asin(b / a)
        return (
            a * a / (0.8 * R) * (math.pi / 2 - phi0 - math.sin(phi0) * math.cos(phi0))
        )

    lo, hi = b * (1 + 1e-12), 1.0
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if load_of(mid) < LOAD else (lo, mid)
    a_hp = math.sqrt(lo * hi)
    assert s.a == pytest.approx(a_hp, rel=1e-6)  # layer: O((a/h)^2)
    beta = b / s.a
    r = np.array([0.0, 0.3, beta * (1 - 1e-6), beta * (1 + 1e-6), 0.8, 0.95])
    exact = rounded_flat_half_plane(b, R, s.a, r)
    err = np.abs(s.pressure(s.a * r) - exact)
    assert np.max(err) <= s._impl.series_truncation + 1e-5 * np.max(exact)
    assert np.max(err / exact) < 1e-3


def test_rounded_flat_tends_to_the_flat_punch() -> None:
    """R -> 0: the contact closes on the face (a - b ~ R^(2/3)), and the
    pressure away from the edges and the indentation tend to the flat
    punch's at the rate R^(2/3) (measured: 2.0 %, 0.44 %, 0.098 % for the
    pressure at R = 1e-1, 1e-2, 1e-3)."""
    b = 0.3
    flat = mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.Flat(b))
    x = b * np.array([0.0, 0.3, 0.6, 0.8])
    dp, dd, da = [], [], []
    for R in (1e-1, 1e-2, 1e-3):
        s = mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.RoundedFlat(b, R))
        assert s.a > b
        dp.append(float(np.max(np.abs(s.pressure(x) / flat.pressure(x) - 1))))
        dd.append(abs(s.indentation / flat.indentation - 1))
        da.append(s.a - b)
    assert dp[-1] < 1.2e-3
    assert dd[-1] < 1.5e-4
    rate = 10 ** (2 / 3)
    for seq in (dp, dd, da):
        assert seq[0] / seq[1] == pytest.approx(rate, rel=0.15)
        assert seq[1] / seq[2] == pytest.approx(rate, rel=0.15)


def test_rounded_flat_tends_to_the_cylinder() -> None:
    """b -> 0: a/h tends to the cylinder's linearly in b (da ~ 0.70 b here),
    to 1e-8 by b = 1e-8."""
    cyl = mp.solve(vstar=0.2, kw=1.0, load=LOAD, radius=100.0)
    gaps = []
    for b in (1e-4, 1e-6, 1e-8):
        s = mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.RoundedFlat(b, 100.0))
        gaps.append(s.a - cyl.a)
    assert 0.0 < gaps[-1] < 1e-8
    assert gaps[0] / gaps[1] == pytest.approx(100.0, rel=0.01)
    exact = mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.RoundedFlat(0.0, 100.0))
    assert exact.a == pytest.approx(cyl.a, rel=1e-13)


def test_cylinder_profile_is_bit_identical() -> None:
    base = mp.solve(vstar=0.2, kw=1.0, load=LOAD, radius=100.0)
    for s in (
        mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.Cylinder(100.0)),
        mp.solve(vstar=0.2, kw=1.0, load=LOAD, radius=100.0, profile=mp.Cylinder(100)),
    ):
        assert (s.a, s.p0, s.indentation, s.error_estimate) == (
            base.a,
            base.p0,
            base.indentation,
            base.error_estimate,
        )
        assert np.array_equal(s.g_coefficients, base.g_coefficients)
        x = np.linspace(-1.0, 1.0, 11)
        assert np.array_equal(s.surface_stress(x), base.surface_stress(x))
        assert s.profile == mp.Cylinder(100.0)
        assert s.end_coefficients == (0.0, 0.0)


def test_parabola_table_reproduces_the_cylinder() -> None:
    """The not-a-knot spline reproduces a parabola exactly, so the table
    gives the cylinder to round-off (through the general right-hand side)."""
    cyl = mp.solve(vstar=0.2, kw=1.0, load=LOAD, radius=100.0)
    table = mp.Profile.from_function(lambda x: x * x / 200.0, 2.0, 41)
    s = mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=table)
    assert s.a == pytest.approx(cyl.a, rel=1e-13)
    assert s.indentation == pytest.approx(cyl.indentation, rel=1e-11)
    x = np.linspace(-0.3, 0.3, 7)
    np.testing.assert_allclose(s.pressure(x), cyl.pressure(x), rtol=1e-11)
    np.testing.assert_allclose(table.slope(x), x / 100.0, atol=1e-16)


def test_sampled_rounded_flat_matches_rounded_flat() -> None:
    """Profile.from_function of the RoundedFlat shape (2001 samples on
    |x| <= 1): the spline smooths the curvature jump at |x| = b over one
    spacing (1e-3 h), which moves a/h by about 1e-5 (measured 2.2e-6)."""
    b, R = 0.2, 100.0
    exact = mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.RoundedFlat(b, R))
    shape = mp.Profile.from_function(
        lambda x: np.maximum(np.abs(x) - b, 0.0) ** 2 / (2 * R), 1.0, 2001
    )
    s = mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=shape)
    assert s.a == pytest.approx(exact.a, rel=1e-5)
    x = exact.a * np.array([0.0, 0.5, 0.9])
    np.testing.assert_allclose(s.pressure(x), exact.pressure(x), rtol=1e-3)


@pytest.mark.parametrize(
    "profile",
    [
        mp.RoundedFlat(0.2, 100.0),
        mp.RoundedFlat(0.5, 1.0),
        mp.Profile.from_function(lambda x: x * x / 200.0 + x**4 / 50.0, 1.5, 301),
    ],
    ids=["rounded-flat-R100", "rounded-flat-R1", "table-quartic"],
)
@pytest.mark.parametrize("tol", [1e-4, 1e-8])
def test_width_estimate_is_honest(profile: Any, tol: float) -> None:
    """error_estimate >= the actual error against an N = 256 reference at
    tol 1e-12, and within 1e4 of it (or at round-off)."""
    s = mp.solve(vstar=0.3, kw=1.0, load=LOAD, profile=profile, tol=tol)
    ref = mp.solve(vstar=0.3, kw=1.0, load=LOAD, profile=profile, tol=1e-12, n=256)
    actual = abs(s.a - ref.a)
    assert actual <= s.error_estimate + 4 * ref.error_estimate
    assert s.error_estimate <= max(1e4 * actual, 1e-13)


@pytest.mark.parametrize(
    "profile",
    [mp.Flat(0.5), mp.RoundedFlat(0.2, 100.0)],
    ids=["flat", "rounded-flat"],
)
def test_stress_estimate_is_honest(profile: Any) -> None:
    """stress_error_estimate bounds sigma_x against an N = 256 reference at
    points away from the contact's ends."""
    s = mp.solve(vstar=0.3, kw=1.0, load=LOAD, profile=profile, tol=1e-6)
    ref = mp.solve(vstar=0.3, kw=1.0, load=LOAD, profile=profile, tol=1e-12, n=256)
    a = s.a
    x = a * np.array([0.0, 0.5, 0.9, 1.1, 2.0, 4.0])
    top = np.max(np.abs(s.surface_stress(x) - ref.surface_stress(x)))
    y = np.array([-0.5, -1.0])
    deep = np.max(np.abs(s.stress_field(x, y).sigma_x - ref.stress_field(x, y).sigma_x))
    actual = max(top, deep)
    est = s.stress_error_estimate
    assert actual <= est
    # The rounded flat's estimate carries the bound of its series' tail
    # (series_truncation, checked against the closed form above), which the
    # reference shares: beyond that it is not absurdly larger.
    assert est <= 1e6 * max(actual, 1e-12) + 10.0 * s._impl.series_truncation


def test_flat_peaks_say_singular() -> None:
    s = mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.Flat(0.4))
    peaks = s.stress_peaks()
    assert peaks.top_compressive == -math.inf
    assert peaks.top_compressive_x == 0.4
    assert any("singular" in w and "end coefficient" in w for w in peaks.warnings)
    assert math.isfinite(peaks.top_tensile)
    assert math.isfinite(peaks.bottom_tensile)
    assert peaks.bottom_tensile > 0.0
    data = s.to_dict()
    assert data["profile"] == {"kind": "flat", "half_width": 0.4}
    assert data["end_coefficients"] == list(s.end_coefficients)


def test_table_must_cover_the_contact() -> None:
    narrow = mp.Profile.from_function(lambda x: x * x / 200.0, 0.2, 41)
    with pytest.raises(ValueError, match=r"extent of the profile's table"):
        mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=narrow)


BAD_PROFILES: list[tuple[Any, str]] = [
    (lambda: mp.Flat(math.nan), "half_width"),
    (lambda: mp.Flat(-0.5), "half_width"),
    (lambda: mp.Flat(0.0), "half_width"),
    (lambda: mp.Flat(60.0), "half_width"),
    (lambda: mp.Flat("0.5"), "half_width"),
    (lambda: mp.RoundedFlat(0.2, -1.0), "radius"),
    (lambda: mp.RoundedFlat(math.inf, 1.0), "half_width"),
    (lambda: mp.Cylinder(0.0), "radius"),
    (lambda: mp.Profile((0.0, -1.0, 1.0, 2.0, 3.0), (0, 1, 2, 3, 4)), "profile.x"),
    (lambda: mp.Profile((-1.0, 0.0, 1.0), (1.0, 0.0, 1.0)), "profile.x"),
    (
        lambda: mp.Profile((-2.0, -1.0, 0.0, 1.0, 2.0), (4.0, 1.0, 0.0, 1.0)),
        "profile.y",
    ),
    (
        lambda: mp.Profile((-2.0, -1.0, 0.0, 1.0, 2.0), (1.0, 1.5, 0.0, 1.5, 1.0)),
        "profile.y",
    ),
    (  # the table must span the punch's axis x = 0
        lambda: mp.Profile((0.5, 1.0, 2.0, 3.0, 4.0), (4.0, 1.0, 0.0, 1.0, 4.0)),
        "profile.x",
    ),
    (  # asymmetric and not convex
        lambda: mp.Profile((-2.0, -1.0, 0.0, 1.0, 2.5), (4.0, 1.0, 0.0, 2.0, 2.5)),
        "profile.y",
    ),
    (
        lambda: mp.Profile((-2.0, -1.0, 0.0, 1.0, 2.0), (4.0, 1.0, math.nan, 1.0, 4.0)),
        "profile.y",
    ),
    (lambda: mp.Profile("abc", (1.0,)), "profile.x"),
    (lambda: mp.Profile.from_function(lambda x: x**3 + x * x, 1.0), "profile.y"),
    (lambda: mp.Profile.from_function(lambda x: x * x, 1.0, points=4), "points"),
]


@pytest.mark.parametrize(("make", "name"), BAD_PROFILES)
def test_bad_profiles_name_the_parameter(make: Any, name: str) -> None:
    with pytest.raises(mp.InvalidParameterError) as info:
        make()
    assert info.value.parameter == name
    assert name.split(".")[-1] in str(info.value)


def test_solve_rules_for_radius_and_profile() -> None:
    kw: dict[str, Any] = {"vstar": 0.2, "kw": 1.0, "load": LOAD}
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(**kw, radius=50.0, profile=mp.Cylinder(100.0))
    assert info.value.parameter == "radius"
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(**kw, radius=50.0, profile=mp.Flat(0.5))
    assert info.value.parameter == "radius"
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(**kw)
    assert info.value.parameter == "radius"
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(**kw, profile="flat")  # type: ignore[call-overload]
    assert info.value.parameter == "profile"
    # The flat punch with damping takes the asymmetric solver (issue 14;
    # tests/python/test_profiles_asymmetric_flat.py).
    flat = mp.solve(**kw, profile=mp.Flat(0.5), damping=0.1)
    assert flat.profile == mp.Flat(0.5)
    assert flat.contact_interval == (-0.5, 0.5)
    s = mp.solve(**kw, radius=100.0, profile=mp.RoundedFlat(0.1, 100.0))
    assert s.radius == 100.0
    assert s.a > 0.1
    damped = mp.solve(**kw, profile=mp.Cylinder(100.0), damping=0.1)
    assert damped.profile == mp.Cylinder(100.0)
    assert damped.end_coefficients == (0.0, 0.0)


def test_profile_round_trips_through_its_dict() -> None:
    from movingpunch.profiles import profile_from_dict

    for p in (
        mp.Cylinder(3.0),
        mp.Flat(0.5),
        mp.RoundedFlat(0.5, 2.0),
        mp.Profile.from_function(lambda x: x * x, 1.0, 9),
    ):
        assert profile_from_dict(p.to_dict()) == p
    with pytest.raises(mp.InvalidParameterError) as info:
        profile_from_dict({"kind": "flta", "half_width": 0.5})
    assert info.value.parameter == "profile.kind"
    with pytest.raises(mp.InvalidParameterError) as info:
        profile_from_dict({"kind": "flat", "halfwidth": 0.5})
    assert info.value.parameter == "profile.halfwidth"
    with pytest.raises(mp.InvalidParameterError) as info:
        profile_from_dict({"kind": "rounded_flat", "half_width": 0.5})
    assert info.value.parameter == "profile.radius"
    with pytest.raises(mp.InvalidParameterError) as info:
        profile_from_dict({"kind": "flat", "half_width": -1})
    assert info.value.parameter == "profile.half_width"


def test_bundled_flat_punch_scene() -> None:
    """The bundled flat punch (b = 0.01 h) against the half-plane closed form,
    at rest and moving: within 1e-3 (the layer's O((b/h)^2) correction,
    largest near V*_cr), and the scene round-trips through TOML."""
    from movingpunch.scene import Scene

    scene = Scene.bundled("flat-punch")
    assert scene.profile == mp.Flat(0.01)
    assert Scene.from_toml(scene.to_toml()) == scene
    result = scene.run()
    curves = result.outputs["pressure"].curves
    assert len(curves) == 3
    for curve in curves:
        exact = flat_closed_form(0.01, curve.x)
        assert np.max(np.abs(curve.y / exact - 1.0)) < 1e-3, curve.label
    widths = result.outputs["contact_width"].columns["a"]
    assert np.all(widths == 0.01)


SCENE = """
[params]
vstar = 0.2
kw = 1.0
load = 0.002
{extra}
[outputs]
contact_width = true
"""


@pytest.mark.parametrize(
    ("extra", "key"),
    [
        ('[params.profile]\nkind = "flta"\nhalf_width = 0.5', "params.profile.kind"),
        (
            '[params.profile]\nkind = "flat"\nhalf_width = -0.5',
            "params.profile.half_width",
        ),
        (
            '[params.profile]\nkind = "flat"\nhalf_width = "a"',
            "params.profile.half_width",
        ),
        ('[params.profile]\nkind = "flat"\nradius = 1.0', "params.profile.radius"),
        (
            '[params.profile]\nkind = "rounded_flat"\nhalf_width = 0.5',
            "params.profile.radius",
        ),
        (
            '[params.profile]\nkind = "table"\nx = [0, 1, 2]\ny = [0, 1, 4]',
            "params.profile.x",
        ),
        (
            '[params.profile]\nkind = "table"\n'
            "x = [-2, -1, 0, 1, 2]\ny = [1, 2, 0, 2, 1]",
            "params.profile.y",
        ),
        (
            '[params.profile]\nkind = "flat"\nhalf_width = 0.5\nfoo = 1',
            "params.profile.foo",
        ),
        (
            "radius = 3.0\n[params.profile]\nkind = 'flat'\nhalf_width = 0.5",
            "params.radius",
        ),
    ],
)
def test_scene_profile_errors_name_the_key(extra: str, key: str) -> None:
    from movingpunch.scene import Scene, SceneError

    with pytest.raises(SceneError) as info:
        Scene.from_toml(SCENE.format(extra=extra), "s.toml")
    assert key in str(info.value)


def test_scene_profiles_round_trip_and_run() -> None:
    from movingpunch.scene import Scene, SceneError

    for extra in (
        '[params.profile]\nkind = "rounded_flat"\nhalf_width = 0.2\nradius = 100.0',
        '[params.profile]\nkind = "table"\nx = [-2, -1, 0, 1, 2]\n'
        "y = [0.02, 0.005, 0, 0.005, 0.02]",
        '[params.profile]\nkind = "cylinder"\nradius = 100.0',
    ):
        scene = Scene.from_toml(SCENE.format(extra=extra))
        assert Scene.from_toml(scene.to_toml()) == scene
        a = scene.run().outputs["contact_width"].columns["a"][0]
        assert a > 0.2
    cylinder = Scene.from_toml(
        SCENE.format(extra='[params.profile]\nkind = "cylinder"\nradius = 100.0')
    )
    assert cylinder.profile is None
    assert cylinder.params["radius"] == 100.0
    with pytest.raises(SceneError, match=r"vary\.param"):
        Scene.from_toml(
            SCENE.format(extra='[params.profile]\nkind = "flat"\nhalf_width = 0.5')
            + '\n[vary]\nparam = "radius"\nvalues = [1.0, 2.0]\n'
        )


def test_tui_profile_selector() -> None:
    """The panel's punch input: flat (b/h), rounded flat, garbage refused
    inline; the summary shows K for the flat punch; the pressure plot shows
    the flat punch's pressure (the API's, at the plot's grid)."""
    import asyncio

    from movingpunch.tui import create_app
    from movingpunch.tui.widgets import CurvePlot, ParamsPanel
    from tui_pilot import screen_of, settle, status_text, summary_text, type_into

    async def run() -> None:
        app = create_app()
        async with app.run_test(size=(100, 32)) as pilot:
            await settle(pilot)
            screen = screen_of(app)
            await type_into(pilot, "half_width", "0.4", paste=True)
            await settle(pilot)
            await type_into(pilot, "profile", "flat", paste=True)
            await settle(pilot)
            assert screen.params.profile == "flat"
            assert "K " in summary_text(app)
            assert "a/h 0.4" in summary_text(app)
            expected = mp.solve(vstar=0.2, kw=1.0, load=0.002, profile=mp.Flat(0.4))
            data = screen.query_one("#plot-pressure", CurvePlot).curves
            assert data is not None
            np.testing.assert_allclose(
                data.series[0].values, expected.pressure(data.grid), rtol=1e-12
            )
            await type_into(pilot, "profile", "rounded flat", paste=True)
            await settle(pilot)
            assert screen.params.profile == "rounded_flat"
            assert "K " not in summary_text(app)
            for text in ("flta", "", "∞", "table"):
                await type_into(pilot, "profile", text, paste=True)
                await settle(pilot)
                assert screen.query_one(ParamsPanel).message("profile"), text
            assert app.is_running
            assert "profile" in status_text(app) or "invalid" in status_text(app)
            await type_into(pilot, "profile", "cylinder", paste=True)
            await settle(pilot)
            assert screen.query_one(ParamsPanel).message("profile") == ""
            assert screen.params.shape() is None

    asyncio.run(run())


@pytest.mark.parametrize(
    "profile", [mp.Flat(0.5), mp.RoundedFlat(0.2, 100.0)], ids=["flat", "rounded"]
)
def test_accuracy_ladder_of_a_profile(profile: Any) -> None:
    """The accuracy ladder takes a profile: every rung's errors against the
    fixed-N reference lie within its estimates (the flat punch's ends are
    exact: error 0)."""
    from movingpunch.accuracy import accuracy_report

    report = accuracy_report(
        {"vstar": 0.2, "kw": 1.0, "load": LOAD}, (1e-4, 1e-8), profile=profile
    )
    assert report is not None
    assert report.scene.profile == profile
    for rung in report.rungs:
        assert rung.failure == ""
        assert rung.bounded
        assert rung.error_a <= max(rung.error_estimate, 1e-15)


@pytest.mark.usefixtures("pool_pays")
def test_profile_scene_sweep_in_worker_processes() -> None:
    """A rounded-flat load sweep gives the same widths in this process and in
    two worker processes (the profile is pickled with the tasks), and each
    width is the API's."""
    from movingpunch.scene import Scene

    scene = Scene.from_toml(
        SCENE.format(
            extra='[params.profile]\nkind = "rounded_flat"\nhalf_width = 0.2\n'
            "radius = 100.0"
        )
        + '\n[sweep]\nparam = "load"\nvalues = [0.001, 0.004]\nquantities = ["a"]\n'
    )
    one, two = scene.run(jobs=1), scene.run(jobs=2)
    assert one.sweep is not None
    assert two.sweep is not None
    assert np.array_equal(one.sweep.data["a"], two.sweep.data["a"])
    direct = mp.solve(vstar=0.2, kw=1.0, load=0.004, profile=mp.RoundedFlat(0.2, 100.0))
    assert one.sweep.data["a"][0][1] == direct.a
