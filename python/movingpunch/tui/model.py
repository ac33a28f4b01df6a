"""What the terminal UI computes, without Textual: parameter sets, the
validation of typed text, the curves of each tab and a thread-safe cache.

Everything here runs in worker threads (the solver releases the GIL); the
app only turns the results into widgets. Nothing in this module touches a
widget, so it can be tested on its own.
"""

from __future__ import annotations

import functools
import math
import threading
from collections import OrderedDict
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any, Literal, cast

import numpy as np
import numpy.typing as npt

from movingpunch.accuracy import LADDER, AccuracyReport, accuracy_report
from movingpunch.contract import ContactSolution
from movingpunch.errors import InvalidParameterError, MovingPunchError
from movingpunch.fields import StressPeaks
from movingpunch.media import (
    SUBLAYER_TYPES,
    GradedLayer,
    HalfSpace,
    Layer,
    Medium,
    Prony,
    Sublayer,
    Winkler,
    Zener,
)
from movingpunch.params import OPTIONAL, PHYSICAL
from movingpunch.params import check as check_param
from movingpunch.profiles import PROFILE_KINDS, Flat, Profile, PunchProfile, RoundedFlat
from movingpunch.regime import given_indentation, half_length, regime_hints
from movingpunch.solver import (
    critical_vstar,
    rayleigh_vstar,
    result_warnings,
    solve,
    solve_punches,
)
from movingpunch.zones import CONTACT_MODES, Punch

FloatArray = npt.NDArray[np.float64]

PARAM_NAMES: tuple[str, ...] = (
    "vstar",
    "kw",
    "kp",
    "radius",
    "half_width",
    "load",
    "nu",
    "damping",
    "friction",
    "tol",
)
"""Every numeric input of the parameters panel, in order (the punch's
kind, ``profile``, is a text input above them: ``parse_profile_kind``)."""

TUI_PROFILES: tuple[str, ...] = PROFILE_KINDS
"""The punch shapes the panel's ``profile`` input takes (a table comes from
a scene file)."""


def parse_profile_kind(text: str) -> str:
    """The punch's kind typed in the panel: cylinder, flat, rounded_flat or
    table (case and "-"/" " for "_" forgiven). Raises InvalidParameterError
    (``.parameter`` "profile") naming the kinds."""
    kind = "_".join(text.strip().lower().replace("-", " ").split())
    if kind not in TUI_PROFILES:
        raise InvalidParameterError(
            f"profile must be one of {', '.join(TUI_PROFILES)}, got {text.strip()!r}",
            parameter="profile",
            allowed=", ".join(TUI_PROFILES),
        )
    return kind


def parse_contact(text: str) -> str:
    """The contact mode typed in the panel: ``auto`` (find the contact set:
    several zones when the single contact is unphysical) or ``single`` (the
    single contact, refused when unphysical). Raises InvalidParameterError
    (``.parameter`` "contact")."""
    mode = text.strip().lower()
    if mode not in CONTACT_MODES:
        raise InvalidParameterError(
            f"contact must be auto or single, got {text.strip()!r}",
            parameter="contact",
            allowed="auto or single",
        )
    return mode


MAX_PUNCHES = 16
"""The most punches ``movingpunch.solve_punches`` takes."""


@dataclass(frozen=True)
class TrainPunch:
    """One punch of a train: its load P_k/(mu h), the position x/h of its
    axis and its shape (None: the panel's punch, R/h and b/h)."""

    load: float
    at: float
    profile: PunchProfile | None = None

    def text(self) -> str:
        return f"{fmt(self.load, 10)}@{fmt(self.at, 10)}"


def parse_punches(text: str) -> tuple[TrainPunch, ...]:
    """The panel's ``punches`` input: empty for the single punch of the
    load input, else ``load@at`` items separated by commas or semicolons
    (``0.002@-1.5, 0.002@1.5``), each a punch of the panel's shape. Raises
    InvalidParameterError (``.parameter`` "punches") naming the item."""
    items = [t.strip() for t in text.replace(";", ",").split(",")]
    if not any(items):
        return ()
    if len(items) > MAX_PUNCHES:
        raise InvalidParameterError(
            f"punches: at most {MAX_PUNCHES} punches, got {len(items)}",
            parameter="punches",
            allowed="load@at, ... (x/h of each axis)",
        )
    out = []
    for k, item in enumerate(items, start=1):
        where = f"punches: item {k} {item!r}"
        load_text, at_sign, at_text = item.partition("@")
        if not at_sign or not load_text.strip() or not at_text.strip():
            raise InvalidParameterError(
                f"{where}: write load@at, e.g. 0.002@-1.5",
                parameter="punches",
                allowed="load@at, ... (x/h of each axis)",
            )
        try:
            load = parse_param("load", load_text)
        except InvalidParameterError as exc:
            raise InvalidParameterError(
                f"{where}: {exc}", parameter="punches", allowed=exc.allowed
            ) from None
        try:
            at = float(at_text.strip())
        except ValueError:
            at = math.nan
        if not math.isfinite(at):
            raise InvalidParameterError(
                f"{where}: the position x/h after @ must be a finite number",
                parameter="punches",
                allowed="load@at, ... (x/h of each axis)",
            )
        out.append(TrainPunch(load, at))
    return tuple(out)


def format_punches(punches: Sequence[TrainPunch]) -> str:
    """The text of the panel's ``punches`` input (the inverse of
    ``parse_punches`` for punches of the panel's shape)."""
    return ", ".join(p.text() for p in punches)


def train_from(punches: Iterable[Punch]) -> tuple[TrainPunch, ...]:
    """``movingpunch.Punch`` objects (e.g. a scene's ``[[punches]]``) as the
    model's train, each keeping its own profile."""
    return tuple(TrainPunch(p.load, p.at, p.profile) for p in punches)


SCENE_PARAMS: tuple[str, ...] = PHYSICAL
"""The physical parameters (a scene's ``params``); ``tol`` is separate."""

TabName = Literal["pressure", "surface", "depth", "sweep", "field", "accuracy"]
TABS: tuple[TabName, ...] = (
    "pressure",
    "surface",
    "depth",
    "sweep",
    "field",
    "accuracy",
)

FieldQuantity = Literal["sigma_x", "von_mises"]

SHORT: dict[str, str] = {
    "vstar": "V*",
    "kw": "kw",
    "radius": "R/h",
    "half_width": "b/h",
    "load": "P/μh",
    "nu": "ν",
    "damping": "damping",
    "kp": "kp",
    "friction": "f",
    "tol": "tol",
}
"""Short labels of the parameters, for legends."""

