"""Viscoelastic layers (issue 28; docs/theory.md section 17): a rigid cylinder
on a quasi-static standard linear solid (Zener) or generalised Maxwell
(Prony) layer on springs.

Independent anchors:

* Hunter's closed form for a rigid cylinder rolling on a viscoelastic
  (standard linear solid) half-space: S. C. Hunter, "The rolling contact of a
  rigid cylinder with a viscoelastic half space", J. Appl. Mech. 28 (1961)
  611-617 (reproduced by B. N. J. Persson, Eur. Phys. J. E 33 (2010) 327).
  ``hunter`` below is our own derivation of it (docs/theory.md section 17.4):
  with Q = p - D p' the contact problem becomes a Cauchy equation with a
  linear right side, and the two ends' conditions are linear in its
  coefficients with the modified Bessel functions I0, I1 of a/(V tau) and K0,
  K1 of a/(ratio V tau). The layer solver approaches it like (a0/h)^2.
* The elastic limits: deborah -> 0 is the elastic layer of the relaxed
  modulus mu_0, deborah -> inf that of the unrelaxed mu_inf = ratio mu_0
  (load and kw over the ratio in mu_0's units), ratio = 1 the elastic layer.
* The energy balance: the drag (from the collocation's pressure and the
  punch's slope) equals the power the layer dissipates per unit distance,
  computed independently by Parseval on the surface from Im M1.
"""

from __future__ import annotations

import json
import math
import subprocess
from collections.abc import Callable

import numpy as np
import pytest
from scipy import optimize, special

import movingpunch as mp
from movingpunch.errors import InvalidParameterError

NU = 0.2
PHI0 = 1.0 - NU  # the relaxed static half-plane's phi1
R = 100.0


def hunter(ratio: float, D: float, radius: float, load: float, phi0: float):
    """(centre, half-width, drag) of a rigid cylinder (radius R) pressed by P
    (per mu_0) sliding quasi-statically over a standard-linear-solid half-plane
    of relaxed compliance factor phi0 = 1 - nu, unrelaxed modulus ratio mu_0,
    D = V tau (tau: relaxation at constant strain), all lengths in one unit.

    Q = p - D p' solves phi0 H[Q] = (x - ratio D)/R on the contact:
    Q(r) = [A0 - f0 r + f1 (1 - r^2)]/sqrt(1 - r^2) (x = c + w r) with
    f1 = w/(phi0 R), f0 = (c - ratio D)/(phi0 R); p(-b) = 0 and the
    undifferentiated equation give
        A0 I0(k) + f0 I1(k) + f1 I1(k)/k = 0,      k = w/D,
        A0 K0(k') - f0 K1(k') - f1 K1(k')/k' = 0,  k' = w/(ratio D),
    and P = pi w (A0 + f1/2); drag = int p x/R / P = (c - D)/R - pi w^2 f0/(2 P R)."""

    def coefficients(w: float) -> tuple[float, float]:
        k, kp = w / D, w / (ratio * D)
        # Exponentially scaled: only the ratios within each row matter.
        i0, i1 = special.ive(0, k), special.ive(1, k)
        k0, k1 = special.kve(0, kp), special.kve(1, kp)
        a, f = np.linalg.solve(np.array([[i0, i1], [k0, -k1]]), [-i1 / k, k1 / kp])
        return float(a), float(f)  # A0/f1, f0/f1

    def carried(w: float) -> float:
        a, _ = coefficients(w)
        return math.pi * w * w / (phi0 * radius) * (a + 0.5) - load

    w0 = math.sqrt(2.0 * phi0 * radius * load / math.pi)  # the relaxed Hertz width
    w = optimize.brentq(
        carried, 0.4 * w0 / math.sqrt(ratio), 2.0 * w0, xtol=1e-15, rtol=1e-15
    )
    _, f = coefficients(w)
    c = ratio * D + w * f
    f0 = f * w / (phi0 * radius)
    drag = (c - D) / radius - math.pi * w * w * f0 / (2.0 * load * radius)
    return c, w, drag


