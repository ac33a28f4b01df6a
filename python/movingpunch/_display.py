"""Numbers shown as what they are: the one rule of every summary the user
reads (the CLI's tables, a scene's summary, the terminal UI's summary).

A value whose magnitude is not above its error estimate, or, for a quantity
with no estimate, below ``ROUND_OFF`` times the quantity's scale, is shown
as 0: it is round-off (a drag of -2.1e-19 from two mirror-image punches, a
peak at x/h = 1e-16 on the axis), not a result. Data files (CSV, JSON,
``--json``, ``to_dict``) keep the raw numbers. docs/architecture.md states
the rule and the scale of each quantity.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

__all__ = ["ROUND_OFF", "drag_scale", "shown", "singular_note"]

ROUND_OFF = 1e-12
"""Below this fraction of its scale a value with no error estimate is
round-off (double precision sums of O(100) terms lose ~1e-14 of their size;
the solver's tightest tolerance is 1e-12)."""


def shown(value: float, *, estimate: float = 0.0, scale: float = 0.0) -> float:
    """``value`` as displayed: 0.0 when ``|value| <= estimate`` (a nonzero
    ``estimate``: the value is below its error estimate) or ``|value| <
    ROUND_OFF * scale``; else ``value`` itself. Non-finite values are kept
    (an infinite pressure at a flat punch's edge is a value)."""
    if not math.isfinite(value):
        return value
    size = abs(value)
    if (estimate > 0.0 and size <= estimate) or size < ROUND_OFF * abs(scale):
        return 0.0
    return value


def drag_scale(ends: Iterable[float], radius: float) -> float:
    """The scale of drag/P = (integral of p x/R dx)/P: the largest |x|/h the
    contact reaches over R/h (the steepest face slope a cylinder presents);
    1 for a punch with no radius (flat, table: a drag of order 1 at most)."""
    reach = max((abs(x) for x in ends if math.isfinite(x)), default=0.0)
    if math.isfinite(radius) and radius > 0.0 and reach > 0.0:
        return reach / radius
    return 1.0


def singular_note(xs: Sequence[float]) -> str:
    """The legend of a stress map's masked points, at the x/h ``xs`` where
    the stress is infinite (a flat punch's sharp edges): "masked: singular
    at x/h = ±0.5"."""
    if len(xs) == 2 and math.isclose(xs[0], -xs[1], rel_tol=1e-12, abs_tol=1e-12):
        where = f"±{abs(xs[1]):.4g}"
    else:
        where = ", ".join(f"{x:.4g}" for x in xs)
    return f"masked: singular at x/h = {where}"
