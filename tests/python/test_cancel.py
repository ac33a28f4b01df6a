"""Cancelling a computation from another thread (``movingpunch.Cancel``).

The terminal UI solves in worker threads; an abandoned solve (the user typed
on, or pressed escape) must stop instead of burning a core until it ends.
The token is an atomic flag the compiled core polls about every 50 ms
without the GIL (cpp/bindings/bind_interrupt.cpp), and every call of the
core on a thread the token is bound to checks it at its entry, so the
Python loops over the core (the zone search, sweeps, the accuracy ladder,
peak searches) stop at their next call. The time bounds below are hang
guards, never performance assertions.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import movingpunch as mp
from movingpunch import _core, zones
from movingpunch.accuracy import accuracy_report
from movingpunch.errors import (
    Cancelled,
    ConvergenceError,
    InvalidParameterError,
    MovingPunchError,
    UnphysicalContactError,
)

STOP_BOUND = 5.0
"""Seconds a cancelled solve may take to end (a hang guard: measured
0.001-0.052 s on a two-core machine at load 12)."""

START_BOUND = 60.0
"""Seconds for a worker to reach its solve (a hang guard)."""

# A solve that runs for seconds in loops the core polls: near the critical
# speed of a stiff Pasternak foundation the search for several zones builds
# the damped kernel, whose quadrature checks the token per panel (red-team
# item 4 of issue 25; it ends, answered or refused, after 5-20 s).
KW, NU, KP = 1e4, 0.4048225797622928, 3.0
LONG: dict[str, Any] = {
    "kw": KW,
    "nu": NU,
    "kp": KP,
    "radius": 0.004383187612912297,
    "load": 319.749150627029,
}


def long_solve(cancel: mp.Cancel) -> None:
    v = 0.9999999 * mp.critical_vstar(KW, NU, KP)
    mp.solve(vstar=v, cancel=cancel, **LONG)


def _run_in_thread(
    work: Callable[[], object],
) -> tuple[threading.Thread, list[BaseException | object], threading.Event]:
    """Starts ``work`` on a thread; its outcome (result or exception) goes
    in the list, the event is set just before it starts."""
    outcome: list[BaseException | object] = []
    started = threading.Event()

    def run() -> None:
        started.set()
        try:
            outcome.append(work())
        except BaseException as exc:  # the test inspects it
            outcome.append(exc)

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    assert started.wait(START_BOUND)
    return thread, outcome, started


def test_cancel_from_another_thread_stops_a_long_solve() -> None:
    token = mp.Cancel()
    thread, outcome, _ = _run_in_thread(lambda: long_solve(token))
    time.sleep(1.0)  # at work in the kernel's quadrature
    assert thread.is_alive(), f"the long solve ended before the cancel: {outcome}"
    sent = time.monotonic()
    token.cancel()
    thread.join(STOP_BOUND)
    took = time.monotonic() - sent
    assert not thread.is_alive(), f"still solving {STOP_BOUND} s after cancel()"
    assert len(outcome) == 1
    assert isinstance(outcome[0], Cancelled), outcome
    assert not isinstance(outcome[0], MovingPunchError)
    print(f"stopped {took:.3f} s after cancel()")


def test_cancel_stops_a_solve_on_the_main_thread_too() -> None:
    # The main thread's guard polls the signals and the token.
    token = mp.Cancel()
    timer = threading.Timer(1.0, token.cancel)
    timer.start()
    try:
        start = time.monotonic()
        with pytest.raises(Cancelled):
            long_solve(token)
        assert time.monotonic() - start < 1.0 + STOP_BOUND
    finally:
        timer.cancel()


def test_a_cancelled_token_stays_cancelled() -> None:
    token = mp.Cancel()
    assert not token.cancelled
    assert "active" in repr(token)
    token.cancel()
    token.cancel()  # idempotent
    assert token.cancelled
    assert "cancelled" in repr(token)
    for _ in range(2):  # every later use: at the entry of the call
        with pytest.raises(Cancelled):
            mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, cancel=token)
    with pytest.raises(Cancelled):
        token.check()
    # Bound by hand, every call of the core on the thread is a stop.
    s = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002)
    with token, pytest.raises(Cancelled):
        s.pressure(np.array([0.0]))
    # ... and only inside the block: the thread is free again after it.
    assert s.pressure(np.array([0.0]))[0] == pytest.approx(s.p0)
    mp.Cancel().check()  # a fresh token is not cancelled


def test_an_unused_token_changes_nothing() -> None:
    # The same numbers, bit for bit, with and without an unused token, on
    # the main thread and on another: the token only adds checks.
    x = np.linspace(-0.3, 0.3, 7)
    cases: list[dict[str, Any]] = [
        {"vstar": 0.31, "kw": 1.7, "radius": 100, "load": 0.002},
        {"vstar": 0.3, "kw": 1.0, "radius": 100, "load": 0.002, "damping": 0.2},
    ]
    for case in cases:
        mp.clear_kernel_cache()
        plain = mp.solve(**case)
        mp.clear_kernel_cache()
        token = mp.Cancel()
        with_token = mp.solve(**case, cancel=token)
        assert not token.cancelled
        assert with_token.a == plain.a
        assert with_token.p0 == plain.p0
        assert np.array_equal(with_token.pressure(x), plain.pressure(x))
        mp.clear_kernel_cache()
        thread, outcome, _ = _run_in_thread(
            lambda c=case: mp.solve(**c, cancel=mp.Cancel())
        )
        thread.join(START_BOUND)
        assert len(outcome) == 1
        other = outcome[0]
        assert isinstance(other, mp.ContactSolution), other
        assert other.a == plain.a
    punches = [mp.Punch(100.0, 0.002, at=-0.6), mp.Punch(100.0, 0.002, at=0.6)]
    train = mp.solve_punches(punches, vstar=0.5, kw=1.0)
    again = mp.solve_punches(punches, vstar=0.5, kw=1.0, cancel=mp.Cancel())
    assert again.contact_zones == train.contact_zones


def test_cancel_must_be_a_token() -> None:
    with pytest.raises(InvalidParameterError, match="cancel must be") as info:
        mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002, cancel=True)  # type: ignore[call-overload]
    assert info.value.parameter == "cancel"


def test_cancelled_is_not_taken_for_a_failure_by_the_zone_search(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The zone search retries a topology that fails (ConvergenceError,
    # UnphysicalContactError) with the next one: a cancellation in the
    # middle of it must end the search, not be tried around. The token is
    # cancelled from inside the search's second solve of a contact set, so
    # the test does not depend on timing.
    real = _core.solve_zones
    calls = 0
    token = mp.Cancel()

    def cancelling(*args: Any, **kwargs: Any) -> Any:
        nonlocal calls
        calls += 1
        if calls == 2:
            token.cancel()
        return real(*args, **kwargs)

    monkeypatch.setattr(_core, "solve_zones", cancelling)
    assert zones._core is _core
    # kw 0.03 at 1 % below V*_cr separates into two zones; uncancelled, the
    # search's second topology fails (ConvergenceError) and it goes on to a
    # third and fourth solve of a contact set.
    case = {"kw": 0.03, "radius": 100.0, "load": 0.002}
    vstar = 0.99 * mp.critical_vstar(0.03)
    with pytest.raises(Cancelled):
        mp.solve(vstar=vstar, **case, cancel=token)
    assert calls == 2, "the search went on after the cancel"
    # Uncancelled, the same search solves several more sets and separates.
    calls = 0
    token = mp.Cancel()
    s = mp.solve(vstar=vstar, **case)
    assert calls > 2
    assert len(s.contact_zones) == 2
    assert not issubclass(Cancelled, MovingPunchError)
    assert not issubclass(Cancelled, (ConvergenceError, UnphysicalContactError))


def test_a_cancelled_sweep_stops_at_its_next_point() -> None:
    scene = mp.Scene.bundled("fig2")
    token = mp.Cancel()
    done: list[int] = []

    def progress(n: int, total: int) -> None:
        done.append(n)
        if n == 3:
            token.cancel()

    with pytest.raises(Cancelled):
        scene.run(jobs=1, progress=progress, cancel=token)
    assert done[-1] == 3, f"points solved after the cancel: {done}"


@pytest.mark.usefixtures("pool_pays")
def test_a_cancelled_sweep_on_worker_processes_stops_its_pool() -> None:
    import multiprocessing

    scene = mp.Scene.bundled("fig2")
    token = mp.Cancel()
    seen: list[int] = []

    def progress(n: int, total: int) -> None:
        seen.append(n)
        token.cancel()

    start = time.monotonic()
    with pytest.raises(Cancelled):
        scene.run(jobs=2, progress=progress, cancel=token)
    assert time.monotonic() - start < 120.0  # a hang guard
    deadline = time.monotonic() + 30.0
    while multiprocessing.active_children() and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not multiprocessing.active_children()


def test_a_cancelled_accuracy_ladder_stops_and_is_not_a_failed_rung() -> None:
    # accuracy_report records a rung that fails (MovingPunchError) and goes
    # on: a cancellation ends the whole study instead.
    token = mp.Cancel()
    rungs: list[int] = []

    def progress(done: int, total: int) -> None:
        rungs.append(done)
        if done == 1:
            token.cancel()

    params = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2}
    with token, pytest.raises(Cancelled):
        accuracy_report(params, (1e-4, 1e-6, 1e-8), progress=progress)
    assert rungs == [1], rungs


def test_peaks_stop_at_their_next_call_of_the_core() -> None:
    s = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002)
    token = mp.Cancel()
    token.cancel()
    with token, pytest.raises(Cancelled):
        s.stress_peaks()
    with token, pytest.raises(Cancelled):
        s.stress_field(np.linspace(-1, 1, 5), np.linspace(-1, 0, 3))


def test_a_token_is_bound_to_the_thread_that_entered_it() -> None:
    # Cancelling a token bound on another thread does not stop this one.
    token = mp.Cancel()
    entered = threading.Event()
    leave = threading.Event()

    def hold() -> None:
        with token:
            entered.set()
            leave.wait(START_BOUND)

    thread = threading.Thread(target=hold, daemon=True)
    thread.start()
    assert entered.wait(START_BOUND)
    token.cancel()
    try:
        s = mp.solve(vstar=0.2, kw=1.0, radius=100, load=0.002)  # unbound here
        assert s.valid
    finally:
        leave.set()
        thread.join(START_BOUND)
