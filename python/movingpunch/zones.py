"""Several contact zones: a separated contact under one punch, and trains of
rigid punches moving together (docs/theory.md section 15).

When the single contact is unphysical (p < 0 inside it near the critical
speed, or the punch would penetrate beside it), :func:`movingpunch.solve`
(``contact="auto"``, the default) finds the real contact set: a union of
intervals with p >= 0 on each, no penetration beside them and p bounded at
every end. :func:`solve_punches` solves several punches moving together at
one speed, each with its own load. Both return a :class:`ZonedSolution`,
which satisfies ``movingpunch.ContactSolution`` like every result: its
fields and evaluations are the superposed response of all zones.

The contact set is found by an active-set search that cannot cycle: start
from the single-contact solution (from each punch's own solution for a
train), solve that topology's end conditions (``_core.solve_zones``:
Newton's method on the zone ends), then check complementarity (p >= 0 on
every zone, gap >= 0 beside them) and change the topology where it fails:
split a zone where p < 0 inside it, shrink it where p < 0 at its end, merge
two zones of one punch where the gap between them closes, add a zone where
the punch penetrates away from its contact. No topology is tried twice.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, overload

import numpy as np
import numpy.typing as npt

from movingpunch import _core, params
from movingpunch._evaluate import _pointwise
from movingpunch._evaluations import ResultFields
from movingpunch.contract import ContactSolution, Points
from movingpunch.errors import (
    ConvergenceError,
    InvalidParameterError,
    UnphysicalContactError,
)
from movingpunch.fields import FloatArray
from movingpunch.media import HalfSpace, Medium
from movingpunch.profiles import Cylinder, Flat, PunchProfile, check_profile
from movingpunch.regime import given_indentation

__all__ = [
    "CONTACT_MODES",
    "Punch",
    "PunchResult",
    "ZonedSolution",
    "check_contact",
    "find_contact_set",
    "separate",
    "single_punch",
    "solve_train",
]

CONTACT_MODES = ("auto", "single")
"""``contact=`` of :func:`movingpunch.solve`: "auto" finds the contact set
(several zones when the single contact is unphysical), "single" keeps the
single contact and refuses an unphysical one."""

_MAX_TOPOLOGIES = 12
"""Contact sets the search tries before it gives up (it never revisits one)."""


def check_contact(value: object) -> str:
    """``value`` as a contact mode ("auto" or "single"), else
    InvalidParameterError naming ``contact``."""
    if isinstance(value, str) and value in CONTACT_MODES:
        return value
    raise InvalidParameterError(
        f'contact must be "auto" or "single", got {value!r}',
        parameter="contact",
        allowed='"auto" or "single"',
    )


@dataclass(frozen=True)
class Punch:
    """One punch of a train: its shape (a profile, or a number: the radius
    R/h of a cylinder), its load P/(mu h) and the position ``at`` (x/h) of
    its axis in the moving frame (the train moves towards +x)."""

    profile: PunchProfile
    load: float
    at: float = 0.0

    def __init__(
        self, profile: PunchProfile | float, load: float, at: float = 0.0
    ) -> None:
        shape = (
            Cylinder(params.check("radius", profile))
            if isinstance(profile, (int, float)) and not isinstance(profile, bool)
            else check_profile(profile)
        )
        if isinstance(shape, Flat):
            raise InvalidParameterError(
                "profile: a flat punch cannot be part of a train or separate "
                "(its contact is its face); use a RoundedFlat",
                parameter="profile",
                allowed="Cylinder, RoundedFlat or Profile",
            )
        object.__setattr__(self, "profile", shape)
        object.__setattr__(self, "load", params.check("load", load))
        if (
            isinstance(at, bool)
            or not isinstance(at, (int, float))
            or not math.isfinite(at)
        ):
            raise InvalidParameterError(
                f"at (the punch's position x/h) must be a finite number, got {at!r}",
                parameter="at",
                allowed="a finite number",
            )
        object.__setattr__(self, "at", float(at))

    def to_dict(self) -> dict[str, object]:
        """The scene-file form (a ``[[punches]]`` table)."""
        return {"profile": self.profile.to_dict(), "load": self.load, "at": self.at}

    def _core(self) -> tuple[str, float, float, list[float], list[float], float, float]:
        a = self.profile.core_args()
        return (
            a["profile"],
            a["radius"],
            a["half_width"],
            a["table_x"],
            a["table_y"],
            self.load,
            self.at,
        )


class _Zones:
    """The zones of a solve and, built on first use (about a millisecond
    each: their Fourier nodes), each as a compiled solution of its own load,
    relative to its punch's axis (``origins``: evaluated at x - origin, so
    that a train far from x = 0 keeps its digits)."""

    def __init__(
        self, core_zones: Sequence[Any], punches: Sequence[Punch], anchored: bool
    ) -> None:
        self.core = tuple(core_zones)
        self.origins = tuple(float(punches[int(z.punch)].at) for z in self.core)
        self.anchored = anchored
        """Under a half-space every zone's displacement is measured from the
        surface at x = DISPLACEMENT_REFERENCE of its own frame (x - origin):
        the sum takes each zone's value at the common point off instead."""
        self._solutions: tuple[Any, ...] | None = None

    @property
    def solutions(self) -> tuple[Any, ...]:
        if self._solutions is None:
            self._solutions = tuple(z.solution for z in self.core)
        return self._solutions


