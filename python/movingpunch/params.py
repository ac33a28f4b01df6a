"""Every user input in one table: its range, unit, meaning and default.

The API (``movingpunch.solve`` and the damped solve), scene validation, the
CLI's ``--help`` and the terminal UI's inputs all read their ranges and texts
from :data:`SPECS` and check values with :func:`check`, so a range is written
once. Pure Python: this module imports only ``movingpunch.errors`` (never
``_core``), so scenes, the CLI and the UI import it cheaply.

Every quantity is dimensionless (layer thickness h = 1, shear modulus mu = 1).
The speed bound vstar < V*_cr(kw, nu, kp) depends on kw, nu and kp: the core checks it
(SupercriticalSpeedError, whose ``parameter`` is ``"vstar"`` too).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass, fields
from types import MappingProxyType

from movingpunch.errors import InvalidParameterError

__all__ = [
    "CONTACT_MODES",
    "PRESETS",
    "SPECS",
    "Numerics",
    "ParamSpec",
    "check",
    "check_size",
    "help_text",
    "range_text",
]

PRESETS: Mapping[str, float] = MappingProxyType(
    {"draft": 1e-4, "default": 1e-8, "precise": 1e-12}
)
"""Named accuracies: preset name -> tol (relative tolerance on a/h). ``tol``
accepts a name wherever it accepts a number (solve, scene files, the CLI's
``--tol``, the terminal UI)."""


def _num(x: float) -> str:
    """A bound as written in a range: 0, 0.5, 1e-12, 1e12, inf."""
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if x == 0 or 0.1 <= abs(x) < 1e4:
        return f"{x:g}"
    mantissa, exponent = f"{x:.12e}".split("e")
    return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"


@dataclass(frozen=True)
class ParamSpec:
    """One input: ``lo``/``hi`` with open or closed ends; ``inf_ok``: +inf is a
    valid value (kw: the smooth rigid base). ``hi_text`` replaces ``hi`` in
    the text when the bound is not a number (vstar < V*_cr(kw, nu))."""

    name: str
    lo: float
    hi: float
    lo_open: bool
    hi_open: bool
    unit: str
    """The dimensionless group the number is (``R/h``), "" for a pure number."""
    meaning: str
    """One line: what the input is."""
    default: float | None
    """The API's default (None: required)."""
    inf_ok: bool = False
    hi_text: str = ""
    note: str = ""
    """Appended to the range in every text (presets, the meaning of inf)."""
    integer: bool = False
    symbol: str = ""
    """How ``describe()`` shows the value: ``"h_i/h ="`` gives
    ``h_i/h = 0.25``; "" gives the name and a space (``mu 1``)."""
    label: str = ""
    """The terminal UI's column heading ("" : the name)."""
    metavar: str = ""
    """The command line's name of the value in a comma-separated option
    (``--layer T,MU,NU``); "" : the name in capitals."""

    @property
    def shown_as(self) -> str:
        """The prefix of the value in ``describe()``."""
        return self.symbol or self.name

    @property
    def heading(self) -> str:
        """The terminal UI's heading of the input."""
        return self.label or self.name

    @property
    def cli_name(self) -> str:
        """The value's name in a comma-separated command-line option."""
        return self.metavar or self.name.upper()

    @property
    def range(self) -> str:
        """The bounds alone: ``0 < radius <= 1e12``."""
        if self.integer:
            lo, hi = _num(self.lo), _num(self.hi)
            return f"None (automatic) or an even integer in [{lo}, {hi}]"
        lo_op = "<" if self.lo_open else "<="
        hi_op = "<" if self.hi_open else "<="
        hi = self.hi_text or _num(self.hi)
        return f"{_num(self.lo)} {lo_op} {self.name} {hi_op} {hi}"

    @property
    def text(self) -> str:
        """The valid range as every message, help line and tooltip shows it:
        ``0 < radius <= 1e12, radius = R/h``."""
        out = self.range
        if self.note:
            out += f" {self.note}"
        if self.unit:
            out += f", {self.name} = {self.unit}"
        return out

    def contains(self, x: float) -> bool:
        """Whether the float ``x`` is in range (NaN never is)."""
        if math.isnan(x):
            return False
        if math.isinf(x):
            return self.inf_ok and x > 0
        above = x > self.lo if self.lo_open else x >= self.lo
        below = x < self.hi if self.hi_open else x <= self.hi
        return above and below


