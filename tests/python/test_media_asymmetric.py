"""The asymmetric solver on layered media and half-space bases (issue 26):
friction, asymmetric profile tables, flat punches with friction and several
contact zones on a stack, each against an independent anchor:

* K identical sublayers are the homogeneous layer (its own closed-form
  response, the asymmetric solver's path for the homogeneous layer): the
  contact ends, pressure and drag within the error estimates;
* a bonded half-space of the layer's own material is the moving half-plane:
  with friction f a cylinder's contact is Muskhelishvili's closed form,
  p = K (a - x)^front (x + b)^back, w^2 = phi1 R P / (2 pi front back), centre
  w (back - front), drag (4/3) w (back - front)/R (Johnson, Contact Mechanics,
  sec. 7.2), front = 1/2 + atan(f Phi)/pi;
* equilibrium (int p dx = P) and p >= 0.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import movingpunch as mp

BASE = {"vstar": 0.2, "load": 0.004, "radius": 50.0, "tol": 1e-10}
IDENTICAL = [mp.Layer(0.37), mp.Layer(0.23), mp.Layer(0.4)]


def _same_contact(a: mp.ContactSolution, b: mp.ContactSolution) -> None:
    tol = 1e-9 + 2.0 * (a.error_estimate + b.error_estimate)
    assert a.contact_interval[0] == pytest.approx(b.contact_interval[0], abs=tol)
    assert a.contact_interval[1] == pytest.approx(b.contact_interval[1], abs=tol)
    assert a.drag == pytest.approx(b.drag, rel=1e-8, abs=1e-12)
    lo, hi = b.contact_interval
    x = np.linspace(lo, hi, 9)[1:-1]
    scale = float(np.max(b.pressure(x)))
    assert np.allclose(a.pressure(x), b.pressure(x), rtol=0, atol=1e-8 * scale)


def _equilibrium(s: mp.ContactSolution) -> None:
    """int p dx = P (p in P/h: the integral is 1) and p >= 0 on the contact."""
    lo, hi = s.contact_interval
    c, w = 0.5 * (lo + hi), 0.5 * (hi - lo)
    m = 4000
    th = math.pi * (np.arange(m) + 0.5) / m
    x = c - w * np.cos(th)
    p = np.asarray(s.pressure(x))
    assert float(np.sum(p * w * np.sin(th)) * math.pi / m) == pytest.approx(
        1.0, abs=2e-4
    )
    assert float(np.min(p)) >= -1e-9 * float(np.max(p))


def test_identical_sublayers_with_friction_are_the_homogeneous_layer() -> None:
    stack = mp.solve(**BASE, layers=IDENTICAL, base=mp.Winkler(1.0), friction=0.3)
    layer = mp.solve(**BASE, kw=1.0, friction=0.3)
    assert isinstance(stack, mp.AsymmetricSolution)
    _same_contact(stack, layer)
    _equilibrium(stack)
    assert stack.end_exponents == pytest.approx(layer.end_exponents, abs=1e-15)
    assert stack.critical_vstar == pytest.approx(layer.critical_vstar, rel=1e-9)
    assert stack.indentation == pytest.approx(layer.indentation, rel=1e-8)


@pytest.mark.slow
def test_identical_sublayers_rounded_flat_and_table_are_the_homogeneous_layer() -> None:
    rounded = mp.RoundedFlat(0.05, 20.0)
    a = mp.solve(
        **BASE | {"radius": None},
        layers=IDENTICAL,
        base=mp.Winkler(2.0),
        friction=0.3,
        profile=rounded,
    )
    _same_contact(
        a, mp.solve(**BASE | {"radius": None}, kw=2.0, friction=0.3, profile=rounded)
    )
    x = np.linspace(-0.6, 0.6, 41)
    table = mp.Profile(
        tuple(x), tuple(x * x / 40.0 + np.where(x > 0, x**3 / 30.0, 0.0))
    )
    assert not table.symmetric
    b = mp.solve(
        **BASE | {"radius": None, "load": 0.002},
        layers=IDENTICAL,
        base=mp.Winkler(2.0),
        profile=table,
    )
    _same_contact(
        b, mp.solve(**BASE | {"radius": None, "load": 0.002}, kw=2.0, profile=table)
    )
    _equilibrium(b)


def test_identical_sublayers_flat_with_friction_has_the_homogeneous_ends() -> None:
    flat = mp.Flat(0.3)
    a = mp.solve(
        **BASE | {"radius": None},
        layers=[mp.Layer(0.6), mp.Layer(0.4)],
        base=mp.Winkler(1.0),
        friction=0.3,
        profile=flat,
    )
    b = mp.solve(**BASE | {"radius": None}, kw=1.0, friction=0.3, profile=flat)
    ka, kb = a.end_coefficients, b.end_coefficients
    tol = 1e-9 + 2.0 * b.end_coefficient_error
    assert ka[0] == pytest.approx(kb[0], abs=tol)
    assert ka[1] == pytest.approx(kb[1], abs=tol)


def test_bonded_half_space_of_the_own_material_is_the_frictional_half_plane() -> None:
    nu, vstar, f, load, radius = 0.2, 0.3, 0.3, 2e-3, 50.0
    s = mp.solve(
        vstar=vstar,
        load=load,
        radius=radius,
        tol=1e-11,
        layers=[mp.Layer(1.0, nu=nu)],
        base=mp.HalfSpace(1.0, nu),
        friction=f,
    )
    phi1 = mp.phi1(vstar, nu)
    back, front = mp.asymmetric.end_exponents(f, vstar=vstar, nu=nu)
    w = math.sqrt(phi1 * radius * load / (2.0 * math.pi * front * back))
    centre = w * (back - front)
    lo, hi = s.contact_interval
    assert 0.5 * (hi - lo) == pytest.approx(w, rel=1e-9)
    assert 0.5 * (hi + lo) == pytest.approx(centre, abs=1e-9 * w)
    assert s.drag == pytest.approx(4.0 / 3.0 * centre / radius, rel=1e-8)
    _equilibrium(s)
    # The displacement under a half-space grows like ln|x|: refused by name.
    with pytest.raises(ValueError, match="logarithmic far field"):
        _ = s.indentation


def test_smooth_half_space_with_friction_runs() -> None:
    s = mp.solve(
        **BASE,
        layers=[mp.Layer(0.4), mp.Layer(0.6, mu=0.5, nu=0.3)],
        base=mp.HalfSpace(2.0, 0.3, interface="smooth"),
        friction=0.3,
    )
    assert s.valid
    assert not s.warnings
    _equilibrium(s)
    lo, hi = s.contact_interval
    assert lo < 0.0 < hi
    assert s.friction == 0.3


def test_several_zones_on_identical_sublayers_are_the_homogeneous_layers() -> None:
    punches = [mp.Punch(50.0, 0.004, at=0.0), mp.Punch(50.0, 0.004, at=1.2)]
    common = {"vstar": 0.3, "tol": 1e-9}
    a = mp.solve_punches(punches, **common, layers=IDENTICAL, base=mp.Winkler(1.0))
    b = mp.solve_punches(punches, **common, kw=1.0)
    za = [z for p in a.punches for z in p.contact_zones]
    zb = [z for p in b.punches for z in p.contact_zones]
    assert len(za) == len(zb) == 2
    tol = 1e-8 + 2.0 * (a.error_estimate + b.error_estimate)
    for (l1, r1), (l2, r2) in zip(za, zb, strict=True):
        assert l1 == pytest.approx(l2, abs=tol)
        assert r1 == pytest.approx(r2, abs=tol)
    # The stresses at depth: the stack's mode profiles (interfaces at -0.37,
    # -0.6 and the base face) against the homogeneous layer's closed forms.
    x = np.array([-0.4, 0.0, 0.6, 1.2, 1.7])
    y = np.array([-0.1, -0.37, -0.6, -1.0])
    fa, fb = a.stress_field(x, y), b.stress_field(x, y)
    scale = float(np.max(np.abs(fb.sigma_y)))
    for part in ("sigma_x", "sigma_y", "tau_xy"):
        diff = np.abs(getattr(fa, part) - getattr(fb, part))
        assert float(np.max(diff)) < 1e-7 * scale, part
    assert [p.drag for p in a.punches] == pytest.approx(
        [p.drag for p in b.punches], rel=1e-7
    )


def test_damped_springs_under_a_stack_are_refused_naming_damping() -> None:
    with pytest.raises(mp.InvalidParameterError, match="damped base") as info:
        mp.solve(
            **BASE, layers=IDENTICAL, base=mp.Winkler(1.0, damping=0.5), friction=0.3
        )
    assert info.value.parameter == "damping"


def test_depth_fields_of_a_stack_on_the_asymmetric_solver_are_refused_by_name() -> None:
    s = mp.solve(**BASE, layers=IDENTICAL, base=mp.Winkler(1.0), friction=0.3)
    with pytest.raises(ValueError, match="not available from the asymmetric solver"):
        s.depth_stress(-0.5)
    assert math.isfinite(float(s.surface_stress(0.0)))


def test_a_separated_contact_on_identical_sublayers_is_the_homogeneous_layers() -> None:
    """Near the critical speed on soft springs the single contact separates
    (test_zones.py's case): the stack's zones are the homogeneous layer's."""
    kw = 0.1
    common = {
        "vstar": 0.99 * mp.critical_vstar(kw, 0.2),
        "radius": 100.0,
        "load": 0.002,
    }
    a = mp.solve(**common, layers=IDENTICAL, base=mp.Winkler(kw))
    b = mp.solve(**common, kw=kw)
    assert isinstance(a, mp.ZonedSolution)
    assert isinstance(b, mp.ZonedSolution)
    assert len(a.contact_zones) == len(b.contact_zones) == 2
    tol = 1e-10 + 2.0 * (a.error_estimate + b.error_estimate)
    for (l1, r1), (l2, r2) in zip(a.contact_zones, b.contact_zones, strict=True):
        assert l1 == pytest.approx(l2, abs=tol)
        assert r1 == pytest.approx(r2, abs=tol)
    _equilibrium_zones(a)


def _equilibrium_zones(s: mp.ContactSolution) -> None:
    """int p dx over the zones = P (p in P/h: the integral is 1), p >= 0."""
    total = 0.0
    for lo, hi in s.contact_zones:
        c, w = 0.5 * (lo + hi), 0.5 * (hi - lo)
        m = 4000
        th = math.pi * (np.arange(m) + 0.5) / m
        p = np.asarray(s.pressure(c - w * np.cos(th)))
        assert float(np.min(p)) >= -1e-9 * float(np.max(p))
        total += float(np.sum(p * w * np.sin(th)) * math.pi / m)
    assert total == pytest.approx(1.0, abs=2e-4)


def test_a_train_on_a_half_space_base_is_measured_from_the_reference_point() -> None:
    """Trains on a half-space (the displacement grows like ln|x|): every
    punch's zones are solved in its own frame, and the sum of their
    displacements is measured from the common surface point x = 100 h.
    Anchors: one punch at x = 3 is the symmetric solver's single contact
    moved by 3, its indentation that one's plus its displacement at 97 h
    (1e-12); two punches: the surface under each face is the face (1e-12 of
    the indentation) and 0 at x = 100 h; a smooth half-space ever stiffer is
    the rigid smooth base (Winkler(inf): another base, another code path) at
    first order in 1/mu (tenfold closer per decade)."""
    layers = [mp.Layer(0.5), mp.Layer(0.5, mu=0.5)]
    base = mp.HalfSpace(2.0, 0.3)
    one = mp.solve(vstar=0.2, radius=50.0, load=0.004, layers=layers, base=base)
    moved = mp.solve_punches(
        [mp.Punch(50.0, 0.004, at=3.0)], vstar=0.2, layers=layers, base=base
    ).punches[0]
    ((left, right),) = moved.contact_zones
    back, front = one.contact_interval
    assert left == pytest.approx(back + 3.0, abs=1e-12)
    assert right == pytest.approx(front + 3.0, abs=1e-12)
    shifted = one.indentation + float(one.surface_displacement(97.0))
    assert moved.indentation == pytest.approx(shifted, abs=1e-12 * one.indentation)
    stack = [mp.Layer(0.3, nu=0.2), mp.Layer(0.7, mu=0.5, nu=0.3, rho=0.8)]
    punches = [mp.Punch(5.0, load=0.05, at=0.0), mp.Punch(5.0, load=0.08, at=1.2)]
    t = mp.solve_punches(
        punches, vstar=0.2, layers=stack, base=mp.HalfSpace(3.0, 0.25, rho=1.5)
    )
    assert t.valid
    assert float(t.surface_displacement(100.0)) == 0.0
    for p in t.punches:
        ((lo, hi),) = p.contact_zones
        x = np.linspace(lo, hi, 9)[1:-1]
        face = -p.indentation + (x - p.at) ** 2 / 10.0
        assert np.max(np.abs(t.surface_displacement(x) - face)) < 1e-12 * p.indentation
    rigid = mp.solve_punches(
        punches, vstar=0.2, layers=stack, base=mp.Winkler(math.inf)
    )
    gaps = []
    for mu in (1e4, 1e5):
        h = mp.solve_punches(
            punches,
            vstar=0.2,
            layers=stack,
            base=mp.HalfSpace(mu, 0.25, rho=1.0, interface="smooth"),
        )
        gaps.append(
            max(
                abs(a.indentation - b.indentation)
                + np.max(np.abs(np.subtract(a.contact_zones, b.contact_zones)))
                for a, b in zip(h.punches, rigid.punches, strict=True)
            )
        )
    assert gaps[1] < 1e-5
    assert 5.0 < gaps[0] / gaps[1] < 20.0


def test_a_scene_runs_a_train_on_a_half_space() -> None:
    """A scene's [[punches]] beside a half-space [base] (it was refused):
    its contact table and its displacement at depth are the API's train."""
    text = """
[params]
vstar = 0.2

[[punches]]
radius = 5.0
load = 0.05
at = 0.0

[[punches]]
radius = 5.0
load = 0.08
at = 1.2

[[layers]]
kind = "layer"
thickness = 0.3
nu = 0.2

[[layers]]
kind = "layer"
thickness = 0.7
mu = 0.5
nu = 0.3
rho = 0.8

[base]
kind = "half_space"
mu = 3.0
nu = 0.25
rho = 1.5

[outputs]
contact_width = true
displacement = { x = [-2.0, 3.0], depth = -0.5, points = 11 }
"""
    scene = mp.Scene.from_toml(text)
    result = scene.run()
    train = mp.solve_punches(
        [mp.Punch(5.0, load=0.05, at=0.0), mp.Punch(5.0, load=0.08, at=1.2)],
        vstar=0.2,
        layers=[mp.Layer(0.3, nu=0.2), mp.Layer(0.7, mu=0.5, nu=0.3, rho=0.8)],
        base=mp.HalfSpace(3.0, 0.25, rho=1.5),
    )
    (curve,) = result.outputs["displacement"].curves
    want = train.displacement(curve.x, -0.5)
    assert np.max(np.abs(curve.y - want)) <= 1e-14 * np.max(np.abs(want))
