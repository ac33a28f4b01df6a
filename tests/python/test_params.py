"""The table of parameters (movingpunch.params) is the one home of every
input's range: the API, the damped solve, scene files, the CLI and the
terminal UI all refuse an out-of-range input with an error whose
``.parameter`` names it and whose text shows the table's range; errors the
C++ core raises carry ``.parameter`` too; and the table's bounds are the
compiled core's own (an independent check written in C++)."""

from __future__ import annotations

import ast
import math
import pickle
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import movingpunch as mp
from movingpunch import _core, cli, params
from movingpunch.errors import InvalidParameterError
from movingpunch.params import SPECS, range_text
from movingpunch.scene import Scene, SceneError
from movingpunch.tui import create_app
from movingpunch.tui.model import parse_param
from movingpunch.tui.widgets import ParamsPanel
from movingpunch.tui.widgets.params import TOOLTIPS
from tui_pilot import screen_of, settle, sync

# The paper's Fig. 4 case, nu and tol at the table's defaults (0.2, 1e-8).
GOOD: dict[str, Any] = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002}
GOOD.update({name: SPECS[name].default for name in ("nu", "tol")})

# One out-of-range value per parameter (each refused by the table alone,
# before any speed check), and one that is not a number.
OUT_OF_RANGE: dict[str, object] = {
    "vstar": -0.1,
    "kw": 0.0,
    "radius": 2e12,
    "load": -1.0,
    "nu": 0.5,
    "damping": -0.5,
    "kp": -0.5,
    "tol": 0.1,
}
CASES = list(OUT_OF_RANGE.items()) + [(n, "abc") for n in OUT_OF_RANGE if n != "tol"]


def _flat(text: str) -> str:
    return " ".join(text.split())


# -- the API ------------------------------------------------------------------


@pytest.mark.parametrize(("name", "value"), CASES, ids=repr)
def test_solve_names_the_parameter(name: str, value: object) -> None:
    with pytest.raises(InvalidParameterError) as info:
        mp.solve(**{**GOOD, name: value})
    err = info.value
    assert err.parameter == name
    assert err.allowed == range_text(name)
    assert str(err).startswith(name)
    assert range_text(name) in str(err)


@pytest.mark.parametrize(("name", "value"), CASES, ids=repr)
def test_damped_solve_names_the_parameter(name: str, value: object) -> None:
    kwargs = {**GOOD, "damping": 0.1, name: value}
    with pytest.raises(InvalidParameterError) as info:
        mp.solve(**kwargs)
    assert info.value.parameter == name
    assert range_text(name) in str(info.value)


@pytest.mark.parametrize("value", [3, 1, 4098, 2.0, True, "8"])
def test_collocation_size_names_n(value: object) -> None:
    with pytest.raises(InvalidParameterError) as info:
        mp.solve(**GOOD, n=value)  # type: ignore[arg-type]
    assert info.value.parameter == "n"
    assert info.value.allowed == range_text("n")


def test_damped_collocation_size_names_n_and_its_own_limit() -> None:
    with pytest.raises(InvalidParameterError, match=r"\[2, 1024\]") as info:
        mp.solve(**GOOD, damping=0.1, n=2048)
    assert info.value.parameter == "n"


def test_output_arguments_name_the_parameter() -> None:
    s = mp.solve(**GOOD)
    for call, name in (
        (lambda: s.depth_stress(-2.0), "y"),
        (lambda: s.displacement([0.0], y=0.5), "y"),
        (lambda: s.stress_peaks(extent=-1.0), "extent"),
        (lambda: s.pressure(math.nan), "x"),
        (lambda: mp.layer_response(-1.0, vstar=0.2, kw=1.0), "t"),
    ):
        with pytest.raises(InvalidParameterError) as info:
            call()
        assert info.value.parameter == name, str(info.value)


@pytest.mark.parametrize("damping", [0.0, 0.1])
def test_speed_errors_name_vstar(damping: float) -> None:
    # Above V*_cr(kw = 1) = 0.5717 undamped; above V*_R = 0.8299 damped.
    vstar = 0.6 if damping == 0 else 0.9
    with pytest.raises(mp.SupercriticalSpeedError) as info:
        mp.solve(**{**GOOD, "vstar": vstar, "damping": damping})
    assert info.value.parameter == "vstar"
    assert info.value.allowed is not None
    assert info.value.allowed.startswith("0 <= vstar < V*_")


