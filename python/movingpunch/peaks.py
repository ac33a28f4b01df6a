"""One search for the peaks of sigma_x along the top and bottom faces.

Pure NumPy over callables (vectorised evaluations of the field at many x), so
the symmetric and the asymmetric solutions share it and tests can feed it closed
forms. ``search_peaks`` finds the lowest and the highest value of the top
face's sigma_x and the highest of the bottom face's on [lo, hi] and says how
far each reported value can be from the true extreme of the evaluated field.

Why it cannot miss a peak (each point is a scale of the physics):

* The grid resolves every length present: the contact (a cosine grid on
  (e1, e2), spacing at most ``step``); the square-root cusp of the top face's
  sigma_x at each contact end (outside an end the grid is uniform in
  s = sqrt(|x - e|), where sigma_x is smooth); the layer thickness h = 1 and
  the wavelength 2 pi/alpha_cr of the slowest free wave (``step`` is at most
  h/6 and lambda/12). Where the samples' fourth differences say the grid does
  not resolve the field near a candidate value, intervals are halved.
* Beyond the near field (the contact plus 6 h + 2 lambda on each side) the
  response is a sum of decaying free waves (every pole of the layer's
  response lies off the real axis below V*_cr; its least-damped one sets the
  decay, slow near V*_cr): the search marches outwards in windows of
  max(2 h, 2 lambda) and stops when the windows' envelope (max |sigma_x|) has
  stopped growing and 1.1 times it cannot reach any current extreme. It then
  checks the decay numerically: groups of 8 points a wavelength wide at
  geometrically growing distances up to the extent must stay under that
  envelope, or a warning says so.
* Every local extreme of the samples that could be the global one (its value
  plus a slack of its two drops to its neighbours reaches the best sample) is
  refined by a vectorised golden-section search in its bracket (in s near a
  contact end) until the values in the bracket agree to ``tolerance``.
  ``uncertainty`` of a peak is the largest amount by which any refined
  candidate could still exceed the reported value.

If the march would need more than ``budget`` evaluations per face, it stops
there and the result carries a warning naming the x up to which it searched.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["Extremum", "PeakSearch", "search_peaks", "search_step"]

FloatArray = npt.NDArray[np.float64]
Field = Callable[[FloatArray], FloatArray]

_GOLD = 0.3819660112501051  # 2 - golden ratio
_MAX_ROUNDS = 90
_MAX_CANDIDATES = 32
_MAX_BATCHES = 8
_MAX_SUBDIVIDE = 6


@dataclass(frozen=True)
class Extremum:
    """One peak: its value, position and the search's own uncertainty (a
    bound on how much the evaluated field's true extreme can exceed it)."""

    value: float
    x: float
    uncertainty: float


@dataclass(frozen=True)
class PeakSearch:
    """Result of ``search_peaks``."""

    top_min: Extremum
    top_max: Extremum
    bottom_max: Extremum
    evaluations: int
    """Field evaluations, top and bottom together."""
    searched_to: tuple[float, float]
    """The interval actually searched point by point (equal to (lo, hi) unless
    the budget ran out or the far field was shown to have decayed)."""
    checked_to: tuple[float, float]
    """How far beyond ``searched_to`` the decay of the far field was checked
    numerically (groups of points at geometrically growing distances);
    beyond, it decays as the physics says (every pole of the response lies
    off the real axis)."""
    warnings: tuple[str, ...]

    @property
    def peaks(self) -> tuple[Extremum, Extremum, Extremum]:
        """(top_min, top_max, bottom_max)."""
        return self.top_min, self.top_max, self.bottom_max


def search_step(wavelength: float) -> float:
    """Grid spacing x/h that resolves the layer (h/6) and a free wave of the
    given wavelength (lambda/12; ignored when not finite), at least h/96."""
    step = 1.0 / 6.0
    if math.isfinite(wavelength) and wavelength > 0.0:
        step = min(step, wavelength / 12.0)
    return max(step, 1.0 / 96.0)


