"""What accuracy costs in time: a ladder of tolerances against a tight reference.

For each tol of a ladder (1e-2, 1e-3, ..., 1e-12) a case (one parameter set:
solve + the sigma_x peaks) or a scene (``Scene.run`` with that tol, then the
sigma_x peaks of its base configurations) is computed with a cold kernel
cache and again warm. Its contact ends (both ends of ``contact_interval``:
+-a/h for the paper's symmetric contact, (x_back, x_front) on a damped
foundation), p0 and sigma_x peaks are compared with a reference computed
differently: a fixed, much larger collocation size (N = max(64, 4 N_auto),
N_auto the size the automatic refinement picks at tol 1e-14; 2 N_auto if the
solver does not take 4 N_auto) at tol 1e-14, so the reference does not share
the refinement's stopping rule. ``movingpunch accuracy`` prints the table, a
log-log plot and writes CSV; the terminal UI's Accuracy tab shows the same.

Every solution is read through ``movingpunch.ContactSolution`` only: the
ladder never asks which solver (symmetric or asymmetric) computed it.

Nothing here imports Textual.
"""

from __future__ import annotations

import importlib
import math
import textwrap
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from movingpunch._version import version
from movingpunch.contract import ContactSolution
from movingpunch.errors import (
    InvalidParameterError,
    MovingPunchError,
    UnphysicalContactError,
)
from movingpunch.fields import StressPeaks
from movingpunch.media import HalfSpace, Medium
from movingpunch.outputs import publish, safe_name
from movingpunch.params import PHYSICAL
from movingpunch.profiles import PunchProfile
from movingpunch.scene import OutputSpec, Scene, load_scene
from movingpunch.scene._model import point_medium
from movingpunch.scene._result import CORE_STAGES
from movingpunch.scene._solve import NO_SPRINGS
from movingpunch.solver import clear_kernel_cache, solve, solve_punches
from movingpunch.zones import Punch

__all__ = [
    "FIG4_CASE",
    "LADDER",
    "AccuracyReport",
    "Rung",
    "accuracy_report",
    "ascii_plot",
    "format_table",
    "render_csv",
    "write_csv",
]

FloatArray = npt.NDArray[np.float64]

LADDER: tuple[float, ...] = tuple(10.0**-k for k in range(2, 13))
"""The default tolerances: 1e-2, 1e-3, ..., 1e-12."""

FIG4_CASE: Mapping[str, float] = {
    "vstar": 0.2,
    "kw": 1.0,
    "radius": 100.0,
    "load": 0.002,
    "nu": 0.2,
}
"""The paper's Fig. 4 case (V* 0.2, kw h/mu 1, R/h 100, mu/(P/h) 500, nu 0.2)."""

_REF_TOLS = (1e-14, 1e-13, 1e-12)
_REF_MIN_N = 64
_REF_MAX_N = 4096
_REF_FACTORS = (4, 2)
_PARAMS = PHYSICAL

Point = tuple[float, float, float, float, float, float, float, float]
Progress = Callable[[int, int], None]


