"""The package's version, read without importing the package root (the
scene exports and the accuracy report stamp it into their files; importing
``movingpunch`` from there would close an import cycle)."""

from __future__ import annotations

import functools

__all__ = ["version"]


@functools.cache
def version() -> str:
    """The installed distribution's version; the compiled core's when the
    package runs from a source tree. Looked up on first use: importlib.metadata
    costs about 60 ms of import time, which every spawned sweep worker would
    pay."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed("movingpunch")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree
        from movingpunch import _core

        return str(_core.__version__)
