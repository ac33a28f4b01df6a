"""The help screen (keys, tabs and inputs of the main screen) and the
full-text screen (every message of the main screen, whole).

The help is rendered from the tables and facts below, and
``tests/python/test_docs_agree.py`` checks docs/tui.md against the same
ones (its Keys table row for row, each fact word for word) and the tables
against the app (its key bindings, its tab names, what a damped set
computes): what the help says and what the docs say are one source.

Paragraphs are single lines that the screen wraps to its width (no hard
breaks inside a paragraph, which left one word per line when the box was
narrower than the breaks); the key, tab and input tables have short lines
(``TABLE_WIDTH``) that fit an 80-column terminal. Longer than the screen,
it scrolls (arrows, page up/down).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import ClassVar, Protocol

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Static

from movingpunch.tui.widgets.params import (
    FULL_TEXT_KEY,
    INPUT_MESSAGE_LINES,
    STATUS_LINES,
    TALL,
)

TABLE_WIDTH = 60
"""The longest line of a table (an 80-column help box is 74 wide inside)."""

KEYS: tuple[tuple[str, str], ...] = (
    ("tab, shift+tab", "move between the inputs and the plots"),
    ("escape, enter", "leave an input; esc outside stops a solve"),
    ("i", "go to the first input (V*)"),
    ("1 ... 6", "go to a tab"),
    ("] and [", "next and previous tab"),
    ("r", "recompute (clears the cache)"),
    ("p", "pin the current curves as a reference"),
    ("c", "clear the pins and the overlay"),
    ("v", "overlay one parameter at several values"),
    ("l", "the medium: sublayers and the base"),
    ("m", "field tab: σx or von Mises"),
    ("w", "a/h sweep over P/(μh), R/h (and V*, drag)"),
    ("F2 ... F6", "the paper's Figs 2-6 (bundled scenes)"),
    ("o / s", "open / save a scene file (TOML)"),
    ("e", "export the tab's data to CSV"),
    (FULL_TEXT_KEY, "all messages whole (a shortened one: …)"),
    ("? or F1", "the help: keys, tabs, inputs, files"),
    ("q", "quit"),
)
"""Every key of the main screen: (key, what it does). docs/tui.md's Keys
table has these rows."""

TABS: tuple[tuple[str, str, str], ...] = (
    ("p(x)", "p(x)", "the contact pressure"),
    ("σx(x,0)", "σx(x)", "σx on the top surface"),
    ("σx(0,y)", "σx(y)", "σx under the centre, through the depth"),
    ("a/h sweep", "sweep", "a/h against P/(μh) or R/h (w)"),
    ("field", "field", "σx or von Mises under the punch (m)"),
    ("accuracy", "accuracy", "errors and times per tol"),
)
"""The tabs in order (keys 1 to 6): (name, name at 80 columns, meaning)."""

GROUPS: tuple[tuple[str, str], ...] = (
    ("speed", "V* = ρV²/μ, and the gauge"),
    ("layer, foundation", "ν, kw, kp, damp"),
    ("punch", "shape, R/h, b/h, P/(μh), fric, train"),
    ("numerics", "tol, cont"),
)
"""The input panel's groups, top to bottom."""

DEBOUNCE_MS = 200
"""The pause in typing before a value is solved, as the help says it (the
app's ``DEBOUNCE_SECONDS``; a test checks they agree)."""

_WORDS = ("no", "one", "two", "three", "four", "five", "six")

FACTS: dict[str, str] = {
    "typing": (
        "A value is checked as you type and solved after a short pause in "
        f"typing ({DEBOUNCE_MS} ms), or at once on enter. A half-typed or "
        "invalid value never replaces the result on screen: its message names "
        "the input and the valid range."
    ),
    "damping": (
        "With damping, every tab works as without: p(x), σx(x,0) "
        "and σx(0,y) plot the asymmetric solution, the field map spans its "
        "contact, the a/h sweep solves every point and the Accuracy ladder "
        "measures it."
    ),
    "damped time": (
        "A damped solve takes 20-45 ms cold and 3-12 ms warm, 0.06-0.13 s "
        "with the σx peaks of the summary; it runs in the worker thread, so "
        "the screen stays responsive."
    ),
    "messages": (
        f"A message longer than its area ({_WORDS[STATUS_LINES[0]]} lines under "
        f"the summary below {TALL} rows, {_WORDS[STATUS_LINES[1]]} from {TALL} "
        f"rows; {_WORDS[INPUT_MESSAGE_LINES[0]]} or "
        f"{_WORDS[INPUT_MESSAGE_LINES[1]]} under an input) is shortened after a "
        f"whole clause or word and ends in …; {FULL_TEXT_KEY} shows every "
        "message in full."
    ),
    "medium": (
        "The medium editor (l) lists the sublayers top to bottom, bonded: "
        "thickness h_i/h, μ and ρ per the top sublayer's (1 for the top), ν "
        "and the grading gamma h (0: homogeneous), and the base: springs (kw, kp, "
        "damp in the panel), a bonded or a smooth elastic half-space (μ, ν, "
        "ρ). ctrl+n adds a sublayer under the focused one and ctrl+r removes "
        "it (each keeps the thicknesses' sum), ctrl+t scales the thicknesses "
        "to sum to 1, enter applies and escape cancels. A message names the "
        "sublayer, the parameter and its valid range. The depth tab draws "
        "the interfaces between sublayers."
    ),
    "files": (
        "Open (o), save (s) and export (e) stay in the working folder: "
        "--root DIR, else the directory the app started in, except inside "
        "movingpunch's source checkout, where it is ~/movingpunch (created at "
        "the first save or export; --root . keeps the checkout). Each prompt "
        "names the folder."
    ),
}
"""Sentences the help and docs/tui.md both say, word for word (docs/tui.md
may wrap them across lines). The damped times were measured with
``mp.solve`` and the TUI's summary on nine damped sets (V* 0.2, 0.4, 0.65;
damping 0.01, 0.1, 0.5; kw 1, R/h 100, P/(μh) 0.002) on a shared 2-core
machine."""


