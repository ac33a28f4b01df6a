"""Fixtures shared by the Python tests: running movingpunch as a user would, in
a subprocess (``run_cli``, ``run_python``), the modules a piece of code loads
(``modules_loaded_by``) and the check every command-line error must pass
(``assert_one_line_error``); a Dask cluster on free ports (``local_cluster``);
tests that need an optional extra skip without it (``@pytest.mark.needs``,
extras.py); and a guard that the tests run against this checkout's
movingpunch.

Subprocesses use this interpreter (``sys.executable``) and inherit the
environment, so they import the same movingpunch as the tests (the editable
install of scripts/setup.sh, or PYTHONPATH in a worktree).
"""

from __future__ import annotations

import json
import os
import pty
import select
import subprocess
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from extras import need

# One BLAS thread per test process, set before anything loads NumPy (the
# test modules, after this file): the suite runs a worker per core
# (pytest-xdist), and OpenBLAS's own threads on top of them spin against
# each other (the NumPy references' batched expm/QR ran 10 times slower:
# 137 s instead of 13 s for one file on 2 cores). Subprocesses inherit it.
for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

ROOT = Path(__file__).resolve().parents[2]


def pytest_collection_modifyitems(
    config: pytest.Config, items: list[pytest.Item]
) -> None:
    """Deselects the ``stress`` runs (tens of CPU minutes each) unless
    MOVINGPUNCH_STRESS=1 or the ``-m`` expression names them: CI runs the
    rest within its budget, a stress run is asked for by name."""
    if not (
        os.environ.get("MOVINGPUNCH_STRESS") == "1"
        or "stress" in (config.option.markexpr or "")
    ):
        keep = [item for item in items if item.get_closest_marker("stress") is None]
        if len(keep) != len(items):
            config.hook.pytest_deselected(
                items=[item for item in items if item.get_closest_marker("stress")]
            )
            items[:] = keep
    _long_runs_first(items)


def _xdist_scope(item: pytest.Item) -> str:
    """The unit pytest-xdist's ``--dist loadgroup`` hands to a worker: the
    test's ``xdist_group``, or the test alone."""
    mark = item.get_closest_marker("xdist_group")
    if mark is not None:
        return str(mark.args[0] if mark.args else mark.kwargs.get("name"))
    return item.nodeid


def _long_runs_first(items: list[pytest.Item]) -> None:
    """Puts the long runs (``slow``, and every test of an ``xdist_group``
    that holds one) before the others, each part in collection order: the
    workers take units in this order, so the long ones start first and the
    many short ones fill in at the end, and no worker idles while another
    finishes a long test that started last (a longest-first schedule). The
    order of the tests of one group is kept."""
    long_scopes = {
        _xdist_scope(item) for item in items if item.get_closest_marker("slow")
    }
    items.sort(key=lambda item: _xdist_scope(item) not in long_scopes)


def pytest_runtest_setup(item: pytest.Item) -> None:
    """``@pytest.mark.needs("dask", ...)``: the test skips, with the reason,
    when one of these extras is missing (fails under
    MOVINGPUNCH_REQUIRE_EXTRAS=1, as in CI; extras.py)."""
    for mark in item.iter_markers("needs"):
        for extra in mark.args:
            need(extra)


def pytest_sessionstart(session: pytest.Session) -> None:
    """Stop before any test if movingpunch comes from another source checkout.

    An editable install's import hook (scripts/setup.sh) takes precedence over
    PYTHONPATH, so a checkout tested with another checkout's .venv would
    silently test that other checkout's code. An installed copy (site-packages)
    or this checkout's python/ are fine.
    """
    import movingpunch

    here = Path(movingpunch.__file__).resolve().parent
    ours = ROOT / "python" / "movingpunch"
    checkout = here.parent.parent
    if here != ours and (checkout / "pyproject.toml").exists():
        pytest.exit(
            f"these tests ({ROOT}) would run against movingpunch from another "
            f"checkout ({here}): its editable install wins over PYTHONPATH. Use "
            "this checkout's own .venv (bash scripts/setup.sh) or a non-editable "
            "environment.",
            returncode=4,
        )


#: Hang guard of one command (imports included; a solve takes milliseconds,
#: the slowest bundled scene some seconds). Never a performance assertion.
CLI_TIMEOUT = 300.0
#: Hang guard of a short Python snippet run in a fresh interpreter.
CODE_TIMEOUT = 120.0

Completed = subprocess.CompletedProcess[str]


