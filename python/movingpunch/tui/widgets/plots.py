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
from movingpunch.tui.widgets.fields import Field, packed_text

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


ZONE_END_COLOUR = (150, 150, 150)
AXIS_COLOUR = (255, 120, 200)


class CurvePlot(PlotextPlot):
    """Curves of one tab; ``curves`` is None until the first result.

    The axes say their units (x/h, y/h, a stress over P/h) and the legend
    sits below the plot, outside the data area: each curve's colour and
    label, the zone ends and a train's punch axes (``legend``)."""

    curves: reactive[Curves | None] = reactive(None)
    placeholder: reactive[str] = reactive("computing...")

    def render(self) -> RenderableType:
        plt = self.plt
        plt.clear_figure()
        data = self.curves
        if data is None:
            return Text(self.placeholder, style="dim")
        width, height = self.size.width, self.size.height
        entries = legend(data)
        key = packed_text(entries, width) if entries else None
        rows = len(key.plain.splitlines()) if key is not None else 0
        plt.title(data.title)
        for i, series in enumerate(data.series):
            finite = np.isfinite(series.values) & np.isfinite(data.grid)
            if not finite.any():
                continue
            grid = data.grid[finite].tolist()
            values = series.values[finite].tolist()
            x, y = (values, grid) if data.vertical_grid else (grid, values)
            plt.plot(x, y, marker="braille", color=PALETTE[i % len(PALETTE)])
        # The zone ends (several zones) and the punch axes (a train).
        for x in data.markers:
            if math.isfinite(x):
                plt.vline(x, color=ZONE_END_COLOUR)
        for x in data.axes:
            if math.isfinite(x):
                plt.vline(x, color=AXIS_COLOUR)
        if data.vertical_grid:
            plt.xlabel(data.value_label)
            plt.ylabel(data.grid_label)
        else:
            plt.xlabel(data.grid_label)
            plt.ylabel(data.value_label)
        if data.log_grid:
            plt.xscale("log")
        plot_height = max(height - rows, 6)
        plt.plotsize(width, plot_height)
        plt._set_size(width, plot_height)
        plt.theme(self._get_plotext_theme_name(self.app.theme))
        drawn = Text.from_ansi(plt.build().rstrip("\n"))
        if key is not None:
            drawn.append("\n")
            drawn.append_text(key)
        return drawn


def legend(data: Curves) -> list[Field]:
    """The legend below a plot: a coloured mark and the label of each curve
    (when there are several), then the zone ends and the punch axes."""
    out: list[Field] = []
    if len(data.series) > 1:
        for i, series in enumerate(data.series):
            r, g, b = PALETTE[i % len(PALETTE)]
            out.append(Field("━━", series.label, "", f"rgb({r},{g},{b})"))
    if data.markers:
        r, g, b = ZONE_END_COLOUR
        out.append(Field("│", "zone ends", "", f"rgb({r},{g},{b})"))
    if data.axes:
        r, g, b = AXIS_COLOUR
        at = " ".join(fmt(x, 3) for x in data.axes)
        out.append(Field("│", f"punch axes x/h {at}", "", f"rgb({r},{g},{b})"))
    return out


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
        unit = "σx/(P/h)" if diverging else "σVM/(P/h)"
        if margin + 10 + bar + len(f" {fmt(hi, 3)}") + len(unit) + 2 <= width:
            out.append(f"  {unit}", "dim")
        return out
