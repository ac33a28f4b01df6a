"""Where a sweep's chunks run: worker processes fed over pipes
(``_pool_map``, this process being one of the jobs) or a Dask scheduler
(``_dask_map``). Both pass each chunk's results on as they arrive; both end
their workers on any exception, a KeyboardInterrupt included.
"""

from __future__ import annotations

import contextlib
import importlib
import multiprocessing
import multiprocessing.process
import os
import signal
import threading
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from multiprocessing import resource_tracker
from multiprocessing.connection import Connection
from multiprocessing.connection import wait as connection_wait
from typing import Any, overload

from movingpunch.errors import ClusterError, MissingExtraError, WorkerError
from movingpunch.scene._plan import (
    DASK_CHUNK_MAX,
    DASK_CHUNK_MIN,
    Chunk,
    SweepPlan,
    chunk_tasks,
)
from movingpunch.scene._solve import solve_chunk

__all__ = ["DASK_CONNECT_TIMEOUT", "DaskEvents"]


DASK_CONNECT_TIMEOUT = 20.0
"""Seconds to wait for a Dask scheduler before giving up (the default of
``Scene.run(dask_timeout=...)``)."""

DaskEvents = Callable[[str, float], None]
"""``on_dask(event, value)``: ``("connecting", timeout)`` just before the
client connects, ``("connected", workers)`` once the scheduler answered
(its number of workers). A failure raises ClusterError instead."""

# Chunks sent ahead to each worker: one computing, one queued, while more
# than _TAIL chunks per process are left; then one, so that no process idles
# at the end while a worker still holds a queued chunk.
_IN_FLIGHT = 2
_TAIL = 2
_STOP_SECONDS = 2.0  # how long stopped workers get to exit before SIGKILL
_DASK_AHEAD = 4  # chunks submitted ahead per Dask worker


# ----------------------------------------------------------------------------
# Worker processes
# ----------------------------------------------------------------------------


@contextlib.contextmanager
def _signals_deferred(*, ignore_sigint: bool = False) -> Iterator[None]:
    """SIGINT and SIGTERM wait (blocked in this thread) until the block
    ends, so that starting or stopping workers is never cut in half. With
    ``ignore_sigint`` (in the main thread only) SIGINT is also ignored
    meanwhile: a process spawned then inherits that, so a Ctrl-C, which the
    terminal sends to every process of the group, is left to the parent."""
    mask = getattr(signal, "pthread_sigmask", None)
    blocked = {signal.SIGINT, signal.SIGTERM}
    old_mask = mask(signal.SIG_BLOCK, blocked) if mask is not None else None
    main = threading.current_thread() is threading.main_thread()
    old_int = (
        signal.signal(signal.SIGINT, signal.SIG_IGN) if ignore_sigint and main else None
    )
    try:
        yield
    finally:
        # Nested: a handler that raises between the two restores (a signal
        # that was pending) must not leave SIGINT and SIGTERM blocked in
        # this thread (its later children would inherit the mask).
        try:
            if ignore_sigint and main:
                signal.signal(
                    signal.SIGINT, old_int if old_int is not None else signal.SIG_DFL
                )
        finally:
            if mask is not None and old_mask is not None:
                mask(signal.SIG_SETMASK, old_mask)


def _exit_with_parent(parent_alive: Connection) -> None:
    """Blocks until the parent is gone (nothing is ever sent on this pipe:
    the read ends when the parent's end closes), then ends this process."""
    with contextlib.suppress(EOFError, OSError):
        parent_alive.recv_bytes()
    os._exit(1)


