"""Several contact zones and trains of punches (movingpunch.zones,
cpp/src/zones.cpp; docs/theory.md section 15), against independent anchors:

- an independent two-zone solver (tests/python/independent_zones.py: its own
  layer response, its own kernel quadrature, a Galerkin discretisation);
- complementarity checked on a fine grid out to 30 h with the Fourier
  (Filon) surface displacement, which the solver's own checks do not use;
- equilibrium by an independent quadrature of the pressure;
- limits: far-apart punches are single punches, a one-element train is
  ``mp.solve``, mirror images give mirror results, the zones join the single
  contact at the separation threshold.
"""

from __future__ import annotations

import itertools
import json
import math

import numpy as np
import pytest

import movingpunch as mp
from independent_zones import two_zone_ends
from movingpunch import zones as Z

KW = 0.1
V99 = 0.99 * mp.critical_vstar(KW, 0.2)
LOAD = 0.002
R = 100.0


@pytest.fixture(scope="module")
def separated() -> mp.ZonedSolution:
    s = mp.solve(vstar=V99, kw=KW, radius=R, load=LOAD)
    assert isinstance(s, mp.ZonedSolution)
    return s


def _zone_integral(s: object, left: float, right: float, m: int = 400) -> float:
    """int p dx over one zone by the trapezoid rule in theta (x = c + w cos
    theta: the integrand w sin(theta) p is smooth and periodic)."""
    c, w = 0.5 * (left + right), 0.5 * (right - left)
    th = (np.arange(m) + 0.5) * math.pi / m
    p = np.asarray(s.pressure(c + w * np.cos(th)))  # type: ignore[attr-defined]
    return float(np.sum(p * w * np.sin(th)) * math.pi / m)


def _gap(s: object, x: np.ndarray, height: np.ndarray, delta: float) -> np.ndarray:
    v = np.asarray(s.surface_displacement(x))  # type: ignore[attr-defined]
    return height - delta - v


def test_the_refused_case_separates_into_two_valid_zones(
    separated: mp.ZonedSolution,
) -> None:
    s = separated
    assert len(s.contact_zones) == 2
    assert s.valid
    assert "separated contact of 2 zones" in s.validity
    assert "single contact was rejected" in s.validity
    (l1, r1), (l2, r2) = s.contact_zones
    assert l1 < r1 < 0.0 < l2 < r2
    assert s.contact_interval == (l1, r2)
    # p >= 0 on every zone (2001 points each), 0 between them.
    for left, right in s.contact_zones:
        x = np.linspace(left, right, 2001)
        assert np.min(s.pressure(x)) >= -1e-12
    assert s.pressure(0.0) == 0.0
    # Equilibrium: int p dx = 1 (per P/h), by an independent quadrature.
    total = sum(_zone_integral(s, lo, hi) for lo, hi in s.contact_zones)
    assert abs(total - 1.0) < 1e-12
    # The punch's two zones carry its load and share one indentation: the
    # gap f - delta - v vanishes on both zones and is >= 0 elsewhere, out to
    # 30 h (the Fourier surface displacement, not the solver's own check).
    x = np.linspace(-30.0, 30.0, 6001)
    x = np.sort(np.concatenate([x, np.linspace(r1, l2, 401)]))
    gap = _gap(s, x, x**2 / (2 * R), s.indentation)
    scale = (r2 - l1) ** 2 / (2 * R)
    inside = np.zeros_like(x, dtype=bool)
    for lo, hi in s.contact_zones:
        inside |= (x > lo) & (x < hi)
    assert np.max(np.abs(gap[inside])) < 1e-9 * scale
    assert np.min(gap[~inside]) > -1e-9 * scale
    # Between the zones the surface is clear of the punch.
    assert np.max(gap[(x > r1 + 0.05) & (x < l2 - 0.05)]) > 1e-6


def test_two_zone_ends_agree_with_an_independent_discretisation(
    separated: mp.ZonedSolution,
) -> None:
    a1, a2 = two_zone_ends(V99, KW, 0.2, R, LOAD, a_guess=(0.7, 1.78))
    (l1, r1), (l2, r2) = separated.contact_zones
    for mine, theirs in ((-r1, a1), (l2, a1), (-l1, a2), (r2, a2)):
        assert abs(mine - theirs) < 1e-8
    # The estimate bounds the error without exaggerating it beyond reason.
    err = max(abs(-r1 - a1), abs(l2 - a1), abs(-l1 - a2), abs(r2 - a2))
    assert err <= separated.error_estimate + 1e-12
    assert separated.error_estimate < 1e-6


