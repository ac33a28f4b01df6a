"""The terminal UI in a real terminal: started in tmux at 80x24 as a user
starts it (``movingpunch`` with no arguments), driven with send-keys, read
back with capture-pane. tmux comes with scripts/setup.sh.
"""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator

import pytest

import movingpunch as mp
from extras import need
from movingpunch.tui.model import fmt

TIMEOUT = 60.0


class Tmux:
    """One tmux server on a private socket (never the user's), a socket file
    of its own per test: a server killed by the previous test may still be
    exiting when the next one starts (CI once failed on that race)."""

    def __init__(self, socket: str) -> None:
        self.socket = socket

    def run(self, *args: str, check: bool = True) -> str:
        proc = subprocess.run(
            ["tmux", "-S", self.socket, *args],
            capture_output=True,
            text=True,
            timeout=30,
            check=False,
        )
        if check and proc.returncode != 0:
            raise AssertionError(
                f"tmux {args[0]} failed ({proc.returncode}): {proc.stderr.strip()}"
            )
        return proc.stdout

    def alive(self) -> bool:
        proc = subprocess.run(
            ["tmux", "-S", self.socket, "has-session", "-t", "mp"],
            capture_output=True,
            timeout=30,
            check=False,
        )
        return proc.returncode == 0

    def screen(self) -> str:
        return self.run("capture-pane", "-p", "-t", "mp")

    def keys(self, *keys: str) -> None:
        self.run("send-keys", "-t", "mp", *keys)

    def wait_for(self, test: Callable[[str], bool], what: str) -> str:
        """The screen once ``test`` holds on it and it is drawn whole: the
        same on two captures 0.2 s apart (a capture may catch a frame half
        written to the terminal on a busy machine)."""
        deadline = time.monotonic() + TIMEOUT
        screen = ""
        while time.monotonic() < deadline:
            screen = self.screen()
            if test(screen):
                time.sleep(0.2)
                again = self.screen()
                if again == screen:
                    return screen
                continue
            time.sleep(0.2)
        raise AssertionError(f"timed out waiting for {what}; screen:\n{screen}")


@pytest.fixture
def tmux() -> Iterator[Tmux]:
    need("tmux")  # skipped without tmux (a failure under scripts/test.sh)
    folder = tempfile.mkdtemp(prefix="mp-tmux-")  # short: sockets cap paths near 100
    session = Tmux(os.path.join(folder, "socket"))
    command = shlex.join([sys.executable, "-m", "movingpunch"])
    session.run(
        "new-session", "-d", "-s", "mp", "-x", "80", "-y", "24", "env",
        "TERM=xterm-256color", *shlex.split(command),
    )  # fmt: skip
    session.run("set-option", "-g", "escape-time", "10")
    try:
        yield session
    finally:
        session.run("kill-server", check=False)
        deadline = time.monotonic() + 10.0
        while session.alive() and time.monotonic() < deadline:
            time.sleep(0.1)
        shutil.rmtree(folder, ignore_errors=True)


def a_text(vstar: float) -> str:
    """a/h as the summary line prints it."""
    return "a/h " + fmt(mp.solve(vstar=vstar, kw=1.0, radius=100.0, load=0.002).a)


def type_keys(tmux: Tmux, *keys: str, gap: float = 0.15) -> None:
    """Sends the keys one by one, ``gap`` seconds apart, as a person types."""
    for key in keys:
        tmux.keys(key)
        time.sleep(gap)


def input_value(screen: str, label: str) -> str:
    """The text of the input ``label`` as the panel shows it."""
    for line in screen.splitlines():
        if line.startswith(label + " "):
            return line.split("▕")[0].removeprefix(label).strip()
    raise AssertionError(f"no {label} input on the screen:\n{screen}")