class _Track:
    """Samples of one field: evaluated points, kept unsorted until asked."""

    def __init__(self, field: Field, lo: float, hi: float) -> None:
        self.field = field
        self.lo, self.hi = lo, hi
        self.xs: list[FloatArray] = []
        self.fs: list[FloatArray] = []
        self.count = 0
        self.low = math.inf  # lowest and highest value seen
        self.high = -math.inf

    def eval(self, x: FloatArray) -> FloatArray:
        # Clipped: the sqrt variable of a bracket may round past an end.
        x = np.ascontiguousarray(np.clip(x, self.lo, self.hi), dtype=np.float64)
        if x.size == 0:
            return np.empty(0)
        f = np.asarray(self.field(x), dtype=np.float64).reshape(-1)
        self.xs.append(x)
        self.fs.append(f)
        self.count += x.size
        self.low = min(self.low, float(np.min(f)))
        self.high = max(self.high, float(np.max(f)))
        return f

    def sorted(self) -> tuple[FloatArray, FloatArray]:
        x = np.concatenate(self.xs)
        f = np.concatenate(self.fs)
        x, idx = np.unique(x, return_index=True)
        return x, f[idx]


def _uniform(a: float, b: float, step: float) -> FloatArray:
    if not b > a:
        return np.array([a])
    n = max(1, math.ceil((b - a) / step))
    return np.linspace(a, b, n + 1)


def _top_near_grid(
    lo: float, hi: float, e1: float, e2: float, step: float
) -> FloatArray:
    """Contact (cosine grid) and each end's sqrt-graded neighbourhood."""
    w = 0.5 * (e2 - e1)
    c = 0.5 * (e2 + e1)
    m = max(48, math.ceil(math.pi * w / step))
    parts = [c - w * np.cos(np.linspace(0.0, math.pi, m + 1))]
    d = min(max(w, step), 1.0)  # graded neighbourhood of each end
    ns = max(12, math.ceil(2.0 * d / step))
    s = np.linspace(0.0, math.sqrt(d), ns + 1)
    parts += [e1 - s**2, e2 + s**2]
    x = np.concatenate(parts)
    return x[(x >= lo) & (x <= hi)]


def _fourth_difference_gaps(x: FloatArray, f: FloatArray) -> FloatArray:
    """Per interval (x_i, x_i+1): an estimate of how far the field strays
    there from the cubic through the four nearest samples: the fourth divided
    difference (about f^(4)/24) times the nodal product at the interval's
    middle; 0 where it cannot be formed. Works on any (non-uniform) grid."""
    n = len(x)
    gap = np.zeros(max(n - 1, 0))
    if n < 5:
        return gap
    d = f.astype(np.float64)
    for k in range(1, 5):
        d = (d[1:] - d[:-1]) / (x[k:] - x[:-k])
    # d[j] = f[x_j .. x_j+4]; the cubic through x_j+1 .. x_j+4 (or x_j ..
    # x_j+3) misses at the middle of interval j+2 (j+1) by about d times the
    # product of the distances to its nodes.
    for shift, nodes in ((1, (0, 1, 2, 3)), (2, (1, 2, 3, 4))):
        i = np.arange(len(d)) + shift  # interval index
        mid = 0.5 * (x[i] + x[i + 1])
        prod = np.ones(len(d))
        for k in nodes:
            prod *= np.abs(mid - x[np.arange(len(d)) + k])
        gap[i] = np.maximum(gap[i], np.abs(d) * prod)
    return gap


