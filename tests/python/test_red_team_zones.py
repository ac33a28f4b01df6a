"""Red-team findings 7-10 of issue 25 (trains far apart, far from x = 0, an
asymmetric table, false refusals of the contact-set search), each right or
refused clearly, checked independently of the solver's own checks:

- p >= 0 on every zone (a grid of the zone's pressure);
- int p dx = P per punch (the trapezoid rule in theta, not the solver's
  Gauss-Chebyshev sums);
- the surface follows each punch on its zones and clears it beside them
  (the gap f_k - delta_k - v from the Fourier (Filon) surface displacement,
  not the solver's spectral gap integral);
- a shifted train is the unshifted solution moved (translation invariance)
  and punches too far apart to interact are each the punch alone.
"""

from __future__ import annotations

import math
import subprocess
import sys
import time

import numpy as np
import pytest

import movingpunch as mp

R = 100.0
LOAD = 0.002


def _zone_integral(p: mp.PunchResult, left: float, right: float, m: int = 400) -> float:
    """int p_k dx over one zone of punch k, per its load (the trapezoid rule
    in theta: x = c + w cos(theta) makes w sin(theta) p smooth, periodic)."""
    c, w = 0.5 * (left + right), 0.5 * (right - left)
    th = (np.arange(m) + 0.5) * math.pi / m
    x = c + w * np.cos(th)
    return float(np.sum(np.asarray(p.pressure(x)) * w * np.sin(th)) * math.pi / m)


def check_independently(s: mp.ZonedSolution, *, gap_tol: float = 1e-7) -> None:
    """p >= 0, int p = P per punch, the surface on each punch over its zones
    and clear of it beside them (2 contact widths each side)."""
    for k, p in enumerate(s.punches):
        total = 0.0
        hull_lo, hull_hi = p.contact_zones[0][0], p.contact_zones[-1][1]
        width = hull_hi - hull_lo
        scale = max(abs(p.indentation), width**2 / 8.0 / R)
        for lo, hi in p.contact_zones:
            assert hi > lo
            x = np.linspace(lo, hi, 401)
            assert np.min(p.pressure(x)) >= -1e-10, (k, lo, hi)
            total += _zone_integral(p, lo, hi)
            inner = lo + (hi - lo) * np.linspace(0.05, 0.95, 7)
            gap = (
                np.asarray(p.profile.height(inner - p.at))
                - p.indentation
                - np.asarray(s.surface_displacement(inner))
            )
            assert np.max(np.abs(gap)) < gap_tol * scale, (k, gap)
        assert abs(total - 1.0) < 1e-9, (k, total)
        # Beside the zones (and between them): no penetration.
        x = np.linspace(hull_lo - 2.0 * width, hull_hi + 2.0 * width, 801)
        outside = np.ones_like(x, dtype=bool)
        for lo, hi in p.contact_zones:
            outside &= (x < lo) | (x > hi)
        x = x[outside]
        if isinstance(p.profile, mp.Profile):
            keep = (x - p.at >= p.profile.x[0]) & (x - p.at <= p.profile.x[-1])
            x = x[keep]
        gap = (
            np.asarray(p.profile.height(x - p.at))
            - p.indentation
            - np.asarray(s.surface_displacement(x))
        )
        assert np.min(gap) > -gap_tol * scale, (k, float(np.min(gap)))
