"""Running a scene: plan the minimal work, do it once, record every stage.

The contact solve is shared by every output of a curve; sweep points that
share (vstar, kw, nu, tol) share the k1 kernel (the core caches it per
process); and because a/h, p/(P/h) and sigma/(P/h) depend on radius and load
only through lambda = radius * load, points with equal (vstar, kw, nu, tol,
lambda) are solved once (displacements and the indentation scale with the
load: v = load * V(x; lambda)). The drag of a damped point scales like
1/radius at fixed lambda (drag = int p x/R dx / P).

Points with damping > 0 (docs/damped.md) are solved by the damped solver:
their contact is (-b, a), they have a drag, and stresses at y/h > -1e-3 are
evaluated at y/h = -1e-3 (``DAMPED_MAX_Y``).
"""

from __future__ import annotations

import contextlib
import importlib
import math
import multiprocessing
import multiprocessing.process
import os
import signal
import threading
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from multiprocessing import resource_tracker
from multiprocessing.connection import Connection
from multiprocessing.connection import wait as connection_wait
from typing import Any

import numpy as np
import numpy.typing as npt

from movingpunch.damped import DampedSolution
from movingpunch.errors import MovingPunchError
from movingpunch.fields import StressField, derived_stresses
from movingpunch.scene._spec import (
    DAMPED_MAX_Y,
    PEAK_QUANTITIES,
    Scene,
    critical_speed,
)
from movingpunch.solver import Solution, rayleigh_vstar, result_warnings, solve

__all__ = [
    "Curve",
    "MissingExtraError",
    "OutputData",
    "SceneResult",
    "Stage",
    "SweepTable",
    "WorkerError",
    "run_scene",
]

FloatArray = npt.NDArray[np.float64]

AnySolution = Solution | DampedSolution
"""A contact solution: undamped, or on a damped foundation (damping > 0)."""

# Stage names of the core solve (Solution.stage_times), nested in "contact".
CORE_STAGES = ("critical_speed", "kernel", "width", "checks")
_TABLES = "#kernel_tables"  # carried with the stage records from workers

DASK_CONNECT_TIMEOUT = 20.0
"""Seconds to wait for a Dask scheduler before giving up."""


class MissingExtraError(MovingPunchError, ImportError):
    """An optional dependency (an extra of the package) is not installed."""


@dataclass(frozen=True)
class Stage:
    """One kind of work a run did: ``count`` times, ``seconds`` in total.

    ``contact`` counts contact solves; ``critical_speed``, ``kernel``,
    ``width`` and ``checks`` are the parts of those solves (``kernel`` counts
    kernel tables built, not reused); the others are the outputs' evaluations.
    """

    name: str
    seconds: float
    count: int


class _Stages:
    def __init__(self) -> None:
        self._data: dict[str, list[float]] = {}
        self.kernel_tables = 0

    def add(self, name: str, seconds: float, count: int = 1) -> None:
        entry = self._data.setdefault(name, [0.0, 0.0])
        entry[0] += seconds
        entry[1] += count

    def add_solution(self, s: AnySolution) -> None:
        self.add("contact", s.elapsed)
        times = getattr(s, "stage_times", None) or {}
        builds = int(getattr(s, "kernel_builds", 0))
        self.kernel_tables += builds
        for name in CORE_STAGES:
            if name in times:
                # kernel: counts the solves that had to build a table.
                count = (1 if builds else 0) if name == "kernel" else 1
                self.add(name, float(times[name]), count)

    def merge(self, records: Sequence[tuple[str, float, int]]) -> None:
        for name, seconds, count in records:
            if name == _TABLES:
                self.kernel_tables += count
            else:
                self.add(name, seconds, count)

    def records(self) -> list[tuple[str, float, int]]:
        out = [(n, v[0], int(v[1])) for n, v in self._data.items()]
        return [*out, (_TABLES, 0.0, self.kernel_tables)]

    def stages(self) -> list[Stage]:
        return [Stage(n, s, c) for n, s, c in self.records() if n != _TABLES]


class ClusterError(MovingPunchError, RuntimeError):
    """The Dask scheduler could not be reached or a task failed on it."""


@dataclass(frozen=True)
class Curve:
    """One curve of an output or a sweep: ``y`` against ``x``; ``value`` is
    the vary parameter's value (None without ``vary``), ``label`` names it."""

    label: str
    value: float | None
    x: FloatArray
    y: FloatArray


@dataclass(frozen=True)
class OutputData:
    """The data of one output: its curves (one per vary value), its stress
    fields (``stress_field`` only) and ``columns``, the table written to CSV
    and JSON (column name -> 1-D array, all of one length)."""

    name: str
    title: str
    x_label: str
    y_label: str
    columns: Mapping[str, FloatArray]
    curves: tuple[Curve, ...] = ()
    fields: tuple[tuple[str, StressField], ...] = ()


@dataclass(frozen=True)
class SweepTable:
    """Scalar quantities against the sweep parameter, one row per vary value.

    ``data[q]`` and ``valid`` are shaped (len(labels), len(values)); a point
    whose solve failed holds NaN and its message in ``errors[(i, j)]``.
    """

    param: str
    values: FloatArray
    quantities: tuple[str, ...]
    labels: tuple[str, ...]
    vary_param: str | None
    vary_values: tuple[float | None, ...]
    data: Mapping[str, FloatArray]
    valid: npt.NDArray[np.bool_]
    errors: Mapping[tuple[int, int], str] = field(default_factory=dict)

    def curves(self, quantity: str) -> tuple[Curve, ...]:
        """One curve of ``quantity`` against the sweep parameter per vary value."""
        return tuple(
            Curve(label, value, self.values, self.data[quantity][i])
            for i, (label, value) in enumerate(
                zip(self.labels, self.vary_values, strict=True)
            )
        )

    def columns(self) -> dict[str, FloatArray]:
        """The table as columns: the parameter, then each quantity (and
        ``valid``) per vary value, named ``quantity[label]``."""
        cols: dict[str, FloatArray] = {self.param: self.values}
        for i, label in enumerate(self.labels):
            for q in self.quantities:
                cols[_col(q, label)] = self.data[q][i]
            cols[_col("valid", label)] = self.valid[i].astype(np.float64)
        return cols