@pytest.mark.parametrize(
    "start",
    [
        [(0, -1.9, -0.3), (0, 0.3, 1.9)],
        [(0, -1.7, -0.9), (0, 0.9, 1.7)],
        [(0, -1.6, -0.5), (0, 0.6, 1.9)],  # asymmetric start
        [(0, -1.78, 1.78)],  # the single contact: the search splits it
    ],
)
def test_the_contact_set_does_not_depend_on_the_start(
    separated: mp.ZonedSolution, start: list[tuple[int, float, float]]
) -> None:
    layer = Z._Layer(V99, KW, 0.2, 0.0, 0.0, 1e-10, 0)
    z, _, _ = Z.find_contact_set(layer, [mp.Punch(R, LOAD)], start)
    got = [(q.left, q.right) for q in z.zones]
    assert len(got) == 2
    for (a, b), (c, d) in zip(got, separated.contact_zones, strict=True):
        assert abs(a - c) < 1e-9
        assert abs(b - d) < 1e-9


def _threshold() -> float:
    """The load at which the single contact's p(0) reaches 0 (bisection on
    the single solver's own validity)."""
    lo, hi = 2e-4, 2e-3
    for _ in range(45):
        mid = 0.5 * (lo + hi)
        s = mp.solve(
            vstar=V99,
            kw=KW,
            radius=R,
            load=mid,
            contact="single",
            allow_unphysical=True,
        )
        lo, hi = (mid, hi) if s.valid else (lo, mid)
    return hi


def test_zones_merge_into_the_single_contact_at_the_threshold() -> None:
    p_star = _threshold()
    below = mp.solve(vstar=V99, kw=KW, radius=R, load=p_star * (1 - 1e-6))
    assert isinstance(below, mp.Solution)
    assert below.valid
    inner = []
    for eps in (1e-2, 1e-3, 1e-4, 1e-6):
        above = mp.solve(vstar=V99, kw=KW, radius=R, load=p_star * (1 + eps))
        assert isinstance(above, mp.ZonedSolution)
        (_l1, r1), (l2, r2) = above.contact_zones
        inner.append(l2)
        assert abs(r1 + l2) < 1e-9  # symmetric
    # The gap closes like sqrt(P - P*): its half-width falls about 3.2 times
    # per decade of P - P*, and the hull, the indentation and the pressure
    # join the single contact's.
    assert inner == sorted(inner, reverse=True)
    ratios = [a / b for a, b in itertools.pairwise(inner)]
    assert all(2.5 < q < 4.0 for q in ratios[:2]), ratios  # one decade each
    # (at 1e-6 the threshold itself, found with the single solve's own
    # accuracy, is uncertain by about 1e-7 P*: only the order is checked)
    assert ratios[2] > 1.0, ratios
    assert inner[-1] < 3e-3
    assert abs(r2 - below.a) < 1e-5 * below.a
    assert abs(above.indentation - below.indentation) < 1e-5 * below.indentation
    x = np.linspace(-0.9 * below.a, 0.9 * below.a, 41)
    assert (
        np.max(np.abs(above.pressure(x) - below.pressure(x))) < 1e-4 * below.p0 + 1e-4
    )


def test_a_symmetric_pair_gives_mirror_results() -> None:
    train = mp.solve_punches(
        [mp.Punch(R, LOAD, at=-1.5), mp.Punch(R, LOAD, at=1.5)], vstar=0.5, kw=1.0
    )
    (l1, r1), (l2, r2) = train.contact_zones
    assert abs(l1 + r2) < 1e-10
    assert abs(r1 + l2) < 1e-10
    x = np.linspace(-4.0, 4.0, 81)
    assert np.allclose(train.pressure(x), train.pressure(-x), atol=1e-9, rtol=0)
    assert np.allclose(
        train.surface_stress(x), train.surface_stress(-x), atol=1e-8, rtol=0
    )
    first, second = train.punches
    assert abs(first.indentation - second.indentation) < 1e-12
    assert abs(first.drag + second.drag) < 1e-12  # each contact leans outwards
    # Unequal loads: swapping them mirrors the whole solution.
    a = mp.solve_punches(
        [mp.Punch(R, 0.001, at=-2.0), mp.Punch(R, 0.003, at=2.0)], vstar=0.5, kw=1.0
    )
    b = mp.solve_punches(
        [mp.Punch(R, 0.003, at=-2.0), mp.Punch(R, 0.001, at=2.0)], vstar=0.5, kw=1.0
    )
    for (p, q), (r, t) in zip(a.contact_zones, reversed(b.contact_zones), strict=True):
        assert abs(p + t) < 1e-10
        assert abs(q + r) < 1e-10
    assert abs(a.punches[0].indentation - b.punches[1].indentation) < 1e-12