def _worker_main(conn: Connection, parent_alive: Connection) -> None:
    """A worker process: solves the chunks it receives until told to stop
    (None), until its pipe closes or, at once, when the parent dies."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C
    if hasattr(signal, "pthread_sigmask"):  # blocked while the parent spawned us
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT, signal.SIGTERM})
    threading.Thread(
        target=_exit_with_parent, args=(parent_alive,), daemon=True
    ).start()
    while True:
        try:
            message = conn.recv()
        except (EOFError, OSError):
            return
        if message is None:
            return
        index, tasks = message
        try:
            reply: tuple[int, Any, str | None] = (index, solve_chunk(tasks), None)
        except Exception as exc:  # a bug: reported by the parent
            reply = (index, None, f"{type(exc).__name__}: {exc}")
        conn.send(reply)


class _WorkerPool:
    """Spawned worker processes fed chunks over pipes.

    Never more than _IN_FLIGHT chunks are sent ahead to a worker, so nothing
    waits on thousands of futures. Each worker watches a pipe whose write end
    only this process holds: when this process dies (even by SIGKILL) the
    pipe closes and the workers exit. ``stop()`` terminates them (SIGTERM,
    then SIGKILL) and reaps them."""

    def __init__(self) -> None:
        self.context = multiprocessing.get_context("spawn")
        self.workers: list[tuple[multiprocessing.process.BaseProcess, Connection]] = []
        self.alive_r, self.alive_w = self.context.Pipe(duplex=False)

    def start(self, n: int) -> None:
        if os.name == "posix":
            # Started here, not inside the first proc.start(): starting it
            # unblocks SIGINT and SIGTERM, which _signals_deferred blocks.
            resource_tracker.ensure_running()
        for _ in range(n):
            conn, child_conn = self.context.Pipe()
            proc = self.context.Process(
                target=_worker_main,
                args=(child_conn, self.alive_r),
                name="movingpunch-worker",
                daemon=True,
            )
            with _signals_deferred(ignore_sigint=True):
                proc.start()
                self.workers.append((proc, conn))
            child_conn.close()
        self.alive_r.close()  # the workers hold it; this process needs none

    def died(self, proc: multiprocessing.process.BaseProcess) -> WorkerError:
        proc.join(1.0)
        code = proc.exitcode
        how = f"exit status {code}" if code is None or code >= 0 else f"signal {-code}"
        return WorkerError(f"a worker process ended before its work was done ({how})")

    def run(
        self,
        messages: Sequence[Any],
        consume: Callable[[int, Any], None],
        solve_here: Callable[[Any], Any] | None = None,
    ) -> None:
        """Sends ``(i, messages[i])`` to the workers and ``consume(i,
        result)`` for each result, in the order they finish. With
        ``solve_here``, this process takes the next message itself whenever
        every worker has _IN_FLIGHT: it is one of the jobs."""
        sent = 0
        in_flight = {id(conn): 0 for _, conn in self.workers}
        by_conn = {id(conn): (proc, conn) for proc, conn in self.workers}
        conns = [conn for _, conn in self.workers]
        if not conns and solve_here is None:
            raise ValueError("no worker and no solve_here")

        processes = len(conns) + (solve_here is not None)

        def feed(proc: multiprocessing.process.BaseProcess, conn: Connection) -> None:
            nonlocal sent
            while sent < len(messages) and in_flight[id(conn)] < (
                _IN_FLIGHT if len(messages) - sent > _TAIL * processes else 1
            ):
                try:
                    conn.send((sent, messages[sent]))
                except OSError:
                    raise self.died(proc) from None
                in_flight[id(conn)] += 1
                sent += 1

        def collect(timeout: float | None) -> int:
            done = 0
            for ready in connection_wait(conns, timeout):
                assert isinstance(ready, Connection)
                proc, conn = by_conn[id(ready)]
                try:
                    index, result, error = conn.recv()
                except (EOFError, OSError):
                    raise self.died(proc) from None
                if error is not None:
                    raise WorkerError(f"a worker process failed: {error}")
                in_flight[id(conn)] -= 1
                done += 1
                consume(index, result)
                feed(proc, conn)
            return done

        for proc, conn in self.workers:
            feed(proc, conn)
        remaining = len(messages)
        while remaining:
            if solve_here is not None and sent < len(messages):
                remaining -= collect(0.0) if conns else 0
                if sent < len(messages):
                    index = sent
                    sent += 1
                    consume(index, solve_here(messages[index]))
                    remaining -= 1
            else:
                remaining -= collect(None)

    def close(self) -> None:
        """Tells the workers to stop and waits for them (briefly)."""
        for _, conn in self.workers:
            with contextlib.suppress(OSError):
                conn.send(None)
        deadline = time.monotonic() + _STOP_SECONDS
        for proc, _ in self.workers:
            proc.join(max(deadline - time.monotonic(), 0.0))
        self.stop()

    def stop(self) -> None:
        """Ends every worker still running (SIGTERM; SIGKILL if one has not
        exited after _STOP_SECONDS) and reaps them all."""
        with _signals_deferred():
            alive = [proc for proc, _ in self.workers if proc.is_alive()]
            for proc in alive:
                proc.terminate()
            deadline = time.monotonic() + _STOP_SECONDS
            for proc in alive:
                proc.join(max(deadline - time.monotonic(), 0.0))
            for proc in alive:
                if proc.is_alive():
                    proc.kill()
                    proc.join(_STOP_SECONDS)
            for proc, conn in self.workers:
                conn.close()
                with contextlib.suppress(ValueError):  # not yet reaped
                    proc.close()
            self.alive_w.close()
            self.alive_r.close()


class _Tasks(Sequence[list[dict[str, Any]]]):
    """The tasks of each chunk, made when the chunk is sent (those of a
    million-point sweep would take a hundred megabytes at once)."""

    def __init__(self, plan: SweepPlan, chunks: Sequence[Chunk]) -> None:
        self.plan, self.chunks = plan, chunks

    def __len__(self) -> int:
        return len(self.chunks)

    @overload
    def __getitem__(self, i: int) -> list[dict[str, Any]]: ...
    @overload
    def __getitem__(self, i: slice) -> Sequence[list[dict[str, Any]]]: ...
    def __getitem__(
        self, i: int | slice
    ) -> list[dict[str, Any]] | Sequence[list[dict[str, Any]]]:
        if isinstance(i, slice):
            return [chunk_tasks(self.plan, c) for c in self.chunks[i]]
        return chunk_tasks(self.plan, self.chunks[i])


def pool_map(
    plan: SweepPlan,
    chunks: Sequence[Chunk],
    n_jobs: int,
    consume: Callable[[Chunk, Sequence[Mapping[str, Any]]], None],
) -> None:
    """Solves ``chunks`` in ``n_jobs`` processes: this one and ``n_jobs - 1``
    spawned workers (never forked: this process may hold threads, the
    core's or Dask's), passing each chunk's results to ``consume`` as they
    arrive. On any exception, a KeyboardInterrupt included, the workers are
    terminated first."""
    if n_jobs <= 1:  # one chunk: no process to start
        for chunk in chunks:
            consume(chunk, solve_chunk(chunk_tasks(plan, chunk)))
        return
    pool = _WorkerPool()
    finished = False
    try:
        pool.start(n_jobs - 1)
        pool.run(
            _Tasks(plan, chunks),
            lambda i, outs: consume(chunks[i], outs),
            solve_here=solve_chunk,
        )
        finished = True
    finally:
        if finished:
            pool.close()
        else:
            pool.stop()


# ----------------------------------------------------------------------------
# Dask
# ----------------------------------------------------------------------------


def _dask_client(distributed: Any, address: str, timeout: float | None = None) -> Any:
    """A client of the scheduler at ``address``; every step of connecting,
    the handshake included, within ``timeout`` seconds (default
    DASK_CONNECT_TIMEOUT; Client's own ``timeout`` does not bound the
    handshake: a listener that accepts and never answers would hang it)."""
    seconds = DASK_CONNECT_TIMEOUT if timeout is None else timeout

    class _BoundedClient(distributed.Client):  # type: ignore[misc]
        def start(self, **kwargs: Any) -> None:
            try:
                super().start(callback_timeout=seconds, **kwargs)
            except BaseException:
                with contextlib.suppress(Exception):
                    self.close(timeout=min(seconds, _STOP_SECONDS))
                raise

    try:
        return _BoundedClient(address, timeout=seconds, set_as_default=False)
    except (OSError, TimeoutError) as exc:
        why = str(exc) or type(exc).__name__
        raise ClusterError(
            f"dask: cannot reach the scheduler at {address!r} within "
            f"{seconds:g} s: {why}"
        ) from None


def dask_map(
    plan: SweepPlan,
    make_chunks: Callable[[int, float, float], list[Chunk]],
    address: str,
    consume: Callable[[Chunk, Sequence[Mapping[str, Any]]], None],
    *,
    timeout: float | None = None,
    on_dask: DaskEvents | None = None,
) -> None:
    """Solves the sweep's chunks on the Dask scheduler at ``address``.

    Every wait is bounded by ``timeout`` (default DASK_CONNECT_TIMEOUT):
    connecting; and while results are awaited, a stretch that long without
    one makes it ask the scheduler (within the same timeout) whether it
    still answers and has workers, and gives up with ClusterError if not.
    ``on_dask`` hears of connecting and of the connection (``DaskEvents``)."""
    try:
        distributed: Any = importlib.import_module("distributed")
    except ImportError:
        raise MissingExtraError(
            "--dask needs Dask distributed: pip install 'movingpunch[dask]'"
        ) from None
    if timeout is None:
        timeout = DASK_CONNECT_TIMEOUT
    if on_dask is not None:
        on_dask("connecting", timeout)
    client = _dask_client(distributed, address, timeout)
    try:
        workers = _dask_workers(client, address, timeout)
        if on_dask is not None:
            on_dask("connected", float(workers))
        chunks = make_chunks(max(workers, 1), DASK_CHUNK_MIN, DASK_CHUNK_MAX)
        # At most _DASK_AHEAD chunks per worker submitted ahead: a long
        # sweep's tasks are made as they are sent, never all at once.
        ahead = _DASK_AHEAD * max(workers, 1)
        index: dict[Any, int] = {}
        done = distributed.as_completed(loop=client.loop, with_results=True)
        sent = 0

        def submit_next() -> None:
            nonlocal sent
            fut = client.submit(
                solve_chunk, chunk_tasks(plan, chunks[sent]), pure=False
            )
            index[fut.key] = sent
            done.add(fut)
            sent += 1

        while sent < min(ahead, len(chunks)):
            submit_next()
        remaining, last = len(chunks), time.monotonic()
        while remaining:
            if not done.has_ready():
                if time.monotonic() - last > timeout:
                    if _dask_workers(client, address, timeout) == 0:
                        raise ClusterError(
                            f"dask: the scheduler at {address!r} has no workers "
                            f"(no result for {timeout:g} s)"
                        )
                    last = time.monotonic()
                time.sleep(0.02)
                continue
            fut, result = next(done)
            if isinstance(result, BaseException):  # cancelled: the task was lost
                raise ClusterError(f"dask: a task was lost: {result!r}")
            remaining -= 1
            last = time.monotonic()
            consume(chunks[index.pop(fut.key)], result)
            if sent < len(chunks):
                submit_next()
    except (OSError, TimeoutError) as exc:
        raise ClusterError(
            f"dask: the scheduler at {address!r} failed: {exc}"
        ) from None
    finally:
        with _signals_deferred(), contextlib.suppress(Exception):
            client.close(timeout=_STOP_SECONDS)


def _dask_workers(client: Any, address: str, timeout: float) -> int:
    """The number of workers of the scheduler, asked within ``timeout``."""
    try:
        return len(client.nthreads(callback_timeout=timeout))
    except (OSError, TimeoutError) as exc:
        raise ClusterError(
            f"dask: the scheduler at {address!r} does not answer within "
            f"{timeout:g} s: {str(exc) or type(exc).__name__}"
        ) from None
