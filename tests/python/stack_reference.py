"""An independent NumPy/SciPy reference for a rigid cylinder sliding steadily
over a STACK of bonded sublayers (each homogeneous, elastic or Zener
viscoelastic) on Winkler springs or on an elastic half-space, in plane
strain.

It was written from the problem statement alone, without the project's
solver sources, to check ``movingpunch.solve`` with viscoelastic sublayers in
a stack (tests/python/test_viscoelastic_stack_independent.py). It extends
``viscoelastic_reference`` (one Zener layer on springs), whose docstring
gives the derivations and sources this module reuses: the mode equations
dX/dy = alpha B(s) X of a homogeneous layer, the correspondence principle,
the half-plane response phi1, the split of the surface response into a
smooth part and a log-kernel part, the Cauchy rays of the alpha tail, and the
Chebyshev collocation with a secant on the half-width.

Units
-----
Lengths over the total thickness h; the stack fills -1 <= y <= 0, sublayer i
(top first) has thickness d_i (sum 1), relaxed shear modulus mu_i, density
rho_i and Poisson's ratio nu_i, with mu_1 = rho_1 = 1 (the top sublayer is
the unit). Stresses are over mu_1, the load P over mu_1 h, vstar =
rho_1 V^2 / mu_1, kw = k_w h / mu_1. A sublayer is
(thickness, mu, nu, rho, ratio, deborah); ratio 1 is elastic. A Zener
sublayer has the modulus mu_i m_i(t), m(t) = (1 - i ratio D t)/(1 - i D t)
at t = alpha h > 0 (the conjugate for alpha < 0), with a constant Poisson's
ratio (``viscoelastic_reference.modulus``).

Modes
-----
In sublayer i a mode is the elastic one at speed parameter
s_i = vstar rho_i / (mu_i m_i(t)) in units of G_i = mu_i m_i(t): with
X = [aU, aW, T/G_i, S/G_i], dX/dy = a B(s_i, nu_i) X
(``viscoelastic_reference.layer_matrix``). The stack carries the global
state Z = [aU, aW, T, S] (stresses in mu_1 units), continuous across bonded
interfaces, so in sublayer i Z' = a D_i B D_i^{-1} Z with
D_i = diag(1, 1, G_i, G_i). Starting at y = -1, the two-dimensional space of
admissible solutions is carried up through each sublayer in steps with
a dy <= 4 by expm and re-orthonormalised (QR) after each step
(Godunov-Conte orthonormalisation; Ascher, Mattheij and Russell, *Numerical
Solution of Boundary Value Problems for ODEs*, sec. 6.4).

* Springs base: T = 0, S = kw W, the basis [1, 0, 0, 0], [0, a, 0, kw].
* Elastic half-space base (mu_b, nu_b, rho_b), bonded: the modes that decay
  downwards, e^{a lambda y} with Re lambda > 0. B(s_b) has the eigenvalues
  +-nT, +-nL (nT = sqrt(1 - s_b), nL = sqrt(1 - s_b/c2), subsonic s_b real
  below 1); its invariant subspace for Re lambda > 0 is taken from an
  ordered real Schur decomposition (``scipy.linalg.schur(sort='rhp')``),
  which stays well defined at s_b = 0, where nT = nL and B is defective.
  In global units that basis is multiplied by diag(1, 1, mu_b, mu_b). It does
  not depend on a.

The top has T = 0, S = -1 (unit pressure amplitude) and the surface response
is M1(a) = -Z_2(0) (in 1/mu_1), as in the single-layer reference.

Beyond a = ``half_plane_from(case)`` = max(60, 36/d_1) the top sublayer is
its own half-plane to far below round-off (the rest of the stack reflects
with e^{-2 a d_1 Re nT_1} < 1e-25 for the speeds used), so there
M1 = H(t) = phi1(vstar/m_1(t), nu_1)/m_1(t).

Limits (checked in the tests): short waves give H(t); long waves give, on
springs, M1/a -> 1/kw + sum_i d_i (-eps_y,i) with the relaxed moduli, where
the stack's common long-wave strain eps_x solves the membrane balance
sum_i d_i (sigma_x,i - rho_i vstar eps_x) = 0 with sigma_y,i = -1 in every
sublayer; on a half-space M1(0) = M0 = phi1(vstar rho_b/mu_b, nu_b)/mu_b, the
substrate's half-plane (the stack is thin against the wave).

Surface displacement
--------------------
v(x) = -(1/pi) Re int_0^inf M1(a)/a phat(a) e^{iax} da. With a half-space
base M1(0) = M0 != 0, so this integral diverges logarithmically and v is
defined up to a constant (v grows like ln|x|). The contact only needs v up to
a constant, because the indentation delta is an unknown of the collocation
anyway. So split

    M1 = G + H_inf (1 - e^{-a}) + M0 e^{-a},

with H_inf = phi1(vstar/ratio_1, nu_1)/ratio_1 the top's unrelaxed
half-plane (phi1(vstar, nu_1) for an elastic top). G(0) = 0 and M1 is
analytic at a = 0+, so G/a is finite there; at infinity G = O(1/a) for a
viscoelastic top and O(e^{-a}) for an elastic one. The G part and the
H_inf part are exactly the single-layer reference's (its
``influence``/``tail_spectrum``, with the top sublayer as its ``Case``;
the tail beyond ``split`` is the top's half-plane, where M0 e^{-a} < e^{-60}
is dropped).
The M0 e^{-a} part uses int_0^inf e^{-a} (1 - cos(au))/a da =
(1/2) ln(1 + u^2) (integrate int e^{-a} sin(au) da = u/(1 + u^2) in u), so
up to a constant (absorbed by delta) it adds
+(M0/(2 pi)) int p(xi) ln(1 + (x - xi)^2) dxi, the same smooth kernel as the
H_inf part with the opposite sign. On springs M0 = 0 and everything is the
single-layer reference's formulation (delta absolute). With a half-space
base delta is relative to an unspecified constant; the ends are not.

Contact
-------
As in the single-layer reference: p = sum b_n U_n(r) sqrt(1 - r^2) on
[c - w, c + w] (bounded at both ends), collocation at
s_k = shrink cos(pi (k + 1/2)/(N + 2)) (below), v(x_k) = -delta + x_k^2/(2R), linear in
(b, delta', c) at fixed w, and a secant on ln w for the load.

Collocation points
------------------
Under an elastic top the points are the plain Chebyshev ones
cos(pi (k + 1/2)/(N + 2)) (shrink 1), and N defaults to 32. A thin top
sublayer makes the kernel analytic only in a strip of half-width ~2 d_1/w in
r, so the pressure series converges more slowly (case B relaxed: N = 16 is
1.7e-8 off, N = 24 4e-14). With the single-layer reference's shrink 0.9 the square
collocation extrapolates from [-0.9, 0.9] and its round-off floor grows like
1.6^N (3e-10 at N = 32, 4e-8 at N = 40); with shrink 1 the ends stay at
1e-15 up to N = 48. Under a viscoelastic top G ~ 1/a and the tail rays need
|s_k| well below 1 (their Gauss-Laguerre integrand has a singularity at a
distance ~ w (1 - |s_k|) split from the real axis): there the points are
shrunk by 0.9 as in the single-layer reference and N defaults to 20.

Convergence (measured)
----------------------
The ends, N - 4 / N + 4 around the default and a second alpha grid (low
panels of width 2 with 30 points, 14-point tail panels, split 500 or
2 half_plane_from, 30 Laguerre points), largest change of either end:

    case A (Zener top, springs)           8.9e-12  2.4e-11  6.5e-12
    case B (Zener middle, half-space)     5.1e-15  2.8e-15  5.2e-15
    case C (B at vstar 0)                 4.1e-15  3.7e-15  3.3e-15
    case D (Zener bottom, springs)        2.7e-15  1.7e-15  7.8e-16

(the cases are in the tests). A Zener top is at the single-layer
reference's ~1e-11 floor; an elastic top is at round-off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy import linalg

import viscoelastic_reference as vref

FloatArray = npt.NDArray[np.float64]
ComplexArray = npt.NDArray[np.complex128]

#: (thickness, mu, nu, rho, ratio, deborah); ratio 1 is elastic.
Sublayer = tuple[float, float, float, float, float, float]
#: ('springs', kw) or ('half_space', mu_b, nu_b, rho_b).
Base = tuple[str, float] | tuple[str, float, float, float]


@dataclass(frozen=True)
class StackCase:
    """One problem: the sublayers top to bottom, the base and the punch."""

    layers: tuple[Sublayer, ...]
    base: Base
    vstar: float
    radius: float
    load: float

    def __post_init__(self) -> None:
        if not self.layers:
            raise ValueError("at least one sublayer")
        top = self.layers[0]
        if top[1] != 1.0 or top[3] != 1.0:
            raise ValueError("the top sublayer is the unit: mu_1 = rho_1 = 1")
        if abs(sum(layer[0] for layer in self.layers) - 1.0) > 1e-14:
            raise ValueError("the thicknesses sum to 1")
        if self.base[0] not in ("springs", "half_space"):
            raise ValueError(f"unknown base {self.base!r}")


def is_elastic(layer: Sublayer) -> bool:
    """Ratio 1 or deborah 0: m(t) = 1."""
    return layer[4] == 1.0 or layer[5] == 0.0


def top_case(case: StackCase) -> vref.Case:
    """The top sublayer as the single-layer reference's Case (its half-plane
    is what the tail uses; kw plays no part there)."""
    _, _, nu, _, ratio, deborah = case.layers[0]
    return vref.Case(
        vstar=case.vstar,
        nu=nu,
        kw=0.0,
        radius=case.radius,
        load=case.load,
        ratio=ratio,
        deborah=deborah,
    )


def h_infinity(case: StackCase) -> float:
    """H_inf: the top sublayer's unrelaxed half-plane, in 1/mu_1."""
    return vref.h_infinity(top_case(case))


