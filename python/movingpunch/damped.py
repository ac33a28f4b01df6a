"""The punch on a damped (Kelvin-Voigt) Winkler foundation.

The base condition becomes sigma_y(x, -h) = k_w v + c_w dv/dt, i.e. in the
moving frame and in units h = mu = c_T = 1::

    sigma_y(x, -1) = kw v - damping * sqrt(vstar) * dv/dx,  damping = c_w c_T / mu

(c_w: pressure per unit velocity). With damping the contact (-b, a) is
asymmetric, a drag force appears without friction, and speeds at or above the
critical speed V*_cr solve; speeds at or above the Rayleigh speed V*_R do not.
``damping = 0`` is the paper's model: use :func:`movingpunch.solve`, which
takes the undamped path then. See docs/damped.md.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from types import MappingProxyType
from typing import overload

import numpy as np
import numpy.typing as npt

from movingpunch import _core, params
from movingpunch._evaluate import (
    _as_points,
    _check_flag,
    _check_kw,
    _check_nu,
    _check_positive,
    _check_tol,
    _check_vstar,
    _chunked_grid,
    _depths,
    _fail,
    _flat,
    _is_scalar,
    _json_safe,
    _pointwise,
    _real,
    _real_any,
)
from movingpunch.contract import Points
from movingpunch.errors import InvalidParameterError, SupercriticalSpeedError
from movingpunch.fields import FloatArray, StressField, StressPeaks, derived_stresses
from movingpunch.peaks import search_peaks

__all__ = ["DampedSolution", "check_damping", "damped_layer_response", "solve_damped"]

_N_MAX = 1024


def check_damping(value: object, *, positive: bool = False) -> float:
    """``value`` as a float damping (finite, >= 0; > 0 when ``positive``).

    Raises InvalidParameterError naming the parameter and its range
    (``movingpunch.params.SPECS["damping"]``).
    """
    x = params.check("damping", value)
    if positive and x == 0:
        raise params.fail(
            "damping",
            "damping must satisfy 0 < damping < inf for the damped solver "
            f"(damping = 0: movingpunch.solve), got {value!r}",
        )
    return x


def _check_damped_size(value: object) -> int:
    return params.check_size(value, _N_MAX, " for the damped solver")


@dataclass(frozen=True)
class DampedSolution:
    """Solution on a damped foundation (dimensionless: lengths per h,
    pressures and stresses per P/h). The punch moves towards +x."""

    vstar: float
    """V* = rho V^2/mu."""
    kw: float
    """k_w h/mu."""
    radius: float
    """R/h."""
    load: float
    """P/(mu h)."""
    nu: float
    """Poisson's ratio."""
    damping: float
    """c_w c_T/mu."""
    tol: float
    """Requested relative tolerance on the contact ends and on the pressure."""
    contact_interval: tuple[float, float]
    """(-b/h, a/h): trailing and leading ends of the contact."""
    drag: float
    """Horizontal force on the punch over P, int p x/R dx / P; positive when it
    opposes the motion."""
    critical_vstar: float
    """Critical speed V*_cr(kw, nu) of the undamped layer (may be exceeded)."""
    rayleigh_vstar: float
    """Rayleigh speed V*_R(nu) (the upper limit)."""
    phi1: float
    """Moving half-plane factor phi1(vstar, nu)."""
    iterations: int
    """Width evaluations over all collocation sizes."""
    collocation_n: int
    """Number N of collocation nodes of the final solve."""
    error_estimate: float
    """Bound on the absolute error of each contact end, in h (within a factor
    100 of the actual error or of the round-off floor; docs/damped.md §8)."""
    pressure_error_estimate: float
    """Bound on the error of p/(P/h) at a fixed relative position r = (x - c)/w
    in the contact (pointwise in x add |dp/dx| error_estimate); the solver
    refines N until it is at most tol * max_pressure."""
    stress_error_estimate: float
    """Bound on the error of the surface sigma_x/(P/h) at points more than
    1e-3 (a + b)/2 from the contact ends (sigma_x has a square-root cusp
    there)."""
    max_pressure: float
    """Maximum of p/(P/h) on the contact."""
    elapsed: float
    """Solve time in seconds."""
    valid: bool
    """True if p >= 0 on the contact and no penetration beside it."""
    validity: str
    """Account of the validity checks."""
    min_pressure: float
    """Minimum of p/(P/h) on the contact (0 at the smooth ends: see
    ``pressure_margin``)."""
    pressure_margin: float
    """min over r in (-1, 1) of p/((P/h) sqrt(1 - r^2)), r = (x - c)/w the
    position scaled to the contact: the safety margin before the contact
    separates (> 0 for a valid contact; 2/(pi a) for a narrow Hertz
    contact)."""
    min_gap: float
    """Minimum gap/h within 2(a + b) beside the contact."""
    other_half_widths: tuple[float, ...]
    """Half-widths (a + b)/(2h) of other contacts that carry the same load
    (above V*_cr the steady solution need not be unique; to about 1 %).
    Empty when none was found on [w/8, 4w]."""
    warnings: tuple[str, ...]
    """One line per requested accuracy that was not met (what, and by how
    much); empty when ``tol`` was met."""
    _impl: _core.DampedSolution = field(repr=False, compare=False)

    @property
    def kernel_builds(self) -> int:
        """Kernel tables this solve built (0: reused from the process-wide
        cache, as in a load or radius sweep at fixed vstar, kw, nu, damping)."""
        return int(self._impl.kernel_builds)

    @property
    def stage_times(self) -> Mapping[str, float]:
        """Seconds per stage of the solve, as ``Solution.stage_times``:
        ``critical_speed``, ``kernel`` (fetching or building the kernel table),
        ``width`` (the iteration on the ends over the N ladder) and ``checks``
        (the scan for other steady states, the estimates, validity). They sum
        to ``elapsed``."""
        return MappingProxyType(dict(self._impl.stage_seconds))

    @property
    def a(self) -> float:
        """Leading end a/h of the contact (-b, a)."""
        return self.contact_interval[1]

    @property
    def b(self) -> float:
        """Trailing end b/h of the contact (-b, a) (negative when the whole
        contact lies ahead of the punch's lowest point)."""
        return -self.contact_interval[0]

    @property
    def half_width(self) -> float:
        """(a + b)/(2h)."""
        return float(self._impl.half_width)

    @property
    def centre(self) -> float:
        """(a - b)/(2h)."""
        return float(self._impl.centre)

    @functools.cached_property
    def dissipation(self) -> float:
        """Power dissipated in the dashpots over P V, from the bottom face's
        slope by Parseval; equals ``drag`` by the energy balance."""
        return float(self._impl.dissipation())

    @overload
    def pressure(self, x: float) -> float: ...
    @overload
    def pressure(self, x: Points) -> FloatArray: ...
    def pressure(self, x: npt.ArrayLike) -> float | FloatArray:
        """p(x)/(P/h) (0 outside the contact)."""
        return _pointwise("x", x, self._impl.pressure)

    @overload
    def surface_slope(self, x: float) -> float: ...
    @overload
    def surface_slope(self, x: Points) -> FloatArray: ...
    def surface_slope(self, x: npt.ArrayLike) -> float | FloatArray:
        """Surface slope dv/dx(x, 0) (x/R on the contact)."""
        return _pointwise("x", x, self._impl.surface_slope)

    @overload
    def bottom_slope(self, x: float) -> float: ...
    @overload
    def bottom_slope(self, x: Points) -> FloatArray: ...
    def bottom_slope(self, x: npt.ArrayLike) -> float | FloatArray:
        """Slope dv/dx(x, -h) of the bottom face."""
        return _pointwise("x", x, self._impl.bottom_slope)

    @overload
    def surface_stress(self, x: float) -> float: ...
    @overload
    def surface_stress(self, x: Points) -> FloatArray: ...
    def surface_stress(self, x: npt.ArrayLike) -> float | FloatArray:
        """sigma_x(x, 0)/(P/h)."""
        return _pointwise("x", x, self._impl.surface_stress)

    @overload
    def depth_stress(self, y: float, x: float = ...) -> float: ...
    @overload
    def depth_stress(self, y: Points, x: float = ...) -> FloatArray: ...
    def depth_stress(self, y: npt.ArrayLike, x: float = 0.0) -> float | FloatArray:
        """sigma_x(x, y)/(P/h) at depths y/h in [-1, 0] (y = 0:
        ``surface_stress``), as ``Solution.depth_stress`` (which is at x = 0).
        The cost does not depend on y (the half-plane part is in closed form)."""
        pts = _depths(y)
        xs = _real_any("x", x)
        if not math.isfinite(xs):
            raise InvalidParameterError(f"x must be a finite number, got {x!r}")
        column = np.array([xs])
        grid = self._impl.stress_field
        return _pointwise("y", y, lambda ys: grid(column, ys)[0][:, 0], pts)

    @property
    def p0(self) -> float:
        """Pressure p(0)/(P/h) under the punch's axis x = 0 (not the contact's
        centre: the damped contact is asymmetric)."""
        return self.pressure(0.0)

    @functools.cached_property
    def indentation(self) -> float:
        """Indentation delta/h: how far the punch's lowest point lies below
        the undisturbed surface. The gap -delta + x^2/(2R) - v(x, 0) vanishes
        on the contact (delta is taken at its centre c: c^2/(2R) - v(c, 0)).
        Computed on first access (well under a millisecond)."""
        return float(self._impl.indentation)

    @overload
    def surface_displacement(self, x: float) -> float: ...
    @overload
    def surface_displacement(self, x: Points) -> FloatArray: ...
    def surface_displacement(self, x: npt.ArrayLike) -> float | FloatArray:
        """Vertical surface displacement v(x, 0)/h at x/h (negative under the
        punch), as ``Solution.surface_displacement``. A float for a scalar
        ``x``, else an array of the shape of ``x``."""
        return _pointwise("x", x, self._impl.surface_displacement)

    @overload
    def displacement(self, x: float, y: float = 0.0) -> float: ...
    @overload
    def displacement(self, x: Points, y: float = 0.0) -> FloatArray: ...
    def displacement(self, x: npt.ArrayLike, y: float = 0.0) -> float | FloatArray:
        """Vertical displacement v(x, y)/h at x/h and one depth y/h in [-1, 0]
        (negative downwards), as ``Solution.displacement``: y = 0 is
        ``surface_displacement``, y = -1 ``bottom_displacement``."""
        depth = _depths(y)
        if depth.ndim != 0:
            raise params.fail("y", f"y must be one depth in [-1, 0], got {y!r}")
        grid = self._impl.displacement
        return _pointwise("x", x, lambda xs: grid(xs, _flat(depth))[0])

    @overload
    def bottom_displacement(self, x: float) -> float: ...
    @overload
    def bottom_displacement(self, x: Points) -> FloatArray: ...
    def bottom_displacement(self, x: npt.ArrayLike) -> float | FloatArray:
        """Displacement v(x, -h)/h of the bottom face."""
        return _pointwise("x", x, self._impl.bottom_displacement)

    @overload
    def foundation_reaction(self, x: float) -> float: ...
    @overload
    def foundation_reaction(self, x: Points) -> FloatArray: ...
    def foundation_reaction(self, x: npt.ArrayLike) -> float | FloatArray:
        """Pressure of the base on the layer, -sigma_y(x, -h)/(P/h)
        (springs and dashpots together)."""
        field = self.stress_field(_flat(_as_points("x", x)), [-1.0])
        values = -field.sigma_y[0]
        return float(values[0]) if _is_scalar(x) else values.reshape(np.shape(x))

    def stress_field(self, x: npt.ArrayLike, y: npt.ArrayLike) -> StressField:
        """All stresses over P/h on the grid ``x`` (x/h) by ``y`` (y/h in
        [-1, 0]); arrays shaped (len(y), len(x)), as ``Solution.stress_field``.
        On the surface y = 0: sigma_x = ``surface_stress``, sigma_y = -p,
        tau_xy = 0 (the punch is frictionless)."""
        xs = _flat(_as_points("x", x))
        ys = _flat(_depths(y))
        sx, sy, txy = _chunked_grid(self._impl.stress_field, xs, ys)
        sz, vm, ms = derived_stresses(sx, sy, txy, self.nu)
        return StressField(
            x=xs,
            y=ys,
            sigma_x=sx,
            sigma_y=sy,
            tau_xy=txy,
            sigma_z=sz,
            von_mises=vm,
            max_shear=ms,
        )

    def stress_peaks(self, extent: float | None = None) -> StressPeaks:
        """Peaks of sigma_x/(P/h), as ``Solution.stress_peaks``: most
        compressive and most tensile on the top surface, most tensile at the
        bottom, with their x/h, and sigma_x at (0, 0) and (0, -h). The damped
        distributions are not even in x: the same search
        (``movingpunch.peaks.search_peaks``) covers -extent <= x <= extent
        (default max(6 max(a, b), 10 h)) with both contact ends as cusps, and
        positions may be negative (behind the punch's lowest point). Each
        value is refined to ``tol`` relative to the larger centre stress;
        ``error_bound`` is ``stress_error_estimate`` (the solution's error)
        plus the search's own uncertainty. Seconds: each surface point costs a
        Fourier integral."""
        lo_end, hi_end = self.contact_interval
        reach = max(abs(lo_end), abs(hi_end))
        if extent is None:
            span = max(6.0 * reach, 10.0)
        else:
            span = _real_any("extent", extent)
            if not (math.isfinite(span) and span > 0.0):
                raise InvalidParameterError(
                    f"extent must be a finite number > 0, got {extent!r}"
                )
        depth = np.array([-1.0])
        centre_top = float(self._impl.surface_stress(np.array([0.0]))[0])
        centre_bottom = float(self._impl.stress_field(np.array([0.0]), depth)[0][0, 0])
        alpha = _core.critical_speed(self.kw, self.nu)[1]
        wave = 2.0 * math.pi / alpha if 0.0 < alpha < math.inf else math.inf
        scale = max(abs(centre_top), abs(centre_bottom), 1e-300)
        found = search_peaks(
            self._impl.surface_stress,
            lambda x: self._impl.stress_field(x, depth)[0][0],
            lo=-float(span),
            hi=float(span),
            ends=(lo_end, hi_end),
            wavelength=wave,
            tolerance=self.tol * scale,
        )
        search = max(p.uncertainty for p in found.peaks)
        return StressPeaks(
            top_compressive=found.top_min.value,
            top_compressive_x=found.top_min.x,
            top_tensile=found.top_max.value,
            top_tensile_x=found.top_max.x,
            bottom_tensile=found.bottom_max.value,
            bottom_tensile_x=found.bottom_max.x,
            centre_top=centre_top,
            centre_bottom=centre_bottom,
            search_extent=float(span),
            error_bound=self.stress_error_estimate + search,
            search_error=search,
            warnings=found.warnings,
        )

    def to_dict(self) -> dict[str, object]:
        """Every public field, JSON-safe."""
        data = {
            f.name: _json_safe(getattr(self, f.name))
            for f in fields(self)
            if not f.name.startswith("_")
        }
        data["contact_interval"] = list(self.contact_interval)
        data["other_half_widths"] = list(self.other_half_widths)
        data["warnings"] = list(self.warnings)
        data["dissipation"] = self.dissipation
        data["indentation"] = self.indentation
        data["p0"] = self.p0
        data["a"] = self.a
        data["half_width"] = self.half_width
        data["centre"] = self.centre
        data["kernel_builds"] = self.kernel_builds
        data["stage_times"] = _json_safe(dict(self.stage_times))
        return data


