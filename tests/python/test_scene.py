"""Scenes through the Python API: the format, its validation, what a run
computes (and what it does not), sweeps reusing work, exports.

Physical numbers are checked against the anchors of docs/theory.md §11 (Table 1, the
critical speeds); the rest are structural or invariance checks."""

from __future__ import annotations

import dataclasses
import json
import math
import os
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.scene import (
    OutputSpec,
    Scene,
    SceneError,
    Sweep,
    Vary,
    bundled_scene_text,
    bundled_scenes,
    read_csv,
    read_json,
    write_outputs,
)

BASE = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2}

# docs/theory.md §11: a/h at R/h = 100, P/(mu h) = 0.002, nu = 0.2.
TABLE1_STATIC = {0.1: 0.372478, 1.0: 0.330419, 10.0: 0.315037, math.inf: 0.311557}
TABLE1_PAPER = {0.1: 0.3729, 1.0: 0.3306, 10.0: 0.3152, math.inf: 0.3117}
# docs/theory.md §8: V*_cr at nu = 0.2.
CRITICAL = {0.01: 0.0869126, 0.1: 0.2475216, 1.0: 0.5716928, 10.0: 0.8185946}
RAYLEIGH = 0.8299135

STRESS_STAGES = ("surface_stress", "depth_stress", "stress_field", "stress_peaks")


# -- bundled scenes and the file format ----------------------------------------


def test_bundled_scenes_cover_the_paper() -> None:
    scenes = bundled_scenes()
    for name in ("table1", "fig2", "fig3", "fig4", "fig5", "fig6", "near-critical"):
        assert name in scenes
        assert scenes[name]
        assert "\n" not in scenes[name]
    assert Scene.bundled("fig3").params["vstar"] == 0.2
    assert Scene.bundled("fig3").vary == Vary("kw", (0.1, 1.0, 10.0, math.inf))


@pytest.mark.parametrize("name", sorted(bundled_scenes()))
def test_round_trip_of_every_bundled_scene(name: str, tmp_path: Path) -> None:
    scene = Scene.bundled(name)
    assert scene.name == name
    assert Scene.from_toml(scene.to_toml()) == scene
    path = tmp_path / f"{name}.toml"
    scene.save(path)
    assert Scene.load(path) == scene
    assert list(tmp_path.iterdir()) == [path]  # no temporary file left
    text = bundled_scene_text(name)
    assert text is not None
    assert Scene.from_toml(text) == scene


def test_scene_built_in_python_round_trips(tmp_path: Path) -> None:
    scene = Scene(
        params={**BASE, "kw": math.inf},
        outputs={
            "pressure": OutputSpec("pressure", x=(-0.5, 0.5), points=11),
            "stress_field": OutputSpec(
                "stress_field",
                y=(-1.0, -0.5),
                points=5,
                depth_points=3,
                component="tau_xy",
            ),
            "displacement": OutputSpec("displacement", depth=-0.25),
        },
        vary=Vary("vstar", (0.0, 0.1)),
        sweep=Sweep.range("load", 1e-3, 4e-3, 7, spacing="log", quantities=["a"]),
        tol=1e-9,
        name="mine",
        description='a test scene with "quotes" and unicode μ',
    )
    assert scene.sweep is not None
    assert len(scene.sweep.values) == 7
    assert scene.sweep.values[0] == pytest.approx(1e-3)
    assert scene.sweep.values[-1] == pytest.approx(4e-3)
    assert "kw = inf" in scene.to_toml()
    path = tmp_path / "mine.toml"
    scene.save(path)
    assert Scene.load(path) == scene
    changed = dataclasses.replace(scene, tol=1e-6)
    assert changed.tol == 1e-6
    assert scene.with_params(radius=50.0).params["radius"] == 50.0
    with pytest.raises(SceneError, match=r"params\.radius"):
        scene.with_params(radius=-1.0)
    with pytest.raises(SceneError, match=r"params\.speed"):
        scene.with_params(speed=1.0)


def test_kw_inf_as_a_string_and_defaults() -> None:
    scene = Scene.from_toml(
        '[params]\nvstar = 0\nkw = "inf"\nradius = 100\nload = 0.002\n'
        "[outputs]\ncontact_width = true\n"
    )
    assert scene.params == {**BASE, "vstar": 0.0, "kw": math.inf}
    assert scene.tol == 1e-8
    assert list(scene.outputs) == ["contact_width"]