@dataclass(frozen=True)
class Rung:
    """One tolerance of the ladder: estimated and actual errors (absolute,
    the largest over the case's points) and the time per stage."""

    tol: float
    collocation_n: int
    """Largest collocation N over the points."""
    kernel_tables: int
    """k1 kernel tables built in the cold run (the kernel's quadrature nodes
    are not exposed by the core; this counts the tables)."""
    error_estimate: float
    """Largest reported error estimate of the contact ends
    (ContactSolution.error_estimate; of a/h for a symmetric contact)."""
    error_a: float
    """Largest actual error of a contact end: max |x_end - reference| over
    both ends of ``contact_interval`` (= |a/h - reference| for a symmetric
    contact)."""
    error_p0: float
    """Largest actual |p0 - reference| (P/h)."""
    stress_error_estimate: float
    """Largest reported sigma_x error bound
    (ContactSolution.stress_error_estimate)."""
    error_top_tensile: float
    """Actual error of the top-surface tensile sigma_x peak (P/h)."""
    error_bottom_tensile: float
    """Actual error of the bottom tensile sigma_x peak (P/h)."""
    bounded: bool
    """Every point's actual contact-end error is within its own estimate, and
    every peak's error within that peak's own bound (``StressPeaks.error_bound``:
    the stress estimate plus the peak search's uncertainty)."""
    stages: Mapping[str, float]
    """Cold seconds per stage; they sum to ``seconds``."""
    seconds: float
    """Cold time (kernel cache cleared first)."""
    warm_seconds: float
    """The same run again with the kernel tables cached."""
    peak_error_bound: float = math.nan
    """Largest bound the sigma_x peaks carry (``StressPeaks.error_bound``):
    ``stress_error_estimate`` plus the peak search's uncertainty. The search
    of the asymmetric solver's peaks stops at tol relative to the centre stress,
    so at loose tols this, not the stress estimate, bounds the peak errors."""
    failure: str = ""
    """Why this rung could not be computed ("" if it was)."""


@dataclass(frozen=True)
class AccuracyReport:
    """The ladder for one case or scene."""

    name: str
    scene: Scene
    """The scene run (for a single case: its contact width, at tol 1e-8)."""
    points: int
    """Contact solutions compared per rung."""
    peak_points: int
    """Configurations whose sigma_x peaks are compared."""
    reference: str
    """How the reference was computed."""
    rungs: tuple[Rung, ...]
    stage_names: tuple[str, ...] = field(default=())

    def columns(self) -> dict[str, FloatArray]:
        """The table as columns (what ``write_csv`` writes)."""
        ok = self.rungs

        def col(get: Callable[[Rung], float]) -> FloatArray:
            return np.array([get(r) for r in ok], dtype=np.float64)

        out: dict[str, FloatArray] = {
            "tol": col(lambda r: r.tol),
            "collocation_n": col(lambda r: r.collocation_n),
            "kernel_tables": col(lambda r: r.kernel_tables),
            "error_estimate_a": col(lambda r: r.error_estimate),
            "error_a": col(lambda r: r.error_a),
            "error_p0": col(lambda r: r.error_p0),
            "stress_error_estimate": col(lambda r: r.stress_error_estimate),
            "peak_error_bound": col(lambda r: r.peak_error_bound),
            "error_top_tensile": col(lambda r: r.error_top_tensile),
            "error_bottom_tensile": col(lambda r: r.error_bottom_tensile),
            "bounded": col(lambda r: float(r.bounded)),
            "cold_seconds": col(lambda r: r.seconds),
            "warm_seconds": col(lambda r: r.warm_seconds),
        }
        for name in self.stage_names:
            out[f"cold_{name}_seconds"] = np.array(
                [r.stages.get(name, math.nan) for r in ok], dtype=np.float64
            )
        return out


def _key(p: Mapping[str, float]) -> Point:
    """The parameters of a point (damping, kp and friction 0.0 when not
    given: the paper's model)."""
    return (
        p["vstar"],
        p.get("kw", NO_SPRINGS),
        p["radius"],
        p["load"],
        p["nu"],
        p.get("damping", 0.0),
        p.get("kp", 0.0),
        p.get("friction", 0.0),
    )