def long_wave_constant(case: StackCase) -> float:
    """M0 = M1(0+): 0 on springs, the substrate's half-plane
    phi1(vstar rho_b/mu_b, nu_b)/mu_b on a half-space."""
    if case.base[0] == "springs":
        return 0.0
    _, mu_b, nu_b, rho_b = case.base
    return float(np.real(vref.phi1(case.vstar * rho_b / mu_b, nu_b)) / mu_b)


def half_plane_from(case: StackCase) -> float:
    """Beyond this a h the top sublayer is its own half-plane."""
    return max(vref.HALF_PLANE_FROM, 36.0 / case.layers[0][0])


def base_basis(alpha: FloatArray, case: StackCase) -> ComplexArray:
    """The admissible states Z at y = -1, shape (len(alpha), 4, 2)."""
    y = np.zeros((alpha.size, 4, 2), dtype=complex)
    if case.base[0] == "springs":
        kw = case.base[1]
        y[:, 0, 0] = 1.0
        y[:, 1, 1] = alpha
        y[:, 3, 1] = kw
        return y
    _, mu_b, nu_b, rho_b = case.base
    b = vref.layer_matrix(case.vstar * rho_b / mu_b, nu_b).real
    _, z, sdim = linalg.schur(b, output="real", sort="rhp")
    if sdim != 2:
        raise ValueError("the half-space base is not subsonic")
    basis = np.diag([1.0, 1.0, mu_b, mu_b]) @ z[:, :2]
    y[:] = basis
    return y