def material_solve(material, load: float, kw: float = 1.0, **kw_):
    layer = mp.Layer(nu=NU, viscoelastic=material)
    return mp.solve(
        vstar=0.0, load=load, radius=R, layers=[layer], base=mp.Winkler(kw), **kw_
    )


def zener_solve(ratio: float, deborah: float, load: float, kw: float = 1.0, **kw_):
    return material_solve(mp.Zener(ratio, deborah), load, kw, **kw_)


def half_plane_case(ratio: float, v_tau: float, a0: float):
    """The layer's and Hunter's (ends, drag R/a0) at Hertz half-width a0/h
    (relaxed) and V tau/a0 = v_tau."""
    load = math.pi * a0 * a0 / (2.0 * PHI0 * R)
    D = v_tau * a0
    c, w, drag = hunter(ratio, D, R, load, PHI0)
    s = zener_solve(ratio, D, load)
    left, right = s.contact_interval
    err_ends = max(abs(right - (c + w)), abs(left - (c - w))) / a0
    err_drag = abs(s.drag - drag) * R / a0
    return err_ends, err_drag, drag * R / a0, s


@pytest.mark.parametrize("ratio", [2.0, 10.0])
@pytest.mark.parametrize("v_tau", [0.3, 1.0])
def test_the_layer_approaches_hunters_half_plane_like_a0_squared(ratio, v_tau):
    e1, d1, _, _ = half_plane_case(ratio, v_tau, 0.02)
    e2, d2, _, s = half_plane_case(ratio, v_tau, 0.01)
    # (a0/h)^2: halving a0/h divides the difference by about 4.
    assert 3.0 < e1 / e2 < 5.0, (e1, e2)
    assert 2.5 < d1 / d2 < 5.0, (d1, d2)
    assert e2 < 1e-3
    assert d2 < 1e-3
    assert s.valid
    assert not s.warnings


@pytest.mark.parametrize("ratio", [2.0, 10.0])
def test_the_resistance_curve_and_its_maximum_follow_hunters(ratio):
    """(F/P)(R/a0) against V tau/a0 rises and falls (the bell curve); its
    maximum from the layer at a0/h = 0.01 is Hunter's to 1e-3."""

    def hunter_curve(v_tau: float) -> float:
        a0 = 1.0
        load = math.pi * a0 * a0 / (2.0 * PHI0 * R)
        return hunter(ratio, v_tau * a0, R, load, PHI0)[2] * R / a0

    best = optimize.minimize_scalar(
        lambda lv: -hunter_curve(math.exp(lv)), bounds=(-5, 3), method="bounded"
    )
    v_max, f_max = math.exp(best.x), -best.fun
    # A maximum inside: both sides lower.
    assert hunter_curve(0.5 * v_max) < f_max
    assert hunter_curve(2.0 * v_max) < f_max
    layer = [
        half_plane_case(ratio, v, 0.01)[3].drag * R / 0.01
        for v in (0.5 * v_max, v_max, 2.0 * v_max)
    ]
    assert layer[1] > layer[0]
    assert layer[1] > layer[2]
    assert abs(layer[1] - f_max) < 1e-3 * f_max, (layer[1], f_max)


def test_deborah_zero_and_infinity_are_the_relaxed_and_unrelaxed_layers():
    ratio, load, kw = 2.0, 0.002, 1.0
    relaxed = mp.solve(vstar=0.0, load=load, radius=R, kw=kw, nu=NU)
    # mu_inf = ratio mu_0: in its own units the load and kw are over the ratio.
    unrelaxed = mp.solve(vstar=0.0, load=load / ratio, radius=R, kw=kw / ratio, nu=NU)
    slow = zener_solve(ratio, 1e-12, load, kw)
    fast = zener_solve(ratio, 1e12, load, kw)
    assert slow.contact_interval == pytest.approx((-relaxed.a, relaxed.a), abs=1e-10)
    assert fast.contact_interval == pytest.approx(
        (-unrelaxed.a, unrelaxed.a), abs=1e-10
    )
    assert abs(slow.drag) < 1e-10
    assert abs(fast.drag) < 1e-10
    # The indentation too (its memory part in closed form).
    assert slow.indentation == pytest.approx(relaxed.indentation, rel=1e-9)
    assert fast.indentation == pytest.approx(unrelaxed.indentation, rel=1e-9)


