"""What a scene is: its parts, their validation, and its TOML form.

A scene file is read with the standard library's ``tomllib`` (``tomli`` on
Python 3.10) and written by hand here (no writer dependency). Every problem is
reported as one ``SceneError`` line: ``FILE: key: problem (allowed: ...)``.
"""

from __future__ import annotations

import functools
import json
import math
import numbers
import os
import re
import stat
import sys
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from movingpunch.errors import InvalidParameterError
from movingpunch.params import PRESETS, SPECS, classify

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10 only
    import tomli as tomllib  # type: ignore[import-not-found, unused-ignore]

if TYPE_CHECKING:
    from movingpunch.scene._run import SceneResult

__all__ = [
    "OUTPUT_KINDS",
    "PARAMS",
    "SWEEP_QUANTITIES",
    "OutputSpec",
    "Scene",
    "SceneError",
    "Sweep",
    "Vary",
    "bundled_scenes",
]

PARAMS: tuple[str, ...] = ("vstar", "kw", "radius", "load", "nu", "damping")
"""The physical parameters of a scene, in the order they are written.
``nu`` defaults to 0.2; ``damping`` (c_w c_T/mu, the Kelvin-Voigt dashpots,
docs/damped.md) to 0 and is kept in ``params`` only when given."""

DAMPED_UNAVAILABLE: dict[str, str] = {
    "displacement": "the damped solver gives no displacement of the layer",
    "indentation": "the damped solver gives no indentation",
}
"""Outputs and sweep quantities a point with damping > 0 cannot give, with
the reason (docs/damped.md, section 3)."""

DAMPED_MAX_Y = -1e-3
"""Damped points evaluate stresses at y/h <= this (the Fourier integral of
the damped solver is not used closer to the surface): depths above it are
clipped to it."""


def _allowed(name: str) -> str:
    """What a scene accepts for the parameter ``name``: its range from the
    table of parameters (``movingpunch.params.SPECS``)."""
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
_OUTPUT_KEYS: dict[str, tuple[str, ...]] = {
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
    "critical_vstar": "critical speed V*_cr(kw, nu)",
    "phi1": "moving half-plane factor phi1",
    "drag": "horizontal force on the punch over P (0 without damping)",
    "contact_start": "trailing end -b/h of the contact (-a/h without damping)",
    "contact_end": "leading end a/h of the contact",
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

_MAX_POINTS = 100_000
_MAX_GRID = 1001  # per axis of a stress field
_MAX_SWEEP = 100_000
"""Most points a sweep computes in all: sweep values times vary values."""
_MAX_VARY = 20
MAX_SCENE_BYTES = 1 << 20
"""Largest scene file read (1 MiB); a long sweep is written as start, stop,
points rather than as a list of values."""
MAX_NESTING = 32
"""Deepest nesting of TOML arrays and inline tables in a scene (a scene needs
2); checked before parsing, which recurses."""
_DEFAULT_TOL = float(SPECS["tol"].default or 1e-8)
_DEFAULT_NU = float(SPECS["nu"].default or 0.2)
RADIUS_MAX, LOAD_MAX = SPECS["radius"].hi, SPECS["load"].hi
"""The largest R/h and P/(mu h) the contact solver takes (its validate() in
cpp/src/contact.cpp); a scene refuses larger ones before it runs
(test_scene_input.py::test_radius_and_load_limits_are_the_solvers)."""


class SceneError(InvalidParameterError):
    """A scene (file or object) is malformed or asks for something impossible.

    The message is one line, ``FILE: key: problem (allowed: ...)``; the
    attributes ``source``, ``key``, ``problem`` and ``allowed`` hold its parts,
    and ``parameter`` the model parameter at fault (``"vstar"``, ``"tol"``,
    ...; None when the key is not one, e.g. an output's ``points``).
    """

    def __init__(
        self,
        source: str,
        key: str,
        problem: str,
        allowed: str = "",
        parameter: str | None = None,
    ) -> None:
        self.source = source
        self.key = key
        self.problem = problem
        text = f"{source}: {key}: {problem}"
        if allowed:
            text += f" (allowed: {allowed})"
        super().__init__(" ".join(text.split()), parameter=parameter, allowed=allowed)


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
            values=_grid(float(start), float(stop), int(points), spacing),
            quantities=tuple(quantities),
            start=float(start),
            stop=float(stop),
            points=int(points),
            spacing=spacing,
        )

    @property
    def is_range(self) -> bool:
        return self.start is not None


