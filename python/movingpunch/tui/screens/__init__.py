"""Screens of the terminal UI."""

from movingpunch.tui.screens.help import HelpScreen
from movingpunch.tui.screens.main import MainScreen
from movingpunch.tui.screens.prompts import OverlayPrompt, PathPrompt

__all__ = ["HelpScreen", "MainScreen", "OverlayPrompt", "PathPrompt"]
