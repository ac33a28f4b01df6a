"""An independent NumPy/SciPy reference for a rigid cylinder sliding steadily
over a viscoelastic (Zener) layer on Winkler springs, in plane strain.

It was written from the problem statement alone, without the project's
solver sources, to check ``movingpunch.solve``
(tests/python/test_viscoelastic_independent.py). Everything is
dimensionless: lengths over the thickness h, stresses over the relaxed shear
modulus mu_0, the load P over mu_0 h, ``vstar`` = rho V^2 / mu_0 and ``kw`` =
k_w h / mu_0. The layer fills -1 <= y <= 0. Its base rests on springs
(shear stress 0, sigma_y = kw v), and its top is frictionless.

Material
--------
The material is a standard linear solid in shear with a constant Poisson's
ratio. With the time factor e^{-i omega t} its modulus is mu(omega) = mu_0 m,
where m = (1 - i ratio omega tau) / (1 - i omega tau) (Christensen, *Theory of
Viscoelasticity*, ch. 1; Tschoegl, *The Phenomenological Theory of Linear
Viscoelastic Behavior*, ch. 3). The frame x = x1 - V t moves with the punch.
There a mode e^{i alpha x} = e^{i alpha x1} e^{-i alpha V t} oscillates at
omega = alpha V. So with t = alpha h and the deborah number D = V tau / h,
m(t) = (1 - i ratio D t) / (1 - i D t) for alpha > 0. For alpha < 0 it is the
conjugate, because the fields are real. By the correspondence principle, a
mode of the viscoelastic layer is the elastic layer's mode in units of
mu_0 m(t).

Layer (one mode)
----------------
In the moving frame d/dt = -V d/dx. In units of the modulus mu, plane-strain
elastodynamics reads laplacian(u) + (l + 1) grad div u = s u_xx, where
l = lambda/mu = 2 nu / (1 - 2 nu) and s = rho V^2 / mu. Take
u = U sin(ax), v = W cos(ax), tau_xy = T sin(ax), sigma_y = S cos(ax) and
X = [aU, aW, T, S]. Hooke's law gives T = U' - aW and
S = l a U + (l + 2) W'. The two equations of motion give
T' = a((l + 2) aU + l W') - s a^2 U and S' = -a T - s a^2 W. Together:
dX/dy = a B X with

    B = [[0, 1, 1, 0],
         [-l/(l+2), 0, 0, 1/(l+2)],
         [4(l+1)/(l+2) - s, 0, 0, l/(l+2)],
         [0, -s, -1, 0]]

(derived here; it matches the brief's matrix). In units of mu_0 m the speed
parameter is s = vstar / m and the spring stiffness is kw / m. The bottom
y = -1 has T = 0 and S = (kw/m) W. The top has T = 0 and S = -1 (a unit
pressure amplitude). The two-dimensional space of bottom solutions is carried
up in steps with a dy <= 4 by expm, and re-orthonormalised (QR) after each
step. This is the orthonormalisation method of Godunov and Conte (Ascher,
Mattheij and Russell, *Numerical Solution of Boundary Value Problems for
ODEs*, sec. 6.4). The surface response is M1(a) = -X_2(0) / m.
M1 -> 1 - nu for the elastic half-plane at rest. On springs M1/a stays
finite as a -> 0: M1/a -> 1/kw + 1/((l + 2) - l^2/(l + 2 - vstar)). That
limit is the springs in series with the layer's long-wave compression at
sigma_x = vstar eps_x (membrane equilibrium with inertia), which checks B's
rows independently of any solver.

Beyond a = 60 the layer is the half-plane to far below round-off, because
the bottom reflects with e^{-2a}. There M1 = H(t) = phi1(s(t)) / m(t), with
the steady subsonic half-plane response

    phi1(s) = s nL / (4 nL nT - (2 - s)^2),  nT = sqrt(1 - s), nL = sqrt(1 - s/c2)

where c2 = 2(1 - nu)/(1 - 2 nu) and the roots are principal. The denominator
is the Rayleigh function (Craggs, J. Mech. Phys. Solids 8 (1960) 85;
Georgiadis and Barber, J. Elasticity 31 (1993) 141). It is evaluated in a
cancellation-free form, obtained by multiplying numerator and denominator
by 4 nL nT + (2 - s)^2:
phi1 = nL (4 nL nT + (2 - s)^2) / (16(1 - 1/c2) + s(16/c2 - 24) + 8 s^2 - s^3).

Surface displacement
--------------------
For a pressure p on [c - w, c + w],
v(x) = -(1/pi) Re int_0^inf M1(a)/a phat(a) e^{iax} da, with
phat(a) = int p(xi) e^{-i a xi} dxi. On springs M1/a is finite at 0, so v,
and with it the indentation, is absolute (no free constant). M1 tends to
H_inf = phi1(vstar/ratio)/ratio only like 1/a. So split
M1 = G + H_inf (1 - e^{-a}): G/a is finite at 0 and O(a^-2) at infinity. The
second part has the real-space kernel
int_0^inf (1 - e^{-a}) cos(a u)/a da = (1/2) ln(1 + 1/u^2). This is the
Frullani-type integral int_0^inf (e^{-pa} - e^{-qa}) cos(au)/a da =
(1/2) ln((q^2 + u^2)/(p^2 + u^2)) (Gradshteyn and Ryzhik 3.948) at p -> 0,
q = 1, and it is checked by quadrature in the tests. The kernel is
integrated against p with its log singularity done exactly, through
int_{-1}^{1} T_k(r) ln|s - r| / sqrt(1 - r^2) dr = -pi ln 2 (k = 0),
-pi T_k(s)/k (k >= 1) (Mason and Handscomb, *Chebyshev Polynomials*, sec. 9.5)
and sqrt(1 - r^2) U_n = (T_n - T_{n+2}) / (2 sqrt(1 - r^2)). The remainder,
ln(1 + (x - xi)^2), is smooth and done by Gauss-Chebyshev quadrature of the
second kind.

The G part is integrated in a by composite Gauss-Legendre: panels of width
1, 20 points on [0, 60] (the finite layer) and 10 on [60, ``split``] (the
half-plane). The integral from ``split`` to infinity is not truncated. G is
the analytic function H(a) - H_inf (1 - e^{-a}), and
J_{n+1} = (H1_{n+1} + H2_{n+1})/2. The H1 part, ~ e^{i a w (1 + s)}, is taken
up the ray a = split + i y, and the H2 part, ~ e^{i a w (s - 1)}, down the
ray a = split - i y. Each ray uses Gauss-Laguerre quadrature in its own decay
e^{-w |1 +- s| y}. This is Cauchy's theorem. The arcs at infinity vanish by
Jordan's lemma. G's only singularities are the pole and zero of m, and the
branch points and Rayleigh pole of phi1 (where s(t) is real). All of them sit
on the imaginary axis, because m(t) = mu real gives
t = i (1 - mu)/(D (mu - ratio)). So nothing is crossed, and the tail is
exact up to the Gauss-Laguerre error. Plainly truncating the a integral
instead leaves an error that decays only like cutoff^-3.5 and oscillates
from one collocation point to the next. The collocation amplifies it by its
condition number. The measured ends with plain cut-offs are below: they
crawl towards the rotated-tail value.

Contact
-------
The pressure is p = sum_n b_n U_n(r) sqrt(1 - r^2) with r = (xi - c)/w. It
is bounded at both ends, and the load is P = w (pi/2) b_0. Its transform is
phat(a) = w e^{-iac} sum_n b_n pi (n + 1) (-i)^n J_{n+1}(a w)/(a w)
(Gradshteyn and Ryzhik 7.355, the Gegenbauer/Bessel integral; checked
numerically in the tests). The collocation points are x_k = c + w s_k with
s_k = 0.9 cos(pi (k + 1/2)/(N + 2)), k = 0..N+1. At each of them
v(x_k) = -delta + x_k^2/(2R). The matrix in v(x_k) = sum_n K_kn(w) b_n
depends on w alone. Because x_k^2 = c^2 + 2 c w s_k + w^2 s_k^2, for a fixed
w the equations are linear in b, in delta' = delta - c^2/(2R) and in c. So
each w takes one linear (N+2)-square solve, and the load fixes w through a
secant iteration on ln(w (pi/2) b_0 / P). That iteration is a Newton method
with a finite-difference derivative in w; c is exact at each w. It starts
from the Hertz width of the unrelaxed half-plane, w^2 = 2 R H_inf P / pi,
which does not depend on the project's answer.

Convergence
-----------
Measured for vstar 0.3, nu 0.25, kw 2, R 5, P 0.05, Zener ratio 3 and
deborah 0.5, where the ends are a = c + w and b = -(c - w).
movingpunch gives a = 0.27923240943857763, b = 0.16102407555420384.

    N   split  Laguerre  a                   b                   max |b_n| (last 2)
    8   1000   40        0.279232409396806   0.161024075492114   4.8e-09
    12  1000   40        0.279232409438704   0.161024075554318   3.8e-14
    16  1000   40        0.279232409439147   0.161024075554722   2.9e-15
    20  1000   40        0.279232409443089   0.161024075557204   1.1e-14
    24  1000   40        0.279232409470822   0.161024075568255   2.6e-14
    16   500   30        0.279232409437399   0.161024075555036
    16  2000   60        0.279232409438197   0.161024075555446
    16  1000   20        0.279232409438608   0.161024075555339

    finer real-axis panels (30 and 16 points): a = 0.279232409437912,
    panels of width 0.5: a = 0.279232409437991.
    plain cut-off, no rays (N = 12): cut-off 2000: a = 0.279232395734,
    4000: 0.279232409985, 8000: 0.279232409419, 16000: 0.279232409452.

The coefficients decay geometrically: |b_n| < 1e-13 from n = 12. From
N = 12 to 20 the ends agree to a few 1e-12, which is the round-off floor:
K's ~1e-15 relative error times the condition number of the collocation
system (8e4 at N = 12, 6e5 at N = 16, 5e6 at N = 20, 4e7 at N = 24). At
N = 24 that floor reaches 3e-11, so the default is N = 16. The split, the
Laguerre order and the panels change the ends by ~1e-12. So the ends are
converged to ~1e-11.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt
from scipy import linalg, special

FloatArray = npt.NDArray[np.float64]
ComplexArray = npt.NDArray[np.complex128]

#: Beyond this a h the layer is the half-plane to far below round-off.
HALF_PLANE_FROM = 60.0

#: The default number of pressure coefficients (see the module docstring).
DEFAULT_N = 16


@dataclass(frozen=True)
class Case:
    """One problem: the punch, the layer, the springs and the material."""

    vstar: float
    nu: float
    kw: float
    radius: float
    load: float
    ratio: float = 1.0
    deborah: float = 0.0


@dataclass
class Result:
    """The reference solution: contact [c - w, c + w] = [-b, a]."""

    centre: float
    half_width: float
    indentation: float
    coefficients: FloatArray
    case: Case
    iterations: int = 0
    history: list[float] = field(default_factory=list)

    @property
    def a(self) -> float:
        """The front end c + w."""
        return self.centre + self.half_width

    @property
    def b(self) -> float:
        """Minus the back end: -(c - w)."""
        return self.half_width - self.centre

    @property
    def drag(self) -> float:
        """(1/P) int p x/R dx = (c P + (pi/4) w^2 b_1) / (P R)."""
        b1 = self.coefficients[1] if self.coefficients.size > 1 else 0.0
        moment = self.centre * self.case.load + math.pi / 4 * self.half_width**2 * b1
        return moment / (self.case.load * self.case.radius)

    def pressure(self, x: npt.ArrayLike) -> FloatArray:
        """p(x) = sum b_n U_n(r) sqrt(1 - r^2), zero outside the contact."""
        r = (np.asarray(x, dtype=float) - self.centre) / self.half_width
        inside = np.abs(r) < 1.0
        theta = np.arccos(np.clip(r, -1.0, 1.0))
        n = np.arange(self.coefficients.size)
        # U_n(cos th) sin th = sin((n + 1) th)
        series = np.sin(np.multiply.outer(theta, n + 1)) @ self.coefficients
        return np.where(inside, series, 0.0)


# --------------------------------------------------------------------------
# Material and half-plane
# --------------------------------------------------------------------------


def modulus(t: npt.ArrayLike, ratio: float, deborah: float) -> ComplexArray:
    """m(t) = mu/mu_0 = (1 - i ratio D t)/(1 - i D t) at t = alpha h
    (t complex allowed: its analytic continuation)."""
    t = np.asarray(t, dtype=complex)
    return (1.0 - 1j * ratio * deborah * t) / (1.0 - 1j * deborah * t)


def phi1(s: npt.ArrayLike, nu: float) -> ComplexArray:
    """Returns the half-plane's surface response s nL / (4 nL nT - (2 - s)^2),
    in units of its own modulus. It is written without the cancellation at
    s -> 0 (phi1(0) = 1 - nu), with principal square roots (Re > 0). The
    extra zeros of the rationalised denominator are removable, since its
    numerator vanishes with them."""
    s = np.asarray(s, dtype=complex)
    c2 = 2 * (1 - nu) / (1 - 2 * nu)
    nt = np.sqrt(1 - s)
    nl = np.sqrt(1 - s / c2)
    den = 16 * (1 - 1 / c2) + s * (16 / c2 - 24) + 8 * s**2 - s**3
    return nl * (4 * nl * nt + (2 - s) ** 2) / den


def phi1_direct(s: npt.ArrayLike, nu: float) -> ComplexArray:
    """phi1 in its textbook form. It cancels near s = 0, and is kept as a
    check of ``phi1``."""
    s = np.asarray(s, dtype=complex)
    c2 = 2 * (1 - nu) / (1 - 2 * nu)
    nt = np.sqrt(1 - s)
    nl = np.sqrt(1 - s / c2)
    return s * nl / (4 * nl * nt - (2 - s) ** 2)


def half_plane_response(t: npt.ArrayLike, case: Case) -> ComplexArray:
    """H(t) = phi1(vstar/m(t)) / m(t): the viscoelastic half-plane."""
    m = modulus(t, case.ratio, case.deborah)
    return phi1(case.vstar / m, case.nu) / m


def h_infinity(case: Case) -> float:
    """H_inf = phi1(vstar/ratio)/ratio, the unrelaxed (t -> inf) limit."""
    return float(np.real(phi1(case.vstar / case.ratio, case.nu)) / case.ratio)


# --------------------------------------------------------------------------
# Finite layer
# --------------------------------------------------------------------------


def layer_matrix(s: npt.ArrayLike, nu: float) -> ComplexArray:
    """B(s) of dX/dy = alpha B X, for each s (shape (..., 4, 4))."""
    s = np.asarray(s, dtype=complex)
    lam = 2 * nu / (1 - 2 * nu)
    b = np.zeros((*s.shape, 4, 4), dtype=complex)
    b[..., 0, 1] = 1.0
    b[..., 0, 2] = 1.0
    b[..., 1, 0] = -lam / (lam + 2)
    b[..., 1, 3] = 1 / (lam + 2)
    b[..., 2, 0] = 4 * (lam + 1) / (lam + 2) - s
    b[..., 2, 3] = lam / (lam + 2)
    b[..., 3, 1] = -s
    b[..., 3, 2] = -1.0
    return b


def layer_response(
    alpha: npt.ArrayLike, case: Case, max_step: float = 4.0
) -> ComplexArray:
    """M1(alpha) = -X_2(0)/m of the layer on springs (alpha > 0). It carries
    the bottom solutions up, re-orthonormalising them after each step."""
    alpha = np.atleast_1d(np.asarray(alpha, dtype=float))
    m = modulus(alpha, case.ratio, case.deborah)
    s = case.vstar / m
    steps = max(1, math.ceil(float(alpha.max()) / max_step))
    dy = 1.0 / steps
    step = linalg.expm(alpha[:, None, None] * dy * layer_matrix(s, case.nu))
    # Bottom: T = 0, S = (kw/m)/alpha X_2: basis [1,0,0,0], [0,alpha,0,kw/m].
    y = np.zeros((*alpha.shape, 4, 2), dtype=complex)
    y[..., 0, 0] = 1.0
    y[..., 1, 1] = alpha
    y[..., 3, 1] = case.kw / m
    y, _ = np.linalg.qr(y)
    for _ in range(steps):
        y, _ = np.linalg.qr(step @ y)
    # Top: T = 0, S = -1.
    rhs = np.zeros((*alpha.shape, 2, 1), dtype=complex)
    rhs[..., 1, 0] = -1.0
    coef = np.linalg.solve(y[..., 2:4, :], rhs)
    x2 = (y[..., 1:2, :] @ coef)[..., 0, 0]
    return -x2 / m


def surface_response(alpha: npt.ArrayLike, case: Case) -> ComplexArray:
    """M1: the finite layer up to alpha = 60, the half-plane beyond."""
    alpha = np.atleast_1d(np.asarray(alpha, dtype=float))
    out = np.empty(alpha.shape, dtype=complex)
    low = alpha <= HALF_PLANE_FROM
    if low.any():
        out[low] = layer_response(alpha[low], case)
    if (~low).any():
        out[~low] = half_plane_response(alpha[~low], case)
    return out


# --------------------------------------------------------------------------
# The alpha quadrature
# --------------------------------------------------------------------------


def panels(
    lo: float, hi: float, width: float, points: int
) -> tuple[FloatArray, FloatArray]:
    """Returns composite Gauss-Legendre nodes and weights on [lo, hi]."""
    count = max(1, math.ceil((hi - lo) / width - 1e-12))
    edges = np.linspace(lo, hi, count + 1)
    x, wt = np.polynomial.legendre.leggauss(points)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    nodes = (mid[:, None] + half[:, None] * x[None, :]).ravel()
    weights = (half[:, None] * wt[None, :]).ravel()
    return nodes, weights


@dataclass
class AlphaGrid:
    """The alpha quadrature, with W_j G(alpha_j)/alpha_j^2 stored once."""

    alpha: FloatArray
    weighted: ComplexArray  # W_j G_j / alpha_j^2
    h_inf: float
    case: Case
    split: float  # the real axis up to here, the two rays beyond
    ray_points: int  # Gauss-Laguerre order (0: plain truncation at split)


def tail_g(alpha: npt.ArrayLike, case: Case, h_inf: float) -> ComplexArray:
    """Returns G = H(alpha) - H_inf (1 - e^{-alpha}) for the half-plane. It
    is analytic off the imaginary axis, and alpha may be complex."""
    alpha = np.asarray(alpha, dtype=complex)
    return half_plane_response(alpha, case) + h_inf * np.expm1(-alpha)


def alpha_grid(
    case: Case,
    split: float = 1000.0,
    low_points: int = 20,
    tail_points: int = 10,
    width: float = 1.0,
    ray_points: int = 40,
    cutoff: float | None = None,
) -> AlphaGrid:
    """Returns the nodes on [0, 60] (finite layer) and [60, split]
    (half-plane), with the rays of ``tail_spectrum`` beyond ``split``. With
    ``cutoff``, the integral is truncated at ``cutoff`` instead (split =
    cutoff, no rays), for comparison."""
    if cutoff is not None:
        split, ray_points = cutoff, 0
    a1, w1 = panels(0.0, HALF_PLANE_FROM, width, low_points)
    a2, w2 = panels(HALF_PLANE_FROM, split, width, tail_points)
    alpha = np.concatenate([a1, a2])
    weights = np.concatenate([w1, w2])
    h_inf = h_infinity(case)
    g = surface_response(alpha, case) + h_inf * np.expm1(-alpha)
    return AlphaGrid(alpha, weights * g / alpha**2, h_inf, case, split, ray_points)


def tail_spectrum(w: float, s: FloatArray, n: int, grid: AlphaGrid) -> ComplexArray:
    """Returns T[k, j] = int_split^inf G(a)/a^2 J_{j+1}(a w) e^{i a w s_k} da
    on the two rays of the module docstring. With gamma = w(1 + s) for H1
    and w(s - 1) for H2, each part runs along a = split + i sign(gamma) y,
    weighted by e^{-|gamma| y}. The scaled Hankel functions hankel1e/2e keep
    the exponentials apart. Needs |s_k| != 1."""
    out = np.zeros((s.size, n), dtype=complex)
    if grid.ray_points == 0:
        return out
    tau, omega = np.polynomial.laguerre.laggauss(grid.ray_points)
    order = np.arange(1, n + 1)
    a0 = grid.split
    for kind, gamma in ((1, w * (1 + s)), (2, w * (s - 1))):
        sigma = np.sign(gamma)
        mag = np.abs(gamma)
        alpha = a0 + 1j * sigma[:, None] * tau[None, :] / mag[:, None]  # (K, q)
        f = tail_g(alpha, grid.case, grid.h_inf) / alpha**2
        z = alpha[:, :, None] * w
        if kind == 1:
            hank = special.hankel1e(order[None, None, :], z)
        else:
            hank = special.hankel2e(order[None, None, :], z)
        ray = np.einsum("q,kq,kqn->kn", omega, f, hank)
        out += 0.5 * (1j * sigma * np.exp(1j * a0 * gamma) / mag)[:, None] * ray
    return out


# --------------------------------------------------------------------------
# The influence matrix and the contact
# --------------------------------------------------------------------------


def collocation_points(n: int, shrink: float = 0.9) -> FloatArray:
    """Returns s_k = 0.9 cos(pi (k + 1/2)/(n + 2)), k = 0..n+1, inside
    (-1, 1)."""
    k = np.arange(n + 2)
    return shrink * np.cos(np.pi * (k + 0.5) / (n + 2))


def log_potential(s: FloatArray, n: int) -> FloatArray:
    """Returns L[k, j] = int_{-1}^{1} U_j(r) sqrt(1 - r^2) ln|s_k - r| dr in
    closed form, for any real s_k. Inside (|s| <= 1) it uses the Chebyshev
    identity of the docstring. Outside, with |s| = cosh(eta),
    ln|s - r| = eta - ln 2 - 2 sum_k e^{-k eta} T_k(sign(s) r)/k
    (Mason and Handscomb 9.5), projected with
    int U_j sqrt(1 - r^2) T_k dr = (pi/4)(delta_{kj} [j >= 1] - delta_{k,j+2})
    for k >= 1, and pi/2 for j = k = 0."""
    s = np.asarray(s, dtype=float)
    out = np.empty((s.size, n))
    inside = np.abs(s) <= 1.0
    theta = np.arccos(np.clip(s[inside], -1.0, 1.0))
    out[inside, 0] = 0.5 * (-np.pi * math.log(2.0) + np.pi * np.cos(2 * theta) / 2)
    for j in range(1, n):
        tj = np.cos(j * theta)
        tj2 = np.cos((j + 2) * theta)
        out[inside, j] = 0.5 * (-np.pi * tj / j + np.pi * tj2 / (j + 2))
    sign = np.sign(s[~inside])
    eta = np.arccosh(np.abs(s[~inside]))
    q = np.exp(-eta)
    for j in range(n):
        val = 2 * sign ** (j + 2) * q ** (j + 2) / (j + 2) * (np.pi / 4)
        if j == 0:
            val = val + (eta - math.log(2.0)) * np.pi / 2
        else:
            val = val - 2 * sign**j * q**j / j * (np.pi / 4)
        out[~inside, j] = val
    return out


def smooth_log_potential(
    s: FloatArray, n: int, w: float, nodes: int = 96
) -> FloatArray:
    """Returns int U_j(r) sqrt(1 - r^2) ln(1 + w^2 (s_k - r)^2) dr, by
    Gauss-Chebyshev quadrature of the second kind. The integrand is analytic,
    with singularities at r = s +- i/w."""
    theta = np.pi * np.arange(1, nodes + 1) / (nodes + 1)
    r = np.cos(theta)
    # weights pi/(M+1) sin^2 th; U_j(cos th) = sin((j+1) th)/sin th
    wt = np.pi / (nodes + 1) * np.sin(theta)
    basis = np.sin(np.multiply.outer(np.arange(1, n + 1), theta)) * wt  # (n, M)
    f = np.log1p(w**2 * (s[:, None] - r[None, :]) ** 2)  # (K, M)
    return f @ basis.T


def influence(w: float, s: FloatArray, n: int, grid: AlphaGrid) -> FloatArray:
    """Returns K[k, j] = v(c + w s_k) for p = U_j(r) sqrt(1 - r^2) on
    [c - w, c + w]. The first term is
    -(1/pi) Re int G/a phat e^{iax} da = -(j+1) Re[(-i)^j int G/a^2
    J_{j+1}(aw) e^{iaws} da]. The H_inf part is
    (H_inf/pi) int p ln|x - xi| - (H_inf/(2 pi)) int p ln(1 + (x - xi)^2)."""
    s = np.asarray(s, dtype=float)
    order = np.arange(1, n + 1)
    bess = special.jv(order[None, :], grid.alpha[:, None] * w)  # (J, n)
    phase = np.exp(1j * w * np.multiply.outer(s, grid.alpha))  # (K, J)
    spec = phase @ (grid.weighted[:, None] * bess)  # (K, n)
    spec += tail_spectrum(w, s, n, grid)
    k1 = -order * np.real((-1j) ** (order - 1) * spec)
    hinf = grid.h_inf
    nodes = 96 if np.all(np.abs(s) <= 1) else 400
    smooth = -hinf / (2 * np.pi) * w * smooth_log_potential(s, n, w, nodes)
    sing = hinf / np.pi * w * log_potential(s, n)
    sing[:, 0] += hinf / np.pi * w * math.log(w) * np.pi / 2
    return k1 + smooth + sing


def solve_at_width(
    w: float, case: Case, n: int, grid: AlphaGrid
) -> tuple[FloatArray, float, float]:
    """Returns (b, delta, c) from the contact condition at a fixed
    half-width w."""
    s = collocation_points(n)
    k = influence(w, s, n, grid)
    # sum_j K b_j + delta' - c w s/R = w^2 s^2 / (2R), delta' = delta - c^2/(2R)
    mat = np.hstack([k, np.ones((s.size, 1)), -(w * s / case.radius)[:, None]])
    rhs = w**2 * s**2 / (2 * case.radius)
    sol = np.linalg.solve(mat, rhs)
    b, dprime, c = sol[:n], float(sol[n]), float(sol[n + 1])
    return b, dprime + c**2 / (2 * case.radius), c


def solve(
    case: Case,
    n: int = DEFAULT_N,
    width0: float | None = None,
    grid: AlphaGrid | None = None,
    tol: float = 1e-10,
    max_iter: int = 40,
) -> Result:
    """Solves for the steady contact, by a secant iteration on ln w for the
    load; c, b and delta are exact at each w. It stops when the step in ln w
    falls below ``tol``. The secant converges superlinearly, so the error
    left is then at the round-off floor."""
    if grid is None:
        grid = alpha_grid(case)
    if width0 is None:
        # Hertz on the unrelaxed half-plane: w^2 = 2 R H_inf P / pi.
        width0 = math.sqrt(2 * case.radius * grid.h_inf * case.load / math.pi)

    def residual(lw: float) -> float:
        b, _, _ = solve_at_width(math.exp(lw), case, n, grid)
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
            msg = f"the secant on the half-width did not converge: {history}"
            raise RuntimeError(msg)
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        x2 = min(max(x2, x1 - 1.0), x1 + 1.0)  # a guarded step
        x0, f0 = x1, f1
        x1, f1 = x2, residual(x2)
        history.append(math.exp(x1))
        if abs(x1 - x0) < tol:
            break
    w = math.exp(x1)
    b, delta, c = solve_at_width(w, case, n, grid)
    return Result(c, w, delta, b, case, iterations, history)


def surface_displacement(
    result: Result, x: npt.ArrayLike, grid: AlphaGrid | None = None
) -> FloatArray:
    """Returns v(x) anywhere, outside the contact too, from the same split
    (x not at the contact's ends)."""
    if grid is None:
        grid = alpha_grid(result.case)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    s = (x - result.centre) / result.half_width
    k = influence(result.half_width, s, result.coefficients.size, grid)
    return k @ result.coefficients