class _Searcher:
    def __init__(
        self,
        top: Field,
        bottom: Field,
        *,
        lo: float,
        hi: float,
        ends: tuple[float, float],
        wavelength: float,
        tolerance: float,
        budget: int,
    ) -> None:
        self.top = _Track(top, lo, hi)
        self.bottom = _Track(bottom, lo, hi)
        self.lo, self.hi = lo, hi
        self.e1, self.e2 = ends
        self.step = search_step(wavelength)
        self.wave = wavelength if math.isfinite(wavelength) else 0.0
        self.tol = tolerance
        self.budget = budget
        self.warnings: list[str] = []
        self.searched = [lo, hi]
        self.far = (0.0, 0.0)  # bound on |top|, |bottom| beyond the march
        self.started = time.perf_counter()
        self.checked = [lo, hi]  # how far the far field was checked

    # ---- the grid ---------------------------------------------------------

    def near(self) -> tuple[float, float]:
        reach = 6.0 + 2.0 * min(self.wave, 100.0)
        e1 = max(self.lo, min(self.hi, self.e1))
        e2 = max(self.lo, min(self.hi, self.e2))
        return max(self.lo, e1 - reach), min(self.hi, e2 + reach)

    def sample_near(self) -> None:
        n1, n2 = self.near()
        grid = np.concatenate(
            [
                _uniform(n1, n2, self.step),
                [min(max(0.0, self.lo), self.hi)],  # the ends: by the march
            ]
        )
        top = np.concatenate(
            [grid, _top_near_grid(self.lo, self.hi, self.e1, self.e2, self.step)]
        )
        top = np.unique(top[(top >= self.lo) & (top <= self.hi)])
        self.top.eval(top)
        self.bottom.eval(np.unique(grid[(grid >= self.lo) & (grid <= self.hi)]))

    def bests(self) -> tuple[float, float, float]:
        """Best sampled values of the three searches (as maxima of s f)."""
        return -self.top.low, self.top.high, self.bottom.high

    def march(self, start: float, end: float) -> float:
        """Samples outwards from ``start`` towards ``end`` (either direction)
        in windows until the far field cannot hold a peak; returns the x
        reached."""
        direction = 1.0 if end > start else -1.0
        width = max(2.0, 2.0 * self.wave)
        env_top: list[float] = []
        env_bot: list[float] = []
        x0 = start
        per_window = math.ceil(width / self.step)
        while direction * (end - x0) > 0.0:
            x1 = x0 + direction * width
            if direction * (x1 - end) > 0.0:
                x1 = end
            pts = np.linspace(x0, x1, per_window + 1)[1:]
            ft = self.top.eval(pts)
            fb = self.bottom.eval(pts)
            env_top.append(float(np.max(np.abs(ft))))
            env_bot.append(float(np.max(np.abs(fb))))
            x0 = x1
            if self._decayed(env_top, env_bot):
                return x0
            if max(self.top.count, self.bottom.count) > self.budget:
                self.warnings.append(
                    f"the field still reaches {max(env_top[-1], env_bot[-1]):.3g} "
                    f"at x/h = {x0:.6g} (a slowly decaying free wave); the peaks "
                    f"were searched up to there only ({self.budget} points per "
                    "face): a larger extent cannot be searched to the stated "
                    "bound"
                )
                return x0
        return end

    def _decayed(self, env_top: list[float], env_bot: list[float]) -> bool:
        if len(env_top) < 3:
            return False
        for env in (env_top, env_bot):
            last = env[-3:]
            if not (last[1] <= 1.05 * last[0] and last[2] <= 1.05 * last[1]):
                return False
        # Beyond, |top| <= et and |bottom| <= eb: no peak there can beat a
        # best value by more than the tolerance (a best below zero is beaten
        # by values near zero, so then the envelope must be under tol).
        et, eb = 1.1 * env_top[-1], 1.1 * env_bot[-1]
        done = all(
            e <= max(b, 0.0) + self.tol
            for e, b in zip((et, et, eb), self.bests(), strict=True)
        )
        if done:
            self.far = (max(self.far[0], et), max(self.far[1], eb))
        return done

    def check_far(
        self, start: float, end: float, envelope: tuple[float, float]
    ) -> None:
        """Groups of 8 points a wavelength wide at geometrically growing
        distances must stay under the envelope seen where the march stopped.
        Stops early (``checked`` says where) when the next group would take
        half the time the search has spent so far (at least 0.25 s):
        a field whose cost grows with |x| (the damped one's) is checked as far
        as is affordable and assumed to keep decaying beyond, as the physics
        says."""
        direction = 1.0 if end > start else -1.0
        span = max(self.wave, 1.0)
        dist = abs(start - 0.5 * (self.e1 + self.e2))
        far = abs(end - 0.5 * (self.e1 + self.e2))
        side = 1 if direction > 0 else 0
        budget = max(0.25, 0.5 * (time.perf_counter() - self.started))
        spent, last = 0.0, 0.0
        while True:
            dist *= 2.0
            if dist > far:
                self.checked[side] = end
                break
            if spent + 2.0 * last > budget:
                break
            x = 0.5 * (self.e1 + self.e2) + direction * dist
            clock = time.perf_counter()
            pts = x + direction * np.linspace(0.0, span, 8)
            pts = pts[(pts >= self.lo) & (pts <= self.hi)]
            ft = self.top.eval(pts)
            fb = self.bottom.eval(pts)
            last = time.perf_counter() - clock
            spent += last
            self.checked[side] = float(pts[-1]) if pts.size else self.checked[side]
            if ft.size and (
                np.max(np.abs(ft)) > 1.1 * envelope[0] + self.tol
                or np.max(np.abs(fb)) > 1.1 * envelope[1] + self.tol
            ):
                self.warnings.append(
                    f"the far field at x/h = {x:.6g} exceeds the envelope "
                    f"{max(envelope):.3g} at which the search stopped: it does "
                    "not decay as expected, peaks beyond may be missed"
                )
                return

    def sample(self) -> None:
        self.sample_near()
        n1, n2 = self.near()
        for start, end in ((n2, self.hi), (n1, self.lo)):
            if start == end:
                continue
            reached = self.march(start, end)
            self.searched[1 if end > start else 0] = reached
            self.checked[1 if end > start else 0] = reached
            if reached != end and not self.warnings:
                self.check_far(reached, end, self._envelope(reached, start))

    def _envelope(self, reached: float, start: float) -> tuple[float, float]:
        """max |field| over the last window of the march (top, bottom)."""
        w = max(2.0, 2.0 * self.wave)
        lo_x, hi_x = sorted((reached, reached - math.copysign(w, reached - start)))
        out = []
        for track in (self.top, self.bottom):
            x, f = track.sorted()
            sel = (x >= lo_x) & (x <= hi_x)
            out.append(float(np.max(np.abs(f[sel]))) if sel.any() else 0.0)
        return out[0], out[1]


