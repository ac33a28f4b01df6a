"""Independent NumPy/SciPy solver for the frictionless cylinder's contact
zones: one symmetric zone (-a, a), or the separated pair (-a2, -a1) U (a1, a2).

Written to check ``movingpunch`` without sharing its code path. Units
h = mu = 1; nothing from ``movingpunch`` is used here.

Layer response. M1(alpha) = -alpha v~(alpha, 0) per unit transformed pressure
is computed from the four plane-strain modes e^{m alpha y} (m = +-n_T shear,
+-n_L dilatation) of the steady moving-frame equations, each written relative
to the face it decays from (4x4 boundary system: top tau = 0 and
sigma_y = -1, bottom tau = 0 and t sigma_y / alpha = k_w v); for
alpha h < 2 the state z = [U, W, T, S] is carried across the layer by
``scipy.linalg.expm`` of the 4x4 first-order system instead. The two forms
agree to ~1e-14 relative where both apply (1e-12 at the near-resonant peak,
where the 4x4 system is ill-conditioned), and both agree with
``movingpunch.layer_response`` to the same level.

Kernel. The surface slope of an even pressure is

    v'(x) = (phi1/pi) PV int p(t)/(x - t) dt + (1/pi) int p(t) k(x - t) dt,
    k(u) = int_0^inf (M1(alpha) - phi1) sin(alpha u) d alpha,

(k = phi1 k1 of docs/theory.md). k is computed by composite Gauss-Legendre
quadrature in alpha (20 nodes per panel, panels of width <= 0.2, graded
geometrically towards the peak of |M1 - phi1| (the near-resonant peak, next
to the critical wavenumber); alpha_max where e^{-2 n_T alpha} < 1e-22) and
held as a Chebyshev interpolant on |u| <= L (cached per parameter set).

Discretisation: Chebyshev-coefficient Galerkin (not nodal collocation). On a
zone x = c + w r, p = sqrt(1 - r^2) sum_n b_n U_n(r). The Cauchy transforms
are in closed form: the zone's own one is sum b_n T_{n+1}(r); the mirror
zone's (two-zone case, p even) is sum b_n (-1)^n q^{n+1}, q = z - sqrt(z^2 - 1)
at z = (x + c)/w > 1. The regular kernel's integral and the projections onto
T_m (weight 1/sqrt(1 - r^2)) are done by Gauss-Legendre quadrature in the
angle theta (r = cos theta) on [0, pi]. Equations m = 1..N fix b_0..b_{N-1};
the m = 0 projection is the consistency condition (p bounded at both ends of
the zone) and int p = P fixes the load. One zone: m = 0 holds by symmetry and
a is found by brentq on the load; two zones: (a1, a2) by Newton-type
``scipy.optimize.fsolve`` on (consistency, load), with a nested brentq
fallback. ``two_zone_report`` checks a solution: p >= 0 on the zones, the gap
x^2/(2R) - delta - v(x) >= 0 in the middle and beside the contact, and the
slope equation's residual away from the quadrature nodes.

Measured (nu = 0.2, R/h = 100, P/(mu h) = 0.002, k_w h/mu = 0.1,
V* = 0.99 V*_cr): a1 = 0.72242290910587, a2 = 1.78259962849419 (changes
<= 1.2e-13 under N = 24..80 and alpha-quadrature refinement); one-zone a
equals ``movingpunch.solve``'s to <= 3e-15 at valid loads.
"""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np
import scipy.linalg
import scipy.optimize
from numpy.polynomial import chebyshev as C

# ---------------------------------------------------------------------------
# Layer response
# ---------------------------------------------------------------------------


def _roots(vstar: float, nu: float) -> tuple[float, float, float]:
    kappa = 3.0 - 4.0 * nu
    c2 = (kappa + 1.0) / (kappa - 1.0)
    return math.sqrt(1.0 - vstar), math.sqrt(1.0 - vstar / c2), c2


def half_plane_phi1(vstar: float, nu: float) -> float:
    """lim M1 = s n_L / (4 n_L n_T - (2 - s)^2), s cancelled analytically."""
    n_t, n_l, _ = _roots(vstar, nu)
    if vstar == 0.0:
        return 1.0 - nu
    return vstar * n_l / (4.0 * n_l * n_t - (2.0 - vstar) ** 2)


