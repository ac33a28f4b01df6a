"""Running a scene: computes what it asks for, and only that, and records
every stage of the work.

The contact solve is shared by every output of a curve; sweep points that
share a key (``_solve``) are solved once. The displacements and the
indentation scale with the load (v = load * V(x; lambda)), the drag of a damped
point like 1/radius at fixed lambda: a shared solution is rescaled to each
point. A sweep runs here, in worker processes or on Dask (``_plan`` decides,
``_executors`` runs it).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from movingpunch.cancel import check_cancelled
from movingpunch.errors import MovingPunchError
from movingpunch.scene._executors import DaskEvents, dask_map, pool_map
from movingpunch.scene._model import SceneData
from movingpunch.scene._outputs import OUTPUTS
from movingpunch.scene._plan import (
    CHUNK_MAX,
    CHUNK_MIN,
    Chunk,
    SweepPlan,
    SweepValues,
    build_sweep_table,
    chunk_target,
    default_jobs,
    plan_sweep,
    split_chunks,
    use_workers,
)
from movingpunch.scene._result import OutputData, RunRecord, SweepTable
from movingpunch.scene._solve import RunState, point_key, point_quantities

__all__ = ["run_scene"]


def sweep_wants_indentation(scene: SceneData) -> bool:
    return scene.sweep is None or "indentation" in scene.sweep.quantities


def _needs_contact(scene: SceneData) -> bool:
    return any(kind != "critical_speed" for kind in scene.outputs)


def run_scene(
    scene: SceneData,
    *,
    jobs: int | None = 1,
    progress: Callable[[int, int], None] | None = None,
    dask: str | None = None,
    dask_timeout: float | None = None,
    on_dask: DaskEvents | None = None,
    keep_solutions: bool = False,
) -> RunRecord:
    """Runs ``scene`` (see ``Scene.run``): all the result but the scene."""
    if jobs is not None and (
        isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1
    ):
        raise ValueError(
            f"jobs must be None (all cores) or an integer >= 1, got {jobs!r}"
        )
    n_jobs = default_jobs() if jobs is None else jobs
    t_start = time.perf_counter()
    run = RunState(scene, progress=progress)

    base_points = (
        [scene.point(v) for v in scene.curve_values()] if _needs_contact(scene) else []
    )
    base_keys = {point_key(p, scene.tol) for p in base_points}
    sweep_plan = plan_sweep(scene) if scene.sweep is not None else None
    remote = sweep_plan is not None and use_workers(sweep_plan, n_jobs, dask)
    # Points solved elsewhere are solved again here if an output needs them.
    run.total = len(base_keys)
    if sweep_plan is not None:
        shared = sum(sweep_plan.find(k) is not None for k in base_keys)
        run.total += sweep_plan.n_keys - (0 if remote else shared)
    # A sweep keeps its numbers, not its solutions (unless asked): the
    # curves' solutions are kept for their outputs.
    run.keep = None if keep_solutions else base_keys

    sweep_table: SweepTable | None = None
    used_jobs = 1
    if sweep_plan is not None:
        sweep_table, used_jobs = _run_sweep(
            run, sweep_plan, n_jobs, dask, remote, (dask_timeout, on_dask)
        )

    outputs: dict[str, OutputData] = {}
    solutions = {
        v: run.solution(p)
        for v, p in zip(scene.curve_values(), base_points, strict=False)
    }
    for kind, spec in scene.outputs.items():
        outputs[kind] = OUTPUTS[kind](run, spec, solutions)

    return RunRecord(
        outputs=outputs,
        sweep=sweep_table,
        solutions=tuple(run.memo.values()),
        stages=run.stages.stages(),
        total_seconds=time.perf_counter() - t_start,
        jobs=used_jobs,
        kernel_tables=run.stages.kernel_tables,
        warnings=tuple(w for found in run.warnings.values() for w in found),
    )


def _run_sweep(
    run: RunState,
    plan: SweepPlan,
    n_jobs: int,
    dask: str | None,
    remote: bool,
    dask_options: tuple[float | None, DaskEvents | None] = (None, None),
) -> tuple[SweepTable, int]:
    scene = run.scene
    assert scene.sweep is not None
    values = SweepValues(plan)
    if not remote:
        for k in range(plan.n_keys):
            p = plan.point(k)
            try:
                s = run.solution(p)
                found: list[str] = []
                values.set(
                    k,
                    point_quantities(
                        s,
                        plan.want_peaks,
                        run.stages,
                        found,
                        sweep_wants_indentation(scene),
                    ),
                )
                run.note_warnings(plan.key(k), p, found)
            except MovingPunchError as exc:
                values.set(k, str(exc))
                run.tick()
        return build_sweep_table(scene, plan, values), 1

    def make_chunks(n: int, lo: float, hi: float) -> list[Chunk]:
        return split_chunks(plan, chunk_target(plan, n, lo, hi))

    def consume(chunk: Chunk, outs: Sequence[Mapping[str, Any]]) -> None:
        check_cancelled()  # a cancelled run stops the pool (movingpunch.cancel)
        for (lo, hi), out in zip(chunk, outs, strict=True):
            run.stages.merge(out["stages"])
            for k, res in zip(range(lo, hi), out["results"], strict=True):
                values.set(k, res)
            for k, found in zip(range(lo, hi), out["warnings"], strict=True):
                if found:
                    run.note_warnings(plan.key(k), plan.point(k), found)
        run.tick(sum(hi - lo for lo, hi in chunk))

    if dask is not None:
        timeout, on_dask = dask_options
        dask_map(plan, make_chunks, dask, consume, timeout=timeout, on_dask=on_dask)
        used_jobs = 0
    else:
        chunks = make_chunks(n_jobs, CHUNK_MIN, CHUNK_MAX)
        used_jobs = min(n_jobs, len(chunks))
        pool_map(plan, chunks, used_jobs, consume)
    return build_sweep_table(scene, plan, values), used_jobs
