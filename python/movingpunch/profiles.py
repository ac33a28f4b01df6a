"""Punch profiles: the shape pressed onto the layer (docs/theory.md section 13).

``movingpunch.solve(..., profile=...)`` takes one of

* ``Cylinder(radius)``: the paper's punch, f(x) = x^2/(2R) (``radius=R`` is
  its shorthand);
* ``Flat(half_width)``: a flat face of half-width b with square corners. The
  contact is the face (-b, b) and the pressure is unbounded at both ends,
  p ~ K/sqrt(2 pi (b - |x|)), with the end coefficient K reported by
  ``Solution.end_coefficients``;
* ``RoundedFlat(half_width, radius)``: a flat face of half-width b whose
  corners have the radius R, in the parabolic approximation the cylinder
  uses: f = 0 on |x| <= b, (|x| - b)^2/(2R) beyond. The contact (-a, a) is
  wider than the face (a > b for every load > 0) and its pressure bounded;
* ``Profile(x, y)``: a convex table of heights y(x) (x ascending, spanning
  the punch's axis x = 0; symmetric or not), interpolated by a not-a-knot
  cubic spline (which reproduces cubics, so a parabola exactly);
  ``Profile.from_function`` samples a callable. An asymmetric table takes
  the asymmetric solver (as damping or friction do).

Each is a frozen dataclass, validated when made (InvalidParameterError names
the parameter and its range); ``to_dict()`` gives the scene-file form
(``[params.profile]``), ``profile_from_dict`` reads it back. Dimensionless:
lengths per layer thickness h.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from movingpunch import _core, params
from movingpunch.errors import InvalidParameterError

__all__ = [
    "PROFILE_KINDS",
    "Cylinder",
    "Flat",
    "Profile",
    "PunchProfile",
    "RoundedFlat",
    "check_profile",
    "profile_from_dict",
    "resolve_profile",
]

FloatArray = npt.NDArray[np.float64]

FLAT_MIN_HALF_WIDTH = 1e-10
"""The narrowest flat face the solver takes (b/h; the supported contact widths
start there)."""


def _half_width(value: object, least: float) -> float:
    """``half_width`` checked against its range and ``least`` (a flat punch's
    face must have a width: >= 1e-10)."""
    x = params.check("half_width", value)
    if x < least:
        raise params.fail(
            "half_width",
            f"half_width of a flat punch must be >= {least:g} (b/h), got {x!r}",
        )
    return x


class _Shape:
    """What every profile offers (see the subclasses)."""

    kind: ClassVar[str]

    def core_args(self) -> dict[str, Any]:
        """Keyword arguments of ``_core.solve_contact`` for this shape: its
        kind and its parameters (radius 1.0 where unused)."""
        x = getattr(self, "x", ())
        y = getattr(self, "y", ())
        return {
            "profile": self.kind,
            "radius": float(getattr(self, "radius", 1.0)),
            "half_width": float(getattr(self, "half_width", 0.0)),
            "table_x": list(x),
            "table_y": list(y),
        }

    @property
    def nominal_radius(self) -> float:
        """What ``Solution.radius`` shows: the cylinder's or the corners'
        radius R/h; inf for a flat punch or a table."""
        return float(getattr(self, "radius", math.inf))

    def describe(self) -> str:
        """One line, e.g. "flat punch, half-width b/h = 0.5"."""
        raise NotImplementedError  # pragma: no cover

    def to_dict(self) -> dict[str, object]:
        """The scene-file form: ``{"kind": ..., <parameters>}``."""
        raise NotImplementedError  # pragma: no cover

    def height(self, x: npt.ArrayLike) -> FloatArray:
        """f(x) - f(0) over h at each x/h, as the solver uses it."""
        return self._shape(x)[0]

    def slope(self, x: npt.ArrayLike) -> FloatArray:
        """f'(x) at each x/h, as the solver uses it (the right-hand side)."""
        return self._shape(x)[1]

    def _shape(self, x: npt.ArrayLike) -> tuple[FloatArray, FloatArray]:
        pts = np.ascontiguousarray(np.asarray(x, dtype=np.float64).reshape(-1))
        if not np.all(np.isfinite(pts)):
            raise InvalidParameterError("x must be finite", parameter="x")
        args = self.core_args()
        f, df = _core.profile_shape(
            kind=args["profile"],
            radius=args["radius"],
            half_width=args["half_width"],
            table_x=args["table_x"],
            table_y=args["table_y"],
            x=pts,
        )
        shape = np.shape(x)
        return f.reshape(shape), df.reshape(shape)