def _grid(start: float, stop: float, points: int, spacing: str) -> tuple[float, ...]:
    if spacing == "log":
        grid = np.geomspace(start, stop, points)
    else:
        grid = np.linspace(start, stop, points)
    return tuple(grid.tolist())


@functools.lru_cache(maxsize=4096)
def critical_speed(kw: float, nu: float) -> tuple[float, float]:
    """(V*_cr, alpha h at the minimum) for (kw, nu), computed once per process."""
    from movingpunch import _core

    return _core.critical_speed(kw, nu)


@functools.lru_cache(maxsize=64)
def rayleigh_speed(nu: float) -> float:
    """V*_R(nu), computed once per process."""
    from movingpunch import _core

    return float(_core.rayleigh_vstar(nu))


# ----------------------------------------------------------------------------
# Reading a scene file
# ----------------------------------------------------------------------------

_FILE_KINDS: tuple[tuple[Callable[[int], bool], str], ...] = (
    (stat.S_ISDIR, "a directory"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def _file_kind(mode: int) -> str:
    for test, name in _FILE_KINDS:
        if test(mode):
            return name
    return "a special file"


def _read_scene_file(path: Path, source: str) -> str:
    """The text of a scene file: a regular file (checked before it is opened,
    and again on the open descriptor) of at most MAX_SCENE_BYTES, UTF-8. It
    is opened non-blocking, so that nothing here waits for a FIFO's writer;
    at most MAX_SCENE_BYTES + 1 bytes are read."""
    allowed = f"a regular file of at most {MAX_SCENE_BYTES >> 20} MiB"

    def refuse(problem: str, what: str = allowed) -> SceneError:
        return SceneError(source, "(file)", problem, what)

    def check(st: os.stat_result) -> None:
        if not stat.S_ISREG(st.st_mode):
            raise refuse(f"cannot read {_file_kind(st.st_mode)}")
        if st.st_size > MAX_SCENE_BYTES:
            raise refuse(f"too large: {st.st_size} bytes")

    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)
    try:
        check(os.stat(path))
        fd = os.open(path, flags)
    except OSError as exc:
        raise refuse(f"cannot read: {exc.strerror or exc}", "a readable file") from None
    chunks: list[bytes] = []
    size = 0
    try:
        check(os.fstat(fd))  # the file opened is the one checked
        while size <= MAX_SCENE_BYTES:
            chunk = os.read(fd, MAX_SCENE_BYTES + 1 - size)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as exc:
        raise refuse(f"cannot read: {exc.strerror or exc}", "a readable file") from None
    finally:
        os.close(fd)
    if size > MAX_SCENE_BYTES:  # it grew while it was read
        raise refuse(f"too large: more than {MAX_SCENE_BYTES} bytes")
    try:
        return b"".join(chunks).decode("utf-8")
    except UnicodeDecodeError as exc:
        raise SceneError(
            source,
            "(file)",
            f"not valid TOML: not UTF-8 text (byte {exc.start})",
            "a UTF-8 TOML document",
        ) from None


# Where the bracket depth of TOML text can change, and where strings and
# comments (inside which brackets do not count) begin.
_TOML_TOKEN = re.compile(r"\"\"\"|'''|[\"'#\[\]{}]")


# The body of each kind of TOML string, up to (not including) what ends it:
# "unrolled" patterns (no nested repetition of alternatives), which the
# regular-expression engine runs in time linear in the text.
_STRING_BODY = {
    '"': re.compile(r'[^"\\\n]*(?:\\.[^"\\\n]*)*'),
    "'": re.compile(r"[^'\n]*"),
    '"""': re.compile(r'[^"\\]*(?:(?:\\.|"(?!""))[^"\\]*)*', re.DOTALL),
    "'''": re.compile(r"[^']*(?:'(?!'')[^']*)*"),
}


def _closing(text: str, start: int, quote: str) -> int:
    """The index just past the string whose body starts at ``start``: past
    its closing ``quote`` (escaped quotes are skipped in basic strings; a
    multi-line string may end in up to two more quotes), or past the newline
    that ends an unterminated single-line string (the parser reports it)."""
    m = _STRING_BODY[quote].match(text, start)
    assert m is not None  # each pattern matches the empty string
    end = m.end()
    if len(quote) == 1:
        return end + 1  # past the quote, the newline, or a trailing backslash
    end += len(quote)
    extra = 0
    while extra < 2 and text.startswith(quote[0], end + extra):
        extra += 1
    return min(end + extra, len(text))


def _nesting_depth(text: str, limit: int) -> int:
    """The deepest nesting of arrays and inline tables (a table header counts
    1 or 2); brackets in strings and comments do not count. Stops as soon as
    the depth exceeds ``limit``. Linear in the text; never recurses."""
    depth = deepest = 0
    i = 0
    while True:
        m = _TOML_TOKEN.search(text, i)
        if m is None:
            return deepest
        tok, i = m.group(), m.end()
        if tok in "[{":
            depth += 1
            if depth > deepest:
                deepest = depth
                if deepest > limit:
                    return deepest
        elif tok in "]}":
            depth = max(depth - 1, 0)
        elif tok == "#":
            nl = text.find("\n", i)
            i = len(text) if nl == -1 else nl + 1
        else:
            i = _closing(text, i, tok)


# ----------------------------------------------------------------------------
# Validation of plain values
# ----------------------------------------------------------------------------


class _Checker:
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
            raise self.fail(key, f"must be a table, got {_show(value)}", names)
        for k in value:
            if k not in allowed:
                where = f"{key}.{k}" if key else str(k)
                raise self.fail(where, "unknown key", names)
        return value

    def number(self, key: str, value: object, allowed: str) -> float:
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
            raise self.fail(key, f"must be a number, got {_show(value)}", allowed)
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
        allowed = SPECS[name].text if name == "tol" else _allowed(name)
        if name == "kw" and isinstance(value, str):
            if value.strip().lower() in ("inf", "+inf", "infinity"):
                return math.inf
            raise self.fail(
                key, f"must be a number or 'inf', got {value!r}", allowed, name
            )
        x, problem = classify(name, value)
        if problem == "type":
            raise self.fail(key, f"must be a number, got {_show(value)}", allowed, name)
        if problem == "overflow":
            raise self.fail(key, "is too large for a float", allowed, name)
        if problem:
            raise self.fail(key, f"out of range: {_show(x)}", allowed, name)
        return x

    def integer(self, key: str, value: object, lo: int, hi: int) -> int:
        allowed = f"an integer {lo} to {hi}"
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
            raise self.fail(key, f"must be an integer, got {_show(value)}", allowed)
        if not lo <= int(value) <= hi:
            raise self.fail(key, f"out of range: {value}", allowed)
        return int(value)

    def string(self, key: str, value: object, choices: Sequence[str] = ()) -> str:
        allowed = ", ".join(choices) if choices else "a string"
        if not isinstance(value, str):
            raise self.fail(key, f"must be a string, got {_show(value)}", allowed)
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
                key, f"must be a list [low, high], got {_show(value)}", allowed
            )
        if len(value) != 2:
            raise self.fail(key, f"must have 2 numbers, got {len(value)}", allowed)
        lo = self.number(f"{key}[0]", value[0], allowed)
        hi = self.number(f"{key}[1]", value[1], allowed)
        if not (ok(lo) and ok(hi)):
            raise self.fail(key, f"out of range: [{_show(lo)}, {_show(hi)}]", allowed)
        if not lo < hi:
            raise self.fail(key, "low must be below high", allowed)
        if not math.isfinite(hi - lo):
            raise self.fail(key, "the span high - low overflows", allowed)
        return lo, hi


