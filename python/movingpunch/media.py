"""The medium under the punch: sublayers and a base (docs/media.md).

``movingpunch.solve(..., layers=[...], base=...)`` takes

* ``Layer(thickness, mu=1.0, nu=0.2, rho=1.0)``: a homogeneous sublayer;
* ``GradedLayer(gamma_h, nu=0.2, thickness=1.0, mu=1.0, rho=1.0)``: a sublayer
  whose shear modulus and density vary as exp(gamma y) from its top value
  (y up; gamma > 0: softer with depth; the wave speeds stay constant);

listed top to bottom and bonded (u, v, tau_xy, sigma_y continuous), on

* ``Winkler(kw, kp=0.0, damping=0.0)``: springs (a Pasternak shear layer with
  kp > 0, dashpots with damping > 0); ``kw=inf`` is a smooth rigid base;
  ``solve(kw=..., kp=..., damping=...)`` is its shorthand;
* ``HalfSpace(mu, nu, rho=1.0, interface="bonded")``: an elastic substrate,
  bonded or in frictionless contact (``interface="smooth"``).

Units are those of the TOP sublayer: lengths per the total thickness h (the
thicknesses sum to 1), moduli and densities per the top sublayer's mu_1 and
rho_1 (so its ``mu`` and ``rho`` are 1), vstar = rho_1 V^2/mu_1, kw = k_w h/mu_1.
Every value type is frozen and checked when made (InvalidParameterError names
the parameter and its range); ``Medium`` is the resolved pair a solve uses.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from movingpunch import _core, params
from movingpunch.errors import InvalidParameterError

__all__ = [
    "BASE_TYPES",
    "SUBLAYER_TYPES",
    "GradedLayer",
    "HalfSpace",
    "Layer",
    "Medium",
    "Prony",
    "ValueType",
    "Viscoelastic",
    "Winkler",
    "Zener",
    "material_from_dict",
    "resolve_medium",
]

INTERFACES = ("bonded", "smooth")

FloatArray = npt.NDArray[np.float64]


def _check(name: str, value: object, what: str) -> float:
    """``value`` checked against the parameter table's ``name`` range, the
    message naming ``what`` (e.g. "Layer.mu")."""
    try:
        return params.check(name, value)
    except InvalidParameterError as err:
        raise InvalidParameterError(
            f"{what}: {err}", parameter=name, allowed=err.allowed
        ) from None


class ValueType:
    """The field table of a medium's value type: everything that reads or
    writes one (its checks, ``describe()``, ``to_dict()``, ``core_args()``,
    scene files, the command line's --layer/--graded/--half-space and the
    terminal UI's medium editor) iterates over these class attributes, and
    each scalar's range, unit, meaning and texts come from
    ``movingpunch.params.SPECS`` under the same name. A new scalar parameter
    of a medium is a dataclass field, its name in ``FIELDS`` and its row in
    ``SPECS`` (docs/media.md, "The value types' fields")."""

    KIND: ClassVar[str]
    """The type's ``kind`` in scene files and ``to_dict()``."""
    FIELDS: ClassVar[tuple[str, ...]]
    """The scalar fields, in the order scenes, ``to_dict()``, ``describe()``
    and the terminal UI show them; each is a key of ``params.SPECS``."""
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {}
    """Fields that take one of a few words (a half-space's ``interface``)."""
    MATERIALS: ClassVar[tuple[str, ...]] = ()
    """Fields that hold a material value (a layer's ``viscoelastic``: a
    ``Zener`` or ``Prony``, or None), not a scalar: ``describe()`` and
    ``to_dict()`` show them; the core takes them as its ``materials=``."""
    CLI: ClassVar[tuple[str, ...]] = ()
    """The positions of the command line's comma-separated values (empty:
    not an option of its own)."""
    CLI_REQUIRED: ClassVar[int] = 0
    """How many leading ``CLI`` positions are required."""
    CLI_TOGETHER: ClassVar[tuple[str, ...]] = ()
    """Optional ``CLI`` positions given all or none."""
    TITLE: ClassVar[str] = "{fields}"
    """``describe()``: ``{fields}`` and each of ``CHOICES`` filled in."""
    ROW: ClassVar[tuple[str, ...]] = ()
    """The core's row of this type (``row()``): the names of its C++ field
    table (empty: the core takes no row of it)."""

    def __post_init__(self) -> None:
        cls = type(self).__name__
        for name in self.FIELDS:
            value = _check(name, getattr(self, name), f"{cls}.{name}")
            object.__setattr__(self, name, value)
        for name, words in self.CHOICES.items():
            value = getattr(self, name)
            if value not in words:
                allowed = " or ".join(repr(w) for w in words)
                raise InvalidParameterError(
                    f"{cls}.{name} must be {allowed}, got {value!r}",
                    parameter=name,
                    allowed=allowed,
                )

    @classmethod
    def default(cls, name: str) -> Any:
        """The default of field ``name`` (``dataclasses.MISSING``: required)."""
        for f in dataclasses.fields(cls):  # type: ignore[arg-type]
            if f.name == name:
                return f.default
        raise KeyError(name)

    @classmethod
    def required(cls) -> tuple[str, ...]:
        """The fields without a default, in ``FIELDS`` order."""
        return tuple(
            n
            for n in (*cls.FIELDS, *cls.CHOICES)
            if cls.default(n) is dataclasses.MISSING
        )

    def describe(self) -> str:
        """One line: each field as ``params.SPECS`` shows it; a field at a
        default of 0 (a term switched off: kp, damping) is left out."""
        shown = []
        for name in self.FIELDS:
            value = float(getattr(self, name))
            if value == 0.0 and self.default(name) == 0.0:
                continue
            shown.append(f"{params.SPECS[name].shown_as} {value:g}")
        words = {name: getattr(self, name) for name in self.CHOICES}
        return self.TITLE.format(fields=", ".join(shown), **words)

    def row(self) -> tuple[float, ...]:
        """The values of ``ROW``, as the core takes them (``layers=`` rows,
        ``half_space=``)."""
        return tuple(float(getattr(self, n)) for n in self.ROW)

    def to_dict(self) -> dict[str, object]:
        """``kind`` and every field, as a scene's table holds them."""
        out: dict[str, object] = {"kind": self.KIND}
        out.update((name, getattr(self, name)) for name in self.FIELDS)
        out.update((name, getattr(self, name)) for name in self.CHOICES)
        return out


def _material_number(
    value: object, what: str, lo: float, hi: float, parameter: str = ""
) -> float:
    """``value`` as a finite float in [lo, hi], or InvalidParameterError whose
    message names ``what`` (e.g. "Prony.weights[1]") and whose parameter is
    ``parameter`` (default: ``what``'s last name, "weights")."""
    name = parameter or what.rsplit(".", 1)[-1].split("[")[0]
    allowed = f"a finite number in [{lo:g}, {hi:g}]"
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)):
        raise InvalidParameterError(
            f"{what} must be a number, got {value!r}", parameter=name, allowed=allowed
        )
    v = float(value)
    if not (math.isfinite(v) and lo <= v <= hi):
        raise InvalidParameterError(
            f"{what} must be in [{lo:g}, {hi:g}], got {v!r}",
            parameter=name,
            allowed=allowed,
        )
    return v


