"""Viscoelastic sublayers in a stack (docs/media.md, "Viscoelastic sublayers
in a stack"; docs/theory.md
section 17.7): a Zener or Prony sublayer anywhere in a stack of sublayers on
springs or on an elastic half-space, propagated at its complex modulus.

Anchors, none of them the stack's own earlier output:

* a viscoelastic layer cut into identical sublayers is the one layer on
  springs, whose closed form (the damped layer's modes at the complex speed)
  is another code path;
* deborah -> 0 and -> infinity are the relaxed and unrelaxed ELASTIC stacks
  (the real propagation and, without friction, the symmetric solver); a
  viscoelastic top's unrelaxed limit after rescaling every modulus by its
  mu_inf;
* the energy balance (the drag from the pressure and the surface slope
  against the dissipation by Parseval from Im M1), p >= 0 and int p = P;
* continuity across a bonded interface: sigma_y, tau and eps_x (the last
  through two different materials' compliances);
* an independent NumPy evaluation (test_viscoelastic_stack_independent.py).
"""

from __future__ import annotations

import math
import subprocess
from collections.abc import Callable

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.errors import InvalidParameterError, SupercriticalSpeedError

NU = 0.25
R = 5.0
LOAD = 0.05
KW = 2.0
X = np.array([-0.6, -0.2, 0.0, 0.15, 0.4])
BASES = {
    "springs": mp.Winkler(KW),
    "half-space": mp.HalfSpace(mu=3.0, nu=0.25, rho=1.5),
}


def solve(layers, base, vstar, load=LOAD, **kw):
    return mp.solve(vstar=vstar, radius=R, load=load, layers=layers, base=base, **kw)


def top_visco(material, sub_mu=2.0):
    """A viscoelastic top (an asphalt course) on an elastic sublayer."""
    return [
        mp.Layer(0.4, nu=NU, viscoelastic=material),
        mp.Layer(0.6, mu=sub_mu, nu=0.3, rho=1.2),
    ]


def deep_visco(material, mu=0.5):
    """An elastic top on a viscoelastic sublayer (a soft, lossy soil)."""
    return [
        mp.Layer(0.3, nu=NU),
        mp.Layer(0.7, mu=mu, nu=0.3, rho=0.8, viscoelastic=material),
    ]


def rel(a, b):
    return np.max(np.abs(np.asarray(a) - np.asarray(b))) / max(
        np.max(np.abs(np.asarray(b))), 1e-300
    )


def check_balance(s, tol=1e-10):
    """drag = dissipation; p >= 0 and int p = P (p in P/h: Gauss-Chebyshev of
    the second kind on the contact, p ~ sqrt at both ends)."""
    assert s.valid, s.validity
    assert s.warnings == ()
    assert s.drag > 0.0
    assert s.drag == pytest.approx(s.dissipation, rel=tol)
    n = 400
    th = np.arange(1, n + 1) * np.pi / (n + 1)
    w, c = s.half_width, s.centre
    p = s.pressure(c + w * np.cos(th))
    assert np.all(p >= 0.0)
    total = w * np.pi / (n + 1) * np.sum(np.sin(th) * p)
    assert total == pytest.approx(1.0, rel=1e-10)


MATERIALS = [mp.Zener(3.0, 0.5), mp.Prony((1.0, 3.0), (0.05, 2.0))]