# -- validation: one line naming the file and the key ---------------------------

MALFORMED = {
    "unknown key": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\nspeed = 3\n"
        "[outputs]\ncontact_width = true\n",
        "params.speed",
    ),
    "unknown section": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"
        "[outputs]\ncontact_width = true\n[plot]\nx = 1\n",
        "plot",
    ),
    "unknown output": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"
        "[outputs]\ntemperature = true\n",
        "outputs.temperature",
    ),
    "wrong type": (
        '[params]\nvstar = "fast"\nkw = 1\nradius = 100\nload = 0.002\n'
        "[outputs]\ncontact_width = true\n",
        "params.vstar",
    ),
    "bool as number": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = true\nload = 0.002\n"
        "[outputs]\ncontact_width = true\n",
        "params.radius",
    ),
    "missing parameter": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\n"
        "[outputs]\ncontact_width = true\n",
        "params.load",
    ),
    "vstar above critical": (
        "[params]\nvstar = 0.6\nkw = 1\nradius = 100\nload = 0.002\n"
        "[outputs]\ncontact_width = true\n",
        "params.vstar",
    ),
    "vary above critical": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"
        "[outputs]\ncontact_width = true\n"
        "[vary]\nparam = 'kw'\nvalues = [1, 0.1, 0.01]\n",
        "vary.values[2]",
    ),
    "sweep above critical": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"
        "[sweep]\nparam = 'vstar'\nstart = 0\nstop = 0.6\npoints = 5\n",
        "sweep.stop",
    ),
    "out of range": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\nnu = 0.5\n"
        "[outputs]\ncontact_width = true\n",
        "params.nu",
    ),
    "tolerance": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"
        "[accuracy]\ntol = 0.5\n[outputs]\ncontact_width = true\n",
        "accuracy.tol",
    ),
    "range order": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"
        "[outputs]\npressure = { x = [1, -1] }\n",
        "outputs.pressure.x",
    ),
    "key of another output": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"
        "[outputs]\npressure = { depth = -0.5 }\n",
        "outputs.pressure.depth",
    ),
    "sweep quantity": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"
        "[sweep]\nparam = 'load'\nvalues = [0.001]\nquantities = ['colour']\n",
        "sweep.quantities[0]",
    ),
    "nothing to compute": (
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n",
        "outputs",
    ),
    "non-TOML text": ("this is = = not toml\n", "(file)"),
    "empty file": ("", "params"),
    "blank file": ("\n  \n", "params"),
}


@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_malformed_scene_files(case: str, tmp_path: Path) -> None:
    text, key = MALFORMED[case]
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SceneError) as info:
        Scene.load(path)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"{path}: {key}: "), message
    assert "(allowed: " in message
    assert info.value.key == key
    assert isinstance(info.value, mp.InvalidParameterError)
    assert isinstance(info.value, ValueError)


def test_non_utf8_bytes(tmp_path: Path) -> None:
    path = tmp_path / "binary.toml"
    path.write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff\xfe")
    with pytest.raises(SceneError, match=rf"^{path}: \(file\): not valid TOML"):
        Scene.load(path)


def test_missing_file(tmp_path: Path) -> None:
    path = tmp_path / "nowhere.toml"
    with pytest.raises(SceneError, match=r"nowhere\.toml: \(file\): cannot read"):
        Scene.load(path)


def test_python_built_scene_is_validated() -> None:
    with pytest.raises(SceneError, match=r"^<Scene>: params\.vstar: .*critical"):
        Scene(
            params={**BASE, "vstar": 0.9},
            outputs={"contact_width": OutputSpec("contact_width")},
        )
    with pytest.raises(SceneError, match=r"sweep\.param"):
        Scene(
            params=BASE,
            vary=Vary("load", (0.001, 0.002)),
            sweep=Sweep("load", (0.001,)),
        )


# -- running: the physics anchors -----------------------------------------------