def search_peaks(
    top: Field,
    bottom: Field,
    *,
    lo: float,
    hi: float,
    ends: tuple[float, float],
    wavelength: float,
    tolerance: float,
    budget: int = 20000,
) -> PeakSearch:
    """Extremes of ``top`` (lowest and highest) and ``bottom`` (highest) on
    [lo, hi].

    ``top`` and ``bottom`` map an array of x/h to the field there; ``ends``
    are the contact's ends (the top field may have square-root cusps there);
    ``wavelength`` is 2 pi/alpha_cr of the slowest free wave (inf if none);
    ``tolerance`` the value accuracy to refine each peak to; ``budget`` the
    most evaluations per face the far-field march may spend.
    """
    if not (math.isfinite(lo) and math.isfinite(hi) and hi >= lo):
        raise ValueError(
            f"search interval must be finite with lo <= hi, got {lo}, {hi}"
        )
    s = _Searcher(
        top,
        bottom,
        lo=lo,
        hi=hi,
        ends=ends,
        wavelength=wavelength,
        tolerance=tolerance,
        budget=budget,
    )
    s.sample()
    edges = [e for e in (s.e1, s.e2) if lo < e < hi]
    _resolve(s.top, edges, tolerance, (-1.0, 1.0))
    _resolve(s.bottom, [], tolerance, (1.0,))
    tmin = _beyond(_refine(s.top, -1.0, edges, tolerance, s.lo, s.hi), s.far[0])
    tmax = _beyond(_refine(s.top, 1.0, edges, tolerance, s.lo, s.hi), s.far[0])
    bmax = _beyond(_refine(s.bottom, 1.0, [], tolerance, s.lo, s.hi), s.far[1])
    return PeakSearch(
        top_min=Extremum(-tmin.value, tmin.x, tmin.uncertainty),
        top_max=tmax,
        bottom_max=bmax,
        evaluations=s.top.count + s.bottom.count,
        searched_to=(s.searched[0], s.searched[1]),
        checked_to=(s.checked[0], s.checked[1]),
        warnings=tuple(s.warnings),
    )


