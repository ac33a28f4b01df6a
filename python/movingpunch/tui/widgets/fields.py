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
"""Between two fields on a line."""


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


def pack(fields: Sequence[Field], width: int) -> list[list[Field]]:
    """The fields in lines of at most ``width`` cells (a field wider than
    the line gets a line of its own; it is never split)."""
    lines: list[list[Field]] = []
    used = 0
    for f in fields:
        need = f.width if not lines or not lines[-1] else len(SEPARATOR) + f.width
        if lines and lines[-1] and used + need <= width:
            lines[-1].append(f)
            used += need
        else:
            lines.append([f])
            used = f.width
    return lines


def packed_text(fields: Sequence[Field], width: int) -> Text:
    """The fields packed to ``width`` as one Text, a line per row."""
    out = Text(no_wrap=True, overflow="crop")
    for i, line in enumerate(pack(fields, max(width, 8))):
        if i:
            out.append("\n")
        for j, f in enumerate(line):
            if j:
                out.append(SEPARATOR)
            out.append_text(f.render())
    return out


class FieldsLine(Widget):
    """Labelled fields packed to the widget's width (height: as many lines
    as they need)."""

    DEFAULT_CSS = """
    FieldsLine { height: auto; width: 1fr; }
    """

    fields: reactive[tuple[Field, ...]] = reactive((), layout=True)

    def _inner_width(self, width: int | None = None) -> int:
        full = self.size.width if width is None else width
        return max(full - self.styles.gutter.width, 8)

    def render(self) -> Text:
        return self._text(self.content_size.width or self._inner_width())

    def _text(self, width: int) -> Text:
        return packed_text(self.fields, width)

    def get_content_height(self, container: Size, viewport: Size, width: int) -> int:
        return max(len(pack(self.fields, max(width, 8))), 1)

    def plain_lines(self, width: int) -> list[str]:
        """The lines as plain text at ``width`` (for tests and logs)."""
        return [
            SEPARATOR.join(f.text() for f in line) for line in pack(self.fields, width)
        ]
