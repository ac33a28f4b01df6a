"""Messages the compute worker posts to the main screen (thread-safe)."""

from __future__ import annotations

from dataclasses import dataclass

from textual.message import Message

from movingpunch.tui.model import Result


@dataclass
class Computed(Message):
    """A worker finished ``result.request``."""

    result: Result


@dataclass
class Progressed(Message):
    """``done`` of ``total`` pieces of request ``generation`` are computed."""

    generation: int
    done: int
    total: int
