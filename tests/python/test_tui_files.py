"""Scene files, export and help in the terminal UI (issue 16): a saved sweep
keeps start, stop, points and spacing; Open and Save suggest the last file
saved or opened; export and save ask before overwriting (the file untouched
until confirmed); the help wraps by paragraph at 80x24 and 120x40.
"""

from __future__ import annotations

import asyncio
import io
import os
import re
from pathlib import Path

import numpy as np
import pytest
import tomllib
from rich.console import Console
from textual.geometry import Region
from textual.pilot import Pilot
from textual.widgets import Input, Label, Static

from movingpunch.scene import Scene, Sweep
from movingpunch.tui import MovingPunchApp, create_app, scene_files
from movingpunch.tui.model import Curves, Params, SweepSpec
from movingpunch.tui.scene_files import SceneState
from movingpunch.tui.screens import MainScreen, PathPrompt
from movingpunch.tui.screens.help import HELP, TABLE_WIDTH, HelpScreen
from tui_pilot import screen_of, settle, sync

SIZE = (100, 32)


def app_on(root: Path, state: SceneState | None = None) -> MovingPunchApp:
    return create_app(
        state or SceneState(params=Params(), name="fig4"),
        show_timing=False,
        cursor_blink=False,
        root=root,
    )


def prompt_message(app: MovingPunchApp) -> str:
    return str(app.screen.query_one("#prompt-msg", Static).render())


def prompt_title(app: MovingPunchApp) -> str:
    return str(app.screen.query_one("#prompt-title", Label).render())


def suggested(app: MovingPunchApp) -> str:
    assert isinstance(app.screen, PathPrompt), app.screen
    return app.screen.query_one("#path", Input).value


async def open_prompt(pilot: Pilot[None], key: str) -> None:
    await pilot.press(key)
    await pilot.pause()
    assert isinstance(pilot.app.screen, PathPrompt), pilot.app.screen


async def type_path(pilot: Pilot[None], path: str) -> None:
    """Clears the prompt's path and types ``path`` key by key, then enter."""
    box = pilot.app.screen.query_one("#path", Input)
    box.clear()
    await pilot.pause()
    await pilot.press(*path)
    await pilot.press("enter")
    await pilot.pause()


async def confirm(pilot: Pilot[None]) -> None:
    """A deliberate second enter (after the guard against a repeated key)."""
    await asyncio.sleep(PathPrompt.CONFIRM_AFTER + 0.05)
    await pilot.press("enter")
    await pilot.pause()


def stamp(path: Path) -> tuple[bytes, int]:
    return path.read_bytes(), path.stat().st_mtime_ns


def aged(path: Path, text: str) -> tuple[bytes, int]:
    """Writes ``text`` to ``path`` with an old mtime; its bytes and mtime."""
    path.write_text(text, encoding="utf-8")
    os.utime(path, ns=(1_000_000_000_000_000_000, 1_000_000_000_000_000_000))
    return stamp(path)


# -- 1. sweeps keep their range ----------------------------------------------


def sweep_table(text: str) -> str:
    """The [sweep] table of a saved scene's TOML text."""
    match = re.search(r"^\[sweep\]\n(.*?)(?=^\[|\Z)", text, re.S | re.M)
    assert match, text
    return match.group(1)


def test_the_default_sweep_is_a_log_range_around_the_current_value() -> None:
    spec = SweepSpec()
    assert spec.is_range
    assert (spec.points, spacing := spec.spacing) == (13, "log"), spacing
    base = Params(load=0.003)
    assert spec.bounds(base) == pytest.approx((0.0003, 0.03), rel=1e-15)
    start, stop = spec.bounds(base)
    np.testing.assert_array_equal(spec.grid(base), np.geomspace(start, stop, 13))
    assert not SweepSpec(values=(1.0, 2.0)).is_range


def test_to_scene_writes_the_default_sweep_as_a_range(tmp_path: Path) -> None:
    params = Params(load=0.003)
    scene = scene_files.to_scene(SceneState(params=params, sweep=SweepSpec()))
    assert scene.sweep is not None
    assert scene.sweep.is_range
    assert (scene.sweep.start, scene.sweep.stop) == pytest.approx(
        (0.0003, 0.03), rel=1e-15
    )
    assert (scene.sweep.points, scene.sweep.spacing) == (13, "log")
    path = tmp_path / "s.toml"
    scene.save(path)
    table = sweep_table(path.read_text(encoding="utf-8"))
    assert "values" not in table
    back = scene_files.load(path).sweep
    assert back is not None
    np.testing.assert_allclose(
        back.grid(params), SweepSpec().grid(params), rtol=1e-12, atol=0
    )


