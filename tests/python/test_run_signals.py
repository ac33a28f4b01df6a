"""Real signals to real ``movingpunch run`` / ``accuracy`` processes: they end
promptly with one line and status 130 (SIGINT) or 143 (SIGTERM), leave no
process behind and no file changed; a parent killed with SIGKILL takes its
worker processes with it (they watch a pipe only the parent holds open).

Each test starts a process on a sweep that would take minutes and stops it
after its workers are up; the timeouts below are hang guards, not
performance assertions."""

from __future__ import annotations

import contextlib
import itertools
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import psutil
import pytest

import movingpunch as mp
from movingpunch.scene import Scene, Sweep, Vary, _plan
from movingpunch.scene._solve import point_key

# About 20 000 cold solves: minutes of work at any --jobs on two cores.
LONG_SWEEP = """\
[params]
kw = 1.0
radius = 100
load = 0.002

[sweep]
param = "vstar"
start = 0.0
stop = 0.5
points = {points}
"""

START_TIMEOUT = 60.0  # hang guard: the workers of a run are up
STOP_TIMEOUT = 5.0  # the process ends this soon after the signal
GONE_TIMEOUT = 10.0  # and every process it started soon after


def _scene_file(tmp_path: Path, points: int) -> Path:
    path = tmp_path / "sweep.toml"
    path.write_text(LONG_SWEEP.format(points=points), encoding="utf-8")
    return path


def _start(*args: str, cwd: Path) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-m", "movingpunch", *args],
        cwd=cwd,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,  # its own process group, as in a terminal
    )


def _wait_for_children(proc: subprocess.Popen[str], n: int) -> list[psutil.Process]:
    """The descendants of ``proc`` once there are ``n`` of them (the
    workers and the resource tracker), and a moment later (at work)."""
    parent = psutil.Process(proc.pid)
    deadline = time.monotonic() + START_TIMEOUT
    while time.monotonic() < deadline:
        assert proc.poll() is None, proc.communicate()
        children = parent.children(recursive=True)
        if len(children) >= n:
            time.sleep(0.5)
            return parent.children(recursive=True)
        time.sleep(0.05)
    raise AssertionError(f"fewer than {n} child processes after {START_TIMEOUT} s")


def _assert_all_gone(processes: list[psutil.Process]) -> None:
    deadline = time.monotonic() + GONE_TIMEOUT
    alive = processes
    while time.monotonic() < deadline:
        alive = [
            p
            for p in processes
            if p.is_running() and p.status() != psutil.STATUS_ZOMBIE
        ]
        if not alive:
            return
        time.sleep(0.05)
    for p in alive:  # do not leave them to the next test
        p.kill()
    raise AssertionError(f"still running {GONE_TIMEOUT} s later: {alive}")


def _stop(proc: subprocess.Popen[str], sig: int, *, group: bool) -> tuple[str, str]:
    if group:  # a terminal's Ctrl-C reaches the whole foreground group
        os.killpg(proc.pid, sig)
    else:
        proc.send_signal(sig)
    try:
        return proc.communicate(timeout=STOP_TIMEOUT)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        raise AssertionError(
            f"still running {STOP_TIMEOUT} s after the signal"
        ) from None


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