def test_ratio_one_and_deborah_zero_are_the_elastic_layer_exactly():
    elastic = mp.solve(vstar=0.0, load=0.002, radius=R, kw=1.0, nu=NU)
    for v in (mp.Zener(1.0, 0.3), mp.Zener(3.0, 0.0)):
        s = mp.solve(
            vstar=0.0,
            load=0.002,
            radius=R,
            layers=[mp.Layer(nu=NU, viscoelastic=v)],
            base=mp.Winkler(1.0),
        )
        assert type(s) is type(elastic)
        assert s.a == elastic.a


def _integral(s) -> float:
    """int p dx/(P/h) by Gauss-Chebyshev (second kind) at 400 nodes."""
    left, right = s.contact_interval
    c, w = 0.5 * (left + right), 0.5 * (right - left)
    m = 400
    th = np.arange(1, m + 1) * math.pi / (m + 1)
    return float(
        w * math.pi / (m + 1) * np.sum(np.sin(th) * s.pressure(c + w * np.cos(th)))
    )


CASES = [
    (mp.Zener(2.0, 0.05), 1.0, 0.002),
    (mp.Zener(10.0, 0.3), 1.0, 0.002),
    (mp.Zener(1000.0, 0.01), 1.0, 0.002),
    (mp.Zener(3.0, 0.1), 0.1, 0.002),
    (mp.Zener(3.0, 0.1), math.inf, 0.01),
    (mp.Prony((0.5, 2.0, 4.0), (0.02, 0.3, 5.0), 1.5), 1.0, 0.002),
]


@pytest.mark.parametrize(("material", "kw", "load"), CASES)
def test_drag_is_the_dissipation_and_the_pressure_carries_the_load(material, kw, load):
    s = material_solve(material, load, kw)
    assert s.valid
    assert not s.warnings
    assert s.drag > 0.0  # it resists the motion
    assert abs(s.drag - s.dissipation) <= 1e-10 * s.drag
    assert abs(_integral(s) - 1.0) < 1e-10
    left, right = s.contact_interval
    x = np.linspace(left, right, 801)[1:-1]
    assert np.all(s.pressure(x) >= 0.0)
    # The contact shifts forward (towards +x, the direction of motion).
    assert left + right > 0.0
    # The slope is the punch's on the contact.
    xs = np.linspace(left, right, 9)[1:-1]
    assert np.allclose(s.surface_slope(xs), xs / R, rtol=1e-8, atol=1e-12)


def tilted_table(tilt: float = 1e-3) -> mp.Profile:
    """A convex table: the cylinder's parabola tilted by ``tilt`` (an
    asymmetric punch: a sliding wheel's worn profile)."""
    x = np.linspace(-0.6, 0.6, 49)
    return mp.Profile(tuple(x), tuple(x * x / (2.0 * R) + tilt * x))


def test_a_table_on_a_viscoelastic_layer_meets_its_elastic_limits_and_balance():
    """A convex (here asymmetric) table on the Zener layer: deborah 1e-12 and
    1e12 are the relaxed and unrelaxed elastic layers under the same table
    (the elastic asymmetric solver), on the ends to 1e-10; between them the
    drag is the dissipation to 1e-10, the pressure carries the load and is
    >= 0."""
    table, load, ratio = tilted_table(), 0.002, 2.0

    def on(material):
        layer = mp.Layer(nu=NU, viscoelastic=material)
        return mp.solve(
            vstar=0.0, load=load, profile=table, layers=[layer], base=mp.Winkler(1.0)
        )

    relaxed = mp.solve(vstar=0.0, load=load, profile=table, kw=1.0, nu=NU)
    unrelaxed = mp.solve(
        vstar=0.0, load=load / ratio, profile=table, kw=1.0 / ratio, nu=NU
    )
    slow, fast = on(mp.Zener(ratio, 1e-12)), on(mp.Zener(ratio, 1e12))
    assert slow.contact_interval == pytest.approx(relaxed.contact_interval, abs=1e-10)
    assert fast.contact_interval == pytest.approx(unrelaxed.contact_interval, abs=1e-10)
    s = on(mp.Zener(ratio, 0.05))
    assert s.valid
    assert not s.warnings
    assert s.drag > 1e-5
    assert abs(s.drag - s.dissipation) <= 1e-10 * s.drag
    assert abs(_integral(s) - 1.0) < 1e-10
    left, right = s.contact_interval
    x = np.linspace(left, right, 801)[1:-1]
    assert np.all(s.pressure(x) >= 0.0)
    # The memory shifts the contact forward of the relaxed one's.
    assert left + right > sum(relaxed.contact_interval)


