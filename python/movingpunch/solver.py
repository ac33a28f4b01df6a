"""Public Python API: validated wrappers around the compiled core.

Every quantity is dimensionless (layer thickness h = 1, shear modulus mu = 1):
vstar = rho V^2/mu, kw = k_w h/mu, kp = k_p/(mu h) (a Pasternak shear layer on
the springs; 0: Winkler), radius = R/h, load = P/(mu h), nu, tol (or
a preset name, see PRESETS). Their valid ranges, units and meanings are in one
table, ``movingpunch.params.SPECS``.

Inputs are checked here first so that messages name the parameter and its
range; the core checks them again. Computations release the GIL.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Literal, cast, overload

import numpy as np
import numpy.typing as npt

from movingpunch import _core, params
from movingpunch._evaluate import (
    _as_points,
    _check_flag,
    _check_kp,
    _check_kw,
    _check_nu,
    _check_solve_inputs,
    _check_tol,
    _check_vstar,
    _depths,
    _fail,
    _flat,
    _is_scalar,
    _pointwise,
)
from movingpunch._evaluations import ResultFields
from movingpunch.cancel import Cancel, cancellable
from movingpunch.errors import (
    ConvergenceError,
    InvalidParameterError,
    UnphysicalContactError,
)
from movingpunch.media import (
    Base,
    GradedLayer,
    HalfSpace,
    Medium,
    Sublayer,
    Winkler,
    resolve_medium,
)
from movingpunch.params import PRESETS, Numerics
from movingpunch.profiles import (
    Cylinder,
    Flat,
    Profile,
    PunchProfile,
    resolve_profile,
)
from movingpunch.zones import (
    Punch,
    PunchResult,
    check_contact,
    separate,
    single_punch,
    solve_train,
)

if TYPE_CHECKING:
    from movingpunch.asymmetric import AsymmetricSolution
    from movingpunch.contract import ContactSolution

__all__ = [
    "PRESETS",
    "Solution",
    "clear_kernel_cache",
    "critical_vstar",
    "critical_wavenumber",
    "kernel_cache_info",
    "layer_response",
    "phi1",
    "phi2",
    "rayleigh_vstar",
    "result_warnings",
    "solve",
    "solve_punches",
]

FloatArray = npt.NDArray[np.float64]


def resolve_tol(tol: float | str) -> float:
    """``tol`` as a number: a preset's value, or the number checked against
    1e-14 <= tol <= 1e-2. Raises InvalidParameterError naming the presets."""
    return _check_tol(tol)


def _check_size(value: object) -> int:
    """The collocation size: None (automatic) or an even int in [2, 4096]."""
    return params.check_size(value)


@dataclass(frozen=True)
class Solution(ResultFields):
    """Solution of the moving-punch contact problem (dimensionless).

    Lengths are in units of the layer thickness h, pressures in units of P/h.
    """

    a: float
    """Contact half-width a/h."""
    p0: float
    """Central pressure p(0)/(P/h)."""
    indentation: float
    """Indentation delta/h."""
    kernel_builds: int = field(compare=False)
    """k1 kernel tables this solve built (0: all reused from the process-wide
    cache, as in a load or radius sweep at fixed vstar, kw, nu and tol)."""
    stage_times: Mapping[str, float] = field(compare=False)
    """Seconds per stage of the solve: ``critical_speed``, ``kernel``
    (fetching or building the k1 table), ``width`` (the iteration on a) and
    ``checks`` (indentation and validity). They sum to ``elapsed`` up to the
    cost of reading the clock."""
    _impl: _core.SymmetricSolution = field(repr=False, compare=False)
    _profile: PunchProfile | None = field(default=None, repr=False, compare=False)
    _medium: Medium | None = field(default=None, repr=False, compare=False)

    @functools.cached_property
    def punches(self) -> tuple[PunchResult, ...]:
        """The one punch (``movingpunch.PunchResult``): at x = 0, its one zone
        (``contact_zones``) with the whole load, ``indentation`` and ``drag``
        as the solution's."""
        return single_punch(self, self._impl)

    @functools.cached_property
    def stress_error_estimate(self) -> float:
        """Estimated bound on the absolute error of sigma_x/(P/h): of the
        peaks (``stress_peaks``) and of the surface, bottom and depth values at
        points more than 1e-3 a from the contact edge |x| = a (where sigma_x
        has a square-root cusp). From the change of the stresses against a
        solve at the next collocation size, the a/h error carried into p and
        the kernel part of the a/h error budget, amplified by the stress
        response (docs/performance.md). Computed on first access (it costs
        that second solve, sharing this one's kernel table)."""
        return _stress_error_estimate(self)

    @property
    def damping(self) -> float:
        """c_w c_T/mu: 0.0, the paper's undamped foundation."""
        return 0.0

    @property
    def friction(self) -> float:
        """Coulomb friction f: 0.0, the paper's frictionless punch."""
        return 0.0

    @property
    def tangential_force(self) -> float:
        """Friction force on the punch over P: 0.0 (frictionless)."""
        return 0.0

    @property
    def end_exponents(self) -> tuple[float, float]:
        """(gamma_back, gamma_front) of p ~ (a + x)^gamma_back (a - x)^gamma_front:
        (0.5, 0.5), the frictionless cylinder."""
        return (0.5, 0.5)

    @property
    def contact_interval(self) -> tuple[float, float]:
        """(x_back, x_front) = (-a/h, a/h): the contact is symmetric."""
        return (-self.a, self.a)

    @property
    def half_width(self) -> float:
        """Half the contact's width over h: a/h."""
        return self.a

    @property
    def centre(self) -> float:
        """Centre of the contact over h: 0.0 (symmetric)."""
        return 0.0

    @property
    def drag(self) -> float:
        """Horizontal force on the punch over P: 0.0 without damping (the
        symmetric pressure does no work)."""
        return 0.0

    @property
    def dissipation(self) -> float:
        """Power dissipated over P V (equal to ``drag`` by the energy
        balance): 0.0 without damping."""
        return 0.0

    @property
    def mu_over_load(self) -> float:
        """The paper's mu/(P/h) = 1/load (500 for load = 0.002)."""
        return 1.0 / self.load

    @property
    def g_coefficients(self) -> FloatArray:
        """Chebyshev-U coefficients of g(r) = p(a r)/((P/h) sqrt(1 - r^2))."""
        return self._impl.g_coefficients

    @overload
    def depth_stress(self, y: float, x: float = ...) -> float: ...
    @overload
    def depth_stress(
        self, y: npt.NDArray[Any] | Sequence[Any], x: float = ...
    ) -> FloatArray: ...
    def depth_stress(self, y: npt.ArrayLike, x: float = 0.0) -> float | FloatArray:
        """sigma_x(x, y)/(P/h), y/h in [-1, 0]; under the centre of the punch
        (x = 0, the default) by the solution's own depth profile."""
        if isinstance(x, (int, float)) and not isinstance(x, bool) and x == 0.0:
            return _pointwise("y", y, self._impl.depth_stress, points=_depths(y))
        return super().depth_stress(y, x)  # type: ignore[arg-type]

    @overload
    def foundation_reaction(self, x: float) -> float: ...
    @overload
    def foundation_reaction(
        self, x: npt.NDArray[Any] | Sequence[Any]
    ) -> FloatArray: ...
    def foundation_reaction(self, x: npt.ArrayLike) -> float | FloatArray:
        """Pressure the base exerts on the layer, -sigma_y(x, -h)/(P/h)
        (= -(kw v - kp v'')(x, -h)/(P/h) for a finite foundation; the rigid base's
        contact pressure for kw = inf). Integrates to 1 over x."""
        return _pointwise("x", x, self._impl.foundation_reaction)


