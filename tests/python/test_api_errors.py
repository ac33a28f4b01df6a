"""Errors users can catch: every bad input of the public API is rejected with
an InvalidParameterError (a ValueError and a MovingPunchError) naming the
parameter; speeds at or above V*_cr raise SupercriticalSpeedError."""

from __future__ import annotations

import dataclasses
import math
import re
from typing import Any

import numpy as np
import pytest

import movingpunch as mp
from movingpunch import _core

GOOD: dict[str, Any] = {
    "vstar": 0.2,
    "kw": 1.0,
    "radius": 100.0,
    "load": 0.002,
    "nu": 0.2,
    "tol": 1e-8,
}

# V*_cr(kw = 1, nu = 0.2) and V*_R(nu = 0.2): docs/theory.md §8.
CRITICAL_KW1 = 0.5716928
RAYLEIGH = 0.8299135134

NOT_REAL = ["abc", None, True, False, 1 + 0j, complex(0.2, 0.0), [0.2], np.bool_(True)]
NON_FINITE = [math.nan, math.inf, -math.inf]

BAD: list[tuple[str, Any]] = []
for name in GOOD:
    # nu=None is "not given" (0.2; per sublayer with layers=).
    BAD += [(name, v) for v in NOT_REAL if not (name == "nu" and v is None)]
    BAD += [(name, v) for v in NON_FINITE if not (name == "kw" and v == math.inf)]
BAD += [
    ("vstar", -0.1),
    ("vstar", -1e-300),
    ("kw", -1.0),
    ("kw", 0.0),  # no foundation: no static equilibrium
    ("radius", -1.0),
    ("radius", 0.0),
    ("radius", 0),
    ("load", -0.002),
    ("load", 0.0),
    ("nu", -0.1),
    ("nu", 0.5),
    ("nu", 0.7),
    ("tol", -1e-8),
    ("tol", 0.0),
    ("tol", 1e-15),
    ("tol", 0.1),
]


@pytest.fixture(scope="module")
def paper() -> mp.Solution:
    return mp.solve(**GOOD)


@pytest.mark.parametrize(("name", "value"), BAD, ids=repr)
def test_solve_rejects_bad_parameter(name: str, value: Any) -> None:
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(**{**GOOD, name: value})
    assert isinstance(info.value, ValueError)
    assert isinstance(info.value, mp.MovingPunchError)
    assert str(info.value).startswith(name)


def test_nu_none_is_the_default(paper: mp.Solution) -> None:
    assert mp.solve(**{**GOOD, "nu": None}).a == paper.a


def test_type_message_names_parameter_and_range() -> None:
    with pytest.raises(mp.InvalidParameterError, match="radius") as info:
        mp.solve(**{**GOOD, "radius": "abc"})
    assert str(info.value) == (
        "radius must be a real number (0 < radius <= 1e12, radius = R/h), got 'abc'"
    )


@pytest.mark.parametrize("value", ["yes", 1, None])
def test_allow_unphysical_must_be_bool(value: Any) -> None:
    with pytest.raises(mp.InvalidParameterError, match="allow_unphysical"):
        mp.solve(**GOOD, allow_unphysical=value)


def test_solve_is_keyword_only() -> None:
    with pytest.raises(TypeError):
        mp.solve(0.2, 1.0, 100.0, 0.002)  # type: ignore[call-arg]


def test_numpy_and_int_inputs_are_accepted() -> None:
    s = mp.solve(vstar=np.float64(0.2), kw=np.int64(1), radius=100, load=0.002)
    assert isinstance(s.kw, float)
    assert s.a > 0


def test_supercritical_speed() -> None:
    with pytest.raises(mp.SupercriticalSpeedError) as info:
        mp.solve(**{**GOOD, "vstar": 0.6})
    err = info.value
    assert isinstance(err, ValueError)
    assert isinstance(err, mp.MovingPunchError)
    assert err.vstar == 0.6
    assert err.critical_vstar == pytest.approx(CRITICAL_KW1, abs=1e-6)
    assert err.rayleigh_vstar == pytest.approx(RAYLEIGH, abs=1e-9)
    numbers = [float(x) for x in re.findall(r"\d+\.\d+(?:[eE][-+]?\d+)?", str(err))]
    assert any(abs(x - CRITICAL_KW1) < 1e-4 for x in numbers), str(err)
    assert any(abs(x - RAYLEIGH) < 1e-4 for x in numbers), str(err)


def test_supercritical_error_defaults() -> None:
    err = mp.SupercriticalSpeedError("too fast")
    assert err.vstar is None
    assert err.critical_vstar is None
    assert err.rayleigh_vstar is None
    assert str(err) == "too fast"


def test_core_translates_invalid_argument() -> None:
    # The core's own checks (bypassing the Python ones) map to the same family.
    with pytest.raises(mp.InvalidParameterError, match="vstar"):
        _core.solve_contact(**{**GOOD, "vstar": math.nan}, allow_unphysical=False)
    with pytest.raises(mp.InvalidParameterError, match="method"):
        _core.layer_response(np.array([1.0]), 0.2, 1.0, 0.2, "nope")


def test_solution_is_frozen(paper: mp.Solution) -> None:
    with pytest.raises(dataclasses.FrozenInstanceError):
        paper.a = 1.0  # type: ignore[misc]
    with pytest.raises(AttributeError):
        paper._impl.a = 1.0  # type: ignore[misc]


@pytest.mark.parametrize(
    "x",
    [
        math.nan,
        math.inf,
        [0.0, math.nan],
        np.array([[0.1], [-math.inf]]),
        "a",
        None,
        1j,
        [0.1, "a"],
    ],
    ids=repr,
)
def test_pressure_rejects_bad_points(paper: mp.Solution, x: Any) -> None:
    with pytest.raises(mp.InvalidParameterError, match="x"):
        paper.pressure(x)
    with pytest.raises(mp.InvalidParameterError, match="x"):
        paper.surface_displacement(x)


@pytest.mark.parametrize(
    ("func", "kwargs", "name"),
    [
        (mp.critical_vstar, {"kw": -1.0}, "kw"),
        (mp.critical_vstar, {"kw": math.nan}, "kw"),
        (mp.critical_vstar, {"kw": 1.0, "nu": 0.5}, "nu"),
        (mp.critical_wavenumber, {"kw": "1"}, "kw"),
        (mp.rayleigh_vstar, {"nu": -0.1}, "nu"),
        (mp.phi1, {"vstar": math.nan}, "vstar"),
        (mp.phi2, {"vstar": -1.0}, "vstar"),
        (mp.phi1, {"vstar": 0.9}, "vstar"),  # above the Rayleigh speed: core check
    ],
)
def test_helpers_reject_bad_parameters(
    func: Any, kwargs: dict[str, Any], name: str
) -> None:
    with pytest.raises(mp.InvalidParameterError, match=name):
        func(**kwargs)


@pytest.mark.parametrize(
    ("t", "kwargs", "name"),
    [
        ([1.0, math.nan], {}, "t"),
        (-1.0, {}, "t"),
        (1.0, {"vstar": -0.1}, "vstar"),
        (1.0, {"vstar": 1.0}, "vstar"),  # core: needs vstar < 1
        (1.0, {"kw": -1.0}, "kw"),
        (1.0, {"method": "exact"}, "method"),
    ],
)
def test_layer_response_rejects_bad_parameters(
    t: Any, kwargs: dict[str, Any], name: str
) -> None:
    args: dict[str, Any] = {"vstar": 0.2, "kw": 1.0, **kwargs}
    with pytest.raises(mp.InvalidParameterError, match=name):
        mp.layer_response(t, **args)
