"""Coulomb friction on the moving punch (issue 14; docs/theory.md section 14).

Conventions: the punch moves towards +x; the layer's surface under it carries
the shear traction tau_xy = f p in the direction of motion; (-b, a) are the
trailing and leading ends; p ~ (x + b)^gamma_back (a - x)^gamma_front.

Every anchor here is independent of the solver: closed forms (the static and
moving half-plane), a layer solve written from scratch with NumPy/SciPy
(eigenvectors of the 4x4 system per wavenumber, the kernel by Gauss-Legendre
sums, a plain Gauss-Jacobi collocation from scipy.special.roots_jacobi and a
Brent root find on the width), and direct quadrature of the solution's own
pressure (equilibrium, Cauchy principal values).
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import roots_jacobi, roots_legendre

import movingpunch as mp
from movingpunch import _core, params
from movingpunch.asymmetric import AsymmetricSolution, coupling_constant, end_exponents
from movingpunch.errors import (
    InvalidParameterError,
    SupercriticalSpeedError,
)

# ---------------------------------------------------------------------------
# An independent layer: the state z = [U, W, tau/alpha, sigma_y/alpha] obeys
# z' = alpha A z (docs/theory.md section 4); its modes from numpy's
# eigenvectors, each written relative to the face it decays from.


def _system(s: float, nu: float) -> tuple[float, np.ndarray]:
    kappa = 3 - 4 * nu
    c2 = (kappa + 1) / (kappa - 1)
    a = np.array(
        [
            [0, 1, 1, 0],
            [-(c2 - 2) / c2, 0, 0, 1 / c2],
            [4 * (c2 - 1) / c2 - s, 0, 0, (c2 - 2) / c2],
            [0, -s, -1, 0],
        ],
        float,
    )
    return c2, a


def _top_states(
    t: float, s: float, kw: float, nu: float, damping: float
) -> tuple[np.ndarray, np.ndarray]:
    """Top states of the unit normal load (T = 0, S = -1) and the unit
    tangential load (T = 1, S = 0) at t = alpha h > 0."""
    _, a = _system(s, nu)
    ev, vec = np.linalg.eig(a)
    ev, vec = ev.real, vec.real

    def columns(y: float) -> np.ndarray:
        e = np.where(ev > 0, np.exp(t * ev * y), np.exp(t * ev * (y + 1)))
        return np.asarray(vec * e[None, :])

    top, bot = columns(0.0), columns(-1.0)
    k = kw - 1j * damping * math.sqrt(s) * t
    m = np.zeros((4, 4), complex)
    m[0], m[1], m[2] = top[2], top[3], bot[2]
    m[3] = bot[1] if math.isinf(kw) else (t * bot[3] - k * bot[1]) / (t + abs(k))
    normal = top @ np.linalg.solve(m, np.array([0, -1, 0, 0], complex))
    tangential = top @ np.linalg.solve(m, np.array([1, 0, 0, 0], complex))
    return normal, tangential


def _half_plane(s: float, nu: float) -> tuple[float, float, float]:
    """(phi1, Wq_inf, Phi) of the moving half-plane from the classical
    Rayleigh-function forms (s > 0)."""
    c2, _ = _system(s, nu)
    nt, nl = math.sqrt(1 - s), math.sqrt(1 - s / c2)
    rayleigh = 4 * nl * nt - (2 - s) ** 2
    wq = (2 - s - 2 * nl * nt) / rayleigh
    return s * nl / rayleigh, wq, (2 - s - 2 * nl * nt) / (s * nl)


def _independent_rule(
    s: float, kw: float, nu: float, damping: float, f: float, n: int
) -> tuple[Any, ...]:
    """What an independent Gauss-Jacobi collocation needs: phi1, the end
    exponents (front, back), the nodes r and weights w (roots_jacobi), the
    collocation points sk, and the regular kernel's samples g at the
    Gauss-Legendre nodes alpha (weights) up to 45/nT:
    g = -i(M1 - phi1) - f (Wq - Wq_inf) from the independent layer."""
    phi1, wq_inf, phi = _half_plane(s, nu)
    front = 0.5 + math.atan(f * phi) / math.pi
    back = 1 - front
    r, w = roots_jacobi(n, front, back)
    with np.errstate(invalid="ignore", divide="ignore"):
        sk, _ = roots_jacobi(n + 1, -front, -back)
    nt = math.sqrt(1 - s)
    x, wl = roots_legendre(16)
    edges = np.linspace(0.0, 45.0 / nt, 401)
    alpha = np.concatenate(
        [0.5 * (b - a) * x + 0.5 * (a + b) for a, b in itertools.pairwise(edges)]
    )
    weight = np.concatenate([0.5 * (b - a) * wl for a, b in itertools.pairwise(edges)])
    g = np.empty(alpha.size, complex)
    for j, t in enumerate(alpha):
        zn, zq = _top_states(float(t), s, kw, nu, damping)
        g[j] = -1j * (-zn[1] - phi1) - f * (zq[1] - wq_inf)
    return phi1, front, back, r, w, sk, alpha, weight, g


def _independent_ends(
    s: float, kw: float, nu: float, damping: float, f: float, lam: float, n: int
) -> tuple[float, float]:
    """(-b, a) from a plain Gauss-Jacobi collocation of
    f Phi p + (1/pi) int p/(xi - x) - int p Lr(x - xi)/phi1 = -x/(R P phi1)
    with Lr(u) = (1/pi) Re int_0^inf [-i(M1 - phi1) - f (Wq - Wq_inf)] e^{i alpha u}."""
    phi1, _, _, r, w, sk, alpha, weight, g = _independent_rule(s, kw, nu, damping, f, n)

    def load_of(width: float) -> tuple[float, float]:
        u = width * (sk[:, None] - r[None, :])
        kern = (np.exp(1j * np.multiply.outer(u, alpha)) @ (weight * g)).real / phi1
        m = np.zeros((n + 1, n + 1))
        m[:, :n] = (w / math.pi)[None, :] * (
            1 / (r[None, :] - sk[:, None]) - width * kern
        )
        m[:, n] = 1
        sol = np.linalg.solve(m, sk)
        return -width * width * float(w @ sol[:n]) / phi1, -width * sol[n]

    lw = brentq(
        lambda v: math.log(load_of(math.exp(v))[0] / lam),
        math.log(0.05),
        math.log(3.0),
        xtol=1e-15,
        rtol=1e-15,
    )
    width = math.exp(lw)
    centre = load_of(width)[1]
    return centre - width, centre + width


# ---------------------------------------------------------------------------


@pytest.mark.parametrize("nu", [0.0, 0.2, 0.3, 0.45])
def test_coupling_constant_static_is_the_classical_value(nu: float) -> None:
    """Static half-plane: Phi = (1 - 2 nu)/(2 (1 - nu)) (K. L. Johnson,
    Contact Mechanics (1985), section 7.1; Hills, Nowell & Sackfield (1993))."""
    assert coupling_constant(0.0, nu) == pytest.approx(
        (1 - 2 * nu) / (2 * (1 - nu)), rel=1e-14, abs=1e-15
    )


@pytest.mark.parametrize("vstar", [1e-6, 0.1, 0.3, 0.6, 0.82])
def test_coupling_constant_moving_matches_the_layer_at_large_alpha(
    vstar: float,
) -> None:
    """Phi(V*) in closed form equals the Rayleigh-function form and the
    numerical large-alpha limit Wq/phi1 of an independent 4x4 layer solve;
    continuous towards the static value."""
    _, _, phi = _half_plane(vstar, 0.2)
    assert coupling_constant(vstar, 0.2) == pytest.approx(phi, rel=1e-9)
    if vstar >= 0.01:  # the eigenvector basis is ill-conditioned near V = 0
        zn, zq = _top_states(40.0, vstar, 1.0, 0.2, 0.0)
        assert float(zq[1].real) / float(-zn[1].real) == pytest.approx(
            coupling_constant(vstar, 0.2), rel=1e-10
        )
        uq, wq = _core.damped_tangential_response(40.0, vstar, 1.0, 0.2, 0.0)
        assert wq.real == pytest.approx(zq[1].real, rel=1e-10)
        assert uq.real == pytest.approx(zq[0].real, rel=1e-10)
    assert abs(coupling_constant(1e-9, 0.2) - 0.375) < 1e-8


def test_tangential_response_matches_an_independent_layer_with_damping() -> None:
    for t in (0.05, 0.3, 1.0, 3.0, 12.0):
        _, zq = _top_states(t, 0.4, 0.3, 0.25, 0.7)
        uq, wq = _core.damped_tangential_response(t, 0.4, 0.3, 0.25, 0.7)
        assert abs(uq - zq[0]) < 1e-10 * abs(zq[0])
        assert abs(wq - zq[1]) < 1e-10 * max(abs(zq[1]), 1e-3)


def _half_plane_sliding_cylinder(
    f: float, nu: float, radius: float, load: float
) -> tuple[float, float, float, float]:
    """The static half-plane's sliding cylinder with friction (Johnson 1985,
    section 7.1(b)): with cot(pi gamma_back) = f (1 - 2 nu)/(2 (1 - nu)),
    gamma_front = 1 - gamma_back, the bounded solution has g constant:
    p = (w sin(pi gamma_front)/(phi1 R)) (1 - r)^gamma_front (1 + r)^gamma_back,
    w^2 = phi1 R P/(2 pi gamma_front gamma_back), centre c = w (gamma_back -
    gamma_front). Returns (w, c, gamma_back, gamma_front)."""
    phi = (1 - 2 * nu) / (2 * (1 - nu))
    back = math.atan2(1.0, f * phi) / math.pi  # cot(pi back) = f phi
    front = 1 - back
    phi1 = 1 - nu
    w = math.sqrt(phi1 * radius * load / (2 * math.pi * front * back))
    return w, w * (back - front), back, front


@pytest.mark.parametrize("f", [0.05, 0.3, 1.0])
def test_half_plane_limit_static(f: float) -> None:
    """a << h on a rigid base at rest: the exponents, the ends and the
    pressure of the half-plane's sliding cylinder (Johnson 1985, section 7.1)."""
    s = mp.solve(vstar=0.0, kw=math.inf, radius=100.0, load=2e-9, friction=f)
    w, c, back, front = _half_plane_sliding_cylinder(f, 0.2, 100.0, 2e-9)
    assert s.end_exponents == pytest.approx((back, front), abs=1e-14)
    assert math.tan(math.pi * (0.5 - s.end_exponents[0])) == pytest.approx(
        f * 0.375, rel=1e-12
    )
    assert s.half_width == pytest.approx(w, rel=1e-5)
    # The layer moves the centre at first order in a/h (measured 0.36 f w^2;
    # tenfold less per tenfold smaller w, docs/theory.md section 14).
    assert abs(s.centre - c) <= 0.5 * f * w * w
    peak = s.max_pressure if isinstance(s, AsymmetricSolution) else 0.0
    for r in np.linspace(-0.95, 0.95, 9):
        # p/(P/h) of the closed form (p in mu units over the load), at the
        # same relative position r in the contact.
        exact = (
            w
            * math.sin(math.pi * front)
            / ((1 - 0.2) * 100.0 * 2e-9)
            * (1 - r) ** front
            * (1 + r) ** back
        )
        got = s.pressure(s.centre + s.half_width * r)
        assert got == pytest.approx(exact, abs=2e-4 * f * peak)


