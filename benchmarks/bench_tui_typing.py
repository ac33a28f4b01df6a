"""The terminal UI's answer to typing (issue 16): from the last key of a
typed value to its result on screen, at 80x24, keys delivered 100 ms apart
as a terminal delivers them. The time is the debounce (the UI waits for the
user's pause, ``DEBOUNCE_SECONDS``) plus the solve and the redraw; the
benchmark prints both parts and how many solves each value cost (1: the
half-typed prefixes were not solved). Never asserts a time.

    .venv/bin/python benchmarks/bench_tui_typing.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import asyncio
import os
import statistics
import time

from textual import events
from textual.widgets import Input

from movingpunch.tui import create_app
from movingpunch.tui.model import Params
from movingpunch.tui.scene_files import SceneState
from movingpunch.tui.screens.main import DEBOUNCE_SECONDS, MainScreen

GAP = 0.1
KEYS = {".": "full_stop"}


async def measure(values: list[str], damping: float) -> list[tuple[float, int]]:
    """(ms from the last key to the result on screen, solves) per value."""
    app = create_app(SceneState(Params(damping=damping)), show_timing=False)
    out = []
    async with app.run_test(size=(80, 24)) as pilot:
        await app.workers.wait_for_complete()
        await pilot.pause(0.5)
        screen = app.screen
        assert isinstance(screen, MainScreen)
        driver = app._driver
        assert driver is not None
        for text in values:
            box = screen.query_one("#in-vstar", Input)
            box.focus()
            await pilot.pause()
            box.value = ""
            before = len(screen.requested)
            shown = screen.result
            last = 0.0
            for char in text:
                await asyncio.sleep(GAP)
                event = events.Key(KEYS.get(char, char), char)
                event.set_sender(app)
                driver.send_message(event)
                last = time.perf_counter()
            while screen.result is shown or screen.solve_pending:
                await asyncio.sleep(0.002)
            await pilot.pause()  # drawn
            out.append(
                (1e3 * (time.perf_counter() - last), len(screen.requested) - before)
            )
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    values = ["0.3", "0.25", "0.35", "0.4", "0.45", "0.5"][: max(args.repeat, 1)]
    debounce = DEBOUNCE_SECONDS * 1e3
    print(f"load average {os.getloadavg()[0]:.2f}; debounce {debounce:.0f} ms")
    for damping in (0.0, 0.1):
        got = asyncio.run(measure(values, damping))
        ms = statistics.median(t for t, _ in got)
        solves = sorted({n for _, n in got})
        print(
            f"damping {damping}: last key to result {ms:.0f} ms median "
            f"(debounce {debounce:.0f} + solve and redraw "
            f"{ms - debounce:.0f}); solves per value {solves}"
        )


if __name__ == "__main__":
    main()
