"""The yardstick: a plain NumPy implementation of the paper's method.

"Frictionless contact problem between a rigid moving punch and a homogeneous
layer resting on a Winkler foundation" (2019), as restated in docs/theory.md:
plane strain, the layer's response per wavenumber alpha from a 4 x 4 linear
system, the kernel k1(t) = (1/phi1) int_0^inf (M1(alpha) - phi1) sin(alpha t)
d alpha by composite Gauss-Legendre quadrature, Gauss-Chebyshev collocation of
the singular integral equation with N = 24 points, and a secant iteration on
the contact half-width a for the prescribed load. Written to be read, not to be
fast: every trial width recomputes the kernel at the collocation offsets, no
table, no symmetry folding, no caching between solves. The benchmarks time
``movingpunch`` against it in the same process (docs/performance.md); the test
suite checks that it agrees with ``movingpunch`` on a/h
(tests/python/test_baseline_numpy.py), so the yardstick solves the same
problem.

    >>> a = solve(nu=0.2, vstar=0.2, kw=1.0, radius=100.0, mu_over_p=500.0)

Units: lengths in h, the load as mu/(P/h) (the paper's 500 is P/(mu h) =
0.002), vstar = rho V^2/mu, kw = k_w h/mu.
"""

from __future__ import annotations

import numpy as np


def surface_response(
    nu: float, vstar: float, kw: float, alpha: np.ndarray
) -> np.ndarray:
    """M1(alpha) = -alpha v(alpha, 0) per unit transformed pressure (mu = h = 1).

    A mode u = U e^{m alpha y} sin(alpha x), v = W e^{m alpha y} cos(alpha x)
    solves the steady equations of motion on the shear roots m = +-nT (W = -U/m)
    and the dilatational roots m = +-nL (W = -m U), nT^2 = 1 - vstar,
    nL^2 = 1 - vstar/c2, c2 = (kappa + 1)/(kappa - 1), kappa = 3 - 4 nu. Each
    mode is written relative to the face it decays from (no overflow). Per
    mode and unit alpha U: sigma_y = -2 (shear) or -(2 - vstar) (dilatation),
    tau_xy = (1 + m^2)/m or 2 m, alpha v = -U/m or -m U. Conditions: at y = 0
    sigma_y = -1, tau_xy = 0; at y = -1 tau_xy = 0, sigma_y = kw v.
    """
    kappa = 3.0 - 4.0 * nu
    c2 = (kappa + 1.0) / (kappa - 1.0)
    nt, nl = np.sqrt(1.0 - vstar), np.sqrt(1.0 - vstar / c2)
    roots = np.array([nt, -nt, nl, -nl])
    shear = np.array([True, True, False, False])
    sig = np.where(shear, -2.0, -(2.0 - vstar))
    tau = np.where(shear, (1.0 + roots**2) / roots, 2.0 * roots)
    disp = np.where(shear, -1.0 / roots, -roots)  # alpha v per unit alpha U
    al = np.asarray(alpha, dtype=float)[:, None]
    # The modes' values at y = 0 and y = -1: e^{m al y} for m > 0 is 1 at the
    # top and e^{-m al} at the bottom; e^{m al (y + 1)} for m < 0 the reverse.
    decay = np.exp(-np.abs(roots)[None, :] * al)
    top = np.where(roots > 0, 1.0, decay)
    bottom = np.where(roots > 0, decay, 1.0)
    mat = np.empty((al.shape[0], 4, 4))
    mat[:, 0, :] = sig * top
    mat[:, 1, :] = tau * top
    mat[:, 2, :] = tau * bottom
    # sigma_y - kw v = 0 at the bottom (v = alpha v / alpha).
    mat[:, 3, :] = sig * bottom - kw * disp * bottom / al
    rhs = np.zeros((al.shape[0], 4, 1))
    rhs[:, 0, 0] = -1.0
    amp = np.linalg.solve(mat, rhs)[:, :, 0]
    return np.asarray(-(amp * disp * top).sum(axis=1))


def half_plane_factor(nu: float, vstar: float) -> float:
    """phi1 = lim M1 = (1 - nT^2) nL / (4 nL nT - (1 + nT^2)^2)."""
    kappa = 3.0 - 4.0 * nu
    c2 = (kappa + 1.0) / (kappa - 1.0)
    nt, nl = np.sqrt(1.0 - vstar), np.sqrt(1.0 - vstar / c2)
    return (
        float((1.0 - nt**2) * nl / (4.0 * nl * nt - (1.0 + nt**2) ** 2))
        if vstar
        else 1.0 - nu
    )


def kernel_grid(
    nu: float, vstar: float, kw: float, width: float = 0.25, points: int = 12
) -> tuple[np.ndarray, np.ndarray, float]:
    """Nodes, weights times (M1 - phi1)/phi1, and phi1: composite Gauss-Legendre
    on panels of ``width`` out to where M1 - phi1 ~ e^{-2 nT alpha} < 1e-17."""
    phi1 = half_plane_factor(nu, vstar)
    nt = np.sqrt(1.0 - vstar)
    top = 20.0 / nt + 2.0
    x, w = np.polynomial.legendre.leggauss(points)
    edges = np.arange(0.0, top + width, width)
    lo, hi = edges[:-1, None], edges[1:, None]
    nodes = (0.5 * (lo + hi) + 0.5 * (hi - lo) * x).ravel()
    weights = (0.5 * (hi - lo) * w).ravel()
    m1 = surface_response(nu, vstar, kw, nodes)
    return nodes, weights * (m1 - phi1) / phi1, phi1


def solve(
    nu: float, vstar: float, kw: float, radius: float, mu_over_p: float, n: int = 24
) -> float:
    """The contact half-width a/h of the cylinder (radius R/h) under the load
    P/(mu h) = 1/mu_over_p."""
    nodes, wk, phi1 = kernel_grid(nu, vstar, kw)
    i = np.arange(1, n + 1)
    r = np.cos(i * np.pi / (n + 1))
    k = np.arange(1, n + 2)
    s = np.cos(np.pi * (2 * k - 1) / (2 * (n + 1)))
    weight = (1.0 - r**2) / (n + 1)
    # Drop the middle equation (s = 0): it holds by symmetry.
    s = np.delete(s, n // 2)
    diff = r[None, :] - s[:, None]
    target = radius / mu_over_p  # lambda = R P/(mu h^2)

    def load_of(a: float) -> float:
        # k1(a (r_i - s_k)) by the quadrature, then the unit-slope system.
        k1 = (
            wk[None, None, :] * np.sin(nodes[None, None, :] * (a * diff)[:, :, None])
        ).sum(-1)
        mat = weight[None, :] * (1.0 / diff + a * k1)
        g = np.linalg.solve(mat, s)
        return float(-np.pi * a * a * (weight @ g) / phi1)

    # Secant on ln a for lambda(a) = target, from the Hertz width.
    a0 = np.sqrt(2.0 * phi1 * target / np.pi)
    x0, x1 = np.log(a0), np.log(a0) + 0.05
    f0, f1 = np.log(load_of(a0) / target), np.log(load_of(np.exp(x1)) / target)
    for _ in range(50):
        if f1 == f0:
            break
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        x0, f0 = x1, f1
        x1 = x2
        f1 = np.log(load_of(np.exp(x1)) / target)
        if abs(x1 - x0) < 1e-13:
            break
    return float(np.exp(x1))