def _smooth(s: AsymmetricSolution, x: float) -> float:
    """p/((x + b)^gb (a - x)^gf), the smooth factor of the pressure."""
    back, front = s.contact_interval
    gb, gf = s.end_exponents
    x = min(max(x, back + 1e-12 * s.half_width), front - 1e-12 * s.half_width)
    return float(s.pressure(x)) / ((x - back) ** gb * (front - x) ** gf)


def test_equilibrium_and_tangential_force() -> None:
    """int p = P and the friction force f P, to 1e-12, by a 96-point
    Gauss-Jacobi rule (SciPy's) on the pressure's smooth factor, and by
    adaptive quadrature with the end weight (x + b)^gb (a - x)^gf."""
    for damping in (0.0, 0.3):
        s = mp.solve(
            vstar=0.3, kw=1.0, radius=100, load=0.002, friction=0.4, damping=damping
        )
        assert isinstance(s, AsymmetricSolution)
        back, front = s.contact_interval
        gb, gf = s.end_exponents
        r, wr = roots_jacobi(96, gf, gb)
        w = s.half_width
        total = (
            w
            * w
            * sum(
                float(q) * _smooth(s, s.centre + w * float(t))
                for t, q in zip(r, wr, strict=True)
            )
        )
        assert total == pytest.approx(1.0, abs=1e-12)
        adaptive = quad(
            lambda x, s=s: _smooth(s, x), back, front, weight="alg", wvar=(gb, gf)
        )[0]
        assert adaptive == pytest.approx(1.0, abs=1e-10)
        assert s.tangential_force == 0.4
        assert gb + gf == pytest.approx(1.0, abs=1e-15)


