"""Numbers shown as what they are (movingpunch._display) and plots where
curves never hide each other (movingpunch._textplot), in the CLI and a
scene's outputs.

Anchors: mirror symmetry (two equal punches at ±d/2, a punch at rest on a
damped foundation) makes the drag exactly 0 and puts the most compressive
surface stress on the axis, x = 0; the computed values are round-off
(1e-19, 1e-16) that the user must read as 0. Data files keep them raw.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from typing import ClassVar

import numpy as np
import pytest

import movingpunch as mp
from movingpunch._display import ROUND_OFF, drag_scale, shown, singular_note
from movingpunch._textplot import MARKERS, allocate, plain
from movingpunch.scene import Scene, ascii_plots, format_summary, load_scene
from movingpunch.scene._export import render_outputs
from movingpunch.scene._result import Curve, SweepTable

CLI = [sys.executable, "-m", "movingpunch"]
TRAIN = ["--punch", "0.002@-0.5", "--punch", "0.002@0.5", "--radius", "100"]


def run_cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*CLI, *args], capture_output=True, text=True, timeout=120, check=False
    )


def row(text: str, label: str) -> str:
    """The value of the table row ``label`` in the CLI's output."""
    for line in text.splitlines():
        if line.strip().startswith(label):
            return line.strip()[len(label) :].strip()
    raise AssertionError(f"no row {label!r} in\n{text}")


# --- the rule ------------------------------------------------------------------


def test_the_rule() -> None:
    assert shown(-2.1e-19, scale=1e-2) == 0.0
    assert str(shown(-2.1e-19, scale=1e-2)) == "0.0"  # never "-0.0"
    assert shown(2e-12, scale=1.0) == 2e-12  # above 1e-12 of its scale: a value
    assert shown(5e-13, scale=1.0) == 0.0
    assert shown(9e-13 * 2.0, scale=2.0) == 0.0
    assert shown(3e-12, estimate=5e-12) == 0.0  # below its error estimate
    assert shown(6e-12, estimate=5e-12) == 6e-12
    assert shown(0.25, estimate=0.0) == 0.25
    assert shown(float("inf"), scale=1.0) == float("inf")
    assert ROUND_OFF == 1e-12
    assert drag_scale((-0.37, 0.37), 100.0) == pytest.approx(3.7e-3)
    assert drag_scale((-0.5, 0.5), float("inf")) == 1.0
    assert singular_note([-0.5, 0.5]) == "masked: singular at x/h = ±0.5"


def test_a_mirror_image_trains_drag_prints_as_0_and_json_keeps_it_raw() -> None:
    # From an empty kernel cache, as the CLI child's: the raw drag is
    # round-off, and a table this worker's earlier tests left moves it.
    mp.clear_kernel_cache()
    s = mp.solve_punches(
        [mp.Punch(100.0, 0.002, at=-0.5), mp.Punch(100.0, 0.002, at=0.5)],
        vstar=0.2,
        kw=1.0,
    )
    # Each punch drags; by symmetry the two cancel exactly.
    assert s.punches[0].drag == pytest.approx(-s.punches[1].drag, rel=1e-12)
    assert abs(s.drag) < 1e-15
    proc = run_cli("solve", *TRAIN, "--vstar", "0.2", "--kw", "1")
    assert proc.returncode == 0, proc.stderr
    assert row(proc.stdout, "drag (∫p x/R dx)/P") == "0"
    assert row(proc.stdout, "dissipation/(P V)") == "0"
    # The punches' own drags are values: printed as they are.
    assert f"drag/P = {s.punches[1].drag:.10g}" in proc.stdout
    data = json.loads(
        run_cli("solve", *TRAIN, "--vstar", "0.2", "--kw", "1", "--json").stdout
    )
    assert data["drag"] == s.drag  # the data keep the raw number