MAX_VISCO_RATIO = 1e6
"""The largest mu_inf/mu_0 of a viscoelastic material (the core's kMaxViscoRatio)."""
MAX_DEBORAH = 1e12
"""The largest deborah number V tau/h of a branch (the core's kMaxDeborah; the
smallest non-zero one is MIN_DEBORAH, 0 relaxes the branch at once)."""
MIN_DEBORAH = 1e-12
"""The smallest non-zero deborah number (times the shift) of a branch (the
core's kMinDeborah)."""


def _speed_deborah(tau: float, vstar: float, what: str) -> float:
    """The deborah number V tau/h = sqrt(vstar) tau* of a relaxation time
    tau* = tau c_T0/h at the speed vstar (InvalidParameterError naming vstar
    beyond MAX_DEBORAH)."""
    d = math.sqrt(vstar) * tau
    if d != 0.0 and not MIN_DEBORAH <= d <= MAX_DEBORAH:
        raise InvalidParameterError(
            f"vstar = {vstar!r} gives {what} a deborah number sqrt(vstar) tau = "
            f"{d:.6g}, outside [{MIN_DEBORAH:g}, {MAX_DEBORAH:g}] (the solver's "
            "range; 0, at rest, relaxes it at once)",
            parameter="vstar",
            allowed=f"vstar = 0 or {MIN_DEBORAH:g} <= sqrt(vstar) tau <= "
            f"{MAX_DEBORAH:g}",
        )
    return d


def _deborah_floor(d: float, what: str, parameter: str) -> None:
    """0 or at least MIN_DEBORAH (the core's range), else InvalidParameterError."""
    if 0.0 < d < MIN_DEBORAH:
        raise InvalidParameterError(
            f"{what} = {d!r} is below {MIN_DEBORAH:g}, the smallest the solver "
            "takes (0 relaxes the branch at once: the relaxed layer)",
            parameter=parameter,
            allowed=f"0 or [{MIN_DEBORAH:g}, {MAX_DEBORAH:g}]",
        )


def _unresolved(what: str) -> InvalidParameterError:
    return InvalidParameterError(
        f"{what} is given by its relaxation time tau (in units of h/c_T0): its "
        "deborah number sqrt(vstar) tau needs the speed (solve() resolves it; "
        "at_speed(vstar) gives the material at a speed)",
        parameter="tau",
        allowed="a material at a speed (at_speed(vstar)) or given by deborah",
    )