@pytest.mark.parametrize("material", MATERIALS, ids=repr)
@pytest.mark.parametrize("vstar", [0.0, 0.3])
def test_a_layer_cut_into_identical_sublayers_is_the_layer(material, vstar):
    """The complex propagation through 2 and 3 identical viscoelastic
    sublayers against the one layer's closed form: ends, drag and
    dissipation to 1e-12, the fields (with inertia: near the surface too,
    the modes' tail) to 1e-11 of their scale."""
    one = solve([mp.Layer(1.0, nu=NU, viscoelastic=material)], BASES["springs"], vstar)
    ys = np.array([-0.05, -0.4, -0.7, -1.0])
    for cuts in ((0.4, 0.6), (0.25, 0.45, 0.3)):
        layers = [mp.Layer(t, nu=NU, viscoelastic=material) for t in cuts]
        s = solve(layers, BASES["springs"], vstar)
        assert s.contact_interval == pytest.approx(one.contact_interval, rel=1e-12)
        assert s.drag == pytest.approx(one.drag, rel=1e-12)
        assert s.dissipation == pytest.approx(one.dissipation, rel=1e-12)
        a, b = s.stress_field(X, ys), one.stress_field(X, ys)
        for name in ("sigma_x", "sigma_y", "tau_xy"):
            assert rel(getattr(a, name), getattr(b, name)) < 1e-11, name
        e, f = s.strain_field(X, ys), one.strain_field(X, ys)
        for name in ("eps_x", "eps_y", "gamma_xy"):
            assert rel(getattr(e, name), getattr(f, name)) < 1e-11, name
        assert rel(s.displacement(X, -0.5), one.displacement(X, -0.5)) < 1e-11
        assert rel(s.surface_stress(X), one.surface_stress(X)) < 1e-11


@pytest.mark.parametrize("base", list(BASES), ids=str)
@pytest.mark.parametrize("vstar", [0.0, 0.2])
@pytest.mark.parametrize(("deborah", "scale"), [(1e-12, 1.0), (1e12, 4.0)])
def test_a_deep_sublayer_meets_the_relaxed_and_unrelaxed_elastic_stacks(
    base, vstar, deborah, scale
):
    """The elastic stack with mu_0 (deborah -> 0) or mu_inf = 4 mu_0 (->
    inf): the ends to 1e-10, the strains in the viscoelastic sublayer (below
    the interface: its compliance) to 1e-8 of their scale, and the drag -> 0."""
    s = solve(deep_visco(mp.Zener(4.0, deborah)), BASES[base], vstar)
    e = solve(deep_visco(None, mu=0.5 * scale), BASES[base], vstar)
    lo, hi = e.contact_interval
    assert s.contact_interval == pytest.approx((lo, hi), abs=1e-10 * (hi - lo))
    assert abs(s.drag) < 1e-10
    ys = np.array([-0.3, -0.6, -1.0])
    got, want = s.strain_field(X, ys, side="below"), e.strain_field(X, ys, side="below")
    for name in ("eps_x", "eps_y", "gamma_xy"):
        assert rel(getattr(got, name), getattr(want, name)) < 1e-8, name


@pytest.mark.parametrize("base", list(BASES), ids=str)
@pytest.mark.parametrize("vstar", [0.0, 0.3])
def test_a_top_course_meets_the_relaxed_and_the_rescaled_unrelaxed_stacks(base, vstar):
    """deborah 1e-12: the elastic stack of mu_0. deborah 1e12: the top of
    mu_inf = 3 (units mu_1 = 1): the same stack with every modulus, kw and the
    load over 3 and vstar over 3 (rho V^2/mu_inf); lengths unchanged."""
    ratio = 3.0
    relaxed = solve(top_visco(None), BASES[base], vstar)
    s = solve(top_visco(mp.Zener(ratio, 1e-12)), BASES[base], vstar)
    lo, hi = relaxed.contact_interval
    assert s.contact_interval == pytest.approx((lo, hi), abs=1e-10 * (hi - lo))
    scaled = (
        mp.Winkler(KW / ratio)
        if base == "springs"
        else mp.HalfSpace(mu=3.0 / ratio, nu=0.25, rho=1.5)
    )
    unrelaxed = solve(
        top_visco(None, sub_mu=2.0 / ratio), scaled, vstar / ratio, load=LOAD / ratio
    )
    s = solve(top_visco(mp.Zener(ratio, 1e12)), BASES[base], vstar)
    lo, hi = unrelaxed.contact_interval
    assert s.contact_interval == pytest.approx((lo, hi), abs=1e-10 * (hi - lo))


