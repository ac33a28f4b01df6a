"""An independent second evaluation of viscoelastic sublayers in a stack.

``stack_reference`` is a NumPy/SciPy solver written from the problem
statement alone, without the project's solver sources; it extends
``viscoelastic_reference`` (one Zener layer on springs) to a stack of bonded
homogeneous sublayers, elastic or Zener, on Winkler springs or on an elastic
half-space. Its method and sources are in its docstring. These tests check:

1. The reference itself: two identical sublayers are the single-layer
   reference; a stack over a half-space of its own material is the
   half-plane (Hertz); the long- and short-wave limits of M1; the
   half-space's decaying modes; convergence in N and in the alpha grid.
2. The reference against movingpunch's ELASTIC stacks: elastic sublayers,
   and Zener sublayers at deborah 1e-12 (relaxed, mu_i) and 1e12
   (unrelaxed, ratio mu_i; an unrelaxed top by rescaling to its units).
3. Acceptance: movingpunch's viscoelastic stacks against the reference
   (these fail with InvalidParameterError until the feature exists).

Nothing here compares the project with itself.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import movingpunch as mp
import stack_reference as sr
import viscoelastic_reference as vref

# Acceptance cases of the brief. (thickness, mu, nu, rho, ratio, deborah)
CASE_A = sr.StackCase(
    layers=((0.4, 1.0, 0.25, 1.0, 3.0, 0.5), (0.6, 2.0, 0.3, 1.2, 1.0, 0.0)),
    base=("springs", 2.0),
    vstar=0.3,
    radius=5.0,
    load=0.05,
)
CASE_B = sr.StackCase(
    layers=((0.3, 1.0, 0.25, 1.0, 1.0, 0.0), (0.7, 0.5, 0.3, 0.8, 4.0, 0.3)),
    base=("half_space", 3.0, 0.25, 1.5),
    vstar=0.2,
    radius=5.0,
    load=0.05,
)
CASE_C = dataclasses.replace(CASE_B, vstar=0.0)
# Elastic top over a viscoelastic bottom sublayer, on springs.
CASE_D = sr.StackCase(
    layers=((0.5, 1.0, 0.25, 1.0, 1.0, 0.0), (0.5, 1.5, 0.3, 1.0, 2.0, 0.4)),
    base=("springs", 3.0),
    vstar=0.2,
    radius=5.0,
    load=0.05,
)
CASES = {"A": CASE_A, "B": CASE_B, "C": CASE_C, "D": CASE_D}

TOL = 1e-8  # acceptance: movingpunch's default tolerance on the ends
ELASTIC_TOL = 1e-9  # the reference against the project's elastic stacks


def with_deborah(case: sr.StackCase, index: int, deborah: float) -> sr.StackCase:
    layers = list(case.layers)
    layers[index] = (*layers[index][:5], deborah)
    return dataclasses.replace(case, layers=tuple(layers))


def project_layers(case: sr.StackCase, limit: str | None = None) -> list[mp.Layer]:
    """The project's sublayers: Zener ones as Zener, or (limit "relaxed" /
    "unrelaxed") as the elastic sublayer of mu_i / ratio_i mu_i."""
    out = []
    for thickness, mu, nu, rho, ratio, deborah in case.layers:
        if ratio == 1.0 or limit == "relaxed":
            out.append(mp.Layer(thickness, mu=mu, nu=nu, rho=rho))
        elif limit == "unrelaxed":
            out.append(mp.Layer(thickness, mu=ratio * mu, nu=nu, rho=rho))
        else:
            zener = mp.Zener(ratio, deborah=deborah)
            out.append(mp.Layer(thickness, mu=mu, nu=nu, rho=rho, viscoelastic=zener))
    return out


def project_base(case: sr.StackCase, scale: float = 1.0) -> mp.Winkler | mp.HalfSpace:
    if case.base[0] == "springs":
        return mp.Winkler(kw=case.base[1] / scale)
    _, mu_b, nu_b, rho_b = case.base
    return mp.HalfSpace(mu=mu_b / scale, nu=nu_b, rho=rho_b, interface="bonded")


def project_ends(sol: mp.ContactSolution) -> tuple[float, float]:
    left, right = sol.contact_interval
    return float(left), float(right)


def assert_ends_agree(
    mine: tuple[float, float], theirs: tuple[float, float], tol: float, what: str
) -> None:
    for name, m, t in zip(("left", "right"), mine, theirs, strict=True):
        assert abs(m - t) <= tol, f"{what}: {name} reference {m!r} project {t!r}"


@pytest.fixture(scope="module")
def results() -> dict[str, vref.Result]:
    """The reference's solutions of the acceptance cases, at the defaults."""
    return {name: sr.solve_result(case) for name, case in CASES.items()}