def test_f_zero_is_bit_identical() -> None:
    plain = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002)
    zero = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, friction=0.0)
    assert type(zero) is type(plain)
    assert zero.a == plain.a
    assert zero.error_estimate == plain.error_estimate
    assert zero.friction == 0.0
    assert zero.tangential_force == 0.0
    assert zero.end_exponents == (0.5, 0.5)
    d0 = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, damping=0.1)
    d1 = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, damping=0.1, friction=0.0)
    assert d1.contact_interval == d0.contact_interval
    assert d1.error_estimate == d0.error_estimate
    x = np.linspace(-1, 1, 7)
    assert np.array_equal(d1.surface_stress(x), d0.surface_stress(x))
    assert d1.end_exponents == (0.5, 0.5)


def test_f_to_zero_is_continuous() -> None:
    base = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002)
    tiny = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, friction=1e-10)
    assert tiny.contact_interval == pytest.approx(base.contact_interval, abs=1e-9)
    assert tiny.pressure(0.1) == pytest.approx(base.pressure(0.1), abs=1e-8)
    assert tiny.surface_stress(0.8) == pytest.approx(base.surface_stress(0.8), abs=1e-8)
    damped = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, damping=0.1)
    both = mp.solve(
        vstar=0.2, kw=1.0, radius=100, load=0.002, damping=0.1, friction=1e-10
    )
    assert both.contact_interval == pytest.approx(damped.contact_interval, abs=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize("damping", [0.0, 0.5])
def test_ends_against_an_independent_layer_solve(damping: float) -> None:
    """The frictional moving case on the layer (V* = 0.3, kw = 1, f = 0.3):
    the ends agree to 1e-8 with the collocation written from scratch above."""
    s = mp.solve(
        vstar=0.3,
        kw=1.0,
        radius=100,
        load=0.002,
        friction=0.3,
        damping=damping,
        tol=1e-12,
    )
    ends = _independent_ends(0.3, 1.0, 0.2, damping, 0.3, 0.2, 24)
    assert s.contact_interval == pytest.approx(ends, abs=1e-8)


def test_surface_stress_half_plane_limit_and_trailing_tension() -> None:
    """a << h at rest: sigma_x(x, 0) = -p + (2 f/pi) PV int p/(xi - x) (the
    static half-plane's Cauchy integral of the shear traction), evaluated
    here by SciPy's principal value of the solution's pressure; the trailing
    edge carries the larger tension."""
    f = 0.3
    s = mp.solve(vstar=0.0, kw=math.inf, radius=100.0, load=2e-9, friction=f)
    assert isinstance(s, AsymmetricSolution)
    back, front = s.contact_interval
    w = s.half_width
    gb, gf = s.end_exponents
    peak = s.max_pressure if isinstance(s, AsymmetricSolution) else 1.0

    def cauchy(x: float) -> float:
        if back < x < front:
            return float(
                quad(s.pressure, back, front, weight="cauchy", wvar=x, limit=400)[0]
            )
        return float(
            quad(
                lambda t: _smooth(s, t) / (t - x),
                back,
                front,
                weight="alg",
                wvar=(gb, gf),
                limit=400,
            )[0]
        )

    for x in [
        back - 0.5 * w,
        back - 0.01 * w,
        s.centre - 0.4 * w,
        s.centre + 0.7 * w,
        front + 0.01 * w,
        front + 2 * w,
    ]:
        expect = -s.pressure(x) + 2 * f / math.pi * cauchy(x)
        assert s.surface_stress(x) == pytest.approx(expect, abs=3e-3 * peak)
    assert (
        s.surface_stress(back - 1e-6 * w)
        > s.surface_stress(front + 1e-6 * w) + 0.1 * peak
    )


@pytest.mark.parametrize(
    "case",
    [
        {"vstar": 0.3, "kw": 1.0, "friction": 0.5},
        {"vstar": 0.2, "kw": 0.1, "friction": 1.0},
        {"vstar": 0.65, "kw": 1.0, "friction": 0.5, "damping": 0.1},
    ],
)
def test_error_estimates_are_honest(case: dict[str, float]) -> None:
    """Against a fixed n = 96 reference at tol 1e-14: the estimates of the
    ends, the pressure shape and the surface sigma_x bound the actual errors
    of coarse fixed sizes (n = 8, 12) and of the automatic solve, and are
    not absurdly larger (within 1e3 of the actual error or of the floor)."""
    ref = mp.solve(radius=100, load=0.002, n=96, tol=1e-14, **case)
    assert isinstance(ref, AsymmetricSolution)
    for n in (8, 12, None):
        s = mp.solve(radius=100, load=0.002, n=n, **case)
        assert isinstance(s, AsymmetricSolution)
        actual = max(
            abs(u - v)
            for u, v in zip(s.contact_interval, ref.contact_interval, strict=True)
        )
        assert actual <= s.error_estimate + ref.error_estimate, n
        assert s.error_estimate <= 1e3 * actual + 1e-12 * s.half_width, n
        r = np.linspace(-0.99, 0.99, 199)
        p = s.pressure(s.centre + s.half_width * r)
        pr = ref.pressure(ref.centre + ref.half_width * r)
        perr = float(np.max(np.abs(p - pr)))
        assert perr <= s.pressure_error_estimate + ref.pressure_error_estimate, n
        assert s.pressure_error_estimate <= 1e3 * perr + 1e-11 * s.max_pressure, n
        xs = s.centre + s.half_width * np.array([-1.5, -0.5, 0.3, 0.9, 1.4])
        serr = float(np.max(np.abs(s.surface_stress(xs) - ref.surface_stress(xs))))
        assert serr <= s.stress_error_estimate + ref.stress_error_estimate, n


@pytest.mark.parametrize("bad", [math.nan, math.inf, -0.1, "0.3", True, None])
def test_bad_friction_is_refused(bad: object) -> None:
    with pytest.raises(InvalidParameterError) as err:
        mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, friction=bad)  # type: ignore[arg-type]
    assert err.value.parameter == "friction"
    assert "friction" in str(err.value)


