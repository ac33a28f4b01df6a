"""The damped solver's indentation, surface displacement and displacement field
(issue 13), each against an anchor computed independently of it:

- damping -> 0 and V* = 0 (where the dashpot term vanishes): the undamped
  solver, an independent stack down to its kernel;
- the slope of v(x, 0) is ``surface_slope`` (a Cauchy integral plus the
  tabulated kernel, no displacement code), and the gap beside the contact is
  the integral of x/R - ``surface_slope`` from the contact's end (scipy);
- on the contact the gap -delta + x^2/(2R) - v(x, 0) vanishes (the punch's
  boundary condition, which the solver imposes on the slope only);
- the field's faces: ``displacement(x, -1)`` is ``bottom_displacement`` (a
  direct sum of the bottom response, no split), ``displacement(x, 0)`` is
  ``surface_displacement`` (real log potentials and a log1p rule against the
  field's complex potentials).

The interior of the field at finite damping is checked against a direct
Fourier sum in tests/cpp/test_asymmetric_displacement.cpp.
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np
import pytest
from scipy import integrate

import movingpunch as mp
from movingpunch.errors import InvalidParameterError

PAPER = {"radius": 100.0, "load": 0.002, "nu": 0.2}

# Subcritical, the same at two dampings, and above V*_cr(kw = 1) = 0.5717
# (the whole contact ahead of the punch's lowest point).
CASES = {
    "sub-0.1": {"vstar": 0.2, "kw": 1.0, "damping": 0.1},
    "sub-1": {"vstar": 0.2, "kw": 1.0, "damping": 1.0},
    "super-0.1": {"vstar": 0.65, "kw": 1.0, "damping": 0.1},
}


@pytest.fixture(scope="module", params=sorted(CASES))
def damped(request: pytest.FixtureRequest) -> Any:
    return mp.solve(**PAPER, **CASES[str(request.param)])


def _gap(s: Any, x: Any) -> Any:
    return (
        -s.indentation
        + np.asarray(x) ** 2 / (2.0 * s.radius)
        - s.surface_displacement(x)
    )


@pytest.mark.parametrize("damping", [1e-12, 1e-9])
@pytest.mark.parametrize(("vstar", "kw"), [(0.2, 1.0), (0.65, 10.0)])
def test_vanishing_damping_gives_the_undamped_displacement(
    vstar: float, kw: float, damping: float
) -> None:
    """(V* = 0.65 with kw = 10: below its V*_cr = 0.8186, so the undamped
    solver has a solution.) The field's first-order change in the damping
    is odd in x: 1.3e-10 of delta at damping 1e-9; the indentation's is
    second order (5e-14 seen)."""
    undamped = mp.solve(vstar=vstar, kw=kw, **PAPER)
    s = mp.solve(vstar=vstar, kw=kw, damping=damping, **PAPER)
    delta = undamped.indentation
    assert s.indentation == pytest.approx(delta, rel=1e-12)
    x = np.linspace(-3.0, 3.0, 25)
    np.testing.assert_allclose(
        s.surface_displacement(x), undamped.surface_displacement(x), atol=1e-9 * delta
    )
    for y in (0.0, -0.1, -0.5, -1.0):
        np.testing.assert_allclose(
            s.displacement(x, y),
            undamped.displacement(x, y),
            atol=1e-9 * delta,
            err_msg=f"y = {y}",
        )


def test_at_rest_the_dashpots_change_nothing() -> None:
    """At V* = 0 the dashpot term damping sqrt(V*) dv/dx vanishes: the damped
    stack gives the static undamped displacement (5e-15 of delta seen)."""
    undamped = mp.solve(vstar=0.0, kw=1.0, **PAPER)
    s = mp.solve(vstar=0.0, kw=1.0, damping=5.0, **PAPER)
    delta = undamped.indentation
    assert s.indentation == pytest.approx(delta, rel=1e-12)
    x = np.linspace(-2.0, 2.0, 9)
    for y in (0.0, -0.3, -1.0):
        np.testing.assert_allclose(
            s.displacement(x, y), undamped.displacement(x, y), atol=1e-12 * delta
        )


def test_on_a_rigid_base_the_dashpots_are_inert() -> None:
    """kw = inf: the base does not move, so its dashpots do nothing; the
    bottom stays put and the field is the undamped one (6e-16 seen)."""
    undamped = mp.solve(vstar=0.2, kw=math.inf, **PAPER)
    s = mp.solve(vstar=0.2, kw=math.inf, damping=0.1, **PAPER)
    delta = undamped.indentation
    assert s.indentation == pytest.approx(delta, rel=1e-12)
    x = np.linspace(-3.0, 3.0, 7)
    np.testing.assert_allclose(s.displacement(x, -1.0), 0.0, atol=1e-14 * delta)
    np.testing.assert_allclose(
        s.displacement(x, -0.5), undamped.displacement(x, -0.5), atol=1e-12 * delta
    )


def test_dashpots_alone_leave_the_wake_sunk_by_load_over_beta() -> None:
    """kw -> 0: the base carries P through the dashpots only,
    beta (v(+inf) - v(-inf)) = P with beta = damping sqrt(V*) (force balance
    on the bottom face), so far behind the punch the layer has sunk by
    load/beta and far ahead not at all, through the whole thickness."""
    s = mp.solve(vstar=0.3, kw=1e-12, damping=1.0, **PAPER)
    sunk = -s.load / (s.damping * math.sqrt(s.vstar))
    far = np.array([-200.0, -50.0, 50.0, 200.0])
    expected = np.array([sunk, sunk, 0.0, 0.0])
    np.testing.assert_allclose(s.surface_displacement(far), expected, atol=1e-9 * -sunk)
    for y in (-0.5, -1.0):
        np.testing.assert_allclose(s.displacement(far, y), expected, atol=1e-9 * -sunk)


def test_slope_of_the_surface_displacement_is_the_surface_slope(damped: Any) -> None:
    """Five-point differences (h = 1e-3, truncation ~1e-10) of v(x, 0) on and
    beside the contact, away from its ends (where v'' has a square-root
    singularity), against ``surface_slope`` (2e-10 of its maximum seen)."""
    back, front = damped.contact_interval
    w = damped.half_width
    x = np.concatenate(
        [
            np.linspace(back + 0.05 * w, front - 0.05 * w, 9),
            np.linspace(front + 0.1, front + 3.0, 6),
            np.linspace(back - 3.0, back - 0.1, 6),
        ]
    )
    h = 1e-3
    v = damped.surface_displacement
    slope = (v(x - 2 * h) - 8 * v(x - h) + 8 * v(x + h) - v(x + 2 * h)) / (12 * h)
    expected = damped.surface_slope(x)
    np.testing.assert_allclose(
        slope, expected, rtol=0.0, atol=2e-9 * np.max(np.abs(expected))
    )


def test_gap_closes_on_the_contact_and_opens_beside_it(damped: Any) -> None:
    back, front = damped.contact_interval
    delta = damped.indentation
    assert delta > 0.0
    # On the contact: the punch's profile (1e-13 of delta seen).
    on = damped.centre + damped.half_width * np.linspace(-0.99, 0.99, 11)
    np.testing.assert_allclose(_gap(damped, on), 0.0, atol=1e-10 * delta)
    # Beside it, within 2 (a + b) of each end: open, and equal to the
    # integral of x/R - v'(x, 0) from the end (1e-15 of delta seen).
    q = np.linspace(0.0, 1.0, 101)[1:] ** 2 * 4.0 * damped.half_width
    side = np.concatenate([front + q, back - q])
    assert (_gap(damped, side) > 0.0).all()
    for end, x in [(front, front + 0.5), (front, front + 2.0), (back, back - 0.5)]:
        expected = integrate.quad(
            lambda t: t / damped.radius - float(damped.surface_slope(t)),
            end,
            x,
            epsabs=1e-16,
            epsrel=1e-13,
        )[0]
        assert float(_gap(damped, x)) == pytest.approx(expected, abs=1e-10 * delta)
    # The solver's own min_gap (integrated from the slope) sees the same.
    assert damped.min_gap > 0.0


def test_field_faces_are_the_surface_and_bottom_displacements(damped: Any) -> None:
    """Agreement 1e-15 of delta seen on both faces."""
    x = np.linspace(-3.0, 3.0, 13)
    delta = damped.indentation
    np.testing.assert_allclose(
        damped.displacement(x, 0.0),
        damped.surface_displacement(x),
        rtol=0.0,
        atol=1e-12 * delta,
    )
    np.testing.assert_allclose(
        damped.displacement(x, -1.0),
        damped.bottom_displacement(x),
        rtol=0.0,
        atol=1e-12 * delta,
    )


def test_scalars_arrays_and_to_dict(damped: Any) -> None:
    assert isinstance(damped.indentation, float)
    assert isinstance(damped.surface_displacement(0.1), float)
    assert isinstance(damped.displacement(0.1, -0.5), float)
    x = np.array([[-1.0, 0.0], [0.5, 2.0]])
    assert damped.surface_displacement(x).shape == x.shape
    assert damped.displacement(x, -0.5).shape == x.shape
    assert damped.displacement([0.1], -0.5).shape == (1,)
    assert damped.displacement(0.5, -0.5) == pytest.approx(
        damped.displacement(x, -0.5)[1, 0], rel=1e-14
    )
    data = damped.to_dict()
    assert data["indentation"] == damped.indentation
    json.dumps(data)


BAD_POINTS: list[tuple[str, Any, Any]] = [
    ("surface_displacement", (math.nan,), "x"),
    ("surface_displacement", ([0.0, math.inf],), "x"),
    ("surface_displacement", ("a",), "x"),
    ("displacement", (math.nan, -0.5), "x"),
    ("displacement", (0.0, 0.5), "y"),
    ("displacement", (0.0, -1.5), "y"),
    ("displacement", (0.0, math.nan), "y"),
    ("displacement", (0.0, [0.0, -1.0]), "y"),
]


@pytest.mark.parametrize(("method", "args", "parameter"), BAD_POINTS)
def test_bad_points_get_the_undamped_errors(
    method: str, args: tuple[Any, ...], parameter: str
) -> None:
    undamped = mp.solve(vstar=0.2, kw=1.0, **PAPER)
    s = mp.solve(vstar=0.2, kw=1.0, damping=0.1, **PAPER)
    with pytest.raises(InvalidParameterError) as expected:
        getattr(undamped, method)(*args)
    with pytest.raises(InvalidParameterError) as got:
        getattr(s, method)(*args)
    assert got.value.parameter == expected.value.parameter == parameter
    assert str(got.value) == str(expected.value)