_CONFIRM_TOL = 1e-8
"""The tolerance at which ``solve(contact="auto")`` confirms a valid single
contact solved at a coarser one (its validity decides the contact set)."""


@overload
def solve(
    *,
    vstar: float,
    kw: float | None = ...,
    radius: float | None = ...,
    load: float,
    nu: float | None = ...,
    tol: float | str = ...,
    allow_unphysical: bool = ...,
    n: int | None = ...,
    damping: Literal[0] = ...,
    kp: float = ...,
    profile: PunchProfile | None = ...,
    friction: Literal[0] = ...,
    contact: Literal["single"],
    layers: Sequence[Sublayer] | None = ...,
    base: Base | None = ...,
    inertia: bool = ...,
    numerics: Numerics | None = ...,
    cancel: Cancel | None = ...,
) -> Solution: ...


@overload
def solve(
    *,
    vstar: float,
    kw: float | None = ...,
    radius: float | None = ...,
    load: float,
    nu: float | None = ...,
    tol: float | str = ...,
    allow_unphysical: bool = ...,
    n: int | None = ...,
    damping: float = ...,
    kp: float = ...,
    profile: PunchProfile | None = ...,
    friction: float = ...,
    contact: str = ...,
    layers: Sequence[Sublayer] | None = ...,
    base: Base | None = ...,
    inertia: bool = ...,
    numerics: Numerics | None = ...,
    cancel: Cancel | None = ...,
) -> ContactSolution: ...


