"""What a scene is: its parts (``OutputSpec``, ``Vary``, ``Sweep``), the
names and limits they take, and ``SceneData``, what the modules below the
``Scene`` class (validation, TOML writing, the run) read of a scene.

Plain data: nothing here validates, reads files or computes.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from movingpunch.media import (
    BASE_TYPES,
    SUBLAYER_TYPES,
    HalfSpace,
    Medium,
    Winkler,
)
from movingpunch.params import PHYSICAL, SPECS
from movingpunch.profiles import PunchProfile
from movingpunch.zones import Punch

__all__ = [
    "CONTACT_MODES",
    "OUTPUT_KINDS",
    "PARAMS",
    "STRESS_COMPONENTS",
    "SWEEP_QUANTITIES",
    "TRAIN_PARAMS",
    "OutputSpec",
    "SceneData",
    "Sweep",
    "Vary",
    "train_of",
]

PARAMS: tuple[str, ...] = PHYSICAL
"""The physical parameters of a scene, in the order they are written.
``nu`` defaults to 0.2; ``damping`` (c_w c_T/mu, the Kelvin-Voigt dashpots,
docs/damped.md), ``kp`` (k_p/(mu h), the Pasternak shear layer,
docs/theory.md section 12) and ``friction`` (Coulomb f, docs/theory.md
section 14) to 0, each kept in ``params`` only when given."""


TRAIN_PARAMS: tuple[str, ...] = ("spacing",)
"""Parameters a vary or a sweep takes beside ``PARAMS`` in a scene with
``[[punches]]``: ``spacing`` places the K punches equally spaced, centred on
x = 0 (at_k = (k - (K - 1)/2) * spacing)."""

CONTACT_MODES: tuple[str, ...] = ("auto", "single")
"""``[params] contact``: passed to ``movingpunch.solve``."""

MAX_PUNCHES = 16

LAYER_KEYS: dict[str, tuple[str, ...]] = {
    cls.KIND: ("kind", *cls.FIELDS, *cls.CHOICES, *cls.MATERIALS)
    for cls in SUBLAYER_TYPES
}
"""``[[layers]]``: the keys of each kind of sublayer (``kind`` defaults to
"layer"; ``movingpunch.Layer`` and ``GradedLayer``: their field tables)."""

BASE_KEYS: dict[str, tuple[str, ...]] = {
    cls.KIND: ("kind", *cls.FIELDS, *cls.CHOICES) for cls in BASE_TYPES
}
"""``[base]``: the keys of each kind of base (``movingpunch.Winkler`` and
``HalfSpace``: their field tables)."""

MAX_LAYERS = 32
"""Most sublayers a scene's ``[[layers]]`` lists."""

SPRING_PARAMS: tuple[str, ...] = ("kw", "kp", "damping")
"""The parameters of the springs: a half-space base has none of them."""


def allowed_text(name: str) -> str:
    """What a scene accepts for the parameter ``name``: its range from the
    table of parameters (``movingpunch.params.SPECS``)."""
    if name == "spacing":
        return "a finite number > 0 (x/h between neighbouring punches)"
    text = f"a number, {SPECS[name].text}"
    return text + ', or "inf"' if name == "kw" else text


OUTPUT_KINDS: dict[str, str] = {
    "contact_width": "a/h, p0/(P/h), indentation and validity",
    "pressure": "contact pressure p(x)/(P/h) against x/h",
    "surface_stress": "sigma_x(x, 0)/(P/h) on the top surface against x/h",
    "depth_stress": "sigma_x(0, y)/(P/h) under the centre against y/h",
    "stress_field": "all stresses over P/h on an x/h by y/h grid",
    "displacement": "vertical displacement v(x, y)/h at one depth against x/h",
    "critical_speed": "V*_cr, alpha h at the minimum and V*_R (optionally a "
    "curve of V*_cr against kw)",
}
"""Every output a scene may ask for, with a one-line description."""

# Keys each output accepts (besides none at all: ``name = true``).
OUTPUT_KEYS: dict[str, tuple[str, ...]] = {
    "contact_width": (),
    "pressure": ("x", "points"),
    "surface_stress": ("x", "points"),
    "depth_stress": ("y", "points"),
    "stress_field": ("x", "y", "points", "depth_points", "component"),
    "displacement": ("x", "points", "depth"),
    "critical_speed": ("kw", "points"),
}