@pytest.mark.parametrize("name", ["fig2", "fig3", "near-critical", "spacing"])
def test_a_range_sweep_round_trips_as_a_range(name: str, tmp_path: Path) -> None:
    scene = Scene.bundled(name)
    assert scene.sweep is not None
    assert scene.sweep.is_range
    state = scene_files.from_scene(scene)
    assert state.sweep is not None
    assert state.sweep.is_range
    path = tmp_path / f"{name}.toml"
    scene_files.save(state, path)
    saved = Scene.load(path).sweep
    assert saved is not None
    assert saved.is_range
    original = scene.sweep
    assert (saved.param, saved.start, saved.stop, saved.points, saved.spacing) == (
        original.param,
        original.start,
        original.stop,
        original.points,
        original.spacing,
    )
    assert saved.values == original.values
    assert "values" not in sweep_table(path.read_text(encoding="utf-8"))


def test_explicit_sweep_values_stay_explicit(tmp_path: Path) -> None:
    values = (0.001, 0.002, 0.005)
    scene = Scene.bundled("fig4").with_params()
    path = tmp_path / "explicit.toml"
    Scene(
        params=scene.params,
        outputs=scene.outputs,
        sweep=Sweep(param="load", values=values, quantities=("a",)),
    ).save(path)
    state = scene_files.load(path)
    assert state.sweep == SweepSpec(param="load", values=values)
    again = tmp_path / "again.toml"
    scene_files.save(state, again)
    saved = Scene.load(again).sweep
    assert saved is not None
    assert not saved.is_range
    assert saved.values == values
    table = sweep_table(again.read_text(encoding="utf-8"))
    assert "start" not in table
    assert "points" not in table


@sync
async def test_a_sweep_saved_from_the_app_keeps_its_range(tmp_path: Path) -> None:
    app = app_on(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        await pilot.press("4")  # the a/h sweep tab
        await settle(pilot)
        shown = screen.results["sweep"].data
        await open_prompt(pilot, "s")
        await type_path(pilot, "swept.toml")
        assert isinstance(app.screen, MainScreen)
        text = (tmp_path / "swept.toml").read_text(encoding="utf-8")
        table = sweep_table(text)
        assert re.search(r"^start = ", table, re.M), table
        assert re.search(r"^stop = ", table, re.M), table
        assert re.search(r"^points = 13$", table, re.M), table
        assert re.search(r'^spacing = "log"$', table, re.M), table
        assert "values" not in table
        # No list of 13 floats anywhere in the file.
        lists = re.findall(r"\[([^\[\]]*)\]", text)
        assert all(len(item.split(",")) < 13 for item in lists), lists
        data = tomllib.loads(text)["sweep"]
        assert data["start"] == pytest.approx(0.0002, rel=1e-15)
        assert data["stop"] == pytest.approx(0.02, rel=1e-15)
        # Reopened: the same grid.
        grid = screen.sweep.grid(screen.params)
        await open_prompt(pilot, "o")
        await type_path(pilot, "swept.toml")
        await settle(pilot)
        assert isinstance(app.screen, MainScreen)
        assert screen.sweep.is_range
        np.testing.assert_allclose(
            screen.sweep.grid(screen.params), grid, rtol=1e-12, atol=0
        )
        reopened = screen.results["sweep"].data
        assert isinstance(reopened, Curves)
        assert isinstance(shown, Curves)
        np.testing.assert_allclose(reopened.grid, shown.grid, rtol=1e-12, atol=0)
        assert reopened.log_grid


# -- 2. what the prompts suggest ---------------------------------------------


@sync
async def test_open_and_save_suggest_the_last_file(tmp_path: Path) -> None:
    Scene.bundled("fig4").with_params(vstar=0.1).save(tmp_path / "slow.toml")
    app = app_on(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        for key in ("o", "s"):
            await open_prompt(pilot, key)
            assert suggested(app) == "scene.toml"
            await pilot.press("escape")
            await pilot.pause()
        await open_prompt(pilot, "e")
        assert suggested(app) == "movingpunch-pressure.csv"
        await pilot.press("escape")
        # Saved: both suggest the saved file.
        await open_prompt(pilot, "s")
        await type_path(pilot, "mine.toml")
        assert isinstance(app.screen, MainScreen)
        for key in ("o", "s"):
            await open_prompt(pilot, key)
            assert suggested(app) == "mine.toml"
            await pilot.press("escape")
            await pilot.pause()
        # Opened: both suggest the opened file.
        await open_prompt(pilot, "o")
        await type_path(pilot, "slow.toml")
        await settle(pilot)
        assert screen.params.vstar == 0.1
        for key in ("o", "s"):
            await open_prompt(pilot, key)
            assert suggested(app) == "slow.toml"
            await pilot.press("escape")
            await pilot.pause()
        # A bundled scene's name is not a file: the suggestion stays.
        await open_prompt(pilot, "o")
        await type_path(pilot, "fig5")
        await settle(pilot)
        assert screen.overlay is not None
        await open_prompt(pilot, "o")
        assert suggested(app) == "slow.toml"
        await pilot.press("escape")
        # A failed open or a cancelled save changes nothing.
        await open_prompt(pilot, "o")
        await type_path(pilot, "missing.toml")
        assert prompt_message(app).startswith("missing.toml:")
        await pilot.press("escape")
        await open_prompt(pilot, "s")
        await pilot.press("escape")
        await open_prompt(pilot, "o")
        assert suggested(app) == "slow.toml"
        await pilot.press("escape")
        # Export suggests the tab's own name.
        await pilot.press("2")
        await settle(pilot)
        await open_prompt(pilot, "e")
        assert suggested(app) == "movingpunch-surface.csv"


# -- 3. asking before overwriting --------------------------------------------


@pytest.fixture
def slow_confirm(monkeypatch: pytest.MonkeyPatch) -> None:
    """The repeated-key guard at 3 s: a repeated enter sent a moment after
    the question stays within it on a loaded machine (at 0.3 s a busy CI
    once let it through as a confirmation)."""
    monkeypatch.setattr(PathPrompt, "CONFIRM_AFTER", 3.0)


@pytest.mark.usefixtures("slow_confirm")
@sync
async def test_export_twice_to_the_same_name_asks(tmp_path: Path) -> None:
    target = tmp_path / "movingpunch-pressure.csv"
    app = app_on(tmp_path)
    async with app.run_test(size=(80, 24)) as pilot:
        await settle(pilot)
        await open_prompt(pilot, "e")
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, MainScreen)  # a new file: written
        first = aged(target, target.read_text(encoding="utf-8"))
        await open_prompt(pilot, "e")
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, PathPrompt)
        assert prompt_message(app) == (
            "movingpunch-pressure.csv exists: enter again to overwrite, "
            "escape to cancel"
        )
        assert prompt_title(app) == "Overwrite movingpunch-pressure.csv?"
        assert stamp(target) == first
        # A repeated enter (double tap, key repeat) does not confirm.
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, PathPrompt)
        assert stamp(target) == first
        # Escape: untouched.
        await pilot.press("escape")
        await pilot.pause()
        assert isinstance(app.screen, MainScreen)
        assert stamp(target) == first
        # Asked again, then confirmed: written.
        await open_prompt(pilot, "e")
        await pilot.press("enter")
        await pilot.pause()
        assert stamp(target) == first
        await confirm(pilot)
        assert isinstance(app.screen, MainScreen)
        assert stamp(target) != first
        assert target.read_text(encoding="utf-8").startswith("# movingpunch")