def ends(r: vref.Result) -> tuple[float, float]:
    return r.centre - r.half_width, r.centre + r.half_width


# --------------------------------------------------------------------------
# 1. The reference's own checks
# --------------------------------------------------------------------------

SINGLE = vref.Case(
    vstar=0.3, nu=0.25, kw=2.0, radius=5.0, load=0.05, ratio=3.0, deborah=0.5
)
TWO_IDENTICAL = sr.StackCase(
    layers=((0.4, 1.0, 0.25, 1.0, 3.0, 0.5), (0.6, 1.0, 0.25, 1.0, 3.0, 0.5)),
    base=("springs", 2.0),
    vstar=0.3,
    radius=5.0,
    load=0.05,
)


def test_two_identical_sublayers_are_the_single_layer() -> None:
    """A Zener layer cut in two (0.4 + 0.6) is the single-layer reference's
    layer: M1 (measured 1e-12 relative) and the ends (measured 1.5e-12)."""
    alpha = np.array([1e-6, 0.01, 0.3, 1.0, 3.7, 10.0, 30.0, 59.9, 75.0])
    mine = sr.surface_response(alpha, TWO_IDENTICAL)
    single = vref.surface_response(alpha, SINGLE)
    assert np.max(np.abs(mine / single - 1)) < 5e-12
    r1 = sr.solve_result(TWO_IDENTICAL)
    r0 = vref.solve(SINGLE)
    assert abs(r1.a - r0.a) < 5e-12
    assert abs(r1.b - r0.b) < 5e-12
    assert abs(r1.indentation - r0.indentation) < 5e-12  # springs: absolute


@pytest.mark.parametrize("vstar", [0.0, 0.3])
def test_stack_on_its_own_half_space_is_the_hertz_half_plane(vstar: float) -> None:
    """Two sublayers of one elastic material over a half-space of the same
    material are the half-plane: M1 = phi1(vstar, nu) at every wavenumber
    and the contact is Hertz's, w^2 = 2 R P phi1 / pi, centred. This checks
    the half-space modes and the M0 log-kernel split."""
    nu = 0.3
    case = sr.StackCase(
        layers=((0.35, 1.0, nu, 1.0, 1.0, 0.0), (0.65, 1.0, nu, 1.0, 1.0, 0.0)),
        base=("half_space", 1.0, nu, 1.0),
        vstar=vstar,
        radius=4.0,
        load=0.07,
    )
    phi = float(np.real(vref.phi1(vstar, nu)))
    alpha = np.array([1e-8, 0.05, 1.0, 7.0, 40.0, 102.0])
    assert np.max(np.abs(sr.stack_response(alpha, case) - phi)) < 1e-13
    left, right = sr.solve(case, n=16)
    w = math.sqrt(2 * case.radius * case.load * phi / math.pi)
    assert abs(right - w) < 1e-12
    assert abs(left + w) < 1e-12


def test_half_space_modes_are_the_decaying_ones() -> None:
    """B(s) has the eigenvalues +-nT, +-nL; the base basis spans the
    eigenvectors of +nT and +nL (e^{a lambda y} decays as y -> -inf)."""
    s, nu = 0.15, 0.25
    c2 = 2 * (1 - nu) / (1 - 2 * nu)
    b = vref.layer_matrix(s, nu).real
    lam = np.sort(np.linalg.eigvals(b).real)
    nt, nl = math.sqrt(1 - s), math.sqrt(1 - s / c2)
    assert np.allclose(lam, sorted([-nt, -nl, nt, nl]), atol=1e-13)
    case = sr.StackCase(
        layers=((1.0, 1.0, nu, 1.0, 1.0, 0.0),),
        base=("half_space", 1.0, nu, 1.0),
        vstar=s,
        radius=1.0,
        load=1.0,
    )
    basis = sr.base_basis(np.array([1.0]), case)[0]
    # B basis = basis C with eigenvalues of C = {nT, nL}: an invariant subspace
    coef, *_ = np.linalg.lstsq(basis, b @ basis, rcond=None)
    assert np.allclose(b @ basis, basis @ coef, atol=1e-13)
    assert np.allclose(np.sort(np.linalg.eigvals(coef).real), sorted([nt, nl]))


