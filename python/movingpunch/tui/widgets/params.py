"""The parameters panel: one compact input per parameter with its inline
message, grouped (speed, layer and foundation, punch, numerics), μ/(P/h)
beside the load, and the gauge of V* against V*_cr (against the Rayleigh speed
V*_R with damping > 0) under the speed.

An input that does not apply to the current set is hidden (``applies``): b/h
without a flat face, R/h for a flat punch or a table, and the single punch's
load, friction and contact mode beside a train (its punches carry their loads;
a train is frictionless and always finds its contact set). With sublayers
(the medium editor, key ``l``) ν is each sublayer's own, and a half-space
base has no springs (kw, kp, damping): those inputs are hidden, and the
group names the medium."""

from __future__ import annotations

import re
from collections.abc import Sequence

from rich.cells import cell_len
from rich.text import Text
from textual.app import ComposeResult
from textual.containers import Horizontal, VerticalScroll
from textual.content import Content
from textual.geometry import Size
from textual.reactive import reactive
from textual.visual import VisualType
from textual.widgets import Input, Label, Static

from movingpunch.params import help_text
from movingpunch.tui.model import (
    PARAM_NAMES,
    TUI_PROFILES,
    Params,
    fmt,
    format_punches,
)
from movingpunch.tui.widgets.fields import Field, packed_text

TEXT_INPUTS: tuple[str, ...] = ("contact", "punches")
"""The text inputs below the numeric ones (the punch's kind, ``profile``,
is above them)."""

GROUPS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("speed", ("vstar",)),
    ("layer, foundation", ("nu", "kw", "kp", "damping")),
    ("punch", ("profile", "radius", "half_width", "load", "friction", "punches")),
    ("numerics", ("tol", "contact")),
)
"""The panel's groups, top to bottom (the gauge follows the speed)."""

INPUTS: tuple[str, ...] = tuple(name for _, names in GROUPS for name in names)
"""Every input of the panel, top to bottom."""

assert sorted(INPUTS) == sorted(("profile", *PARAM_NAMES, *TEXT_INPUTS))


def applies(name: str, params: Params) -> bool:
    """Whether the input ``name`` means something for ``params`` (the panel
    hides it otherwise)."""
    if name == "radius":
        return params.profile in ("cylinder", "rounded_flat")
    if name == "half_width":
        return params.profile in ("flat", "rounded_flat")
    if name in ("load", "friction", "contact"):
        return not params.punches
    return params.applies(name)


LABELS: dict[str, str] = {
    "vstar": "V*",
    "kw": "kw h/μ",
    "kp": "kp/μh",
    "radius": "R/h",
    "half_width": "b/h",
    "profile": "shape",
    "load": "P/(μh)",
    "nu": "ν",
    "damping": "damp",
    "friction": "fric",
    "tol": "tol",
    "contact": "cont",
    "punches": "train",
}

TOOLTIPS: dict[str, str] = {name: help_text(name) for name in PARAM_NAMES}
TOOLTIPS["profile"] = (
    "the punch's shape: "
    + ", ".join(TUI_PROFILES)
    + " (R/h is the cylinder's or the rounded corners' radius, b/h the flat face's "
    "half-width; a table comes from a scene file)"
)
TOOLTIPS["contact"] = (
    "auto: find the contact set (several zones where the single contact would "
    "pull on the layer, p < 0, near the critical speed); single: one contact "
    "interval, refused when unphysical. A train always finds its contact set."
)
TOOLTIPS["punches"] = (
    "a train of punches moving together: load@at, ... e.g. 0.002@-1.5, 0.002@1.5 "
    "(P_k/(μh) at x/h of each axis; each punch has the panel's shape, R/h and "
    "b/h; frictionless). Empty: the single punch of P/(μh)."
)
"""Meaning, valid range and default of each input: the table of parameters."""

WARN_FRACTION = 0.95
"""The gauge turns to a warning above this fraction of V*_cr."""