def test_far_apart_punches_are_single_punches() -> None:
    # 100 h apart on a stiff base: the layer's response has decayed.
    single = mp.solve(vstar=0.3, kw=10.0, radius=R, load=LOAD, tol=1e-12)
    heavy = mp.solve(vstar=0.3, kw=10.0, radius=50.0, load=0.004, tol=1e-12)
    train = mp.solve_punches(
        [mp.Punch(R, LOAD, at=-50.0), mp.Punch(50.0, 0.004, at=50.0)],
        vstar=0.3,
        kw=10.0,
        tol=1e-12,
    )
    (l1, r1), (l2, r2) = train.contact_zones
    assert abs(l1 + 50.0 + single.a) < 1e-8
    assert abs(r1 + 50.0 - single.a) < 1e-8
    assert abs(l2 - 50.0 + heavy.a) < 1e-8
    assert abs(r2 - 50.0 - heavy.a) < 1e-8
    assert (
        abs(train.punches[0].indentation - single.indentation)
        < 1e-8 * single.indentation
    )
    assert (
        abs(train.punches[1].indentation - heavy.indentation) < 1e-8 * heavy.indentation
    )
    x = np.linspace(-0.99, 0.99, 11) * single.a
    # The train's pressure per its total load 0.006: the first punch's share.
    assert np.allclose(
        train.pressure(x - 50.0) * 0.006 / LOAD, single.pressure(x), atol=1e-8, rtol=0
    )
    assert np.allclose(
        train.punches[0].pressure(x - 50.0), single.pressure(x), atol=1e-8
    )


def test_a_one_punch_train_is_solve() -> None:
    ref = mp.solve(vstar=0.5, kw=1.0, radius=R, load=LOAD)
    one = mp.solve_punches([mp.Punch(R, LOAD)], vstar=0.5, kw=1.0)
    assert type(one) is type(ref)
    skip = {"elapsed", "stage_times", "kernel_builds"}
    a = {k: v for k, v in one.to_dict().items() if k not in skip}
    b = {k: v for k, v in ref.to_dict().items() if k not in skip}
    assert a == b


@pytest.mark.parametrize(
    ("shape", "atol"),
    # (A rounded flat's zone: the kinked slope's projection and the
    # half-plane tail, as the single contact's: docs/theory.md section 15.2.)
    [(R, 1e-8), (mp.RoundedFlat(0.3, 100.0), 1e-7)],
    ids=["cylinder", "rounded-flat"],
)
def test_a_moved_punch_is_the_single_one_moved(
    shape: float | mp.RoundedFlat, atol: float
) -> None:
    # Moved to x0 = 7: the same contact, moved.
    if isinstance(shape, float):
        ref = mp.solve(vstar=0.5, kw=1.0, radius=shape, load=LOAD)
    else:
        ref = mp.solve(vstar=0.5, kw=1.0, profile=shape, load=LOAD)
    moved = mp.solve_punches([mp.Punch(shape, LOAD, at=7.0)], vstar=0.5, kw=1.0)
    assert isinstance(moved, mp.ZonedSolution)
    (lo, hi) = moved.contact_zones[0]
    assert abs(lo - 7.0 + ref.a) < 1e-10
    assert abs(hi - 7.0 - ref.a) < 1e-10
    assert abs(moved.indentation - ref.indentation) < 1e-10 * ref.indentation
    x = np.linspace(-2.0, 2.0, 21)
    assert np.allclose(moved.surface_stress(x + 7.0), ref.surface_stress(x), atol=atol)


