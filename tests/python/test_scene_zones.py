"""Scenes with several contact zones: ``[[punches]]`` tables (a train solved
by ``movingpunch.solve_punches``), ``[params] contact``, sweeps over
``spacing``, the ``zones`` quantity, contact zones and per-punch results in
the exports, the bundled scenes separated, two-axle, bogie and spacing, and
the CLI's ``solve --contact`` / ``--punch``."""

from __future__ import annotations

import json
import math
import subprocess
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.accuracy import accuracy_report
from movingpunch.scene import (
    Scene,
    SceneError,
    Sweep,
    bundled_scenes,
    format_summary,
    read_csv,
    read_json,
    write_outputs,
)

TRAIN = """
name = "train"
[params]
vstar = 0.5
kw = 1.0
[[punches]]
radius = 100
load = 0.002
at = -1.5
[[punches]]
load = 0.003
at = 1.5
[punches.profile]
kind = "rounded_flat"
half_width = 0.2
radius = 50
[outputs]
contact_width = true
pressure = { points = 41 }
"""

SEPARATED = {"vstar": 0.99 * mp.critical_vstar(0.1), "kw": 0.1}
"""The paper's soft foundation pushed to 0.99 V*_cr: a two-zone contact at
R/h = 100, P/(mu h) = 0.002."""


def _two(spacing_lines: str = "", punches: str | None = None) -> str:
    body = (
        punches
        if punches is not None
        else "[[punches]]\nradius = 100\nload = 0.002\nat = -2\n"
        "[[punches]]\nradius = 100\nload = 0.002\nat = 2\n"
    )
    return f"[params]\nvstar = 0.5\nkw = 1.0\n{body}{spacing_lines}"


# -- parsing and running -------------------------------------------------------


def test_a_train_scene_parses_round_trips_and_matches_solve_punches(
    tmp_path: Path,
) -> None:
    scene = Scene.from_toml(TRAIN)
    assert scene.punches == (
        mp.Punch(100.0, 0.002, -1.5),
        mp.Punch(mp.RoundedFlat(0.2, 50.0), 0.003, 1.5),
    )
    assert "load" not in scene.params
    assert "radius" not in scene.params
    assert Scene.from_toml(scene.to_toml()) == scene
    scene.save(tmp_path / "t.toml")
    assert Scene.load(tmp_path / "t.toml") == scene

    result = scene.run()
    direct = mp.solve_punches(list(scene.punches), vstar=0.5, kw=1.0)
    cw = result.outputs["contact_width"]
    # The same solve up to round-off: the kernel tables an earlier solve in
    # this process left behind move the last digit (1 ulp of the
    # indentation after other zone tests).
    same = {"rel": 1e-13, "abs": 0.0}
    assert cw.columns["a"][0] == pytest.approx(direct.a, **same)
    assert cw.columns["indentation"][0] == pytest.approx(direct.indentation, **same)
    assert cw.columns["contact_start"][0] == pytest.approx(
        direct.contact_interval[0], **same
    )
    assert cw.columns["zones"][0] == len(direct.contact_zones) == 2
    np.testing.assert_allclose(
        cw.details["contact_zones"][0],
        [list(z) for z in direct.contact_zones],
        rtol=1e-13,
    )
    assert cw.details["punches"] == [[p.to_dict() for p in direct.punches]]
    pressure = result.outputs["pressure"]
    x = pressure.curves[0].x
    # The plot's range covers the whole hull of the zones.
    assert x[0] < direct.contact_interval[0]
    assert x[-1] > direct.contact_interval[1]
    p_direct = direct.pressure(x)
    np.testing.assert_allclose(
        pressure.curves[0].y,
        p_direct,
        rtol=0,
        atol=1e-12 * float(np.max(np.abs(p_direct))),
    )
    summary = format_summary(result)
    assert "contact zones: " in summary
    assert "punch 2 at x/h = 1.5" in summary