GRID_LABELS: dict[str, str] = {
    "vstar": "V* = ρV²/μ",
    "kw": "k_w h/μ",
    "radius": "R/h",
    "load": "P/(μh)",
    "nu": "ν",
    "damping": "damping c_w c_T/μ",
    "kp": "k_p/(μh)",
    "friction": "friction f",
    "spacing": "spacing/h",
}
"""Axis labels of a swept parameter (the paper's normalisations)."""


def fmt(value: float, digits: int = 6) -> str:
    """A compact number: ``inf`` for infinity, ``n/a`` for NaN (a quantity
    the medium does not give), else ``digits`` significant."""
    if math.isnan(value):
        return "n/a"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    return f"{value:.{digits}g}"


def parse_param(name: str, text: str) -> float:
    """The value typed for ``name``, checked as ``movingpunch.solve`` checks
    it (the table ``movingpunch.params.SPECS``). Raises InvalidParameterError
    naming the parameter and its range (``.parameter`` is ``name``).

    The bound vstar < V*_cr depends on kw and nu: the solve checks it.
    """
    stripped = text.strip()
    try:
        value: object = float(stripped)
    except ValueError:
        value = stripped  # the check rejects it with the usual message
    if not stripped:
        value = text
    return check_param(name, value)


@dataclass(frozen=True)
class Params:
    """One parameter set (hashable: the key of every cache)."""

    vstar: float = 0.2
    kw: float = 1.0
    radius: float = 100.0
    load: float = 0.002
    nu: float = 0.2
    tol: float = 1e-8
    damping: float = 0.0
    """c_w c_T/mu: dashpots in the foundation (docs/damped.md); 0: none."""
    kp: float = 0.0
    """k_p/(mu h): the Pasternak shear layer on the springs (docs/theory.md
    section 12); 0: springs alone."""
    profile: str = "cylinder"
    """The punch's kind (``TUI_PROFILES``): a cylinder of ``radius``, a flat
    face of ``half_width``, a rounded flat (``half_width``, corners of
    ``radius``) or the ``table`` of a scene file."""
    half_width: float = 0.5
    """b/h of a flat or rounded flat punch (unused by the others)."""
    table: Profile | None = None
    """The tabulated profile of a scene file (kind "table")."""
    friction: float = 0.0
    """Coulomb friction f (docs/theory.md section 14); 0: frictionless."""
    contact: str = "auto"
    """``movingpunch.solve``'s ``contact=``: "auto" (several zones when the
    single contact is unphysical) or "single" (refused when unphysical)."""
    punches: tuple[TrainPunch, ...] = ()
    """A train (``movingpunch.solve_punches``); (): the single punch of
    ``load`` (the train's punches carry their own loads)."""
    layers: tuple[Sublayer, ...] = ()
    """The sublayers, top to bottom (``movingpunch.Layer``, ``GradedLayer``;
    the medium editor); (): the homogeneous layer of Poisson's ratio ``nu``."""
    half_space: HalfSpace | None = None
    """The base: an elastic half-space under the layers; None: the springs
    ``kw``, ``kp`` and ``damping``."""
    inertia: bool = True
    """The layer's inertia (False: quasi-static, vstar setting only the
    relaxation of a viscoelastic material given by tau; the medium editor)."""

    def medium(self) -> Medium | None:
        """The medium ``movingpunch.solve`` takes as ``layers=``/``base=``;
        None for the homogeneous layer on springs (``kw=``, ``nu=``, ...)."""
        if not self.layers and self.half_space is None:
            return None
        layers = self.layers or (Layer(1.0, nu=self.nu),)
        base: Winkler | HalfSpace = self.half_space or Winkler(
            self.kw, self.kp, self.damping
        )
        return Medium(layers=layers, base=base, inertia=self.inertia)

    def interfaces(self) -> tuple[float, ...]:
        """y/h of the interfaces between sublayers, top to bottom (the
        bottom of the stack, y/h = -1, is not one of them)."""
        out = []
        depth = 0.0
        for sub in self.layers[:-1]:
            depth += sub.thickness
            out.append(-depth)
        return tuple(out)

    def medium_label(self) -> str:
        """The medium in a few characters ("" for the homogeneous layer on
        springs): ``2 sublayers on springs``, ``graded on bonded half-space``."""
        if self.medium() is None:
            return ""
        top = self.layers[0] if self.layers else None
        material = top.viscoelastic if isinstance(top, Layer) else None
        if len(self.layers) > 1:
            stack = f"{len(self.layers)} sublayers"
        elif isinstance(top, GradedLayer):
            stack = f"graded gamma h={fmt(top.gamma_h, 4)}"
        elif isinstance(material, Zener):
            time = (
                f"tau={fmt(material.tau, 4)}"
                if material.tau is not None
                else f"De={fmt(float(material.deborah or 0.0), 4)}"
            )
            stack = f"Zener {fmt(material.ratio, 4)}, {time}"
        elif isinstance(material, Prony):
            stack = "Prony layer"
        else:
            stack = "layer"
        still = "" if self.inertia else ", quasi-static"
        if self.half_space is None:
            return f"{stack} on springs{still}"
        return f"{stack} on {self.half_space.interface} half-space{still}"

    def applies(self, name: str) -> bool:
        """Whether the parameter ``name`` means something for this medium:
        ν is the sublayers' own when there are sublayers; kw, kp and damping
        are the springs' (none under a half-space)."""
        if name == "nu":
            return not self.layers
        if name in ("kw", "kp", "damping"):
            return self.half_space is None
        return True

    @property
    def damped(self) -> bool:
        return self.damping > 0.0

    def shape(self) -> PunchProfile | None:
        """The punch solve() takes (None: the cylinder of ``radius``).
        Raises InvalidParameterError naming the input at fault."""
        if self.profile == "flat":
            return Flat(self.half_width)
        if self.profile == "rounded_flat":
            return RoundedFlat(self.half_width, self.radius)
        if self.profile == "table":
            if self.table is None:
                raise InvalidParameterError(
                    "profile table: open a scene file with a [params.profile] "
                    "table (the panel has no table editor)",
                    parameter="profile",
                )
            return self.table
        return None

    def train(self) -> list[Punch]:
        """The train's punches as ``movingpunch.Punch`` (each of its own
        profile, else the panel's shape). Raises InvalidParameterError."""
        shape = self.shape()
        own: PunchProfile | float = self.radius if shape is None else shape
        return [
            Punch(own if p.profile is None else p.profile, p.load, at=p.at)
            for p in self.punches
        ]

    def get(self, name: str) -> float:
        if name == "spacing":  # a train's: its first two axes' distance
            if len(self.punches) < 2:
                return math.nan
            return self.punches[1].at - self.punches[0].at
        value: float = getattr(self, name)
        return value

    def with_value(self, name: str, value: float) -> Params:
        if name == "spacing":
            return self.spaced(value)
        if name not in PARAM_NAMES:
            raise InvalidParameterError(f"unknown parameter {name!r}")
        if not self.applies(name):
            raise InvalidParameterError(
                f"{name}: does not apply to the medium ({self.medium_label()}): "
                + (
                    "each sublayer has its own ν (the medium editor, l)"
                    if name == "nu"
                    else "a half-space base has no springs"
                ),
                parameter=name,
            )
        changes: dict[str, object] = {name: value}
        return replace(self, **changes)  # type: ignore[arg-type]

    def spaced(self, spacing: float) -> Params:
        """The train with its punches equally ``spacing`` apart, centred on
        x = 0 (at_k = (k - (K - 1)/2) spacing: a scene's sweep over
        ``spacing``); their loads and shapes kept."""
        k = len(self.punches)
        if k < 2:
            raise InvalidParameterError(
                "spacing: applies to a train of two or more punches (the train input)",
                parameter="spacing",
            )
        train = tuple(
            replace(p, at=(i - (k - 1) / 2) * spacing)
            for i, p in enumerate(self.punches)
        )
        return replace(self, punches=train)

    def _shown(self, name: str) -> bool:
        """damping, kp and friction only when > 0 (0 is the paper's model)."""
        return name not in OPTIONAL or self.get(name) > 0.0

    def physical(self) -> dict[str, float]:
        """The scene's ``params`` mapping (without tol; damping, kp and
        friction only if > 0; radius only for a cylinder or a rounded flat)."""
        return {
            name: self.get(name)
            for name in SCENE_PARAMS
            if self._shown(name)
            and (name != "radius" or self.profile in ("cylinder", "rounded_flat"))
        }

    def label(self, against: Params | None = None) -> str:
        """``V*=0.2 kw=1 ...``; only the values that differ from ``against``
        (damping, kp and friction 0 are not shown)."""
        names = [
            n
            for n in SCENE_PARAMS
            if self.applies(n)
            and (
                (against is None and self._shown(n))
                or (against is not None and self.get(n) != against.get(n))
            )
        ]
        shape = self.shape_label()
        if against is not None and shape == against.shape_label():
            shape = ""
        extra = self._zones_label()
        if against is not None and extra == against._zones_label():
            extra = []
        medium = self.medium_label()
        if against is not None and (self.layers, self.half_space, self.inertia) == (
            against.layers,
            against.half_space,
            against.inertia,
        ):
            medium = ""
        elif against is not None and not medium:
            medium = "homogeneous layer"
        if medium:
            extra = [*extra, medium]
        if not names and not shape and not extra:
            return "same"
        return " ".join(
            [f"{SHORT[n]}={fmt(self.get(n), 4)}" for n in names]
            + ([shape] if shape else [])
            + extra
        )

    def _zones_label(self) -> list[str]:
        """The train and a "single" contact mode (auto is the default)."""
        out = []
        if self.punches:
            out.append("punches=" + ",".join(p.text() for p in self.punches))
        if self.contact != "auto":
            out.append(f"contact={self.contact}")
        return out

    def shape_label(self) -> str:
        """ "" for a cylinder, else the punch in a few characters."""
        if self.profile == "flat":
            return f"flat b={fmt(self.half_width, 4)}"
        if self.profile == "rounded_flat":
            return f"rflat b={fmt(self.half_width, 4)}"
        if self.profile == "table":
            return "table"
        return ""


