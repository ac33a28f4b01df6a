"""Viscoelastic layers in the terminal UI (issue 28): the medium editor's
material selector per sublayer (elastic, Zener by deborah or by tau, a
scene's Prony series kept) and its inertia selector, the speed sweep of one
material (``w``: a/h and the drag against V*), and the bundled bell-curve
scene. Numbers on screen are checked against ``mp.solve``, never a number of
another medium."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import pytest
from textual.pilot import Pilot
from textual.widgets import Select

import movingpunch as mp
from movingpunch.scene import Scene
from movingpunch.tui import create_app
from movingpunch.tui import model as tui_model
from movingpunch.tui.model import Params
from movingpunch.tui.scene_files import from_scene, to_scene
from movingpunch.tui.widgets import CurvePlot, Gauge
from test_tui_media import open_editor, row, type_in
from tui_pilot import (
    assert_summary_is,
    half_digit,
    screen_of,
    settle,
    status_text,
    summary_fields,
    sync,
    type_into,
)

SIZE = (100, 32)
BELL = {"kw": 1.0, "radius": 100.0, "load": 0.002}


def bell_layer(tau: float = 100.0) -> mp.Layer:
    return mp.Layer(nu=0.3, viscoelastic=mp.Zener(10.0, tau=tau))


async def choose(pilot: Pilot[None], select: Select[str], value: str) -> None:
    select.value = value
    await pilot.pause()


@sync
async def test_the_bundled_bell_scene_opens_with_its_material_and_its_curve() -> None:
    scene = Scene.bundled("viscoelastic-bell")
    state = from_scene(scene)
    assert state.params.medium() == scene.medium
    assert state.sweep is not None
    assert state.sweep.quantity == "drag"
    assert to_scene(state).medium == scene.medium
    app = create_app(scene=state, cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        api = mp.solve(vstar=1e-6, layers=[bell_layer()], inertia=False, **BELL)
        assert_summary_is(app, api, "the bell scene")
        screen = screen_of(app)
        screen.action_show_tab("sweep")
        await settle(pilot)
        data = screen.query_one("#plot-sweep", CurvePlot).curves
        assert data is not None
        assert data.title.startswith("Drag F/P against V*")
        grid, drag = data.grid, data.series[0].values
        k = int(np.argmax(drag))
        assert 0 < k < len(grid) - 1  # the bell's maximum inside
        # A point of the curve is the API's drag at that speed.
        at = mp.solve(
            vstar=float(grid[k]), layers=[bell_layer()], inertia=False, **BELL
        )
        assert drag[k] == at.drag


@sync
async def test_the_editor_makes_a_quasi_static_zener_layer() -> None:
    """Elastic -> Zener (tau) and inertia off on the Fig. 4 case (V* = 0.2):
    the summary is the API's quasi-static solve, deborah = sqrt(0.2) tau."""
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        editor = await open_editor(pilot)
        top = row(editor, 1)
        assert top.material_kind == "elastic"
        assert not top.box("ratio").display
        await choose(pilot, top.query_one(".m-kind", Select), "zener-tau")
        assert top.box("ratio").display
        assert top.box("time").display
        await type_in(pilot, top.box("ratio"), "4")
        await type_in(pilot, top.box("time"), "0.5")
        await choose(pilot, editor.query_one("#inertia", Select), "off")
        assert editor.error == ""
        await pilot.press("enter")
        await settle(pilot)
        screen = screen_of(app)
        layer = mp.Layer(nu=0.2, viscoelastic=mp.Zener(4.0, tau=0.5))
        assert screen.params.layers == (layer,)
        assert not screen.params.inertia
        api = mp.solve(
            vstar=0.2, kw=1.0, radius=100.0, load=0.002, layers=[layer], inertia=False
        )
        at_rest = mp.solve(
            vstar=0.0,
            kw=1.0,
            radius=100.0,
            load=0.002,
            layers=[mp.Layer(nu=0.2, viscoelastic=mp.Zener(4.0, math.sqrt(0.2) * 0.5))],
        )
        assert api.contact_interval == at_rest.contact_interval
        assert_summary_is(app, api, "quasi-static Zener")
        assert "quasi-static" in screen.params.medium_label()
        # w: load, radius, then the material's speed: a/h, then the drag.
        seen = []
        for _ in range(4):
            screen.action_toggle_sweep()
            seen.append((screen.sweep.param, screen.sweep.quantity))
            if screen.sweep.param == "vstar":
                # Below the relaxed critical speed (V* = 0.2 x 100 is not).
                stop = screen.sweep.stop
                assert stop is not None
                assert stop == 0.95 * mp.critical_vstar(kw=1.0, nu=0.2)
        assert seen == [
            ("radius", "a"),
            ("vstar", "a"),
            ("vstar", "drag"),
            ("load", "a"),
        ]