def _presets_note() -> str:
    return "(relative, on a/h), or a preset: " + ", ".join(
        f'"{name}" ({_num(tol)})' for name, tol in PRESETS.items()
    )


FRICTION_MAX = 10.0
"""Largest Coulomb friction coefficient taken (cpp/src/asymmetric.cpp validate):
real coefficients lie below about 2; at f = 10 the trailing end's exponent
is already below 0.08 (a near-jump of the pressure) and beyond it the
contact grows and the solve's cost with it (f = 100: minutes)."""

SIZE_MAX = 4096

PHYSICAL: tuple[str, ...] = (
    "vstar",
    "kw",
    "radius",
    "load",
    "nu",
    "damping",
    "kp",
    "friction",
)
"""The physical parameters of a point, in the order scenes write them (the
punch's shape beyond a cylinder's radius is a profile, not a number here)."""

OPTIONAL: tuple[str, ...] = ("damping", "kp", "friction")
"""The physical parameters that default to 0 (the paper's model: no dashpots,
springs alone, no friction); scenes and the TUI show them only when > 0."""
"""Largest collocation size n the undamped solver takes."""

SPECS: Mapping[str, ParamSpec] = MappingProxyType(
    {
        s.name: s
        for s in (
            ParamSpec(
                "vstar",
                0.0,
                math.inf,
                False,
                True,
                "rho V^2/mu",
                "speed of the punch",
                None,
                hi_text="V*_cr(kw, nu, kp)",
                note="(< V*_R(nu) with damping > 0)",
            ),
            ParamSpec(
                "kw",
                1e-12,
                math.inf,
                False,
                False,
                "k_w h/mu",
                "stiffness of the Winkler foundation",
                None,
                inf_ok=True,
                note="(inf: smooth rigid base)",
                symbol="kw =",
            ),
            ParamSpec(
                "kp",
                0.0,
                1e12,
                False,
                False,
                "k_p/(mu h)",
                "shear stiffness of a Pasternak layer on the springs "
                "(two-parameter foundation)",
                0.0,
                note="(0: Winkler springs alone)",
                symbol="kp =",
            ),
            ParamSpec(
                "radius", 0.0, 1e12, True, False, "R/h", "radius of the punch", None
            ),
            ParamSpec(
                "thickness",
                0.0,
                1.0,
                True,
                False,
                "h_i/h",
                "thickness of a sublayer (the sublayers' sum to 1)",
                None,
                symbol="h_i/h =",
                label="h_i/h",
                metavar="T",
            ),
            ParamSpec(
                "mu",
                0.0,
                1e12,
                True,
                False,
                "mu_i/mu_1",
                "shear modulus of a sublayer or the half-space, per the top's",
                1.0,
                note="(1 for the top sublayer)",
                label="μ/μ₁",
            ),
            ParamSpec(
                "rho",
                0.0,
                1e12,
                True,
                False,
                "rho_i/rho_1",
                "density of a sublayer or the half-space, per the top's",
                1.0,
                note="(1 for the top sublayer)",
                label="ρ/ρ₁",
            ),
            ParamSpec(
                "gamma_h",
                -50.0,
                50.0,
                False,
                False,
                "gamma h",
                "grading of a sublayer: mu and rho vary as exp(gamma y) from its top",
                None,
                note="(0: homogeneous)",
                symbol="gamma h =",
                label="gamma h",
            ),
            ParamSpec(
                "half_width",
                0.0,
                50.0,
                False,
                False,
                "b/h",
                "half-width of a flat punch's face (flat, rounded_flat profiles)",
                None,
                note="(>= 1e-10 for a flat punch; 0: a rounded flat is a cylinder)",
            ),
            ParamSpec(
                "load",
                0.0,
                1e6,
                True,
                False,
                "P/(mu h)",
                "load per unit length (the paper's mu/(P/h) = 1/load)",
                None,
            ),
            ParamSpec(
                "nu",
                0.0,
                0.5,
                False,
                True,
                "",
                "Poisson's ratio of the layer",
                0.2,
                label="ν",
            ),
            ParamSpec(
                "damping",
                0.0,
                math.inf,
                False,
                True,
                "c_w c_T/mu",
                "dashpots beside the foundation's springs (Kelvin-Voigt)",
                0.0,
                note="(0: no dashpots, the paper's model)",
                symbol="damping =",
            ),
            ParamSpec(
                "friction",
                0.0,
                FRICTION_MAX,
                False,
                False,
                "",
                "Coulomb friction coefficient between punch and layer (shear "
                "traction f p on the layer, in the direction of motion)",
                0.0,
                note="(0: frictionless, the paper's model)",
            ),
            ParamSpec(
                "tol",
                1e-14,
                1e-2,
                False,
                False,
                "",
                "relative tolerance on the contact half-width a/h",
                1e-8,
                note=_presets_note(),
            ),
            ParamSpec(
                "n",
                2,
                SIZE_MAX,
                False,
                False,
                "",
                "collocation size",
                None,
                integer=True,
            ),
            ParamSpec(
                "y",
                -1.0,
                0.0,
                False,
                False,
                "",
                "depth in the layer",
                0.0,
                note="(y/h, the layer)",
            ),
            ParamSpec(
                "extent",
                0.0,
                math.inf,
                True,
                True,
                "x/h",
                "half-length of the surface searched for stress peaks",
                None,
            ),
            ParamSpec("t", 0.0, math.inf, False, True, "alpha h", "wavenumber", None),
        )
    }
)
"""Every user input, by the name the API, scenes and the CLI use."""


