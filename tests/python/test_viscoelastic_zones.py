"""Trains of punches and separated contacts on viscoelastic media
(docs/theory.md section 17.8): the zones' solver with the material's memory
taken exactly between every pair of zones (MemoryKernel::block_at).

Anchors, none of them this solver's own earlier output:

* deborah -> 0 and -> infinity: the elastic trains of mu_0 and (rescaled)
  mu_inf, solved without any memory (the relaxed limit exercises the memory
  blocks between zones fully: there they carry the relaxed part of every
  zone's Cauchy term);
* the energy balance: the punches' drag (from the pressure and the punches'
  slopes) against the dissipation by Parseval from Im M1 of the train's
  whole pressure transform (an independent route), to 1e-10;
* punches far apart: each the single contact (the asymmetric solver), up to
  the relaxation the leading punch leaves behind (e^{-d/(ratio V tau)});
* a separated contact (one punch, two zones) in the relaxed limit: the
  elastic one.
"""

from __future__ import annotations

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.errors import InvalidParameterError

NU = 0.25
R = 5.0
LOAD = 0.05
KW = 2.0


def layer(material):
    return [mp.Layer(1.0, nu=NU, viscoelastic=material)]


def train(vstar, layers, base, spacing=1.2, loads=(LOAD, LOAD), profile=None):
    shape = profile if profile is not None else mp.Cylinder(R)
    punches = [
        mp.Punch(shape, load, at)
        for load, at in zip(loads, (-spacing / 2, spacing / 2), strict=True)
    ]
    return mp.solve_punches(punches, vstar=vstar, layers=layers, base=base)


@pytest.mark.parametrize("vstar", [0.0, 0.3])
def test_a_train_meets_the_relaxed_and_unrelaxed_elastic_trains(vstar):
    """Zener ratio 3: deborah 1e-12 is the elastic train of mu_0; 1e12 the
    elastic train of mu_inf = 3 (vstar, kw and the loads over 3): the zones'
    ends to 1e-10 (measured 2e-12 and 4e-14), the drag -> 0."""
    relaxed = train(vstar, layer(mp.Zener(3.0, 1e-12)), mp.Winkler(KW))
    want = train(vstar, layer(None), mp.Winkler(KW))
    assert np.allclose(relaxed.contact_zones, want.contact_zones, rtol=0, atol=1e-10)
    assert abs(relaxed.drag) < 1e-10
    unrelaxed = train(vstar, layer(mp.Zener(3.0, 1e12)), mp.Winkler(KW))
    want = train(
        vstar / 3.0, layer(None), mp.Winkler(KW / 3.0), loads=(LOAD / 3, LOAD / 3)
    )
    assert np.allclose(unrelaxed.contact_zones, want.contact_zones, rtol=0, atol=1e-10)


MEDIA = {
    "zener-layer": (layer(mp.Zener(3.0, 0.5)), mp.Winkler(KW)),
    "prony-layer": (layer(mp.Prony((1.0, 3.0), (0.05, 2.0))), mp.Winkler(KW)),
    "course-on-base": (
        [
            mp.Layer(0.4, nu=NU, viscoelastic=mp.Zener(3.0, 0.5)),
            mp.Layer(0.6, mu=2.0, nu=0.3, rho=1.2),
        ],
        mp.Winkler(KW),
    ),
    "lossy-subgrade": (
        [
            mp.Layer(0.3, nu=NU),
            mp.Layer(0.7, mu=0.5, nu=0.3, rho=0.8, viscoelastic=mp.Zener(4.0, 0.3)),
        ],
        mp.Winkler(KW),
    ),
}


@pytest.mark.parametrize("medium", list(MEDIA), ids=str)
@pytest.mark.parametrize("vstar", [0.0, 0.2])
def test_the_trains_drag_is_its_dissipation(medium, vstar):
    """Two unequal punches 1.2 h apart: the punches' drag against the power
    by Parseval over the train's whole pressure transform (1e-10); each
    zone's pressure >= 0, the loads carried, the rear punch's drag the
    smaller (it rides on the material the front one left relaxing)."""
    layers, base = MEDIA[medium]
    s = train(vstar, layers, base, loads=(0.04, 0.06))
    assert s.valid, s.validity
    assert s.warnings == ()
    assert s.drag > 0.0
    assert s.drag == pytest.approx(s.dissipation, rel=1e-10)
    assert [p.load for p in s.punches] == [0.04, 0.06]
    for p in s.punches:
        lo, hi = p.contact_zones[0]
        x = np.linspace(lo, hi, 41)[1:-1]
        assert np.all(p.pressure(x) >= 0.0)
    assert s.punches[0].drag < s.punches[1].drag