def _beyond(peak: Extremum, far: float) -> Extremum:
    """``peak`` with the far field's bound (values up to ``far`` beyond the
    march) in its uncertainty."""
    extra = max(far - peak.value, 0.0)
    if extra == 0.0:
        return peak
    return Extremum(peak.value, peak.x, max(peak.uncertainty, extra))


def _resolve(
    track: _Track, edges: Sequence[float], tol: float, signs: Sequence[float]
) -> None:
    """Halves the intervals whose fourth differences say the grid may hide a
    value above a search's best sample."""
    for _ in range(_MAX_SUBDIVIDE):
        x, f = track.sorted()
        gap = _fourth_difference_gaps(x, f)
        # No difference across a cusp: it is not smooth there.
        for e in edges:
            k = int(np.searchsorted(x, e))
            gap[max(k - 3, 0) : k + 3] = 0.0
        spread = float(np.ptp(f)) if f.size else 0.0
        need = np.zeros(len(gap), dtype=bool)
        for sgn in signs:
            g = sgn * f
            best = float(np.max(g))
            top_pair = np.maximum(g[:-1], g[1:])
            need |= (top_pair + 8.0 * gap >= best - tol) & (
                gap > max(tol, 1e-3 * spread)
            )
        if not need.any():
            return
        track.eval(0.5 * (x[:-1][need] + x[1:][need]))


@dataclass
class _Brackets:
    """Golden-section brackets in a variable t: x = anchor + side * t**2 when
    ``root`` (near a cusp), else x = t."""

    t_lo: FloatArray
    t_b: FloatArray
    t_hi: FloatArray
    g_lo: FloatArray
    g_b: FloatArray
    g_hi: FloatArray
    anchor: FloatArray
    side: FloatArray
    root: npt.NDArray[np.bool_]

    def x(self, t: FloatArray) -> FloatArray:
        return np.where(self.root, self.anchor + self.side * t * t, t)


_Var = tuple[bool, float, float]


def _variable(x: float, seg: tuple[float, float], edges: Sequence[float]) -> _Var:
    """(root, anchor, side) of the bracket variable for a point of segment
    ``seg``: t = sqrt(|x - e|) from the nearer segment end e that is a
    contact end (the field is smooth in t there), else t = x."""
    best: _Var = (False, 0.0, 1.0)
    dist = math.inf
    for e in seg:
        if e in edges and abs(x - e) < dist:
            dist = abs(x - e)
            best = (True, e, 1.0 if e == seg[0] else -1.0)
    return best


def _to_t(x: float, var: _Var) -> float:
    root, anchor, side = var
    return math.sqrt(max(side * (x - anchor), 0.0)) if root else x


