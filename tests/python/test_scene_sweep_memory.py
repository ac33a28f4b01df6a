"""A sweep in bounded memory: it keeps its table, not a solution or an object
per point (its plan is arrays); its files are written in pieces as they are
made; its printed summary shows the ends of a long table.

The bound is measured with tracemalloc (every Python allocation, numpy's
included: deterministic, unlike RSS): the memory a finished sweep keeps
grows by less than 150 bytes a point from 400 to 2400 points. The table
itself takes about 60 (its values, two quantities, ``valid``, the grid as the
scene holds it); one solution a point would take several kilobytes, one dict
a point hundreds of bytes.
"""

from __future__ import annotations

import errno
import gc
import json
import tracemalloc
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from movingpunch import outputs
from movingpunch.scene import (
    OutputSpec,
    Scene,
    Sweep,
    Vary,
    _export,
    read_csv,
    read_json,
)
from movingpunch.scene._export import format_summary, stream_outputs, write_outputs

BASE = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2}


def _load_sweep(points: int) -> Scene:
    return Scene(params=BASE, sweep=Sweep.range("load", 1e-3, 4e-3, points))


def _kept_bytes(points: int) -> int:
    """Bytes the run of a ``points``-point load sweep keeps (its result
    alive), beyond those of its scene."""
    scene = _load_sweep(points)
    gc.collect()
    tracemalloc.start()
    try:
        before = tracemalloc.get_traced_memory()[0]
        result = scene.run()
        gc.collect()
        kept = tracemalloc.get_traced_memory()[0] - before
    finally:
        tracemalloc.stop()
    assert result.sweep is not None
    assert np.isfinite(result.sweep.data["a"]).all()
    return kept


def test_a_sweep_keeps_its_table_not_its_points() -> None:
    _kept_bytes(50)  # the kernel, the caches: built before the measurement
    small, large = _kept_bytes(400), _kept_bytes(2400)
    per_point = (large - small) / 2000
    print(f"kept {per_point:.0f} bytes a point")
    assert per_point < 150, per_point


def test_a_sweep_keeps_solutions_only_when_asked() -> None:
    scene = Scene(
        params=BASE,
        outputs={"contact_width": OutputSpec("contact_width")},
        sweep=Sweep.range("load", 1.1e-3, 4.1e-3, 40),  # not the curve's 2e-3
    )
    result = scene.run()
    assert len(result.solutions) == 1  # the curve's, for its output
    kept = scene.run(keep_solutions=True)
    assert len(kept.solutions) == 41  # the 40 points and the curve's
    assert result.sweep is not None
    assert kept.sweep is not None
    np.testing.assert_array_equal(result.sweep.data["a"], kept.sweep.data["a"])
    by_load = {s.load: s.a for s in kept.solutions}
    for x, a in zip(kept.sweep.values, kept.sweep.data["a"][0], strict=True):
        assert by_load[float(x)] == a
    with pytest.raises(TypeError, match="keep_solutions"):
        scene.run(keep_solutions=1)  # type: ignore[arg-type]


def test_shared_keys_are_solved_once_and_rescaled() -> None:
    """radius and load enter only through lambda = radius * load: a radius
    sweep under a vary of the load repeats keys across curves; each is
    solved once and rescaled (indentation ~ load, drag ~ 1/radius) to the
    numbers of a direct solve."""
    import movingpunch as mp

    sweep = Sweep("radius", (50.0, 100.0, 200.0), quantities=("a", "indentation"))
    scene = Scene(params=BASE, vary=Vary("load", (0.001, 0.002, 0.004)), sweep=sweep)
    result = scene.run(keep_solutions=True)
    assert len(result.solutions) == 5  # lambda 0.05 ... 0.8: five, not nine
    assert result.sweep is not None
    for i, load in enumerate((0.001, 0.002, 0.004)):
        for j, radius in enumerate(sweep.values):
            s = mp.solve(**{**BASE, "radius": radius, "load": load})
            assert result.sweep.data["a"][i, j] == pytest.approx(s.a, rel=1e-12)
            assert result.sweep.data["indentation"][i, j] == pytest.approx(
                s.indentation, rel=1e-9
            )


@pytest.fixture
def small_pieces(monkeypatch: pytest.MonkeyPatch) -> None:
    """Rows formatted 7 at a time: a short table crosses several pieces."""
    monkeypatch.setattr(_export, "_ROWS", 7)