def test_close_punches_near_the_critical_speed_interact() -> None:
    v = 0.9 * mp.critical_vstar(KW)
    alone = mp.solve(vstar=v, kw=KW, radius=R, load=LOAD)
    train = mp.solve_punches(
        [mp.Punch(R, LOAD, at=-2.0), mp.Punch(R, LOAD, at=2.0)], vstar=v, kw=KW
    )
    # Each punch sinks less than alone by a third: the other's wave lifts it.
    assert train.punches[0].indentation < 0.75 * alone.indentation
    far = mp.solve_punches(
        [mp.Punch(R, LOAD, at=-40.0), mp.Punch(R, LOAD, at=40.0)], vstar=v, kw=KW
    )
    assert (
        abs(far.punches[0].indentation - alone.indentation) < 1e-3 * alone.indentation
    )


def test_contact_modes_and_the_contract() -> None:
    with pytest.raises(mp.UnphysicalContactError):
        mp.solve(vstar=V99, kw=KW, radius=R, load=LOAD, contact="single")
    s = mp.solve(
        vstar=V99, kw=KW, radius=R, load=LOAD, contact="single", allow_unphysical=True
    )
    assert isinstance(s, mp.Solution)
    assert not s.valid
    assert s.contact_zones == ((-s.a, s.a),)
    with pytest.raises(mp.InvalidParameterError) as err:
        mp.solve(vstar=0.5, kw=1.0, radius=R, load=LOAD, contact="zones")
    assert err.value.parameter == "contact"
    d = mp.solve(vstar=0.5, kw=1.0, radius=R, load=LOAD, damping=0.5)
    assert d.contact_zones == (d.contact_interval,)


def test_every_evaluation_of_the_contract_works(separated: mp.ZonedSolution) -> None:
    s = separated
    assert isinstance(s, mp.ContactSolution)
    fld = s.stress_field(np.linspace(-3, 3, 7), [0.0, -0.5, -1.0])
    assert fld.sigma_x.shape == (3, 7)
    assert np.all(np.isfinite(fld.von_mises))
    # On the surface sigma_y = -p.
    assert np.allclose(fld.sigma_y[0], -s.pressure(np.linspace(-3, 3, 7)), atol=1e-9)
    peaks = s.stress_peaks()
    assert math.isfinite(peaks.top_compressive)
    assert peaks.error_bound > 0
    assert s.depth_stress(-0.5) == pytest.approx(float(fld.sigma_x[1, 3]), abs=1e-12)
    assert math.isfinite(s.displacement(0.5, -0.5))
    assert math.isfinite(s.foundation_reaction(0.0))
    assert s.dissipation == 0.0
    assert abs(s.drag) < 1e-12
    data = json.loads(json.dumps(s.to_dict()))
    assert len(data["contact_zones"]) == 2
    assert len(data["punches"]) == 1
    assert data["punches"][0]["zone_loads"] == pytest.approx(
        [LOAD / 2, LOAD / 2], rel=1e-12
    )


def test_damped_trains_balance_energy() -> None:
    train = mp.solve_punches(
        [mp.Punch(R, LOAD, at=-1.5), mp.Punch(R, 0.003, at=1.5)],
        vstar=0.5,
        kw=1.0,
        damping=0.3,
    )
    assert train.drag > 0
    assert abs(train.dissipation - train.drag) < 1e-6 * train.drag


def test_the_error_estimate_bounds_a_coarse_solve() -> None:
    ref = mp.solve_punches(
        [mp.Punch(R, LOAD, at=-1.5), mp.Punch(R, LOAD, at=1.5)],
        vstar=0.5,
        kw=1.0,
        tol=1e-12,
    )
    for n in (8, 12, 16):
        coarse = mp.solve_punches(
            [mp.Punch(R, LOAD, at=-1.5), mp.Punch(R, LOAD, at=1.5)],
            vstar=0.5,
            kw=1.0,
            n=n,
        )
        err = max(
            abs(a - b)
            for za, zb in zip(coarse.contact_zones, ref.contact_zones, strict=True)
            for a, b in zip(za, zb, strict=True)
        )
        assert err <= coarse.error_estimate + 1e-13


