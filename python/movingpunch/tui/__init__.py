"""The movingpunch terminal UI (Textual): ``movingpunch`` or
``movingpunch tui [SCENE|NAME]``; ``movingpunch serve`` in a browser.

Textual loads only when the app is asked for: ``movingpunch.tui.model``
(what the workers compute) imports without it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from movingpunch.tui.app import MovingPunchApp, create_app, main

__all__ = ["MovingPunchApp", "create_app", "main"]


def __getattr__(name: str) -> Any:
    if name in __all__:
        from movingpunch.tui import app

        return getattr(app, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