@cancellable
def solve(
    *,
    vstar: float,
    kw: float | None = None,
    radius: float | None = None,
    load: float,
    nu: float | None = None,
    tol: float | str = 1e-8,
    allow_unphysical: bool = False,
    n: int | None = None,
    damping: float = 0.0,
    kp: float = 0.0,
    profile: PunchProfile | None = None,
    friction: float = 0.0,
    contact: str = "auto",
    layers: Sequence[Sublayer] | None = None,
    base: Base | None = None,
    inertia: bool = True,
    numerics: Numerics | None = None,
    cancel: Cancel | None = None,
) -> ContactSolution:
    """Solves the contact problem of a rigid punch sliding over the layer.

    Parameters are dimensionless (see the module docstring). Raises
    InvalidParameterError (bad input), SupercriticalSpeedError (vstar at or
    above the critical speed), UnphysicalContactError (p < 0 or penetration,
    unless ``allow_unphysical``; then the solution comes back with
    ``valid=False``) and ConvergenceError.

    ``tol`` is the relative tolerance on a/h (1e-14 to 1e-2) or a preset
    name from ``PRESETS``: "draft" (1e-4), "default" (1e-8), "precise"
    (1e-12). It drives the collocation size N, the root find on a and the
    k1 kernel quadrature (to 1e-2 tol), which the stresses also use.

    ``n`` fixes the number of collocation points (even, 2 to 4096) instead of
    refining N until a/h meets ``tol``; the error estimate then compares with
    solves at finer sizes (2n, 4n, ... up to 1024; n > 256: with a half and a
    quarter of n), and a result whose estimate is above ``tol`` warns.

    ``valid`` is a physical verdict, the same at every ``tol``: p >= 0 on the
    contact and no penetration beside it, up to the solution's own error
    estimate (and 1e-6 of the peak); a sign that only the estimate leaves
    open is named in ``warnings``.

    ``damping`` = c_w c_T/mu >= 0 adds dashpots to the springs (a Kelvin-Voigt
    foundation, docs/damped.md). 0 (the default) is the paper's model and
    returns a Solution; > 0 returns a ``movingpunch.asymmetric.AsymmetricSolution``
    (asymmetric contact, drag; speeds up to the Rayleigh speed). Both satisfy
    ``movingpunch.ContactSolution``, the one contract callers use.

    ``kp`` = k_p/(mu h) >= 0 adds a Pasternak shear layer to the springs
    (a two-parameter foundation: sigma_y(x, -h) = kw v - kp v'', the stiffness
    kw + kp (alpha h)^2 per wavenumber; docs/theory.md section 12). 0 (the
    default) is the Winkler foundation, bit for bit. It raises the critical
    speed (``critical_vstar(kw, nu, kp)``).

    ``profile`` is the punch's shape (``movingpunch.profiles``): a
    ``Cylinder(radius)`` (the default: ``radius=R`` is its shorthand),
    ``Flat(half_width)`` (a flat face: its end coefficients in
    ``end_coefficients``), ``RoundedFlat(half_width, radius)`` or a
    convex table ``Profile(x, y)``. Give ``radius`` or
    ``profile``; both only if they agree (a Cylinder or a RoundedFlat of that
    very radius), else InvalidParameterError naming ``radius``. With
    ``damping > 0`` or ``friction > 0`` every profile solves on the
    asymmetric solver (a flat punch there: index +1 Gauss-Jacobi collocation
    on its face, both end coefficients in ``end_coefficients``); an
    asymmetric table takes the asymmetric solver even without them. ``tol``
    is on a/h (on the end coefficients for a flat punch, whose contact is
    its face).

    ``friction`` = f >= 0 is Coulomb friction between punch and layer (the
    punch moves towards +x and drags the surface with a shear traction f p;
    docs/theory.md section 14). f > 0 takes the asymmetric path (a
    ``AsymmetricSolution``, with damping >= 0): Gauss-Jacobi collocation with
    the end exponents of cot(pi gamma_back) = f Phi(vstar, nu).

    ``contact`` = "auto" (the default) finds the real contact set when the
    single contact is unphysical (p < 0 inside it near the critical speed,
    or penetration beside it): several zones, a ``ZonedSolution``
    (``movingpunch.zones``; its ``validity`` says the contact separated and
    why the single one was rejected). "single" keeps the single contact and
    refuses an unphysical one (UnphysicalContactError). With
    ``allow_unphysical=True`` the single contact comes back as it is,
    flagged ``valid=False``, without the search. Several zones need a
    frictionless punch with bounded ends (not a flat punch).

    ``layers`` and ``base`` give the medium (``movingpunch.media``,
    docs/media.md): sublayers ``Layer(thickness, mu, nu, rho)`` and
    ``GradedLayer(gamma_h, ...)`` top to bottom, bonded, their thicknesses
    summing to 1 and the top one the unit of mu and rho; the base
    ``Winkler(kw, kp, damping)`` (``kw=``, ``kp=``, ``damping=`` are its
    shorthand) or ``HalfSpace(mu, nu, rho, interface)``. Giving ``nu=`` with
    ``layers=``, or ``kw=``/``kp=``/``damping=`` with ``base=``, is an
    InvalidParameterError naming it. One homogeneous sublayer on springs is
    the paper's layer, solved exactly as the shorthand is. Every medium
    takes every punch profile, friction, asymmetric tables and several
    contact zones; not yet, each refused by name: damped springs under a
    stack (``damping``), a graded top sublayer (``layers``), and several
    zones under a half-space base.

    A ``Layer(..., viscoelastic=Zener(ratio, deborah=...))`` (or ``Prony``)
    is a viscoelastic sublayer (docs/theory.md section 17), solved
    quasi-statically: at ``vstar=0``, the speed entering through the deborah
    numbers. A material given by its relaxation time instead
    (``Zener(ratio, tau=...)``, tau in units of h/c_T0) takes its deborah
    number sqrt(vstar) tau from the speed; ``inertia=False`` then neglects the
    layer's inertia (the layer is solved at rest with the material at that
    speed; the solution's ``vstar`` is the speed and its medium says
    ``inertia=False``), which is how a speed sweep of one material runs.
    ``inertia=False`` with vstar > 0 and no such material is an
    InvalidParameterError naming vstar (the speed would change nothing).

    ``numerics`` (``movingpunch.Numerics``: tol, n, allow_unphysical,
    contact as one checked value) stands for those four keywords; giving
    one of them too is an InvalidParameterError naming it.

    ``cancel`` is a ``movingpunch.Cancel`` token (None: none): its
    ``cancel()``, from any thread, stops the solve, which raises
    ``movingpunch.Cancelled`` within about 50 ms (``movingpunch.cancel``).
    The token is bound to this thread for the call; it does not follow the
    result (a lazy property computed later, e.g. ``stress_error_estimate``,
    runs unbound: compute it inside ``with token:`` to make it cancellable).
    """
    from movingpunch.asymmetric import check_damping, check_friction, solve_asymmetric

    if numerics is not None:
        tol, n, allow_unphysical, contact = params.numerics_keywords(
            numerics, tol=tol, n=n, allow_unphysical=allow_unphysical, contact=contact
        )
    medium: Medium | None = None
    inert = _check_flag("inertia", inertia)
    if layers is not None or base is not None:
        medium = resolve_medium(
            layers=layers,
            base=base,
            kw=kw,
            kp=kp if kp != 0.0 else None,
            damping=damping if damping != 0.0 else None,
            nu=nu,
            inertia=inert,
        )
        if medium.speed_dependent or not inert:
            speed = _check_vstar(vstar)
            if not inert:
                _check_quasi_static(medium, speed)
                if speed > 0.0:
                    # Solved at rest on the material at its speed; the
                    # solution's vstar is the speed (its medium says the
                    # inertia was neglected).
                    at = medium.at_speed(speed)
                    still = solve(
                        vstar=0.0,
                        radius=radius,
                        load=load,
                        tol=tol,
                        allow_unphysical=allow_unphysical,
                        n=n,
                        profile=profile,
                        friction=friction,
                        contact=contact,
                        layers=list(at.layers),
                        base=at.base,
                        inertia=False,
                    )
                    quasi: ContactSolution = dataclasses.replace(
                        cast(Any, still), vstar=speed, _medium=at
                    )
                    return quasi
            medium = medium.at_speed(speed)
        if medium.homogeneous:
            # The paper's layer: the shorthand's own path, bit for bit.
            springs = medium.base
            assert isinstance(springs, Winkler)
            kw, kp, damping, nu = springs.kw, springs.kp, springs.damping, medium.nu
            medium = None
    elif not inert:
        _check_quasi_static(None, _check_vstar(vstar))
    if medium is not None:
        return _solve_layered(
            medium,
            vstar,
            radius,
            load,
            tol,
            allow_unphysical,
            n,
            profile,
            friction,
            contact,
        )
    if kw is None:
        raise InvalidParameterError(
            "kw: the foundation's stiffness is required (or base=Winkler(...) or "
            "base=HalfSpace(...) with layers=)",
            parameter="kw",
            allowed=params.SPECS["kw"].text,
        )
    springs_kw: float = kw
    nu = 0.2 if nu is None else nu
    shape = resolve_profile(radius, profile)
    mode = check_contact(contact)
    flag = _check_flag("allow_unphysical", allow_unphysical)
    asymmetric_shape = isinstance(shape, Profile) and not shape.symmetric
    damp, fric = check_damping(damping), check_friction(friction)
    # Several zones: frictionless punches with bounded ends (a flat punch's
    # contact is its face). The single solve may then be unphysical.
    zoned = mode == "auto" and fric == 0.0 and not isinstance(shape, Flat)

    def single_at(accuracy: float | str, size: int | None) -> ContactSolution:
        if damp > 0 or fric > 0 or asymmetric_shape:
            return solve_asymmetric(
                vstar=vstar,
                kw=springs_kw,
                load=load,
                nu=nu,
                damping=damping,
                tol=accuracy,
                allow_unphysical=flag or zoned,
                n=size,
                kp=kp,
                friction=friction,
                profile=shape,
            )
        return _solve_profile(
            shape, vstar, springs_kw, load, nu, accuracy, flag or zoned, size, kp
        )

    try:
        single = single_at(tol, n)
    except UnphysicalContactError as err:
        if mode != "auto" or fric == 0.0:
            raise
        raise UnphysicalContactError(
            f"{err}; contact 'auto' looks for separated contact zones only "
            "without friction (friction = 0): lower the friction or the speed, "
            "or pass allow_unphysical=True to get the single contact flagged "
            "invalid"
        ) from None
    if zoned and single.valid and n is None and single.tol > _CONFIRM_TOL:
        # A coarse tolerance stops on the contact's ends, which converge
        # before the pressure's shape: near the critical speed p(0) can
        # still have the wrong sign. The contact set is decided at 1e-8.
        finer = single_at(_CONFIRM_TOL, None)
        if not finer.valid:
            single = finer
    if single.valid or not zoned:
        return single
    # The single contact is unphysical: find the contact set (zones.py);
    # allow_unphysical asks for the single contact as it is.
    if flag:
        return single
    try:
        return separate(single, damping=damp, kp=single.kp, n=n)
    except (UnphysicalContactError, ConvergenceError) as err:
        shape = single.profile
        what = (
            f"radius={shape.radius:.8g}"
            if isinstance(shape, Cylinder)
            else f"profile: {shape.describe()}"
        )
        raise UnphysicalContactError(
            f"vstar={single.vstar:.8g}, kw={single.kw:.8g}, {what}, "
            f"load={single.load:.8g}, nu={single.nu:.8g}: {single.validity} "
            f"(a/h = {single.a:.8g}); the search for several contact zones "
            f"failed: {err}"
        ) from err