async def moving_zener_layer(pilot: Pilot[None], app: Any) -> Any:
    """The medium editor makes the top a Zener layer (ratio 2, deborah 0.1)
    with its inertia on (the editor's default) and applies it; the screen."""
    await settle(pilot)
    screen = screen_of(app)
    editor = await open_editor(pilot)
    top = row(editor, 1)
    await choose(pilot, top.query_one(".m-kind", Select), "zener-deborah")
    await type_in(pilot, top.box("time"), "0.1")
    assert editor.error == ""
    await pilot.press("enter")
    await settle(pilot)
    return screen


@sync
async def test_inertia_on_a_viscoelastic_layer_shows_the_moving_solve() -> None:
    """Zener (deborah 0.1) with the inertia on at the Fig. 4 speed V* = 0.2:
    the summary is the API's moving solve (drag, surface and bottom peaks),
    the surface and depth curves the API's."""
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        screen = await moving_zener_layer(pilot, app)  # inertia on, V* = 0.2
        assert screen.params.inertia
        layer = mp.Layer(nu=screen.params.nu, viscoelastic=mp.Zener(2.0, 0.1))
        api = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, layers=[layer])
        assert api.drag > 0.0
        assert_summary_is(app, api, "inertia on")
        # sigma_x against depth: the API's below the contact's centre.
        screen.action_show_tab("depth")
        await settle(pilot)
        depth = screen.query_one("#plot-depth", CurvePlot).curves
        assert depth is not None
        assert np.array_equal(depth.series[0].values, api.depth_stress(depth.grid))
        screen.action_show_tab("surface")
        await settle(pilot)
        curves = screen.query_one("#plot-surface", CurvePlot).curves
        assert curves is not None
        grid = curves.grid
        assert np.array_equal(curves.series[0].values, api.surface_stress(grid))


@sync
async def test_a_moving_zener_layer_runs_past_the_relaxed_critical_speed() -> None:
    """Typed V* = 0.7 beyond the relaxed V*_cr (0.572) with the inertia on:
    the summary is the API's solve, the gauge measures V* against V*_R (the
    bound of a material that damps), and 0.85 (beyond V*_R) is refused."""
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        screen = await moving_zener_layer(pilot, app)
        await type_into(pilot, "vstar", "0.7", paste=True)
        layer = mp.Layer(nu=screen.params.nu, viscoelastic=mp.Zener(2.0, 0.1))
        api = mp.solve(vstar=0.7, kw=1.0, radius=100.0, load=0.002, layers=[layer])
        assert api.critical_vstar < 0.7 < api.rayleigh_vstar
        assert_summary_is(app, api, "beyond V*_cr")
        gauge = screen.query_one(Gauge)
        assert gauge.damped
        rendered = str(gauge.render())
        assert rendered.startswith("V*/V*_R "), rendered
        assert "above V*_cr" in rendered
        await type_into(pilot, "vstar", "0.85", paste=True)
        assert status_text(app).startswith("supercritical speed"), status_text(app)
        assert "showing the result for V* 0.7" in status_text(app)