def _m1_modal(t: np.ndarray, vstar: float, kw: float, nu: float) -> np.ndarray:
    """M1 from the four exponential modes (t = alpha h >= ~0.5)."""
    n_t, n_l, _ = _roots(vstar, nu)
    s = vstar
    # mode vectors [U, W, T, S] (T = tau~/alpha, S = sigma_y~/alpha), m > 0
    v_t = np.array([1.0, -1.0 / n_t, (1.0 + n_t**2) / n_t, -2.0])
    v_l = np.array([1.0, -n_l, 2.0 * n_l, -(2.0 - s)])
    flip = np.array([1.0, -1.0, -1.0, 1.0])  # m < 0: W and T change sign
    vecs = [v_t, v_l, v_t * flip, v_l * flip]
    e_t = np.exp(-n_t * t)
    e_l = np.exp(-n_l * t)
    one = np.ones_like(t)
    top = [one, one, e_t, e_l]
    bot = [e_t, e_l, one, one]
    if math.isinf(kw):
        ws, ww = np.zeros_like(t), -one
    else:
        ws, ww = t / (t + kw), -kw / (t + kw)
    mat = np.empty((t.size, 4, 4))
    for j in range(4):
        _, w_, tt, ss = vecs[j]
        mat[:, 0, j] = tt * top[j]
        mat[:, 1, j] = ss * top[j]
        mat[:, 2, j] = tt * bot[j]
        mat[:, 3, j] = (ws * ss + ww * w_) * bot[j]
    rhs = np.zeros((t.size, 4, 1))
    rhs[:, 1, 0] = -1.0
    amp = np.linalg.solve(mat, rhs)[:, :, 0]
    w0 = sum(amp[:, j] * vecs[j][1] * top[j] for j in range(4))
    return -w0


def _system_matrix(vstar: float, nu: float) -> np.ndarray:
    _, _, c2 = _roots(vstar, nu)
    return np.array(
        [
            [0.0, 1.0, 1.0, 0.0],
            [-(c2 - 2.0) / c2, 0.0, 0.0, 1.0 / c2],
            [4.0 * (c2 - 1.0) / c2 - vstar, 0.0, 0.0, (c2 - 2.0) / c2],
            [0.0, -vstar, -1.0, 0.0],
        ]
    )


def _m1_transfer(t: np.ndarray, vstar: float, kw: float, nu: float) -> np.ndarray:
    """M1 by carrying z = [U, W, T, S] across the layer (dz/d(alpha y) = A z)."""
    a = _system_matrix(vstar, nu)
    e = scipy.linalg.expm(-t[:, None, None] * a[None, :, :])
    # z(-h) = U0 e[:, 0] + W0 e[:, 1] - e[:, 3]; rows: T(-h) = 0, spring row
    if math.isinf(kw):
        spring = np.zeros((t.size, 4))
        spring[:, 1] = -1.0
    else:
        spring = np.zeros((t.size, 4))
        spring[:, 1] = -kw / (t + kw)
        spring[:, 3] = t / (t + kw)
    rows = np.stack([e[:, 2, :], np.einsum("ij,ijk->ik", spring, e)], axis=1)
    m = rows[:, :, :2]
    r = rows[:, :, 3:4]
    return -np.linalg.solve(m, r)[:, 1, 0]


def m1(t: np.ndarray | float, vstar: float, kw: float, nu: float) -> np.ndarray:
    """Surface slope response M1(t), t = alpha h (own evaluation)."""
    t = np.atleast_1d(np.asarray(t, dtype=float))
    out = np.empty(t.size)
    small = t < 2.0
    if small.any():
        out[small] = _m1_transfer(t[small], vstar, kw, nu)
    if (~small).any():
        out[~small] = _m1_modal(t[~small], vstar, kw, nu)
    return out


# ---------------------------------------------------------------------------
# Regular kernel k(u) = int_0^inf (M1 - phi1) sin(alpha u) d alpha
# ---------------------------------------------------------------------------


@functools.lru_cache(maxsize=16)
def _critical_alpha(vstar: float, kw: float, nu: float) -> float:
    """Wavenumber of the largest |M1 - phi1| (the near-resonant peak)."""
    grid = np.linspace(0.01, 12.0, 2400)
    f = np.abs(m1(grid, vstar, kw, nu) - half_plane_phi1(vstar, nu))
    i = int(np.argmax(f))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    res = scipy.optimize.minimize_scalar(
        lambda x: -abs(m1(x, vstar, kw, nu)[0] - half_plane_phi1(vstar, nu)),
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": 1e-10},
    )
    return float(res.x)