def _col(name: str, label: str) -> str:
    return f"{name}[{label}]" if label else name


@dataclass(frozen=True)
class SceneResult:
    """What a scene run computed, and the record of the work it did."""

    scene: Scene
    outputs: Mapping[str, OutputData]
    sweep: SweepTable | None
    solutions: tuple[AnySolution, ...]
    """Contact solutions computed in this process (sweep points solved in
    worker processes or on Dask return their numbers only)."""
    stages: list[Stage]
    total_seconds: float
    """Wall-clock time of the whole run."""
    jobs: int = 1
    """Worker processes used for the sweep (1: this process; 0: Dask)."""
    kernel_tables: int = 0
    """k1 kernel tables built in all (the ``kernel`` stage counts the solves
    that built any: a first solve may build two as it widens the table to the
    contact it finds)."""
    warnings: tuple[str, ...] = ()
    """Every warning of every solved point (``Solution.warnings``: a
    requested accuracy not met), each prefixed by the point it came from."""

    def ran(self, name: str) -> bool:
        """Whether the stage ``name`` did any work (``count > 0``)."""
        return any(s.name == name and s.count > 0 for s in self.stages)

    def stage(self, name: str) -> Stage:
        """The record of stage ``name`` (count 0 if it never ran)."""
        for s in self.stages:
            if s.name == name:
                return s
        return Stage(name, 0.0, 0)


# ----------------------------------------------------------------------------
# Solving points
# ----------------------------------------------------------------------------

# vstar, kw, nu, tol, damping, lambda
_Key = tuple[float, float, float, float, float, float]


def _damping(p: Mapping[str, float]) -> float:
    return p.get("damping", 0.0)


def _key(p: Mapping[str, float], tol: float) -> _Key:
    return (p["vstar"], p["kw"], p["nu"], tol, _damping(p), p["radius"] * p["load"])


def is_damped(scene: Scene) -> bool:
    """Whether any point the scene computes has damping > 0."""
    values = [scene.params.get("damping", 0.0)]
    for part in (scene.vary, scene.sweep):
        if part is not None and part.param == "damping":
            values += list(part.values)
    return any(v > 0.0 for v in values)


def _label(param: str | None, value: float | None) -> str:
    if param is None or value is None:
        return ""
    return f"{param}={'inf' if math.isinf(value) else format(value, '.6g')}"


def _solve(p: Mapping[str, float], tol: float, stages: _Stages) -> AnySolution:
    s = solve(
        vstar=p["vstar"],
        kw=p["kw"],
        radius=p["radius"],
        load=p["load"],
        nu=p["nu"],
        tol=tol,
        allow_unphysical=True,
        damping=_damping(p),
    )
    stages.add_solution(s)
    return s


