"""A sweep on a Dask distributed cluster (LocalCluster on loopback) gives the
numbers of the local run. Needs the ``dask`` extra, which CI installs."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from distributed import LocalCluster

import movingpunch as mp
from movingpunch.scene import ClusterError, Scene, Sweep, _executors


def _scene() -> Scene:
    return dataclasses.replace(
        Scene.bundled("fig3"),
        sweep=Sweep(
            "load", (0.001, 0.002, 0.003), quantities=("a", "p0", "indentation")
        ),
    )


@pytest.mark.parametrize("processes", [False, True])
def test_dask_sweep_matches_the_local_sweep(processes: bool) -> None:
    scene = _scene()
    local = scene.run(jobs=1)
    mp.clear_kernel_cache()  # in-process workers (processes=False) share it
    seen: list[tuple[int, int]] = []
    with LocalCluster(
        n_workers=2 if processes else 1,
        threads_per_worker=1,
        processes=processes,
        host="127.0.0.1",
        protocol="tcp://",
        dashboard_address=None,
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


def test_unreachable_scheduler_is_a_one_line_error(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(_executors, "DASK_CONNECT_TIMEOUT", 1.0)
    with pytest.raises(ClusterError, match="cannot reach the scheduler"):
        _scene().run(dask="tcp://127.0.0.1:9")
