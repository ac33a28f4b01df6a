"""Planning a sweep: its points and their unique keys in solve order (groups
that share a kernel, widest contact first), the estimated cost of each point,
whether worker processes pay for themselves, the chunks sent to workers, and
the sweep's table assembled from the numbers of each key.

A plan holds arrays, never an object per point: the keys (one row of
``Key`` per unique solve), the row of every point's key, and every point's
radius and load (about 40 bytes a point and 90 a key), so that a sweep of a
million points plans in tens of megabytes.
"""

from __future__ import annotations

import itertools
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from movingpunch.media import Medium
from movingpunch.profiles import PunchProfile
from movingpunch.scene._model import PEAK_QUANTITIES, SceneData
from movingpunch.scene._result import SweepTable
from movingpunch.scene._solve import (
    NO_SPRINGS,
    Key,
    curve_label,
)
from movingpunch.zones import Punch

__all__ = [
    "SweepPlan",
    "SweepValues",
    "build_sweep_table",
    "plan_sweep",
    "split_chunks",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]

# The columns of a key (``point_key``): the first seven are its group's.
_GROUP = 7
_LAMBDA = 7


@dataclass
class SweepPlan:
    """A sweep's unique keys in solve order, grouped by shared kernel
    (vstar, kw, nu, tol, damping, kp, friction), each group in descending
    lambda; and where each point's numbers come from.

    ``keys[k]`` is key ``k`` (``point_key`` of its points); ``starts``
    bounds the groups (group g: keys ``starts[g]:starts[g + 1]``);
    ``index[i, j]`` is the key of point j of curve i; ``rep[k]`` the flat
    index (curve * grid + j) of the first point with key k, whose
    parameters are solved (``point``)."""

    scene: SceneData
    keys: FloatArray  # (n_keys, 9)
    starts: IntArray  # (n_groups + 1,)
    index: IntArray  # (n_curves, n_grid)
    rep: IntArray  # (n_keys,)
    radius: FloatArray  # (n_curves, n_grid): each point's radius
    load: FloatArray  # (n_curves, n_grid): each point's load
    want_peaks: bool
    damped: bool
    spaced: bool = False
    """Its points place a train of punches by their spacing."""

    @property
    def n_keys(self) -> int:
        return len(self.keys)

    @property
    def n_groups(self) -> int:
        return len(self.starts) - 1

    def key(self, k: int) -> Key:
        """Key ``k`` as ``point_key`` gives it."""
        key: Key = tuple(self.keys[k].tolist())
        return key

    def group(self, k: int) -> tuple[float, ...]:
        """The group (shared kernel) of key ``k``."""
        return tuple(self.keys[k, :_GROUP].tolist())

    def point(self, k: int) -> dict[str, float]:
        """The parameters of the point solved for key ``k``."""
        sw = self.scene.sweep
        assert sw is not None
        curve, j = divmod(int(self.rep[k]), len(sw.values))
        return self.scene.point(
            self.scene.curve_values()[curve], **{sw.param: sw.values[j]}
        )

    def find(self, key: Key) -> int | None:
        """The row of ``key`` among the plan's keys, or None."""
        hit = np.flatnonzero(np.all(self.keys == np.asarray(key), axis=1))
        return int(hit[0]) if len(hit) else None

    @property
    def profile(self) -> PunchProfile | None:
        return self.scene.profile

    @property
    def contact(self) -> str:
        return self.scene.contact

    @property
    def punches(self) -> tuple[Punch, ...]:
        return tuple(self.scene.punches)

    @property
    def medium(self) -> Medium | None:
        return self.scene.medium