class _ZoneSum:
    """The superposed response of some zones (each compiled zone weighted
    by its share of the load ``total``): what the shared evaluations
    (``movingpunch._evaluations``) call ``_impl``."""

    def __init__(self, zones: _Zones, indices: Sequence[int], total: float) -> None:
        self._all = zones
        self._indices = tuple(indices)
        self.weights = tuple(float(zones.core[i].load) / total for i in self._indices)
        self.origins = tuple(zones.origins[i] for i in self._indices)

    @property
    def zones(self) -> tuple[Any, ...]:
        built = self._all.solutions
        return tuple(built[i] for i in self._indices)

    def _sum(
        self, f: Callable[[Any, FloatArray], Any], x: FloatArray, weighted: bool = True
    ) -> Any:
        out = None
        xs = np.asarray(x, dtype=np.float64)
        for z, w, o in zip(self.zones, self.weights, self.origins, strict=True):
            v = np.asarray(f(z, xs - o), dtype=np.float64) * (w if weighted else 1.0)
            out = v if out is None else out + v
        return out

    def pressure(self, x: FloatArray) -> FloatArray:
        return self._sum(lambda z, u: z.pressure(u), x)  # type: ignore[no-any-return]

    def surface_stress(self, x: FloatArray) -> FloatArray:
        return self._sum(lambda z, u: z.surface_stress(u), x)  # type: ignore[no-any-return]

    def surface_slope(self, x: FloatArray) -> FloatArray:
        return self._sum(lambda z, u: z.surface_slope(u), x, weighted=False)  # type: ignore[no-any-return]

    @functools.cached_property
    def _reference(self) -> float:
        """What the zones' own references leave in the sum under a
        half-space: each zone's surface displacement at the common reference
        point x = DISPLACEMENT_REFERENCE (in its frame; 0 on springs). Once
        per sum (every displacement and indentation reads it)."""
        if not self._all.anchored:
            return 0.0
        at = _core.DISPLACEMENT_REFERENCE
        return float(
            sum(
                z.surface_displacement(np.array([at - o]))[0]
                for z, o in zip(self.zones, self.origins, strict=True)
            )
        )

    def surface_displacement(self, x: FloatArray) -> FloatArray:
        v: FloatArray = self._sum(
            lambda z, u: z.surface_displacement(u), x, weighted=False
        )
        return v - self._reference

    def bottom_slope(self, x: FloatArray) -> FloatArray:
        return self._sum(lambda z, u: z.bottom_slope(u), x, weighted=False)  # type: ignore[no-any-return]

    def bottom_displacement(self, x: FloatArray) -> FloatArray:
        return self._sum(  # type: ignore[no-any-return]
            lambda z, u: z.bottom_displacement(u), x, weighted=False
        )

    def displacement(self, x: FloatArray, y: FloatArray) -> FloatArray:
        v: FloatArray = self._sum(lambda z, u: z.displacement(u, y), x, weighted=False)
        return v - self._reference

    def stress_field(
        self, x: FloatArray, y: FloatArray, below: bool = False
    ) -> tuple[FloatArray, ...]:
        xs = np.asarray(x, dtype=np.float64)
        parts = [
            z.stress_field(xs - o, y, below)
            for z, o in zip(self.zones, self.origins, strict=True)
        ]
        return tuple(
            sum(
                (
                    w * np.asarray(p[i], dtype=np.float64)
                    for p, w in zip(parts, self.weights, strict=True)
                ),
                np.zeros((len(y), len(x))),
            )
            for i in range(3)
        )


