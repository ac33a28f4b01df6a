"""Red-team findings 6 and 11 of issue 25, each refused clearly or right.

6. ``solve --profile table --table FILE`` reads FILE as a scene file is read
   (``scene._toml.read_bounded_file``): only a regular file of at most 1 MiB;
   /dev/zero, a FIFO and a huge file are refused at once, naming the file
   and the limit (they grew to 3.5 GB, blocked forever, were read whole).
11. ``--out ''`` is refused naming --out (it wrote into the current folder
   with exit 0); ``Profile.from_function`` takes a function of a float only
   (``math.cos``) by calling it point by point, and a function that fails
   both ways is an InvalidParameterError naming f (a bare TypeError before).

The subprocess timeouts are hang guards, not performance assertions.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.errors import InvalidParameterError

Completed = subprocess.CompletedProcess[str]
Run = Callable[..., Completed]

HANG_GUARD = 120.0  # seconds; each refusal comes before any solve
SOLVE = ("solve", "--vstar", "0.2", "--kw", "1", "--load", "0.002")


def _table(path: Path, points: int = 41) -> Path:
    """The cylinder R/h = 100 as a table: y = x^2/200 on |x| <= 2."""
    x = np.linspace(-2.0, 2.0, points)
    path.write_text("".join(f"{v!r} {v * v / 200.0!r}\n" for v in x.tolist()))
    return path


def _solve_table(run_cli: Run, table: str, cwd: Path | None = None) -> Completed:
    return run_cli(
        *SOLVE, "--profile", "table", "--table", table, cwd=cwd, timeout=HANG_GUARD
    )


def test_a_table_file_is_read_and_solved(tmp_path: Path, run_cli: Run) -> None:
    # The control: a regular table file is read. A parabola x^2/200 is the
    # cylinder R/h = 100 (the spline is exact for it).
    proc = run_cli(
        *SOLVE,
        "--profile",
        "table",
        "--table",
        str(_table(tmp_path / "parabola.txt")),
        "--json",
        timeout=HANG_GUARD,
    )
    assert proc.returncode == 0, proc.stderr
    a = json.loads(proc.stdout)["a"]
    cylinder = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
    assert a == pytest.approx(cylinder.a, rel=1e-7)


def test_dev_zero_as_a_table_is_refused(
    run_cli: Run, assert_one_line_error: Callable[..., None]
) -> None:
    proc = _solve_table(run_cli, "/dev/zero")
    assert_one_line_error(
        proc, "--table /dev/zero", "character device", "a regular file of at most 1 MiB"
    )


def test_a_fifo_as_a_table_is_refused_without_waiting(
    tmp_path: Path, run_cli: Run, assert_one_line_error: Callable[..., None]
) -> None:
    fifo = tmp_path / "table.fifo"
    os.mkfifo(fifo)  # nobody writes: opening it for reading would block
    proc = _solve_table(run_cli, str(fifo))
    assert_one_line_error(
        proc, f"--table {fifo}", "FIFO", "a regular file of at most 1 MiB"
    )


def test_a_table_over_the_limit_is_refused_unread(
    tmp_path: Path, run_cli: Run, assert_one_line_error: Callable[..., None]
) -> None:
    big = tmp_path / "big.txt"
    line = b"0.5 0.00125\n"
    big.write_bytes(line * ((1 << 20) // len(line) + 1))  # just over 1 MiB
    proc = _solve_table(run_cli, str(big))
    assert_one_line_error(
        proc,
        f"--table {big}",
        f"too large: {big.stat().st_size} bytes",
        "a regular file of at most 1 MiB",
    )


@pytest.mark.parametrize(
    ("name", "content", "words"),
    [
        ("latin1.txt", b"\xff 1 2\n", ("not UTF-8 text (byte 0)",)),
        ("folder", None, ("cannot read a directory",)),
        ("missing.txt", b"", ("cannot read: No such file or directory",)),
    ],
)
def test_other_unreadable_tables_are_refused(
    tmp_path: Path,
    run_cli: Run,
    assert_one_line_error: Callable[..., None],
    name: str,
    content: bytes | None,
    words: tuple[str, ...],
) -> None:
    path = tmp_path / name
    if content is None:
        path.mkdir()
    elif name != "missing.txt":
        path.write_bytes(content)
    proc = _solve_table(run_cli, str(path))
    assert_one_line_error(proc, f"--table {path}", *words)


def test_an_empty_table_name_is_refused(
    tmp_path: Path, run_cli: Run, assert_one_line_error: Callable[..., None]
) -> None:
    proc = _solve_table(run_cli, "", cwd=tmp_path)
    assert_one_line_error(proc, "argument --table", "must name a file, got ''")


@pytest.mark.parametrize(
    "command", [("run", "table1", "--no-plot"), ("accuracy", "fig4", "--tols", "1e-3")]
)
def test_an_empty_out_folder_is_refused(
    tmp_path: Path,
    run_cli: Run,
    assert_one_line_error: Callable[..., None],
    command: tuple[str, ...],
) -> None:
    # It wrote into the current folder with exit 0.
    proc = run_cli(*command, "--out", "", cwd=tmp_path, timeout=HANG_GUARD)
    assert_one_line_error(
        proc, "argument --out", "must name a folder, got ''", "use '.'"
    )
    assert list(tmp_path.iterdir()) == []


# -- Profile.from_function --------------------------------------------------


def test_from_function_calls_a_scalar_function_point_by_point() -> None:
    # math.cos takes no array (TypeError); a branch on x > 0 none either
    # (ValueError): each is called once per x and gives the table of the
    # vectorised function.
    scalar = mp.Profile.from_function(lambda x: 1.0 - math.cos(x), 1.0, points=101)
    vector = mp.Profile.from_function(lambda x: 1.0 - np.cos(x), 1.0, points=101)
    assert scalar.x == vector.x
    np.testing.assert_allclose(scalar.y, vector.y, rtol=0.0, atol=1e-15)

    def branchy(x: float) -> float:
        return x * x / 200.0 if x >= 0 else x * x / 100.0

    table = mp.Profile.from_function(branchy, 2.0, points=101)  # type: ignore[arg-type]
    xs = np.asarray(table.x)
    np.testing.assert_array_equal(
        table.y, np.where(xs >= 0, xs * xs / 200.0, xs * xs / 100.0)
    )
    assert not table.symmetric


def test_from_function_of_math_cos_is_a_clear_refusal() -> None:
    # The red-team call: cos is concave, which the table check refuses by
    # name (a bare TypeError came first before).
    with pytest.raises(InvalidParameterError, match="must be convex") as info:
        mp.Profile.from_function(lambda x: math.cos(x), 2.0)
    assert not isinstance(info.value, TypeError)


def test_from_function_that_fails_both_ways_names_f() -> None:
    with pytest.raises(InvalidParameterError) as info:
        mp.Profile.from_function(lambda x: math.sqrt(x), 1.0)
    message = str(info.value)
    assert info.value.parameter == "f"
    assert message.startswith("f must accept a NumPy array of x/h")
    assert "TypeError" in message  # the array call
    assert "x = -1.0" in message
    assert "math domain error" in message  # the first point's call
