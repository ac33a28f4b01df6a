"""The medium's value types are table-driven (issue 26): every field of
``Layer``, ``GradedLayer``, ``Winkler`` and ``HalfSpace`` (their ``FIELDS``,
``CHOICES`` and ``CLI`` tables in movingpunch.media, each scalar's range and
texts in ``movingpunch.params.SPECS``) is walked here through every way in:
the API (made, checked, passed to the core), a scene file (read, written,
read back; a bad value refused naming ``layers[k].key`` and the range), the
command line (``--layer``/``--graded``/``--half-space`` or ``--kw``/``--kp``/
``--damping``), the terminal UI (the medium editor's input, or the panel's
for the springs: it exists and a bad value gets the message naming the
parameter and its range) and docs/media.md (the table of fields).

A field added to a type and to ``SPECS`` is picked up by each of these with
no edit here: a way in that does not iterate over the table fails."""

from __future__ import annotations

import argparse
import dataclasses
import math
from pathlib import Path
from typing import Any

import pytest
from textual.widgets import Input, Select

import movingpunch as mp
from movingpunch import cli
from movingpunch._cli_media import cli_form, medium_of, parse_cli
from movingpunch.errors import InvalidParameterError, SceneError
from movingpunch.media import (
    BASE_TYPES,
    HALF_SPACE_ROW,
    SUBLAYER_ROW,
    SUBLAYER_TYPES,
    GradedLayer,
    HalfSpace,
    Layer,
    Medium,
    ValueType,
    Winkler,
    fields_table,
    resolve_medium,
)
from movingpunch.params import SPECS
from movingpunch.scene import OutputSpec, Scene
from movingpunch.tui import create_app
from movingpunch.tui.model import HALF_SPACE_FIELDS, SUBLAYER_FIELDS
from movingpunch.tui.screens.medium import HEADINGS, MediumEditor, SublayerRow
from movingpunch.tui.widgets import ParamsPanel
from tui_pilot import screen_of, settle, sync

ROOT = Path(__file__).resolve().parents[2]
TYPES: tuple[type[ValueType], ...] = (*SUBLAYER_TYPES, *BASE_TYPES)
CASES = [(cls, name) for cls in TYPES for name in cls.FIELDS]
IDS = [f"{cls.__name__}.{name}" for cls, name in CASES]


def good_value(cls: type[ValueType], name: str) -> float:
    """A valid value of the field that is not its default."""
    spec = SPECS[name]
    default = cls.default(name)
    for x in (0.3, 2.0, 0.5 * (spec.lo + min(spec.hi, spec.lo + 10.0))):
        if spec.contains(x) and x != default:
            return x
    raise AssertionError(f"no valid value of {name} found")  # pragma: no cover


def bad_value(name: str) -> float:
    """A finite value outside the field's range."""
    spec = SPECS[name]
    x = 2.0 * spec.hi + 1.0 if math.isfinite(spec.hi) else spec.lo - 1.0
    assert not spec.contains(x)
    return x


def make(cls: type[ValueType], name: str, value: object) -> Any:
    """An instance of ``cls`` with ``name`` = ``value`` (the other required
    fields given valid values; a sublayer's thickness 0.5)."""
    kwargs: dict[str, object] = {}
    if cls in SUBLAYER_TYPES:
        kwargs["thickness"] = 0.5
    for req in cls.required():
        kwargs[req] = good_value(cls, req)
    kwargs[name] = value
    return cls(**kwargs)


def medium_with(value: ValueType) -> Medium:
    """A valid medium holding ``value``: a sublayer second under a unit top
    sublayer (the top's mu and rho are the units) on springs, a base under
    one sublayer."""
    if isinstance(value, (Layer, GradedLayer)):
        top = Layer(thickness=1.0 - value.thickness)
        return resolve_medium(layers=[top, value], base=Winkler(2.0))
    return resolve_medium(layers=[Layer(1.0, nu=0.25)], base=value)


def range_named(text: str, name: str) -> bool:
    return name in text and SPECS[name].text in text


# -- the table ---------------------------------------------------------------