def _alpha_rule(
    vstar: float, kw: float, nu: float, refine: int = 1
) -> tuple[np.ndarray, np.ndarray]:
    n_t, _, _ = _roots(vstar, nu)
    alpha_max = 25.0 / n_t
    ac = _critical_alpha(vstar, kw, nu)
    width = 0.2 / refine
    breaks = [*np.arange(0.0, alpha_max, width), alpha_max]
    d = 0.002 / refine
    while d < 1.0:
        breaks += [ac - d, ac + d]
        d *= 1.5 if refine == 1 else 1.25
    breaks = np.unique(np.clip(np.array([*breaks, ac]), 0.0, alpha_max))
    xg, wg = np.polynomial.legendre.leggauss(20 + 4 * (refine - 1))
    lo, hi = breaks[:-1], breaks[1:]
    half = 0.5 * (hi - lo)
    nodes = (0.5 * (hi + lo))[:, None] + half[:, None] * xg[None, :]
    weights = half[:, None] * wg[None, :]
    return nodes.ravel(), weights.ravel()


class _Kernel:
    """k(u) on |u| <= L as a Chebyshev interpolant of the alpha quadrature."""

    def __init__(self, vstar: float, kw: float, nu: float, span: float, refine: int):
        self.phi1 = half_plane_phi1(vstar, nu)
        alpha, w = _alpha_rule(vstar, kw, nu, refine)
        self._alpha = alpha
        self._wf = w * (m1(alpha, vstar, kw, nu) - self.phi1)
        self.span = span
        deg = int(1.2 * alpha.max() * span) + 64
        deg += deg % 2 + 1  # odd degree: k is odd
        self._cheb = C.Chebyshev.interpolate(self.direct, deg, domain=[-span, span])
        coef = self._cheb.coef
        coef[0::2] = 0.0  # exactly odd
        self.tail = float(np.max(np.abs(coef[-10:])))

    def direct(self, u: np.ndarray) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        out = np.sin(np.multiply.outer(u.ravel(), self._alpha)) @ self._wf
        return out.reshape(u.shape)

    def __call__(self, u: np.ndarray) -> np.ndarray:
        return self._cheb(u)


@functools.lru_cache(maxsize=16)
def _kernel(vstar: float, kw: float, nu: float, span: float, refine: int) -> _Kernel:
    return _Kernel(vstar, kw, nu, span, refine)


def kernel(vstar: float, kw: float, nu: float, need: float, refine: int = 1):
    """Cached kernel covering |u| <= need (span rounded up to a multiple of 2)."""
    span = 2.0 * math.ceil(max(need, 1.0) * 1.05 / 2.0)
    return _kernel(float(vstar), float(kw), float(nu), span, refine)


# ---------------------------------------------------------------------------
# Galerkin system on one zone x = c + w r (mirror zone optional)
# ---------------------------------------------------------------------------


