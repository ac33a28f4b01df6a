"""movingpunch: a rigid cylindrical punch sliding over an elastic layer on a
Winkler foundation (plane strain, steady state, frictionless).

All quantities are dimensionless (layer thickness h = 1, shear modulus mu = 1)::

    import movingpunch as mp
    s = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
    s.a, s.p0, s.pressure(0.1)

See README.md for the parameters and docs/theory.md for the method.
"""

from __future__ import annotations

from movingpunch.errors import (
    Cancelled,
    ConvergenceError,
    InvalidParameterError,
    MovingPunchError,
    OutputError,
    SupercriticalSpeedError,
    UnphysicalContactError,
)

try:
    from movingpunch import _core  # noqa: F401  (the compiled extension: fails early)
except ImportError as exc:  # pragma: no cover - depends on how it was installed
    raise ImportError(
        "movingpunch's compiled extension movingpunch._core is missing or "
        f"cannot be loaded ({exc}). Build and install the package: run "
        "`pip install .` from the repository or see README"
    ) from exc

from movingpunch.asymmetric import AsymmetricSolution
from movingpunch.cancel import Cancel
from movingpunch.contract import ContactSolution
from movingpunch.fields import StressField, StressPeaks
from movingpunch.media import (
    GradedLayer,
    HalfSpace,
    Layer,
    Medium,
    Prony,
    Winkler,
    Zener,
)
from movingpunch.params import Numerics
from movingpunch.profiles import Cylinder, Flat, Profile, PunchProfile, RoundedFlat
from movingpunch.scene import Scene, SceneError, SceneResult, bundled_scenes
from movingpunch.solver import (
    PRESETS,
    Solution,
    clear_kernel_cache,
    critical_vstar,
    critical_wavenumber,
    kernel_cache_info,
    layer_response,
    phi1,
    phi2,
    rayleigh_vstar,
    solve,
    solve_punches,
)
from movingpunch.zones import Punch, PunchResult, ZonedSolution

DampedSolution = AsymmetricSolution
"""Deprecated name of ``AsymmetricSolution`` (the asymmetric solver's result;
not in ``__all__``)."""


def __getattr__(name: str) -> str:
    """``__version__``, looked up on first use (``movingpunch._version``)."""
    if name != "__version__":
        raise AttributeError(f"module 'movingpunch' has no attribute {name!r}")
    from movingpunch._version import version

    found = version()
    globals()["__version__"] = found
    return found


__all__ = [
    "PRESETS",
    "AsymmetricSolution",
    "Cancel",
    "Cancelled",
    "ContactSolution",
    "ConvergenceError",
    "Cylinder",
    "Flat",
    "GradedLayer",
    "HalfSpace",
    "InvalidParameterError",
    "Layer",
    "Medium",
    "MovingPunchError",
    "Numerics",
    "OutputError",
    "Profile",
    "Prony",
    "Punch",
    "PunchProfile",
    "PunchResult",
    "RoundedFlat",
    "Scene",
    "SceneError",
    "SceneResult",
    "Solution",
    "StressField",
    "StressPeaks",
    "SupercriticalSpeedError",
    "UnphysicalContactError",
    "Winkler",
    "Zener",
    "ZonedSolution",
    "__version__",
    "bundled_scenes",
    "clear_kernel_cache",
    "critical_vstar",
    "critical_wavenumber",
    "kernel_cache_info",
    "layer_response",
    "phi1",
    "phi2",
    "rayleigh_vstar",
    "solve",
    "solve_punches",
]