CASES = {
    "top-springs": (top_visco(mp.Zener(3.0, 0.5)), BASES["springs"]),
    "top-half-space": (top_visco(mp.Zener(3.0, 0.5)), BASES["half-space"]),
    "deep-springs": (deep_visco(mp.Zener(4.0, 0.3)), BASES["springs"]),
    "deep-half-space": (deep_visco(mp.Zener(4.0, 0.3)), BASES["half-space"]),
    "prony-sandwich": (
        [
            mp.Layer(0.2, nu=NU),
            mp.Layer(
                0.3, mu=0.8, nu=0.35, viscoelastic=mp.Prony((2.0, 5.0), (0.1, 3.0))
            ),
            mp.Layer(0.5, mu=1.5, nu=0.3, rho=1.1),
        ],
        BASES["springs"],
    ),
    "two-materials": (
        [
            mp.Layer(0.3, nu=NU, viscoelastic=mp.Zener(10.0, 0.2)),
            mp.Layer(0.7, mu=0.4, nu=0.3, viscoelastic=mp.Zener(2.0, 2.0)),
        ],
        BASES["half-space"],
    ),
}


@pytest.mark.parametrize("case", list(CASES), ids=str)
@pytest.mark.parametrize("vstar", [0.0, 0.25])
def test_the_drag_is_the_dissipation_and_the_pressure_carries_the_load(case, vstar):
    layers, base = CASES[case]
    check_balance(solve(layers, base, vstar))


@pytest.mark.parametrize("case", ["top-springs", "deep-half-space", "two-materials"])
def test_the_fields_are_continuous_across_a_bonded_interface(case):
    """sigma_y and tau are continuous at the interface, and so is eps_x
    (the displacements are): above it through one material's compliance,
    below through the other's (or Hooke's law of an elastic one)."""
    layers, base = CASES[case]
    s = solve(layers, base, 0.25)
    y = [-layers[0].thickness]
    a, b = s.stress_field(X, y), s.stress_field(X, y, side="below")
    for name in ("sigma_y", "tau_xy"):
        assert rel(getattr(a, name), getattr(b, name)) < 1e-12, name
    assert rel(a.sigma_x, b.sigma_x) > 1e-3  # the materials differ: it jumps
    ea, eb = s.strain_field(X, y), s.strain_field(X, y, side="below")
    assert rel(ea.eps_x, eb.eps_x) < 1e-9


@pytest.mark.parametrize("direction", [1, -1])
def test_a_speed_sweep_of_a_deep_material_reads_the_same_both_ways(direction):
    """A soil sublayer given by its relaxation time (deborah follows the
    speed): a scene's sweep up and down gives the direct solves' numbers."""
    values = [0.05, 0.15, 0.3][::direction]
    text = f"""
name = "lossy-soil"

[params]
vstar = {values[0]!r}
radius = {R!r}
load = {LOAD!r}

[[layers]]
thickness = 0.3
nu = {NU!r}

[[layers]]
thickness = 0.7
mu = 0.5
nu = 0.3
rho = 0.8
viscoelastic = {{ kind = "zener", ratio = 4.0, tau = 1.5 }}

[base]
kind = "half_space"
mu = 3.0
nu = 0.25
rho = 1.5

[sweep]
param = "vstar"
values = {values!r}
quantities = ["drag", "contact_start", "contact_end"]
"""
    table = mp.Scene.from_toml(text).run().sweep
    assert table is not None
    for j, v in enumerate(values):
        direct = solve(deep_visco(mp.Zener(4.0, tau=1.5)), BASES["half-space"], v)
        assert table.data["drag"][0][j] == direct.drag
        assert table.data["contact_end"][0][j] == direct.contact_interval[1]