def _key_columns(
    p: Mapping[str, float], param: str, grid: FloatArray, tol: float
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The key columns (n_grid, 9) of one curve's points (``point_key`` on
    arrays: the same products, so the same keys), their radius and load."""
    n = len(grid)

    def column(name: str, default: float) -> FloatArray:
        if name == param:
            return grid
        return np.full(n, float(p.get(name, default)))

    radius, load = column("radius", 0.0), column("load", 0.0)
    with np.errstate(invalid="ignore", over="ignore"):
        lam = np.where(np.isfinite(radius), radius * load, -load)
    cols = [
        column("vstar", 0.0),
        column("kw", NO_SPRINGS),
        column("nu", 0.0),
        np.full(n, tol),
        column("damping", 0.0),
        column("kp", 0.0),
        column("friction", 0.0),
        lam,
        column("spacing", 0.0),
    ]
    # + 0.0: a -0.0 is the key of 0.0 (tuples compare them equal).
    return np.stack(cols, axis=1) + 0.0, radius, load


def plan_sweep(scene: SceneData) -> SweepPlan:
    assert scene.sweep is not None
    sw = scene.sweep
    grid = np.asarray(sw.values, dtype=np.float64)
    curves = scene.curve_values()
    parts = [_key_columns(scene.point(v), sw.param, grid, scene.tol) for v in curves]
    every = np.concatenate([k for k, _, _ in parts])
    radius = np.stack([r for _, r, _ in parts])
    load = np.stack([q for _, _, q in parts])
    del parts
    # Solve order: by group, then descending lambda (the widest kernel
    # first), then spacing; lexsort is stable, so equal keys keep the order
    # of their points and the first of them is the representative.
    sort_cols = [every[:, c] for c in range(_GROUP)]
    sort_cols += [-every[:, _LAMBDA], every[:, 8]]
    order = np.lexsort(sort_cols[::-1])
    del sort_cols
    ordered = every[order]
    del every
    new = np.ones(len(ordered), dtype=bool)
    new[1:] = np.any(ordered[1:] != ordered[:-1], axis=1)
    keys = np.ascontiguousarray(ordered[new])
    del ordered
    rep = order[new].astype(np.intp)
    index = np.empty(len(order), dtype=np.intp)
    index[order] = np.cumsum(new) - 1
    del order, new
    group_new = np.ones(len(keys), dtype=bool)
    group_new[1:] = np.any(keys[1:, :_GROUP] != keys[:-1, :_GROUP], axis=1)
    starts = np.append(np.flatnonzero(group_new), len(keys)).astype(np.intp)
    want_peaks = any(q in PEAK_QUANTITIES for q in sw.quantities)
    # the asymmetric solver: damping or friction
    damped = bool(np.any(keys[:, 4] > 0.0) or np.any(keys[:, 6] > 0.0))
    spaced = "spacing" in scene.point(curves[0], **{sw.param: sw.values[0]})
    return SweepPlan(
        spaced=spaced,
        scene=scene,
        keys=keys,
        starts=starts,
        index=index.reshape(len(curves), len(grid)),
        rep=rep,
        radius=radius,
        load=load,
        want_peaks=want_peaks,
        damped=damped,
    )


# Rough serial cost, in seconds, of a sweep point whose solve builds its kernel
# table (cold) or reuses the table of the point before it (warm), of its stress
# peaks, of a damped point; and of starting one worker process (its imports).
# Measured as CPU time in fresh processes (benchmarks/bench_jobs.py): 2000
# cold points of a vstar sweep 2.3 s, of a kw sweep 3.8 s (each kw its own
# critical speed too); 20 000 warm points of a load sweep 6.5 s.
_COLD_SECONDS, _WARM_SECONDS, _PEAKS_SECONDS = 1.5e-3, 3e-4, 3e-2
_DAMPED_SECONDS = 0.7
_TRAIN_SECONDS = 0.01  # two to four punches (the bundled spacing scene: 5 ms)
_STARTUP_SECONDS = 0.6
_PAY_MARGIN = 1.5  # the saving a pool must promise, in start-ups
# A chunk (the unit of work a worker is sent) is sized to about
# 1/_CHUNKS_PER_JOB of a worker's share, within [CHUNK_MIN, CHUNK_MAX]
# seconds (on Dask [DASK_CHUNK_MIN, DASK_CHUNK_MAX]) and _CHUNK_POINTS points.
_CHUNKS_PER_JOB = 8
CHUNK_MIN, CHUNK_MAX = 0.02, 0.1
DASK_CHUNK_MIN, DASK_CHUNK_MAX = 0.05, 1.0
_CHUNK_POINTS = 1000

# One unit of work: pieces (first key, end key), each contiguous keys of one
# group.
Chunk = list[tuple[int, int]]


def _point_seconds(plan: SweepPlan, cold: bool) -> float:
    if plan.damped:
        return _DAMPED_SECONDS
    if plan.punches:  # a train: its punches' solves and the zone search
        return _TRAIN_SECONDS + (_PEAKS_SECONDS if plan.want_peaks else 0.0)
    seconds = _COLD_SECONDS if cold else _WARM_SECONDS
    return seconds + (_PEAKS_SECONDS if plan.want_peaks else 0.0)


def _sweep_seconds(plan: SweepPlan) -> float:
    """The estimated serial time of the sweep."""
    cold, warm = _point_seconds(plan, True), _point_seconds(plan, False)
    return plan.n_groups * cold + (plan.n_keys - plan.n_groups) * warm


def default_jobs() -> int:
    """The cores this process may run on."""
    affinity = getattr(os, "sched_getaffinity", None)
    if affinity is not None:
        return max(len(affinity(0)), 1)
    return os.cpu_count() or 1


def use_workers(plan: SweepPlan, n_jobs: int, dask: str | None) -> bool:
    """Whether the sweep goes to worker processes (or Dask, always when
    given): never for one point or one job, and only when the estimated time
    the workers save exceeds _PAY_MARGIN times their start-up. ``jobs`` is
    a limit, not an order: a sweep too small to pay for a pool runs in this
    process, never slower than serial (``RunRecord.jobs`` says 1)."""
    if dask is not None:
        return True
    if n_jobs <= 1 or plan.n_keys <= 1:
        return False
    saved = _sweep_seconds(plan) * (1.0 - 1.0 / n_jobs)
    return saved > _PAY_MARGIN * _STARTUP_SECONDS


def split_chunks(plan: SweepPlan, target: float) -> list[Chunk]:
    """The sweep's keys in chunks of about ``target`` seconds, in solve
    order: a chunk holds contiguous keys of one or more groups, so that a
    group split across chunks still reuses its kernel within each (the first
    key of each piece, the widest contact, builds it). A group that fits
    in a chunk is never split: the chunk is closed before it instead."""
    chunks: list[Chunk] = []
    pieces: Chunk = []
    seconds, count = 0.0, 0
    cold, warm = _point_seconds(plan, True), _point_seconds(plan, False)
    limit = target * (1 + 1e-9)
    bounds = plan.starts.tolist()
    for lo, hi in itertools.pairwise(bounds):
        size = hi - lo
        whole = cold + (size - 1) * warm
        if (
            pieces
            and whole <= target
            and (seconds + whole > limit or count + size > _CHUNK_POINTS)
        ):
            chunks.append(pieces)
            pieces, seconds, count = [], 0.0, 0
        start = lo
        while start < hi:
            # The keys of this group that join the open chunk: up to the
            # first that brings it to ``target`` seconds or _CHUNK_POINTS.
            need = target - seconds - cold  # seconds left after the first key
            by_seconds = (
                1 if need <= 0 else (1 + math.ceil(need / warm) if warm > 0 else hi)
            )
            take = min(hi - start, by_seconds, _CHUNK_POINTS - count)
            pieces.append((start, start + take))
            seconds += cold + (take - 1) * warm
            count += take
            start += take
            if take == by_seconds or seconds >= target or count >= _CHUNK_POINTS:
                chunks.append(pieces)
                pieces, seconds, count = [], 0.0, 0
    if pieces:
        chunks.append(pieces)
    return chunks


def chunk_target(plan: SweepPlan, n: int, lo: float, hi: float) -> float:
    """Seconds of work per chunk for ``n`` workers: about 1/_CHUNKS_PER_JOB
    of a worker's share within [lo, hi], and at most a worker's share (every
    worker gets a chunk)."""
    total = _sweep_seconds(plan)
    target = min(max(total / (_CHUNKS_PER_JOB * n), lo), hi)
    return min(target, total / n)


def chunk_tasks(plan: SweepPlan, chunk: Chunk) -> list[dict[str, Any]]:
    """A chunk as the tasks ``solve_chunk`` takes (plain data: it is
    pickled to a worker). A few microseconds a piece: a cold sweep's chunk
    is hundreds of one-point groups."""
    rep_radius = plan.radius.ravel()[plan.rep[chunk[0][0] : chunk[-1][1]]]
    rep_load = plan.load.ravel()[plan.rep[chunk[0][0] : chunk[-1][1]]]
    first = chunk[0][0]
    spaced = plan.spaced
    tasks = []
    for lo, hi in chunk:
        group = plan.group(lo)
        radius = rep_radius[lo - first : hi - first].tolist()
        load = rep_load[lo - first : hi - first].tolist()
        tasks.append(
            {
                "vstar": group[0],
                "kw": group[1],
                "nu": group[2],
                "tol": group[3],
                "damping": group[4],
                "kp": group[5],
                "friction": group[6],
                "points": list(zip(radius, load, strict=True)),
                "peaks": plan.want_peaks,
                "indentation": "indentation" in plan.scene.sweep.quantities
                if plan.scene.sweep is not None
                else True,
                "profile": plan.profile,
                "contact": plan.contact,
                "punches": plan.punches,
                "medium": plan.medium,
                "spacings": (
                    [plan.point(k).get("spacing") for k in range(lo, hi)]
                    if spaced
                    else [None] * (hi - lo)
                ),
            }
        )
    return tasks


class SweepValues:
    """The numbers of each key that the sweep's table needs (its quantities,
    ``valid``, and the load and radius solved, which rescale the indentation
    and the drag to each point), in arrays; a failed key's message."""

    def __init__(self, plan: SweepPlan) -> None:
        sw = plan.scene.sweep
        assert sw is not None
        n = plan.n_keys
        self.names = (*sw.quantities, "valid", "load", "radius")
        self.data = {q: np.full(n, np.nan) for q in self.names}
        self.errors: dict[int, str] = {}

    def set(self, k: int, res: Mapping[str, float] | str) -> None:
        if isinstance(res, str):
            self.errors[k] = res
            return
        for q in self.names:
            self.data[q][k] = res[q]