def test_a_peak_on_the_axis_prints_at_0() -> None:
    # At rest on a damped foundation the contact is symmetric: the most
    # compressive surface stress is under the centre, x = 0.
    s = mp.solve(vstar=0.0, kw=1.0, radius=100.0, load=0.002, damping=0.1)
    peaks = s.stress_peaks()
    assert abs(peaks.top_compressive_x) < 1e-12
    proc = run_cli(
        "solve", "--vstar", "0", "--kw", "1", "--radius", "100", "--load", "0.002",
        "--damping", "0.1", "--stress",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert row(proc.stdout, "top, most compressive x/h") == "0"
    assert row(proc.stdout, "drag (∫p x/R dx)/P") == "0"
    assert row(proc.stdout, "top, most tensile x/h") == f"{peaks.top_tensile_x:.10g}"


def test_a_damped_drag_is_shown_as_it_is() -> None:
    s = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, damping=0.1)
    proc = run_cli(
        "solve", "--vstar", "0.2", "--kw", "1", "--radius", "100", "--load", "0.002",
        "--damping", "0.1",
    )  # fmt: skip
    assert row(proc.stdout, "drag (∫p x/R dx)/P") == f"{s.drag:.10g}"
    assert s.drag > 1e-5


def test_a_scene_summary_shows_round_off_as_0_and_its_files_keep_it() -> None:
    result = load_scene("separated").run()
    drag = float(result.outputs["contact_width"].columns["drag"][0])
    assert abs(drag) < 1e-15  # a symmetric contact: 0 up to round-off
    text = format_summary(result)
    header, values = text.split("Contact\n")[1].splitlines()[:2]
    at = header.index("drag/P")
    assert values[at:].split()[0] == "0", text
    files = dict(render_outputs(result, "csv"))
    csv = files["separated-contact_width.csv"].decode()
    assert repr(drag) in csv


# --- a flat punch's stress field in a scene ------------------------------------

FLAT_FIELD = """
name = "flat-field"
[params]
vstar = 0.2
kw = 1.0
load = 0.002
[params.profile]
kind = "flat"
half_width = 0.5
[outputs]
stress_field = { x = [-2.0, 2.0], y = [-1.0, 0.0], points = 81, depth_points = 11, component = "von_mises" }
"""  # noqa: E501


def test_a_flat_punchs_stress_field_output_has_no_nan() -> None:
    result = Scene.from_toml(FLAT_FIELD, "test").run()  # no RuntimeWarning
    ((_, f),) = result.outputs["stress_field"].fields
    assert {-0.5, 0.5} <= set(f.x.tolist())
    for name in ("sigma_x", "sigma_y", "von_mises", "max_shear", "sigma_z"):
        values = getattr(f, name)
        assert not np.isnan(values).any(), name
        assert (~np.isfinite(values)).sum() == 2, name  # the two edges
    files = dict(render_outputs(result, "csv"))
    (csv,) = (v.decode() for k, v in files.items() if "stress_field" in k)
    assert "nan" not in csv
    assert "inf" in csv


def test_a_flat_punchs_png_map_masks_and_names_the_singular_edges() -> None:
    pytest.importorskip("matplotlib", reason="the png extra is not installed")
    from movingpunch.scene._export import field_figure, pyplot

    result = Scene.from_toml(FLAT_FIELD, "test").run()
    plt = pyplot()
    fig = field_figure(plt, result.outputs["stress_field"], "von_mises")
    try:
        (ax,) = [a for a in fig.axes if a.get_legend() is not None]
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert labels == ["masked: singular at x/h = ±0.5"]
        mesh = ax.collections[0]
        assert np.isfinite(mesh.norm.vmin)
        assert np.isfinite(mesh.norm.vmax)
    finally:
        plt.close(fig)


# --- ASCII plots: no curve hides another --------------------------------------


def _canvas(block: str) -> str:
    rows = []
    for line in block.splitlines():
        m = re.search(r"[│┤](.*)│$", line)
        if m:
            rows.append(m.group(1))
    return "\n".join(rows)


