"""Curves in a text plot where no curve hides another (the CLI's ASCII plots
and the terminal UI's curve tabs).

A text canvas has one character per cell: where two curves pass through the
same cell, the one drawn last would cover the other, and a curve lying on
another (kw = 10 under kw = inf at the width of a terminal) or crossing it
would vanish or break. Here each series has its own marker (``MARKERS``;
the legend names them) and the canvas is composed cell by cell:

1. the frame is drawn once with every series in blank markers (so the axes
   and their ranges are those of all the data), then once per series with
   that series alone in its marker: the cells where it differs from the
   frame are the series' cells;
2. a cell of one series shows its marker; a cell several series share shows
   the marker of the one that has the fewest cells shown so far (ties: the
   first series). Two curves lying on each other therefore alternate their
   markers (``xoxo``), a curve crossing another keeps its cells on both
   sides, and every series that has a cell at all shows at least one.

Pure text: ``compose`` takes a function that draws the figure (plotext, any
theme) with some series in their markers and returns what was built.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence

__all__ = ["BLANK", "MARKERS", "Cell", "compose", "plain"]

MARKERS: tuple[str, ...] = ("•", "+", "x", "o", "*", "#", "%", "@", "=", "~")
"""The marker of each series, in order (repeating past ten)."""

BLANK = " "
"""The marker of a series that is drawn for the ranges only."""

Cell = tuple[int, int]
"""(line, column) of a character of the built plot."""

_ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")


def plain(text: str) -> str:
    """``text`` without its ANSI colour codes."""
    return _ANSI.sub("", text)


def _cells(frame: list[str], drawn: list[str]) -> set[Cell]:
    """The cells where ``drawn`` differs from ``frame`` (same layout)."""
    out: set[Cell] = set()
    for i, (a, b) in enumerate(zip(frame, drawn, strict=False)):
        for j in range(min(len(a), len(b))):
            if a[j] != b[j]:
                out.add((i, j))
    return out


def allocate(cells: Sequence[set[Cell]]) -> dict[Cell, int]:
    """Which series each cell shows: its own series where it has one; where
    several share it, the one with the fewest cells shown so far (ties: the
    lowest index), the shared cells taken column by column."""
    owners: dict[Cell, list[int]] = {}
    for k, mine in enumerate(cells):
        for cell in mine:
            owners.setdefault(cell, []).append(k)
    shown: dict[Cell, int] = {}
    counts = [0] * len(cells)
    for cell, ks in owners.items():
        if len(ks) == 1:
            shown[cell] = ks[0]
            counts[ks[0]] += 1
    for cell in sorted((c for c, ks in owners.items() if len(ks) > 1), key=_by_column):
        k = min(owners[cell], key=lambda k: (counts[k], k))
        shown[cell] = k
        counts[k] += 1
    return shown


def _by_column(cell: Cell) -> tuple[int, int]:
    return (cell[1], cell[0])


def compose(
    draw: Callable[[int | None], str], count: int
) -> tuple[str, dict[Cell, int]]:
    """(frame, shown): ``draw(None)`` builds the figure with every series
    blank, ``draw(k)`` with series ``k`` alone in its marker (the others
    blank, drawn first); ``shown`` maps each cell of the frame's text (lines
    of ``plain(frame)``) to the series whose marker it shows."""
    frame = draw(None)
    base = plain(frame).splitlines()
    cells = [_cells(base, plain(draw(k)).splitlines()) for k in range(count)]
    return frame, allocate(cells)
