"""The solver against independent anchors: the paper's Table 1, the moving
half-plane (Hertz) limit, closed forms of the layer response, the critical
speed table, conservation of load, and an independent integration of the
indentation. Anchors are listed in docs/theory.md §11."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, special

import movingpunch as mp

INF = math.inf
KW = [0.1, 1.0, 10.0, INF]
TABLE1_STATIC = [0.372478, 0.330419, 0.315037, 0.311557]
TABLE1_SLOW = [0.372878, 0.330577, 0.315152, 0.311665]
PAPER = {"radius": 100.0, "load": 0.002, "nu": 0.2}


@pytest.mark.parametrize(
    ("vstar", "kw", "want"),
    [(0.0, k, a) for k, a in zip(KW, TABLE1_STATIC, strict=True)]
    + [(1e-3, k, a) for k, a in zip(KW, TABLE1_SLOW, strict=True)],
)
def test_paper_table1(vstar: float, kw: float, want: float) -> None:
    sol = mp.solve(vstar=vstar, kw=kw, **PAPER)
    assert sol.a == pytest.approx(want, abs=2e-6)
    assert sol.valid


@pytest.mark.parametrize("vstar", [0.0, 0.2, 0.4, 0.6])
def test_half_plane_limit(vstar: float) -> None:
    # a/h -> sqrt(2 phi1 radius load / pi) when the contact is small against h.
    sol = mp.solve(vstar=vstar, kw=INF, radius=1.0, load=5e-7, nu=0.2)
    assert sol.a <= 1e-3
    hertz = math.sqrt(2.0 * mp.phi1(vstar, 0.2) * 1.0 * 5e-7 / math.pi)
    assert sol.a == pytest.approx(hertz, rel=1e-5)
    assert sol.p0 == pytest.approx(2.0 / (math.pi * sol.a), rel=1e-4)


@pytest.mark.parametrize(
    ("vstar", "a_half_plane"),
    [(0.0, 0.31915), (0.2, 0.3491), (0.4, 0.3979), (0.6, 0.5018)],
)
def test_phi1_reproduces_published_half_plane_widths(
    vstar: float, a_half_plane: float
) -> None:
    a = math.sqrt(2.0 * mp.phi1(vstar, 0.2) * 100.0 * 0.002 / math.pi)
    assert a == pytest.approx(a_half_plane, abs=6e-5)


def _half_plane_factor(s: float, nu: float) -> float:
    kappa = 3 - 4 * nu
    c2 = (kappa + 1) / (kappa - 1)
    nt, nl = math.sqrt(1 - s), math.sqrt(1 - s / c2)
    return (1 - nt**2) * nl / (4 * nl * nt - (1 + nt**2) ** 2)


def test_phi1_limits_and_moving_half_plane_factor() -> None:
    for nu in (0.0, 0.2, 0.3, 0.45):
        assert mp.phi1(0.0, nu) == pytest.approx(1.0 - nu, abs=1e-15)
        assert mp.phi2(0.0, nu) == pytest.approx(1.0, abs=1e-14)
    for s in (0.05, 0.2, 0.5, 0.8):
        assert mp.phi1(s, 0.2) == pytest.approx(_half_plane_factor(s, 0.2), rel=1e-12)
    assert mp.phi2(0.2, 0.2) == pytest.approx(1.2395847348537, abs=1e-12)


def test_static_rigid_base_response_closed_form() -> None:
    t = np.array([0.3, 1.0, 2.5])
    m1, _ = mp.layer_response(t, vstar=0.0, kw=INF, nu=0.2)
    exact = 0.8 * (np.cosh(2 * t) - 1) / (np.sinh(2 * t) + 2 * t)
    np.testing.assert_allclose(m1, exact, atol=1e-12, rtol=0)


def test_layer_response_is_finite_over_the_whole_range() -> None:
    t = np.logspace(-8, 5, 200)
    for kw in (0.01, 1.0, INF):
        for vstar in (0.0, 1e-14, 0.3):
            m1, m2 = mp.layer_response(t, vstar=vstar, kw=kw, nu=0.2)
            assert np.all(np.isfinite(m1))
            assert np.all(np.isfinite(m2))
            assert m1[-1] == pytest.approx(mp.phi1(vstar, 0.2), abs=1e-14)
            assert m2[-1] == pytest.approx(mp.phi2(vstar, 0.2), abs=1e-14)


@pytest.mark.parametrize(
    ("kw", "want"),
    [(0.01, 0.0869126), (0.1, 0.2475216), (1.0, 0.5716928), (10.0, 0.8185946)],
)
def test_critical_speed_table(kw: float, want: float) -> None:
    assert mp.critical_vstar(kw, nu=0.2) == pytest.approx(want, abs=2e-6)


def test_rayleigh_and_supercritical() -> None:
    assert mp.rayleigh_vstar(0.2) == pytest.approx(0.8299135, abs=1e-7)
    assert mp.critical_vstar(INF, nu=0.2) == mp.rayleigh_vstar(0.2)
    with pytest.raises(mp.SupercriticalSpeedError) as info:
        mp.solve(vstar=0.6, kw=1.0, **PAPER)
    assert isinstance(info.value, ValueError)
    assert "0.57169" in str(info.value)
    assert "0.82991" in str(info.value)
    sol = mp.solve(vstar=0.2, kw=1.0, **PAPER)
    assert sol.critical_vstar == pytest.approx(0.5716928, abs=2e-6)


def test_zero_speed_is_continuous() -> None:
    a = [mp.solve(vstar=v, kw=1.0, **PAPER).a for v in (0.0, 1e-14, 1e-10)]
    assert max(a) - min(a) <= 1e-10


def test_tolerance_is_met_and_error_estimate_bounds_the_error() -> None:
    for kw in KW:
        for vstar in (0.0, 1e-3, 0.2):
            ref = mp.solve(vstar=vstar, kw=kw, tol=1e-13, **PAPER).a
            for tol in (1e-6, 1e-8, 1e-10, 1e-12):
                sol = mp.solve(vstar=vstar, kw=kw, tol=tol, **PAPER)
                err = abs(sol.a - ref)
                assert err <= tol, (kw, vstar, tol, err)
                assert err <= sol.error_estimate + 1e-15, (kw, vstar, tol, err)


@pytest.mark.parametrize(
    ("vstar", "kw"), [(0.0, 0.1), (0.2, 1.0), (0.2, 0.1), (0.4, INF)]
)
def test_equilibrium_symmetry_and_sign(vstar: float, kw: float) -> None:
    sol = mp.solve(vstar=vstar, kw=kw, **PAPER)
    # int p dx / (P/h) = 1, by a 200-point Gauss-Legendre rule in theta
    # (x = a cos theta makes the integrand smooth), independent of the solver.
    g, w = np.polynomial.legendre.leggauss(200)
    theta = 0.5 * np.pi * (g + 1)
    total = (
        0.5
        * np.pi
        * np.sum(w * sol.pressure(sol.a * np.cos(theta)) * np.sin(theta))
        * sol.a
    )
    assert total == pytest.approx(1.0, rel=1e-12)
    x = np.linspace(-sol.a, sol.a, 401)
    p = sol.pressure(x)
    np.testing.assert_allclose(p, p[::-1], atol=1e-14)
    assert np.all(p >= 0)
    assert sol.pressure(1.001 * sol.a) == 0.0
    assert sol.pressure(0.0) == pytest.approx(sol.p0, rel=1e-14)


def _m1_static_rigid(t: np.ndarray, nu: float) -> np.ndarray:
    t = np.minimum(t, 30.0)  # the closed form overflows; the tail is exp(-60) away
    return (1 - nu) * (np.cosh(2 * t) - 1) / (np.sinh(2 * t) + 2 * t)


def test_indentation_against_independent_integration() -> None:
    # Static layer on a smooth rigid base (closed-form M1): delta/h = load *
    # (2/pi) int_0^inf (M1/alpha) ptilde(alpha) d alpha, with
    # ptilde = int_0^a p cos(alpha x) dx,
    # integrated here by brute force on [0, A] plus the exact Ci tail beyond A.
    nu, load = 0.2, 0.002
    sol = mp.solve(vstar=0.0, kw=INF, radius=100.0, load=load, nu=nu)
    a = sol.a
    th, wth = np.polynomial.legendre.leggauss(200)
    theta = 0.25 * np.pi * (th + 1)  # x = a sin(theta), theta in [0, pi/2]
    xs = a * np.sin(theta)
    px = sol.pressure(xs) * a * np.cos(theta) * 0.25 * np.pi * wth
    big_a = 200.0
    g, wg = np.polynomial.legendre.leggauss(16)
    edges = np.linspace(0.0, big_a, 801)
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    al = (mid[:, None] + half[:, None] * g).ravel()
    wa = (half[:, None] * wg).ravel()
    ptilde = np.cos(np.outer(al, xs)) @ px
    head = np.sum(wa * _m1_static_rigid(al, nu) / al * ptilde)
    # Tail: phi1 int_A^inf ptilde/alpha = phi1 int_0^a p(x) (-Ci(A x)) dx.
    tail, _ = integrate.quad(
        lambda x: sol.pressure(x) * -special.sici(big_a * x)[1],
        0.0,
        a,
        limit=400,
        points=[1e-6],
    )
    delta_ref = load * 2.0 / np.pi * (head + (1 - nu) * tail)
    assert sol.indentation == pytest.approx(delta_ref, rel=1e-6)


@pytest.mark.parametrize(("vstar", "kw"), [(0.0, 0.1), (0.2, 1.0), (0.2, INF)])
def test_surface_follows_the_punch_profile(vstar: float, kw: float) -> None:
    sol = mp.solve(vstar=vstar, kw=kw, **PAPER)
    x = np.linspace(-sol.a, sol.a, 21)
    v = sol.surface_displacement(x)
    np.testing.assert_allclose(v, -sol.indentation + x**2 / 200.0, atol=1e-10)
    # Outside the contact the surface stays below the punch.
    xo = np.linspace(1.01 * sol.a, 3 * sol.a, 50)
    assert np.all(-sol.indentation + xo**2 / 200.0 - sol.surface_displacement(xo) > 0)


def test_softer_faster_wider() -> None:
    # The paper's qualitative statements: the contact widens with speed, radius
    # and load, and as the foundation softens.
    base = mp.solve(vstar=0.2, kw=1.0, **PAPER).a
    assert mp.solve(vstar=0.3, kw=1.0, **PAPER).a > base
    assert mp.solve(vstar=0.2, kw=0.5, **PAPER).a > base
    assert mp.solve(vstar=0.2, kw=1.0, radius=150.0, load=0.002, nu=0.2).a > base
    assert mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.003, nu=0.2).a > base


def test_radius_and_load_enter_only_through_their_product() -> None:
    a1 = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, nu=0.2)
    a2 = mp.solve(vstar=0.2, kw=1.0, radius=50.0, load=0.004, nu=0.2)
    assert a1.a == pytest.approx(a2.a, rel=1e-12)
    assert a1.p0 == pytest.approx(a2.p0, rel=1e-10)


def test_pressure_maximum_moves_off_centre_but_stays_valid() -> None:
    # docs/theory.md §9: kw = 0.1, vstar = 0.2, R/h = 100, P/(mu h) = 0.01.
    sol = mp.solve(vstar=0.2, kw=0.1, radius=100.0, load=0.01, nu=0.2)
    assert sol.valid
    x = np.linspace(0, sol.a, 200)
    assert sol.pressure(x).max() > 1.05 * sol.p0


def test_separating_contact_is_reported_never_returned_as_valid() -> None:
    kwargs = {"vstar": 0.086, "kw": 0.01, "radius": 100.0, "load": 0.002, "nu": 0.2}
    with pytest.raises(mp.UnphysicalContactError, match="unphysical"):
        mp.solve(**kwargs, contact="single")
    sol = mp.solve(**kwargs, contact="single", allow_unphysical=True)
    assert not sol.valid
    assert sol.min_pressure < 0
    assert "negative" in sol.validity
    # contact auto returns the separated contact instead, never the single one
    zoned = mp.solve(**kwargs)
    assert zoned.valid
    assert len(zoned.contact_zones) >= 2
    assert zoned.min_pressure >= 0