def _show(value: object) -> str:
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


# ----------------------------------------------------------------------------
# The scene
# ----------------------------------------------------------------------------

_TOP_KEYS = ("name", "description", "params", "outputs", "vary", "sweep", "accuracy")


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
    tol: float = _DEFAULT_TOL
    name: str = ""
    description: str = ""

    def __post_init__(self) -> None:
        _validate(self, "<Scene>")

    # -- construction -------------------------------------------------------

    @classmethod
    def from_toml(cls, text: str, source: str = "<string>") -> Scene:
        """Parses and validates a scene from TOML text (``source`` names it in
        errors)."""
        if not isinstance(text, str):
            raise SceneError(source, "(file)", "must be text", "a TOML document")
        if not text.strip():
            raise SceneError(
                source,
                "params",
                "missing: the file is empty",
                "a TOML document with [params] and [outputs] or [sweep]",
            )
        nesting = f"arrays and inline tables nested at most {MAX_NESTING} deep"
        if _nesting_depth(text, MAX_NESTING) > MAX_NESTING:
            raise SceneError(
                source, "(file)", f"nested more than {MAX_NESTING} deep", nesting
            )
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise SceneError(
                source, "(file)", f"not valid TOML: {exc}", "a TOML document"
            ) from None
        except RecursionError:  # a nesting the scan above did not see
            raise SceneError(source, "(file)", "nested too deeply", nesting) from None
        return _from_mapping(data, source)

    @classmethod
    def load(cls, path: str | Path) -> Scene:
        """Reads and validates a scene file. The scene's name defaults to the
        file's stem.

        Only a regular file of at most ``MAX_SCENE_BYTES`` is read (a FIFO,
        a device such as /dev/zero or a directory is refused before it is
        read from), UTF-8 text nested at most ``MAX_NESTING`` deep."""
        p = Path(path)
        source = str(path)
        text = _read_scene_file(p, source)
        scene = cls.from_toml(text, source)
        if not scene.name:
            scene = _replace(scene, name=p.stem)
        return scene

    @classmethod
    def bundled(cls, name: str) -> Scene:
        """One of the scenes shipped with the package (``bundled_scenes()``)."""
        text = _bundled_text(name)
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
        return _to_toml(self)

    def save(self, path: str | Path) -> None:
        """Writes ``to_toml()`` to ``path`` atomically (temp file, then rename;
        a new file gets the umask's mode, a replaced one keeps its mode).
        Raises ``OutputError`` (the path and the reason)."""
        from movingpunch.outputs import atomic_write

        atomic_write(Path(path), self.to_toml().encode("utf-8"))

    # -- running ------------------------------------------------------------

    def run(
        self,
        *,
        jobs: int | None = 1,
        progress: Callable[[int, int], None] | None = None,
        dask: str | None = None,
    ) -> SceneResult:
        """Computes what the scene asks for, and only that.

        ``jobs``: worker processes for a sweep (``None``: all cores; 1: in
        this process). ``dask``: address of a Dask scheduler to run the sweep
        on instead. ``progress(done, total)`` is called as solves finish.
        """
        from movingpunch.scene._run import run_scene

        return run_scene(self, jobs=jobs, progress=progress, dask=dask)

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
        if self.vary is not None and vary_value is not None:
            p[self.vary.param] = vary_value
        p.update(override)
        return p


