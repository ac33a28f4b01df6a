"""The damped (Kelvin-Voigt) foundation through the Python API and the CLI.

Anchors: the undamped solver and the paper's Table 1 (damping -> 0), energy
conservation per mode and for the whole contact, the static limit, and a
drag integrated here from the pressure (independent of the core's closed form).
"""

from __future__ import annotations

import json
import math
import subprocess
from collections.abc import Callable

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.asymmetric import (
    AsymmetricSolution,
    damped_layer_response,
    solve_asymmetric,
)

PAPER = {"radius": 100.0, "load": 0.002, "nu": 0.2}


def drag_by_quadrature(s: AsymmetricSolution) -> float:
    """int p x/R dx / P by Gauss-Chebyshev (U) quadrature of the pressure."""
    m = 400
    theta = np.arange(1, m + 1) * np.pi / (m + 1)
    r = np.cos(theta)
    x = s.centre + s.half_width * r
    p = np.asarray(s.pressure(x))
    g = p / np.sin(theta)  # p = g sqrt(1 - r^2)
    w = np.pi * np.sin(theta) ** 2 / (m + 1)
    return float(s.half_width * np.sum(w * g * x) / s.radius)


def test_zero_damping_is_the_undamped_solver() -> None:
    plain = mp.solve(vstar=0.2, kw=1.0, **PAPER)
    zero = mp.solve(vstar=0.2, kw=1.0, damping=0.0, **PAPER)
    assert isinstance(zero, mp.Solution)
    assert zero.a == plain.a  # the same path, bit for bit
    assert zero.p0 == plain.p0


@pytest.mark.parametrize(
    ("kw", "paper_a"),
    [(0.1, 0.3729), (1.0, 0.3306), (10.0, 0.3152), (math.inf, 0.3117)],
)
def test_tiny_damping_reproduces_table1(kw: float, paper_a: float) -> None:
    und = mp.solve(vstar=1e-3, kw=kw, **PAPER)
    s = mp.solve(vstar=1e-3, kw=kw, damping=1e-9, **PAPER)
    assert isinstance(s, AsymmetricSolution)
    left, right = s.contact_interval
    assert right == pytest.approx(paper_a, abs=5e-5)
    assert right == pytest.approx(und.a, abs=1e-8)
    assert left == pytest.approx(-und.a, abs=1e-8)
    x = np.linspace(-0.3, 0.3, 7)
    np.testing.assert_allclose(s.pressure(x), und.pressure(x), atol=1e-7)
    xs = np.array([0.0, 0.2, 0.5, 1.5])
    np.testing.assert_allclose(s.surface_stress(xs), und.surface_stress(xs), atol=1e-7)
    ys = [-1.0, -0.5, -0.1, -0.01]
    np.testing.assert_allclose(s.depth_stress(ys), und.depth_stress(ys), atol=1e-8)
    assert abs(s.drag) < 1e-12


def test_layer_response_limits_and_energy_per_mode() -> None:
    for t in (0.01, 0.3, 1.0, 3.0, 20.0):
        m1, _, _ = damped_layer_response(t, vstar=0.3, kw=1.0, damping=0.0)
        m1_real, _ = mp.layer_response(t, vstar=0.3, kw=1.0)
        assert m1.imag == 0.0
        assert m1.real == pytest.approx(float(m1_real), rel=1e-13)
        # Power in at the top = power taken by the dashpots at the bottom.
        for vstar in (0.3, 0.7):
            m1, _, wb = damped_layer_response(t, vstar=vstar, kw=1.0, damping=0.4)
            diss = 0.4 * math.sqrt(vstar) * abs(wb) ** 2
            assert m1.imag >= 0.0
            assert m1.imag == pytest.approx(diss, rel=1e-11)


@pytest.mark.parametrize(
    ("vstar", "kw", "damping"),
    [(0.2, 1.0, 0.1), (0.2, 0.1, 2.0), (0.65, 1.0, 0.05), (0.3, 0.01, 0.2)],
)
def test_energy_balance_and_drag(vstar: float, kw: float, damping: float) -> None:
    s = solve_asymmetric(vstar=vstar, kw=kw, damping=damping, **PAPER)
    assert s.drag > 0  # opposes the motion
    assert s.dissipation == pytest.approx(s.drag, rel=1e-6)
    assert drag_by_quadrature(s) == pytest.approx(s.drag, rel=1e-9)
    assert s.valid, s.validity
    # The surface follows the punch on the contact.
    x = s.centre + s.half_width * np.array([-0.8, 0.0, 0.5])
    np.testing.assert_allclose(s.surface_slope(x), x / s.radius, atol=1e-10)
    assert s.to_dict()["contact_interval"] == list(s.contact_interval)