@dataclass(frozen=True)
class Zener:
    """A standard linear solid in shear (docs/theory.md section 17): the
    relaxed modulus mu_0 is the sublayer's ``mu``, the unrelaxed one
    mu_inf = ``ratio`` mu_0 (ratio >= 1; 1 is elastic), relaxing with the time
    tau at constant strain. Give ``deborah`` = V tau/h (the material at one
    speed; 0: relaxed at once, the elastic layer of mu_0), or ``tau`` = the
    relaxation time in units of h/c_T0 (c_T0 = sqrt(mu_0/rho) of the top
    sublayer): the material itself, whose deborah number sqrt(vstar) tau
    follows the speed of each solve (a speed sweep of one material). Solved
    quasi-statically: ``vstar=0``, or ``inertia=False`` with a ``tau``
    (the speed then sets the relaxation only)."""

    ratio: float
    deborah: float | None = None
    tau: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(
            self,
            "ratio",
            _material_number(self.ratio, "Zener.ratio", 1.0, MAX_VISCO_RATIO),
        )
        if (self.deborah is None) == (self.tau is None):
            raise InvalidParameterError(
                "Zener: give one of deborah (V tau/h, at one speed) and tau (the "
                f"relaxation time in h/c_T0), got deborah={self.deborah!r}, "
                f"tau={self.tau!r}",
                parameter="deborah" if self.deborah is None else "tau",
                allowed="exactly one of deborah and tau",
            )
        for name in ("deborah", "tau"):
            value = getattr(self, name)
            if value is not None:
                checked = _material_number(value, f"Zener.{name}", 0.0, MAX_DEBORAH)
                object.__setattr__(self, name, checked)
        if self.deborah is not None:
            _deborah_floor(self.deborah, "Zener.deborah", "deborah")

    @property
    def speed_dependent(self) -> bool:
        """Given by its relaxation time (``tau``): its deborah number follows
        the speed (``at_speed``)."""
        return self.tau is not None

    @property
    def relaxes(self) -> bool:
        """It relaxes in time at a speed > 0 (ratio > 1 and a time > 0)."""
        time = self.deborah if self.deborah is not None else self.tau
        return self.ratio != 1.0 and bool(time)

    def at_speed(self, vstar: float) -> Zener:
        """The material at the speed vstar (deborah = sqrt(vstar) tau); itself
        when given by deborah."""
        if self.tau is None:
            return self
        return Zener(self.ratio, _speed_deborah(self.tau, vstar, "Zener.tau"))

    def branches(self) -> tuple[tuple[float, ...], tuple[float, ...], float]:
        """(weights, deborah numbers, shift) of its generalised Maxwell form:
        one branch of weight ratio - 1 (none when elastic)."""
        if self.deborah is None:
            raise _unresolved("Zener(tau=...)")
        if self.ratio == 1.0 or self.deborah == 0.0:
            return (), (), 1.0
        return (self.ratio - 1.0,), (self.deborah,), 1.0

    def modulus(self, t: npt.ArrayLike) -> npt.NDArray[np.complex128]:
        """mu(omega)/mu_0 at t = alpha h (omega = alpha V; time factor
        e^{-i omega t}: Im < 0, a loss): (1 - i ratio deborah t)/(1 - i deborah t)."""
        return _modulus(self.branches(), t)

    def describe(self) -> str:
        if self.tau is not None:
            return f"Zener ratio {self.ratio:g}, tau {self.tau:g} h/c_T0"
        return f"Zener ratio {self.ratio:g}, deborah {self.deborah:g}"

    def to_dict(self) -> dict[str, object]:
        time = "deborah" if self.tau is None else "tau"
        return {"kind": "zener", "ratio": self.ratio, time: getattr(self, time)}


def _material_numbers(
    value: object, what: str, lo: float, hi: float
) -> tuple[float, ...]:
    if isinstance(value, (str, bytes)) or not isinstance(value, (Sequence, np.ndarray)):
        name = what.rsplit(".", 1)[-1]
        raise InvalidParameterError(
            f"{what} must be a sequence of numbers, got {value!r}",
            parameter=name,
            allowed="a sequence of numbers",
        )
    return tuple(
        _material_number(v, f"{what}[{i}]", lo, hi) for i, v in enumerate(value)
    )