PAPER_FIG4 = Params()
"""The paper's Fig. 4 case: V* = 0.2, kw = 1, R/h = 100, μ/(P/h) = 500, ν = 0.2."""


@dataclass(frozen=True)
class Overlay:
    """One parameter set to several values, drawn over the current curves."""

    param: str
    values: tuple[float, ...]

    def members(self, base: Params) -> list[tuple[str, Params]]:
        return [
            (f"{SHORT[self.param]}={fmt(v, 4)}", base.with_value(self.param, v))
            for v in self.values
        ]


def parse_values(name: str, text: str) -> tuple[float, ...]:
    """A list of values for ``name`` typed as ``0.1, 0.2 0.3``; each checked."""
    parts = [p for p in text.replace(",", " ").replace(";", " ").split() if p]
    if not parts:
        raise InvalidParameterError(f"give one or more values of {name}")
    if len(parts) > 12:
        raise InvalidParameterError(f"at most 12 values of {name}, got {len(parts)}")
    return tuple(parse_param(name, p) for p in parts)


@dataclass(frozen=True)
class SweepSpec:
    """The a/h tab: a/h against ``param`` (the paper's Figs 2-3), on explicit
    ``values`` or on a range: ``points`` values from ``start`` to ``stop``
    spaced ``"log"`` or ``"linear"`` (what a saved scene keeps as start,
    stop, points and spacing).

    The default (no values, no start and stop) is a range too: 13 points on
    a log scale from a tenth to ten times the current value of ``param``.
    """

    param: str = "load"
    values: tuple[float, ...] | None = None
    """Explicit values (a scene's ``values = [...]``); None: a range."""
    start: float | None = None
    """The range's first value; None (with ``stop``): the current / 10."""
    stop: float | None = None
    """The range's last value; None (with ``start``): the current * 10."""
    points: int = 13
    spacing: str = "log"
    """``"log"`` or ``"linear"``."""
    quantity: str = "a"
    """What is plotted: ``"a"`` (a/h) or ``"drag"`` (F/P: the resistance
    curve of a damped, rough or viscoelastic case)."""

    @property
    def is_range(self) -> bool:
        return self.values is None

    def bounds(self, base: Params) -> tuple[float, float]:
        """The range's start and stop (relative to ``base`` when not fixed)."""
        if self.start is not None and self.stop is not None:
            return self.start, self.stop
        centre = base.get(self.param)
        start = centre / 10.0 if self.start is None else self.start
        stop = centre * 10.0 if self.stop is None else self.stop
        return start, stop

    def grid(self, base: Params) -> FloatArray:
        if self.values is not None:
            return np.asarray(self.values, dtype=np.float64)
        start, stop = self.bounds(base)
        if self.spacing == "log":
            return np.geomspace(start, stop, self.points)
        return np.linspace(start, stop, self.points)


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class Series:
    label: str
    values: FloatArray


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class Curves:
    """The curves of one tab on a shared grid (what the CSV export writes)."""

    tab: TabName
    title: str
    grid_label: str
    value_label: str
    grid: FloatArray
    series: tuple[Series, ...]
    markers: tuple[float, ...] = ()
    """x/h of the zone ends of the current set, drawn as vertical lines
    (the pressure tab with several zones)."""
    axes: tuple[float, ...] = ()
    """x/h of the axes of a train's punches (the pressure and surface tabs),
    drawn as dotted vertical lines of their own colour."""
    vertical_grid: bool = False
    """Draw the grid vertically (σx through the depth: y/h upwards)."""
    log_grid: bool = False
    interfaces: tuple[float, ...] = ()
    """y/h of the interfaces between the current set's sublayers (the depth
    tab), drawn as horizontal lines."""