def range_text(name: str) -> str:
    """``SPECS[name].text``: the valid range of ``name`` as every message,
    help line and tooltip shows it."""
    return SPECS[name].text


def help_text(name: str) -> str:
    """One line for ``--help`` and tooltips: meaning, range, default."""
    spec = SPECS[name]
    out = f"{spec.meaning}; {spec.text}"
    if spec.default is not None:
        out += f" (default {_num(spec.default)})"
    return out


def fail(name: str, message: str) -> InvalidParameterError:
    """An InvalidParameterError for ``name`` with its range as ``allowed``."""
    spec = SPECS.get(name)
    return InvalidParameterError(
        message, parameter=name, allowed=spec.text if spec else None
    )


def classify(name: str, value: object) -> tuple[float, str]:
    """``value`` as a float and what is wrong with it: "" (nothing),
    "type" (not a real number: bool, str, None, complex, ...), "overflow"
    (an integer beyond float range), "finite" (NaN or an infinity the
    range refuses) or "range". Presets and integers are not handled here."""
    spec = SPECS[name]
    if type(value) is float:  # the usual case, without the ABC's check
        x = value
    elif isinstance(value, bool) or not isinstance(value, numbers.Real):
        return math.nan, "type"
    else:
        try:
            x = float(value)
        except OverflowError:
            return math.nan, "overflow"
    if math.isnan(x) or (math.isinf(x) and not (spec.inf_ok and x > 0)):
        return x, "finite"
    return x, "" if spec.contains(x) else "range"


def check(name: str, value: object) -> float:
    """``value`` as a float if it is valid for ``name`` (a preset name too for
    ``tol``). Raises InvalidParameterError whose message names the parameter
    and its range, with ``parameter`` and ``allowed`` set."""
    spec = SPECS[name]
    if type(value) is float and spec.contains(value):  # the usual case, at once
        return value
    if name == "tol" and isinstance(value, str):
        preset = PRESETS.get(value.strip().lower())
        if preset is not None:
            return preset
        raise fail(name, f"tol must satisfy {spec.text}, got {value!r}")
    x, problem = classify(name, value)
    if problem == "type":
        raise fail(name, f"{name} must be a real number ({spec.text}), got {value!r}")
    if problem == "overflow":
        raise fail(name, f"{name} is too large for a float ({spec.text})")
    if problem == "finite":
        kind = "number" if spec.inf_ok else "finite number"
        raise fail(name, f"{name} must be a {kind} ({spec.text}), got {x!r}")
    if problem == "range":
        raise fail(name, f"{name} must satisfy {spec.text}, got {x!r}")
    return x