def test_contact_auto_and_single_in_params() -> None:
    text = (
        f"[params]\nvstar = {SEPARATED['vstar']!r}\nkw = 0.1\nradius = 100\n"
        'load = 0.002\ncontact = "{}"\n[outputs]\ncontact_width = true\n'
    )
    auto = Scene.from_toml(text.format("auto"))
    single = Scene.from_toml(text.format("single"))
    assert auto.contact == "auto"
    assert single.contact == "single"
    assert "contact =" not in auto.to_toml()  # the default is not written
    assert Scene.from_toml(single.to_toml()) == single
    direct = mp.solve(**SEPARATED, radius=100, load=0.002)
    assert len(direct.contact_zones) == 2
    a = auto.run().outputs["contact_width"]
    assert a.columns["zones"][0] == 2
    assert a.columns["valid"][0] == 1.0
    assert a.columns["a"][0] == direct.a
    s = single.run().outputs["contact_width"]
    assert s.columns["zones"][0] == 1
    assert s.columns["valid"][0] == 0.0
    with pytest.raises(SceneError, match=r"params\.contact"):
        Scene.from_toml(text.format("double"))


def test_spacing_sweep_both_directions_and_zones_quantity() -> None:
    sweep = '[sweep]\nparam = "spacing"\nvalues = {}\nquantities = {}\n'
    q = '["indentation", "a", "zones"]'
    up = Scene.from_toml(_two(sweep.format("[3.0, 4.0, 6.0]", q)))
    down = Scene.from_toml(_two(sweep.format("[6.0, 4.0, 3.0]", q)))
    r_up, r_down = up.run(), down.run()
    assert r_up.sweep is not None
    assert r_down.sweep is not None
    for name in ("indentation", "a", "zones"):
        np.testing.assert_array_equal(
            r_up.sweep.data[name][0], r_down.sweep.data[name][0][::-1]
        )
    # at_k = (k - (K - 1)/2) * spacing
    direct = mp.solve_punches(
        [mp.Punch(100, 0.002, -2.0), mp.Punch(100, 0.002, 2.0)], vstar=0.5, kw=1.0
    )
    assert r_up.sweep.data["indentation"][0][1] == direct.indentation
    assert r_up.sweep.data["a"][0][1] == direct.a
    assert list(r_up.sweep.data["zones"][0]) == [2.0, 2.0, 2.0]
    # A range sweep over spacing (workers too) gives the same numbers.
    ranged = Scene.from_toml(
        _two('[sweep]\nparam = "spacing"\nstart = 3.0\nstop = 6.0\npoints = 4\n')
    )
    assert ranged.run().sweep is not None


def test_load_sweep_scales_every_punch() -> None:
    scene = Scene.from_toml(
        _two(
            '[sweep]\nparam = "load"\nvalues = [0.002, 0.008]\n'
            'quantities = ["indentation"]\n'
        )
    )
    result = scene.run()
    assert result.sweep is not None
    # load = the train's total load: 0.008 is 0.004 on each punch.
    direct = mp.solve_punches(
        [mp.Punch(100, 0.004, -2.0), mp.Punch(100, 0.004, 2.0)], vstar=0.5, kw=1.0
    )
    assert result.sweep.data["indentation"][0][1] == direct.indentation


def test_scene_built_in_python_with_punches() -> None:
    scene = Scene(
        params={"vstar": 0.5, "kw": 1.0},
        punches=(mp.Punch(100, 0.002, -2.0), mp.Punch(100, 0.002, 2.0)),
        sweep=Sweep("spacing", (4.0, 5.0), ("zones",)),
    )
    assert Scene.from_toml(scene.to_toml()) == scene
    with pytest.raises(SceneError, match=r"sweep\.param.*spacing needs"):
        Scene(
            params={"vstar": 0.5, "kw": 1.0, "radius": 100.0, "load": 0.002},
            sweep=Sweep("spacing", (4.0, 5.0)),
        )
    with pytest.raises(SceneError, match=r"punches\[1\]\.at"):
        Scene(
            params={"vstar": 0.5, "kw": 1.0},
            punches=(mp.Punch(100, 0.002, 1.0), mp.Punch(100, 0.002, 1.0)),
            outputs={"contact_width": mp.scene.OutputSpec("contact_width")},
        )


# -- broken tables -------------------------------------------------------------

_P0 = "[[punches]]\nradius = 100\nload = 0.002\nat = -2\n"
_OUT = "[outputs]\ncontact_width = true\n"


