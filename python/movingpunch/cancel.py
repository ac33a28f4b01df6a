"""Cancelling a computation from another thread (``movingpunch.Cancel``).

A token is made, handed to the computation and cancelled from anywhere::

    token = mp.Cancel()
    # on a worker thread:
    s = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, cancel=token)
    # on any other thread, later:
    token.cancel()  # the solve raises mp.Cancelled within about 50 ms

``with token:`` binds the token to the current thread for a block: every
call of the compiled core on that thread (a solve, the zone search's solves,
a sweep's points, a result's stresses and maps) checks it, at its entry and,
in long loops, about every 50 ms (an atomic flag read, without the GIL). The
``cancel=`` keyword of ``solve``, ``solve_punches`` and ``Scene.run`` does
exactly that around the call. A cancelled computation raises
``movingpunch.Cancelled`` (``movingpunch.errors``), which is not a
MovingPunchError: no retry or "failed point" handler takes it for a failure.
A token stays cancelled; a token never cancelled changes nothing (the same
numbers, bit for bit). On the main thread Ctrl-C keeps working beside it.

A sweep on worker processes (``Scene.run(jobs=...)``) is stopped between
chunks: the pool is shut down and its processes end.
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Callable, Iterator
from typing import ParamSpec, TypeVar

from movingpunch import _core
from movingpunch.errors import Cancelled, InvalidParameterError

__all__ = ["Cancel", "Cancelled", "bound", "cancellable", "check_cancelled"]

Cancel = _core.Cancel
"""A cancellation token: ``cancel()``, ``cancelled``, ``check()``, and
``with token:`` to bind it to the current thread (see the module docstring)."""

check_cancelled: Callable[[], None] = _core.check_cancelled
"""Raises Cancelled if a token bound to this thread is cancelled (for
Python loops between calls of the core)."""

_P = ParamSpec("_P")
_T = TypeVar("_T")


def check_cancel(cancel: object) -> Cancel | None:
    """``cancel`` if it is a token or None; InvalidParameterError otherwise."""
    if cancel is None or isinstance(cancel, Cancel):
        return cancel
    raise InvalidParameterError(
        f"cancel must be a movingpunch.Cancel or None, got {cancel!r}",
        parameter="cancel",
        allowed="a movingpunch.Cancel or None",
    )


@contextlib.contextmanager
def bound(cancel: object) -> Iterator[None]:
    """Binds ``cancel`` (a token, or None: nothing) to the current thread."""
    token = check_cancel(cancel)
    if token is None:
        yield
        return
    with token:
        yield


def cancellable(fn: Callable[_P, _T]) -> Callable[_P, _T]:
    """Runs ``fn`` with its ``cancel=`` keyword's token bound to the thread."""

    @functools.wraps(fn)
    def call(*args: _P.args, **kwargs: _P.kwargs) -> _T:
        token = kwargs.get("cancel")
        if token is None:  # nothing to bind: no context manager
            return fn(*args, **kwargs)
        with bound(token):
            return fn(*args, **kwargs)

    return call
