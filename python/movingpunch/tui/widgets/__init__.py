"""Widgets of the terminal UI."""

from movingpunch.tui.widgets.accuracy import AccuracyView
from movingpunch.tui.widgets.params import Gauge, ParamsPanel
from movingpunch.tui.widgets.plots import CurvePlot, StressMap

__all__ = ["AccuracyView", "CurvePlot", "Gauge", "ParamsPanel", "StressMap"]