def _check_quasi_static(medium: Medium | None, vstar: float) -> None:
    """A speed under ``inertia=False`` must be 0 or set a material's
    relaxation (``tau``), below the medium's critical speed; else
    InvalidParameterError naming vstar."""
    if vstar > 0.0 and (medium is None or not medium.speed_dependent):
        raise InvalidParameterError(
            f"vstar = {vstar!r} with inertia=False changes nothing: the layer's "
            "inertia is neglected and no material takes its relaxation from the "
            "speed (give a viscoelastic sublayer by its relaxation time, "
            "Zener(ratio, tau=...), or vstar=0)",
            parameter="vstar",
            allowed="0 with inertia=False, unless a material is given by tau",
        )
    if vstar > 0.0:
        assert medium is not None
        below_critical_speed(medium, vstar)


def below_critical_speed(medium: Medium, vstar: float) -> None:
    """A quasi-static speed stays below the medium's critical speed (the
    relaxed layer's for a viscoelastic one): beyond it the inertia neglected
    would be the whole story. InvalidParameterError naming vstar."""
    vcr = medium.critical_speed()[0]
    if not vstar < vcr:
        raise InvalidParameterError(
            f"vstar = {vstar!r} with inertia=False is at or above the critical "
            f"speed V*_cr = {vcr:.10g} of the (relaxed) medium, where the inertia "
            "neglected dominates; the quasi-static layer is fair for vstar << 1",
            parameter="vstar",
            allowed=f"0 <= vstar < {vcr:.10g} with inertia=False",
        )


