"""The gap beside a contact, checked independently of the solver's own check.

Near V*_cr on a stiff foundation the layer's surface carries waves shorter
than the contact: a check sampling the gap at a few dozen points missed a
dip of -7 h and a fuzz case came back "valid" while the punch penetrated
the layer (issue 25). Here every valid result's surface displacement is
evaluated on a very fine grid (20 000 points over the zones' hull and 10 h
beyond it on both sides: far finer than the surface's shortest wave) and the
gap f(x) - delta - v(x) beside the zones must be >= 0 up to the solution's
own scale of error; an invalid result must say why. Anchor: the geometry of
the cylinder (f = x^2/(2R)) and the returned surface, nothing of the check.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import movingpunch as mp

# The fuzz case (contact "auto"): the single contact penetrates (gap -9.8 h);
# the zone search returned the same half-width as one "separated" zone,
# valid with min_gap +0.012 while the surface rose 7 h above the punch at
# x/h = 1.25, at 1 - 1.4e-6 of V*_cr. Its neighbours: stiff kw, kp 1-3.
CASES = [
    {
        "vstar": 0.9077755690130134,
        "kw": 188.23511456244728,
        "kp": 1.8485252956901026,
        "nu": 0.4796286698932096,
        "radius": 0.006658417914496064,
        "load": 77.02450703705429,
    },
    # Found by sampling 1 - V*/V*_cr in 1e-6.5..1e-4, kw 1e2..1e3, kp 1..3:
    # valid on the old check with the surface 4.3 h above the punch at 1.25.
    {
        "vstar": 0.9078647450863184,
        "kw": 154.1,
        "kp": 1.11,
        "nu": 0.48,
        "radius": 0.0067,
        "load": 77.0,
    },
    # Valid single contacts whose gap dips close to 0 (fine-grid minimum
    # +0.005 h at x/h = 1.02) and a stiffer one.
    {
        "vstar": 0.907847113572762,
        "kw": 123.6,
        "kp": 2.2,
        "nu": 0.48,
        "radius": 0.0067,
        "load": 77.0,
    },
    {
        "vstar": 0.9078631617782578,
        "kw": 706.7,
        "kp": 2.29,
        "nu": 0.48,
        "radius": 0.0067,
        "load": 77.0,
    },
]


def _fine_gap(s: Any) -> tuple[float, float, float]:
    """The smallest gap beside the zones on 20 000 points over +-(hull + 10 h),
    where, and the smallest of its dips (local minima off the zones' ends:
    beside an end the gap rises from 0; inf without a dip)."""
    zones = list(s.contact_zones)
    lo = min(z[0] for z in zones)
    hi = max(z[1] for z in zones)
    x = np.linspace(lo - 10.0, hi + 10.0, 20_000)
    inside = np.zeros(x.shape, dtype=bool)
    for left, right in zones:
        inside |= (x >= left) & (x <= right)
    v = np.asarray(s.surface_displacement(x), dtype=float)
    gap = x**2 / (2.0 * s.radius) - s.indentation - v
    gap[inside] = np.inf
    i = int(np.argmin(gap))
    mid = gap[1:-1]
    dips = np.isfinite(mid) & (mid < gap[:-2]) & (mid < gap[2:])
    dips &= np.isfinite(gap[:-2]) & np.isfinite(gap[2:])
    dip = float(mid[dips].min()) if dips.any() else float("inf")
    return float(gap[i]), float(x[i]), dip


@pytest.mark.parametrize(
    "case", CASES, ids=lambda c: f"kw{c['kw']:.4g}-kp{c['kp']:.3g}"
)
def test_valid_means_no_penetration_on_a_fine_grid(case: dict[str, float]) -> None:
    refusal = ""
    try:
        s = mp.solve(**case)
    except mp.UnphysicalContactError as exc:
        refusal = str(exc)
    if refusal:
        # A clear refusal: it names the penetration it found.
        assert "penetrat" in refusal
        return
    assert s.valid
    gap, x, dip = _fine_gap(s)
    # The gap's scale: the indentation (36 h here); a penetration of 1e-4 of
    # it is far beyond any error estimate of the solution.
    scale = max(
        abs(s.indentation), max(z[1] - z[0] for z in s.contact_zones) ** 2 / s.radius
    )
    assert gap >= -1e-4 * scale, (
        f"valid ({s.validity}) but the surface rises {-gap:.4g} h "
        f"above the punch at x/h = {x:.6g}"
    )
    # The solver's own minimum sees every dip of the fine grid's.
    assert s.min_gap <= dip + 1e-4 * scale, (
        f"the solver's min_gap {s.min_gap:.4g} h misses the fine grid's dip {dip:.4g} h"
    )


# A graded top (gamma h 2) near its critical speed on soft and stiff springs:
# its gap scan samples at the band of the displacement less the kernel's
# subtracted gamma/alpha series (that part is smooth beside the contact; the
# scan clusters its points at the contact's end), 14 times coarser than the
# whole displacement's band. The fine grid must agree.
GRADED = [
    {"kw": kw, "frac": frac, "radius": radius}
    for kw in (30.0, 150.0)
    for frac, radius in ((0.9, 1.0), (0.99, 0.2))
]


@pytest.mark.parametrize(
    "case", GRADED, ids=lambda c: f"kw{c['kw']:g}-{c['frac']:g}vcr-R{c['radius']:g}"
)
def test_graded_top_valid_means_no_penetration_on_a_fine_grid(
    case: dict[str, float],
) -> None:
    medium: dict[str, Any] = {
        "layers": [mp.GradedLayer(2.0, thickness=1.0)],
        "base": mp.Winkler(case["kw"]),
    }
    vstar = case["frac"] * mp.critical_vstar(**medium)
    s = mp.solve(vstar=vstar, radius=case["radius"], load=0.5, **medium)
    assert s.valid
    gap, x, dip = _fine_gap(s)
    scale = max(abs(s.indentation), s.a**2 / s.radius)
    assert gap >= -1e-6 * scale, (
        f"the surface rises {-gap:.4g} h above the punch at {x:.6g}"
    )
    assert s.min_gap <= dip + 1e-6 * scale
    # Beside the contact the gap opens: the solver's minimum is that of the
    # fine grid off the contact's end (within the grid's step there).
    assert s.min_gap >= -1e-6 * scale
