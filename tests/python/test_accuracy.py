"""The accuracy knob and what it costs: presets, the stress error bound, the
accuracy ladder (``movingpunch.accuracy``) and its command.

Actual errors are measured against a reference computed differently from the
solves under test: a fixed, large collocation size (N = 64 or more) at
tol 1e-14, not the automatic refinement. The reference itself is checked
against another fixed size (N = 96) and against the paper's Table 1.
"""

from __future__ import annotations

import dataclasses
import math
import subprocess
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import movingpunch as mp
from movingpunch import accuracy
from movingpunch.scene import OutputSpec, Scene, Sweep, read_csv

FIG4 = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2}

# Cases where the collocation size matters (wide contacts, fast punches, a
# soft foundation, a rigid base near the Rayleigh speed) and easy ones.
CASES: list[dict[str, float]] = [
    FIG4,
    {"vstar": 0.2, "kw": 0.1, "radius": 100.0, "load": 0.002, "nu": 0.2},
    {"vstar": 0.5, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2},
    {"vstar": 0.0, "kw": math.inf, "radius": 100.0, "load": 0.002, "nu": 0.2},
    {"vstar": 0.2, "kw": 0.1, "radius": 100.0, "load": 0.006, "nu": 0.2},
    {"vstar": 0.7, "kw": math.inf, "radius": 100.0, "load": 0.002, "nu": 0.3},
    {"vstar": 0.2, "kw": 10.0, "radius": 50.0, "load": 0.004, "nu": 0.35},
]


def reference(case: Mapping[str, float]) -> mp.Solution:
    return mp.solve(**case, tol=1e-14, n=64)


# ----------------------------------------------------------------------------
# Presets
# ----------------------------------------------------------------------------


def test_presets_are_exported_and_ordered() -> None:
    assert dict(mp.PRESETS) == {"draft": 1e-4, "default": 1e-8, "precise": 1e-12}
    with pytest.raises(TypeError):
        mp.PRESETS["draft"] = 1.0  # type: ignore[index]


@pytest.mark.parametrize("name", ["draft", "default", "precise", " Precise "])
def test_solve_accepts_a_preset_name(name: str) -> None:
    s = mp.solve(**FIG4, tol=name)
    assert s.tol == mp.PRESETS[name.strip().lower()]


@pytest.mark.parametrize("bad", ["fast", "", "1e-3x", None, 1.0, float("nan")])
def test_a_bad_tol_names_the_parameter_the_presets_and_the_range(
    bad: object,
) -> None:
    with pytest.raises(mp.InvalidParameterError) as info:
        mp.solve(**FIG4, tol=bad)  # type: ignore[arg-type]
    message = str(info.value)
    assert message.startswith("tol ")
    for word in ("draft", "default", "precise", "1e-14 <= tol <= 1e-2"):
        assert word in message


@pytest.mark.parametrize("case", CASES[1:3], ids=["soft", "fast"])
def test_presets_are_monotone(case: dict[str, float]) -> None:
    """A tighter preset gives a smaller actual error (a/h and p0), each within
    its tolerance, and a smaller error estimate.

    At equal N two presets differ only by their kernel quadratures, which meet
    1e-2 tol (never looser than 1e-10): the tighter one may then be worse by
    at most that much. (Draft and precise no longer differ by orders of
    magnitude in p0: N is refined over at least three sizes, which gives
    N = 16 for all three here.)
    """
    ref = reference(case)
    eps = 4 * np.finfo(float).eps
    names = ("draft", "default", "precise")
    err_a, err_p0, estimates = [], [], []
    for name in names:
        s = mp.solve(**case, tol=name)
        err_a.append(abs(s.a - ref.a))
        err_p0.append(abs(s.p0 - ref.p0))
        estimates.append(s.error_estimate)
        assert err_a[-1] <= mp.PRESETS[name] * ref.a
        assert err_a[-1] <= s.error_estimate + eps * ref.a
    for looser, tighter in ((0, 1), (1, 2)):
        quadrature = 1e-2 * mp.PRESETS[names[looser]]
        assert err_a[tighter] <= err_a[looser] + (eps + quadrature) * ref.a
        assert err_p0[tighter] <= err_p0[looser] + (eps + quadrature) * ref.p0
    assert estimates[2] < estimates[0]