@dataclass(frozen=True, eq=False)  # arrays: compared by identity
class FieldMap:
    """A stress over P/h on x by y under the punch (the coloured map)."""

    quantity: FieldQuantity
    title: str
    x: FloatArray
    y: FloatArray
    values: FloatArray
    """Shaped (len(y), len(x))."""
    a: float
    centre: float = 0.0
    """x/h at the middle of the map."""
    zones: tuple[tuple[float, float], ...] = ()
    """The contact zones when there are several (() for one contact)."""


@dataclass(frozen=True, eq=False)
class AccuracyTable:
    """The Accuracy tab: errors and times for tol 1e-2 ... 1e-12 at the
    current parameters (``movingpunch.accuracy``)."""

    report: AccuracyReport
    tab: TabName = "accuracy"


@dataclass(frozen=True)
class Notice:
    """A tab that has nothing to show for these parameters, and why."""

    tab: TabName
    text: str


TabData = Curves | FieldMap | AccuracyTable | Notice


@dataclass(frozen=True)
class PunchSummary:
    """One punch of a train in the summary."""

    load: float
    at: float
    indentation: float
    contact_zones: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class Summary:
    params: Params
    a: float
    p0: float
    indentation: float
    top_tensile: float
    bottom_tensile: float
    iterations: int
    error_estimate: float
    elapsed: float
    valid: bool
    critical_vstar: float
    rayleigh_vstar: float
    contact_interval: tuple[float, float] = (math.nan, math.nan)
    """(-b/h, a/h); (-a/h, a/h) without damping."""
    drag: float = 0.0
    """Horizontal force on the punch over P (0 without damping)."""
    end_coefficient: float = 0.0
    """A flat punch's end coefficient K/((P/h) sqrt(h)) (0: bounded ends);
    the leading edge's (K_front) on the asymmetric solver."""
    end_coefficient_back: float = 0.0
    """The trailing edge's K_back (= end_coefficient when symmetric)."""
    warnings: tuple[str, ...] = ()
    """The solution's warnings (a requested accuracy not met)."""
    tangential_force: float = 0.0
    """Friction force on the punch over P (f; 0 without friction)."""
    contact_zones: tuple[tuple[float, float], ...] = ()
    """Every contact zone (left, right)/h ((): the one ``contact_interval``)."""
    punches: tuple[PunchSummary, ...] = ()
    """Each punch of a train ((): a single punch)."""
    medium: str = ""
    """The medium solved (``Medium.describe()``); "" for the homogeneous
    layer on springs."""

    @property
    def damped(self) -> bool:
        return self.params.damped


def summary_hints(s: Summary) -> tuple[str, ...]:
    """The plausibility hints of a summary (``movingpunch.regime``)."""
    if s.punches:
        indentation = max(abs(p.indentation) for p in s.punches)
        half = max(half_length(p.contact_zones) for p in s.punches)
        load = sum(p.load for p in s.punches)  # stresses are over the total P
    else:
        indentation = s.indentation
        half = half_length((s.contact_interval,))
        load = s.params.load
    peak = max(
        [abs(s.p0)]
        + [abs(v) for v in (s.top_tensile, s.bottom_tensile) if not math.isnan(v)]
    )
    return regime_hints(
        indentation=indentation,
        half_length=half,
        peak_strain=peak * load,
        vstar=s.params.vstar,
        critical_vstar=s.critical_vstar,
        rayleigh_vstar=s.rayleigh_vstar,
        damped=s.damped,
    )


@dataclass(frozen=True)
class Request:
    """What one worker computes: the summary of ``params`` and the data of
    one tab for the current set, the overlay and the pins."""

    generation: int
    params: Params
    tab: TabName
    pins: tuple[Params, ...] = ()
    overlay: Overlay | None = None
    sweep: SweepSpec = field(default_factory=SweepSpec)
    quantity: FieldQuantity = "sigma_x"


@dataclass(frozen=True)
class Result:
    request: Request
    summary: Summary
    data: TabData
    notes: tuple[str, ...] = ()
    """Overlay or pin members that could not be solved, one line each."""


class Cache:
    """Solutions, peaks and curves per parameter set (thread-safe, bounded)."""

    def __init__(self, size: int = 256) -> None:
        self._size = size
        self._lock = threading.Lock()
        self._items: OrderedDict[tuple[object, ...], object] = OrderedDict()
        self.misses: dict[str, int] = {}

    def get_or_make(
        self, key: tuple[object, ...], make: Callable[[], object]
    ) -> object:
        with self._lock:
            if key in self._items:
                self._items.move_to_end(key)
                return self._items[key]
        value = make()  # outside the lock: solves run in parallel
        with self._lock:
            kind = str(key[0])
            self.misses[kind] = self.misses.get(kind, 0) + 1
            self._items[key] = value
            while len(self._items) > self._size:
                self._items.popitem(last=False)
        return value

    def peek(self, key: tuple[object, ...]) -> object | None:
        """The cached value of ``key``, or None (nothing is computed)."""
        with self._lock:
            return self._items.get(key)

    def kinds(self) -> set[tuple[str, Params]]:
        """(kind, params) of every cached item whose key has params second."""
        with self._lock:
            return {(str(k[0]), k[1]) for k in self._items if isinstance(k[1], Params)}

    def clear(self) -> None:
        with self._lock:
            self._items.clear()
            self.misses.clear()


def solution(cache: Cache, params: Params) -> ContactSolution:
    # cast, not isinstance: a runtime Protocol check reads every member,
    # computing the lazy ones (a second solve for stress_error_estimate, the
    # damped indentation): 8-19 ms on every redraw.
    return cast(
        ContactSolution, cache.get_or_make(("solution", params), lambda: _solve(params))
    )


