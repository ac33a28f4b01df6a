"""A scene's TOML form: reading a scene file (safely: only a regular file of
bounded size and nesting), parsing its tables into a scene's fields, and
writing a scene back as TOML text that reads back equal.

A scene file is read with the standard library's ``tomllib`` (``tomli`` on
Python 3.10) and written by hand here (no writer dependency).
"""

from __future__ import annotations

import json
import math
import os
import re
import stat
import sys
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from movingpunch.errors import SceneError
from movingpunch.media import HalfSpace, Layer, Medium, Winkler
from movingpunch.params import OPTIONAL
from movingpunch.profiles import Cylinder
from movingpunch.scene._model import (
    CONTACT_MODES,
    DEFAULT_NU,
    DEFAULT_TOL,
    MAX_NESTING,
    MAX_SCENE_BYTES,
    MAX_SWEEP,
    MAX_VARY,
    OUTPUT_KINDS,
    PARAMS,
    SPRING_PARAMS,
    SWEEP_QUANTITIES,
    TRAIN_PARAMS,
    OutputSpec,
    SceneData,
    Sweep,
    Vary,
    allowed_text,
    output_items,
)
from movingpunch.scene._validate import (
    Checker,
    parse_base,
    parse_layers,
    parse_output,
    parse_profile,
    parse_punches,
    range_bounds,
    show,
    values_list,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10 only
    import tomli as tomllib  # type: ignore[import-not-found, unused-ignore]

__all__ = ["parse_toml", "read_bounded_file", "read_scene_file", "to_toml", "tomllib"]

_TOP_KEYS = (
    "name",
    "description",
    "params",
    "punches",
    "layers",
    "base",
    "outputs",
    "vary",
    "sweep",
    "accuracy",
)
_AXIS_PARAMS = (*PARAMS, *TRAIN_PARAMS)  # spacing: validate checks the punches


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


def read_bounded_file(
    path: Path, limit: int, refuse: Callable[[str, str], Exception]
) -> bytes:
    """The bytes of a regular file (checked before it is opened, and again on
    the open descriptor) of at most ``limit`` bytes: the reader of scene files
    and of the CLI's profile tables. It is opened non-blocking, so that
    nothing here waits for a FIFO's writer; at most ``limit + 1`` bytes are
    read (a device such as /dev/zero is refused before any). A refusal raises
    ``refuse(problem, allowed)``."""
    allowed = f"a regular file of at most {_bytes(limit)}"

    def check(st: os.stat_result) -> None:
        if not stat.S_ISREG(st.st_mode):
            raise refuse(f"cannot read {_file_kind(st.st_mode)}", allowed)
        if st.st_size > limit:
            raise refuse(f"too large: {st.st_size} bytes", allowed)

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
        while size <= limit:
            chunk = os.read(fd, limit + 1 - size)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as exc:
        raise refuse(f"cannot read: {exc.strerror or exc}", "a readable file") from None
    finally:
        os.close(fd)
    if size > limit:  # it grew while it was read
        raise refuse(f"too large: more than {limit} bytes", allowed)
    return b"".join(chunks)


def _bytes(n: int) -> str:
    """A size limit for a message: "1 MiB" for a whole number of MiB."""
    return f"{n >> 20} MiB" if n >= 1 << 20 and n % (1 << 20) == 0 else f"{n} bytes"


def read_scene_file(path: Path, source: str) -> str:
    """The text of a scene file: a regular file of at most MAX_SCENE_BYTES
    (``read_bounded_file``), UTF-8."""
    data = read_bounded_file(
        path,
        MAX_SCENE_BYTES,
        lambda problem, allowed: SceneError(source, "(file)", problem, allowed),
    )
    try:
        return data.decode("utf-8")
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


def parse_toml(text: str, source: str) -> dict[str, Any]:
    """The fields of the scene in the TOML ``text`` (``source`` names it in
    errors), each value checked; the scene built from them is validated as a
    whole by ``Scene``."""
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


def _from_mapping(data: Mapping[str, Any], source: str) -> dict[str, Any]:
    c = Checker(source)
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
    raw_params = c.table(
        "params", data["params"], (*PARAMS, "profile", "contact", "inertia")
    )
    profile = (
        parse_profile(c, raw_params["profile"]) if "profile" in raw_params else None
    )
    punches = parse_punches(c, data["punches"]) if "punches" in data else ()
    layers = parse_layers(c, data["layers"]) if "layers" in data else None
    base = parse_base(c, data["base"]) if "base" in data else None
    if layers is not None and "nu" in raw_params:
        raise c.fail(
            "params.nu",
            "is given together with [[layers]] (each sublayer has its own nu)",
            "no nu in [params] beside [[layers]]: give nu in each [[layers]] table",
            "nu",
        )
    if base is not None:
        for name_ in SPRING_PARAMS:
            if name_ in raw_params:
                kind = "winkler" if isinstance(base, Winkler) else "half_space"
                why = (
                    "give the springs once, in [base]"
                    if kind == "winkler"
                    else "a half-space has no springs"
                )
                raise c.fail(
                    f"params.{name_}",
                    f'is given together with [base] kind = "{kind}" ({why})',
                    f"no {name_} in [params] beside [base]",
                    name_,
                )
    contact = "auto"
    if "contact" in raw_params:
        contact = c.string("params.contact", raw_params["contact"], CONTACT_MODES)
    params: dict[str, float] = {}
    for name_ in PARAMS:
        key = f"params.{name_}"
        if name_ == "radius" and profile is not None and name_ not in raw_params:
            continue  # the profile's (validate sets it)
        if punches and name_ in ("radius", "load") and name_ not in raw_params:
            continue  # the punches' own (validate refuses them in [params])
        if base is not None and name_ in SPRING_PARAMS:
            if isinstance(base, Winkler) and (name_ == "kw" or getattr(base, name_)):
                params[name_] = float(getattr(base, name_))
            continue  # the base's (none under a half-space)
        if layers is not None and name_ == "nu":
            params[name_] = layers[0].nu  # the top sublayer's
            continue
        if name_ in raw_params:
            params[name_] = c.param(key, name_, raw_params[name_])
        elif name_ == "nu":
            params[name_] = DEFAULT_NU
        elif vary is not None and vary.param == name_:
            params[name_] = vary.values[0]
        elif sweep is not None and sweep.param == name_:
            params[name_] = sweep.values[0]
        elif name_ not in OPTIONAL:  # optional, 0
            raise c.fail(key, "missing", allowed_text(name_), name_)

    inertia = True
    if "inertia" in raw_params:
        inertia = raw_params["inertia"]
        if not isinstance(inertia, bool):
            raise c.fail(
                "params.inertia",
                f"must be true or false, got {show(inertia)}",
                "true (the default) or false (quasi-static: the layer's inertia "
                "neglected, vstar setting only the relaxation of a material given "
                "by tau)",
            )
        if layers is None:
            raise c.fail(
                "params.inertia",
                "is given without [[layers]]: the quasi-static speed sets the "
                "relaxation of a viscoelastic sublayer given by tau",
                "inertia beside [[layers]] with a material of tau (taus)",
            )
    medium: Medium | None = None
    if layers is not None or base is not None:
        if base is None:  # the springs of [params]
            base = Winkler(
                params["kw"], params.get("kp", 0.0), params.get("damping", 0.0)
            )
        if layers is None:  # the homogeneous layer of [params] nu
            layers = (Layer(nu=params["nu"]),)
        medium = Medium(layers, base, inertia)

    tol = DEFAULT_TOL
    if "accuracy" in data:
        acc = c.table("accuracy", data["accuracy"], ("tol",))
        if "tol" in acc:
            tol = c.tol("accuracy.tol", acc["tol"])

    outputs: dict[str, OutputSpec] = {}
    if "outputs" in data:
        raw_outputs = c.table("outputs", data["outputs"], OUTPUT_KINDS)
        for kind, spec in raw_outputs.items():
            parsed = parse_output(c, kind, spec)
            if parsed is not None:
                outputs[kind] = parsed

    return {
        "params": params,
        "profile": profile,
        "punches": punches,
        "contact": contact,
        "medium": medium,
        "outputs": outputs,
        "vary": vary,
        "sweep": sweep,
        "tol": tol,
        "name": name,
        "description": description,
    }


def _parse_vary(c: Checker, raw: object) -> Vary:
    t = c.table("vary", raw, ("param", "values"))
    if "param" not in t:
        raise c.fail("vary.param", "missing", ", ".join(PARAMS))
    param = c.string("vary.param", t["param"], _AXIS_PARAMS)
    if "values" not in t:
        raise c.fail("vary.values", "missing", allowed_text(param), param)
    return Vary(param, values_list(c, "vary.values", param, t["values"], MAX_VARY))


def _parse_sweep(c: Checker, raw: object) -> Sweep:
    keys = ("param", "values", "start", "stop", "points", "spacing", "quantities")
    t = c.table("sweep", raw, keys)
    if "param" not in t:
        raise c.fail("sweep.param", "missing", ", ".join(PARAMS))
    param = c.string("sweep.param", t["param"], _AXIS_PARAMS)
    quantities: tuple[str, ...] = ("a", "p0")
    if "quantities" in t:
        q = t["quantities"]
        if isinstance(q, str) or not isinstance(q, Sequence) or not q:
            raise c.fail(
                "sweep.quantities",
                f"must be a non-empty list, got {show(q)}",
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
        values = values_list(c, "sweep.values", param, t["values"], MAX_SWEEP)
        return Sweep(param, values, quantities)
    for k in ("start", "stop", "points"):
        if k not in t:
            raise c.fail(
                f"sweep.{k}", "missing", "either values = [...] or start, stop, points"
            )
    start, stop, points, spacing = range_bounds(
        c, param, t["start"], t["stop"], t["points"], t.get("spacing", "linear")
    )
    return Sweep.range(
        param, start, stop, points, spacing=spacing, quantities=quantities
    )


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
    if isinstance(value, dict):  # an inline table (a layer's material)
        return (
            "{ " + ", ".join(f"{k} = {_toml_value(v)}" for k, v in value.items()) + " }"
        )
    raise TypeError(f"cannot write {type(value).__name__} as TOML")


def to_toml(scene: SceneData) -> str:
    """``scene`` as TOML text that ``Scene.from_toml`` reads back equal."""
    lines: list[str] = []
    if scene.name:
        lines.append(f"name = {_toml_value(scene.name)}")
    if scene.description:
        lines.append(f"description = {_toml_value(scene.description)}")
    if lines:
        lines.append("")
    lines.append("[params]")
    profile = scene.profile
    medium = scene.medium
    for name in PARAMS:
        if name == "radius" and profile is not None:
            continue  # the profile carries its own shape
        if name == "nu" and medium is not None:
            continue  # each [[layers]] table has its own
        if name in scene.params:
            lines.append(f"{name} = {_toml_value(scene.params[name])}")
    if scene.contact != "auto":
        lines.append(f"contact = {_toml_value(scene.contact)}")
    if medium is not None and not medium.inertia:
        lines.append("inertia = false")
    if profile is not None:
        lines += ["", "[params.profile]"]
        lines += [f"{k} = {_toml_value(v)}" for k, v in profile.to_dict().items()]
    for punch in scene.punches:
        lines += ["", "[[punches]]"]
        lines += [f"load = {_toml_value(punch.load)}", f"at = {_toml_value(punch.at)}"]
        if isinstance(punch.profile, Cylinder):
            lines.append(f"radius = {_toml_value(punch.profile.radius)}")
        else:
            lines += ["", "[punches.profile]"]
            lines += [
                f"{k} = {_toml_value(v)}" for k, v in punch.profile.to_dict().items()
            ]
    if medium is not None:
        for layer in medium.layers:
            lines += ["", "[[layers]]"]
            lines += [f"{k} = {_toml_value(v)}" for k, v in layer.to_dict().items()]
        if isinstance(medium.base, HalfSpace):  # on springs: [params] kw, kp, damping
            lines += ["", "[base]"]
            lines += [
                f"{k} = {_toml_value(v)}" for k, v in medium.base.to_dict().items()
            ]
    lines += ["", "[accuracy]", f"tol = {_toml_value(scene.tol)}"]
    if scene.outputs:
        lines += ["", "[outputs]"]
        for kind, spec in scene.outputs.items():
            items = output_items(spec)
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
