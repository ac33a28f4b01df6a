"""The TUI's plots as a person reads them: the stress map of a flat punch
(whose pressure is singular at its sharp edges x = ±b) has no NaN, no
RuntimeWarning, and says where it masks a point; overlaid curves each keep
their own marker on the canvas, named by the legend below the plot."""

from __future__ import annotations

import re

import numpy as np
import pytest
from textual.app import App, ComposeResult

import movingpunch as mp
from movingpunch.tui import create_app, model
from movingpunch.tui.model import Curves, FieldMap, Params, Series
from movingpunch.tui.scene_files import SceneState
from movingpunch.tui.widgets import CurvePlot, StressMap
from movingpunch.tui.widgets.plots import MARKERS, MASK_MARK, legend
from tui_pilot import settle, summary_text, sync, type_into

SIZES = ((80, 20), (118, 34))


class _One(App[None]):
    """An app holding one widget, to render it at a size."""

    def __init__(self, widget: StressMap | CurvePlot) -> None:
        super().__init__()
        self.widget = widget

    def compose(self) -> ComposeResult:
        yield self.widget


async def _rendered(widget: StressMap | CurvePlot, size: tuple[int, int]) -> str:
    app = _One(widget)
    async with app.run_test(size=size) as pilot:
        await pilot.pause()
        return str(widget.render())


def _flat_map(quantity: model.FieldQuantity) -> FieldMap:
    # b = 0.5 on the TUI's grid x = linspace(-2, 2, 97): two columns land
    # exactly on x = ±b, where the pressure is infinite.
    data = model._field(model.Cache(), Params(profile="flat"), quantity)
    assert 0.5 in data.x
    assert -0.5 in data.x
    return data


@pytest.mark.parametrize("quantity", ["von_mises", "sigma_x"])
def test_a_flat_punchs_map_masks_its_singular_edges(
    quantity: model.FieldQuantity,
) -> None:
    data = _flat_map(quantity)  # filterwarnings=error: no RuntimeWarning
    assert not np.isnan(data.values).any()
    bad = np.argwhere(~np.isfinite(data.values))
    # Only the two surface points on the edges are not finite.
    assert {(int(i), float(data.x[j])) for i, j in bad} == {
        (len(data.y) - 1, -0.5),
        (len(data.y) - 1, 0.5),
    }
    for size in SIZES:
        text = sync_render(StressMap(), data, size)
        assert f"{MASK_MARK} masked: singular at x/h = ±0.5" in text
        assert text.count(MASK_MARK) == 3  # two edges and the legend's
        # The colour bar spans the finite values (not -inf .. inf).
        assert "inf" not in text
        assert "nan" not in text


def test_a_cylinders_map_has_no_mask_legend() -> None:
    data = model._field(model.Cache(), Params(), "von_mises")
    assert np.isfinite(data.values).all()
    text = sync_render(StressMap(), data, (80, 20))
    assert "masked" not in text
    assert MASK_MARK not in text


def test_the_api_field_at_a_flat_edge_is_infinite_never_nan() -> None:
    s = mp.solve(vstar=0.2, kw=1.0, profile=mp.Flat(0.5), load=0.002, friction=0.3)
    x = np.linspace(-2.0, 2.0, 9)  # lands on ±0.5
    f = s.stress_field(x, np.linspace(-1.0, 0.0, 5))
    for name in ("sigma_x", "sigma_y", "tau_xy", "sigma_z", "von_mises", "max_shear"):
        assert not np.isnan(getattr(f, name)).any(), name
    top = f.von_mises[-1]
    assert np.isposinf(top[[3, 5]]).all()
    assert np.isposinf(f.max_shear[-1, [3, 5]]).all()
    assert np.isfinite(np.delete(top, [3, 5])).all()
    # Approaching the edge, the field grows without bound (1/sqrt(distance)).
    near = s.stress_field(np.array([0.5 - 1e-2, 0.5 - 1e-4]), np.array([0.0]))
    assert near.von_mises[0, 1] > 5.0 * near.von_mises[0, 0]


def sync_render(
    widget: StressMap | CurvePlot, data: object, size: tuple[int, int]
) -> str:
    if isinstance(widget, StressMap):
        assert isinstance(data, FieldMap)
        widget.field = data
    else:
        assert isinstance(data, Curves)
        widget.curves = data

    @sync
    async def run() -> None:
        out.append(await _rendered(widget, size))

    out: list[str] = []
    run()
    return out[0]


# --- overlaid curves ---------------------------------------------------------


def _crossing_curves(count: int) -> Curves:
    """``count`` curves that cross and coincide: the first flat, the others
    lines through it, the last equal to the one before (hidden by drawing
    order alone)."""
    x = np.linspace(0.0, 1.0, 41)
    series = [Series("V*=0.2", np.full_like(x, 0.5))]
    for k in range(1, count):
        slope = (-1.0) ** k * (0.4 + 0.1 * k)
        series.append(Series(f"V*={0.2 + 0.1 * k:g}", 0.5 + slope * (x - 0.5)))
    if count >= 3:
        series[-1] = Series(series[-1].label, series[-2].values.copy())
    return Curves(
        tab="pressure",
        title="Contact pressure",
        grid_label="x/h",
        value_label="p/(P/h)",
        grid=x,
        series=tuple(series),
    )


def _canvas(text: str) -> str:
    """The inside of the plot's frame (between its │ borders)."""
    rows = []
    for line in text.splitlines():
        m = re.search(r"[│┤](.*)│\s*$", line)
        if m:
            rows.append(m.group(1))
    return "\n".join(rows)


@pytest.mark.parametrize("count", [2, 3, 4, 5])
def test_overlaid_curves_each_keep_a_marker_named_by_the_legend(count: int) -> None:
    data = _crossing_curves(count)
    for size in SIZES:
        text = sync_render(CurvePlot(), data, size)
        canvas = _canvas(text)
        key = text.splitlines()[-3:]
        for k, series in enumerate(data.series):
            mark = MARKERS[k]
            assert mark in canvas, (series.label, text)
            assert f"{mark} {series.label}" in " ".join(key) or any(
                f"{mark}─ {series.label}" in line for line in key
            ), text
    entries = legend(data)
    assert [e.value for e in entries] == [s.label for s in data.series]
    assert len({e.label for e in entries}) == count  # one marker each


# --- the summary: round-off shown as 0 ----------------------------------------


def test_the_summary_shows_a_symmetric_damped_drag_as_0() -> None:
    # At rest on a damped foundation the contact is symmetric: drag 0 by
    # symmetry; the solver sums it to round-off (~1e-19).
    params = Params(vstar=0.0, damping=0.1)
    s = mp.solve(vstar=0.0, kw=1.0, radius=100.0, load=0.002, damping=0.1)
    assert abs(s.drag) < 1e-15
    moving = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, damping=0.1)
    texts: list[str] = []

    @sync
    async def run() -> None:
        app = create_app(SceneState(params=params), show_timing=False)
        async with app.run_test(size=(100, 32)) as pilot:
            await settle(pilot)
            texts.append(summary_text(app))
            await type_into(pilot, "vstar", "0.2", paste=True)
            texts.append(summary_text(app))

    run()
    at_rest, sliding = texts
    assert "drag/P 0 " in at_rest + " ", at_rest
    assert "e-1" not in at_rest.split("drag/P")[1].split()[0]
    # A real drag is shown as it is.
    assert f"drag/P {model.fmt(moving.drag, 4)}" in sliding, sliding