def test_friction_without_damping_above_critical_speed_is_refused() -> None:
    with pytest.raises(SupercriticalSpeedError):
        mp.solve(vstar=0.6, kw=1.0, radius=100, load=0.002, friction=0.3)


def test_to_dict_and_the_surface_traction() -> None:
    s = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, friction=0.3)
    d = s.to_dict()
    assert d["tangential_force"] == 0.3
    assert d["end_exponents"] == list(s.end_exponents)
    assert d["indentation"] == s.indentation
    top = s.stress_field([0.0, 0.1], [0.0])
    assert top.tau_xy[0] == pytest.approx(
        0.3 * s.pressure(np.array([0.0, 0.1])), rel=1e-15
    )


@pytest.mark.parametrize(("kw", "damping"), [(1.0, 0.0), (math.inf, 0.0), (1.0, 0.3)])
def test_displacement_follows_the_punch(kw: float, damping: float) -> None:
    """The surface displacement (its half-plane parts from the Jacobi
    density's log potential, the shear traction's Poisson step in closed
    form) makes the gap -delta + x^2/(2R) - v(x, 0) vanish on the contact
    (measured 4e-18), and beside it equals the integral of x/R minus the
    independently computed surface slope (Cauchy closed form and kernel)."""
    s = mp.solve(
        vstar=0.2, kw=kw, radius=100, load=0.002, friction=0.4, damping=damping
    )
    assert isinstance(s, AsymmetricSolution)
    delta = s.indentation
    x = s.centre + s.half_width * np.linspace(-0.999, 0.999, 21)
    gap = -delta + x**2 / 200.0 - s.surface_displacement(x)
    assert np.max(np.abs(gap)) < 1e-13 * delta
    back = s.contact_interval[0]
    for end in (back - 0.5, back - 2.0):
        # adaptive (QAGS): x/R - v' has the end's d^gamma behaviour
        integral = -quad(
            lambda t: t / 100.0 - s.surface_slope(t),
            end,
            back,
            epsabs=1e-17,
            epsrel=1e-13,
            limit=200,
        )[0]
        g_end = -delta + end**2 / 200.0 - s.surface_displacement(end)
        assert g_end == pytest.approx(integral, abs=1e-11 * delta)
    assert s.displacement(x, 0.0) == pytest.approx(s.surface_displacement(x), abs=1e-15)
    bottom = np.array([-2.0, -0.3, 0.0, 0.6, 2.5])
    if math.isinf(kw):
        assert np.max(np.abs(s.displacement(bottom, -1.0))) < 1e-15
    else:  # two paths: the split one at y = -1 and the bottom face's direct sum
        np.testing.assert_allclose(
            s.displacement(bottom, -1.0),
            s.bottom_displacement(bottom),
            rtol=0,
            atol=1e-12 * delta,
        )


