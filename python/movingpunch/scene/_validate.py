"""Validation of a scene: of each raw (TOML or Python) value, naming the key
at fault, and of the scene as a whole (also a scene built in Python): ranges,
limits, and every speed below the critical speed (the Rayleigh speed with
damping). Every problem is one ``SceneError`` line:
``FILE: key: problem (allowed: ...)``.
"""

from __future__ import annotations

import functools
import itertools
import math
import numbers
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any, TypeVar

import numpy as np

from movingpunch.errors import InvalidParameterError, SceneError
from movingpunch.media import (
    BASE_TYPES,
    SUBLAYER_TYPES,
    HalfSpace,
    Medium,
    Sublayer,
    ValueType,
    Winkler,
    material_from_dict,
    resolve_medium,
)
from movingpunch.params import OPTIONAL, PRESETS, SPECS, classify
from movingpunch.profiles import (
    Cylinder,
    Flat,
    Profile,
    PunchProfile,
    RoundedFlat,
    profile_from_dict,
)
from movingpunch.scene._model import (
    BASE_KEYS,
    CONTACT_MODES,
    DEFAULT_NU,
    LAYER_KEYS,
    MAX_GRID,
    MAX_LAYERS,
    MAX_POINTS,
    MAX_PUNCHES,
    MAX_SWEEP,
    MAX_VARY,
    OUTPUT_KEYS,
    OUTPUT_KINDS,
    PARAMS,
    SPRING_PARAMS,
    STRESS_COMPONENTS,
    SWEEP_QUANTITIES,
    TRAIN_PARAMS,
    OutputSpec,
    SceneData,
    Sweep,
    Vary,
    allowed_text,
    output_items,
    point_medium,
    sweep_grid,
    train_of,
)
from movingpunch.zones import Punch

__all__ = [
    "Checker",
    "critical_speed",
    "medium_critical_speed",
    "parse_base",
    "parse_layers",
    "parse_profile",
    "parse_punches",
    "rayleigh_speed",
    "validate",
]

_PROFILE_KEYS = ("kind", "radius", "half_width", "x", "y")


def parse_profile(
    c: Checker, raw: object, where: str = "params.profile"
) -> PunchProfile:
    """A scene's ``[params.profile]`` table (or a punch's
    ``[punches.profile]``, ``where`` naming it: ``kind`` = "cylinder",
    "flat", "rounded_flat" or "table" and its keys); errors name the key."""
    t = c.table(where, raw, _PROFILE_KEYS)
    try:
        return profile_from_dict(t, where)
    except InvalidParameterError as exc:
        key = exc.parameter or where
        problem = str(exc)
        for prefix in (f"{where}: ", f"{key}: ", f"{key} "):
            problem = problem.removeprefix(prefix)
        raise c.fail(key, problem, exc.allowed or "", exc.parameter) from exc


def _kinds_text(types: Iterable[type[ValueType]]) -> str:
    """``kind = "layer" (thickness, mu, nu, rho) or "graded" (...)``: each
    type's keys from its field table (a choice with its words)."""
    return "kind = " + " or ".join(
        f'"{cls.KIND}" ('
        + ", ".join(
            [
                *cls.FIELDS,
                *(
                    f"{name} = " + " or ".join(f'"{w}"' for w in words)
                    for name, words in cls.CHOICES.items()
                ),
            ]
        )
        + ")"
        for cls in types
    )


_LAYERS_ALLOWED = "[[layers]] tables, top to bottom: " + _kinds_text(SUBLAYER_TYPES)


def _media_fail(c: Checker, key: str, exc: InvalidParameterError) -> SceneError:
    """An InvalidParameterError of movingpunch.media as a SceneError on ``key``."""
    problem = str(exc)
    for prefix in (f"{exc.parameter}: ", "layers: "):
        problem = problem.removeprefix(prefix)
    return c.fail(key, problem, exc.allowed or "", exc.parameter)


def parse_layers(c: Checker, raw: object) -> tuple[Sublayer, ...]:
    """A scene's ``[[layers]]`` tables, top to bottom: ``kind`` = "layer"
    (the default) or "graded", each with its type's fields (``LAYER_KEYS``),
    bonded; the thicknesses sum to 1 and the top sublayer's mu and rho are 1
    (the units). Errors name ``layers[k].key`` (k from 0)."""
    if isinstance(raw, (str, bytes, Mapping)) or not isinstance(raw, Sequence):
        raise c.fail(
            "layers", f"must be a list of tables, got {show(raw)}", _LAYERS_ALLOWED
        )
    if not 1 <= len(raw) <= MAX_LAYERS:
        raise c.fail(
            "layers", f"has {len(raw)} sublayers", f"1 to {MAX_LAYERS} sublayers"
        )
    out: list[Sublayer] = []
    for k, item in enumerate(raw):
        where = f"layers[{k}]"
        kinds = tuple(LAYER_KEYS)
        if not isinstance(item, Mapping):
            raise c.fail(where, f"must be a table, got {show(item)}", _LAYERS_ALLOWED)
        kind = c.string(f"{where}.kind", item.get("kind", "layer"), kinds)
        t = c.table(where, item, LAYER_KEYS[kind])
        cls = next(s for s in SUBLAYER_TYPES if kind == s.KIND)
        out.append(_value_of(c, where, cls, t))
    try:
        return resolve_medium(layers=out, kw=1.0).layers
    except InvalidParameterError as exc:
        key = "layers[0]" if "layers[0]" in str(exc) else "layers"
        raise _media_fail(c, key, exc) from exc