def _solve_layered(
    medium: Medium,
    vstar: float,
    radius: float | None,
    load: float,
    tol: float | str,
    allow_unphysical: object,
    n: int | None,
    profile: PunchProfile | None,
    friction: object,
    contact: str,
) -> ContactSolution:
    """The solve on a layered medium (or a half-space base): the symmetric
    solver for a frictionless symmetric punch, the asymmetric one for
    friction or an asymmetric table; several contact zones when the single
    contact separates (frictionless punches with bounded ends)."""
    from movingpunch.asymmetric import check_friction, solve_asymmetric

    shape = resolve_profile(radius, profile)
    mode = check_contact(contact)
    flag = _check_flag("allow_unphysical", allow_unphysical)
    if isinstance(medium.base, Winkler) and medium.base.damping > 0:
        raise InvalidParameterError(
            "damping: a damped base (damped springs, Winkler(damping > 0)) under "
            "a stack of sublayers is not supported yet (the stack's response is "
            "propagated in real arithmetic); damping runs on the homogeneous layer "
            f"(layers=None); the medium given is {medium.describe()}",
            parameter="damping",
            allowed="0 under layers= (damping > 0: the homogeneous layer only)",
        )
    if (
        isinstance(medium.layers[0], GradedLayer)
        and medium.layers[0].gamma_h != 0
        and shape.kind == "flat"
    ):
        raise InvalidParameterError(
            "profile: a flat punch on a graded TOP sublayer is not solved yet (its "
            "first-kind collocation does not integrate the graded kernel's sgn and "
            "u ln|u| terms exactly); use a rounded flat, or put a homogeneous "
            "sublayer on top",
            parameter="profile",
            allowed="a bounded contact (cylinder, rounded flat, table) on a graded top",
        )
    fric = check_friction(friction)
    asymmetric_shape = isinstance(shape, Profile) and not shape.symmetric
    zoned = mode == "auto" and fric == 0.0 and not isinstance(shape, Flat)
    springs = medium.base if isinstance(medium.base, Winkler) else None
    kw = springs.kw if springs else math.inf
    kp = springs.kp if springs else 0.0
    single: Solution | AsymmetricSolution
    if fric > 0 or asymmetric_shape or medium.viscoelastic:
        single = solve_asymmetric(
            vstar=vstar,
            kw=kw,
            radius=None,
            load=load,
            nu=medium.nu,
            damping=0.0,
            tol=tol,
            allow_unphysical=True,
            n=n,
            kp=kp,
            friction=fric,
            profile=shape,
            medium=medium,
        )
    else:
        single = _solve_profile(
            shape, vstar, kw, load, medium.nu, tol, True, n, kp, medium=medium
        )
    if single.valid or flag:
        return single
    graded_top = (
        isinstance(medium.layers[0], GradedLayer) and medium.layers[0].gamma_h != 0
    )
    if zoned and graded_top:
        raise UnphysicalContactError(
            f"vstar={single.vstar:.8g}, {medium.describe()}, {shape.describe()}, "
            f"load={single.load:.8g}: {single.validity} (a/h = {single.a:.8g}); "
            "several contact zones on a graded top sublayer are not supported yet "
            "(the zones' solver does not take the graded kernel's singular terms); "
            "allow_unphysical=True returns the single contact, flagged"
        )
    if zoned and isinstance(medium.base, HalfSpace):
        raise UnphysicalContactError(
            f"vstar={single.vstar:.8g}, {medium.describe()}, {shape.describe()}, "
            f"load={single.load:.8g}: {single.validity} (a/h = {single.a:.8g}); "
            "several contact zones under a half-space base are not supported yet "
            "(their indentations need the displacement, which grows like ln|x| "
            "there); allow_unphysical=True returns the single contact, flagged"
        )
    if zoned:
        try:
            return separate(single, damping=0.0, kp=kp, n=n)
        except (UnphysicalContactError, ConvergenceError) as err:
            raise UnphysicalContactError(
                f"vstar={single.vstar:.8g}, {medium.describe()}, {shape.describe()}, "
                f"load={single.load:.8g}: {single.validity} (a/h = {single.a:.8g}); "
                f"the search for several contact zones failed: {err}"
            ) from err
    raise UnphysicalContactError(
        f"vstar={single.vstar:.8g}, {medium.describe()}, {shape.describe()}, "
        f"load={single.load:.8g}: {single.validity} (a/h = {single.a:.8g}) "
        "(allow_unphysical=True returns the single contact, flagged)"
    )


def _solve_profile(
    shape: PunchProfile,
    vstar: object,
    kw: object,
    load: object,
    nu: object,
    tol: object,
    allow_unphysical: object,
    n: object,
    kp: object = 0.0,
    medium: Medium | None = None,
) -> Solution:
    """The undamped solve of ``shape`` (validated inputs, the core's solve,
    the Solution) on the homogeneous layer of (kw, nu, kp), or on ``medium``
    (kw, kp: its springs'; inf, 0 under a half-space)."""
    # The shape's own parameters are checked by it; radius shows its nominal
    # radius (inf for a flat punch or a table).
    inputs = _check_solve_inputs(vstar, kw, 1.0, load, nu, tol, kp)
    inputs["radius"] = shape.nominal_radius
    flag = _check_flag("allow_unphysical", allow_unphysical)
    size = _check_size(n)
    core = _core_inputs(inputs, shape)
    if medium is not None:
        core.update(medium.core_args())
        if isinstance(medium.base, HalfSpace):
            inputs["kw"] = math.nan  # no springs: the medium says what the base is
    impl = _core.solve_contact(**core, allow_unphysical=flag, n=size)
    return Solution(
        **inputs,
        a=impl.a,
        p0=impl.p0,
        indentation=impl.indentation,
        critical_vstar=impl.critical_vstar,
        rayleigh_vstar=impl.rayleigh_vstar,
        phi1=impl.phi1,
        iterations=impl.iterations,
        collocation_n=impl.collocation_n,
        error_estimate=impl.error_estimate,
        elapsed=impl.elapsed,
        valid=impl.valid,
        validity=impl.validity,
        min_pressure=impl.min_pressure,
        min_gap=impl.min_gap,
        pressure_margin=impl.pressure_margin,
        warnings=tuple(impl.warnings),
        kernel_builds=impl.kernel_builds,
        stage_times=MappingProxyType(dict(impl.stage_seconds)),
        _impl=impl,
        _profile=shape,
        _medium=medium,
    )