@dataclass(frozen=True)
class Prony:
    """A generalised Maxwell solid in shear (a Prony series, as measured
    master curves are given): mu(omega)/mu_0 = 1 + sum_j weights_j
    (-i omega tau_j)/(1 - i omega tau_j), with ``deborahs`` = V tau_j/h at the
    reference temperature (the material at one speed), or ``taus`` = tau_j in
    units of h/c_T0 (the material itself: deborah_j = sqrt(vstar) tau_j at
    each solve's speed), and ``shift`` = a_T, the time-temperature shift
    factor applied to every tau_j. mu_inf/mu_0 = 1 + sum of the weights."""

    weights: tuple[float, ...]
    deborahs: tuple[float, ...] | None = None
    shift: float = 1.0
    taus: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        w = _material_numbers(self.weights, "Prony.weights", 0.0, MAX_VISCO_RATIO - 1.0)
        if (self.deborahs is None) == (self.taus is None):
            raise InvalidParameterError(
                "Prony: give one of deborahs (V tau_j/h, at one speed) and taus "
                "(the relaxation times in h/c_T0)",
                parameter="deborahs" if self.deborahs is None else "taus",
                allowed="exactly one of deborahs and taus",
            )
        name = "deborahs" if self.taus is None else "taus"
        d = _material_numbers(getattr(self, name), f"Prony.{name}", 0.0, MAX_DEBORAH)
        if len(w) != len(d) or not w:
            raise InvalidParameterError(
                f"Prony: {len(w)} weights and {len(d)} {name}; give one "
                "relaxation time per branch, at least one branch",
                parameter=name,
                allowed=f"as many {name} as weights, at least one",
            )
        if any(v <= 0.0 for v in w):
            raise InvalidParameterError(
                f"Prony.weights must be > 0, got {w!r}",
                parameter="weights",
                allowed=f"(0, {MAX_VISCO_RATIO - 1:g}]",
            )
        shift = _material_number(self.shift, "Prony.shift", 0.0, 1e12)
        if shift <= 0.0:
            raise InvalidParameterError(
                f"Prony.shift must be > 0, got {shift!r}",
                parameter="shift",
                allowed="(0, 1e12]",
            )
        if name == "deborahs":
            for i, v in enumerate(d):
                _deborah_floor(v * shift, f"Prony.deborahs[{i}] * shift", "deborahs")
        object.__setattr__(self, "weights", w)
        object.__setattr__(self, name, d)
        object.__setattr__(self, "shift", shift)

    @property
    def speed_dependent(self) -> bool:
        """Given by its relaxation times (``taus``): its deborah numbers follow
        the speed (``at_speed``)."""
        return self.taus is not None

    @property
    def relaxes(self) -> bool:
        """A branch relaxes in time at a speed > 0 (a time > 0)."""
        times = self.deborahs if self.deborahs is not None else self.taus
        return any(t > 0 for t in times or ())

    def at_speed(self, vstar: float) -> Prony:
        """The material at the speed vstar (deborahs = sqrt(vstar) taus);
        itself when given by deborahs."""
        if self.taus is None:
            return self
        d = tuple(_speed_deborah(t, vstar, "Prony.taus") for t in self.taus)
        try:
            return Prony(self.weights, d, self.shift)
        except InvalidParameterError as exc:  # the shift times a deborah number
            raise InvalidParameterError(
                f"vstar = {vstar!r}: {exc}",
                parameter="vstar",
                allowed=f"vstar = 0 or shift sqrt(vstar) tau_j in "
                f"[{MIN_DEBORAH:g}, {MAX_DEBORAH:g}]",
            ) from None

    def branches(self) -> tuple[tuple[float, ...], tuple[float, ...], float]:
        """(weights, deborah numbers, shift) of the branches that relax in
        time, as the core takes them (a branch of deborah 0 relaxes at once
        and adds nothing at any frequency; none left: elastic)."""
        if self.deborahs is None:
            raise _unresolved("Prony(taus=...)")
        kept = [
            (w, d) for w, d in zip(self.weights, self.deborahs, strict=True) if d > 0
        ]
        return tuple(w for w, _ in kept), tuple(d for _, d in kept), self.shift

    def modulus(self, t: npt.ArrayLike) -> npt.NDArray[np.complex128]:
        """mu(omega)/mu_0 at t = alpha h (omega = alpha V; e^{-i omega t})."""
        return _modulus(self.branches(), t)

    def describe(self) -> str:
        given = "" if self.taus is None else " (taus in h/c_T0)"
        return f"Prony {len(self.weights)} branches{given}, shift {self.shift:g}"

    def to_dict(self) -> dict[str, object]:
        name = "deborahs" if self.taus is None else "taus"
        return {
            "kind": "prony",
            "weights": list(self.weights),
            name: list(getattr(self, name)),
            "shift": self.shift,
        }


Viscoelastic = Zener | Prony

MATERIAL_KEYS: dict[str, tuple[str, ...]] = {
    "zener": ("kind", "ratio", "deborah", "tau"),
    "prony": ("kind", "weights", "deborahs", "taus", "shift"),
}
"""A material's keys in a scene (``viscoelastic = { kind = "zener", ... }``)."""


