"""Evaluating a solution at user-given points: the shared plumbing of every
result class (movingpunch.contract).

Points are checked (finite reals; masked arrays refused; depths in the
layer), evaluated by the core's vectorised functions in slices of about
``_CHUNK_SECONDS`` (so Ctrl-C stops a long evaluation), and returned as a
float for a scalar argument, else an array of the argument's shape.

Pure NumPy: no _core import (callers pass the core's functions).
"""

from __future__ import annotations

import math
import numbers
import time
from collections.abc import Callable, Mapping

import numpy as np
import numpy.typing as npt

from movingpunch import params
from movingpunch.errors import InvalidParameterError
from movingpunch.fields import FloatArray


def _as_points(name: str, x: object) -> FloatArray:
    """``x`` as a float64 array of finite values (any shape). Masked arrays
    are refused: their mask would be ignored."""
    if isinstance(x, np.ma.MaskedArray):
        raise InvalidParameterError(
            f"{name} must be a plain array; masked arrays are not supported: "
            f"use {name}.filled(...) or {name}.compressed()",
            parameter=name,
        )
    try:
        raw = np.asarray(x)
    except (TypeError, ValueError) as exc:
        raise InvalidParameterError(
            f"{name} must be a real number or an array of them, got {x!r}",
            parameter=name,
        ) from exc
    if raw.dtype.kind not in "iuf":
        raise InvalidParameterError(
            f"{name} must be a real number or an array of them, got {x!r}",
            parameter=name,
        )
    points = np.asarray(raw, dtype=np.float64)
    bad = ~np.isfinite(points)
    if bad.any():
        first = float(points[bad].flat[0])
        raise InvalidParameterError(
            f"{name} must contain only finite numbers, got {first!r}", parameter=name
        )
    return points


def _depths(y: object) -> FloatArray:
    """``y`` as float64 depths y/h, each in [-1, 0]."""
    points = _as_points("y", y)
    bad = (points < -1.0) | (points > 0.0)
    if bad.any():
        x = float(points[bad].flat[0])
        raise params.fail("y", f"y must satisfy {params.range_text('y')}, got {x!r}")
    return points


def _check_positive_extent(value: object) -> float:
    return params.check("extent", value)


def _real_any(name: str, value: object) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise InvalidParameterError(
            f"{name} must be a real number, got {value!r}", parameter=name
        )
    try:
        return float(value)
    except OverflowError:
        raise InvalidParameterError(
            f"{name} is too large for a float", parameter=name
        ) from None


def _real(name: str, value: object) -> float:
    """``value`` as a float if it is a real number (bool, str, None, complex
    and everything else are rejected; so are integers beyond float range).
    The range of ``name`` is not checked (``movingpunch.params.check`` does)."""
    x, problem = params.classify(name, value)
    if problem in ("type", "overflow"):
        params.check(name, value)  # raises, naming name and its range
    return x


def _fail(name: str, x: float) -> InvalidParameterError:
    return params.fail(
        name, f"{name} must satisfy {params.range_text(name)}, got {x!r}"
    )


def _check_vstar(value: object) -> float:
    # The upper bound V*_cr(kw, nu) is checked by the core, which raises
    # SupercriticalSpeedError with the critical and Rayleigh speeds.
    return params.check("vstar", value)


def _check_kw(value: object) -> float:
    # kw = 0 (no foundation) has no static equilibrium (V*_cr = 0); below 1e-12
    # the lowest free wave lies beyond the critical-speed search.
    return params.check("kw", value)


def _check_kp(value: object) -> float:
    # The Pasternak layer's shear stiffness: finite, >= 0 (0: springs alone).
    return params.check("kp", value)


def _check_positive(name: str, value: object) -> float:
    """radius or load (the name says which): its range in movingpunch.params."""
    return params.check(name, value)


def _check_nu(value: object) -> float:
    return params.check("nu", value)


def _check_tol(value: object) -> float:
    """A tolerance: a number in [1e-14, 1e-2] or the name of a preset."""
    return params.check("tol", value)


def _check_flag(name: str, value: object) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise InvalidParameterError(
            f"{name} must be True or False, got {value!r}",
            parameter=name,
            allowed="True or False",
        )
    return bool(value)