@pytest.mark.parametrize("cls", TYPES, ids=lambda c: c.__name__)
def test_the_field_table_is_the_dataclass(cls: type[ValueType]) -> None:
    """FIELDS, CHOICES and MATERIALS are exactly the dataclass's fields; each scalar
    is a row of SPECS whose default is the type's (where it has one); the
    command line's positions are fields."""
    declared = {f.name for f in dataclasses.fields(cls)}  # type: ignore[arg-type]
    assert declared == {*cls.FIELDS, *cls.CHOICES, *cls.MATERIALS}
    for name in cls.FIELDS:
        assert name in SPECS
        default = cls.default(name)
        if default is not dataclasses.MISSING and SPECS[name].default is not None:
            assert default == SPECS[name].default, name
    assert set(cls.CLI) <= set(cls.FIELDS)
    if cls in SUBLAYER_TYPES or cls is HalfSpace:  # an option of their own
        assert set(cls.CLI) == set(cls.FIELDS)
        assert set(cls.required()) & set(cls.CLI) <= set(cls.CLI[: cls.CLI_REQUIRED])


def test_the_editor_and_the_core_row_hold_every_sublayer_field() -> None:
    fields = {n for cls in SUBLAYER_TYPES for n in cls.FIELDS}
    assert set(SUBLAYER_FIELDS) == fields
    assert set(SUBLAYER_ROW) == fields
    assert HALF_SPACE_FIELDS == HalfSpace.FIELDS
    assert set(HALF_SPACE_ROW) == set(HalfSpace.FIELDS)
    for name in (*SUBLAYER_FIELDS, *HALF_SPACE_FIELDS):
        assert HEADINGS[name] == SPECS[name].heading


# -- the API -----------------------------------------------------------------


@pytest.mark.parametrize(("cls", "name"), CASES, ids=IDS)
def test_api_takes_the_field_and_refuses_a_bad_value_by_name(
    cls: type[ValueType], name: str
) -> None:
    good = good_value(cls, name)
    value = make(cls, name, good)
    assert getattr(value, name) == good
    assert f"{SPECS[name].shown_as} {good:g}" in value.describe()
    assert value.to_dict()[name] == good
    # It reaches the core's arguments.
    medium = medium_with(value)
    args = medium.core_args()
    if isinstance(value, (Layer, GradedLayer)):
        assert args["layers"][1][SUBLAYER_ROW.index(name)] == good
    elif isinstance(value, HalfSpace):
        assert args["half_space"][HALF_SPACE_ROW.index(name)] == good
    else:
        assert getattr(medium.base, name) == good  # solve's kw, kp, damping
    for bad in (bad_value(name), math.nan, "1"):
        with pytest.raises(InvalidParameterError) as info:
            make(cls, name, bad)
        assert info.value.parameter == name
        assert info.value.allowed == SPECS[name].text
        assert f"{cls.__name__}.{name}" in str(info.value)
        assert range_named(str(info.value), name), str(info.value)


def test_a_bad_word_is_refused_naming_the_choice() -> None:
    for cls in TYPES:
        for name, words in cls.CHOICES.items():
            with pytest.raises(InvalidParameterError) as info:
                make(cls, name, "glued")
            assert info.value.parameter == name
            assert all(repr(w) in str(info.value) for w in words)


def test_a_sublayer_field_reaches_the_solve() -> None:
    """The keyword arguments the solve passes on take every sublayer field
    (the critical speed of a stack of the table's values is the core's)."""
    for cls, name in CASES:
        if cls not in SUBLAYER_TYPES:
            continue
        medium = medium_with(make(cls, name, good_value(cls, name)))
        vc = mp.critical_vstar(layers=list(medium.layers), base=medium.base)
        assert 0.0 < vc < math.inf, (cls, name)


# -- scene files -------------------------------------------------------------

PARAMS = {"vstar": 0.0, "radius": 100.0, "load": 0.002}


def scene_of(medium: Medium) -> Scene:
    outputs = {"contact_width": OutputSpec("contact_width")}
    return Scene(params=dict(PARAMS), outputs=outputs, medium=medium)