@sync
async def test_garbage_in_the_material_is_named_and_never_applied() -> None:
    app = create_app(cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        editor = await open_editor(pilot)
        top = row(editor, 1)
        await choose(pilot, top.query_one(".m-kind", Select), "zener-tau")
        for box, text, said in (
            ("ratio", "x", "ratio must be a number"),
            ("ratio", "0.5", "Zener.ratio must be in [1"),
            ("time", "-1", "Zener.tau must be in [0"),
            ("time", "nan", "Zener.tau"),
        ):
            good = top.box(box).value
            await type_in(pilot, top.box(box), text)
            assert said in editor.error, editor.error
            assert "sublayer 1" in editor.error, editor.error
            assert top.box(box).has_class("-invalid")
            await pilot.press("enter")
            await pilot.pause()
            assert pilot.app.screen is editor  # not applied
            await type_in(pilot, top.box(box), good)
            assert editor.error == ""
        # A graded sublayer cannot carry a material.
        await type_in(pilot, top.box("gamma_h"), "1")
        assert "graded" in editor.error, editor.error


def test_a_prony_series_is_kept_as_loaded() -> None:
    prony = mp.Prony((1.0, 3.0), taus=(20.0, 400.0))
    layers = (mp.Layer(nu=0.3, viscoelastic=prony),)
    params = tui_model.with_medium(Params(), layers, None, inertia=False)
    assert params.layers == layers
    assert not params.inertia
    assert tui_model.material_of(layers[0])[0] == "prony"
    assert tui_model.parse_material(1, "prony", "", "", prony) is prony
    # An elastic single layer with inertia is the panel's layer again.
    back = tui_model.with_medium(params, (mp.Layer(nu=0.3),), None)
    assert back.layers == ()
    assert back.nu == 0.3
    assert back.inertia


def test_the_sweep_of_a_speed_keeps_its_quantity_in_a_saved_scene() -> None:
    state = from_scene(Scene.bundled("viscoelastic-bell"))
    scene = to_scene(state)
    assert scene.sweep is not None
    assert scene.sweep.quantities == ("drag",)
    assert scene.sweep.param == "vstar"


@sync
async def test_w_sweeps_the_speed_of_a_moving_material() -> None:
    """The bell scene with the inertia on (at V* = 1e-4): `w` goes on to the
    drag against V* of the moving layer; a point of the curve is the API's
    moving solve at that speed."""
    text = Scene.bundled("viscoelastic-bell").to_toml().replace("inertia = false\n", "")
    scene = Scene.from_toml(text.replace("vstar = 1e-06", "vstar = 0.0001"))
    state = from_scene(scene)
    assert state.params.inertia
    app = create_app(scene=state, cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        seen = []
        for _ in range(5):  # the scene's (vstar, drag), round to it again
            screen.action_toggle_sweep()
            seen.append((screen.sweep.param, screen.sweep.quantity))
            if seen[-1] == ("vstar", "drag"):
                break
        assert seen[-3:] == [("radius", "a"), ("vstar", "a"), ("vstar", "drag")], seen
        await settle(pilot)
        data = screen.query_one("#plot-sweep", CurvePlot).curves
        assert data is not None
        assert data.title.startswith("Drag F/P against V*")
        grid, drag = data.grid, data.series[0].values
        k = len(grid) // 2
        at = mp.solve(vstar=float(grid[k]), layers=[bell_layer()], **BELL)
        assert at.medium is not None
        assert at.medium.inertia
        assert drag[k] == at.drag


def test_an_output_the_medium_does_not_give_is_na_and_a_notice(monkeypatch) -> None:
    """The summary's peaks and a tab's curves when the medium refuses the
    stresses (an InvalidParameterError after a solve that succeeded; as the
    stresses nearer the surface than the moving layer gives): n/a and a
    notice naming why, never a number of another medium."""
    layer = mp.Layer(nu=0.2, viscoelastic=mp.Zener(2.0, 0.1))
    params = tui_model.with_medium(Params(), (layer,), None, inertia=True)

    def refuse(*_args: object, **_kwargs: object) -> None:
        raise mp.InvalidParameterError("y: not given here", parameter="y")

    monkeypatch.setattr(mp.AsymmetricSolution, "stress_peaks", refuse)
    monkeypatch.setattr(mp.AsymmetricSolution, "surface_stress", refuse)
    cache = tui_model.Cache()
    head = tui_model.summary(cache, params)
    assert math.isnan(head.top_tensile)
    assert math.isnan(head.bottom_tensile)
    assert tui_model.fmt(head.top_tensile) == "n/a"
    assert head.drag > 0.0
    assert tui_model.summary_hints(head) is not None
    result = tui_model.compute(
        cache, tui_model.Request(generation=1, params=params, tab="surface")
    )
    assert isinstance(result.data, tui_model.Notice)
    assert "not given here" in result.data.text


def test_a_viscoelastic_sublayer_on_a_half_space_in_the_panel() -> None:
    """A lossy soil sublayer under an elastic top on a half-space: the
    panel's summary is the API's solve (drag, contact, the indentation from
    the reference point); with friction, whose indentation the asymmetric
    solver does not give under a half-space (a logarithmic far field), it is
    n/a, never a number; the depth tab draws."""
    soil = mp.Layer(0.7, mu=0.5, nu=0.3, rho=0.8, viscoelastic=mp.Zener(4.0, 0.3))
    top = mp.Layer(0.3, nu=0.25)
    base = mp.HalfSpace(mu=3.0, nu=0.25, rho=1.5)
    params = tui_model.with_medium(
        Params(vstar=0.2, radius=5.0, load=0.05), (top, soil), base, inertia=True
    )
    cache = tui_model.Cache()
    head = tui_model.summary(cache, params)
    api = mp.solve(vstar=0.2, radius=5.0, load=0.05, layers=[top, soil], base=base)
    assert head.drag == api.drag > 0.0
    assert head.contact_interval == api.contact_interval
    assert head.indentation == api.indentation > 0.0
    result = tui_model.compute(
        cache, tui_model.Request(generation=1, params=params, tab="depth")
    )
    assert not isinstance(result.data, tui_model.Notice)
    # Friction on an elastic stack on a half-space: no indentation.
    rough = dataclasses.replace(
        tui_model.with_medium(
            Params(vstar=0.2, radius=5.0, load=0.05),
            (top, dataclasses.replace(soil, viscoelastic=None)),
            base,
            inertia=True,
        ),
        friction=0.2,
    )
    head = tui_model.summary(cache, rough)
    assert math.isnan(head.indentation)
    assert tui_model.fmt(head.indentation) == "n/a"
    assert head.tangential_force == pytest.approx(0.2)
    assert tui_model.summary_hints(head) is not None


@sync
async def test_a_flat_punch_on_a_zener_layer_shows_what_it_has() -> None:
    """A flat punch on a Zener layer (a scene): the summary is the API's
    solve (drag, the edges' coefficients), and what it does not give yet
    (the indentation, the stresses' peaks below the surface) reads n/a."""
    from test_viscoelastic_flat import SCENE, flat

    state = from_scene(Scene.from_toml(SCENE))
    app = create_app(scene=state, cursor_blink=False, show_timing=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        api = flat(0.1)
        fields = dict(summary_fields(app))
        back, front = api.end_coefficients
        for label, want in (
            ("drag/P", api.drag),
            ("p0", api.p0),
            ("K back", back),
            ("K front", front),
        ):
            printed = fields[label]
            assert abs(float(printed) - want) <= half_digit(printed) * (1 + 1e-9), (
                label,
                printed,
                want,
            )
        for label in ("δ/h", "σx⁺ top", "bot"):
            assert fields[label] == "n/a", (label, fields)