@dataclass(frozen=True)
class Cylinder(_Shape):
    """A cylinder of radius R/h (parabolic approximation f = x^2/(2R)): the
    paper's punch; ``solve(radius=R)`` is its shorthand."""

    radius: float
    kind: ClassVar[str] = "cylinder"

    def __post_init__(self) -> None:
        object.__setattr__(self, "radius", params.check("radius", self.radius))

    def describe(self) -> str:
        return f"cylinder, R/h = {self.radius:g}"

    def to_dict(self) -> dict[str, object]:
        return {"kind": self.kind, "radius": self.radius}


@dataclass(frozen=True)
class Flat(_Shape):
    """A flat face of half-width b/h with square corners. The contact is the
    face; the pressure is unbounded at its ends (index +1),
    p(b r) = (P/h) g(r)/sqrt(1 - r^2), and ``Solution.end_coefficients``
    gives K = lim_{x -> b} sqrt(2 pi (b - x)) p(x) in (P/h) sqrt(h)
    (P/sqrt(pi b) on a half-plane). ``half_width`` in [1e-10, 50]."""

    half_width: float
    kind: ClassVar[str] = "flat"

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "half_width", _half_width(self.half_width, FLAT_MIN_HALF_WIDTH)
        )

    def describe(self) -> str:
        return f"flat punch, half-width b/h = {self.half_width:g}"

    def to_dict(self) -> dict[str, object]:
        return {"kind": self.kind, "half_width": self.half_width}


@dataclass(frozen=True)
class RoundedFlat(_Shape):
    """A flat face of half-width b/h (``half_width`` in [0, 50]; 0 is the
    cylinder) with corners of radius R/h (``radius``), parabolic as the
    cylinder: f = 0 on |x| <= b, (|x| - b)^2/(2R) beyond. The contact
    (-a, a) reaches past the face (a > b for any load) and its pressure is
    bounded."""

    half_width: float
    radius: float
    kind: ClassVar[str] = "rounded_flat"

    def __post_init__(self) -> None:
        object.__setattr__(self, "half_width", _half_width(self.half_width, 0.0))
        object.__setattr__(self, "radius", params.check("radius", self.radius))

    def describe(self) -> str:
        return (
            f"rounded flat punch, half-width b/h = {self.half_width:g}, "
            f"corner radius R/h = {self.radius:g}"
        )

    def to_dict(self) -> dict[str, object]:
        return {
            "kind": self.kind,
            "half_width": self.half_width,
            "radius": self.radius,
        }


def _table(name: str, values: object) -> tuple[float, ...]:
    if isinstance(values, (str, bytes)) or not isinstance(
        values, (Sequence, np.ndarray)
    ):
        raise InvalidParameterError(
            f"{name} must be a sequence of numbers, got {values!r}", parameter=name
        )
    out = []
    for i, v in enumerate(values):
        if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Real):
            raise InvalidParameterError(
                f"{name}[{i}] must be a real number, got {v!r}", parameter=name
            )
        out.append(float(v))
    return tuple(out)