def _replace(scene: Scene, **changes: Any) -> Scene:
    import dataclasses

    return dataclasses.replace(scene, **changes)


# ----------------------------------------------------------------------------
# From a mapping (TOML) to a Scene
# ----------------------------------------------------------------------------


def _from_mapping(data: Mapping[str, Any], source: str) -> Scene:
    c = _Checker(source)
    c.table("", data, _TOP_KEYS)
    name = c.string("name", data["name"]) if "name" in data else ""
    description = (
        c.string("description", data["description"]) if "description" in data else ""
    )

    vary = _parse_vary(c, data["vary"]) if "vary" in data else None
    sweep = _parse_sweep(c, data["sweep"]) if "sweep" in data else None
    if vary is not None and sweep is not None and vary.param == sweep.param:
        raise c.fail(
            "sweep.param",
            f"{sweep.param!r} is already the vary parameter",
            "a parameter other than vary.param",
        )

    if "params" not in data:
        raise c.fail("params", "missing", "a table [params] with " + ", ".join(PARAMS))
    raw_params = c.table("params", data["params"], PARAMS)
    params: dict[str, float] = {}
    for name_ in PARAMS:
        key = f"params.{name_}"
        if name_ in raw_params:
            params[name_] = c.param(key, name_, raw_params[name_])
        elif name_ == "nu":
            params[name_] = _DEFAULT_NU
        elif vary is not None and vary.param == name_:
            params[name_] = vary.values[0]
        elif sweep is not None and sweep.param == name_:
            params[name_] = sweep.values[0]
        elif name_ != "damping":  # damping: optional, 0
            raise c.fail(key, "missing", _allowed(name_), name_)

    tol = _DEFAULT_TOL
    if "accuracy" in data:
        acc = c.table("accuracy", data["accuracy"], ("tol",))
        if "tol" in acc:
            tol = c.tol("accuracy.tol", acc["tol"])

    outputs: dict[str, OutputSpec] = {}
    if "outputs" in data:
        raw_outputs = c.table("outputs", data["outputs"], OUTPUT_KINDS)
        for kind, spec in raw_outputs.items():
            parsed = _parse_output(c, kind, spec)
            if parsed is not None:
                outputs[kind] = parsed

    scene = Scene.__new__(Scene)
    for k, v in {
        "params": params,
        "outputs": outputs,
        "vary": vary,
        "sweep": sweep,
        "tol": tol,
        "name": name,
        "description": description,
    }.items():
        object.__setattr__(scene, k, v)
    _validate(scene, source)
    return scene


