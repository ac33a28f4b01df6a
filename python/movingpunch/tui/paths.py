"""The working folder of the terminal UI: the only place Open, Save and
Export read and write.

A path typed into a prompt is taken relative to the folder (the directory
the app started in, or ``--root DIR``), with symbolic links resolved; a path
that ends up outside it (``..``, an absolute path elsewhere, a link leading
out) is refused. Writing asks before replacing an existing file and goes
through the atomic writer; its errors name the path the user typed, never a
temporary file. Pure Python (no Textual), so it is testable alone.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from movingpunch.errors import InvalidParameterError, OutsideFolderError

__all__ = ["OutsideFolderError", "OverwriteNeeded", "WorkingFolder", "write_error"]


class OverwriteNeeded(Exception):
    """The target exists: the user must confirm before it is replaced."""


@dataclass(frozen=True)
class WorkingFolder:
    """A directory (its real path, links resolved) that paths must stay in."""

    root: Path

    @classmethod
    def at(cls, root: str | os.PathLike[str] | None = None) -> WorkingFolder:
        """The folder ``root`` (None: the current directory).

        Raises InvalidParameterError if it is not an existing directory.
        """
        given = os.getcwd() if root is None else os.fspath(root)
        real = os.path.realpath(os.path.expanduser(given))
        if not os.path.isdir(real):
            raise InvalidParameterError(
                f"root: {given} is not an existing directory "
                "(allowed: a folder to open, save and export in)"
            )
        return cls(Path(real))

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