def _solve(params: Params) -> ContactSolution:
    medium = params.medium()
    if params.punches and medium is not None:
        # A train on the medium (solve_punches refuses what it cannot take
        # yet, naming it: a train under a half-space, damped springs under a
        # stack, a viscoelastic layer).
        if not medium.inertia:
            raise InvalidParameterError(
                "inertia: a train of punches is solved with the layer's inertia "
                "(the quasi-static layer takes one punch)",
                parameter="inertia",
                allowed="inertia on beside a train",
            )
        return solve_punches(
            params.train(),
            vstar=params.vstar,
            friction=params.friction,
            tol=params.tol,
            layers=list(medium.layers),
            base=medium.base,
        )
    if medium is not None:
        shape = params.shape()
        return solve(
            vstar=params.vstar,
            radius=params.radius if shape is None else None,
            profile=shape,
            load=params.load,
            tol=params.tol,
            friction=params.friction,
            contact=params.contact,
            **medium.solve_args(),
        )
    if params.punches:
        return solve_punches(
            params.train(),
            vstar=params.vstar,
            kw=params.kw,
            nu=params.nu,
            kp=params.kp,
            damping=params.damping,
            friction=params.friction,
            tol=params.tol,
        )
    shape = params.shape()
    return solve(
        vstar=params.vstar,
        kw=params.kw,
        radius=params.radius if shape is None else None,
        profile=shape,
        load=params.load,
        nu=params.nu,
        tol=params.tol,
        damping=params.damping,
        kp=params.kp,
        friction=params.friction,
        contact=params.contact,
    )


def zones_of(s: ContactSolution) -> tuple[tuple[float, float], ...]:
    """A solution's contact zones, as floats."""
    return tuple((float(lo), float(hi)) for lo, hi in s.contact_zones)


def _punch_summaries(s: ContactSolution) -> tuple[PunchSummary, ...]:
    """Each punch of a train (several punches, or one off the axis)."""
    punches = s.punches
    if len(punches) < 2 and all(p.at == 0.0 for p in punches):
        return ()
    return tuple(
        PunchSummary(
            load=float(p.load),
            at=float(p.at),
            indentation=given_indentation(p),
            contact_zones=tuple((float(a), float(b)) for a, b in p.contact_zones),
        )
        for p in punches
    )


def limits(kw: float, nu: float, kp: float = 0.0) -> tuple[float, float]:
    """(V*_cr, V*_R) for the foundation and Poisson's ratio."""
    return critical_vstar(kw, nu, kp), rayleigh_vstar(nu)


def medium_limits(params: Params) -> tuple[float, float]:
    """(V*_cr, V*_R) of the medium of ``params`` (V*_R: its top sublayer's
    Rayleigh speed); raises MovingPunchError when the medium is refused."""
    medium = params.medium()
    if medium is None:
        return limits(params.kw, params.nu, params.kp)
    vcr = critical_vstar(layers=list(medium.layers), base=medium.base)
    return vcr, rayleigh_vstar(medium.nu)


def summary(cache: Cache, params: Params) -> Summary:
    s = solution(cache, params)
    try:
        peaks = cache.get_or_make(("peaks", params), s.stress_peaks)
        assert isinstance(peaks, StressPeaks)
        top, bottom = peaks.top_tensile, peaks.bottom_tensile
    except InvalidParameterError:
        # An output the medium does not give (the stresses of a viscoelastic
        # layer with inertia): shown as n/a, never another medium's number.
        top = bottom = math.nan
    return Summary(
        params=params,
        a=s.a,
        p0=s.p0,
        indentation=given_indentation(s),
        top_tensile=top,
        bottom_tensile=bottom,
        iterations=s.iterations,
        error_estimate=s.error_estimate,
        elapsed=s.elapsed,
        valid=s.valid,
        critical_vstar=s.critical_vstar,
        rayleigh_vstar=s.rayleigh_vstar,
        contact_interval=s.contact_interval,
        drag=s.drag,
        end_coefficient=s.end_coefficients[1],
        end_coefficient_back=s.end_coefficients[0],
        warnings=result_warnings(s),
        tangential_force=s.tangential_force,
        contact_zones=zones_of(s),
        punches=_punch_summaries(s),
        medium=_medium_text(params),
    )


def _medium_text(params: Params) -> str:
    medium = params.medium()
    return "" if medium is None else medium.describe()


Progress = Callable[[int, int], None]


def _members(request: Request) -> list[tuple[str, Params]]:
    """(label, params) of every curve: the current set, the overlay, the pins."""
    out: list[tuple[str, Params]] = [("current", request.params)]
    if request.overlay is not None:
        overlay = request.overlay
        value = fmt(request.params.get(overlay.param), 4)
        out[0] = (f"current {SHORT[overlay.param]}={value}", request.params)
        # A value equal to the current one would draw the same curve twice.
        # (An overlay of a parameter the medium has no use for: no members;
        # ``compute`` notes it.)
        if request.params.applies(overlay.param):
            members = overlay.members(request.params)
            out += [m for m in members if m[1] != request.params]
    for i, pin in enumerate(request.pins, start=1):
        out.append((f"pin{i} {pin.label(request.params)}", pin))
    return out


def compute(
    cache: Cache,
    request: Request,
    progress: Progress | None = None,
    cancelled: Callable[[], bool] | None = None,
) -> Result | None:
    """The summary and the visible tab's data for ``request``.

    Errors of the current set propagate (the app shows them inline); overlay
    and pin members that fail are left out with a note. Returns None if
    ``cancelled()`` turns true (a newer request superseded this one).
    """
    report = progress or (lambda done, total: None)
    stop = cancelled or (lambda: False)
    head = summary(cache, request.params)
    members = _members(request)
    solved: list[tuple[str, Params, ContactSolution]] = []
    notes: list[str] = []
    overlay = request.overlay
    if overlay is not None and not request.params.applies(overlay.param):
        notes.append(
            f"overlay {overlay.param}: not drawn, it does not apply to the "
            f"medium ({request.params.medium_label()})"
        )
    for label, params in members:
        try:
            solved.append((label, params, solution(cache, params)))
        except MovingPunchError as exc:
            notes.append(f"{label}: {_one_line(exc)}")
    if stop():
        return None
    data: TabData
    if request.tab == "accuracy":
        table = _accuracy(cache, request.params, report, stop)
        if table is None:
            return None
        data = table
    elif request.tab == "field":
        try:
            data = _field(cache, request.params, request.quantity)
        except InvalidParameterError as exc:
            # An output the medium does not give (the solve itself succeeded).
            data = Notice("field", _one_line(exc))
    elif (
        request.tab == "sweep"
        and request.params.punches
        and (request.sweep.param == "load")
    ):
        data = Notice(
            "sweep",
            "A train's punches carry their own loads (the train input): the "
            "load sweep does not apply; w sweeps R/h.",
        )
    elif request.tab == "sweep" and not request.params.applies(request.sweep.param):
        data = Notice(
            "sweep",
            f"The sweep over {request.sweep.param} does not apply to the medium "
            f"({request.params.medium_label()}); w sweeps P/(μh) and R/h.",
        )
    elif request.tab == "sweep":
        out = _sweep(cache, request, solved, report, stop)
        if out is None:
            return None
        data = out
    else:
        try:
            data = _curves(cache, request.tab, solved, report, stop)
        except InvalidParameterError as exc:
            # An output the medium does not give (the solve itself succeeded).
            data = Notice(request.tab, _one_line(exc))
    return Result(request=request, summary=head, data=data, notes=tuple(notes))


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