def toml_of(value: ValueType, name: str, text: str | None) -> tuple[str, str]:
    """A scene whose ``value``'s table has ``name = text`` (None: no
    ``name``); the key an error on it names."""

    def table(v: ValueType) -> list[str]:
        return [
            f"{k} = {x!r}" if isinstance(x, float) else f'{k} = "{x}"'
            for k, x in v.to_dict().items()
        ]

    head = ["[params]", *(f"{k} = {v!r}" for k, v in PARAMS.items())]
    rows = [
        r if not r.startswith(f"{name} = ") else f"{name} = {text}"
        for r in table(value)
        if text is not None or not r.startswith(f"{name} = ")
    ]
    if isinstance(value, (Layer, GradedLayer)):
        top = table(Layer(1.0 - value.thickness))
        lines = [*head, "kw = 2.0", "", "[[layers]]", *top, "", "[[layers]]", *rows]
        key = f"layers[1].{name}"
    else:
        top = table(Layer(1.0, nu=0.25))
        lines = [*head, "", "[[layers]]", *top, "", "[base]", *rows]
        key = f"base.{name}"
    lines += ["", "[outputs]", "contact_width = true"]
    return "\n".join(lines) + "\n", key


@pytest.mark.parametrize(("cls", "name"), CASES, ids=IDS)
def test_scene_reads_writes_and_refuses_the_field(
    cls: type[ValueType], name: str
) -> None:
    good = good_value(cls, name)
    value = make(cls, name, good)
    scene = scene_of(medium_with(value))
    again = Scene.from_toml(scene.to_toml())
    assert again == scene
    assert again.medium is not None
    held = again.medium.layers[1] if cls in SUBLAYER_TYPES else again.medium.base
    assert getattr(held, name) == good
    text, key = toml_of(value, name, repr(good))
    assert Scene.from_toml(text).medium == scene.medium
    text, key = toml_of(value, name, repr(bad_value(name)))
    with pytest.raises(SceneError) as info:
        Scene.from_toml(text, "s.toml")
    assert info.value.key == key, str(info.value)
    assert SPECS[name].text in str(info.value), str(info.value)
    text, key = toml_of(value, name, None)
    if name in cls.required():
        with pytest.raises(SceneError, match="missing") as info:
            Scene.from_toml(text, "s.toml")
        assert info.value.key == key
    elif name == "thickness":  # the default 1 beside the top's: too thick
        with pytest.raises(SceneError, match="sum to 1"):
            Scene.from_toml(text, "s.toml")
    else:  # the default
        read = Scene.from_toml(text).medium
        assert read is not None
        held = read.layers[1] if cls in SUBLAYER_TYPES else read.base
        assert getattr(held, name) == cls.default(name)


# -- the command line --------------------------------------------------------

OPTION = {Layer: "--layer", GradedLayer: "--graded", HalfSpace: "--half-space"}
BASE_ARGS = ["solve", "--vstar", "0", "--radius", "100", "--load", "0.002"]


def cli_text(value: ValueType) -> str:
    cls = type(value)
    out = ",".join(repr(float(getattr(value, n))) for n in cls.CLI)
    for name in cls.CHOICES:
        out += f",{getattr(value, name)}"
    return out


def parsed_medium(argv: list[str]) -> Medium:
    args = cli._build_parser().parse_args(argv)
    medium = medium_of(args)
    assert medium is not None
    return medium