def test_table1_matches_the_anchors() -> None:
    result = Scene.bundled("table1").run()
    sweep = result.sweep
    assert sweep is not None
    assert sweep.labels == ("vstar=0", "vstar=0.001")
    for j, kw in enumerate(sweep.values):
        assert sweep.data["a"][0, j] == pytest.approx(TABLE1_STATIC[kw], abs=1e-6)
        assert sweep.data["a"][1, j] == pytest.approx(TABLE1_PAPER[kw], abs=6e-5)
    assert sweep.valid.all()


def test_fig2_and_fig3_agree_where_radius_times_load_coincide() -> None:
    fig2 = Scene.bundled("fig2").run()
    fig3 = Scene.bundled("fig3").run()
    assert fig2.sweep is not None
    assert fig3.sweep is not None
    # Fig. 2: k_w h/mu = 1, load 0.002; Fig. 3: V* = 0.2, R/h = 100.
    a2 = fig2.sweep.data["a"][fig2.sweep.labels.index("vstar=0.2")]
    a3 = fig3.sweep.data["a"][fig3.sweep.labels.index("kw=1")]
    lam2 = fig2.sweep.values * fig2.scene.params["load"]
    lam3 = fig3.sweep.values * fig3.scene.params["radius"]
    matches = 0
    for i, lam in enumerate(lam2):
        j = np.flatnonzero(np.isclose(lam3, lam, rtol=1e-14, atol=0.0))
        for k in j:
            assert abs(a2[i] - a3[k]) <= 1e-12
            matches += 1
    assert matches >= 10


def test_critical_speed_output_alone_solves_no_contact() -> None:
    scene = Scene(
        params=BASE,
        outputs={"critical_speed": OutputSpec("critical_speed")},
        vary=Vary("kw", (0.01, 0.1, 1.0, 10.0, math.inf)),
    )
    result = scene.run()
    assert not result.ran("contact")
    assert result.solutions == ()
    cols = result.outputs["critical_speed"].columns
    for kw, vcr in zip(cols["kw"], cols["critical_vstar"], strict=True):
        expected = RAYLEIGH if math.isinf(kw) else CRITICAL[float(kw)]
        assert vcr == pytest.approx(expected, abs=2e-7)
    assert cols["rayleigh_vstar"] == pytest.approx(RAYLEIGH, abs=2e-7)


def test_critical_speed_curve_against_kw() -> None:
    spec = OutputSpec("critical_speed", kw=(0.01, 10.0), points=4)
    result = Scene(params=BASE, outputs={"critical_speed": spec}).run()
    (curve,) = result.outputs["critical_speed"].curves
    np.testing.assert_allclose(curve.x, [0.01, 0.1, 1.0, 10.0], rtol=1e-12)
    np.testing.assert_allclose(
        curve.y, [CRITICAL[k] for k in (0.01, 0.1, 1.0, 10.0)], atol=2e-7
    )


# -- only what is asked -----------------------------------------------------------


def _width_only() -> Scene:
    return Scene(params=BASE, outputs={"contact_width": OutputSpec("contact_width")})


def _full() -> Scene:
    return Scene(
        params=BASE,
        outputs={
            kind: OutputSpec(kind)
            for kind in (
                "contact_width",
                "pressure",
                "surface_stress",
                "depth_stress",
                "stress_field",
                "displacement",
                "critical_speed",
            )
        },
        sweep=Sweep("load", (0.001, 0.002), quantities=("a", "top_tensile")),
    )


def test_contact_width_only_runs_no_stress_stage() -> None:
    result = _width_only().run()
    assert result.ran("contact")
    assert result.stage("contact").count == 1
    for stage in (*STRESS_STAGES, "pressure", "displacement"):
        assert not result.ran(stage), stage
    names = {s.name for s in result.stages}
    assert names <= {"contact", "critical_speed", "kernel", "width", "checks"}
    (s,) = result.solutions
    assert result.outputs["contact_width"].columns["a"][0] == s.a
    assert all(s.seconds >= 0 for s in result.stages)
    assert result.total_seconds > 0


def test_full_scene_runs_every_stage_once_per_need() -> None:
    mp.clear_kernel_cache()
    result = _full().run()
    for stage in (*STRESS_STAGES, "pressure", "displacement", "contact", "kernel"):
        assert result.ran(stage), stage
    # The base point (load 0.002) is also a sweep point: solved once.
    assert result.stage("contact").count == 2
    assert result.stage("stress_field").count == 1
    assert result.stage("stress_peaks").count == 2
    field = result.outputs["stress_field"].fields[0][1]
    assert field.sigma_x.shape == (41, 81)
    assert len(result.outputs["stress_field"].columns["x"]) == 41 * 81


