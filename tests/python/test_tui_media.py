"""The medium in the terminal UI (issue 26): the medium editor (key ``l``:
a sublayer list and a base selector), its messages for bad values, the
solve of the medium shown (never the numbers of another medium), the
solver's refusals on the status line, and the interfaces on the depth plot.

Numbers on screen are checked against ``mp.solve``; a stack of two identical
sublayers against the plain homogeneous layer (an independent anchor: the
same slab cut in two). The ``_stack_`` tests solve a real stack: they pass
once the core's stack medium is built (before that, the solve refuses with
"layered media are not built yet" and they fail on purpose)."""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np
import pytest
from textual.pilot import Pilot
from textual.widgets import Input, Select

import movingpunch as mp
from movingpunch.errors import InvalidParameterError
from movingpunch.scene import Scene
from movingpunch.tui import create_app
from movingpunch.tui import model as tui_model
from movingpunch.tui.model import Params, parse_sublayer, with_medium
from movingpunch.tui.scene_files import SceneState, from_scene, to_scene
from movingpunch.tui.screens import MainScreen
from movingpunch.tui.screens.medium import MediumEditor, SublayerRow
from movingpunch.tui.widgets import CurvePlot, ParamsPanel
from movingpunch.tui.widgets.plots import legend
from tui_pilot import (
    NUMBER,
    assert_summary_is,
    screen_of,
    settle,
    status_text,
    summary_fields,
    sync,
    type_into,
)

SIZE = (100, 32)


async def open_editor(pilot: Pilot[None]) -> MediumEditor:
    screen_of(pilot.app).action_leave_input()  # (letters act outside inputs)
    await pilot.press("l")
    await pilot.pause()
    editor = pilot.app.screen
    assert isinstance(editor, MediumEditor), editor
    return editor


async def type_in(pilot: Pilot[None], box: Input, text: str) -> None:
    """Types ``text`` into ``box`` key by key, as a user does."""
    box.focus()
    box.clear()
    await pilot.pause()
    await pilot.press(*text)
    await pilot.pause()


def row(editor: MediumEditor, k: int) -> SublayerRow:
    """Row ``k`` (1: the top sublayer)."""
    return editor.rows()[k - 1]


async def build(
    pilot: Pilot[None], rows: list[dict[str, str]], base: str = "springs"
) -> MediumEditor:
    """Opens the editor and types the sublayers of ``rows`` (by field name)
    and the base kind; leaves the editor open."""
    editor = await open_editor(pilot)
    while len(editor.rows()) < len(rows):
        row(editor, len(editor.rows())).box("thickness").focus()
        await pilot.press("ctrl+n")
        await pilot.pause()
    for k, texts in enumerate(rows, start=1):
        for name, text in texts.items():
            await type_in(pilot, row(editor, k).box(name), text)
    editor.query_one("#base-kind", Select).value = base
    await pilot.pause()
    return editor


def shown_numbers(app: object) -> dict[str, float]:
    """The summary's numbers that do not depend on how the solve ran (a/h,
    p0, δ/h and the σx peaks)."""
    out = {}
    for label, value in summary_fields(app):
        if label in ("a/h", "p0", "δ/h", "σx⁺ top", "bot"):
            out[label] = float(NUMBER.findall(value)[0])
    return out


# -- the editor ----------------------------------------------------------------


@sync
async def test_medium_one_sublayer_is_the_plain_layer_on_screen() -> None:
    """One homogeneous sublayer on springs, ν edited in the editor: the
    panel's ν shows it and the summary is the plain solve's numbers."""
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        editor = await open_editor(pilot)
        assert len(editor.rows()) == 1
        shown = {"thickness": "1", "mu": "1", "nu": "0.2", "rho": "1", "gamma_h": "0"}
        assert shown.items() <= row(editor, 1).texts().items()
        await type_in(pilot, row(editor, 1).box("nu"), "0.3")
        assert editor.error == ""
        await pilot.press("enter")
        await settle(pilot)
        screen = screen_of(app)
        assert screen.params == Params(nu=0.3)  # the panel's layer, ν 0.3
        assert screen.query_one(ParamsPanel).text("nu") == "0.3"
        plain = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, nu=0.3)
        assert_summary_is(app, plain, "one sublayer")
        api = mp.solve(
            vstar=0.2,
            radius=100.0,
            load=0.002,
            layers=[mp.Layer(1.0, nu=0.3)],
            base=mp.Winkler(1.0),
        )
        assert_summary_is(app, api, "one sublayer, layers=")
        assert "ready" in status_text(app), status_text(app)