def _quantities(
    s: AnySolution, want_peaks: bool, stages: _Stages, warnings: list[str]
) -> dict[str, float]:
    """The sweep's numbers of one solved point; the stress peak search's
    warnings (``StressPeaks.warnings``) are appended to ``warnings``."""
    q: dict[str, float] = {
        "a": s.a,
        "min_pressure": s.min_pressure,
        "critical_vstar": s.critical_vstar,
        "phi1": s.phi1,
        "valid": 1.0 if s.valid else 0.0,
        "load": s.load,
        "radius": s.radius,
    }
    if isinstance(s, DampedSolution):
        # Validation refuses the indentation for damped points.
        q.update(
            p0=float(s.pressure(0.0)),
            indentation=math.nan,
            drag=s.drag,
            contact_start=s.contact_interval[0],
            contact_end=s.contact_interval[1],
        )
    else:
        q.update(
            p0=s.p0,
            indentation=s.indentation,
            drag=0.0,
            contact_start=-s.a,
            contact_end=s.a,
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
    names = ["vstar", "kw", "radius", "load", "nu"]
    if _damping(p) > 0.0:
        names.append("damping")
    return ", ".join(f"{n}={p[n]:.6g}" for n in names)


def _solve_group(task: Mapping[str, Any]) -> dict[str, Any]:
    """Solves one group of sweep points sharing (vstar, kw, nu, tol, damping), in
    descending lambda (the first solve builds the widest kernel; the rest
    reuse it). Runs in a worker process or on a Dask worker."""
    stages = _Stages()
    results: list[dict[str, float] | str] = []
    warnings: list[list[str]] = []
    for radius, load in task["points"]:
        p = {
            "vstar": task["vstar"],
            "kw": task["kw"],
            "nu": task["nu"],
            "damping": task["damping"],
            "radius": radius,
            "load": load,
        }
        try:
            s = _solve(p, task["tol"], stages)
            found = list(result_warnings(s))
            results.append(_quantities(s, task["peaks"], stages, found))
            warnings.append(found)
        except MovingPunchError as exc:
            results.append(str(exc))
            warnings.append([])
    return {"results": results, "stages": stages.records(), "warnings": warnings}


# ----------------------------------------------------------------------------
# The run
# ----------------------------------------------------------------------------


@dataclass
class _Run:
    scene: Scene
    stages: _Stages = field(default_factory=_Stages)
    memo: dict[_Key, AnySolution] = field(default_factory=dict)
    warnings: dict[_Key, list[str]] = field(default_factory=dict)
    done: int = 0
    total: int = 0
    progress: Callable[[int, int], None] | None = None

    def tick(self, n: int = 1) -> None:
        self.done += n
        if self.progress is not None:
            self.progress(self.done, self.total)

    def solution(self, p: Mapping[str, float]) -> AnySolution:
        key = _key(p, self.scene.tol)
        if key not in self.memo:
            self.memo[key] = _solve(p, self.scene.tol, self.stages)
            self.note_warnings(key, p, result_warnings(self.memo[key]))
            self.tick()
        return self.memo[key]

    def note_warnings(
        self, key: _Key, p: Mapping[str, float], found: Sequence[str]
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


def _needs_contact(scene: Scene) -> bool:
    return any(kind != "critical_speed" for kind in scene.outputs)


def run_scene(
    scene: Scene,
    *,
    jobs: int | None = 1,
    progress: Callable[[int, int], None] | None = None,
    dask: str | None = None,
) -> SceneResult:
    """Runs ``scene`` (see ``Scene.run``)."""
    if jobs is not None and (
        isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1
    ):
        raise ValueError(
            f"jobs must be None (all cores) or an integer >= 1, got {jobs!r}"
        )
    n_jobs = _default_jobs() if jobs is None else jobs
    t_start = time.perf_counter()
    run = _Run(scene, progress=progress)

    base_points = (
        [scene.point(v) for v in scene.curve_values()] if _needs_contact(scene) else []
    )
    base_keys = {_key(p, scene.tol) for p in base_points}
    sweep_plan = _plan_sweep(scene) if scene.sweep is not None else None
    remote = sweep_plan is not None and _use_workers(
        sweep_plan, n_jobs, dask, auto_jobs=jobs is None
    )
    sweep_keys = set(sweep_plan.keys) if sweep_plan is not None else set()
    # Points solved elsewhere are solved again here if an output needs them.
    run.total = len(sweep_keys) + len(base_keys if remote else base_keys - sweep_keys)

    sweep_table: SweepTable | None = None
    used_jobs = 1
    if sweep_plan is not None:
        sweep_table, used_jobs = _run_sweep(run, sweep_plan, n_jobs, dask, remote)

    outputs: dict[str, OutputData] = {}
    solutions = {
        v: run.solution(p)
        for v, p in zip(scene.curve_values(), base_points, strict=False)
    }
    for kind, spec in scene.outputs.items():
        outputs[kind] = _OUTPUTS[kind](run, spec, solutions)

    return SceneResult(
        scene=scene,
        outputs=outputs,
        sweep=sweep_table,
        solutions=tuple(run.memo.values()),
        stages=run.stages.stages(),
        total_seconds=time.perf_counter() - t_start,
        jobs=used_jobs,
        kernel_tables=run.stages.kernel_tables,
        warnings=tuple(w for found in run.warnings.values() for w in found),
    )


# ----------------------------------------------------------------------------
# Sweeps
# ----------------------------------------------------------------------------


@dataclass
class _SweepPlan:
    points: list[list[dict[str, float]]]  # [curve][grid] -> parameters
    keys: list[_Key]  # unique keys, in solve order
    groups: dict[tuple[float, ...], list[_Key]]
    representative: dict[_Key, dict[str, float]]
    want_peaks: bool
    damped: bool


def _plan_sweep(scene: Scene) -> _SweepPlan:
    assert scene.sweep is not None
    sw = scene.sweep
    points = [
        [scene.point(v, **{sw.param: x}) for x in sw.values]
        for v in scene.curve_values()
    ]
    representative: dict[_Key, dict[str, float]] = {}
    for row in points:
        for p in row:
            representative.setdefault(_key(p, scene.tol), p)
    groups: dict[tuple[float, ...], list[_Key]] = {}
    for key in representative:
        groups.setdefault(key[:5], []).append(key)
    for members in groups.values():
        members.sort(key=lambda k: -k[5])  # descending lambda: widest kernel first
    keys = [k for members in groups.values() for k in members]
    want_peaks = any(q in PEAK_QUANTITIES for q in sw.quantities)
    damped = any(k[4] > 0.0 for k in keys)
    return _SweepPlan(points, keys, groups, representative, want_peaks, damped)


# Rough serial cost, in seconds, of a sweep point whose solve builds its kernel
# table (cold) or reuses the table of the point before it (warm), of its stress
# peaks, of a damped point; and of starting one worker process (its imports).
# Measured as CPU time in fresh processes (benchmarks/bench_jobs.py): 2000
# cold points of a vstar sweep 2.3 s, of a kw sweep 3.8 s (each kw its own
# critical speed too); 20 000 warm points of a load sweep 6.5 s.
_COLD_SECONDS, _WARM_SECONDS, _PEAKS_SECONDS = 1.5e-3, 3e-4, 3e-2
_DAMPED_SECONDS = 0.7
_STARTUP_SECONDS = 0.6
# A chunk (the unit of work a worker is sent) is sized to about
# 1/_CHUNKS_PER_JOB of a worker's share, within [_CHUNK_MIN, _CHUNK_MAX]
# seconds (on Dask [_DASK_CHUNK_MIN, _DASK_CHUNK_MAX]) and _CHUNK_POINTS points.
_CHUNKS_PER_JOB = 8
_CHUNK_MIN, _CHUNK_MAX = 0.02, 0.1
_DASK_CHUNK_MIN, _DASK_CHUNK_MAX = 0.05, 1.0
_CHUNK_POINTS = 1000
# Chunks sent ahead to each worker: one computing, one queued, while more
# than _TAIL chunks per process are left; then one, so that no process idles
# at the end while a worker still holds a queued chunk.
_IN_FLIGHT = 2
_TAIL = 2
_STOP_SECONDS = 2.0  # how long stopped workers get to exit before SIGKILL

# One unit of work: (group, keys) pieces, each contiguous points of one group.
_Chunk = list[tuple[tuple[float, ...], list[_Key]]]


def _point_seconds(plan: _SweepPlan, cold: bool) -> float:
    if plan.damped:
        return _DAMPED_SECONDS
    seconds = _COLD_SECONDS if cold else _WARM_SECONDS
    return seconds + (_PEAKS_SECONDS if plan.want_peaks else 0.0)


def _sweep_seconds(plan: _SweepPlan) -> float:
    """The estimated serial time of the sweep."""
    cold, warm = _point_seconds(plan, True), _point_seconds(plan, False)
    return sum(cold + (len(m) - 1) * warm for m in plan.groups.values())


def _default_jobs() -> int:
    """The cores this process may run on."""
    affinity = getattr(os, "sched_getaffinity", None)
    if affinity is not None:
        return max(len(affinity(0)), 1)
    return os.cpu_count() or 1


def _use_workers(
    plan: _SweepPlan, n_jobs: int, dask: str | None, *, auto_jobs: bool
) -> bool:
    """Whether the sweep goes to worker processes (or Dask): never for one
    point or one job; with automatic jobs only when the estimated time saved
    pays for starting the workers."""
    if dask is not None:
        return True
    if n_jobs <= 1 or len(plan.keys) <= 1:
        return False
    saved = _sweep_seconds(plan) * (1.0 - 1.0 / n_jobs)
    return not auto_jobs or saved > _STARTUP_SECONDS


def _chunks(plan: _SweepPlan, target: float) -> list[_Chunk]:
    """The sweep's points in chunks of about ``target`` seconds, in solve
    order: a chunk holds contiguous points of one or more groups, so that a
    group split across chunks still reuses its kernel within each (the first
    point of each piece, the widest contact, builds it). A group that fits
    in a chunk is never split: the chunk is closed before it instead."""
    chunks: list[_Chunk] = []
    pieces: _Chunk = []
    seconds, count = 0.0, 0
    cold, warm = _point_seconds(plan, True), _point_seconds(plan, False)
    for group, members in plan.groups.items():
        whole = cold + (len(members) - 1) * warm
        if (
            pieces
            and whole <= target
            and (
                seconds + whole > target * (1 + 1e-9)
                or count + len(members) > _CHUNK_POINTS
            )
        ):
            chunks.append(pieces)
            pieces, seconds, count = [], 0.0, 0
        piece: list[_Key] | None = None
        for key in members:
            if piece is None:
                piece = []
                pieces.append((group, piece))
            seconds += _point_seconds(plan, cold=not piece)
            piece.append(key)
            count += 1
            if seconds >= target or count >= _CHUNK_POINTS:
                chunks.append(pieces)
                pieces, piece, seconds, count = [], None, 0.0, 0
    if pieces:
        chunks.append(pieces)
    return chunks


def _chunk_target(plan: _SweepPlan, n: int, lo: float, hi: float) -> float:
    """Seconds of work per chunk for ``n`` workers: about 1/_CHUNKS_PER_JOB
    of a worker's share within [lo, hi], and at most a worker's share (every
    worker gets a chunk)."""
    total = _sweep_seconds(plan)
    target = min(max(total / (_CHUNKS_PER_JOB * n), lo), hi)
    return min(target, total / n)


def _tasks(plan: _SweepPlan, chunk: _Chunk) -> list[dict[str, Any]]:
    """A chunk as the tasks ``_solve_chunk`` takes (plain data: it is
    pickled to a worker)."""
    return [
        {
            "vstar": group[0],
            "kw": group[1],
            "nu": group[2],
            "tol": group[3],
            "damping": group[4],
            "points": [
                (plan.representative[k]["radius"], plan.representative[k]["load"])
                for k in keys
            ],
            "peaks": plan.want_peaks,
        }
        for group, keys in chunk
    ]


def _solve_chunk(tasks: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """Solves the groups of a chunk (in a worker process or on Dask)."""
    return [_solve_group(task) for task in tasks]


def _run_sweep(
    run: _Run, plan: _SweepPlan, n_jobs: int, dask: str | None, remote: bool
) -> tuple[SweepTable, int]:
    scene = run.scene
    assert scene.sweep is not None
    values: dict[_Key, dict[str, float] | str] = {}
    if not remote:
        for key in plan.keys:
            try:
                s = run.solution(plan.representative[key])
                found: list[str] = []
                values[key] = _quantities(s, plan.want_peaks, run.stages, found)
                run.note_warnings(key, plan.representative[key], found)
            except MovingPunchError as exc:
                values[key] = str(exc)
                run.tick()
        return _sweep_table(scene, plan, values), 1

    def make_chunks(n: int, lo: float, hi: float) -> list[_Chunk]:
        return _chunks(plan, _chunk_target(plan, n, lo, hi))

    def consume(chunk: _Chunk, outs: Sequence[Mapping[str, Any]]) -> None:
        for (_, keys), out in zip(chunk, outs, strict=True):
            run.stages.merge(out["stages"])
            for key, res in zip(keys, out["results"], strict=True):
                values[key] = res
            for key, found in zip(keys, out["warnings"], strict=True):
                run.note_warnings(key, plan.representative[key], found)
        run.tick(sum(len(keys) for _, keys in chunk))

    if dask is not None:
        _dask_map(plan, make_chunks, dask, consume)
        used_jobs = 0
    else:
        chunks = make_chunks(n_jobs, _CHUNK_MIN, _CHUNK_MAX)
        used_jobs = min(n_jobs, len(chunks))
        _pool_map(plan, chunks, used_jobs, consume)
    return _sweep_table(scene, plan, values), used_jobs


# ----------------------------------------------------------------------------
# Worker processes
# ----------------------------------------------------------------------------


class WorkerError(MovingPunchError, RuntimeError):
    """A worker process ended before it finished its work, or failed."""


@contextlib.contextmanager
def _signals_deferred(*, ignore_sigint: bool = False) -> Iterator[None]:
    """SIGINT and SIGTERM wait (blocked in this thread) until the block
    ends, so that starting or stopping workers is never cut in half. With
    ``ignore_sigint`` (in the main thread only) SIGINT is also ignored
    meanwhile: a process spawned then inherits that, so a Ctrl-C, which the
    terminal sends to every process of the group, is left to the parent."""
    mask = getattr(signal, "pthread_sigmask", None)
    blocked = {signal.SIGINT, signal.SIGTERM}
    old_mask = mask(signal.SIG_BLOCK, blocked) if mask is not None else None
    main = threading.current_thread() is threading.main_thread()
    old_int = (
        signal.signal(signal.SIGINT, signal.SIG_IGN) if ignore_sigint and main else None
    )
    try:
        yield
    finally:
        if ignore_sigint and main:
            signal.signal(
                signal.SIGINT, old_int if old_int is not None else signal.SIG_DFL
            )
        if mask is not None and old_mask is not None:
            mask(signal.SIG_SETMASK, old_mask)


def _exit_with_parent(parent_alive: Connection) -> None:
    """Blocks until the parent is gone (nothing is ever sent on this pipe:
    the read ends when the parent's end closes), then ends this process."""
    with contextlib.suppress(EOFError, OSError):
        parent_alive.recv_bytes()
    os._exit(1)


def _worker_main(conn: Connection, parent_alive: Connection) -> None:
    """A worker process: solves the chunks it receives until told to stop
    (None), until its pipe closes or, at once, when the parent dies."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C
    if hasattr(signal, "pthread_sigmask"):  # blocked while the parent spawned us
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT, signal.SIGTERM})
    threading.Thread(
        target=_exit_with_parent, args=(parent_alive,), daemon=True
    ).start()
    while True:
        try:
            message = conn.recv()
        except (EOFError, OSError):
            return
        if message is None:
            return
        index, tasks = message
        try:
            reply: tuple[int, Any, str | None] = (index, _solve_chunk(tasks), None)
        except Exception as exc:  # a bug: reported by the parent
            reply = (index, None, f"{type(exc).__name__}: {exc}")
        conn.send(reply)


class _WorkerPool:
    """Spawned worker processes fed chunks over pipes.

    Never more than _IN_FLIGHT chunks are sent ahead to a worker, so nothing
    waits on thousands of futures. Each worker watches a pipe whose write end
    only this process holds: when this process dies (even by SIGKILL) the
    pipe closes and the workers exit. ``stop()`` terminates them (SIGTERM,
    then SIGKILL) and reaps them."""

    def __init__(self) -> None:
        self.context = multiprocessing.get_context("spawn")
        self.workers: list[tuple[multiprocessing.process.BaseProcess, Connection]] = []
        self.alive_r, self.alive_w = self.context.Pipe(duplex=False)

    def start(self, n: int) -> None:
        if os.name == "posix":
            # Started here, not inside the first proc.start(): starting it
            # unblocks SIGINT and SIGTERM, which _signals_deferred blocks.
            resource_tracker.ensure_running()
        for _ in range(n):
            conn, child_conn = self.context.Pipe()
            proc = self.context.Process(
                target=_worker_main,
                args=(child_conn, self.alive_r),
                name="movingpunch-worker",
                daemon=True,
            )
            with _signals_deferred(ignore_sigint=True):
                proc.start()
                self.workers.append((proc, conn))
            child_conn.close()
        self.alive_r.close()  # the workers hold it; this process needs none

    def died(self, proc: multiprocessing.process.BaseProcess) -> WorkerError:
        proc.join(1.0)
        code = proc.exitcode
        how = f"exit status {code}" if code is None or code >= 0 else f"signal {-code}"
        return WorkerError(f"a worker process ended before its work was done ({how})")

    def run(
        self,
        messages: Sequence[Any],
        consume: Callable[[int, Any], None],
        solve_here: Callable[[Any], Any] | None = None,
    ) -> None:
        """Sends ``(i, messages[i])`` to the workers and ``consume(i,
        result)`` for each result, in the order they finish. With
        ``solve_here``, this process takes the next message itself whenever
        every worker has _IN_FLIGHT: it is one of the jobs."""
        sent = 0
        in_flight = {id(conn): 0 for _, conn in self.workers}
        by_conn = {id(conn): (proc, conn) for proc, conn in self.workers}
        conns = [conn for _, conn in self.workers]
        if not conns and solve_here is None:
            raise ValueError("no worker and no solve_here")

        processes = len(conns) + (solve_here is not None)

        def feed(proc: multiprocessing.process.BaseProcess, conn: Connection) -> None:
            nonlocal sent
            while sent < len(messages) and in_flight[id(conn)] < (
                _IN_FLIGHT if len(messages) - sent > _TAIL * processes else 1
            ):
                try:
                    conn.send((sent, messages[sent]))
                except OSError:
                    raise self.died(proc) from None
                in_flight[id(conn)] += 1
                sent += 1

        def collect(timeout: float | None) -> int:
            done = 0
            for ready in connection_wait(conns, timeout):
                assert isinstance(ready, Connection)
                proc, conn = by_conn[id(ready)]
                try:
                    index, result, error = conn.recv()
                except (EOFError, OSError):
                    raise self.died(proc) from None
                if error is not None:
                    raise WorkerError(f"a worker process failed: {error}")
                in_flight[id(conn)] -= 1
                done += 1
                consume(index, result)
                feed(proc, conn)
            return done

        for proc, conn in self.workers:
            feed(proc, conn)
        remaining = len(messages)
        while remaining:
            if solve_here is not None and sent < len(messages):
                remaining -= collect(0.0) if conns else 0
                if sent < len(messages):
                    index = sent
                    sent += 1
                    consume(index, solve_here(messages[index]))
                    remaining -= 1
            else:
                remaining -= collect(None)

    def close(self) -> None:
        """Tells the workers to stop and waits for them (briefly)."""
        for _, conn in self.workers:
            with contextlib.suppress(OSError):
                conn.send(None)
        deadline = time.monotonic() + _STOP_SECONDS
        for proc, _ in self.workers:
            proc.join(max(deadline - time.monotonic(), 0.0))
        self.stop()

    def stop(self) -> None:
        """Ends every worker still running (SIGTERM; SIGKILL if one has not
        exited after _STOP_SECONDS) and reaps them all."""
        with _signals_deferred():
            alive = [proc for proc, _ in self.workers if proc.is_alive()]
            for proc in alive:
                proc.terminate()
            deadline = time.monotonic() + _STOP_SECONDS
            for proc in alive:
                proc.join(max(deadline - time.monotonic(), 0.0))
            for proc in alive:
                if proc.is_alive():
                    proc.kill()
                    proc.join(_STOP_SECONDS)
            for proc, conn in self.workers:
                conn.close()
                with contextlib.suppress(ValueError):  # not yet reaped
                    proc.close()
            self.alive_w.close()
            self.alive_r.close()


def _pool_map(
    plan: _SweepPlan,
    chunks: Sequence[_Chunk],
    n_jobs: int,
    consume: Callable[[_Chunk, Sequence[Mapping[str, Any]]], None],
) -> None:
    """Solves ``chunks`` in ``n_jobs`` processes: this one and ``n_jobs - 1``
    spawned workers (never forked: this process may hold threads, the
    core's or Dask's), passing each chunk's results to ``consume`` as they
    arrive. On any exception, a KeyboardInterrupt included, the workers are
    terminated first."""
    if n_jobs <= 1:  # one chunk: no process to start
        for chunk in chunks:
            consume(chunk, _solve_chunk(_tasks(plan, chunk)))
        return
    pool = _WorkerPool()
    finished = False
    try:
        pool.start(n_jobs - 1)
        pool.run(
            [_tasks(plan, chunk) for chunk in chunks],
            lambda i, outs: consume(chunks[i], outs),
            solve_here=_solve_chunk,
        )
        finished = True
    finally:
        if finished:
            pool.close()
        else:
            pool.stop()


# ----------------------------------------------------------------------------
# Dask
# ----------------------------------------------------------------------------


def _dask_client(distributed: Any, address: str) -> Any:
    """A client of the scheduler at ``address``; every step of connecting,
    the handshake included, within DASK_CONNECT_TIMEOUT seconds (Client's own
    ``timeout`` does not bound the handshake: a listener that accepts and
    never answers would hang it)."""
    timeout = DASK_CONNECT_TIMEOUT

    class _BoundedClient(distributed.Client):  # type: ignore[misc]
        def start(self, **kwargs: Any) -> None:
            try:
                super().start(callback_timeout=timeout, **kwargs)
            except BaseException:
                with contextlib.suppress(Exception):
                    self.close(timeout=min(timeout, _STOP_SECONDS))
                raise

    try:
        return _BoundedClient(address, timeout=timeout, set_as_default=False)
    except (OSError, TimeoutError) as exc:
        why = str(exc) or type(exc).__name__
        raise ClusterError(
            f"dask: cannot reach the scheduler at {address!r} within "
            f"{timeout:g} s: {why}"
        ) from None


def _dask_map(
    plan: _SweepPlan,
    make_chunks: Callable[[int, float, float], list[_Chunk]],
    address: str,
    consume: Callable[[_Chunk, Sequence[Mapping[str, Any]]], None],
) -> None:
    """Solves the sweep's chunks on the Dask scheduler at ``address``.

    Every wait is bounded by DASK_CONNECT_TIMEOUT: connecting; and while
    results are awaited, a stretch that long without one makes it ask the
    scheduler (within the same timeout) whether it still answers and has
    workers, and gives up with ClusterError if not."""
    try:
        distributed: Any = importlib.import_module("distributed")
    except ImportError:
        raise MissingExtraError(
            "--dask needs Dask distributed: pip install 'movingpunch[dask]'"
        ) from None
    timeout = DASK_CONNECT_TIMEOUT
    client = _dask_client(distributed, address)
    try:
        workers = _dask_workers(client, address, timeout)
        chunks = make_chunks(max(workers, 1), _DASK_CHUNK_MIN, _DASK_CHUNK_MAX)
        futures = [
            client.submit(_solve_chunk, _tasks(plan, chunk), pure=False)
            for chunk in chunks
        ]
        index = {fut.key: i for i, fut in enumerate(futures)}
        done = distributed.as_completed(futures, loop=client.loop, with_results=True)
        remaining, last = len(futures), time.monotonic()
        while remaining:
            if not done.has_ready():
                if time.monotonic() - last > timeout:
                    if _dask_workers(client, address, timeout) == 0:
                        raise ClusterError(
                            f"dask: the scheduler at {address!r} has no workers "
                            f"(no result for {timeout:g} s)"
                        )
                    last = time.monotonic()
                time.sleep(0.02)
                continue
            fut, result = next(done)
            if isinstance(result, BaseException):  # cancelled: the task was lost
                raise ClusterError(f"dask: a task was lost: {result!r}")
            remaining -= 1
            last = time.monotonic()
            consume(chunks[index[fut.key]], result)
    except (OSError, TimeoutError) as exc:
        raise ClusterError(
            f"dask: the scheduler at {address!r} failed: {exc}"
        ) from None
    finally:
        with _signals_deferred(), contextlib.suppress(Exception):
            client.close(timeout=_STOP_SECONDS)


def _dask_workers(client: Any, address: str, timeout: float) -> int:
    """The number of workers of the scheduler, asked within ``timeout``."""
    try:
        return len(client.nthreads(callback_timeout=timeout))
    except (OSError, TimeoutError) as exc:
        raise ClusterError(
            f"dask: the scheduler at {address!r} does not answer within "
            f"{timeout:g} s: {str(exc) or type(exc).__name__}"
        ) from None


def _sweep_table(
    scene: Scene, plan: _SweepPlan, values: Mapping[_Key, dict[str, float] | str]
) -> SweepTable:
    sw = scene.sweep
    assert sw is not None
    n_curves, n_grid = len(plan.points), len(sw.values)
    data = {q: np.full((n_curves, n_grid), np.nan) for q in sw.quantities}
    valid = np.zeros((n_curves, n_grid), dtype=bool)
    errors: dict[tuple[int, int], str] = {}
    for i, row in enumerate(plan.points):
        for j, p in enumerate(row):
            res = values[_key(p, scene.tol)]
            if isinstance(res, str):
                errors[(i, j)] = res
                continue
            for q in sw.quantities:
                value = res[q]
                if q == "indentation":  # v = load * V(lambda)
                    value *= p["load"] / res["load"]
                elif q == "drag":  # int p x/R dx / P at fixed lambda
                    value *= res["radius"] / p["radius"]
                data[q][i, j] = value
            valid[i, j] = bool(res["valid"])
    vary_param = scene.vary.param if scene.vary is not None else None
    return SweepTable(
        param=sw.param,
        values=np.asarray(sw.values, dtype=np.float64),
        quantities=sw.quantities,
        labels=tuple(_label(vary_param, v) for v in scene.curve_values()),
        vary_param=vary_param,
        vary_values=scene.curve_values(),
        data=data,
        valid=valid,
        errors=errors,
    )


# ----------------------------------------------------------------------------
# Outputs
# ----------------------------------------------------------------------------

_Solutions = Mapping[float | None, AnySolution]


def _curves(
    run: _Run,
    stage: str,
    solutions: _Solutions,
    x: FloatArray,
    evaluate: Callable[[AnySolution, Mapping[str, float]], FloatArray],
) -> tuple[Curve, ...]:
    scene = run.scene
    param = scene.vary.param if scene.vary is not None else None
    out = []
    for v, s in solutions.items():
        p = scene.point(v)
        with run.timed(stage):
            y = evaluate(s, p)
        out.append(Curve(_label(param, v), v, x, np.asarray(y, dtype=np.float64)))
    return tuple(out)


def _curve_columns(
    xname: str, yname: str, curves: Sequence[Curve]
) -> dict[str, FloatArray]:
    cols: dict[str, FloatArray] = {xname: curves[0].x}
    for c in curves:
        cols[_col(yname, c.label)] = c.y
    return cols


def _x_grid(
    spec_x: tuple[float, float] | None, default: tuple[float, float], n: int
) -> FloatArray:
    lo, hi = spec_x if spec_x is not None else default
    return np.linspace(lo, hi, n)


def _out_contact_width(run: _Run, spec: Any, solutions: _Solutions) -> OutputData:
    scene = run.scene
    cols: dict[str, list[float]] = {}
    if scene.vary is not None:
        cols[scene.vary.param] = []
    damped = is_damped(scene)
    names = ["a", "p0", "indentation", "valid", "error_estimate", "collocation_n"]
    if damped:  # the contact interval (-b, a) and the drag
        names[1:1] = ["contact_start", "contact_end", "drag"]
    for name in names:
        cols[name] = []
    for v, s in solutions.items():
        p = scene.point(v)
        if scene.vary is not None:
            cols[scene.vary.param].append(float(v) if v is not None else math.nan)
        cols["a"].append(s.a)
        if isinstance(s, DampedSolution):
            cols["p0"].append(float(s.pressure(0.0)))
            cols["indentation"].append(math.nan)  # not given by the damped solver
            cols["contact_start"].append(s.contact_interval[0])
            cols["contact_end"].append(s.contact_interval[1])
            # int p x/R dx / P: 1/radius at fixed lambda (shared solutions).
            cols["drag"].append(s.drag * s.radius / p["radius"])
        else:
            cols["p0"].append(s.p0)
            cols["indentation"].append(s.indentation * p["load"] / s.load)
            if damped:
                cols["contact_start"].append(-s.a)
                cols["contact_end"].append(s.a)
                cols["drag"].append(0.0)
        cols["valid"].append(1.0 if s.valid else 0.0)
        cols["error_estimate"].append(s.error_estimate)
        cols["collocation_n"].append(float(s.collocation_n))
    return OutputData(
        name="contact_width",
        title="Contact half-width",
        x_label=scene.vary.param if scene.vary is not None else "",
        y_label="a/h",
        columns={k: np.asarray(v, dtype=np.float64) for k, v in cols.items()},
    )


def _out_pressure(run: _Run, spec: Any, solutions: _Solutions) -> OutputData:
    if is_damped(run.scene):  # 1.25 x the span of every (asymmetric) contact
        ends = [e for s in solutions.values() for e in _interval(s)]
        reach = max(abs(e) for e in ends)
        default = (-1.25 * reach, 1.25 * reach)
    else:
        a_max = max(s.a for s in solutions.values())
        default = (-1.25 * a_max, 1.25 * a_max)
    x = _x_grid(spec.x, default, spec.resolved_points())
    curves = _curves(
        run, "pressure", solutions, x, lambda s, p: np.asarray(s.pressure(x))
    )
    return OutputData(
        "pressure",
        "Contact pressure",
        "x/h",
        "p/(P/h)",
        _curve_columns("x", "p", curves),
        curves,
    )


def _interval(s: AnySolution) -> tuple[float, float]:
    """The contact (-b/h, a/h); (-a/h, a/h) for an undamped solution."""
    if isinstance(s, DampedSolution):
        return s.contact_interval
    return (-s.a, s.a)


def _clipped_depths(y: FloatArray) -> tuple[FloatArray, FloatArray, npt.NDArray[Any]]:
    """For a damped point: (the depths evaluated: y, with DAMPED_MAX_Y < y < 0
    clipped to DAMPED_MAX_Y; their distinct values below the surface; the
    index of each depth among them, -1 at the surface y = 0)."""
    clipped = np.where(y < 0.0, np.minimum(y, DAMPED_MAX_Y), 0.0)
    below = clipped < 0.0
    distinct, index = np.unique(clipped[below], return_inverse=True)
    full = np.full(len(y), -1, dtype=np.intp)
    full[below] = index
    return clipped, distinct, full


def _depth_stress(s: AnySolution, y: FloatArray) -> FloatArray:
    """sigma_x(0, y); for a damped point at the clipped depths, and at y = 0
    the surface value sigma_x(0, 0) (``surface_stress``)."""
    if not isinstance(s, DampedSolution):
        return np.asarray(s.depth_stress(y), dtype=np.float64)
    _, distinct, index = _clipped_depths(y)
    out = np.empty(len(y))
    if len(distinct):
        values = np.asarray(s.depth_stress(distinct), dtype=np.float64)
        out[index >= 0] = values[index[index >= 0]]
    if (index < 0).any():
        out[index < 0] = float(np.asarray(s.surface_stress(0.0)))
    return out


def _stress_field(s: AnySolution, x: FloatArray, y: FloatArray) -> StressField:
    """The stress field; for a damped point at the clipped depths, and on the
    surface y = 0 from the surface values (sigma_x(x, 0), sigma_y = -p,
    tau_xy = 0: the punch is frictionless)."""
    if not isinstance(s, DampedSolution):
        return s.stress_field(x, y)
    clipped, distinct, index = _clipped_depths(y)
    comps = {name: np.empty((len(y), len(x))) for name in ("sx", "sy", "txy")}
    if len(distinct):
        f = s.stress_field(x, distinct)
        rows = index >= 0
        comps["sx"][rows] = f.sigma_x[index[rows]]
        comps["sy"][rows] = f.sigma_y[index[rows]]
        comps["txy"][rows] = f.tau_xy[index[rows]]
    top = index < 0
    if top.any():
        comps["sx"][top] = np.asarray(s.surface_stress(x), dtype=np.float64)
        comps["sy"][top] = -np.asarray(s.pressure(x), dtype=np.float64)
        comps["txy"][top] = 0.0
    sz, vm, ms = derived_stresses(comps["sx"], comps["sy"], comps["txy"], s.nu)
    return StressField(
        x=np.asarray(x, dtype=np.float64),
        y=clipped,
        sigma_x=comps["sx"],
        sigma_y=comps["sy"],
        tau_xy=comps["txy"],
        sigma_z=sz,
        von_mises=vm,
        max_shear=ms,
    )


def _undamped(s: AnySolution, output: str) -> Solution:
    if isinstance(s, DampedSolution):  # refused by the scene's validation
        raise MovingPunchError(f"{output} is not available with damping > 0")
    return s


def _out_surface_stress(run: _Run, spec: Any, solutions: _Solutions) -> OutputData:
    x = _x_grid(spec.x, (-3.0, 3.0), spec.resolved_points())
    curves = _curves(
        run,
        "surface_stress",
        solutions,
        x,
        lambda s, p: np.asarray(s.surface_stress(x), dtype=np.float64),
    )
    return OutputData(
        "surface_stress",
        "In-plane stress on the top surface",
        "x/h",
        "sigma_x(x, 0)/(P/h)",
        _curve_columns("x", "sigma_x", curves),
        curves,
    )


def _out_depth_stress(run: _Run, spec: Any, solutions: _Solutions) -> OutputData:
    lo, hi = spec.resolved_y()
    y = np.linspace(lo, hi, spec.resolved_points())
    curves = _curves(
        run, "depth_stress", solutions, y, lambda s, p: _depth_stress(s, y)
    )
    return OutputData(
        "depth_stress",
        "In-plane stress under the centre",
        "y/h",
        "sigma_x(0, y)/(P/h)",
        _curve_columns("y", "sigma_x", curves),
        curves,
    )


def _out_displacement(run: _Run, spec: Any, solutions: _Solutions) -> OutputData:
    x = _x_grid(spec.x, (-3.0, 3.0), spec.resolved_points())
    depth = spec.resolved_depth()
    curves = _curves(
        run,
        "displacement",
        solutions,
        x,
        # v = load * V(x; lambda): rescale a solution shared through lambda.
        lambda s, p: (
            _undamped(s, "displacement").displacement(x, depth) * (p["load"] / s.load)
        ),
    )
    return OutputData(
        "displacement",
        f"Vertical displacement at y/h = {depth:g}",
        "x/h",
        "v/h",
        _curve_columns("x", "v", curves),
        curves,
    )


def _out_stress_field(run: _Run, spec: Any, solutions: _Solutions) -> OutputData:
    scene = run.scene
    x = _x_grid(spec.x, (-2.0, 2.0), spec.resolved_points())
    lo, hi = spec.resolved_y()
    y = np.linspace(lo, hi, spec.resolved_depth_points())
    param = scene.vary.param if scene.vary is not None else None
    fields_: list[tuple[str, StressField]] = []
    cols: dict[str, list[FloatArray]] = {}
    for v, s in solutions.items():
        with run.timed("stress_field"):
            f = _stress_field(s, x, y)
        label = _label(param, v)
        fields_.append((label, f))
        gx, gy = np.meshgrid(f.x, f.y)
        if param is not None:
            cols.setdefault(param, []).append(
                np.full(gx.size, float(v) if v is not None else math.nan)
            )
        cols.setdefault("x", []).append(gx.ravel())
        cols.setdefault("y", []).append(gy.ravel())
        for comp in (
            "sigma_x",
            "sigma_y",
            "tau_xy",
            "sigma_z",
            "von_mises",
            "max_shear",
        ):
            cols.setdefault(comp, []).append(np.asarray(getattr(f, comp)).ravel())
    return OutputData(
        "stress_field",
        "Stresses in the layer",
        "x/h",
        "y/h",
        {k: np.concatenate(v) for k, v in cols.items()},
        (),
        tuple(fields_),
    )


def _out_critical_speed(run: _Run, spec: Any, solutions: _Solutions) -> OutputData:
    scene = run.scene
    combos: list[tuple[float, float]] = []
    for v in scene.curve_values():
        p = scene.point(v)
        if (p["kw"], p["nu"]) not in combos:
            combos.append((p["kw"], p["nu"]))
    nus = list(dict.fromkeys(nu for _, nu in combos))
    curves: list[Curve] = []
    if spec.kw is not None:
        grid = np.geomspace(spec.kw[0], spec.kw[1], spec.resolved_points())
        combos = [(float(k), nu) for nu in nus for k in grid]
    rows = []
    for kw, nu in combos:
        with run.timed("critical_speed"):
            vcr, alpha = critical_speed(kw, nu)
        rows.append((kw, nu, vcr, alpha, rayleigh_vstar(nu)))
    table = np.asarray(rows, dtype=np.float64).reshape(-1, 5)
    if spec.kw is not None:
        n = spec.resolved_points()
        for i, nu in enumerate(nus):
            block = table[i * n : (i + 1) * n]
            label = _label("nu", nu) if len(nus) > 1 else ""
            curves.append(
                Curve(label, nu if len(nus) > 1 else None, block[:, 0], block[:, 2])
            )
    names = ("kw", "nu", "critical_vstar", "critical_wavenumber", "rayleigh_vstar")
    return OutputData(
        "critical_speed",
        "Critical speed",
        "kw = k_w h/mu",
        "V*_cr",
        {n: table[:, i] for i, n in enumerate(names)},
        tuple(curves),
    )


_OUTPUTS: dict[str, Callable[[_Run, Any, _Solutions], OutputData]] = {
    "contact_width": _out_contact_width,
    "pressure": _out_pressure,
    "surface_stress": _out_surface_stress,
    "depth_stress": _out_depth_stress,
    "stress_field": _out_stress_field,
    "displacement": _out_displacement,
    "critical_speed": _out_critical_speed,
}