class Gauge(Static):
    """V* against V*_cr as a bar, with V*_cr and the Rayleigh V*_R. With
    damping > 0 the bar measures V* against V*_R: the critical speed no
    longer bounds the solution, the Rayleigh speed does."""

    limits: reactive[tuple[float, float, float] | None] = reactive(None, layout=True)
    """(vstar, V*_cr, V*_R), or None before the first result."""
    damped: reactive[bool] = reactive(False, layout=True)
    """Damping > 0, or a viscoelastic layer with its inertia (the material
    damps): the limit is V*_R."""

    def render(self) -> Text:
        if self.limits is None:
            return Text("V*/V*_cr  ...", style="dim")
        vstar, vcr, vr = self.limits
        width = self.content_size.width or 28
        limit, name = (vr, "V*_R") if self.damped else (vcr, "V*_cr")
        ratio = vstar / limit if limit > 0 else float("inf")
        self.set_class(ratio > WARN_FRACTION, "-warning")
        # The bar takes what the label and the ratio leave (12 in a panel
        # 30 cells wide, less beside a scrollbar): the line never wraps.
        head = f"V*/{name} ".ljust(9)
        bar = max(min(width - len(head) - 5, 12), 3)
        filled = round(min(max(ratio, 0.0), 1.0) * bar)
        out = Text(head)
        bar_style = "bold red" if ratio > WARN_FRACTION else "green"
        out.append("█" * filled, bar_style)
        out.append("░" * (bar - filled), "dim")
        out.append(f" {min(ratio, 9.99):.2f}\n")
        speeds = (Field("V*_cr", fmt(vcr, 5), ""), Field("V*_R", fmt(vr, 5), ""))
        out.append_text(packed_text(speeds, width))
        note = self._note(vstar, vcr, ratio)
        if note is not None:
            out.append("\n")
            out.append(*note)
        return out

    def _note(self, vstar: float, vcr: float, ratio: float) -> tuple[str, str] | None:
        """(text, style) of the line under the speeds, if any."""
        if self.damped:
            if ratio >= 1.0:
                return ("at or above the Rayleigh speed", "bold red")
            if ratio > WARN_FRACTION:
                return ("near the Rayleigh speed", "bold red")
            if vstar >= vcr:
                return ("damped: above V*_cr", "yellow")
            return None
        if ratio >= 1.0:
            return ("above the critical speed", "bold red")
        if ratio > WARN_FRACTION:
            return ("near the critical speed", "bold red")
        return None


ELLIPSIS = "…"
"""Ends a message shortened to fit its area (the full text: ``FULL_TEXT_KEY``)."""

FULL_TEXT_KEY = "x"
"""The key that shows every message of the screen in full."""

TALL = 30
"""A terminal at least this many rows tall gives messages more lines."""

STATUS_LINES = (2, 3)
"""Lines of the message area under the summary: (below ``TALL`` rows, from
``TALL`` rows); 2 keep the plot and its legend whole at 80x24."""

INPUT_MESSAGE_LINES = (3, 5)
"""Lines of a message under an input (the panel's rows at 80x24 hold every
input, the gauge and one 3-line message)."""

_CLAUSE_ENDS = re.compile(r"(?=; |: |, | \(| — |\. )")
"""Where a clause ends: before ``; ``, ``: ``, ``, ``, `` (``, `` — ``, ``. ``."""

_MIN_KEPT = 12
"""A shortened part keeps at least this many characters (or its first words)."""


def line_count(plain: str, width: int) -> int:
    """Lines ``plain`` takes wrapped to ``width`` as Textual wraps it."""
    return len(Content(plain).wrap(max(width, 1))) if plain else 0


_SEPARATORS = re.compile(r"  +")
"""Between two items of a message line (two spaces: a warning and the next,
the overlay and its notes): never shortened, so each item is summarised on
its own."""


def _parts(text: Text) -> list[Text]:
    """``text`` cut where its style changes and at item separators: the
    items of a message line (an error, ``; showing the last result``, the
    warnings, the hints, the overlay) and the separators between them."""
    cuts = {x for span in text.spans for x in (span.start, span.end)}
    for m in _SEPARATORS.finditer(text.plain):
        cuts |= {m.start(), m.end()}
    inside = sorted(c for c in cuts if 0 < c < len(text.plain))
    return [part for part in text.divide(inside) if part.plain]