def stack_response(
    alpha: npt.ArrayLike, case: StackCase, max_step: float = 4.0
) -> ComplexArray:
    """M1(alpha) = -Z_2(0) of the stack (alpha > 0), by orthonormalised
    transfer of the base's solution space up through each sublayer."""
    alpha = np.atleast_1d(np.asarray(alpha, dtype=float))
    y, _ = np.linalg.qr(base_basis(alpha, case))
    for thickness, mu, nu, rho, ratio, deborah in reversed(case.layers):
        g = mu * vref.modulus(alpha, ratio, deborah)  # G_i(t), mu_1 units
        s = case.vstar * rho / g
        steps = max(1, math.ceil(float(alpha.max()) * thickness / max_step))
        dy = thickness / steps
        step = linalg.expm(alpha[:, None, None] * dy * vref.layer_matrix(s, nu))
        # global units: D step D^{-1}, D = diag(1, 1, g, g)
        scale = np.ones((alpha.size, 4), dtype=complex)
        scale[:, 2:] = g[:, None]
        step = scale[:, :, None] * step / scale[:, None, :]
        for _ in range(steps):
            y, _ = np.linalg.qr(step @ y)
    rhs = np.zeros((alpha.size, 2, 1), dtype=complex)
    rhs[:, 1, 0] = -1.0
    coef = np.linalg.solve(y[:, 2:4, :], rhs)
    return -(y[:, 1:2, :] @ coef)[:, 0, 0]


def surface_response(alpha: npt.ArrayLike, case: StackCase) -> ComplexArray:
    """M1(alpha) for alpha > 0: the stack up to ``half_plane_from``, the top
    sublayer's half-plane beyond."""
    alpha = np.atleast_1d(np.asarray(alpha, dtype=float))
    out = np.empty(alpha.shape, dtype=complex)
    low = alpha <= half_plane_from(case)
    if low.any():
        out[low] = stack_response(alpha[low], case)
    if (~low).any():
        out[~low] = vref.half_plane_response(alpha[~low], top_case(case))
    return out


@dataclass
class StackGrid:
    """The alpha quadrature (the single-layer reference's grid of the top
    sublayer, with the stack's G) and the long-wave constant M0."""

    grid: vref.AlphaGrid
    m0: float