@dataclass(frozen=True)
class PunchResult:
    """One punch of a solution (``ContactSolution.punches``): its contact
    zones, load share of each, indentation and drag. A single contact's one
    punch is this too (``single_punch``): at x = 0, one zone with the whole
    load, the solution's own indentation and drag."""

    profile: PunchProfile
    load: float
    """P_k/(mu h)."""
    at: float
    """x/h of its axis."""
    contact_zones: tuple[tuple[float, float], ...]
    """Its zones (x_left, x_right)/h from left to right."""
    zone_loads: tuple[float, ...]
    """The load each zone carries, P_zone/(mu h) (they sum to ``load``)."""
    drag: float
    """Horizontal force of the normal pressure on it over P_k, int p f_k' dx
    / P_k (positive: opposes the motion towards +x)."""
    _impl: Any = field(repr=False, compare=False)
    """Its own pressure (``pressure(x)`` over P_k/h): a ``_ZoneSum`` of its
    zones, or a single contact's compiled result."""
    _indentation: Callable[[], float] = field(repr=False, compare=False)
    """Computes ``indentation`` (called once, on first access)."""

    @functools.cached_property
    def indentation(self) -> float:
        """delta_k/h: how far its lowest point (its axis) lies below the
        undisturbed surface: f_k(x) - v(x, 0) at its most loaded zone's
        centre, v the whole train's displacement (a single contact: the
        solution's ``indentation``; computed on first access)."""
        return self._indentation()

    @overload
    def pressure(self, x: float) -> float: ...
    @overload
    def pressure(self, x: Points) -> FloatArray: ...
    def pressure(self, x: npt.ArrayLike) -> float | FloatArray:
        """Its own contact pressure p/(P_k/h) at x/h (0 off its zones)."""
        return _pointwise("x", x, self._impl.pressure)

    def to_dict(self) -> dict[str, object]:
        """JSON-safe; the indentation None where the medium does not give it
        (``regime.given_indentation``)."""
        given = given_indentation(self)
        indentation = None if math.isnan(given) else given
        return {
            "profile": self.profile.to_dict(),
            "load": self.load,
            "at": self.at,
            "contact_zones": [list(z) for z in self.contact_zones],
            "zone_loads": list(self.zone_loads),
            "indentation": indentation,
            "drag": self.drag,
        }


@dataclass(frozen=True)
class ZonedSolution(ResultFields):
    """Several contact zones (a separated contact, or a train of punches):
    the contract's fields and evaluations of the whole surface (the
    superposed response), pressures and stresses over P/h with P the total
    load, and ``punches``, one ``PunchResult`` each. ``profile``,
    ``radius``, ``indentation`` are the first punch's."""

    damping: float
    friction: float
    tangential_force: float
    end_exponents: tuple[float, float]
    contact_interval: tuple[float, float]
    """The hull (x_first, x_last)/h of all zones."""
    drag: float
    """Horizontal force of the normal pressure on all punches over P."""
    pressure_error_estimate: float
    """Bound on the error of p/(P/h) at fixed relative positions in each zone."""
    stress_error_estimate: float
    """Bound on the error of the surface sigma_x/(P/h) more than 1e-3 of a
    zone's half-width from its ends."""
    max_pressure: float
    punches: tuple[PunchResult, ...]
    single_validity: str
    """What the single-contact solution was (why it was rejected), or "" for
    a train."""
    topologies: int
    """Contact sets the search solved before this one was found (1: the
    first was right)."""
    _impl: _ZoneSum = field(repr=False, compare=False)
    _contact_zones: tuple[tuple[float, float], ...] = field(default=(), repr=False)
    _solved: Any = field(default=None, repr=False, compare=False)
    _profile: PunchProfile | None = field(default=None, repr=False, compare=False)
    _stage_times: Mapping[str, float] = field(
        default_factory=dict, repr=False, compare=False
    )
    _kernel_builds: int = field(default=0, repr=False, compare=False)
    _medium: Medium | None = field(default=None, repr=False, compare=False)

    @property
    def kernel_builds(self) -> int:
        """Kernel tables the zones' solve built (0: all from the cache; the
        single solves before it not counted)."""
        return self._kernel_builds

    @property
    def contact_zones(self) -> tuple[tuple[float, float], ...]:
        """Every zone (x_left, x_right)/h, from left to right."""
        return self._contact_zones

    @property
    def _even(self) -> bool:
        """Whether every distribution is even in x: one punch on the axis,
        symmetric, undamped (a separated contact); never a train."""
        if self.damping != 0.0 or len(self.punches) != 1 or self.punches[0].at != 0.0:
            return False
        return bool(getattr(self.profile, "symmetric", True))

    @property
    def stage_times(self) -> Mapping[str, float]:
        """Seconds: ``width`` (the single solves and the zone solves of the
        search), ``checks`` (the rest); ``critical_speed`` and ``kernel`` are
        counted inside them (0.0 here)."""
        return MappingProxyType(dict(self._stage_times))

    @functools.cached_property
    def indentation(self) -> float:
        """The first punch's indentation delta/h (``PunchResult.indentation``;
        computed on first access)."""
        return self.punches[0].indentation

    @property
    def a(self) -> float:
        """The hull's leading end x/h."""
        return self.contact_interval[1]

    @property
    def half_width(self) -> float:
        """Half the hull's length."""
        return 0.5 * (self.contact_interval[1] - self.contact_interval[0])

    @property
    def centre(self) -> float:
        """The hull's midpoint."""
        return 0.5 * (self.contact_interval[1] + self.contact_interval[0])

    @property
    def p0(self) -> float:
        """p(0)/(P/h) (0 where x = 0 lies between zones)."""
        return self.pressure(0.0)

    @functools.cached_property
    def dissipation(self) -> float:
        """Power dissipated in the dashpots over P V, damping sqrt(vstar)/P
        int (dv/dx(x, -h))^2 dx (0 without damping), by Parseval on the bottom
        face from the zones' summed pressure transform (in the core); equals
        ``drag`` by the energy balance."""
        return float(self._solved.dissipation())

    @overload
    def surface_slope(self, x: float) -> float: ...
    @overload
    def surface_slope(self, x: Points) -> FloatArray: ...
    def surface_slope(self, x: npt.ArrayLike) -> float | FloatArray:
        """Surface slope dv/dx(x, 0)."""
        return _pointwise("x", x, self._impl.surface_slope)