@functools.lru_cache(maxsize=8)
def _theta_rule(m: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(m)
    return 0.5 * math.pi * (x + 1.0), 0.5 * math.pi * w


def _mirror_cauchy(z: np.ndarray, nmax: int) -> np.ndarray:
    """(1/pi) int sqrt(1-t^2) U_n(t)/(z - t) dt = q^{n+1}, q = 1/(z+sqrt(z^2-1))."""
    q = 1.0 / (z + np.sign(z) * np.sqrt(z * z - 1.0))
    return q[:, None] ** np.arange(1, nmax + 1)[None, :]


def _assemble(
    c: float, w: float, mirror: bool, k: _Kernel, n: int, mq: int
) -> tuple[np.ndarray, np.ndarray]:
    """Rows m = 0..n (projections on T_m, normalised by 2/pi) of the operator
    acting on b_0..b_{n-1}, and the right side for unit curvature 1/R = 1."""
    phi1 = k.phi1
    th, wt = _theta_rule(mq)
    r = np.cos(th)
    x = c + w * r
    ns = np.arange(n)
    # source side: sin(theta) sin((n+1) theta) = sin^2 U_n(cos theta)
    src = np.sin(th)[:, None] * np.sin(np.outer(th, ns + 1)) * wt[:, None]
    diff = x[:, None] - x[None, :]
    kern = k(diff)
    if mirror:
        kern = kern + k(x[:, None] + x[None, :])
    reg = (w / math.pi) * (kern @ src)  # (mq, n): value at x_i
    if mirror:
        sgn = (-1.0) ** ns
        reg = reg + phi1 * sgn[None, :] * _mirror_cauchy((x + c) / w, n)
    proj = (2.0 / math.pi) * np.cos(np.outer(np.arange(n + 1), th)) * wt[None, :]
    a = proj @ reg
    a[1:, :] += phi1 * np.eye(n)  # own Cauchy transform: T_{n+1}
    rhs = np.zeros(n + 1)
    rhs[0] = 2.0 * c
    rhs[1] = w
    return a, rhs


def _solve_zone(c, w, mirror, k, n, mq):
    a, rhs = _assemble(c, w, mirror, k, n, mq)
    b = np.linalg.solve(a[1:], rhs[1:])
    consistency = float(a[0] @ b - rhs[0])
    return b, consistency


# ---------------------------------------------------------------------------
# Public functions
# ---------------------------------------------------------------------------


def one_zone_end(
    vstar: float,
    kw: float,
    nu: float,
    radius: float,
    load: float,
    *,
    n: int = 40,
    refine: int = 1,
) -> float:
    """Half-width a of the single symmetric contact (-a, a)."""
    lam = radius * load
    phi1 = half_plane_phi1(vstar, nu)
    a_h = math.sqrt(2.0 * phi1 * lam / math.pi)
    mq = 2 * n + 24

    def carried(a: float) -> float:
        k = kernel(vstar, kw, nu, 2.0 * a, refine)
        b, _ = _solve_zone(0.0, a, False, k, n, mq)
        return math.pi * a * b[0] / 2.0  # lambda = R int p for unit curvature

    def f(log_a: float) -> float:
        return math.log(carried(math.exp(log_a)) / lam)

    lo, hi = math.log(0.5 * a_h), math.log(1.5 * a_h)
    while f(lo) > 0:
        lo -= 0.3
    while f(hi) < 0:
        hi += 0.3
    return math.exp(scipy.optimize.brentq(f, lo, hi, xtol=1e-15, rtol=1e-15))


def _two_zone_residual(ends, vstar, kw, nu, lam, n, refine):
    a1, a2 = ends
    c, w = 0.5 * (a1 + a2), 0.5 * (a2 - a1)
    k = kernel(vstar, kw, nu, 2.0 * a2, refine)
    b, cons = _solve_zone(c, w, True, k, n, 2 * n + 24)
    # unit curvature: the load carried, lam(a1, a2) = pi w b_0 (both zones)
    return np.array([cons / (2.0 * c), math.pi * w * b[0] / lam - 1.0]), b


def _nested_ends(vstar, kw, nu, lam, n, refine, a2_start):
    """Robust fallback: a1(a2) from the consistency condition (brentq), then
    a2 from the load (brentq on a bracket grown from a2_start)."""

    def res(a1, a2):
        return _two_zone_residual((a1, a2), vstar, kw, nu, lam, n, refine)[0]

    def inner(a2):
        grid = a2 * np.geomspace(1e-3, 0.999, 25)
        vals = [res(a1, a2)[0] for a1 in grid]
        for i in range(len(grid) - 1):
            if vals[i] > 0.0 >= vals[i + 1]:
                return scipy.optimize.brentq(
                    lambda a1: res(a1, a2)[0], grid[i], grid[i + 1], xtol=1e-15
                )
        return None

    def outer(a2):
        a1 = inner(a2)
        return 1.0 if a1 is None else res(a1, a2)[1]

    lo = hi = a2_start
    f_lo = f_hi = outer(a2_start)
    for _ in range(60):
        if f_lo <= 0.0 <= f_hi:
            break
        if f_lo > 0.0:
            hi, f_hi = lo, f_lo
            lo /= 1.05
            f_lo = outer(lo)
        else:
            lo, f_lo = hi, f_hi
            hi *= 1.05
            f_hi = outer(hi)
    else:
        raise RuntimeError("no bracket for the two-zone ends")
    a2 = scipy.optimize.brentq(outer, lo, hi, xtol=1e-15)
    return inner(a2), a2


def _fsolve(f, x0):
    # fsolve warns (RuntimeWarning) when xtol is below what round-off allows;
    # the caller checks the residual itself.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return scipy.optimize.fsolve(f, x0, xtol=1e-14, full_output=True)[0]


def two_zone_ends(
    vstar: float,
    kw: float,
    nu: float,
    radius: float,
    load: float,
    *,
    a_guess: tuple[float, float] | None = None,
    n: int = 40,
    refine: int = 1,
) -> tuple[float, float]:
    """Ends (a1, a2) of the separated symmetric contact (-a2,-a1) U (a1,a2).

    Newton-type ``fsolve`` from ``a_guess`` (default: 0.4 and 1.0 times the
    single-contact width); nested brentq if that fails."""
    lam = radius * load
    if a_guess is None:
        a_s = one_zone_end(vstar, kw, nu, radius, load, n=n, refine=refine)
        a_guess = (0.4 * a_s, a_s)

    def f(x):
        a1, a2 = np.exp(x)
        if not 0.0 < a1 < a2:
            return np.array([1.0, 1.0])
        return _two_zone_residual((a1, a2), vstar, kw, nu, lam, n, refine)[0]

    x = _fsolve(f, np.log(np.asarray(a_guess, float)))
    if np.max(np.abs(f(x))) > 1e-12:
        x = np.log(_nested_ends(vstar, kw, nu, lam, n, refine, float(a_guess[1])))
        x = _fsolve(f, x)
        if np.max(np.abs(f(x))) > 1e-12:
            raise RuntimeError("two-zone ends did not converge")
    a1, a2 = np.exp(x)
    return float(a1), float(a2)


def two_zone_report(
    vstar: float,
    kw: float,
    nu: float,
    radius: float,
    load: float,
    ends: tuple[float, float],
    *,
    n: int = 40,
    refine: int = 1,
) -> dict[str, float]:
    """Checks of a two-zone solution (lengths in h, pressures in P/h):
    the residuals of the two end conditions, the slope equation's residual
    off the Galerkin nodes, min p/sqrt(1 - r^2) on the zone (> 0: p >= 0 and
    square-root ends), the zone load, and the gap x^2/(2R) - delta - v(x) in
    the middle |x| < a1 and beside the contact a2 < |x| < a2 + 1."""
    a1, a2 = ends
    lam = radius * load
    res, b = _two_zone_residual((a1, a2), vstar, kw, nu, lam, n, refine)
    c, w = 0.5 * (a1 + a2), 0.5 * (a2 - a1)
    k = kernel(vstar, kw, nu, 2.0 * a2 + 1.0, refine)
    b = b / radius  # actual curvature 1/R
    nn = np.arange(b.size)
    # p / sqrt(1 - r^2) = sum b_n U_n(r), U_n(cos th) = sin((n+1) th)/sin(th)
    th = np.linspace(1e-9, math.pi - 1e-9, 4001)
    g = (np.sin(np.outer(th, nn + 1)) @ b) / np.sin(th)
    phi1 = k.phi1
    thq, wq = _theta_rule(2 * b.size + 24)
    xs = c + w * np.cos(thq)
    dens = w * wq * np.sin(thq) * (np.sin(np.outer(thq, nn + 1)) @ b)  # p dt

    def slope(x: np.ndarray) -> np.ndarray:
        inside = np.abs(x - c) < w
        zr = (x - c) / w
        cr = np.empty(x.size)
        zi = np.clip(zr[inside], -1.0, 1.0)
        cr[inside] = np.cos(np.outer(np.arccos(zi), nn + 1)) @ b
        cr[~inside] = _mirror_cauchy(zr[~inside], b.size) @ b
        cl = _mirror_cauchy((x + c) / w, b.size) @ (b * (-1.0) ** nn)
        reg = (k(x[:, None] - xs[None, :]) + k(x[:, None] + xs[None, :])) @ dens
        return phi1 * (cr + cl) + reg / math.pi

    xr = c + w * np.cos(np.linspace(0.013, math.pi - 0.011, 301))
    resid = float(np.max(np.abs(slope(xr) - xr / radius)) / (a2 / radius))
    xg, wg = np.polynomial.legendre.leggauss(60)

    def gap(x0: float, x1: float) -> float:
        # gap(x0) = int_{x1}^{x0} (x/R - v'(x)) dx with gap(x1) = 0 (x1 a zone end)
        s = x1 + (x0 - x1) * 0.5 * (xg + 1.0)
        return float(0.5 * (x0 - x1) * wg @ (s / radius - slope(s)))

    inner = [gap(x0, a1) for x0 in np.linspace(0.0, a1, 41)[:-1]]
    outer = [gap(x0, a2) for x0 in np.linspace(a2, a2 + 1.0, 41)[1:]]
    return {
        "consistency": float(res[0]),
        "load_residual": float(res[1]),
        "slope_residual": resid,
        "min_p_over_sqrt": float(np.min(g)) * radius / lam,
        "p_over_sqrt_ends": (float(g[-1]) * radius / lam, float(g[0]) * radius / lam),
        "zone_load_over_P": float(math.pi * w * b[0] / 2.0 / load),
        "gap_inner_min": float(min(inner)),
        "gap_at_0": inner[0],
        "gap_outer_min": float(min(outer)),
        "kernel_tail": k.tail,
    }
