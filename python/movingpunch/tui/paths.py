"""The working folder of the terminal UI: the only place Open, Save and
Export read and write.

The folder is ``--root DIR``, else the directory the app started in, except
inside movingpunch's own source checkout (``source_checkout``): exports and
scenes never land silently in the source tree, so there it is
``DEFAULT_FOLDER`` (``~/movingpunch``, created at the first save or export;
``--root .`` keeps the checkout). Each prompt names the folder (``label``).

A path typed into a prompt is taken relative to the folder, with symbolic
links resolved; a path
that ends up outside it (``..``, an absolute path elsewhere, a link leading
out) is refused. Writing asks before replacing an existing file and goes
through the atomic writer; its errors name the path the user typed, never a
temporary file. Pure Python (no Textual), so it is testable alone.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

from movingpunch.errors import InvalidParameterError, OutsideFolderError

__all__ = [
    "DEFAULT_FOLDER",
    "OutsideFolderError",
    "OverwriteNeeded",
    "WorkingFolder",
    "source_checkout",
    "write_error",
]

DEFAULT_FOLDER = "~/movingpunch"
"""The working folder of an app started inside the source checkout without
``--root`` (created at the first save or export)."""

_PROJECT_NAME = re.compile(r'^name\s*=\s*"movingpunch"\s*$', re.MULTILINE)


def source_checkout(start: str | os.PathLike[str]) -> Path | None:
    """The movingpunch source checkout ``start`` is in (``start`` or a
    parent folder holding a ``pyproject.toml`` of the project movingpunch
    and ``python/movingpunch``), or None."""
    here = Path(os.path.realpath(start))
    for folder in (here, *here.parents):
        toml = folder / "pyproject.toml"
        if not (folder / "python" / "movingpunch").is_dir() or not toml.is_file():
            continue
        try:
            with toml.open(encoding="utf-8") as f:
                head = f.read(100_000)
        except (OSError, UnicodeDecodeError):
            continue
        if _PROJECT_NAME.search(head):
            return folder
    return None


def _default_folder() -> Path:
    return Path(os.path.realpath(os.path.expanduser(DEFAULT_FOLDER)))


class OverwriteNeeded(Exception):
    """The target exists: the user must confirm before it is replaced."""


@dataclass(frozen=True)
class WorkingFolder:
    """A directory (its real path, links resolved) that paths must stay in."""

    root: Path
    checkout: Path | None = None
    """The source checkout the app started in, when the folder is
    ``DEFAULT_FOLDER`` instead of it."""

    @classmethod
    def at(cls, root: str | os.PathLike[str] | None = None) -> WorkingFolder:
        """The folder ``root``; None: the current directory, or
        ``DEFAULT_FOLDER`` when that is inside the source checkout.

        Raises InvalidParameterError if ``root`` is not an existing directory
        (``DEFAULT_FOLDER`` may not exist yet: it is made when written to).
        """
        if root is None:
            here = os.getcwd()
            checkout = source_checkout(here)
            if checkout is not None:
                return cls(_default_folder(), checkout)
            return cls(Path(os.path.realpath(here)))
        given = os.fspath(root)
        if not given:  # would silently mean the current directory
            raise InvalidParameterError(
                "root: '' names no folder (allowed: an existing folder; "
                "'.' for the current directory)"
            )
        real = os.path.realpath(os.path.expanduser(given))
        if not os.path.isdir(real) and Path(real) != _default_folder():
            raise InvalidParameterError(
                f"root: {given} is not an existing directory "
                "(allowed: a folder to open, save and export in)"
            )
        return cls(Path(real))

    @property
    def label(self) -> str:
        """The folder as a prompt names it (``~`` for the home folder)."""
        home = os.path.realpath(os.path.expanduser("~"))
        root = str(self.root)
        if root == home or root.startswith(home.rstrip(os.sep) + os.sep):
            return "~" + root[len(home) :]
        return root

    def resolve(self, text: str) -> Path:
        """The real path of ``text`` (relative to the folder); raises
        OutsideFolderError if it is not strictly inside the folder."""
        root = str(self.root)
        real = os.path.realpath(os.path.join(root, os.path.expanduser(text)))
        try:
            inside = os.path.commonpath([root, real]) == root
        except ValueError:  # different drives (Windows)
            inside = False
        if not inside or real == root:
            raise OutsideFolderError(
                f"{text}: outside the working folder {root}; "
                "give a file name or a path inside it"
            )
        return Path(real)

    def target(self, text: str, *, overwrite: bool) -> Path:
        """Where writing ``text`` goes: resolved inside the folder, not a
        folder itself; raises OverwriteNeeded if the file exists and
        ``overwrite`` is False."""
        path = self.resolve(text)
        if not self.root.exists() and self.root == _default_folder():
            self.root.mkdir(parents=True, exist_ok=True)
        if path.is_dir():
            raise OutsideFolderError(f"{text}: is a folder; give a file name")
        if path.exists() and not overwrite:
            raise OverwriteNeeded(
                f"{text} exists: enter again to overwrite, escape to cancel"
            )
        return path


def write_error(text: str, error: OSError) -> str:
    """``cannot write PATH: reason`` with the path as typed (the error's own
    file name may be the writer's temporary file)."""
    reason = error.strerror or type(error).__name__
    return f"cannot write {text}: {reason}"