# ---------------------------------------------------------------------------
# The search for the contact set


_FIRST_N = 24
"""The first size of a zone solve's ladder from a rough start (the search's
second pass, a train whose punches' own contacts overlap): at N = 8 a stiff
foundation's short kernel is unresolved, and Newton's method there once
wandered for minutes before it stalled."""

_TRAIN_FIRST_N = 8
"""The first size of a train's ladder from its punches' own contacts (a close
start: N = 8 then a step or two at each finer size; from N = 24 a two-punch
train costs twice as much)."""


@dataclass
class _Layer:
    vstar: float
    kw: float
    nu: float
    damping: float
    kp: float
    tol: float
    n: int
    first_n: int = _FIRST_N
    """The ladder's first size."""
    medium: Medium | None = None
    """A layered medium (or a half-space base; ``movingpunch.media``), or
    None: the homogeneous layer of (kw, nu, kp, damping)."""


def _solve_topology(
    layer: _Layer,
    punches: Sequence[Punch],
    zones: Sequence[tuple[int, float, float]],
    builds: list[int] | None = None,
) -> Any:
    z = _core.solve_zones(
        vstar=layer.vstar,
        kw=layer.kw,
        nu=layer.nu,
        damping=layer.damping,
        kp=layer.kp,
        tol=layer.tol,
        n=layer.n,
        punches=[p._core() for p in punches],
        zones=list(zones),
        first_n=layer.first_n,
        **(layer.medium.core_args() if layer.medium is not None else {}),
    )
    if builds is not None:
        builds.append(int(z.kernel_builds))
    return z


def _negative_runs(zone: Any, origin: float) -> list[tuple[float, float, bool, bool]]:
    """Where p < 0 in a zone: (x_from, x_to, touches_left, touches_right) of
    each run of negative g = p/sqrt(1 - r^2) on a 2001-point grid (its
    solution is relative to its punch's axis ``origin``)."""
    sol = zone.solution
    w = float(sol.half_width)
    c = float(sol.centre)
    r = np.cos(np.linspace(math.pi, 0.0, 2001))
    r = r[1:-1]
    g = (
        np.asarray(sol.pressure(c + w * r))
        / np.sqrt(1.0 - r * r)
        * math.copysign(1.0, zone.load)
    )
    neg = g < 0.0
    runs = []
    i = 0
    while i < len(r):
        if not neg[i]:
            i += 1
            continue
        j = i
        while j + 1 < len(r) and neg[j + 1]:
            j += 1
        runs.append(
            (origin + c + w * r[i], origin + c + w * r[j], i == 0, j == len(r) - 1)
        )
        i = j + 1
    return runs


def _complementarity(z: Any) -> tuple[bool, str]:
    """Whether the solved topology is the contact set: p >= 0 on each zone
    (its margin), gap >= 0 beside them; the account."""
    bad = []
    for k, zone in enumerate(z.zones):
        if zone.load <= 0.0 or zone.margin < -1e-9 * max(1.0, abs(zone.margin)):
            bad.append(
                f"zone {k + 1} ({zone.left:.6g}, {zone.right:.6g}): p < 0 near x/h = "
                f"{zone.margin_x:.6g}"
            )
    if z.min_gap < -1e-6 * z.gap_scale:
        bad.append(f"penetration at x/h = {z.min_gap_x:.6g} (gap/h = {z.min_gap:.3g})")
    return (not bad, "; ".join(bad))


