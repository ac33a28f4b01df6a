"""Scenes: what to compute, written down.

A scene is a physical configuration (``[params]``), the outputs to show
(``[outputs]``), optional overlaid curves (``[vary]``) or a parameter sweep
(``[sweep]``), and an accuracy (``[accuracy]``). It lives in a TOML file
(docs/scenes.md) or is built in Python; running it computes only what it asks
for and records every stage of the work::

    from movingpunch.scene import Scene
    result = Scene.bundled("fig2").run(jobs=None)
    result.sweep.curves("a"), result.stages, result.ran("stress_field")

The paper's Table 1 and Figs. 2-6 ship as bundled scenes (``bundled_scenes``).
"""

from __future__ import annotations

from movingpunch.scene._export import (
    ascii_plots,
    atomic_write,
    format_summary,
    read_csv,
    read_json,
    write_outputs,
    write_pngs,
)
from movingpunch.scene._run import (
    ClusterError,
    Curve,
    MissingExtraError,
    OutputData,
    SceneResult,
    Stage,
    SweepTable,
    WorkerError,
)
from movingpunch.scene._spec import (
    OUTPUT_KINDS,
    STRESS_COMPONENTS,
    SWEEP_QUANTITIES,
    OutputSpec,
    Scene,
    SceneError,
    Sweep,
    Vary,
    bundled_scene_text,
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