def test_scene_accuracy_accepts_presets_and_numbers() -> None:
    base = (
        "[params]\nvstar = 0.2\nkw = 1.0\nradius = 100.0\nload = 0.002\n"
        "[outputs]\ncontact_width = true\n"
    )
    precise = Scene.from_toml(base + '[accuracy]\ntol = "precise"\n', "p.toml")
    assert precise.tol == 1e-12
    assert Scene.from_toml(precise.to_toml(), "again") == precise
    assert dataclasses.replace(precise, tol="draft").tol == 1e-4  # type: ignore[arg-type]
    assert Scene.from_toml(base + "[accuracy]\ntol = 1e-6\n", "n.toml").tol == 1e-6
    for bad, problem in (('"fast"', "unknown preset"), ("0.5", "out of range")):
        with pytest.raises(mp.SceneError) as info:
            Scene.from_toml(base + f"[accuracy]\ntol = {bad}\n", "bad.toml")
        message = str(info.value)
        assert message.startswith("bad.toml: accuracy.tol: " + problem)
        assert '"draft"' in message
        assert "1e-14 <= tol <= 1e-2" in message


# ----------------------------------------------------------------------------
# The stress error estimate
# ----------------------------------------------------------------------------


def _peak(s: mp.Solution, peaks: mp.StressPeaks, name: str) -> float:
    """The peak ``name`` of ``s``: the search's value, improved by a dense
    scan (401 points) over twice the search's final step around it. The
    search (a grid, then 3 rounds of 15 points) stops within ~span/4e4 of the
    maximum, which can miss its value by ~1e-9 at a smooth peak (kw = 0.1,
    V* = 0.2, R P = 0.6, tol 1e-12: 1.5e-9 while sigma_x agrees with the
    reference to 1e-15 around it): the search's resolution, not the solver's
    error, which is what stress_error_estimate bounds."""
    x0 = getattr(peaks, f"{name}_x")
    half = 2.0 * peaks.search_extent / (120 * 7**3)
    xs = np.clip(x0 + np.linspace(-half, half, 401), 0.0, peaks.search_extent)
    if name.startswith("bottom"):
        vals = np.asarray(s.stress_field(xs, [-1.0]).sigma_x[0])
    else:
        vals = np.asarray(s.surface_stress(xs))
    found = float(getattr(peaks, name))
    if name == "top_compressive":
        return min(found, float(vals.min()))
    return max(found, float(vals.max()))


@pytest.mark.parametrize("case", CASES, ids=lambda c: f"{c}")
def test_stress_error_estimate_bounds_the_actual_error(case: dict[str, float]) -> None:
    """sigma_x/(P/h) on the surface, at the bottom and through the depth (at
    points at least 1e-3 a from the edge) and the peaks, for tol 1e-2 to
    1e-12, against the fixed-N reference."""
    ref = reference(case)
    a = ref.a
    x = np.linspace(0.0, 3.7 * a, 61) + 0.031 * a
    assert np.min(np.abs(x - a)) > 1e-3 * a
    y = np.linspace(-1.0, 0.0, 21)
    ref_peaks = ref.stress_peaks()
    ref_curves = (
        ref.surface_stress(x),
        ref.stress_field(x, [-1.0]).sigma_x[0],
        ref.depth_stress(y),
    )
    for tol in (1e-2, 1e-6, 1e-10, 1e-12):
        s = mp.solve(**case, tol=tol)
        peaks = s.stress_peaks()
        curves = (s.surface_stress(x), s.stress_field(x, [-1.0]).sigma_x[0])
        errors = [
            float(np.max(np.abs(c - r)))
            for c, r in zip(curves, ref_curves[:2], strict=True)
        ]
        errors.append(float(np.max(np.abs(s.depth_stress(y) - ref_curves[2]))))
        errors += [
            abs(_peak(s, peaks, f) - _peak(ref, ref_peaks, f))
            for f in ("top_tensile", "bottom_tensile", "top_compressive")
        ]
        assert 0 < s.stress_error_estimate < math.inf
        assert max(errors) <= s.stress_error_estimate, (tol, errors)