def test_indentation_continuous_in_friction() -> None:
    base = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002)
    tiny = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, friction=1e-10)
    assert tiny.indentation == pytest.approx(base.indentation, rel=1e-8)
    x = np.array([-2.0, -0.2, 0.3, 1.5])
    np.testing.assert_allclose(
        tiny.displacement(x, -0.4),
        base.displacement(x, -0.4),
        rtol=0,
        atol=1e-9 * base.indentation,
    )


@pytest.mark.slow
def test_dissipation_is_the_bottom_slope_by_parseval() -> None:
    """With friction the dashpots take the power of both tractions: the
    Parseval sum equals D sqrt(V*)/load int (dv/dx(x, -1))^2 dx by Simpson's
    rule on the bottom slope (measured agreement: 3e-12 with 601 points,
    7e-16 with 1201; 8e-6 with 301: the rule converges geometrically on
    this smooth, decaying slope); it exceeds the normal pressure's drag (the
    shear traction's power adds)."""
    from scipy.integrate import simpson

    s = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, friction=0.4, damping=0.5)
    assert isinstance(s, AsymmetricSolution)
    xs = np.linspace(-30.0, 30.0, 601)
    slope = s.bottom_slope(xs)
    direct = 0.5 * math.sqrt(0.2) * simpson(slope**2, x=xs) / 0.002
    assert s.dissipation == pytest.approx(direct, rel=1e-8)
    assert s.dissipation > s.drag


