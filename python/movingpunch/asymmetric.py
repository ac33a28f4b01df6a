"""The asymmetric solution: the punch on a damped (Kelvin-Voigt) Winkler
foundation and/or sliding with Coulomb friction.

The base condition becomes sigma_y(x, -h) = k_w v + c_w dv/dt, i.e. in the
moving frame and in units h = mu = c_T = 1::

    sigma_y(x, -1) = kw v - damping * sqrt(vstar) * dv/dx,  damping = c_w c_T / mu

(c_w: pressure per unit velocity). With damping the contact (-b, a) is
asymmetric, a drag force appears without friction, and speeds at or above the
critical speed V*_cr solve; speeds at or above the Rayleigh speed V*_R do not.
``damping = 0`` is the paper's model: use :func:`movingpunch.solve`, which
takes the undamped path then. See docs/damped.md.

Coulomb friction (``friction`` = f > 0, with any damping >= 0): the punch
moves towards +x and the layer's surface under it carries the shear traction
f p in the direction of motion; the contact (-b, a) is asymmetric, the
pressure ends like (x + b)^gamma_back (a - x)^gamma_front with
cot(pi gamma_back) = f Phi(vstar, nu) (docs/theory.md section 14).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import overload

import numpy.typing as npt

from movingpunch import _core, params
from movingpunch._evaluate import (
    _check_flag,
    _check_kp,
    _check_kw,
    _check_nu,
    _check_solve_inputs,
    _check_vstar,
    _fail,
    _pointwise,
    _real,
)
from movingpunch._evaluations import ResultFields
from movingpunch.contract import Points
from movingpunch.errors import SupercriticalSpeedError
from movingpunch.fields import FloatArray
from movingpunch.media import HalfSpace, Medium
from movingpunch.profiles import Profile, PunchProfile, resolve_profile
from movingpunch.zones import PunchResult, single_punch

__all__ = [
    "AsymmetricSolution",
    "check_damping",
    "check_friction",
    "coupling_constant",
    "damped_layer_response",
    "end_exponents",
    "solve_asymmetric",
]

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
            "damping must satisfy 0 < damping < inf for the asymmetric solver "
            f"(damping = 0: movingpunch.solve), got {value!r}",
        )
    return x


def check_friction(value: object) -> float:
    """``value`` as a float Coulomb friction coefficient (finite, >= 0).

    Raises InvalidParameterError naming the parameter and its range
    (``movingpunch.params.SPECS["friction"]``)."""
    return params.check("friction", value)


def coupling_constant(vstar: float, nu: float = 0.2) -> float:
    """Phi(V*, nu) = (2 - s - 2 nL nT)/(s nL): the factor of the local term
    f Phi p(x) that friction adds to the moving half-plane's equation
    ((1 - 2 nu)/(2 (1 - nu)) at rest; finite at the Rayleigh speed)."""
    return float(_core.tangential_half_plane(_check_vstar(vstar), _check_nu(nu))[2])


def end_exponents(
    friction: float, vstar: float, nu: float = 0.2
) -> tuple[float, float]:
    """(gamma_back, gamma_front) of a cylinder sliding with friction f on the
    moving half-plane (and on the layer, whose regular kernels do not change
    them): cot(pi gamma_back) = f Phi(V*, nu), gamma_front = 1 - gamma_back."""
    back, front = _core.end_exponents(
        check_friction(friction), coupling_constant(vstar, nu)
    )
    return (float(back), float(front))


def _check_asymmetric_size(value: object) -> int:
    return params.check_size(value, _N_MAX, " for the asymmetric solver")


@dataclass(frozen=True)
class AsymmetricSolution(ResultFields):
    """The asymmetric solution: a damped foundation and/or Coulomb friction
    (dimensionless: lengths per h, pressures and stresses per P/h). The punch
    moves towards +x; (-b, a) are its trailing and leading ends."""

    damping: float
    """c_w c_T/mu (0 allowed with friction > 0)."""
    friction: float
    """Coulomb coefficient f: the shear traction on the layer is f p, towards
    +x (the direction of motion)."""
    tangential_force: float
    """Friction force on the punch over P, f (positive: it opposes the
    motion, as ``drag``)."""
    end_exponents: tuple[float, float]
    """(gamma_back, gamma_front): p ~ (x + b)^gamma_back (a - x)^gamma_front
    at the trailing and leading ends; (0.5, 0.5) without friction."""
    contact_interval: tuple[float, float]
    """(-b/h, a/h): trailing and leading ends of the contact."""
    drag: float
    """Horizontal force of the normal pressure on the punch over P,
    int p x/R dx / P; positive when it opposes the motion (the friction force
    is ``tangential_force`` apart)."""
    pressure_error_estimate: float
    """Bound on the error of p/(P/h) at a fixed relative position r = (x - c)/w
    in the contact (pointwise in x add |dp/dx| error_estimate); the solver
    refines N until it is at most tol * max_pressure. A flat punch, whose
    pressure is unbounded at its edges: the bound is on g = p/((P/h) w(r)),
    w = (1 - r)^gamma_front (1 + r)^gamma_back, so |dp| <= it times w(r)."""
    max_pressure: float
    """Maximum of p/(P/h) on the contact (inf for a flat punch)."""
    other_half_widths: tuple[float, ...]
    """Half-widths (a + b)/(2h) of other contacts that carry the same load
    (above V*_cr the steady solution need not be unique; to about 1 %).
    Empty when none was found on [w/8, 4w]."""
    _impl: _core.AsymmetricSolution = field(repr=False, compare=False)
    _profile: PunchProfile | None = field(default=None, repr=False, compare=False)
    _medium: Medium | None = field(default=None, repr=False, compare=False)

    @functools.cached_property
    def punches(self) -> tuple[PunchResult, ...]:
        """The one punch (``movingpunch.PunchResult``): at x = 0, its one zone
        (``contact_zones``) with the whole load, ``indentation`` and ``drag``
        as the solution's."""
        return single_punch(self, self._impl)

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
    def stress_error_estimate(self) -> float:
        """Bound on the error of the surface sigma_x/(P/h) at points more than
        1e-3 (a + b)/2 from the contact ends (sigma_x has a square-root cusp
        there). Computed on first access (the pressure's transform at the
        fine Fourier nodes: about as long as a warm solve of a smooth punch),
        as ``Solution.stress_error_estimate``."""
        return float(self._impl.stress_error_estimate)

    @functools.cached_property
    def dissipation(self) -> float:
        """Power dissipated in the dashpots over P V, from the bottom face's
        slope by Parseval; equals ``drag`` by the energy balance without
        friction (with it the shear traction's power adds)."""
        return float(self._impl.dissipation())

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
    def bottom_displacement(self, x: float) -> float: ...
    @overload
    def bottom_displacement(self, x: Points) -> FloatArray: ...
    def bottom_displacement(self, x: npt.ArrayLike) -> float | FloatArray:
        """Displacement v(x, -h)/h of the bottom face."""
        return _pointwise("x", x, self._impl.bottom_displacement)