_PADS = (0.02, 0.12, 0.25)
"""How far (as a fraction of the zone's length) a new zone end is placed
beyond the run of p < 0 it avoids: the search tries them in turn (Newton's
method from a gap much narrower than the true one can stall)."""


def _carve(
    left: float,
    right: float,
    runs: Sequence[tuple[float, float, bool, bool]],
    frac: float,
) -> list[tuple[float, float]]:
    """What remains of the zone (left, right) without its runs of p < 0,
    each widened by ``frac`` of the zone's length (a run at an end takes
    that end off); pieces shorter than 2 % of the zone are dropped."""
    pad, least = frac * (right - left), 0.02 * (right - left)
    pieces = [(left, right)]
    for lo, hi, at_left, at_right in runs:
        cut_lo = left if at_left else lo - pad
        cut_hi = right if at_right else hi + pad
        kept = []
        for a, b in pieces:
            if cut_hi <= a or cut_lo >= b:
                kept.append((a, b))
                continue
            if cut_lo > a:
                kept.append((a, cut_lo))
            if cut_hi < b:
                kept.append((cut_hi, b))
        pieces = kept
    return [(a, b) for a, b in pieces if b - a >= least]


def _next_topologies(
    z: Any, punches: Sequence[Punch], mirror: bool = False
) -> list[list[tuple[int, float, float]]]:
    """The contact sets to try after ``z`` failed complementarity, best
    first (empty: no rule applies). ``mirror``: the problem is symmetric
    about x = 0 (a new zone gets its mirror image too)."""
    zones = [(int(q.punch), float(q.left), float(q.right)) for q in z.zones]
    runs = [
        _negative_runs(q, punches[int(q.punch)].at)
        if (q.load <= 0.0 or q.margin < 0.0)
        else []
        for q in z.zones
    ]
    if any(runs):
        # p < 0: take every run of p < 0 out of its zone (split it, or
        # shrink its end), in every zone at once (a symmetric contact stays
        # symmetric), with a margin beyond each run tried in turn.
        out = []
        for frac in _PADS:
            fixed: list[tuple[int, float, float]] = []
            for k, zone_runs in enumerate(runs):
                punch, left, right = zones[k]
                if not zone_runs:
                    fixed.append(zones[k])
                    continue
                fixed += [
                    (punch, a, b) for a, b in _carve(left, right, zone_runs, frac)
                ]
            if all(any(t[0] == k for t in fixed) for k in range(len(punches))):
                out.append(fixed)
        return out
    # Penetration between two zones of one punch: merge them; elsewhere: a
    # new zone (or grow the nearest end when the point is close to it).
    if z.min_gap < -1e-6 * z.gap_scale:
        j = int(z.min_gap_after_zone)
        x = float(z.min_gap_x)
        if j >= 0:
            nxt = next(
                i for i in range(j + 1, len(zones)) if zones[i][0] == zones[j][0]
            )
            merged = (zones[j][0], zones[j][1], zones[nxt][2])
            if mirror and len(zones) == nxt + 1 + j:  # and the mirror pair
                m = len(zones) - 1 - nxt
                pair = (zones[m][0], zones[m][1], zones[len(zones) - 1 - j][2])
                if m > nxt:
                    return [[*zones[:j], merged, *zones[nxt + 1 : m], pair]]
            return [[*zones[:j], merged, *zones[j + 1 : nxt], *zones[nxt + 1 :]]]
        points = [x, -x] if mirror and abs(x) > 1e-9 else [x]
        # Two starts: the nearest end grown over the point (when it is
        # close), and a new zone there. A topology's ends are fixed by its
        # end conditions, so a grown end often solves back to the set that
        # failed (the search then takes the new zone: _search).
        grown, added = list(zones), list(zones)
        for xp in points:
            near = min(
                range(len(zones)),
                key=lambda i: min(abs(xp - zones[i][1]), abs(xp - zones[i][2])),
            )
            punch, left, right = zones[near]
            width = right - left
            lo, hi = xp - 0.02 * width, xp + 0.02 * width
            if xp < left and left - xp < 0.1 * width:
                grown[near] = (punch, xp - 0.01 * width, grown[near][2])
                hi = min(hi, xp + 0.5 * (left - xp))
            elif xp > right and xp - right < 0.1 * width:
                grown[near] = (punch, grown[near][1], xp + 0.01 * width)
                lo = max(lo, xp - 0.5 * (xp - right))
            else:
                grown.append((punch, lo, hi))
            added.append((punch, lo, hi))
        grown.sort(key=lambda t: t[1])
        added.sort(key=lambda t: t[1])
        return [grown, added] if grown != added else [added]
    return []


