"""Snapshots of the terminal UI (pytest-textual-snapshot): the main screen at
80x24 and 120x40, and the stress map. Deterministic: the solve time is
hidden (``show_timing=False``), the cursor does not blink, the kernel cache
starts empty, and every worker has finished before the screen is taken.

Regenerate after an intended change of the screen:
``pytest tests/python/test_tui_snapshots.py --snapshot-update``.
"""

from __future__ import annotations

from collections.abc import Callable

import pytest

import movingpunch as mp
from movingpunch.tui import create_app
from movingpunch.tui.model import TabName
from tui_pilot import settle

SnapCompare = Callable[..., bool]


@pytest.fixture(autouse=True)
def _cold_kernel_cache() -> None:
    # The summary shows the iteration count, which depends on whether an
    # earlier test left a (wider) kernel table in the process-wide cache.
    mp.clear_kernel_cache()


def app(tab: TabName = "pressure") -> object:
    return create_app(show_timing=False, cursor_blink=False, tab=tab)


def test_main_screen_80x24(snap_compare: SnapCompare) -> None:
    assert snap_compare(app(), terminal_size=(80, 24), run_before=settle)


def test_main_screen_120x40(snap_compare: SnapCompare) -> None:
    assert snap_compare(app(), terminal_size=(120, 40), run_before=settle)


def test_stress_map_120x40(snap_compare: SnapCompare) -> None:
    assert snap_compare(app("field"), terminal_size=(120, 40), run_before=settle)