def _values_list(
    c: _Checker, key: str, param: str, raw: object, limit: int
) -> tuple[float, ...]:
    if isinstance(raw, (str, bytes)) or not isinstance(raw, Sequence):
        raise c.fail(key, f"must be a list, got {_show(raw)}", _allowed(param), param)
    if not 1 <= len(raw) <= limit:
        raise c.fail(key, f"has {len(raw)} values", f"1 to {limit} values")
    values = tuple(c.param(f"{key}[{i}]", param, v) for i, v in enumerate(raw))
    if len(set(values)) != len(values):
        raise c.fail(key, "values repeat", "distinct values")
    return values


def _parse_vary(c: _Checker, raw: object) -> Vary:
    t = c.table("vary", raw, ("param", "values"))
    if "param" not in t:
        raise c.fail("vary.param", "missing", ", ".join(PARAMS))
    param = c.string("vary.param", t["param"], PARAMS)
    if "values" not in t:
        raise c.fail("vary.values", "missing", _allowed(param), param)
    return Vary(param, _values_list(c, "vary.values", param, t["values"], _MAX_VARY))


def _parse_sweep(c: _Checker, raw: object) -> Sweep:
    keys = ("param", "values", "start", "stop", "points", "spacing", "quantities")
    t = c.table("sweep", raw, keys)
    if "param" not in t:
        raise c.fail("sweep.param", "missing", ", ".join(PARAMS))
    param = c.string("sweep.param", t["param"], PARAMS)
    quantities: tuple[str, ...] = ("a", "p0")
    if "quantities" in t:
        q = t["quantities"]
        if isinstance(q, str) or not isinstance(q, Sequence) or not q:
            raise c.fail(
                "sweep.quantities",
                f"must be a non-empty list, got {_show(q)}",
                ", ".join(SWEEP_QUANTITIES),
            )
        quantities = tuple(
            c.string(f"sweep.quantities[{i}]", v, tuple(SWEEP_QUANTITIES))
            for i, v in enumerate(q)
        )
        if len(set(quantities)) != len(quantities):
            raise c.fail("sweep.quantities", "quantities repeat", "distinct names")
    range_keys = [k for k in ("start", "stop", "points", "spacing") if k in t]
    if "values" in t:
        if range_keys:
            raise c.fail(
                f"sweep.{range_keys[0]}",
                "cannot be combined with sweep.values",
                "either values = [...] or start, stop, points (, spacing)",
            )
        values = _values_list(c, "sweep.values", param, t["values"], _MAX_SWEEP)
        return Sweep(param, values, quantities)
    for k in ("start", "stop", "points"):
        if k not in t:
            raise c.fail(
                f"sweep.{k}", "missing", "either values = [...] or start, stop, points"
            )
    start, stop, points, spacing = _range_bounds(
        c, param, t["start"], t["stop"], t["points"], t.get("spacing", "linear")
    )
    return Sweep.range(
        param, start, stop, points, spacing=spacing, quantities=quantities
    )


