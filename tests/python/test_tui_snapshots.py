"""Snapshots of the terminal UI: the gallery in docs/tui.md (SVG
screenshots of every tab and the help at 80x24 and 120x40 on the paper's
Fig. 4 scene, ``docs/images/tui-<tab>-<W>x<H>.svg``) is the stored picture,
and the app must still draw it. Deterministic: the solve time is hidden, the
cursor does not blink, the kernel cache starts empty, and every worker has
finished before a screen is taken (``movingpunch.tui.screenshots``).

The Accuracy tab shows measured times, which differ from run to run: its
file is checked to exist and the layout tests scan its screen.

Regenerate after an intended change of the screen, and review the diff:
``.venv/bin/python scripts/gallery.py``.
"""

from __future__ import annotations

import asyncio
import difflib
from pathlib import Path

import pytest

from movingpunch.scene import Scene
from movingpunch.tui.model import TABS
from movingpunch.tui.scene_files import from_scene
from movingpunch.tui.screenshots import GALLERY_SCENE, SIZES, gallery_name, shots

IMAGES = Path(__file__).resolve().parents[2] / "docs" / "images"
TIMED = frozenset({"accuracy"})
"""Tabs whose screen holds measured times (not compared)."""


@pytest.mark.parametrize("size", SIZES, ids=[f"{w}x{h}" for w, h in SIZES])
def test_the_app_still_draws_the_gallery(size: tuple[int, int]) -> None:
    state = from_scene(Scene.bundled(GALLERY_SCENE))
    taken = asyncio.run(shots(state, TABS, size, help_screen=True))
    assert set(taken) == {*TABS, "help"}
    changed = []
    for name, shot in taken.items():
        path = IMAGES / gallery_name(name, size)
        assert path.is_file(), f"{path.name} is missing: run scripts/gallery.py"
        stored = path.read_text(encoding="utf-8")
        assert stored.startswith("<svg")
        if name in TIMED or stored == shot.svg:
            continue
        diff = difflib.unified_diff(
            stored.splitlines(), shot.svg.splitlines(), lineterm="", n=0
        )
        changed.append(f"{path.name}:\n" + "\n".join(list(diff)[:12]))
    assert not changed, (
        "the screen changed; if intended, run scripts/gallery.py and review:\n"
        + "\n".join(changed)
    )


def test_the_gallery_is_in_the_docs() -> None:
    """docs/tui.md shows every picture of the gallery, and no stale one."""
    doc = (IMAGES.parent / "tui.md").read_text(encoding="utf-8")
    wanted = {gallery_name(t, s) for t in (*TABS, "help") for s in SIZES}
    for name in wanted:
        assert f"images/{name}" in doc, name
    stored = {p.name for p in IMAGES.glob("tui-*.svg")}
    assert stored == wanted
