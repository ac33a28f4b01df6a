"""Screenshots of the terminal UI: its screen as plain text (what the layout
tests scan) and as SVG (the gallery in docs/tui.md, written by
``scripts/gallery.py``).

Each screenshot runs the app headless at a given terminal size on a scene,
shows one tab, waits for every solve and captures the screen. The solve time
is hidden and the cursor does not blink, so the same scene gives the same
picture.
"""

from __future__ import annotations

import asyncio
import contextlib
import io
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from rich.console import Console
from textual.app import App
from textual.errors import NoWidget
from textual.pilot import Pilot
from textual.worker import WorkerFailed

from movingpunch import clear_kernel_cache
from movingpunch.scene import Scene
from movingpunch.tui.app import create_app
from movingpunch.tui.model import TABS, TabName
from movingpunch.tui.scene_files import SceneState, from_scene
from movingpunch.tui.screens.main import MainScreen

SIZES: tuple[tuple[int, int], ...] = ((80, 24), (120, 40))
"""The terminal sizes of the gallery and the layout tests."""

GALLERY_SCENE = "fig4"
"""The gallery's scene: the paper's Fig. 4 case."""


@dataclass(frozen=True)
class Shot:
    """One screen: its plain text (a line per terminal row), its SVG, and
    the phrases it must show whole (``phrases``)."""

    text: str
    svg: str
    phrases: tuple[str, ...] = ()
    status: str = ""
    """The message area's text (it wraps: checked word by word)."""
    messages: tuple[tuple[str, str], ...] = ()
    """Each message area on screen: (its whole text, the text visible in
    its region of the screen), to find a message cut at its widget's edge."""


def phrases(screen: MainScreen) -> tuple[str, ...]:
    """What the main screen must show whole, each on one line: the tab
    names, the summary's fields, the panel's group titles and visible labels,
    and the visible plot's title, axis labels and legend entries."""
    from textual.widgets import Label, TabbedContent

    from movingpunch.tui.widgets import CurvePlot, ParamsPanel
    from movingpunch.tui.widgets.fields import FieldsLine
    from movingpunch.tui.widgets.plots import legend

    out: list[str] = []
    tabs = screen.query_one("#tabs", TabbedContent)
    out += [str(tabs.get_tab(f"tab-{tab}").label) for tab in TABS]
    out += [f.text() for f in screen.query_one("#summary", FieldsLine).fields]
    panel = screen.query_one(ParamsPanel)
    out += [str(label.render()) for label in panel.query(".group-title").results(Label)]
    for row in panel.query(".param-row"):
        if row.display:
            out += [str(label.render()) for label in row.query(Label)]
    plot = screen.query_one(f"#plot-{screen.tab}")
    if isinstance(plot, CurvePlot) and plot.curves is not None:
        c = plot.curves
        out += [c.title, c.grid_label, c.value_label]
        out += [f.text() for f in legend(c)]
    return tuple(p for p in out if p.strip())


def visible_messages(screen: MainScreen, text: str) -> tuple[tuple[str, str], ...]:
    """(whole text, text visible on ``text``, the screen's plain text) of
    every message area with a message: the status line and the messages
    under the inputs. The visible text is read from the screen inside the
    widget's region clipped by its containers."""
    rows = text.split("\n")
    out = []
    for widget in screen.query("#status, .param-msg"):
        whole = getattr(widget, "full", None)
        if whole is None:  # a plain Static: its whole text
            whole = str(widget.render())
        if not whole.strip() or not widget.display:
            continue
        try:
            where = screen.find_widget(widget)
        except NoWidget:  # not on screen (a hidden row, scrolled away)
            out.append((whole, ""))
            continue
        seen = where.region.intersection(where.clip)
        lines = [
            rows[y][seen.x : seen.right] if y < len(rows) else ""
            for y in range(seen.y, seen.bottom)
        ]
        out.append((whole, "\n".join(lines)))
    return tuple(out)


def screen_text(app: App[None]) -> str:
    """The app's screen as plain text, one line per row (styles dropped)."""
    width, height = app.size
    console = Console(
        width=width,
        height=height,
        file=io.StringIO(),
        force_terminal=True,
        color_system="truecolor",
        record=True,
        legacy_windows=False,
        safe_box=False,
    )
    console.print(
        app.screen._compositor.render_update(
            full=True, screen_stack=app._background_screens
        )
    )
    return console.export_text(styles=False)


async def settled(pilot: Pilot[None]) -> None:
    """Waits until no solve is pending (a typed value waiting for the
    user's pause) or running, its messages are handled and the screen is
    drawn. A worker that raised is no error here: the app shows its error
    inline, on the screen."""
    await pilot.pause()
    while True:
        with contextlib.suppress(WorkerFailed):
            await pilot.app.workers.wait_for_complete()
        await pilot.pause()
        screen = pilot.app.screen
        pending = isinstance(screen, MainScreen) and screen.solve_pending
        if not pending and not any(w.is_running for w in pilot.app.workers):
            break
        await pilot.pause(0.05)
    await pilot.wait_for_scheduled_animations()
    await pilot.pause()


async def shots(
    scene: SceneState,
    tabs: Sequence[TabName],
    size: tuple[int, int],
    *,
    help_screen: bool = False,
) -> dict[str, Shot]:
    """The screens of ``tabs`` (and the help, with ``help_screen``) of the
    app on ``scene`` at ``size``, keyed by tab name (``"help"``)."""
    # The iteration counts in the summary depend on the kernel tables an
    # earlier solve in this process left behind: start from none.
    clear_kernel_cache()
    app = create_app(scene, show_timing=False, cursor_blink=False)
    app.animation_level = "none"  # the tab underline does not slide
    out: dict[str, Shot] = {}
    async with app.run_test(size=size) as pilot:
        await settled(pilot)
        screen = app.screen
        assert isinstance(screen, MainScreen)
        for tab in tabs:
            screen.action_show_tab(tab)
            await settled(pilot)
            text = screen_text(app)
            out[tab] = Shot(
                text,
                _svg(app, f"movingpunch: {tab}"),
                phrases(screen),
                str(screen.query_one("#status").render()),
                visible_messages(screen, text),
            )
        if help_screen:  # over the first tab (the same picture every time)
            screen.action_show_tab(tabs[0] if tabs else "pressure")
            await settled(pilot)
            await pilot.press("question_mark")
            await pilot.pause()
            out["help"] = Shot(screen_text(app), _svg(app, "movingpunch: help"))
            await pilot.press("escape")
    return out


def _svg(app: App[None], title: str) -> str:
    """The SVG screenshot with its random-looking ids made stable (the same
    screen gives the same file)."""
    svg = app.export_screenshot(title=title)
    return re.sub(r"terminal-\d+", "terminal", svg)


def gallery_name(tab: str, size: tuple[int, int]) -> str:
    """``tui-pressure-80x24.svg``: a gallery file's name."""
    return f"tui-{tab}-{size[0]}x{size[1]}.svg"


def write_gallery(folder: Path, scene: str = GALLERY_SCENE) -> list[Path]:
    """Writes the gallery (every tab and the help at every size of
    ``SIZES``) into ``folder``; returns the files written."""
    state = from_scene(Scene.bundled(scene))
    written = []
    folder.mkdir(parents=True, exist_ok=True)
    for size in SIZES:
        taken = asyncio.run(shots(state, TABS, size, help_screen=True))
        for tab, shot in taken.items():
            path = folder / gallery_name(tab, size)
            tmp = path.with_name(f".{path.name}.tmp")
            tmp.write_text(shot.svg, encoding="utf-8")
            tmp.replace(path)
            written.append(path)
    return written
