"""The help screen: the keys, tabs and inputs of the main screen.

Paragraphs are single lines that the screen wraps to its width (no hard
breaks inside a paragraph, which left one word per line when the box was
narrower than the breaks); the key, tab and input tables have short lines
(``TABLE_WIDTH``) that fit an 80-column terminal. Longer than the screen,
it scrolls (arrows, page up/down).
"""

from __future__ import annotations

from typing import ClassVar

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Static

TABLE_WIDTH = 60
"""The longest line of a table (an 80-column help box is 74 wide inside)."""

KEYS = """\
Keys (letters act outside the inputs; escape leaves one)
  tab, shift+tab  move between the inputs and the plots
  escape          leave an input
  i               go to the first input (V*)
  1 ... 6         go to a tab
  ] and [         next and previous tab
  r               recompute (clears the cache)
  p               pin the current curves as a reference
  c               clear the pins and the overlay
  v               overlay one parameter at several values
  m               field tab: σx or von Mises
  w               a/h sweep: against P/(μh) or R/h
  F2 ... F6       the paper's Figs 2-6 (bundled scenes)
  o / s           open / save a scene file (TOML)
  e               export the tab's data to CSV
  ? or F1         this help
  q               quit"""

TABS = """\
Tabs
  1  p(x): the contact pressure
  2  σx(x,0): σx on the top surface
  3  σx(0,y): σx under the centre, through the depth
  4  a/h sweep: a/h against P/(μh) or R/h (w)
  5  field: σx or von Mises under the punch (m)
  6  accuracy: errors and times per tol
  (at 80 columns the tabs are p(x) σx(x) σx(y) sweep field
  accuracy)"""

INPUTS = """\
Inputs, in four groups (those that do not apply are hidden)
  speed              V* = ρV²/μ, and the gauge
  layer, foundation  ν, kw, kp, damp
  punch              shape, R/h, b/h, P/(μh), fric, train
  numerics           tol, cont"""

PARAGRAPHS = (
    "movingpunch: a rigid punch sliding at a constant speed over an elastic "
    "layer on a Winkler foundation. Everything is dimensionless (h = 1, "
    "μ = 1) and the stresses are over P/h.",
    KEYS,
    TABS,
    INPUTS,
    "shape is the punch's shape: cylinder, flat, rounded_flat, or table (from "
    "a scene file). R/h is the cylinder's radius (a rounded flat's corners), "
    "b/h a flat face's half-width, P/(μh) the load and ν the layer's Poisson "
    "ratio. kw is the foundation's stiffness k_w h/μ (inf: a rigid base) and "
    "kp its Pasternak shear layer k_p/(μh) (0: springs alone). damp is the "
    "foundation's damping c_w c_T/μ >= 0 (dashpots; 0: the paper's model). "
    "fric is the Coulomb friction f in [0, 10] (0: frictionless). tol is the "
    "solver's tolerance. cont is the contact: auto finds the contact zones "
    "(several where a single contact would pull on the layer), single keeps "
    "one and refuses it when unphysical. train is a train of punches moving "
    "together, load@at items such as 0.002@-1.5, 0.002@1.5 (P/(μh) and x/h "
    "of each axis; empty: one punch of P/(μh)).",
    "A value is checked as you type and solved after a short pause in typing "
    "(about 200 ms), or at once on enter. A half-typed or invalid value never "
    "replaces the result on screen: its message names the input and the "
    "valid range, and the last result you saw stays.",
    "The gauge compares V* with the critical speed V*_cr(kw, ν, kp) and turns "
    "red above 95 %. With damping > 0 it compares V* with the Rayleigh speed "
    "V*_R (V* may exceed V*_cr); the summary then shows the contact (-b, a) "
    "and the drag over P, and the p(x), σx(x,0) and σx(0,y) tabs plot the "
    "asymmetric solution, while the a/h sweep, field and Accuracy tabs show a "
    "message instead. Damped solves take 0.4-1.5 s. Friction > 0 also gives "
    "an asymmetric contact, its end exponents and the friction force f P.",
    "Plausibility hints (one line, never blocking) say when a result leaves "
    "small-strain linear theory, δ/h > 0.05, a/h > 5 or a strain > 0.05, or "
    "when V* is within 1 % of its speed limit (V*_cr, or V*_R with damping).",
    "Files: open (o), save (s) and export (e) stay in the working folder "
    "(where the app started, or --root DIR); paths are relative to it and "
    "paths leading out are refused. Open takes a TOML file or a bundled "
    "scene's name. Open and save suggest the last file saved or opened "
    "(scene.toml at first), export suggests movingpunch-<tab>.csv. A saved "
    "scene keeps the a/h sweep as start, stop, points and spacing. Replacing "
    "an existing file asks first: enter again to overwrite, escape to cancel.",
    "Press escape, q, ? or F1 to close; arrows and page up/down scroll.",
)

HELP = "\n\n".join(PARAGRAPHS)
"""The help text: paragraphs on one line each (wrapped by the screen) and
tables of short lines."""


class HelpScreen(ModalScreen[None]):
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("escape,q,question_mark,f1", "dismiss_help", "Close"),
    ]

    def compose(self) -> ComposeResult:
        with VerticalScroll(id="help-box"):
            yield Static(HELP, id="help-text", markup=False)

    def action_dismiss_help(self) -> None:
        self.dismiss(None)