_V = TypeVar("_V", bound=ValueType)


def _value_of(c: Checker, where: str, cls: type[_V], t: Mapping[str, Any]) -> _V:
    """The value type ``cls`` of a scene's table ``t`` (its keys checked):
    every field from the type's table, checked against ``params.SPECS``;
    a missing required field, a bad value or a bad word named as
    ``where.key``."""
    for name in cls.required():
        if name not in t:
            allowed = (
                allowed_text(name)
                if name in cls.FIELDS
                else " or ".join(repr(w) for w in cls.CHOICES[name])
            )
            raise c.fail(f"{where}.{name}", "missing", allowed, name)
    values: dict[str, Any] = {
        name: c.param(f"{where}.{name}", name, t[name])
        for name in cls.FIELDS
        if name in t
    }
    for name, words in cls.CHOICES.items():
        if name in t:
            values[name] = c.string(f"{where}.{name}", t[name], words)
    for name in cls.MATERIALS:
        if name in t:
            try:
                values[name] = material_from_dict(t[name], f"{where}.{name}")
            except InvalidParameterError as exc:
                raise c.fail(
                    f"{where}.{name}", str(exc), exc.allowed or "", exc.parameter
                ) from exc
    try:
        return cls(**values)
    except InvalidParameterError as exc:  # pragma: no cover - c.param checked
        raise _media_fail(c, f"{where}.{exc.parameter}", exc) from exc


def parse_base(c: Checker, raw: object) -> Winkler | HalfSpace:
    """A scene's ``[base]`` table: ``kind`` = "winkler" (kw, kp, damping:
    the springs of [params] moved here) or "half_space" (mu, nu, rho per the
    top sublayer's, interface = "bonded" or "smooth"): each with its type's
    fields (``BASE_KEYS``)."""
    allowed = _kinds_text(BASE_TYPES)
    if not isinstance(raw, Mapping):
        raise c.fail("base", f"must be a table, got {show(raw)}", allowed)
    if "kind" not in raw:
        raise c.fail("base.kind", "missing", ", ".join(BASE_KEYS))
    kind = c.string("base.kind", raw["kind"], tuple(BASE_KEYS))
    t = c.table("base", raw, BASE_KEYS[kind])
    cls = next(b for b in BASE_TYPES if kind == b.KIND)
    return _value_of(c, "base", cls, t)


def _check_medium(c: Checker, scene: SceneData, raw: dict[str, Any]) -> Medium | None:
    """The scene's medium (None: the homogeneous layer of params kw, nu, kp,
    damping), checked as the API checks it; ``raw`` (the params) made to
    hold what the medium fixes: nu = the top sublayer's, and kw, kp, damping
    = its springs' (none under a half-space). A parameter given both ways
    with different values is refused, naming it."""
    medium = getattr(scene, "medium", None)
    if medium is None:
        return None
    if not isinstance(medium, Medium):
        raise c.fail(
            "layers",
            f"the medium must be a movingpunch.Medium, got {show(medium)}",
            "Medium(layers=(Layer(...), ...), base=Winkler(...) or HalfSpace(...))",
        )
    try:
        medium = resolve_medium(
            layers=list(medium.layers), base=medium.base, inertia=medium.inertia
        )
    except InvalidParameterError as exc:
        raise _media_fail(
            c, "base" if exc.parameter == "base" else "layers", exc
        ) from exc
    if "nu" in raw and raw["nu"] != medium.nu:
        raise c.fail(
            "params.nu",
            "is given together with [[layers]] (each sublayer has its own nu)",
            "no nu in [params] beside [[layers]]: give nu in each [[layers]] table",
            "nu",
        )
    raw["nu"] = medium.nu
    base = medium.base
    if isinstance(base, HalfSpace):
        for name in SPRING_PARAMS:
            if name in raw:
                raise c.fail(
                    f"params.{name}",
                    f"is given together with a half-space [base] ({base.describe()}), "
                    "which has no springs",
                    f'no {name} beside a half-space base (or [base] kind = "winkler")',
                    name,
                )
        return medium
    for name in SPRING_PARAMS:
        value = float(getattr(base, name))
        if name in raw and raw[name] != value:
            raise c.fail(
                f"params.{name}",
                f"= {_fmt_num(float(raw[name]))} differs from the base's "
                f"{name} = {_fmt_num(value)}",
                f"{name} given once: in [params] or in [base]",
                name,
            )
        if name == "kw" or value != 0.0:
            raw[name] = value
    return medium