def _table(title: str, rows: Iterable[tuple[str, str]], key_width: int) -> str:
    lines = [title]
    lines += [f"  {key.ljust(key_width)}  {what}" for key, what in rows]
    return "\n".join(lines)


def help_text() -> str:
    """The help: paragraphs on one line each (wrapped by the screen) and
    tables of short lines."""
    keys = _table("Keys (letters act outside the inputs; escape leaves one)", KEYS, 14)
    tabs = _table(
        "Tabs",
        ((str(k), f"{name}: {what}") for k, (name, _, what) in enumerate(TABS, 1)),
        1,
    )
    tabs += "\n  at 80 columns: " + " ".join(short for _, short, _ in TABS)
    groups = _table(
        "Inputs, in four groups (those that do not apply are hidden)", GROUPS, 17
    )
    paragraphs = (
        "movingpunch: a rigid punch sliding at a constant speed over an elastic "
        "layer on a Winkler foundation. Everything is dimensionless (h = 1, "
        "μ = 1) and the stresses are over P/h.",
        keys,
        tabs,
        groups,
        "shape is the punch's shape: cylinder, flat, rounded_flat, or table "
        "(from a scene file). R/h is the cylinder's radius (a rounded flat's "
        "corners), b/h a flat face's half-width, P/(μh) the load and ν the "
        "layer's Poisson ratio. kw is the foundation's stiffness k_w h/μ (inf: "
        "a rigid base) and kp its Pasternak shear layer k_p/(μh) (0: springs "
        "alone). damp is the foundation's damping c_w c_T/μ >= 0 (dashpots; 0: "
        "the paper's model). fric is the Coulomb friction f in [0, 10] (0: "
        "frictionless). tol is the solver's tolerance. cont is the contact: "
        "auto finds the contact zones (several where a single contact would "
        "pull on the layer), single keeps one and refuses it when unphysical. "
        "train is a train of punches moving together, load@at items such as "
        "0.002@-1.5, 0.002@1.5 (P/(μh) and x/h of each axis; empty: one punch "
        "of P/(μh)).",
        FACTS["typing"],
        FACTS["medium"]
        + " With sublayers ν is each one's own and the ν input is hidden; "
        "under a half-space kw, kp and damp are. The panel and the status "
        "line name the medium solved; a medium the solver does not take yet "
        "is refused on the status line.",
        FACTS["messages"],
        "The gauge compares V* with the critical speed V*_cr(kw, ν, kp) and "
        "turns red above 95 %. With damping > 0 it compares V* with the "
        "Rayleigh speed V*_R (V* may exceed V*_cr) and the summary shows the "
        "contact (-b,a)/h and the drag over P. "
        + FACTS["damping"]
        + " "
        + FACTS["damped time"]
        + " Friction > 0 also gives an asymmetric contact (-b,a)/h and the "
        "friction force over P (friction/P).",
        "Plausibility hints (one line, never blocking) say when a result leaves "
        "small-strain linear theory, δ/h > 0.05, a/h > 5 or a strain > 0.05, or "
        "when V* is within 1 % of its speed limit (V*_cr, or V*_R with damping).",
        FACTS["files"] + " Paths are relative to the folder and paths leading out are "
        "refused. Open takes a TOML file or a bundled scene's name. Open and "
        "save suggest the last file saved or opened (scene.toml at first), "
        "export suggests movingpunch-<tab>.csv. A saved scene keeps the a/h "
        "sweep as start, stop, points and spacing. Replacing an existing file "
        "asks first: enter again to overwrite, escape to cancel.",
        "Press escape, q, ? or F1 to close; arrows and page up/down scroll.",
    )
    return "\n\n".join(paragraphs)


HELP = help_text()
"""The help text."""


class HelpScreen(ModalScreen[None]):
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("escape,q,question_mark,f1", "dismiss_help", "Close"),
    ]

    def compose(self) -> ComposeResult:
        with VerticalScroll(id="help-box"):
            yield Static(HELP, id="help-text", markup=False)

    def action_dismiss_help(self) -> None:
        self.dismiss(None)


class Message(Protocol):
    """A message area of the main screen (``widgets.params.MessageLine``)."""

    @property
    def title(self) -> str: ...

    @property
    def full(self) -> str: ...


def messages_text(messages: Iterable[Message]) -> str:
    """Every non-empty message whole, each after what it is about."""
    out = [f"{m.title}: {m.full}" for m in messages if m.full.strip()]
    return "\n\n".join(out) or "no messages"


class MessagesScreen(ModalScreen[None]):
    """Every message of the main screen in full (key ``x``): the status
    line's and each input's, as they were when the key was pressed."""

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("escape,q,x", "dismiss_messages", "Close"),
    ]

    def __init__(self, messages: Iterable[Message]) -> None:
        super().__init__()
        self._text = messages_text(messages)

    @property
    def text(self) -> str:
        return self._text

    def compose(self) -> ComposeResult:
        with VerticalScroll(id="help-box"):
            yield Static(
                "Messages in full (escape, q or x closes)", classes="panel-title"
            )
            yield Static(self._text, id="messages-text", markup=False)

    def action_dismiss_messages(self) -> None:
        self.dismiss(None)
