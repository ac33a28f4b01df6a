"""The benchmarks' yardstick solves the paper's problem.

benchmarks/baseline_numpy.py is a plain NumPy implementation of the paper's
method, written separately from the C++ core (its own 4 x 4 layer system, its
own quadrature of the kernel, no table). It is the second, independent solver
the cylinder's a/h is checked against here, and the benchmarks' ratios are
only meaningful if it computes the same thing.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

import movingpunch as mp

BASELINE = Path(__file__).resolve().parents[2] / "benchmarks" / "baseline_numpy.py"


def _baseline() -> ModuleType:
    spec = importlib.util.spec_from_file_location("baseline_numpy", BASELINE)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["baseline_numpy"] = module
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize(
    ("nu", "vstar", "kw", "radius", "mu_over_p"),
    [
        (0.2, 0.001, 1.0, 100.0, 500.0),  # near the static limit
        (0.2, 0.2, 1.0, 100.0, 500.0),  # the paper's Fig. 4 case
        (0.2, 0.2, 0.1, 100.0, 500.0),  # a soft foundation
        (0.3, 0.5, 1.0, 50.0, 200.0),
    ],
)
def test_baseline_and_movingpunch_agree_on_the_contact_width(
    nu: float, vstar: float, kw: float, radius: float, mu_over_p: float
) -> None:
    base = _baseline()
    a = base.solve(nu, vstar, kw, radius, mu_over_p)
    s = mp.solve(
        vstar=vstar, kw=kw, nu=nu, radius=radius, load=1.0 / mu_over_p, tol=1e-12
    )
    assert s.valid
    # Measured: 1e-16 to 7e-14 apart (the baseline's composite quadrature and
    # N = 24 are at round-off on these smooth cases).
    assert abs(a - s.a) <= 1e-11 * s.a


def test_baseline_layer_response_has_the_documented_limits() -> None:
    base = _baseline()
    # M1 -> phi1, the moving half-plane factor, at large alpha h.
    assert base.surface_response(0.2, 0.2, 1.0, np.array([60.0]))[0] == pytest.approx(
        mp.phi1(0.2, 0.2), rel=1e-12
    )
    # Near-static, rigid base: M1 = (1 - nu)(cosh 2t - 1)/(sinh 2t + 2t), t = alpha h
    # (the exponential basis loses about log10(1/V*) digits near V* = 0).
    t = np.array([0.3, 1.0, 2.0])
    exact = 0.7 * (np.cosh(2 * t) - 1) / (np.sinh(2 * t) + 2 * t)
    assert base.surface_response(0.3, 1e-8, 1e12, t) == pytest.approx(exact, rel=1e-6)
