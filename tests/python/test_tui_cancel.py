"""The terminal UI cancels an abandoned computation (its worker's token,
``movingpunch.Cancel``): an edit that supersedes a long solve stops it, and
the screen shows the new result; escape outside the inputs cancels on the
user's request and says so; quitting stops it; typing stays responsive.

A solve is made long by standing in for the app's solve of one marked
parameter set (V* = ``SLOW_VSTAR``) with a near-critical solve the core
polls (seconds of kernel quadrature); every other set is solved as the app
solves it. The time bounds are hang guards, not performance assertions.
"""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest
from textual.pilot import Pilot
from textual.widgets import Input

import movingpunch as mp
from movingpunch.errors import Cancelled
from movingpunch.tui import create_app, model
from movingpunch.tui.model import Params
from movingpunch.tui.scene_files import SceneState
from tui_pilot import assert_summary_is, screen_of, settle, status_text, sync

SIZE = (80, 24)
SLOW_VSTAR = 0.31
"""The V* the app solves slowly in these tests."""
STOP_BOUND = 10.0
"""Seconds for a cancelled computation's thread to end (a hang guard)."""
START_BOUND = 60.0


class SlowSolve:
    """Stands in for ``model._solve``: V* = SLOW_VSTAR runs a long
    near-critical solve (seconds), recording how it ended."""

    def __init__(self) -> None:
        self.real = model._solve
        self.started = threading.Event()
        self.outcomes: list[str] = []

    def __call__(self, params: Params) -> mp.ContactSolution:
        if params.vstar != SLOW_VSTAR:
            return self.real(params)
        self.started.set()
        kw, nu, kp = 1e4, 0.4048225797622928, 3.0
        v = 0.9999999 * mp.critical_vstar(kw, nu, kp)
        try:
            # The worker's token is bound to this thread: no cancel= here.
            s = mp.solve(
                vstar=v,
                kw=kw,
                nu=nu,
                kp=kp,
                radius=0.004383187612912297,
                load=319.749150627029,
            )
        except Cancelled:
            self.outcomes.append("cancelled")
            raise
        except mp.MovingPunchError:
            self.outcomes.append("finished")
            raise
        self.outcomes.append("finished")
        return s


@pytest.fixture
def slow(monkeypatch: pytest.MonkeyPatch) -> SlowSolve:
    stand_in = SlowSolve()
    monkeypatch.setattr(model, "_solve", stand_in)
    return stand_in


async def wait_until(pilot: Pilot[None], ok: Any, bound: float, what: str) -> float:
    """Pauses the pilot until ``ok()``; the seconds it took (fails after
    ``bound``)."""
    start = time.monotonic()
    while not ok():
        if time.monotonic() - start > bound:
            raise AssertionError(f"{what}: not after {bound} s")
        await pilot.pause(0.02)
    return time.monotonic() - start


async def enter_value(pilot: Pilot[None], name: str, text: str) -> None:
    """Types ``text`` over the input ``name`` and presses enter (no wait
    for the solve)."""
    box = pilot.app.screen.query_one(f"#in-{name}", Input)
    box.focus()
    box.clear()
    await pilot.pause()
    await pilot.press(*text, "enter")


async def start_slow(pilot: Pilot[None], slow: SlowSolve) -> None:
    await enter_value(pilot, "vstar", str(SLOW_VSTAR))
    start = time.monotonic()
    while not slow.started.is_set():
        assert time.monotonic() - start < START_BOUND, "the slow solve never started"
        await pilot.pause(0.02)
    await pilot.pause(0.3)  # at work in the core
    assert screen_of(pilot.app).computations_running == 1
    assert "solving" in status_text(pilot.app)


