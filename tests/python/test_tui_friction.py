"""Friction in the terminal UI (issue 14): the input, the summary's contact
interval and friction force, the asymmetric pressure plot, and the range
message. Numbers are checked against ``mp.solve``."""

from __future__ import annotations

import numpy as np

import movingpunch as mp
from movingpunch.asymmetric import AsymmetricSolution
from movingpunch.tui import create_app
from movingpunch.tui.model import Params, fmt
from movingpunch.tui.widgets import CurvePlot, ParamsPanel
from tui_pilot import screen_of, settle, summary_text, sync, type_into

SIZE = (100, 32)


@sync
async def test_friction_input_summary_and_pressure() -> None:
    app = create_app()
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = screen_of(app)
        assert screen.params.friction == 0.0
        await type_into(pilot, "friction", "0.3", paste=True)
        assert screen.params == Params(friction=0.3)
        s = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, friction=0.3)
        assert isinstance(s, AsymmetricSolution)
        text = summary_text(app)
        start, end = s.contact_interval
        assert f"(-b,a)/h ({start:.5g}, {end:.5g})" in text, text
        assert "friction/P 0.3" in text, text
        assert f"δ/h {fmt(s.indentation, 3)}" in text, text
        plot = screen.query_one("#plot-pressure", CurvePlot).curves
        assert plot is not None
        values = plot.series[0].values
        np.testing.assert_allclose(values, s.pressure(plot.grid), atol=1e-12)
        assert plot.grid[int(np.argmax(values))] < 0.0  # the peak moves back
        await type_into(pilot, "friction", "11", paste=True)
        message = screen.query_one(ParamsPanel).message("friction")
        assert "0 <= friction <= 10" in message, message