def test_a_short_memory_dissipation_settles_or_is_flagged():
    """deborah 1e-4 (memory 2e-4 h under a 0.33 h contact): the Parseval
    reach runs to alpha h ~ 1e6 before the total settles, at its round-off
    floor, and the energy balance holds to 1e-10 (it stopped at the cap of
    2^16 panels and returned silently before). deborah 1e-6: the memory is
    below the nodes' spacing; the solve says so in warnings, and the
    dissipation still returns (the balance is then off by what the warning
    says)."""
    s = zener_solve(2.0, 1e-4, 0.002)
    assert not s.warnings
    assert abs(s.drag - s.dissipation) <= 1e-10 * s.drag
    short = zener_solve(2.0, 1e-6, 0.002)
    assert any("viscoelastic memory" in w for w in short.warnings)
    assert abs(short.drag - short.dissipation) < 1e-4 * short.drag


def test_prony_limits_and_the_shift_factor():
    weights, deborahs = (0.5, 2.0, 4.0), (0.02, 0.3, 5.0)

    def prony(ds, shift=1.0, load=0.002):
        return mp.solve(
            vstar=0.0,
            load=load,
            radius=R,
            layers=[mp.Layer(nu=NU, viscoelastic=mp.Prony(weights, ds, shift))],
            base=mp.Winkler(1.0),
        )

    # The shift multiplies every relaxation time.
    a = prony(deborahs, shift=2.0)
    b = prony(tuple(2.0 * d for d in deborahs))
    assert a.contact_interval == b.contact_interval
    assert a.drag == b.drag
    # All relaxed / all unrelaxed: the elastic layers of mu_0 and 7.5 mu_0.
    relaxed = mp.solve(vstar=0.0, load=0.002, radius=R, kw=1.0, nu=NU)
    unrelaxed = mp.solve(vstar=0.0, load=0.002 / 7.5, radius=R, kw=1.0 / 7.5, nu=NU)
    assert prony((1e-12,) * 3).contact_interval == pytest.approx(
        (-relaxed.a, relaxed.a), abs=1e-10
    )
    assert prony((1e12,) * 3).contact_interval == pytest.approx(
        (-unrelaxed.a, unrelaxed.a), abs=1e-10
    )


def test_the_modulus_and_its_sign():
    z = mp.Zener(3.0, 0.2)
    t = np.array([0.0, 0.5, 2.0, 1e4])
    want = (1 - 3j * 0.2 * t) / (1 - 0.2j * t)
    assert np.allclose(z.modulus(t), want, rtol=1e-15)
    assert np.all(z.modulus(t[1:]).imag < 0)  # e^{-i omega t}: a loss
    p = mp.Prony((2.0,), (0.2,))
    assert np.allclose(p.modulus(t), want, rtol=1e-15)