def _solve_point(
    key: Point,
    tol: float,
    n: int | None = None,
    profile: PunchProfile | None = None,
    train: Sequence[Punch] = (),
    medium: Medium | None = None,
) -> ContactSolution:
    """The point ``key`` (a cylinder of its radius, or ``profile``; or the
    punches ``train`` on its layer; on ``medium``'s sublayers when given, on
    the point's springs or the medium's half-space)."""
    vstar, kw, radius, load, nu, damping, kp, friction = key
    if train:
        return solve_punches(
            train, vstar=vstar, kw=kw, nu=nu, kp=kp, damping=damping, tol=tol, n=n
        )
    args: dict[str, Any] = {
        "vstar": vstar,
        "radius": radius if profile is None else None,
        "profile": profile,
        "load": load,
        "friction": friction,
        "tol": tol,
        "n": n,
    }
    if medium is None:
        args.update(kw=kw, nu=nu, damping=damping, kp=kp)
    else:
        springs = {"kw": kw, "kp": kp, "damping": damping}
        here = medium if kw == NO_SPRINGS else point_medium(medium, springs)
        args.update(here.solve_args())
    # As a scene solves it: several zones where the single contact separates
    # (their ends are then the ends compared), else the single contact,
    # flagged when unphysical.
    found: ContactSolution
    try:
        found = solve(**args)
    except UnphysicalContactError:
        found = solve(**args, allow_unphysical=True)
    return found


def _reference(
    key: Point,
    profile: PunchProfile | None = None,
    train: Sequence[Punch] = (),
    medium: Medium | None = None,
) -> tuple[ContactSolution, int, float]:
    """The reference solution: fixed N = max(64, 4 N_auto) at tol 1e-14 (or
    1e-13, 1e-12 if tighter tolerances are out of reach). If the solver does
    not take that N (each solver has its largest size: 4096, the asymmetric one
    1024), 2 N_auto, the refusal naming ``n``."""
    last: MovingPunchError | None = None
    for tol in _REF_TOLS:
        try:
            auto = _solve_point(key, tol, profile=profile, train=train, medium=medium)
        except MovingPunchError as exc:
            last = exc
            continue
        sizes = [
            min(max(_REF_MIN_N, k * auto.collocation_n), _REF_MAX_N)
            for k in _REF_FACTORS
        ]
        for n in dict.fromkeys(sizes):
            try:
                return _solve_point(key, tol, n, profile, train, medium), n, tol
            except InvalidParameterError as exc:
                if exc.parameter != "n":
                    raise
                last = exc
            except MovingPunchError as exc:
                last = exc
                break
    assert last is not None
    raise last


def _end_error(s: ContactSolution, ref: ContactSolution) -> float:
    """The larger error of the two contact ends (x_back, x_front)."""
    # Every zone's ends (one zone: the contact's); a different number of
    # zones is no agreement at all.
    ends = [x for zone in s.contact_zones for x in zone]
    refs = [x for zone in ref.contact_zones for x in zone]
    if len(ends) != len(refs):
        return math.inf
    return max(abs(x - r) for x, r in zip(ends, refs, strict=True))


def _timed_peaks(
    sols: Mapping[Point, ContactSolution], base: Sequence[Point]
) -> tuple[dict[Point, StressPeaks], float]:
    """The sigma_x peaks of the base configurations, and the seconds taken."""
    t0 = time.perf_counter()
    peaks = {k: sols[k].stress_peaks() for k in base if k in sols}
    return peaks, time.perf_counter() - t0


@dataclass
class _Target:
    """A case or a scene: how to run one rung and which points it solves."""

    name: str
    scene: Scene
    single: bool

    def run(
        self, tol: float
    ) -> tuple[dict[Point, ContactSolution], list[Point], float, dict[str, float], int]:
        """(solutions by point, base points, seconds, stages, kernel tables)."""
        if self.single:
            key = _key(_train_params(self.scene))
            s = _solve_point(
                key,
                tol,
                profile=self.scene.profile,
                train=self.scene.punches,
                medium=self.scene.medium,
            )
            parts = {name: float(s.stage_times.get(name, 0.0)) for name in CORE_STAGES}
            return {key: s}, [key], s.elapsed, parts, s.kernel_builds
        scene = replace(self.scene, tol=tol)
        result = scene.run(jobs=1, keep_solutions=True)
        sols = {_key(_params_of(s)): s for s in result.solutions}
        base = [_key(scene.point(v)) for v in scene.curve_values()]
        stages: dict[str, float] = {}
        for st in result.stages:
            if st.name == "contact":
                continue  # its parts are listed: critical_speed ... checks
            stages[st.name] = stages.get(st.name, 0.0) + st.seconds
        contact = sum(st.seconds for st in result.stages if st.name == "contact")
        core = sum(stages.get(n, 0.0) for n in CORE_STAGES)
        stages["contact_other"] = max(contact - core, 0.0)
        listed = sum(stages.values())
        stages["other"] = max(result.total_seconds - listed, 0.0)
        total = sum(stages.values())
        return sols, base, total, stages, result.kernel_tables