@pytest.mark.parametrize(
    ("text", "key"),
    [
        (_two(_OUT, "[[punches]]\nradius = 100\nat = 1\n"), "punches[0].load"),
        (
            _two(_OUT, _P0 + "[[punches]]\nradius = 100\nload = -0.002\n"),
            "punches[1].load",
        ),
        (
            _two(_OUT, "[[punches]]\nradius = 100\nload = 0.002\nat = nan\n"),
            "punches[0].at",
        ),
        (
            _two(_OUT, "[[punches]]\nradius = 100\nload = 0.002\nat = inf\n"),
            "punches[0].at",
        ),
        (
            _two(_OUT, '[[punches]]\nradius = 100\nload = 0.002\nat = "x"\n'),
            "punches[0].at",
        ),
        (
            _two(_OUT, "[[punches]]\nradius = 100\nload = 0.002\nwheel = 1\n"),
            "punches[0].wheel",
        ),
        (_two(_OUT, "[[punches]]\nload = 0.002\n"), "punches[0].radius"),
        (_two(_OUT, "[[punches]]\nload = 0.002\nradius = -1\n"), "punches[0].radius"),
        (
            _two(
                _OUT,
                "[[punches]]\nload = 0.002\nradius = 5\n"
                '[punches.profile]\nkind = "cylinder"\nradius = 5\n',
            ),
            "punches[0].radius",
        ),
        (
            _two(
                _OUT,
                "[[punches]]\nload = 0.002\n"
                '[punches.profile]\nkind = "flat"\nhalf_width = 1\n',
            ),
            "punches[0].profile",
        ),
        (
            _two(
                _OUT, '[[punches]]\nload = 0.002\n[punches.profile]\nkind = "ellipse"\n'
            ),
            "punches[0].profile.kind",
        ),
        (
            _two(
                _OUT,
                "[[punches]]\nload = 0.002\n"
                '[punches.profile]\nkind = "rounded_flat"\nradius = 5\n',
            ),
            "punches[0].profile.half_width",
        ),
        (
            _two(_OUT, _P0 + "[[punches]]\nradius = 100\nload = 0.002\nat = -2\n"),
            "punches[1].at",
        ),
        ("punches = 3\n" + _two(_OUT, ""), "punches"),
        ("punches = []\n" + _two(_OUT, ""), "punches"),
        ("[params]\nvstar = 0.5\nkw = 1.0\nload = 0.002\n" + _P0 + _OUT, "params.load"),
        (
            "[params]\nvstar = 0.5\nkw = 1.0\nradius = 100\n" + _P0 + _OUT,
            "params.radius",
        ),
        (
            "[params]\nvstar = 0.5\nkw = 1.0\nfriction = 0.1\n" + _P0 + _OUT,
            "params.friction",
        ),
        (
            '[params]\nvstar = 0.5\nkw = 1.0\ncontact = "single"\n' + _P0 + _OUT,
            "params.contact",
        ),
        (
            '[params]\nvstar = 0.5\nkw = 1.0\n[params.profile]\nkind = "cylinder"\n'
            "radius = 100\n" + _P0 + _OUT,
            "params.profile",
        ),
        (_two('[sweep]\nparam = "radius"\nvalues = [50.0, 100.0]\n'), "sweep.param"),
        (_two('[sweep]\nparam = "spacing"\nvalues = [0.0, 3.0]\n'), "sweep.values[0]"),
        (_two('[sweep]\nparam = "spacing"\nvalues = [-1.0, 3.0]\n'), "sweep.values[0]"),
        (_two('[vary]\nparam = "spacing"\nvalues = [nan]\n' + _OUT), "vary.values[0]"),
        (
            "[params]\nvstar = 0.5\nkw = 1.0\nradius = 100\nload = 0.002\n"
            '[sweep]\nparam = "spacing"\nvalues = [3.0, 4.0]\n',
            "sweep.param",
        ),
        (_two(_OUT, "[[punches]]\nradius = 100\nload = 0.002\n" * 17), "punches"),
    ],
)
def test_broken_punches_give_a_scene_error_naming_the_key(text: str, key: str) -> None:
    with pytest.raises(SceneError) as info:
        Scene.from_toml(text, "bad.toml")
    assert info.value.key == key, str(info.value)
    assert str(info.value).startswith(f"bad.toml: {key}:")
    assert "\n" not in str(info.value)