def test_zero_speed_on_a_rigid_base() -> None:
    """V* = 0 with kw = inf: the static, rigid-base anchor of Table 1."""
    scene = Scene(
        params={**BASE, "vstar": 0.0, "kw": math.inf},
        outputs={"contact_width": OutputSpec("contact_width")},
        tol=1e-10,
    )
    result = scene.run()
    assert result.outputs["contact_width"].columns["a"][0] == pytest.approx(
        TABLE1_STATIC[math.inf], abs=1e-6
    )
    assert result.stage("contact").count == 1


def test_lambda_invariance_numerically() -> None:
    """a/h, p/(P/h), sigma/(P/h) depend on radius and load only through their
    product; displacements scale with the load."""
    x = np.linspace(-2.0, 2.0, 9)
    y = np.linspace(-1.0, 0.0, 5)
    ref = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002, tol=1e-12)
    for radius, load in ((25.0, 0.008), (400.0, 0.0005), (80.0, 0.0025)):
        s = mp.solve(vstar=0.2, kw=1.0, radius=radius, load=load, tol=1e-12)
        assert s.a == pytest.approx(ref.a, rel=1e-12)
        assert s.p0 == pytest.approx(ref.p0, rel=1e-12)
        np.testing.assert_allclose(s.pressure(x), ref.pressure(x), atol=1e-12)
        np.testing.assert_allclose(
            s.surface_stress(x), ref.surface_stress(x), atol=1e-12
        )
        np.testing.assert_allclose(s.depth_stress(y), ref.depth_stress(y), atol=1e-12)
        np.testing.assert_allclose(
            s.displacement(x, -0.5) / load,
            ref.displacement(x, -0.5) / 0.002,
            rtol=1e-12,
        )
        assert s.indentation / load == pytest.approx(ref.indentation / 0.002, rel=1e-12)


# -- sweeps reuse work ------------------------------------------------------------


def test_load_sweep_of_200_points_builds_the_kernel_once() -> None:
    scene = Scene(
        params=BASE,
        sweep=Sweep.range("load", 1e-4, 4e-3, 200, quantities=("a", "p0")),
    )
    mp.clear_kernel_cache()
    result = scene.run(jobs=1)
    assert result.stage("contact").count == 200
    # One solve (the widest contact, solved first) built kernel tables; the
    # other 199 reused them.
    assert result.stage("kernel").count == 1
    assert 1 <= result.kernel_tables <= 2
    assert mp.kernel_cache_info()["misses"] == result.kernel_tables
    assert result.sweep is not None
    a = result.sweep.data["a"][0]
    assert np.all(np.diff(a) > 0)  # wider contact under a larger load


def test_points_with_equal_radius_times_load_are_solved_once() -> None:
    # Powers of two: 0.002 * 25 == 0.001 * 50 exactly in floating point.
    scene = Scene(
        params=BASE,
        vary=Vary("load", (0.001, 0.002)),
        sweep=Sweep("radius", (25.0, 50.0, 100.0), quantities=("a", "indentation")),
        tol=1e-10,
    )
    result = scene.run()
    assert result.stage("contact").count == 4  # lambda = 0.025, 0.05, 0.1, 0.2
    assert result.sweep is not None
    for i, load in enumerate((0.001, 0.002)):
        for j, radius in enumerate((25.0, 50.0, 100.0)):
            s = mp.solve(vstar=0.2, kw=1.0, radius=radius, load=load, tol=1e-10)
            assert result.sweep.data["a"][i, j] == pytest.approx(s.a, rel=1e-9)
            assert result.sweep.data["indentation"][i, j] == pytest.approx(
                s.indentation, rel=1e-7
            )


