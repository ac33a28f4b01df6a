"""``movingpunch run / scenes / scene show``, run as a user would (in a
subprocess)."""

from __future__ import annotations

import json
import math
import re
import subprocess
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.scene import Scene, read_csv, read_json

# docs/theory.md §11: a/h at R/h = 100, P/(mu h) = 0.002, nu = 0.2.
TABLE1 = {
    "0.1": (0.372478, 0.3729),
    "1": (0.330419, 0.3306),
    "10": (0.315037, 0.3152),
    "inf": (0.311557, 0.3117),
}

VALID = "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"


def test_run_table1_prints_both_columns(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("run", "table1", "--jobs", "1")
    assert proc.returncode == 0, proc.stderr
    header = next(line for line in proc.stdout.splitlines() if "a/h (vstar=0)" in line)
    assert "a/h (vstar=0.001)" in header
    # Columns: kw, then a/h and p0/(P/h) for vstar = 0, then for vstar = 1e-3.
    for kw, (static, paper) in TABLE1.items():
        match = re.search(rf"^\s+{re.escape(kw)}\s+(.*)$", proc.stdout, re.MULTILINE)
        assert match, proc.stdout
        numbers = [float(v) for v in match.group(1).split()]
        assert numbers[0] == pytest.approx(static, abs=1e-6)
        assert numbers[2] == pytest.approx(paper, abs=6e-5)
    assert "Stages" in proc.stdout
    assert proc.stderr == ""


def test_run_writes_csv_and_json_that_load_back(
    tmp_path: Path, run_cli: Callable[..., subprocess.CompletedProcess[str]]
) -> None:
    proc = run_cli("run", "fig6", "--out", str(tmp_path), "--no-plot")
    assert proc.returncode == 0, proc.stderr
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted(
        f"fig6-{k}.csv"
        for k in ("contact_width", "pressure", "surface_stress", "depth_stress")
    )
    meta, cols = read_csv(tmp_path / "fig6-contact_width.csv")
    assert meta["scene"] == Scene.bundled("fig6")
    assert meta["movingpunch_version"] == mp.__version__
    s = mp.solve(vstar=0.2, kw=1.0, radius=10.0, load=0.002)
    assert cols["radius"][0] == 10.0
    assert cols["a"][0] == pytest.approx(s.a, rel=1e-8)
    assert np.loadtxt(tmp_path / "fig6-depth_stress.csv", delimiter=",").shape == (
        101,
        5,
    )

    proc = run_cli(
        "run", "table1", "--format", "json", "--out", ".", "--jobs", "2", cwd=tmp_path
    )
    assert proc.returncode == 0, proc.stderr
    # 8 points: too few to pay for a worker, and it says so.
    assert "--jobs 2: the sweep ran in this process" in proc.stderr
    meta, cols = read_json(tmp_path / "table1-sweep.json")
    assert meta["scene"] == Scene.bundled("table1")
    assert cols["kw"][-1] == math.inf
    assert cols["a[vstar=0]"] == pytest.approx(
        [v[0] for v in TABLE1.values()], abs=1e-6
    )


def test_run_plots_in_ascii(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("run", "fig2", "--plot", "--jobs", "1")
    assert proc.returncode == 0, proc.stderr
    assert "contact half-width a/h against R/h" in proc.stdout
    assert "vstar=0.5" in proc.stdout
    assert "\x1b[" not in proc.stdout  # no colour codes into a pipe
    assert "┤" in proc.stdout


@pytest.mark.needs("png")
def test_png_writes_real_figures(
    tmp_path: Path, run_cli: Callable[..., subprocess.CompletedProcess[str]]
) -> None:
    proc = run_cli("run", "fig4", "--png", "--no-plot", "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    pngs = sorted(tmp_path.glob("*.png"))
    assert pngs, proc.stdout
    for png in pngs:
        data = png.read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n", png
        width = int.from_bytes(data[16:20], "big")
        height = int.from_bytes(data[20:24], "big")
        assert width >= 300, (png, width)
        assert height >= 200, (png, height)
        assert str(png.name) in proc.stdout
    # No temporary or half-written files are left beside them.
    assert {p.suffix for p in tmp_path.iterdir()} <= {".png", ".csv"}


def test_png_without_matplotlib_is_a_one_line_error(
    tmp_path: Path, run_python: Callable[..., subprocess.CompletedProcess[str]]
) -> None:
    code = (
        "import sys; sys.modules['matplotlib'] = None; "
        "from movingpunch.cli import main; raise SystemExit(main(sys.argv[1:]))"
    )
    proc = run_python(
        code, "run", "table1", "--png", "--out", str(tmp_path), timeout=300
    )
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    assert proc.stderr.strip().splitlines() == [
        "movingpunch: error: --png needs matplotlib: pip install 'movingpunch[png]'"
    ]


def test_scenes_lists_the_bundled_scenes(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("scenes")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    names = [line.split()[0] for line in lines]
    assert names[:6] == ["table1", "fig2", "fig3", "fig4", "fig5", "fig6"]
    assert "near-critical" in names
    assert all(len(line.split(maxsplit=1)) == 2 for line in lines)


def test_scene_show_prints_loadable_toml(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("scene", "show", "fig3")
    assert proc.returncode == 0, proc.stderr
    assert Scene.from_toml(proc.stdout) == Scene.bundled("fig3")
    assert proc.stdout.startswith('name = "fig3"')


MALFORMED = {
    "unknown key": (
        VALID + "colour = 3\n[outputs]\ncontact_width = true\n",
        "params.colour",
    ),
    "wrong type": (
        VALID + "[outputs]\npressure = { points = 'many' }\n",
        "outputs.pressure.points",
    ),
    "missing parameter": (
        "[params]\nvstar = 0.2\nradius = 100\nload = 0.002\n"
        "[outputs]\ncontact_width = true\n",
        "params.kw",
    ),
    "vstar above critical": (
        VALID.replace("0.2", "0.58") + "[outputs]\ncontact_width = true\n",
        "params.vstar",
    ),
    "non-TOML bytes": (b"\x00\x01\xff\xfe garbage [[[", "(file)"),
    "empty file": ("", "params"),
}


@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_malformed_scene_is_a_one_line_error(
    case: str,
    tmp_path: Path,
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    content, key = MALFORMED[case]
    path = tmp_path / "scene.toml"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    proc = run_cli("run", str(path))
    assert_one_line_error(proc, str(path), f": {key}: ")
    assert list(tmp_path.iterdir()) == [path]


def test_unknown_scene_name(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    proc = run_cli("run", "fig7")
    assert_one_line_error(proc, "fig7", "table1", "near-critical")


@pytest.mark.parametrize("jobs", ["0", "-2", "two"])
def test_bad_jobs(
    jobs: str,
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    assert_one_line_error(run_cli("run", "table1", "--jobs", jobs), "--jobs")


def test_run_piped_prints_the_numbers(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    # `movingpunch run fig4 | cat`: no plots, the computed numbers as plain
    # text tables (each output's columns, to 10 significant digits).
    proc = run_cli("run", "fig4", "--jobs", "1")
    assert proc.returncode == 0, proc.stderr
    assert "⣀" not in proc.stdout  # no braille plot
    lines = proc.stdout.splitlines()
    start = lines.index("Output pressure: Contact pressure")
    header = lines[start + 1].split()
    direct = Scene.bundled("fig4").run(jobs=1).outputs["pressure"].columns
    assert header == list(direct)
    rows = []
    for line in lines[start + 2 :]:
        if not line.strip():
            break
        rows.append([float(v) for v in line.split()])
    table = np.array(rows)
    assert table.shape == (len(direct["x"]), len(direct))
    for j, name in enumerate(direct):
        np.testing.assert_allclose(table[:, j], direct[name], rtol=1e-9, atol=1e-12)
    for output in ("contact_width", "surface_stress", "depth_stress"):
        assert any(line.startswith(f"Output {output}:") for line in lines), output


def test_run_format_json_without_out_prints_one_document(
    tmp_path: Path, run_cli: Callable[..., subprocess.CompletedProcess[str]]
) -> None:
    # stdout is the JSON document and nothing else; no file is written.
    proc = run_cli("run", "fig4", "--format", "json", "--jobs", "1", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert list(tmp_path.iterdir()) == []
    doc = json.loads(proc.stdout)
    assert doc["scene_name"] == "fig4"
    assert doc["movingpunch_version"] == mp.__version__
    assert Scene.from_toml(doc["scene"]) == Scene.bundled("fig4")
    assert doc["params"]["radius"] == 100.0
    direct = Scene.bundled("fig4").run(jobs=1)
    assert list(doc["outputs"]) == list(direct.outputs)
    for name, data in direct.outputs.items():
        got = doc["outputs"][name]
        assert got["title"] == data.title
        assert list(got["columns"]) == list(data.columns)
        for col, values in data.columns.items():
            np.testing.assert_allclose(
                np.asarray(got["columns"][col], dtype=float),
                values,
                rtol=1e-9,
                atol=1e-12,
                err_msg=f"{name}.{col}",
            )
    # The summary's values: a/h, p0, δ/h of each curve.
    width = doc["outputs"]["contact_width"]["columns"]
    s = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
    assert width["a"][width["vstar"].index(0.2)] == pytest.approx(s.a, rel=1e-9)
    assert [st["name"] for st in doc["stages"]] == [st.name for st in direct.stages]


def test_run_format_json_is_the_files_serialisation(
    tmp_path: Path, run_cli: Callable[..., subprocess.CompletedProcess[str]]
) -> None:
    # table1 has kw = inf: non-finite numbers are written as in the JSON
    # files ("inf"), so that the document is valid JSON (no Infinity).
    proc = run_cli("run", "table1", "--format", "json", "--jobs", "1")
    assert proc.returncode == 0, proc.stderr
    assert "Infinity" not in proc.stdout
    assert "NaN" not in proc.stdout
    doc = json.loads(proc.stdout)
    files = run_cli(
        "run", "table1", "--format", "json", "--out", str(tmp_path), "--jobs", "1"
    )
    assert files.returncode == 0, files.stderr
    for name, data in doc["outputs"].items():
        on_disk = json.loads((tmp_path / f"table1-{name}.json").read_text())
        assert data["title"] == on_disk["title"]
        assert data["columns"] == on_disk["columns"]
    assert doc["outputs"]["sweep"]["columns"]["kw"][-1] == "inf"


def test_run_format_json_refuses_plot(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    proc = run_cli("run", "fig4", "--format", "json", "--plot")
    assert_one_line_error(proc, "--plot", "--format json", "--out")


def test_progress_only_when_stderr_is_a_terminal(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    run_on_a_terminal: Callable[..., tuple[int, str, str]],
) -> None:
    # table1's sweep reports progress; piped, stderr stays empty.
    piped = run_cli("run", "table1", "--jobs", "1", "--no-plot")
    assert piped.returncode == 0, piped.stderr
    assert piped.stderr == ""
    # On a terminal the same run draws its bar there (never on stdout).
    status, out, terminal = run_on_a_terminal("run", "table1", "--jobs", "1")
    assert status == 0, terminal
    assert "\r[" in terminal, terminal
    assert "] 8/8" in terminal, terminal
    assert "\r" not in out
    assert "[#" not in out


VALID_LOAD_50 = VALID.replace("load = 0.002", "load = 50")


@pytest.mark.parametrize(("params", "hint"), [(VALID, False), (VALID_LOAD_50, True)])
def test_run_prints_plausibility_hints(
    params: str,
    hint: bool,
    tmp_path: Path,
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    path = tmp_path / "scene.toml"
    path.write_text(params + "[outputs]\ncontact_width = true\n", encoding="utf-8")
    proc = run_cli("run", str(path), "--no-plot")
    assert proc.returncode == 0, proc.stderr
    lines = [line for line in proc.stdout.splitlines() if line.startswith("hint: ")]
    if hint:
        assert len(lines) == 1, proc.stdout
        assert "δ/h 2.4 > 0.05" in lines[0]
        assert "a/h 21.6 > 5" in lines[0]
    else:
        assert lines == [], proc.stdout
    doc = json.loads(run_cli("run", str(path), "--format", "json").stdout)
    assert bool(doc["hints"]) is hint


# --- ASCII plots: legends and labels outside the data -------------------------


def _plots(name: str, width: int = 80) -> list[list[str]]:
    from movingpunch.scene import ascii_plots

    text = ascii_plots(Scene.bundled(name).run(jobs=1), width=width)
    blocks: list[list[str]] = [[]]
    for line in text.splitlines():
        if line == "":
            blocks.append([])
        else:
            blocks[-1].append(line)
    return [b for b in blocks if b]


@pytest.mark.parametrize(
    ("name", "width"),
    [("fig4", 80), ("pasternak", 80), ("two-axle", 80), ("fig5", 60)],
)
def test_ascii_plots_keep_legends_and_labels_outside(name: str, width: int) -> None:
    scene = Scene.bundled(name)
    labels = {
        c.label
        for data in scene.run(jobs=1).outputs.values()
        for c in data.curves
        if c.label
    }
    blocks = _plots(name, width)
    assert blocks
    for block in blocks:
        top = next(i for i, line in enumerate(block) if "┌" in line)
        bottom = next(i for i, line in enumerate(block) if "└" in line)
        inside = block[top : bottom + 1]
        below = block[bottom + 1 :]
        # (d) nothing wider than asked.
        assert all(len(line) <= width for line in block), block
        # (c) both axes with their units, under the frame.
        axes = next(line for line in below if "x axis:" in line)
        assert "y axis:" in " ".join(below), block
        assert re.search(r"x axis: \S+", axes)
        # (a) no legend or label text in the frame.
        for line in inside:
            assert "axis" not in line, block
            assert "legend" not in line, block
            for label in labels:
                assert label not in line, (label, block)
        legend = [line for line in below if line.lstrip().startswith("legend:")]
        if scene.vary is not None:
            # (b) a legend after the frame: one distinct marker per series,
            # each drawn in the frame.
            assert legend, block
            entries = re.findall(r"(\S) (\S+=\S+)", " ".join(below))
            markers = [m for m, _ in entries]
            assert len(markers) == len(scene.vary.values) == len(set(markers))
            if name != "pasternak":  # there V*_cr's curves coincide
                for marker in markers:
                    assert any(marker in line for line in inside[1:-1]), marker
        else:
            assert legend == [], block


def test_ascii_plots_state_units() -> None:
    text = "\n".join(line for b in _plots("fig4") for line in b)
    assert "x axis: x/h   y axis: p/(P/h)" in text
    assert "x axis: x/h   y axis: sigma_x(x, 0)/(P/h)" in text
    assert "x axis: y/h   y axis: sigma_x(0, y)/(P/h)" in text
    text = "\n".join(line for b in _plots("pasternak") for line in b)
    assert "x axis: k_p/(μh)   y axis: a/h" in text


def test_run_help_documents_json_and_dask_timeout(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("run", "--help")
    assert proc.returncode == 0, proc.stderr
    text = " ".join(proc.stdout.split())
    assert "--format json without --out prints the whole result as one JSON" in text
    assert "--dask-timeout SECONDS" in text
    assert "0 < SECONDS <= 3600" in text