def test_stress_error_estimate_is_in_the_dict_and_tightens_with_tol() -> None:
    """On a wide contact, where N matters (at Fig. 4 N = 16 already gives
    sigma_x to 2.5e-12 at any tol, and the estimate says so)."""
    wide = {"vstar": 0.2, "kw": 0.1, "radius": 100.0, "load": 0.006}
    loose = mp.solve(**wide, tol=1e-3)
    tight = mp.solve(**wide, tol=1e-12)
    assert loose.to_dict()["stress_error_estimate"] == loose.stress_error_estimate
    assert tight.stress_error_estimate < 1e-3 * loose.stress_error_estimate
    fig4 = mp.solve(**FIG4, tol=1e-3)
    assert fig4.stress_error_estimate < 1e-10


# ----------------------------------------------------------------------------
# The accuracy ladder
# ----------------------------------------------------------------------------


def test_the_reference_is_independent_of_its_size_and_matches_table_1() -> None:
    for case in CASES:
        ref = reference(case)
        other = mp.solve(**case, tol=1e-14, n=96)
        assert abs(ref.a - other.a) <= 1e-14
        assert abs(ref.p0 - other.p0) <= 1e-12
    # docs/theory.md §11: V* = 0, R/h = 100, P/(mu h) = 0.002, nu = 0.2.
    for kw, a in (
        (0.1, 0.372478),
        (1.0, 0.330419),
        (10.0, 0.315037),
        (math.inf, 0.311557),
    ):
        s = reference({"vstar": 0.0, "kw": kw, "radius": 100.0, "load": 0.002})
        assert s.a == pytest.approx(a, abs=6e-7)


def check_acceptance(report: accuracy.AccuracyReport) -> None:
    """For every tol down to 1e-10: the actual a/h error is below the tol and
    below the reported estimate (and every point's error within its own)."""
    assert [r.tol for r in report.rungs] == list(accuracy.LADDER)
    for r in report.rungs:
        assert not r.failure, r.failure
        if r.tol >= 1e-10:
            assert r.error_a < r.tol
            assert r.error_a <= r.error_estimate
        assert r.bounded
        assert r.error_p0 <= r.stress_error_estimate
        # The stages sum to the reported cold time.
        assert sum(r.stages.values()) == pytest.approx(r.seconds, rel=1e-12)
        assert all(t >= 0.0 for t in r.stages.values())
        assert r.seconds > 0
        assert r.warm_seconds > 0


def test_accuracy_ladder_of_the_fig4_case() -> None:
    report = accuracy.accuracy_report()
    assert report is not None
    assert report.name == "fig4-case"
    assert report.points == 1
    check_acceptance(report)
    assert set(report.stage_names) == {
        "critical_speed",
        "kernel",
        "width",
        "checks",
        "stress_peaks",
    }
    # Cold rungs built their kernel tables; the reference is at N = 64.
    assert all(r.kernel_tables >= 1 for r in report.rungs)
    assert report.reference == "fixed N = 64 at tol 1e-14"
    columns = report.columns()
    assert len(columns["tol"]) == len(accuracy.LADDER)
    text = accuracy.format_table(report)
    for tol in accuracy.LADDER:
        assert f"\n{tol:.0e} " in text
    plot = accuracy.ascii_plot(report, width=70, height=18)
    assert "log-log" in plot
    lines = plot.splitlines()
    assert 15 <= len(lines) <= 18
    assert all(len(line) <= 70 for line in lines)
    # The legend is below the frame, outside the data area; the frame's
    # inside holds only the markers (never a legend's words).
    bottom = max(i for i, line in enumerate(lines) if "└" in line)
    legend = " ".join(lines[bottom + 1 :])
    assert "markers: a = a/h" in legend
    inside = [line.split("│")[1] for line in lines[:bottom] if line.count("│") >= 2]
    assert inside
    assert not any("a/h" in row or "σx" in row for row in inside)


