"""Scenes: what to compute, written down.

A scene is a physical configuration (``[params]``), the outputs to show
(``[outputs]``), optional overlaid curves (``[vary]``) or a parameter sweep
(``[sweep]``), and an accuracy (``[accuracy]``). It lives in a TOML file
(docs/scenes.md) or is built in Python; running it computes only what it asks
for and records every stage of the work::

    from movingpunch.scene import Scene
    result = Scene.bundled("fig2").run(jobs=None)
    result.sweep.curves("a"), result.stages, result.ran("stress_field")

The paper's Table 1 and Figs. 2-6 ship as bundled scenes (``bundled_scenes``,
the files of the folder ``movingpunch/bundled_scenes/``).

The modules, lowest first: ``_model`` (the parts and their names),
``_validate``, ``_toml`` (reading and writing scene files), ``_bundled`` (the
registry of the bundled files), ``_result`` (what a run gives), ``_solve``
(solving points), ``_plan`` (a sweep's plan and chunks), ``_executors``
(worker processes, Dask), ``_outputs`` (the output evaluators), ``_run`` (the
run), ``_scene`` (``Scene`` and ``SceneResult``), ``_export`` (files, plots and
the summary of a result). The exceptions live in ``movingpunch.errors``.
"""

from __future__ import annotations

from movingpunch.errors import (
    ClusterError,
    MissingExtraError,
    SceneError,
    WorkerError,
)
from movingpunch.outputs import atomic_write
from movingpunch.scene._bundled import bundled_scene_text
from movingpunch.scene._export import (
    ascii_plots,
    format_summary,
    read_csv,
    read_json,
    write_outputs,
    write_pngs,
)
from movingpunch.scene._model import (
    OUTPUT_KINDS,
    STRESS_COMPONENTS,
    SWEEP_QUANTITIES,
    OutputSpec,
    Sweep,
    Vary,
)
from movingpunch.scene._result import Curve, OutputData, Stage, SweepTable
from movingpunch.scene._scene import (
    Scene,
    SceneResult,
    bundled_scenes,
    load_scene,
)

__all__ = [
    "OUTPUT_KINDS",
    "STRESS_COMPONENTS",
    "SWEEP_QUANTITIES",
    "ClusterError",
    "Curve",
    "MissingExtraError",
    "OutputData",
    "OutputSpec",
    "Scene",
    "SceneError",
    "SceneResult",
    "Stage",
    "Sweep",
    "SweepTable",
    "Vary",
    "WorkerError",
    "ascii_plots",
    "atomic_write",
    "bundled_scene_text",
    "bundled_scenes",
    "format_summary",
    "load_scene",
    "read_csv",
    "read_json",
    "write_outputs",
    "write_pngs",
]
