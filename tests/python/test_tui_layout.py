"""The terminal UI's layout at 80x24 and 120x40: every tab of every kind of
scene (the paper's model with an overlay, damping, friction, several contact
zones, a train of punches, near the critical speed), captured as plain text
and scanned: no line wraps or is cut, no label is truncated, no unit is left
alone on a line.

Each screen is also a text snapshot (``tests/python/__screens__``): a change
of layout shows as a diff. After an intended change, regenerate them with
``MOVINGPUNCH_UPDATE_SCREENS=1 pytest tests/python/test_tui_layout.py``
and review the diff. The Accuracy tab shows measured times: it is scanned,
not compared.
"""

from __future__ import annotations

import asyncio
import os
import re
from pathlib import Path

import pytest

import movingpunch as mp
from movingpunch.scene import Scene
from movingpunch.tui.model import TABS, Params
from movingpunch.tui.scene_files import SceneState, from_scene
from movingpunch.tui.screenshots import SIZES, Shot, shots

SCREENS = Path(__file__).resolve().parent / "__screens__"
UPDATE = os.environ.get("MOVINGPUNCH_UPDATE_SCREENS") == "1"

VARIANTS: dict[str, str] = {
    "paper": "fig4",  # no damping, an overlay of four speeds
    "damped": "damped",
    "friction": "friction",
    "zones": "separated",
    "train": "bogie",
    "critical": "",  # V* 0.5 % below V*_cr, a large load: the hints show
}
"""Layout variants: their bundled scenes."""


def state_of(variant: str) -> SceneState:
    if VARIANTS[variant]:
        return from_scene(Scene.bundled(VARIANTS[variant]))
    vcr = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002).critical_vstar
    return SceneState(Params(vstar=round(0.995 * vcr, 6), load=0.2))


UNITS = frozenset({"ms", "s", "%", "h", "P/h", "(P/h)", "μ", "μh", "mm"})
"""Tokens that must never start a line of text (a value's unit wrapped away
from it); the axes' titles x/h and y/h do, by design."""

_cache: dict[tuple[str, tuple[int, int]], dict[str, Shot]] = {}


def screens(variant: str, size: tuple[int, int]) -> dict[str, Shot]:
    key = (variant, size)
    if key not in _cache:
        _cache[key] = asyncio.run(
            shots(state_of(variant), TABS, size, help_screen=True)
        )
    return _cache[key]


def problems(shot: Shot, size: tuple[int, int]) -> list[str]:
    """What is wrong with one screen (empty: nothing)."""
    width, height = size
    lines = shot.text.rstrip("\n").split("\n")
    out = []
    if len(lines) != height:
        out.append(f"{len(lines)} lines, not {height}")
    out += [f"line {i} is {len(x)} wide" for i, x in enumerate(lines) if len(x) > width]
    # Every phrase whole on one line (a cut label, a split field fails).
    for phrase in shot.phrases:
        if not any(phrase in line for line in lines):
            out.append(f"{phrase!r} is not whole on any line")
    # The message area wraps at spaces: each of its words is whole somewhere.
    tokens = {t for line in lines for t in line.split()}
    out += [f"status word {w!r} broken" for w in shot.status.split() if w not in tokens]
    # No unit alone at the start of a line of text (the plots' own axis
    # titles start their line by design: they are phrases above).
    for i, line in enumerate(lines):
        for part in re.split(r"[▕│]", line):
            words = part.split()
            if words and words[0] in UNITS:
                out.append(f"line {i}: a lone unit {part.strip()!r}")
    return out


CASES = [(v, s) for v in VARIANTS for s in SIZES]


@pytest.mark.parametrize(
    ("variant", "size"), CASES, ids=[f"{v}-{w}x{h}" for v, (w, h) in CASES]
)
def test_every_tab_fits(variant: str, size: tuple[int, int]) -> None:
    taken = screens(variant, size)
    assert set(taken) == {*TABS, "help"}
    if variant == "critical":  # the hints are in the message area, whole
        status = taken["pressure"].status
        assert "hint:" in status
        assert "of V*_cr" in status
        assert "beyond small-strain linear theory" in status
    found = {name: problems(shot, size) for name, shot in taken.items()}
    found = {name: p for name, p in found.items() if p and name != "help"}
    assert not found, found
    for name, shot in taken.items():
        if name in ("accuracy", "help"):
            continue
        path = SCREENS / f"{variant}-{name}-{size[0]}x{size[1]}.txt"
        if UPDATE or not path.exists():
            assert UPDATE, (
                f"{path.name} is missing: run with MOVINGPUNCH_UPDATE_SCREENS=1"
            )
            path.parent.mkdir(exist_ok=True)
            path.write_text(shot.text, encoding="utf-8")
        assert shot.text == path.read_text(encoding="utf-8"), (
            f"{path.name} changed; if intended, regenerate (module docstring)"
        )


def test_scanner_finds_broken_layouts() -> None:
    """The scan itself: a wrapped unit, a cut label, a too-long line fail."""
    good = Shot("a/h 0.33  it 9  0.6 ms\nready\n", "", ("a/h 0.33", "0.6 ms"), "ready")
    assert problems(good, (40, 2)) == []
    wrapped = Shot("a/h 0.33  it 9  0.6\nms\n", "", ("0.6 ms",), "")
    found = problems(wrapped, (40, 2))
    assert any("'0.6 ms'" in p for p in found)
    assert any("lone unit" in p for p in found)
    cut = Shot("p(x)  σx(x,0)  Accurac\n", "", ("Accuracy",), "")
    assert any("Accuracy" in p for p in problems(cut, (40, 1)))
    wide = Shot("x" * 41 + "\n", "", (), "")
    assert any("41 wide" in p for p in problems(wide, (40, 1)))
    broken = Shot(
        "V* is at or above the cri-\ntical speed\n", "", (), "the critical speed"
    )
    assert any("critical" in p for p in problems(broken, (40, 2)))