def _run_cli(
    *args: str, cwd: Path | None = None, timeout: float = CLI_TIMEOUT
) -> Completed:
    return subprocess.run(
        [sys.executable, "-m", "movingpunch", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
        cwd=cwd,
    )


def _run_python(code: str, *args: str, timeout: float = CODE_TIMEOUT) -> Completed:
    return subprocess.run(
        [sys.executable, "-c", code, *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


def _run_on_a_terminal(
    *args: str, timeout: float = CLI_TIMEOUT
) -> tuple[int, str, str]:
    """``movingpunch ARGS`` with stderr on a pseudo-terminal and stdout into
    a file: (status, stdout, what the terminal received)."""
    master, slave = pty.openpty()
    with tempfile.TemporaryFile() as out:
        proc = subprocess.Popen(
            [sys.executable, "-m", "movingpunch", *args],
            stdout=out,
            stderr=slave,
            stdin=subprocess.DEVNULL,
        )
        os.close(slave)
        received = bytearray()
        try:
            while select.select([master], [], [], timeout)[0]:
                try:
                    chunk = os.read(master, 4096)
                except OSError:  # the child closed its end
                    break
                if not chunk:
                    break
                received += chunk
        finally:
            os.close(master)
            if proc.poll() is None:
                proc.kill()
            status = proc.wait()
        out.seek(0)
        text = out.read().decode()
    return status, text, received.decode("utf-8", "replace")


def _modules_loaded_by(code: str) -> set[str]:
    # The list goes last on stdout, after anything CODE prints.
    proc = _run_python(
        code + "\nimport json as _j, sys as _s\nprint(_j.dumps(sorted(_s.modules)))\n"
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return set(json.loads(proc.stdout.splitlines()[-1]))


def _assert_one_line_error(proc: Completed, *words: str) -> None:
    assert proc.returncode == 2, proc
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("movingpunch: error: "), proc.stderr
    for word in words:
        assert word in lines[0], proc.stderr
    assert proc.stdout == ""


@pytest.fixture
def pool_pays(monkeypatch: pytest.MonkeyPatch) -> None:
    """Worker processes start on any sweep of more than one point (their
    start-up estimated free): the pool's own tests run small sweeps on it,
    which ``jobs`` would otherwise keep in this process."""
    from movingpunch.scene import _plan

    monkeypatch.setattr(_plan, "_STARTUP_SECONDS", 0.0)


@pytest.fixture
def run_cli() -> Callable[..., Completed]:
    """``run_cli(*args, cwd=None, timeout=CLI_TIMEOUT)``: ``python -m
    movingpunch ARGS`` in a subprocess; stdout and stderr captured as text,
    the exit status not checked."""
    return _run_cli


@pytest.fixture
def run_on_a_terminal() -> Callable[..., tuple[int, str, str]]:
    """``run_on_a_terminal(*args, timeout=CLI_TIMEOUT)``: ``python -m
    movingpunch ARGS`` with stderr on a pseudo-terminal (stdout into a
    file): (exit status, stdout, everything the terminal received)."""
    return _run_on_a_terminal


@pytest.fixture
def run_python() -> Callable[..., Completed]:
    """``run_python(code, *args, timeout=CODE_TIMEOUT)``: ``python -c CODE
    ARGS`` in a fresh interpreter (e.g. to see which modules an import loads);
    output captured as text, the exit status not checked."""
    return _run_python


@pytest.fixture
def modules_loaded_by() -> Callable[[str], set[str]]:
    """``modules_loaded_by(code)``: the names in ``sys.modules`` after CODE
    ran in a fresh interpreter (which must succeed), e.g. to prove that an
    import does not load Textual."""
    return _modules_loaded_by


@pytest.fixture
def assert_one_line_error() -> Callable[..., None]:
    """``assert_one_line_error(proc, *words)``: the command failed with exit
    status 2, no traceback, nothing on stdout and one stderr line
    ``movingpunch: error: ...`` that contains every word."""
    return _assert_one_line_error


@pytest.fixture
def local_cluster() -> Callable[..., Any]:
    """``local_cluster(**kwargs)``: a ``distributed.LocalCluster`` (a context
    manager) on loopback that takes no fixed port: the scheduler on a free
    port, no dashboard, and the scheduler's HTTP server, which Dask starts
    even without a dashboard (on 8787 by default), on a free port too, so that
    a busy 8787 (a user's Dask dashboard, a Jupyter session) changes nothing.
    ``kwargs`` go to LocalCluster (n_workers, processes, ...). Skips without
    the ``dask`` extra (see extras.py)."""
    need("dask")
    from distributed import LocalCluster

    def make(**kwargs: Any) -> Any:
        options: dict[str, Any] = {
            "host": "127.0.0.1",
            "protocol": "tcp://",
            "scheduler_port": 0,
            "dashboard_address": None,
            "worker_dashboard_address": None,
            "scheduler_kwargs": {"dashboard_address": "127.0.0.1:0"},
        }
        options.update(kwargs)
        return LocalCluster(**options)

    return make
