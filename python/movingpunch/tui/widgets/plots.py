"""The plots: curves on a shared grid (plotext) and the coloured stress map.

Both keep their data in a reactive and draw it in ``render()`` at the size
the widget has, so they follow the terminal from 80x24 up.
"""

from __future__ import annotations

import math

import numpy as np
from rich.console import RenderableType
from rich.style import Style
from rich.text import Text
from textual.reactive import reactive
from textual.widget import Widget
from textual_plotext import PlotextPlot

from movingpunch.tui.model import Curves, FieldMap, fmt

# Distinct colours for the current curve, the overlay and the pins.
PALETTE: tuple[tuple[int, int, int], ...] = (
    (255, 200, 60),
    (90, 170, 255),
    (120, 220, 120),
    (255, 110, 110),
    (200, 140, 255),
    (90, 220, 220),
    (255, 150, 220),
    (200, 200, 200),
)


class CurvePlot(PlotextPlot):
    """Curves of one tab; ``curves`` is None until the first result."""

    curves: reactive[Curves | None] = reactive(None)
    placeholder: reactive[str] = reactive("computing...")

    def render(self) -> RenderableType:
        plt = self.plt
        plt.clear_figure()
        data = self.curves
        if data is None:
            return Text(self.placeholder, style="dim")
        plt.title(data.title)
        for i, series in enumerate(data.series):
            finite = np.isfinite(series.values) & np.isfinite(data.grid)
            if not finite.any():
                continue
            grid = data.grid[finite].tolist()
            values = series.values[finite].tolist()
            x, y = (values, grid) if data.vertical_grid else (grid, values)
            plt.plot(
                x,
                y,
                marker="braille",
                color=PALETTE[i % len(PALETTE)],
                label=series.label if len(data.series) > 1 else None,
            )
        # The zone ends (several zones): thin vertical lines, one colour.
        for x in data.markers:
            if math.isfinite(x):
                plt.vline(x, color=(150, 150, 150))
        if data.vertical_grid:
            plt.xlabel(data.value_label)
            plt.ylabel(data.grid_label)
        else:
            plt.xlabel(data.grid_label)
            plt.ylabel(data.value_label)
        if data.log_grid:
            plt.xscale("log")
        drawn = super().render()
        assert isinstance(drawn, Text)
        return drawn


def _lerp(
    c0: tuple[int, int, int], c1: tuple[int, int, int], t: float
) -> tuple[int, int, int]:
    r, g, b = (round(u + (v - u) * t) for u, v in zip(c0, c1, strict=True))
    return (r, g, b)


def colour(value: float, lo: float, hi: float, diverging: bool) -> str:
    """An RGB colour for ``value``: blue-white-red around 0 for a signed
    stress (compression blue, tension red), dark-to-yellow otherwise."""
    if not math.isfinite(value):
        return "rgb(0,0,0)"
    if diverging:
        span = max(abs(lo), abs(hi), 1e-300)
        t = max(-1.0, min(1.0, value / span))
        if t < 0:
            r, g, b = _lerp((235, 235, 235), (30, 60, 200), -t)
        else:
            r, g, b = _lerp((235, 235, 235), (200, 30, 30), t)
    else:
        t = 0.0 if hi <= lo else max(0.0, min(1.0, (value - lo) / (hi - lo)))
        stops = ((40, 20, 80), (30, 120, 140), (90, 190, 90), (250, 230, 50))
        k = min(int(t * 3), 2)
        r, g, b = _lerp(stops[k], stops[k + 1], t * 3 - k)
    return f"rgb({r},{g},{b})"


class StressMap(Widget):
    """The stress field under the punch as a coloured map (two pixels per
    cell with half blocks), with the y/h and x/h axes and a colour bar."""

    DEFAULT_CSS = """
    StressMap { width: 1fr; height: 1fr; }
    """

    field: reactive[FieldMap | None] = reactive(None)
    placeholder: reactive[str] = reactive("computing...")
    """Shown while ``field`` is None (a notice if the map is unavailable)."""

    def render(self) -> RenderableType:
        data = self.field
        if data is None:
            return Text(self.placeholder, style="dim")
        width, height = self.size.width, self.size.height
        margin = 6  # y labels
        cols = max(width - margin, 4)
        rows = max(height - 3, 2)  # title, x axis, colour bar
        lo, hi = float(np.nanmin(data.values)), float(np.nanmax(data.values))
        diverging = data.quantity == "sigma_x"
        nx, ny = len(data.x), len(data.y)
        # data.y runs from -1 up to 0; the screen runs from y = 0 down.
        xi = np.minimum((np.arange(cols) + 0.5) * nx / cols, nx - 1).astype(int)
        yi = np.minimum((np.arange(2 * rows) + 0.5) * ny / (2 * rows), ny - 1)
        yi = (ny - 1 - yi.astype(int)).astype(int)
        out = Text(no_wrap=True, overflow="crop")
        if data.zones:
            ends = " ".join(f"[{fmt(lo, 3)},{fmt(hi, 3)}]" for lo, hi in data.zones)
            note = f"{len(data.zones)} zones {ends}"
        else:
            note = f"a/h = {fmt(data.a, 5)}"
        out.append(f"{data.title}  ({note})"[:width] + "\n")
        for r in range(rows):
            if r == 0:
                label = "0"
            elif r == rows - 1:
                label = "-1"
            elif r == rows // 2:
                label = "-0.5"
            else:
                label = ""
            if r == rows // 2 - 1:
                label = "y/h"
            out.append(f"{label:>{margin - 1}} ")
            top, bottom = yi[2 * r], yi[2 * r + 1]
            for c in range(cols):
                up = colour(float(data.values[top, xi[c]]), lo, hi, diverging)
                down = colour(float(data.values[bottom, xi[c]]), lo, hi, diverging)
                out.append("▀", Style.parse(f"{up} on {down}"))
            out.append("\n")
        left, right = fmt(float(data.x[0]), 3), fmt(float(data.x[-1]), 3)
        mid = f"{fmt(data.centre, 3)} x/h"
        axis = [" "] * cols
        for pos, text in ((0, left), (cols // 2, mid), (cols - len(right), right)):
            for k, ch in enumerate(text):
                if 0 <= pos + k < cols:
                    axis[pos + k] = ch
        out.append(" " * margin + "".join(axis) + "\n")
        bar = max(cols - 30, 8)
        out.append(" " * margin + f"{fmt(lo, 3):>9} ")
        for k in range(bar):
            v = lo + (hi - lo) * (k + 0.5) / bar
            out.append(" ", Style.parse(f"on {colour(v, lo, hi, diverging)}"))
        out.append(f" {fmt(hi, 3)}")
        return out
