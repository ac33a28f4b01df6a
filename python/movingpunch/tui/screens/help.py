"""The help screen: every key of the main screen."""

from __future__ import annotations

from typing import ClassVar

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Static

HELP = """\
movingpunch: a rigid punch sliding over an elastic layer on a Winkler
foundation. Dimensionless: h = 1, μ = 1; stresses in P/h.

Keys (letters act outside the inputs; Escape leaves an input)
  tab / shift+tab   move between the inputs and the plots
  escape            leave an input
  i                 go to the first input (V*)
  r                 recompute (clears the cache)
  p                 pin the current curves as a reference
  c                 clear the pins and the overlay
  v                 overlay: one parameter at several values
  ] / [             next / previous plot tab
  1 ... 6           go to a tab (6: Accuracy, errors and times per tol)
  m                 field map: σx or von Mises
  w                 a/h sweep: against P/(μh) or R/h
  F2 ... F6         the paper's Figs 2-6 (bundled scenes)
  o / s             open / save a scene file (TOML)
  e                 export the visible curves to CSV
  ? or F1           this help
  q                 quit

Inputs are checked as you type; the message names the valid range and
the last valid result stays on screen. kw accepts inf (rigid base).
The gauge compares V* with the critical speed V*_cr(kw, ν); it turns red
above 95 %.

Files: open, save and export stay in the working folder (where the app
started, or --root DIR); paths are relative to it and paths leading out are
refused. Replacing an existing file needs a second enter.

damp: foundation damping c_w c_T/μ >= 0 (dashpots; 0: the paper's model).
fric: Coulomb friction f in [0, 10] (0: frictionless); > 0 gives the asymmetric
contact, the end exponents and the friction force f P.
With damping > 0 the gauge compares V* with the Rayleigh speed V*_R (V* may
exceed V*_cr), the summary shows the contact (-b, a) and the drag over P,
and the p(x), σx(x,0) and σx(0,y) tabs plot the asymmetric solution; the
a/h sweep, field and Accuracy tabs show a message instead (too slow or not
available for the damped solver). Damped solves take 0.4-1.5 s.

Press escape, q or ? to close."""


class HelpScreen(ModalScreen[None]):
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("escape,q,question_mark,f1", "dismiss_help", "Close"),
    ]

    def compose(self) -> ComposeResult:
        with VerticalScroll(id="help-box"):
            yield Static(HELP, id="help-text", markup=False)

    def action_dismiss_help(self) -> None:
        self.dismiss(None)