def _zoned(solved: Sequence[tuple[str, Params, ContactSolution]]) -> bool:
    """Whether any member has several zones or is a train (its grid then
    follows the zones' hull, not a contact centred on x = 0)."""
    return any(p.punches or len(zones_of(s)) > 1 for _, p, s in solved)


def _hull(
    solved: Sequence[tuple[str, Params, ContactSolution]],
) -> tuple[float, float, float]:
    """(left, right, widest zone) over every member's zones."""
    zones = [z for _, _, s in solved for z in zones_of(s)]
    return (
        min(lo for lo, _ in zones),
        max(hi for _, hi in zones),
        max(hi - lo for lo, hi in zones),
    )


def _centred(lo: float, hi: float, reach: float) -> tuple[float, float]:
    """(centre, half) of a window around the hull (lo, hi): half is
    ``reach`` rounded up, the centre rounded to a tenth of its step (stable
    grids, stable caches)."""
    half = _round_up(reach)
    step = 10.0 ** (math.floor(math.log10(half)) - 1)
    return round(0.5 * (lo + hi) / step) * step, half


def _window(
    tab: TabName, solved: Sequence[tuple[str, Params, ContactSolution]]
) -> tuple[float, float]:
    """(centre, half-length) of the x grid of the pressure and surface tabs.

    One contact per member: centred on x = 0 out to the farthest contact
    end (the damped contact (-b, a) is asymmetric). Several zones or a
    train: centred on the hull of every zone, with a margin."""
    if not _zoned(solved):
        amax = max(max(abs(e) for e in s.contact_interval) for _, _, s in solved)
        if tab == "pressure":
            return 0.0, _round_up(1.15 * amax)
        return 0.0, _round_up(max(3.0, 4.0 * amax))
    lo, hi, widest = _hull(solved)
    half = 0.5 * (hi - lo)
    if tab == "pressure":
        return _centred(lo, hi, half + max(0.15 * half, 0.25 * widest))
    return _centred(lo, hi, max(3.0, half + max(2.0, 3.0 * widest)))


def _round_up(x: float) -> float:
    """x rounded up to 2 significant digits (stable grids, stable caches)."""
    step = 10.0 ** (math.floor(math.log10(x)) - 1)
    return math.ceil(x / step) * step


INTERFACE_SIDE = 1e-9
"""The depth tab's grid holds y/h = interface ± this: σx on either side."""

_LABELS = {
    "pressure": ("Contact pressure", "x/h", "p(x)/(P/h)"),
    "surface": ("σx on the surface y = 0", "x/h", "σx(x,0)/(P/h)"),
    "depth": ("σx under the centre x = 0", "y/h", "σx(0,y)/(P/h)"),
}


def _curves(
    cache: Cache,
    tab: TabName,
    solved: Sequence[tuple[str, Params, ContactSolution]],
    report: Progress,
    stop: Callable[[], bool],
) -> Curves:
    title, grid_label, value_label = _LABELS[tab]
    interfaces: tuple[float, ...] = ()
    if tab == "depth":
        n = 101
        grid = np.linspace(-1.0, 0.0, n)
        # sigma_x jumps across a bonded interface: both sides on the grid.
        cuts = sorted({y for _, p, _ in solved for y in p.interfaces()})
        if cuts:
            sides = [y + d for y in cuts for d in (-INTERFACE_SIDE, INTERFACE_SIDE)]
            grid = np.union1d(grid, np.asarray(sides, dtype=np.float64))
        key: tuple[object, ...] = (n, tuple(cuts))
        if solved:
            interfaces = solved[0][1].interfaces()
    else:
        centre, half = _window(tab, solved)
        grid = np.linspace(
            centre - half, centre + half, 241 if tab == "surface" else 201
        )
        ends: tuple[float, ...] = ()
        if tab == "pressure" and _zoned(solved):
            # Every zone's ends on the grid: p drops to 0 exactly there.
            ends = tuple(
                sorted({e for _, _, s in solved for z in zones_of(s) for e in z})
            )
            grid = np.union1d(grid, np.asarray(ends, dtype=np.float64))
        key = (centre, half, len(grid), ends)
    series = []
    for i, (label, params, s) in enumerate(solved):
        if stop():
            break
        make = {
            "pressure": lambda s=s: s.pressure(grid),
            "surface": lambda s=s: s.surface_stress(grid),
            "depth": lambda s=s: s.depth_stress(grid),
        }[tab]
        values = cache.get_or_make((tab, params, *key), make)
        assert isinstance(values, np.ndarray)
        series.append(Series(label, values))
        report(i + 1, len(solved))
    markers: tuple[float, ...] = ()
    axes: tuple[float, ...] = ()
    if tab == "pressure" and solved:
        current = zones_of(solved[0][2])
        if len(current) > 1:
            markers = tuple(e for z in current for e in z)
    punches = solved[0][2].punches if solved else ()
    if tab != "depth" and len(punches) > 1:  # a train: its punches' axes
        axes = tuple(float(p.at) for p in punches)
    return Curves(
        tab=tab,
        title=title,
        grid_label=grid_label,
        value_label=value_label,
        grid=grid,
        series=tuple(series),
        markers=markers,
        axes=axes,
        vertical_grid=tab == "depth",
        interfaces=interfaces,
    )


def _sweep(
    cache: Cache,
    request: Request,
    solved: Sequence[tuple[str, Params, ContactSolution]],
    report: Progress,
    stop: Callable[[], bool],
) -> Curves | None:
    spec = request.sweep
    grid = spec.grid(request.params)
    total = len(solved) * len(grid)
    done = 0
    series = []
    quantity = spec.quantity
    for label, params, _ in solved:
        values = np.full(len(grid), np.nan)
        for j, x in enumerate(grid):
            if stop():
                return None
            point = params.with_value(spec.param, float(x))
            got = cache.get_or_make(
                (quantity, point), functools.partial(_quantity_or_nan, point, quantity)
            )
            assert isinstance(got, float)
            values[j] = got
            done += 1
            report(done, total)
        series.append(Series(label, values))
    swept = GRID_LABELS[spec.param]
    what = "Contact half-width" if quantity == "a" else "Drag F/P"
    return Curves(
        tab="sweep",
        title=f"{what} against {swept}",
        grid_label=swept,
        value_label="a/h" if quantity == "a" else "drag/P",
        grid=grid,
        series=tuple(series),
        log_grid=spec.is_range and spec.spacing == "log",
    )


