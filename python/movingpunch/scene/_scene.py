"""The scene: ``Scene`` (a validated configuration, read from and written to
TOML, run), ``SceneResult`` (what a run gives, with the scene that ran), and
the ways to get a scene by name: ``load_scene``, ``bundled_scenes``.

The modules below do the work: ``_model`` (the parts), ``_validate``,
``_toml`` (reading and writing), ``_bundled`` (the shipped files) and
``_run`` (the computation); they read a scene through ``SceneData``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from movingpunch.cancel import Cancel, bound
from movingpunch.errors import SceneError
from movingpunch.media import Medium
from movingpunch.outputs import atomic_write
from movingpunch.profiles import PunchProfile
from movingpunch.scene._bundled import bundled_names, bundled_text
from movingpunch.scene._model import (
    DEFAULT_TOL,
    PARAMS,
    OutputSpec,
    Sweep,
    Vary,
)
from movingpunch.scene._result import RunRecord
from movingpunch.scene._run import run_scene
from movingpunch.scene._toml import parse_toml, read_scene_file, to_toml
from movingpunch.scene._validate import validate
from movingpunch.zones import Punch

__all__ = ["Scene", "SceneResult", "bundled_scenes", "load_scene"]


@dataclass(frozen=True)
class Scene:
    """A physical configuration, the outputs to show, optional overlaid
    curves (``vary``) or a parameter sweep (``sweep``), and an accuracy.

    Built directly, ``Scene.load(path)``, ``Scene.from_toml(text)`` or
    ``Scene.bundled(name)``; every way validates (``SceneError``).
    ``params`` holds vstar, kw (``math.inf``: rigid base), radius, load, nu.
    """

    params: Mapping[str, float]
    outputs: Mapping[str, OutputSpec] = field(default_factory=dict)
    vary: Vary | None = None
    sweep: Sweep | None = None
    tol: float = DEFAULT_TOL
    name: str = ""
    description: str = ""
    profile: PunchProfile | None = None
    """The punch's shape (``[params.profile]``); None: a cylinder of
    ``params.radius`` (a Cylinder profile becomes that). Beside another
    profile ``params.radius`` is its nominal radius (inf for a flat punch or
    a table) and cannot vary."""
    punches: tuple[Punch, ...] = ()
    """A train of punches (``[[punches]]``, ``movingpunch.Punch`` each),
    solved together by ``movingpunch.solve_punches``; ``params`` then holds
    no radius and no load (each punch has its own). A vary or sweep over
    ``load`` sets the train's total load (every punch's load scaled in
    proportion), over ``spacing`` places the punches equally spaced, centred
    on x = 0."""
    contact: str = "auto"
    """``[params] contact``: "auto" (several contact zones where the single
    contact separates) or "single" (the single contact, flagged invalid where
    it is unphysical), as ``movingpunch.solve``'s ``contact``."""
    medium: Medium | None = None
    """The medium under the punch (``[[layers]]`` and ``[base]``,
    ``movingpunch.Medium``); None: the homogeneous layer of ``params`` nu on
    the springs of ``params`` kw, kp, damping. With a medium ``params.nu``
    is its top sublayer's, and ``params`` kw, kp, damping are its springs
    (a vary or sweep over them changes the springs); under a half-space
    ``params`` holds none of them."""

    def __post_init__(self) -> None:
        validate(self, "<Scene>")

    # -- construction -------------------------------------------------------

    @classmethod
    def from_toml(cls, text: str, source: str = "<string>") -> Scene:
        """Parses and validates a scene from TOML text (``source`` names it in
        errors)."""
        scene = cls.__new__(cls)
        for key, value in parse_toml(text, source).items():
            object.__setattr__(scene, key, value)
        validate(scene, source)
        return scene

    @classmethod
    def load(cls, path: str | Path) -> Scene:
        """Reads and validates a scene file. The scene's name defaults to the
        file's stem.

        Only a regular file of at most ``MAX_SCENE_BYTES`` is read (a FIFO,
        a device such as /dev/zero or a directory is refused before it is
        read from), UTF-8 text nested at most ``MAX_NESTING`` deep."""
        p = Path(path)
        source = str(path)
        text = read_scene_file(p, source)
        scene = cls.from_toml(text, source)
        if not scene.name:
            scene = _replace(scene, name=p.stem)
        return scene

    @classmethod
    def bundled(cls, name: str) -> Scene:
        """One of the scenes shipped with the package (``bundled_scenes()``)."""
        text = bundled_text(name)
        return cls.from_toml(text, f"<bundled scene {name}>")

    def with_params(self, **changes: float) -> Scene:
        """A copy with some of ``params`` changed, validated."""
        for key in changes:
            if key not in PARAMS:
                raise SceneError(
                    "<Scene>", f"params.{key}", "unknown key", ", ".join(PARAMS)
                )
        return _replace(self, params={**self.params, **changes})

    # -- writing ------------------------------------------------------------

    def to_toml(self) -> str:
        """The scene as TOML text that ``Scene.from_toml`` reads back equal."""
        return to_toml(self)

    def save(self, path: str | Path) -> None:
        """Writes ``to_toml()`` to ``path`` atomically (temp file, then rename;
        a new file gets the umask's mode, a replaced one keeps its mode).
        Raises ``OutputError`` (the path and the reason)."""
        atomic_write(Path(path), self.to_toml().encode("utf-8"))

    # -- running ------------------------------------------------------------

    def run(
        self,
        *,
        jobs: int | None = 1,
        progress: Callable[[int, int], None] | None = None,
        dask: str | None = None,
        dask_timeout: float | None = None,
        on_dask: Callable[[str, float], None] | None = None,
        cancel: Cancel | None = None,
        keep_solutions: bool = False,
    ) -> SceneResult:
        """Computes what the scene asks for, and only that.

        ``jobs``: at most this many processes for a sweep (``None``: all
        cores; 1: this process alone); a sweep too short for worker processes
        to pay for their start-up runs in this process (``result.jobs`` is
        then 1). ``dask``: address of a Dask scheduler to run the sweep
        on instead; ``dask_timeout``: seconds any wait on it may last
        (default ``DASK_CONNECT_TIMEOUT``, 20); ``on_dask(event, value)``
        hears ``("connecting", timeout)`` and ``("connected", workers)``.
        ``progress(done, total)`` is called as solves finish. ``cancel``: a
        ``movingpunch.Cancel`` token whose ``cancel()`` stops the run with
        ``movingpunch.Cancelled`` (a sweep on worker processes between
        chunks, its pool shut down). ``keep_solutions``: keep every sweep
        point solved in this process in ``solutions`` (by default a sweep
        keeps only its table, so that its memory does not grow with its
        points beyond the table itself; the curves' solutions are kept).
        """
        if not isinstance(keep_solutions, bool):
            raise TypeError(
                f"keep_solutions must be True or False, got {keep_solutions!r}"
            )
        if dask_timeout is not None and not (
            isinstance(dask_timeout, (int, float))
            and math.isfinite(dask_timeout)
            and dask_timeout > 0
        ):
            raise ValueError(
                f"dask_timeout must be a number of seconds > 0, got {dask_timeout!r}"
            )
        with bound(cancel):
            record = run_scene(
                self,
                jobs=jobs,
                progress=progress,
                dask=dask,
                dask_timeout=dask_timeout,
                on_dask=on_dask,
                keep_solutions=keep_solutions,
            )
        return SceneResult(scene=self, **vars(record))

    # -- derived ------------------------------------------------------------

    def curve_values(self) -> tuple[float | None, ...]:
        """The value of the vary parameter of each overlaid curve (``(None,)``
        without ``vary``)."""
        return (None,) if self.vary is None else self.vary.values

    def point(
        self, vary_value: float | None = None, **override: float
    ) -> dict[str, float]:
        """The parameters of one computation: ``params`` with the vary value
        and any overrides applied."""
        p = dict(self.params)
        if self.punches:  # the train's total load, the first punch's radius
            p["load"] = math.fsum(q.load for q in self.punches)
            p["radius"] = self.punches[0].profile.nominal_radius
        if self.vary is not None and vary_value is not None:
            p[self.vary.param] = vary_value
        p.update(override)
        return p


def _replace(scene: Scene, **changes: Any) -> Scene:
    return dataclasses.replace(scene, **changes)


@dataclass(frozen=True)
class SceneResult(RunRecord):
    """What a scene run computed, and the record of the work it did: a
    ``RunRecord`` with the ``scene`` that ran."""

    scene: Scene = field(kw_only=True)


def bundled_scenes() -> dict[str, str]:
    """The scenes shipped with the package: name -> one-line description."""
    out: dict[str, str] = {}
    for name in bundled_names():
        scene = Scene.bundled(name)
        out[name] = scene.description.splitlines()[0] if scene.description else ""
    return out


def load_scene(ref: str | Path) -> Scene:
    """A scene from a file path, or else the bundled scene of that name."""
    p = Path(ref)
    if p.exists() or p.suffix == ".toml" or len(p.parts) > 1:
        return Scene.load(p)
    names = bundled_names()
    if str(ref) in names:
        return Scene.bundled(str(ref))
    raise SceneError(
        str(ref),
        "(file)",
        "no such scene file or bundled scene",
        "a TOML file, or one of " + ", ".join(names),
    )