def _point_gaps(x: FloatArray, f: FloatArray, edges: Sequence[float]) -> FloatArray:
    """Per sample: the larger cubic-interpolation gap of its two intervals
    (0 next to a contact end, where the field has a cusp)."""
    gap = _fourth_difference_gaps(x, f)
    out = np.zeros(len(x))
    if len(gap):
        out[:-1] = gap
        out[1:] = np.maximum(out[1:], gap)
    for e in edges:
        k = int(np.searchsorted(x, e))
        out[max(k - 3, 0) : k + 4] = 0.0
    return out


def _slack(xs: FloatArray, gs: FloatArray, gap: FloatArray) -> FloatArray:
    """How much the field may exceed each sample that is a local maximum of
    the samples: twice the rise of the parabola through it and its two
    neighbours (a quarter of its drops at a segment end, where the field may
    still rise a little past the sample), plus four times the interpolation
    gap of the samples around it."""
    n = len(xs)
    out = np.zeros(n)
    if n == 1:
        return out
    h1 = np.empty(n)
    h2 = np.empty(n)
    d1 = np.empty(n)
    d2 = np.empty(n)
    h1[1:] = xs[1:] - xs[:-1]
    h2[:-1] = xs[1:] - xs[:-1]
    d1[1:] = gs[1:] - gs[:-1]  # rise from the left neighbour
    d2[:-1] = gs[:-1] - gs[1:]  # drop to the right neighbour
    inner = slice(1, n - 1)
    # Parabola through (-h1, g - d1), (0, g), (h2, g - d2): slopes s1 = d1/h1,
    # s2 = -d2/h2, curvature c = (s2 - s1)/(h1 + h2) < 0 at a maximum.
    s1 = d1[inner] / h1[inner]
    s2 = -d2[inner] / h2[inner]
    curv = 2.0 * (s2 - s1) / (h1[inner] + h2[inner])
    slope0 = s1 + 0.5 * curv * h1[inner]
    with np.errstate(divide="ignore", invalid="ignore"):
        rise = np.where(curv < 0.0, -(slope0**2) / (2.0 * curv), 0.0)
    out[inner] = 2.0 * np.minimum(rise, d1[inner] + d2[inner])
    out[0] = 0.25 * abs(d2[0])
    out[-1] = 0.25 * abs(d1[-1])
    return out + 4.0 * gap


def _refine(
    track: _Track,
    sign: float,
    edges: Sequence[float],
    tol: float,
    lo: float,
    hi: float,
) -> Extremum:
    """The largest value of sign * field: every local maximum of the samples
    that could be it (its value plus twice its two drops to its neighbours
    reaches the best sample), refined by golden section in its bracket."""
    x, f = track.sorted()
    g = sign * f
    best_sample = float(np.max(g))
    cuts = sorted({lo, hi, *edges})
    gap = _point_gaps(x, f, edges)
    # (reach, x_lo, x_b, x_hi, g_lo, g_b, g_hi, variable)
    cands: list[_Cand] = []
    for a, b in itertools.pairwise(cuts):
        sel = np.nonzero((x >= a) & (x <= b))[0]
        xs, gs = x[sel], g[sel]
        n = len(xs)
        if n == 0:
            continue
        left = np.concatenate([[-np.inf], gs[:-1]])
        right = np.concatenate([gs[1:], [-np.inf]])
        peak = (gs >= left) & (gs >= right)
        reach = gs + _slack(xs, gs, gap[sel])
        for i in np.nonzero(peak & (reach >= best_sample - tol))[0]:
            i0, i1 = max(i - 1, 0), min(i + 1, n - 1)
            var = _variable(float(xs[i]), (a, b), edges)
            cands.append(
                (
                    float(reach[i]),
                    float(xs[i0]),
                    float(xs[i]),
                    float(xs[i1]),
                    float(gs[i0]),
                    float(gs[i]),
                    float(gs[i1]),
                    var,
                )
            )
    # Refine in batches, most promising first, until no candidate left can
    # reach the best refined value.
    pending = sorted(cands, key=lambda c: (-c[5], -c[0]))
    value, where, reach_all = -math.inf, math.nan, -math.inf
    for _ in range(_MAX_BATCHES):
        batch = pending[:_MAX_CANDIDATES]
        pending = pending[_MAX_CANDIDATES:]
        v, w, r = _refine_batch(track, sign, batch, tol)
        if v > value:
            value, where = v, w
        reach_all = max(reach_all, r)
        pending = [c for c in pending if c[0] >= value - tol]
        if not pending:
            break
    if pending:
        reach_all = max(reach_all, max(c[0] for c in pending))
    return Extremum(
        value=value,
        x=min(max(where, track.lo), track.hi),
        uncertainty=max(reach_all - value, 0.0),
    )


