"""A line of labelled fields that never breaks a field: at any width the
fields are packed into as many lines as they need, each field (its label and
value, e.g. ``a/h 0.330419`` or ``0.6 ms``) whole on one line.

The summary under the plots uses it: a plain text would wrap between a value
and its unit (``0.6`` at the end of a line, ``ms`` alone on the next).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from rich.text import Text
from textual.geometry import Size
from textual.reactive import reactive
from textual.widget import Widget

SEPARATOR = "  "
"""Between two fields on a line (one space where that saves a line)."""


@dataclass(frozen=True)
class Field:
    """``label`` (dim) then ``value`` (bold); no label: the value dim."""

    label: str
    value: str
    style: str = "bold"
    label_style: str = "dim"

    @property
    def width(self) -> int:
        return len(self.text())

    def text(self) -> str:
        return f"{self.label} {self.value}" if self.label else self.value

    def render(self) -> Text:
        if not self.label:
            return Text(self.value, style="dim" if self.style == "bold" else self.style)
        out = Text(self.label, style=self.label_style)
        out.append(" ")
        out.append(self.value, self.style)
        return out


def pack(
    fields: Sequence[Field], width: int, separator: str = SEPARATOR
) -> list[list[Field]]:
    """The fields in lines of at most ``width`` cells (a field wider than
    the line gets a line of its own; it is never split)."""
    lines: list[list[Field]] = []
    used = 0
    for f in fields:
        need = len(separator) + f.width
        if lines and used + need <= width:
            lines[-1].append(f)
            used += need
        else:
            lines.append([f])
            used = f.width
    return lines


def layout(fields: Sequence[Field], width: int) -> tuple[list[list[Field]], str]:
    """(lines, separator): two spaces between fields, or one where that
    saves a line (the summary of the paper's case fits one 80-column line)."""
    width = max(width, 8)
    wide = pack(fields, width, SEPARATOR)
    tight = pack(fields, width, " ")
    return (tight, " ") if len(tight) < len(wide) else (wide, SEPARATOR)


def packed_text(fields: Sequence[Field], width: int) -> Text:
    """The fields packed to ``width`` as one Text, a line per row."""
    out = Text(no_wrap=True, overflow="crop")
    lines, separator = layout(fields, width)
    for i, line in enumerate(lines):
        if i:
            out.append("\n")
        for j, f in enumerate(line):
            if j:
                out.append(separator)
            out.append_text(f.render())
    return out


def plain_lines(fields: Sequence[Field], width: int) -> list[str]:
    """The packed lines as plain text (for tests and logs)."""
    lines, separator = layout(fields, width)
    return [separator.join(f.text() for f in line) for line in lines]


class FieldsLine(Widget):
    """Labelled fields packed to the widget's width (height: as many lines
    as they need)."""

    DEFAULT_CSS = """
    FieldsLine { height: auto; width: 1fr; }
    """

    fields: reactive[tuple[Field, ...]] = reactive((), layout=True)

    def render(self) -> Text:
        return packed_text(self.fields, self.content_size.width)

    def get_content_height(self, container: Size, viewport: Size, width: int) -> int:
        return max(len(layout(self.fields, width)[0]), 1)
