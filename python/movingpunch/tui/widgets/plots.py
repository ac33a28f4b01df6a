"""The plots: curves on a shared grid (plotext) and the coloured stress map.

Both keep their data in a reactive and draw it in ``render()`` at the size
the widget has, so they follow the terminal from 80x24 up.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
import numpy.typing as npt
from rich.console import RenderableType
from rich.style import Style
from rich.text import Text
from textual.reactive import reactive
from textual.widget import Widget
from textual_plotext import PlotextPlot

from movingpunch._display import singular_note
from movingpunch._textplot import BLANK, MARKERS, Cell, compose
from movingpunch.tui.model import Curves, FieldMap, FloatArray, fmt
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
INTERFACE_COLOUR = (120, 200, 255)


class CurvePlot(PlotextPlot):
    """Curves of one tab; ``curves`` is None until the first result.

    The axes say their units (x/h, y/h, a stress over P/h) and the legend
    sits below the plot, outside the data area: each curve's marker, colour
    and label, the zone ends and a train's punch axes (``legend``).

    One curve is drawn in braille dots; several each in their own marker
    (``MARKERS``) and colour, composed so that none hides another
    (``movingpunch._textplot``): where curves share a cell the marker of the
    one least shown so far is drawn, so curves lying on each other alternate
    their markers and a crossing keeps every curve on both sides."""

    curves: reactive[Curves | None] = reactive(None)
    placeholder: reactive[str] = reactive("computing...")
    _drawn: tuple[Curves, tuple[int, int, str], Text] | None = None
    """The last plot drawn: its curves, (width, height, theme) and text:
    composing several curves builds the plot once per curve."""

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
        plot_height = max(height - rows, 6)
        drawn_series = []
        for i, series in enumerate(data.series):
            finite = np.isfinite(series.values) & np.isfinite(data.grid)
            if finite.any():
                drawn_series.append((i, data.grid[finite], series.values[finite]))
        several = len(data.series) > 1

        def draw(only: int | None) -> str:
            """The plot with series ``only`` in its marker, the others blank
            (drawn first); every series in its marker for ``only`` = -1."""
            plt.clear_figure()
            plt.title(data.title)
            order = [d for d in drawn_series if d[0] != only]
            order += [d for d in drawn_series if d[0] == only]
            for i, grid, values in order:
                xs, ys = (values, grid) if data.vertical_grid else (grid, values)
                marker = BLANK
                if only == -1 or i == only:
                    marker = MARKERS[i % len(MARKERS)] if several else "braille"
                plt.plot(
                    xs.tolist(),
                    ys.tolist(),
                    marker=marker,
                    color=PALETTE[i % len(PALETTE)],
                )
            # The zone ends (several zones) and the punch axes (a train).
            for x in data.markers:
                if math.isfinite(x):
                    plt.vline(x, color=ZONE_END_COLOUR)
            for x in data.axes:
                if math.isfinite(x):
                    plt.vline(x, color=AXIS_COLOUR)
            # The interfaces between sublayers (the depth tab: y/h upwards).
            for y in data.interfaces:
                if math.isfinite(y):
                    plt.hline(y, color=INTERFACE_COLOUR)
            if data.vertical_grid:
                plt.xlabel(data.value_label)
                plt.ylabel(data.grid_label)
            else:
                plt.xlabel(data.grid_label)
                plt.ylabel(data.value_label)
            if data.log_grid:
                plt.xscale("log")
                ticks = decade_ticks(data.grid)
                if ticks:
                    plt.xticks(ticks, [f"1e{round(math.log10(t))}" for t in ticks])
            plt.plotsize(width, plot_height)
            plt._set_size(width, plot_height)
            plt.theme(self._get_plotext_theme_name(self.app.theme))
            return str(plt.build()).rstrip("\n")

        theme = self.app.theme
        memo = (width, plot_height, theme)
        if (
            self._drawn is not None
            and self._drawn[0] is data
            and self._drawn[1] == memo
        ):
            drawn = self._drawn[2].copy()  # a redraw: the composing is done
        elif several and drawn_series:
            frame, cells = compose(draw, len(data.series))
            drawn = _overlay(frame, cells)
        else:
            drawn = Text.from_ansi(draw(-1))
        self._drawn = (data, memo, drawn.copy())
        if key is not None:
            drawn.append("\n")
            drawn.append_text(key)
        return drawn


def _overlay(frame: str, cells: Mapping[Cell, int]) -> Text:
    """The built ``frame`` (ANSI) with each cell's series marker written in,
    in the series' colour."""
    by_line: dict[int, dict[int, int]] = {}
    for (i, j), k in cells.items():
        by_line.setdefault(i, {})[j] = k
    out = Text()
    for i, raw in enumerate(frame.split("\n")):
        if i:
            out.append("\n")
        line = Text.from_ansi(raw)
        marks = {j: k for j, k in by_line.get(i, {}).items() if j < len(line.plain)}
        if not marks:
            out.append_text(line)
            continue
        cuts = sorted({c for j in marks for c in (j, j + 1)})
        starts = [0, *cuts]
        for start, piece in zip(starts, line.divide(cuts), strict=False):
            series = marks.get(start) if piece.plain else None
            if series is None:
                out.append_text(piece)
            else:
                r, g, b = PALETTE[series % len(PALETTE)]
                mark = MARKERS[series % len(MARKERS)]
                out.append(mark, style=f"bold rgb({r},{g},{b})")
    return out


