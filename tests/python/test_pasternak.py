"""The two-parameter (Pasternak) foundation, kp = k_p/(mu h): the base
condition sigma_y(x, -h) = kw v - kp v'', the stiffness kw + kp (alpha h)^2
per wavenumber (docs/theory.md section 12).

Anchors, all written here independently of the code: the static layer's
M1(t) from an Airy stress function solved in 40-digit decimal arithmetic; a
Gauss-Chebyshev solve written from scratch on the kernel from that M1; the
free-wave 4 x 4 determinant in NumPy minimised by SciPy; the membrane's
sinking P/(2 sqrt(kw kp)); the base condition itself by finite differences.
"""

from __future__ import annotations

import itertools
import json
import math
from decimal import Decimal, localcontext

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

import movingpunch as mp
from movingpunch import _core, cli
from movingpunch.accuracy import accuracy_report
from movingpunch.asymmetric import damped_layer_response
from movingpunch.errors import InvalidParameterError, SupercriticalSpeedError
from movingpunch.params import SPECS, range_text
from movingpunch.scene import Scene, SceneError, bundled_scenes
from movingpunch.tui import create_app
from movingpunch.tui.widgets import CurvePlot, ParamsPanel
from tui_pilot import screen_of, settle, sync, type_into

CASE = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002}

# -- independent anchors --------------------------------------------------------


def _decimal_solve(a: list[list[Decimal]], b: list[Decimal]) -> list[Decimal]:
    """Gaussian elimination with partial pivoting."""
    n = len(b)
    a = [row[:] for row in a]
    b = b[:]
    for i in range(n):
        p = max(range(i, n), key=lambda r: abs(a[r][i]))
        a[i], a[p] = a[p], a[i]
        b[i], b[p] = b[p], b[i]
        for r in range(i + 1, n):
            f = a[r][i] / a[i][i]
            for c in range(i, n):
                a[r][c] -= f * a[i][c]
            b[r] -= f * b[i]
    x = [Decimal(0)] * n
    for i in reversed(range(n)):
        x[i] = (b[i] - sum(a[i][c] * x[c] for c in range(i + 1, n))) / a[i][i]
    return x


def static_m1(t: float, kw: float, kp: float, nu: float) -> float:
    """M1 = -alpha v(alpha, 0)/p of a static layer (h = mu = 1) on the base
    sigma_y = (kw + kp t^2) v, from the Airy function phi = F(y) cos(t x),
    F = (A + B y) e^{t y} + (C + D y) e^{-t y}: sigma_x = F'', sigma_y =
    -t^2 F, tau = t F'; u = U sin(t x), U = ((1 - nu) F'' + nu t^2 F)/(2 t);
    v = V cos(t x), V = (U' - tau/sin)/t. Top: sigma_y = -cos(t x), tau = 0;
    bottom: tau = 0, sigma_y = (kw + kp t^2) v. 40 digits."""
    with localcontext() as ctx:
        ctx.prec = 40
        T, w, p, n = (Decimal(repr(float(v))) for v in (t, kw, kp, nu))
        stiff = w + p * T * T
        basis = [(T, 0), (T, 1), (-T, 0), (-T, 1)]

        def d(s: Decimal, k: int, y: Decimal, order: int) -> Decimal:
            e = (s * y).exp()
            if k:
                return (s**order * y + order * s ** (order - 1)) * e
            return s**order * e

        def vv(s: Decimal, k: int, y: Decimal) -> Decimal:
            third = (1 - n) * d(s, k, y, 3) + n * T * T * d(s, k, y, 1)
            return third / (2 * T * T) - d(s, k, y, 1)

        zero, bottom = Decimal(0), Decimal(-1)
        rows = [
            [d(s, k, zero, 0) for s, k in basis],
            [d(s, k, zero, 1) for s, k in basis],
            [d(s, k, bottom, 1) for s, k in basis],
            [-T * T * d(s, k, bottom, 0) - stiff * vv(s, k, bottom) for s, k in basis],
        ]
        c = _decimal_solve(rows, [1 / (T * T), zero, zero, zero])
        return float(
            -T * sum(ci * vv(s, k, zero) for ci, (s, k) in zip(c, basis, strict=True))
        )