@pytest.mark.parametrize("vstar", [0.2, 0.65])
def test_kelvin_voigt_base_condition_in_real_space(vstar: float) -> None:
    """sigma_y(x, -h) = kw v - damping sqrt(vstar) dv/dx and tau = 0 there,
    from the field, the bottom displacement and its slope (three separate
    Fourier integrals); the reaction carries the load."""
    damping, kw, load = 0.3, 1.0, 0.002
    s = solve_asymmetric(vstar=vstar, kw=kw, damping=damping, **PAPER)
    x = np.array([-1.5, -0.3, 0.0, 0.4, 2.5])
    f = s.stress_field(x, [-1.0])
    v = np.asarray(s.bottom_displacement(x))
    dv = np.asarray(s.bottom_slope(x))
    np.testing.assert_allclose(
        load * f.sigma_y[0], kw * v - damping * math.sqrt(vstar) * dv, atol=1e-9 * load
    )
    np.testing.assert_allclose(f.tau_xy[0], 0.0, atol=1e-9)
    np.testing.assert_allclose(s.foundation_reaction(x), -f.sigma_y[0], rtol=1e-14)
    xs = np.linspace(-30.0, 30.0, 1201)
    r = np.asarray(s.foundation_reaction(xs))
    total = float(np.sum(0.5 * (r[1:] + r[:-1]) * np.diff(xs)))
    assert total == pytest.approx(1.0, abs=2e-3)  # the base carries P


def test_supercritical_speed_solves_and_rayleigh_is_refused() -> None:
    vcr = mp.critical_vstar(1.0)
    with pytest.raises(mp.SupercriticalSpeedError):
        mp.solve(vstar=0.65, kw=1.0, **PAPER)
    s = mp.solve(vstar=0.65, kw=1.0, damping=0.1, **PAPER)
    assert isinstance(s, AsymmetricSolution)
    assert s.vstar > vcr
    assert s.contact_interval[0] < s.contact_interval[1]
    vr = mp.rayleigh_vstar(0.2)
    with pytest.raises(mp.SupercriticalSpeedError, match="Rayleigh"):
        mp.solve(vstar=vr, kw=1.0, damping=0.1, **PAPER)
    with pytest.raises(mp.SupercriticalSpeedError, match="Rayleigh"):
        mp.solve(vstar=0.95, kw=1.0, damping=0.1, **PAPER)


def test_no_effect_at_rest_and_drag_vanishes_with_speed() -> None:
    static = mp.solve(vstar=0.0, kw=1.0, **PAPER)
    s = mp.solve(vstar=0.0, kw=1.0, damping=3.0, **PAPER)
    assert isinstance(s, AsymmetricSolution)
    assert s.a == pytest.approx(static.a, abs=1e-9)
    assert s.b == pytest.approx(static.a, abs=1e-9)
    assert abs(s.drag) < 1e-14
    drags = [
        solve_asymmetric(vstar=v, kw=1.0, damping=1.0, **PAPER).drag
        for v in (1e-2, 1e-4, 1e-6)
    ]
    assert all(d > 0 for d in drags)
    assert drags[1] < 0.2 * drags[0]
    assert drags[2] < 0.2 * drags[1]


def test_depth_stress_near_surface_against_flamant() -> None:
    """At rest (where damping does nothing) sigma_x(0, y) minus the static
    half-plane (Flamant) integral of the same pressure is smooth in y, and
    its extrapolation to y = 0 must be the surface value minus the half-plane's
    -p(0): an anchor independent of both depth-stress evaluations."""
    s = solve_asymmetric(vstar=0.0, kw=1.0, damping=1.0, **PAPER)
    m = 20000
    theta = np.arange(1, m + 1) * np.pi / (m + 1)
    xi = s.centre + s.half_width * np.cos(theta)
    p = np.asarray(s.pressure(xi))
    w = s.half_width * np.pi / (m + 1) * np.sin(theta)

    def flamant(z: float) -> float:
        return float(-(2 / np.pi) * np.sum(w * p * xi**2 * z / (xi**2 + z**2) ** 2))

    zs = np.array([0.005, 0.01, 0.02])
    rem = np.array([float(s.depth_stress(-z)) - flamant(z) for z in zs])
    at_zero = np.polyval(np.polyfit(zs, rem, 2), 0.0)
    surface = float(s.surface_stress(0.0)) + float(s.pressure(0.0))
    assert at_zero == pytest.approx(surface, abs=5e-6)


def test_limiting_absorption() -> None:
    ends = [
        solve_asymmetric(vstar=0.65, kw=1.0, damping=d, **PAPER).contact_interval
        for d in (1e-3, 1e-4, 1e-5)
    ]
    d1 = ends[1][1] - ends[0][1]
    d2 = ends[2][1] - ends[1][1]
    assert 8.0 < d1 / d2 < 12.0  # first order in the damping
    assert abs(d2) < 1e-4


def test_multiple_steady_states_are_reported() -> None:
    s = solve_asymmetric(vstar=0.65, kw=1.0, damping=0.01, radius=100.0, load=0.0025)
    assert len(s.other_half_widths) == 2
    assert "not unique" in s.validity
    unique = solve_asymmetric(vstar=0.65, kw=1.0, damping=0.01, **PAPER)
    assert unique.other_half_widths == ()