def _check_medium_use(
    c: Checker, scene: SceneData, medium: Medium, profile: PunchProfile | None
) -> None:
    """What a medium other than the homogeneous layer on springs cannot be
    given with yet (damped springs under a stack; a train under a half-space),
    and the vary or sweep parameters it makes meaningless, each refused
    naming the key."""
    axes = [
        (part, axis)
        for part, axis in (("vary", scene.vary), ("sweep", scene.sweep))
        if isinstance(axis, (Vary, Sweep))
    ]
    for part, axis in axes:
        if axis.param == "nu":
            raise c.fail(
                f"{part}.param",
                "nu cannot vary beside [[layers]]: each sublayer has its own nu",
                "vstar, radius, load, kw, kp (springs), friction, damping",
            )
        if isinstance(medium.base, HalfSpace) and axis.param in SPRING_PARAMS:
            raise c.fail(
                f"{part}.param",
                f"{axis.param} cannot vary under a half-space [base] "
                f"({medium.base.describe()}): it has no springs",
                'vstar, radius, load (or [base] kind = "winkler")',
            )
    crit = (
        scene.outputs.get("critical_speed")
        if isinstance(scene.outputs, Mapping)
        else None
    )
    if isinstance(medium.base, HalfSpace) and crit is not None and crit.kw is not None:
        raise c.fail(
            "outputs.critical_speed.kw",
            "a range of kw means nothing under a half-space [base] (no springs)",
            "no kw range beside a half-space base",
        )
    if medium.homogeneous:
        return  # the paper's layer: everything it supports
    # A layered medium or a half-space base: friction, asymmetric tables and
    # trains run on it (the asymmetric solver reads the medium; under a
    # half-space a train's displacements are measured from the surface at
    # x = 100 h); damped springs under a stack do not yet.
    refused = (
        "damped springs under a layered medium are not solved yet (the stack's "
        "propagation is real)"
    )
    if scene.params.get("damping", 0.0) != 0.0:
        raise c.fail(
            "params.damping",
            f"damping > 0 beside this medium ({medium.describe()}): {refused}",
            "damping = 0 beside [[layers]]",
            "damping",
        )
    for part, axis in axes:
        if axis.param == "damping":
            raise c.fail(
                f"{part}.param",
                f"damping cannot vary beside this medium: {refused}",
                "vstar, radius, load, kw, kp, friction",
            )


_PUNCH_KEYS = ("load", "at", "radius", "profile")


def parse_punches(c: Checker, raw: object) -> tuple[Punch, ...]:
    """A scene's ``[[punches]]`` tables: each with ``load``, ``at`` (x/h,
    default 0) and either ``radius`` (a cylinder) or a ``[punches.profile]``
    sub-table (the form of ``[params.profile]``). Errors name
    ``punches[k].key`` (k from 0, in the order of the tables)."""
    allowed = "[[punches]] tables with load, at and radius or [punches.profile]"
    if isinstance(raw, (str, bytes, Mapping)) or not isinstance(raw, Sequence):
        raise c.fail("punches", f"must be a list of tables, got {show(raw)}", allowed)
    if not 1 <= len(raw) <= MAX_PUNCHES:
        raise c.fail(
            "punches", f"has {len(raw)} punches", f"1 to {MAX_PUNCHES} punches"
        )
    out: list[Punch] = []
    for k, item in enumerate(raw):
        where = f"punches[{k}]"
        t = c.table(where, item, _PUNCH_KEYS)
        if "load" not in t:
            raise c.fail(f"{where}.load", "missing", allowed_text("load"), "load")
        load = c.param(f"{where}.load", "load", t["load"])
        at = 0.0
        if "at" in t:
            at = c.number(f"{where}.at", t["at"], "a finite number x/h")
            if not math.isfinite(at):
                raise c.fail(
                    f"{where}.at", f"must be finite, got {show(at)}", "a finite x/h"
                )
        shape: PunchProfile | float
        if "radius" in t and "profile" in t:
            raise c.fail(
                f"{where}.radius",
                "is given beside [punches.profile]",
                "either radius (a cylinder) or a [punches.profile] table",
                "radius",
            )
        if "radius" in t:
            shape = c.param(f"{where}.radius", "radius", t["radius"])
        elif "profile" in t:
            shape = parse_profile(c, t["profile"], f"{where}.profile")
        else:
            raise c.fail(
                f"{where}.radius",
                "missing (no radius and no [punches.profile])",
                "either radius (a cylinder) or a [punches.profile] table",
                "radius",
            )
        out.append(_punch(c, where, shape, load, at))
    return tuple(out)


def _punch(
    c: Checker, where: str, shape: PunchProfile | float, load: float, at: float
) -> Punch:
    try:
        return Punch(shape, load, at)
    except InvalidParameterError as exc:
        key = exc.parameter or "profile"
        key = key if key.startswith(where) else f"{where}.{key}"
        raise c.fail(key, str(exc), exc.allowed or "", exc.parameter) from exc


def _check_punches(c: Checker, scene: SceneData) -> tuple[Punch, ...]:
    """The punches of a scene (a scene built in Python: a sequence of
    ``movingpunch.Punch``); their positions distinct."""
    punches: object = scene.punches  # a scene built in Python: anything
    if punches is None:
        return ()
    if isinstance(punches, (str, bytes)) or not isinstance(punches, Sequence):
        raise c.fail(
            "punches", f"must be a sequence of Punch, got {show(punches)}", "Punch"
        )
    if len(punches) > MAX_PUNCHES:
        raise c.fail(
            "punches", f"has {len(punches)} punches", f"1 to {MAX_PUNCHES} punches"
        )
    seen: dict[float, int] = {}
    for k, q in enumerate(punches):
        if not isinstance(q, Punch):
            raise c.fail(
                f"punches[{k}]", f"must be a movingpunch.Punch, got {show(q)}", "Punch"
            )
        if q.at in seen:
            raise c.fail(
                f"punches[{k}].at",
                f"x/h = {q.at:g} is also punches[{seen[q.at]}].at: the punches overlap",
                "a distinct position for each punch",
            )
        seen[q.at] = k
    return tuple(punches)


