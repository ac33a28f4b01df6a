"""The flat punch on the asymmetric solver (issue 14; docs/theory.md section
14, "The flat punch on the asymmetric solver"): damping > 0 and/or friction
> 0 with ``profile=mp.Flat(b)``.

The contact is the face (-b, b); p ~ (b - x)^(gamma_front - 1)
(x + b)^(gamma_back - 1) at its edges (index +1), the end coefficients
K_end = lim sqrt(2 pi) d^(1 - gamma_end) p over (P/h) h^(1 - gamma_end).

Every anchor is independent of the solver: the half-plane closed forms
(frictionless: p = P/(pi sqrt(b^2 - x^2)); with friction the classical
Gauss-Jacobi closed form, K. L. Johnson, Contact Mechanics (1985) section
2.8, and D. A. Hills, D. Nowell & A. Sackfield, Mechanics of Elastic
Contacts (1993)), the undamped flat punch (a separately written solver,
contact.cpp's T-series), a NumPy/SciPy Gauss-Jacobi collocation written from
scratch on _core's layer responses, a high-N reference, and the energy
balance (the dashpots' dissipation, computed by Parseval on the bottom face,
against the edges' forces from the end coefficients).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.interpolate import BarycentricInterpolator
from scipy.special import roots_jacobi, roots_legendre

import movingpunch as mp
from movingpunch import _core
from movingpunch.asymmetric import AsymmetricSolution, coupling_constant, end_exponents

LOAD = 0.002


def _roots_jacobi(n: int, a: float, b: float) -> tuple[np.ndarray, np.ndarray]:
    # scipy's recurrence divides 0/0 in a discarded branch when a + b = -1.
    with np.errstate(invalid="ignore", divide="ignore"):
        r, w = roots_jacobi(n, a, b)
    return np.asarray(r), np.asarray(w)


def _interior(b: float) -> np.ndarray:
    return np.array([-0.97, -0.6, -0.2, 0.0, 0.35, 0.8, 0.96]) * b


def _flat(**kw: object) -> AsymmetricSolution:
    s = mp.solve(load=LOAD, **kw)  # type: ignore[call-overload]
    assert isinstance(s, AsymmetricSolution)
    return s


# ---------------------------------------------------------------------------
# 1. The half-plane limit (a face much narrower than the layer).


@pytest.mark.parametrize(
    ("vstar", "kw", "b"),
    [(0.2, 100.0, 1e-4), (0.4, 100.0, 1e-4), (0.2, 1.0, 1e-6)],
)
def test_half_plane_limit(vstar: float, kw: float, b: float) -> None:
    # The layer's correction is O(b |K(0)|) (damping makes the kernel's even
    # part nonzero at u = 0): about 5e-5 b/1e-4 on kw = 1, 2e-8 on kw = 100.
    s = _flat(vstar=vstar, kw=kw, profile=mp.Flat(b), damping=0.5)
    x = _interior(b)
    exact = 1.0 / (math.pi * np.sqrt(b * b - x * x))
    np.testing.assert_allclose(s.pressure(x), exact, rtol=1e-6, atol=0)
    k = 1.0 / math.sqrt(math.pi * b)
    assert s.end_coefficients == pytest.approx((k, k), rel=1e-6)
    assert s.contact_interval == (-b, b)
    assert s.end_exponents == (-0.5, -0.5)
    assert s.pressure(b) == math.inf
    assert s.pressure(-b) == math.inf
    assert s.pressure(1.0001 * b) == 0.0
    assert s.valid
    assert s.tangential_force == 0.0


# ---------------------------------------------------------------------------
# 2. damping -> 0 is the undamped flat punch (contact.cpp's T-series solve).


@pytest.mark.parametrize(
    ("vstar", "kw", "b"), [(0.2, 1.0, 1.0), (0.4, 0.5, 2.0), (0.1, 10.0, 0.3)]
)
def test_vanishing_damping_is_the_undamped_flat_punch(
    vstar: float, kw: float, b: float
) -> None:
    u = mp.solve(vstar=vstar, kw=kw, load=LOAD, profile=mp.Flat(b))
    d = _flat(vstar=vstar, kw=kw, profile=mp.Flat(b), damping=1e-9)
    x = _interior(b)
    np.testing.assert_allclose(d.pressure(x), u.pressure(x), rtol=1e-7)
    ku = u.end_coefficients[0]
    assert d.end_coefficients == pytest.approx((ku, ku), rel=1e-7)
    assert d.indentation == pytest.approx(u.indentation, rel=1e-7)
    xs = np.array([-3.0, -1.5, -0.5, 0.0, 0.5, 1.5, 3.0]) * b
    scale = float(np.max(np.abs(u.surface_stress(xs))))
    np.testing.assert_allclose(
        d.surface_stress(xs), u.surface_stress(xs), rtol=0, atol=1e-7 * scale
    )
    np.testing.assert_allclose(
        d.surface_displacement(xs),
        u.surface_displacement(xs),
        rtol=0,
        atol=1e-7 * u.indentation,
    )
    # Inside the layer and on its bottom face (the undamped solver's field
    # evaluator is its own code too).
    depths = [-0.3, -0.7, -1.0]
    fu, fd = u.stress_field(xs, depths), d.stress_field(xs, depths)
    for name in ("sigma_x", "sigma_y", "tau_xy"):
        np.testing.assert_allclose(
            getattr(fd, name), getattr(fu, name), rtol=0, atol=1e-7 * scale
        )
    np.testing.assert_allclose(
        d.displacement(xs, -0.5), u.displacement(xs, -0.5), atol=1e-7 * u.indentation
    )


@pytest.mark.parametrize("extra", [{"damping": 0.3}, {"damping": 0.3, "friction": 0.5}])
def test_the_base_carries_the_load(extra: dict[str, float]) -> None:
    # Global equilibrium of the layer: int -sigma_y(x, -h) dx = P.
    s = _flat(vstar=0.3, kw=1.0, profile=mp.Flat(1.0), **extra)
    xs = np.linspace(-80.0, 80.0, 16001)
    reaction = s.foundation_reaction(xs)
    assert float(np.trapezoid(reaction, xs)) == pytest.approx(1.0, abs=1e-9)


# ---------------------------------------------------------------------------
# The face stays flat: v(x, 0) = -delta on it, the slope vanishes there.


@pytest.mark.parametrize(
    "extra",
    [{"damping": 0.3}, {"friction": 0.4}, {"damping": 0.2, "friction": 1.0}],
)
def test_the_face_is_flat_and_indentation_is_its_depth(extra: dict[str, float]) -> None:
    b = 0.8
    s = _flat(vstar=0.3, kw=1.0, profile=mp.Flat(b), **extra)
    x = np.linspace(-0.999, 0.999, 11) * b
    v = s.surface_displacement(x)
    assert np.ptp(v) <= 5e-10 * abs(s.indentation)
    assert s.indentation == pytest.approx(-float(v[5]), rel=1e-12)
    assert s.indentation > 0
    assert np.max(np.abs(s.surface_slope(x))) <= 1e-7 * s.load
    # Equilibrium by an independent Gauss-Jacobi rule on the solution's p.
    back, front = s.end_exponents
    r, w = _roots_jacobi(60, front, back)
    g = s.pressure(b * r) / ((1 - r) ** front * (1 + r) ** back)
    assert b * float(w @ g) == pytest.approx(1.0, abs=1e-12)


# ---------------------------------------------------------------------------
# 3. Friction on the static half-plane: the closed form.


@pytest.mark.parametrize("f", [0.3, 1.0, 10.0])
def test_friction_static_half_plane_closed_form(f: float) -> None:
    # p = C (b - x)^(gamma_front - 1) (b + x)^(gamma_back - 1), cot(pi
    # gamma_back) = f Phi, Phi = (1 - 2 nu)/(2 (1 - nu)) (Johnson 1985
    # section 2.8; Hills, Nowell & Sackfield 1993). Equilibrium: int_{-b}^{b}
    # (b - x)^a (b + x)^c dx = (2b)^(a + c + 1) B(a + 1, c + 1) =
    # Gamma(gamma_front) Gamma(gamma_back) = pi/sin(pi gamma_back) (a + c =
    # -1), so C = P sin(pi gamma_back)/pi. The layer (kw = inf: a rigid base
    # one h below) changes p by O(b/h): b = 1e-8.
    b, nu = 1e-8, 0.2
    s = _flat(vstar=0.0, kw=math.inf, nu=nu, profile=mp.Flat(b), friction=f)
    phi = (1 - 2 * nu) / (2 * (1 - nu))
    g_back = math.atan2(1.0, f * phi) / math.pi  # cot(pi g) = f Phi, 0 < g < 1/2
    g_front = 1.0 - g_back
    assert s.end_exponents == pytest.approx((g_back - 1, g_front - 1), abs=1e-14)
    x = _interior(b)
    c = math.sin(math.pi * g_back) / math.pi
    exact = c * (b - x) ** (g_front - 1) * (b + x) ** (g_back - 1)
    np.testing.assert_allclose(s.pressure(x), exact, rtol=1e-6)
    # K_end = sqrt(2 pi) C (2b)^(gamma_other - 1).
    k_back = math.sqrt(2 * math.pi) * c * (2 * b) ** (g_front - 1)
    k_front = math.sqrt(2 * math.pi) * c * (2 * b) ** (g_back - 1)
    assert s.end_coefficients == pytest.approx((k_back, k_front), rel=1e-6)
    assert s.tangential_force == f
    assert s.friction == f
    r, w = _roots_jacobi(40, g_front - 1, g_back - 1)
    g = s.pressure(b * r) / ((1 - r) ** (g_front - 1) * (1 + r) ** (g_back - 1))
    assert b * float(w @ g) == pytest.approx(1.0, abs=1e-12)


def test_friction_to_zero_is_continuous() -> None:
    # f -> 0 (damping 0) approaches the undamped flat punch; the exponents
    # approach -1/2.
    b = 0.7
    u = mp.solve(vstar=0.3, kw=1.0, load=LOAD, profile=mp.Flat(b))
    s = _flat(vstar=0.3, kw=1.0, profile=mp.Flat(b), friction=1e-9)
    x = _interior(b)
    np.testing.assert_allclose(s.pressure(x), u.pressure(x), rtol=1e-7)
    ku = u.end_coefficients[0]
    assert s.end_coefficients == pytest.approx((ku, ku), rel=1e-7)
    assert s.end_exponents == pytest.approx((-0.5, -0.5), abs=1e-8)


# ---------------------------------------------------------------------------
# 4. A moving frictional flat punch on a damped layer against a NumPy/SciPy
# collocation written from scratch.


def _independent_flat(
    s: float, kw: float, nu: float, damping: float, f: float, b: float, n: int
) -> tuple[float, float]:
    """(K_back, K_front) from a plain Gauss-Jacobi collocation of
    f Phi p + (1/pi) int p/(xi - x) - int p Lr(x - xi)/phi1 = 0 on (-b, b),
    int p = 1, with Lr(u) = (1/pi) Re int_0^inf [-i(M1 - phi1) - f (Wq -
    Wq_inf)] e^{i alpha u} d alpha by Gauss-Legendre panels on _core's
    layer responses."""
    phi1 = _core.phi1(s, nu)
    _, wq_inf, phi = _core.tangential_half_plane(s, nu)
    front = 0.5 + math.atan(f * phi) / math.pi
    a1, b1 = front - 1.0, -front  # alpha' = gamma_front - 1, beta' = gamma_back - 1
    r, w = _roots_jacobi(n, a1, b1)
    sk, _ = _roots_jacobi(n - 1, -a1, -b1)
    nt = math.sqrt(1 - s)
    x, wl = roots_legendre(16)
    edges = np.linspace(0.0, 45.0 / nt, 401)
    alpha = np.concatenate(
        [0.5 * (q - p) * x + 0.5 * (p + q) for p, q in itertools.pairwise(edges)]
    )
    weight = np.concatenate([0.5 * (q - p) * wl for p, q in itertools.pairwise(edges)])
    g = np.empty(alpha.size, complex)
    for j, t in enumerate(alpha):
        m1 = _core.damped_layer_response(float(t), s, kw, nu, damping)[0]
        wq = _core.damped_tangential_response(float(t), s, kw, nu, damping)[1]
        g[j] = -1j * (m1 - phi1) - f * (wq - wq_inf)
    u = b * (sk[:, None] - r[None, :])
    kern = (np.exp(1j * np.multiply.outer(u, alpha)) @ (weight * g)).real
    m = np.zeros((n, n))
    m[: n - 1] = (w / math.pi)[None, :] * (
        1 / (r[None, :] - sk[:, None]) - b * kern / phi1
    )
    m[n - 1] = b * w  # int p dx = b int w(r) g(r) dr = 1
    rhs = np.zeros(n)
    rhs[-1] = 1.0
    gn = np.linalg.solve(m, rhs)
    interp = BarycentricInterpolator(r, gn)
    g_back, g_front = float(interp(-1.0)), float(interp(1.0))
    root = math.sqrt(2 * math.pi)
    return (
        root * b ** (-b1) * 2.0**a1 * g_back,
        root * b ** (-a1) * 2.0**b1 * g_front,
    )


def test_moving_frictional_flat_against_an_independent_collocation() -> None:
    vs, kw, nu, damping, f, b = 0.3, 1.0, 0.2, 0.15, 0.4, 0.6
    k40 = _independent_flat(vs, kw, nu, damping, f, b, 40)
    k48 = _independent_flat(vs, kw, nu, damping, f, b, 48)
    assert k48 == pytest.approx(k40, rel=1e-11)  # the reference has converged
    s = _flat(vstar=vs, kw=kw, nu=nu, profile=mp.Flat(b), damping=damping, friction=f)
    assert s.end_coefficients == pytest.approx(k48, rel=1e-8)
    phi = coupling_constant(vs, nu)
    back, front = end_exponents(f, vs, nu)
    assert s.end_exponents == pytest.approx((back - 1, front - 1), abs=1e-14)
    assert 1 / math.tan(math.pi * back) == pytest.approx(f * phi, rel=1e-12)
    assert s.end_coefficient_error <= 1e-8 * max(s.end_coefficients)


# ---------------------------------------------------------------------------
# The energy balance: the dashpots' dissipation (Parseval on the bottom
# face) equals the edges' forces load phi1 (K_front^2 - K_back^2)/4.


@pytest.mark.parametrize(
    ("vstar", "kw", "b", "damping"),
    [(0.2, 1.0, 0.3, 0.1), (0.2, 1.0, 1.0, 0.5), (0.5, 1.0, 2.0, 0.2)],
)
def test_dissipation_equals_the_edges_forces(
    vstar: float, kw: float, b: float, damping: float
) -> None:
    s = _flat(vstar=vstar, kw=kw, profile=mp.Flat(b), damping=damping)
    k_back, k_front = s.end_coefficients
    assert k_front > k_back > 0  # the dashpots load the leading edge
    edges = s.load * s.phi1 * (k_front**2 - k_back**2) / 4
    assert s.drag == pytest.approx(edges, rel=1e-14)
    assert s.dissipation == pytest.approx(edges, rel=1e-8)


# ---------------------------------------------------------------------------
# 5. Error estimates bound the actual error (against a fixed-N reference);
# hard cases.

HONEST = {
    "damped": {"vstar": 0.2, "kw": 1.0, "profile": mp.Flat(1.0), "damping": 0.1},
    "wide-friction": {
        "vstar": 0.2,
        "kw": 1.0,
        "profile": mp.Flat(5.0),
        "friction": 0.3,
    },
    "near-critical": {
        "vstar": 0.999 * mp.critical_vstar(1.0, 0.2),
        "kw": 1.0,
        "profile": mp.Flat(1.0),
        "damping": 0.05,
    },
    "friction-10": {
        "vstar": 0.2,
        "kw": 10.0,
        "profile": mp.Flat(0.5),
        "damping": 0.1,
        "friction": 10.0,
    },
    "tiny-face": {"vstar": 0.2, "kw": 1.0, "profile": mp.Flat(1e-6), "damping": 0.3},
    "soft-wide": {"vstar": 0.1, "kw": 0.1, "profile": mp.Flat(15.0), "damping": 1.0},
}


@pytest.mark.parametrize("name", sorted(HONEST))
@pytest.mark.parametrize("tol", [1e-4, 1e-8])
def test_error_estimates_bound_the_error(name: str, tol: float) -> None:
    args = HONEST[name]
    ref = _flat(**args, n=256)
    s = _flat(**args, tol=tol)
    kmax = max(map(abs, ref.end_coefficients))
    assert ref.end_coefficient_error <= 1e-9 * kmax
    actual = max(
        abs(p - q)
        for p, q in zip(s.end_coefficients, ref.end_coefficients, strict=True)
    )
    assert actual <= s.end_coefficient_error + ref.end_coefficient_error
    assert s.end_coefficient_error <= tol * kmax or s.warnings
    # The pressure's bound is on g = p/w(r): |dp| <= pressure_error_estimate w(r).
    b = s.half_width
    back, front = s.end_exponents
    r = np.linspace(-0.999, 0.999, 41)
    wr = (1 - r) ** front * (1 + r) ** back
    dp = np.abs(s.pressure(b * r) - ref.pressure(b * r))
    assert np.all(dp <= (s.pressure_error_estimate + ref.pressure_error_estimate) * wr)
    # The surface sigma_x more than 1e-3 b from the edges, on and beside the face.
    xs = b * np.array([-3.0, -1.5, -1.01, -0.99, -0.5, 0.0, 0.5, 0.99, 1.01, 1.5, 3.0])
    ds = np.abs(s.surface_stress(xs) - ref.surface_stress(xs))
    assert np.all(ds <= s.stress_error_estimate + ref.stress_error_estimate)
    assert all(math.isfinite(v) for v in s.end_coefficients)
    assert math.isfinite(s.indentation)


def test_huge_face_on_a_soft_foundation_is_refused_clearly() -> None:
    # 20 h on kw = 0.01 near V*_cr: the pressure goes negative inside the face.
    args = {
        "vstar": 0.99 * mp.critical_vstar(0.01, 0.2),
        "kw": 0.01,
        "profile": mp.Flat(20.0),
        "damping": 0.5,
    }
    with pytest.raises(mp.UnphysicalContactError, match="negative inside the face"):
        _flat(**args)
    s = _flat(**args, allow_unphysical=True)
    assert not s.valid
    assert s.pressure_margin < 0
    assert all(math.isfinite(v) for v in s.end_coefficients)
    assert math.isfinite(s.end_coefficient_error)
    assert np.all(np.isfinite(s.pressure(np.linspace(-19.9, 19.9, 51))))


def test_tensile_edge_is_named() -> None:
    # Above V*_cr with light damping on a narrow face the trailing edge's
    # coefficient goes negative: the edge would pull on the layer.
    args = {"vstar": 0.7, "kw": 1.0, "profile": mp.Flat(0.3), "damping": 0.05}
    with pytest.raises(mp.UnphysicalContactError, match="trailing edge"):
        _flat(**args)
    s = _flat(**args, allow_unphysical=True)
    assert not s.valid
    assert "trailing edge" in s.validity
    k_back, k_front = s.end_coefficients
    assert k_back < 0 < k_front
    assert math.isfinite(s.end_coefficient_error)


def test_bad_inputs_name_the_parameter() -> None:
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.Flat(0.5), damping=-1.0)
    assert info.value.parameter == "damping"
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.Flat(0.5), friction=11.0)
    assert info.value.parameter == "friction"
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(vstar=0.2, kw=1.0, load=LOAD, profile=mp.Flat(0.5), damping=0.1, n=7)
    assert info.value.parameter == "n"


def test_stress_peaks_see_both_sides_and_the_singular_edges() -> None:
    b = 0.3
    s = _flat(vstar=0.2, kw=1.0, profile=mp.Flat(b), damping=0.5)
    peaks = s.stress_peaks()
    assert peaks.top_compressive == -math.inf
    assert peaks.top_compressive_x == b  # K_front > K_back > 0
    assert math.isfinite(peaks.top_tensile)
    # The search covers x < 0 too (damping: sigma_x is not even): no grid
    # point away from the edges exceeds the tensile peak.
    grid = np.concatenate(
        [np.linspace(-10, -1.001 * b, 400), np.linspace(1.001 * b, 10, 400)]
    )
    assert (
        float(np.max(s.surface_stress(grid))) <= peaks.top_tensile + peaks.error_bound
    )
    assert any("singular" in w for w in peaks.warnings)
    # Friction: the shear traction's Cauchy term is +inf just behind the
    # trailing edge (and -inf inside the face).
    f = _flat(vstar=0.2, kw=1.0, profile=mp.Flat(b), friction=0.3)
    assert f.surface_stress(-b - 1e-7) > 1e3
    assert f.surface_stress(-b + 1e-7) < -1e3
    fp = f.stress_peaks()
    assert fp.top_tensile == math.inf
    assert fp.top_tensile_x == -b
    assert fp.top_compressive == -math.inf
    assert math.isfinite(fp.bottom_tensile)


@pytest.mark.parametrize("extra", [{"damping": 0.2}, {"damping": 0.2, "friction": 0.3}])
def test_large_fixed_n_keeps_every_output(extra: dict[str, float]) -> None:
    # The closed-form Cauchy potential's terms grow like rho^N off the face:
    # at N = 512 it must hand over to the Gauss-Jacobi rule (once 1e238).
    args = {"vstar": 0.2, "kw": 1.0, "profile": mp.Flat(0.5), **extra}
    auto = _flat(**args)
    big = _flat(**args, n=512)
    assert big.indentation == pytest.approx(auto.indentation, rel=1e-10)
    x = np.array([-1.0, 0.2, 0.7])
    np.testing.assert_allclose(
        big.stress_field(x, [-0.3]).sigma_x,
        auto.stress_field(x, [-0.3]).sigma_x,
        rtol=1e-9,
        atol=1e-9,
    )


def test_tui_summary_carries_both_end_coefficients() -> None:
    from movingpunch.tui.model import Cache, Params, summary

    params = Params(vstar=0.2, kw=1.0, profile="flat", half_width=0.3, damping=0.5)
    s = summary(Cache(), params)
    solved = _flat(vstar=0.2, kw=1.0, profile=mp.Flat(0.3), damping=0.5)
    assert (s.end_coefficient_back, s.end_coefficient) == solved.end_coefficients
    assert s.end_coefficient_back < s.end_coefficient