@sync
async def test_medium_add_and_remove_rows_keep_the_sum() -> None:
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        editor = await open_editor(pilot)
        await pilot.press("ctrl+n")  # under the focused (top) row
        await pilot.pause()
        assert [r.box("thickness").value for r in editor.rows()] == ["0.5", "0.5"]
        await type_in(pilot, row(editor, 2).box("mu"), "0.5")
        await pilot.press("ctrl+n")  # under row 2: half of its thickness
        await pilot.pause()
        assert [r.box("thickness").value for r in editor.rows()] == [
            "0.5",
            "0.25",
            "0.25",
        ]
        assert row(editor, 3).box("mu").has_focus
        assert [
            str(r.query_one(".sublayer-number").render()) for r in editor.rows()
        ] == [
            "1",
            "2",
            "3",
        ]
        assert editor.error == ""
        await pilot.press("ctrl+r")  # the focused row 3: row 2 takes its share
        await pilot.pause()
        assert [r.box("thickness").value for r in editor.rows()] == ["0.5", "0.5"]
        assert row(editor, 2).box("mu").value == "0.5"
        choice = editor.choice()
        assert choice.layers == (mp.Layer(0.5), mp.Layer(0.5, mu=0.5))
        assert choice.half_space is None
        row(editor, 1).box("thickness").focus()
        await pilot.press("ctrl+r")  # the top row: the one below takes its share
        await pilot.pause()
        assert [r.box("thickness").value for r in editor.rows()] == ["1"]
        await pilot.press("ctrl+r")  # the last row stays
        await pilot.pause()
        assert len(editor.rows()) == 1
        await pilot.press("escape")  # cancel: nothing changes
        await settle(pilot)
        assert isinstance(app.screen, MainScreen)
        assert screen_of(app).params == Params()


@sync
async def test_medium_bad_values_are_named_and_never_applied() -> None:
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        editor = await build(pilot, [{}, {"mu": "abc"}])
        box = row(editor, 2).box("mu")
        assert editor.error.startswith("sublayer 2: mu "), editor.error
        assert "0 < mu <= 1e12" in editor.error, editor.error
        assert box.has_class("-invalid")
        await pilot.press("enter")  # refused: the editor stays
        await pilot.pause()
        assert app.screen is editor
        await type_in(pilot, box, "0.5")
        assert editor.error == ""
        assert not box.has_class("-invalid")
        cases = {
            (2, "gamma_h", "99"): ("sublayer 2", "gamma_h", "-50"),
            (2, "nu", "0.5"): ("sublayer 2", "nu", "0 <= nu < 0.5"),
            (1, "mu", "2"): ("sublayer 1", "mu", "1 by definition"),
            (2, "thickness", "-1"): ("sublayer 2", "thickness", "0 < thickness"),
        }
        for (k, name, text), words in cases.items():
            target = row(editor, k).box(name)
            before = target.value
            await type_in(pilot, target, text)
            for word in words:
                assert word in editor.error, (name, text, editor.error)
            assert target.has_class("-invalid"), (name, text)
            await type_in(pilot, target, before)
            assert editor.error == "", (name, editor.error)
        # The sum of the thicknesses, named with every row's; ctrl+t fixes it.
        await type_in(pilot, row(editor, 2).box("thickness"), "0.4")
        assert "sum to 0.9" in editor.error, editor.error
        assert "1 0.5, 2 0.4" in editor.error, editor.error
        await pilot.press("ctrl+t")
        await pilot.pause()
        values = [float(r.box("thickness").value) for r in editor.rows()]
        assert math.fsum(values) == 1.0
        assert values[0] == pytest.approx(0.5 / 0.9, rel=1e-15)
        assert editor.error == ""
        # A half-space's inputs, named as the half-space's.
        editor.query_one("#base-kind", Select).value = "bonded"
        await pilot.pause()
        await type_in(pilot, editor.query_one(".hs-nu", Input), "x")
        assert editor.error.startswith("half-space: "), editor.error
        assert "nu" in editor.error, editor.error
        await pilot.press("escape")
        await settle(pilot)
        assert screen_of(app).params == Params()