@pytest.mark.parametrize(
    ("make", "name"),
    [
        (lambda: mp.Punch(mp.Flat(0.5), LOAD), "profile"),
        (lambda: mp.Punch(R, -1.0), "load"),
        (lambda: mp.Punch(R, LOAD, at=math.nan), "at"),
        (lambda: mp.Punch(R, LOAD, at="1"), "at"),
        (lambda: mp.solve_punches([], vstar=0.5, kw=1.0), "punches"),
        (lambda: mp.solve_punches([1.0], vstar=0.5, kw=1.0), "punches"),
        (
            lambda: mp.solve_punches(
                [mp.Punch(R, LOAD)], vstar=0.5, kw=1.0, friction=0.2
            ),
            "friction",
        ),
        (
            lambda: mp.solve_punches(
                [mp.Punch(R, LOAD, at=0.0), mp.Punch(R, LOAD, at=0.02)],
                vstar=0.5,
                kw=1.0,
            ),
            "punches",
        ),
        (
            lambda: mp.solve_punches(
                [mp.Punch(R, LOAD, at=0.0), mp.Punch(R, LOAD, at=3.0)],
                vstar=0.5,
                kw=1.0,
                n=7,
            ),
            "n",
        ),
    ],
)
def test_bad_input_names_the_parameter(make: object, name: str) -> None:
    with pytest.raises(mp.InvalidParameterError) as err:
        make()  # type: ignore[operator]
    assert err.value.parameter == name


def test_supercritical_trains_are_refused() -> None:
    with pytest.raises(mp.SupercriticalSpeedError):
        mp.solve_punches(
            [mp.Punch(R, LOAD, at=-1.5), mp.Punch(R, LOAD, at=1.5)],
            vstar=mp.critical_vstar(1.0),
            kw=1.0,
        )


# --------------------------------------------------------------------------
# Hard cases and fuzz


def test_a_damped_separated_contact_balances_energy() -> None:
    # Light dashpots at 0.99 V*_cr: the contact still separates (p < 0 in the
    # single one), now asymmetric; the dashpots take the drag's power.
    s = mp.solve(vstar=V99, kw=KW, radius=R, load=LOAD, damping=0.01)
    assert isinstance(s, mp.ZonedSolution)
    assert len(s.contact_zones) == 2
    assert s.valid
    assert s.drag > 0
    assert abs(s.dissipation - s.drag) < 1e-6 * s.drag


def test_punches_1000_h_apart() -> None:
    single = mp.solve(vstar=0.5, kw=1.0, radius=R, load=LOAD)
    train = mp.solve_punches(
        [mp.Punch(R, LOAD, at=-500.0), mp.Punch(R, LOAD, at=500.0)], vstar=0.5, kw=1.0
    )
    assert abs(train.contact_zones[1][1] - 500.0 - single.a) < 1e-9
    assert abs(train.punches[0].indentation - single.indentation) < 1e-9


def _check_train(s: mp.ZonedSolution) -> None:
    """Complementarity and equilibrium of a train, independently of the
    solver's own checks."""
    total = 0.0
    for p in s.punches:
        for (lo, hi), load in zip(p.contact_zones, p.zone_loads, strict=True):
            assert hi > lo
            assert load > 0
            x = np.linspace(lo, hi, 201)
            assert np.min(s.pressure(x)) >= -1e-10
            # The surface follows the punch: f - delta - v = 0 on the zone.
            inner = lo + (hi - lo) * np.linspace(0.05, 0.95, 9)
            gap = _gap(
                s, inner, np.asarray(p.profile.height(inner - p.at)), p.indentation
            )
            scale = max(abs(p.indentation), (hi - lo) ** 2 / 200.0)
            assert np.max(np.abs(gap)) < 1e-6 * scale
            total += _zone_integral(s, lo, hi)
    assert abs(total - 1.0) < 1e-9