def _params_of(s: ContactSolution) -> dict[str, float]:
    """The point's parameters, through the contract's fields (no kw under a
    half-space base: the scene's points have none)."""
    out = {name: float(getattr(s, name)) for name in _PARAMS}
    if isinstance(s.medium.base, HalfSpace):
        del out["kw"]
    return out


def _train_params(scene: Scene) -> dict[str, float]:
    """A scene's parameters; with punches, their total load and the first
    punch's radius stand for ``load`` and ``radius`` (the key of its one
    point)."""
    if not scene.punches:
        return dict(scene.params)
    return {
        **scene.params,
        "radius": scene.punches[0].profile.nominal_radius,
        "load": sum(p.load for p in scene.punches),
    }


def _target(
    target: Scene | Mapping[str, float] | str | Path | None,
    profile: PunchProfile | None = None,
    medium: Medium | None = None,
) -> _Target:
    if target is None:
        target = FIG4_CASE
    if isinstance(target, (str, Path)):
        scene = load_scene(target)
        # A train's scene: its punches as written (one configuration; its
        # sweep is not re-run).
        return _Target(scene.name or str(target), scene, single=bool(scene.punches))
    if isinstance(target, Scene):
        return _Target(target.name or "scene", target, single=bool(target.punches))
    params = {name: float(target[name]) for name in _PARAMS if name in target}
    if medium is None:
        params.setdefault("nu", 0.2)
    else:
        # The medium fixes nu (its top sublayer's) and the springs (none
        # under a half-space): the scene takes them from it.
        for name in ("nu", "kw", "kp", "damping"):
            params.pop(name, None)
    scene = Scene(
        params=params,
        profile=profile,
        medium=medium,
        outputs={"contact_width": OutputSpec("contact_width")},
        name="case",
        description="one parameter set: solve and the sigma_x peaks",
    )
    name = (
        "fig4-case"
        if profile is None and _key(scene.params) == _key(FIG4_CASE)
        else "case"
    )
    return _Target(name, replace(scene, name=name), single=True)


