"""One viscoelastic material at many speeds (issue 28; docs/media.md "One
material at many speeds"): a material given by its relaxation time tau (in
h/c_T0) takes its deborah number sqrt(vstar) tau from each solve's speed;
``inertia=False`` (a scene's ``[params] inertia = false``, the command line's
``--quasi-static``) neglects the layer's inertia, so a sweep over vstar is
the quasi-static resistance curve of one material.

Independent anchors: Hunter's closed form for the half-plane (``hunter`` of
test_viscoelastic.py, our own derivation; S. C. Hunter, J. Appl. Mech. 28
(1961) 611-617), met by a scene's speed sweep at a0/h = 0.01 point by point;
and the elastic limits (the relaxed layer of mu_0 slow, the unrelaxed one of
ratio mu_0 fast), which bound the contact of every speed.
"""

from __future__ import annotations

import json
import math
import subprocess
from collections.abc import Callable

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.errors import InvalidParameterError
from movingpunch.media import material_from_dict
from test_viscoelastic import PHI0, hunter

NU = 1.0 - PHI0
R = 100.0
LOAD = 0.002


def layer(material: mp.Zener | mp.Prony, nu: float = NU) -> mp.Layer:
    return mp.Layer(nu=nu, viscoelastic=material)


def quasi_static(vstar: float, material: mp.Zener | mp.Prony, **kw: object):
    return mp.solve(
        vstar=vstar,
        radius=R,
        load=LOAD,
        layers=[layer(material)],
        base=mp.Winkler(1.0),
        inertia=False,
        **kw,
    )


# -- the material ---------------------------------------------------------


def test_a_material_of_tau_takes_its_deborah_number_from_the_speed():
    z = mp.Zener(10.0, tau=100.0)
    assert z.relaxes
    assert z.deborah is None
    assert z.at_speed(1e-6) == mp.Zener(10.0, math.sqrt(1e-6) * 100.0)
    assert z.at_speed(0.0) == mp.Zener(10.0, 0.0)
    given = mp.Zener(10.0, 0.5)
    assert given.at_speed(0.3) is given
    p = mp.Prony((1.0, 3.0), taus=(2.0, 50.0), shift=2.0)
    assert p.at_speed(0.04) == mp.Prony((1.0, 3.0), (0.4, 10.0), 2.0)
    for m in (z, p, given, mp.Prony((1.0,), (0.1,))):
        assert material_from_dict(m.to_dict(), "m") == m
    assert "tau 100 h/c_T0" in z.describe()
    assert not mp.Zener(1.0, tau=5.0).relaxes
    assert not mp.Zener(3.0, tau=0.0).relaxes


@pytest.mark.parametrize(
    ("make", "named"),
    [
        (lambda: mp.Zener(2.0), "deborah"),
        (lambda: mp.Zener(2.0, 0.1, 0.1), "tau"),
        (lambda: mp.Zener(2.0, tau=-1.0), "tau"),
        (lambda: mp.Zener(2.0, tau=math.nan), "tau"),
        (lambda: mp.Prony((1.0,)), "deborahs"),
        (lambda: mp.Prony((1.0,), (0.1,), taus=(0.1,)), "taus"),
        (lambda: mp.Prony((1.0, 2.0), taus=(0.1,)), "taus"),
        (lambda: mp.Prony((1.0,), taus=(math.inf,)), "taus"),
        # below the solver's smallest deborah number (0 relaxes at once)
        (lambda: mp.Zener(2.0, 1e-14), "deborah"),
        (lambda: mp.Prony((1.0,), (1e-10,), 1e-3), "deborahs"),
        (lambda: mp.Zener(2.0, tau=1e-4).at_speed(1e-20), "vstar"),
        (lambda: mp.Prony((1.0,), taus=(1e-4,), shift=1e-3).at_speed(1e-12), "vstar"),
    ],
)
def test_a_material_needs_one_kind_of_time(make, named):
    with pytest.raises(InvalidParameterError) as err:
        make()
    assert err.value.parameter == named