def test_overlapping_punches_are_a_scene_error_naming_the_key() -> None:
    close = _P0.replace("-2", "0") + _P0.replace("-2", "0.1")
    with pytest.raises(
        SceneError, match=r"punches\[0\] and punches\[1\] overlap"
    ) as info:
        Scene.from_toml(_two(_OUT, close), "bad.toml")
    assert info.value.key == "punches[1].at"
    # A vary over spacing blames the value at fault (0.02: punches at
    # +-0.01, which the solver refuses; 0.5 it solves, their zones apart).
    vary = '[vary]\nparam = "spacing"\nvalues = [4.0, 0.02]\n'
    with pytest.raises(SceneError) as info:
        Scene.from_toml(_two(_OUT + vary), "bad.toml")
    assert info.value.key == "vary.values[1]"
    # A sweep's point too close (no contact set keeps the punches apart) is
    # that point's error, not the scene's.
    sweep = '[sweep]\nparam = "spacing"\nvalues = [0.02, 4.0]\nquantities = ["a"]\n'
    result = Scene.from_toml(_two(sweep)).run()
    assert result.sweep is not None
    assert "overlap" in result.sweep.errors[(0, 0)]
    assert math.isnan(result.sweep.data["a"][0][0])
    assert math.isfinite(result.sweep.data["a"][0][1])


# -- exports -------------------------------------------------------------------


def test_exports_hold_zones_and_punches(tmp_path: Path) -> None:
    scene = Scene.from_toml(TRAIN)
    result = scene.run()
    write_outputs(result, tmp_path / "json", "json")
    write_outputs(result, tmp_path / "csv", "csv")
    meta, cols = read_json(tmp_path / "json" / "train-contact_width.json")
    direct = mp.solve_punches(list(scene.punches), vstar=0.5, kw=1.0)
    zones = [[list(z) for z in direct.contact_zones]]
    assert meta["contact_zones"] == zones
    assert meta["punches"][0][1]["indentation"] == direct.punches[1].indentation
    assert meta["punches"][0][1]["profile"] == {
        "kind": "rounded_flat",
        "half_width": 0.2,
        "radius": 50.0,
    }
    assert meta["scene"] == scene
    assert cols["zones"][0] == 2.0
    meta_csv, cols_csv = read_csv(tmp_path / "csv" / "train-contact_width.csv")
    assert meta_csv["contact_zones"] == zones
    assert meta_csv["punches"] == json.loads(json.dumps(meta["punches"]))
    assert meta_csv["scene"] == scene
    np.testing.assert_array_equal(cols_csv["a"], cols["a"])


def test_ordinary_results_have_one_zone(tmp_path: Path) -> None:
    scene = Scene.from_toml(
        "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n" + _OUT
    )
    cw = scene.run().outputs["contact_width"]
    a = cw.columns["a"][0]
    assert cw.columns["zones"][0] == 1.0
    # Every result has its punches (the contract): a single one at x = 0.
    (punch,) = cw.details["punches"][0]
    assert cw.details == {"contact_zones": [[[-a, a]]], "punches": [[punch]]}
    assert punch["profile"] == mp.Cylinder(100.0).to_dict()
    assert (punch["at"], punch["load"], punch["drag"]) == (0.0, 0.002, 0.0)
    assert punch["contact_zones"] == [[-a, a]]
    assert punch["zone_loads"] == [0.002]
    assert punch["indentation"] == cw.columns["indentation"][0]


# -- bundled scenes ------------------------------------------------------------


def test_the_new_bundled_scenes_are_listed() -> None:
    names = bundled_scenes()
    for name in ("separated", "two-axle", "bogie", "spacing"):
        assert name in names
        assert names[name]


@pytest.mark.parametrize("name", ["separated", "two-axle", "bogie"])
def test_bundled_zone_scenes_run(name: str) -> None:
    result = Scene.bundled(name).run()
    cw = result.outputs["contact_width"]
    expected = {"separated": 2, "two-axle": 2, "bogie": 4}[name]
    assert cw.columns["zones"][0] == expected
    assert cw.columns["valid"][0] == 1.0
    if name == "separated":
        lo, hi = cw.details["contact_zones"][0][1]
        assert (lo, hi) == pytest.approx((0.7224, 1.7826), abs=1e-3)


