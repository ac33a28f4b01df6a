"""Helpers shared by the terminal UI's pilot tests (test_tui*.py): run an
async test, wait for the workers, read the screen, type into an input,
deliver keys as a terminal does."""

from __future__ import annotations

import asyncio
import functools
import re
from collections.abc import Callable, Coroutine
from typing import Any, ParamSpec

from textual import events
from textual.message import Message
from textual.pilot import Pilot
from textual.widgets import Input, Static
from textual.worker import WorkerCancelled

import movingpunch as mp
from movingpunch.tui import MovingPunchApp
from movingpunch.tui.screens import MainScreen
from movingpunch.tui.screenshots import settled
from movingpunch.tui.widgets.fields import FieldsLine

P = ParamSpec("P")


def sync(test: Callable[P, Coroutine[Any, Any, None]]) -> Callable[P, None]:
    """Runs an async pilot test in its own event loop (no pytest plugin)."""

    @functools.wraps(test)
    def run(*args: P.args, **kwargs: P.kwargs) -> None:
        asyncio.run(test(*args, **kwargs))

    return run


async def settle(pilot: Pilot[None]) -> None:
    """Waits until no solve is pending or running and the screen is drawn
    (``screenshots.settled``: an error of a worker is shown inline, and the
    tests read it from the screen). A worker superseded by a newer request
    (cancelled: its result would be dropped) is waited past."""
    while True:
        try:
            await settled(pilot)
        except WorkerCancelled:
            await pilot.pause(0.01)
        else:
            return


def screen_of(app: MovingPunchApp) -> MainScreen:
    screen = app.screen
    assert isinstance(screen, MainScreen), screen
    return screen


def summary_text(app: MovingPunchApp) -> str:
    """The summary's fields as one line of plain text."""
    fields = screen_of(app).query_one("#summary", FieldsLine).fields
    return "  ".join(f.text() for f in fields)


def summary_fields(app: object) -> list[tuple[str, str]]:
    """The summary's fields as (label, value)."""
    assert isinstance(app, MovingPunchApp)
    fields = screen_of(app).query_one("#summary", FieldsLine).fields
    return [(f.label, f.value) for f in fields]


KEY_NAMES = {
    ".": "full_stop",
    "-": "minus",
    "+": "plus",
    "]": "right_square_bracket",
    "[": "left_square_bracket",
    " ": "space",
}
"""Textual's names of the keys of these characters."""


def deliver(app: object, key: str | Message) -> None:
    """Sends a key (a character or a name: ``backspace``, ``ctrl+shift+a``),
    a paste or another event as the terminal driver does: queued behind the
    keys sent before, not waited for (the pilot's ``press`` waits until the
    screen is idle after each key)."""
    assert isinstance(app, MovingPunchApp)
    driver = app._driver
    assert driver is not None
    if isinstance(key, str):
        event: Message = events.Key(
            KEY_NAMES.get(key, key), key if len(key) == 1 else None
        )
    else:
        event = key
    event.set_sender(app)
    driver.send_message(event)


def click_into(app: object, name: str) -> None:
    """Moves the focus to the input of ``name`` as a click does, queued
    behind the keys sent before (``deliver``)."""
    assert isinstance(app, MovingPunchApp)
    box = app.screen.query_one(f"#in-{name}", Input)
    deliver(app, events.Callback(callback=box.focus))


def status_text(app: MovingPunchApp) -> str:
    return str(screen_of(app).query_one("#status", Static).render())


def status_ok(app: MovingPunchApp) -> bool:
    """The message area shows no error, warning or unfinished input (it may
    show plausibility hints, an overlay or pins, or "ready")."""
    text = status_text(app)
    bad = ("showing the", "warning", "typing", "invalid", "solving")
    return not any(word in text for word in bad)


async def type_into(
    pilot: Pilot[None], name: str, text: str, *, paste: bool = False
) -> None:
    """Types ``text`` into the input of ``name`` as a user would, key by key
    (each prefix is checked and, if valid, solved), or pastes it at once."""
    box = pilot.app.screen.query_one(f"#in-{name}", Input)
    box.focus()
    box.clear()
    await pilot.pause()
    if paste:
        box.insert_text_at_cursor(text)
    elif text:
        await pilot.press(*text)
    await settle(pilot)


# -- the summary against the API ---------------------------------------------

_PEAKS: dict[int, tuple[mp.ContactSolution, float, float]] = {}


def peaks(solution: mp.ContactSolution) -> tuple[float, float]:
    """The API's σx peaks (top, bottom) of ``solution`` (computed once: the
    cache keeps the solution, so its id is never reused)."""
    key = id(solution)
    if key not in _PEAKS:
        p = solution.stress_peaks()
        _PEAKS[key] = (solution, p.top_tensile, p.bottom_tensile)
    return _PEAKS[key][1:]


NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?inf")


def half_digit(text: str) -> float:
    """Half a unit in the last place of a printed number (``0.330419``:
    5e-7; ``8e-15``: 5e-16; ``1.33``: 5e-3)."""
    mantissa, _, exponent = text.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 0.5 * 10.0 ** (int(exponent or 0) - decimals)


def expected(solution: mp.ContactSolution, label: str) -> list[float] | None:
    """The API's numbers a summary field of ``label`` prints (None: a field
    this test does not know)."""
    top, bottom = peaks(solution)
    back, front = solution.end_coefficients
    zones = [e for z in solution.contact_zones for e in z]
    table: dict[str, list[float]] = {
        "a/h": [solution.a],
        "(-b,a)/h": list(solution.contact_interval),
        "p0": [solution.p0],
        "δ/h": [solution.indentation],
        "σx⁺ top": [top],
        "bot": [bottom],
        "drag/P": [solution.drag],
        "K": [front],
        "K front": [front],
        "K back": [back],
        "friction/P": [solution.tangential_force],
        "err": [solution.error_estimate],
    }
    # "it" (the width iterations) is not compared: it counts the work of the
    # solve that printed it (its start and the kernel tables it found built),
    # not a property of the inputs (9 or 10 for Fig. 4 by the process's past).
    if re.fullmatch(r"\d+ zones", label):
        return zones
    return table.get(label)


def assert_summary_is(
    app: object, solution: mp.ContactSolution, what: str = ""
) -> None:
    """Every number of the summary is the API's to the printed digits."""
    fields = summary_fields(app)
    labels = [label for label, _ in fields]
    assert "p0" in labels, (what, fields)
    assert "δ/h" in labels, (what, fields)
    for label, value in fields:
        if label == "" and value == "INVALID":
            assert not solution.valid, (what, fields)
            continue
        want = expected(solution, label)
        if want is None:
            continue
        got = NUMBER.findall(value)
        assert len(got) == len(want), (what, label, value, want)
        for text, number in zip(got, want, strict=True):
            printed = float(text)
            if label == "err" and max(abs(printed), abs(number)) < 1e-12:
                continue  # round-off (its digits vary between runs)
            # Half a unit in the last printed place (a rounding), plus
            # the run-to-run round-off of a damped solve (1e-12).
            slack = half_digit(text) * (1 + 1e-9) + 1e-12 * max(1.0, abs(number))
            assert abs(printed - number) <= slack, (what, label, value, number)
    if solution.valid:
        assert "INVALID" not in [v for _, v in fields], (what, fields)