def material_from_dict(raw: object, where: str) -> Zener | Prony:
    """The material of ``to_dict()``'s table (a scene's ``viscoelastic``):
    ``kind`` "zener" (ratio, deborah) or "prony" (weights, deborahs, shift);
    InvalidParameterError naming ``where`` and the key otherwise."""
    kinds = " or ".join(f'"{k}"' for k in MATERIAL_KEYS)
    if not isinstance(raw, Mapping):
        raise InvalidParameterError(
            f"{where} must be a table with kind {kinds}, got {raw!r}",
            parameter="viscoelastic",
            allowed=f"a table with kind {kinds}",
        )
    kind = raw.get("kind")
    if kind not in MATERIAL_KEYS:
        raise InvalidParameterError(
            f"{where}.kind must be {kinds}, got {kind!r}",
            parameter="kind",
            allowed=kinds,
        )
    for key in raw:
        if key not in MATERIAL_KEYS[kind]:
            raise InvalidParameterError(
                f"{where}.{key}: unknown key of a {kind} material",
                parameter=str(key),
                allowed=", ".join(MATERIAL_KEYS[kind]),
            )
    required, times = (
        ("ratio", ("deborah", "tau"))
        if kind == "zener"
        else ("weights", ("deborahs", "taus"))
    )
    if required not in raw:
        raise InvalidParameterError(
            f"{where}.{required}: missing",
            parameter=required,
            allowed=", ".join(MATERIAL_KEYS[kind]),
        )
    given = [t for t in times if t in raw]
    if len(given) != 1:
        raise InvalidParameterError(
            f"{where}: give one of {times[0]} (at one speed) and {times[1]} (the "
            f"relaxation time in h/c_T0), got {', '.join(given) or 'neither'}",
            parameter=times[0] if not given else times[1],
            allowed=f"exactly one of {times[0]} and {times[1]}",
        )
    if kind == "zener":
        return Zener(raw["ratio"], raw.get("deborah"), raw.get("tau"))
    return Prony(
        raw["weights"], raw.get("deborahs"), raw.get("shift", 1.0), raw.get("taus")
    )


def _modulus(
    branches: tuple[tuple[float, ...], tuple[float, ...], float], t: npt.ArrayLike
) -> npt.NDArray[np.complex128]:
    weights, deborahs, shift = branches
    tt = np.asarray(t, dtype=np.float64)
    m = np.ones(tt.shape, dtype=np.complex128)
    for g, d in zip(weights, deborahs, strict=True):
        z = -1j * tt * d * shift
        m = m + g * z / (1.0 + z)
    return m


SUBLAYER_ROW: tuple[str, ...] = tuple(_core.SUBLAYER_FIELDS)
"""A sublayer's row as the core takes it (``_core`` ``layers=``): the C++
``Sublayer``'s field table (cpp/include/movingpunch/medium.hpp
``kSublayerFields``), whose names are those of the value types' fields."""

HALF_SPACE_ROW: tuple[str, ...] = tuple(_core.HALF_SPACE_FIELDS)
"""A half-space's row as the core takes it (``_core`` ``half_space=``): the
C++ ``BaseSpec``'s half-space field table (``kHalfSpaceFields``)."""


@dataclass(frozen=True)
class Layer(ValueType):
    """A homogeneous sublayer: ``thickness`` (h_i/h in (0, 1]), shear modulus
    ``mu`` and density ``rho`` per the top sublayer's (1 for the top), and
    Poisson's ratio ``nu`` in [0, 0.5)."""

    thickness: float = 1.0
    mu: float = 1.0
    nu: float = 0.2
    rho: float = 1.0
    viscoelastic: Zener | Prony | None = None
    """A viscoelastic material (``Zener`` or ``Prony``; None: elastic): ``mu``
    is then its relaxed modulus mu_0."""

    KIND: ClassVar[str] = "layer"
    FIELDS: ClassVar[tuple[str, ...]] = ("thickness", "mu", "nu", "rho")
    MATERIALS: ClassVar[tuple[str, ...]] = ("viscoelastic",)
    CLI: ClassVar[tuple[str, ...]] = ("thickness", "mu", "nu", "rho")
    CLI_REQUIRED: ClassVar[int] = 3
    TITLE: ClassVar[str] = "layer {fields}"

    ROW: ClassVar[tuple[str, ...]] = SUBLAYER_ROW

    def __post_init__(self) -> None:
        super().__post_init__()
        v = self.viscoelastic
        if v is not None and not isinstance(v, (Zener, Prony)):
            raise InvalidParameterError(
                f"Layer.viscoelastic must be movingpunch.Zener(...), Prony(...) or "
                f"None, got {v!r}",
                parameter="viscoelastic",
                allowed="Zener(ratio, deborah), Prony(weights, deborahs, shift), None",
            )

    @property
    def gamma_h(self) -> float:
        return 0.0

    @property
    def elastic(self) -> bool:
        """No viscoelastic branch (none given, or a Zener of ratio 1 or deborah 0)."""
        return self.viscoelastic is None or not self.viscoelastic.relaxes

    def at_speed(self, vstar: float) -> Layer:
        """This sublayer with its material at the speed vstar (``Zener.at_speed``)."""
        v = self.viscoelastic
        at = v if v is None else v.at_speed(vstar)
        return self if at is v else dataclasses.replace(self, viscoelastic=at)

    def describe(self) -> str:
        text = super().describe()
        if self.viscoelastic is not None:
            text += f", {self.viscoelastic.describe()}"
        return text

    def to_dict(self) -> dict[str, object]:
        out = super().to_dict()
        if self.viscoelastic is not None:
            out["viscoelastic"] = self.viscoelastic.to_dict()
        return out