def _signature(zones: Sequence[tuple[int, float, float]]) -> tuple[object, ...]:
    """A start of the search (its punches in order, its ends to 1e-4 of
    the hull): the search never solves one twice (nor one within 1e-4 of
    the hull of it)."""
    scale = 1e-4 * max(1e-300, zones[-1][2] - zones[0][1])
    return tuple((z[0], round(z[1] / scale), round(z[2] / scale)) for z in zones)


_SEARCH_N = 48
"""The fixed collocation size per zone of the search's first pass."""


def find_contact_set(
    layer: _Layer,
    punches: Sequence[Punch],
    start: Sequence[tuple[int, float, float]],
    *,
    mirror: bool = False,
    builds: list[int] | None = None,
) -> tuple[Any, int, list[str]]:
    """The active-set search from the contact set ``start``: the solved
    topology that satisfies complementarity, the number of topologies
    solved and the account of each. Raises UnphysicalContactError when no
    contact set is found (naming what failed); never returns one that
    fails complementarity.

    With the automatic ladder (``layer.n`` 0) and one punch (a separated
    contact: the search starts far from the set) the search first decides the
    topologies at the fixed size ``_SEARCH_N`` (a topology whose zones
    nearly merge would otherwise climb the ladder to its largest size only
    to be rejected), then solves the set it found on the ladder from its
    own ends (from ``_FIRST_N``) and checks it again; when the first pass
    finds nothing, or its set fails on the ladder, the search runs on the
    ladder. ``builds`` (optional) collects the kernel tables each solve built."""
    if layer.n != 0 or len(punches) > 1:  # a train starts close: the ladder
        return _search(layer, punches, start, mirror, builds)
    try:
        rough, solved, account = _search(
            dataclasses.replace(layer, n=_SEARCH_N), punches, start, mirror, builds
        )
    except UnphysicalContactError:
        return _search(layer, punches, start, mirror, builds)
    zones = [(int(q.punch), float(q.left), float(q.right)) for q in rough.zones]
    try:
        z = _solve_topology(
            dataclasses.replace(layer, first_n=_FIRST_N), punches, zones, builds
        )
    except ConvergenceError:
        return _search(layer, punches, start, mirror, builds)
    if _complementarity(z)[0]:
        return z, solved, account
    return _search(layer, punches, start, mirror, builds)


def _search(
    layer: _Layer,
    punches: Sequence[Punch],
    start: Sequence[tuple[int, float, float]],
    mirror: bool,
    builds: list[int] | None = None,
) -> tuple[Any, int, list[str]]:
    """find_contact_set's search at the layer's own sizes."""
    seen: set[tuple[object, ...]] = set()
    reached: set[tuple[object, ...]] = set()  # the sets solved so far
    candidates = [list(start)]
    account: list[str] = []
    solved = 0
    unsolved = False  # the last round's starts failed to converge
    while candidates and solved < _MAX_TOPOLOGIES:
        z = None
        unsolved = False
        for zones in candidates:
            key = _signature(zones)
            if key in seen:
                continue
            seen.add(key)
            try:
                z = _solve_topology(layer, punches, zones, builds)
            except ConvergenceError as err:
                account.append(f"{len(zones)} zones: {err}")
                unsolved = True
                continue
            got = _signature([(int(q.punch), q.left, q.right) for q in z.zones])
            if got not in reached:
                reached.add(got)
                break
            z = None  # solved back to a set already tried: the next start
        if z is None:
            break
        solved += 1
        ok, why = _complementarity(z)
        if ok:
            return z, solved, account
        account.append(f"{len(z.zones)} zones: {why}")
        candidates = _next_topologies(z, punches, mirror)
    lead = (
        "no contact set found (the end conditions of the next contact set "
        "could not be solved)"
        if unsolved
        else "no contact set satisfies p >= 0 and gap >= 0"
    )
    raise UnphysicalContactError(
        f"{lead}: the search tried " + " | ".join(account or ["nothing"])
    )


def _indentation_at(everything: _ZoneSum, x: float, height: float) -> float:
    """A punch's indentation: its profile's height f_k(x) less the whole
    surface's displacement v(x, 0) at x (its most loaded zone's centre)."""
    return height - float(everything.surface_displacement(np.array([x]))[0])


def single_punch(s: ContactSolution, impl: Any) -> tuple[PunchResult, ...]:
    """``punches`` of a single contact ``s`` (``impl``: its compiled result,
    whose ``pressure`` is the punch's): its one punch, described as a
    train's are: at x = 0, its one zone carrying the whole load, the
    solution's own drag and (on first access) indentation."""
    return (
        PunchResult(
            profile=s.profile,
            load=s.load,
            at=0.0,
            contact_zones=s.contact_zones,
            zone_loads=(s.load,),
            drag=s.drag,
            _impl=impl,
            _indentation=lambda: s.indentation,
        ),
    )