def _check_profile(
    c: Checker, scene: SceneData, raw: dict[str, Any]
) -> PunchProfile | None:
    """The scene's profile (None: a cylinder of params.radius, which a
    Cylinder profile becomes); ``raw`` (the params) loses a radius the
    profile carries. A radius beside another profile must be its own."""
    profile: object = scene.profile  # a scene built in Python: anything
    if profile is None:
        return None
    if not isinstance(profile, (Cylinder, Flat, RoundedFlat, Profile)):
        raise c.fail(
            "params.profile",
            f"must be a punch profile, got {show(profile)}",
            "movingpunch.Cylinder, Flat, RoundedFlat or Profile",
        )
    if "radius" in raw:
        # The profile's own radius (a validated scene holds its nominal
        # radius, inf for a flat punch or a table) is no conflict.
        if raw["radius"] != profile.nominal_radius:
            raise c.fail(
                "params.radius",
                f"is given beside [params.profile] ({profile.describe()}), which "
                "carries its own shape",
                "no radius beside a profile (or the profile's own radius)",
                "radius",
            )
        del raw["radius"]
    if isinstance(profile, Cylinder):
        raw["radius"] = profile.radius
        return None
    return profile


@functools.lru_cache(maxsize=4096)
def critical_speed(kw: float, nu: float, kp: float = 0.0) -> tuple[float, float]:
    """(V*_cr, alpha h at the minimum) for (kw, nu, kp), computed once per
    process."""
    from movingpunch import _core

    return _core.critical_speed(kw, nu, kp)


@functools.lru_cache(maxsize=1024)
def medium_critical_speed(medium: Medium) -> float | None:
    """V*_cr of a medium (``movingpunch.critical_vstar(layers=, base=)``),
    once per process; None where the core cannot compute it (a medium it
    does not build: the run then reports that by name)."""
    from movingpunch.solver import critical_vstar

    try:
        return critical_vstar(layers=list(medium.layers), base=medium.base)
    except InvalidParameterError:
        return None


@functools.lru_cache(maxsize=64)
def rayleigh_speed(nu: float) -> float:
    """V*_R(nu), computed once per process."""
    from movingpunch import _core

    return float(_core.rayleigh_vstar(nu))


class Checker:
    """Validates raw (TOML or Python) values; errors name ``source`` and key."""

    def __init__(self, source: str) -> None:
        self.source = source

    def fail(
        self, key: str, problem: str, allowed: str = "", parameter: str | None = None
    ) -> SceneError:
        return SceneError(self.source, key, problem, allowed, parameter)

    def table(
        self, key: str, value: object, allowed_keys: Iterable[str]
    ) -> Mapping[str, Any]:
        allowed = tuple(allowed_keys)
        names = ", ".join(allowed) if allowed else "no keys"
        if not isinstance(value, Mapping):
            raise self.fail(key, f"must be a table, got {show(value)}", names)
        for k in value:
            if k not in allowed:
                where = f"{key}.{k}" if key else str(k)
                raise self.fail(where, "unknown key", names)
        return value

    def number(self, key: str, value: object, allowed: str) -> float:
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
            raise self.fail(key, f"must be a number, got {show(value)}", allowed)
        try:
            return float(value)
        except OverflowError:
            raise self.fail(key, "is too large for a float", allowed) from None

    def tol(self, key: str, value: object) -> float:
        """A tolerance: a number in [1e-14, 1e-2] or a preset name."""
        if isinstance(value, str):
            preset = PRESETS.get(value.strip().lower())
            if preset is None:
                raise self.fail(
                    key, f"unknown preset {value!r}", SPECS["tol"].text, "tol"
                )
            return preset
        return self.param(key, "tol", value)

    def param(self, key: str, name: str, value: object) -> float:
        """``value`` checked against the table of parameters (SPECS)."""
        allowed = SPECS[name].text if name == "tol" else allowed_text(name)
        if name == "spacing":
            x = self.number(key, value, allowed)
            if not (math.isfinite(x) and x > 0.0):
                raise self.fail(key, f"out of range: {show(x)}", allowed, name)
            return x
        if name == "kw" and isinstance(value, str):
            if value.strip().lower() in ("inf", "+inf", "infinity"):
                return math.inf
            raise self.fail(
                key, f"must be a number or 'inf', got {value!r}", allowed, name
            )
        x, problem = classify(name, value)
        if problem == "type":
            raise self.fail(key, f"must be a number, got {show(value)}", allowed, name)
        if problem == "overflow":
            raise self.fail(key, "is too large for a float", allowed, name)
        if problem:
            raise self.fail(key, f"out of range: {show(x)}", allowed, name)
        return x

    def integer(self, key: str, value: object, lo: int, hi: int) -> int:
        allowed = f"an integer {lo} to {hi}"
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
            raise self.fail(key, f"must be an integer, got {show(value)}", allowed)
        if not lo <= int(value) <= hi:
            raise self.fail(key, f"out of range: {value}", allowed)
        return int(value)

    def string(self, key: str, value: object, choices: Sequence[str] = ()) -> str:
        allowed = ", ".join(choices) if choices else "a string"
        if not isinstance(value, str):
            raise self.fail(key, f"must be a string, got {show(value)}", allowed)
        if choices and value not in choices:
            raise self.fail(key, f"unknown value {value!r}", allowed)
        return value

    def pair(
        self,
        key: str,
        value: object,
        allowed: str,
        ok: Callable[[float], bool] = math.isfinite,
    ) -> tuple[float, float]:
        if isinstance(value, (str, bytes)) or not isinstance(value, Sequence):
            raise self.fail(
                key, f"must be a list [low, high], got {show(value)}", allowed
            )
        if len(value) != 2:
            raise self.fail(key, f"must have 2 numbers, got {len(value)}", allowed)
        lo = self.number(f"{key}[0]", value[0], allowed)
        hi = self.number(f"{key}[1]", value[1], allowed)
        if not (ok(lo) and ok(hi)):
            raise self.fail(key, f"out of range: [{show(lo)}, {show(hi)}]", allowed)
        if not lo < hi:
            raise self.fail(key, "low must be below high", allowed)
        if not math.isfinite(hi - lo):
            raise self.fail(key, "the span high - low overflows", allowed)
        return lo, hi


