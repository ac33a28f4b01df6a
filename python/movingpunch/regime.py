"""Plausibility hints: where a result, however accurate, leaves the regime the
model is built for.

The model is linear elasticity with small strains, a punch that touches the
layer over a contact comparable with its thickness, and a steady state that
only exists below the critical speed. A solution can meet its tolerance and
still describe nothing physical: P/(μh) = 50 on R/h = 100 gives δ/h 2.4 and
a/h 21.6. These hints say so, one short clause each; they never block a
result (the numbers are the model's, correct to their error estimate).

Pure Python: ``regime_hints`` takes numbers (the terminal UI's summary);
``hints_for`` reads a solution of the result contract (the CLI).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING

from movingpunch.errors import InvalidParameterError

if TYPE_CHECKING:
    from movingpunch.contract import ContactSolution, SolvedPunch
    from movingpunch.fields import StressPeaks

__all__ = [
    "NEAR_CRITICAL",
    "SMALL_STRAIN",
    "WIDE_CONTACT",
    "given_indentation",
    "half_length",
    "hints_for",
    "regime_hints",
]

SMALL_STRAIN = 0.05
"""δ/h and the peak strain |σ|/μ above which small-strain theory is doubtful."""

WIDE_CONTACT = 5.0
"""a/h (the contact's half-length over h) above which the contact is far wider
than the layer is thick: outside the paper's range."""

NEAR_CRITICAL = 0.01
"""A speed within this fraction of its limit (V*_cr without damping, V*_R
with damping) is hypersensitive: small changes of V* change the result a lot."""


def regime_hints(
    *,
    indentation: float,
    half_length: float,
    peak_strain: float,
    vstar: float,
    critical_vstar: float,
    rayleigh_vstar: float = math.nan,
    damped: bool = False,
) -> tuple[str, ...]:
    """The hints for one result, each a short clause (empty: plausible).

    ``indentation``: δ/h (the largest of a train's punches); ``half_length``:
    half the contact's extent over h (a/h of a symmetric contact);
    ``peak_strain``: the largest |stress|/μ (a stress over P/h times
    P/(μh)); ``critical_vstar`` and ``rayleigh_vstar``: the limits of V*.
    Non-finite inputs give no hint (nothing to judge).
    """
    out: list[str] = []
    if math.isfinite(indentation) and abs(indentation) > SMALL_STRAIN:
        out.append(f"δ/h {_g(abs(indentation))} > {SMALL_STRAIN:g}")
    if math.isfinite(half_length) and half_length > WIDE_CONTACT:
        out.append(f"a/h {_g(half_length)} > {WIDE_CONTACT:g}")
    if math.isfinite(peak_strain) and peak_strain > SMALL_STRAIN:
        out.append(f"strain |σ|/μ {_g(peak_strain)} > {SMALL_STRAIN:g}")
    small_strain = bool(out)
    if small_strain:
        out[-1] += ": beyond small-strain linear theory"
    limit, name = (rayleigh_vstar, "V*_R") if damped else (critical_vstar, "V*_cr")
    if (
        math.isfinite(limit)
        and limit > 0
        and math.isfinite(vstar)
        and (1.0 - NEAR_CRITICAL) * limit <= vstar < limit
    ):
        gap = 100.0 * (1.0 - vstar / limit)
        out.append(
            f"V* within {gap:.2g} % of {name}: the result is very sensitive to V*"
        )
    return tuple(out)


def given_indentation(solved: ContactSolution | SolvedPunch) -> float:
    """The indentation delta/h of a solution or one of its punches; NaN
    where the medium does not give it (the asymmetric solver with friction
    under a half-space: a logarithmic far field, refused there by name).
    What every display shows as n/a."""
    try:
        return float(solved.indentation)
    except InvalidParameterError:
        return math.nan


def hints_for(
    solution: ContactSolution, peaks: StressPeaks | None = None
) -> tuple[str, ...]:
    """The hints for a solution of the result contract: its indentation (a
    train's largest), contact, speed limits and, with ``peaks`` (its
    ``stress_peaks()``, which the caller has usually computed), the peak
    strain. Reads only the contract's fields."""
    punches = solution.punches  # a single contact's one, a train's own
    given = [abs(v) for v in map(given_indentation, punches) if math.isfinite(v)]
    indent = max(given) if given else math.nan
    stresses = [abs(float(solution.p0))]
    if peaks is not None:
        stresses += [
            abs(float(peaks.top_compressive)),
            abs(float(peaks.top_tensile)),
            abs(float(peaks.bottom_tensile)),
        ]
    finite = [v for v in stresses if math.isfinite(v)]
    strain = max(finite) * float(solution.load) if finite else math.nan
    # Each punch's own contact, not the train's hull.
    half = max(half_length(p.contact_zones) for p in punches)
    return regime_hints(
        indentation=indent,
        half_length=half,
        peak_strain=strain,
        vstar=float(solution.vstar),
        critical_vstar=float(solution.critical_vstar),
        rayleigh_vstar=float(solution.rayleigh_vstar),
        damped=float(solution.damping) > 0,
    )


def half_length(zones: Iterable[tuple[float, float]]) -> float:
    """Half the extent over h of a punch's contact zones (a/h of one
    symmetric zone; NaN for none)."""
    ends = [float(e) for zone in zones for e in zone]
    return 0.5 * (max(ends) - min(ends)) if ends else math.nan


def _g(value: float) -> str:
    return f"{value:.3g}"