def test_error_constructor_is_backwards_compatible() -> None:
    err = InvalidParameterError("bad input")
    assert str(err) == "bad input"
    assert err.parameter is None
    assert err.allowed is None
    assert mp.SupercriticalSpeedError("too fast").allowed is None


def test_errors_keep_their_attributes_through_pickle() -> None:
    with pytest.raises(InvalidParameterError) as api:
        mp.solve(**{**GOOD, "nu": 0.7})
    with pytest.raises(SceneError) as scene:
        Scene.from_toml(_scene_text("nu", "0.7"), "my.toml")
    with pytest.raises(mp.SupercriticalSpeedError) as fast:
        mp.solve(**{**GOOD, "vstar": 0.6})
    for err in (api.value, scene.value, fast.value):
        copy = pickle.loads(pickle.dumps(err))
        assert type(copy) is type(err)
        assert str(copy) == str(err)
        assert copy.parameter == err.parameter
        assert copy.allowed == err.allowed
    assert pickle.loads(pickle.dumps(scene.value)).key == "params.nu"


# -- the compiled core -----------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "value", "allowed"),
    [
        ("nu", 0.7, "[0, 0.5)"),
        ("nu", math.nan, "[0, 0.5)"),
        ("vstar", math.nan, None),
        ("kw", -1.0, None),
        ("radius", 2e12, "(0, 1e+12]"),
        ("load", 0.0, "(0, 1000000]"),
        ("tol", 1.0, "[1e-14, 0.01]"),
        ("n", 3, "0 (automatic) or even in [2, 4096]"),
    ],
)
def test_core_errors_name_the_parameter(
    name: str, value: float, allowed: str | None
) -> None:
    # The core's own checks, bypassing the Python ones.
    args = {**GOOD, "n": 0, name: value}
    with pytest.raises(InvalidParameterError) as info:
        _core.solve_contact(**args, allow_unphysical=False)
    assert info.value.parameter == name
    assert str(info.value).startswith(name)
    if allowed is not None:
        assert info.value.allowed == allowed
        assert allowed in str(info.value)


def test_core_errors_of_other_functions_name_the_parameter() -> None:
    with pytest.raises(InvalidParameterError) as info:
        _core.critical_speed(-1.0, 0.2)
    assert info.value.parameter == "kw"
    with pytest.raises(InvalidParameterError) as info:
        _core.rayleigh_vstar(0.5)
    assert info.value.parameter == "nu"
    damped = {**GOOD, "damping": -1.0, "n": 0}
    with pytest.raises(InvalidParameterError) as info:
        _core.solve_asymmetric(**damped, allow_unphysical=False)
    assert info.value.parameter == "damping"
    with pytest.raises(InvalidParameterError) as info:
        _core.solve_asymmetric(
            **{**damped, "damping": 0.1, "n": 3}, allow_unphysical=False
        )
    assert info.value.parameter == "n"
    impl = _core.solve_contact(**GOOD, n=0, allow_unphysical=False)
    for x, y, name in (([math.nan], [-0.5], "x"), ([0.0], [0.5], "y")):
        with pytest.raises(InvalidParameterError) as info:
            impl.stress_field(np.array(x), np.array(y))
        assert info.value.parameter == name


def _core_refuses(name: str, value: float) -> bool:
    """Whether the compiled core (its own validate(), written separately
    from the table) refuses ``name = value`` as an invalid parameter."""
    args = {**GOOD, "vstar": 0.0, "n": 8, name: value}
    try:
        _core.solve_contact(**args, allow_unphysical=True)
    except InvalidParameterError as exc:
        # Refused jointly (radius * load beyond the supported a/h) is not a
        # refusal of the value: it passed the core's range check.
        error = exc
    except mp.MovingPunchError:
        return False  # refused for another reason: the value itself passed
    else:
        return False
    refused = error.parameter == name
    assert refused or not str(error).startswith(f"{name} must"), str(error)
    return refused