def test_deleting_to_an_earlier_value_shows_its_result(tmux: Tmux) -> None:
    """Issue 25: ``i``, End, three BSpace, ``0``, Enter, keys 150 ms apart:
    deleting 0.2 passes through 0 (valid: solved after the pause), 0. and
    the empty box (being typed: the pending solve stops); the ``0`` typed
    then equals the last valid value. The screen showed V* 0.2's result and
    said "ready"; it shows V* 0's after enter. Then (back in the input) BSpace,
    ``0.3``, Enter: V* 0.3's, not one edit behind."""
    fig4 = a_text(0.2)
    tmux.wait_for(lambda s: fig4 in s and "ready" in s, "the Fig. 4 summary")
    type_keys(tmux, "i", "End", "BSpace", "BSpace", "BSpace", "0", "Enter")
    at_rest = a_text(0.0)
    assert at_rest == "a/h 0.330419"  # the value
    screen = tmux.wait_for(lambda s: at_rest in s, "the a/h of V* = 0")
    assert input_value(screen, "V*") == "0"
    assert fig4 not in screen
    screen = tmux.wait_for(lambda s: "ready" in s, "ready")
    assert at_rest in screen
    type_keys(tmux, "i", "BSpace", "0", ".", "3", "Enter")
    faster = a_text(0.3)
    screen = tmux.wait_for(lambda s: faster in s and "ready" in s, "V* = 0.3")
    assert input_value(screen, "V*") == "0.3"
    assert at_rest not in screen


TAB_CHECKS: dict[str, tuple[str, ...]] = {
    "1": ("Contact pressure", "p(x)/(P/h)", "x/h"),
    "2": ("σx on the surface y = 0", "σx(x,0)/(P/h)"),
    "3": ("σx under the centre x = 0", "σx(0,y)/(P/h)", "y/h"),
    "4": ("Contact half-width against", "a/h"),
    "5": ("σx/(P/h) under the punch", "x/h"),
    "6": ("Accuracy against time", "every estimate bounds its actual error"),
}
"""Keys 1-6 and what each tab shows (its title, axes and units)."""

TAB_BAR = ("p(x)", "σx(x)", "σx(y)", "sweep", "field", "accuracy")
"""The short tab names at 80 columns, every one whole."""


def assert_calm(screen: str) -> None:
    """80 columns, 24 rows; the tab names whole; no unit alone on a line."""
    lines = screen.rstrip("\n").split("\n")
    assert len(lines) <= 24
    assert all(len(line) <= 80 for line in lines)
    for name in TAB_BAR:
        assert f" {name} " in lines[0] + " ", (name, lines[0])
    for line in lines:
        assert line.split()[:1] not in (["ms"], ["h"], ["%"]), line


def test_every_tab_the_help_and_quit(tmux: Tmux) -> None:
    fig4 = a_text(0.2)
    screen = tmux.wait_for(lambda s: fig4 in s, "the Fig. 4 summary")
    assert "Contact pressure" in screen
    assert "p(x)/(P/h)" in screen
    assert "V*_cr 0.57169" in screen
    assert_calm(screen)

    tmux.keys("i")  # to the V* input
    tmux.wait_for(lambda s: "esc Leave input" in s, "the focus in the input")
    tmux.keys(*["BSpace"] * 8)
    # An empty box is still being typed into: no error, the result stays.
    screen = tmux.wait_for(lambda s: "typing V*" in s, "an empty V* input")
    assert fig4 in screen
    assert "showing the result for V* 0.2" in screen
    tmux.keys("0", ".", "3", "5")
    faster = a_text(0.35)
    screen = tmux.wait_for(lambda s: faster in s, "the a/h of V* = 0.35")
    assert fig4 not in screen
    tmux.keys("Escape")
    tmux.wait_for(lambda s: "Leave input" not in s, "the focus out of the input")

    for key, words in TAB_CHECKS.items():
        tmux.keys(key)
        screen = tmux.wait_for(
            lambda s, words=words: all(w in s for w in words), f"tab {key}"
        )
        assert faster in screen  # the summary stays under every tab
        assert_calm(screen)
    assert any(ch in screen for ch in "⠁⠂⠄⡀⢀⠠⠐⠈⣀⠤") or "1e-" in screen

    tmux.keys("?")
    screen = tmux.wait_for(lambda s: "Press escape" in s or "Keys" in s, "the help")
    assert all(len(line) <= 80 for line in screen.splitlines())
    tmux.keys("Escape")
    tmux.wait_for(lambda s: "Accuracy against time" in s, "the help closed")

    tmux.keys("q")
    deadline = time.monotonic() + TIMEOUT
    while tmux.alive() and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not tmux.alive(), "the app did not quit"