def _core_inputs(inputs: Mapping[str, float], shape: PunchProfile) -> dict[str, Any]:
    """The keyword arguments of ``_core.solve_contact`` for the checked
    ``inputs`` and the punch ``shape`` (its radius replaces ``radius``)."""
    return {**inputs, **shape.core_args()}


if TYPE_CHECKING:

    def _satisfies_the_contract(s: Solution) -> ContactSolution:
        """mypy proves here that Solution satisfies ContactSolution."""
        return s


def result_warnings(result: object) -> tuple[str, ...]:
    """The ``warnings`` of a solution (Solution, AsymmetricSolution or anything
    with that attribute) as a tuple of one-line strings; () if it has none.
    Every display (CLI, scenes, terminal UI) shows them through this."""
    found = getattr(result, "warnings", ())
    return tuple(str(w) for w in found) if found else ()


_EPS = float(np.finfo(np.float64).eps)


_EDGE = 1e-3
"""Relative distance from the contact edge beyond which
``stress_error_estimate`` holds pointwise (sigma_x has a square-root cusp at
|x| = a, so an error da in a moves it there by about p0 sqrt(2 da/a))."""


def _chebyshev_tail(c: FloatArray) -> float:
    """Estimated sum of the omitted magnitudes of a geometrically decaying
    series whose kept magnitudes are ``c`` (see _stress_error_estimate)."""
    if len(c) < 4 or not np.all(c[-4:-1] > 0.0):
        return float(c[-1]) if len(c) else 0.0  # too few terms to see a decay
    r_last, r_prev, r_before = (float(c[k] / c[k - 1]) for k in (-1, -2, -3))
    if r_last < 0.1 * r_prev and r_prev < 0.5:
        # An abrupt drop after a steady decay: the last coefficient sits near
        # a zero of its own; the one it should have been, c[-2] r_prev,
        # stands for it.
        first = float(c[-2]) * r_prev
        rho = max(r_prev, r_before)
    else:
        # The slowest of the mean rates over the last one, two and three
        # steps (a pair of equal coefficients is a bump being resolved: the
        # rate over two steps spans it).
        rho = max(
            r_last, math.sqrt(r_last * r_prev), (r_last * r_prev * r_before) ** (1 / 3)
        )
        first = float(c[-1]) * rho
    rho = min(rho, 0.9)
    return first / (1.0 - rho)


_SIZES = (8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256, 384, 512, 640, 768, 896)
"""The collocation sizes the core tries in turn (cpp/src/contact.cpp kSizes,
without its cap 1024)."""


def _finer_size(n: int) -> int:
    """The size the core would try after n (0: none)."""
    above = [m for m in _SIZES if m > n]
    return above[0] if above else 0


def _stress_samples(impl: _core.SymmetricSolution, a: float) -> FloatArray:
    """sigma_x/(P/h) at sample points: the surface on and off the contact
    (more than 1e-3 a from its edge), its bottom, and under the centre."""
    r = np.cos(np.linspace(0.0, math.pi / 2, 24))
    xs = a * np.concatenate([r, 2.0 - r[:-1], [2.5, 3.0, 4.0, 5.0, 6.0]])
    xs = xs[np.abs(np.abs(xs) - a) > 2e-3 * a]
    top = impl.surface_stress(xs)
    bottom = impl.stress_field(xs, np.array([-1.0]))[0][0]
    return np.concatenate([top, bottom, impl.depth_stress(np.array([-0.5]))])


def _stress_error_estimate(s: Solution) -> float:
    """A bound on |error| of sigma_x/(P/h) (see Solution.stress_error_estimate).

    Every stress is a linear map of p: on the surface sigma_x = -phi2 p + a
    smoother layer term, so an error of p carries over at least multiplied by
    ``gain`` = 2 (1 + phi2) (near V*_cr the layer's resonance amplifies the
    error's oscillating part far more: 50 times that at kw = 10, 1 - 1e-6).
    Parts:

    * the collocation's truncation, measured: 3 times the largest change of
      sigma_x at sample points (_stress_samples) between this solve and one at
      the next collocation size (the core's next N; its own error is a small
      fraction of this one's, since convergence in N is geometric), which
      includes the resonance's amplification. Without a next size (N at the
      cap, or that solve failing) the pressure's Chebyshev tail
      (_chebyshev_tail, counted twice since the collocation also aliases it
      onto the kept coefficients) times ``gain`` stands in;
    * the k1 kernel's quadrature, which both solves share: the kernel part of
      the a/h error budget, relative, times sum |b_k| (the size of p), 10
      (the load's slope in a is about 2, and the stresses' own alpha integrals
      on the same panels err by as much again) and ``gain``; not the a-priori
      1e-2 tol the quadrature was asked for, which is 1e2 to 1e6 times what it
      delivers (the core never builds the kernel looser than 1e-10, so a
      table reused from another solve at a loose tol is as good);
    * round-off, 64 eps N sum |b_k| times ``gain``;
    * the a/h error da (error_estimate): p moves by p0 da/a, and the edge's
      cusp -phi2 p by phi2 p0 (da/a)/sqrt(2 d) at a relative distance
      d >= 1e-3 from it.

    Calibrated against N = 256 references (docs/performance.md, "Error
    estimates"): at most 63 times the actual error on the near-V*_cr grid of
    tests/python/test_estimates.py, 3 to 10 times away from it (tol <= 1e-8).
    """
    impl = s._impl
    # The collocated coefficients (a rounded flat's series goes on with the
    # half-plane tail, bounded by series_truncation: counted below).
    b = np.asarray(impl.g_coefficients, dtype=np.float64)[: impl.collocation_n]
    c = np.abs(b[::2])
    total = float(c.sum())
    a = impl.a
    p0 = abs(impl.p0)
    kernel = 10.0 * total * impl.error_budget["kernel"] / a
    roundoff = 64.0 * _EPS * len(b) * total
    try:
        phi2_value = _core.phi2(s.vstar, s.nu)
    except ValueError:  # pragma: no cover - vstar < V*_cr <= V*_R always
        phi2_value = 1.0
    gain = 2.0 * (1.0 + abs(phi2_value))
    tail = 2.0 * _chebyshev_tail(c)
    finer = _finer_size(len(b))
    if finer:
        try:
            shape = s._profile if s._profile is not None else Cylinder(s.radius)
            # On the same medium (a half-space base has no springs: kw nan).
            kw = s.kw if not math.isnan(s.kw) else math.inf
            inputs = {"vstar": s.vstar, "kw": kw, "load": s.load, "nu": s.nu}
            other = _core.solve_contact(
                **_core_inputs({**inputs, "kp": s.kp}, shape),
                **s.medium.core_args(),
                # Its width and kernel well below this one's collocation
                # error: at a loose tol the change would measure the root's
                # own 1e-2 tol, and at N = 24 the 1e-10 kernel of a tol-1e-6
                # solve moves sigma_x by 6e-10 where N = 16 is right to 1e-12
                # (kw = 10, V* = 0.5).
                tol=min(max(1e-2 * s.tol, 1e-14), 1e-10),
                allow_unphysical=True,
                n=finer,
            )
            change = _stress_samples(impl, a) - _stress_samples(other, a)
            tail = 3.0 * float(np.max(np.abs(change))) / gain
        except (ValueError, RuntimeError, ArithmeticError):
            pass  # keep the tail of the series
    # da/a moves p by p0 da/a, and the edge's cusp -phi2 p by
    # phi2 p0 (da/a)/sqrt(2 d) at a relative distance d >= 1e-3 from it.
    edge = abs(phi2_value) / math.sqrt(2.0 * _EDGE)
    width = p0 * (impl.error_estimate / a) * (gain + edge)
    # A kinked slope's series truncation (rounded flat, table): a bound on
    # the pressure's error, carried into sigma_x like the tail.
    truncation = impl.series_truncation
    return gain * (tail + kernel + roundoff + truncation) + width