@pytest.mark.parametrize("name", ["kw", "kp", "radius", "load", "nu", "tol"])
def test_table_bounds_are_the_cores(name: str) -> None:
    spec = SPECS[name]
    probes = [spec.lo, math.nextafter(spec.lo, -math.inf), math.nan]
    probes.append(math.nextafter(spec.lo, math.inf))
    if math.isfinite(spec.hi):
        probes += [spec.hi, math.nextafter(spec.hi, math.inf)]
        probes.append(math.nextafter(spec.hi, -math.inf))
    probes.append(math.inf)
    for x in probes:
        assert _core_refuses(name, x) == (not spec.contains(x)), (name, x)
        if spec.contains(x):
            assert params.check(name, x) == x
        else:
            with pytest.raises(InvalidParameterError) as info:
                params.check(name, x)
            assert info.value.parameter == name


# -- scene files ---------------------------------------------------------------


def _scene_text(name: str, value: str) -> str:
    values = {"vstar": "0.2", "kw": "1.0", "radius": "100.0", "load": "0.002"}
    lines = [f"{k} = {v}" for k, v in values.items() if k != name]
    if name not in ("tol", ""):
        lines.append(f"{name} = {value}")
    text = "[params]\n" + "\n".join(lines) + "\n[outputs]\ncontact_width = true\n"
    if name == "tol":
        text += f"[accuracy]\ntol = {value}\n"
    return text


@pytest.mark.parametrize(("name", "value"), CASES, ids=repr)
def test_scene_names_the_parameter(name: str, value: object) -> None:
    toml = f'"{value}"' if isinstance(value, str) else repr(value)
    with pytest.raises(SceneError) as info:
        Scene.from_toml(_scene_text(name, toml), "my.toml")
    err = info.value
    assert err.parameter == name
    key = "accuracy.tol" if name == "tol" else f"params.{name}"
    assert str(err).startswith(f"my.toml: {key}: "), str(err)
    assert range_text(name) in str(err)


def test_scene_vary_and_sweep_values_name_the_parameter() -> None:
    base = _scene_text("", "")
    with pytest.raises(SceneError) as info:
        Scene.from_toml(base + '[vary]\nparam = "nu"\nvalues = [0.1, 0.6]\n')
    assert (info.value.key, info.value.parameter) == ("vary.values[1]", "nu")
    with pytest.raises(SceneError) as info:
        Scene.from_toml(
            base + '[sweep]\nparam = "load"\nstart = -1.0\nstop = 1.0\npoints = 3\n'
        )
    assert (info.value.key, info.value.parameter) == ("sweep.start", "load")


def test_scene_speed_error_names_the_parameter() -> None:
    with pytest.raises(SceneError, match="critical speed") as info:
        Scene.from_toml(_scene_text("vstar", "0.6"))
    assert info.value.parameter == "vstar"
    # A kw sweep that pushes V*_cr below vstar blames kw, where the key is.
    text = _scene_text("vstar", "0.3") + '[vary]\nparam = "kw"\nvalues = [1.0, 0.01]\n'
    with pytest.raises(SceneError, match="critical speed") as info:
        Scene.from_toml(text)
    assert (info.value.key, info.value.parameter) == ("vary.values[1]", "kw")


# -- the CLI --------------------------------------------------------------------


def _cli_args(name: str, value: str) -> list[str]:
    args = {**GOOD, "damping": 0.0, name: value}
    return ["solve"] + [x for k, v in args.items() for x in (f"--{k}", str(v))]