def show(value: object) -> str:
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, Mapping):
        return "a table"
    if isinstance(value, (list, tuple)):
        return "a list"
    if isinstance(value, bool):
        return "true" if value else "false"
    return f"{type(value).__name__} {value!r}"[:60]


def values_list(
    c: Checker, key: str, param: str, raw: object, limit: int
) -> tuple[float, ...]:
    if isinstance(raw, (str, bytes)) or not isinstance(raw, Sequence):
        raise c.fail(
            key, f"must be a list, got {show(raw)}", allowed_text(param), param
        )
    if not 1 <= len(raw) <= limit:
        raise c.fail(key, f"has {len(raw)} values", f"1 to {limit} values")
    values = tuple(c.param(f"{key}[{i}]", param, v) for i, v in enumerate(raw))
    if len(set(values)) != len(values):
        raise c.fail(key, "values repeat", "distinct values")
    return values


def range_bounds(
    c: Checker,
    param: str,
    start_: object,
    stop_: object,
    points_: object,
    spacing_: object,
) -> tuple[float, float, int, str]:
    """The checked start, stop, points and spacing of a range sweep."""
    start = c.param("sweep.start", param, start_)
    stop = c.param("sweep.stop", param, stop_)
    for k, v in (("start", start), ("stop", stop)):
        if not math.isfinite(v):
            raise c.fail(
                f"sweep.{k}",
                "must be finite",
                "finite numbers; list inf in values",
                param,
            )
    points = c.integer("sweep.points", points_, 2, MAX_SWEEP)
    spacing = c.string("sweep.spacing", spacing_, ("linear", "log"))
    if start == stop:
        raise c.fail("sweep.stop", "equals sweep.start", "stop != start")
    if spacing == "log" and min(start, stop) <= 0:
        raise c.fail(
            "sweep.start", "log spacing needs positive bounds", "start, stop > 0"
        )
    return start, stop, points, spacing


def _check_range(c: Checker, s: Sweep) -> None:
    """A range sweep: its bounds, and its values the grid they span (which
    lies between two valid bounds: no value needs a check of its own)."""
    start, stop, points, spacing = range_bounds(
        c, s.param, s.start, s.stop, s.points, s.spacing
    )
    if s.values != sweep_grid(start, stop, points, spacing):
        raise c.fail(
            "sweep.values",
            "do not match start, stop, points and spacing",
            "the grid of Sweep.range(param, start, stop, points, spacing=...)",
        )
    if len(set(s.values)) != len(s.values):
        raise c.fail(
            "sweep.points",
            f"{points} points between {start:g} and {stop:g} repeat values",
            "fewer points, or bounds further apart",
        )


def parse_output(c: Checker, kind: str, raw: object) -> OutputSpec | None:
    key = f"outputs.{kind}"
    if isinstance(raw, bool):
        return OutputSpec(kind) if raw else None
    t = c.table(key, raw, OUTPUT_KEYS[kind])
    spec: dict[str, Any] = {}
    if "x" in t:
        spec["x"] = c.pair(f"{key}.x", t["x"], "[low, high], finite x/h, low < high")
    if "y" in t:
        spec["y"] = c.pair(
            f"{key}.y", t["y"], "[low, high], -1 <= y/h <= 0, low < high", _in_layer
        )
    if "points" in t:
        hi = MAX_GRID if kind == "stress_field" else MAX_POINTS
        spec["points"] = c.integer(f"{key}.points", t["points"], 2, hi)
    if "depth_points" in t:
        spec["depth_points"] = c.integer(
            f"{key}.depth_points", t["depth_points"], 2, MAX_GRID
        )
    if "depth" in t:
        d = c.number(f"{key}.depth", t["depth"], "-1 <= y/h <= 0")
        if not _in_layer(d):
            raise c.fail(f"{key}.depth", f"out of range: {show(d)}", "-1 <= y/h <= 0")
        spec["depth"] = d
    if "component" in t:
        spec["component"] = c.string(
            f"{key}.component", t["component"], STRESS_COMPONENTS
        )
    if "kw" in t:
        spec["kw"] = c.pair(
            f"{key}.kw", t["kw"], "[low, high], 1e-12 <= kw < inf", _finite_kw
        )
    return OutputSpec(kind, **spec)


def _in_layer(y: float) -> bool:
    return -1.0 <= y <= 0.0


def _finite_kw(kw: float) -> bool:
    return math.isfinite(kw) and SPECS["kw"].contains(kw)


# ----------------------------------------------------------------------------
# Whole-scene validation (also for scenes built in Python)
# ----------------------------------------------------------------------------


