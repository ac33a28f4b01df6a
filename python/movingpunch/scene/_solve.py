"""Solving the points of a scene: the key that identifies a solve, one solve,
the numbers a sweep tabulates of a solved point, a group or chunk of sweep
points (what a worker process or a Dask worker runs), and ``RunState``, the state
of one run (solutions by key, their warnings, the stages, the progress).

Sweep points that share (vstar, kw, nu, tol, damping, kp) share the k1 kernel
(the core caches it per process); and because a/h, p/(P/h) and sigma/(P/h)
depend on radius and load only through lambda = radius * load, points with
equal (vstar, kw, nu, tol, damping, kp, lambda) share one key and are solved
once.
"""

from __future__ import annotations

import contextlib
import math
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from movingpunch.contract import ContactSolution
from movingpunch.errors import (
    InvalidParameterError,
    MovingPunchError,
    UnphysicalContactError,
)
from movingpunch.media import Medium
from movingpunch.profiles import PunchProfile
from movingpunch.scene._model import (
    PEAK_QUANTITIES,
    SceneData,
    point_medium,
    train_of,
)
from movingpunch.scene._result import Stages
from movingpunch.solver import result_warnings, solve, solve_punches
from movingpunch.zones import Punch

__all__ = ["RunState", "point_key", "solve_point"]

# vstar, kw, nu, tol, damping, kp, friction, lambda, spacing
Key = tuple[float, float, float, float, float, float, float, float, float]


def _damping(p: Mapping[str, float]) -> float:
    return p.get("damping", 0.0)


def _kp(p: Mapping[str, float]) -> float:
    return p.get("kp", 0.0)


def _friction(p: Mapping[str, float]) -> float:
    return p.get("friction", 0.0)


NO_SPRINGS = -1.0
"""The kw of a point's key under a half-space base (no springs: its params
hold no kw; never a valid kw)."""


def point_key(p: Mapping[str, float], tol: float) -> Key:
    # Beside a flat punch or a table (radius inf) the load alone tells the
    # points apart (negated: never a cylinder's lambda).
    # A train's points (radius: its first punch's, fixed) differ in the total
    # load and the spacing (0: the punches' own positions).
    lam = p["radius"] * p["load"] if math.isfinite(p["radius"]) else -p["load"]
    spacing = p.get("spacing", 0.0)
    return (
        p["vstar"],
        p.get("kw", NO_SPRINGS),
        p["nu"],
        tol,
        _damping(p),
        _kp(p),
        _friction(p),
        lam,
        spacing,
    )


def radius_ratio(solved: float, wanted: float) -> float:
    """solved/wanted radius (the lambda rescaling of a shared solution); 1
    when they are equal, inf included (a flat punch, a table)."""
    return 1.0 if solved == wanted else solved / wanted


def curve_label(param: str | None, value: float | None) -> str:
    if param is None or value is None:
        return ""
    return f"{param}={'inf' if math.isinf(value) else format(value, '.6g')}"


def solve_point(
    p: Mapping[str, float],
    tol: float,
    stages: Stages,
    profile: PunchProfile | None = None,
    contact: str = "auto",
    punches: Sequence[Punch] = (),
    medium: Medium | None = None,
) -> ContactSolution:
    """One point of a scene: a cylinder of p["radius"], or ``profile``, or
    the train ``punches`` (``solve_punches``; their loads and positions for
    this point from ``train_of``), on the homogeneous layer of p (nu, kw,
    kp, damping) or on ``medium`` (its springs those of p: ``point_medium``)."""
    if punches:
        # On the scene's medium when it has one (its [[layers]] and base:
        # the springs those of p), else the homogeneous layer of p.
        where: dict[str, Any]
        if medium is not None:
            m = point_medium(medium, p)
            if not m.inertia:
                raise InvalidParameterError(
                    "inertia: a train of punches is solved with the medium's inertia "
                    "(inertia = false is for one punch's speed sweep of a material)",
                    parameter="inertia",
                    allowed="true for a train of punches",
                )
            where = {"layers": list(m.layers), "base": m.base}
        else:
            where = {
                "kw": p["kw"],
                "nu": p["nu"],
                "kp": _kp(p),
                "damping": _damping(p),
            }
        s: ContactSolution = solve_punches(
            train_of(punches, p), vstar=p["vstar"], tol=tol, **where
        )
        stages.add_solution(s)
        return s
    args: dict[str, Any] = {
        "vstar": p["vstar"],
        "radius": p["radius"] if profile is None else None,
        "profile": profile,
        "load": p["load"],
        "tol": tol,
        "friction": _friction(p),
    }
    if medium is None:
        args.update(kw=p["kw"], nu=p["nu"], damping=_damping(p), kp=_kp(p))
    else:
        m = point_medium(medium, p)
        args.update(m.solve_args())
    # A sweep goes on through unphysical points: contact "auto" finds the
    # zones where the single contact separates, and where no contact set is
    # found (or with "single") the point is the single contact, flagged
    # invalid (valid = 0 in the tables).
    found: ContactSolution | None = None
    if contact == "auto":
        with contextlib.suppress(UnphysicalContactError):
            found = solve(**args, contact=contact)
    if found is None:
        found = solve(**args, allow_unphysical=True, contact=contact)
    stages.add_solution(found)
    return found


