"""Helpers shared by the terminal UI's pilot tests (test_tui*.py): run an
async test, wait for the workers, read the screen, type into an input."""

from __future__ import annotations

import asyncio
import functools
from collections.abc import Callable, Coroutine
from typing import Any, ParamSpec

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


def status_text(app: MovingPunchApp) -> str:
    return str(screen_of(app).query_one("#status", Static).render())


def status_ok(app: MovingPunchApp) -> bool:
    """The message area shows no error, warning or unfinished input (it may
    show plausibility hints, an overlay or pins, or "ready")."""
    text = status_text(app)
    bad = ("showing the last result", "warning", "typing", "invalid")
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