CLAUSE_SHARE = 0.6
"""A summary ends after a whole clause if that keeps at least this share of
what ending after a word would keep."""


def _shorter(part: Text) -> Text | None:
    """``part`` one step shorter, ending in the ellipsis: cut after its last
    whole clause (``; ``, ``: ``, ``, ``, before `` (``), or after its last
    whole word where the clause would lose much more; never mid-word. None:
    it is as short as it gets (its first words, or a separator)."""
    plain = part.plain
    if _SEPARATORS.fullmatch(plain):
        return None
    base = plain[:-1] if plain.endswith(ELLIPSIS) else plain
    base = base.rstrip()
    words = [m.start() for m in re.finditer(r" (?=\S)", base)]
    if not words:
        return None
    minimum = min(_MIN_KEPT, words[min(2, len(words) - 1)])

    def kept(cut: int) -> int:
        return len(base[:cut].rstrip(" ;:,(—."))

    by_word = max((kept(c) for c in words if kept(c) >= minimum), default=0)
    by_clause = max(
        (
            kept(m.start())
            for m in _CLAUSE_ENDS.finditer(base)
            if kept(m.start()) >= minimum
        ),
        default=0,
    )
    size = by_clause if by_clause >= CLAUSE_SHARE * by_word else by_word
    if not size:
        return None
    short = part[:size]
    short.append(ELLIPSIS)
    return short


