"""Helpers shared by the terminal UI's pilot tests (test_tui*.py): run an
async test, wait for the workers, read the screen, type into an input,
deliver keys as a terminal does."""

from __future__ import annotations

import asyncio
import functools
from collections.abc import Callable, Coroutine
from typing import Any, ParamSpec

from textual import events
from textual.message import Message
from textual.pilot import Pilot
from textual.widgets import Input, Static

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
    tests read it from the screen)."""
    await settled(pilot)


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