@pytest.mark.parametrize("vstar", [0.0, 0.3])
def test_punches_far_apart_are_each_the_single_contact(vstar):
    """60 h apart: the front punch is the single contact to 1e-12; the rear
    one too, up to the relaxation the front one leaves behind, which decays
    like e^{-d/(ratio V tau)} = e^{-40} here."""
    one = mp.solve(
        vstar=vstar,
        radius=R,
        load=LOAD,
        layers=layer(mp.Zener(3.0, 0.5)),
        base=mp.Winkler(KW),
    )
    s = train(vstar, layer(mp.Zener(3.0, 0.5)), mp.Winkler(KW), spacing=60.0)
    lo, hi = one.contact_interval
    for zone, at in zip(s.contact_zones, (-30.0, 30.0), strict=True):
        assert zone[0] - at == pytest.approx(lo, abs=1e-12)
        assert zone[1] - at == pytest.approx(hi, abs=1e-12)
    assert s.drag == pytest.approx(one.drag, rel=1e-10)
    assert s.dissipation == pytest.approx(one.dissipation, rel=1e-10)


def test_a_separated_contact_on_a_viscoelastic_layer():
    """The bundled scene's soft foundation at 99 % of V*_cr: two zones under
    one cylinder; in the relaxed limit the elastic separated contact (1e-9),
    and with a memory the energy balance (1e-10) and the zones shifted
    forward (the material ahead is stiffer)."""
    vstar = 0.2450464183670153
    args = {"vstar": vstar, "radius": 100.0, "load": 0.002, "base": mp.Winkler(0.1)}
    elastic = mp.solve(**args, layers=[mp.Layer(1.0, nu=0.2)])
    assert len(elastic.contact_zones) == 2
    relaxed = mp.solve(
        **args, layers=[mp.Layer(1.0, nu=0.2, viscoelastic=mp.Zener(1.5, 1e-12))]
    )
    assert np.allclose(relaxed.contact_zones, elastic.contact_zones, rtol=0, atol=1e-9)
    s = mp.solve(
        **args, layers=[mp.Layer(1.0, nu=0.2, viscoelastic=mp.Zener(1.5, 0.05))]
    )
    assert len(s.contact_zones) == 2
    assert s.valid
    assert s.drag == pytest.approx(s.dissipation, rel=1e-10)
    assert sum(z[0] + z[1] for z in s.contact_zones) > 0.0  # shifted forward


def test_what_the_zones_do_not_take_on_a_viscoelastic_medium_is_refused():
    with pytest.raises(InvalidParameterError) as e:
        train(
            0.1,
            layer(mp.Zener(3.0, 0.5)),
            mp.Winkler(KW),
            profile=mp.RoundedFlat(0.2, 5.0),
        )
    assert e.value.parameter == "profile"


def test_a_train_on_a_viscoelastic_layer_over_a_half_space():
    """A viscoelastic layer on a half-space carries a train too (it was
    refused naming base): the energy balance, the faces and the reference
    point x = 100 h (test_media_asymmetric.py anchors the half-space trains'
    reference against the symmetric solver)."""
    s = train(0.1, layer(mp.Zener(3.0, 0.5)), mp.HalfSpace(mu=3.0, nu=0.25))
    assert s.valid
    assert s.drag > 0.0
    assert s.drag == pytest.approx(s.dissipation, rel=1e-10)
    assert float(s.surface_displacement(100.0)) == 0.0


TWO_PUNCHES = f"""
[[punches]]
radius = {R!r}
load = {LOAD!r}
at = -0.6

[[punches]]
radius = {R!r}
load = {LOAD!r}
at = 0.6

[outputs]
contact_width = true
"""
"""Two punches 1.2 h apart and the scenes' contact table (a scene's tail)."""


def test_a_bogie_scene_on_an_asphalt_course():
    """A scene's train of punches on a viscoelastic course: its drag table is
    the API's."""
    text = f"""
name = "asphalt-bogie"

[params]
vstar = 0.1
kw = {KW!r}

[[layers]]
thickness = 0.4
nu = {NU!r}
viscoelastic = {{ kind = "zener", ratio = 3.0, deborah = 0.5 }}

[[layers]]
thickness = 0.6
mu = 2.0
nu = 0.3
rho = 1.2

{TWO_PUNCHES}"""
    out = mp.Scene.from_toml(text).run()
    table = out.outputs["contact_width"].columns
    layers, base = MEDIA["course-on-base"]
    direct = train(0.1, layers, base)
    assert table["drag"][0] == pytest.approx(direct.drag, rel=1e-14)


def test_a_train_scene_on_an_elastic_stack_is_solved_on_the_stack():
    """A scene's [[punches]] with [[layers]]: the stack's train (it was the
    homogeneous layer of [params] before: the layers silently ignored)."""
    text = f"""
name = "stack-bogie"

[params]
vstar = 0.2
kw = {KW!r}

[[layers]]
thickness = 0.3
nu = {NU!r}

[[layers]]
thickness = 0.7
mu = 0.3
nu = 0.3

{TWO_PUNCHES}"""
    out = mp.Scene.from_toml(text).run()
    start = out.outputs["contact_width"].columns["contact_start"][0]
    layers = [mp.Layer(0.3, nu=NU), mp.Layer(0.7, mu=0.3, nu=0.3)]
    direct = train(0.2, layers, mp.Winkler(KW))
    homogeneous = train(0.2, [mp.Layer(1.0, nu=0.2)], mp.Winkler(KW))
    assert start == direct.contact_interval[0]
    assert abs(start - homogeneous.contact_interval[0]) > 1e-3