def test_a_material_of_tau_has_no_modulus_without_a_speed():
    with pytest.raises(InvalidParameterError, match="needs the speed") as err:
        mp.Zener(2.0, tau=1.0).modulus(1.0)
    assert err.value.parameter == "tau"
    # A solve at rest: deborah 0, the relaxed elastic layer.
    s = mp.solve(
        vstar=0.0, radius=R, load=LOAD, layers=[layer(mp.Zener(2.0, tau=1.0))], kw=1.0
    )
    elastic = mp.solve(vstar=0.0, radius=R, load=LOAD, kw=1.0, nu=NU)
    assert s.contact_interval == pytest.approx((-elastic.a, elastic.a), abs=1e-12)
    # A time too short for any speed but rest is still the relaxed layer at
    # rest (asking whether it follows the speed once resolved it at vstar 1).
    tiny = mp.solve(
        vstar=0.0, radius=R, load=LOAD, layers=[layer(mp.Zener(2.0, tau=1e-13))], kw=1.0
    )
    assert tiny.contact_interval == pytest.approx((-elastic.a, elastic.a), abs=1e-12)


# -- the solve --------------------------------------------------------------


@pytest.mark.parametrize("vstar", [1e-9, 1e-7, 1e-5])
def test_inertia_false_is_the_material_at_its_deborah_number_at_rest(vstar):
    s = quasi_static(vstar, mp.Zener(10.0, tau=100.0))
    at_rest = mp.solve(
        vstar=0.0,
        radius=R,
        load=LOAD,
        layers=[layer(mp.Zener(10.0, math.sqrt(vstar) * 100.0))],
        kw=1.0,
    )
    assert s.vstar == vstar  # the speed (the inertia neglected: its medium says)
    assert s.medium is not None
    assert not s.medium.inertia
    assert s.contact_interval == at_rest.contact_interval
    assert s.drag == at_rest.drag
    assert s.drag > 0.0
    assert s.drag == pytest.approx(s.dissipation, rel=1e-10)


def test_a_prony_series_of_taus_sweeps_like_its_deborahs():
    p = mp.Prony((1.0, 3.0), taus=(20.0, 400.0))
    s = quasi_static(1e-6, p)
    at = quasi_static(0.0, mp.Prony((1.0, 3.0), (0.02, 0.4)))
    assert s.contact_interval == at.contact_interval
    assert s.drag == pytest.approx(s.dissipation, rel=1e-10)


@pytest.mark.parametrize(
    ("kwargs", "named", "text"),
    [
        # with inertia the material's deborah number sqrt(vstar) tau stays in range
        (
            {"vstar": 1e-4, "layers": [layer(mp.Zener(10.0, tau=1e-11))], "kw": 1.0},
            "vstar",
            "deborah",
        ),
        # the speed would change nothing
        (
            {
                "vstar": 1e-4,
                "layers": [layer(mp.Zener(10.0, 0.1))],
                "kw": 1.0,
                "inertia": False,
            },
            "vstar",
            "changes nothing",
        ),
        ({"vstar": 1e-4, "kw": 1.0, "nu": NU, "inertia": False}, "vstar", "nothing"),
        (
            {
                "vstar": math.nan,
                "layers": [layer(mp.Zener(10.0, tau=1.0))],
                "kw": 1.0,
                "inertia": False,
            },
            "vstar",
            "finite",
        ),
        (
            {
                "vstar": 1e-4,
                "layers": [layer(mp.Zener(10.0, tau=1.0))],
                "kw": 1.0,
                "inertia": "no",
            },
            "inertia",
            "True or False",
        ),
        # the quasi-static layer stays below the relaxed critical speed
        (
            {
                "vstar": 0.6,
                "layers": [layer(mp.Zener(10.0, tau=1.0))],
                "kw": 1.0,
                "inertia": False,
            },
            "vstar",
            "critical",
        ),
    ],
)
def test_the_speed_of_a_material_is_refused_by_name(kwargs, named, text):
    with pytest.raises(InvalidParameterError, match=text) as err:
        mp.solve(radius=R, load=LOAD, **kwargs)
    assert err.value.parameter == named


def test_inertia_false_at_rest_is_the_solve_at_rest():
    """Nothing to neglect at vstar = 0: the paper's layer bit for bit."""
    a = mp.solve(vstar=0.0, radius=R, load=LOAD, kw=1.0, inertia=False).a
    assert a == mp.solve(vstar=0.0, radius=R, load=LOAD, kw=1.0).a


# -- scenes -----------------------------------------------------------------

A0 = 0.01
T = 10.0  # tau in h/c_T0
V_TAU = (0.05, 0.135, 0.4, 1.0)  # V tau/a0