@dataclass(frozen=True)
class GradedLayer(ValueType):
    """An exponentially graded sublayer: mu(y) = mu exp(gamma_h (y - y_top)/h)
    and rho likewise (y up, so gamma_h > 0 softens with depth; the wave speeds
    are constant). ``mu``, ``rho``: the values at its top, per the top
    sublayer's (1 when it is the top sublayer)."""

    gamma_h: float
    nu: float = 0.2
    thickness: float = 1.0
    mu: float = 1.0
    rho: float = 1.0

    KIND: ClassVar[str] = "graded"
    FIELDS: ClassVar[tuple[str, ...]] = ("thickness", "gamma_h", "mu", "nu", "rho")
    CLI: ClassVar[tuple[str, ...]] = ("thickness", "gamma_h", "nu", "mu", "rho")
    CLI_REQUIRED: ClassVar[int] = 3
    CLI_TOGETHER: ClassVar[tuple[str, ...]] = ("mu", "rho")
    TITLE: ClassVar[str] = "graded layer {fields} at its top"
    ROW: ClassVar[tuple[str, ...]] = SUBLAYER_ROW


Sublayer = Layer | GradedLayer

SUBLAYER_TYPES: tuple[type[Layer] | type[GradedLayer], ...] = (Layer, GradedLayer)
"""The kinds of sublayer, the homogeneous first."""


@dataclass(frozen=True)
class Winkler(ValueType):
    """Springs under the stack: ``kw`` = k_w h/mu_1 (inf: a smooth rigid
    base), a Pasternak shear layer ``kp`` = k_p/(mu_1 h), dashpots
    ``damping`` = c_w c_T/mu_1."""

    kw: float
    kp: float = 0.0
    damping: float = 0.0

    KIND: ClassVar[str] = "winkler"
    FIELDS: ClassVar[tuple[str, ...]] = ("kw", "kp", "damping")


@dataclass(frozen=True)
class HalfSpace(ValueType):
    """An elastic half-space under the stack: ``mu``, ``rho`` per the top
    sublayer's, Poisson's ratio ``nu``; ``interface`` "bonded" (u, v, tau,
    sigma_y continuous) or "smooth" (frictionless contact: tau = 0)."""

    mu: float
    nu: float
    rho: float = 1.0
    interface: str = "bonded"

    KIND: ClassVar[str] = "half_space"
    FIELDS: ClassVar[tuple[str, ...]] = ("mu", "nu", "rho")
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {"interface": INTERFACES}
    CLI: ClassVar[tuple[str, ...]] = ("mu", "nu", "rho")
    CLI_REQUIRED: ClassVar[int] = 2
    TITLE: ClassVar[str] = "{interface} half-space ({fields})"
    ROW: ClassVar[tuple[str, ...]] = HALF_SPACE_ROW


Base = Winkler | HalfSpace

BASE_TYPES: tuple[type[Winkler] | type[HalfSpace], ...] = (Winkler, HalfSpace)
"""The kinds of base."""

CLI_OPTIONS: dict[str, str] = {
    "layer": "--layer",
    "graded": "--graded",
    "half_space": "--half-space",
    "winkler": "--kw, --kp, --damping",
}
"""The command line's option of each kind (movingpunch._cli_media)."""