@pytest.mark.parametrize("bad", [-1.0, math.nan, math.inf, "0.1", True, None, 1j])
def test_bad_damping_is_named(bad: object) -> None:
    with pytest.raises(mp.InvalidParameterError, match="damping"):
        mp.solve(vstar=0.2, kw=1.0, damping=bad, **PAPER)  # type: ignore[call-overload]


def test_bad_depth_and_size() -> None:
    s = solve_asymmetric(vstar=0.2, kw=1.0, damping=0.1, **PAPER)
    with pytest.raises(mp.InvalidParameterError, match="y must satisfy"):
        s.depth_stress(1e-4)
    with pytest.raises(mp.InvalidParameterError, match="n must be"):
        solve_asymmetric(vstar=0.2, kw=1.0, damping=0.1, n=2048, **PAPER)
    fixed = solve_asymmetric(vstar=0.2, kw=1.0, damping=0.1, n=32, **PAPER)
    assert fixed.collocation_n == 32
    assert fixed.contact_interval == pytest.approx(s.contact_interval, abs=1e-8)


def test_unphysical_supercritical_contact_is_flagged() -> None:
    args = {"vstar": 0.3, "kw": 0.01, "radius": 100.0, "load": 0.02, "damping": 0.01}
    with pytest.raises(mp.UnphysicalContactError):
        solve_asymmetric(**args)
    s = solve_asymmetric(**args, allow_unphysical=True)
    assert not s.valid
    assert s.min_pressure < 0


def test_cli_damping(run_cli: Callable[..., subprocess.CompletedProcess[str]]) -> None:
    case = ["--vstar", "0.65", "--kw", "1", "--radius", "100", "--load", "0.002"]
    proc = run_cli("solve", *case, "--damping", "0.1", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    api = solve_asymmetric(vstar=0.65, kw=1.0, damping=0.1, **PAPER)
    assert data["contact_interval"] == pytest.approx(
        list(api.contact_interval), abs=1e-12
    )
    assert data["drag"] == pytest.approx(api.drag, rel=1e-12)
    table = run_cli("solve", *case, "--damping", "0.1")
    assert table.returncode == 0, table.stderr
    assert "drag" in table.stdout
    assert "contact (x_back/h, x_front/h)" in table.stdout
    assert "indentation δ/h" in table.stdout
    bad = run_cli("solve", *case, "--damping", "-1")
    assert bad.returncode == 2
    assert "damping" in bad.stderr
    assert "Traceback" not in bad.stderr
    stress = run_cli("solve", *case, "--damping", "0.1", "--stress", "--json")
    assert stress.returncode == 0, stress.stderr
    peaks = api.stress_peaks()
    assert json.loads(stress.stdout)["stress"]["top_tensile"] == pytest.approx(
        peaks.top_tensile, rel=1e-12
    )
    table = run_cli("solve", *case, "--damping", "0.1", "--stress")
    assert "Stress sigma_x/(P/h)" in table.stdout


def test_stress_peaks_match_the_symmetric_solver_and_are_the_extremes() -> None:
    # Independent anchor: with damping 1e-9 the peaks are the undamped
    # solver's (found by its own, different search); at a supercritical speed
    # the damped peaks are at least as extreme as a dense scan of the surface
    # and of the bottom, and each is the field's value at its position.
    args = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002}
    undamped = mp.solve(**args).stress_peaks()
    tiny = mp.solve(**args, damping=1e-9).stress_peaks()
    for name in ("top_compressive", "top_tensile", "bottom_tensile"):
        assert getattr(tiny, name) == pytest.approx(
            getattr(undamped, name), rel=1e-6
        ), name
    assert abs(tiny.top_tensile_x) == pytest.approx(undamped.top_tensile_x, abs=0.01)
    assert tiny.centre_top == pytest.approx(undamped.centre_top, rel=1e-6)
    assert tiny.centre_bottom == pytest.approx(undamped.centre_bottom, rel=1e-6)

    s = mp.solve(vstar=0.65, kw=1.0, radius=100.0, load=0.002, damping=0.1)
    pk = s.stress_peaks()
    assert pk.search_extent == pytest.approx(10.0)
    x = np.linspace(-pk.search_extent, pk.search_extent, 601)
    top = np.asarray(s.surface_stress(x))
    bottom = s.stress_field(x, [-1.0]).sigma_x[0]
    assert pk.top_tensile >= np.max(top) - 1e-12
    assert pk.top_compressive <= np.min(top) + 1e-12
    assert pk.bottom_tensile >= np.max(bottom) - 1e-12
    assert pk.top_tensile == pytest.approx(
        s.surface_stress(pk.top_tensile_x), abs=1e-13
    )
    assert pk.centre_top == pytest.approx(s.surface_stress(0.0), abs=1e-13)
    with pytest.raises(mp.InvalidParameterError, match="extent"):
        s.stress_peaks(extent=-1.0)