def solve_asymmetric(
    *,
    vstar: float,
    kw: float,
    radius: float | None = None,
    load: float,
    nu: float = 0.2,
    damping: float,
    tol: float | str = 1e-8,
    allow_unphysical: bool = False,
    n: int | None = None,
    kp: float = 0.0,
    friction: float = 0.0,
    profile: PunchProfile | None = None,
    medium: Medium | None = None,
) -> AsymmetricSolution:
    """Solves the asymmetric contact problem: a damped foundation
    (``damping`` > 0) and/or Coulomb friction (``friction`` > 0, then
    ``damping`` >= 0).

    Speeds up to (not including) the Rayleigh speed solve, above the critical
    speed too. Raises InvalidParameterError, SupercriticalSpeedError (vstar >=
    V*_R), UnphysicalContactError (unless ``allow_unphysical``) and
    ConvergenceError.

    ``radius`` and ``profile`` as in :func:`movingpunch.solve`: a cylinder,
    a rounded flat or a table (an asymmetric table needs neither damping nor
    friction), or a flat punch (its face is the contact; ``end_coefficients``
    gives (K_back, K_front), ``end_exponents`` the exponents of p at its
    edges, gamma - 1 of the bounded case's: (-0.5, -0.5) without friction).

    ``medium``: a layered medium or a half-space base (``movingpunch.media``;
    ``kw``, ``kp``, ``nu`` are then its springs' and its top sublayer's, kw =
    inf under a half-space, and ``damping`` must be 0). The contact,
    pressure, drag, surface slope and surface stress are solved on it, and
    the fields and displacements below the surface (under a half-space
    measured from the surface at x = 100 h); with friction the fields below
    the surface of a layered medium, and under a half-space the
    displacements and the indentation (a logarithmic far field), are
    refused by name.
    """
    shape = resolve_profile(radius, profile)
    inputs = _check_solve_inputs(vstar, kw, 1.0, load, nu, tol, kp)
    inputs["radius"] = shape.nominal_radius
    inputs["friction"] = check_friction(friction)
    asymmetric_shape = isinstance(shape, Profile) and not shape.symmetric
    dissipative = medium is not None and medium.viscoelastic
    inputs["damping"] = check_damping(
        damping,
        positive=inputs["friction"] == 0 and not asymmetric_shape and not dissipative,
    )
    flag = _check_flag("allow_unphysical", allow_unphysical)
    size = _check_asymmetric_size(n)
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
    layered = medium.core_args() if medium is not None else {}
    impl = _core.solve_asymmetric(
        **{**inputs, **shape.core_args(), **layered}, allow_unphysical=flag, n=size
    )
    if medium is not None and isinstance(medium.base, HalfSpace):
        inputs["kw"] = math.nan  # no springs: the medium says what the base is
    back, front = impl.end_exponents
    return AsymmetricSolution(
        **inputs,
        tangential_force=float(impl.tangential_force),
        end_exponents=(float(back), float(front)),
        contact_interval=(float(impl.left), float(impl.right)),
        drag=float(impl.drag),
        critical_vstar=float(impl.critical_vstar),
        rayleigh_vstar=float(impl.rayleigh_vstar),
        phi1=float(impl.phi1),
        iterations=int(impl.iterations),
        collocation_n=int(impl.collocation_n),
        error_estimate=float(impl.error_estimate),
        pressure_error_estimate=float(impl.pressure_error_estimate),
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
        _profile=shape,
        _medium=medium,
    )


def damped_layer_response(
    t: float,
    *,
    vstar: float,
    kw: float,
    nu: float = 0.2,
    damping: float,
    kp: float = 0.0,
) -> tuple[complex, complex, complex]:
    """(M1, M2, Wb) of the damped layer per unit transformed pressure at
    t = alpha h >= 0: M1 = -alpha v^(alpha, 0)/p^, M2 = -sigma_x^(alpha, 0)/p^,
    Wb = alpha v^(alpha, -h)/p^, for modes e^{i alpha x} (alpha < 0: the
    complex conjugates)."""
    tt = _real("t", t)
    if not (math.isfinite(tt) and tt >= 0):
        raise _fail("t", tt)
    m1, m2, wb = _core.damped_layer_response(
        tt,
        _check_vstar(vstar),
        _check_kw(kw),
        _check_nu(nu),
        check_damping(damping),
        _check_kp(kp),
    )
    return complex(m1), complex(m2), complex(wb)
