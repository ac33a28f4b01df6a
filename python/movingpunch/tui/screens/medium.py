"""The medium editor (key ``l`` on the main screen): the sublayers, top to
bottom, each a row of inputs (the fields of ``movingpunch.media``'s sublayer types:
thickness h_i/h, μ_i/μ_1, ν, ρ_i/ρ_1, gamma h; gamma h ≠ 0 makes it a graded
sublayer) over its material (elastic, or a Zener solid of modulus ratio
μ∞/μ₀ given by its deborah number Vτ/h or its relaxation time τ in h/c_T0; a
scene's Prony series is kept as loaded), the base (the springs of the panel,
or an elastic half-space bonded to the stack or in frictionless contact) and
the layer's inertia (on, or neglected: quasi-static, the panel's V* then
setting only a material's relaxation, deborah = √V* τ).

Every input is checked as it is typed, as the panel's are: a message names
the sublayer, the parameter and its valid range, and the editor is not
applied until every input holds a valid value and the thicknesses sum to 1
(ctrl+t scales them to). Enter applies the medium, escape leaves it as it
was."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Horizontal, Vertical, VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Footer, Input, Label, Select, Static

from movingpunch.errors import InvalidParameterError
from movingpunch.media import HalfSpace, Layer, Prony, Sublayer, Zener
from movingpunch.params import SPECS
from movingpunch.tui.model import (
    BASE_KINDS,
    HALF_SPACE_FIELDS,
    MATERIAL_KINDS,
    SUBLAYER_FIELDS,
    Params,
    check_thicknesses,
    fmt,
    material_of,
    normalised,
    parse_base,
    parse_material,
    parse_param,
    parse_sublayer,
)

MAX_SUBLAYERS = 8
"""The most sublayers the editor holds."""

HEADINGS: dict[str, str] = {
    name: SPECS[name].heading for name in (*SUBLAYER_FIELDS, *HALF_SPACE_FIELDS)
}
"""The column headings of the sublayer rows (and the half-space's): the
parameter table's labels (``movingpunch.params.SPECS``)."""


def box_width() -> int:
    """The editor's width: the sublayer number, an input (12 and a margin of
    1, app.tcss) per field of ``SUBLAYER_FIELDS`` and the frame (76 for
    five fields)."""
    return 6 + 5 + 13 * len(SUBLAYER_FIELDS)


BASE_LABELS: dict[str, str] = {
    "springs": "springs (kw, kp, damp)",
    "bonded": "bonded half-space",
    "smooth": "smooth half-space",
}


INERTIA_LABELS: dict[str, str] = {
    "on": "inertia on",
    "off": "quasi-static (inertia neglected)",
}


@dataclass(frozen=True)
class MediumChoice:
    """What the editor returns: the sublayers, the base (None: springs) and
    the layer's inertia."""

    layers: tuple[Sublayer, ...]
    half_space: HalfSpace | None
    inertia: bool = True


def _rows_of(params: Params) -> list[Sublayer]:
    return list(params.layers) or [Layer(1.0, nu=params.nu)]


MATERIAL_INPUTS = ("ratio", "time")
"""The material line's inputs: the modulus ratio and the deborah number or
relaxation time (by the selector)."""


class SublayerRow(Vertical):
    """One sublayer: its number and an input per ``SUBLAYER_FIELDS``, and
    under them its material (a selector, the modulus ratio and the time)."""

    def __init__(self, sub: Sublayer) -> None:
        super().__init__(classes="sublayer")
        self._sub = sub
        v = sub.viscoelastic if isinstance(sub, Layer) else None
        self._kept: Zener | Prony | None = v
        """A scene's Prony series (the selector's "prony" keeps it)."""

    def compose(self) -> ComposeResult:
        with Horizontal(classes="sublayer-row"):
            yield Label("", classes="sublayer-number")
            for name in SUBLAYER_FIELDS:
                value = float(getattr(self._sub, name))
                yield Input(
                    fmt(value, 10),
                    classes=f"medium-input f-{name}",
                    compact=True,
                    select_on_focus=False,
                )
        kind, ratio, time = material_of(self._sub)
        kinds = [
            (label, k)
            for k, label in MATERIAL_KINDS.items()
            if k != "prony" or isinstance(self._kept, Prony)
        ]
        with Horizontal(classes="material-row"):
            yield Label("", classes="sublayer-number")
            yield Select(
                kinds, value=kind, allow_blank=False, compact=True, classes="m-kind"
            )
            yield Label("μ∞/μ₀", classes="material-label")
            yield Input(
                ratio,
                classes="medium-input m-ratio",
                compact=True,
                select_on_focus=False,
            )
            yield Label("", classes="material-label m-time-label")
            yield Input(
                time, classes="medium-input m-time", compact=True, select_on_focus=False
            )
            yield Label("", classes="material-note")

    def on_mount(self) -> None:
        self.show_material()

    def box(self, name: str) -> Input:
        if name in MATERIAL_INPUTS:
            return self.query_one(f".m-{name}", Input)
        return self.query_one(f".f-{name}", Input)

    @property
    def material_kind(self) -> str:
        return str(self.query_one(".m-kind", Select).value)

    def show_material(self) -> None:
        """Shows the ratio and time inputs a Zener takes (the time's label by
        the selector) and a kept Prony series' description."""
        kind = self.material_kind
        zener = kind.startswith("zener")
        for name in MATERIAL_INPUTS:
            self.box(name).display = zener
        self.query_one(".m-ratio", Input).display = zener
        label = self.query_one(".m-time-label", Label)
        label.update("τ c/h" if kind == "zener-tau" else "Vτ/h")
        label.display = zener
        for lab in self.query(".material-label"):
            lab.display = zener
        note = self.query_one(".material-note", Label)
        kept = self._kept
        note.update(kept.describe() if kind == "prony" and kept is not None else "")

    def texts(self) -> dict[str, str]:
        return {name: self.box(name).value for name in SUBLAYER_FIELDS}

    def sublayer(self, row: int) -> Sublayer:
        """The sublayer typed (its fields and material); raises
        InvalidParameterError naming the row and the parameter."""
        sub = parse_sublayer(row, self.texts())
        material = parse_material(
            row,
            self.material_kind,
            self.box("ratio").value,
            self.box("time").value,
            self._kept,
        )
        if material is None:
            return sub
        if not isinstance(sub, Layer):
            raise InvalidParameterError(
                f"sublayer {row}: a graded sublayer (gamma h != 0) cannot be "
                "viscoelastic",
                parameter="viscoelastic",
                allowed="elastic, or gamma h = 0",
            )
        return replace(sub, viscoelastic=material)


class MediumEditor(ModalScreen[MediumChoice | None]):
    """The sublayer list and the base selector; dismisses with the medium
    (enter) or None (escape)."""

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("ctrl+n", "add_row", "Add sublayer", key_display="^n"),
        Binding("ctrl+r", "remove_row", "Remove", key_display="^r"),
        Binding("ctrl+t", "normalise", "Normalise h", key_display="^t"),
        Binding("ctrl+s", "apply", "Apply", key_display="enter"),
        Binding("escape", "cancel", "Cancel", key_display="esc"),
    ]

    def __init__(self, params: Params) -> None:
        super().__init__()
        self._params = params
        self.error = ""
        """The message shown (the first input at fault), "" when valid."""

    def compose(self) -> ComposeResult:
        hs = self._params.half_space or HalfSpace(1.0, self._params.nu)
        kind = "springs" if self._params.half_space is None else hs.interface
        with Vertical(classes="prompt-box", id="medium-box"):
            yield Label(
                "medium: sublayers top to bottom (bonded), then the base",
                classes="panel-title",
            )
            with Horizontal(classes="sublayer-row", id="medium-headings"):
                yield Label("#", classes="sublayer-number")
                for name in SUBLAYER_FIELDS:
                    yield Label(HEADINGS[name], classes="medium-heading")
            with VerticalScroll(id="sublayers"):
                for sub in _rows_of(self._params):
                    yield SublayerRow(sub)
            with Horizontal(id="base-row"):
                yield Label("base", classes="sublayer-number")
                yield Select(
                    [(BASE_LABELS[k], k) for k in BASE_KINDS],
                    value=kind,
                    allow_blank=False,
                    compact=True,
                    id="base-kind",
                )
            with Horizontal(classes="sublayer-row", id="half-space-row"):
                yield Label("", classes="sublayer-number")
                for name in HALF_SPACE_FIELDS:
                    yield Label(HEADINGS[name], classes="medium-heading-short")
                    yield Input(
                        fmt(float(getattr(hs, name)), 10),
                        classes=f"medium-input hs-{name}",
                        compact=True,
                        select_on_focus=False,
                    )
            with Horizontal(id="inertia-row"):
                yield Label("", classes="sublayer-number")
                yield Select(
                    [(label, k) for k, label in INERTIA_LABELS.items()],
                    value="on" if self._params.inertia else "off",
                    allow_blank=False,
                    compact=True,
                    id="inertia",
                )
            yield Static("", id="medium-msg")
            yield Footer(compact=True)

    def on_mount(self) -> None:
        self.query_one("#medium-box", Vertical).styles.width = box_width()
        self._renumber()
        self._show_base()
        self.validate()
        self.rows()[0].box("thickness").focus()

    # -- state --------------------------------------------------------------

    def rows(self) -> list[SublayerRow]:
        return list(self.query(SublayerRow))

    @property
    def base_kind(self) -> str:
        value = self.query_one("#base-kind", Select).value
        return str(value)

    def _renumber(self) -> None:
        for k, row in enumerate(self.rows(), start=1):
            row.query_one(".sublayer-number", Label).update(str(k))

    def _show_base(self) -> None:
        row = self.query_one("#half-space-row", Horizontal)
        row.display = self.base_kind != "springs"

    def _half_space_texts(self) -> dict[str, str]:
        return {
            name: self.query_one(f".hs-{name}", Input).value
            for name in HALF_SPACE_FIELDS
        }

    @property
    def inertia(self) -> bool:
        return str(self.query_one("#inertia", Select).value) == "on"

    def choice(self) -> MediumChoice:
        """The medium typed; raises InvalidParameterError naming the
        sublayer (or the half-space), the parameter and its range."""
        layers = [r.sublayer(k) for k, r in enumerate(self.rows(), 1)]
        half_space = parse_base(self.base_kind, self._half_space_texts())
        check_thicknesses(layers)
        return MediumChoice(tuple(layers), half_space, self.inertia)

    def validate(self) -> bool:
        """Marks every input holding an invalid value and shows the first
        error (or the medium's summary); whether the medium is valid."""
        for k, row in enumerate(self.rows(), start=1):
            for name in SUBLAYER_FIELDS:
                box = row.box(name)
                try:
                    parse_sublayer(k, {**row.texts(), name: box.value})
                except InvalidParameterError as exc:
                    bad = exc.parameter == name
                else:
                    bad = False
                box.set_class(bad, "-invalid")
            try:
                row.sublayer(k)
            except InvalidParameterError as exc:
                wrong = exc.parameter
            else:
                wrong = None
            row.box("ratio").set_class(wrong == "ratio", "-invalid")
            row.box("time").set_class(wrong in ("deborah", "tau"), "-invalid")
        for name in HALF_SPACE_FIELDS:
            box = self.query_one(f".hs-{name}", Input)
            try:
                parse_param(name, box.value)
            except InvalidParameterError:
                bad = self.base_kind != "springs"
            else:
                bad = False
            box.set_class(bad, "-invalid")
        msg = self.query_one("#medium-msg", Static)
        try:
            choice = self.choice()
        except InvalidParameterError as exc:
            self.error = " ".join(str(exc).split())
            msg.update(self.error)
            msg.add_class("-error")
            return False
        self.error = ""
        preview = replace(
            self._params,
            layers=choice.layers,
            half_space=choice.half_space,
            inertia=choice.inertia,
        )
        medium = preview.medium()
        assert medium is not None  # (layers given)
        text = medium.describe()
        msg.update(f"{text}; enter applies, escape cancels")
        msg.remove_class("-error")
        return True

    # -- events -------------------------------------------------------------

    def on_input_changed(self, event: Input.Changed) -> None:
        event.stop()
        self.validate()

    def on_select_changed(self, event: Select.Changed) -> None:
        event.stop()
        self._show_base()
        for row in self.rows():
            row.show_material()
        self.validate()

    def on_input_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        self.action_apply()

    def action_apply(self) -> None:
        if not self.validate():
            self.notify(self.error, severity="error")
            return
        self.dismiss(self.choice())

    def action_cancel(self) -> None:
        self.dismiss(None)

    def _focused_row(self) -> SublayerRow | None:
        node = self.focused
        while node is not None and not isinstance(node, SublayerRow):
            node = node.parent  # type: ignore[assignment]
        return node

    async def action_add_row(self) -> None:
        """A sublayer under the focused one (or at the bottom): half of its
        thickness moves to the new one, so the sum stays 1."""
        rows = self.rows()
        if len(rows) >= MAX_SUBLAYERS:
            self.notify(f"at most {MAX_SUBLAYERS} sublayers", severity="warning")
            return
        above = self._focused_row() or rows[-1]
        try:
            half = 0.5 * parse_param("thickness", above.box("thickness").value)
        except InvalidParameterError:
            half = 0.5
        texts = above.texts()
        try:
            nu = parse_param("nu", texts["nu"])
        except InvalidParameterError:
            nu = 0.2
        new = SublayerRow(Layer(half, nu=nu))
        await self.query_one("#sublayers", VerticalScroll).mount(new, after=above)
        above.box("thickness").value = fmt(half, 10)
        self._renumber()
        new.box("mu").focus()
        self.validate()

    async def action_remove_row(self) -> None:
        """Removes the focused sublayer (or the bottom one); its thickness
        goes to the one above it (the top's to the one below), so the sum
        stays 1. The last sublayer stays."""
        rows = self.rows()
        if len(rows) == 1:
            self.notify("the medium keeps at least one sublayer", severity="warning")
            return
        gone = self._focused_row() or rows[-1]
        k = rows.index(gone)
        heir = rows[k - 1] if k > 0 else rows[1]
        try:
            total = parse_param("thickness", gone.box("thickness").value) + parse_param(
                "thickness", heir.box("thickness").value
            )
        except InvalidParameterError:
            total = None
        await gone.remove()
        if total is not None and total <= 1.0:
            heir.box("thickness").value = fmt(total, 10)
        self._renumber()
        heir.box("thickness").focus()
        self.validate()

    def action_normalise(self) -> None:
        """Scales the thicknesses to sum to 1."""
        rows = self.rows()
        try:
            values = [parse_param("thickness", r.box("thickness").value) for r in rows]
            scaled = normalised(values)
        except InvalidParameterError as exc:
            self.notify(" ".join(str(exc).split()), severity="error")
            return
        for row, value in zip(rows, scaled, strict=True):
            row.box("thickness").value = repr(value) if value != 1.0 else "1"
        self.validate()