def test_medium_model_names_the_sublayer_and_the_range() -> None:
    texts = {"thickness": "0.5", "mu": "1", "nu": "0.2", "rho": "1", "gamma_h": "0"}
    assert parse_sublayer(1, texts) == mp.Layer(0.5)
    graded = parse_sublayer(2, {**texts, "mu": "0.5", "gamma_h": "1.5"})
    assert graded == mp.GradedLayer(1.5, nu=0.2, thickness=0.5, mu=0.5)
    for name, text in (("rho", "0"), ("nu", "nan"), ("thickness", "2"), ("mu", "")):
        with pytest.raises(InvalidParameterError, match="sublayer 2: ") as info:
            parse_sublayer(2, {**texts, name: text})
        assert info.value.parameter == name
    with pytest.raises(InvalidParameterError, match=r"sum to 0\.75"):
        with_medium(Params(), [mp.Layer(0.5), mp.Layer(0.25)], None)
    # One homogeneous sublayer on springs is the panel's layer.
    assert with_medium(Params(), [mp.Layer(1.0, nu=0.3)], None) == Params(nu=0.3)
    hs = mp.HalfSpace(2.0, 0.3)
    on_hs = with_medium(Params(), [mp.Layer(1.0, nu=0.3)], hs)
    assert on_hs.layers == ()
    assert on_hs.half_space == hs
    assert on_hs.nu == 0.3
    medium = on_hs.medium()
    assert medium is not None
    assert medium.base == hs
    assert medium.layers == (mp.Layer(1.0, nu=0.3),)
    # Parameters the medium has no use for are hidden and refused by name.
    stack = with_medium(Params(), [mp.Layer(0.4), mp.Layer(0.6, mu=0.5)], hs)
    assert stack.interfaces() == (-0.4,)
    for name in ("nu", "kw", "kp", "damping"):
        assert not stack.applies(name)
        with pytest.raises(InvalidParameterError) as err:
            stack.with_value(name, 0.1)
        assert err.value.parameter == name
    assert "2 sublayers on bonded half-space" in stack.label()
    assert "nu" not in stack.label()
    assert "kw" not in stack.label()
    assert stack.label(Params()).endswith("2 sublayers on bonded half-space")
    assert Params().label(stack).endswith("homogeneous layer")


def test_medium_scene_round_trip() -> None:
    """A medium is the scene's [[layers]] and [base]: saved and opened back
    unchanged (the bundled media scenes too), never dropped."""
    hs = mp.HalfSpace(0.1, 0.3, interface="smooth")
    for layers, base in (
        ([mp.Layer(0.4), mp.Layer(0.6, mu=0.5, nu=0.3)], None),
        ([mp.Layer(0.4), mp.GradedLayer(1.0, thickness=0.6, mu=0.5)], hs),
        ([mp.Layer(1.0, nu=0.3)], hs),
    ):
        params = with_medium(Params(vstar=0.05), layers, base)
        scene = to_scene(SceneState(params=params))
        assert scene.medium == params.medium()
        back = from_scene(Scene.from_toml(scene.to_toml())).params
        assert back == params, (back, params)
    assert to_scene(SceneState(params=Params())).medium is None
    for name in ("pavement", "graded-coating", "half-space-vs-winkler"):
        scene = Scene.bundled(name)
        params = from_scene(scene).params
        assert params.medium() == scene.medium, name
        assert to_scene(SceneState(params=params)).medium == scene.medium, name


def test_medium_train_runs_on_the_medium_and_on_a_half_space() -> None:
    """A train on a stack on springs is solved on the stack (two identical
    sublayers: the homogeneous layer's train, the anchor); on a half-space
    it is the API's train there."""
    train = tui_model.parse_punches("0.002@-1.5, 0.002@1.5")
    stack = with_medium(Params(punches=train), [mp.Layer(0.4), mp.Layer(0.6)], None)
    got = tui_model.solution(tui_model.Cache(), stack)
    want = tui_model.solution(tui_model.Cache(), Params(punches=train))
    assert got.medium is not None
    assert not got.medium.homogeneous
    for g, w in zip(got.punches, want.punches, strict=True):
        np.testing.assert_allclose(
            g.contact_zones, w.contact_zones, rtol=1e-8, atol=1e-12
        )
        assert g.indentation == pytest.approx(w.indentation, rel=1e-8)
    # On a half-space too (measured from the surface at x = 100 h): the API's.
    on_hs = with_medium(Params(punches=train), [mp.Layer(1.0)], mp.HalfSpace(0.5, 0.3))
    got = tui_model.solution(tui_model.Cache(), on_hs)
    assert got.medium is not None
    assert on_hs.medium() is not None
    api = mp.solve_punches(
        on_hs.train(),
        vstar=on_hs.vstar,
        layers=list(on_hs.medium().layers),
        base=mp.HalfSpace(0.5, 0.3),
    )
    for g, w in zip(got.punches, api.punches, strict=True):
        assert g.contact_zones == w.contact_zones
        assert g.indentation == w.indentation


# -- solves and refusals ---------------------------------------------------------


