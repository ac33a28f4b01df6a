"""Tests of what the optional extras add skip, with the reason, when the extra
is absent: ``pip install '.[test]'`` alone gives a green run.

CI (scripts/test.sh installs every extra) sets MOVINGPUNCH_REQUIRE_EXTRAS=1:
there a missing extra fails the tests that need it instead, so a broken
install cannot turn into a green run made of skips.

Three ways to say that tests need an extra:

- ``@pytest.mark.needs("dask")`` on a test or a class, or ``pytestmark =
  pytest.mark.needs("serve")`` for a module (conftest.py checks the marker);
- ``need("png")`` inside a test or a fixture;
- ``aiohttp = module("serve", "aiohttp")`` at the top of a module that imports
  what the extra installs (the whole module is skipped without it).
"""

from __future__ import annotations

import importlib
import importlib.util
import os
import shutil
from types import ModuleType

import pytest

REQUIRE_ENV = "MOVINGPUNCH_REQUIRE_EXTRAS"

#: extra -> (what it provides, what must be found: modules or executables
#: ("$name"), how to get it).
EXTRAS: dict[str, tuple[str, tuple[str, ...], str]] = {
    "dask": (
        "Dask distributed",
        ("distributed",),
        "pip install 'movingpunch[dask]'",
    ),
    "png": ("matplotlib", ("matplotlib",), "pip install 'movingpunch[png]'"),
    "serve": (
        "textual-serve",
        ("textual_serve", "aiohttp"),
        "pip install 'movingpunch[serve]'",
    ),
    "tmux": (
        "the tmux executable",
        ("$tmux",),
        "apt-get install tmux (scripts/setup.sh does)",
    ),
}


def require_all() -> bool:
    """True when a missing extra must fail its tests (CI) instead of skipping."""
    return os.environ.get(REQUIRE_ENV, "") not in ("", "0")


def missing(extra: str) -> str | None:
    """Why the tests that need ``extra`` cannot run here, or None."""
    if extra not in EXTRAS:
        raise ValueError(f"unknown extra {extra!r}: one of {sorted(EXTRAS)}")
    what, needed, how = EXTRAS[extra]
    absent = [
        name
        for name in needed
        if (
            shutil.which(name[1:]) is None
            if name.startswith("$")
            else importlib.util.find_spec(name) is None
        )
    ]
    if not absent:
        return None
    names = ", ".join(n.lstrip("$") for n in absent)
    return f"needs the '{extra}' extra ({what}; {names} not found): {how}"


def need(extra: str, *, module_level: bool = False) -> None:
    """Skips the calling test (or module) when ``extra`` is missing; fails it
    instead under MOVINGPUNCH_REQUIRE_EXTRAS=1."""
    reason = missing(extra)
    if reason is None:
        return
    if require_all():
        pytest.fail(
            f"{reason} ({REQUIRE_ENV}=1: every extra must be installed)",
            pytrace=False,
        )
    pytest.skip(reason, allow_module_level=module_level)


def module(extra: str, name: str) -> ModuleType:
    """``import name`` for a module-level import from ``extra``: the whole
    module is skipped (or fails, see ``need``) when the extra is missing."""
    need(extra, module_level=True)
    return importlib.import_module(name)