def reference_width(kw: float, kp: float, nu: float, lam: float, n: int = 32) -> float:
    """a/h at V* = 0 by a Gauss-Chebyshev solve written from theory.md
    section 5: the kernel k1(u) = int (M1 - phi1)/phi1 sin(alpha u) by
    composite Gauss-Legendre on [0, 24] (panels down to alpha = 0.01) with
    M1 from ``static_m1``; all N + 1 - 1 equations, no folding."""
    phi1 = 1.0 - nu
    edges = np.concatenate(
        [[0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5], np.arange(1.0, 24.01, 0.5)]
    )
    x, w = np.polynomial.legendre.leggauss(16)
    alpha = np.concatenate(
        [0.5 * (b - a) * x + 0.5 * (a + b) for a, b in itertools.pairwise(edges)]
    )
    weight = np.concatenate([0.5 * (b - a) * w for a, b in itertools.pairwise(edges)])
    m1 = np.array([static_m1(t, kw, kp, nu) for t in alpha])
    f = weight * (m1 - phi1) / phi1
    i = np.arange(1, n + 1)
    r = np.cos(i * np.pi / (n + 1))
    wr = (1 - r**2) / (n + 1)
    k = np.arange(1, n + 2)
    s = np.delete(np.cos(np.pi * (2 * k - 1) / (2 * (n + 1))), n // 2)

    def log_load_error(log_a: float) -> float:
        a = math.exp(log_a)
        dist = r[None, :] - s[:, None]
        k1 = np.sin(np.multiply.outer(a * dist, alpha)) @ f
        g = np.linalg.solve(wr[None, :] * (1.0 / dist + a * k1), s)
        return math.log(-math.pi * a * a * float(wr @ g) / phi1 / lam)

    return math.exp(brentq(log_load_error, math.log(0.05), math.log(3.0), xtol=1e-14))


def _c2(nu: float) -> float:
    kappa = 3.0 - 4.0 * nu
    return (kappa + 1.0) / (kappa - 1.0)


def free_wave_det(s: float, t: float, kw: float, kp: float, nu: float) -> float:
    """The 4 x 4 free-wave determinant (traction-free top; bottom tau = 0,
    sigma_y = (kw + kp t^2) v) on the modes e^{m t y}, m = +-nT (W = -U/m),
    +-nL (W = -m U), each scaled to 1 at the face it decays from."""
    c2 = _c2(nu)
    nt, nl = math.sqrt(1.0 - s), math.sqrt(1.0 - s / c2)
    stiff = kw + kp * t * t
    cols = []
    for m, shear in ((nt, True), (-nt, True), (nl, False), (-nl, False)):
        w = -1.0 / m if shear else -m
        top, bot = (1.0, math.exp(-m * t)) if m > 0 else (math.exp(m * t), 1.0)
        sig = t * ((c2 - 2.0) * (1.0 + m * w) + 2.0 * m * w)
        tau = t * (m - w)
        cols.append([tau * top, sig * top, tau * bot, (sig - stiff * w) * bot])
    return float(np.linalg.det(np.array(cols).T))


def rayleigh(nu: float) -> float:
    c2 = _c2(nu)
    return brentq(
        lambda s: (2 - s) ** 2 - 4 * math.sqrt(1 - s) * math.sqrt(1 - s / c2),
        1e-6,
        1 - 1e-12,
        xtol=1e-16,
    )


def first_wave(t: float, kw: float, kp: float, nu: float) -> float:
    """Lowest V* < V*_R with a free wave of wavenumber t (V*_R if none)."""
    vr = rayleigh(nu)
    grid = vr * (1 - 1e-12) * 0.5 * (1 - np.cos(np.pi * np.arange(1, 401) / 400))
    grid[0] = 1e-9
    values = [free_wave_det(s, t, kw, kp, nu) for s in grid]
    for j in range(1, len(grid)):
        if np.sign(values[j]) != np.sign(values[j - 1]):
            return brentq(
                lambda s: free_wave_det(s, t, kw, kp, nu),
                grid[j - 1],
                grid[j],
                xtol=1e-15,
                rtol=1e-15,
            )
    return vr


def reference_critical(kw: float, kp: float, nu: float) -> float:
    logs = np.linspace(math.log(0.05), math.log(30.0), 36)
    speeds = [first_wave(math.exp(x), kw, kp, nu) for x in logs]
    j = int(np.argmin(speeds))
    lo, hi = logs[max(j - 1, 0)], logs[min(j + 1, len(logs) - 1)]
    found = minimize_scalar(
        lambda x: first_wave(math.exp(x), kw, kp, nu),
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": 1e-9},
    )
    return float(found.fun)


# -- kp = 0 is Winkler ------------------------------------------------------------


@pytest.mark.parametrize("damping", [0.0, 0.3])
def test_zero_kp_is_winkler_bit_for_bit(damping: float) -> None:
    winkler = mp.solve(**CASE, damping=damping)
    pasternak = mp.solve(**CASE, damping=damping, kp=0.0)
    assert (winkler.kp, pasternak.kp) == (0.0, 0.0)
    assert pasternak.contact_interval == winkler.contact_interval
    assert pasternak.p0 == winkler.p0
    assert pasternak.indentation == winkler.indentation
    assert pasternak.critical_vstar == winkler.critical_vstar
    xs = np.linspace(-1.0, 1.0, 7)
    ys = np.array([-1.0, -0.5, -0.1])
    assert np.array_equal(pasternak.surface_stress(xs), winkler.surface_stress(xs))
    a, b = pasternak.stress_field(xs, ys), winkler.stress_field(xs, ys)
    for name in ("sigma_x", "sigma_y", "tau_xy"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert np.array_equal(
        pasternak.foundation_reaction(xs), winkler.foundation_reaction(xs)
    )
    assert pasternak.to_dict()["kp"] == 0.0
    # Same cache behaviour: kp = 0 reuses the Winkler table.
    assert pasternak.kernel_builds == 0


def test_winkler_path_reports_kp_in_every_result() -> None:
    s = mp.solve(**CASE, kp=0.25)
    d = mp.solve(**CASE, kp=0.25, damping=0.1)
    assert s.kp == d.kp == 0.25
    assert s.to_dict()["kp"] == d.to_dict()["kp"] == 0.25
    assert s.critical_vstar == d.critical_vstar == mp.critical_vstar(1.0, 0.2, 0.25)


# -- the layer response against the Airy closed form -----------------------------------


def test_reference_reproduces_the_rigid_base_closed_form() -> None:
    # The reference's own check: kw -> inf gives (1 - nu)(cosh 2t - 1)/(sinh 2t + 2t).
    for t in (0.3, 1.3, 4.0):
        want = 0.8 * (math.cosh(2 * t) - 1) / (math.sinh(2 * t) + 2 * t)
        assert static_m1(t, 1e200, 0.0, 0.2) == pytest.approx(want, rel=1e-14)


@pytest.mark.parametrize(
    ("kw", "kp"), [(0.1, 0.2), (1.0, 3.0), (1e-3, 1e-2), (10.0, 1e4)]
)
def test_static_m1_matches_the_airy_closed_form(kw: float, kp: float) -> None:
    ts = [1e-3, 0.01, 0.1, 0.3, 0.49, 0.5, 0.51, 1.0, 2.5, 7.0, 15.0]
    for method in ("auto", "modal", "transfer"):
        pts = [t for t in ts if method != "transfer" or t <= 4.0]
        m1, _ = mp.layer_response(np.array(pts), vstar=0.0, kw=kw, kp=kp, method=method)
        want = np.array([static_m1(t, kw, kp, 0.2) for t in pts])
        np.testing.assert_allclose(m1, want, rtol=1e-12, err_msg=method)
    # The damped model with damping 0 is the same layer.
    got = damped_layer_response(1.7, vstar=0.0, kw=kw, damping=0.0, kp=kp)[0]
    assert got.real == pytest.approx(static_m1(1.7, kw, kp, 0.2), rel=1e-12)


def test_small_t_limit_is_springs_plus_squeeze() -> None:
    # M1 ~ t [1/(kw + kp t^2) + (1 - nu)/2] while t^2 << 1: kp enters at O(t^3).
    t, kw, kp = 1e-4, 0.5, 2.0
    m1, _ = mp.layer_response(t, vstar=0.0, kw=kw, kp=kp)
    assert m1 == pytest.approx(t * (1 / (kw + kp * t * t) + 0.4), rel=1e-6)


@pytest.mark.parametrize(("kw", "kp"), [(0.1, 0.2), (1.0, 100.0)])
def test_static_width_matches_an_independent_solve(kw: float, kp: float) -> None:
    want = reference_width(kw, kp, 0.2, 100.0 * 0.002)
    got = mp.solve(vstar=0.0, kw=kw, kp=kp, radius=100.0, load=0.002, tol=1e-12)
    assert got.a == pytest.approx(want, rel=1e-10)
    # kp stiffens the base: narrower than springs alone, wider than rigid.
    springs = mp.solve(vstar=0.0, kw=kw, radius=100.0, load=0.002).a
    rigid = mp.solve(vstar=0.0, kw=math.inf, radius=100.0, load=0.002).a
    assert rigid < got.a < springs


# -- the critical speed --------------------------------------------------------------


@pytest.mark.parametrize(
    ("kw", "kp"), [(1.0, 0.1), (0.1, 0.3), (10.0, 0.1), (1e-3, 0.01), (0.3, 1e-6)]
)
def test_critical_speed_matches_the_free_wave_determinant(kw: float, kp: float) -> None:
    want = reference_critical(kw, kp, 0.2)
    assert mp.critical_vstar(kw, 0.2, kp) == pytest.approx(want, abs=1e-8)
    assert math.isfinite(mp.critical_wavenumber(kw, 0.2, kp))


def test_critical_speed_grows_with_kp() -> None:
    kps = [0.0, 1e-12, 1e-6, 1e-3, 0.01, 0.03, 0.1, 0.2, 0.4, 0.7, 1.0, 3.0, 1e3, 1e12]
    for nu in (0.0, 0.2, 0.45):
        vr = mp.rayleigh_vstar(nu)
        for kw in (1e-12, 1e-4, 0.01, 0.1, 1.0, 10.0, 100.0, math.inf):
            v = [mp.critical_vstar(kw, nu, kp) for kp in kps]
            assert all(b >= a for a, b in itertools.pairwise(v)), (nu, kw, v)
            assert all(x <= vr for x in v)
            # Stiff enough, no free wave is slower than the Rayleigh wave.
            assert v[-1] == vr
            assert mp.critical_wavenumber(kw, nu, 1e3) == math.inf
    # On a soft foundation the shear layer lifts V*_cr by about kp (its
    # membrane tension: the phase speed of long waves gains kp).
    assert mp.critical_vstar(1e-8, 0.2, 0.05) == pytest.approx(
        mp.critical_vstar(1e-8, 0.2) + 0.05, rel=0.05
    )


def test_speed_at_the_pasternak_critical_speed_is_refused_naming_kp() -> None:
    vcr = mp.critical_vstar(1.0, 0.2, 0.2)
    assert vcr > mp.critical_vstar(1.0, 0.2)
    with pytest.raises(SupercriticalSpeedError) as info:
        mp.solve(**{**CASE, "vstar": vcr}, kp=0.2)
    assert "kp = 0.2" in str(info.value)
    assert info.value.critical_vstar == vcr
    assert info.value.parameter == "vstar"
    # Between the Winkler and the Pasternak critical speeds it solves.
    s = mp.solve(**{**CASE, "vstar": 0.5 * (vcr + mp.critical_vstar(1.0, 0.2))}, kp=0.2)
    assert s.valid
    assert s.critical_vstar == vcr


# -- bad input -----------------------------------------------------------------------

BAD = [math.nan, math.inf, -math.inf, -1.0, -1e-300, 2e12, "0.2", None, True, 1j]


@pytest.mark.parametrize("value", BAD, ids=repr)
def test_bad_kp_is_refused_naming_kp(value: object) -> None:
    calls = [
        lambda: mp.solve(**CASE, kp=value),  # type: ignore[arg-type]
        lambda: mp.solve(**CASE, damping=0.1, kp=value),  # type: ignore[arg-type]
        lambda: mp.critical_vstar(1.0, 0.2, value),  # type: ignore[arg-type]
        lambda: mp.critical_wavenumber(1.0, 0.2, value),  # type: ignore[arg-type]
        lambda: mp.layer_response(1.0, vstar=0.1, kw=1.0, kp=value),  # type: ignore[arg-type]
        lambda: damped_layer_response(1.0, vstar=0.1, kw=1.0, damping=0.1, kp=value),  # type: ignore[arg-type]
    ]
    for call in calls:
        with pytest.raises(InvalidParameterError) as info:
            call()
        assert info.value.parameter == "kp"
        assert info.value.allowed == range_text("kp")
        assert str(info.value).startswith("kp")
        assert range_text("kp") in str(info.value)


def test_core_refuses_what_the_table_refuses() -> None:
    spec = SPECS["kp"]
    probes = [0.0, -0.0, 1e-300, -1e-300, 1e12, math.nextafter(1e12, math.inf)]
    for x in [*probes, math.nan, math.inf]:
        if spec.contains(x):
            assert _core.critical_speed(1.0, 0.2, x)[0] > 0.0
        else:
            with pytest.raises(InvalidParameterError) as info:
                _core.critical_speed(1.0, 0.2, x)
            assert info.value.parameter == "kp"


# -- the base condition, equilibrium, the membrane ------------------------------


def test_base_condition_and_equilibrium() -> None:
    kw, kp = 1.0, 0.3
    s = mp.solve(**{**CASE, "kp": kp}, tol=1e-10)
    xs = np.linspace(-3.0, 3.0, 25)
    step = 0.02
    v = [s.displacement(xs + k * step, -1.0) for k in (-2, -1, 0, 1, 2)]
    vxx = (-v[0] + 16 * v[1] - 30 * v[2] + 16 * v[3] - v[4]) / (12 * step * step)
    # sigma_y(x, -h) = kw v - kp v'', i.e. reaction = -(kw v - kp v'')/load.
    want = -(kw * v[2] - kp * vxx) / CASE["load"]
    reaction = s.foundation_reaction(xs)
    assert np.max(np.abs(reaction - want)) < 1e-6 * np.max(np.abs(reaction))
    # The kp term integrates to zero: the base still carries the load.
    assert abs(float(np.max(np.abs(kp * vxx)))) > 1e-2 * abs(float(np.max(kw * v[2])))
    x = np.linspace(-60.0, 60.0, 24001)
    assert np.trapezoid(s.foundation_reaction(x), x) == pytest.approx(1.0, abs=1e-8)


@pytest.mark.parametrize("kw", [1.0, 0.01])
def test_indentation_gains_the_membrane_sinking(kw: float) -> None:
    # kp >> kw: the base is a membrane on springs under the (nearly point)
    # load, sinking P/(2 sqrt(kw kp)) beside a layer on a rigid base; the
    # rest is O(sqrt(kw/kp)) relative.
    rigid = mp.solve(**{**CASE, "kw": math.inf})
    for kp in (1e6, 1e10):
        s = mp.solve(**{**CASE, "kw": kw, "kp": kp})
        sinking = CASE["load"] / (2.0 * math.sqrt(kw * kp))
        ratio = (s.indentation - rigid.indentation) / sinking
        assert ratio == pytest.approx(1.0, abs=5.0 * math.sqrt(kw / kp) + 1e-6)
        assert s.a == pytest.approx(rigid.a, rel=1e-4)


def test_damped_with_vanishing_damping_is_the_undamped_pasternak() -> None:
    s = mp.solve(**CASE, kp=0.3)
    d = mp.solve(**CASE, kp=0.3, damping=1e-9)
    assert d.a == pytest.approx(s.a, rel=1e-6)
    assert d.contact_interval[0] == pytest.approx(-s.a, rel=1e-6)
    assert d.indentation == pytest.approx(s.indentation, rel=1e-6)


# -- the bundled scene, scenes, the CLI, the TUI --------------------------------------


def test_bundled_pasternak_scene_matches_the_api_and_the_paper() -> None:
    assert "pasternak" in bundled_scenes()
    scene = Scene.bundled("pasternak")
    assert scene.sweep is not None
    assert scene.vary is not None
    assert scene.sweep.param == "kp"
    kps = scene.sweep.values
    result = scene.run()
    data = result.sweep.data
    for i, vstar in enumerate(scene.vary.values):
        for j, kp in enumerate(kps):
            s = mp.solve(vstar=vstar, kw=1.0, radius=100.0, load=0.002, kp=kp)
            assert data["a"][i, j] == pytest.approx(s.a, abs=1e-12)
            assert data["p0"][i, j] == pytest.approx(s.p0, rel=1e-10)
            assert data["critical_vstar"][i, j] == mp.critical_vstar(1.0, 0.2, kp)
        # The shear layer narrows the contact, towards the rigid base's.
        assert all(b < a for a, b in itertools.pairwise(data["a"][i]))
        rigid = mp.solve(vstar=vstar, kw=math.inf, radius=100.0, load=0.002).a
        assert data["a"][i, -1] > rigid
    # kp = 0 is the paper's Winkler case (Table 1, Comez 2013: 0.330419) and a
    # stiff shear layer nears its rigid base (0.311557).
    assert kps[0] == 0.0
    assert data["a"][0, 0] == pytest.approx(0.330419, abs=1e-6)
    assert data["a"][0, -1] == pytest.approx(0.311557, abs=5e-4)
    assert data["critical_vstar"][0, -1] == pytest.approx(RAYLEIGH_02, rel=1e-12)


RAYLEIGH_02 = 0.8299135133739661


def test_scene_kp_param_vary_and_errors() -> None:
    text = (
        "[params]\nvstar = 0.6\nkw = 1.0\nradius = 100.0\nload = 0.002\nkp = 0.2\n"
        "[outputs]\ncontact_width = true\n"
    )
    scene = Scene.from_toml(text)
    assert scene.params["kp"] == 0.2
    assert Scene.from_toml(scene.to_toml()) == scene
    # V* = 0.6 is above V*_cr of the springs alone (0.5717), below V*_cr(kp).
    cw = scene.run().outputs["contact_width"].columns
    assert cw["a"][0] == mp.solve(vstar=0.6, kw=1.0, radius=100.0, load=0.002, kp=0.2).a
    # Without kp the same speed is refused, naming the critical speed.
    with pytest.raises(SceneError, match="V\\*_cr"):
        Scene.from_toml(text.replace("kp = 0.2\n", ""))
    # A vary over kp whose smallest value is too soft blames that value.
    with pytest.raises(SceneError) as info:
        Scene.from_toml(text + '[vary]\nparam = "kp"\nvalues = [0.0, 0.2]\n')
    assert info.value.parameter == "kp"
    assert info.value.key == "vary.values[0]"
    for bad in ("-0.1", '"abc"', "nan", "inf", "1e13"):
        with pytest.raises(SceneError) as info:
            Scene.from_toml(text.replace("kp = 0.2", f"kp = {bad}"))
        assert info.value.parameter == "kp"
        assert info.value.key == "params.kp"
        assert range_text("kp") in str(info.value)


def test_cli_takes_kp(capsys: pytest.CaptureFixture[str]) -> None:
    args = ["--vstar", "0.6", "--kw", "1", "--radius", "100", "--load", "0.002"]
    assert cli.main(["solve", *args, "--kp", "0.2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["kp"] == 0.2
    want = mp.solve(vstar=0.6, kw=1.0, radius=100.0, load=0.002, kp=0.2)
    assert data["a"] == want.a
    assert cli.main(["critical", "--kw", "1", "--kp", "0.2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["critical_vstar"] == mp.critical_vstar(1.0, 0.2, 0.2)
    for bad in ("abc", "-1", "nan"):
        with pytest.raises(SystemExit):
            cli.main(["solve", *args, "--kp", bad])
        err = capsys.readouterr().err
        assert "kp" in err
        assert range_text("kp") in err


@sync
async def test_tui_kp_input_validates_and_lifts_the_critical_speed() -> None:
    app = create_app()
    async with app.run_test(size=(100, 32)) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        panel = screen.query_one(ParamsPanel)
        for garbage in ("abc", "-1", "nan"):
            before = screen.result
            await type_into(pilot, "kp", garbage, paste=True)
            assert "kp" in panel.message("kp")
            assert range_text("kp") in panel.message("kp")
            assert screen.result is before
        await type_into(pilot, "kp", "0.2", paste=True)
        assert panel.message("kp") == ""
        # V* = 0.6: above V*_cr of the springs alone, below V*_cr with kp.
        await type_into(pilot, "vstar", "0.6", paste=True)
        assert panel.message("vstar") == ""
        assert screen.result is not None
        summary = screen.result.summary
        assert summary.params.kp == 0.2
        assert summary.critical_vstar == mp.critical_vstar(1.0, 0.2, 0.2)


# -- hard cases ---------------------------------------------------------------------

PAPER = {"radius": 100.0, "load": 0.002, "nu": 0.2}


@pytest.mark.parametrize("eps", [1e-2, 1e-4, 1e-6])
@pytest.mark.parametrize(("kw", "kp"), [(1.0, 0.1), (0.1, 0.3), (10.0, 0.1)])
def test_near_the_pasternak_critical_speed(kw: float, kp: float, eps: float) -> None:
    # Just below V*_cr(kw, nu, kp) (above the springs' own V*_cr): the
    # solve converges, its error estimate bounds the error against a tight
    # solve and is within 10 tol.
    vcr = mp.critical_vstar(kw, 0.2, kp)
    assert vcr > mp.critical_vstar(kw, 0.2)
    args = {"vstar": vcr * (1 - eps), "kw": kw, "kp": kp, "allow_unphysical": True}
    s = mp.solve(**args, **PAPER)
    ref = mp.solve(**args, **PAPER, tol=1e-12)
    assert math.isfinite(s.a)
    assert s.error_estimate >= abs(s.a - ref.a)
    assert s.error_estimate <= 10 * 1e-8 * s.a
    # The contact widens towards V*_cr (and stays finite).
    assert s.a > mp.solve(vstar=0.0, kw=kw, kp=kp, **PAPER).a


def test_near_rayleigh_on_a_stiff_shear_layer_is_the_rigid_base() -> None:
    # kp = 10: V*_cr = V*_R; near it the base acts as a rigid one for the
    # short waves that matter, and a stiffer kp converges to the rigid base.
    # (The rigid base penetrates there: physics, test_hard_cases.py.)
    vstar = RAYLEIGH_02 * (1 - 1e-6)
    args = {"vstar": vstar, "allow_unphysical": True, **PAPER}
    # (kp = 1e12 is within about 1e-14 of the rigid base, far below either
    # a/h's error estimate here, ~6e-11: their order is round-off, not
    # physics; each is within the two estimates of the other.)
    rigid = mp.solve(kw=math.inf, **args)
    stiff = mp.solve(kw=1.0, kp=10.0, **args)
    stiffer = mp.solve(kw=1.0, kp=1e12, **args)
    assert rigid.a < stiff.a
    assert stiffer.a < stiff.a
    assert abs(stiffer.a - rigid.a) <= stiffer.error_estimate + rigid.error_estimate
    assert stiffer.a == pytest.approx(rigid.a, rel=1e-8)


@pytest.mark.parametrize("damping", [0.0, 0.2])
def test_tiny_kp_is_continuous_with_winkler(damping: float) -> None:
    springs = mp.solve(**CASE, damping=damping)
    tiny = mp.solve(**CASE, damping=damping, kp=1e-12)
    assert tiny.a == pytest.approx(springs.a, rel=1e-10)
    assert tiny.indentation == pytest.approx(springs.indentation, rel=1e-10)
    assert tiny.critical_vstar - springs.critical_vstar == pytest.approx(0.0, abs=1e-11)
    assert mp.critical_vstar(1e-12, 0.2, 1e-12) > mp.critical_vstar(1e-12, 0.2)


@pytest.mark.parametrize("kw", [1e-12, 1.0, 1e6])
@pytest.mark.parametrize("kp", [1e6, 1e9, 1e12])
def test_huge_kp_is_the_rigid_base(kw: float, kp: float) -> None:
    # The shear layer makes the base rigid for waves shorter than
    # sqrt(kp/kw): a/h nears the rigid base's like 1/kp (0.024/kp at kw = 1).
    rigid = mp.solve(**{**CASE, "kw": math.inf})
    s = mp.solve(**{**CASE, "kw": kw, "kp": kp})
    assert s.valid
    assert abs(s.a - rigid.a) <= 0.05 / kp + 1e-8 * rigid.a
    assert s.critical_vstar == rigid.critical_vstar
    # The membrane sinks P/(2 sqrt(kw kp)) on top of the rigid base's indentation.
    sinking = CASE["load"] / (2 * math.sqrt(kw * kp))
    assert s.indentation - rigid.indentation == pytest.approx(
        sinking, rel=5 * math.sqrt(kw / kp) + 1e-6, abs=1e-7 * rigid.indentation
    )


@pytest.mark.parametrize("vstar", [0.3, 0.7])
def test_kp_with_damping_balances_energy(vstar: float) -> None:
    # kw = 1, kp = 0.1: V*_cr = 0.6316; 0.7 is above it (damping solves there).
    s = mp.solve(**{**CASE, "vstar": vstar}, kp=0.1, damping=0.1)
    assert (vstar > s.critical_vstar) == (vstar == 0.7)
    assert s.drag > 0.0
    # The dashpots' power (from the bottom face's response) equals the
    # towing force's (from the collocation solution): an independent balance.
    assert s.dissipation == pytest.approx(s.drag, rel=1e-9)
    # Above V*_cr the waves behind the punch decay only through the dashpots.
    x = np.linspace(-400.0, 400.0, 8001)
    assert np.trapezoid(s.foundation_reaction(x), x) == pytest.approx(1.0, abs=1e-7)
    # A stiffer shear layer carries the same load with less drag.
    stiffer = mp.solve(**{**CASE, "vstar": vstar}, kp=1.0, damping=0.1)
    assert stiffer.drag < s.drag


def test_accuracy_ladder_with_kp_is_bounded() -> None:
    vstar = 0.99 * mp.critical_vstar(1.0, 0.2, 0.3)
    report = accuracy_report(
        {"vstar": vstar, "kw": 1.0, "radius": 100.0, "load": 0.002, "kp": 0.3},
        tols=(1e-4, 1e-8),
    )
    assert report is not None
    assert report.scene.params["kp"] == 0.3
    for rung in report.rungs:
        assert not rung.failure
        assert rung.bounded, rung


@sync
async def test_tui_opens_the_bundled_pasternak_scene() -> None:
    app = create_app("pasternak", tab="sweep")
    async with app.run_test(size=(100, 32)) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        assert screen.sweep.param == "kp"
        data = screen.query_one("#plot-sweep", CurvePlot).curves
        assert data is not None
        assert data.grid_label == "k_p/(μh)"
        scene = Scene.bundled("pasternak")
        assert scene.sweep is not None
        np.testing.assert_array_equal(data.grid, scene.sweep.values)
        current = data.series[0].values
        want = [
            mp.solve(vstar=0.0, kw=1.0, radius=100.0, load=0.002, kp=kp).a
            for kp in scene.sweep.values
        ]
        np.testing.assert_allclose(current, want, rtol=1e-12)