def accuracy_report(
    target: Scene | Mapping[str, float] | str | Path | None = None,
    tols: Sequence[float] = LADDER,
    *,
    progress: Progress | None = None,
    cancelled: Callable[[], bool] | None = None,
    profile: PunchProfile | None = None,
    medium: Medium | None = None,
) -> AccuracyReport | None:
    """The accuracy ladder of ``target``: None (the paper's Fig. 4 case), a
    parameter mapping (vstar, kw, radius, load, optional nu, damping, kp and
    friction), a
    ``Scene`` (damped points included), or
    a scene file / bundled scene name. Each rung is run cold (the kernel
    cache cleared first: this empties the process-wide cache) and then warm.
    Returns None if ``cancelled()`` turns true. ``profile``: the punch of
    a parameter mapping (a scene carries its own; docs/theory.md section 13).
    ``medium``: the medium of a parameter mapping (``movingpunch.Medium``;
    it fixes nu and the springs, so the mapping's nu, kw, kp and damping
    are not read; a scene carries its own).
    """
    report = progress or (lambda done, total: None)
    stop = cancelled or (lambda: False)
    tgt = _target(target, profile, medium)
    ladder = [float(t) for t in tols]
    total = len(ladder)
    # The points are those of the first rung that runs (the same set at every
    # tol: a scene plans its points from the parameters alone); the reference
    # is computed for them once.
    rungs: list[Rung] = []
    refs: dict[Point, ContactSolution] = {}
    ref_peaks: dict[Point, StressPeaks] = {}
    ref_text = ""
    stage_names: list[str] = []
    for i, tol in enumerate(ladder):
        if stop():
            return None
        clear_kernel_cache()
        try:
            sols, base, seconds, stages, tables = tgt.run(tol)
            # A scene whose sweep tabulates peaks has its own stress_peaks.
            own = "stress_peaks_report" if "stress_peaks" in stages else "stress_peaks"
            peaks, stages[own] = _timed_peaks(sols, base)
            seconds += stages[own]
            warm_sols, warm_base, warm, _, _ = tgt.run(tol)
            warm += _timed_peaks(warm_sols, warm_base)[1]
        except MovingPunchError as exc:
            rungs.append(_failed(tol, exc))
            report(i + 1, total)
            continue
        if not sols:
            raise InvalidParameterError(
                f"{tgt.name}: the scene solves no contact (its outputs need "
                "none), so there is no accuracy to measure; add contact_width"
            )
        if not refs:
            ref_n: list[int] = []
            ref_tol: list[float] = []
            for k in sols:
                ref, n, rtol = _reference(
                    k, tgt.scene.profile, tgt.scene.punches, tgt.scene.medium
                )
                refs[k] = ref
                ref_n.append(n)
                ref_tol.append(rtol)
            for k in base:
                if k in refs:
                    ref_peaks[k] = refs[k].stress_peaks()
            ref_text = (
                f"fixed N = {min(ref_n)}..{max(ref_n)} at tol {max(ref_tol):.0e}"
                if min(ref_n) != max(ref_n)
                else f"fixed N = {ref_n[0]} at tol {max(ref_tol):.0e}"
            )
        for name in stages:
            if name not in stage_names:
                stage_names.append(name)
        rungs.append(
            _rung(tol, sols, peaks, refs, ref_peaks, stages, seconds, warm, tables)
        )
        report(i + 1, total)
    return AccuracyReport(
        name=tgt.name,
        scene=tgt.scene,
        points=len(refs),
        peak_points=len(ref_peaks),
        reference=ref_text or "none (every rung failed)",
        rungs=tuple(rungs),
        stage_names=tuple(stage_names),
    )


def _failed(tol: float, exc: BaseException) -> Rung:
    nan = math.nan
    return Rung(
        tol=tol,
        collocation_n=0,
        kernel_tables=0,
        error_estimate=nan,
        error_a=nan,
        error_p0=nan,
        stress_error_estimate=nan,
        error_top_tensile=nan,
        error_bottom_tensile=nan,
        bounded=False,
        stages={},
        seconds=nan,
        warm_seconds=nan,
        failure=" ".join(str(exc).split()) or type(exc).__name__,
    )


