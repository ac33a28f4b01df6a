"""Trains of rounded flats (cpp/src/zones.cpp; docs/theory.md sections 13 and
15.2): the slope's kinks at the faces' ends are collocated by their
projection, each zone's series carries the half-plane tail, and the gap
beside a zone sums that whole tail in closed form. Against independent
anchors:

- limits: punches far apart are single rounded flats (``mp.solve``, the
  single contact's own solver; one rounded flat moved off the axis is the
  single one moved: test_zones.py);
- symmetry: an undamped train placed symmetrically gives mirror-image
  zones, and its total drag is zero (no power is dissipated);
- energy: a damped train's drag (the slope's closed-form moments) equals the
  dissipation (Parseval on the bottom face);
- complementarity and equilibrium on fine grids from the Fourier (Filon)
  surface displacement and an independent quadrature of the pressure;
- convergence: the ends at a small N agree with a large N to the tolerance
  (the kinks made them converge like N^-1.5 before), and the error
  estimate bounds a coarse solve's error.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import movingpunch as mp

B, RC, LOAD = 0.3, 100.0, 0.002
FLAT = mp.RoundedFlat(B, RC)


def _train(count: int, spacing: float, **layer: float) -> mp.ZonedSolution:
    punches = [
        mp.Punch(FLAT, LOAD, at=spacing * (i - (count - 1) / 2)) for i in range(count)
    ]
    s = mp.solve_punches(punches, **layer)
    assert isinstance(s, mp.ZonedSolution)
    return s


@pytest.fixture(scope="module")
def eight() -> mp.ZonedSolution:
    """Issue 27's train: 8 rounded flats 0.3/100, 3 h apart, kw 1, V* 0.2."""
    return _train(8, 3.0, vstar=0.2, kw=1.0)


def _zone_integral(s: mp.ZonedSolution, left: float, right: float) -> float:
    # The midpoint rule in theta is exact for the series' 4096 terms.
    m = 8192
    c, w = 0.5 * (left + right), 0.5 * (right - left)
    th = (np.arange(m) + 0.5) * math.pi / m
    p = np.asarray(s.pressure(c + w * np.cos(th)))
    return float(np.sum(p * w * np.sin(th)) * math.pi / m)


def test_eight_rounded_flats_converge_without_a_warning(
    eight: mp.ZonedSolution,
) -> None:
    s = eight
    assert s.warnings == ()
    assert s.valid
    assert len(s.contact_zones) == 8
    assert s.error_estimate < 1e-8 * max(hi - lo for lo, hi in s.contact_zones)
    # Every zone reaches past its face (a > b for a rounded flat).
    for p in s.punches:
        ((lo, hi),) = p.contact_zones
        assert lo < p.at - B
        assert hi > p.at + B
    # Mirror images (undamped: the layer's response is even): zone j and
    # zone 7 - j, and no power dissipated in all.
    zones = np.array(s.contact_zones)
    assert np.max(np.abs(zones + zones[::-1, ::-1])) < 1e-10
    assert abs(s.drag) < 1e-12


def test_eight_rounded_flats_meet_complementarity_and_equilibrium(
    eight: mp.ZonedSolution,
) -> None:
    # Checked from the Fourier surface displacement (not the solver's own
    # integration of v') and an independent quadrature of the pressure.
    s = eight
    total = 0.0
    for p in s.punches:
        ((lo, hi),) = p.contact_zones
        x = np.linspace(lo, hi, 401)
        assert np.min(s.pressure(x)) >= -1e-10
        inner = lo + (hi - lo) * np.linspace(0.02, 0.98, 25)
        gap = (
            np.asarray(p.profile.height(inner - p.at))
            - p.indentation
            - np.asarray(s.surface_displacement(inner))
        )
        assert np.max(np.abs(gap)) < 1e-8 * abs(p.indentation)
        # Beside the zone, out to the next one: no penetration.
        beside = (np.linspace(hi, hi + 1.0, 61)[1:], np.linspace(lo - 1.0, lo, 61)[:-1])
        for side in beside:
            gap = (
                np.asarray(p.profile.height(side - p.at))
                - p.indentation
                - np.asarray(s.surface_displacement(side))
            )
            assert np.min(gap) > -1e-9 * abs(p.indentation)
        total += _zone_integral(s, lo, hi)
    assert abs(total - 1.0) < 1e-9


