"""Small modal prompts: a file path (open, save, export) and an overlay."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import ClassVar

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Input, Label, Select, Static

from movingpunch.errors import MovingPunchError
from movingpunch.tui.model import SCENE_PARAMS, Overlay, parse_values
from movingpunch.tui.paths import OverwriteNeeded
from movingpunch.tui.widgets.params import LABELS

Attempt = Callable[[str, bool], str | None]
"""Tries a path (with ``True`` once the user confirmed overwriting it);
returns an error message (the prompt stays open) or None. It may raise
OverwriteNeeded: the prompt shows the message and a second enter on the same
path tries again with ``True``."""


class PathPrompt(ModalScreen[str | None]):
    """Asks for a path and runs ``attempt`` on it; errors appear inline.

    Replacing an existing file takes a second enter on the same path, at
    least ``CONFIRM_AFTER`` seconds after the question appeared (so a
    double-tapped or auto-repeated enter never confirms it); editing the
    path drops the question (the new path is asked about on its own).
    """

    BINDINGS: ClassVar[list[BindingType]] = [Binding("escape", "cancel", "Cancel")]

    CONFIRM_AFTER: ClassVar[float] = 0.3
    """Seconds after the overwrite question before an enter confirms it."""

    HINT = "enter: ok   escape: cancel"

    def __init__(self, title: str, default: str, attempt: Attempt) -> None:
        super().__init__()
        self._title = title
        self._default = default
        self._attempt = attempt
        self._confirm: str | None = None
        """The path whose overwriting the next enter confirms."""
        self._asked_at = 0.0
        """When the overwrite question appeared (time.monotonic())."""

    def compose(self) -> ComposeResult:
        with Vertical(classes="prompt-box"):
            yield Label(self._title, classes="panel-title", id="prompt-title")
            yield Input(self._default, id="path")
            yield Static(self.HINT, id="prompt-msg")

    @property
    def asking(self) -> str | None:
        """The path the overwrite question is about (None: no question)."""
        return self._confirm

    def on_input_changed(self, event: Input.Changed) -> None:
        event.stop()
        if self._confirm is not None and event.value.strip() != self._confirm:
            self._drop_question()  # an edited path must be confirmed anew
            msg = self.query_one("#prompt-msg", Static)
            msg.update(self.HINT)
            msg.remove_class("-error")

    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        path = event.value.strip()
        if not path:
            self._show("give a file name or a path inside the working folder")
            return
        confirmed = self._confirm == path
        if confirmed and time.monotonic() - self._asked_at < self.CONFIRM_AFTER:
            return  # the same keypress repeated: the question stays
        self._drop_question()
        try:
            error = self._attempt(path, confirmed)
        except OverwriteNeeded as ask:
            self._ask(path, str(ask))
            return
        except OSError as exc:  # its file name may be a temporary one: not shown
            error = f"{path}: {exc.strerror or type(exc).__name__}"
        except (MovingPunchError, ValueError) as exc:
            error = " ".join(str(exc).split()) or type(exc).__name__
        if error:
            self._show(error)
        else:
            self.dismiss(path)

    def _ask(self, path: str, question: str) -> None:
        """Shows the overwrite question about ``path``; the title says it."""
        self._confirm = path
        self._asked_at = time.monotonic()
        self.query_one("#prompt-title", Label).update(f"Overwrite {path}?")
        self._show(question)

    def _drop_question(self) -> None:
        if self._confirm is not None:
            self.query_one("#prompt-title", Label).update(self._title)
        self._confirm = None

    def _show(self, message: str) -> None:
        msg = self.query_one("#prompt-msg", Static)
        msg.update(message)
        msg.add_class("-error")

    def action_cancel(self) -> None:
        self.dismiss(None)


class OverlayPrompt(ModalScreen[Overlay | None]):
    """Pick a parameter and a list of values to draw over the current curves."""

    BINDINGS: ClassVar[list[BindingType]] = [Binding("escape", "cancel", "Cancel")]

    def __init__(self, param: str = "vstar", values: str = "0, 0.2, 0.4") -> None:
        super().__init__()
        self._param = param
        self._values = values

    def compose(self) -> ComposeResult:
        with Vertical(classes="prompt-box"):
            yield Label(
                "Overlay: one parameter at several values", classes="panel-title"
            )
            yield Select(
                [(f"{LABELS[n]} ({n})", n) for n in SCENE_PARAMS],
                value=self._param,
                allow_blank=False,
                id="overlay-param",
            )
            yield Input(self._values, id="overlay-values")
            yield Static("values separated by commas; enter: ok", id="prompt-msg")

    def on_mount(self) -> None:
        self.query_one("#overlay-values", Input).focus()

    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        param = str(self.query_one("#overlay-param", Select).value)
        try:
            values = parse_values(param, event.value)
        except MovingPunchError as exc:
            msg = self.query_one("#prompt-msg", Static)
            msg.update(" ".join(str(exc).split()))
            msg.add_class("-error")
            return
        self.dismiss(Overlay(param, values))

    def action_cancel(self) -> None:
        self.dismiss(None)
