"""Planning a sweep: its points and their unique keys in solve order (groups
that share a kernel, widest contact first), the estimated cost of each point,
whether worker processes pay for themselves, the chunks sent to workers, and
the sweep's table assembled from the numbers of each key.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from movingpunch.media import Medium
from movingpunch.profiles import PunchProfile
from movingpunch.scene._model import PEAK_QUANTITIES, SceneData
from movingpunch.scene._result import SweepTable
from movingpunch.scene._solve import Key, curve_label, point_key, radius_ratio
from movingpunch.zones import Punch

__all__ = ["SweepPlan", "build_sweep_table", "plan_sweep", "split_chunks"]


@dataclass
class SweepPlan:
    """A sweep's points and the unique keys to solve, grouped by shared
    kernel (vstar, kw, nu, tol, damping, kp, friction), each group in
    descending lambda."""

    points: list[list[dict[str, float]]]  # [curve][grid] -> parameters
    keys: list[Key]  # unique keys, in solve order
    groups: dict[tuple[float, ...], list[Key]]
    representative: dict[Key, dict[str, float]]
    want_peaks: bool
    damped: bool
    profile: PunchProfile | None = None
    contact: str = "auto"
    punches: tuple[Punch, ...] = ()
    medium: Medium | None = None


def plan_sweep(scene: SceneData) -> SweepPlan:
    assert scene.sweep is not None
    sw = scene.sweep
    points = [
        [scene.point(v, **{sw.param: x}) for x in sw.values]
        for v in scene.curve_values()
    ]
    representative: dict[Key, dict[str, float]] = {}
    for row in points:
        for p in row:
            representative.setdefault(point_key(p, scene.tol), p)
    groups: dict[tuple[float, ...], list[Key]] = {}
    for key in representative:
        groups.setdefault(key[:7], []).append(key)
    for members in groups.values():
        members.sort(key=lambda k: -k[7])  # descending lambda: widest kernel first
    keys = [k for members in groups.values() for k in members]
    want_peaks = any(q in PEAK_QUANTITIES for q in sw.quantities)
    damped = any(k[4] > 0.0 or k[6] > 0.0 for k in keys)  # the asymmetric solver
    return SweepPlan(
        points,
        keys,
        groups,
        representative,
        want_peaks,
        damped,
        scene.profile,
        scene.contact,
        tuple(scene.punches),
        scene.medium,
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
# A chunk (the unit of work a worker is sent) is sized to about
# 1/_CHUNKS_PER_JOB of a worker's share, within [CHUNK_MIN, CHUNK_MAX]
# seconds (on Dask [DASK_CHUNK_MIN, DASK_CHUNK_MAX]) and _CHUNK_POINTS points.
_CHUNKS_PER_JOB = 8
CHUNK_MIN, CHUNK_MAX = 0.02, 0.1
DASK_CHUNK_MIN, DASK_CHUNK_MAX = 0.05, 1.0
_CHUNK_POINTS = 1000

# One unit of work: (group, keys) pieces, each contiguous points of one group.
Chunk = list[tuple[tuple[float, ...], list[Key]]]


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
    return sum(cold + (len(m) - 1) * warm for m in plan.groups.values())


def default_jobs() -> int:
    """The cores this process may run on."""
    affinity = getattr(os, "sched_getaffinity", None)
    if affinity is not None:
        return max(len(affinity(0)), 1)
    return os.cpu_count() or 1


def use_workers(
    plan: SweepPlan, n_jobs: int, dask: str | None, *, auto_jobs: bool
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


def split_chunks(plan: SweepPlan, target: float) -> list[Chunk]:
    """The sweep's points in chunks of about ``target`` seconds, in solve
    order: a chunk holds contiguous points of one or more groups, so that a
    group split across chunks still reuses its kernel within each (the first
    point of each piece, the widest contact, builds it). A group that fits
    in a chunk is never split: the chunk is closed before it instead."""
    chunks: list[Chunk] = []
    pieces: Chunk = []
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
        piece: list[Key] | None = None
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


def chunk_target(plan: SweepPlan, n: int, lo: float, hi: float) -> float:
    """Seconds of work per chunk for ``n`` workers: about 1/_CHUNKS_PER_JOB
    of a worker's share within [lo, hi], and at most a worker's share (every
    worker gets a chunk)."""
    total = _sweep_seconds(plan)
    target = min(max(total / (_CHUNKS_PER_JOB * n), lo), hi)
    return min(target, total / n)


def chunk_tasks(plan: SweepPlan, chunk: Chunk) -> list[dict[str, Any]]:
    """A chunk as the tasks ``_solve_chunk`` takes (plain data: it is
    pickled to a worker)."""
    return [
        {
            "vstar": group[0],
            "kw": group[1],
            "nu": group[2],
            "tol": group[3],
            "damping": group[4],
            "kp": group[5],
            "friction": group[6],
            "points": [
                (plan.representative[k]["radius"], plan.representative[k]["load"])
                for k in keys
            ],
            "peaks": plan.want_peaks,
            "profile": plan.profile,
            "contact": plan.contact,
            "punches": plan.punches,
            "medium": plan.medium,
            "spacings": [plan.representative[k].get("spacing") for k in keys],
        }
        for group, keys in chunk
    ]


def build_sweep_table(
    scene: SceneData, plan: SweepPlan, values: Mapping[Key, dict[str, float] | str]
) -> SweepTable:
    sw = scene.sweep
    assert sw is not None
    n_curves, n_grid = len(plan.points), len(sw.values)
    data = {q: np.full((n_curves, n_grid), np.nan) for q in sw.quantities}
    valid = np.zeros((n_curves, n_grid), dtype=bool)
    errors: dict[tuple[int, int], str] = {}
    for i, row in enumerate(plan.points):
        for j, p in enumerate(row):
            res = values[point_key(p, scene.tol)]
            if isinstance(res, str):
                errors[(i, j)] = res
                continue
            for q in sw.quantities:
                value = res[q]
                if q == "indentation":  # v = load * V(lambda)
                    value *= p["load"] / res["load"]
                elif q == "drag":  # int p x/R dx / P at fixed lambda
                    value *= radius_ratio(res["radius"], p["radius"])
                data[q][i, j] = value
            valid[i, j] = bool(res["valid"])
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