def long_wave_springs(case: sr.StackCase) -> float:
    """lim M1/a on springs, with relaxed moduli: the sublayers share eps_x,
    sigma_y = -1 in each, and sum d_i (sigma_x,i - rho_i vstar eps_x) = 0."""
    num = den = 0.0
    for d, mu, nu, rho, _, _ in case.layers:
        lam = 2 * nu / (1 - 2 * nu)
        num += d * lam / (lam + 2)
        den += d * (mu * ((lam + 2) - lam**2 / (lam + 2)) - rho * case.vstar)
    eps_x = num / den
    compression = 0.0
    for d, mu, nu, _, _, _ in case.layers:
        lam = 2 * nu / (1 - 2 * nu)
        compression += d * (1 + lam * mu * eps_x) / ((lam + 2) * mu)
    return 1 / case.base[1] + compression


def test_long_wave_limits() -> None:
    """Springs: M1/a -> the membrane formula (elastic exactly, Zener relaxed
    up to O(a)); half-space: M1(0) = phi1(vstar rho_b/mu_b, nu_b)/mu_b, and
    G(a)/a = (M1 - M0)/a stays finite (M1 analytic at 0+)."""
    elastic = sr.StackCase(
        layers=(
            (0.3, 1.0, 0.25, 1.0, 1.0, 0.0),
            (0.5, 2.0, 0.3, 1.2, 1.0, 0.0),
            (0.2, 0.7, 0.35, 0.9, 1.0, 0.0),
        ),
        base=("springs", 1.5),
        vstar=0.25,
        radius=1.0,
        load=1.0,
    )
    small = 1e-6
    got = sr.stack_response([small], elastic)[0] / small
    assert abs(got - long_wave_springs(elastic)) < 1e-9 * long_wave_springs(elastic)
    for case in (CASE_A, CASE_D):
        got = sr.stack_response([small], case)[0] / small
        assert abs(got - long_wave_springs(case)) < 1e-5
    for case in (CASE_B, CASE_C):
        m0 = sr.long_wave_constant(case)
        _, mu_b, nu_b, rho_b = case.base
        assert m0 == pytest.approx(
            float(np.real(vref.phi1(case.vstar * rho_b / mu_b, nu_b))) / mu_b, 1e-15
        )
        tiny = np.array([1e-9, 1e-7, 1e-5])
        slope = (sr.stack_response(tiny, case) - m0) / tiny
        assert abs(sr.stack_response([1e-11], case)[0] - m0) < 1e-11
        assert np.max(np.abs(slope - slope[0])) < 1e-4 * abs(slope[0])


@pytest.mark.parametrize("name", ["A", "B", "D"])
def test_short_wave_limit_is_the_top_half_plane(name: str) -> None:
    """Short waves see only the top sublayer: M1 = phi1(vstar/m_1)/m_1."""
    case = CASES[name]
    start = sr.half_plane_from(case)
    alpha = np.array([0.6, 0.8, 1.0]) * start
    top = vref.half_plane_response(alpha, sr.top_case(case))
    assert np.max(np.abs(sr.stack_response(alpha, case) / top - 1)) < 1e-13


@pytest.mark.parametrize("name", ["A", "B"])
def test_reference_converges(name: str, results: dict[str, vref.Result]) -> None:
    """N - 4 and N + 4 around the default, and a second alpha grid (wider
    low panels of 30 points, 14-point tail panels, other split and Laguerre
    order): the ends move by < 1e-10 (measured: A ~1e-11, B ~3e-15)."""
    case = CASES[name]
    base = ends(results[name])
    n = sr.default_n(case)
    split = 500.0 if name == "A" else 2 * sr.half_plane_from(case)
    grid = sr.alpha_grid(
        case, split=split, low_points=30, width=2.0, tail_points=14, ray_points=30
    )
    for alt in (
        sr.solve(case, n=n - 4),
        sr.solve(case, n=n + 4),
        sr.solve(case, sgrid=grid),
    ):
        assert abs(alt[0] - base[0]) < 1e-10
        assert abs(alt[1] - base[1]) < 1e-10


@pytest.mark.parametrize("name", ["A", "B", "C", "D"])
def test_reference_satisfies_its_equations(
    name: str, results: dict[str, vref.Result]
) -> None:
    """The load, p >= 0 inside, coefficients decayed to round-off, and the
    dissipation: the contact shifts forward and the drag is positive."""
    case, r = CASES[name], results[name]
    assert abs(r.half_width * math.pi / 2 * r.coefficients[0] - case.load) < 1e-11
    x = r.centre + r.half_width * np.linspace(-0.98, 0.98, 15)
    assert np.all(r.pressure(x) > 0)
    assert np.max(np.abs(r.coefficients[-3:])) < 1e-11
    assert r.centre > 1e-3
    assert r.drag > 1e-4