def solve_damped(
    *,
    vstar: float,
    kw: float,
    radius: float,
    load: float,
    nu: float = 0.2,
    damping: float,
    tol: float | str = 1e-8,
    allow_unphysical: bool = False,
    n: int | None = None,
) -> DampedSolution:
    """Solves the contact problem on a damped foundation (``damping`` > 0).

    Speeds up to (not including) the Rayleigh speed solve, above the critical
    speed too. Raises InvalidParameterError, SupercriticalSpeedError (vstar >=
    V*_R), UnphysicalContactError (unless ``allow_unphysical``) and
    ConvergenceError.
    """
    inputs = {
        "vstar": _check_vstar(vstar),
        "kw": _check_kw(kw),
        "radius": _check_positive("radius", radius),
        "load": _check_positive("load", load),
        "nu": _check_nu(nu),
        "damping": check_damping(damping, positive=True),
        "tol": _check_tol(tol),
    }
    flag = _check_flag("allow_unphysical", allow_unphysical)
    size = _check_damped_size(n)
    vr = float(_core.rayleigh_vstar(inputs["nu"]))
    if inputs["vstar"] >= vr:
        raise SupercriticalSpeedError(
            f"vstar = {inputs['vstar']!r} is at or above the Rayleigh speed "
            f"V*_R = {vr:.10f} (nu = {inputs['nu']!r}): even with damping there "
            f"is no steady solution there; vstar must be in [0, {vr:.10f})",
            vstar=inputs["vstar"],
            critical_vstar=None,
            rayleigh_vstar=vr,
        )
    impl = _core.solve_damped(**inputs, allow_unphysical=flag, n=size)
    return DampedSolution(
        **inputs,
        contact_interval=(float(impl.left), float(impl.right)),
        drag=float(impl.drag),
        critical_vstar=float(impl.critical_vstar),
        rayleigh_vstar=float(impl.rayleigh_vstar),
        phi1=float(impl.phi1),
        iterations=int(impl.iterations),
        collocation_n=int(impl.collocation_n),
        error_estimate=float(impl.error_estimate),
        pressure_error_estimate=float(impl.pressure_error_estimate),
        stress_error_estimate=float(impl.stress_error_estimate),
        max_pressure=float(impl.max_pressure),
        elapsed=float(impl.elapsed),
        valid=bool(impl.valid),
        validity=str(impl.validity),
        min_pressure=float(impl.min_pressure),
        pressure_margin=float(impl.pressure_margin),
        min_gap=float(impl.min_gap),
        other_half_widths=tuple(float(w) for w in impl.other_half_widths),
        warnings=tuple(str(w) for w in impl.warnings),
        _impl=impl,
    )


def damped_layer_response(
    t: float, *, vstar: float, kw: float, nu: float = 0.2, damping: float
) -> tuple[complex, complex, complex]:
    """(M1, M2, Wb) of the damped layer per unit transformed pressure at
    t = alpha h >= 0: M1 = -alpha v^(alpha, 0)/p^, M2 = -sigma_x^(alpha, 0)/p^,
    Wb = alpha v^(alpha, -h)/p^, for modes e^{i alpha x} (alpha < 0: the
    complex conjugates)."""
    tt = _real("t", t)
    if not (math.isfinite(tt) and tt >= 0):
        raise _fail("t", tt)
    m1, m2, wb = _core.damped_layer_response(
        tt, _check_vstar(vstar), _check_kw(kw), _check_nu(nu), check_damping(damping)
    )
    return complex(m1), complex(m2), complex(wb)