STRESS_COMPONENTS: tuple[str, ...] = (
    "sigma_x",
    "sigma_y",
    "tau_xy",
    "sigma_z",
    "von_mises",
    "max_shear",
)

SWEEP_QUANTITIES: dict[str, str] = {
    "a": "contact half-width a/h",
    "p0": "central pressure p(0)/(P/h)",
    "indentation": "indentation delta/h",
    "min_pressure": "minimum of p/(P/h) on the contact",
    "critical_vstar": "critical speed V*_cr(kw, nu, kp)",
    "phi1": "moving half-plane factor phi1",
    "drag": "drag F/P (from damping, friction or a viscoelastic layer)",
    "contact_start": "trailing end -b/h of the contact (-a/h when symmetric)",
    "contact_end": "leading end a/h of the contact",
    "zones": "number of contact zones (1: a single contact; more: a separated "
    "contact or a train of punches)",
    "top_compressive": "most compressive sigma_x/(P/h) on the top surface",
    "top_tensile": "most tensile sigma_x/(P/h) on the top surface",
    "bottom_tensile": "most tensile sigma_x/(P/h) at the bottom",
    "centre_top": "sigma_x(0, 0)/(P/h)",
    "centre_bottom": "sigma_x(0, -h)/(P/h)",
}
"""Scalar quantities a sweep can tabulate against its parameter."""

PEAK_QUANTITIES = frozenset(
    {"top_compressive", "top_tensile", "bottom_tensile", "centre_top", "centre_bottom"}
)

MAX_POINTS = 100_000
MAX_GRID = 1001  # per axis of a stress field
MAX_SWEEP = 2_000_000  # points of a sweep (times its vary values)
"""Most points a sweep computes in all: sweep values times vary values."""
MAX_VARY = 20
MAX_SCENE_BYTES = 1 << 20
"""Largest scene file read (1 MiB); a long sweep is written as start, stop,
points rather than as a list of values."""
MAX_NESTING = 32
"""Deepest nesting of TOML arrays and inline tables in a scene (a scene needs
2); checked before parsing, which recurses."""
DEFAULT_TOL = float(SPECS["tol"].default or 1e-8)
DEFAULT_NU = float(SPECS["nu"].default or 0.2)
RADIUS_MAX, LOAD_MAX = SPECS["radius"].hi, SPECS["load"].hi
"""The largest R/h and P/(mu h) the contact solver takes (its validate() in
cpp/src/contact.cpp); a scene refuses larger ones before it runs
(test_scene_input.py::test_radius_and_load_limits_are_the_solvers)."""


@dataclass(frozen=True)
class OutputSpec:
    """One requested output and its plot range and resolution.

    ``x`` and ``y`` are ranges in units of h (``None``: the default of the
    output; for ``pressure``, 1.25 times the widest contact). ``points`` is
    the number of samples along the curve (along x for a stress field),
    ``depth_points`` along y for a stress field, ``depth`` the y/h of a
    displacement curve, ``component`` the stress a field plot shows, ``kw``
    a range of k_w h/mu for a curve of V*_cr (log-spaced).
    """

    kind: str
    x: tuple[float, float] | None = None
    y: tuple[float, float] | None = None
    points: int | None = None
    depth_points: int | None = None
    depth: float | None = None
    component: str | None = None
    kw: tuple[float, float] | None = None

    def resolved_points(self) -> int:
        """``points`` or the output's default."""
        if self.points is not None:
            return self.points
        return {"stress_field": 81, "depth_stress": 101, "critical_speed": 41}.get(
            self.kind, 201
        )

    def resolved_depth_points(self) -> int:
        return 41 if self.depth_points is None else self.depth_points

    def resolved_y(self) -> tuple[float, float]:
        return (-1.0, 0.0) if self.y is None else self.y

    def resolved_depth(self) -> float:
        return 0.0 if self.depth is None else self.depth

    def resolved_component(self) -> str:
        return "sigma_x" if self.component is None else self.component


@dataclass(frozen=True)
class Vary:
    """One parameter over a list of values: one overlaid curve per value."""

    param: str
    values: tuple[float, ...]