def _result(
    z: Any,
    layer: _Layer,
    punches: Sequence[Punch],
    *,
    topologies: int,
    single_validity: str,
    elapsed: float,
    search_seconds: float,
    kernel_builds: int,
) -> ZonedSolution:
    total = sum(p.load for p in punches)
    built = _Zones(
        z.zones,
        punches,
        layer.medium is not None and isinstance(layer.medium.base, HalfSpace),
    )
    every = range(len(z.zones))
    impl = _ZoneSum(built, every, total)
    results = []
    for k, p in enumerate(punches):
        mine = [i for i, q in enumerate(z.zones) if q.punch == k]
        results.append(
            PunchResult(
                profile=p.profile,
                load=p.load,
                at=p.at,
                contact_zones=tuple(
                    (float(z.zones[i].left), float(z.zones[i].right)) for i in mine
                ),
                zone_loads=tuple(float(z.zones[i].load) for i in mine),
                drag=float(z.drag[k]),
                _impl=_ZoneSum(built, mine, p.load),
                _indentation=functools.partial(
                    _indentation_at,
                    impl,
                    float(z.indentation_x[k]),
                    float(z.indentation_height[k]),
                ),
            )
        )
    zones = tuple((float(q.left), float(q.right)) for q in z.zones)
    margins = [q.margin * q.load / total for q in z.zones]
    n_zones = len(zones)
    what = (
        f"separated contact of {n_zones} zones"
        if len(punches) == 1
        else f"{len(punches)} punches in {n_zones} zones"
    )
    validity = (
        f"valid: {what}; p >= 0 on every zone and no penetration within 2 contact "
        "widths of each punch's zones (complementarity)"
    )
    if single_validity:
        validity += f"; the single contact was rejected: {single_validity}"
    warnings = tuple(str(w) for w in z.warnings)
    first = punches[0]
    return ZonedSolution(
        vstar=layer.vstar,
        kw=layer.kw,
        kp=layer.kp,
        radius=first.profile.nominal_radius,
        load=total,
        nu=layer.nu,
        tol=layer.tol,
        critical_vstar=float(z.critical_vstar),
        rayleigh_vstar=float(z.rayleigh_vstar),
        phi1=float(z.phi1),
        iterations=int(z.iterations),
        collocation_n=int(z.collocation_n),
        error_estimate=float(z.error_estimate),
        elapsed=elapsed,
        valid=True,
        validity=validity,
        min_pressure=min(q.min_pressure * q.load / total for q in z.zones),
        min_gap=float(z.min_gap),
        pressure_margin=min(margins),
        warnings=warnings,
        damping=layer.damping,
        friction=0.0,
        tangential_force=0.0,
        end_exponents=(0.5, 0.5),
        contact_interval=(zones[0][0], zones[-1][1]),
        _contact_zones=zones,
        _solved=z,
        drag=float(z.drag_total),
        pressure_error_estimate=float(z.pressure_error_estimate) / total,
        stress_error_estimate=float(z.stress_error_estimate),
        max_pressure=float(z.max_pressure),
        punches=tuple(results),
        single_validity=single_validity,
        topologies=topologies,
        _impl=impl,
        _profile=first.profile,
        _stage_times={
            "critical_speed": 0.0,
            "kernel": 0.0,
            "width": search_seconds,
            "checks": max(0.0, elapsed - search_seconds),
        },
        _kernel_builds=kernel_builds,
        _medium=layer.medium,
    )


