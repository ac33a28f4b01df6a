"""The Accuracy tab: what each tolerance really gives and what it costs.

Shows the table of ``movingpunch.accuracy`` (tol, N, estimated and actual
errors of a/h, p0 and the sigma_x peaks, cold and warm times; as many
columns as fit) and, below it when there is room, a log-log plot of the
actual errors against the cold time, drawn to the size of the widget.
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Callable

from rich.console import RenderableType
from rich.text import Text
from textual.reactive import reactive
from textual.widget import Widget

from movingpunch.accuracy import Rung, ascii_plot
from movingpunch.tui.model import AccuracyTable


def _e(x: float) -> str:
    return f"{x:.1e}" if math.isfinite(x) else "-"


def _ms(x: float) -> str:
    return f"{x * 1e3:.1f}" if math.isfinite(x) else "-"


Column = tuple[str, Callable[[Rung], str]]

# In order of priority: the first seven fit 50 cells (the tab at 80x24).
COLUMNS: tuple[Column, ...] = (
    ("tol", lambda r: f"{r.tol:.0e}"),
    ("N", lambda r: str(r.collocation_n)),
    ("est a/h", lambda r: _e(r.error_estimate)),
    ("err a/h", lambda r: _e(r.error_a)),
    # The sigma_x peaks' error next to their own bound (the solution's
    # stress_error_estimate plus the peak search's uncertainty).
    ("est σx", lambda r: _e(r.peak_error_bound)),
    ("err σx", lambda r: _e(max(r.error_top_tensile, r.error_bottom_tensile))),
    ("cold ms", lambda r: _ms(r.seconds)),
    ("warm ms", lambda r: _ms(r.warm_seconds)),
    ("err p0", lambda r: _e(r.error_p0)),
    ("tables", lambda r: str(r.kernel_tables)),
)


def table_lines(data: AccuracyTable, width: int) -> list[str]:
    """The header and one line per rung, with the columns that fit ``width``."""
    rungs = data.report.rungs
    cells = [[name, *(get(r) for r in rungs if not r.failure)] for name, get in COLUMNS]
    widths = [max(len(c) for c in col) for col in cells]
    chosen: list[int] = []
    used = 0
    for i, w in enumerate(widths):
        need = w + (1 if chosen else 0)
        if used + need > width and len(chosen) >= 2:
            break
        chosen.append(i)
        used += need
    lines = []
    ok = iter(range(1, len(rungs) + 1))
    header = " ".join(cells[i][0].rjust(widths[i]) for i in chosen)
    lines.append(header)
    for r in rungs:
        if r.failure:  # wrapped at spaces: never cut mid-word
            lines += textwrap.wrap(f"{r.tol:.0e} failed: {r.failure}", width)
            continue
        k = next(ok)
        lines.append(" ".join(cells[i][k].rjust(widths[i]) for i in chosen))
    return lines


class AccuracyView(Widget):
    """The accuracy ladder of the current parameters; computed when the tab
    is opened (once per parameter set)."""

    DEFAULT_CSS = """
    AccuracyView { width: 1fr; height: 1fr; }
    """

    table: reactive[AccuracyTable | None] = reactive(None)
    placeholder: reactive[str] = reactive("computing the accuracy ladder...")
    """Shown while ``table`` is None (a notice if the ladder is unavailable)."""

    def render(self) -> RenderableType:
        data = self.table
        if data is None:
            return Text(self.placeholder, style="dim")
        report = data.report
        width, height = self.size.width, self.size.height
        out = Text(no_wrap=True, overflow="crop")
        title = f"Accuracy against time; reference {report.reference}"
        heading = textwrap.wrap(title, max(width, 8))
        for line in heading:
            out.append(line + "\n", "bold")
        lines = table_lines(data, width)
        for k, line in enumerate(lines):
            out.append(line[:width] + "\n", "dim" if k == 0 else "")
        bounded = all(r.bounded for r in report.rungs if not r.failure)
        verdict = (
            "every estimate bounds its actual error"
            if bounded
            else "an actual error exceeds its estimate"
        )
        out.append(verdict[:width], "green" if bounded else "bold red")
        room = height - len(lines) - len(heading) - 1
        if room >= 8 and width >= 40:
            out.append("\n")
            out.append(ascii_plot(report, width=width, height=room))
        return out