def test_end_exponents_function() -> None:
    back, front = end_exponents(0.3, 0.3, 0.2)
    assert 1 / math.tan(math.pi * back) == pytest.approx(
        0.3 * coupling_constant(0.3), rel=1e-13
    )
    assert back + front == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("damping", [0.0, 0.2])
def test_surface_follows_the_punch_and_separates_beside_it(damping: float) -> None:
    """The surface slope computed from the pressure (Cauchy integral of the
    Jacobi density, the local f Phi p term, the kernel) equals the punch's
    x/R on the contact: a check of the whole representation of p at points
    other than the collocation points; beside the contact the gap opens."""
    s = mp.solve(
        vstar=0.3, kw=1.0, radius=100, load=0.002, friction=0.6, damping=damping
    )
    assert isinstance(s, AsymmetricSolution)
    r = np.linspace(-0.999, 0.999, 41)
    x = s.centre + s.half_width * r
    slope = s.surface_slope(x)
    # measured 8e-18 (the slope scale w/R is 4e-3)
    assert np.max(np.abs(slope - x / 100.0)) < 1e-12 * s.half_width / 100.0
    assert s.min_gap >= 0.0
    assert s.valid


def test_trailing_edge_tension_is_two_f_p0_when_uncoupled() -> None:
    """nu -> 1/2 decouples friction from the pressure (Phi -> 0: Hertz
    pressure, exponents 1/2); the surface sigma_x of a half-plane under the
    Hertz pressure and the traction f p is then -p - 2 f p0 x/a on the
    contact: +2 f p0 at the trailing edge, -2 f p0 at the leading edge
    (Smith & Liu, J. Appl. Mech. 20 (1953) 157; Johnson 1985, section 7.1)."""
    f = 0.25
    s = mp.solve(vstar=0.0, kw=math.inf, radius=100.0, load=2e-9, nu=0.4999, friction=f)
    assert isinstance(s, AsymmetricSolution)
    back, front = s.contact_interval
    p0 = s.max_pressure
    assert s.surface_stress(back) == pytest.approx(2 * f * p0, rel=2e-3)
    assert s.surface_stress(front) == pytest.approx(-2 * f * p0, rel=2e-3)


def test_bundled_friction_scene() -> None:
    """The bundled friction sweep: the f = 0 curve is the frictionless
    solve's (symmetric), the trailing-edge tension grows with f and the
    tension ahead of the leading edge falls; the points equal direct solves."""
    from movingpunch.scene import Scene

    result = Scene.bundled("friction").run()
    width = result.outputs["contact_width"].columns
    assert list(width["friction"]) == [0.0, 0.2, 0.4, 0.6]
    stress = result.outputs["surface_stress"].columns
    x = stress["x"]
    behind, ahead = [], []
    for f in (0.0, 0.2, 0.4, 0.6):
        sx = stress[f"sigma_x[friction={f:g}]"]
        behind.append(float(sx[x < 0].max()))
        ahead.append(float(sx[x > 0].max()))
        s = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, friction=f)
        assert np.allclose(sx, s.surface_stress(x), rtol=0, atol=1e-12)
    assert behind[0] == pytest.approx(ahead[0], abs=1e-9)
    assert all(b2 > b1 for b1, b2 in itertools.pairwise(behind))
    assert all(a2 < a1 for a1, a2 in itertools.pairwise(ahead))
    assert np.all(np.isfinite(width["indentation"]))