@pytest.mark.usefixtures("pool_pays")
def test_worker_processes_give_the_same_numbers() -> None:
    scene = dataclasses.replace(
        Scene.bundled("fig2"),
        sweep=Sweep.range("radius", 25.0, 100.0, 4, quantities=("a", "p0")),
        outputs={"contact_width": OutputSpec("contact_width")},
    )
    seen: list[tuple[int, int]] = []
    local = scene.run(jobs=1)
    pooled = scene.run(jobs=2, progress=lambda done, total: seen.append((done, total)))
    assert local.sweep is not None
    assert pooled.sweep is not None
    assert pooled.jobs == 2
    for q in ("a", "p0"):
        np.testing.assert_allclose(
            pooled.sweep.data[q], local.sweep.data[q], rtol=1e-12
        )
    # 16 sweep points in the workers, then the 4 base points (R/h = 100, also
    # sweep points) again here for the contact_width output.
    assert seen[-1] == (20, 20)
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)
    assert pooled.stage("contact").count == 20
    assert local.stage("contact").count == 16
    np.testing.assert_array_equal(
        pooled.outputs["contact_width"].columns["a"], local.sweep.data["a"][:, -1]
    )


def test_progress_reports_every_solve() -> None:
    seen: list[tuple[int, int]] = []
    Scene.bundled("table1").run(progress=lambda d, t: seen.append((d, t)))
    assert seen == [(i, 8) for i in range(1, 9)]


def test_jobs_must_be_positive() -> None:
    with pytest.raises(ValueError, match="jobs"):
        Scene.bundled("table1").run(jobs=0)


# -- exports ------------------------------------------------------------------------


def test_csv_files_load_back_with_their_metadata(tmp_path: Path) -> None:
    scene = Scene.bundled("fig4")
    result = scene.run()
    paths = write_outputs(result, tmp_path, "csv")
    assert {p.name for p in paths} == {
        f"fig4-{k}.csv"
        for k in ("contact_width", "pressure", "surface_stress", "depth_stress")
    }
    assert sorted(tmp_path.iterdir()) == sorted(paths)
    pressure = tmp_path / "fig4-pressure.csv"
    numbers = np.loadtxt(pressure, delimiter=",")
    assert numbers.shape == (201, 5)
    meta, cols = read_csv(pressure)
    assert meta["scene"] == scene
    assert meta["movingpunch_version"] == mp.__version__
    assert meta["output"] == "pressure"
    assert list(cols) == [
        "x",
        "p[vstar=0]",
        "p[vstar=0.2]",
        "p[vstar=0.4]",
        "p[vstar=0.5]",
    ]
    curve = result.outputs["pressure"].curves[1]
    np.testing.assert_array_equal(cols["p[vstar=0.2]"], curve.y)
    np.testing.assert_array_equal(cols["x"], curve.x)
    # Outside the contact the pressure is zero; at the centre it is p0.
    width = read_csv(tmp_path / "fig4-contact_width.csv")[1]
    assert width["a"] == pytest.approx(result.outputs["contact_width"].columns["a"])


def test_json_files_load_back_with_their_metadata(tmp_path: Path) -> None:
    scene = Scene.bundled("table1")
    result = scene.run()
    (path,) = write_outputs(result, tmp_path, "json")
    assert path.name == "table1-sweep.json"
    doc = json.loads(path.read_text(encoding="utf-8"))
    assert doc["movingpunch_version"] == mp.__version__
    meta, cols = read_json(path)
    assert meta["scene"] == scene
    assert cols["kw"][-1] == math.inf
    assert cols["a[vstar=0]"] == pytest.approx(list(TABLE1_STATIC.values()), abs=1e-6)


def test_a_failed_write_leaves_no_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    result = Scene.bundled("table1").run()

    def broken_replace(src: object, dst: object) -> None:
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", broken_replace)
    with pytest.raises(OSError, match="disk full"):
        write_outputs(result, tmp_path, "csv")
    with pytest.raises(OSError, match="disk full"):
        Scene.bundled("fig2").save(tmp_path / "fig2.toml")
    assert list(tmp_path.iterdir()) == []


def test_importing_scenes_loads_no_optional_dependency(
    modules_loaded_by: Callable[[str], set[str]],
) -> None:
    """plotext, matplotlib and Dask load only when a plot, a PNG or a cluster
    is asked for (the CLI starts fast; the extras stay optional)."""
    loaded = modules_loaded_by(
        "import movingpunch, movingpunch.scene, movingpunch.cli\n"
        "movingpunch.scene.Scene.bundled('table1').run()\n"
    )
    optional = {"plotext", "matplotlib", "distributed", "dask", "textual"}
    assert sorted(optional & loaded) == []