def _rung(
    tol: float,
    sols: Mapping[Point, ContactSolution],
    peaks: Mapping[Point, StressPeaks],
    refs: Mapping[Point, ContactSolution],
    ref_peaks: Mapping[Point, StressPeaks],
    stages: Mapping[str, float],
    seconds: float,
    warm: float,
    tables: int,
) -> Rung:
    ea = {k: _end_error(s, refs[k]) for k, s in sols.items() if k in refs}
    ep0 = [abs(s.p0 - refs[k].p0) for k, s in sols.items() if k in refs]
    top = [abs(p.top_tensile - ref_peaks[k].top_tensile) for k, p in peaks.items()]
    bot = [
        abs(p.bottom_tensile - ref_peaks[k].bottom_tensile) for k, p in peaks.items()
    ]
    stress_est = [sols[k].stress_error_estimate for k in peaks]
    # The actual error is known only to within the reference's own estimate
    # (at its large fixed N round-off can dominate: a rounded flat with
    # friction at N = 768 estimates 6e-10 and lies 4e-13 from the N = 16..512
    # solutions, which agree to 3e-14).
    bounded = all(
        ea[k] <= sols[k].error_estimate + refs[k].error_estimate for k in ea
    ) and all(
        max(t, b) <= p.error_bound + ref_peaks[k].error_bound
        for (k, p), t, b in zip(peaks.items(), top, bot, strict=True)
    )
    return Rung(
        tol=tol,
        collocation_n=max(s.collocation_n for s in sols.values()),
        kernel_tables=tables,
        error_estimate=max(s.error_estimate for s in sols.values()),
        error_a=max(ea.values(), default=math.nan),
        error_p0=max(ep0, default=math.nan),
        stress_error_estimate=max(stress_est, default=math.nan),
        peak_error_bound=max((p.error_bound for p in peaks.values()), default=math.nan),
        error_top_tensile=max(top, default=math.nan),
        error_bottom_tensile=max(bot, default=math.nan),
        bounded=bounded,
        stages=dict(stages),
        seconds=seconds,
        warm_seconds=warm,
    )


# ----------------------------------------------------------------------------
# Showing and saving
# ----------------------------------------------------------------------------


def _e(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x:.1e}"


def _ms(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x * 1e3:.2f}"


HEADER = (
    "tol",
    "N",
    "tables",
    "est a/h",
    "err a/h",
    "err p0",
    "est σx",
    "est pk",
    "err σx top",
    "err σx bot",
    "ok",
    "cold ms",
    "warm ms",
)


def table_rows(report: AccuracyReport) -> list[tuple[str, ...]]:
    """The rows of the table (strings), one per rung, in HEADER's order (a
    failed rung: its tol and the reason)."""
    rows: list[tuple[str, ...]] = []
    for r in report.rungs:
        if r.failure:
            rows.append((f"{r.tol:.0e}", "failed: " + r.failure[:60]))
            continue
        rows.append(
            (
                f"{r.tol:.0e}",
                str(r.collocation_n),
                str(r.kernel_tables),
                _e(r.error_estimate),
                _e(r.error_a),
                _e(r.error_p0),
                _e(r.stress_error_estimate),
                _e(r.peak_error_bound),
                _e(r.error_top_tensile),
                _e(r.error_bottom_tensile),
                "yes" if r.bounded else "NO",
                _ms(r.seconds),
                _ms(r.warm_seconds),
            )
        )
    return rows


