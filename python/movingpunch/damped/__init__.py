"""Deprecated: the asymmetric solver's old module name.

The asymmetric solver (a damped foundation, Coulomb friction, asymmetric
profiles) is named by its role now: :mod:`movingpunch.asymmetric`, whose result
is ``AsymmetricSolution``. This module re-exports it under the old names
(``DampedSolution``, ``solve_damped``) and warns once, on import, with a
``DeprecationWarning``. Import :mod:`movingpunch.asymmetric` instead.

(A package rather than a ``damped.py`` beside ``asymmetric.py``, so that git
sees damped.py renamed to asymmetric.py and carries its history over.)
"""

from __future__ import annotations

import warnings

from movingpunch.asymmetric import (
    AsymmetricSolution,
    check_damping,
    check_friction,
    coupling_constant,
    damped_layer_response,
    end_exponents,
    solve_asymmetric,
)

warnings.warn(
    "movingpunch.damped is deprecated: import movingpunch.asymmetric "
    "(DampedSolution is AsymmetricSolution, solve_damped is solve_asymmetric)",
    DeprecationWarning,
    stacklevel=2,
)

DampedSolution = AsymmetricSolution
"""Deprecated name of :class:`movingpunch.asymmetric.AsymmetricSolution`."""

solve_damped = solve_asymmetric
"""Deprecated name of :func:`movingpunch.asymmetric.solve_asymmetric`."""

__all__ = [
    "AsymmetricSolution",
    "DampedSolution",
    "check_damping",
    "check_friction",
    "coupling_constant",
    "damped_layer_response",
    "end_exponents",
    "solve_asymmetric",
    "solve_damped",
]
