"""A sweep on a Dask distributed cluster (LocalCluster on loopback, free ports:
the ``local_cluster`` fixture) gives the numbers of the local run. The tests
that connect need the ``dask`` extra, which CI installs (skipped without it,
with the reason: extras.py); without it ``--dask`` is a one-line error."""

from __future__ import annotations

import dataclasses
import re
import socket
import subprocess
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.scene import ClusterError, Scene, Sweep, _executors, _plan


def _scene() -> Scene:
    return dataclasses.replace(
        Scene.bundled("fig3"),
        sweep=Sweep(
            "load", (0.001, 0.002, 0.003), quantities=("a", "p0", "indentation")
        ),
    )


@pytest.mark.parametrize("processes", [False, True])
def test_dask_sweep_matches_the_local_sweep(
    processes: bool, local_cluster: Callable[..., Any]
) -> None:
    scene = _scene()
    local = scene.run(jobs=1)
    mp.clear_kernel_cache()  # in-process workers (processes=False) share it
    seen: list[tuple[int, int]] = []
    with local_cluster(
        n_workers=2 if processes else 1, threads_per_worker=1, processes=processes
    ) as cluster:
        remote = scene.run(
            dask=cluster.scheduler_address,
            progress=lambda done, total: seen.append((done, total)),
        )
    assert local.sweep is not None
    assert remote.sweep is not None
    assert remote.jobs == 0
    for q in ("a", "p0", "indentation"):
        np.testing.assert_allclose(
            remote.sweep.data[q], local.sweep.data[q], rtol=1e-12
        )
    assert seen[-1] == (12, 12)
    # Four groups (one per kw), one task each: four kernel builds.
    assert remote.stage("kernel").count == 4
    assert remote.stage("contact").count == 12