def test_what_is_not_solved_yet_is_refused_by_name():
    layer = [mp.Layer(nu=NU, viscoelastic=mp.Zener(2.0, 0.1))]
    args = {"load": 0.002, "layers": layer, "base": mp.Winkler(1.0)}
    with pytest.raises(InvalidParameterError) as e:
        mp.solve(vstar=0.0, radius=R, friction=0.2, **args)
    assert e.value.parameter == "friction"
    # (A flat punch is solved: tests/python/test_viscoelastic_flat.py.)
    with pytest.raises(InvalidParameterError, match="not solved yet") as e:
        mp.solve(vstar=0.0, profile=mp.RoundedFlat(0.3, 100.0), **args)
    assert e.value.parameter == "profile"
    with pytest.raises(InvalidParameterError) as e:
        mp.solve(
            vstar=0.0,
            radius=R,
            load=0.002,
            layers=layer,
            base=mp.Winkler(1.0, damping=0.5),
        )
    assert e.value.parameter == "damping"
    s = mp.solve(vstar=0.0, radius=R, **args)
    assert s.displacement([0.1, 0.4], 0.0) == pytest.approx(
        s.surface_displacement([0.1, 0.4]), rel=1e-14
    )


@pytest.mark.parametrize("y", [-0.01, -0.3, -1.0])
def test_the_displacement_below_the_surface_meets_the_elastic_limits(y):
    """deborah 1e-12 / 1e12: the relaxed and unrelaxed elastic layers'
    displacement at depth (their own path, the elastic half-plane in closed
    form), to 1e-9 of its largest value."""
    ratio, load, kw = 2.0, 0.002, 1.0
    x = np.linspace(-2.0, 2.0, 17)
    relaxed = mp.solve(vstar=0.0, load=load, radius=R, kw=kw, nu=NU)
    unrelaxed = mp.solve(vstar=0.0, load=load / ratio, radius=R, kw=kw / ratio, nu=NU)
    for deborah, elastic in ((1e-12, relaxed), (1e12, unrelaxed)):
        want = elastic.displacement(x, y)
        got = zener_solve(ratio, deborah, load, kw).displacement(x, y)
        assert np.max(np.abs(got - want)) < 1e-9 * np.max(np.abs(want)), deborah


def test_the_strains_meet_the_elastic_limits_and_the_displacement():
    """A mode's strain is its stress over mu_0 m(alpha): deborah 1e-12 gives
    the relaxed layer's strains, 1e12 the unrelaxed one's (per P/(mu_0 h):
    its own over the ratio), to 1e-10; and eps_y is dv/dy of the
    displacement (computed apart, through the half-plane's closed form and
    its memory) to the central difference's 1e-7. (Hooke's law at mu_0 alone
    gave the relaxed material's strains at every deborah before.)"""
    ratio, load, kw = 2.0, 0.002, 1.0
    x = np.linspace(-1.5, 1.5, 13)
    ys = np.array([0.0, -0.3, -1.0])
    relaxed = mp.solve(vstar=0.0, load=load, radius=R, kw=kw, nu=NU)
    unrelaxed = mp.solve(vstar=0.0, load=load / ratio, radius=R, kw=kw / ratio, nu=NU)
    for deborah, elastic, scale in ((1e-12, relaxed, 1.0), (1e12, unrelaxed, ratio)):
        got = zener_solve(ratio, deborah, load, kw).strain_field(x, ys)
        want = elastic.strain_field(x, ys)
        for name in ("eps_x", "eps_y", "gamma_xy"):
            g, w = getattr(got, name), getattr(want, name) / scale
            assert np.max(np.abs(g - w)) < 1e-10 * np.max(np.abs(w)), (deborah, name)
    s = zener_solve(10.0, 0.1, load, kw)
    y0, h = -0.3, 1e-4
    eps_y = s.strain_field(x, np.array([y0])).eps_y[0]
    dv_dy = (s.displacement(x, y0 + h) - s.displacement(x, y0 - h)) / (2.0 * h) / load
    assert np.max(np.abs(eps_y - dv_dy)) < 1e-7 * np.max(np.abs(eps_y))
    # The design strain at the layer's bottom: between the relaxed and the
    # unrelaxed layers' (the material stiffens with frequency).
    bottom = s.design_strains().bottom_horizontal[0]
    soft = mp.solve(vstar=0.0, load=load, radius=R, kw=kw, nu=NU)
    stiff = mp.solve(vstar=0.0, load=load / 10.0, radius=R, kw=kw / 10.0, nu=NU)
    lo, hi = sorted(
        (
            soft.design_strains().bottom_horizontal[0],
            stiff.design_strains().bottom_horizontal[0] / 10.0,
        )
    )
    assert lo < bottom < hi