def legend(data: Curves) -> list[Field]:
    """The legend below a plot: the marker (in its colour) and the label of
    each curve (when there are several), then the zone ends, the punch axes
    and the interfaces between sublayers (the depth tab)."""
    out: list[Field] = []
    if len(data.series) > 1:
        for i, series in enumerate(data.series):
            r, g, b = PALETTE[i % len(PALETTE)]
            mark = MARKERS[i % len(MARKERS)]
            out.append(Field(f"─{mark}─", series.label, "", f"bold rgb({r},{g},{b})"))
    if data.markers:
        r, g, b = ZONE_END_COLOUR
        out.append(Field("│", "zone ends", "", f"rgb({r},{g},{b})"))
    if data.axes:
        r, g, b = AXIS_COLOUR
        at = " ".join(fmt(x, 3) for x in data.axes)
        out.append(Field("│", f"punch axes x/h {at}", "", f"rgb({r},{g},{b})"))
    if data.interfaces:
        r, g, b = INTERFACE_COLOUR
        at = " ".join(fmt(y, 3) for y in data.interfaces)
        out.append(Field("─", f"interfaces y/h {at}", "", f"rgb({r},{g},{b})"))
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


MASK_MARK = "\u00d7"  # a multiplication sign: a cross
"""Drawn in a map's cell whose point is not finite: a flat punch's sharp
edges x = ±b on the surface, where the pressure is square-root singular."""
MASK_STYLE = "bold rgb(255,0,255)"


def singular_columns(x: FloatArray, values: FloatArray) -> list[float]:
    """x/h of the map's columns holding a non-finite value (singular points)."""
    bad = ~np.isfinite(values).all(axis=0)
    return [float(v) for v in x[bad]]


def mask_note(xs: Sequence[float]) -> str:
    """The legend of the masked cells: where the stress is singular."""
    return f"{MASK_MARK} {singular_note(xs)}"


class StressMap(Widget):
    """The stress field under the punch as a coloured map (two pixels per
    cell with half blocks), with the y/h and x/h axes and a colour bar.

    A point where the stress is infinite (a flat punch's edges x = ±b on the
    surface) is masked: drawn as a magenta cross (``MASK_MARK``), left out of the colour
    scale, and named under the colour bar ("masked: singular at x/h =
    ±0.5" after the cross). The map's column nearest such a point always shows it."""

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
        masked = singular_columns(data.x, data.values)
        rows = max(height - (4 if masked else 3), 2)  # title, x axis, bar, note
        finite = data.values[np.isfinite(data.values)]
        lo, hi = (
            (float(finite.min()), float(finite.max())) if finite.size else (0.0, 0.0)
        )
        diverging = data.quantity == "sigma_x"
        nx, ny = len(data.x), len(data.y)
        # data.y runs from -1 up to 0; the screen runs from y = 0 down.
        xi = np.minimum((np.arange(cols) + 0.5) * nx / cols, nx - 1).astype(int)
        for j in np.flatnonzero(~np.isfinite(data.values).all(axis=0)):
            if j not in xi:  # a masked point is always shown
                xi[int(np.argmin(np.abs((np.arange(cols) + 0.5) * nx / cols - j)))] = j
        yi = np.minimum((np.arange(2 * rows) + 0.5) * ny / (2 * rows), ny - 1)
        yi = (ny - 1 - yi.astype(int)).astype(int)
        # The surface row y = 0 is always drawn (the singular points lie on it).
        yi[0] = ny - 1
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
                up_value = float(data.values[top, xi[c]])
                down_value = float(data.values[bottom, xi[c]])
                up = colour(up_value, lo, hi, diverging)
                down = colour(down_value, lo, hi, diverging)
                if not math.isfinite(up_value) or not math.isfinite(down_value):
                    behind = down if math.isfinite(down_value) else up
                    if not math.isfinite(up_value) and not math.isfinite(down_value):
                        behind = "rgb(0,0,0)"
                    out.append(MASK_MARK, Style.parse(f"{MASK_STYLE} on {behind}"))
                else:
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
        if masked:
            text = mask_note(masked)
            out.append("\n" + " " * margin)
            out.append(text[:1], MASK_STYLE)
            out.append(text[1 : max(width - margin, 1)], "dim")
        return out


def decade_ticks(grid: npt.ArrayLike, most: int = 6) -> list[float]:
    """The powers of ten within a log grid's positive range, every k-th so
    that at most ``most`` remain; none (plotext's own labels) when fewer than
    three fit: plotext labels a log axis in fixed point, fine over a decade
    or two (0.0002 ... 0.02) and unreadable over many (0.000000010)."""
    g = np.asarray(grid, dtype=np.float64)
    g = g[np.isfinite(g) & (g > 0)]
    if len(g) == 0:
        return []
    lo, hi = (
        math.ceil(math.log10(g.min()) - 1e-9),
        math.floor(math.log10(g.max()) + 1e-9),
    )
    if hi - lo < 2:
        return []
    step = max(1, math.ceil((hi - lo + 1) / most))
    return [10.0**k for k in range(lo, hi + 1, step)]