def hunter_scene(values: tuple[float, ...]) -> str:
    load = math.pi * A0 * A0 / (2.0 * PHI0 * R)
    return f"""
name = "hunter-speed"

[params]
vstar = {values[0]!r}
kw = 1.0
radius = {R!r}
load = {load!r}
inertia = false

[[layers]]
nu = {NU!r}
viscoelastic = {{ kind = "zener", ratio = 10.0, tau = {T!r} }}

[outputs]
contact_width = true

[sweep]
param = "vstar"
values = {list(values)!r}
quantities = ["drag", "contact_start", "contact_end"]
"""


def test_a_scenes_speed_sweep_meets_hunters_curve():
    """deborah = sqrt(vstar) tau = V tau/h: the sweep's points at
    V tau/a0 = 0.05 ... 1 against Hunter's half-plane at a0/h = 0.01 (the
    layer approaches it like (a0/h)^2: about 1e-4 of its values here)."""
    values = tuple((v * A0 / T) ** 2 for v in V_TAU)
    scene = mp.Scene.from_toml(hunter_scene(values))
    table = scene.run().sweep
    assert table is not None
    load = math.pi * A0 * A0 / (2.0 * PHI0 * R)
    for j, v_tau in enumerate(V_TAU):
        c, w, drag = hunter(10.0, v_tau * A0, R, load, PHI0)
        got = table.data["drag"][0][j]
        assert abs(got - drag) * R / A0 < 2e-4, (v_tau, got, drag)
        back, front = (
            table.data["contact_start"][0][j],
            table.data["contact_end"][0][j],
        )
        assert abs(back - (c - w)) / A0 < 2e-4
        assert abs(front - (c + w)) / A0 < 2e-4


def test_the_bundled_bell_curve_lies_between_the_elastic_limits():
    scene = mp.Scene.bundled("viscoelastic-bell")
    medium = scene.medium
    assert medium is not None
    assert not medium.inertia
    assert medium.speed_dependent
    assert mp.Scene.from_toml(scene.to_toml()) == scene
    result = scene.run()
    table = result.sweep
    assert table is not None
    drag = np.asarray(table.data["drag"][0])
    front = np.asarray(table.data["contact_end"][0])
    back = np.asarray(table.data["contact_start"][0])
    nu, kw, ratio = medium.nu, 1.0, 10.0
    relaxed = mp.solve(vstar=0.0, radius=R, load=LOAD, kw=kw, nu=nu).a
    unrelaxed = mp.solve(vstar=0.0, radius=R, load=LOAD / ratio, kw=kw / ratio, nu=nu).a
    # Every speed's contact lies between the relaxed and unrelaxed layers'
    # (the front end shrinks from one to the other as the layer stiffens).
    assert np.all(front < relaxed)
    assert np.all(front > unrelaxed)
    assert np.all(np.diff(front) < 0)
    assert np.all(back > -relaxed)
    # The bell: drag > 0, one maximum inside, falling on both sides.
    k = int(np.argmax(drag))
    assert 0 < k < len(drag) - 1
    assert np.all(drag > 0)
    assert np.all(np.diff(drag[: k + 1]) > 0)
    assert np.all(np.diff(drag[k:]) < 0)
    assert drag[0] < 0.1 * drag[k]
    assert drag[-1] < 0.05 * drag[k]
    assert all("deborah" not in w for w in result.warnings)


def test_a_speed_sweep_reads_the_same_both_ways():
    values = (1e-8, 1e-7, 1e-6)
    up = mp.Scene.from_toml(hunter_scene(values)).run().sweep
    down = mp.Scene.from_toml(hunter_scene(values[::-1])).run().sweep
    assert up is not None
    assert down is not None
    for name in ("drag", "contact_start", "contact_end"):
        assert list(up.data[name][0]) == list(down.data[name][0])[::-1]


@pytest.mark.parametrize(
    ("edit", "key"),
    [
        ("inertia = false", "inertia = 0"),
        ("tau = 10.0 }", "deborah = 0.1 }"),
        # with inertia too: the material's deborah numbers stay in range
        ("tau = 10.0 }", "tau = 1e-14 }"),
        ("values = [", "values = [1e30, "),
    ],
)
def test_a_scene_refuses_a_speed_it_cannot_solve(edit, key):
    text = hunter_scene((1e-8, 1e-7))
    assert edit in text
    with pytest.raises(mp.SceneError) as err:
        mp.Scene.from_toml(text.replace(edit, key, 1))
    assert "inertia" in str(err.value) or "vstar" in str(err.value)


def test_a_scene_with_inertia_keeps_the_deborah_numbers_in_range():
    text = hunter_scene((1e-8, 1e-7)).replace("inertia = false\n", "")
    with pytest.raises(mp.SceneError, match="deborah") as err:
        mp.Scene.from_toml(text.replace("tau = 10.0 }", "tau = 1e-14 }"))
    assert "vstar" in str(err.value)


