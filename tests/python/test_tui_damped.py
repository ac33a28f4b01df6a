"""Damping in the terminal UI (issue 8): the input, the gauge against V*_R,
the summary's contact interval and drag, the damped curves, and the tabs the
damped solver does not serve. Numbers are checked against ``mp.solve``."""

from __future__ import annotations

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.asymmetric import AsymmetricSolution
from movingpunch.scene import Scene
from movingpunch.tui import create_app, model
from movingpunch.tui.model import Cache, Curves, Params, Request, fmt
from movingpunch.tui.scene_files import SceneState, from_scene, to_scene
from movingpunch.tui.widgets import CurvePlot, Gauge, ParamsPanel, StressMap
from tui_pilot import screen_of, settle, summary_text, sync, type_into

SIZE = (100, 32)


def damped(vstar: float, damping: float) -> AsymmetricSolution:
    s = mp.solve(vstar=vstar, kw=1.0, radius=100.0, load=0.002, damping=damping)
    assert isinstance(s, AsymmetricSolution)
    return s


@sync
async def test_damping_above_the_critical_speed_shows_interval_and_drag() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        assert screen.params.damping == 0.0
        assert "a/h 0.372881" in summary_text(app)
        await type_into(pilot, "damping", "0.1", paste=True)
        await type_into(pilot, "vstar", "0.65", paste=True)
        assert screen.params == Params(vstar=0.65, damping=0.1)
        s = damped(0.65, 0.1)
        assert s.critical_vstar < 0.65 < s.rayleigh_vstar
        text = summary_text(app)
        start, end = s.contact_interval
        assert f"(-b,a)/h ({start:.5g}, {end:.5g})" in text, text
        assert f"drag/P {s.drag:.4g}" in text, text
        assert f"δ/h {fmt(s.indentation, 3)}" in text, text
        assert "INVALID" not in text
        gauge = screen.query_one(Gauge)
        assert gauge.damped
        rendered = str(gauge.render())
        assert rendered.startswith("V*/V*_R ")
        assert f"{0.65 / s.rayleigh_vstar:.2f}" in rendered
        assert "damped: above V*_cr" in rendered
        assert not gauge.has_class("-warning")
        # The pressure tab plots the damped (asymmetric) pressure.
        plot = screen.query_one("#plot-pressure", CurvePlot).curves
        assert plot is not None
        values = plot.series[0].values
        np.testing.assert_allclose(values, s.pressure(plot.grid), atol=1e-12)
        assert plot.grid[int(np.argmax(values))] > 0.0  # ahead of the punch
        # The stress map is the damped solution's own field.
        await pilot.press("escape", "5")
        await settle(pilot)
        smap = screen.query_one("#plot-field", StressMap)
        assert smap.field is not None
        # Same values up to round-off: a grid of more than 64 x is evaluated
        # in slices whose sizes follow the measured time per point
        # (_evaluate._chunk_calls), and the field at a point changes in the
        # last bits with the slice it is computed in (5e-15 seen).
        expected = s.stress_field(smap.field.x, smap.field.y).sigma_x
        np.testing.assert_allclose(
            smap.field.values, expected, rtol=0.0, atol=1e-12 * np.abs(expected).max()
        )
        # Back to damping 0 at that speed: the undamped limit applies again.
        await type_into(pilot, "damping", "0", paste=True)
        message = screen.query_one(ParamsPanel).message("vstar")
        assert "V*_cr" in message
        assert "need 0 <= V* < V*_cr" in message


@sync
async def test_invalid_damping_shows_the_range_and_keeps_the_last_result() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        before = screen.result
        shown = summary_text(app)
        for text, words in (
            ("-0.1", ("damping must satisfy", "0 <= damping < inf")),
            ("abc", ("damping must be a real number",)),
            ("inf", ("damping must be a finite number", "0 <= damping < inf")),
        ):
            await type_into(pilot, "damping", text, paste=True)
            message = screen.query_one(ParamsPanel).message("damping")
            for word in words:
                assert word in message, message
            assert screen.query_one("#msg-damping").has_class("-shown")
            assert screen.result is before
            assert summary_text(app) == shown
        await type_into(pilot, "damping", "0", paste=True)
        assert screen.query_one(ParamsPanel).message("damping") == ""


def test_depth_tab_of_a_damped_set_reaches_the_surface() -> None:
    """101 depths down to the surface like the undamped tab (the damped
    depth stresses no longer cost ~1/|y|): the last is the surface value,
    the one above it (y = -0.01) the solution's own depth_stress."""
    cache = Cache()
    params = Params(vstar=0.4, damping=0.1)
    result = model.compute(cache, Request(generation=1, params=params, tab="depth"))
    assert result is not None
    data = result.data
    assert isinstance(data, Curves)
    assert len(data.grid) == 101
    s = model.solution(cache, params)
    assert isinstance(s, AsymmetricSolution)
    values = data.series[0].values
    assert values[-1] == pytest.approx(float(s.surface_stress(0.0)), rel=1e-12)
    np.testing.assert_allclose(
        values[-2:], s.depth_stress(data.grid[-2:]), rtol=1e-12, atol=0
    )
    summary = result.summary
    assert summary.damped
    assert summary.contact_interval == s.contact_interval
    assert summary.drag == s.drag
    assert summary.indentation == s.indentation
    assert summary.p0 == float(s.pressure(0.0))


def test_damped_sweep_tab_is_computed() -> None:
    """The a/h sweep with damping > 0 (once a Notice: damped solves took a
    second) solves every point: each equals the API's solve."""
    cache = Cache()
    params = Params(vstar=0.2, damping=0.1)
    result = model.compute(cache, Request(generation=1, params=params, tab="sweep"))
    assert result is not None
    data = result.data
    assert isinstance(data, Curves)
    values = data.series[0].values
    assert np.isfinite(values).all()
    for j in (0, len(values) - 1):
        point = params.with_value("load", float(data.grid[j]))
        assert values[j] == model.solution(cache, point).a


def test_damped_field_tab_is_the_solutions_stress_field() -> None:
    """The stress map with damping > 0 (once a Notice): the solution's own
    stress_field over the whole layer, spanning the asymmetric contact."""
    cache = Cache()
    params = Params(vstar=0.65, damping=0.5)
    request = Request(generation=1, params=params, tab="field")
    result = model.compute(cache, request)
    assert result is not None
    data = result.data
    assert isinstance(data, model.FieldMap)
    s = model.solution(cache, params)
    assert data.x[-1] >= 3.0 * max(abs(e) for e in s.contact_interval)
    assert data.y[0] == -1.0
    assert data.y[-1] == 0.0
    f = s.stress_field(data.x, data.y)
    # The map is computed in time-sliced chunks of rows and columns, whose
    # Filon sums may round differently from one call on the whole grid (seen
    # once at 1e-15 under load): equal to round-off, not bit for bit.
    scale = float(np.max(np.abs(f.sigma_x)))
    np.testing.assert_allclose(data.values, f.sigma_x, rtol=0.0, atol=1e-12 * scale)
    assert model.to_csv(data, params).splitlines()[0].startswith("# movingpunch")


def test_a_damped_scene_round_trips_through_the_app_state() -> None:
    state = from_scene(Scene.bundled("damped"))
    assert state.params.damping == 0.1
    assert state.overlay is not None
    assert state.overlay.param == "vstar"
    scene = to_scene(
        SceneState(params=state.params, overlay=None, sweep=None, name="x")
    )
    assert scene.params["damping"] == 0.1
    plain = to_scene(SceneState(params=Params(), overlay=None, sweep=None, name="y"))
    assert "damping" not in plain.params
