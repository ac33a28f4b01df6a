"""The medium's value types and their way into solve (movingpunch.media).

The physical anchors of layered media (identical sublayers, the half-space
closed forms, the staircase) are in test_media_anchors.py; here: the API's
contract (validation naming the parameter, the shorthand's equivalence, the
refusals of combinations not supported yet).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import movingpunch as mp

PAPER = {"vstar": 0.2, "load": 0.002, "radius": 100.0, "tol": 1e-10}


@pytest.mark.parametrize(
    ("make", "parameter"),
    [
        (lambda: mp.Layer(0.0), "thickness"),
        (lambda: mp.Layer(1.5), "thickness"),
        (lambda: mp.Layer(0.5, mu=-1.0), "mu"),
        (lambda: mp.Layer(0.5, mu=math.nan), "mu"),
        (lambda: mp.Layer(0.5, nu=0.5), "nu"),
        (lambda: mp.Layer(0.5, rho=0.0), "rho"),
        (lambda: mp.Layer(0.5, rho="heavy"), "rho"),
        (lambda: mp.GradedLayer(51.0), "gamma_h"),
        (lambda: mp.GradedLayer(math.inf), "gamma_h"),
        (lambda: mp.Winkler(-1.0), "kw"),
        (lambda: mp.Winkler(1.0, kp=-0.1), "kp"),
        (lambda: mp.Winkler(1.0, damping=math.nan), "damping"),
        (lambda: mp.HalfSpace(0.0, 0.3), "mu"),
        (lambda: mp.HalfSpace(1.0, 0.6), "nu"),
        (lambda: mp.HalfSpace(1.0, 0.3, interface="glued"), "interface"),
    ],
)
def test_value_types_name_the_bad_parameter(make: object, parameter: str) -> None:
    with pytest.raises(mp.InvalidParameterError) as info:
        make()  # type: ignore[operator]
    assert info.value.parameter == parameter
    assert info.value.allowed


@pytest.mark.parametrize(
    ("kwargs", "parameter", "says"),
    [
        ({"layers": [mp.Layer(1.0)], "nu": 0.3, "kw": 1.0}, "nu", "per sublayer"),
        (
            {"layers": [mp.Layer(1.0)], "base": mp.HalfSpace(2.0, 0.3), "kw": 1.0},
            "kw",
            "no springs",
        ),
        ({"base": mp.Winkler(1.0), "kp": 0.2}, "kp", "Winkler"),
        ({"layers": [mp.Layer(0.5), mp.Layer(0.4)], "kw": 1.0}, "layers", "sum to 0.9"),
        (
            {"layers": [mp.Layer(0.5, mu=2.0), mp.Layer(0.5)], "kw": 1.0},
            "layers",
            "units",
        ),
        ({"layers": [], "kw": 1.0}, "layers", "at least one"),
        ({"layers": [(0.5, 1.0)], "kw": 1.0}, "layers", r"layers\[0\]"),
        ({"layers": [mp.Layer()]}, "kw", "required"),
        ({"layers": [mp.Layer()], "base": "springs"}, "base", "Winkler"),
    ],
)
def test_conflicting_or_broken_media_are_refused_by_name(
    kwargs: dict[str, object], parameter: str, says: str
) -> None:
    with pytest.raises(mp.InvalidParameterError, match=says) as info:
        mp.solve(**PAPER, **kwargs)  # type: ignore[arg-type]
    assert info.value.parameter == parameter


def test_solve_without_kw_or_base_names_kw() -> None:
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(**PAPER)  # type: ignore[call-overload]
    assert info.value.parameter == "kw"


@pytest.mark.parametrize(
    ("shorthand", "medium"),
    [
        ({"kw": 1.0}, {"layers": [mp.Layer(1.0)], "base": mp.Winkler(1.0)}),
        ({"kw": 2.0, "nu": 0.35}, {"layers": [mp.Layer(nu=0.35)], "kw": 2.0}),
        ({"kw": 1.0, "kp": 0.3}, {"base": mp.Winkler(1.0, kp=0.3)}),
        ({"kw": math.inf, "nu": 0.1}, {"layers": [mp.Layer(nu=0.1)], "kw": math.inf}),
        ({"kw": 1.0, "damping": 0.4}, {"base": mp.Winkler(1.0, damping=0.4)}),
    ],
)
def test_one_homogeneous_sublayer_is_the_shorthand_bit_for_bit(
    shorthand: dict[str, object], medium: dict[str, object]
) -> None:
    a = mp.solve(**PAPER, **shorthand)  # type: ignore[arg-type]
    b = mp.solve(**PAPER, **medium)  # type: ignore[arg-type]
    assert type(a) is type(b)
    assert b.contact_interval == a.contact_interval
    assert b.indentation == a.indentation
    x = np.linspace(-2 * a.half_width, 2 * a.half_width, 7)
    y = np.array([0.0, -0.4, -1.0])
    fa, fb = a.stress_field(x, y), b.stress_field(x, y)
    assert np.array_equal(fa.sigma_x, fb.sigma_x)
    assert np.array_equal(fa.tau_xy, fb.tau_xy)
    assert b.medium.homogeneous
    assert b.medium == a.medium


def test_the_medium_of_a_solution_describes_it() -> None:
    s = mp.solve(**PAPER, kw=1.0, kp=0.2, nu=0.3)
    assert s.medium == mp.Medium(
        layers=(mp.Layer(1.0, nu=0.3),), base=mp.Winkler(1.0, kp=0.2)
    )
    assert s.medium.describe() == (
        "layer h_i/h = 1, mu 1, nu 0.3, rho 1 on kw = 1, kp = 0.2"
    )


def test_critical_speed_of_the_homogeneous_medium_is_the_layers() -> None:
    assert mp.critical_vstar(layers=[mp.Layer(nu=0.3)], base=mp.Winkler(2.0)) == (
        mp.critical_vstar(2.0, 0.3)
    )
    assert mp.critical_vstar(kw=1.0) == mp.critical_vstar(1.0, 0.2)
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.critical_vstar(layers=[mp.Layer()])
    assert info.value.parameter == "kw"
