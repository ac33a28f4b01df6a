"""What a run gives: its stages (the record of the work), the curves and
tables of each output (``OutputData``), a sweep's table (``SweepTable``) and
``RunRecord``, all of it but the scene (``SceneResult`` adds the scene).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from movingpunch.contract import ContactSolution
from movingpunch.fields import StressField

__all__ = ["Curve", "OutputData", "RunRecord", "Stage", "SweepTable"]


FloatArray = npt.NDArray[np.float64]

# Stage names of the core solve (Solution.stage_times), nested in "contact".
CORE_STAGES = ("critical_speed", "kernel", "width", "checks")
_TABLES = "#kernel_tables"  # carried with the stage records from workers


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


class Stages:
    def __init__(self) -> None:
        self._data: dict[str, list[float]] = {}
        self.kernel_tables = 0

    def add(self, name: str, seconds: float, count: int = 1) -> None:
        entry = self._data.setdefault(name, [0.0, 0.0])
        entry[0] += seconds
        entry[1] += count

    def add_solution(self, s: ContactSolution) -> None:
        self.add("contact", s.elapsed)
        times = s.stage_times
        builds = int(s.kernel_builds)
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
    details: Mapping[str, Any] = field(default_factory=dict)
    """What does not fit a column, per curve (lists in the order of the
    curves): ``contact_zones`` ([[x_left, x_right], ...] of every curve) and,
    for a separated contact or a train of punches, ``punches``
    (``PunchResult.to_dict()`` of each punch). Written to JSON as objects, to
    CSV as one JSON text per ``#`` header line."""


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
                cols[column_name(q, label)] = self.data[q][i]
            cols[column_name("valid", label)] = self.valid[i].astype(np.float64)
        return cols


def column_name(name: str, label: str) -> str:
    return f"{name}[{label}]" if label else name


@dataclass(frozen=True)
class RunRecord:
    """What a run computed, and the record of the work it did
    (``SceneResult`` adds the scene that ran)."""

    outputs: Mapping[str, OutputData]
    sweep: SweepTable | None
    solutions: tuple[ContactSolution, ...]
    """Contact solutions of the scene's curves computed in this process;
    a sweep's points only with ``Scene.run(keep_solutions=True)`` (and never
    those solved in worker processes or on Dask: they return their numbers
    only)."""
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