SWEPT_QUANTITIES = ("a", "drag")
"""What the sweep tab plots: a/h, or the drag F/P."""


def _quantity_or_nan(params: Params, quantity: str) -> float:
    """a/h or the drag of the solve of ``params``; NaN where it fails (a
    point beyond the critical speed, a refused medium)."""
    try:
        return float(getattr(_solve(params), quantity))
    except MovingPunchError:
        return math.nan


def _field(cache: Cache, params: Params, quantity: FieldQuantity) -> FieldMap:
    s = solution(cache, params)
    zones = zones_of(s)
    if params.punches or len(zones) > 1:
        lo, hi, widest = _hull([("", params, s)])
        centre, extent = _centred(lo, hi, max(2.0, 0.5 * (hi - lo) + 1.0 + widest))
    else:
        reach = max(abs(e) for e in s.contact_interval)
        centre, extent = 0.0, _round_up(max(2.0, 3.0 * reach))
    x = np.linspace(centre - extent, centre + extent, 97)
    y = np.linspace(-1.0, 0.0, 41)

    def make() -> FloatArray:
        f = s.stress_field(x, y)
        return f.sigma_x if quantity == "sigma_x" else f.von_mises

    values = cache.get_or_make((f"field-{quantity}", params, centre, extent), make)
    assert isinstance(values, np.ndarray)
    name = "σx/(P/h)" if quantity == "sigma_x" else "von Mises σ/(P/h)"
    return FieldMap(
        quantity=quantity,
        title=f"{name} under the punch",
        x=x,
        y=y,
        values=values,
        a=s.a,
        centre=centre,
        zones=zones if len(zones) > 1 else (),
    )


def _accuracy(
    cache: Cache, params: Params, report: Progress, stop: Callable[[], bool]
) -> AccuracyTable | Notice | None:
    """The accuracy ladder of ``params`` (solve + sigma_x peaks per tol),
    computed once per parameter set (its tol does not matter: the ladder runs
    every tol). Each rung clears the core's kernel cache for a cold time.
    A train: a Notice (the ladder runs one punch)."""
    if params.punches:
        return Notice(
            "accuracy",
            "The accuracy ladder runs a single punch: clear the train input to see it.",
        )
    key = ("accuracy", replace(params, tol=PAPER_FIG4.tol))
    known = cache.peek(key)
    if isinstance(known, AccuracyTable):
        return known
    out = accuracy_report(
        params.physical(),
        LADDER,
        progress=report,
        cancelled=stop,
        profile=params.shape(),
        medium=params.medium(),
    )
    if out is None:
        return None
    table = cache.get_or_make(key, lambda: AccuracyTable(out))
    assert isinstance(table, AccuracyTable)
    return table


def to_csv(data: TabData, source: Params) -> str:
    """The tab's data as CSV that ``numpy.loadtxt(..., delimiter=",")``
    reads back: ``#`` comment lines, then numbers only."""
    lines = [f"# movingpunch {source.label()} tol={fmt(source.tol)}"]
    medium = source.medium()
    if medium is not None:
        lines.append(f"# medium: {medium.describe()}")
    if isinstance(data, AccuracyTable):
        lines.append(f"# accuracy against time; reference {data.report.reference}")
        table = data.report.columns()
        lines.append("# " + ", ".join(table))
        for row in np.column_stack(list(table.values())):
            lines.append(",".join(_csv_number(v) for v in row))
    elif isinstance(data, Notice):
        lines.append(f"# {data.text}")
    elif isinstance(data, Curves):
        lines.append(f"# {data.title}")
        names = [data.grid_label] + [
            f"{data.value_label} [{s.label}]" for s in data.series
        ]
        lines.append("# " + ", ".join(names))
        columns = [data.grid] + [s.values for s in data.series]
        for row in np.column_stack(columns):
            lines.append(",".join(_csv_number(v) for v in row))
    else:
        lines.append(f"# {data.title}")
        lines.append("# x/h, y/h, " + data.title.split(" under")[0])
        for j, yv in enumerate(data.y):
            for i, xv in enumerate(data.x):
                lines.append(
                    ",".join(_csv_number(v) for v in (xv, yv, data.values[j, i]))
                )
    return "\n".join(lines) + "\n"


def _csv_number(value: float) -> str:
    return repr(float(value))


def describe(values: Iterable[float]) -> str:
    return ", ".join(fmt(v, 4) for v in values)


# -- the medium editor ---------------------------------------------------------

SUBLAYER_FIELDS: tuple[str, ...] = tuple(
    dict.fromkeys(name for cls in SUBLAYER_TYPES for name in cls.FIELDS)
)
"""The inputs of a sublayer's row in the medium editor: every field of every
kind of sublayer (``movingpunch.media`` field tables; gamma_h 0: a
homogeneous ``Layer``, else a ``GradedLayer``)."""

HALF_SPACE_FIELDS: tuple[str, ...] = HalfSpace.FIELDS
"""The inputs of a half-space base."""

BASE_KINDS: tuple[str, ...] = ("springs", "bonded", "smooth")
"""The base selector: the springs (kw, kp, damping in the panel), or an
elastic half-space bonded to the stack or in frictionless contact with it."""

THICKNESS_SLACK = 1e-12
"""The thicknesses must sum to 1 within this (``movingpunch.media``)."""


def parse_sublayer(row: int, texts: dict[str, str]) -> Sublayer:
    """The sublayer of row ``row`` (1: the top) from the texts typed in its
    inputs (``SUBLAYER_FIELDS``; a field without a text takes its default,
    gamma_h 0). Raises InvalidParameterError naming the row, the parameter
    and its range (``.parameter``: the field's name). The top row's mu and
    rho are the units: 1."""
    values: dict[str, float] = {}
    for name in SUBLAYER_FIELDS:
        if name not in texts:
            continue
        try:
            values[name] = parse_param(name, texts[name])
        except InvalidParameterError as exc:
            raise InvalidParameterError(
                f"sublayer {row}: {exc}", parameter=name, allowed=exc.allowed
            ) from None
    if row == 1:
        for name in ("mu", "rho"):
            if values.get(name, 1.0) != 1.0:
                raise InvalidParameterError(
                    f"sublayer 1: the top sublayer's {name} is the unit of every "
                    f"{name} (1 by definition), got {fmt(values[name])}; give "
                    "the others per the top's",
                    parameter=name,
                    allowed="1 for the top sublayer",
                )
    if values.get("gamma_h", 0.0) == 0.0:
        scalars: dict[str, Any] = {n: v for n, v in values.items() if n in Layer.FIELDS}
        return Layer(**scalars)
    return GradedLayer(**{n: v for n, v in values.items() if n in GradedLayer.FIELDS})


