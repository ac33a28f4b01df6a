"""The movingpunch terminal UI (Textual).

``movingpunch`` (no arguments) or ``movingpunch tui [SCENE|NAME]`` starts it;
``create_app`` builds it for tests and for ``movingpunch serve``.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from textual.app import App

from movingpunch.tui.model import PAPER_FIG4, TabName
from movingpunch.tui.paths import WorkingFolder
from movingpunch.tui.scene_files import SceneState
from movingpunch.tui.screens.main import MainScreen


class MovingPunchApp(App[None]):
    """Edit the parameters, watch the contact pressure and stresses move."""

    CSS_PATH = "app.tcss"
    ENABLE_COMMAND_PALETTE = False
    TITLE = "movingpunch"
    SUB_TITLE = "rigid punch sliding over a layer on a Winkler foundation"

    def __init__(
        self,
        scene: SceneState | None = None,
        *,
        show_timing: bool = True,
        cursor_blink: bool = True,
        tab: TabName = "pressure",
        folder: WorkingFolder | None = None,
    ) -> None:
        super().__init__()
        self.scene = scene or SceneState(params=PAPER_FIG4, name="fig4")
        self.folder = folder or WorkingFolder.at()
        self._show_timing = show_timing
        self._cursor_blink = cursor_blink
        self._tab = tab

    def on_mount(self) -> None:
        self.push_screen(self.main_screen())

    def main_screen(self) -> MainScreen:
        return MainScreen(
            self.scene.params,
            overlay=self.scene.overlay,
            sweep=self.scene.sweep,
            show_timing=self._show_timing,
            cursor_blink=self._cursor_blink,
            tab=self._tab,
            folder=self.folder,
        )


def create_app(
    scene: str | Path | SceneState | None = None,
    *,
    show_timing: bool = True,
    cursor_blink: bool = True,
    tab: TabName = "pressure",
    root: str | Path | None = None,
) -> MovingPunchApp:
    """The app on a scene: a SceneState, a scene file, a bundled scene's name,
    or None for the paper's Fig. 4 case (V* = 0.2, kw h/μ = 1, R/h = 100,
    P/(μh) = 0.002, ν = 0.2). ``show_timing=False`` hides the solve time (for
    reproducible screenshots); ``cursor_blink=False`` freezes the cursor.
    ``root``: the working folder Open, Save and Export stay in (default: the
    current directory).

    Raises SceneError if the scene cannot be read, InvalidParameterError if
    ``root`` is not a directory.
    """
    from movingpunch.tui import scene_files

    state = (
        scene
        if isinstance(scene, SceneState) or scene is None
        else scene_files.load(scene)
    )
    return MovingPunchApp(
        state,
        show_timing=show_timing,
        cursor_blink=cursor_blink,
        tab=tab,
        folder=WorkingFolder.at(root),
    )


def main(
    scene: str | None = None,
    *,
    show_timing: bool = True,
    root: str | Path | None = None,
) -> int:
    """Runs the app in this terminal; returns the exit status."""
    app = create_app(scene, show_timing=show_timing, root=root)
    app.run()
    return 0


def run(argv: Sequence[str] | None = None) -> int:
    """``python -m movingpunch.tui [SCENE]``."""
    args = list(argv or [])
    return main(args[0] if args else None)
