"""Shape and type contract of the public Python API (not the physics: see
test_anchors.py and test_layer.py)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import movingpunch as mp


@pytest.fixture(scope="module")
def paper() -> mp.Solution:
    return mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)


def test_public_names() -> None:
    for name in mp.__all__:
        assert hasattr(mp, name), name
    assert isinstance(mp.__version__, str)
    assert issubclass(mp.InvalidParameterError, ValueError)
    assert issubclass(mp.ConvergenceError, RuntimeError)
    assert issubclass(mp.UnphysicalContactError, mp.MovingPunchError)


def test_solution_fields(paper: mp.Solution) -> None:
    assert (paper.vstar, paper.kw, paper.radius, paper.load, paper.nu, paper.tol) == (
        0.2,
        1.0,
        100.0,
        0.002,
        0.2,
        1e-8,
    )
    assert paper.mu_over_load == pytest.approx(500.0)
    assert isinstance(paper.iterations, int)
    assert isinstance(paper.collocation_n, int)
    assert isinstance(paper.valid, bool)
    assert isinstance(paper.validity, str)
    assert paper.valid
    assert "_impl" not in repr(paper)
    assert paper.g_coefficients.ndim == 1


def test_pressure_shapes(paper: mp.Solution) -> None:
    p = paper.pressure(0.1)
    assert isinstance(p, float)
    assert paper.pressure(0) == pytest.approx(paper.p0)
    assert isinstance(paper.pressure(np.float64(0.1)), float)
    grid = np.linspace(-0.5, 0.5, 12).reshape(3, 4)
    values = paper.pressure(grid)
    assert values.shape == (3, 4)
    assert values.dtype == np.float64
    assert values[1, 1] == pytest.approx(paper.pressure(float(grid[1, 1])))
    assert paper.pressure([]).shape == (0,)
    assert paper.pressure(np.array(0.1)).shape == ()
    assert paper.pressure(2 * paper.a) == 0.0  # outside the contact
    # Non-contiguous and integer input.
    assert paper.pressure(grid[:, ::2]).shape == (3, 2)
    assert paper.pressure([0, 1]).shape == (2,)


def test_surface_displacement_shapes(paper: mp.Solution) -> None:
    v = paper.surface_displacement(0.0)
    assert isinstance(v, float)
    assert v == pytest.approx(-paper.indentation, rel=1e-6)
    assert paper.surface_displacement([[0.0, 0.5]]).shape == (1, 2)


def test_to_dict_is_json_safe(paper: mp.Solution) -> None:
    data = paper.to_dict()
    assert "_impl" not in data
    assert data["a"] == paper.a
    assert json.loads(json.dumps(data, allow_nan=False)) == data
    rigid = mp.solve(vstar=0.0, kw=math.inf, radius=100.0, load=0.002)
    assert rigid.to_dict()["kw"] == "inf"
    json.dumps(rigid.to_dict(), allow_nan=False)


def test_helpers_return_floats_and_arrays() -> None:
    assert isinstance(mp.critical_vstar(1.0), float)
    assert mp.critical_wavenumber(math.inf) == math.inf
    assert isinstance(mp.rayleigh_vstar(), float)
    m1, m2 = mp.layer_response(1.0, vstar=0.2, kw=1.0)
    assert isinstance(m1, float)
    assert isinstance(m2, float)
    a1, a2 = mp.layer_response([[0.5, 1.0, 2.0]], vstar=0.2, kw=1.0)
    assert a1.shape == a2.shape == (1, 3)
    assert a1[0, 1] == m1


def test_the_old_module_name_warns_and_still_works(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # movingpunch.damped was the asymmetric solver's module before it was
    # named by its role (issue 26): importing it warns and re-exports it.
    import importlib
    import sys

    from movingpunch.asymmetric import AsymmetricSolution, solve_asymmetric

    monkeypatch.delitem(sys.modules, "movingpunch.damped", raising=False)
    with pytest.warns(DeprecationWarning, match=r"movingpunch\.asymmetric"):
        damped = importlib.import_module("movingpunch.damped")
    assert damped.DampedSolution is AsymmetricSolution
    assert damped.solve_damped is solve_asymmetric
    assert mp.DampedSolution is mp.AsymmetricSolution
    assert "AsymmetricSolution" in mp.__all__
    assert "DampedSolution" not in mp.__all__
    s = damped.solve_damped(vstar=0.2, kw=1.0, radius=100.0, load=0.002, damping=0.1)
    assert isinstance(s, damped.DampedSolution)
    same = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, damping=0.1)
    assert (s.contact_interval, s.drag) == (same.contact_interval, same.drag)
