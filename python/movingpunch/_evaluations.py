"""The evaluations every solution computes the same way from its compiled
result (``_impl``): the pressure, the surface stress and displacement, the
displacement at a depth, the stress field, the stress peaks and
``to_dict``. ``Solution``, ``AsymmetricSolution`` and ``ZonedSolution``
inherit them (one implementation of the contract's
shared members; the compiled results bind the same members once,
``bind_result_common`` in cpp/bindings/bindings.hpp)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, overload

import numpy as np
import numpy.typing as npt

from movingpunch import params
from movingpunch._evaluate import (
    _as_points,
    _check_positive_extent,
    _chunked_grid,
    _depths,
    _flat,
    _is_scalar,
    _json_safe,
    _pointwise,
    _real_any,
)
from movingpunch.contract import CONTRACT_FIELDS, Points, SolvedPunch
from movingpunch.errors import InvalidParameterError
from movingpunch.fields import (
    DesignStrains,
    FloatArray,
    StrainField,
    StressField,
    StressPeaks,
    derived_stresses,
    plane_strains,
)
from movingpunch.media import HalfSpace, Layer, Medium, Winkler
from movingpunch.peaks import search_peaks
from movingpunch.profiles import Cylinder, Flat, Profile, PunchProfile, RoundedFlat

_PROFILE_TYPES = (Flat, RoundedFlat, Profile)

__all__ = ["Evaluations", "ResultFields"]


class Evaluations:
    """Mixin: the shared evaluations, on ``self._impl`` and ``self.nu``."""

    __slots__ = ()

    if TYPE_CHECKING:
        _impl: Any
        nu: float
        kw: float
        radius: float
        kp: float

        @property
        def damping(self) -> float: ...

        @property
        def stress_error_estimate(self) -> float: ...
        @property
        def contact_interval(self) -> tuple[float, float]: ...
        @property
        def end_exponents(self) -> tuple[float, float]: ...
        @property
        def punches(self) -> tuple[SolvedPunch, ...]: ...

    @property
    def profile(self) -> PunchProfile:
        """The punch's shape (``movingpunch.profiles``): the solve's
        ``profile``, or ``Cylinder(radius)``."""
        found = getattr(self, "_profile", None)
        return found if found is not None else Cylinder(self.radius)

    @property
    def medium(self) -> Medium:
        """The medium solved on (``movingpunch.media``): the sublayers and
        the base; the homogeneous layer of (kw, nu, kp, damping) unless
        ``layers=`` or ``base=`` gave another."""
        found = getattr(self, "_medium", None)
        if found is not None:
            return found  # type: ignore[no-any-return]
        return Medium(
            layers=(Layer(nu=self.nu),),
            base=Winkler(kw=self.kw, kp=self.kp, damping=self.damping),
        )

    @property
    def contact_zones(self) -> tuple[tuple[float, float], ...]:
        """Every contact zone (x_left, x_right)/h from left to right: the one
        ``contact_interval`` of a single contact; several when the contact
        has separated or a train of punches is solved
        (``movingpunch.zones.ZonedSolution``, whose ``contact_interval`` is
        their hull)."""
        back, front = self.contact_interval
        return ((float(back), float(front)),)

    @property
    def end_coefficients(self) -> tuple[float, float]:
        """(K_back, K_front): the stress-intensity-like coefficients of a
        pressure that is square-root singular at the contact's ends (a flat
        punch), K = lim sqrt(2 pi d) p over (P/h) sqrt(h) as the distance d
        to that end goes to 0 (1/sqrt(pi b/h) each on a half-plane:
        p = P/(pi sqrt(b^2 - x^2))). With friction the asymmetric solver's
        flat punch has p ~ d^gamma (``end_exponents``, gamma = -1/2 without
        friction) and K = lim sqrt(2 pi) d^(-gamma) p over (P/h) h^(-gamma).
        (0.0, 0.0) for bounded ends."""
        both = getattr(self._impl, "end_coefficients", None)
        if both is not None:
            return (float(both[0]), float(both[1]))
        k = float(getattr(self._impl, "end_coefficient", 0.0))
        return (k, k)

    @property
    def end_coefficient_error(self) -> float:
        """Estimated bound on the absolute error of each of
        ``end_coefficients`` (from the change between collocation sizes, the
        kernel's error carried through the solve and round-off); 0.0 for
        bounded ends, whose coefficients are exactly 0."""
        return float(getattr(self._impl, "end_coefficient_error", 0.0))

    @overload
    def pressure(self, x: float) -> float: ...
    @overload
    def pressure(self, x: Points) -> FloatArray: ...
    def pressure(self, x: npt.ArrayLike) -> float | FloatArray:
        """Contact pressure p/(P/h) at x/h (0 outside the contact; +inf at
        a flat punch's edges |x| = b, where it is square-root singular).

        A float for a scalar ``x``, else an array of the shape of ``x``.
        """
        return _pointwise("x", x, self._impl.pressure)

    @overload
    def surface_stress(self, x: float) -> float: ...
    @overload
    def surface_stress(self, x: Points) -> FloatArray: ...
    def surface_stress(self, x: npt.ArrayLike) -> float | FloatArray:
        """sigma_x(x, 0)/(P/h) on the top surface at x/h, inside and outside
        the contact (tension positive)."""
        return _pointwise("x", x, self._impl.surface_stress)

    @overload
    def surface_displacement(self, x: float) -> float: ...
    @overload
    def surface_displacement(self, x: Points) -> FloatArray: ...
    def surface_displacement(self, x: npt.ArrayLike) -> float | FloatArray:
        """Vertical surface displacement v(x, 0)/h at x/h (negative under the
        punch). A float for a scalar ``x``, else an array of the shape of ``x``.
        """
        return _pointwise("x", x, self._impl.surface_displacement)

    @overload
    def displacement(self, x: float, y: float = 0.0) -> float: ...
    @overload
    def displacement(self, x: Points, y: float = 0.0) -> FloatArray: ...
    def displacement(self, x: npt.ArrayLike, y: float = 0.0) -> float | FloatArray:
        """Vertical displacement v(x, y)/h at x/h and one depth y/h in [-1, 0]
        (negative downwards)."""
        depth = _depths(y)
        if depth.ndim != 0:
            raise params.fail("y", f"y must be one depth in [-1, 0], got {y!r}")
        grid = self._impl.displacement
        return _pointwise("x", x, lambda xs: grid(xs, _flat(depth))[0])

    @overload
    def depth_stress(self, y: float, x: float = ...) -> float: ...
    @overload
    def depth_stress(self, y: Points, x: float = ...) -> FloatArray: ...
    def depth_stress(self, y: npt.ArrayLike, x: float = 0.0) -> float | FloatArray:
        """sigma_x(x, y)/(P/h) at depths y/h in [-1, 0] (y = 0:
        ``surface_stress``), at x = 0 unless ``x`` is given (the symmetric
        ``Solution`` has its own, at x = 0). The cost does not depend on y
        (the half-plane part is in closed form)."""
        pts = _depths(y)
        xs = _real_any("x", x)
        if not math.isfinite(xs):
            raise InvalidParameterError(f"x must be a finite number, got {x!r}")
        column = np.array([xs])
        grid = self._impl.stress_field
        return _pointwise("y", y, lambda ys: grid(column, ys)[0][:, 0], pts)

    @overload
    def foundation_reaction(self, x: float) -> float: ...
    @overload
    def foundation_reaction(self, x: Points) -> FloatArray: ...
    def foundation_reaction(self, x: npt.ArrayLike) -> float | FloatArray:
        """Pressure of the base on the layer, -sigma_y(x, -h)/(P/h)
        (springs and dashpots together), from the stress field."""
        field = self.stress_field(_flat(_as_points("x", x)), [-1.0])
        values = -field.sigma_y[0]
        return float(values[0]) if _is_scalar(x) else values.reshape(np.shape(x))

    def _stresses(
        self, x: npt.ArrayLike, y: npt.ArrayLike, side: str, compliance: bool = False
    ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, bool]:
        xs = _flat(_as_points("x", x))
        ys = _flat(_depths(y))
        if side not in ("above", "below"):
            raise InvalidParameterError(
                f"side must be 'above' or 'below' (which material an interface "
                f"depth takes), got {side!r}",
                parameter="side",
                allowed="'above' or 'below'",
            )
        below = side == "below"
        impl = self._impl

        def grid(xx: FloatArray, yy: FloatArray) -> tuple[FloatArray, ...]:
            if compliance:  # through the compliance of each depth's material
                return tuple(impl.compliance_stress_field(xx, yy, below))
            return tuple(impl.stress_field(xx, yy, below))

        sx, sy, txy = _chunked_grid(grid, xs, ys)
        return xs, ys, sx, sy, txy, below

    def stress_field(
        self, x: npt.ArrayLike, y: npt.ArrayLike, side: str = "above"
    ) -> StressField:
        """All stresses over P/h on the grid ``x`` (x/h) by ``y`` (y/h in
        [-1, 0]); arrays shaped (len(y), len(x)). On the surface y = 0:
        sigma_x = ``surface_stress``, sigma_y = -p, tau_xy = f p (0 for a
        frictionless punch). At an interface between sublayers (a layered
        ``medium``) sigma_x jumps: ``side`` "above" (the default) or "below"
        says which material's; sigma_y and tau_xy are continuous."""
        xs, ys, sx, sy, txy, below = self._stresses(x, y, side)
        _, nu = self.medium.material(ys, below)
        sz, vm, ms = derived_stresses(sx, sy, txy, nu[:, None])
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

    def strain_field(
        self, x: npt.ArrayLike, y: npt.ArrayLike, side: str = "above"
    ) -> StrainField:
        """Strains per P/(mu_1 h) on the grid ``x`` by ``y`` (as
        ``stress_field``), from the stresses by Hooke's law of the material at
        each depth (``medium.material``); ``side`` picks the material at an
        interface depth (eps_x is continuous across a bonded interface, eps_y
        jumps). On a viscoelastic layer a mode's strain is its stress over
        mu_0 m(alpha): the stresses pass through the material's compliance
        along x (its memory, ``compliance_stress_field``) before Hooke's law
        at the relaxed mu_0 (docs/theory.md section 17.5)."""
        xs, ys, sx, sy, txy, below = self._stresses(
            x, y, side, compliance=self.medium.viscoelastic
        )
        mu, nu = self.medium.material(ys, below)
        ex, ey, gxy = plane_strains(sx, sy, txy, mu[:, None], nu[:, None])
        return StrainField(x=xs, y=ys, eps_x=ex, eps_y=ey, gamma_xy=gxy, side=side)

    @overload
    def depth_strain(self, y: float, x: float = ..., side: str = ...) -> float: ...
    @overload
    def depth_strain(
        self, y: Points, x: float = ..., side: str = ...
    ) -> FloatArray: ...
    def depth_strain(
        self, y: npt.ArrayLike, x: float = 0.0, side: str = "above"
    ) -> float | FloatArray:
        """eps_x(x, y) per P/(mu_1 h) at depths y/h in [-1, 0], at x = 0
        unless ``x`` is given (``strain_field``'s eps_x)."""
        xs = _real_any("x", x)
        if not math.isfinite(xs):
            raise InvalidParameterError(f"x must be a finite number, got {x!r}")
        pts = _depths(y)
        field = self.strain_field(np.array([xs]), _flat(pts), side)
        values = field.eps_x[:, 0]
        return float(values[0]) if _is_scalar(y) else values.reshape(np.shape(y))

    def design_strains(self) -> DesignStrains:
        """The pavement engineer's strains at x = 0 (``DesignStrains``): eps_x
        at the bottom of each sublayer (its own material), eps_y at the top of
        the base (the half-space's material; None on springs)."""
        medium = self.medium
        bottoms = [*medium.interfaces, -1.0]
        field = self.strain_field(np.array([0.0]), np.array(bottoms), "above")
        base: float | None = None
        if isinstance(medium.base, HalfSpace):
            under = self.strain_field(np.array([0.0]), np.array([-1.0]), "below")
            base = float(under.eps_y[0, 0])
        return DesignStrains(
            bottom_horizontal=tuple(float(v) for v in field.eps_x[:, 0]),
            base_vertical=base,
        )

    def stress_peaks(self, extent: float | None = None) -> StressPeaks:
        """Peaks of sigma_x/(P/h): most compressive and most tensile on the
        top surface, most tensile at the bottom, with their x/h, and sigma_x
        at (0, 0) and (0, -h). Searched by ``movingpunch.peaks.search_peaks``
        on -extent <= x <= extent (0 <= x <= extent for a symmetric contact,
        whose distributions are even; default extent max(6 max(|x_back|,
        |x_front|), 10 h)): a grid on the scales of the problem (the contact,
        the cusps at both ends, the layer, the slowest free wave), a march
        into the far field until the response has decayed below the peaks,
        and a refinement of every candidate; each value is within
        ``error_bound`` (``stress_error_estimate`` plus the search's own
        uncertainty) of the field's extreme (see StressPeaks)."""
        back, front = self.contact_interval
        k_back, k_front = self.end_coefficients
        singular = k_back != 0.0 or k_front != 0.0
        friction = float(getattr(self, "friction", 0.0))
        # Damping or friction: the distributions are not even, even on a
        # symmetric contact (a flat punch's face).
        # Several zones or punches: even only when they say so (``_even``).
        asymmetric = (
            float(getattr(self, "damping", 0.0)) > 0.0
            or friction > 0.0
            or not getattr(self, "_even", True)
        )
        surface = self._impl.surface_stress
        if singular:
            # A flat punch: sigma_x(x, 0) ~ -phi2 K/sqrt(2 pi d) at its edges.
            # The search sees it capped (its other peaks are finite); the
            # singular extreme is reported as such below.
            def surface(x: FloatArray) -> FloatArray:
                values = np.asarray(self._impl.surface_stress(x), dtype=np.float64)
                return np.clip(values, -_SINGULAR_CAP, _SINGULAR_CAP)

        span = (
            max(6.0 * max(abs(back), abs(front)), 10.0)
            if extent is None
            else _check_positive_extent(extent)
        )
        alpha = self.medium.critical_speed()[1]
        wave = 2.0 * math.pi / alpha if 0.0 < alpha < math.inf else math.inf
        depth = np.array([-1.0])
        centre = self._impl.stress_field(np.array([0.0]), np.array([0.0, -1.0]))[0][
            :, 0
        ]
        found = search_peaks(
            surface,
            lambda x: self._impl.stress_field(x, depth)[0][0],
            lo=0.0 if back == -front and not asymmetric else -float(span),
            hi=float(span),
            ends=(back, front),
            wavelength=wave,
            # A quarter of the solution's own sigma_x error: the search adds
            # little to the bound (refining to tol instead left damped bounds
            # 176 times the error at tol 1e-2).
            tolerance=0.25 * self.stress_error_estimate,
        )
        search = max(p.uncertainty for p in found.peaks)
        top_min, top_max, warnings = found.top_min, found.top_max, found.warnings
        if singular and (k_back != k_front or friction > 0.0):
            # The asymmetric solver's flat punch: inside the face sigma_x ~
            # -(phi2 + f^2 C_q Phi) p at both edges (-inf where K > 0); with
            # friction the shear traction's Cauchy term is singular beside
            # the edges too, +inf just behind the trailing edge for K_back >
            # 0 (docs/theory.md section 14).
            inf = math.inf
            infinite = []
            minus = [x for x, k in ((front, k_front), (back, k_back)) if k > 0]
            plus = [x for x, k in ((back, k_back), (front, k_front)) if k < 0]
            if friction > 0.0 and k_back != 0.0:
                minus, plus = minus or [back], [back]
            if minus:
                top_min = type(top_min)(-inf, minus[0], 0.0)
                infinite.append(f"-inf at x/h = {minus[0]:g}")
            if plus:
                top_max = type(top_max)(inf, plus[0], 0.0)
                infinite.append(f"+inf at x/h = {plus[0]:g}")
            finite = [found.bottom_max]
            if not minus:
                finite.append(top_min)
            if not plus:
                finite.append(top_max)
            search = max(p.uncertainty for p in finite)
            warnings = (
                *warnings,
                f"sigma_x(x, 0) is singular at the flat punch's edges x/h = {back:g}, "
                f"{front:g} (end coefficients (K_back, K_front) = ({k_back:.6g}, "
                f"{k_front:.6g}), exponents {self.end_exponents}): the top surface's "
                f"extremes are {' and '.join(infinite)}; the other peaks are finite",
            )
        elif singular:
            inf = math.inf
            k = k_front
            edge = (front, 0.0)
            if k > 0:
                top_min = type(top_min)(-inf, edge[0], 0.0)
            else:
                top_max = type(top_max)(inf, edge[0], 0.0)
            search = max(
                p.uncertainty for p in (found.bottom_max, top_max if k > 0 else top_min)
            )
            warnings = (
                *warnings,
                f"sigma_x(x, 0) is singular at the flat punch's edges x/h = "
                f"+-{front:g}: it goes like -phi2 K/sqrt(2 pi (b - |x|)) inside the "
                f"contact (end coefficient K = {k:.6g} (P/h) sqrt(h)), so the top "
                f"surface's most {'compressive' if k > 0 else 'tensile'} sigma_x is "
                f"{'-inf' if k > 0 else '+inf'} at the edges (see end_coefficients); "
                "the other peaks are finite",
            )
        return StressPeaks(
            top_compressive=top_min.value,
            top_compressive_x=top_min.x,
            top_tensile=top_max.value,
            top_tensile_x=top_max.x,
            bottom_tensile=found.bottom_max.value,
            bottom_tensile_x=found.bottom_max.x,
            centre_top=float(centre[0]),
            centre_bottom=float(centre[1]),
            search_extent=float(span),
            error_bound=self.stress_error_estimate + search,
            search_error=search,
            warnings=warnings,
        )

    def to_dict(self) -> dict[str, object]:
        """Every public field and every field of the contract, JSON-safe
        (tuples become lists, non-finite floats "inf", "-inf", "nan"); a
        field the medium does not give (the asymmetric solver's indentation
        under a half-space: a logarithmic far field) is None."""
        names = [f.name for f in dataclasses.fields(self)]  # type: ignore[arg-type]
        names += [n for n in CONTRACT_FIELDS if n not in names]
        return {
            n: (
                [p.to_dict() for p in self.punches]
                if n == "punches"
                else _json_safe(_listed(self._given(n)))
            )
            for n in names
            if not n.startswith("_")
        }

    def _given(self, name: str) -> object:
        """The field ``name``, or None where the medium refuses it by name."""
        try:
            return getattr(self, name)
        except InvalidParameterError:
            return None


def _listed(value: object) -> object:
    if isinstance(value, (Cylinder, *_PROFILE_TYPES, Medium)):
        return value.to_dict()  # a punch profile, a medium: the scene-file form
    if isinstance(value, tuple):  # nested too: contact_zones
        return [_listed(v) for v in value]
    return value


_SINGULAR_CAP = 1e6
"""|sigma_x|/(P/h) beyond which the peak search sees a flat punch's singular
edge values capped (stress_peaks reports that extreme as infinite)."""


@dataclass(frozen=True)
class ResultFields(Evaluations):
    """The data fields every solution has (docs: ``ContactSolution``);
    each solution adds its own after them."""

    vstar: float
    """V* = rho V^2/mu."""
    kw: float
    """k_w h/mu (inf: smooth rigid base)."""
    kp: float
    """k_p/(mu h): the Pasternak shear layer on the springs (0.0: Winkler)."""
    radius: float
    """R/h."""
    load: float
    """P/(mu h)."""
    nu: float
    """Poisson's ratio."""
    tol: float
    """Requested relative tolerance on the contact ends (a/h when symmetric)."""
    critical_vstar: float
    """Critical speed V*_cr(kw, nu, kp) of the undamped layer (damping lifts it)."""
    rayleigh_vstar: float
    """Rayleigh speed V*_R(nu)."""
    phi1: float
    """Moving half-plane factor phi1(vstar, nu)."""
    iterations: int
    """Width (load) evaluations over all collocation sizes."""
    collocation_n: int
    """Number N of collocation nodes of the final solve."""
    error_estimate: float
    """Absolute error estimate of the contact ends (of a/h when symmetric),
    in h."""
    elapsed: float
    """Solve time in seconds."""
    valid: bool
    """True if p >= 0 on the contact and the punch does not penetrate the
    surface beside it."""
    validity: str
    """Account of the validity checks."""
    min_pressure: float
    """Minimum of p/(P/h) on the contact (0 at the smooth ends: see
    ``pressure_margin``)."""
    min_gap: float
    """Minimum gap/h between punch and surface beside the contact."""
    pressure_margin: float
    """Minimum over the open contact -1 < r < 1 (r the position scaled to the
    contact) of p/((P/h) sqrt(1 - r^2)): the safety margin before the contact
    separates (> 0 for a valid contact; 2/(pi a/h) in the half-plane limit)."""
    warnings: tuple[str, ...]
    """One line per requested accuracy that was not met (what, and by how
    much); empty when ``tol`` was met."""