def test_friction_bounds_are_the_cores() -> None:
    """The table's range of friction, [0, 10], is the core's (each probe is
    refused by both or by neither), and the message names the parameter."""
    spec = params.SPECS["friction"]
    probes = [0.0, math.nextafter(0.0, -1.0), -0.0, 10.0, math.nextafter(10.0, 11.0)]
    probes += [math.nextafter(10.0, 0.0), math.nan, math.inf]

    def call(x: float) -> None:
        _core.solve_asymmetric(
            vstar=0.2,
            kw=1.0,
            radius=100.0,
            load=0.002,
            nu=0.2,
            damping=0.1,
            tol=1e-4,
            allow_unphysical=True,
            n=8,
            friction=x,
        )

    for x in probes:
        if spec.contains(x):
            call(x)
        else:
            with pytest.raises(InvalidParameterError) as info:
                call(x)
            assert info.value.parameter == "friction"


def _bottom_direct(
    s: AsymmetricSolution, x: np.ndarray, y: float = -1.0
) -> tuple[np.ndarray, np.ndarray]:
    """sigma_x and sigma_y on the bottom face y = -1 by the direct Fourier
    integral (1/pi) Re int_0^inf [Sigma_x, S](normal + i f tangential) p^
    e^{i alpha x} d alpha, from the independent 4x4 layer (eigenvectors) and
    p^ by SciPy's Gauss-Jacobi rule on the solution's pressure (any depth
    y; it converges like exp(nT alpha y)). The bar pole
    C0/alpha of the tangential Sigma_x makes Re(...) ~ sin(alpha x)/alpha:
    integrable as it stands (graded panels near 0)."""
    c2, a = _system(s.vstar, s.nu)
    ev, vec = np.linalg.eig(a)
    ev, vec = ev.real, vec.real
    back, front = s.contact_interval
    gb, gf = s.end_exponents
    r, wr = roots_jacobi(200, gf, gb)
    xs = s.centre + s.half_width * r
    smooth = s.pressure(xs) / ((xs - back) ** gb * (front - xs) ** gf)
    x0, wl = roots_legendre(20)
    top = 60.0 / min(1.0, -y)  # the integrand decays like exp(nT alpha y)
    edges = np.concatenate(
        [[0.0], np.logspace(-7, 0, 50), np.linspace(1.1, top, int(8 * top) + 20)]
    )
    alpha = np.concatenate(
        [0.5 * (b - a) * x0 + 0.5 * (a + b) for a, b in itertools.pairwise(edges)]
    )
    weight = np.concatenate([0.5 * (b - a) * wl for a, b in itertools.pairwise(edges)])
    ep = 4 * (c2 - 1) / c2
    gx = np.empty(alpha.size, complex)
    gy = np.empty(alpha.size, complex)
    for j, t in enumerate(alpha):
        e0 = np.where(ev > 0, 1.0, np.exp(t * ev))
        e1 = np.where(ev > 0, np.exp(-t * ev), 1.0)
        ey = np.where(ev > 0, np.exp(t * ev * y), np.exp(t * ev * (y + 1)))
        top, bot = vec * e0[None, :], vec * e1[None, :]
        at = vec * ey[None, :]
        m = np.zeros((4, 4), complex)
        m[0], m[1], m[2] = top[2], top[3], bot[2]
        k = s.kw - 1j * s.damping * math.sqrt(s.vstar) * t
        m[3] = (t * bot[3] - k * bot[1]) / (t + abs(k))
        zn = at @ np.linalg.solve(m, np.array([0, -1, 0, 0], complex))
        zq = at @ np.linalg.solve(m, np.array([1, 0, 0, 0], complex))
        ph = s.half_width**2 * np.sum(wr * smooth * np.exp(-1j * t * xs))
        sxn = ep * zn[0] + (c2 - 2) / c2 * zn[3]
        sxq = ep * zq[0] + (c2 - 2) / c2 * zq[3]
        gx[j] = (sxn + 1j * s.friction * sxq) * ph
        gy[j] = (zn[3] + 1j * s.friction * zq[3]) * ph
    phase = np.exp(1j * np.multiply.outer(x, alpha))
    return (phase @ (weight * gx)).real / math.pi, (
        phase @ (weight * gy)
    ).real / math.pi