def _pointwise(
    name: str,
    x: npt.ArrayLike,
    evaluate: Callable[[FloatArray], FloatArray],
    points: FloatArray | None = None,
) -> float | FloatArray:
    """Applies a vectorised core function to ``x``: a float for a scalar
    ``x``, else an array of the shape of ``x``."""
    pts = _as_points(name, x) if points is None else points
    values = _chunked(evaluate, _flat(pts))
    return float(values[0]) if _is_scalar(x) else values.reshape(pts.shape)


_FIRST_CHUNK = 32
"""Points of the first call of a chunked evaluation (which times it)."""
_CHUNK_SECONDS = 0.2
"""Target duration of each further call: Python takes control between calls,
so Ctrl-C (KeyboardInterrupt) stops a long evaluation within about this."""


def _chunked(
    evaluate: Callable[[FloatArray], FloatArray], points: FloatArray
) -> FloatArray:
    """``evaluate(points)`` (a 1-d array in, one value per point out) in calls
    of about ``_CHUNK_SECONDS`` each, sized by the measured cost per point,
    so that the interpreter can raise KeyboardInterrupt in between. Small
    calls take one call."""
    parts = _chunk_calls(lambda lo, hi: evaluate(points[lo:hi]), len(points))
    return parts[0] if len(parts) == 1 else np.concatenate(parts)


def _chunk_calls(run: Callable[[int, int], FloatArray], n: int) -> list[FloatArray]:
    """Calls ``run(lo, hi)`` over [0, n) in consecutive slices: first
    ``_FIRST_CHUNK`` points, then slices that take about ``_CHUNK_SECONDS``
    at the cost per point measured so far (the rest in one call if it would
    take no longer). Returns the results in order."""
    if n <= _FIRST_CHUNK:
        return [run(0, n)]
    parts: list[FloatArray] = []
    done, spent = 0, 0.0
    size = _FIRST_CHUNK
    while done < n:
        hi = min(n, done + size)
        start = time.perf_counter()
        parts.append(run(done, hi))
        spent += time.perf_counter() - start
        done = hi
        per_point = max(spent / done, 1e-9)
        size = max(_FIRST_CHUNK, int(_CHUNK_SECONDS / per_point))
        if (n - done) * per_point <= 1.25 * _CHUNK_SECONDS:
            size = n - done
    return parts


def _chunked_grid(
    evaluate: Callable[[FloatArray, FloatArray], tuple[FloatArray, ...]],
    xs: FloatArray,
    ys: FloatArray,
) -> tuple[FloatArray, ...]:
    """A grid evaluation (arrays shaped (len(ys), len(xs))) in slices of
    ``xs`` as ``_chunked`` does, joined along x."""
    parts: list[tuple[FloatArray, ...]] = []

    def run(lo: int, hi: int) -> FloatArray:
        parts.append(evaluate(xs[lo:hi], ys))
        return np.empty(0)

    _chunk_calls(run, len(xs))
    if len(parts) == 1:
        return parts[0]
    return tuple(
        np.concatenate([p[k] for p in parts], axis=1) for k in range(len(parts[0]))
    )


def _is_scalar(x: npt.ArrayLike) -> bool:
    """A plain scalar (not a 0-d array): results for it are floats."""
    return not isinstance(x, np.ndarray) and np.ndim(x) == 0


def _flat(points: FloatArray) -> FloatArray:
    return np.ascontiguousarray(points.reshape(-1))


def _json_safe(value: object) -> object:
    if isinstance(value, Mapping):
        return {str(k): _json_safe(v) for k, v in value.items()}
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)  # "inf", "-inf", "nan"
    return value


def _check_solve_inputs(
    vstar: object,
    kw: object,
    radius: object,
    load: object,
    nu: object,
    tol: object,
    kp: object = 0.0,
) -> dict[str, float]:
    """The inputs every solve takes, checked (InvalidParameterError names the
    first bad one and its range), as keyword arguments of the core's solve."""
    return {
        "vstar": _check_vstar(vstar),
        "kw": _check_kw(kw),
        "kp": _check_kp(kp),
        "radius": _check_positive("radius", radius),
        "load": _check_positive("load", load),
        "nu": _check_nu(nu),
        "tol": _check_tol(tol),
    }