@sync
async def test_save_twice_to_the_same_name_asks(tmp_path: Path) -> None:
    target = tmp_path / "scene.toml"
    app = app_on(tmp_path)
    async with app.run_test(size=(80, 24)) as pilot:
        await settle(pilot)
        await open_prompt(pilot, "s")
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, MainScreen)
        first = aged(target, target.read_text(encoding="utf-8"))
        await open_prompt(pilot, "s")
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, PathPrompt)
        assert prompt_message(app) == (
            "scene.toml exists: enter again to overwrite, escape to cancel"
        )
        assert stamp(target) == first
        await pilot.press("enter")  # too soon: a repeated key
        await pilot.pause()
        assert stamp(target) == first
        await confirm(pilot)
        assert isinstance(app.screen, MainScreen)
        assert stamp(target) != first
        assert Scene.load(target).params["vstar"] == 0.2


@sync
async def test_a_changed_path_needs_its_own_confirmation(tmp_path: Path) -> None:
    one = tmp_path / "one.csv"
    two = tmp_path / "two.csv"
    for key in ("e", "s"):
        before_one = aged(one, "one\n")
        before_two = aged(two, "two\n")
        app = app_on(tmp_path)
        async with app.run_test(size=SIZE) as pilot:
            await settle(pilot)
            await open_prompt(pilot, key)
            prompt = app.screen
            assert isinstance(prompt, PathPrompt)
            await type_path(pilot, "one.csv")
            assert prompt.asking == "one.csv"
            assert "one.csv exists" in prompt_message(app)
            # Another existing path: asked about on its own, nothing written.
            await type_path(pilot, "two.csv")
            assert prompt.asking == "two.csv"
            assert "two.csv exists" in prompt_message(app)
            assert stamp(one) == before_one
            assert stamp(two) == before_two
            # Editing the path drops the question (the title too).
            box = prompt.query_one("#path", Input)
            box.value = "one.cs"
            await pilot.pause()
            assert prompt.asking is None
            assert prompt_message(app) == PathPrompt.HINT
            assert not prompt_title(app).startswith("Overwrite")
            box.value = "one.csv"
            await pilot.pause()
            await asyncio.sleep(PathPrompt.CONFIRM_AFTER + 0.05)
            await pilot.press("enter")  # first enter on the edited path: asks
            await pilot.pause()
            assert app.screen is prompt
            assert prompt.asking == "one.csv"
            assert stamp(one) == before_one
            await confirm(pilot)
            assert isinstance(app.screen, MainScreen)
            assert stamp(one) != before_one
            assert stamp(two) == before_two