@pytest.mark.parametrize("interface", ["bonded", "smooth"])
@pytest.mark.parametrize("vstar", [0.0, 0.2])
@pytest.mark.parametrize(("deborah", "scale"), [(1e-12, 1.0), (1e12, 4.0)])
def test_the_surface_under_a_half_space_meets_the_elastic_stacks(
    interface, vstar, deborah, scale
):
    """Under a half-space the surface displacement grows like ln|x|; it is
    measured from x = 100 h (as the symmetric solver's): the viscoelastic
    stack's (the asymmetric solver: the substrate's m0 e^-alpha/alpha taken
    out of its Fourier sum as a logarithm in x) in the limits against the
    elastic stacks' own (the symmetric solver), the indentation to 1e-10 of
    itself and the displacement to 1e-9 of its largest value from x = -3 h
    to 40 h."""
    base = mp.HalfSpace(mu=3.0, nu=0.25, rho=1.5, interface=interface)
    s = solve(deep_visco(mp.Zener(4.0, deborah)), base, vstar)
    e = solve(deep_visco(None, mu=0.5 * scale), base, vstar)
    assert s.indentation == pytest.approx(e.indentation, rel=1e-10)
    x = np.array([-3.0, -0.5, 0.0, 0.2, 1.0, 5.0, 40.0, 100.0])
    got, want = s.surface_displacement(x), e.surface_displacement(x)
    assert np.max(np.abs(got - want)) < 1e-9 * np.max(np.abs(want))
    assert abs(got[-1]) < 1e-15 * s.indentation  # the reference point
    assert np.array_equal(s.displacement(x, 0.0), got)
    # The punch's face on the contact (the rigid indentation).
    back, front = s.contact_interval
    on = np.linspace(0.9 * back, 0.9 * front, 7)
    face = -s.indentation + on**2 / (2.0 * R)
    assert np.max(np.abs(s.surface_displacement(on) - face)) < 1e-9 * s.indentation


DEPTHS = (-0.1, -0.3, -0.6, -1.0)
FAR_X = np.array([-3.0, -1.0, 0.0, 0.2, 0.5, 2.0, 50.0, 100.0])


@pytest.mark.parametrize("interface", ["bonded", "smooth"])
@pytest.mark.parametrize("vstar", [0.0, 0.2])
@pytest.mark.parametrize(("deborah", "scale"), [(1e-12, 1.0), (1e12, 4.0)])
def test_below_the_surface_of_a_half_space_the_displacement_meets_the_elastic_stacks(
    interface, vstar, deborah, scale
):
    """Below the surface too (the substrate's m0 e^-alpha/alpha taken out of
    every depth's Fourier sum as the surface's logarithm, measured from the
    surface at x = 100 h): the viscoelastic stack in the limits against the
    elastic stacks' displacement at depth by the symmetric solver, to 1e-10
    of the largest (measured 3e-12 ... 1e-16: the limits' own ends agree to
    about 1e-12), near the contact and 50 h and 100 h away."""
    base = mp.HalfSpace(mu=3.0, nu=0.25, rho=1.5, interface=interface)
    s = solve(deep_visco(mp.Zener(4.0, deborah)), base, vstar)
    e = solve(deep_visco(None, mu=0.5 * scale), base, vstar)
    for y in DEPTHS:
        got, want = s.displacement(FAR_X, y), e.displacement(FAR_X, y)
        assert np.max(np.abs(got - want)) < 1e-10 * np.max(np.abs(want)), y


