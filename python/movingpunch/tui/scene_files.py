"""Between the app's state and ``movingpunch.scene`` files and bundled scenes.

Opening keeps the scene's parameters, medium (``[[layers]]``, ``[base]``),
accuracy, overlaid values (``[vary]``) and sweep; saving writes them back
with the outputs the app shows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from movingpunch.errors import InvalidParameterError
from movingpunch.media import HalfSpace
from movingpunch.profiles import Profile
from movingpunch.scene import (
    OutputSpec,
    Scene,
    SceneError,
    Sweep,
    Vary,
    bundled_scene_text,
    bundled_scenes,
)
from movingpunch.tui.model import (
    SCENE_PARAMS,
    Overlay,
    Params,
    SweepSpec,
    parse_contact,
    train_from,
    with_medium,
)
from movingpunch.tui.paths import WorkingFolder

SAVED_OUTPUTS: tuple[str, ...] = (
    "contact_width",
    "pressure",
    "surface_stress",
    "depth_stress",
    "stress_field",
)
"""What a saved scene asks for: the quantities of the app's tabs."""


@dataclass(frozen=True)
class SceneState:
    """What the app takes from (and gives to) a scene."""

    params: Params
    overlay: Overlay | None = None
    sweep: SweepSpec | None = None
    name: str = ""
    description: str = ""


def load(source: str | Path) -> SceneState:
    """A scene file (a path that exists or ends in .toml) or a bundled name.

    Raises SceneError (an InvalidParameterError) with a one-line message.
    """
    text = str(source)
    path = Path(text).expanduser()
    if path.exists() or text.endswith(".toml") or "/" in text:
        scene = Scene.load(path)
    else:
        scene = Scene.bundled(text)
    return from_scene(scene)


def is_file_name(folder: WorkingFolder, text: str) -> bool:
    """Whether the Open prompt takes ``text`` as a file (it exists in the
    folder, ends in .toml or has a folder in it) rather than a bundled
    scene's name."""
    p = Path(text)
    return p.suffix == ".toml" or len(p.parts) > 1 or (folder.root / text).exists()


def load_in(folder: WorkingFolder, text: str) -> SceneState:
    """What the Open prompt reads: a scene file inside the working folder
    (a name that exists there, ends in .toml or has a folder in it) or a
    bundled scene's name. Errors name the path as typed.

    Raises SceneError, or OutsideFolderError for a path leaving the folder.
    """
    if is_file_name(folder, text):
        real = folder.resolve(text)
        try:
            scene = Scene.load(real)
        except SceneError as exc:
            if exc.source != str(real):
                raise
            raise SceneError(
                text, exc.key, exc.problem, exc.allowed or "", exc.parameter
            ) from None
    elif bundled_scene_text(text) is not None:
        scene = Scene.bundled(text)
    else:
        raise SceneError(
            text,
            "(file)",
            "no such scene file or bundled scene",
            "a TOML file in the working folder, or one of "
            + ", ".join(bundled_scenes()),
        )
    return from_scene(scene)


def from_scene(scene: Scene) -> SceneState:
    values: dict[str, Any] = {
        name: float(scene.params.get(name, 0.0)) for name in SCENE_PARAMS
    }
    shape = scene.profile
    if scene.punches:
        # A train: its punches carry the loads and shapes; the panel shows
        # the first punch's (the train input holds them all).
        values["load"] = float(scene.punches[0].load)
        values["radius"] = float(scene.punches[0].profile.nominal_radius)
    if not math.isfinite(values["radius"]):  # a flat punch or a table: no radius
        values["radius"] = Params.radius
    params = Params(
        **values,
        tol=float(scene.tol),
        profile=shape.kind if shape is not None else "cylinder",
        half_width=float(getattr(shape, "half_width", Params.half_width)),
        table=shape if isinstance(shape, Profile) else None,
        **_zones_of(scene),
    )
    overlay = (
        None
        if scene.vary is None
        else Overlay(scene.vary.param, tuple(float(v) for v in scene.vary.values))
    )
    medium = scene.medium
    if medium is not None:
        # [[layers]] and [base]: under a half-space params holds no springs.
        half_space = medium.base if isinstance(medium.base, HalfSpace) else None
        if half_space is not None:
            params = replace(params, kw=Params.kw, kp=0.0, damping=0.0)
        params = with_medium(params, medium.layers, half_space, medium.inertia)
    sweep = None if scene.sweep is None else _sweep_spec(scene.sweep)
    return SceneState(
        params=params,
        overlay=overlay,
        sweep=sweep,
        name=scene.name,
        description=scene.description,
    )