@pytest.mark.parametrize("value", ["0.25", "0.2"])
@sync
async def test_an_edit_during_a_long_solve_cancels_it(
    value: str, slow: SlowSolve
) -> None:
    # 0.25: a new solve supersedes the long one; 0.2: the result on screen
    # before is the answer again (no solve), which makes the long one moot.
    app = create_app(SceneState(Params()), show_timing=False, cursor_blink=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        await start_slow(pilot, slow)
        await enter_value(pilot, "vstar", value)
        took = await wait_until(
            pilot,
            lambda: screen.computations_running == 0,
            STOP_BOUND,
            "the abandoned solve's thread still computing",
        )
        await settle(pilot)
        assert slow.outcomes == ["cancelled"], slow.outcomes
        assert screen.computations_running == 0
        expected = mp.solve(vstar=float(value), kw=1.0, radius=100.0, load=0.002)
        assert_summary_is(app, expected, f"V* {value} after the long solve")
        status = status_text(app)
        # A superseded computation vanishes silently.
        assert "cancelled" not in status, status
        assert "showing the" not in status, status
        print(f"the abandoned solve ended {took:.3f} s after the edit")


@sync
async def test_escape_cancels_and_says_so_until_r(slow: SlowSolve) -> None:
    app = create_app(SceneState(Params()), show_timing=False, cursor_blink=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        before = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
        await start_slow(pilot, slow)
        assert not isinstance(screen.focused, Input)  # enter left the input
        await pilot.press("escape")
        await wait_until(
            pilot,
            lambda: screen.computations_running == 0,
            STOP_BOUND,
            "the cancelled solve's thread still computing",
        )
        await settle(pilot)
        assert slow.outcomes == ["cancelled"]
        status = status_text(app)
        assert status.startswith("cancelled"), status
        # The screen says plainly it shows another set's result, and it does.
        assert "showing the result for V* 0.2" in status, status
        assert_summary_is(app, before, "after escape")
        # Not solved again by itself (the rule of the screen) ...
        await pilot.pause(0.5)
        assert screen.computations_running == 0
        assert slow.outcomes == ["cancelled"]
        # ... until r: it runs again (and escape stops it again).
        await pilot.press("r")
        await wait_until(
            pilot, lambda: screen.computations_running == 1, START_BOUND, "r"
        )
        await pilot.pause(0.3)
        await pilot.press("escape")
        await wait_until(
            pilot, lambda: screen.computations_running == 0, STOP_BOUND, "escape"
        )
        await settle(pilot)
        assert slow.outcomes == ["cancelled", "cancelled"]
        assert status_text(app).startswith("cancelled")


@sync
async def test_escape_in_an_input_leaves_it_and_does_not_cancel(
    slow: SlowSolve,
) -> None:
    app = create_app(SceneState(Params()), show_timing=False, cursor_blink=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        await start_slow(pilot, slow)
        screen.query_one("#in-kw", Input).focus()
        await pilot.pause()
        await pilot.press("escape")  # leaves the input
        await pilot.pause(0.3)
        assert not isinstance(screen.focused, Input)
        assert screen.computations_running == 1
        assert slow.outcomes == []
        await pilot.press("escape")  # now outside: cancels
        await wait_until(
            pilot, lambda: screen.computations_running == 0, STOP_BOUND, "escape"
        )
        assert slow.outcomes == ["cancelled"]


@sync
async def test_typing_during_a_long_solve_stays_responsive(slow: SlowSolve) -> None:
    app = create_app(SceneState(Params()), show_timing=False, cursor_blink=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        screen.debounce = 5.0  # the typed value is not solved while typing
        await start_slow(pilot, slow)
        box = screen.query_one("#in-kw", Input)
        box.focus()
        box.clear()
        await pilot.pause()
        slowest = 0.0
        for i, key in enumerate("12.5"):
            await pilot.press(key)
            slowest = max(
                slowest,
                await wait_until(
                    pilot, lambda i=i: len(box.value) == i + 1, 2.0, f"key {key!r}"
                ),
            )
        assert box.value == "12.5"
        assert screen.computations_running == 1  # the long solve still runs
        await pilot.press("enter")  # kw 12.5 at V* 0.31 supersedes it
        await wait_until(
            pilot,
            lambda: slow.outcomes == ["cancelled"],
            STOP_BOUND,
            "the superseded solve",
        )
        print(f"slowest key during the solve: {slowest:.3f} s")


def test_quitting_during_a_long_solve_stops_it(slow: SlowSolve) -> None:
    import asyncio

    async def main() -> float:
        app = create_app(SceneState(Params()), show_timing=False, cursor_blink=False)
        async with app.run_test(size=SIZE) as pilot:
            await settle(pilot)
            await start_slow(pilot, slow)
            quit_at = time.monotonic()
            await pilot.press("q")
        return quit_at

    quit_at = asyncio.run(main())
    deadline = quit_at + STOP_BOUND
    while not slow.outcomes and time.monotonic() < deadline:
        time.sleep(0.02)
    assert slow.outcomes == ["cancelled"]
