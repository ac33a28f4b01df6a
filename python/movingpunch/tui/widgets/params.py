"""The parameters panel: one compact input per parameter with its inline
message, μ/(P/h) beside the load, and the gauge of V* against V*_cr (against
the Rayleigh speed V*_R with damping > 0)."""

from __future__ import annotations

from rich.text import Text
from textual.app import ComposeResult
from textual.containers import Horizontal, VerticalScroll
from textual.reactive import reactive
from textual.widgets import Input, Label, Static

from movingpunch.params import help_text
from movingpunch.tui.model import (
    PARAM_NAMES,
    TUI_PROFILES,
    Params,
    fmt,
    format_punches,
)

TEXT_INPUTS: tuple[str, ...] = ("contact", "punches")
"""The text inputs below the numeric ones (the punch's kind, ``profile``,
is above them)."""

INPUTS: tuple[str, ...] = ("profile", *PARAM_NAMES, *TEXT_INPUTS)
"""Every input of the panel, top to bottom."""

LABELS: dict[str, str] = {
    "vstar": "V*",
    "kw": "kw h/μ",
    "kp": "kp/μh",
    "radius": "R/h",
    "half_width": "b/h",
    "profile": "punch",
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

    limits: reactive[tuple[float, float, float] | None] = reactive(None)
    """(vstar, V*_cr, V*_R), or None before the first result."""
    damped: reactive[bool] = reactive(False)
    """Damping > 0: the limit is V*_R."""

    def render(self) -> Text:
        if self.limits is None:
            return Text("V*/V*_cr  ...", style="dim")
        vstar, vcr, vr = self.limits
        if self.damped:
            return self._render_damped(vstar, vcr, vr)
        ratio = vstar / vcr if vcr > 0 else float("inf")
        self.set_class(ratio > WARN_FRACTION, "-warning")
        width = 12  # fixed: the panel is 30 cells wide at every size
        filled = round(min(max(ratio, 0.0), 1.0) * width)
        out = Text("V*/V*_cr ")
        bar_style = "bold red" if ratio > WARN_FRACTION else "green"
        out.append("█" * filled, bar_style)
        out.append("░" * (width - filled), "dim")
        out.append(f" {min(ratio, 9.99):.2f}\n")
        out.append(f"V*_cr {fmt(vcr, 5)}  V*_R {fmt(vr, 5)}")
        if ratio >= 1.0:
            out.append("\nabove the critical speed", "bold red")
        elif ratio > WARN_FRACTION:
            out.append("\nnear the critical speed", "bold red")
        return out

    def _render_damped(self, vstar: float, vcr: float, vr: float) -> Text:
        ratio = vstar / vr if vr > 0 else float("inf")
        self.set_class(ratio > WARN_FRACTION, "-warning")
        width = 12
        filled = round(min(max(ratio, 0.0), 1.0) * width)
        out = Text("V*/V*_R  ")
        bar_style = "bold red" if ratio > WARN_FRACTION else "green"
        out.append("█" * filled, bar_style)
        out.append("░" * (width - filled), "dim")
        out.append(f" {min(ratio, 9.99):.2f}\n")
        out.append(f"V*_cr {fmt(vcr, 5)}  V*_R {fmt(vr, 5)}")
        if ratio >= 1.0:
            out.append("\nat or above the Rayleigh speed", "bold red")
        elif ratio > WARN_FRACTION:
            out.append("\nnear the Rayleigh speed", "bold red")
        elif vstar >= vcr:
            out.append("\ndamped: above V*_cr", "yellow")
        return out


class ParamsPanel(VerticalScroll):
    """Inputs for every parameter; the screen validates what is typed."""

    def __init__(self, params: Params, *, cursor_blink: bool = True) -> None:
        super().__init__(id="params")
        self._initial = params
        self._blink = cursor_blink
        self._messages: dict[str, str] = dict.fromkeys(INPUTS, "")

    def compose(self) -> ComposeResult:
        yield Label("Parameters", classes="panel-title")
        for name in INPUTS:
            with Horizontal(classes="param-row"):
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
            yield Static("", id=f"msg-{name}", classes="param-msg")
        yield Gauge(id="gauge")

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
        msg = self.query_one(f"#msg-{name}", Static)
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