def test_bundled_spacing_sweep_solves_every_point() -> None:
    result = Scene.bundled("spacing").run(jobs=1)
    sw = result.sweep
    assert sw is not None
    assert not sw.errors
    assert sw.valid.all()
    assert np.isfinite(sw.data["indentation"]).all()
    # Far apart, each punch indents nearly as it would alone.
    alone = mp.solve(vstar=0.2227694712427412, kw=0.1, radius=100, load=0.002)
    assert sw.data["indentation"][0][-1] == pytest.approx(alone.indentation, rel=0.05)


# -- the CLI -------------------------------------------------------------------


@pytest.mark.parametrize("name", ["separated", "two-axle", "bogie", "spacing"])
def test_cli_runs_the_bundled_zone_scenes(
    name: str, run_cli: Callable[..., subprocess.CompletedProcess[str]]
) -> None:
    proc = run_cli("run", name, "--no-plot", "--jobs", "1")
    assert proc.returncode == 0, proc.stderr
    if name != "spacing":
        assert "contact zones: (" in proc.stdout


def test_cli_solve_contact_and_punches(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
    assert_one_line_error: Callable[..., None],
) -> None:
    case = ["--vstar", repr(SEPARATED["vstar"]), "--kw", "0.1", "--radius", "100"]
    proc = run_cli("solve", *case, "--load", "0.002")
    assert proc.returncode == 0, proc.stderr
    assert "contact zones" in proc.stdout
    assert "(-1.7826, -0.722423) (0.722423, 1.7826)" in proc.stdout
    single = run_cli("solve", *case, "--load", "0.002", "--contact", "single")
    assert_one_line_error(single, "unphysical")
    train = run_cli(
        "solve",
        "--vstar",
        "0.5",
        "--kw",
        "1",
        "--radius",
        "100",
        "--punch",
        "0.002@-1.5",
        "--punch",
        "0.002@1.5",
        "--json",
    )
    assert train.returncode == 0, train.stderr
    data = json.loads(train.stdout)
    direct = mp.solve_punches(
        [mp.Punch(100, 0.002, -1.5), mp.Punch(100, 0.002, 1.5)], vstar=0.5, kw=1.0
    )
    # A fresh process (cold kernel cache) agrees to rounding.
    assert np.allclose(data["contact_zones"], direct.contact_zones, rtol=1e-12)
    assert [p["indentation"] for p in data["punches"]] == pytest.approx(
        [p.indentation for p in direct.punches], rel=1e-12
    )
    table = run_cli(
        "solve",
        "--vstar",
        "0.5",
        "--kw",
        "1",
        "--radius",
        "100",
        "--punch",
        "0.002@-1.5",
        "--punch",
        "0.002@1.5",
    )
    assert table.returncode == 0, table.stderr
    assert "punch 2 at x/h = 1.5" in table.stdout
    both = run_cli(
        "solve",
        "--vstar",
        "0.5",
        "--kw",
        "1",
        "--radius",
        "100",
        "--load",
        "0.002",
        "--punch",
        "0.002@-1.5",
    )
    assert_one_line_error(both, "--load", "--punch")
    bad = run_cli("solve", "--vstar", "0.5", "--kw", "1", "--punch", "x@1")
    assert_one_line_error(bad, "LOAD@AT")
    missing = run_cli("solve", "--vstar", "0.5", "--kw", "1", "--radius", "100")
    assert_one_line_error(missing, "--load")
    assert math.isfinite(direct.a)


def test_the_accuracy_report_covers_a_train() -> None:
    # The punches as the scene writes them, against solve_punches' own
    # reference (fixed N, tol 1e-14): every rung's errors within its
    # estimates, on every zone end.
    report = accuracy_report(Scene.bundled("two-axle"), tols=[1e-2, 1e-8])
    assert report is not None
    assert len(report.rungs) == 2
    for rung in report.rungs:
        assert rung.bounded, rung


@pytest.mark.usefixtures("pool_pays")
def test_a_train_sweep_in_worker_processes_gives_the_same_numbers() -> None:
    scene = Scene.bundled("spacing")
    here, pooled = scene.run(jobs=1), scene.run(jobs=2)
    assert here.sweep is not None
    assert pooled.sweep is not None
    assert pooled.jobs == 2
    # The same numbers to round-off: a worker's kernel tables are built for
    # the spacings it saw (another range), which moves the last digits only.
    for q in scene.sweep.quantities if scene.sweep is not None else ():
        np.testing.assert_allclose(
            pooled.sweep.data[q], here.sweep.data[q], rtol=1e-11, atol=1e-15
        )
