"""The damped solver's stresses near the surface (issue 13): ``stress_field``
and ``depth_stress`` for every -1 <= y <= 0, the surface layer y > -1e-3
included, each against an anchor computed independently of it:

- damping -> 0: the undamped solver's field evaluator (its own contact,
  pressure series, alpha quadrature and remainder), at y = 0 down to -1 and
  at points just inside and outside the contact ends and far away;
- continuity: sigma(x, y) - sigma(x, 0) is first order in y (a smooth limit,
  no jump at the surface), within |y| max|d sigma/dy|, where the gradient of
  the square-root cusps at the contact ends is (P/h)/sqrt(w d), d the
  distance to the nearer end; sigma_y -> -p and tau -> 0;
- equilibrium: the integral of sigma_y over x at a depth is minus the load
  (the layer moves steadily: the inertia term integrates to zero when the
  field decays, as it does subcritically with damping).

The interior at finite damping (0.1 and 1) is checked against a direct
Fourier sum without split in tests/cpp/test_asymmetric_stress_field.cpp, to
1e-10 of the peak pressure at depths from -1e-3 to -1.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.errors import InvalidParameterError

PAPER = {"radius": 100.0, "load": 0.002}
DEPTHS = [0.0, -1e-6, -1e-4, -1e-2, -0.5, -1.0]
COMPONENTS = ("sigma_x", "sigma_y", "tau_xy")


def _scale(field: Any) -> float:
    return max(float(np.abs(getattr(field, k)).max()) for k in COMPONENTS)


@pytest.mark.parametrize(("vstar", "kw"), [(0.2, 1.0), (0.65, 10.0)])
def test_vanishing_damping_gives_the_undamped_stress_field(
    vstar: float, kw: float
) -> None:
    """Damping 1e-12: the undamped stress field at every depth, the surface
    and 1e-6 below it included, to 1e-9 of max|sigma| (measured 1e-10 at
    y = 0, where the cusps at the ends meet the surface; 1e-13 deep down)."""
    u = mp.solve(vstar=vstar, kw=kw, **PAPER)
    d = mp.solve(vstar=vstar, kw=kw, damping=1e-12, **PAPER)
    a = u.a
    ends = a * np.array([1 - 1e-6, 1 - 1e-3, 1 + 1e-3, -1 + 1e-6, -1 + 1e-3, -1 - 1e-3])
    far = np.array([-100.0, -20.0, 20.0, 100.0])
    x = np.concatenate([np.linspace(-3.0, 3.0, 61), ends, far])
    fu = u.stress_field(x, DEPTHS)
    fd = d.stress_field(x, DEPTHS)
    scale = _scale(fu)
    for k in COMPONENTS:
        np.testing.assert_allclose(
            getattr(fd, k), getattr(fu, k), rtol=0.0, atol=1e-9 * scale, err_msg=k
        )
    ys = np.linspace(-1.0, 0.0, 21)
    np.testing.assert_allclose(
        d.depth_stress(ys), u.depth_stress(ys), rtol=0.0, atol=1e-9 * scale
    )


@pytest.mark.parametrize(
    ("vstar", "damping"), [(0.2, 1.0), (0.65, 0.1)], ids=["sub-1", "super-0.1"]
)
def test_stresses_tend_to_the_surface_values(vstar: float, damping: float) -> None:
    """sigma(x, y) -> (surface_stress, -p, 0) as y -> 0-: at y = -1e-8 within
    |y| * 10 (P/h)/sqrt(w d) (d the distance to the nearer contact end, w the
    half-width: the y-gradient of the square-root cusps; measured 3e-7 of
    max|sigma| at d = 0.01 w), and the difference is first order in y (it
    shrinks tenfold from y = -1e-8 to -1e-9: a limit, not a jump)."""
    s = mp.solve(vstar=vstar, kw=1.0, damping=damping, **PAPER)
    lo, hi = s.contact_interval
    c, w = s.centre, s.half_width
    r = np.concatenate(
        [np.linspace(-0.99, 0.99, 41), [-3.0, -1.5, -1.01, 1.01, 1.5, 3.0]]
    )
    x = c + w * r
    f = s.stress_field(x, [0.0, -1e-9, -1e-8])
    top = (
        np.asarray(s.surface_stress(x)),
        -np.asarray(s.pressure(x)),
        np.zeros_like(x),
    )
    for k, surface in zip(COMPONENTS, top, strict=True):
        assert np.array_equal(getattr(f, k)[0], surface), k
    scale = _scale(f)
    dist = np.minimum(np.abs(x - lo), np.abs(x - hi))
    bound = 1e-8 * 10.0 * scale / np.sqrt(w * dist)
    for k in COMPONENTS:
        values = getattr(f, k)
        near, nearer = np.abs(values[2] - values[0]), np.abs(values[1] - values[0])
        assert (near <= bound).all(), (k, float((near / bound).max()))
        big = nearer > 1e-12 * scale  # above round-off
        assert big.sum() > 30, k
        np.testing.assert_allclose(near[big] / nearer[big], 10.0, rtol=0.01, err_msg=k)


@pytest.mark.parametrize("damping", [0.1, 1.0])
def test_vertical_equilibrium_in_depth(damping: float) -> None:
    """The integral over x of sigma_y(x, y) is -1 (the load, in P/h times
    h) from y = -0.05 down to the base: the trapezoidal rule on a uniform
    0.01 h grid is spectrally accurate for these smooth, decaying
    (subcritical, damped) distributions. (Nearer the surface sigma_y keeps
    the square-root edges of -p over ~|y|, which a uniform rule resolves only
    to ~h^1.5: the surface is checked by continuity above.)"""
    s = mp.solve(vstar=0.2, kw=1.0, damping=damping, **PAPER)
    x = np.linspace(-30.0, 30.0, 6001)
    f = s.stress_field(x, [-0.05, -0.3, -1.0])
    assert np.abs(f.sigma_y[:, [0, -1]]).max() < 1e-12  # decayed at |x| = 30
    total = np.trapezoid(f.sigma_y, x, axis=1)
    np.testing.assert_allclose(total, -1.0, rtol=0.0, atol=1e-12)


def test_depth_stress_accepts_the_whole_layer() -> None:
    """depth_stress and stress_field take y in [-1, 0] as the undamped
    Solution does (the same error naming y outside), at any x; the surface
    is surface_stress exactly, the other depths the field's sigma_x."""
    s = mp.solve(vstar=0.65, kw=1.0, damping=0.1, **PAPER)
    u = mp.solve(vstar=0.2, kw=1.0, **PAPER)
    ys = np.array([0.0, -1e-12, -1e-6, -1e-4, -5e-4, -0.5, -1.0])
    for x in (0.0, s.centre, s.contact_interval[1] + 0.01):
        values = s.depth_stress(ys, x=x)
        assert values[0] == s.surface_stress(x)
        np.testing.assert_array_equal(values, s.stress_field([x], ys).sigma_x[:, 0])
    assert isinstance(s.depth_stress(-1e-5), float)
    for bad in (1e-4, -1.0 - 1e-9, float("nan")):
        for sol in (s, u):
            with pytest.raises(InvalidParameterError, match="y must") as e:
                sol.depth_stress(bad)
            assert e.value.parameter == "y"
            with pytest.raises(InvalidParameterError, match="y must"):
                sol.stress_field([0.0], [bad])


def test_a_depth_evaluated_again_gives_the_same_stresses() -> None:
    """The remainder's Filon coefficients of the last few depths are kept
    (a search along the bottom computes them once): values from the kept
    coefficients equal a fresh solution's, bit for bit, whatever the order
    of the depths and after more depths than are kept."""
    args = {"vstar": 0.65, "kw": 1.0, "radius": 100.0, "load": 0.002, "damping": 0.1}
    x = np.linspace(-3.0, 3.0, 13)
    depths = [-1.0, -0.5, -1e-4, -0.25, -0.75, -0.1, -1.0]
    s = mp.solve(**args)
    seen = [s.stress_field(x, [y]).sigma_x[0] for y in depths]
    for y, values in zip(depths, seen, strict=True):
        fresh = mp.solve(**args)
        np.testing.assert_array_equal(values, fresh.stress_field(x, [y]).sigma_x[0])
        np.testing.assert_array_equal(values, s.stress_field(x, [y]).sigma_x[0])