def check_thicknesses(layers: Sequence[Sublayer]) -> None:
    """Raises InvalidParameterError (``.parameter`` "thickness") unless the
    thicknesses sum to 1, naming the sum and each row's thickness."""
    total = math.fsum(s.thickness for s in layers)
    if abs(total - 1.0) > THICKNESS_SLACK:
        rows = ", ".join(
            f"{k} {fmt(s.thickness, 6)}" for k, s in enumerate(layers, start=1)
        )
        raise InvalidParameterError(
            f"thickness: the sublayers' thicknesses sum to {fmt(total, 8)}, they "
            f"must sum to 1 (lengths are per the total thickness h; rows {rows}): "
            "ctrl+t normalises them",
            parameter="thickness",
            allowed="thicknesses summing to 1",
        )


def normalised(thicknesses: Sequence[float]) -> tuple[float, ...]:
    """The thicknesses scaled to sum to 1 (the last one takes the rounding,
    so the sum is 1 to the last bit where it can be)."""
    total = math.fsum(thicknesses)
    if not total > 0.0 or not math.isfinite(total):
        raise InvalidParameterError(
            "thickness: nothing to normalise (the thicknesses must be positive)",
            parameter="thickness",
            allowed="0 < thickness",
        )
    out = [t / total for t in thicknesses]
    if len(out) > 1:
        out[-1] = 1.0 - math.fsum(out[:-1])
    return tuple(out)


MATERIAL_KINDS: dict[str, str] = {
    "elastic": "elastic",
    "zener-deborah": "Zener, deborah",
    "zener-tau": "Zener, tau (h/c_T0)",
    "prony": "Prony (as loaded)",
}
"""The medium editor's material selector per sublayer: elastic, a standard
linear solid given by its deborah number V tau/h (one speed) or by its
relaxation time tau in h/c_T0 (deborah = sqrt(vstar) tau: the speed of the
panel sets it), or a scene's Prony series, kept as loaded."""


def material_of(sub: Sublayer) -> tuple[str, str, str]:
    """(kind, ratio text, time text) of a sublayer's material for the editor."""
    v = sub.viscoelastic if isinstance(sub, Layer) else None
    if v is None:
        return "elastic", "2", "0.1"
    if isinstance(v, Prony):
        return "prony", "", ""
    if v.tau is not None:
        return "zener-tau", fmt(v.ratio, 10), fmt(v.tau, 10)
    return "zener-deborah", fmt(v.ratio, 10), fmt(float(v.deborah or 0.0), 10)


def parse_material(
    row: int, kind: str, ratio: str, time: str, kept: Zener | Prony | None = None
) -> Zener | Prony | None:
    """The material of sublayer ``row`` from the editor's selector (a key of
    ``MATERIAL_KINDS``) and the texts of its ratio and time; "prony" keeps
    ``kept`` (a scene's series). Raises InvalidParameterError naming the row
    and the parameter (``.parameter``: "ratio", "deborah" or "tau")."""
    if kind not in MATERIAL_KINDS:
        raise InvalidParameterError(
            f"sublayer {row}: material must be one of {', '.join(MATERIAL_KINDS)}, "
            f"got {kind!r}",
            parameter="viscoelastic",
            allowed=", ".join(MATERIAL_KINDS),
        )
    if kind == "elastic":
        return None
    if kind == "prony":
        if not isinstance(kept, Prony):
            raise InvalidParameterError(
                f"sublayer {row}: a Prony series comes from a scene file; here "
                "choose elastic or Zener",
                parameter="viscoelastic",
                allowed="elastic, Zener (deborah or tau)",
            )
        return kept
    time_name = "tau" if kind == "zener-tau" else "deborah"
    values: dict[str, float] = {}
    for name, text in (("ratio", ratio), (time_name, time)):
        try:
            values[name] = float(text.strip())
        except ValueError:
            raise InvalidParameterError(
                f"sublayer {row}: {name} must be a number, got {text!r}",
                parameter=name,
                allowed="ratio >= 1; deborah, tau >= 0",
            ) from None
    try:
        return Zener(**values)
    except InvalidParameterError as exc:
        raise InvalidParameterError(
            f"sublayer {row}: {exc}", parameter=exc.parameter, allowed=exc.allowed
        ) from None


def parse_base(kind: str, texts: dict[str, str]) -> HalfSpace | None:
    """The base chosen: None for the springs (``kind`` "springs"), else a
    half-space ``kind`` "bonded" or "smooth" of the texts typed (mu, nu,
    rho). Raises InvalidParameterError naming the parameter and its range."""
    if kind not in BASE_KINDS:
        raise InvalidParameterError(
            f"base must be one of {', '.join(BASE_KINDS)}, got {kind!r}",
            parameter="base",
            allowed=", ".join(BASE_KINDS),
        )
    if kind == "springs":
        return None
    values = {}
    for name in HALF_SPACE_FIELDS:
        try:
            values[name] = parse_param(name, texts[name])
        except InvalidParameterError as exc:
            raise InvalidParameterError(
                f"half-space: {exc}", parameter=name, allowed=exc.allowed
            ) from None
    return HalfSpace(**values, interface=kind)


def with_medium(
    params: Params,
    layers: Sequence[Sublayer],
    half_space: HalfSpace | None,
    inertia: bool = True,
) -> Params:
    """``params`` on the medium of ``layers`` (top to bottom; their
    thicknesses checked), the base and the layer's ``inertia``. One
    homogeneous elastic sublayer with inertia is the panel's layer: its ν
    goes to the ν input and ``layers`` stays ()."""
    layers = tuple(layers)
    if not layers:
        raise InvalidParameterError(
            "layers: give at least one sublayer",
            parameter="layers",
            allowed="one or more sublayers, top to bottom",
        )
    check_thicknesses(layers)
    top = layers[0]
    if (
        len(layers) == 1
        and isinstance(top, Layer)
        and top.viscoelastic is None
        and inertia
    ):
        return replace(
            params, layers=(), half_space=half_space, nu=top.nu, inertia=True
        )
    return replace(params, layers=layers, half_space=half_space, inertia=inertia)