def validate(scene: SceneData, source: str) -> None:
    c = Checker(source)
    if not isinstance(scene.params, Mapping):
        raise c.fail("params", "must be a mapping", ", ".join(PARAMS))
    c.table("params", scene.params, PARAMS)
    raw = dict(scene.params)
    punches = _check_punches(c, scene)
    contact = c.string("params.contact", scene.contact, CONTACT_MODES)
    if punches:
        _check_train_params(c, scene, raw, contact)
    profile = _check_profile(c, scene, raw)
    medium = _check_medium(c, scene, raw)
    half_space = medium is not None and isinstance(medium.base, HalfSpace)
    params: dict[str, float] = {}
    for name in PARAMS:
        if half_space and name in SPRING_PARAMS:
            continue  # no springs (_check_medium refused them)
        if name == "radius" and profile is not None:
            params[name] = profile.nominal_radius  # inf: a flat punch or a table
            continue
        if punches and name in ("radius", "load"):
            continue  # the punches carry their own
        if name not in raw:
            if name == "nu":
                params[name] = DEFAULT_NU
                continue
            if name in OPTIONAL:  # 0; kept only when given
                continue
            raise c.fail(f"params.{name}", "missing", allowed_text(name), name)
        params[name] = c.param(f"params.{name}", name, raw[name])
    object.__setattr__(scene, "params", params)
    object.__setattr__(scene, "profile", profile)
    object.__setattr__(scene, "punches", punches)
    object.__setattr__(scene, "contact", contact)
    object.__setattr__(scene, "medium", medium)

    tol = c.tol("accuracy.tol", scene.tol)
    object.__setattr__(scene, "tol", tol)
    c.string("name", scene.name)
    c.string("description", scene.description)

    if not isinstance(scene.outputs, Mapping):
        raise c.fail("outputs", "must be a mapping", ", ".join(OUTPUT_KINDS))
    outputs: dict[str, OutputSpec] = {}
    for kind, spec in scene.outputs.items():
        if kind not in OUTPUT_KINDS:
            raise c.fail(f"outputs.{kind}", "unknown key", ", ".join(OUTPUT_KINDS))
        if not isinstance(spec, OutputSpec) or spec.kind != kind:
            raise c.fail(f"outputs.{kind}", "must be an OutputSpec of that kind")
        as_toml = dict(output_items(spec))
        checked = parse_output(c, kind, as_toml)
        if checked != spec:
            raise c.fail(
                f"outputs.{kind}",
                "has keys this output does not take",
                ", ".join(OUTPUT_KEYS[kind]) or "no keys",
            )
        outputs[kind] = spec
    object.__setattr__(scene, "outputs", outputs)

    for part, axis in (("vary", scene.vary), ("sweep", scene.sweep)):
        if isinstance(axis, (Vary, Sweep)) and axis.param == "spacing" and not punches:
            raise c.fail(
                f"{part}.param",
                "spacing needs [[punches]] (it places the punches)",
                ", ".join(PARAMS) + "; spacing beside [[punches]]",
            )
        if isinstance(axis, (Vary, Sweep)) and axis.param == "radius" and punches:
            raise c.fail(
                f"{part}.param",
                "radius cannot vary beside [[punches]]: each punch carries its shape",
                "vstar, kw, nu, kp, damping, load (the train's total load, "
                "every punch scaled) or spacing",
            )
    if scene.vary is not None:
        v = scene.vary
        if not isinstance(v, Vary):
            raise c.fail("vary", "must be a Vary")
        c.string("vary.param", v.param, _axis_params(punches))
        values_list(c, "vary.values", v.param, list(v.values), MAX_VARY)
    if scene.sweep is not None:
        s = scene.sweep
        if not isinstance(s, Sweep):
            raise c.fail("sweep", "must be a Sweep")
        c.string("sweep.param", s.param, _axis_params(punches))
        if s.is_range:
            _check_range(c, s)
        else:
            values_list(c, "sweep.values", s.param, list(s.values), MAX_SWEEP)
        n_curves = len(scene.curve_values())
        if n_curves * len(s.values) > MAX_SWEEP:
            raise c.fail(
                "sweep.points" if s.is_range else "sweep.values",
                f"{len(s.values)} sweep values times {n_curves} vary values are "
                f"{n_curves * len(s.values)} points",
                f"at most {MAX_SWEEP} points in all",
            )
        for i, q in enumerate(s.quantities):
            c.string(f"sweep.quantities[{i}]", q, tuple(SWEEP_QUANTITIES))
        if not s.quantities:
            raise c.fail("sweep.quantities", "is empty", ", ".join(SWEEP_QUANTITIES))
        if scene.vary is not None and scene.vary.param == s.param:
            raise c.fail(
                "sweep.param",
                f"{s.param!r} is already the vary parameter",
                "a parameter other than vary.param",
            )
    if profile is not None:
        for part, axis in (("vary", scene.vary), ("sweep", scene.sweep)):
            if axis is not None and axis.param == "radius":
                raise c.fail(
                    f"{part}.param",
                    f"radius cannot vary beside [params.profile] "
                    f"({profile.describe()}): the profile carries its shape",
                    "vstar, kw, load, nu or damping",
                )
    if not outputs and scene.sweep is None:
        raise c.fail(
            "outputs",
            "nothing to compute",
            "at least one of " + ", ".join(OUTPUT_KINDS) + ", or a [sweep]",
        )
    if medium is not None:
        _check_medium_use(c, scene, medium, profile)
    _check_speeds(scene, c)
    if punches:
        _check_overlap(scene, c)


def _axis_params(punches: Sequence[Punch]) -> tuple[str, ...]:
    """The parameters a vary or sweep takes: ``spacing`` only beside
    punches."""
    return (*PARAMS, *TRAIN_PARAMS) if punches else PARAMS