@pytest.mark.parametrize("vstar", [0.0, 0.2])
@pytest.mark.parametrize(("deborah", "scale"), [(1e-12, 1.0), (1e12, 3.0)])
def test_a_viscoelastic_top_on_a_half_space_at_depth_meets_the_elastic_stacks(
    vstar, deborah, scale
):
    """A viscoelastic top (its memory: the half-plane part's convolution,
    with inertia its tail panels) on a half-space, at depth: the relaxed and
    unrelaxed limits against the elastic stacks in units of mu_0 and mu_inf
    (every modulus, the load and vstar over the scale; the densities as they
    are), by the symmetric solver, to 1e-10 of the largest."""
    base = mp.HalfSpace(mu=3.0, nu=0.25, rho=1.5)
    s = solve(top_visco(mp.Zener(3.0, deborah)), base, vstar)
    e = mp.solve(
        vstar=vstar / scale,
        radius=R,
        load=LOAD / scale,
        layers=[mp.Layer(0.4, nu=NU), mp.Layer(0.6, mu=2.0 / scale, nu=0.3, rho=1.2)],
        base=mp.HalfSpace(mu=3.0 / scale, nu=0.25, rho=1.5),
    )
    for y in DEPTHS:
        got, want = s.displacement(FAR_X, y), e.displacement(FAR_X, y)
        assert np.max(np.abs(got - want)) < 1e-10 * np.max(np.abs(want)), y


@pytest.mark.parametrize("case", ["top-half-space", "deep-half-space"])
def test_below_the_surface_of_a_half_space_the_displacement_meets_the_surface(case):
    """A genuinely viscoelastic stack (no elastic limit): the displacement at
    depth (its own sums) tends to the surface's (surface_value, another code
    path) at first order in |y| (the strain): 100 times closer at y = -1e-7
    than at -1e-5, and within 1e-6 of the indentation there; 0 at the
    reference point x = 100 h on the surface."""
    layers, base = CASES[case]
    s = solve(layers, base, 0.0)
    top = s.displacement(FAR_X, 0.0)
    assert abs(top[-1]) < 1e-15 * s.indentation
    far = np.max(np.abs(s.displacement(FAR_X, -1e-5) - top))
    near = np.max(np.abs(s.displacement(FAR_X, -1e-7) - top))
    assert near < 1e-6 * s.indentation
    assert 50.0 < far / near < 200.0


def test_with_friction_on_a_half_space_the_displacement_is_refused():
    base = BASES["half-space"]
    rough = solve(deep_visco(None), base, 0.2, friction=0.2)
    with pytest.raises(InvalidParameterError, match="friction"):
        rough.surface_displacement(X)
    with pytest.raises(InvalidParameterError, match="friction"):
        rough.displacement(X, -0.5)
    assert rough.to_dict()["indentation"] is None


def test_the_relaxed_critical_speed_bounds_a_viscoelastic_stack():
    layers, base = CASES["deep-half-space"]
    relaxed = deep_visco(None)
    vcr = mp.critical_vstar(layers=layers, base=base)
    assert vcr == mp.critical_vstar(layers=relaxed, base=base)
    near = solve(layers, base, 0.98 * vcr)
    check_balance(near)
    with pytest.raises(SupercriticalSpeedError):
        solve(layers, base, vcr)


def test_what_a_viscoelastic_stack_does_not_take_is_refused_by_name():
    layers, base = CASES["top-springs"]
    with pytest.raises(InvalidParameterError) as e:
        solve(layers, base, 0.0, friction=0.2)
    assert e.value.parameter == "friction"
    with pytest.raises(InvalidParameterError) as e:
        mp.solve(
            vstar=0.0,
            profile=mp.RoundedFlat(0.1, 100.0),
            load=LOAD,
            layers=layers,
            base=base,
        )
    assert e.value.parameter == "profile"
    with pytest.raises(InvalidParameterError) as e:
        solve(layers, mp.Winkler(KW, damping=0.5), 0.1)
    assert e.value.parameter == "damping"
    for bad in (-0.1, math.nan, math.inf):
        with pytest.raises(InvalidParameterError) as e:
            solve(deep_visco(mp.Zener(bad, 0.3)), base, 0.1)
        assert "ratio" in str(e.value)