def alpha_grid(
    case: StackCase,
    split: float | None = None,
    low_points: int = 20,
    tail_points: int = 10,
    width: float = 1.0,
    ray_points: int = 40,
    tail_width: float = 4.0,
) -> StackGrid:
    """Composite Gauss-Legendre on [0, half_plane_from] (the stack) and on
    [half_plane_from, split] (the top's half-plane), rays beyond split.
    ``split`` defaults to 1000 under a viscoelastic top (G ~ 1/a) and to
    half_plane_from under an elastic one, where G = H_inf e^{-a} there
    (the rays then carry a remainder below 1e-26)."""
    start = half_plane_from(case)
    if split is None:
        split = start if is_elastic(case.layers[0]) else 1000.0
    a1, w1 = vref.panels(0.0, start, width, low_points)
    a2, w2 = vref.panels(start, split, tail_width, tail_points)
    alpha = np.concatenate([a1, a2])
    weights = np.concatenate([w1, w2])
    h_inf = h_infinity(case)
    m0 = long_wave_constant(case)
    g = surface_response(alpha, case) + h_inf * np.expm1(-alpha) - m0 * np.exp(-alpha)
    grid = vref.AlphaGrid(
        alpha, weights * g / alpha**2, h_inf, top_case(case), split, ray_points
    )
    return StackGrid(grid, m0)


def influence(w: float, s: FloatArray, n: int, sgrid: StackGrid) -> FloatArray:
    """K[k, j] = v(c + w s_k) (up to a constant common to all points when
    M0 != 0) for p = U_j(r) sqrt(1 - r^2) on [c - w, c + w]."""
    s = np.asarray(s, dtype=float)
    k = vref.influence(w, s, n, sgrid.grid)
    if sgrid.m0 != 0.0:
        nodes = 96 if np.all(np.abs(s) <= 1) else 400
        k = k + sgrid.m0 / (2 * np.pi) * w * vref.smooth_log_potential(s, n, w, nodes)
    return k


def collocation_shrink(case: StackCase) -> float:
    """0.9 (the single-layer reference's points) under a viscoelastic top,
    whose G decays only like 1/a: there the tail rays need |s_k| well below
    1. Under an elastic top the tail is exponentially small and the plain
    Chebyshev points (1.0) keep the collocation well conditioned to large
    N (a thin top sublayer needs N ~ 28)."""
    return 1.0 if is_elastic(case.layers[0]) else 0.9


def default_n(case: StackCase) -> int:
    """20 under a viscoelastic top (shrunk points), 32 under an elastic
    top."""
    return 32 if is_elastic(case.layers[0]) else 20


def solve_at_width(
    w: float, case: StackCase, n: int, sgrid: StackGrid
) -> tuple[FloatArray, float, float]:
    """(b, delta, c) from the contact condition at a fixed half-width w."""
    s = vref.collocation_points(n, collocation_shrink(case))
    k = influence(w, s, n, sgrid)
    mat = np.hstack([k, np.ones((s.size, 1)), -(w * s / case.radius)[:, None]])
    rhs = w**2 * s**2 / (2 * case.radius)
    sol = np.linalg.solve(mat, rhs)
    b, dprime, c = sol[:n], float(sol[n]), float(sol[n + 1])
    return b, dprime + c**2 / (2 * case.radius), c


def solve_result(
    case: StackCase,
    n: int | None = None,
    sgrid: StackGrid | None = None,
    tol: float = 1e-10,
    max_iter: int = 40,
) -> vref.Result:
    """The full solution (the single-layer reference's Result: centre,
    half_width, a, b, drag, pressure), by a secant on ln w for the load."""
    if n is None:
        n = default_n(case)
    if sgrid is None:
        sgrid = alpha_grid(case)
    width0 = math.sqrt(2 * case.radius * sgrid.grid.h_inf * case.load / math.pi)

    def residual(lw: float) -> float:
        b, _, _ = solve_at_width(math.exp(lw), case, n, sgrid)
        load = math.exp(lw) * math.pi / 2 * b[0]
        if load <= 0:
            return -50.0
        return math.log(load / case.load)

    x0, x1 = math.log(width0), math.log(width0) + 0.05
    f0, f1 = residual(x0), residual(x1)
    history = [math.exp(x0), math.exp(x1)]
    iterations = 0
    while f1 != f0:
        iterations += 1
        if iterations > max_iter:
            raise RuntimeError(f"the secant did not converge: {history}")
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        x2 = min(max(x2, x1 - 1.0), x1 + 1.0)
        x0, f0 = x1, f1
        x1, f1 = x2, residual(x2)
        history.append(math.exp(x1))
        if abs(x1 - x0) < tol:
            break
    w = math.exp(x1)
    b, delta, c = solve_at_width(w, case, n, sgrid)
    return vref.Result(c, w, delta, b, case, iterations, history)  # type: ignore[arg-type]


def solve(
    case: StackCase, n: int | None = None, sgrid: StackGrid | None = None
) -> tuple[float, float]:
    """The contact ends (left, right) = (c - w, c + w) in units of h."""
    r = solve_result(case, n=n, sgrid=sgrid)
    return r.centre - r.half_width, r.centre + r.half_width