@pytest.mark.parametrize(("cls", "name"), CASES, ids=IDS)
def test_cli_takes_the_field_and_refuses_a_bad_value_by_name(
    cls: type[ValueType], name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    good = good_value(cls, name)
    value = make(cls, name, good)
    if cls is Winkler:
        option, argv = f"--{name}", [f"--{name}", repr(good)]
        if name != "kw":
            argv += ["--kw", "2"]
        medium = parsed_medium([*BASE_ARGS, "--layer", "1,1,0.25", *argv])
        assert getattr(medium.base, name) == good
        bad = [*BASE_ARGS, "--layer", "1,1,0.25", "--kw", "2"]
        bad += [option, repr(bad_value(name))]
    else:
        option = OPTION[cls]
        text = cli_text(value)
        if cls in SUBLAYER_TYPES:
            top = f"{1.0 - value.thickness!r},1,0.25"
            medium = parsed_medium(
                [*BASE_ARGS, "--kw", "2", "--layer", top, option, text]
            )
            assert medium.layers[1] == value
        else:
            medium = parsed_medium([*BASE_ARGS, "--layer", "1,1,0.25", option, text])
            assert medium.base == value
        assert parse_cli(option, cls, text) == value
        texts = cli_text(value).split(",")
        texts[cls.CLI.index(name)] = repr(bad_value(name))
        with pytest.raises(argparse.ArgumentTypeError) as info:
            parse_cli(option, cls, ",".join(texts))
        assert option in str(info.value)
        assert range_named(str(info.value), name), str(info.value)
        bad = [*BASE_ARGS, "--kw", "2", option, ",".join(texts)]
        if cls is HalfSpace:
            bad.remove("--kw")
            bad.remove("2")
            bad += ["--layer", "1,1,0.25"]
    capsys.readouterr()
    try:
        status = cli.main(bad)
    except SystemExit as exc:  # an argparse type's error
        status = exc.code
    assert status == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert range_named(err, name), err
    if cls is not Winkler:
        assert option in err, err


def test_cli_help_shows_every_field_and_its_range() -> None:
    sub = cli._build_parser()._subparsers
    assert sub is not None
    solve = next(
        a for a in sub._group_actions if isinstance(a, argparse._SubParsersAction)
    ).choices["solve"]
    help_text = " ".join(solve.format_help().split())
    for cls, option in OPTION.items():
        assert f"{option} {cli_form(cls)}" in help_text
        for name in cls.CLI:
            assert SPECS[name].cli_name in cli_form(cls)
            assert f"{SPECS[name].cli_name}: {SPECS[name].text}" in help_text, name
    for name in Winkler.FIELDS:
        assert f"--{name}" in help_text


# -- the terminal UI ---------------------------------------------------------


async def _bad_then_good(
    pilot: Any, editor: MediumEditor, box: Input, name: str, where: str
) -> None:
    before = box.value
    box.value = repr(bad_value(name))
    await pilot.pause()
    assert box.has_class("-invalid"), name
    assert where in editor.error, editor.error
    assert range_named(editor.error, name), editor.error
    box.value = before
    await pilot.pause()
    assert not box.has_class("-invalid"), name


@sync
async def test_tui_has_an_input_per_field_and_names_a_bad_value() -> None:
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=(110, 36)) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        panel = screen.query_one(ParamsPanel)
        for name in Winkler.FIELDS:  # the springs: the panel's inputs
            box = screen.query_one(f"#in-{name}", Input)
            before = box.value
            box.value = repr(bad_value(name))
            await pilot.pause()
            assert range_named(panel.message(name), name), panel.message(name)
            box.value = before
            await settle(pilot)
            assert panel.message(name) == ""
        screen.action_leave_input()
        await pilot.press("l")
        await pilot.pause()
        editor = app.screen
        assert isinstance(editor, MediumEditor)
        editor.rows()[0].box("thickness").focus()
        await pilot.press("ctrl+n")  # a second sublayer (the top's mu is 1)
        await pilot.pause()
        rows = editor.query(SublayerRow)
        assert len(rows) == 2
        assert editor.error == "", editor.error
        for name in SUBLAYER_FIELDS:
            box = rows[1].box(name)
            await _bad_then_good(pilot, editor, box, name, "sublayer 2")
        editor.query_one("#base-kind", Select).value = "bonded"
        await pilot.pause()
        for name in HALF_SPACE_FIELDS:
            box = editor.query_one(f".hs-{name}", Input)
            await _bad_then_good(pilot, editor, box, name, "half-space")
        assert editor.error == "", editor.error


# -- docs --------------------------------------------------------------------


