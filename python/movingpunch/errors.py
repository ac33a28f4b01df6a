"""Exceptions raised by movingpunch.

Pure Python on purpose: the compiled module ``movingpunch._core`` imports these
classes to translate the core's C++ exceptions, so this module must never
import ``_core``.
"""

from __future__ import annotations

__all__ = [
    "Cancelled",
    "ClusterError",
    "ConvergenceError",
    "InvalidParameterError",
    "MissingExtraError",
    "MovingPunchError",
    "OutputError",
    "OutsideFolderError",
    "SceneError",
    "ServeError",
    "SupercriticalSpeedError",
    "UnphysicalContactError",
    "WorkerError",
]


def _rebuild(
    cls: type[BaseException], args: tuple[object, ...], state: dict[str, object]
) -> BaseException:
    """Unpickles an error with keyword attributes (``__reduce__`` below)."""
    error = cls.__new__(cls)
    BaseException.__init__(error, *args)
    error.__dict__.update(state)
    return error


class MovingPunchError(Exception):
    """Base class of every error movingpunch raises on purpose."""

    def __reduce__(self) -> tuple[object, ...]:
        # Keeps keyword attributes (parameter, allowed, vstar, path, ...)
        # across processes (a sweep's worker pool): pickle's default calls
        # the class with ``args`` alone.
        return (_rebuild, (type(self), self.args, dict(self.__dict__)))


class InvalidParameterError(MovingPunchError, ValueError):
    """An input is of the wrong type or outside its valid range.

    The message names the parameter and its valid range. Attributes:
    ``parameter``, the name of the input at fault (``"vstar"``, ``"kw"``, ...,
    as the API spells it; None when unknown) and ``allowed``, its valid range
    as text (None when unknown). The API's checks (``movingpunch.params``),
    scenes and the compiled core set both.
    """

    def __init__(
        self,
        message: str = "",
        *,
        parameter: str | None = None,
        allowed: str | None = None,
    ) -> None:
        super().__init__(message)
        self.parameter = parameter
        self.allowed = allowed


class SupercriticalSpeedError(MovingPunchError, ValueError):
    """The speed is at or above the critical speed: no bounded steady solution.

    Attributes ``vstar`` (the requested V*), ``critical_vstar`` (V*_cr for the
    foundation and Poisson's ratio) and ``rayleigh_vstar`` (V*_R) are floats
    when known, else None. Like InvalidParameterError it names the input at
    fault: ``parameter`` is always ``"vstar"`` and ``allowed`` the speed
    range as text (None when neither speed is known).
    """

    parameter = "vstar"

    def __init__(
        self,
        message: str = "",
        *,
        vstar: float | None = None,
        critical_vstar: float | None = None,
        rayleigh_vstar: float | None = None,
    ) -> None:
        super().__init__(message)
        self.vstar = vstar
        self.critical_vstar = critical_vstar
        self.rayleigh_vstar = rayleigh_vstar

    @property
    def allowed(self) -> str | None:
        """``0 <= vstar < V*_cr`` (``< V*_R`` when only that is known)."""
        if self.critical_vstar is not None:
            return f"0 <= vstar < V*_cr = {self.critical_vstar!r}"
        if self.rayleigh_vstar is not None:
            return f"0 <= vstar < V*_R = {self.rayleigh_vstar!r}"
        return None


class UnphysicalContactError(MovingPunchError, ValueError):
    """The single-contact solution has p < 0 or the punch penetrates the surface.

    Pass ``allow_unphysical=True`` to get the flagged solution instead.
    """


class ConvergenceError(MovingPunchError, RuntimeError):
    """An iteration did not meet its tolerance within its budget."""


class Cancelled(Exception):
    """A computation was stopped by its cancellation token
    (``movingpunch.Cancel``): the caller asked for it, nothing failed.

    Deliberately not a MovingPunchError: code that handles a failed solve
    (``except MovingPunchError``: the zone search's retries, a sweep point
    recorded as failed, a scene's per-point errors) must not take a
    cancellation for a failure and carry on, so it unwinds to the caller that
    holds the token. Not a BaseException either (unlike KeyboardInterrupt):
    it is a normal outcome of a request, caught with ``except Cancelled``.
    """


class OutputError(MovingPunchError, OSError):
    """A result file or folder cannot be written: an existing file where a
    folder is wanted, a missing permission, a read-only filesystem, a full
    disk. The message is one line naming the path and the reason.

    Attributes ``path`` (the file or folder, a ``pathlib.Path`` or None),
    ``errno`` (the OS error number, or None) and ``strerror`` (the reason
    alone, without the path, or None).
    """

    def __init__(
        self,
        message: str,
        *,
        path: object = None,
        errno: int | None = None,
        reason: str | None = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.path = path
        self.errno = errno
        self.strerror = reason

    def __str__(self) -> str:
        # OSError would print "[Errno N] strerror"; the message names the path.
        return self.message


class SceneError(InvalidParameterError):
    """A scene (file or object) is malformed or asks for something impossible.

    The message is one line, ``FILE: key: problem (allowed: ...)``; the
    attributes ``source``, ``key``, ``problem`` and ``allowed`` hold its parts,
    and ``parameter`` the model parameter at fault (``"vstar"``, ``"tol"``,
    ...; None when the key is not one, e.g. an output's ``points``).
    """

    def __init__(
        self,
        source: str,
        key: str,
        problem: str,
        allowed: str = "",
        parameter: str | None = None,
    ) -> None:
        self.source = source
        self.key = key
        self.problem = problem
        text = f"{source}: {key}: {problem}"
        if allowed:
            text += f" (allowed: {allowed})"
        super().__init__(" ".join(text.split()), parameter=parameter, allowed=allowed)


class MissingExtraError(MovingPunchError, ImportError):
    """An optional dependency (an extra of the package) is not installed."""


class ClusterError(MovingPunchError, RuntimeError):
    """The Dask scheduler could not be reached or a task failed on it."""


class WorkerError(MovingPunchError, RuntimeError):
    """A worker process ended before it finished its work, or failed."""


class OutsideFolderError(InvalidParameterError):
    """A path leaves the terminal UI's working folder (or is the folder
    itself)."""


class ServeError(MovingPunchError):
    """``movingpunch serve`` cannot start (busy port, unknown host, remote
    host without ``--allow-remote``): a one-line message for the command
    line."""