@dataclass(frozen=True)
class Profile(_Shape):
    """A tabulated punch: heights ``y`` (over h) at positions ``x`` (over h,
    strictly ascending, x_0 < 0 < x_{n-1}: heights count from the punch's
    axis x = 0) and convex (chord slopes non-decreasing to 1e-9 of the
    largest). At least 5 points. A table symmetric about x = 0
    (x_i = -x_{n-1-i}, y_i = y_{n-1-i} to 1e-9 of max|x| and of the range of
    y) solves on the undamped (symmetric) solver when damping and friction
    are 0; any other takes the asymmetric solver. The solver
    uses the slope of the table's not-a-knot cubic spline (exact for a
    parabola; a C^2 interpolant of smooth data, error O(spacing^4) in the
    height). The contact must stay within the table: a load that needs a
    wider contact is refused, naming the table's extent."""

    x: tuple[float, ...]
    y: tuple[float, ...]
    kind: ClassVar[str] = "table"

    def __post_init__(self) -> None:
        xs, ys = _table("profile.x", self.x), _table("profile.y", self.y)
        _core.check_profile_table(list(xs), list(ys))  # InvalidParameterError
        object.__setattr__(self, "x", xs)
        object.__setattr__(self, "y", ys)

    @classmethod
    def from_function(
        cls,
        f: Callable[[FloatArray], npt.ArrayLike],
        half_extent: float,
        points: int = 2001,
    ) -> Profile:
        """The table of ``f`` (heights over h, vectorised over x/h) at
        ``points`` (odd, >= 5) equally spaced x in [-half_extent,
        half_extent], mirrored exactly about 0; f is called once on all of
        them (f need not be even: an asymmetric table takes the asymmetric
        solver). A function of a float only (``math.cos``, an ``if x > 0``:
        TypeError or ValueError on the array) is called once per point
        instead; one that fails both ways is an InvalidParameterError naming
        ``f``."""
        extent = params.check("half_width", half_extent)
        if extent <= 0:
            raise params.fail("half_width", f"half_extent must be > 0, got {extent!r}")
        count: object = points
        if (
            isinstance(count, bool)
            or not isinstance(count, numbers.Integral)
            or int(count) < 5
            or int(count) % 2 == 0
        ):
            raise InvalidParameterError(
                f"points must be an odd integer >= 5, got {points!r}",
                parameter="points",
            )
        half = extent * np.linspace(0.0, 1.0, (int(count) + 1) // 2)
        xs = np.concatenate([-half[:0:-1], half])
        ys = _heights(f, xs)
        if ys.shape != xs.shape:
            raise InvalidParameterError(
                f"f must return one height per x ({xs.size}), got {ys.size}",
                parameter="profile.y",
            )
        return cls(tuple(xs.tolist()), tuple(ys.tolist()))

    @property
    def half_extent(self) -> float:
        """The table's extent on both sides, min(-x_0, x_{n-1}) (a symmetric
        contact must stay within it)."""
        return min(-self.x[0], self.x[-1])

    @property
    def symmetric(self) -> bool:
        """True when the table is symmetric about x = 0 (to 1e-9 of max|x|
        and of the range of y)."""
        return bool(_core.profile_table_symmetric(list(self.x), list(self.y)))

    def describe(self) -> str:
        if not self.symmetric:
            return (
                f"asymmetric tabulated profile of {len(self.x)} points, "
                f"{self.x[0]:g} <= x/h <= {self.x[-1]:g}"
            )
        return (
            f"tabulated profile of {len(self.x)} points, |x|/h <= {self.half_extent:g}"
        )

    def to_dict(self) -> dict[str, object]:
        return {"kind": self.kind, "x": list(self.x), "y": list(self.y)}


def _heights(f: Callable[[FloatArray], npt.ArrayLike], xs: FloatArray) -> FloatArray:
    """``f`` at every x of ``xs`` (a 1-d array): one call on the array; if
    ``f`` does not take arrays (TypeError or ValueError), one call per x."""
    try:
        return np.asarray(f(xs), dtype=np.float64).reshape(-1)
    except (TypeError, ValueError) as exc:
        on_array = f"{type(exc).__name__}: {exc}"
    point: Callable[[float], object] = f  # type: ignore[assignment]
    x = float(xs[0])
    try:
        values = []
        for x in xs.tolist():
            values.append(float(point(x)))  # type: ignore[arg-type]
    except Exception as exc:
        raise InvalidParameterError(
            "f must accept a NumPy array of x/h and return one height per x "
            "(or accept a float x/h and return a float height); called with "
            f"the array of {xs.size} x it raised {on_array}; called with "
            f"x = {x!r} it raised {type(exc).__name__}: {exc}",
            parameter="f",
            allowed="a function of x/h, vectorised over NumPy arrays",
        ) from exc
    return np.asarray(values, dtype=np.float64)


PunchProfile = Cylinder | Flat | RoundedFlat | Profile
"""Any punch shape ``solve(profile=...)`` takes."""

PROFILE_KINDS: tuple[str, ...] = ("cylinder", "flat", "rounded_flat", "table")
"""The ``kind`` names of the scene files' ``[params.profile]``."""


def check_profile(value: object) -> PunchProfile:
    """``value`` if it is a profile, else InvalidParameterError."""
    if isinstance(value, (Cylinder, Flat, RoundedFlat, Profile)):
        return value
    raise InvalidParameterError(
        "profile must be movingpunch.Cylinder, Flat, RoundedFlat or Profile, "
        f"got {value!r}",
        parameter="profile",
        allowed="Cylinder, Flat, RoundedFlat or Profile",
    )


def resolve_profile(radius: object, profile: object) -> PunchProfile:
    """The punch of ``solve(radius=..., profile=...)``: ``profile`` (checked),
    or ``Cylinder(radius)``. Both given: only if the profile has that very
    radius (a Cylinder or a RoundedFlat's corners), else InvalidParameterError
    naming ``radius``; neither: InvalidParameterError naming ``radius``."""
    if profile is None:
        if radius is None:
            raise InvalidParameterError(
                f"radius must be given ({params.range_text('radius')}, a cylinder) "
                "unless profile is (mp.Cylinder, Flat, RoundedFlat or Profile)",
                parameter="radius",
                allowed=params.range_text("radius"),
            )
        return Cylinder(radius)  # type: ignore[arg-type]
    shape = check_profile(profile)
    if radius is not None:
        r = params.check("radius", radius)
        own = getattr(shape, "radius", None)
        if own is None or own != r:
            raise InvalidParameterError(
                f"radius = {r!r} disagrees with profile = {shape.describe()}: give "
                "radius (a cylinder) or profile, or both only when the profile has "
                "that radius (a Cylinder or a RoundedFlat's corners)",
                parameter="radius",
                allowed="None when profile is given (or the profile's own radius)",
            )
    return shape


_KEYS: Mapping[str, tuple[str, ...]] = {
    "cylinder": ("radius",),
    "flat": ("half_width",),
    "rounded_flat": ("half_width", "radius"),
    "table": ("x", "y"),
}


def profile_from_dict(
    data: Mapping[str, object], where: str = "profile"
) -> PunchProfile:
    """The profile of a scene file's ``[params.profile]`` table (``kind`` and
    its keys: ``to_dict()``'s form). Errors name ``where.key``."""
    kind = data.get("kind")
    if kind not in _KEYS:
        raise InvalidParameterError(
            f"{where}.kind must be one of {', '.join(PROFILE_KINDS)}, got {kind!r}",
            parameter=f"{where}.kind",
            allowed=", ".join(PROFILE_KINDS),
        )
    keys = _KEYS[str(kind)]
    unknown = sorted(set(data) - {"kind", *keys})
    if unknown:
        raise InvalidParameterError(
            f"{where}: unknown key {unknown[0]!r} for kind = {kind!r} "
            f"(its keys: {', '.join(keys)})",
            parameter=f"{where}.{unknown[0]}",
        )
    missing = [k for k in keys if k not in data]
    if missing:
        raise InvalidParameterError(
            f"{where}: kind = {kind!r} needs {', '.join(keys)}; "
            f"{missing[0]!r} is missing",
            parameter=f"{where}.{missing[0]}",
        )
    try:
        if kind == "cylinder":
            return Cylinder(data["radius"])  # type: ignore[arg-type]
        if kind == "flat":
            return Flat(data["half_width"])  # type: ignore[arg-type]
        if kind == "rounded_flat":
            return RoundedFlat(data["half_width"], data["radius"])  # type: ignore[arg-type]
        return Profile(data["x"], data["y"])  # type: ignore[arg-type]
    except InvalidParameterError as exc:
        name = exc.parameter or ""
        key = name.split(".")[-1] if name else ""
        raise InvalidParameterError(
            f"{where}: {exc}",
            parameter=f"{where}.{key}" if key else where,
            allowed=exc.allowed,
        ) from exc