def fields_table() -> str:
    """The value types' fields as a Markdown table (docs/media.md holds it
    verbatim; tests/python/test_param_table.py checks it)."""
    lines = [
        "| type (scene `kind`) | field (scene key) | CLI | TUI | range, unit "
        "| default | meaning |",
        "|---|---|---|---|---|---|---|",
    ]
    for cls in (*SUBLAYER_TYPES, *BASE_TYPES):
        for name in (*cls.FIELDS, *cls.CHOICES):
            default = cls.default(name)
            if default is dataclasses.MISSING:
                shown = "required"
            else:
                shown = f'"{default}"' if isinstance(default, str) else f"{default:g}"
            if name in cls.CHOICES:
                rng = " or ".join(f'"{w}"' for w in cls.CHOICES[name])
                meaning = "the interface with the stack (smooth: frictionless)"
                cli, tui = "a last word", "the base selector"
            else:
                spec = params.SPECS[name]
                rng, meaning, tui = spec.text, spec.meaning, spec.heading
                cli = (
                    f"{CLI_OPTIONS[cls.KIND]} {spec.cli_name}"
                    if name in cls.CLI
                    else f"--{name}"
                )
                if cls is Winkler:
                    tui = f"panel: {name}"
            lines.append(
                f"| {cls.__name__} (`{cls.KIND}`) | `{name}` | `{cli}` | {tui} | "
                f"{rng.replace('|', '/')} | {shown} | {meaning} |"
            )
    return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class Medium:
    """The resolved medium of a solve: its sublayers (top to bottom) and its
    base. ``homogeneous``: one homogeneous sublayer on springs (the paper's
    layer, solved exactly as ``kw=``/``nu=`` are). ``inertia`` False: its
    inertia neglected (quasi-static; the speed vstar then only sets the
    relaxation of the materials given by ``tau``: ``solve(inertia=False)``)."""

    layers: tuple[Sublayer, ...]
    base: Base
    inertia: bool = True

    @property
    def speed_dependent(self) -> bool:
        """A material is given by its relaxation times (``tau``/``taus``):
        its deborah numbers follow the speed (``at_speed``)."""
        return any(
            isinstance(s, Layer)
            and s.viscoelastic is not None
            and s.viscoelastic.speed_dependent
            for s in self.layers
        )

    def at_speed(self, vstar: float) -> Medium:
        """The medium with every material at the speed vstar (deborah =
        sqrt(vstar) tau); itself when none is given by tau."""
        layers = tuple(
            s.at_speed(vstar) if isinstance(s, Layer) else s for s in self.layers
        )
        if all(a is b for a, b in zip(layers, self.layers, strict=True)):
            return self
        return dataclasses.replace(self, layers=layers)

    @property
    def homogeneous(self) -> bool:
        return (
            len(self.layers) == 1
            and isinstance(self.layers[0], Layer)
            and self.layers[0].elastic
            and isinstance(self.base, Winkler)
        )

    @property
    def viscoelastic(self) -> bool:
        """A sublayer has a viscoelastic material (with a branch)."""
        return any(isinstance(s, Layer) and not s.elastic for s in self.layers)

    @property
    def beyond_critical(self) -> bool:
        """Steady contacts exist beyond V*_cr, up to the top's Rayleigh speed
        V*_R: one viscoelastic layer on springs with its inertia (it dissipates
        at every wavenumber but 0 and infinity: no free steady wave;
        docs/theory.md section 17.9)."""
        return (
            self.inertia
            and self.viscoelastic
            and len(self.layers) == 1
            and isinstance(self.base, Winkler)
        )

    @property
    def nu(self) -> float:
        """Poisson's ratio of the top sublayer (its half-plane constants)."""
        return self.layers[0].nu

    @property
    def interfaces(self) -> tuple[float, ...]:
        """Depths y/h of the interfaces between sublayers, top to bottom
        (strictly inside (-1, 0)); empty for one sublayer."""
        out: list[float] = []
        depth = 0.0
        for s in self.layers[:-1]:
            depth -= s.thickness
            out.append(depth)
        return tuple(out)

    def material(
        self, y: npt.ArrayLike, below: bool = False
    ) -> tuple[FloatArray, FloatArray]:
        """(mu, nu) per the top sublayer's mu at each depth y/h in [-1, 0]: at
        an interface (within 1e-12 h) the material above it, or below it when
        ``below``; at y = -1 with ``below`` the half-space's (springs: the
        bottom sublayer's)."""
        ys = np.asarray(y, dtype=np.float64)
        mu = np.empty(ys.shape)
        nu = np.empty(ys.shape)
        tops = [0.0, *self.interfaces]
        for idx, yv in np.ndenumerate(ys):
            i = 0
            for k in range(1, len(tops)):
                at = tops[k]
                if yv < at - 1e-12 or (below and abs(yv - at) <= 1e-12):
                    i = k
            s = self.layers[i]
            m, n = s.mu * math.exp(s.gamma_h * (min(yv, tops[i]) - tops[i])), s.nu
            if below and yv <= -1.0 + 1e-12 and isinstance(self.base, HalfSpace):
                m, n = self.base.mu, self.base.nu
            mu[idx], nu[idx] = m, n
        return mu, nu

    def critical_speed(self) -> tuple[float, float]:
        """(V*_cr, alpha h at the minimum) of this medium: the lowest speed of
        a free steady wave (alpha h inf or 0: an infimum approached by short
        or long waves; docs/media.md)."""
        base = self.base
        if self.homogeneous or (
            self.viscoelastic and len(self.layers) == 1 and isinstance(base, Winkler)
        ):
            # A viscoelastic layer: its relaxed (slowest) elastic layer's.
            assert isinstance(base, Winkler)
            vc, t = _core.critical_speed(base.kw, self.nu, base.kp)
        else:
            # (A stack with viscoelastic sublayers: its relaxed elastic stack's,
            # which the rows alone describe.)
            springs = base if isinstance(base, Winkler) else None
            vc, t = _core.medium_critical_speed(
                **self.core_args(materials=False),
                kw=springs.kw if springs else math.inf,
                kp=springs.kp if springs else 0.0,
            )
        return float(vc), float(t)

    def core_args(self, materials: bool = True) -> dict[str, Any]:
        """The keyword arguments of ``_core.solve_contact`` for this medium
        (kw and kp are the springs'; inf and 0 under a half-space);
        ``materials=False``: the relaxed elastic medium's (no ``materials``:
        a material given by tau needs no speed then)."""
        if self.homogeneous:
            return {}
        base = self.base
        out: dict[str, Any] = {"layers": [s.row() for s in self.layers]}
        if self.viscoelastic and materials:
            out["materials"] = [
                s.viscoelastic.branches()
                if isinstance(s, Layer) and s.viscoelastic is not None
                else ((), (), 1.0)
                for s in self.layers
            ]
        if isinstance(base, Winkler):
            out.update(base="springs")
        else:
            out.update(base=base.interface, half_space=base.row())
        return out

    def solve_args(self) -> dict[str, Any]:
        """The medium as ``movingpunch.solve`` takes it: ``layers=``,
        ``base=`` and ``inertia=``."""
        return {"layers": list(self.layers), "base": self.base, "inertia": self.inertia}

    def describe(self) -> str:
        parts = "; ".join(s.describe() for s in self.layers)
        still = "" if self.inertia else ", quasi-static (inertia neglected)"
        return f"{parts} on {self.base.describe()}{still}"

    def to_dict(self) -> dict[str, object]:
        out: dict[str, object] = {
            "layers": [s.to_dict() for s in self.layers],
            "base": self.base.to_dict(),
        }
        if not self.inertia:
            out["inertia"] = False
        return out