def format_table(report: AccuracyReport, *, stages: bool = True) -> str:
    """The ladder as an aligned text table, then the cold seconds per stage."""
    head = [
        f"Accuracy against time: {report.name} ({report.points} contact "
        f"solution(s), σx peaks of {report.peak_points})",
        f"reference: {report.reference}; errors are absolute (a/h: the worse "
        "contact end; p0, σx: P/h); est pk: the peaks' own bound; "
        "cold: kernel cache cleared; tables: k1 kernel tables built",
        "",
    ]
    rows = [HEADER, *table_rows(report)]
    widths = [
        max(len(r[i]) for r in rows if len(r) > i and len(r) == len(HEADER))
        for i in range(len(HEADER))
    ]
    lines = []
    for r in rows:
        if len(r) != len(HEADER):
            lines.append("  ".join(r))
            continue
        lines.append("  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)))
    out = head + lines
    if stages and report.stage_names:
        names = list(report.stage_names)
        out += ["", "Cold time per stage (ms)"]
        srows = [("tol", *names)]
        for rung in report.rungs:
            if rung.failure:
                continue
            srows.append(
                (f"{rung.tol:.0e}", *(_ms(rung.stages.get(n, math.nan)) for n in names))
            )
        sw = [max(len(r[i]) for r in srows) for i in range(len(srows[0]))]
        out += [
            "  ".join(c.rjust(w) for c, w in zip(r, sw, strict=True)) for r in srows
        ]
    return "\n".join(out)


def plot_series(
    report: AccuracyReport,
) -> list[tuple[str, list[float], list[float]]]:
    """(label, cold seconds, error) of each error series, positive errors
    only (a log-log plot cannot show an exact zero). A label's first letter
    is its marker."""
    series = []
    for label, name in (
        ("a  a/h", "error_a"),
        ("p  p0", "error_p0"),
        ("t  σx top", "error_top_tensile"),
        ("b  σx bottom", "error_bottom_tensile"),
        ("e  est a/h", "error_estimate"),
    ):
        pts = [
            (r.seconds, float(getattr(r, name)))
            for r in report.rungs
            if not r.failure and 0 < float(getattr(r, name)) < math.inf
        ]
        if pts:
            series.append((label, [p[0] for p in pts], [p[1] for p in pts]))
    return series


def ascii_plot(
    report: AccuracyReport, *, width: int = 80, height: int = 22, color: bool = False
) -> str:
    """A log-log plotext plot of the actual errors against the cold time;
    its legend (each series' marker letter) below the plot, outside the
    data area, wrapped at ``width``."""
    plt: Any = importlib.import_module("plotext")
    series = plot_series(report)
    legend = textwrap.wrap(
        "markers: "
        + ", ".join(label.replace("  ", " = ", 1) for label, _, _ in series),
        max(width, 20),
    )
    plt.clear_figure()
    plt.plotsize(width, max(height - len(legend), 6))
    if not color:
        plt.theme("clear")
    lo, hi = math.inf, -math.inf
    for label, x, y in series:
        ly = [math.log10(v) for v in y]
        lo, hi = min(lo, *ly), max(hi, *ly)
        plt.scatter([math.log10(v) for v in x], ly, marker=label[0])
    if math.isfinite(lo):
        ticks = list(range(math.floor(lo), math.ceil(hi) + 1, 2))
        plt.yticks(ticks, [f"1e{t}" for t in ticks])
    plt.title(f"Error against cold time: {report.name} (log-log)")
    plt.xlabel("log10 seconds (cold)")
    plt.ylabel("absolute error")
    text = str(plt.build()).rstrip("\n")
    plt.clear_figure()
    text = text if color else str(plt.uncolorize(text))
    return "\n".join([text, *legend]) if series else text


def render_csv(report: AccuracyReport) -> tuple[str, bytes]:
    """(file name, content) of the ladder's CSV: ``<name>-accuracy.csv``
    (the name through ``safe_name``), ``#`` metadata lines (the version, the
    reference, the columns and the scene as TOML, as scene exports have;
    ``movingpunch.scene.read_csv`` reads it), then numbers only
    (``np.loadtxt(path, delimiter=",")``)."""
    columns = report.columns()
    lines = [
        f"# movingpunch_version: {version()}",
        f"# scene_name: {report.scene.name}",
        "# output: accuracy",
        f"# title: accuracy against time ({report.name})",
        f"# reference: {report.reference}",
        "# columns: " + ",".join(columns),
        "# scene:",
    ]
    lines += [
        f"#   {line}" if line else "#" for line in report.scene.to_toml().splitlines()
    ]
    arrays = list(columns.values())
    for i in range(len(report.rungs)):
        lines.append(",".join(repr(float(a[i])) for a in arrays))
    name = f"{safe_name(report.name)}-accuracy.csv"
    return name, ("\n".join(lines) + "\n").encode("utf-8")


def write_csv(report: AccuracyReport, out_dir: str | Path) -> Path:
    """Writes ``render_csv(report)`` into ``out_dir`` (created if missing)
    atomically (``movingpunch.outputs.publish``); returns its path."""
    (path,) = publish(out_dir, [render_csv(report)])
    return path