def test_the_reported_max_pressure_is_the_pressures_largest_value(
    eight: mp.ZonedSolution,
) -> None:
    s = eight
    dense = max(
        float(np.max(s.pressure(np.linspace(lo, hi, 20001))))
        for lo, hi in s.contact_zones
    )
    assert dense <= s.max_pressure * (1 + 1e-12)
    assert s.max_pressure <= dense * (1 + 1e-6)


def test_far_apart_rounded_flats_are_single_rounded_flats() -> None:
    single = mp.solve(vstar=0.3, kw=10.0, profile=FLAT, load=LOAD, tol=1e-12)
    train = _train(2, 100.0, vstar=0.3, kw=10.0, tol=1e-12)
    assert train.warnings == ()
    for (lo, hi), at in zip(train.contact_zones, (-50.0, 50.0), strict=True):
        assert abs(lo - at + single.a) < 1e-9
        assert abs(hi - at - single.a) < 1e-9
    for p in train.punches:
        assert abs(p.indentation - single.indentation) < 1e-9 * single.indentation
        x = np.linspace(-0.995, 0.995, 41) * single.a
        # Both series carry the half-plane tail to 4096 terms; the heads
        # agree to the tolerance.
        assert np.allclose(p.pressure(x + p.at), single.pressure(x), atol=1e-8, rtol=0)


def test_rounded_flat_trains_converge_fast_and_the_estimate_bounds_the_error() -> None:
    layer = {"vstar": 0.4, "kw": 1.0}
    ref = _train(2, 1.6, tol=1e-12, **layer)
    ends = np.array(ref.contact_zones)
    # At N = 24 per zone the ends are already at the reference's accuracy
    # (a pointwise collocation of the kinked slope was 1e-5 off at N = 256).
    for n in (12, 24):
        coarse = _train(2, 1.6, n=n, **layer)
        err = float(np.max(np.abs(np.array(coarse.contact_zones) - ends)))
        assert err <= coarse.error_estimate + ref.error_estimate, (n, err)
        if n == 24:
            assert err < 1e-9


def test_damped_rounded_flat_trains_balance_energy() -> None:
    s = _train(3, 2.5, vstar=0.2, kw=1.0, damping=0.3)
    assert s.warnings == ()
    assert s.drag > 0
    assert abs(s.dissipation - s.drag) < 1e-6 * s.drag


def test_sharp_corners_in_a_train_warn_as_the_single_punch_does() -> None:
    # Corners much sharper than the contact: the 4096-term series resolves
    # the kinks only coarsely. Far apart, each punch is the single one, and
    # both say so with about the same share of p at the contact's centre
    # (the train's bound is rigorous, the single contact's extrapolated:
    # within a factor 2).
    sharp = mp.RoundedFlat(0.5, 1e-3)
    single = mp.solve(vstar=0.2, kw=10.0, profile=sharp, load=LOAD)
    punches = [mp.Punch(sharp, LOAD, at=-50.0), mp.Punch(sharp, LOAD, at=50.0)]
    train = mp.solve_punches(punches, vstar=0.2, kw=10.0)
    (one,) = [w for w in single.warnings if "kinks" in w]
    # (Too far apart to interact: each punch is solved alone and warns,
    # naming itself.)
    kinks = [w for w in train.warnings if "kinks" in w]
    assert [w.split(":")[0] for w in kinks] == ["punches 0", "punches 1"]

    def share(text: str) -> float:
        return float(text.split("series_truncation; ")[1].split(" of p")[0])

    for two in kinks:
        assert "rounded flat punch" in two
        assert 0.5 < share(two) / share(one) < 2.0