def test_accuracy_ladder_of_a_scene_with_its_stages() -> None:
    scene = Scene.bundled("table1")
    report = accuracy.accuracy_report(scene, (1e-3, 1e-8))
    assert report is not None
    assert report.points == 8
    assert report.peak_points == 2
    for r in report.rungs:
        assert r.bounded
        assert r.error_a < r.tol
        assert sum(r.stages.values()) == pytest.approx(r.seconds, rel=1e-12)
    # The scene's own record: the parts of the contact solves sum to the
    # contact stage, and the stages together fit in the run's total.
    result = dataclasses.replace(scene, tol=1e-8).run(jobs=1)
    contact = result.stage("contact").seconds
    parts = sum(
        result.stage(n).seconds for n in ("critical_speed", "kernel", "width", "checks")
    )
    assert parts == pytest.approx(contact, rel=1e-3, abs=1e-5)
    top = sum(
        s.seconds
        for s in result.stages
        if s.name not in ("critical_speed", "kernel", "width", "checks")
    )
    assert top <= result.total_seconds


def test_stages_sum_to_the_time_when_the_scene_has_its_own_peaks() -> None:
    scene = Scene(
        params=FIG4,
        outputs={"contact_width": OutputSpec("contact_width")},
        sweep=Sweep("load", (0.001, 0.002, 0.004), ("a", "top_tensile")),
        name="peaks",
    )
    report = accuracy.accuracy_report(scene, (1e-6,))
    assert report is not None
    (rung,) = report.rungs
    assert {"stress_peaks", "stress_peaks_report"} <= set(rung.stages)
    assert sum(rung.stages.values()) == pytest.approx(rung.seconds, rel=1e-12)
    assert report.points == 3
    assert rung.bounded


def test_a_cancelled_ladder_returns_none() -> None:
    assert accuracy.accuracy_report(FIG4, cancelled=lambda: True) is None


def test_write_csv_is_read_back(tmp_path: Path) -> None:
    report = accuracy.accuracy_report(FIG4, (1e-4, 1e-8))
    assert report is not None
    path = accuracy.write_csv(report, tmp_path / "out")
    assert path.name == "fig4-case-accuracy.csv"
    assert [p.name for p in path.parent.iterdir()] == [path.name]  # no temp left
    meta, columns = read_csv(path)
    assert meta["output"] == "accuracy"
    assert meta["scene"].params == FIG4
    np.testing.assert_array_equal(columns["tol"], [1e-4, 1e-8])
    np.testing.assert_array_equal(columns["error_a"], [r.error_a for r in report.rungs])
    assert np.loadtxt(path, delimiter=",").shape == (2, len(columns))


