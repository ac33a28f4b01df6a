"""The terminal UI's Accuracy tab and the tolerance presets in the tol input.

The ladder's errors are checked against a reference the test computes
itself at another fixed collocation size (N = 96), not against the UI.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from textual.widgets import Input

import movingpunch as mp
from movingpunch.accuracy import LADDER
from movingpunch.tui import MovingPunchApp, create_app
from movingpunch.tui.model import AccuracyTable, Params
from movingpunch.tui.screens import MainScreen, PathPrompt
from movingpunch.tui.widgets import AccuracyView, ParamsPanel
from tui_pilot import screen_of, settle, sync, type_into


def shown(app: MovingPunchApp) -> AccuracyTable:
    table = screen_of(app).query_one(AccuracyView).table
    assert table is not None
    return table


def accuracy_builds(screen: MainScreen) -> int:
    return screen.cache.misses.get("accuracy", 0)


@sync
async def test_accuracy_tab_is_computed_when_opened() -> None:
    app = create_app(show_timing=False)
    async with app.run_test(size=(120, 40)) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        assert accuracy_builds(screen) == 0  # not until the tab is opened
        assert shown_or_none(app) is None
        await pilot.press("6")
        await settle(pilot)
        assert screen.tab == "accuracy"
        assert accuracy_builds(screen) == 1
        report = shown(app).report
        assert [r.tol for r in report.rungs] == list(LADDER)
        ref = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, tol=1e-14, n=96)
        for r in report.rungs:
            assert not r.failure
            assert r.bounded
            if r.tol >= 1e-10:
                assert r.error_a < r.tol
                assert r.error_a <= r.error_estimate
            s = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, tol=r.tol)
            assert r.error_a == pytest.approx(abs(s.a - ref.a), abs=1e-15)
            assert r.error_p0 == pytest.approx(abs(s.p0 - ref.p0), abs=1e-13)
        text = screen.query_one(AccuracyView).render()
        plain = str(text)
        for tol in LADDER:
            assert f"\n{tol:.0e} " in plain
        assert "every estimate bounds its actual error" in plain
        assert "log-log" in plain  # room for the plot at 120x40
        # Only tol changes: the ladder (which runs every tol) is reused.
        await type_into(pilot, "tol", "1e-6")
        assert screen.params.tol == 1e-6
        assert accuracy_builds(screen) == 1
        # A physical parameter changes: the ladder is computed for it.
        await type_into(pilot, "kw", "10")
        assert accuracy_builds(screen) == 2
        assert shown(app).report.scene.params["kw"] == 10.0


def shown_or_none(app: MovingPunchApp) -> AccuracyTable | None:
    return screen_of(app).query_one(AccuracyView).table


@sync
async def test_accuracy_tab_fits_80x24() -> None:
    app = create_app(show_timing=False, tab="accuracy")
    async with app.run_test(size=(80, 24)) as pilot:
        await settle(pilot)
        view = screen_of(app).query_one(AccuracyView)
        lines = str(view.render()).splitlines()
        width = view.size.width
        assert all(len(line) <= width for line in lines)
        # The header follows the title (wrapped at spaces, never cut).
        at = [i for i, line in enumerate(lines) if line.split()[:2] == ["tol", "N"]]
        assert len(at) == 1
        header = lines[at[0]].split()
        assert "reference fixed N = 64" in " ".join(lines[: at[0]])
        assert {"est", "err", "cold"} <= set(header)


@sync
async def test_tol_input_takes_a_preset_name() -> None:
    app = create_app(show_timing=False)
    async with app.run_test(size=(100, 32)) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        before = screen.result
        assert before is not None
        await type_into(pilot, "tol", "precise")
        assert screen.params == Params(tol=1e-12)
        after = screen.result
        assert after is not None
        assert after.summary.params.tol == 1e-12
        assert after.summary.error_estimate < before.summary.error_estimate
        await type_into(pilot, "tol", "fast")
        message = screen.query_one(ParamsPanel).message("tol")
        for word in ("tol", "draft", "default", "precise", "1e-14 <= tol <= 1e-2"):
            assert word in message
        assert screen.params.tol == 1e-12  # the last valid value stays


@sync
async def test_export_of_the_accuracy_tab(tmp_path: Path) -> None:
    app = create_app(show_timing=False, tab="accuracy", root=tmp_path)
    async with app.run_test(size=(100, 32)) as pilot:
        await settle(pilot)
        target = tmp_path / "accuracy.csv"
        await pilot.press("e")
        await pilot.pause()
        assert isinstance(app.screen, PathPrompt)
        app.screen.query_one("#path", Input).value = str(target)
        await pilot.press("enter")
        await pilot.pause()
        table = np.loadtxt(target, delimiter=",")
        report = shown(app).report
        assert table.shape[0] == len(LADDER)
        np.testing.assert_array_equal(table[:, 0], LADDER)
        np.testing.assert_array_equal(table[:, 4], [r.error_a for r in report.rungs])
