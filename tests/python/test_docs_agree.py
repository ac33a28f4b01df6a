"""The README and docs/tui.md agree with the app and the package: the tab
keys, the bundled scenes (issue 16: the README said keys 1-6 and docs/tui.md
1-5; the README's scene list lacked a scene)."""

from __future__ import annotations

import re
from pathlib import Path

import movingpunch as mp
from movingpunch.tui import model

ROOT = Path(__file__).resolve().parents[2]


def test_the_tab_keys_agree_with_the_app() -> None:
    tabs = len(model.TABS)
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    tui = (ROOT / "docs" / "tui.md").read_text(encoding="utf-8")
    assert re.findall(r"`1`\u2013`(\d)`", readme) == [str(tabs)]  # an en dash
    assert re.findall(r"`1` … `(\d)`", tui) == [str(tabs)]


def test_every_bundled_scene_is_listed_in_the_readme() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    lists = [line for line in readme.splitlines() if "table1, fig2 ... fig6" in line]
    assert lists
    for line in lists:
        for name in mp.bundled_scenes():
            if re.fullmatch(r"fig[2-6]", name):
                continue  # "fig2 ... fig6"
            assert re.search(rf"\b{re.escape(name)}\b", line), (name, line)
