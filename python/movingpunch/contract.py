"""The result contract: what every contact solution offers.

``movingpunch.solve`` returns a ``Solution`` (frictionless, undamped: the
paper's model) or, with ``damping > 0``, a ``AsymmetricSolution`` (an asymmetric
contact with drag). Both satisfy ``ContactSolution``, and everything that
consumes a solution — scenes, the CLI, the terminal UI — uses only this
contract, never the concrete class. A new physical effect (a punch profile,
friction, another foundation) returns a result that satisfies it too.

Dimensionless throughout: lengths per layer thickness h, pressures and
stresses per P/h, the punch moving towards +x.

Pure typing: no _core import, no NumPy work.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Protocol, overload, runtime_checkable

import numpy.typing as npt

from movingpunch.fields import (
    DesignStrains,
    FloatArray,
    StrainField,
    StressField,
    StressPeaks,
)
from movingpunch.media import Medium

if TYPE_CHECKING:
    from movingpunch.profiles import PunchProfile

__all__ = [
    "CONTRACT_FIELDS",
    "CONTRACT_METHODS",
    "ContactSolution",
    "Points",
    "SolvedPunch",
]

Points = npt.NDArray[Any] | Sequence[Any]
"""Several positions: an array or a sequence (a scalar gives a float)."""


# runtime_checkable for the contract test; on Python 3.11 isinstance reads
# every member and so computes the lazy ones: not for hot paths.
@runtime_checkable
class SolvedPunch(Protocol):
    """One punch of a solution (``ContactSolution.punches``; the class is
    ``movingpunch.PunchResult``): ``profile`` (its shape), ``load``
    (P_k/(mu h)), ``at`` (x/h of its axis), ``contact_zones`` (its zones
    (x_left, x_right)/h, left to right), ``zone_loads`` (the load of each,
    summing to ``load``), ``drag`` (the normal pressure's horizontal force on
    it over P_k), ``indentation`` (delta_k/h), ``pressure(x)`` (its own
    pressure over P_k/h) and ``to_dict()``. A single contact has one, at
    x = 0 with its one zone."""

    @property
    def profile(self) -> PunchProfile: ...
    @property
    def load(self) -> float: ...
    @property
    def at(self) -> float: ...
    @property
    def contact_zones(self) -> tuple[tuple[float, float], ...]: ...
    @property
    def zone_loads(self) -> tuple[float, ...]: ...
    @property
    def drag(self) -> float: ...
    @property
    def indentation(self) -> float: ...
    @overload
    def pressure(self, x: float) -> float: ...
    @overload
    def pressure(self, x: Points) -> FloatArray: ...
    def to_dict(self) -> dict[str, object]: ...


@runtime_checkable
class ContactSolution(Protocol):
    """Every solution's fields and evaluations (see the module docstring).

    Parameters: ``vstar``, ``kw``, ``kp`` (0.0 for the paper's Winkler
    springs), ``radius``, ``load``, ``nu``, ``tol``, ``damping`` (0.0 for the
    paper's model), ``friction`` (Coulomb f, 0.0 for the paper's model). The
    contact: ``contact_interval``
    (x_back, x_front), ``contact_zones`` (every zone, left to right: one for
    a single contact, ``contact_interval`` their hull), ``punches`` (each
    punch, ``SolvedPunch``: one for a single punch, a train's in its
    order), ``half_width``, ``centre``, ``a`` (the leading end;
    the half-width of a symmetric contact), ``p0`` (the pressure under the
    punch's axis x = 0, over P/h), ``indentation``, ``drag`` (the
    horizontal force of the normal pressure over P; 0.0 without damping),
    ``tangential_force`` (the friction force on the punch over P, f; positive:
    it opposes the motion towards +x), ``end_exponents`` ((gamma_back,
    gamma_front): p ~ (x - x_back)^gamma_back (x_front - x)^gamma_front;
    (0.5, 0.5) without friction; a flat punch on the asymmetric solver
    reports its own, 1 less: (-0.5, -0.5) without friction) and
    ``dissipation`` (the power dissipated over P V, equal to ``drag`` by the
    energy balance without friction; a flat punch's drag is its edges'
    force, docs/theory.md section 14).
    Trust: ``error_estimate`` (of the contact ends), ``stress_error_estimate``,
    ``valid``, ``validity``, ``warnings``. The punch: ``profile`` (its
    shape, ``movingpunch.profiles``; ``radius`` is the cylinder's or the
    rounded corners' R/h, inf for a flat punch or a table) and
    ``end_coefficients`` (K_back, K_front) of a pressure square-root
    singular at the ends (a flat punch; (0.0, 0.0) for bounded ends) with
    ``end_coefficient_error``, the bound on their error. Cost:
    ``stage_times``, ``kernel_builds``, ``iterations``, ``elapsed``,
    ``collocation_n``.
    """

    # Data: read-only (results are immutable).
    @property
    def vstar(self) -> float: ...
    @property
    def kw(self) -> float: ...
    @property
    def kp(self) -> float: ...
    @property
    def radius(self) -> float: ...
    @property
    def load(self) -> float: ...
    @property
    def nu(self) -> float: ...
    @property
    def tol(self) -> float: ...
    @property
    def damping(self) -> float: ...
    @property
    def friction(self) -> float: ...
    @property
    def tangential_force(self) -> float: ...
    @property
    def end_exponents(self) -> tuple[float, float]: ...
    @property
    def a(self) -> float: ...
    @property
    def contact_interval(self) -> tuple[float, float]: ...
    @property
    def contact_zones(self) -> tuple[tuple[float, float], ...]: ...
    @property
    def punches(self) -> tuple[SolvedPunch, ...]: ...
    @property
    def medium(self) -> Medium: ...
    @property
    def half_width(self) -> float: ...
    @property
    def centre(self) -> float: ...
    @property
    def p0(self) -> float: ...
    @property
    def indentation(self) -> float: ...
    @property
    def drag(self) -> float: ...
    @property
    def dissipation(self) -> float: ...
    @property
    def critical_vstar(self) -> float: ...
    @property
    def rayleigh_vstar(self) -> float: ...
    @property
    def phi1(self) -> float: ...
    @property
    def iterations(self) -> int: ...
    @property
    def collocation_n(self) -> int: ...
    @property
    def error_estimate(self) -> float: ...
    @property
    def stress_error_estimate(self) -> float: ...
    @property
    def elapsed(self) -> float: ...
    @property
    def valid(self) -> bool: ...
    @property
    def validity(self) -> str: ...
    @property
    def min_pressure(self) -> float: ...
    @property
    def pressure_margin(self) -> float: ...
    @property
    def min_gap(self) -> float: ...
    @property
    def warnings(self) -> tuple[str, ...]: ...
    @property
    def kernel_builds(self) -> int: ...
    @property
    def profile(self) -> PunchProfile: ...
    @property
    def end_coefficients(self) -> tuple[float, float]: ...
    @property
    def end_coefficient_error(self) -> float: ...
    @property
    def stage_times(self) -> Mapping[str, float]: ...

    # Evaluations: a float for a scalar argument, else an array of its shape.
    @overload
    def pressure(self, x: float) -> float: ...
    @overload
    def pressure(self, x: Points) -> FloatArray: ...
    @overload
    def surface_stress(self, x: float) -> float: ...
    @overload
    def surface_stress(self, x: Points) -> FloatArray: ...
    @overload
    def depth_stress(self, y: float) -> float: ...
    @overload
    def depth_stress(self, y: Points) -> FloatArray: ...
    @overload
    def displacement(self, x: float, y: float = 0.0) -> float: ...
    @overload
    def displacement(self, x: Points, y: float = 0.0) -> FloatArray: ...
    @overload
    def surface_displacement(self, x: float) -> float: ...
    @overload
    def surface_displacement(self, x: Points) -> FloatArray: ...
    @overload
    def foundation_reaction(self, x: float) -> float: ...
    @overload
    def foundation_reaction(self, x: Points) -> FloatArray: ...
    def stress_field(
        self, x: npt.ArrayLike, y: npt.ArrayLike, side: str = "above"
    ) -> StressField: ...
    def strain_field(
        self, x: npt.ArrayLike, y: npt.ArrayLike, side: str = "above"
    ) -> StrainField: ...
    @overload
    def depth_strain(self, y: float, x: float = 0.0, side: str = "above") -> float: ...
    @overload
    def depth_strain(
        self, y: Points, x: float = 0.0, side: str = "above"
    ) -> FloatArray: ...
    def design_strains(self) -> DesignStrains: ...
    def stress_peaks(self, extent: float | None = None) -> StressPeaks: ...
    def to_dict(self) -> dict[str, object]: ...


CONTRACT_FIELDS: tuple[str, ...] = (
    "vstar",
    "kw",
    "kp",
    "radius",
    "load",
    "nu",
    "tol",
    "damping",
    "friction",
    "tangential_force",
    "end_exponents",
    "a",
    "contact_interval",
    "contact_zones",
    "punches",
    "medium",
    "half_width",
    "centre",
    "p0",
    "indentation",
    "drag",
    "dissipation",
    "critical_vstar",
    "rayleigh_vstar",
    "phi1",
    "iterations",
    "collocation_n",
    "error_estimate",
    "stress_error_estimate",
    "elapsed",
    "valid",
    "validity",
    "min_pressure",
    "pressure_margin",
    "min_gap",
    "warnings",
    "kernel_builds",
    "stage_times",
    "profile",
    "end_coefficients",
    "end_coefficient_error",
)
"""The contract's data fields, each also a key of ``to_dict()`` (``profile``
as its scene-file form ``{"kind": ..., ...}``, ``punches`` as each punch's
``to_dict()``, ``medium`` as its ``to_dict()``)."""

CONTRACT_METHODS: tuple[str, ...] = (
    "pressure",
    "surface_stress",
    "depth_stress",
    "stress_field",
    "strain_field",
    "depth_strain",
    "design_strains",
    "displacement",
    "surface_displacement",
    "foundation_reaction",
    "stress_peaks",
    "to_dict",
)
"""The contract's evaluations."""