def check_size(value: object, most: int = SIZE_MAX, what: str = "") -> int:
    """The collocation size: None (automatic) -> 0, or an even int in
    [2, ``most``]. ``what`` is appended to the range in the message (the
    asymmetric solver takes at most 1024: " for the asymmetric solver")."""
    if value is None:
        return 0
    if not isinstance(value, bool) and isinstance(value, numbers.Integral):
        size = int(value)
        if 2 <= size <= most and size % 2 == 0:
            return size
    allowed = f"None (automatic) or an even integer in [2, {most}]"
    raise InvalidParameterError(
        f"n must be {allowed}{what}, got {value!r}", parameter="n", allowed=allowed
    )


CONTACT_MODES: tuple[str, ...] = ("auto", "single")
"""``contact=``: "auto" finds the contact set (several zones when the single
contact is unphysical), "single" keeps the single contact
(``movingpunch.zones.CONTACT_MODES``)."""


@dataclass(frozen=True)
class Numerics:
    """How a solve computes, as one value: ``tol`` (relative, on a/h, or a
    preset name: kept as the number), ``n`` (None: automatic, else an even
    collocation size), ``allow_unphysical`` and ``contact`` ("auto" or
    "single"), checked when made as ``movingpunch.solve`` checks its
    keywords of the same names (InvalidParameterError naming the parameter
    and its range). ``movingpunch.solve(..., numerics=Numerics(...))`` takes
    it instead of those keywords."""

    tol: float | str = 1e-8
    n: int | None = None
    allow_unphysical: bool = False
    contact: str = "auto"

    def __post_init__(self) -> None:
        object.__setattr__(self, "tol", check("tol", self.tol))
        check_size(self.n)
        if not isinstance(self.allow_unphysical, bool):
            raise InvalidParameterError(
                f"allow_unphysical must be True or False, got "
                f"{self.allow_unphysical!r}",
                parameter="allow_unphysical",
                allowed="True or False",
            )
        if not isinstance(self.contact, str) or self.contact not in CONTACT_MODES:
            allowed = " or ".join(f'"{m}"' for m in CONTACT_MODES)
            raise InvalidParameterError(
                f"contact must be {allowed}, got {self.contact!r}",
                parameter="contact",
                allowed=allowed,
            )

    def keywords(self, **given: object) -> tuple[float | str, int | None, bool, str]:
        """(tol, n, allow_unphysical, contact) for solve; ``given``: solve's
        keywords of those names as the call had them (giving one both ways,
        away from its default, is an InvalidParameterError naming it)."""
        for f in fields(self):
            value = given.get(f.name, f.default)
            if value is not f.default and value != f.default:
                raise InvalidParameterError(
                    f"{f.name}: the numerics are given by numerics= ({self!r}); "
                    f"give {f.name} there, not as a keyword too",
                    parameter=f.name,
                    allowed="omitted when numerics= is given",
                )
        return self.tol, self.n, self.allow_unphysical, self.contact


def numerics_keywords(
    numerics: object, **given: object
) -> tuple[float | str, int | None, bool, str]:
    """``numerics.keywords(**given)`` for a solve's ``numerics=`` argument,
    which must be a :class:`Numerics` (anything else: InvalidParameterError
    naming ``numerics``)."""
    if not isinstance(numerics, Numerics):
        raise InvalidParameterError(
            f"numerics must be a movingpunch.Numerics, got {numerics!r}",
            parameter="numerics",
            allowed="a movingpunch.Numerics(tol, n, allow_unphysical, contact)",
        )
    return numerics.keywords(**given)
