"""A viscoelastic layer with its inertia (issue 28): vstar > 0 with the
material's complex wave constants vstar/m(alpha) at every wavenumber, and the
half-plane's memory of poles and a cut (docs/theory.md section 17.6).

Anchors, each independent of the moving viscoelastic path:
* deborah -> 0 is the elastic layer of mu_0 at vstar, deborah -> inf the
  elastic layer of mu_inf = ratio mu_0 at vstar/ratio (with kw/ratio and the
  load over ratio in its units): the ends, the drag, the surface sigma_x and
  the stresses from the bottom to y = -0.005 to 1e-10 (the elastic solver is
  the paper's, checked against its tables);
* ratio 1 is the elastic layer exactly;
* the energy balance: the drag (from the pressure) equals the dissipation
  (Parseval on the surface, from Im M1) to 1e-10 at every case;
* p >= 0 and int p = P;
* vstar -> 0 is the quasi-static layer (its own anchors: Hunter's closed
  form, test_viscoelastic.py).
The independent second evaluation of a moving case (a reference solver
written separately) is test_viscoelastic_independent.py."""

from __future__ import annotations

import json
import math
import subprocess
from collections.abc import Callable

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.errors import InvalidParameterError, SupercriticalSpeedError

NU = 0.25
KW = 2.0
R = 5.0
LOAD = 0.05
X = np.array([-1.5, -0.5, -0.1, 0.0, 0.1, 0.2, 0.5, 1.5])


def visco(
    vstar: float,
    material: mp.Zener | mp.Prony,
    *,
    kw: float = KW,
    load: float = LOAD,
    radius: float = R,
    nu: float = NU,
) -> mp.ContactSolution:
    return mp.solve(
        vstar=vstar,
        radius=radius,
        load=load,
        layers=[mp.Layer(1.0, nu=nu, viscoelastic=material)],
        base=mp.Winkler(kw=kw),
    )


def elastic(vstar: float, scale: float = 1.0) -> mp.ContactSolution:
    """The elastic layer of modulus scale mu_0, in units of mu_0."""
    return mp.solve(
        vstar=vstar / scale,
        radius=R,
        load=LOAD / scale,
        nu=NU,
        kw=KW / scale,
    )


@pytest.mark.parametrize("vstar", [1e-6, 0.01, 0.3, 0.6])
@pytest.mark.parametrize(("deborah", "scale"), [(1e-12, 1.0), (1e12, 3.0)])
def test_the_relaxed_and_unrelaxed_limits_are_the_elastic_layers(vstar, deborah, scale):
    s = visco(vstar, mp.Zener(3.0, deborah))
    e = elastic(vstar, scale)
    assert s.valid
    back, front = s.contact_interval
    assert abs(front - e.a) < 1e-10
    assert abs(-back - e.a) < 1e-10
    assert 0.0 <= s.drag < 1e-10
    assert s.indentation == pytest.approx(e.indentation, rel=1e-9)
    scale_x = np.max(np.abs(e.surface_stress(X)))
    assert np.max(np.abs(s.surface_stress(X) - e.surface_stress(X))) < 1e-10 * scale_x
    # The bottom (y = -1), the lower part and near the surface (the modes'
    # tail beyond the fine nodes summed to 36/(nT |y|)).
    depths = [-1.0, -0.9, -0.3, -0.05, -0.005]
    f, g = s.stress_field(X, depths), e.stress_field(X, depths)
    for name in ("sigma_x", "sigma_y", "tau_xy"):
        got, want = getattr(f, name), getattr(g, name)
        assert np.max(np.abs(got - want)) < 1e-10 * np.max(np.abs(g.sigma_x)), name


def test_ratio_one_is_the_elastic_layer_exactly():
    s = visco(0.3, mp.Zener(1.0, 0.5))
    e = mp.solve(
        vstar=0.3,
        radius=R,
        load=LOAD,
        layers=[mp.Layer(1.0, nu=NU)],
        base=mp.Winkler(KW),
    )
    assert s.contact_interval == e.contact_interval
    assert s.drag == e.drag


MATERIALS = [
    mp.Zener(2.0, 0.3),
    mp.Zener(10.0, 0.05),
    mp.Zener(10.0, 3.0),
    mp.Zener(1000.0, 1.0),
    mp.Prony((1.0, 3.0, 0.5), (0.01, 1.0, 30.0)),
]


