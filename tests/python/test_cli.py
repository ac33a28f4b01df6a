"""The command-line interface, run as a user would: in a subprocess (the
stress peaks are compared with the Python API in this process)."""

from __future__ import annotations

import dataclasses
import json
import re
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

import movingpunch as mp
from extras import need

PAPER_CASE = ["--vstar", "0.2", "--kw", "1", "--radius", "100", "--load", "0.002"]


def number_after(label: str, table: str) -> float:
    """The value in the row of ``table`` whose label is ``label``."""
    match = re.search(rf"^\s*{re.escape(label)}\s+(\S+)", table, re.MULTILINE)
    assert match, f"no row {label!r} in:\n{table}"
    return float(match.group(1))


def test_solve_prints_a_table(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("solve", *PAPER_CASE)
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


def test_solve_json(run_cli: Callable[..., subprocess.CompletedProcess[str]]) -> None:
    proc = run_cli("solve", *PAPER_CASE, "--json")
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


def test_solve_json_rigid_base_is_json_safe(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli(
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


STRESS_ROWS = {
    # table label: StressPeaks field
    "top, most compressive": "top_compressive",
    "top, most compressive x/h": "top_compressive_x",
    "top, most tensile": "top_tensile",
    "top, most tensile x/h": "top_tensile_x",
    "bottom, most tensile": "bottom_tensile",
    "bottom, most tensile x/h": "bottom_tensile_x",
    "centre, top (0, 0)": "centre_top",
    "centre, bottom (0, -h)": "centre_bottom",
}


def _peaks() -> dict[str, float]:
    # As in the CLI's fresh process: a kernel table cached by an earlier test
    # (another width) moves the error bound in its 3rd digit.
    mp.clear_kernel_cache()
    sol = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
    return dataclasses.asdict(sol.stress_peaks())


def test_solve_stress_table(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("solve", *PAPER_CASE, "--stress")
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    assert "Stress sigma_x/(P/h)" in out
    want = _peaks()
    for label, key in STRESS_ROWS.items():
        row = re.search(rf"^\s*{re.escape(label)}\s+(\S+)\s*$", out, re.MULTILINE)
        assert row, f"no row {label!r} in:\n{out}"
        # Printed with 10 significant digits.
        assert float(row.group(1)) == pytest.approx(want[key], rel=1e-9, abs=1e-12)
    # The paper's case: tension outside the contact and at the bottom,
    # compression under the punch.
    assert number_after("top, most tensile", out) > 0
    assert number_after("bottom, most tensile", out) > 0
    assert number_after("top, most compressive", out) < 0
    assert number_after("a/h", out) == pytest.approx(0.37288, abs=1e-5)


def test_solve_stress_json(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("solve", *PAPER_CASE, "--stress", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["a"] == pytest.approx(0.37288, abs=1e-5)
    stress = data["stress"]
    want = _peaks()
    assert set(stress) == set(want)
    for key, value in want.items():
        assert stress[key] == pytest.approx(value, rel=1e-12, abs=1e-14), key
    assert stress["top_tensile_x"] > data["a"]


def test_solve_without_stress_prints_no_stress(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("solve", *PAPER_CASE, "--json")
    assert proc.returncode == 0, proc.stderr
    assert "stress" not in json.loads(proc.stdout)
    table = run_cli("solve", *PAPER_CASE)
    assert "sigma_x" not in table.stdout


def test_solve_stress_rigid_base_json(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    rigid = replace(replace(PAPER_CASE, "--vstar", "0"), "--kw", "inf")
    proc = run_cli("solve", *rigid, "--stress", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["kw"] == "inf"
    assert data["stress"]["centre_top"] < 0


def test_critical(run_cli: Callable[..., subprocess.CompletedProcess[str]]) -> None:
    proc = run_cli("critical", "--kw", "1")
    assert proc.returncode == 0, proc.stderr
    vcr = number_after("V*_cr", proc.stdout)
    assert vcr == pytest.approx(0.5716928, abs=1e-6)
    assert "0.8299135" in proc.stdout  # Rayleigh, nu = 0.2


def test_critical_json_rigid_base(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("critical", "--kw", "inf", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["critical_wavenumber"] == "inf"
    assert data["critical_vstar"] == pytest.approx(0.8299135134, rel=1e-9)
    assert data["rayleigh_vstar"] == pytest.approx(0.8299135134, rel=1e-9)


def test_help_lists_the_commands(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("--help")
    assert proc.returncode == 0
    for command in ("solve", "critical", "tui", "serve"):
        assert command in proc.stdout


def test_no_subcommand_starts_the_terminal_ui(monkeypatch: pytest.MonkeyPatch) -> None:
    # In this process, with App.run replaced: the real terminal run is in
    # test_tui_tmux.py.
    from movingpunch import cli
    from movingpunch.tui import MovingPunchApp
    from movingpunch.tui.model import PAPER_FIG4

    started: list[MovingPunchApp] = []

    def fake_run(self: MovingPunchApp, *args: object, **kwargs: object) -> None:
        started.append(self)

    monkeypatch.setattr(MovingPunchApp, "run", fake_run)
    assert cli.main([]) == 0
    assert cli.main(["tui", "fig5"]) == 0
    assert len(started) == 2
    assert started[0].scene.params == PAPER_FIG4
    assert started[1].scene.overlay is not None
    assert started[1].scene.overlay.param == "kw"


def test_tui_bad_scene_is_one_line(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    assert_one_line_error(run_cli("tui", "no-such-scene"), "no-such-scene")
    need("serve")  # without textual-serve, serve says that first
    assert_one_line_error(run_cli("serve", "no-such-scene"), "no-such-scene")


def test_serve_without_textual_serve_is_one_line(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from movingpunch import cli

    monkeypatch.setitem(sys.modules, "textual_serve", None)
    monkeypatch.setitem(sys.modules, "textual_serve.server", None)
    with pytest.raises(SystemExit) as info:
        cli.main(["serve"])
    assert info.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("movingpunch: error: serve needs textual-serve")
    assert "movingpunch[serve]" in err
    assert len(err.splitlines()) == 1


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
def test_bad_values_exit_2_with_one_line(
    flag: str,
    value: str,
    word: str,
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    assert_one_line_error(run_cli("solve", *replace(PAPER_CASE, flag, value)), word)


@pytest.mark.parametrize(
    "extra",
    [["--nu", "0.5"], ["--tol", "1"], ["--nu", "x"]],
)
def test_bad_optional_values(
    extra: list[str],
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    assert_one_line_error(run_cli("solve", *PAPER_CASE, *extra), extra[0].lstrip("-"))


def test_missing_required_argument(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    assert_one_line_error(run_cli("solve", "--vstar", "0.2", "--kw", "1"), "--load")
    # --radius is the cylinder's (the default profile): required for it only.
    assert_one_line_error(
        run_cli("solve", "--vstar", "0.2", "--kw", "1", "--load", "0.002"), "--radius"
    )


def test_solve_takes_a_profile(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
    tmp_path: Any,
) -> None:
    base = ("solve", "--vstar", "0.2", "--kw", "1", "--load", "0.002")
    out = run_cli(*base, "--profile", "flat", "--half-width", "0.5", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["profile"] == {"kind": "flat", "half_width": 0.5}
    assert data["a"] == 0.5
    assert data["end_coefficients"][0] > 0.0
    # K's error bar: bounded by the tolerance's scale, shown beside K.
    assert 0.0 < data["end_coefficient_error"] <= 1e-6 * data["end_coefficients"][0]
    out = run_cli(*base, "--profile", "flat", "--half-width", "0.5")
    assert out.returncode == 0, out.stderr
    line = next(x for x in out.stdout.splitlines() if "end coefficient" in x)
    assert "±" in line
    out = run_cli(
        *base, "--profile", "rounded_flat", "--half-width", "0.2", "--radius", "100"
    )
    assert out.returncode == 0, out.stderr
    assert "rounded flat punch" in out.stdout
    table = tmp_path / "parabola.txt"
    table.write_text("# x y\n-2 0.02\n-1, 0.005\n0 0\n1 0.005\n2 0.02\n")
    out = run_cli(*base, "--profile", "table", "--table", str(table), "--json")
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["a"] == pytest.approx(0.37288077, rel=1e-6)
    assert_one_line_error(
        run_cli(*base, "--profile", "flat", "--half-width", "0.5", "--radius", "3"),
        "--radius",
    )
    assert_one_line_error(run_cli(*base, "--profile", "flat"), "--half-width")
    assert_one_line_error(run_cli(*base, "--profile", "flta"), "--profile")
    assert_one_line_error(
        run_cli(*base, "--profile", "flat", "--half-width", "nan"), "half_width"
    )
    # An asymmetric table solves (on the asymmetric solver); a non-convex one
    # is refused, naming profile.y.
    table.write_text("-2 4\n-1 1\n0 0\n1 1.5\n2 4\n")
    out = run_cli(*base, "--profile", "table", "--table", str(table))
    assert out.returncode == 0, out.stderr
    assert "asymmetric tabulated profile" in out.stdout
    table.write_text("-2 4\n-1 1\n0 0\n1 3\n2 4\n")
    assert_one_line_error(
        run_cli(*base, "--profile", "table", "--table", str(table)), "profile.y"
    )
    table.write_text("-2 4\nfoo bar\n")
    assert_one_line_error(
        run_cli(*base, "--profile", "table", "--table", str(table)), "line 2"
    )


def test_unknown_subcommand_and_option(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    assert_one_line_error(run_cli("frobnicate"))
    assert_one_line_error(run_cli("solve", *PAPER_CASE, "--bogus"), "--bogus")


def test_critical_bad_nu(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    assert_one_line_error(run_cli("critical", "--kw", "1", "--nu", "0.5"), "nu")


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


def test_abbreviated_options_are_refused(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    """``--n 8`` is not ``--nu 8`` (argparse's prefix matching is off): the
    solve must not run with nu = 8's error or, worse, another value."""
    proc = run_cli("solve", *PAPER_CASE, "--n", "8")
    assert proc.returncode == 2, proc
    assert "unrecognized arguments: --n 8" in proc.stderr


def test_solve_hints_when_the_result_leaves_small_strains(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    # P/(mu h) = 50 on R/h = 100: delta/h 2.4, a/h 21.6 (movingpunch.regime).
    heavy = [*PAPER_CASE[:-1], "50"]
    proc = run_cli("solve", *heavy)
    assert proc.returncode == 0, proc.stderr  # a hint never fails the command
    hints = [line for line in proc.stderr.splitlines() if line.startswith("hint: ")]
    assert len(hints) == 1, proc.stderr
    assert "δ/h 2.4 > 0.05" in hints[0]
    assert "a/h 21.6 > 5" in hints[0]
    assert "beyond small-strain linear theory" in hints[0]
    assert "hint" not in proc.stdout
    data = json.loads(run_cli("solve", *heavy, "--json").stdout)
    assert any(h.startswith("δ/h 2.4") for h in data["hints"])


def test_solve_paper_case_has_no_hint(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("solve", *PAPER_CASE, "--stress")
    assert proc.returncode == 0, proc.stderr
    assert "hint" not in proc.stderr
    data = json.loads(run_cli("solve", *PAPER_CASE, "--json").stdout)
    assert data["hints"] == []


# -- the medium options (issue 26) ---------------------------------------------

TABLE1_CASE = ["--vstar", "0", "--radius", "100", "--load", "0.002"]


def test_solve_on_one_layer_given_by_layer_is_the_paper_layer(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    """--layer 1,1,0.2 on --kw 1 is the paper's layer: Table 1's a/h
    (docs/theory.md §11), and the medium shown in the table."""
    proc = run_cli("solve", *TABLE1_CASE, "--kw", "1", "--layer", "1,1,0.2")
    assert proc.returncode == 0, proc.stderr
    assert number_after("a/h", proc.stdout) == pytest.approx(0.330419, abs=1e-6)
    assert re.search(
        r"medium\s+layer h_i/h = 1, mu 1, nu 0.2, rho 1 on kw = 1", proc.stdout
    )
    crit = run_cli("critical", "--kw", "1", "--layer", "1,1,0.2")
    assert crit.returncode == 0, crit.stderr
    assert number_after("V*_cr", crit.stdout) == pytest.approx(0.5716928, abs=1e-6)
    data = json.loads(
        run_cli(
            "solve", *TABLE1_CASE, "--kw", "1", "--layer", "1,1,0.2", "--json"
        ).stdout
    )
    assert data["a"] == pytest.approx(0.330419, abs=1e-6)
    (layer,) = data["medium"]["layers"]
    expected = {"kind": "layer", "thickness": 1.0, "mu": 1.0, "nu": 0.2, "rho": 1.0}
    assert expected.items() <= layer.items()  # (and any field added, at its default)


def test_help_documents_the_medium_options(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    for command in ("solve", "critical"):
        out = run_cli(command, "--help").stdout
        for text in (
            "--layer T,MU,NU[,RHO",  # (and any field added to the table)
            "--graded T,GAMMA_H,NU[,MU,RHO",
            "--half-space MU,NU[,RHO",
        ):
            assert text in out, (command, text)


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (["--kw", "1", "--layer", "1,1"], ["--layer", "T,MU,NU[,RHO", "'1,1'"]),
        (["--kw", "1", "--layer", "1,a,0.2"], ["--layer", "T,MU,NU[,RHO"]),
        (["--kw", "1", "--layer", "1,1,0.7"], ["--layer 1,1,0.7", "nu", "0.5"]),
        (["--kw", "1", "--graded", "1,1,0.2,2"], ["--graded", "MU and RHO together"]),
        (["--half-space", "0.1"], ["--half-space", "MU,NU[,RHO", "bonded|smooth]"]),
        (["--half-space", "0.1,0.3,glued"], ["--half-space", "bonded|smooth"]),
        (["--kw", "1", "--half-space", "0.1,0.3"], ["--kw", "--half-space"]),
        (["--kp", "1", "--half-space", "0.1,0.3"], ["--kp", "--half-space"]),
        (["--kw", "1", "--nu", "0.3", "--layer", "1,1,0.3"], ["--nu", "--layer"]),
        (["--layer", "1,1,0.3"], ["--kw", "--half-space"]),
        (
            ["--kw", "1", "--layer", "0.5,1,0.3", "--layer", "0.4,1,0.3"],
            ["--layer/--graded", "sum to 1"],
        ),
        (["--kw", "1", "--layer", "1,2,0.3"], ["--layer/--graded", "1 by definition"]),
        (["--nu", "0.2"], ["--kw"]),
    ],
)
def test_medium_options_errors_name_the_option(
    extra: list[str],
    words: list[str],
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    assert_one_line_error(run_cli("solve", *TABLE1_CASE, *extra), *words)


def test_a_train_on_a_stack_and_under_a_half_space(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    """--punch beside --layer runs the train on the stack: two identical
    sublayers give the homogeneous layer's train (the anchor); under a
    half-space the train is the API's (measured from the surface at
    x = 100 h)."""
    train = ["--punch", "0.002@-2", "--punch", "0.002@2", "--json"]
    head = ["solve", "--vstar", "0", "--radius", "100"]
    stack = run_cli(*head, "--kw", "1", "--layer", "0.4,1,0.2",
                    "--layer", "0.6,1,0.2", *train)  # fmt: skip
    plain = run_cli(*head, "--kw", "1", "--nu", "0.2", *train)
    assert stack.returncode == 0, stack.stderr
    assert plain.returncode == 0, plain.stderr
    got, want = json.loads(stack.stdout), json.loads(plain.stdout)
    assert len(got["medium"]["layers"]) == 2
    for key in ("a", "indentation"):
        assert got[key] == pytest.approx(want[key], rel=1e-8), key
    proc = run_cli(*head, "--layer", "1,1,0.2", "--half-space", "0.5,0.3", *train)
    assert proc.returncode == 0, proc.stderr
    api = mp.solve_punches(
        [mp.Punch(100.0, 0.002, at=-2.0), mp.Punch(100.0, 0.002, at=2.0)],
        vstar=0.0,
        layers=[mp.Layer(1.0, mu=1.0, nu=0.2)],
        base=mp.HalfSpace(0.5, 0.3),
    )
    got = json.loads(proc.stdout)
    assert got["indentation"] == pytest.approx(api.indentation, rel=1e-12)
    assert got["a"] == pytest.approx(api.a, rel=1e-12)


def test_solve_on_identical_stack_sublayers_is_the_paper_layer(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    """Two identical bonded sublayers (one --layer, one --graded of gamma h
    = 0), in command-line order: the homogeneous layer (Table 1). Needs the
    stack medium of the core."""
    proc = run_cli(
        "solve", *TABLE1_CASE, "--kw", "1",
        "--layer", "0.4,1,0.2", "--graded", "0.6,0,0.2,1,1",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert number_after("a/h", proc.stdout) == pytest.approx(0.330419, abs=1e-6)
    assert "layer h_i/h = 0.4" in proc.stdout
    assert proc.stdout.index("h_i/h = 0.4") < proc.stdout.index("h_i/h = 0.6")


def test_solve_on_a_half_space_stack_shows_no_springs(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    """Needs the half-space medium of the core."""
    proc = run_cli(
        "solve", *TABLE1_CASE, "--layer", "1,1,0.2", "--half-space", "0.1,0.3,smooth"
    )
    assert proc.returncode == 0, proc.stderr
    assert "smooth half-space (mu 0.1, nu 0.3, rho 1)" in proc.stdout
    assert re.search(r"k_w h/μ\s+- \(half-space\)", proc.stdout)
    crit = run_cli("critical", "--half-space", "0.1,0.3", "--json")
    assert crit.returncode == 0, crit.stderr
    data = json.loads(crit.stdout)
    assert data["kw"] is None
    assert data["medium"]["base"]["kind"] == "half_space"