# --------------------------------------------------------------------------
# 2. The reference against the project's elastic stacks
# --------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "index", "deborah", "limit"),
    [
        ("A", 0, 1e-12, "relaxed"),
        ("B", 1, 1e-12, "relaxed"),
        ("B", 1, 1e12, "unrelaxed"),
        ("C", 1, 1e12, "unrelaxed"),
        ("D", 1, 1e-12, "relaxed"),
        ("D", 1, 1e12, "unrelaxed"),
        ("B", 1, 1.0, "elastic"),  # ratio 1: the sublayer is elastic
    ],
)
def test_elastic_limits_match_the_project(
    name: str, index: int, deborah: float, limit: str
) -> None:
    """A Zener sublayer at deborah 1e-12 is the elastic one of mu_i, at 1e12
    the one of ratio mu_i (measured agreement 1e-12 to 1e-14)."""
    case = with_deborah(CASES[name], index, deborah)
    if limit == "elastic":
        layers = list(case.layers)
        layers[index] = (*layers[index][:4], 1.0, 0.0)
        case = dataclasses.replace(case, layers=tuple(layers))
        limit = "relaxed"
    mine = sr.solve(case)
    sol = mp.solve(
        vstar=case.vstar,
        radius=case.radius,
        load=case.load,
        layers=project_layers(case, limit),
        base=project_base(case),
    )
    assert_ends_agree(mine, project_ends(sol), ELASTIC_TOL, f"{name} {deborah}")


def test_unrelaxed_top_matches_the_project_in_its_units() -> None:
    """Case A at deborah 1e12: the top is elastic with mu = 3. In its units
    (moduli, vstar, kw, P over 3; lengths unchanged) it is the project's
    elastic stack (measured 3e-12)."""
    case = with_deborah(CASE_A, 0, 1e12)
    ratio = case.layers[0][4]
    mine = sr.solve(case)
    layers = [
        mp.Layer(d, mu=(ratio if i == 0 else 1.0) * mu / ratio, nu=nu, rho=rho)
        for i, (d, mu, nu, rho, _, _) in enumerate(case.layers)
    ]
    sol = mp.solve(
        vstar=case.vstar / ratio,
        radius=case.radius,
        load=case.load / ratio,
        layers=layers,
        base=project_base(case, scale=ratio),
    )
    assert_ends_agree(mine, project_ends(sol), ELASTIC_TOL, "unrelaxed top")


def test_elastic_stack_on_springs_matches_the_project() -> None:
    """The brief's elastic example (0.4 over 0.6 of mu 2, nu 0.3, rho 1.2 on
    kw 2, vstar 0.3), with a third sublayer as well."""
    case = sr.StackCase(
        layers=(
            (0.4, 1.0, 0.25, 1.0, 1.0, 0.0),
            (0.35, 2.0, 0.3, 1.2, 1.0, 0.0),
            (0.25, 0.8, 0.2, 0.9, 1.0, 0.0),
        ),
        base=("springs", 2.0),
        vstar=0.3,
        radius=5.0,
        load=0.05,
    )
    mine = sr.solve(case)
    sol = mp.solve(
        vstar=case.vstar,
        radius=case.radius,
        load=case.load,
        layers=project_layers(case),
        base=project_base(case),
    )
    assert_ends_agree(mine, project_ends(sol), ELASTIC_TOL, "three elastic")


# --------------------------------------------------------------------------
# 3. Acceptance: the project's viscoelastic stacks against the reference
# --------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["A", "B", "C", "D"])
def test_viscoelastic_stack_matches_the_reference(
    name: str, results: dict[str, vref.Result]
) -> None:
    """A: Zener top over elastic on springs; B: elastic top over a Zener
    sublayer on a bonded half-space at vstar 0.2; C: B at vstar 0; D:
    elastic top over a Zener bottom sublayer on springs. Both ends to 1e-8."""
    case = CASES[name]
    sol = mp.solve(
        vstar=case.vstar,
        radius=case.radius,
        load=case.load,
        layers=project_layers(case),
        base=project_base(case),
    )
    assert_ends_agree(ends(results[name]), project_ends(sol), TOL, f"case {name}")