@pytest.mark.parametrize("material", MATERIALS, ids=lambda m: repr(m))
@pytest.mark.parametrize("vstar", [0.05, 0.3, 0.65])
def test_the_drag_is_the_dissipation_and_the_pressure_carries_the_load(material, vstar):
    s = visco(vstar, material)
    assert s.valid, s.validity
    assert s.warnings == ()
    assert s.drag > 0.0
    assert s.drag == pytest.approx(s.dissipation, rel=1e-10)
    back, front = s.contact_interval
    assert back < front  # (at high drag the contact can lie wholly ahead of x = 0)
    # p >= 0 and int p = P (p in units of P/h; Gauss-Chebyshev of the second
    # kind on the contact: p ~ sqrt at both ends).
    n = 400
    k = np.arange(1, n + 1)
    th = k * np.pi / (n + 1)
    w, c = s.half_width, s.centre
    p = s.pressure(c + w * np.cos(th))
    assert np.all(p >= 0.0)
    total = w * np.pi / (n + 1) * np.sum(np.sin(th) * p)  # int p = w int sqrt(1-r^2) g
    assert total == pytest.approx(1.0, rel=1e-10)


def test_the_speed_is_continuous_into_the_quasi_static_layer_at_rest():
    material = mp.Zener(3.0, 0.5)
    still = visco(0.0, material)
    slow = visco(1e-10, material)
    assert slow.contact_interval == pytest.approx(still.contact_interval, rel=1e-9)
    assert slow.drag == pytest.approx(still.drag, rel=1e-9)


def test_inertia_moves_the_contact_against_the_quasi_static_layer():
    """The same material at the same speed, with and without the inertia:
    the inertia softens the layer (vstar/m(alpha) in its waves), the
    contact widens and the drag grows; inertia=False is the layer at rest."""
    material = mp.Zener(10.0, tau=2.0)
    moving = visco(0.3, material)
    still = mp.solve(
        vstar=0.3,
        radius=R,
        load=LOAD,
        layers=[mp.Layer(1.0, nu=NU, viscoelastic=material)],
        base=mp.Winkler(KW),
        inertia=False,
    )
    assert moving.half_width > still.half_width
    assert moving.drag > still.drag
    # tau is the material: at vstar its deborah number is sqrt(vstar) tau.
    same = visco(0.3, mp.Zener(10.0, math.sqrt(0.3) * 2.0))
    assert same.contact_interval == moving.contact_interval


@pytest.mark.parametrize("direction", [1, -1])
def test_a_speed_sweep_of_one_material_with_inertia_reads_the_same_both_ways(direction):
    values = [0.05, 0.2, 0.4, 0.6][::direction]
    text = f"""
name = "moving-bell"

[params]
vstar = {values[0]!r}
kw = {KW!r}
radius = {R!r}
load = {LOAD!r}

[[layers]]
nu = {NU!r}
viscoelastic = {{ kind = "zener", ratio = 10.0, tau = 2.0 }}

[sweep]
param = "vstar"
values = {values!r}
quantities = ["drag", "contact_start", "contact_end"]
"""
    table = mp.Scene.from_toml(text).run().sweep
    assert table is not None
    for j, v in enumerate(values):
        direct = visco(v, mp.Zener(10.0, tau=2.0))
        assert table.data["drag"][0][j] == direct.drag
        assert table.data["contact_end"][0][j] == direct.contact_interval[1]


def test_what_the_layer_with_inertia_does_not_give_is_refused_by_name():
    s = visco(0.3, mp.Zener(3.0, 0.5))
    with pytest.raises(InvalidParameterError) as err:
        s.stress_field(X, [-0.3, -1e-3])
    assert err.value.parameter == "y"
    assert "inertia" in str(err.value)
    with pytest.raises(InvalidParameterError) as err:
        s.displacement(X, -1e-3)
    assert err.value.parameter == "y"
    # The surface displacement is given: the punch's face on the contact.
    back, front = s.contact_interval
    xs = np.linspace(0.9 * back, 0.9 * front, 7)
    face = -s.indentation + xs**2 / (2.0 * R)
    assert np.max(np.abs(s.surface_displacement(xs) - face)) < 1e-9 * s.indentation