def _sweep_spec(sweep: Sweep) -> SweepSpec:
    """A scene's sweep as the a/h tab's: a range stays a range (start, stop,
    points, spacing), explicit values stay explicit; it plots the drag when
    that is the scene's first quantity (a resistance curve), else a/h."""
    quantity = "drag" if sweep.quantities[:1] == ("drag",) else "a"
    if sweep.is_range:
        assert sweep.start is not None
        assert sweep.stop is not None
        return SweepSpec(
            param=sweep.param,
            start=float(sweep.start),
            stop=float(sweep.stop),
            points=int(sweep.points or len(sweep.values)),
            spacing=sweep.spacing,
            quantity=quantity,
        )
    values = tuple(float(v) for v in sweep.values)
    return SweepSpec(param=sweep.param, values=values, quantity=quantity)


def _sweep_of(spec: SweepSpec, params: Params) -> Sweep:
    """The a/h tab's sweep as a scene's: a range (the default one too) is
    written as start, stop, points and spacing; explicit values as values."""
    if spec.values is not None:
        values = tuple(float(v) for v in spec.values)
        return Sweep(param=spec.param, values=values, quantities=(spec.quantity,))
    start, stop = spec.bounds(params)
    return Sweep.range(
        spec.param,
        float(start),
        float(stop),
        spec.points,
        spacing=spec.spacing,
        quantities=(spec.quantity,),
    )


def _zones_of(scene: Scene) -> dict[str, Any]:
    """The contact mode and the train (``[[punches]]``) of a scene."""
    out: dict[str, Any] = {"contact": parse_contact(scene.contact)}
    if scene.punches:
        out["punches"] = train_from(scene.punches)
    return out


_TRAIN_PARAMS = frozenset({"vstar", "kw", "nu", "kp", "damping"})
"""The [params] keys a scene with [[punches]] takes."""


def _zone_fields(params: Params) -> dict[str, Any]:
    """What to give ``Scene`` for the contact mode and the train."""
    out: dict[str, Any] = {"contact": params.contact}
    if params.punches:
        out["punches"] = tuple(params.train())
    return out


def to_scene(state: SceneState) -> Scene:
    """The state as a Scene (validated: raises SceneError). A medium other
    than the homogeneous layer on springs is the scene's ``medium``
    (``[[layers]]`` and ``[base]``); ``params`` then holds no ν (each
    sublayer has its own) and, under a half-space, no kw, kp or damping."""
    vary = (
        None
        if state.overlay is None
        else Vary(state.overlay.param, tuple(state.overlay.values))
    )
    sweep = None
    spec = state.sweep
    if spec is not None and (vary is None or vary.param != spec.param):
        sweep = _sweep_of(spec, state.params)
    try:
        shape = state.params.shape()
    except InvalidParameterError as exc:
        raise SceneError("<terminal UI>", "params.profile", str(exc)) from exc
    extra = _zone_fields(state.params)
    physical = state.params.physical()
    medium = state.params.medium()
    if medium is not None:
        extra["medium"] = medium
        fixed = {"nu"} | ({"kw", "kp", "damping"} if state.params.half_space else set())
        physical = {k: v for k, v in physical.items() if k not in fixed}
    if state.params.punches:
        # A train: each punch carries its own load and shape.
        physical = {k: v for k, v in physical.items() if k in _TRAIN_PARAMS}
        shape = None
    return Scene(
        params=physical,
        profile=shape,
        outputs={kind: OutputSpec(kind) for kind in SAVED_OUTPUTS},
        vary=vary,
        sweep=sweep,
        tol=state.params.tol,
        name=state.name,
        description=state.description,
        **extra,
    )


def save(state: SceneState, path: Path) -> None:
    """Writes the state as a scene file (atomically)."""
    to_scene(state).save(path)