@pytest.mark.parametrize("damping", [0.0, 0.3])
def test_bottom_face_against_a_direct_fourier_sum(damping: float) -> None:
    s = mp.solve(
        vstar=0.2, kw=1.0, radius=100, load=0.002, friction=0.4, damping=damping
    )
    assert isinstance(s, AsymmetricSolution)
    x = np.array([-3.0, -0.8, -0.2, 0.0, 0.3, 1.1, 4.0])
    sx, sy = _bottom_direct(s, x)
    field = s.stress_field(x, [-1.0])
    scale = float(np.max(np.abs(sx)))
    assert np.max(np.abs(field.sigma_x[0] - sx)) < 1e-8 * scale
    assert np.max(np.abs(field.sigma_y[0] - sy)) < 1e-8 * scale
    assert np.max(np.abs(field.tau_xy[0])) < 1e-12 * scale  # the shear-free base


@pytest.mark.parametrize(("vstar", "damping"), [(0.0, 0.0), (0.3, 0.0), (0.65, 0.1)])
def test_far_field_is_the_bar_carrying_the_friction_force(
    vstar: float, damping: float
) -> None:
    """The shear-free base takes no horizontal force: far from the punch the
    layer is a bar, and its momentum balance [sigma_x - rho V^2 u_x] h = -f P
    with sigma_x = Ep u_x (Ep = 4 (c2 - 1)/c2, plane strain, sigma_y = 0)
    makes sigma_x jump by -f C0, C0 = Ep/(Ep - V*), uniform over the
    thickness; the steady state splits it evenly: +f C0/2 far behind,
    -f C0/2 far ahead, on both faces."""
    f = 0.3
    s = mp.solve(
        vstar=vstar, kw=1.0, radius=100, load=0.002, friction=f, damping=damping
    )
    c2, _ = _system(vstar, 0.2)
    ep = 4 * (c2 - 1) / c2
    half_jump = f * ep / (ep - vstar) / 2
    for x, sign in ((-400.0, 1.0), (400.0, -1.0)):
        field = s.stress_field([x], [0.0, -1.0])
        assert field.sigma_x[:, 0] == pytest.approx(
            [sign * half_jump] * 2, abs=2e-3 * f
        )
    if damping == 0.0:  # below V*_cr: the top tension peaks behind the punch
        assert s.stress_peaks().top_tensile_x < 0


@pytest.mark.parametrize(("y", "damping"), [(-0.3, 0.0), (-0.6, 0.3)])
def test_interior_field_against_a_direct_fourier_sum(y: float, damping: float) -> None:
    """Inside the layer the field is the remainder (Filon) plus the
    half-plane parts of the normal load and of the shear traction in closed
    form from the Jacobi density's complex Cauchy potential: checked against
    the direct sum of the independent layer, where it converges."""
    s = mp.solve(
        vstar=0.2, kw=1.0, radius=100, load=0.002, friction=0.4, damping=damping
    )
    assert isinstance(s, AsymmetricSolution)
    x = np.array([-3.0, -0.8, -0.2, 0.0, 0.3, 1.1, 4.0])
    sx, sy = _bottom_direct(s, x, y)
    field = s.stress_field(x, [y])
    scale = float(np.max(np.abs(sx)))
    assert np.max(np.abs(field.sigma_x[0] - sx)) < 1e-8 * scale
    assert np.max(np.abs(field.sigma_y[0] - sy)) < 1e-8 * scale


def test_interior_field_is_continuous_to_both_faces() -> None:
    """y -> 0: sigma_y -> -p, tau_xy -> f p (the shear traction), sigma_x ->
    surface_stress; y -> -1: the interior path (half-plane split) meets the
    bottom face's direct sum; the vertical force balance int sigma_y dx = -P
    holds at depth."""
    f = 0.3
    s = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, friction=f)
    assert isinstance(s, AsymmetricSolution)
    x = np.array([-1.0, -0.2, 0.0, 0.2, 0.5, 1.5])
    near = s.stress_field(x, [-1e-9])
    p = s.pressure(x)
    assert np.max(np.abs(near.sigma_y[0] + p)) < 1e-6
    assert np.max(np.abs(near.tau_xy[0] - f * p)) < 1e-6
    assert np.max(np.abs(near.sigma_x[0] - s.surface_stress(x))) < 1e-6
    inner = s.stress_field(x, [-1.0 + 1e-10])
    face = s.stress_field(x, [-1.0])
    assert np.max(np.abs(inner.sigma_x - face.sigma_x)) < 1e-8
    assert np.max(np.abs(inner.sigma_y - face.sigma_y)) < 1e-8
    xs = np.linspace(-60.0, 60.0, 24001)
    sy = s.stress_field(xs, [-0.5]).sigma_y[0]
    assert float(np.sum(sy) * (xs[1] - xs[0])) == pytest.approx(-1.0, abs=1e-6)