def test_a_dask_sweep_of_more_chunks_than_it_sends_ahead(
    local_cluster: Callable[..., Any], monkeypatch: pytest.MonkeyPatch
) -> None:
    """One chunk sent ahead per worker (the window at its smallest): every
    chunk is still submitted as the earlier ones come back, in order, and
    the numbers are the local run's."""
    monkeypatch.setattr(_executors, "_DASK_AHEAD", 1)
    monkeypatch.setattr(_plan, "DASK_CHUNK_MIN", 0.003)
    monkeypatch.setattr(_executors, "DASK_CHUNK_MIN", 0.003)
    scene = Scene(
        params={"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2},
        sweep=Sweep.range("vstar", 0.0, 0.4, 40, quantities=("a", "p0")),
    )
    plan = _plan.plan_sweep(scene)
    chunks = _plan.split_chunks(
        plan, _plan.chunk_target(plan, 2, 0.003, _plan.DASK_CHUNK_MAX)
    )
    assert len(chunks) >= 10  # many more than the window of 2
    local = scene.run(jobs=1)
    seen: list[tuple[int, int]] = []
    with local_cluster(n_workers=2, threads_per_worker=1, processes=False) as cluster:
        remote = scene.run(
            dask=cluster.scheduler_address,
            progress=lambda done, total: seen.append((done, total)),
        )
    assert remote.sweep is not None
    assert local.sweep is not None
    for q in ("a", "p0"):
        np.testing.assert_allclose(
            remote.sweep.data[q], local.sweep.data[q], rtol=1e-12
        )
    assert seen[-1] == (40, 40)
    assert len(seen) >= 10  # one progress step per chunk


@pytest.mark.needs("dask")
def test_a_busy_dashboard_port_changes_nothing(
    local_cluster: Callable[..., Any],
) -> None:
    # Dask's scheduler starts an HTTP server even without a dashboard, on
    # 8787 by default: with that port held (a user's own Dask dashboard, a
    # Jupyter session) the cluster failed to start. Hold it here (if nobody
    # else does already) and start one.
    holder = socket.socket()
    try:
        holder.bind(("127.0.0.1", 8787))
        holder.listen()
    except OSError:  # held by another process: the case under test too
        pass
    try:
        with local_cluster(n_workers=1, threads_per_worker=1, processes=False) as c:
            assert c.scheduler.http_server.port not in (0, 8787)
            result = _scene().run(dask=c.scheduler_address)
    finally:
        holder.close()
    assert result.sweep is not None
    assert result.stage("contact").count == 12


@pytest.mark.needs("dask")
def test_unreachable_scheduler_is_a_one_line_error(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(_executors, "DASK_CONNECT_TIMEOUT", 1.0)
    with pytest.raises(ClusterError, match="cannot reach the scheduler"):
        _scene().run(dask="tcp://127.0.0.1:9")


DEAD = "tcp://127.0.0.1:1"


@pytest.mark.needs("dask")
def test_cli_dead_scheduler_counts_down_and_names_the_timeout(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    # Piped stderr: plain lines (no \r), then one error naming --dask, the
    # address and the timeout.
    proc = run_cli("run", "fig3", "--dask", DEAD, "--dask-timeout", "2")
    assert proc.returncode == 2, proc.stderr
    assert proc.stdout == ""
    assert "\r" not in proc.stderr
    lines = proc.stderr.splitlines()
    assert lines[0] == f"connecting to {DEAD} … (timeout 2 s)"
    assert lines[-1].startswith(
        f"movingpunch: error: --dask {DEAD} (--dask-timeout 2 s)"
    )
    assert "cannot reach the scheduler" in lines[-1]
    assert len(lines) == 2  # a countdown line at most every 5 s
    assert "Traceback" not in proc.stderr


@pytest.mark.needs("dask")
def test_cli_dead_scheduler_countdown_on_a_terminal(
    run_on_a_terminal: Callable[..., tuple[int, str, str]],
) -> None:
    # On a terminal: one line redrawn in place with the seconds left.
    status, out, terminal = run_on_a_terminal(
        "run", "fig3", "--dask", DEAD, "--dask-timeout", "2.5"
    )
    assert status == 2, terminal
    assert out == ""
    assert f"\r\x1b[Kconnecting to {DEAD} … (timeout 2.5 s)" in terminal
    assert re.search(
        rf"\r\x1b\[Kconnecting to {re.escape(DEAD)} … [12] s left", terminal
    )
    assert f"movingpunch: error: --dask {DEAD} (--dask-timeout 2.5 s)" in terminal


@pytest.mark.parametrize("value", ["0", "-1", "3601", "nan", "soon"])
def test_cli_bad_dask_timeout(
    value: str,
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    proc = run_cli("run", "fig3", "--dask", DEAD, "--dask-timeout", value)
    assert_one_line_error(proc, "--dask-timeout", "0 < SECONDS <= 3600", value)


def test_cli_connects_and_says_so(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    local_cluster: Callable[..., Any],
) -> None:
    with local_cluster(n_workers=1, threads_per_worker=1, processes=False) as cluster:
        address = cluster.scheduler_address
        proc = run_cli("run", "table1", "--dask", address, "--no-plot")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stderr.splitlines()
    assert lines[0] == f"connecting to {address} … (timeout 20 s)"
    assert f"connected to {address} (1 worker)" in lines
    assert "Stages" in proc.stdout


@pytest.mark.needs("dask")
def test_run_reports_connecting_with_its_timeout() -> None:
    events: list[tuple[str, float]] = []
    with pytest.raises(ClusterError, match=r"within 1\.5 s"):
        _scene().run(
            dask=DEAD,
            dask_timeout=1.5,
            on_dask=lambda event, value: events.append((event, value)),
        )
    assert events == [("connecting", 1.5)]


@pytest.mark.parametrize("value", [0.0, -1.0, float("nan"), float("inf")])
def test_run_refuses_a_bad_dask_timeout(value: float) -> None:
    with pytest.raises(ValueError, match="dask_timeout"):
        _scene().run(dask=DEAD, dask_timeout=value)


def test_dask_without_the_extra_is_a_one_line_error(
    run_python: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    # Runs whether the extra is installed or not: Dask is hidden here.
    code = (
        "import sys; sys.modules['distributed'] = None; "
        "from movingpunch.cli import main; raise SystemExit(main(sys.argv[1:]))"
    )
    proc = run_python(code, "run", "fig3", "--dask", DEAD, "--no-plot")
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    assert proc.stdout == ""
    assert proc.stderr.splitlines() == [
        "movingpunch: error: --dask needs Dask distributed: "
        "pip install 'movingpunch[dask]'"
    ]