def _sublayers(layers: object) -> tuple[Sublayer, ...]:
    if isinstance(layers, (Layer, GradedLayer)):
        layers = [layers]
    if isinstance(layers, (str, bytes)) or not isinstance(layers, Sequence):
        raise InvalidParameterError(
            f"layers must be a list of movingpunch.Layer or GradedLayer, got "
            f"{layers!r}",
            parameter="layers",
            allowed="a list of Layer or GradedLayer, top to bottom",
        )
    out: list[Sublayer] = []
    for i, item in enumerate(layers):
        if not isinstance(item, (Layer, GradedLayer)):
            raise InvalidParameterError(
                f"layers[{i}] must be a movingpunch.Layer or GradedLayer, got {item!r}",
                parameter="layers",
                allowed="a list of Layer or GradedLayer, top to bottom",
            )
        out.append(item)
    if not out:
        raise InvalidParameterError(
            "layers must list at least one sublayer",
            parameter="layers",
            allowed="a list of Layer or GradedLayer, top to bottom",
        )
    total = math.fsum(s.thickness for s in out)
    if abs(total - 1.0) > 1e-12:
        raise InvalidParameterError(
            f"layers: the thicknesses sum to {total!r}; they must sum to 1 "
            "(lengths are per the total thickness h)",
            parameter="layers",
            allowed="thicknesses summing to 1",
        )
    top = out[0]
    if top.mu != 1.0 or top.rho != 1.0:
        raise InvalidParameterError(
            f"layers[0]: the top sublayer's mu and rho are the units (1 by "
            f"definition), got mu = {top.mu!r}, rho = {top.rho!r}; divide every "
            "sublayer's mu and rho by the top's",
            parameter="layers",
            allowed="mu = rho = 1 for the top sublayer",
        )
    return tuple(out)


def resolve_medium(
    *,
    layers: object = None,
    base: object = None,
    kw: object = None,
    kp: object = None,
    damping: object = None,
    nu: object = None,
    inertia: bool = True,
) -> Medium:
    """The medium of a solve's keyword arguments. ``layers``/``base`` are the
    value types; ``kw``, ``kp``, ``damping`` and ``nu`` their shorthand
    (None: not given). Giving a parameter both ways (``nu`` with ``layers``,
    ``kw`` with a ``base``) is an InvalidParameterError naming it."""
    if layers is not None and nu is not None:
        raise InvalidParameterError(
            "nu: give Poisson's ratio per sublayer (Layer(..., nu=...)) when "
            "layers= is given, not nu=",
            parameter="nu",
            allowed="omitted when layers= is given",
        )
    for name, value in (("kw", kw), ("kp", kp), ("damping", damping)):
        if base is not None and value is not None:
            where = (
                f"give {name} there (Winkler(kw, kp, damping)), not as a keyword too"
                if isinstance(base, Winkler)
                else f"a half-space base has no springs: drop {name}="
            )
            raise InvalidParameterError(
                f"{name}: the base is given by base= ({base!r}); {where}",
                parameter=name,
                allowed="omitted when base= is given",
            )
    if base is None:
        if kw is None:
            raise InvalidParameterError(
                "kw: the foundation's stiffness is required (or base=Winkler(...) "
                "or base=HalfSpace(...))",
                parameter="kw",
                allowed=params.SPECS["kw"].text,
            )
        base = Winkler(
            kw=kw,  # type: ignore[arg-type]
            kp=0.0 if kp is None else kp,  # type: ignore[arg-type]
            damping=0.0 if damping is None else damping,  # type: ignore[arg-type]
        )
    elif not isinstance(base, (Winkler, HalfSpace)):
        raise InvalidParameterError(
            f"base must be movingpunch.Winkler(...) or HalfSpace(...), got {base!r}",
            parameter="base",
            allowed="Winkler(kw, kp, damping) or HalfSpace(mu, nu, rho, interface)",
        )
    if layers is None:
        sub: tuple[Sublayer, ...] = (
            Layer(nu=0.2 if nu is None else nu),  # type: ignore[arg-type]
        )
    else:
        sub = _sublayers(layers)
    return Medium(layers=sub, base=base, inertia=inertia)