@pytest.mark.parametrize(
    ("material", "kw", "load"),
    [(mp.Zener(10.0, 0.1), 1.0, 0.002), (mp.Zener(1000.0, 0.01), 0.1, 0.002)],
)
def test_the_displacement_at_the_base_is_what_the_springs_push(material, kw, load):
    """On Winkler springs sigma_y(x, -h) = k_w v(x, -h): the stress, whose
    half-plane part has no memory (a stress per unit pressure does not depend
    on the modulus), against the displacement, whose half-plane part at depth
    carries the material's memory (its convolution taken there), to 1e-12.
    And v at y -> 0 is the surface's (computed in closed form otherwise)."""
    s = material_solve(material, load, kw)
    x = np.linspace(-3.0, 3.0, 25)
    v = s.displacement(x, -1.0)
    sigma_y = s.stress_field(x, np.array([-1.0])).sigma_y[0]
    assert np.max(np.abs(kw * v / load - sigma_y)) < 1e-12 * np.max(np.abs(sigma_y))
    top = s.displacement(x, 0.0)
    near = s.displacement(x, -1e-9)
    assert np.max(np.abs(near - top)) < 1e-8 * np.max(np.abs(top))


@pytest.mark.parametrize(
    ("make", "parameter"),
    [
        (lambda: mp.Zener(0.5, 0.1), "ratio"),
        (lambda: mp.Zener(2.0, float("nan")), "deborah"),
        (lambda: mp.Zener(2.0, -1.0), "deborah"),
        (lambda: mp.Zener(float("inf"), 0.1), "ratio"),
        (lambda: mp.Zener("2", 0.1), "ratio"),
        (lambda: mp.Prony((1.0, 2.0), (0.1,)), "deborahs"),
        (lambda: mp.Prony((1.0, -2.0), (0.1, 0.2)), "weights"),
        (lambda: mp.Prony((1.0,), (0.1,), shift=0.0), "shift"),
        (lambda: mp.Prony("ab", (0.1,)), "weights"),
        (lambda: mp.Layer(viscoelastic="zener"), "viscoelastic"),
    ],
)
def test_bad_materials_name_their_parameter(make, parameter):
    with pytest.raises(InvalidParameterError) as e:
        make()
    assert e.value.parameter == parameter


def test_the_medium_says_it_is_viscoelastic():
    layer = mp.Layer(nu=NU, viscoelastic=mp.Zener(2.0, 0.1))
    m = mp.Medium((layer,), mp.Winkler(1.0))
    assert m.viscoelastic
    assert not m.homogeneous
    assert "Zener ratio 2, deborah 0.1" in m.describe()
    assert layer.to_dict()["viscoelastic"] == {
        "kind": "zener",
        "ratio": 2.0,
        "deborah": 0.1,
    }
    assert not mp.Medium(
        (mp.Layer(viscoelastic=mp.Zener(1.0, 0.1)),), mp.Winkler(1.0)
    ).viscoelastic


@pytest.mark.parametrize(("material", "kw", "load"), CASES[:2] + CASES[3:5])
def test_the_surface_displacement_is_the_punch_on_the_contact_and_the_slope_beside(
    material, kw, load
):
    """The displacement (its memory through the basis' potentials and an
    exponential convolution) against two independent things: the punch's
    shape on the contact (v = x^2/2R - delta) and the slope beside it (from
    the collocation's kernel and the memory's moments)."""
    s = material_solve(material, load, kw)
    left, right = s.contact_interval
    x = np.linspace(left, right, 9)[1:-1]
    v = s.surface_displacement(x)
    # v = -(delta - x^2/2R) on the contact (v up, the punch pressed down by delta).
    assert np.allclose(
        v - x * x / (2 * R), -s.indentation, rtol=0, atol=1e-9 * s.indentation
    )
    for side in (-1, 1):
        edge = right if side > 0 else left
        for d in (0.05, 0.3):
            xs, h = edge + side * d * (right - left), 1e-4 * (right - left)
            f = s.surface_displacement(xs + h * np.array([-2.0, -1.0, 1.0, 2.0]))
            slope = (f[0] - 8 * f[1] + 8 * f[2] - f[3]) / (12 * h)  # O(h^4)
            assert abs(slope - s.surface_slope(xs)) < 1e-7 * (right - left) / R, (
                side,
                d,
            )