def build_sweep_table(
    scene: SceneData, plan: SweepPlan, values: SweepValues
) -> SweepTable:
    sw = scene.sweep
    assert sw is not None
    index = plan.index
    failed = np.zeros(plan.n_keys, dtype=bool)
    failed[list(values.errors)] = True
    solved_load = values.data["load"][index]
    solved_radius = values.data["radius"][index]
    data: dict[str, FloatArray] = {}
    for q in sw.quantities:
        value = values.data[q][index]
        if q == "indentation":  # v = load * V(lambda)
            value = value * (plan.load / solved_load)
        elif q == "drag":  # int p x/R dx / P at fixed lambda (1 if equal: inf)
            same = solved_radius == plan.radius
            with np.errstate(invalid="ignore", divide="ignore"):
                value = value * np.where(same, 1.0, solved_radius / plan.radius)
        data[q] = np.where(failed[index], np.nan, value)
    valid = ~failed[index] & (values.data["valid"][index] == 1.0)
    errors: dict[tuple[int, int], str] = {}
    if values.errors:
        for flat in np.flatnonzero(failed[index].ravel()).tolist():
            k = int(index.ravel()[flat])
            errors[divmod(flat, len(sw.values))] = values.errors[k]
    vary_param = scene.vary.param if scene.vary is not None else None
    return SweepTable(
        param=sw.param,
        values=np.asarray(sw.values, dtype=np.float64),
        quantities=sw.quantities,
        labels=tuple(curve_label(vary_param, v) for v in scene.curve_values()),
        vary_param=vary_param,
        vary_values=scene.curve_values(),
        data=data,
        valid=valid,
        errors=errors,
    )