# ----------------------------------------------------------------------------
# The command
# ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["table1", "fig4"])
def test_accuracy_command_on_a_bundled_scene(
    name: str, tmp_path: Path, run_cli: Callable[..., subprocess.CompletedProcess[str]]
) -> None:
    proc = run_cli("accuracy", name, "--plot", "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    assert f"Accuracy against time: {name}" in out
    assert "Cold time per stage (ms)" in out
    assert "log-log" in out
    meta, columns = read_csv(tmp_path / f"{name}-accuracy.csv")
    assert meta["scene"].name == name
    tols = columns["tol"]
    np.testing.assert_allclose(tols, accuracy.LADDER, rtol=1e-15)
    down_to = tols >= 1e-10
    assert np.all(columns["error_a"][down_to] < tols[down_to])
    assert np.all(columns["error_a"][down_to] <= columns["error_estimate_a"][down_to])
    assert np.all(columns["bounded"] == 1.0)
    # Each printed row shows the same actual a/h error as the file.
    for tol, err in zip(tols, columns["error_a"], strict=True):
        row = next(line for line in out.splitlines() if line.startswith(f"{tol:.0e} "))
        assert f"{err:.1e}" in row.split()


def test_accuracy_command_tols_and_errors(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli("accuracy", "--tols", "draft,1e-6,precise", "--no-plot")
    assert proc.returncode == 0, proc.stderr
    assert "log-log" not in proc.stdout
    for tol in ("1e-04 ", "1e-06 ", "1e-12 "):
        assert any(line.startswith(tol) for line in proc.stdout.splitlines())
    bad = run_cli("accuracy", "--tols", "fast")
    assert bad.returncode == 2
    assert "Traceback" not in bad.stderr
    assert "precise" in bad.stderr
    assert "--tols" in bad.stderr
    missing = run_cli("accuracy", "no-such-scene")
    assert missing.returncode == 2
    assert missing.stderr.startswith("movingpunch: error: no-such-scene")


def test_solve_command_takes_a_preset(
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    proc = run_cli(
        "solve",
        *("--vstar", "0.2", "--kw", "1", "--radius", "100", "--load", "0.002"),
        *("--tol", "precise"),
    )
    assert proc.returncode == 0, proc.stderr
    assert "tolerance" in proc.stdout
    assert "1e-12" in proc.stdout
    assert "error bound (σx/(P/h))" in proc.stdout
    bad = run_cli(
        "solve",
        *("--vstar", "0.2", "--kw", "1", "--radius", "100", "--load", "0.002"),
        *("--tol", "fast"),
    )
    assert bad.returncode == 2
    line = bad.stderr.strip()
    assert line.startswith("movingpunch: error: tol ")
    assert "draft" in line


def test_a_scene_without_contact_is_a_clear_error(tmp_path: Path) -> None:
    scene = Scene(params=FIG4, outputs={"critical_speed": OutputSpec("critical_speed")})
    with pytest.raises(mp.InvalidParameterError, match="solves no contact"):
        accuracy.accuracy_report(scene, (1e-4,))


def test_a_failed_rung_is_reported_and_the_others_run(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    real = mp.solve

    def flaky(**kwargs: Any) -> mp.Solution:
        if kwargs["tol"] == 1e-6 and kwargs.get("n") is None:
            raise mp.ConvergenceError("a/h did not converge (injected)")
        return real(**kwargs)

    monkeypatch.setattr(accuracy, "solve", flaky)
    report = accuracy.accuracy_report(FIG4, (1e-4, 1e-6, 1e-8))
    assert report is not None
    ok, failed, last = report.rungs
    assert failed.failure == "a/h did not converge (injected)"
    assert not failed.bounded
    assert math.isnan(failed.error_a)
    assert ok.bounded
    assert last.bounded
    assert "1e-06  failed: a/h did not converge (injected)" in accuracy.format_table(
        report
    )
    assert np.isnan(report.columns()["error_a"][1])


def test_accuracy_ladder_of_an_asymmetric_table_with_damping() -> None:
    """A profile on the asymmetric solver (an asymmetric table, damped): every
    rung's estimates bound its errors against the reference, allowing for the
    reference's own estimate (its large fixed N has a round-off floor of its
    own)."""
    xs = [-1.5 + 0.005 * i for i in range(801)]
    prof = mp.Profile(tuple(xs), tuple((x - 0.2) ** 2 / 200.0 for x in xs))
    case = {"vstar": 0.2, "kw": 1.0, "load": 0.002, "damping": 0.5}
    report = accuracy.accuracy_report(case, tols=(1e-4, 1e-8, 1e-12), profile=prof)
    assert report is not None
    assert report.scene.profile == prof
    for r in report.rungs:
        assert not r.failure, r.failure
        assert r.bounded
        assert r.error_a <= max(r.tol, 1e-12)
