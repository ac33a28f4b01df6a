"""A scene's punches are refused only where the solver refuses them (issue
25, red-team finding 10): two punches whose contacts would overlap alone lift
each other in a train, and ``solve_punches`` may well solve them with their
zones apart; the scene check (``_check_overlap``) then lets the scene run,
and refuses, naming both punches, only a pair the solver refuses."""

from __future__ import annotations

import math

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.scene import Scene, SceneError

R, LOAD = 100.0, 0.002
LAYER = {"vstar": 0.5, "kw": 1.0}


def _scene(ats: list[float], extra: str = "") -> str:
    punches = "".join(
        f"[[punches]]\nradius = {R}\nload = {LOAD}\nat = {at!r}\n" for at in ats
    )
    return (
        f"[params]\nvstar = {LAYER['vstar']}\nkw = {LAYER['kw']}\n{punches}"
        "[outputs]\ncontact_width = true\npressure = { points = 41 }\n" + extra
    )


def _load(p: mp.PunchResult, lo: float, hi: float) -> float:
    """int_lo^hi p dx by Gauss-Legendre in theta (x = c + w cos theta)."""
    t, w = np.polynomial.legendre.leggauss(64)
    theta = 0.5 * math.pi * (t + 1.0)
    c, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    x = c + half * np.cos(theta)
    return (
        0.5
        * math.pi
        * float(np.sum(w * np.asarray(p.pressure(x)) * half * np.sin(theta)))
    )


def test_punches_whose_own_contacts_overlap_run_as_the_solver_solves_them() -> None:
    # Alone each contact reaches past the other's axis (refused before as
    # overlapping); solve_punches solves the pair with the zones apart.
    alone = mp.solve(**LAYER, radius=R, load=LOAD)
    assert alone.a > 0.5
    scene = Scene.from_toml(_scene([-0.5, 0.5]), "pair.toml")
    result = scene.run()
    direct = mp.solve_punches(list(scene.punches), **LAYER)
    cw = result.outputs["contact_width"]
    assert cw.columns["a"][0] == direct.a
    assert cw.columns["indentation"][0] == direct.indentation
    assert cw.columns["valid"][0] == 1.0
    assert cw.details["contact_zones"] == [[list(z) for z in direct.contact_zones]]
    pressure = result.outputs["pressure"]
    x = pressure.curves[0].x
    np.testing.assert_array_equal(pressure.curves[0].y, direct.pressure(x))
    # Independent of the solver's verdicts: the zones end apart, each punch's
    # pressure is >= 0 and carries its own load (over P_k/h: 1).
    (_, r1), (l2, _) = direct.contact_zones
    assert r1 < l2
    for punch in direct.punches:
        ((lo, hi),) = punch.contact_zones
        assert _load(punch, lo, hi) == pytest.approx(1.0, abs=1e-8)
        assert np.min(punch.pressure(np.linspace(lo, hi, 401))) >= 0.0


def test_a_spacing_vary_runs_every_spacing_the_solver_solves() -> None:
    # 0.5 was refused before (alone the contacts overlap); both run now, each
    # curve the train solve_punches gives at that spacing.
    vary = '[vary]\nparam = "spacing"\nvalues = [4.0, 0.5]\n'
    result = Scene.from_toml(_scene([-2.0, 2.0], vary), "vary.toml").run()
    cw = result.outputs["contact_width"]
    for i, spacing in enumerate((4.0, 0.5)):
        half = 0.5 * spacing
        direct = mp.solve_punches(
            [mp.Punch(R, LOAD, at=-half), mp.Punch(R, LOAD, at=half)], **LAYER
        )
        assert cw.columns["a"][i] == direct.a
        assert cw.details["contact_zones"][i] == [list(z) for z in direct.contact_zones]


@pytest.mark.parametrize(
    ("ats", "pair"),
    [
        ([-0.01, 0.01], (0, 1)),
        ([0.0, 0.1], (0, 1)),
        ([-3.0, 0.0, 0.02], (1, 2)),
    ],
)
def test_punches_the_solver_refuses_are_a_scene_error_naming_both(
    ats: list[float], pair: tuple[int, int]
) -> None:
    k1, k2 = pair
    with pytest.raises(mp.InvalidParameterError) as solver:
        mp.solve_punches([mp.Punch(R, LOAD, at=at) for at in ats], **LAYER)
    assert solver.value.parameter == "punches"
    assert f"punches[{k1}] and punches[{k2}]" in str(solver.value)
    with pytest.raises(SceneError) as info:
        Scene.from_toml(_scene(ats), "close.toml")
    assert info.value.key == f"punches[{k2}].at"
    msg = str(info.value)
    assert f"punches[{k1}] and punches[{k2}] overlap" in msg
    assert "no contact set keeps them apart" in msg
    assert "\n" not in msg
