"""Result types for stresses: the field on a grid and the peak values.

Pure NumPy on arrays the core computed; no Textual, no _core import.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = [
    "DesignStrains",
    "StrainField",
    "StressField",
    "StressPeaks",
    "derived_stresses",
    "plane_strains",
]

FloatArray = npt.NDArray[np.float64]


def plane_strains(
    sigma_x: FloatArray,
    sigma_y: FloatArray,
    tau_xy: FloatArray,
    mu: float | FloatArray,
    nu: float | FloatArray,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(eps_x, eps_y, gamma_xy) of plane strain from the stresses by Hooke's
    law of the local material (shear modulus ``mu``, Poisson's ratio ``nu``,
    scalars or arrays broadcasting against the stresses):
    eps_x = (sigma_x - nu (sigma_x + sigma_y))/(2 mu), eps_y likewise,
    gamma_xy = tau_xy/mu. Stresses per P/h and mu per mu_1 give strains per
    P/(mu_1 h)."""
    sx, sy, txy = (np.asarray(a, dtype=np.float64) for a in (sigma_x, sigma_y, tau_xy))
    trace = np.asarray(nu) * (sx + sy)
    two_mu = 2.0 * np.asarray(mu, dtype=np.float64)
    return (sx - trace) / two_mu, (sy - trace) / two_mu, txy / np.asarray(mu)


def derived_stresses(
    sigma_x: FloatArray, sigma_y: FloatArray, tau_xy: FloatArray, nu: float | FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(sigma_z, von_mises, max_shear) of a plane-strain state.

    sigma_z = nu (sigma_x + sigma_y); von Mises from the three normal stresses
    and tau_xy; max_shear is Tresca's (sigma_max - sigma_min)/2 over the three
    principal stresses (sigma_z is one of them).

    At a singular point (a flat punch's sharp edge x = +-b on the surface,
    where the pressure and so sigma_x, sigma_y, and with friction tau_xy, are
    infinite) von Mises and max_shear are +inf, the limit of the field as the
    edge is approached (it grows like 1/sqrt(distance)), never NaN.
    """
    sigma_x, sigma_y, tau_xy = (
        np.asarray(a, dtype=np.float64) for a in (sigma_x, sigma_y, tau_xy)
    )
    singular = ~(np.isfinite(sigma_x) & np.isfinite(sigma_y) & np.isfinite(tau_xy))
    if singular.any():
        # inf - inf is NaN: compute on the regular points only.
        sx, sy, txy = (np.where(singular, 0.0, a) for a in (sigma_x, sigma_y, tau_xy))
    else:
        sx, sy, txy = sigma_x, sigma_y, tau_xy
    sigma_z = nu * (sigma_x + sigma_y)
    sz = nu * (sx + sy)
    von_mises = np.sqrt(
        0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3.0 * txy**2
    )
    centre = 0.5 * (sx + sy)
    radius = np.hypot(0.5 * (sx - sy), txy)
    principal = np.stack([centre + radius, centre - radius, sz])
    max_shear = 0.5 * (principal.max(axis=0) - principal.min(axis=0))
    if singular.any():
        von_mises = np.where(singular, np.inf, von_mises)
        max_shear = np.where(singular, np.inf, max_shear)
    return sigma_z, von_mises, max_shear


@dataclass(frozen=True)
class StressField:
    """Stresses over P/h on the grid ``x`` (x/h) by ``y`` (y/h, -1 <= y <= 0).

    Every array is shaped (len(y), len(x)); tension is positive.
    """

    x: FloatArray
    y: FloatArray
    sigma_x: FloatArray
    sigma_y: FloatArray
    tau_xy: FloatArray
    sigma_z: FloatArray
    """Out-of-plane normal stress of plane strain, nu (sigma_x + sigma_y)."""
    von_mises: FloatArray
    max_shear: FloatArray
    """Tresca: half the spread of the three principal stresses."""


@dataclass(frozen=True)
class StrainField:
    """Strains of plane strain on a grid, per P/(mu_1 h) (mu_1: the top
    sublayer's shear modulus): ``x`` (x/h) by ``y`` (y/h), each array shaped
    (len(y), len(x)); extension positive. eps_x and gamma_xy/2 are continuous
    across a bonded interface only where the displacement is (eps_x always;
    eps_y jumps with the moduli); ``side`` says which material an interface
    depth took."""

    x: FloatArray
    y: FloatArray
    eps_x: FloatArray
    eps_y: FloatArray
    gamma_xy: FloatArray
    side: str = "above"


@dataclass(frozen=True)
class DesignStrains:
    """What a pavement engineer reads (per P/(mu_1 h), at x = 0 under the
    punch's axis): the horizontal strain eps_x at the bottom of each sublayer
    (top to bottom; tension positive: fatigue cracking of bound layers) and
    the vertical strain eps_y at the top of the base (compression negative:
    rutting of the subgrade), None on springs (no continuum below)."""

    bottom_horizontal: tuple[float, ...]
    base_vertical: float | None

    def to_dict(self) -> dict[str, object]:
        return {
            "bottom_horizontal": list(self.bottom_horizontal),
            "base_vertical": self.base_vertical,
        }


@dataclass(frozen=True)
class StressPeaks:
    """Peak values of sigma_x/(P/h), with their positions x/h (x >= 0 for the
    symmetric solver, whose distributions are even in x; of either sign for
    the damped foundation's asymmetric ones).

    Found by one search (``movingpunch.peaks``) whose grid resolves every
    length of the problem (contact width, the square-root cusp at the contact
    ends, layer thickness, the wavelength of the slowest free wave) and whose
    march into the far field stops only where the decaying response can no
    longer reach a peak; every local extreme that could be the global one is
    refined. Each peak is a value of the field at its position, within
    ``error_bound`` of the field's true extreme on the searched interval,
    unless ``warnings`` says the search could not get there.
    """

    top_compressive: float
    """Most compressive (lowest) sigma_x on the top surface."""
    top_compressive_x: float
    top_tensile: float
    """Most tensile (highest) sigma_x on the top surface."""
    top_tensile_x: float
    bottom_tensile: float
    """Most tensile sigma_x on the bottom surface (y = -h)."""
    bottom_tensile_x: float
    centre_top: float
    """sigma_x(0, 0)."""
    centre_bottom: float
    """sigma_x(0, -h)."""
    search_extent: float
    """The peaks were searched on 0 <= x <= search_extent (symmetric solver)
    or -search_extent <= x <= search_extent (damped foundation)."""
    error_bound: float
    """Bound on the absolute error of each peak value: ``search_error`` plus
    the solution's stress error estimate (``Solution.stress_error_estimate``;
    the asymmetric solver has no stress error estimate, so for it this is the
    search's part alone)."""
    search_error: float
    """The search's own part of ``error_bound``: how far the true extreme of
    the computed field on the searched interval can lie beyond the reported
    value (from the refinement brackets of every candidate peak)."""
    warnings: tuple[str, ...] = ()
    """Why the peaks may not be the extremes on the whole extent: the far
    field decayed too slowly to be searched within the search's budget of
    points, or did not decay as it should. Empty when the bound holds."""