def _check_train_params(
    c: Checker, scene: SceneData, raw: Mapping[str, Any], contact: str
) -> None:
    """[params] beside [[punches]]: no load, radius or profile (each punch
    has its own), no friction, contact "auto"."""
    for name in ("load", "radius"):
        if name in raw:
            raise c.fail(
                f"params.{name}",
                f"is not allowed together with [[punches]] (each punch has its "
                f"own {name}; a sweep over load sets the train's total load)",
                "vstar, kw, nu, kp, damping beside [[punches]]",
                name,
            )
    if scene.profile is not None:
        raise c.fail(
            "params.profile",
            "is not allowed together with [[punches]] (each punch has its own "
            "radius or [punches.profile])",
            "vstar, kw, nu, kp, damping beside [[punches]]",
        )
    if raw.get("friction", 0.0) != 0.0:
        raise c.fail(
            "params.friction",
            "must be 0 with [[punches]] (several contact zones with friction "
            "are not supported)",
            "0 beside [[punches]]",
            "friction",
        )
    if contact != "auto":
        raise c.fail(
            "params.contact",
            f"{contact!r} is not allowed with [[punches]] (a train finds its "
            "contact zones)",
            '"auto" beside [[punches]]',
        )


def _sweep_extremes(sweep: Sweep) -> list[int]:
    """The indices of the smallest and the largest sweep value, in order.

    They decide the speed checks of the whole sweep: the bound on vstar,
    V*_cr(kw, nu, kp), grows with kw, with nu and with kp, and V*_R(nu) with
    nu (test_scene_input.py checks both on dense grids, test_pasternak.py kp),
    so the tightest point of a sweep over vstar, kw, nu or kp is its largest
    vstar or its smallest kw, nu or kp; over damping, the smallest value is
    the only one that may be 0 (the undamped check) and the largest the one
    most surely > 0. Validation thus solves O(1) critical speeds per sweep,
    not one per point."""
    n = len(sweep.values)
    if sweep.is_range:
        return [0, n - 1]
    values = np.asarray(sweep.values, dtype=np.float64)
    return sorted({int(np.argmin(values)), int(np.argmax(values))})


def _check_speeds(scene: SceneData, c: Checker) -> None:
    """vstar < V*_cr(kw, nu) for every combination the scene computes
    (vstar < V*_R(nu) where damping > 0). Of a sweep only its extremes are
    checked (``_sweep_extremes``)."""
    needs_contact = any(k != "critical_speed" for k in scene.outputs)
    combos: list[tuple[dict[str, float], dict[str, str]]] = []
    sw = scene.sweep
    for vi, v in enumerate(scene.curve_values()):
        bases: list[int] = [-1] if needs_contact else []
        if sw is not None:
            bases.extend(_sweep_extremes(sw))
        for si in bases:
            p = scene.point(v)
            where = {name: f"params.{name}" for name in PARAMS}
            if scene.vary is not None:
                where[scene.vary.param] = f"vary.values[{vi}]"
            if sw is not None and si >= 0:
                p[sw.param] = sw.values[si]
                where[sw.param] = (
                    f"sweep.{'start' if si == 0 else 'stop'}"
                    if sw.is_range
                    else f"sweep.values[{si}]"
                )
            combos.append((p, where))
    seen: set[tuple[float, float, float, bool, float]] = set()
    medium = getattr(scene, "medium", None)
    layered = medium is not None and (not medium.homogeneous or not medium.inertia)
    for p, where in combos:
        if layered:
            assert medium is not None
            _check_medium_speed(c, point_medium(medium, p), p, where)
            continue
        damped = p.get("damping", 0.0) > 0.0
        kp = p.get("kp", 0.0)
        key = (p["vstar"], p["kw"], p["nu"], damped, kp)
        if key in seen:
            continue
        seen.add(key)
        if p["vstar"] == 0.0:
            continue
        if damped:
            vr = rayleigh_speed(p["nu"])
            if not p["vstar"] < vr:
                culprit, blamed = where["vstar"], "vstar"
                if culprit.startswith("params.") and not where["nu"].startswith(
                    "params."
                ):
                    culprit, blamed = where["nu"], "nu"
                raise c.fail(
                    culprit,
                    f"vstar = {p['vstar']:.10g} is at or above the Rayleigh speed "
                    f"V*_R = {vr:.10g} (nu = {p['nu']:g}): no steady solution, "
                    "even with damping",
                    f"0 <= vstar < {vr:.10g} with damping > 0",
                    blamed,
                )
            continue
        vcr, _ = critical_speed(p["kw"], p["nu"], kp)
        if not p["vstar"] < vcr:
            # Blame the key that moved the point off the base parameters.
            culprit, allowed = where["vstar"], f"0 <= vstar < {vcr:.10g}"
            blamed = "vstar"
            if culprit.startswith("params."):
                for name in ("kw", "nu", "damping", "kp"):
                    if not where[name].startswith("params."):
                        culprit, blamed = where[name], name
                        allowed = (
                            f"{name} with V*_cr(kw, nu, kp) > vstar = {p['vstar']:g}"
                        )
                        if name == "damping":
                            allowed = "damping > 0 above V*_cr"
            raise c.fail(
                culprit,
                f"vstar = {p['vstar']:.10g} is at or above the critical speed "
                f"V*_cr = {vcr:.10g} (kw = {_fmt_num(p['kw'])}, nu = {p['nu']:g}"
                f"{f', kp = {kp:g}' if kp else ''}): "
                "no steady solution without damping",
                f"{allowed}, or damping > 0 (then vstar < V*_R)"
                if allowed.startswith("0 <=")
                else allowed,
                blamed,
            )


