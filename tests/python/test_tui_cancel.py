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

import asyncio
import contextlib
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
from tui_pilot import (
    assert_summary_is,
    deliver,
    screen_of,
    settle,
    status_text,
    sync,
)

SIZE = (80, 24)
SLOW_VSTAR = 0.31
"""The V* the app solves slowly in these tests."""
STOP_BOUND = 10.0
"""Seconds for a cancelled computation's thread to end (a hang guard)."""
START_BOUND = 60.0


LONG_SECONDS = 120.0
"""How long the stand-in computes unless cancelled."""


class SlowSolve:
    """Stands in for ``model._solve``: V* = SLOW_VSTAR computes for
    ``LONG_SECONDS`` unless cancelled (near-critical solves of a stiff
    Pasternak foundation, each from an empty kernel cache: 5-20 s of
    kernel quadrature each, which the core polls), recording how it ended."""

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
        end = time.monotonic() + LONG_SECONDS
        try:
            while time.monotonic() < end:
                mp.clear_kernel_cache()
                # The worker's token is bound to this thread: no cancel= here.
                with contextlib.suppress(mp.MovingPunchError):
                    mp.solve(
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
        self.outcomes.append("finished")
        return self.real(params)


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
    """Types ``text`` over the input ``name`` and presses enter, keys sent
    as a terminal sends them (``deliver``: the pilot's ``press`` waits for
    the process to idle, up to a second a key while a solve runs); returns
    once enter has left the input (no wait for the solve)."""
    app = pilot.app
    box = app.screen.query_one(f"#in-{name}", Input)
    box.focus()
    box.clear()
    await pilot.pause(0.05)
    for key in text:
        deliver(app, key)
    deliver(app, "enter")
    await wait_until(
        pilot,
        lambda: box.value == text and app.screen.focused is not box,
        START_BOUND,
        f"{text!r} entered into {name}",
    )


async def start_slow(pilot: Pilot[None], slow: SlowSolve) -> None:
    """Enters V* = SLOW_VSTAR and waits until its solve is at work (the
    values typed on the way, 0, 0.3, are not solved: a long debounce)."""
    screen_of(pilot.app).debounce = 60.0
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
        edited = time.monotonic()
        await enter_value(pilot, "vstar", value)
        await wait_until(
            pilot,
            lambda: screen.computations_running == 0,
            STOP_BOUND,
            "the abandoned solve's thread still computing",
        )
        took = time.monotonic() - edited
        await settle(pilot)
        assert slow.outcomes == ["cancelled"], slow.outcomes
        assert screen.computations_running == 0
        expected = mp.solve(vstar=float(value), kw=1.0, radius=100.0, load=0.002)
        assert_summary_is(app, expected, f"V* {value} after the long solve")
        status = status_text(app)
        # A superseded computation vanishes silently.
        assert "cancelled" not in status, status
        assert "showing the" not in status, status
        print(f"the abandoned solve ended {took:.3f} s after the edit began")


async def cancelled_by_escape(pilot: Pilot[None], slow: SlowSolve) -> None:
    """Sends escape and waits until the computation's thread has ended."""
    screen = screen_of(pilot.app)
    count = len(slow.outcomes)
    deliver(pilot.app, "escape")
    await wait_until(
        pilot,
        lambda: screen.computations_running == 0 and len(slow.outcomes) > count,
        STOP_BOUND,
        "the cancelled solve's thread still computing",
    )


@sync
async def test_escape_cancels_and_says_so_until_r(slow: SlowSolve) -> None:
    app = create_app(SceneState(Params()), show_timing=False, cursor_blink=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        before = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
        await start_slow(pilot, slow)
        assert not isinstance(screen.focused, Input)  # enter left the input
        await cancelled_by_escape(pilot, slow)
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
        assert status_text(app) == status
        # ... until r: it runs again (and escape stops it again).
        slow.started.clear()
        deliver(app, "r")
        await wait_until(pilot, slow.started.is_set, START_BOUND, "r")
        await pilot.pause(0.3)
        assert "solving" in status_text(app)
        await cancelled_by_escape(pilot, slow)
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
        await pilot.pause(0.05)
        deliver(app, "escape")  # leaves the input
        await wait_until(
            pilot,
            lambda: not isinstance(screen.focused, Input),
            START_BOUND,
            "escape leaves the input",
        )
        await pilot.pause(0.3)
        assert screen.computations_running == 1
        assert slow.outcomes == []
        await cancelled_by_escape(pilot, slow)  # now outside: cancels
        assert slow.outcomes == ["cancelled"]


@sync
async def test_typing_during_a_long_solve_stays_responsive(slow: SlowSolve) -> None:
    # Keys sent as a terminal sends them, 0.1 s apart: each shows in the
    # input at once although a solve runs (the core releases the GIL and its
    # token is polled without it). The bound is a hang guard. No prefix of
    # 0.35 is the set on screen (V* 0.2: typing it would make the long
    # solve moot, and cancel it).
    app = create_app(SceneState(Params()), show_timing=False, cursor_blink=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        await start_slow(pilot, slow)  # (typed values wait for enter)
        box = screen.query_one("#in-vstar", Input)
        box.focus()
        box.clear()
        await pilot.pause(0.05)
        slowest = 0.0
        for i, key in enumerate("0.35"):
            deliver(app, key)
            slowest = max(
                slowest,
                await wait_until(
                    pilot, lambda i=i: len(box.value) == i + 1, 2.0, f"key {key!r}"
                ),
            )
            await pilot.pause(0.1)
        assert box.value == "0.35"
        assert screen.computations_running == 1  # the long solve still runs
        assert slow.outcomes == []
        deliver(app, "enter")  # V* 0.35 supersedes it
        await wait_until(
            pilot,
            lambda: slow.outcomes == ["cancelled"],
            STOP_BOUND,
            "the superseded solve",
        )
        await settle(pilot)
        expected = mp.solve(vstar=0.35, kw=1.0, radius=100.0, load=0.002)
        assert_summary_is(app, expected, "V* 0.35 typed during the long solve")
        print(f"slowest key during the solve: {slowest:.3f} s")


def test_quitting_during_a_long_solve_stops_it(slow: SlowSolve) -> None:
    async def main() -> float:
        app = create_app(SceneState(Params()), show_timing=False, cursor_blink=False)
        async with app.run_test(size=SIZE) as pilot:
            await settle(pilot)
            await start_slow(pilot, slow)
            quit_at = time.monotonic()
            deliver(app, "q")
            await wait_until(pilot, lambda: not app.is_running, STOP_BOUND, "q")
        return quit_at

    quit_at = asyncio.run(main())
    deadline = quit_at + STOP_BOUND
    while not slow.outcomes and time.monotonic() < deadline:
        time.sleep(0.02)
    assert slow.outcomes == ["cancelled"]