_Cand = tuple[float, float, float, float, float, float, float, _Var]


def _refine_batch(
    track: _Track, sign: float, kept: Sequence[_Cand], tol: float
) -> tuple[float, float, float]:
    """(best value, its x, the most any bracket may still hold) of a batch
    of candidates refined together."""
    br = _Brackets(
        t_lo=np.array([_to_t(c[1], c[7]) for c in kept]),
        t_b=np.array([_to_t(c[2], c[7]) for c in kept]),
        t_hi=np.array([_to_t(c[3], c[7]) for c in kept]),
        g_lo=np.array([c[4] for c in kept]),
        g_b=np.array([c[5] for c in kept]),
        g_hi=np.array([c[6] for c in kept]),
        anchor=np.array([c[7][1] for c in kept]),
        side=np.array([c[7][2] for c in kept]),
        root=np.array([c[7][0] for c in kept], dtype=bool),
    )
    # t_lo < t_hi in the bracket variable (the sqrt map reverses the order
    # below an anchor).
    swap = br.t_lo > br.t_hi
    br.t_lo[swap], br.t_hi[swap] = br.t_hi[swap], br.t_lo[swap].copy()
    br.g_lo[swap], br.g_hi[swap] = br.g_hi[swap], br.g_lo[swap].copy()
    _golden(track, sign, br, tol)
    spread = br.g_b - np.minimum(br.g_lo, br.g_hi)
    win = int(np.argmax(br.g_b))
    return (
        float(br.g_b[win]),
        float(br.x(br.t_b)[win]),
        float(np.max(br.g_b + 2.0 * spread)),
    )


def _golden(track: _Track, sign: float, br: _Brackets, tol: float) -> None:
    for _ in range(_MAX_ROUNDS):
        width = br.t_hi - br.t_lo
        spread = br.g_b - np.minimum(br.g_lo, br.g_hi)
        scale = np.maximum(np.abs(br.t_b), 1.0)
        active = (spread > tol) & (width > 4e-16 * scale)
        if not active.any():
            return
        idx = np.nonzero(active)[0]
        right = (br.t_hi - br.t_b) >= (br.t_b - br.t_lo)
        t_new = np.where(
            right,
            br.t_b + _GOLD * (br.t_hi - br.t_b),
            br.t_b - _GOLD * (br.t_b - br.t_lo),
        )[idx]
        g_new = sign * track.eval(_x_of(br, idx, t_new))
        for j, k in enumerate(idx):
            tn, gn = float(t_new[j]), float(g_new[j])
            if gn > br.g_b[k]:
                if tn > br.t_b[k]:
                    br.t_lo[k], br.g_lo[k] = br.t_b[k], br.g_b[k]
                else:
                    br.t_hi[k], br.g_hi[k] = br.t_b[k], br.g_b[k]
                br.t_b[k], br.g_b[k] = tn, gn
            elif tn > br.t_b[k]:
                br.t_hi[k], br.g_hi[k] = tn, gn
            else:
                br.t_lo[k], br.g_lo[k] = tn, gn


def _x_of(br: _Brackets, idx: npt.NDArray[np.intp], t: FloatArray) -> FloatArray:
    return np.where(br.root[idx], br.anchor[idx] + br.side[idx] * t * t, t)