def test_an_unresolved_memory_boundary_layer_is_said():
    """deborah 1e-6 under a contact of a/h ~ 0.019: the retardation length
    (2e-6 h) is far below the nodes' spacing at the ends, the ladder's sizes
    all miss the trailing boundary layer alike and its estimates are at
    round-off; the result says what it could not resolve (and the drag and
    the dissipation, which weigh that layer, differ by far more than tol)."""
    layer = mp.Layer(nu=NU, viscoelastic=mp.Zener(2.0, 1e-6))
    s = mp.solve(
        vstar=0.0, load=6.918e-6, radius=R, layers=[layer], base=mp.Winkler(10.0)
    )
    assert any("viscoelastic memory" in w for w in s.warnings), s.warnings
    assert abs(s.drag - s.dissipation) > 1e-8 * s.drag
    # Resolved memories do not warn.
    assert not zener_solve(2.0, 0.05, 0.002).warnings


def test_ratio_near_one_is_elastic_to_its_distance_from_one():
    """ratio = 1 + 1e-9: the memory's weight c = 1e-9 moves the ends by
    about that much relative (drag ~ 1e-9 of the Zener's at ratio 2), and
    the energy still balances."""
    relaxed = mp.solve(vstar=0.0, load=0.002, radius=R, kw=1.0, nu=NU)
    near = zener_solve(1.0 + 1e-9, 0.1, 0.002)
    left, right = near.contact_interval
    assert abs(right - relaxed.a) < 2e-9 * relaxed.a
    assert abs(left + relaxed.a) < 2e-9 * relaxed.a
    ref = zener_solve(2.0, 0.1, 0.002).drag
    assert 0.0 < near.drag < 1e-8 * ref
    assert (
        abs(near.drag - near.dissipation)
        <= 1e-8 * near.drag + 1e-13 * (right - left) / R
    )


@pytest.mark.parametrize("deborah", [1e-3, 0.1, 10.0, 1e3])
def test_ratio_1000_solves_valid_and_balances_energy(deborah):
    """mu_inf = 1000 mu_0 (a glassy-rubbery polymer): the contact narrows
    from the relaxed to the unrelaxed width across the deborah numbers and
    shifts forward; valid, the energy balanced."""
    s = zener_solve(1000.0, deborah, 0.002)
    assert s.valid
    assert not s.warnings
    left, right = s.contact_interval
    assert left + right > 0.0
    assert abs(s.drag - s.dissipation) <= 1e-10 * s.drag + 1e-13 * (right - left) / R


SCENE = """
name = "visco"

[params]
vstar = 0.0
kw = 1.0
radius = 100.0
load = 0.002

[[layers]]
thickness = 1.0
nu = 0.2
viscoelastic = { kind = "zener", ratio = 2.0, deborah = 0.1 }

[accuracy]
tol = 1e-8

[outputs]
contact_width = true

[vary]
param = "load"
values = [0.001, 0.002]
"""


def test_a_scene_takes_a_viscoelastic_layer_and_writes_it_back():
    scene = mp.Scene.from_toml(SCENE)
    layer = scene.medium.layers[0]
    assert layer.viscoelastic == mp.Zener(2.0, 0.1)
    again = mp.Scene.from_toml(scene.to_toml())
    assert again.medium == scene.medium
    prony = SCENE.replace(
        'viscoelastic = { kind = "zener", ratio = 2.0, deborah = 0.1 }',
        'viscoelastic = { kind = "prony", weights = [1.0, 3.0], '
        "deborahs = [0.02, 0.5], shift = 2.0 }",
    )
    p = mp.Scene.from_toml(prony)
    assert p.medium.layers[0].viscoelastic == mp.Prony((1.0, 3.0), (0.02, 0.5), 2.0)
    assert mp.Scene.from_toml(p.to_toml()).medium == p.medium
    out = scene.run().outputs["contact_width"].columns
    direct = zener_solve(2.0, 0.1, 0.002)
    assert out["drag"][1] == pytest.approx(direct.drag, rel=1e-12)
    assert out["contact_start"][1] == pytest.approx(
        direct.contact_interval[0], rel=1e-12
    )