def kernel_cache_info() -> dict[str, int]:
    """The process-wide cache of k1 kernel tables: ``size`` (tables held),
    ``hits`` (solves that reused a table), ``misses`` (tables built); and the
    same for the asymmetric solver's (damped and/or frictional) kernel
    tables: ``asymmetric_size``, ``asymmetric_hits``, ``asymmetric_misses``.

    Tables are keyed on (vstar, kw, nu, tol, kp), so solves that change only the
    radius or the load reuse one table (when the cached table covers the new
    contact width).
    """
    return dict(_core.kernel_cache_info())


def clear_kernel_cache() -> None:
    """Empties the kernel cache and resets its counters."""
    _core.clear_kernel_cache()


def _critical(
    kw: float | None,
    nu: float | None,
    kp: float,
    layers: Sequence[Sublayer] | None,
    base: Base | None,
) -> tuple[float, float]:
    if layers is not None or base is not None:
        medium = resolve_medium(
            layers=layers, base=base, kw=kw, kp=kp if kp != 0.0 else None, nu=nu
        )
        if not medium.homogeneous:
            return medium.critical_speed()
        assert isinstance(medium.base, Winkler)
        kw, kp, nu = medium.base.kw, medium.base.kp, medium.nu
    if kw is None:
        raise InvalidParameterError(
            "kw: the foundation's stiffness is required (or base=/layers=)",
            parameter="kw",
            allowed=params.SPECS["kw"].text,
        )
    vc, t = _core.critical_speed(
        _check_kw(kw), _check_nu(0.2 if nu is None else nu), _check_kp(kp)
    )
    return float(vc), float(t)


def critical_vstar(
    kw: float | None = None,
    nu: float | None = None,
    kp: float = 0.0,
    *,
    layers: Sequence[Sublayer] | None = None,
    base: Base | None = None,
) -> float:
    """Critical speed V*_cr(kw, nu, kp): the minimum phase speed of free waves
    in the layer on springs (and a Pasternak shear layer kp; the Rayleigh
    speed for kw = inf, and once kp is so stiff that no free wave is slower
    than the Rayleigh wave). Grows with kw and with kp. With ``layers=`` /
    ``base=`` (as ``solve`` takes them): the medium's, including the infima
    approached only at short or long waves (docs/media.md)."""
    return _critical(kw, nu, kp, layers, base)[0]


def critical_wavenumber(
    kw: float | None = None,
    nu: float | None = None,
    kp: float = 0.0,
    *,
    layers: Sequence[Sublayer] | None = None,
    base: Base | None = None,
) -> float:
    """alpha h at which the phase speed is minimal (inf for kw = inf, and
    when V*_cr is the Rayleigh speed; inf or 0 for a medium's infimum
    approached at short or long waves)."""
    return _critical(kw, nu, kp, layers, base)[1]


def rayleigh_vstar(nu: float = 0.2) -> float:
    """Rayleigh speed V*_R = rho c_R^2/mu."""
    return _core.rayleigh_vstar(_check_nu(nu))


def phi1(vstar: float, nu: float = 0.2) -> float:
    """Moving half-plane factor phi1 = lim M1 (phi1(0) = 1 - nu); needs
    vstar < rayleigh_vstar(nu)."""
    return _core.phi1(_check_vstar(vstar), _check_nu(nu))


def phi2(vstar: float, nu: float = 0.2) -> float:
    """Half-plane limit phi2 = lim M2 of the surface sigma_x response
    (phi2(0) = 1); needs vstar < rayleigh_vstar(nu)."""
    return _core.phi2(_check_vstar(vstar), _check_nu(nu))


