"""The terminal UI's layout at 80x24 and 120x40: every tab of every kind of
scene (the paper's model with an overlay, damping, friction, several contact
zones, a train of punches, near the critical speed), captured as plain text
and scanned: no line wraps or is cut, no label is truncated, no unit is left
alone on a line, and no message is cut at its widget's edge (a message is
whole, or a summary ending in the ellipsis, never a sentence broken off).

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
from movingpunch.tui.model import TABS, Overlay, Params
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
    "overlay-supercritical": "",  # an overlay member above V*_cr (issue 25)
}
"""Layout variants: their bundled scenes."""


def state_of(variant: str) -> SceneState:
    if VARIANTS[variant]:
        return from_scene(Scene.bundled(VARIANTS[variant]))
    if variant == "overlay-supercritical":  # `v`, V* 0.2, 0.9, 1.2 on kw 1
        return SceneState(Params(), overlay=Overlay("vstar", (0.2, 0.9, 1.2)))
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
    out += cut_messages(shot)
    # No unit alone at the start of a line of text (the plots' own axis
    # titles start their line by design: they are phrases above).
    for i, line in enumerate(lines):
        for part in re.split(r"[▕│]", line):
            words = part.split()
            if words and words[0] in UNITS:
                out.append(f"line {i}: a lone unit {part.strip()!r}")
    return out


ELLIPSIS = "…"


def cut_messages(shot: Shot) -> list[str]:
    """Messages cut at their widget's edge: what is visible of a message
    must be the whole message, or a summary whose every piece is a piece of
    the message ending at a word's end and marked by the ellipsis. Text
    that stops mid-word, or short of the message's end without the
    ellipsis (a clipped area, a hidden line), is a cut sentence."""
    out = []
    for whole, visible in shot.messages:
        full, seen = " ".join(whole.split()), " ".join(visible.split())
        if seen == full:
            continue
        pieces = [p.strip() for p in seen.split(ELLIPSIS)]
        at = 0
        for k, piece in enumerate(pieces):
            last = k == len(pieces) - 1
            if not piece:
                continue
            found = full.find(piece, at)
            end = found + len(piece)
            if found < 0:
                out.append(f"message cut: {piece!r} is not in {full!r}")
                break
            if not last and end < len(full) and full[end].isalnum():
                out.append(f"message cut mid-word: {piece!r}{ELLIPSIS}")
                break
            if last and end < len(full):
                out.append(
                    f"message cut mid-sentence: {seen!r} stops at the edge of "
                    f"its area before {full[end:][:30]!r}, with no {ELLIPSIS}"
                )
            at = end
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
    if variant == "overlay-supercritical":  # the message shows, whole or summed up
        for tab, shot in taken.items():
            if tab != "help":
                assert any(
                    "0.9" in seen and "at or above" in seen for _, seen in shot.messages
                ), (tab, shot.messages)
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


def test_scanner_finds_a_cut_sentence() -> None:
    """A message clipped at its area's edge (issue 25: the overlay's
    supercritical member cut after "at or above the critical") fails; the
    whole message, or a summary ending in the ellipsis, passes."""
    whole = (
        "overlay vstar: 0.2, 0.9  V*=0.9: vstar = 0.9 is at or above the "
        "critical speed V*_cr = 0.5716928222 of this layer on its foundation"
    )
    clipped = (
        "overlay vstar: 0.2, 0.9  V*=0.9: vstar = 0.9 is at or above\nthe critical"
    )
    assert any(
        "mid-sentence" in p
        for p in cut_messages(Shot("", "", messages=((whole, clipped),)))
    )
    mid_word = "overlay vstar: 0.2, 0.9  V*=0.9: vstar = 0.9 is at or above the crit…"
    assert any(
        "mid-word" in p
        for p in cut_messages(Shot("", "", messages=((whole, mid_word),)))
    )
    summary = (
        "overlay vstar: 0.2, 0.9  V*=0.9: vstar = 0.9 is at or above\n"
        "the critical speed…"
    )
    assert cut_messages(Shot("", "", messages=((whole, summary),))) == []
    middle = "overlay vstar: 0.2, 0.9  V*=0.9: vstar = 0.9…; showing the last result"
    assert (
        cut_messages(
            Shot("", "", messages=((whole + "; showing the last result", middle),))
        )
        == []
    )
    assert (
        cut_messages(Shot("", "", messages=((whole, whole.replace(" ", "\n")),))) == []
    )


def test_the_scanner_catches_a_clipped_message_area(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """On the real app: with the summary's line budget lifted above what
    the message area's container shows (the area before issue 25: 4 lines,
    then clipped), the supercritical overlay's message is cut and the scan
    says so; with the budget, it is summarised and passes."""
    from movingpunch.tui.widgets import params

    state = state_of("overlay-supercritical")
    monkeypatch.setattr(params, "STATUS_LINES", (9, 9))
    monkeypatch.setattr(params.MessageLine, "max_lines", lambda self, rows: 9)
    clipped = asyncio.run(shots(state, ("pressure",), (80, 24)))["pressure"]
    assert any("mid-sentence" in p for p in problems(clipped, (80, 24)))
    monkeypatch.undo()
    fitted = asyncio.run(shots(state, ("pressure",), (80, 24)))["pressure"]
    assert problems(fitted, (80, 24)) == []
    assert ELLIPSIS in fitted.messages[0][1]


@pytest.mark.parametrize("size", SIZES, ids=[f"{w}x{h}" for w, h in SIZES])
def test_a_message_under_an_input_fits(size: tuple[int, int]) -> None:
    """V* typed above V*_cr: the message under V* and the status line are
    whole or summarised, never cut, and the full text is one key away."""
    from textual.widgets import Input

    from movingpunch.tui.app import create_app
    from movingpunch.tui.screens.help import MessagesScreen
    from movingpunch.tui.screens.main import MainScreen
    from movingpunch.tui.screenshots import screen_text, settled, visible_messages

    async def run() -> None:
        app = create_app(SceneState(Params()), show_timing=False, cursor_blink=False)
        async with app.run_test(size=size) as pilot:
            await settled(pilot)
            screen = app.screen
            assert isinstance(screen, MainScreen)
            box = screen.query_one("#in-vstar", Input)
            box.focus()
            box.value = "0.95"
            await pilot.press("enter")
            await settled(pilot)
            text = screen_text(app)
            shot = Shot(text, "", messages=visible_messages(screen, text))
            assert len(shot.messages) == 2, shot.messages  # under V*, and the status
            assert cut_messages(shot) == []
            assert all(len(line) <= size[0] for line in text.splitlines())
            under_v = screen.query_one("#msg-vstar")
            assert "0.95" in str(under_v.render())
            await pilot.press("x")
            await pilot.pause()
            full = app.screen
            assert isinstance(full, MessagesScreen)
            assert "need 0 <= V* < V*_cr" in full.text
            await pilot.press("escape")

    asyncio.run(run())


def test_fit_summarises_after_a_clause_and_keeps_short_items() -> None:
    """``fit``: a message that fits is unchanged; one that does not is cut
    after a whole clause or word of its longest item and ends in the
    ellipsis, the short item after it (``; showing the last result``)
    whole, and it then fits its lines."""
    from rich.text import Text

    from movingpunch.tui.widgets.params import fit, line_count

    error = (
        "V*: vstar = 0.9 is at or above the critical speed V*_cr = 0.5716928222 "
        "of this layer on its foundation (Rayleigh value V*_R = 0.8299135134); "
        "no bounded steady solution exists there: vstar must be in [0, 0.57169)"
    )
    text = Text()
    text.append(error, "bold red")
    text.append("; showing the last result", "yellow")
    same, shortened = fit(text, 400, 1)
    assert (same.plain, shortened) == (text.plain, False)
    for width, lines in ((78, 2), (78, 1), (40, 3), (28, 3)):
        short, shortened = fit(text, width, lines)
        assert shortened
        assert line_count(short.plain, width) <= lines, (width, short.plain)
        head, _, tail = short.plain.partition(ELLIPSIS)
        assert error.startswith(head)
        assert not error[len(head)].isalnum()  # never mid-word
        assert tail == "; showing the last result"
        assert short.spans[-1].style == "yellow"
    assert fit(text, 78, 2)[0].plain.startswith(
        "V*: vstar = 0.9 is at or above the critical speed V*_cr = 0.5716928222 "
        "of this layer on its foundation…"  # the clause before "(Rayleigh"
    )