@pytest.mark.parametrize(("deborah", "scale"), [(1e-12, 1.0), (1e12, 3.0)])
def test_the_displacement_below_the_surface_meets_the_limits_and_the_springs(
    deborah, scale
):
    """v(x, y) in the elastic limits (1e-10 of its scale) from the
    base to y = -0.01; and the springs' law at the base, sigma_y(x, -h) =
    k_w v(x, -h) (the stress and the displacement come by different routes),
    for a material in between."""
    s = visco(0.3, mp.Zener(3.0, deborah))
    e = elastic(0.3, scale)
    for y in (-1.0, -0.1, -0.01):
        got, want = s.displacement(X, y), e.displacement(X, y)
        assert np.max(np.abs(got - want)) < 1e-10 * np.max(np.abs(want)), y
    s = visco(0.3, mp.Zener(3.0, 0.5))
    v = s.displacement(X, -1.0)
    sigma_y = s.stress_field(X, [-1.0]).sigma_y[0]
    assert np.max(np.abs(sigma_y - KW * v / LOAD)) < 1e-12 * np.max(np.abs(sigma_y))
    # It meets the surface's as y -> 0, linearly (the slope dv/dy is finite).
    top = s.surface_displacement(X)
    d1 = np.max(np.abs(s.displacement(X, -0.005) - top))
    d2 = np.max(np.abs(s.displacement(X, -0.0025) - top))
    assert d2 < 0.6 * d1
    assert d2 < 0.01 * s.indentation


def test_the_layer_carries_a_steady_contact_beyond_its_relaxed_critical_speed():
    """The material dissipates at every wavenumber but 0 and infinity (Im
    m(alpha) != 0), so no free steady wave exists below the relaxed Rayleigh
    speed: the steady contact is bounded beyond the relaxed V*_cr too
    (docs/theory.md section 17.9). Anchors: the energy balance and the load
    at every speed; nothing happens at V*_cr (the contact continuous through
    it to 1e-7); deborah -> inf is the unrelaxed elastic layer at vstar/3,
    subcritical for it, to 1e-10; the relaxed Rayleigh speed still bounds
    it. The independent reference's evaluation of a case beyond V*_cr is
    test_viscoelastic_independent.py."""
    vcr = mp.critical_vstar(layers=[mp.Layer(1.0, nu=NU)], base=mp.Winkler(KW))
    vr = mp.rayleigh_vstar(NU)
    material = mp.Zener(3.0, 0.5)
    for vstar in (0.98 * vcr, 1.05 * vcr, 0.5 * (vcr + vr), 0.995 * vr):
        s = visco(vstar, material)
        assert s.valid, s.validity
        assert s.warnings == ()
        assert s.drag == pytest.approx(s.dissipation, rel=1e-10)
        w, c = s.half_width, s.centre
        th = np.arange(1, 401) * np.pi / 401
        p = s.pressure(c + w * np.cos(th))
        assert np.all(p >= 0.0)
        assert w * np.pi / 401 * np.sum(np.sin(th) * p) == pytest.approx(1.0, rel=1e-10)
    below, above = visco(vcr * (1 - 1e-9), material), visco(vcr * (1 + 1e-9), material)
    gap = np.subtract(below.contact_interval, above.contact_interval)
    assert np.max(np.abs(gap)) < 1e-7
    assert above.drag == pytest.approx(below.drag, rel=1e-7)
    vstar = 1.15 * vcr
    s, e = visco(vstar, mp.Zener(3.0, 1e12)), elastic(vstar, 3.0)
    back, front = s.contact_interval
    assert abs(front - e.a) < 1e-10
    assert abs(-back - e.a) < 1e-10
    assert 0.0 <= s.drag < 1e-10
    with pytest.raises(SupercriticalSpeedError):
        visco(vr, material)
    # A stack's elastic sublayer could carry a free wave: its relaxed V*_cr
    # still bounds it.
    stack = [mp.Layer(0.5, nu=NU, viscoelastic=material), mp.Layer(0.5, nu=NU)]
    vcr_stack = mp.critical_vstar(layers=stack, base=mp.Winkler(KW))
    with pytest.raises(SupercriticalSpeedError):
        mp.solve(
            vstar=1.05 * vcr_stack,
            radius=R,
            load=LOAD,
            layers=stack,
            base=mp.Winkler(KW),
        )


def test_a_train_runs_beyond_the_relaxed_critical_speed():
    vcr = mp.critical_vstar(layers=[mp.Layer(1.0, nu=NU)], base=mp.Winkler(KW))
    t = mp.solve_punches(
        [mp.Punch(R, load=LOAD, at=0.0), mp.Punch(R, load=LOAD, at=3.0)],
        vstar=1.1 * vcr,
        layers=[mp.Layer(1.0, nu=NU, viscoelastic=mp.Zener(3.0, 0.5))],
        base=mp.Winkler(KW),
    )
    assert t.valid
    assert t.drag == pytest.approx(t.dissipation, rel=1e-10)