def test_the_command_line_makes_a_lower_sublayer_viscoelastic(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    """--visco-layer 1 puts --zener on the second sublayer."""
    proc = run_cli(
        "solve",
        "--vstar",
        "0.2",
        "--radius",
        str(R),
        "--load",
        str(LOAD),
        "--layer",
        "0.3,1,0.25",
        "--layer",
        "0.7,0.5,0.3,0.8",
        "--half-space",
        "3,0.25,1.5",
        "--zener",
        "4,0.3",
        "--visco-layer",
        "1",
        "--json",
    )
    assert proc.returncode == 0, proc.stderr
    import json

    out = json.loads(proc.stdout)
    direct = solve(deep_visco(mp.Zener(4.0, 0.3)), BASES["half-space"], 0.2)
    assert out["drag"] == pytest.approx(direct.drag, rel=1e-14)
    bad = run_cli(
        "solve",
        "--vstar",
        "0.2",
        "--radius",
        str(R),
        "--load",
        str(LOAD),
        "--kw",
        "2",
        "--zener",
        "4,0.3",
        "--visco-layer",
        "1",
    )
    assert bad.returncode != 0
    assert "--visco-layer" in bad.stderr


def test_a_deep_material_by_its_relaxation_time_sweeps_quasi_statically():
    """inertia=False with a lower sublayer's material given by tau: the
    stack at rest with that material at deborah = sqrt(vstar) tau (the
    relaxed critical speed's check read the material before its speed was
    known, and refused it naming tau)."""
    for base in BASES.values():
        for vstar in (1e-6, 0.01):
            s = solve(deep_visco(mp.Zener(4.0, tau=10.0)), base, vstar, inertia=False)
            at_rest = solve(
                deep_visco(mp.Zener(4.0, math.sqrt(vstar) * 10.0)), base, 0.0
            )
            assert s.vstar == vstar
            assert s.contact_interval == at_rest.contact_interval
            assert s.drag == at_rest.drag > 0.0


def test_the_bundled_asphalt_scene_is_the_api_and_its_resistance_peaks():
    """The bundled `asphalt-rolling-resistance` sweep (a Zener course given
    by tau over an elastic base, with the stack's inertia): each speed's drag
    and ends are the API's direct solve, the drag peaks inside the sweep, and
    at the peak drag = dissipation."""
    scene = mp.Scene.bundled("asphalt-rolling-resistance")
    table = scene.run().sweep
    assert table is not None
    drags = np.asarray(table.data["drag"][0])
    k = int(np.argmax(drags))
    assert 0 < k < len(drags) - 1
    course = mp.Layer(0.25, mu=1.0, nu=0.35, viscoelastic=mp.Zener(10.0, tau=20.0))
    base = mp.Layer(0.75, mu=0.1, nu=0.3, rho=0.85)
    for j in (0, k, len(drags) - 1):
        v = float(table.values[j])
        direct = mp.solve(
            vstar=v,
            radius=100.0,
            load=0.002,
            layers=[course, base],
            base=mp.Winkler(0.05),
        )
        assert drags[j] == direct.drag
        assert table.data["contact_start"][0][j] == direct.contact_interval[0]
        if j == k:
            assert direct.drag == pytest.approx(direct.dissipation, rel=1e-10)
    # The contact shifts ahead of the axle as the course stiffens.
    ends = np.asarray(table.data["contact_start"][0]) + np.asarray(
        table.data["contact_end"][0]
    )
    assert np.all(ends > 0.0)


@pytest.mark.parametrize("vstar", [0.0, 0.25])
@pytest.mark.parametrize("case", ["top-springs", "top-half-space", "prony-sandwich"])
def test_a_flat_punch_on_a_viscoelastic_stack_balances_its_energy(case, vstar):
    """A flat face on a viscoelastic top (docs/theory.md section 17.10): the
    drag from its edges' suction at H_inf is the power dissipated, computed
    apart in x, to 1e-10 (measured 4e-15 ... 3e-12)."""
    layers, base = CASES[case]
    s = mp.solve(vstar=vstar, profile=mp.Flat(0.3), load=LOAD, layers=layers, base=base)
    assert s.valid
    assert s.drag > 0.0
    assert s.dissipation == pytest.approx(s.drag, rel=1e-10, abs=0.0)
