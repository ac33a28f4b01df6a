"""Several contact zones in the terminal UI: a separated contact (the single
contact unphysical near the critical speed: ``contact`` auto), the
``contact`` input (single: the old refusal) and trains of punches (the
``train`` input, ``load@at, ...``: ``movingpunch.solve_punches``).

Numbers on screen are checked against the Python API; the parsers and the
model run without Textual.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from textual.pilot import Pilot
from textual.widgets import Input

import movingpunch as mp
from movingpunch.errors import InvalidParameterError
from movingpunch.tui import MovingPunchApp, create_app, model
from movingpunch.tui.model import (
    Cache,
    Curves,
    FieldMap,
    Notice,
    Params,
    Request,
    TrainPunch,
    parse_punches,
)
from movingpunch.tui.scene_files import SceneState
from movingpunch.tui.widgets import CurvePlot, ParamsPanel, StressMap
from tui_pilot import (
    screen_of,
    settle,
    status_ok,
    status_text,
    summary_text,
    sync,
    type_into,
)

SIZE = (100, 32)

SEPARATED = Params(vstar=0.99 * mp.critical_vstar(0.1), kw=0.1, radius=100.0)
"""kw 0.1, V* = 0.99 V*_cr, R/h 100, load 0.002: the single contact has
p < 0 inside; the contact set is two zones."""

TRAIN = "0.002@-1.5, 0.002@1.5"


def app_at(params: Params) -> MovingPunchApp:
    return create_app(SceneState(params=params), show_timing=False, cursor_blink=False)


def curves(app: MovingPunchApp, tab: str) -> Curves:
    data = screen_of(app).query_one(f"#plot-{tab}", CurvePlot).curves
    assert data is not None
    return data


async def set_text(pilot: Pilot[None], name: str, text: str) -> None:
    """Replaces the text of an input at once (one change, as a paste over a
    selection would), then waits for the workers."""
    box = pilot.app.screen.query_one(f"#in-{name}", Input)
    box.value = text
    await settle(pilot)


def message(app: MovingPunchApp, name: str) -> str:
    return screen_of(app).query_one(ParamsPanel).message(name)


# -- the model, without Textual ---------------------------------------------


def test_parse_punches() -> None:
    assert parse_punches("") == ()
    assert parse_punches("  ") == ()
    assert parse_punches("0.002@-1.5, 0.003@1.5") == (
        TrainPunch(0.002, -1.5),
        TrainPunch(0.003, 1.5),
    )
    assert parse_punches("0.002@-1.5; 0.002 @ 2") == (
        TrainPunch(0.002, -1.5),
        TrainPunch(0.002, 2.0),
    )
    assert model.format_punches(parse_punches(TRAIN)) == "0.002@-1.5, 0.002@1.5"
    for bad, words in (
        ("garbage", "item 1 'garbage'"),
        ("0.002@-1.5, x@1", "item 2 'x@1'"),
        ("0.002@", "write load@at"),
        ("-1@0", "load"),
        ("0.002@nan", "finite"),
        ("0.002@1,", "item 2"),
    ):
        with pytest.raises(InvalidParameterError) as info:
            parse_punches(bad)
        assert info.value.parameter == "punches"
        assert str(info.value).startswith("punches: ")
        assert words in str(info.value)
    with pytest.raises(InvalidParameterError, match="at most 16"):
        parse_punches(", ".join(f"0.001@{k}" for k in range(17)))


def test_parse_contact() -> None:
    assert model.parse_contact(" Single ") == "single"
    assert model.parse_contact("auto") == "auto"
    with pytest.raises(InvalidParameterError) as info:
        model.parse_contact("both")
    assert info.value.parameter == "contact"


def test_the_separated_pressure_grid_covers_every_zone() -> None:
    cache = Cache()
    result = model.compute(cache, Request(1, SEPARATED, "pressure"))
    assert result is not None
    ref = mp.solve(vstar=SEPARATED.vstar, kw=0.1, radius=100.0, load=0.002)
    assert isinstance(ref, mp.ZonedSolution)
    assert len(ref.contact_zones) == 2
    assert np.array(result.summary.contact_zones) == pytest.approx(
        np.array(ref.contact_zones)
    )
    data = result.data
    assert isinstance(data, Curves)
    lo, hi = ref.contact_interval
    assert data.grid[0] < lo
    assert data.grid[-1] > hi
    # Every zone end is on the grid and marked; the curve carries the load.
    ends = [e for z in ref.contact_zones for e in z]
    assert data.markers == pytest.approx(ends)
    for e in ends:
        assert np.min(np.abs(data.grid - e)) == 0.0
    p = data.series[0].values
    assert np.trapezoid(p, data.grid) == pytest.approx(1.0, rel=2e-2)
    # Between the zones the pressure is 0.
    gap = (data.grid > ref.contact_zones[0][1]) & (data.grid < ref.contact_zones[1][0])
    assert gap.any()
    assert np.all(p[gap] == 0.0)


def test_an_offset_train_is_plotted_around_its_hull() -> None:
    """A train off x = 0: the grids follow its hull, not a window on 0."""
    params = replace(Params(), punches=parse_punches("0.002@4, 0.002@7"))
    cache = Cache()
    tabs: tuple[model.TabName, ...] = ("pressure", "surface", "field")
    for tab in tabs:
        result = model.compute(cache, Request(1, params, tab))
        assert result is not None
        zones = result.summary.contact_zones
        assert len(zones) == 2
        assert len(result.summary.punches) == 2
        data = result.data
        assert isinstance(data, FieldMap | Curves)
        x = data.x if isinstance(data, FieldMap) else data.grid
        assert x[0] < zones[0][0]
        assert x[-1] > zones[-1][1]
        assert x[0] > 0.0  # not centred on the origin
    # The accuracy ladder runs one punch: the tab says so.
    result = model.compute(cache, Request(1, params, "accuracy"))
    assert result is not None
    assert isinstance(result.data, Notice)
    assert "single punch" in model.to_csv(result.data, params)
    # The load sweep does not change a train's own loads; R/h does.
    result = model.compute(cache, Request(1, params, "sweep"))
    assert result is not None
    assert isinstance(result.data, Notice)
    spec = model.SweepSpec(param="radius", values=(50.0, 100.0))
    result = model.compute(cache, Request(1, params, "sweep", sweep=spec))
    assert result is not None
    assert isinstance(result.data, Curves)
    assert np.all(np.isfinite(result.data.series[0].values))


def test_a_train_keeps_a_scenes_own_profiles() -> None:
    punches = [
        mp.Punch(mp.RoundedFlat(0.3, 50.0), 0.002, at=-2.0),
        mp.Punch(80.0, 0.002, at=2.0),
    ]
    train = model.train_from(punches)
    params = replace(Params(), punches=train)
    built = params.train()
    assert built[0].profile == punches[0].profile
    assert built[1].profile == punches[1].profile
    assert [p.at for p in built] == [-2.0, 2.0]


# -- the app --------------------------------------------------------------------


@sync
async def test_a_separated_contact_shows_its_zones() -> None:
    app = app_at(SEPARATED)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        text = summary_text(app)
        ref = mp.solve(vstar=SEPARATED.vstar, kw=0.1, radius=100.0, load=0.002)
        assert isinstance(ref, mp.ZonedSolution)
        assert "2 zones" in text
        (l1, r1), (l2, r2) = ref.contact_zones
        assert f"[{model.fmt(l1, 4)},{model.fmt(r1, 4)}]" in text
        assert f"[{model.fmt(l2, 4)},{model.fmt(r2, 4)}]" in text
        assert "INVALID" not in text
        assert status_ok(app), status_text(app)
        p = curves(app, "pressure")
        assert p.grid[0] < l1
        assert p.grid[-1] > r2
        assert len(p.markers) == 4
        rendered = str(screen_of(app).query_one("#plot-pressure", CurvePlot).render())
        assert "Contact pressure" in rendered
        # Every other tab renders the superposed solution.
        for tab in ("surface", "depth", "field"):
            await pilot.press(str(model.TABS.index(tab) + 1))
            await settle(pilot)
            assert "2 zones" in summary_text(app)
            assert status_ok(app), status_text(app)
        field = screen_of(app).query_one(StressMap)
        assert field.field is not None
        assert len(field.field.zones) == 2
        assert "2 zones" in str(field.render())

        # contact single: the old refusal on the status line
        await type_into(pilot, "contact", "single")
        assert screen_of(app).params.contact == "single"
        assert "unphysical contact" in status_text(app)
        assert "contact auto" in status_text(app)
        await type_into(pilot, "contact", "auto")
        assert status_ok(app), status_text(app)
        assert "2 zones" in summary_text(app)
        # garbage in the contact input is named there
        await type_into(pilot, "contact", "maybe")
        assert "contact must be auto or single" in message(app, "contact")
        assert "invalid " in status_text(app)


@sync
async def test_a_train_of_punches() -> None:
    app = app_at(Params())
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        assert "a/h" in summary_text(app)
        await type_into(pilot, "punches", TRAIN, paste=True)
        screen = screen_of(app)
        assert screen.params.punches == parse_punches(TRAIN)
        text = summary_text(app)
        ref = mp.solve_punches(
            [mp.Punch(100.0, 0.002, at=-1.5), mp.Punch(100.0, 0.002, at=1.5)],
            vstar=0.2,
            kw=1.0,
        )
        assert "2 punches" in text
        assert "2 zones" in text
        for k, punch in enumerate(ref.punches, start=1):
            assert f"#{k}@{model.fmt(punch.at, 4)}" in text
            assert f"δ/h {model.fmt(punch.indentation, 3)}" in text
        p = curves(app, "pressure")
        assert p.grid[0] < ref.contact_interval[0]
        assert p.grid[-1] > ref.contact_interval[1]
        # The plotted pressure is the train's (over P/h, P the total load).
        assert p.series[0].values == pytest.approx(ref.pressure(p.grid), abs=1e-9)
        assert status_ok(app), status_text(app)

        # garbage: a message naming the input, the last result stays
        await set_text(pilot, "punches", "0.002@-1.5, lots")
        assert message(app, "punches").startswith("punches: item 2")
        assert "invalid " in status_text(app)
        assert screen.params.punches == parse_punches(TRAIN)
        assert "2 punches" in summary_text(app)

        # punches whose contacts overlap: the solver's refusal, named
        await set_text(pilot, "punches", "0.002@0, 0.002@0.1")
        assert "punches" in message(app, "punches")
        assert "overlap" in status_text(app)

        # empty: the single punch again
        await type_into(pilot, "punches", "")
        assert screen.params.punches == ()
        assert message(app, "punches") == ""
        text = summary_text(app)
        assert "a/h" in text
        assert "punches" not in text
        assert not math.isnan(float(text.split("a/h ", 1)[1].split()[0]))


def test_a_train_and_the_contact_mode_survive_save_and_open(tmp_path: Path) -> None:
    """Save writes the train ([[punches]]) and the contact mode to the scene
    file; opening it gives the same parameters back."""
    from movingpunch.scene import Scene
    from movingpunch.tui import scene_files

    train = replace(Params(), punches=parse_punches(TRAIN))
    scene = scene_files.to_scene(SceneState(params=train))
    assert [p.at for p in scene.punches] == [p.at for p in train.punches]
    path = tmp_path / "train.toml"
    scene.save(path)
    back = scene_files.from_scene(Scene.load(path))
    # The same loads and positions (the punches come back with their shape
    # written out: cylinders of the panel's radius).
    assert [(p.load, p.at) for p in back.params.punches] == [
        (p.load, p.at) for p in train.punches
    ]
    assert all(p.profile == mp.Cylinder(train.radius) for p in back.params.punches)
    single = replace(Params(), contact="single")
    again = scene_files.from_scene(scene_files.to_scene(SceneState(params=single)))
    assert again.params.contact == "single"
    assert scene_files.to_scene(SceneState(params=Params())).params["load"] == 0.002
    # A bundled train opens as a train.
    bogie = scene_files.from_scene(Scene.bundled("bogie"))
    assert len(bogie.params.punches) == 4


@pytest.mark.parametrize("name", ["two-axle", "bogie", "spacing", "separated"])
@sync
async def test_the_bundled_zone_scenes_open_in_the_app(name: str) -> None:
    """Each bundled scene of several zones opens (the way `movingpunch tui
    NAME` does), solves and renders every tab."""
    from movingpunch.scene import Scene
    from movingpunch.tui import scene_files

    state = scene_files.from_scene(Scene.bundled(name))
    app = create_app(state, show_timing=False, cursor_blink=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        assert "zones" in summary_text(app), summary_text(app)
        for tab in model.TABS:
            await pilot.press(str(model.TABS.index(tab) + 1))
            await settle(pilot)
            assert "Traceback" not in status_text(app)
        assert "zones" in summary_text(app)


@sync
async def test_the_spacing_scene_sweeps_its_spacing() -> None:
    """The bundled ``spacing`` scene's a/h tab sweeps the train's spacing
    (it said "unknown parameter 'spacing'"): each point is the train placed
    as the scene places it, centred on x = 0, solved independently here."""
    from movingpunch.scene import Scene
    from movingpunch.tui.scene_files import from_scene

    state = from_scene(Scene.bundled("spacing"))
    app = create_app(state, show_timing=False, cursor_blink=False, tab="sweep")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        c = curves(app, "sweep")
        assert c.grid_label == "spacing/h"
        assert status_ok(app), status_text(app)
        p = state.params
        for j in (0, len(c.grid) // 2, len(c.grid) - 1):
            s = float(c.grid[j])
            ref = mp.solve_punches(
                [
                    mp.Punch(p.radius, 0.002, at=-s / 2),
                    mp.Punch(p.radius, 0.002, at=s / 2),
                ],
                vstar=p.vstar,
                kw=p.kw,
                nu=p.nu,
            )
            assert c.series[0].values[j] == pytest.approx(ref.a, rel=1e-9)
        # w cycles the sweep: load (a notice for a train), radius, spacing.
        await pilot.press("w")
        await settle(pilot)
        assert screen_of(app).sweep.param == "load"
        await pilot.press("w", "w")
        await settle(pilot)
        assert screen_of(app).sweep.param == "spacing"


def test_spacing_needs_a_train() -> None:
    with pytest.raises(InvalidParameterError, match="spacing: applies to a train"):
        Params().with_value("spacing", 3.0)
    train = Params(punches=parse_punches("0.002@0, 0.001@1, 0.002@5"))
    spaced = train.with_value("spacing", 4.0)
    assert [q.at for q in spaced.punches] == [-4.0, 0.0, 4.0]
    assert [q.load for q in spaced.punches] == [0.002, 0.001, 0.002]
    assert spaced.get("spacing") == 4.0
    assert math.isnan(Params().get("spacing"))