def point_quantities(
    s: ContactSolution,
    want_peaks: bool,
    stages: Stages,
    warnings: list[str],
    want_indentation: bool = True,
) -> dict[str, float]:
    """The sweep's numbers of one solved point; the stress peak search's
    warnings (``StressPeaks.warnings``) are appended to ``warnings``. The
    indentation a medium does not give (the asymmetric solver under a
    half-space: a logarithmic far field) is NaN, with its refusal among the
    warnings when the sweep asks for it."""
    q: dict[str, float] = {
        "a": s.a,
        "min_pressure": s.min_pressure,
        "critical_vstar": s.critical_vstar,
        "phi1": s.phi1,
        "valid": 1.0 if s.valid else 0.0,
        "load": s.load,
        "radius": s.radius,
    }
    try:
        indentation = s.indentation
    except InvalidParameterError as exc:
        indentation = math.nan
        if want_indentation:
            warnings.append(f"indentation: {exc}")
    q.update(
        p0=s.p0,
        indentation=indentation,
        drag=s.drag,
        contact_start=s.contact_interval[0],
        contact_end=s.contact_interval[1],
        zones=float(len(s.contact_zones)),
    )
    if want_peaks:
        t0 = time.perf_counter()
        peaks = s.stress_peaks()
        stages.add("stress_peaks", time.perf_counter() - t0)
        warnings.extend(f"stress peaks: {w}" for w in peaks.warnings)
        for name in PEAK_QUANTITIES:
            q[name] = float(getattr(peaks, name))
    return q


def _point_text(p: Mapping[str, float]) -> str:
    """The parameters of a solved point, for its warnings."""
    names = [n for n in ("vstar", "kw", "radius", "load", "nu") if n in p]
    if _damping(p) > 0.0:
        names.append("damping")
    if _kp(p) > 0.0:
        names.append("kp")
    if _friction(p) > 0.0:
        names.append("friction")
    if "spacing" in p:
        names.append("spacing")
    return ", ".join(f"{n}={p[n]:.6g}" for n in names)


def solve_group(task: Mapping[str, Any]) -> dict[str, Any]:
    """Solves one group of sweep points sharing (vstar, kw, nu, tol, damping,
    kp, friction), in descending lambda (the first solve builds the widest
    kernel; the rest reuse it). Runs in a worker process or on a Dask worker."""
    stages = Stages()
    results: list[dict[str, float] | str] = []
    warnings: list[list[str]] = []
    spacings = task.get("spacings") or [None] * len(task["points"])
    for (radius, load), spacing in zip(task["points"], spacings, strict=True):
        p = {
            "vstar": task["vstar"],
            "kw": task["kw"],
            "nu": task["nu"],
            "damping": task["damping"],
            "kp": task.get("kp", 0.0),
            "friction": task.get("friction", 0.0),
            "radius": radius,
            "load": load,
        }
        if p["kw"] == NO_SPRINGS:  # a half-space base
            del p["kw"], p["kp"], p["damping"]
        if spacing is not None:
            p["spacing"] = spacing
        try:
            s = solve_point(
                p,
                task["tol"],
                stages,
                task.get("profile"),
                task.get("contact", "auto"),
                task.get("punches", ()),
                task.get("medium"),
            )
            found = list(result_warnings(s))
            results.append(
                point_quantities(
                    s, task["peaks"], stages, found, task.get("indentation", True)
                )
            )
            warnings.append(found)
        except MovingPunchError as exc:
            results.append(str(exc))
            warnings.append([])
    return {"results": results, "stages": stages.records(), "warnings": warnings}


def solve_chunk(tasks: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """Solves the groups of a chunk (in a worker process or on Dask)."""
    return [solve_group(task) for task in tasks]


# ----------------------------------------------------------------------------
# The state of a run
# ----------------------------------------------------------------------------


@dataclass
class RunState:
    """The state of one run: its solutions by key, their warnings, its
    stages and its progress (``done`` of ``total`` points)."""

    scene: SceneData
    stages: Stages = field(default_factory=Stages)
    memo: dict[Key, ContactSolution] = field(default_factory=dict)
    warnings: dict[Key, list[str]] = field(default_factory=dict)
    done: int = 0
    total: int = 0
    progress: Callable[[int, int], None] | None = None
    keep: set[Key] | None = None
    """The keys whose solutions are kept (``memo``) once solved; None: all."""

    def tick(self, n: int = 1) -> None:
        self.done += n
        if self.progress is not None:
            self.progress(self.done, self.total)

    def solution(self, p: Mapping[str, float]) -> ContactSolution:
        """The solution of point ``p``: solved once, kept if its key is one
        ``keep`` names (a sweep's other points are solved, read and let go)."""
        key = point_key(p, self.scene.tol)
        found = self.memo.get(key)
        if found is None:
            found = solve_point(
                p,
                self.scene.tol,
                self.stages,
                self.scene.profile,
                self.scene.contact,
                self.scene.punches,
                self.scene.medium,
            )
            if self.keep is None or key in self.keep:
                self.memo[key] = found
            self.note_warnings(key, p, result_warnings(found))
            self.tick()
        return found

    def note_warnings(
        self, key: Key, p: Mapping[str, float], found: Sequence[str]
    ) -> None:
        """Records the warnings of a solved point (its solution's and its
        stress peaks'), each prefixed with the point's parameters."""
        if found:
            self.warnings.setdefault(key, []).extend(
                f"{_point_text(p)}: {w}" for w in found
            )

    @contextlib.contextmanager
    def timed(self, name: str) -> Iterator[None]:
        t0 = time.perf_counter()
        yield
        self.stages.add(name, time.perf_counter() - t0)