def test_docs_list_every_field() -> None:
    """docs/media.md holds the table of fields as ``fields_table()`` writes
    it (regenerate it when a field changes), and docs/scenes.md names each
    kind of sublayer and base."""
    media = (ROOT / "docs" / "media.md").read_text(encoding="utf-8")
    assert fields_table() in media
    for cls, name in CASES:
        assert f"| {cls.__name__} (`{cls.KIND}`) | `{name}` |" in media
    scenes = (ROOT / "docs" / "scenes.md").read_text(encoding="utf-8")
    for cls in TYPES:
        assert f'"{cls.KIND}"' in scenes, cls.KIND


# -- the numerics ------------------------------------------------------------


def test_numerics_are_checked_as_solve_checks_its_keywords() -> None:
    assert mp.Numerics(tol="precise").tol == 1e-12
    assert mp.Numerics(n=16, contact="single").n == 16
    bad: list[tuple[dict[str, Any], str, str]] = [
        ({"tol": 0.5}, "tol", SPECS["tol"].text),
        ({"tol": "rough"}, "tol", SPECS["tol"].text),
        ({"n": 7}, "n", "an even integer in [2, 4096]"),
        ({"allow_unphysical": 1}, "allow_unphysical", "True or False"),
        ({"contact": "zones"}, "contact", '"auto" or "single"'),
    ]
    for kwargs, name, allowed in bad:
        with pytest.raises(InvalidParameterError) as info:
            mp.Numerics(**kwargs)
        assert info.value.parameter == name
        assert allowed in str(info.value), str(info.value)
    assert mp.params.CONTACT_MODES == mp.zones.CONTACT_MODES


def test_solve_takes_the_numerics_as_its_keywords() -> None:
    physical = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002}
    numerics = mp.Numerics(tol=1e-6, n=32, contact="single")
    by_value = mp.solve(**physical, numerics=numerics)
    by_keyword = mp.solve(**physical, tol=1e-6, n=32, contact="single")
    assert type(by_value) is type(by_keyword)
    assert by_value.tol == by_keyword.tol == 1e-6
    assert by_value.collocation_n == by_keyword.collocation_n == 32
    assert by_value.a == by_keyword.a
    # A keyword at its default beside numerics= is no conflict; another is.
    mp.solve(**physical, numerics=numerics, allow_unphysical=False)
    with pytest.raises(InvalidParameterError) as info:
        mp.solve(**physical, numerics=numerics, tol=1e-4)
    assert info.value.parameter == "tol"
    assert "numerics=" in str(info.value)


def test_solve_punches_takes_the_numerics_as_its_keywords() -> None:
    train = [
        mp.Punch(mp.Cylinder(100.0), 0.002, at=-1.5),
        mp.Punch(mp.Cylinder(100.0), 0.002, at=1.5),
    ]
    by_value = mp.solve_punches(
        train, vstar=0.5, kw=1.0, numerics=mp.Numerics(tol=1e-6)
    )
    by_keyword = mp.solve_punches(train, vstar=0.5, kw=1.0, tol=1e-6)
    assert by_value.tol == by_keyword.tol == 1e-6
    assert by_value.contact_zones == by_keyword.contact_zones
    with pytest.raises(InvalidParameterError) as info:
        mp.solve_punches(train, vstar=0.5, kw=1.0, numerics=mp.Numerics(), tol=1e-4)
    assert info.value.parameter == "tol"
    for odd in (mp.Numerics(contact="single"), mp.Numerics(allow_unphysical=True)):
        with pytest.raises(InvalidParameterError) as info:
            mp.solve_punches(train, vstar=0.5, kw=1.0, numerics=odd)
        assert info.value.parameter == "numerics"
        assert 'contact="auto"' in str(info.value)


def test_numerics_of_the_wrong_type_is_refused_by_name() -> None:
    for bad in ("x", 3, 1e-6, {"tol": 1e-6}):
        with pytest.raises(InvalidParameterError) as info:
            mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, numerics=bad)  # type: ignore[arg-type]
        assert info.value.parameter == "numerics"
        with pytest.raises(InvalidParameterError) as info:
            mp.solve_punches([mp.Punch(100.0, 0.002)], vstar=0.2, kw=1.0, numerics=bad)  # type: ignore[arg-type]
        assert info.value.parameter == "numerics"