@sync
async def test_medium_refusal_is_shown_on_the_status_line() -> None:
    """A damped base under a stack runs on the asymmetric solver, which takes
    the homogeneous layer only: the solver's refusal is on the status line,
    the last result stays and the status names the medium it is for."""
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await type_into(pilot, "damping", "0.1", paste=True)
        before = summary_fields(app)
        editor = await build(pilot, [{"thickness": "0.4"}, {"thickness": "0.6"}])
        assert editor.error == ""
        await pilot.press("enter")
        await settle(pilot)
        screen = screen_of(app)
        assert screen.params.layers == (mp.Layer(0.4), mp.Layer(0.6))
        status = status_text(app)
        assert "damped base" in status, status
        assert "showing the result for medium homogeneous layer" in status, status
        assert summary_fields(app) == before  # never a number of this medium
        assert screen.result is not None
        assert screen.result.request.params.layers == ()
        # The panel names the medium and hides ν (each sublayer has its own).
        panel = screen.query_one(ParamsPanel)
        note = str(panel.query_one("#medium-note").render())
        assert "2 sublayers on springs" in note, note
        assert not panel.query_one("#row-nu").display
        assert panel.query_one("#row-kw").display


@sync
async def test_medium_stack_bundled_pavement_opens_with_its_medium() -> None:
    """The bundled pavement scene (two sublayers on soft springs): the panel
    names the medium, ν is hidden, and the summary is the scene's medium
    solved by the API."""
    app = create_app("pavement", cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        scene = Scene.bundled("pavement")
        assert screen.params.medium() == scene.medium
        panel = screen.query_one(ParamsPanel)
        assert "2 sublayers on springs" in str(panel.query_one("#medium-note").render())
        assert not panel.query_one("#row-nu").display
        assert scene.medium is not None
        api = mp.solve(
            vstar=screen.params.vstar,
            radius=screen.params.radius,
            load=screen.params.load,
            layers=list(scene.medium.layers),
            base=scene.medium.base,
        )
        assert_summary_is(app, api, "pavement")
        assert "medium: layer h_i/h = 0.25" in status_text(app), status_text(app)


@sync
async def test_medium_stack_two_identical_sublayers_are_the_plain_layer() -> None:
    """The homogeneous layer cut in two identical sublayers (0.4 + 0.6):
    the numbers on screen are the plain layer's, and the depth plot marks
    the interface at y/h = -0.4."""
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        plain = shown_numbers(app)
        await build(pilot, [{"thickness": "0.4"}, {"thickness": "0.6"}])
        await pilot.press("enter")
        await settle(pilot)
        assert "ready" in status_text(app) or "medium:" in status_text(app), (
            status_text(app)
        )
        cut = shown_numbers(app)
        assert cut.keys() == plain.keys()
        for label, value in plain.items():
            assert cut[label] == pytest.approx(value, rel=2e-6), label
        api = mp.solve(
            vstar=0.2,
            radius=100.0,
            load=0.002,
            layers=[mp.Layer(0.4), mp.Layer(0.6)],
            base=mp.Winkler(1.0),
        )
        assert_summary_is(app, api, "two identical sublayers")


@sync
async def test_medium_stack_two_sublayers_summary_and_depth_interface() -> None:
    """A soft lower sublayer: the summary is the API's, the status names the
    medium, and the depth tab draws the interface and plots σx on both of
    its sides (σx jumps across a bonded interface)."""
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await build(
            pilot,
            [{"thickness": "0.4"}, {"thickness": "0.6", "mu": "0.5", "nu": "0.3"}],
        )
        await pilot.press("enter")
        await settle(pilot)
        layers = [mp.Layer(0.4), mp.Layer(0.6, mu=0.5, nu=0.3)]
        api = mp.solve(
            vstar=0.2, radius=100.0, load=0.002, layers=layers, base=mp.Winkler(1.0)
        )
        assert_summary_is(app, api, "a soft lower sublayer")
        assert "medium: layer h_i/h = 0.4" in status_text(app), status_text(app)
        screen = screen_of(app)
        screen.action_show_tab("depth")
        await settle(pilot)
        plot = screen.query_one("#plot-depth", CurvePlot)
        curves = plot.curves
        assert curves is not None
        assert curves.interfaces == (-0.4,)
        assert any("interfaces y/h -0.4" in f.value for f in legend(curves))
        assert "interfaces y/h -0.4" in str(plot.render())
        above = np.flatnonzero(
            np.isclose(curves.grid, -0.4 + 1e-9, rtol=0.0, atol=1e-12)
        )
        below = np.flatnonzero(
            np.isclose(curves.grid, -0.4 - 1e-9, rtol=0.0, atol=1e-12)
        )
        assert len(above) == 1
        assert len(below) == 1
        values = curves.series[0].values
        sides = api.depth_stress(np.array([-0.4 - 1e-9, -0.4 + 1e-9]))
        np.testing.assert_allclose(values[[below[0], above[0]]], sides, rtol=1e-9)
        assert abs(sides[1] - sides[0]) > 1e-3 * np.max(np.abs(values))  # a jump
        csv = tui_model.to_csv(curves, screen.params)
        assert "# medium: layer h_i/h = 0.4" in csv, csv[:300]


@sync
async def test_medium_depth_plot_draws_the_interfaces() -> None:
    """The depth plot draws each interface as a horizontal line across the
    plot at its y/h and names it in the legend (no layered solve: the
    homogeneous layer's curve with an interface at y/h = -0.4 given)."""
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=(80, 24)) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        screen.action_show_tab("depth")
        await settle(pilot)
        plot = screen.query_one("#plot-depth", CurvePlot)
        curves = plot.curves
        assert curves is not None
        assert curves.interfaces == ()

        def ruled(text: str) -> list[int]:
            """Rows of the plot crossed by a horizontal line."""
            return [
                i
                for i, line in enumerate(text.splitlines())
                if re.search(r"[├┼]─{20,}", line)
            ]

        lines = str(plot.render()).splitlines()
        assert ruled("\n".join(lines)) == []
        assert "interfaces" not in lines[-1]
        plot.curves = replace(curves, interfaces=(-0.4,))
        await pilot.pause()
        lines = str(plot.render()).splitlines()
        rows = ruled("\n".join(lines))
        assert len(rows) == 1, lines
        ticks = {
            float(m.group(1)): i
            for i, line in enumerate(lines)
            if (m := re.match(r"\s*(-?\d\.\d\d)┤", line))
        }
        assert ticks[-0.33] < rows[0] < ticks[-0.5], (ticks, rows, lines)
        assert "interfaces y/h -0.4" in lines[-1], lines[-1]


