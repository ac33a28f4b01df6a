"""Writing result files: safe names, an output folder checked before the
work, and all the files of one run published at once.

- ``safe_name(text)`` turns user text (a scene's name) into a file-name stem
  that cannot leave the output folder: ``[a-z0-9-]`` only, never empty.
- ``prepare(out_dir)`` checks, before anything is computed, that ``out_dir``
  is a folder we can write into, or a missing one we can create (missing
  parents are created too, like ``mkdir -p``, but only when the files are
  published: a run that fails creates no folder).
- ``publish(out_dir, files)`` writes every file into a hidden temporary
  folder inside ``out_dir`` (``.movingpunch-tmp-*``: same filesystem), and
  only once all of them are written and fsynced renames each over its target
  (``os.replace``). The previous files are kept as hard links in the
  temporary folder until every rename succeeded; if one fails, the renamed
  ones are put back. A failure therefore leaves the previous results, never a
  mix of new and old. The only window is a crash of the process or machine
  during the rename phase itself (a few renames in one folder).
- ``atomic_write(path, data)`` writes one file the same way (``Scene.save``,
  the terminal UI).

New files get the mode ``0o666 & ~umask`` (0644 under umask 022, 0600 under
077); a file written over keeps the mode of the one it replaces.

Every failure is an ``OutputError`` (a ``MovingPunchError`` and an
``OSError``) whose message is one line naming the path and the reason.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import shutil
import stat
import tempfile
import unicodedata
from collections.abc import Iterable, Sequence
from pathlib import Path

from movingpunch.errors import OutputError

__all__ = [
    "OutputError",
    "atomic_write",
    "prepare",
    "publish",
    "safe_name",
]

#: Longest stem ``safe_name`` returns (file names stay far below 255 bytes).
MAX_STEM = 64
_STAGING_PREFIX = ".movingpunch-tmp-"


# ----------------------------------------------------------------------------
# Names
# ----------------------------------------------------------------------------


def safe_name(text: str, default: str = "scene") -> str:
    """A file-name stem from user text: accents dropped (``é`` -> ``e``),
    ASCII letters and digits lower-cased, every other run of characters one
    ``-``, at most ``MAX_STEM`` characters; ``default`` if nothing is left.
    The result has no ``/``, ``\\``, ``.`` or leading ``-``, so it can never
    name a path outside the folder it is joined to."""
    decomposed = unicodedata.normalize("NFKD", text)
    keep = [
        ch.lower() if ch.isascii() and ch.isalnum() else "-"
        for ch in decomposed
        if not unicodedata.combining(ch)
    ]
    stem = "-".join(part for part in "".join(keep).split("-") if part)
    stem = stem[:MAX_STEM].rstrip("-")
    return stem or default


def _check_basename(name: str) -> None:
    """``publish`` writes only plain names into its folder: no separator,
    not ``.``/``..``, no leading dot (hidden names are its own)."""
    if (
        not name
        or name.startswith(".")
        or "/" in name
        or "\\" in name
        or "\0" in name
        or os.sep in name
        or (os.altsep is not None and os.altsep in name)
        or len(name.encode("utf-8")) > 255
    ):
        raise ValueError(f"not a plain file name: {name!r}")


# ----------------------------------------------------------------------------
# Errors
# ----------------------------------------------------------------------------


def _reason(exc: OSError) -> str:
    return exc.strerror or str(exc) or type(exc).__name__


def _error(action: str, path: Path, exc: OSError | str) -> OutputError:
    """``cannot <action> <path>: <reason>`` as an OutputError."""
    reason = exc if isinstance(exc, str) else _reason(exc)
    code = None if isinstance(exc, str) else exc.errno
    return OutputError(
        f"cannot {action} {path}: {reason}", path=path, errno=code, reason=reason
    )


# ----------------------------------------------------------------------------
# The output folder
# ----------------------------------------------------------------------------


def prepare(out_dir: str | Path) -> Path:
    """Checks that ``out_dir`` can receive files, before anything is
    computed; returns it as a Path.

    An existing folder must accept a new file (a hidden probe file is
    created and removed: this catches permissions, read-only filesystems and
    a full disk's inode table). A missing folder is fine if its nearest
    existing ancestor is a writable folder: it is created (with its missing
    parents) when the files are published. Anything else (an existing file,
    a parent that is a file, a broken link) is an ``OutputError``.
    """
    directory = Path(out_dir)
    try:
        st = os.stat(directory)
    except FileNotFoundError:
        _check_creatable(directory)
        return directory
    except OSError as exc:
        raise _error("write into", directory, exc) from None
    if not stat.S_ISDIR(st.st_mode):
        raise _error("write into", directory, "exists and is not a directory")
    try:
        _probe(directory)
    except OSError as exc:
        raise _error("write into", directory, exc) from None
    return directory


def _check_creatable(directory: Path) -> None:
    if os.path.lexists(directory):
        raise _error("write into", directory, "a broken symbolic link")
    ancestor = directory.absolute().parent
    while not os.path.lexists(ancestor) and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    try:
        st = os.stat(ancestor)
    except OSError as exc:
        raise _error("create", directory, f"{ancestor}: {_reason(exc)}") from None
    if not stat.S_ISDIR(st.st_mode):
        raise _error("create", directory, f"{ancestor} is not a directory")
    if not os.access(ancestor, os.W_OK | os.X_OK):
        reason = "read-only file system" if _read_only(ancestor) else "not writable"
        raise _error("create", directory, f"{ancestor} is {reason}")


def _read_only(path: Path) -> bool:
    try:
        return bool(os.statvfs(path).f_flag & os.ST_RDONLY)
    except (OSError, AttributeError):
        return False


def _probe(directory: Path) -> None:
    """Creates and removes a hidden empty file in ``directory``."""
    probe = directory / f".movingpunch-probe-{secrets.token_hex(6)}"
    fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    os.close(fd)
    os.unlink(probe)


def _make_dir(directory: Path) -> None:
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise _error("write into", directory, "exists and is not a directory") from None
    except OSError as exc:
        raise _error("create", directory, exc) from None


# ----------------------------------------------------------------------------
# Files
# ----------------------------------------------------------------------------


def _kept_mode(target: Path) -> int | None:
    """The permission bits of the regular file at ``target`` (kept when it
    is written over), or None (a new file: the umask decides)."""
    try:
        st = os.lstat(target)
    except OSError:
        return None
    return stat.S_IMODE(st.st_mode) & 0o777 if stat.S_ISREG(st.st_mode) else None


Content = bytes | Iterable[bytes]
"""A file's content: whole, or in pieces written as they come (a long
table is then never whole in memory)."""


def _write_file(path: Path, data: Content, mode: int | None) -> None:
    """Creates ``path`` (it must not exist) with ``data``, flushed to disk.
    Created with 0o666, which the kernel masks with the umask; ``mode``
    (an overwritten file's) is set exactly."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0)
    fd = os.open(path, flags, 0o666)
    with open(fd, "wb") as f:
        if mode is not None:
            os.chmod(path, mode)
        if isinstance(data, bytes):
            f.write(data)
        else:
            for piece in data:
                f.write(piece)
        f.flush()
        os.fsync(f.fileno())


def _replace(src: Path, dst: Path) -> None:
    """``os.replace`` (looked up at each call: tests patch either)."""
    os.replace(src, dst)


def _keep_previous(target: Path, backup: Path) -> None:
    """``backup`` becomes a second name of the file at ``target`` (a hard
    link; a copy where links are not supported)."""
    try:
        os.link(target, backup, follow_symlinks=False)
    except FileExistsError:
        raise
    except (OSError, NotImplementedError):
        shutil.copy2(target, backup, follow_symlinks=False)


def _fsync_dir(directory: Path) -> None:
    with contextlib.suppress(OSError):
        fd = os.open(directory, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def publish(out_dir: str | Path, files: Sequence[tuple[str, Content]]) -> list[Path]:
    """Writes ``files`` (plain file name, content: bytes, or pieces of bytes
    written as they come) into ``out_dir``: all of them or, on any failure,
    none (the previous files stay as they were).
    Creates ``out_dir`` and its missing parents. Returns the paths written;
    raises ``OutputError`` (one line: the path and the reason)."""
    directory = Path(out_dir)
    names = [name for name, _ in files]
    for name in names:
        _check_basename(name)
    if len(set(names)) != len(names):
        raise ValueError(f"file names repeat: {names}")
    targets = [directory / name for name in names]
    if not files:
        return []
    prepare(directory)
    _make_dir(directory)
    try:
        staging = Path(tempfile.mkdtemp(prefix=_STAGING_PREFIX, dir=directory))
    except OSError as exc:
        raise _error("write into", directory, exc) from None
    keep_staging = False
    try:
        for (name, data), target in zip(files, targets, strict=True):
            try:
                _write_file(staging / name, data, _kept_mode(target))
            except OSError as exc:
                raise _error("write", target, exc) from None
        backups: dict[int, Path] = {}
        for i, target in enumerate(targets):
            if os.path.lexists(target):
                backup = staging / f".previous-{i}"
                try:
                    _keep_previous(target, backup)
                except OSError as exc:
                    raise _error("replace", target, exc) from None
                backups[i] = backup
        done = 0
        try:
            for name, target in zip(names, targets, strict=True):
                _replace(staging / name, target)
                done += 1
        except BaseException as exc:
            keep_staging = not _restore(targets[:done], backups)
            if isinstance(exc, OSError):
                message = _error("write", targets[done], exc)
                if keep_staging:
                    message = OutputError(
                        f"{message} (some previous files could not be put back: "
                        f"they are in {staging})",
                        path=targets[done],
                        errno=exc.errno,
                        reason=message.strerror,
                    )
                raise message from None
            raise
        _fsync_dir(directory)
    finally:
        if not keep_staging:
            shutil.rmtree(staging, ignore_errors=True)
    return targets


def _restore(renamed: Sequence[Path], backups: dict[int, Path]) -> bool:
    """Undoes the renames of ``renamed`` (the first targets): the previous
    file back from its backup, a new one removed. True if all went back."""
    ok = True
    for i in reversed(range(len(renamed))):
        try:
            if i in backups:
                os.replace(backups[i], renamed[i])
            else:
                os.unlink(renamed[i])
        except OSError:
            ok = False
    return ok


def atomic_write(path: str | Path, data: bytes) -> None:
    """Writes ``data`` to ``path`` through a hidden temporary file in the
    same folder and ``os.replace``: readers see the old file or the whole new
    one; a failure leaves the old file and no temporary one. A new file gets
    ``0o666 & ~umask``, a replaced one keeps its mode. Does not create the
    folder. Raises ``OutputError`` naming ``path`` and the reason."""
    target = Path(path)
    mode = _kept_mode(target)
    tmp = target.parent / f".{target.name}.{secrets.token_hex(6)}.tmp"
    try:
        _write_file(tmp, data, mode)
        _replace(tmp, target)
    except OSError as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise _error("write", target, exc) from None
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