def separate(single: Any, *, damping: float, kp: float, n: int | None) -> ZonedSolution:
    """The contact set of one punch whose single contact ``single`` (solved
    with allow_unphysical) is unphysical: the search from that contact."""
    t0 = time.perf_counter()
    # A fixed size of the single solve (2 to 4096) as the zones' (8 to 256).
    size = 0 if n is None else min(256, max(8, 2 * (n // 2)))
    layer = _Layer(
        single.vstar,
        single.kw,
        single.nu,
        damping,
        kp,
        single.tol,
        size,
        medium=single._medium,
    )
    punch = Punch(single.profile, single.load, 0.0)
    lo, hi = single.contact_interval
    # Symmetric about x = 0: a symmetric punch without damping.
    mirror = damping == 0.0 and bool(getattr(single.profile, "symmetric", True))
    builds: list[int] = []
    z, topologies, _ = find_contact_set(
        layer, [punch], [(0, float(lo), float(hi))], mirror=mirror, builds=builds
    )
    elapsed = time.perf_counter() - t0 + single.elapsed
    return _result(
        z,
        layer,
        [punch],
        topologies=topologies,
        single_validity=single.validity,
        elapsed=elapsed,
        search_seconds=elapsed,
        kernel_builds=sum(builds),
    )


def _check_position(k: int, at: float, single: Any) -> None:
    """Refuses a punch placed where the doubles are too sparse for its
    contact (its zone ends resolved to less than 1e-3 of its narrowest zone's
    half-width), naming ``at`` and the positions that work. Nearer x = 0 the
    train is solved relative to its punches (the problem is translation
    invariant) and moved there, to the spacing of doubles at ``at``."""
    half = min(0.5 * (hi - lo) for lo, hi in single.contact_zones)
    reach = max(max(abs(lo), abs(hi)) for lo, hi in single.contact_zones)
    far = abs(at) + reach
    if abs(at) <= 1.0 or math.ulp(far) <= 1e-3 * half:
        return
    limit = 2.0 ** (math.floor(math.log2(1e-3 * half)) + 53) - reach
    raise InvalidParameterError(
        f"punches[{k}]: at = {at!r} is too far from x = 0: positions there are "
        f"resolved only to {math.ulp(far):.3g} h (the spacing of doubles), too "
        f"coarse for its contact zone (half-width {half:.6g} h); |at| must be at "
        f"most {limit:.6g} for this punch. A train's result does not depend on "
        "where it is: place it near x = 0",
        parameter="at",
        allowed=f"|at| <= {limit:.6g}",
    )


def solve_train(
    punches: Sequence[Punch],
    singles: Sequence[Any],
    *,
    damping: float,
    tol: float,
    n: int,
    t0: float,
) -> ZonedSolution:
    """The train of ``punches`` from each punch's own solution ``singles``
    (their contact zones, moved to the punch, start the search); ``n`` 0
    (the ladder) or the zones' fixed size; ``t0`` when the solve began
    (``time.perf_counter``). Raises InvalidParameterError naming ``punches``
    when the punches' own contacts overlap."""
    first = singles[0]
    layer = _Layer(
        first.vstar,
        first.kw,
        first.nu,
        damping,
        first.kp,
        tol,
        n,
        _TRAIN_FIRST_N,
        medium=first._medium,
    )
    for k, (p, s) in enumerate(zip(punches, singles, strict=True)):
        _check_position(k, p.at, s)
    start: list[tuple[int, float, float]] = []
    for k, (p, s) in enumerate(zip(punches, singles, strict=True)):
        start += [(k, p.at + lo, p.at + hi) for lo, hi in s.contact_zones]
    start.sort(key=lambda t: t[1])
    # Punches whose own contacts would overlap start from them clipped apart
    # (about the middle of the overlap): in a train the punches lift each
    # other, and their zones may well end apart. Refused (naming the
    # punches) only when clipping leaves a punch no zone or the search then
    # finds no contact set.
    overlap = None
    for i in range(len(start) - 1):
        (k1, left_l, r1), (k2, l2, right_r) = start[i], start[i + 1]
        if l2 > r1:
            continue
        overlap = overlap or (k1, k2, r1, l2)
        middle = 0.5 * (punches[k1].at + punches[k2].at)
        if not left_l < middle < right_r:
            middle = 0.5 * (r1 + l2)
        margin = 0.02 * min(r1 - left_l, right_r - l2)
        start[i] = (k1, left_l, middle - margin)
        start[i + 1] = (k2, middle + margin, right_r)

    def too_close(why: str) -> InvalidParameterError:
        assert overlap is not None
        k1, k2, r1, l2 = overlap
        return InvalidParameterError(
            f"punches[{k1}] and punches[{k2}] are so close that their contacts "
            f"overlap (alone they reach x/h = {r1:.6g} and {l2:.6g}, and together "
            f"no contact set keeps them apart: {why}): place them further apart",
            parameter="punches",
            allowed="punches whose contacts do not overlap",
        )

    no_zone = any(b <= a for _, a, b in start) or any(
        all(t[0] != k for t in start) for k in range(len(punches))
    )
    if overlap is not None:
        layer.first_n = _FIRST_N  # a rough start
        if no_zone:
            raise too_close("a punch would have no zone")
    t1 = time.perf_counter()
    builds: list[int] = []
    try:
        z, topologies, _ = find_contact_set(layer, punches, start, builds=builds)
    except (UnphysicalContactError, ConvergenceError) as err:
        if overlap is None:
            raise
        raise too_close(str(err)) from err
    elapsed = time.perf_counter() - t0
    return _result(
        z,
        layer,
        punches,
        topologies=topologies,
        single_validity="",
        elapsed=elapsed,
        search_seconds=time.perf_counter() - t1,
        kernel_builds=sum(builds),
    )