@pytest.mark.parametrize(("name", "value"), CASES, ids=repr)
def test_cli_names_the_parameter(
    name: str, value: object, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as info:
        cli.main(_cli_args(name, str(value)))
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert err.startswith("movingpunch: error: ")
    assert re.search(rf"\b{name}\b", err), err
    assert range_text(name) in err


# -- the terminal UI ------------------------------------------------------------


@pytest.mark.parametrize(("name", "value"), CASES, ids=repr)
def test_tui_input_names_the_parameter(name: str, value: object) -> None:
    with pytest.raises(InvalidParameterError) as info:
        parse_param(name, str(value))
    assert info.value.parameter == name
    assert range_text(name) in str(info.value)


@sync
async def test_tui_shows_a_core_error_at_the_input_it_names() -> None:
    # The message of a core error starts with the parameter; one that does
    # not shows at the same input: the screen reads .parameter.
    with pytest.raises(InvalidParameterError) as info:
        _core.solve_contact(**{**GOOD, "nu": 0.7, "n": 0}, allow_unphysical=False)
    reworded = InvalidParameterError("Poisson ratio too large", parameter="nu")
    app = create_app(show_timing=False)
    async with app.run_test(size=(100, 32)) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        panel = screen.query_one(ParamsPanel)
        for err in (info.value, reworded):
            screen.show_error(err)
            await pilot.pause()
            assert panel.message("nu") == str(err)
            assert panel.message("vstar") == ""


# -- one source -------------------------------------------------------------------


@pytest.mark.parametrize(
    "name", ["vstar", "kw", "radius", "load", "nu", "damping", "kp"]
)
def test_every_surface_shows_the_tables_range(
    name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    text = range_text(name)
    # The API's error, the scene's allowed text, the TUI's tooltip.
    with pytest.raises(InvalidParameterError) as api:
        mp.solve(**{**GOOD, name: OUT_OF_RANGE[name]})
    with pytest.raises(SceneError) as scene:
        Scene.from_toml(_scene_text(name, repr(OUT_OF_RANGE[name])))
    assert api.value.allowed == text
    assert scene.value.allowed is not None
    assert text in scene.value.allowed
    assert text in TOOLTIPS[name]
    # The CLI's --help (argparse wraps lines).
    with pytest.raises(SystemExit):
        cli.main(["solve", "--help"])
    assert text in _flat(capsys.readouterr().out)


def test_tol_text_is_the_same_everywhere(capsys: pytest.CaptureFixture[str]) -> None:
    text = range_text("tol")
    assert "1e-14 <= tol <= 1e-2" in text
    for preset, value in params.PRESETS.items():
        assert preset in text
        assert params.check("tol", preset) == value
    with pytest.raises(SceneError) as scene:
        Scene.from_toml(_scene_text("tol", '"fast"'))
    assert scene.value.parameter == "tol"
    assert scene.value.allowed == text
    assert text in TOOLTIPS["tol"]
    with pytest.raises(SystemExit):
        cli.main(["solve", "--help"])
    assert text in _flat(capsys.readouterr().out)


def test_no_range_is_written_outside_the_table() -> None:
    root = Path(mp.__file__).parent
    texts = {
        p: p.read_text(encoding="utf-8")
        for p in root.rglob("*.py")
        if p.name != "params.py"
    }
    for old in ("_RANGES", "_PARAM_ALLOWED", "_DAMPING_RANGE", "R/h > 0"):
        assert not [p for p, t in texts.items() if old in t], old
    screen = (root / "tui" / "screens" / "main.py").read_text(encoding="utf-8")
    assert "_parameter_named" not in screen  # no guessing from the message


def test_params_module_is_pure_python() -> None:
    tree = ast.parse(Path(params.__file__).read_text(encoding="utf-8"))
    imported = {
        node.module
        for node in ast.walk(tree)
        if isinstance(node, ast.ImportFrom) and node.module
    } | {
        alias.name
        for node in ast.walk(tree)
        if isinstance(node, ast.Import)
        for alias in node.names
    }
    ours = {m for m in imported if m.startswith("movingpunch")}
    assert ours == {"movingpunch.errors"}


def test_every_spec_is_complete() -> None:
    for name, spec in SPECS.items():
        assert spec.name == name
        assert spec.meaning
        assert spec.range.startswith(("None", "0", "1e", "-1", "-50"))
        assert name in spec.text
        if spec.default is not None and not spec.integer:
            assert spec.contains(spec.default), name
    assert np.isinf(SPECS["kw"].hi)
    assert SPECS["kw"].contains(math.inf)
    assert not SPECS["radius"].contains(math.inf)