@sync
async def test_prompt_errors_name_the_path(tmp_path: Path) -> None:
    app = app_on(tmp_path)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await open_prompt(pilot, "o")
        await type_path(pilot, "nosuch")
        assert prompt_message(app).startswith("nosuch: (file): no such scene file")
        app.screen.query_one("#path", Input).value = "  "
        await pilot.press("enter")
        await pilot.pause()
        assert "give a file name" in prompt_message(app)
        await pilot.press("escape")
        await open_prompt(pilot, "s")
        await type_path(pilot, "../up.toml")
        assert prompt_message(app).startswith("../up.toml: outside the working folder")


# -- 4. the help screen --------------------------------------------------------


def help_lines(app: MovingPunchApp) -> list[str]:
    """Every rendered line of the help text at the screen's width (also the
    lines scrolled out of view)."""
    text = app.screen.query_one("#help-text", Static)
    width, height = text.size
    return [s.text.rstrip() for s in text.render_lines(Region(0, 0, width, height))]


def screen_text(app: MovingPunchApp) -> str:
    """The screen as plain text, one row per line."""
    width, height = app.size
    console = Console(
        record=True,
        width=width,
        height=height,
        file=io.StringIO(),
        legacy_windows=False,
    )
    console.print(app.screen._compositor.render_update(full=True))
    return console.export_text()


def norm(line: str) -> str:
    return " ".join(line.split())


@pytest.mark.parametrize("size", [(80, 24), (120, 40)])
@sync
async def test_the_help_wraps_by_paragraph(size: tuple[int, int]) -> None:
    app = create_app(show_timing=False, cursor_blink=False)
    async with app.run_test(size=size) as pilot:
        await settle(pilot)
        await pilot.press("question_mark")
        await pilot.pause()
        assert isinstance(app.screen, HelpScreen)
        lines = help_lines(app)
        assert norm(" ".join(lines)) == norm(HELP)  # all of it, nothing cut
        source = {norm(line) for line in HELP.splitlines()}
        for i, line in enumerate(lines):
            words = line.split()
            if len(words) == 1 and norm(line) not in source:
                # A lone word wrapped from its paragraph ends the paragraph:
                # a hard break inside a paragraph would go on below it.
                following = lines[i + 1] if i + 1 < len(lines) else ""
                assert not following.strip(), (lines[i - 1 : i + 2], size)
        # Every line of the tables on one line, intact.
        table = [line for line in HELP.splitlines() if line.startswith("  ")]
        assert len(table) > 20
        shown = set(lines)
        for line in table:
            assert len(line) <= TABLE_WIDTH
            assert line in shown, (line, size)
        # The screen shows the box's first lines inside its borders; a help
        # longer than the screen scrolls.
        box = app.screen.query_one("#help-box")
        rows = screen_text(app).splitlines()
        assert len(rows) == size[1]
        assert "movingpunch: a rigid punch" in rows[1]
        assert all(len(row) <= size[0] for row in rows)
        assert any(lines[1] in row for row in rows)
        if len(lines) + 2 > size[1]:
            assert box.max_scroll_y > 0
            await pilot.press("end")
            await pilot.pause()
            assert box.scroll_y == box.max_scroll_y
        await pilot.press("escape")
        await pilot.pause()
        assert isinstance(app.screen, MainScreen)


def test_the_help_is_current() -> None:
    for text in (
        "1 ... 6",
        "speed",
        "foundation",
        "punch",
        "numerics",
        "R/h",
        "b/h",
        "P/(μh)",
        "ν",
        "kw",
        "kp",
        "damp",
        "fric",
        "tol",
        "cont",
        "train",
        "200 ms",
        "δ/h > 0.05",
        "a/h > 5",
        "strain > 0.05",
        "within 1 %",
        "enter again to overwrite, escape to cancel",
        "start, stop, points and spacing",
    ):
        assert text in HELP, text
    # No hard break inside a paragraph: only table lines are short lines.
    for block in HELP.split("\n\n"):
        lines = block.splitlines()
        if len(lines) > 1:
            assert all(line.startswith("  ") for line in lines[1:]), lines[0]
