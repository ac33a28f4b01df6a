"""The command-line interface, run as a user would: in a subprocess."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

PAPER_CASE = ["--vstar", "0.2", "--kw", "1", "--radius", "100", "--load", "0.002"]


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "movingpunch", *args],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )


def number_after(label: str, table: str) -> float:
    """The value in the row of ``table`` whose label is ``label``."""
    match = re.search(rf"^\s*{re.escape(label)}\s+(\S+)", table, re.MULTILINE)
    assert match, f"no row {label!r} in:\n{table}"
    return float(match.group(1))


def assert_one_line_error(proc: subprocess.CompletedProcess[str], *words: str) -> None:
    assert proc.returncode == 2, proc
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("movingpunch: error: "), proc.stderr
    for word in words:
        assert word in lines[0], proc.stderr
    assert proc.stdout == ""


def test_solve_prints_a_table() -> None:
    proc = run("solve", *PAPER_CASE)
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    for label in (
        "a/h",
        "p0/(P/h)",
        "δ/h",
        "V*_cr",
        "V*_R",
        "φ1",
        "μ/(P/h)",
        "collocation N",
        "iterations",
        "error estimate",
        "solve time",
        "validity",
    ):
        assert label in out, label
    assert re.search(r"μ/\(P/h\)\s+500\b", out)
    a = number_after("a/h", out)
    assert a == pytest.approx(0.3, abs=0.1)


def test_solve_json() -> None:
    proc = run("solve", *PAPER_CASE, "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["a"] == pytest.approx(0.3, abs=0.1)
    assert data["load"] == 0.002
    assert data["kw"] == 1.0
    assert data["valid"] is True
    assert data["critical_vstar"] == pytest.approx(0.5716928, rel=1e-6)
    for key in (
        "p0",
        "indentation",
        "rayleigh_vstar",
        "phi1",
        "iterations",
        "collocation_n",
        "error_estimate",
        "elapsed",
        "validity",
        "min_pressure",
        "min_gap",
        "tol",
        "nu",
        "radius",
        "vstar",
    ):
        assert key in data


def test_solve_json_rigid_base_is_json_safe() -> None:
    proc = run(
        "solve",
        "--vstar",
        "0",
        "--kw",
        "inf",
        "--radius",
        "100",
        "--load",
        "0.002",
        "--json",
    )
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["kw"] == "inf"


def test_critical() -> None:
    proc = run("critical", "--kw", "1")
    assert proc.returncode == 0, proc.stderr
    vcr = number_after("V*_cr", proc.stdout)
    assert vcr == pytest.approx(0.5716928, abs=1e-6)
    assert "0.8299135" in proc.stdout  # Rayleigh, nu = 0.2


def test_critical_json_rigid_base() -> None:
    proc = run("critical", "--kw", "inf", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["critical_wavenumber"] == "inf"
    assert data["critical_vstar"] == pytest.approx(0.8299135134, rel=1e-9)
    assert data["rayleigh_vstar"] == pytest.approx(0.8299135134, rel=1e-9)


def test_no_subcommand_prints_help() -> None:
    proc = run()
    assert proc.returncode == 0
    assert "solve" in proc.stdout
    assert "critical" in proc.stdout


def replace(args: list[str], flag: str, value: str) -> list[str]:
    out = list(args)
    out[out.index(flag) + 1] = value
    return out


@pytest.mark.parametrize(
    ("flag", "value", "word"),
    [
        ("--radius", "-1", "radius"),
        ("--radius", "0", "radius"),
        ("--radius", "abc", "radius"),
        ("--vstar", "nan", "vstar"),
        ("--kw", "-1", "kw"),
        ("--load", "inf", "load"),
        ("--vstar", "0.6", "critical"),  # supercritical at kw = 1
    ],
)
def test_bad_values_exit_2_with_one_line(flag: str, value: str, word: str) -> None:
    assert_one_line_error(run("solve", *replace(PAPER_CASE, flag, value)), word)


@pytest.mark.parametrize(
    "extra",
    [["--nu", "0.5"], ["--tol", "1"], ["--nu", "x"]],
)
def test_bad_optional_values(extra: list[str]) -> None:
    assert_one_line_error(run("solve", *PAPER_CASE, *extra), extra[0].lstrip("-"))


def test_missing_required_argument() -> None:
    assert_one_line_error(run("solve", "--vstar", "0.2", "--kw", "1"), "--radius")


def test_unknown_subcommand_and_option() -> None:
    assert_one_line_error(run("frobnicate"))
    assert_one_line_error(run("solve", *PAPER_CASE, "--bogus"), "--bogus")


def test_critical_bad_nu() -> None:
    assert_one_line_error(run("critical", "--kw", "1", "--nu", "0.5"), "nu")


def test_console_script() -> None:
    script = Path(sys.executable).with_name("movingpunch")
    if not script.exists():
        pytest.skip("console script not installed next to this interpreter")
    proc = subprocess.run(
        [str(script), "critical", "--kw", "1", "--json"],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["critical_vstar"] == pytest.approx(
        0.5716928, abs=1e-6
    )