def _fuzz_trains(draws: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    for _ in range(draws):
        kw = float(10 ** rng.uniform(-1.3, 1.0))
        vstar = float(rng.uniform(0.0, 0.95)) * mp.critical_vstar(kw)
        damping = float(rng.choice([0.0, 0.3]))
        k = int(rng.integers(2, 4))
        spacing = float(rng.uniform(1.5, 15.0))
        punches = [
            mp.Punch(
                float(rng.uniform(30.0, 200.0)),
                float(10 ** rng.uniform(-3.5, -2.3)),
                at=(i - (k - 1) / 2) * spacing,
            )
            for i in range(k)
        ]
        args = {"vstar": vstar, "kw": kw, "damping": damping}
        failure: mp.MovingPunchError | None = None
        try:
            s = mp.solve_punches(punches, **args)
        except (
            mp.InvalidParameterError,
            mp.UnphysicalContactError,
            mp.ConvergenceError,
        ) as exc:
            failure = exc
        if isinstance(failure, mp.InvalidParameterError):
            assert failure.parameter == "punches", (args, punches)  # too close
            continue
        if failure is not None:  # no contact set found: said so
            assert "zones" in str(failure) or "contact" in str(failure), failure
            continue
        assert isinstance(s, mp.ZonedSolution), (args, punches)
        assert s.valid
        assert math.isfinite(s.error_estimate)
        _check_train(s)


def test_fuzz_trains_12() -> None:
    _fuzz_trains(12, 15)


@pytest.mark.slow
def test_fuzz_trains_60() -> None:
    _fuzz_trains(60, 1515)


def test_stress_peaks_of_a_separated_contact_match_a_dense_scan(
    separated: mp.ZonedSolution,
) -> None:
    s = separated
    pk = s.stress_peaks()
    # A dense scan, finer near every zone end (sigma_x has square-root cusps
    # there), on both sides (the search covers x >= 0 of an even field).
    ends = [x for zone in s.contact_zones for x in zone]
    x = np.concatenate(
        [np.linspace(-pk.search_extent, pk.search_extent, 8001)]
        + [e + np.linspace(-0.02, 0.02, 401) for e in ends]
    )
    top = np.asarray(s.surface_stress(x))
    bottom = s.stress_field(x, [-1.0]).sigma_x[0]
    bound = pk.error_bound + 1e-12 * np.max(np.abs(top))
    # The reported extremes are the field's: no scanned value beats them by
    # more than the bound, and each is attained (within it) where reported.
    assert np.min(top) >= pk.top_compressive - bound
    assert np.max(top) <= pk.top_tensile + bound
    assert np.max(bottom) <= pk.bottom_tensile + bound
    assert s.surface_stress(pk.top_compressive_x) == pytest.approx(
        pk.top_compressive, abs=bound
    )
    assert s.surface_stress(pk.top_tensile_x) == pytest.approx(
        pk.top_tensile, abs=bound
    )


@pytest.mark.slow
def test_near_rayleigh_the_ripples_touch_the_punch() -> None:
    # 1e-6 below V*_R on a rigid base the single contact's surface rises
    # above the punch just outside it (tests/python/test_hard_cases.py):
    # the contact set is the main zone and two tiny zones where the ripple
    # touches, symmetric, each p >= 0, no penetration left.
    vr = mp.rayleigh_vstar(0.2)
    s = mp.solve(vstar=vr * (1 - 1e-6), kw=math.inf, radius=R, load=2e-4)
    assert isinstance(s, mp.ZonedSolution)
    assert len(s.contact_zones) == 3
    (a, b), (c, d), (e, f) = s.contact_zones
    assert abs(a + f) < 1e-9
    assert abs(b + e) < 1e-9
    assert abs(c + d) < 1e-9
    x = np.linspace(-3.0, 3.0, 3001)
    gap = _gap(s, x, x**2 / (2 * R), s.indentation)
    assert np.min(gap) > -1e-9 * d**2 / (2 * R)
    for lo, hi in s.contact_zones:
        assert np.min(s.pressure(np.linspace(lo, hi, 201))) >= -1e-12


def test_kernel_builds_count_the_zones_tables() -> None:
    mp.clear_kernel_cache()
    punches = [mp.Punch(R, LOAD, at=-2.0), mp.Punch(R, LOAD, at=2.0)]
    cold = mp.solve_punches(punches, vstar=0.45, kw=2.0)
    warm = mp.solve_punches(punches, vstar=0.45, kw=2.0)
    assert cold.kernel_builds >= 1
    assert warm.kernel_builds == 0


def test_a_load_sweep_through_separation_agrees_both_ways() -> None:
    # Up and down through the threshold (about 5.1e-4 here): the same
    # contact sets, whatever the kernel cache holds from the last point.
    loads = np.geomspace(3e-4, 3e-3, 7)

    def zones(load: float) -> tuple[tuple[float, float], ...]:
        return mp.solve(vstar=V99, kw=KW, radius=R, load=float(load)).contact_zones

    up = [zones(p) for p in loads]
    mp.clear_kernel_cache()
    down = [zones(p) for p in loads[::-1]][::-1]
    assert [len(z) for z in up] == [1, 1, 2, 2, 2, 2, 1]
    for a, b in zip(up, down, strict=True):
        assert len(a) == len(b)
        for (p, q), (r, t) in zip(a, b, strict=True):
            assert abs(p - r) < 1e-9
            assert abs(q - t) < 1e-9
