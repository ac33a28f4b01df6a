"""The terminal UI in a real terminal: started in tmux at 80x24 as a user
starts it (``movingpunch`` with no arguments), driven with send-keys, read
back with capture-pane. tmux comes with scripts/setup.sh.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import time
from collections.abc import Callable, Iterator

import pytest

import movingpunch as mp
from movingpunch.tui.model import fmt

TIMEOUT = 60.0


class Tmux:
    """One tmux server on a private socket (never the user's)."""

    def __init__(self, socket: str) -> None:
        self.socket = socket

    def run(self, *args: str, check: bool = True) -> str:
        proc = subprocess.run(
            ["tmux", "-L", self.socket, *args],
            capture_output=True,
            text=True,
            timeout=30,
            check=check,
        )
        return proc.stdout

    def alive(self) -> bool:
        proc = subprocess.run(
            ["tmux", "-L", self.socket, "has-session", "-t", "mp"],
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
        deadline = time.monotonic() + TIMEOUT
        screen = ""
        while time.monotonic() < deadline:
            screen = self.screen()
            if test(screen):
                return screen
            time.sleep(0.2)
        raise AssertionError(f"timed out waiting for {what}; screen:\n{screen}")


@pytest.fixture
def tmux() -> Iterator[Tmux]:
    assert shutil.which("tmux"), "tmux is missing: run scripts/setup.sh"
    session = Tmux(f"movingpunch-test-{os.getpid()}")
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


def a_text(vstar: float) -> str:
    """a/h as the summary line prints it."""
    return "a/h " + fmt(mp.solve(vstar=vstar, kw=1.0, radius=100.0, load=0.002).a)


def test_change_the_speed_switch_tabs_and_quit(tmux: Tmux) -> None:
    fig4 = a_text(0.2)
    screen = tmux.wait_for(lambda s: fig4 in s, "the Fig. 4 summary")
    assert "Contact pressure" in screen
    assert "p(x)/(P/h)" in screen
    assert "V*_cr 0.57169" in screen

    tmux.keys("i")  # to the V* input
    tmux.wait_for(lambda s: "esc Leave input" in s, "the focus in the input")
    tmux.keys(*["BSpace"] * 8)

    # The message names vstar and ends "got ''"; the panel wraps it anywhere,
    # so the panel's column is read as one line.
    def panel_text(screen: str) -> str:
        return " ".join(
            " ".join(line.split("▕")[0] for line in screen.splitlines()).split()
        )

    tmux.wait_for(
        lambda s: (
            "vstar must be a real number" in panel_text(s)
            and re.search(r"got ''", panel_text(s)) is not None
        ),
        "an empty V* input",
    )
    tmux.keys("0", ".", "3", "5")
    faster = a_text(0.35)
    screen = tmux.wait_for(lambda s: faster in s, "the a/h of V* = 0.35")
    assert fig4 not in screen

    tmux.keys("Escape")
    tmux.wait_for(lambda s: "Leave input" not in s, "the focus out of the input")
    tmux.keys("]", "]")  # two tabs on: sigma_x through the depth
    screen = tmux.wait_for(lambda s: "σx under the centre" in s, "the depth plot")
    assert "σx(0,y)/(P/h)" in screen
    assert "y/h" in screen
    assert faster in screen
    assert any(ch in screen for ch in "⠁⠂⠄⡀⢀⠠⠐⠈⣀⠤"), "no plotted curve"

    tmux.keys("q")
    deadline = time.monotonic() + TIMEOUT
    while tmux.alive() and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not tmux.alive(), "the app did not quit"