def fit(text: Text | str, width: int, lines: int) -> tuple[Text, bool]:
    """(``text`` as it fits ``lines`` lines of ``width`` cells, wrapped at
    spaces; whether it was shortened). A message that does not fit is
    summarised, never cut mid-sentence: its longest item is cut after a
    whole clause (or, if that loses much more, a whole word) and ends in
    ``ELLIPSIS``, step by step, the longest item first, until it fits;
    short items (``; showing the last result``) stay whole."""
    text = Text(text) if isinstance(text, str) else text
    if width <= 0 or line_count(text.plain, width) <= lines:
        return text, False
    parts = _parts(text)

    def joined(items: Sequence[Text]) -> Text:
        out = Text(end="")
        for item in items:
            out.append_text(item)
        return out

    def fits(items: Sequence[Text]) -> bool:
        return line_count(joined(items).plain, width) <= lines

    while not fits(parts):
        steps = {k: _shorter(part) for k, part in enumerate(parts)}
        left = [k for k, step in steps.items() if step is not None]
        if not left:
            break
        k = max(left, key=lambda k: cell_len(parts[k].plain))
        step = steps[k]
        assert step is not None
        parts[k] = step
    while len(parts) > 1 and not fits(parts):
        parts.pop()  # drop items from the end
        if _SEPARATORS.fullmatch(parts[-1].plain):
            parts.pop()
        if not parts[-1].plain.endswith(ELLIPSIS):
            parts[-1] = parts[-1].copy()
            parts[-1].append(ELLIPSIS)
    out = joined(parts)
    while len(out) > 1 and line_count(out.plain, width) > lines:
        # one word longer than the area: its head, marked
        out = out[: max(len(out) - width // 2 - 2, 1)]
        out.append(ELLIPSIS)
    return out, True


class MessageLine(Static):
    """A message area: its text summarised to at most ``lines`` lines
    (``fit``; the screen wraps it at spaces); ``full`` keeps the whole text, which the
    full-text screen (key ``FULL_TEXT_KEY``) shows."""

    def __init__(
        self,
        content: VisualType = "",
        *,
        title: str,
        lines: tuple[int, int],
        id: str | None = None,
        classes: str | None = None,
    ) -> None:
        super().__init__(content, id=id, classes=classes, markup=False)
        self.title = title
        """What the message is about (the input's label, or ``status``)."""
        self._lines = lines
        self.shortened = False
        """The text on screen is a summary of ``full``."""

    @property
    def full(self) -> str:
        """The whole message as plain text."""
        content = self.content
        return content.plain if isinstance(content, Text) else str(content)

    def _text(self) -> Text:
        content = self.content
        return content if isinstance(content, Text) else Text(str(content))

    def max_lines(self, rows: int) -> int:
        """Lines allowed in a terminal ``rows`` tall."""
        return self._lines[1] if rows >= TALL else self._lines[0]

    def _fitted(self, width: int, rows: int) -> Text:
        text, shortened = fit(self._text(), width, self.max_lines(rows))
        if shortened != self.shortened:
            self.shortened = shortened
            if self.is_mounted:  # the footer shows the full-text key or not
                self.call_after_refresh(self.screen.refresh_bindings)
        return text

    def render(self) -> Text:
        return self._fitted(self.content_size.width, self.app.size.height)

    def get_content_height(self, container: Size, viewport: Size, width: int) -> int:
        if not self.full:
            return 0
        return line_count(self._fitted(width, viewport.height).plain, width)


class ParamsPanel(VerticalScroll):
    """Inputs for every parameter; the screen validates what is typed."""

    def __init__(self, params: Params, *, cursor_blink: bool = True) -> None:
        super().__init__(id="params")
        self._initial = params
        self._blink = cursor_blink
        self._messages: dict[str, str] = dict.fromkeys(INPUTS, "")

    def compose(self) -> ComposeResult:
        for title, names in GROUPS:
            yield Label(title, classes="group-title")
            if title == "layer, foundation":
                note = Label("", id="medium-note")
                note.display = False
                yield note
            for name in names:
                yield from self._row(name)
            if title == "speed":
                yield Gauge(id="gauge")

    def _row(self, name: str) -> ComposeResult:
        shown = applies(name, self._initial)
        with Horizontal(classes="param-row", id=f"row-{name}") as row:
            row.display = shown
            yield Label(LABELS[name], classes="param-label")
            box = Input(
                self._text_of(self._initial, name),
                id=f"in-{name}",
                compact=True,
                select_on_focus=False,
                tooltip=TOOLTIPS[name],
            )
            box.cursor_blink = self._blink
            yield box
            if name == "load":
                yield Label(self._mu_text(self._initial.load), id="mu-note")
        yield MessageLine(
            "",
            title=LABELS[name],
            lines=INPUT_MESSAGE_LINES,
            id=f"msg-{name}",
            classes="param-msg",
        )

    def on_mount(self) -> None:
        self.show_medium(self._initial)

    def show_medium(self, params: Params) -> None:
        """Names the medium under the group's title (hidden for the
        homogeneous layer on springs)."""
        note = self.query_one("#medium-note", Label)
        label = params.medium_label()
        note.update(f"medium {label} (l edits)" if label else "")
        note.display = bool(label)

    def show_applicable(self, params: Params) -> tuple[str, ...]:
        """Shows the inputs that apply to ``params`` and hides the others;
        returns the names just hidden."""
        hidden = []
        for name in INPUTS:
            row = self.query_one(f"#row-{name}", Horizontal)
            shown = applies(name, params)
            if row.display and not shown:
                hidden.append(name)
            row.display = shown
        return tuple(hidden)

    @staticmethod
    def _text_of(params: Params, name: str) -> str:
        if name == "profile":
            return params.profile
        if name == "contact":
            return params.contact
        if name == "punches":
            return format_punches(params.punches)
        return fmt(params.get(name), 10)

    @staticmethod
    def _mu_text(load: float) -> str:
        return f"μ/(P/h) {fmt(1.0 / load, 4)}"

    def show_load(self, load: float) -> None:
        self.query_one("#mu-note", Label).update(self._mu_text(load))

    def set_message(self, name: str, message: str) -> None:
        self._messages[name] = message
        msg = self.query_one(f"#msg-{name}", MessageLine)
        msg.update(message)
        msg.set_class(bool(message), "-shown")
        self.query_one(f"#in-{name}", Input).set_class(bool(message), "-invalid")

    def message(self, name: str) -> str:
        return self._messages[name]

    def text(self, name: str) -> str:
        return self.query_one(f"#in-{name}", Input).value

    def set_values(self, params: Params) -> None:
        for name in INPUTS:
            box = self.query_one(f"#in-{name}", Input)
            text = self._text_of(params, name)
            if box.value != text:
                box.value = text