def _check_medium_speed(
    c: Checker, medium: Medium, p: Mapping[str, float], where: Mapping[str, str]
) -> None:
    """vstar < V*_cr of a layered medium (or one on a half-space) at the
    point ``p``; unchecked where the core cannot compute V*_cr (the run
    reports why). A quasi-static medium (inertia false): its speed must set
    the relaxation of a material given by tau, keep its deborah numbers in
    range and stay below the relaxed layer's V*_cr (``below_critical_speed``);
    a viscoelastic medium with inertia keeps its deborah numbers in range and
    stays below the relaxed V*_cr of a stack (one viscoelastic layer on
    springs runs on beyond it: ``Medium.beyond_critical``)."""
    from movingpunch.solver import below_critical_speed

    speed = p["vstar"]
    if not medium.inertia:
        if speed > 0.0 and not medium.speed_dependent:
            raise c.fail(
                where["vstar"],
                f"vstar = {speed:.10g} with inertia = false changes nothing: no "
                "material takes its relaxation from the speed",
                "vstar = 0, or a viscoelastic sublayer given by tau (taus)",
                "vstar",
            )
        try:
            if speed > 0.0:
                medium.at_speed(speed)
                below_critical_speed(medium, speed)
        except InvalidParameterError as exc:
            raise c.fail(where["vstar"], str(exc), exc.allowed or "", "vstar") from exc
        return
    if medium.speed_dependent and speed > 0.0:
        try:
            medium.at_speed(speed)
        except InvalidParameterError as exc:
            raise c.fail(where["vstar"], str(exc), exc.allowed or "", "vstar") from exc
    if medium.beyond_critical:
        # (A viscoelastic layer with its inertia runs on to V*_R: the solve
        # refuses a speed beyond it, naming vstar.)
        return
    vcr = medium_critical_speed(medium)
    if vcr is None or p["vstar"] == 0.0 or p["vstar"] < vcr:
        return
    culprit, blamed = where["vstar"], "vstar"
    allowed = f"0 <= vstar < {vcr:.10g}"
    if culprit.startswith("params.") and not where["kw"].startswith("params."):
        culprit, blamed = where["kw"], "kw"
        allowed = f"kw with V*_cr > vstar = {p['vstar']:g}"
    raise c.fail(
        culprit,
        f"vstar = {p['vstar']:.10g} is at or above the critical speed "
        f"V*_cr = {vcr:.10g} of the medium ({medium.describe()}): no steady "
        "solution",
        allowed,
        blamed,
    )


def _check_overlap(scene: SceneData, c: Checker) -> None:
    """The punches of every curve the scene computes (outputs other than
    critical_speed) must be a train the solver solves: each punch solved
    alone (cheap: the kernel is shared), its contact shifted to its ``at``;
    where two such contacts overlap the train is solved as the run solves it
    (``solve_punches``: together the punches lift each other, and their
    zones may well end apart), and the scene is refused, naming both
    punches, only when the solver refuses them as too close. A sweep's
    points are checked by their solves (an overlap is that point's
    error)."""
    from movingpunch.errors import MovingPunchError
    from movingpunch.solver import solve, solve_punches

    if not any(k != "critical_speed" for k in scene.outputs):
        return
    medium = scene.medium
    for vi, v in enumerate(scene.curve_values()):
        p = scene.point(v)
        train = train_of(scene.punches, p)
        vstar = p["vstar"]
        # The point's medium: its sublayers and base, or the homogeneous layer.
        on: dict[str, Any]
        if medium is not None:
            m = point_medium(medium, p)
            if not m.inertia:
                return  # a train is solved with the inertia: the run refuses it
            on = {"layers": list(m.layers), "base": m.base}
        else:
            on = {
                "kw": p["kw"],
                "nu": p["nu"],
                "kp": p.get("kp", 0.0),
                "damping": p.get("damping", 0.0),
            }
        ends: list[tuple[float, float, int]] = []
        for k, q in enumerate(train):
            try:
                alone = solve(
                    vstar=vstar,
                    **on,
                    profile=q.profile,
                    load=q.load,
                    tol=max(scene.tol, 1e-6),
                )
            except MovingPunchError:
                return  # the run reports it
            lo, hi = alone.contact_interval
            ends.append((q.at + lo, q.at + hi, k))
        ends.sort()
        close = [
            (a, b)
            for a, b in itertools.pairwise(ends)
            if b[0] <= a[1]  # alone, their contacts overlap
        ]
        if not close:
            continue
        try:
            solve_punches(train, vstar=vstar, **on, tol=scene.tol)
            continue  # together they keep apart: the run solves them
        except InvalidParameterError as err:
            if err.parameter != "punches":
                return  # the run reports it
            refused = str(err)
        except MovingPunchError:
            return  # the run reports it
        (l1, r1, k1), (l2, r2, k2) = next(
            (
                (a, b)
                for a, b in close
                if f"punches[{min(a[2], b[2])}] and punches[{max(a[2], b[2])}]"
                in refused
            ),
            close[0],
        )
        varied = scene.vary is not None and scene.vary.param in ("spacing", "load")
        key = f"vary.values[{vi}]" if varied else f"punches[{max(k1, k2)}].at"
        raise c.fail(
            key,
            f"punches[{k1}] and punches[{k2}] overlap: alone their contacts "
            f"span x/h = {l1:.6g} to {r1:.6g} and {l2:.6g} to {r2:.6g}, and "
            "solved together no contact set keeps them apart",
            "punches further apart",
        )


def _fmt_num(x: float) -> str:
    return "inf" if math.isinf(x) else f"{x:.10g}"
