"""The terminal UI driven through Textual's pilot (``App.run_test``).

Numbers on screen are checked against the Python API and against physical
facts that do not come from the UI (the pressure integrates to the load;
a faster punch or a softer foundation widens the contact).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from textual.widgets import Input

import movingpunch as mp
from movingpunch.errors import ConvergenceError
from movingpunch.tui import MovingPunchApp, create_app
from movingpunch.tui.messages import Computed
from movingpunch.tui.model import (
    PAPER_FIG4,
    Curves,
    FieldMap,
    Params,
    Request,
    Result,
    Series,
)
from movingpunch.tui.screens import MainScreen, OverlayPrompt, PathPrompt
from movingpunch.tui.widgets import CurvePlot, Gauge, ParamsPanel, StressMap
from movingpunch.tui.widgets.params import LABELS, MessageLine
from tui_pilot import (
    screen_of,
    settle,
    status_ok,
    status_text,
    summary_text,
    sync,
    type_into,
)

SIZE = (100, 32)


def curves(app: MovingPunchApp, tab: str) -> Curves:
    data = screen_of(app).query_one(f"#plot-{tab}", CurvePlot).curves
    assert data is not None
    return data


def a_on_screen(app: MovingPunchApp) -> float:
    text = summary_text(app)
    return float(text.split("a/h ", 1)[1].split()[0])


@sync
async def test_starts_on_the_papers_fig4_case() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        assert screen.params == PAPER_FIG4
        assert PAPER_FIG4.physical() == {
            "vstar": 0.2,
            "kw": 1.0,
            "radius": 100.0,
            "load": 0.002,
            "nu": 0.2,
        }
        ref = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
        assert a_on_screen(app) == pytest.approx(ref.a, rel=1e-5)
        assert "μ/(P/h) 500" in str(screen.query_one("#mu-note").render())
        # The pressure curve carries the load: its integral over x/h is 1.
        p = curves(app, "pressure")
        assert p.grid_label == "x/h"
        assert p.value_label == "p(x)/(P/h)"
        assert np.trapezoid(p.series[0].values, p.grid) == pytest.approx(1.0, rel=2e-3)
        # The gauge shows V*_cr(kw = 1) = 0.5716928 (docs/theory.md §8) and V*_R.
        limits = screen.query_one(Gauge).limits
        assert limits is not None
        assert limits[1] == pytest.approx(0.5716928, rel=1e-6)
        assert limits[2] == pytest.approx(0.8299135134, rel=1e-9)
        assert not screen.query_one(Gauge).has_class("-warning")


@sync
async def test_only_the_visible_tab_is_computed() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        kinds = {kind for kind, _ in screen.cache.kinds()}
        assert "pressure" in kinds
        assert not kinds & {"surface", "depth", "a", "field-sigma_x"}
        for key, tab, kind in (
            ("2", "surface", "surface"),
            ("3", "depth", "depth"),
            ("4", "sweep", "a"),
            ("5", "field", "field-sigma_x"),
        ):
            await pilot.press(key)
            await settle(pilot)
            assert screen.tab == tab
            assert kind in {k for k, _ in screen.cache.kinds()}
        field = screen.query_one("#plot-field", StressMap).field
        assert isinstance(field, FieldMap)
        # sigma_x under the centre of the map's top row is compressive.
        centre = int(np.argmin(np.abs(field.x)))
        assert field.values[-1, centre] < 0 < np.max(field.values[0])
        await pilot.press("m")
        await settle(pilot)
        vm = screen.query_one("#plot-field", StressMap).field
        assert vm is not None
        assert vm.quantity == "von_mises"
        assert float(np.min(vm.values)) >= 0.0


# name, typed text, expected sign of the change of a/h (physics: a faster
# punch, a softer foundation, a larger radius or load widen the contact).
CHANGES = [
    ("vstar", "0.35", +1),
    ("kw", "10", -1),
    ("kw", "inf", -1),
    ("radius", "200", +1),
    ("load", "0.004", +1),
    ("nu", "0.3", -1),
    ("tol", "1e-5", 0),
]


@sync
async def test_each_parameter_changes_the_summary_and_the_plot() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        a_fig4 = a_on_screen(app)
        for name, text, sign in CHANGES:
            before = screen.result
            assert before is not None
            p_before = curves(app, "pressure").series[0].values.copy()
            await type_into(pilot, name, text)  # key by key
            after = screen.result
            assert after is not None
            assert after is not before
            assert after.summary.params.get(name) == float(text)
            changed = {**PAPER_FIG4.physical(), "tol": PAPER_FIG4.tol}
            ref = mp.solve(**{**changed, name: float(text)})
            assert a_on_screen(app) == pytest.approx(ref.a, rel=1e-5), name
            p_after = curves(app, "pressure").series[0].values
            if sign:
                assert np.sign(a_on_screen(app) - a_fig4) == sign, name
                assert not np.allclose(p_after, p_before), name
            else:  # a looser tolerance: the same curve, solved at that tol
                # (Fig. 4 converges at N = 16 on a 1e-10 kernel at either
                # tol, so the error estimate barely moves).
                assert after.summary.error_estimate <= 1e-5 * after.summary.a
                assert after.summary.error_estimate == pytest.approx(
                    ref.error_estimate, rel=1e-6
                )
                np.testing.assert_allclose(p_after, p_before, atol=1e-4)
            if name == "load":
                note = str(screen.query_one("#mu-note").render())
                assert "μ/(P/h) 250" in note
            assert screen.query_one(ParamsPanel).message(name) == ""
            await type_into(pilot, name, PAPER_FIG4_TEXT[name], paste=True)
            assert a_on_screen(app) == pytest.approx(a_fig4, rel=1e-12)


INVALID = [
    ("vstar", "abc", ["vstar", "real number", "0 <= vstar < V*_cr"]),
    ("vstar", "-0.1", ["vstar", "0 <= vstar < V*_cr"]),
    ("vstar", "nan", ["vstar", "finite"]),
    ("kw", "-1", ["kw", "1e-12 <= kw <= inf"]),
    ("kw", "0", ["kw", "1e-12 <= kw <= inf"]),
    ("radius", "0", ["radius", "0 < radius <= 1e12", "R/h"]),
    ("radius", "inf", ["radius", "finite"]),
    ("load", "-2", ["load", "0 < load <= 1e6", "P/(mu h)"]),
    ("load", "", ["load", "real number"]),
    ("nu", "0.5", ["nu", "0 <= nu < 0.5"]),
    ("tol", "1", ["tol", "1e-14 <= tol <= 1e-2"]),
    ("tol", "1e999", ["tol", "finite"]),
]


@sync
async def test_invalid_input_shows_the_range_and_keeps_the_last_result() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        for name, text, words in INVALID:
            before = screen.result
            shown = summary_text(app)
            p_before = curves(app, "pressure")
            # Pasted: typed key by key, a valid prefix ("-0" of "-0.1") would
            # become the last valid result.
            await type_into(pilot, name, text, paste=True)
            if not text:  # an empty box is still being typed into until enter
                assert screen.query_one(ParamsPanel).message(name) == ""
                assert "typing" in status_text(app)
                await pilot.press("enter")
                await settle(pilot)
            message = screen.query_one(ParamsPanel).message(name)
            for word in words:
                assert word in message, message
            assert screen.query_one(f"#msg-{name}").has_class("-shown")
            assert f"invalid {LABELS[name]}" in status_text(app)
            assert f"showing the result for {LABELS[name]}" in status_text(app)
            assert screen.result is before
            assert summary_text(app) == shown
            assert curves(app, "pressure") is p_before
            # Fixing the input clears the message and computes again.
            await type_into(pilot, name, PAPER_FIG4_TEXT[name], paste=True)
            assert screen.query_one(ParamsPanel).message(name) == ""
            assert "invalid" not in status_text(app)


PAPER_FIG4_TEXT = {"vstar": "0.2", "kw": "1", "radius": "100", "load": "0.002"}
PAPER_FIG4_TEXT |= {"nu": "0.2", "tol": "1e-8"}


@sync
async def test_supercritical_speed_is_an_inline_message_on_vstar() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        before = screen.result
        await type_into(pilot, "vstar", "0.6", paste=True)  # V*_cr(1) = 0.5717
        message = screen.query_one(ParamsPanel).message("vstar")
        assert "V*_cr = 0.571693" in message
        assert "0 <= V* < V*_cr" in message
        assert "supercritical" in status_text(app)
        assert screen.result is before
        assert screen.query_one(Gauge).has_class("-warning")
        # Near the limit (> 95 % of V*_cr) the gauge warns, the solve works.
        await type_into(pilot, "vstar", "0.56")
        assert screen.query_one(ParamsPanel).message("vstar") == ""
        assert screen.query_one(Gauge).has_class("-warning")
        assert screen.result is not before
        await type_into(pilot, "vstar", "0.3")
        assert not screen.query_one(Gauge).has_class("-warning")


@sync
async def test_unphysical_and_convergence_errors_are_inline() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        # kw = 0.01 makes V* = 0.2 supercritical; V* = 0.086 (1 % below V*_cr)
        # with the paper's load separates the contact (docs/theory.md §9):
        # unphysical as a single contact (contact auto finds its zones).
        await type_into(pilot, "contact", "single")
        await type_into(pilot, "kw", "0.01")
        assert "V*_cr" in screen.query_one(ParamsPanel).message("vstar")
        kept = screen.result
        await type_into(pilot, "vstar", "0.086", paste=True)
        assert screen.query_one(ParamsPanel).message("vstar") == ""
        assert "unphysical contact" in status_text(app)
        # the whole message (key x): the summary may end before this clause
        assert "separates" in screen.query_one("#status", MessageLine).full
        assert screen.result is kept
        # A convergence failure of the current request: the same inline path.
        screen.show_error(ConvergenceError("the width iteration missed its tolerance"))
        await pilot.pause()
        assert "no convergence: the width iteration" in status_text(app)
        await type_into(pilot, "vstar", "0.05")
        assert status_ok(app), status_text(app)


@sync
async def test_hostile_typing_never_crashes() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        for text in ["1e309", "--1", "0x10", "1,5", "∞", " ", "1e-320", "inf"]:
            await type_into(pilot, "radius", text, paste=True)
        for name in ("vstar", "kw", "load", "nu", "tol"):
            for text in ["1e309", "∞", "-inf"]:
                await type_into(pilot, name, text, paste=True)
        await type_into(pilot, "radius", "-1e3x")  # key by key
        await type_into(pilot, "radius", "100", paste=True)
        await type_into(pilot, "vstar", "0.2", paste=True)
        assert screen_of(app).query_one(ParamsPanel).message("radius") == ""
        assert app.is_running
        assert isinstance(app.screen, MainScreen)


@sync
async def test_a_stale_result_never_overwrites_a_newer_one() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        current = screen.result
        assert current is not None
        old = Request(
            generation=screen.generation - 1, params=Params(vstar=0.4), tab="pressure"
        )
        stale = Result(
            request=old,
            summary=current.summary,
            data=Curves(
                "pressure", "t", "x", "p", np.zeros(2), (Series("s", np.ones(2)),)
            ),
        )
        screen.post_message(Computed(stale))
        await settle(pilot)
        assert screen.result is current
        assert curves(app, "pressure") is current.data


@sync
async def test_pin_and_clear() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        await pilot.press("p")
        await settle(pilot)
        await type_into(pilot, "vstar", "0.4")
        await pilot.press("escape")
        data = curves(app, "pressure")
        assert [s.label for s in data.series] == ["current", "pin1 V*=0.2"]
        # The pinned curve is the V* = 0.2 pressure, the current one wider.
        pinned = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
        np.testing.assert_allclose(data.series[1].values, pinned.pressure(data.grid))
        assert "1 pinned" in status_text(app)
        await pilot.press("2")
        await settle(pilot)
        assert len(curves(app, "surface").series) == 2
        await pilot.press("c")
        await settle(pilot)
        assert len(curves(app, "surface").series) == 1
        assert screen.pins == []


@sync
async def test_overlay_from_the_prompt() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        await pilot.press("v")
        await pilot.pause()
        prompt = app.screen
        assert isinstance(prompt, OverlayPrompt)
        box = prompt.query_one("#overlay-values", Input)
        box.clear()
        await pilot.press(*"0.1, 0.3, oops", "enter")
        await pilot.pause()
        assert "vstar" in str(prompt.query_one("#prompt-msg").render())
        assert app.screen is prompt
        box.clear()
        await pilot.press(*"0.1, 0.3, 0.6", "enter")
        await settle(pilot)
        assert app.screen is screen
        labels = [s.label for s in curves(app, "pressure").series]
        assert labels == ["current V*=0.2", "V*=0.1", "V*=0.3"]
        # V* = 0.6 is above V*_cr(kw = 1): left out, with a note.
        assert "V*=0.6: vstar = 0.6 is at or above" in status_text(app)
        # The sweep tab draws one a/h curve per member; faster is wider.
        await pilot.press("4")
        await settle(pilot)
        sweep = curves(app, "sweep")
        assert [s.label for s in sweep.series] == labels
        current, slow, fast = (s.values for s in sweep.series)
        assert np.all(slow < current)
        assert np.all(current < fast)


@sync
async def test_export_writes_a_csv_that_loads_back(tmp_path: Path) -> None:
    app = create_app(root=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        for key, tab in (("1", "pressure"), ("4", "sweep"), ("5", "field")):
            await pilot.press(key)
            await settle(pilot)
            target = tmp_path / f"{tab}.csv"
            await pilot.press("e")
            await pilot.pause()
            assert isinstance(app.screen, PathPrompt)
            box = app.screen.query_one("#path", Input)
            box.value = str(target)
            await pilot.press("enter")
            await pilot.pause()
            table = np.loadtxt(target, delimiter=",")
            data = screen_of(app).results[tab].data
            if isinstance(data, Curves):
                np.testing.assert_array_equal(table[:, 0], data.grid)
                np.testing.assert_array_equal(table[:, 1], data.series[0].values)
            else:
                assert table.shape == (data.values.size, 3)
                np.testing.assert_array_equal(table[:, 2], data.values.ravel())
        # An unwritable path is an inline message in the prompt, not a crash.
        await pilot.press("e")
        await pilot.pause()
        prompt = app.screen
        prompt.query_one("#path", Input).value = str(tmp_path / "no" / "dir.csv")
        await pilot.press("enter")
        await pilot.pause()
        assert app.screen is prompt
        assert "No such file" in str(prompt.query_one("#prompt-msg").render())
        await pilot.press("escape")


@sync
async def test_help_and_escape() -> None:
    app = create_app()
    async with app.run_test(size=(80, 24)) as pilot:
        await settle(pilot)
        await pilot.press("question_mark")
        await pilot.pause()
        assert type(app.screen).__name__ == "HelpScreen"
        await pilot.press("escape")
        await pilot.pause()
        assert isinstance(app.screen, MainScreen)
        await pilot.press("i")
        assert app.focused is app.screen.query_one("#in-vstar", Input)
        await pilot.press("q")  # a letter in an input is text, not quit
        assert app.is_running
        await pilot.press("escape")
        assert not isinstance(app.focused, Input)
        await pilot.press("q")
        await pilot.pause()
        assert not app.is_running


@sync
async def test_figure_keys_load_the_bundled_scenes() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        await pilot.press("f5")  # Fig. 5: several foundation stiffnesses
        await settle(pilot)
        assert screen.overlay is not None
        assert screen.overlay.param == "kw"
        assert screen.tab == "pressure"
        series = curves(app, "pressure").series
        assert len(series) == 1 + len(screen.overlay.values) - 1  # 1.0 is current
        # Stiffer foundations raise the contact pressure peak (the paper's
        # reading of Fig. 5): compare the peaks of kw = 0.1 and kw = inf.
        peaks = {s.label: float(np.max(s.values)) for s in series}
        assert peaks["kw=0.1"] < peaks["current kw=1"] < peaks["kw=inf"]
        await pilot.press("f2")  # Fig. 2: a/h against R/h for several V*
        await settle(pilot)
        assert screen.tab == "sweep"
        sweep = curves(app, "sweep")
        assert sweep.grid_label == "R/h"
        assert len(sweep.grid) == 20
        # a/h grows with the radius on every curve.
        for s in sweep.series:
            assert np.all(np.diff(s.values) > 0), s.label


@sync
async def test_open_and_save_a_scene_round_trip(tmp_path: Path) -> None:
    from movingpunch.scene import Scene

    app = create_app("fig6", root=tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        assert screen.overlay is not None
        assert screen.overlay.param == "radius"
        await type_into(pilot, "load", "0.003", paste=True)
        await type_into(pilot, "kw", "inf", paste=True)
        await pilot.press("escape")
        target = tmp_path / "mine.toml"
        await pilot.press("s")
        await pilot.pause()
        assert isinstance(app.screen, PathPrompt)
        app.screen.query_one("#path", Input).value = str(target)
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, MainScreen)
        saved = Scene.load(target)
        assert saved.params["load"] == 0.003
        assert math.isinf(saved.params["kw"])
        assert saved.vary is not None
        assert saved.vary.values == (10.0, 25.0, 50.0, 100.0)
        # Change everything, then open the file: the saved state comes back.
        await type_into(pilot, "load", "0.001", paste=True)
        await pilot.press("escape", "c")
        await settle(pilot)
        assert screen.overlay is None
        await pilot.press("o")
        await pilot.pause()
        prompt = app.screen
        prompt.query_one("#path", Input).value = str(tmp_path / "missing.toml")
        await pilot.press("enter")
        await pilot.pause()
        assert app.screen is prompt  # the error is shown in the prompt
        assert "cannot read" in str(prompt.query_one("#prompt-msg").render())
        prompt.query_one("#path", Input).value = str(target)
        await pilot.press("enter")
        await settle(pilot)
        assert screen.params == Params(
            vstar=0.2, kw=math.inf, radius=100.0, load=0.003, nu=0.2, tol=1e-8
        )
        assert screen.query_one("#in-load", Input).value == "0.003"
        assert screen.query_one("#in-kw", Input).value == "inf"
        assert screen.overlay is not None
        assert screen.overlay.param == "radius"
        ref = mp.solve(vstar=0.2, kw=math.inf, radius=100.0, load=0.003)
        assert a_on_screen(app) == pytest.approx(ref.a, rel=1e-5)


def test_the_model_does_not_import_textual(
    modules_loaded_by: Callable[[str], set[str]],
) -> None:
    # What the workers compute is plain Python + NumPy (testable alone).
    loaded = modules_loaded_by("import movingpunch.tui.model")
    assert "movingpunch.tui.model" in loaded
    assert sorted(m for m in loaded if m.split(".")[0] == "textual") == []


@sync
async def test_progress_of_the_current_request_only() -> None:
    from textual.widgets import ProgressBar

    from movingpunch.tui.messages import Progressed

    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        await pilot.press("4")  # the sweep: 13 solves, reported one by one
        await settle(pilot)
        bar = screen.query_one("#progress", ProgressBar)
        assert bar.total == 13
        assert bar.progress == 13
        assert not bar.has_class("-busy")  # hidden when done
        screen.post_message(Progressed(screen.generation - 1, 1, 99))
        await pilot.pause()
        assert bar.total == 13
        screen.post_message(Progressed(screen.generation, 5, 20))
        await pilot.pause()
        assert (bar.progress, bar.total) == (5, 20)