def test_a_scene_without_layers_refuses_inertia():
    text = """
[params]
vstar = 0.0
kw = 1.0
radius = 100.0
load = 0.002
inertia = false

[outputs]
contact_width = true
"""
    with pytest.raises(mp.SceneError, match=r"params\.inertia"):
        mp.Scene.from_toml(text)


# -- the command line -------------------------------------------------------


def test_the_command_line_sweeps_one_material_quasi_statically(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    base = ("solve", "--kw", "1", "--radius", "100", "--load", "0.002")
    proc = run_cli(
        *base, "--vstar", "1e-7", "--zener", "10,tau=100", "--quasi-static", "--json"
    )
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    direct = quasi_static(1e-7, mp.Zener(10.0, tau=100.0))
    assert data["drag"] == pytest.approx(direct.drag, rel=1e-12)
    assert data["quasi_static_vstar"] == 1e-7
    assert data["medium"]["inertia"] is False
    text = run_cli(*base, "--vstar", "1e-7", "--zener", "10,tau=100", "--quasi-static")
    assert "quasi-static" in text.stdout
    assert "deborah 0.0316228" in text.stdout
    for extra, said in (
        (("--zener", "10,tau=1e-11"), "deborah"),
        (("--zener", "10,0.1", "--quasi-static"), "changes nothing"),
        (("--quasi-static",), "--quasi-static needs"),
        (("--prony", "1,tau=10,2,0.1", "--quasi-static"), "every time"),
        (("--zener", "10,tau=x", "--quasi-static"), "10,tau=x"),
    ):
        proc = run_cli(*base, "--vstar", "1e-7", *extra)
        assert proc.returncode != 0
        assert said in proc.stderr, proc.stderr
        assert "Traceback" not in proc.stderr


def test_the_accuracy_ladder_of_a_speed_sweep_compares_each_speed():
    """The ladder keys each solution by its vstar: a quasi-static solution
    carries its speed (it came back with vstar 0 before, so the ladder
    compared one speed's contact with another's: errors of 0.2 in a/h)."""
    from movingpunch import accuracy

    scene = mp.Scene.from_toml(hunter_scene((1e-9, 1e-8, 1e-7)))
    report = accuracy.accuracy_report(scene, (1e-4, 1e-8))
    assert report is not None
    assert report.points == 3
    cols = report.columns()
    assert np.all(cols["error_a"] < cols["tol"])
    assert np.all(cols["error_a"] <= cols["error_estimate_a"])


def test_a_quasi_static_speed_just_below_the_relaxed_critical_speed_solves():
    """Near the relaxed layer's V*_cr (nu 0.2, kw 1: 0.5717) the quasi-static
    layer has nothing critical (no inertia): 0.999 V*_cr solves valid and
    balanced, V*_cr itself is refused naming vstar."""
    vcr = mp.critical_vstar(kw=1.0, nu=0.2)
    material = mp.Zener(10.0, tau=0.5)
    s = quasi_static(0.999 * vcr, material)
    assert s.valid
    assert s.vstar == 0.999 * vcr
    assert abs(s.drag - s.dissipation) <= 1e-10 * s.drag
    with pytest.raises(InvalidParameterError, match="critical") as err:
        quasi_static(vcr, material)
    assert err.value.parameter == "vstar"


@pytest.mark.parametrize("vstar", [0.0, 0.2])
def test_a_viscoelastic_contact_is_unique_and_grows_with_its_load(vstar):
    """A passive material's form is positive (Re M1 > 0: Re 1/m > 0 for
    every Zener or Prony modulus), so the frictionless contact is unique:
    the solver says so instead of scanning the load curve for other steady
    states, and (its consequence, checked independently of that claim) the
    contact grows with the load over three decades, both ends moving out."""
    material = mp.Zener(3.0, 0.2)
    ends = []
    for load in np.geomspace(1e-4, 0.1, 12):
        s = mp.solve(
            vstar=vstar,
            radius=R,
            load=float(load),
            layers=[layer(material)],
            base=mp.Winkler(1.0),
        )
        assert s.valid
        assert "unique (the medium's form is positive" in s.validity
        assert s.other_half_widths == ()
        ends.append(s.contact_interval)
    lo, hi = np.array(ends).T
    assert np.all(np.diff(hi) > 0.0)
    assert np.all(np.diff(lo) < 0.0)