def test_medium_stack_overlay_and_sweep_of_a_hidden_parameter_say_so() -> None:
    """An overlay of ν beside sublayers draws no curve of its own and says
    why; a sweep of kw under a half-space is a notice; the accuracy ladder
    runs on the medium (its reference too). The current curve is the
    medium's, as the API computes it."""
    cache = tui_model.Cache()
    stack = with_medium(Params(), [mp.Layer(0.4), mp.Layer(0.6, mu=0.5)], None)
    request = tui_model.Request(
        generation=1,
        params=stack,
        tab="pressure",
        overlay=tui_model.Overlay("nu", (0.1, 0.3)),
    )
    result = tui_model.compute(cache, request)
    assert result is not None
    assert isinstance(result.data, tui_model.Curves)
    assert [s.label for s in result.data.series] == ["current ν=0.2"]
    assert any("overlay nu: not drawn" in n for n in result.notes), result.notes
    api = mp.solve(
        vstar=0.2,
        radius=100.0,
        load=0.002,
        layers=[mp.Layer(0.4), mp.Layer(0.6, mu=0.5)],
        base=mp.Winkler(1.0),
    )
    np.testing.assert_allclose(
        result.data.series[0].values, api.pressure(result.data.grid), atol=1e-12
    )
    assert result.summary.medium == api.medium.describe()
    on_hs = with_medium(
        Params(vstar=0.05), [mp.Layer(1.0)], mp.HalfSpace(0.5, 0.3, interface="smooth")
    )
    sweep = tui_model.compute(
        cache,
        tui_model.Request(
            generation=2, params=on_hs, tab="sweep", sweep=tui_model.SweepSpec("kw")
        ),
    )
    assert sweep is not None
    assert isinstance(sweep.data, tui_model.Notice)
    assert "does not apply" in sweep.data.text
    ladder = tui_model.compute(
        cache, tui_model.Request(generation=3, params=on_hs, tab="accuracy")
    )
    assert ladder is not None
    assert isinstance(ladder.data, tui_model.AccuracyTable)
    # The ladder runs on the medium (its reference too: a reference on the
    # homogeneous layer on springs would put every error near 1e-1), each
    # rung's error within its estimate.
    report = ladder.data.report
    assert report.scene.medium == on_hs.medium()
    for rung in report.rungs:
        assert not rung.failure, rung
        assert rung.error_a <= rung.error_estimate + 1e-14, rung
        assert rung.error_a <= max(rung.tol, 1e-12), rung