def _range_bounds(
    c: _Checker,
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
    points = c.integer("sweep.points", points_, 2, _MAX_SWEEP)
    spacing = c.string("sweep.spacing", spacing_, ("linear", "log"))
    if start == stop:
        raise c.fail("sweep.stop", "equals sweep.start", "stop != start")
    if spacing == "log" and min(start, stop) <= 0:
        raise c.fail(
            "sweep.start", "log spacing needs positive bounds", "start, stop > 0"
        )
    return start, stop, points, spacing


def _check_range(c: _Checker, s: Sweep) -> None:
    """A range sweep: its bounds, and its values the grid they span (which
    lies between two valid bounds: no value needs a check of its own)."""
    start, stop, points, spacing = _range_bounds(
        c, s.param, s.start, s.stop, s.points, s.spacing
    )
    if s.values != _grid(start, stop, points, spacing):
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


def _parse_output(c: _Checker, kind: str, raw: object) -> OutputSpec | None:
    key = f"outputs.{kind}"
    if isinstance(raw, bool):
        return OutputSpec(kind) if raw else None
    t = c.table(key, raw, _OUTPUT_KEYS[kind])
    spec: dict[str, Any] = {}
    if "x" in t:
        spec["x"] = c.pair(f"{key}.x", t["x"], "[low, high], finite x/h, low < high")
    if "y" in t:
        spec["y"] = c.pair(
            f"{key}.y", t["y"], "[low, high], -1 <= y/h <= 0, low < high", _in_layer
        )
    if "points" in t:
        hi = _MAX_GRID if kind == "stress_field" else _MAX_POINTS
        spec["points"] = c.integer(f"{key}.points", t["points"], 2, hi)
    if "depth_points" in t:
        spec["depth_points"] = c.integer(
            f"{key}.depth_points", t["depth_points"], 2, _MAX_GRID
        )
    if "depth" in t:
        d = c.number(f"{key}.depth", t["depth"], "-1 <= y/h <= 0")
        if not _in_layer(d):
            raise c.fail(f"{key}.depth", f"out of range: {_show(d)}", "-1 <= y/h <= 0")
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


def _validate(scene: Scene, source: str) -> None:
    c = _Checker(source)
    if not isinstance(scene.params, Mapping):
        raise c.fail("params", "must be a mapping", ", ".join(PARAMS))
    c.table("params", scene.params, PARAMS)
    params: dict[str, float] = {}
    for name in PARAMS:
        if name not in scene.params:
            if name == "nu":
                params[name] = _DEFAULT_NU
                continue
            if name == "damping":  # optional, 0; kept only when given
                continue
            raise c.fail(f"params.{name}", "missing", _allowed(name), name)
        params[name] = c.param(f"params.{name}", name, scene.params[name])
    object.__setattr__(scene, "params", params)

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
        as_toml = dict(_output_items(spec))
        checked = _parse_output(c, kind, as_toml)
        if checked != spec:
            raise c.fail(
                f"outputs.{kind}",
                "has keys this output does not take",
                ", ".join(_OUTPUT_KEYS[kind]) or "no keys",
            )
        outputs[kind] = spec
    object.__setattr__(scene, "outputs", outputs)

    if scene.vary is not None:
        v = scene.vary
        if not isinstance(v, Vary):
            raise c.fail("vary", "must be a Vary")
        c.string("vary.param", v.param, PARAMS)
        _values_list(c, "vary.values", v.param, list(v.values), _MAX_VARY)
    if scene.sweep is not None:
        s = scene.sweep
        if not isinstance(s, Sweep):
            raise c.fail("sweep", "must be a Sweep")
        c.string("sweep.param", s.param, PARAMS)
        if s.is_range:
            _check_range(c, s)
        else:
            _values_list(c, "sweep.values", s.param, list(s.values), _MAX_SWEEP)
        n_curves = len(scene.curve_values())
        if n_curves * len(s.values) > _MAX_SWEEP:
            raise c.fail(
                "sweep.points" if s.is_range else "sweep.values",
                f"{len(s.values)} sweep values times {n_curves} vary values are "
                f"{n_curves * len(s.values)} points",
                f"at most {_MAX_SWEEP} points in all",
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
    if not outputs and scene.sweep is None:
        raise c.fail(
            "outputs",
            "nothing to compute",
            "at least one of " + ", ".join(OUTPUT_KINDS) + ", or a [sweep]",
        )
    _check_speeds(scene, c)


def _sweep_extremes(sweep: Sweep) -> list[int]:
    """The indices of the smallest and the largest sweep value, in order.

    They decide the speed checks of the whole sweep: the bound on vstar,
    V*_cr(kw, nu), grows with kw and with nu, and V*_R(nu) with nu
    (test_scene_input.py checks both on dense grids), so the tightest point
    of a sweep over vstar, kw or nu is its largest vstar or its smallest kw
    or nu; over damping, the smallest value is the only one that may be 0
    (the undamped check) and the largest the one most surely > 0. Validation
    thus solves O(1) critical speeds per sweep, not one per point."""
    n = len(sweep.values)
    if sweep.is_range:
        return [0, n - 1]
    values = np.asarray(sweep.values, dtype=np.float64)
    return sorted({int(np.argmin(values)), int(np.argmax(values))})


def _check_speeds(scene: Scene, c: _Checker) -> None:
    """vstar < V*_cr(kw, nu) for every combination the scene computes
    (vstar < V*_R(nu) where damping > 0), and no output or sweep quantity
    the damped solver cannot give at a point with damping > 0. Of a sweep
    only its extremes are checked (``_sweep_extremes``)."""
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
    seen: set[tuple[float, float, float, bool]] = set()
    damped_where: str | None = None
    for p, where in combos:
        damped = p.get("damping", 0.0) > 0.0
        if damped and damped_where is None:
            damped_where = where["damping"]
        key = (p["vstar"], p["kw"], p["nu"], damped)
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
        vcr, _ = critical_speed(p["kw"], p["nu"])
        if not p["vstar"] < vcr:
            # Blame the key that moved the point off the base parameters.
            culprit, allowed = where["vstar"], f"0 <= vstar < {vcr:.10g}"
            blamed = "vstar"
            if culprit.startswith("params."):
                for name in ("kw", "nu", "damping"):
                    if not where[name].startswith("params."):
                        culprit, blamed = where[name], name
                        allowed = f"{name} with V*_cr(kw, nu) > vstar = {p['vstar']:g}"
                        if name == "damping":
                            allowed = "damping > 0 above V*_cr"
            raise c.fail(
                culprit,
                f"vstar = {p['vstar']:.10g} is at or above the critical speed "
                f"V*_cr = {vcr:.10g} (kw = {_fmt_num(p['kw'])}, nu = {p['nu']:g}): "
                "no steady solution without damping",
                f"{allowed}, or damping > 0 (then vstar < V*_R)"
                if allowed.startswith("0 <=")
                else allowed,
                blamed,
            )
    if damped_where is not None:
        _check_damped_outputs(scene, c, damped_where)


def _check_damped_outputs(scene: Scene, c: _Checker, damped_where: str) -> None:
    """Outputs and sweep quantities a damped point cannot give, and depth
    ranges that lie wholly above y/h = -1e-3 (``DAMPED_MAX_Y``)."""
    why = f"damping > 0 at {damped_where}"
    for kind, spec in scene.outputs.items():
        if kind in DAMPED_UNAVAILABLE:
            raise c.fail(
                f"outputs.{kind}",
                f"not available with {why}: {DAMPED_UNAVAILABLE[kind]}",
                "contact_width, pressure, surface_stress, depth_stress, "
                "stress_field, critical_speed",
            )
        if kind in ("depth_stress", "stress_field"):
            lo, _ = spec.resolved_y()
            if lo > DAMPED_MAX_Y:
                raise c.fail(
                    f"outputs.{kind}.y",
                    f"lies above y/h = {DAMPED_MAX_Y:g}, where the damped solver "
                    f"gives no stresses ({why})",
                    f"a range reaching below y/h = {DAMPED_MAX_Y:g}",
                )
    if scene.sweep is not None:
        for i, q in enumerate(scene.sweep.quantities):
            if q in DAMPED_UNAVAILABLE:
                raise c.fail(
                    f"sweep.quantities[{i}]",
                    f"{q!r} is not available with {why}: {DAMPED_UNAVAILABLE[q]}",
                    ", ".join(
                        k for k in SWEEP_QUANTITIES if k not in DAMPED_UNAVAILABLE
                    ),
                )


def _fmt_num(x: float) -> str:
    return "inf" if math.isinf(x) else f"{x:.10g}"


# ----------------------------------------------------------------------------
# TOML writing
# ----------------------------------------------------------------------------


def _toml_value(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        text = repr(value)
        return text if any(ch in text for ch in ".en") else text + ".0"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} as TOML")


def _output_items(spec: OutputSpec) -> list[tuple[str, object]]:
    items: list[tuple[str, object]] = []
    for key in ("x", "y", "points", "depth_points", "depth", "component", "kw"):
        value = getattr(spec, key)
        if value is not None:
            items.append((key, list(value) if isinstance(value, tuple) else value))
    return items


def _to_toml(scene: Scene) -> str:
    lines: list[str] = []
    if scene.name:
        lines.append(f"name = {_toml_value(scene.name)}")
    if scene.description:
        lines.append(f"description = {_toml_value(scene.description)}")
    if lines:
        lines.append("")
    lines.append("[params]")
    for name in PARAMS:
        if name in scene.params:
            lines.append(f"{name} = {_toml_value(scene.params[name])}")
    lines += ["", "[accuracy]", f"tol = {_toml_value(scene.tol)}"]
    if scene.outputs:
        lines += ["", "[outputs]"]
        for kind, spec in scene.outputs.items():
            items = _output_items(spec)
            if items:
                body = ", ".join(f"{k} = {_toml_value(v)}" for k, v in items)
                lines.append(f"{kind} = {{ {body} }}")
            else:
                lines.append(f"{kind} = true")
    if scene.vary is not None:
        lines += [
            "",
            "[vary]",
            f"param = {_toml_value(scene.vary.param)}",
            f"values = {_toml_value(list(scene.vary.values))}",
        ]
    if scene.sweep is not None:
        s = scene.sweep
        lines += ["", "[sweep]", f"param = {_toml_value(s.param)}"]
        if s.is_range:
            lines += [
                f"start = {_toml_value(s.start)}",
                f"stop = {_toml_value(s.stop)}",
                f"points = {_toml_value(s.points)}",
                f"spacing = {_toml_value(s.spacing)}",
            ]
        else:
            lines.append(f"values = {_toml_value(list(s.values))}")
        lines.append(f"quantities = {_toml_value(list(s.quantities))}")
    return "\n".join(lines) + "\n"


# ----------------------------------------------------------------------------
# Bundled scenes
# ----------------------------------------------------------------------------


def _bundled_dir() -> Any:
    return resources.files("movingpunch").joinpath("scenes")


def _bundled_names() -> list[str]:
    names = [
        entry.name[: -len(".toml")]
        for entry in _bundled_dir().iterdir()
        if entry.name.endswith(".toml")
    ]
    order = ["table1", "fig2", "fig3", "fig4", "fig5", "fig6"]
    return sorted(
        names, key=lambda n: (order.index(n) if n in order else len(order), n)
    )


def _bundled_text(name: str) -> str:
    names = _bundled_names()
    if name not in names:
        raise SceneError(
            f"<bundled scene {name}>",
            "name",
            f"no bundled scene {name!r} and no such file",
            ", ".join(names),
        )
    text: str = _bundled_dir().joinpath(f"{name}.toml").read_text(encoding="utf-8")
    return text


def bundled_scenes() -> dict[str, str]:
    """The scenes shipped with the package: name -> one-line description."""
    out: dict[str, str] = {}
    for name in _bundled_names():
        scene = Scene.bundled(name)
        out[name] = scene.description.splitlines()[0] if scene.description else ""
    return out


def bundled_scene_text(name: str) -> str | None:
    """The TOML text (with its comments) of a bundled scene, None if there is
    no bundled scene of that name."""
    if name not in _bundled_names():
        return None
    return _bundled_text(name)


def load_scene(ref: str | Path) -> Scene:
    """A scene from a file path, or else the bundled scene of that name."""
    p = Path(ref)
    if p.exists() or p.suffix == ".toml" or len(p.parts) > 1:
        return Scene.load(p)
    names = _bundled_names()
    if str(ref) in names:
        return Scene.bundled(str(ref))
    raise SceneError(
        str(ref),
        "(file)",
        "no such scene file or bundled scene",
        "a TOML file, or one of " + ", ".join(names),
    )