def _sweep_result() -> object:
    scene = Scene(
        params=BASE,
        vary=Vary("vstar", (0.0, 0.2)),
        sweep=Sweep.range("load", 1e-3, 4e-3, 30, quantities=("a", "p0", "drag")),
    )
    return scene.run()


@pytest.mark.usefixtures("small_pieces")
def test_a_streamed_csv_is_the_whole_table() -> None:
    result = _sweep_result()
    ((name, body),) = stream_outputs(result, "csv")  # type: ignore[arg-type]
    assert not isinstance(body, bytes)
    text = b"".join(body).decode("utf-8")
    sweep = result.sweep  # type: ignore[attr-defined]
    columns = sweep.columns()
    header = [line for line in text.splitlines() if line.startswith("#")]
    assert header[-len(result.scene.to_toml().splitlines()) - 2] == (  # type: ignore[attr-defined]
        "# columns: " + ",".join(columns)
    )
    rows = [line for line in text.splitlines() if not line.startswith("#")]
    assert len(rows) == 30
    for i, row in enumerate(rows):
        assert row == ",".join(repr(float(c[i])) for c in columns.values())
    assert text.endswith("\n")
    assert name.endswith("-sweep.csv")


@pytest.mark.usefixtures("small_pieces")
def test_a_streamed_json_is_the_whole_document(tmp_path: Path) -> None:
    result = _sweep_result()
    ((_, body),) = stream_outputs(result, "json")  # type: ignore[arg-type]
    text = b"".join(body).decode("utf-8")
    doc = json.loads(text)
    # The same bytes as json.dumps of the whole document.
    assert text == json.dumps(doc, indent=1, allow_nan=False) + "\n"
    sweep = result.sweep  # type: ignore[attr-defined]
    for key, values in sweep.columns().items():
        assert doc["columns"][key] == [float(v) for v in values]
    (path,) = write_outputs(result, tmp_path, "json")  # type: ignore[arg-type]
    meta, cols = read_json(path)
    assert meta["scene"] == result.scene  # type: ignore[attr-defined]
    np.testing.assert_array_equal(cols["a[vstar=0.2]"], sweep.data["a"][1])


def test_an_empty_column_streams_as_json() -> None:
    text = "".join(_export._json_pieces({"a": "b"}, "x = 1\n", {"c": np.array([])}))
    assert (
        text
        == json.dumps({"a": "b", "scene": "x = 1\n", "columns": {"c": []}}, indent=1)
        + "\n"
    )
    text = "".join(_export._json_pieces({"a": "b"}, "", {}))
    assert json.loads(text) == {"a": "b", "scene": "", "columns": {}}


def test_a_disk_that_fills_while_a_table_streams_keeps_the_old_file(
    tmp_path: Path,
) -> None:
    (tmp_path / "t.csv").write_bytes(b"old\n")
    made = []

    def pieces() -> Iterator[bytes]:
        for k in range(5):
            made.append(k)
            if k == 3:
                raise OSError(errno.ENOSPC, "No space left on device")
            yield b"row\n" * 1000

    with pytest.raises(outputs.OutputError, match="No space left on device"):
        outputs.publish(tmp_path, [("t.csv", pieces())])
    assert made == [0, 1, 2, 3]  # made as written: stopped at the failure
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.csv"]
    assert (tmp_path / "t.csv").read_bytes() == b"old\n"
    written = outputs.publish(tmp_path, [("t.csv", iter([b"a\n", b"b\n"]))])
    assert written == [tmp_path / "t.csv"]
    assert (tmp_path / "t.csv").read_bytes() == b"a\nb\n"


def test_a_long_sweep_prints_its_ends_and_writes_every_row(tmp_path: Path) -> None:
    result = _load_sweep(1500).run()
    text = format_summary(result)
    assert "(1500 points)" in text
    assert "... 1460 rows not shown (--out DIR writes all)" in text
    assert "0.004" in text.split("rows not shown")[1]  # the last row
    (path,) = write_outputs(result, tmp_path, "csv")
    _, cols = read_csv(path)
    assert result.sweep is not None
    np.testing.assert_array_equal(cols["a"], result.sweep.data["a"][0])
    assert len(cols["load"]) == 1500