@overload
def layer_response(
    t: float,
    *,
    vstar: float,
    kw: float,
    nu: float = ...,
    method: Literal["auto", "modal", "transfer"] = ...,
    kp: float = ...,
) -> tuple[float, float]: ...
@overload
def layer_response(
    t: npt.NDArray[Any] | Sequence[Any],
    *,
    vstar: float,
    kw: float,
    nu: float = ...,
    method: Literal["auto", "modal", "transfer"] = ...,
    kp: float = ...,
) -> tuple[FloatArray, FloatArray]: ...
def layer_response(
    t: npt.ArrayLike,
    *,
    vstar: float,
    kw: float,
    nu: float = 0.2,
    method: Literal["auto", "modal", "transfer"] = "auto",
    kp: float = 0.0,
) -> tuple[float, float] | tuple[FloatArray, FloatArray]:
    """Surface responses (M1, M2) of the layer per unit transformed pressure
    at wavenumbers t = alpha h >= 0 (M1 -> phi1, M2 -> phi2 as t -> inf).

    Floats for a scalar ``t``, else two arrays of the shape of ``t``.
    ``method`` forces one of the two evaluations (for cross-checks).
    """
    points = _as_points("t", t)
    if (points < 0).any():
        raise _fail("t", float(points[points < 0].flat[0]))
    if method not in ("auto", "modal", "transfer"):
        raise InvalidParameterError(
            f"method must be 'auto', 'modal' or 'transfer', got {method!r}",
            parameter="method",
            allowed="'auto', 'modal' or 'transfer'",
        )
    m1, m2 = _core.layer_response(
        _flat(points),
        _check_vstar(vstar),
        _check_kw(kw),
        _check_nu(nu),
        method,
        _check_kp(kp),
    )
    if _is_scalar(t):
        return float(m1[0]), float(m2[0])
    return m1.reshape(points.shape), m2.reshape(points.shape)


@cancellable
def solve_punches(
    punches: Sequence[Punch],
    *,
    vstar: float,
    kw: float | None = None,
    nu: float | None = None,
    kp: float = 0.0,
    damping: float = 0.0,
    friction: float = 0.0,
    tol: float | str = 1e-8,
    n: int | None = None,
    cancel: Cancel | None = None,
    layers: Sequence[Sublayer] | None = None,
    base: Base | None = None,
    numerics: Numerics | None = None,
) -> ContactSolution:
    """Solves a train of rigid punches moving together at one speed
    (``Punch(profile, load, at=x0)`` each; positions x/h of their axes in the
    moving frame, the train moving towards +x): each punch's contact zones
    (several when its contact separates), pressure, indentation and drag,
    and every field and stress of the whole surface (the superposed
    response). A single punch at ``at = 0`` is :func:`movingpunch.solve`'s
    result itself.

    Frictionless (``friction`` must be 0: friction with several zones is
    not supported yet); ``damping`` >= 0 and ``kp`` >= 0 as in
    ``movingpunch.solve``. ``n`` fixes the collocation size per zone (even,
    8 to 256). ``layers`` and ``base``: the medium, as ``movingpunch.solve``
    takes them (undamped under a stack). Raises InvalidParameterError
    (naming the parameter: a punch's index in ``punches[k]``),
    SupercriticalSpeedError,
    UnphysicalContactError (no contact set found) and ConvergenceError.
    ``cancel``: a ``movingpunch.Cancel`` token, as ``movingpunch.solve``'s
    (the search for each contact set stops at its next solve).
    ``numerics``: ``movingpunch.Numerics`` instead of ``tol`` and ``n`` (a
    train searches its contact sets itself: its ``allow_unphysical`` must
    be False and its ``contact`` "auto").
    """
    from movingpunch.asymmetric import check_damping, check_friction

    t0 = time.perf_counter()
    if numerics is not None:
        tol, n, allow, contact = params.numerics_keywords(numerics, tol=tol, n=n)
        if allow or contact != "auto":
            raise InvalidParameterError(
                "numerics: a train of punches finds its contact sets itself; "
                "give Numerics(tol=..., n=...) with allow_unphysical=False and "
                f'contact="auto", got {numerics!r}',
                parameter="numerics",
                allowed='Numerics with allow_unphysical=False, contact="auto"',
            )
    given: object = punches  # anything, at run time
    if isinstance(given, (str, bytes)) or not isinstance(given, Sequence) or not given:
        raise InvalidParameterError(
            f"punches must be a non-empty list of movingpunch.Punch, got {punches!r}",
            parameter="punches",
            allowed="a non-empty list of Punch",
        )
    for k, p in enumerate(punches):
        if not isinstance(p, Punch):
            raise InvalidParameterError(
                f"punches[{k}] must be a movingpunch.Punch, got {p!r}",
                parameter="punches",
                allowed="a non-empty list of Punch",
            )
    if check_friction(friction) > 0.0:
        raise InvalidParameterError(
            "friction must be 0 for a train of punches (several contact zones with "
            f"friction are not supported yet), got {friction!r}",
            parameter="friction",
            allowed="0 for solve_punches",
        )
    damp = check_damping(damping)
    if len(punches) > 16:
        raise InvalidParameterError(
            f"punches: at most 16 punches, got {len(punches)}",
            parameter="punches",
            allowed="1 to 16 punches",
        )
    size = 0 if n is None else params.check_size(n, 256, " for several zones")
    # Each punch alone (its own contact set starts the train's search);
    # identical punches (a train's wheels) share one solve.
    alone: dict[tuple[object, float], ContactSolution] = {}
    singles = []
    for p in punches:
        key = (p.profile, p.load)
        if key not in alone:
            alone[key] = solve(
                vstar=vstar,
                kw=kw,
                load=p.load,
                nu=nu,
                tol=tol,
                n=n,
                damping=damp,
                kp=kp,
                profile=p.profile,
                layers=layers,
                base=base,
            )
        singles.append(alone[key])
    if len(punches) == 1 and punches[0].at == 0.0:
        return singles[0]
    return solve_train(
        punches, singles, damping=damp, tol=resolve_tol(tol), n=size, t0=t0
    )