@pytest.mark.slow
@pytest.mark.parametrize(
    ("sig", "status", "line", "group"),
    [
        (signal.SIGINT, 130, "movingpunch: interrupted\n", False),
        (signal.SIGINT, 130, "movingpunch: interrupted\n", True),
        (signal.SIGTERM, 143, "movingpunch: interrupted (SIGTERM)\n", False),
    ],
    ids=["SIGINT", "SIGINT-to-group", "SIGTERM"],
)
def test_signal_stops_a_run_with_workers(
    tmp_path: Path, sig: int, status: int, line: str, group: bool
) -> None:
    # A previous result of the same scene, which the interrupted run must
    # leave as it was.
    scene = _scene_file(tmp_path, points=3)
    out = tmp_path / "out"
    done = subprocess.run(
        [sys.executable, "-m", "movingpunch", "run", str(scene), "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    before = _snapshot(out)
    assert "sweep-sweep.csv" in before

    scene = _scene_file(tmp_path, points=20_000)
    proc = _start("run", str(scene), "--jobs", "2", "--out", str(out), cwd=tmp_path)
    # --jobs 2: this process and one worker; and the resource tracker.
    children = _wait_for_children(proc, 2)
    stdout, stderr = _stop(proc, sig, group=group)

    assert proc.returncode == status, stderr
    assert stderr == line
    assert stdout == ""
    _assert_all_gone(children)
    assert _snapshot(out) == before  # no file written, none half-written


@pytest.mark.slow
def test_sigterm_stops_a_serial_run(tmp_path: Path) -> None:
    scene = _scene_file(tmp_path, points=20_000)
    proc = _start("run", str(scene), "--jobs", "1", cwd=tmp_path)
    time.sleep(2.0)  # importing, validating, solving
    assert proc.poll() is None
    assert psutil.Process(proc.pid).children() == []  # serial: no worker
    stdout, stderr = _stop(proc, signal.SIGTERM, group=False)
    assert proc.returncode == 143, stderr
    assert stderr == "movingpunch: interrupted (SIGTERM)\n"
    assert stdout == ""


@pytest.mark.slow
def test_sigint_stops_accuracy(tmp_path: Path) -> None:
    scene = _scene_file(tmp_path, points=2_000)
    proc = _start("accuracy", str(scene), "--out", str(tmp_path), cwd=tmp_path)
    time.sleep(2.0)
    assert proc.poll() is None
    stdout, stderr = _stop(proc, signal.SIGINT, group=True)
    assert proc.returncode == 130, stderr
    assert stderr == "movingpunch: interrupted\n"
    assert stdout == ""
    assert list(tmp_path.glob("*.csv")) == []


@pytest.mark.slow
@pytest.mark.parametrize("jobs", [2, 3])
def test_kill_9_of_the_parent_ends_its_workers(tmp_path: Path, jobs: int) -> None:
    scene = _scene_file(tmp_path, points=20_000)
    proc = _start("run", str(scene), "--jobs", str(jobs), cwd=tmp_path)
    children = _wait_for_children(proc, jobs)  # jobs - 1 workers, the tracker
    workers = [c for c in children if "resource_tracker" not in " ".join(c.cmdline())]
    assert len(workers) == jobs - 1, children
    proc.kill()
    proc.wait(timeout=STOP_TIMEOUT)
    # Orphans are re-parented: wait on the processes recorded before the kill.
    _assert_all_gone(children)
    proc.communicate(timeout=STOP_TIMEOUT)  # the pipes they shared are closed


@pytest.mark.slow
def test_sigint_stops_a_dask_run(
    tmp_path: Path, local_cluster: Callable[..., Any]
) -> None:
    scene = _scene_file(tmp_path, points=20_000)
    Scene.load(scene)  # valid
    with local_cluster(n_workers=1, threads_per_worker=1, processes=False) as cluster:
        proc = _start(
            "run", str(scene), "--dask", cluster.scheduler_address, cwd=tmp_path
        )
        deadline = time.monotonic() + START_TIMEOUT
        while not cluster.scheduler.tasks and time.monotonic() < deadline:
            assert proc.poll() is None, proc.communicate()
            time.sleep(0.05)
        assert cluster.scheduler.tasks, "no task reached the scheduler"
        stdout, stderr = _stop(proc, signal.SIGINT, group=False)
        address = cluster.scheduler_address
    assert proc.returncode == 130, stderr
    # The connection's two lines (stderr is not a terminal: no countdown
    # redrawn in place), then the interruption.
    assert stderr.splitlines() == [
        f"connecting to {address} … (timeout 20 s)",
        f"connected to {address} (1 worker)",
        "movingpunch: interrupted",
    ]
    assert stdout == ""


BUSY_WORKER = """\
import time
from movingpunch.scene import _executors

if __name__ == "__main__":
    pool = _executors._WorkerPool()
    pool.start(1)
    proc, conn = pool.workers[0]
    # One chunk of 4000 damped points with their stress peaks (~30 ms each):
    # minutes of work without a look at its pipe.
    task = {
        "vstar": 0.2, "kw": 1.0, "nu": 0.2, "tol": 1e-8, "damping": 0.5,
        "points": [(100.0, 0.002 * (1 + i / 4000)) for i in range(4000)],
        "peaks": True,
    }
    conn.send((0, [task]))
    print(proc.pid, flush=True)
    time.sleep(600)
"""


@pytest.mark.slow
def test_a_busy_worker_exits_when_its_parent_is_killed(tmp_path: Path) -> None:
    """Mid-chunk, a worker reads no pipe: it is its watcher thread that sees
    the parent go (the pipe only the parent holds open closes)."""
    script = tmp_path / "busy.py"
    script.write_text(BUSY_WORKER, encoding="utf-8")
    proc = subprocess.Popen(
        [sys.executable, str(script)],
        stdout=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    assert proc.stdout is not None
    worker = psutil.Process(int(proc.stdout.readline()))
    deadline = time.monotonic() + START_TIMEOUT
    try:
        while worker.cpu_times().user < 1.0:  # imported, and solving
            assert time.monotonic() < deadline, "the worker never got to work"
            time.sleep(0.1)
        assert worker.is_running()  # still busy with the chunk
    except BaseException:
        for p in (worker, psutil.Process(proc.pid)):
            with contextlib.suppress(psutil.NoSuchProcess):
                p.kill()
        proc.wait(timeout=STOP_TIMEOUT)
        proc.stdout.close()
        raise
    proc.kill()
    proc.wait(timeout=STOP_TIMEOUT)
    proc.stdout.close()  # the worker shares it: do not wait for its end
    _assert_all_gone([worker])


# -- chunks: the unit of work of the pool (no process started) -------------------

BASE = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2}


@pytest.mark.parametrize(
    ("sweep", "jobs"),
    [
        (Sweep.range("vstar", 0.0, 0.5, 2000), 2),  # 2000 groups of one point
        (Sweep.range("load", 1e-4, 4e-3, 20_000), 2),  # one group of 20 000
        (Sweep.range("radius", 25.0, 100.0, 7), 4),  # tiny: a chunk per job
        (Sweep.range("load", 1e-3, 4e-3, 50), 2),  # with a vary: 4 groups
    ],
    ids=["cold", "one-group", "tiny", "groups"],
)
def test_chunks_cover_the_sweep_in_solve_order(sweep: Sweep, jobs: int) -> None:
    vary = Vary("vstar", (0.0, 0.1, 0.2, 0.3)) if len(sweep.values) == 50 else None
    plan = _plan.plan_sweep(Scene(params=BASE, vary=vary, sweep=sweep))
    target = _plan.chunk_target(plan, jobs, _plan.CHUNK_MIN, _plan.CHUNK_MAX)
    chunks = _plan.split_chunks(plan, target)
    # Every key once, in the plan's order (descending lambda in a group).
    ranges = [r for chunk in chunks for r in chunk]
    assert ranges[0][0] == 0
    assert ranges[-1][1] == plan.n_keys
    assert all(a[1] == b[0] for a, b in itertools.pairwise(ranges))
    assert len(chunks) >= min(jobs, plan.n_keys)
    starts = plan.starts.tolist()
    for g in range(plan.n_groups):  # one group: one kernel, lambda descending
        members = plan.keys[starts[g] : starts[g + 1]]
        assert (members[:, :7] == members[0, :7]).all()
        assert (np.diff(members[:, 7]) < 0).all()
    for chunk in chunks:
        groups = [plan.group(lo) for lo, _ in chunk]
        assert len(set(groups)) == len(chunk)
        for lo, hi in chunk:
            assert hi > lo
            assert all(plan.group(k) == plan.group(lo) for k in range(lo, hi))
        seconds = sum(
            _plan._point_seconds(plan, i == 0)
            for lo, hi in chunk
            for i in range(hi - lo)
        )
        assert seconds <= target + _plan._point_seconds(plan, True)
        assert sum(hi - lo for lo, hi in chunk) <= _plan._CHUNK_POINTS
    # A group that fits in a chunk is in one chunk (one kernel build).
    cold, warm = _plan._point_seconds(plan, True), _plan._point_seconds(plan, False)
    for g in range(plan.n_groups):
        lo, hi = starts[g], starts[g + 1]
        if cold + (hi - lo - 1) * warm <= target:
            holders = [c for c in chunks if any(a <= lo < b for a, b in c)]
            assert len(holders) == 1, g
            assert (lo, hi) in holders[0]
    # Every point's key is the key of its parameters (point_key).
    sw = plan.scene.sweep
    for i, v in enumerate(plan.scene.curve_values()):
        for j in range(0, len(sw.values), max(len(sw.values) // 50, 1)):
            p = plan.scene.point(v, **{sw.param: sw.values[j]})
            assert plan.key(int(plan.index[i, j])) == point_key(p, plan.scene.tol)
    # Never thousands of units: the in-flight bound makes the pool's waits
    # O(jobs) whatever the sweep.
    assert len(chunks) <= 4 * jobs + _plan._sweep_seconds(plan) / _plan.CHUNK_MIN


def test_automatic_jobs_run_small_sweeps_here() -> None:
    small = _plan.plan_sweep(
        Scene(params=BASE, sweep=Sweep.range("load", 1e-3, 4e-3, 200))
    )
    cold = _plan.plan_sweep(
        Scene(params=BASE, sweep=Sweep.range("vstar", 0.0, 0.5, 2000))
    )
    assert not _plan.use_workers(small, 2, None)  # jobs=2 is a limit
    assert _plan.use_workers(small, 2, "tcp://127.0.0.1:1")  # Dask: as asked
    assert _plan.use_workers(cold, 2, None)
    assert not _plan.use_workers(cold, 1, None)


def test_jobs_on_a_small_sweep_run_here_with_the_same_numbers() -> None:
    """--jobs 2 on a sweep too small to pay for a worker: no process is
    started (result.jobs 1), the numbers are the serial ones."""
    import multiprocessing

    scene = Scene(params=BASE, sweep=Sweep.range("load", 1e-3, 4e-3, 40))
    before = set(multiprocessing.active_children())
    pooled = scene.run(jobs=2)
    assert pooled.jobs == 1
    assert set(multiprocessing.active_children()) <= before
    serial = scene.run(jobs=1)
    assert pooled.sweep is not None
    assert serial.sweep is not None
    np.testing.assert_array_equal(pooled.sweep.data["a"], serial.sweep.data["a"])


@pytest.mark.usefixtures("pool_pays")
def test_a_group_split_across_workers_gives_the_serial_numbers() -> None:
    """One load group in chunks on two processes: the numbers of the serial
    run (each chunk rebuilds or reuses its kernel; the answer is the same)."""
    scene = Scene(
        params=BASE,
        sweep=Sweep.range("load", 1e-4, 4e-3, 60, quantities=("a", "p0")),
    )
    mp.clear_kernel_cache()
    serial = scene.run(jobs=1)
    pooled = scene.run(jobs=2)
    assert pooled.jobs == 2
    assert serial.sweep is not None
    assert pooled.sweep is not None
    for q in ("a", "p0"):
        np.testing.assert_allclose(
            pooled.sweep.data[q], serial.sweep.data[q], rtol=1e-10
        )
    assert pooled.stage("contact").count == 60