@pytest.mark.parametrize(
    ("edit", "named"),
    [
        ("ratio = 2.0", "ratio = 0.5"),
        ('kind = "zener"', 'kind = "maxwell"'),
        ("deborah = 0.1", "deborah = -1.0"),
        ("deborah = 0.1", "deborah = 0.1, tau = 0.1"),
        ("deborah = 0.1", "tau = -1.0"),
        ("deborah = 0.1", "shift = 1.0"),
    ],
)
def test_a_scene_with_a_bad_material_names_it(edit, named):
    with pytest.raises(mp.SceneError, match=r"layers\[0\]\.viscoelastic"):
        mp.Scene.from_toml(SCENE.replace(edit, named))


def test_the_command_line_takes_the_top_sublayers_material(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    base = ("solve", "--vstar", "0", "--kw", "1", "--radius", "100", "--load", "0.002")
    proc = run_cli(*base, "--zener", "2,0.1", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    direct = zener_solve(2.0, 0.1, 0.002)
    assert data["drag"] == pytest.approx(direct.drag, rel=1e-12)
    assert data["contact_interval"][0] == pytest.approx(
        direct.contact_interval[0], rel=1e-12
    )
    proc = run_cli(*base, "--prony", "1,0.02,3,0.5", "--shift", "2", "--json")
    assert proc.returncode == 0, proc.stderr
    layer = mp.Layer(nu=NU, viscoelastic=mp.Prony((1.0, 3.0), (0.02, 0.5), 2.0))
    want = mp.solve(
        vstar=0.0, load=0.002, radius=R, layers=[layer], base=mp.Winkler(1.0)
    )
    assert json.loads(proc.stdout)["drag"] == pytest.approx(want.drag, rel=1e-12)
    for bad, named in (
        (("--zener", "0.5,0.1"), "Zener.ratio"),
        (("--zener", "2"), "RATIO,DEBORAH"),
        (("--prony", "1,0.1,2"), "W1,D1"),
        (("--shift", "2"), "--shift"),
        (("--zener", "2,0.1", "--prony", "1,0.1"), "not allowed with"),
    ):
        proc = run_cli(*base, *bad)
        assert proc.returncode == 2, bad
        assert named in proc.stderr, (bad, proc.stderr)


def test_the_terminal_ui_keeps_a_viscoelastic_scenes_material():
    """The medium editor holds the material (it used to refuse such a scene:
    its elastic inputs would have dropped it): opened and saved, the scene's
    medium is the same."""
    from movingpunch.tui import model, scene_files

    scene = mp.Scene.from_toml(SCENE)
    state = scene_files.from_scene(scene)
    assert state.params.medium() == scene.medium
    assert scene_files.to_scene(state).medium == scene.medium
    params = model.with_medium(model.Params(), scene.medium.layers, None)
    assert params.layers == scene.medium.layers


def test_a_branch_of_deborah_zero_adds_nothing():
    """A branch that relaxes at once is no stiffness at any frequency: the
    Prony (1, 2) with deborahs (0, 0.1) is the Zener of ratio 3 (the
    unrelaxed modulus counted it, and the solve went wrong, before), and a
    Prony of such branches only is the elastic layer, on its own path."""
    z = zener_solve(3.0, 0.1, 0.002)
    p = material_solve(mp.Prony((1.0, 2.0), (0.0, 0.1)), 0.002)
    assert p.contact_interval == pytest.approx(z.contact_interval, abs=1e-14)
    assert p.drag == pytest.approx(z.drag, rel=1e-12)
    elastic = mp.solve(vstar=0.0, load=0.002, radius=R, kw=1.0, nu=NU)
    only = material_solve(mp.Prony((1.0,), (0.0,)), 0.002)
    assert type(only) is type(elastic)
    assert only.a == elastic.a