def test_the_command_line_solves_the_moving_layer(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli(
        "solve",
        "--vstar",
        "0.3",
        "--kw",
        str(KW),
        "--nu",
        str(NU),
        "--radius",
        str(R),
        "--load",
        str(LOAD),
        "--zener",
        "3,0.5",
        "--json",
    )
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    direct = visco(0.3, mp.Zener(3.0, 0.5))
    assert data["drag"] == direct.drag
    assert data["dissipation"] == pytest.approx(direct.drag, rel=1e-10)
    assert tuple(data["contact_interval"]) == direct.contact_interval


@pytest.mark.parametrize(("deborah", "scale"), [(1e-12, 1.0), (1e12, 3.0)])
def test_the_strains_near_the_surface_meet_the_elastic_limits(deborah, scale):
    """The strains pass the stresses through the material's compliance along
    x (the retardation spectrum, with or without inertia): near the surface,
    where the stresses' tail beyond the fine nodes is summed, they are the
    elastic layers' (the unrelaxed one's strains are its stresses over mu_inf:
    in units of mu_0, divided by the ratio)."""
    s = visco(0.3, mp.Zener(3.0, deborah))
    e = elastic(0.3, scale)
    xs = [0.0, 0.1]
    got = s.strain_field(xs, [-0.05])
    want = e.strain_field(xs, [-0.05])
    for name in ("eps_x", "eps_y", "gamma_xy"):
        a, b = getattr(got, name), getattr(want, name) / scale
        assert np.max(np.abs(a - b)) < 1e-9 * np.max(np.abs(b)), name


def test_a_scenes_speed_sweep_crosses_the_relaxed_critical_speed():
    """A scene's sweep of one moving Zener layer from below to beyond its
    relaxed V*_cr (the scene's checks let it through; a speed beyond V*_R
    fails at its point, naming the Rayleigh speed): every point is the
    API's solve."""
    vcr = mp.critical_vstar(layers=[mp.Layer(1.0, nu=NU)], base=mp.Winkler(KW))
    vr = mp.rayleigh_vstar(NU)
    speeds = (0.9 * vcr, 1.1 * vcr, 0.5 * (vcr + vr), 1.01 * vr)
    text = f"""
[params]
load = {LOAD}
radius = {R}
kw = {KW}

[[layers]]
thickness = 1.0
nu = {NU}
viscoelastic = {{ kind = "zener", ratio = 3.0, deborah = 0.5 }}

[sweep]
param = "vstar"
values = [{", ".join(repr(v) for v in speeds)}]
quantities = ["drag", "a"]
"""
    table = mp.Scene.from_toml(text).run().sweep
    assert table is not None
    for j, vstar in enumerate(speeds[:-1]):
        s = visco(vstar, mp.Zener(3.0, 0.5))
        assert table.data["drag"][0][j] == s.drag
        assert table.data["a"][0][j] == s.a
    assert math.isnan(table.data["drag"][0][-1])


def test_a_nearly_elastic_material_beyond_v_cr_is_the_limiting_absorption():
    """Beyond V*_cr the elastic layer has no steady state; a material with a
    vanishing loss (ratio 1 + eps) tends, at first order in eps, to the
    limiting-absorption solution that dashpots of vanishing strength give on
    the independent damped path (docs/damped.md: a/h = 1.2436873,
    -b/h = 0.4215438, drag 9.098258e-3 at V* = 0.65, k_w 1). Measured: the
    ends 1.1e-5, 1.2e-6 away at eps = 1e-4, 1e-5 (shrinking tenfold)."""
    damped = mp.solve(
        vstar=0.65, load=0.002, radius=100.0, kw=1.0, nu=0.2, damping=1e-7
    )
    gaps = []
    for eps in (1e-4, 1e-5):
        s = mp.solve(
            vstar=0.65,
            load=0.002,
            radius=100.0,
            layers=[mp.Layer(nu=0.2, viscoelastic=mp.Zener(1.0 + eps, 0.1))],
            base=mp.Winkler(1.0),
        )
        assert s.valid
        assert s.warnings == ()
        assert s.drag == pytest.approx(s.dissipation, rel=1e-10)
        gaps.append(
            np.max(np.abs(np.subtract(s.contact_interval, damped.contact_interval)))
        )
        assert abs(s.drag - damped.drag) < 1e-3 * eps
    assert gaps[1] < 5e-6
    assert 5.0 < gaps[0] / gaps[1] < 20.0  # first order in eps