@dataclass(frozen=True)
class Sweep:
    """A parameter over a grid: scalar ``quantities`` tabulated against it.

    Either explicit ``values``, or a range ``start``..``stop`` with
    ``points`` samples spaced ``"linear"`` or ``"log"`` (``values`` is then
    the grid it spans; use ``Sweep.range`` to build one).
    """

    param: str
    values: tuple[float, ...]
    quantities: tuple[str, ...] = ("a", "p0")
    start: float | None = None
    stop: float | None = None
    points: int | None = None
    spacing: str = "linear"

    @classmethod
    def range(
        cls,
        param: str,
        start: float,
        stop: float,
        points: int,
        *,
        spacing: str = "linear",
        quantities: Sequence[str] = ("a", "p0"),
    ) -> Sweep:
        """A sweep of ``param`` over ``points`` values from ``start`` to
        ``stop`` (both included), linear or log spaced."""
        return cls(
            param=param,
            values=sweep_grid(float(start), float(stop), int(points), spacing),
            quantities=tuple(quantities),
            start=float(start),
            stop=float(stop),
            points=int(points),
            spacing=spacing,
        )

    @property
    def is_range(self) -> bool:
        return self.start is not None


def sweep_grid(
    start: float, stop: float, points: int, spacing: str
) -> tuple[float, ...]:
    if spacing == "log":
        grid = np.geomspace(start, stop, points)
    else:
        grid = np.linspace(start, stop, points)
    return tuple(grid.tolist())


def output_items(spec: OutputSpec) -> list[tuple[str, object]]:
    """The keys an output was given, as its TOML table holds them."""
    items: list[tuple[str, object]] = []
    for key in ("x", "y", "points", "depth_points", "depth", "component", "kw"):
        value = getattr(spec, key)
        if value is not None:
            items.append((key, list(value) if isinstance(value, tuple) else value))
    return items


class SceneData(Protocol):
    """What validation, the TOML writer and the run read of a scene.

    ``movingpunch.scene.Scene`` satisfies it; those modules sit below the
    ``Scene`` class (which calls them) and so take this instead of importing
    it.
    """

    @property
    def params(self) -> Mapping[str, float]: ...
    @property
    def profile(self) -> PunchProfile | None: ...
    @property
    def punches(self) -> tuple[Punch, ...]: ...
    @property
    def contact(self) -> str: ...
    @property
    def medium(self) -> Medium | None: ...
    @property
    def outputs(self) -> Mapping[str, OutputSpec]: ...
    @property
    def vary(self) -> Vary | None: ...
    @property
    def sweep(self) -> Sweep | None: ...
    @property
    def tol(self) -> float: ...
    @property
    def name(self) -> str: ...
    @property
    def description(self) -> str: ...
    def curve_values(self) -> tuple[float | None, ...]: ...
    def point(
        self, vary_value: float | None = None, **override: float
    ) -> dict[str, float]: ...


def train_of(punches: Sequence[Punch], p: Mapping[str, float]) -> list[Punch]:
    """The punches of one point of a scene with ``[[punches]]``: their loads
    scaled by p["load"] / (their total load) (a vary or sweep over ``load``
    sets the train's total load), and, when p has a ``spacing``, placed
    equally spaced centred on x = 0, at_k = (k - (K - 1)/2) * spacing (in the
    order of the tables)."""
    total = math.fsum(q.load for q in punches)
    factor = p["load"] / total if "load" in p else 1.0
    k_mid = 0.5 * (len(punches) - 1)
    out = []
    for k, q in enumerate(punches):
        at = (k - k_mid) * p["spacing"] if "spacing" in p else q.at
        load = q.load if factor == 1.0 else q.load * factor
        out.append(Punch(q.profile, load, at))
    return out


def point_medium(medium: Medium, p: Mapping[str, float]) -> Medium:
    """The medium of one point of a scene with [[layers]] or a [base]: its
    sublayers on a half-space, or on the springs of the point's kw, kp and
    damping (a vary or sweep over them changes the springs)."""
    if isinstance(medium.base, HalfSpace):
        return medium
    springs = Winkler(p["kw"], p.get("kp", 0.0), p.get("damping", 0.0))
    return (
        medium if springs == medium.base else dataclasses.replace(medium, base=springs)
    )