def _result_of(curves: list[Curve]) -> object:
    """A stand-in SceneResult holding one sweep of ``curves`` (ascii_plots
    reads ``outputs``, ``sweep`` and ``scene.sweep``)."""
    x = curves[0].x
    sweep = SweepTable(
        param="load",
        values=x,
        quantities=("a",),
        labels=tuple(c.label for c in curves),
        vary_param="kw",
        vary_values=tuple(float(k) for k in range(len(curves))),
        data={"a": np.stack([c.y for c in curves])},
        valid=np.ones((len(curves), len(x)), dtype=bool),
    )

    class _Scene:
        sweep = None

    class _Result:
        outputs: ClassVar[dict[str, object]] = {}
        scene = _Scene()

    r = _Result()
    r.sweep = sweep  # type: ignore[attr-defined]
    return r


@pytest.mark.parametrize("count", [2, 3, 4, 5])
@pytest.mark.parametrize("color", [False, True])
def test_every_overlaid_curve_keeps_its_marker(count: int, color: bool) -> None:
    # Curves that cross, and two that coincide (drawn last, the second
    # would cover the first entirely).
    x = np.linspace(1.0, 2.0, 20)
    curves = [Curve("kw=0.1", 0.1, x, 0.3 * x)]
    for k in range(1, count):
        curves.append(Curve(f"kw={10**k}", float(k), x, 0.6 - 0.1 * k * (x - 1.5)))
    if count >= 3:
        curves[-1] = Curve(curves[-1].label, 0.0, x, curves[-2].y * (1 + 1e-4))
    text = ascii_plots(_result_of(curves), color=color)  # type: ignore[arg-type]
    shown_text = plain(text)
    canvas = _canvas(shown_text)
    legend = [line for line in shown_text.splitlines() if "legend:" in line]
    assert legend, text
    for k, c in enumerate(curves):
        assert MARKERS[k] in canvas, (c.label, shown_text)
        assert f"{MARKERS[k]} {c.label}" in shown_text.split("legend:")[1]
    assert all(len(line) <= 80 for line in shown_text.splitlines())


def test_fig3_shows_every_foundation(tmp_path: object) -> None:
    proc = run_cli("run", "fig3", "--plot")
    assert proc.returncode == 0, proc.stderr
    blocks = proc.stdout.split("contact half-width a/h against")[1]
    block = blocks.split("legend:")[0]
    canvas = _canvas(block)
    for k in range(4):  # kw = 0.1, 1, 10, inf
        assert MARKERS[k] in canvas, block
    assert "legend: • kw=0.1   + kw=1   x kw=10   o kw=inf" in proc.stdout


def test_allocate_shares_a_cell_fairly() -> None:
    # Two series on the same cells alternate; a third with one shared cell
    # keeps it.
    a = {(0, j) for j in range(6)}
    shown_cells = allocate([a, set(a), {(0, 3)}])
    owners = [shown_cells[(0, j)] for j in range(6)]
    assert set(owners) == {0, 1, 2}
    assert owners.count(0) >= 2
    assert owners.count(1) >= 2


TRAIN_SWEEP = """
name = "mirror-train"
[params]
vstar = 0.2
kw = 1.0
[[punches]]
radius = 100.0
load = 0.002
at = -0.5
[[punches]]
radius = 100.0
load = 0.002
at = 0.5
[sweep]
param = "spacing"
start = 1.0
stop = 3.0
points = 3
quantities = ["a", "drag"]
"""


def test_a_sweeps_round_off_drag_is_shown_as_0() -> None:
    # Two equal punches at ±d/2: the drags of the two cancel by symmetry.
    result = Scene.from_toml(TRAIN_SWEEP, "test").run()
    sweep = result.sweep
    assert sweep is not None
    raw = sweep.data["drag"][0]
    assert np.all(np.abs(raw) < 1e-15)
    text = format_summary(result)
    table = text.split("Sweep over")[1].split("\n\n")[0].splitlines()
    header = table[1]
    at = header.index("drag/P")
    values = [line[at:].split()[0] for line in table[2:5]]
    assert values == ["0", "0", "0"], text
    # The files keep the raw sums.
    files = dict(render_outputs(result, "csv"))
    csv = files["mirror-train-sweep.csv"].decode()
    assert all(repr(float(v)) in csv for v in raw)
