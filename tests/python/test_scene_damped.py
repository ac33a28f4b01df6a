"""Damping in scenes (issue 8): ``[params] damping``, vary/sweep over it,
the speed check up to V*_R, the damped outputs and the refused ones.

Every damped number is checked against ``mp.solve(..., damping=...)`` solved
separately, and the tiny-damping case against the undamped solver."""

from __future__ import annotations

import math

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.asymmetric import AsymmetricSolution
from movingpunch.scene import OutputSpec, Scene, SceneError, Sweep, Vary, bundled_scenes

FIG4 = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002, "nu": 0.2}
HEAD = "[params]\nvstar = {vstar}\nkw = 1\nradius = 100\nload = 0.002\n"


def damped(
    vstar: float, damping: float, radius: float = 100.0, load: float = 0.002
) -> AsymmetricSolution:
    s = mp.solve(vstar=vstar, kw=1.0, radius=radius, load=load, damping=damping)
    assert isinstance(s, AsymmetricSolution)
    return s


def undamped(vstar: float) -> mp.Solution:
    return mp.solve(vstar=vstar, kw=1.0, radius=100.0, load=0.002)


def test_bundled_damped_scene_matches_the_api() -> None:
    assert "damped" in bundled_scenes()
    scene = Scene.bundled("damped")
    assert scene.params["damping"] == 0.1
    vcr = mp.critical_vstar(1.0)
    assert scene.vary is not None
    speeds = scene.vary.values
    assert min(speeds) < vcr < max(speeds) < mp.rayleigh_vstar(0.2)
    result = scene.run()
    cw = result.outputs["contact_width"].columns
    pressure = result.outputs["pressure"]
    for i, vstar in enumerate(speeds):
        s = damped(vstar, 0.1)
        assert cw["contact_start"][i] == pytest.approx(s.contact_interval[0], abs=1e-12)
        assert cw["contact_end"][i] == pytest.approx(s.contact_interval[1], abs=1e-12)
        assert cw["a"][i] == pytest.approx(s.a, abs=1e-12)
        assert cw["drag"][i] == pytest.approx(s.drag, rel=1e-10)
        assert cw["indentation"][i] == pytest.approx(s.indentation, rel=1e-10)
        assert cw["p0"][i] == pytest.approx(float(s.pressure(0.0)), rel=1e-10)
        curve = pressure.curves[i]
        np.testing.assert_allclose(curve.y, s.pressure(curve.x), atol=1e-12)
    # The pressure range spans every contact, the supercritical one included.
    x = pressure.curves[0].x
    assert x[0] < min(cw["contact_start"])
    assert x[-1] > max(cw["contact_end"])
    # Asymmetric with damping; the supercritical contact lies ahead of x = 0.
    assert cw["drag"][-1] > cw["drag"][0] > 0.0
    assert cw["contact_start"][-1] > 0.0
    assert result.stage("contact").count == len(speeds)


def test_tiny_damping_gives_the_undamped_symmetric_contact() -> None:
    """Independent anchor: damping 1e-9 below V*_cr is the undamped solve
    (drag 0, interval (-a, a) with the undamped a), and the damped depth and
    field outputs (surface row from the surface values, clipped depths)
    reproduce the undamped solver's stresses."""
    scene = Scene(
        params={**FIG4, "damping": 1e-9},
        outputs={
            "contact_width": OutputSpec("contact_width"),
            "depth_stress": OutputSpec("depth_stress", points=5),
            "stress_field": OutputSpec(
                "stress_field", x=(-0.5, 0.5), points=5, depth_points=3
            ),
        },
    )
    result = scene.run()
    u = undamped(0.2)
    cw = result.outputs["contact_width"].columns
    assert abs(cw["drag"][0]) < 1e-9
    assert cw["contact_start"][0] == pytest.approx(-u.a, rel=1e-8)
    assert cw["contact_end"][0] == pytest.approx(u.a, rel=1e-8)
    depth = result.outputs["depth_stress"].curves[0]
    np.testing.assert_allclose(depth.x, [-1.0, -0.75, -0.5, -0.25, 0.0])
    np.testing.assert_allclose(depth.y, u.depth_stress(depth.x), rtol=1e-6)
    ((_, field),) = result.outputs["stress_field"].fields
    ref = u.stress_field(field.x, [-1.0, -0.5, 0.0])
    np.testing.assert_allclose(field.y, [-1.0, -0.5, 0.0])
    for comp in ("sigma_x", "sigma_y", "von_mises"):
        np.testing.assert_allclose(
            getattr(field, comp), getattr(ref, comp), rtol=1e-6, atol=1e-8
        )
    np.testing.assert_allclose(field.tau_xy[-1], 0.0)


def test_near_surface_depths_of_damped_points_are_the_solutions_own() -> None:
    """Depths in the top 1e-3 (once clipped to -1e-3) are evaluated where
    asked; they approach the surface value (continuity), and are the
    undamped ones as damping -> 0 (independent anchor)."""
    out = {}
    for damping in (0.1, 1e-12):
        scene = Scene(
            params={**FIG4, "vstar": 0.4, "damping": damping},
            outputs={
                "depth_stress": OutputSpec("depth_stress", y=(-1e-3, 0.0), points=3)
            },
        )
        result = scene.run()
        curve = result.outputs["depth_stress"].curves[0]
        s = result.solutions[0]
        np.testing.assert_allclose(curve.x, [-1e-3, -5e-4, 0.0])
        np.testing.assert_array_equal(curve.y, s.depth_stress(curve.x))
        assert curve.y[2] == pytest.approx(float(s.surface_stress(0.0)), rel=1e-12)
        assert abs(curve.y[1] - curve.y[2]) < abs(curve.y[0] - curve.y[2])
        out[damping] = curve.y
    u = undamped(0.4)
    np.testing.assert_allclose(
        out[1e-12], u.depth_stress([-1e-3, -5e-4, 0.0]), rtol=1e-8
    )


def test_sweep_shares_lambda_and_rescales_the_drag() -> None:
    """(R, P) = (50, 0.004) and (100, 0.002) share lambda = R P: one solve,
    and drag = int p x/R dx / P scales like 1/R. Checked against a separate
    solve at (50, 0.004)."""
    scene = Scene(
        params={**FIG4, "vstar": 0.4, "damping": 0.1},
        vary=Vary("load", (0.002, 0.004)),
        sweep=Sweep(
            "radius", (50.0, 100.0), quantities=("drag", "contact_start", "contact_end")
        ),
    )
    result = scene.run()
    assert result.stage("contact").count == 3  # lambda 0.1, 0.2 (twice), 0.4
    sw = result.sweep
    assert sw is not None
    direct = damped(0.4, 0.1, radius=50.0, load=0.004)
    assert sw.data["drag"][1, 0] == pytest.approx(direct.drag, rel=1e-7)
    assert sw.data["contact_start"][1, 0] == pytest.approx(
        direct.contact_interval[0], rel=1e-7
    )
    assert sw.data["contact_end"][1, 0] == pytest.approx(
        direct.contact_interval[1], rel=1e-7
    )
    assert sw.data["drag"][1, 0] == pytest.approx(2.0 * sw.data["drag"][0, 1])


def test_sweep_over_damping_and_undamped_quantities() -> None:
    scene = Scene(
        params={**FIG4, "vstar": 1e-3},
        sweep=Sweep("damping", (0.0, 0.5), quantities=("a", "drag", "contact_start")),
    )
    result = scene.run()
    sw = result.sweep
    assert sw is not None
    a0 = undamped(1e-3).a
    assert sw.data["a"][0, 0] == a0
    assert sw.data["drag"][0, 0] == 0.0
    assert sw.data["contact_start"][0, 0] == -a0
    s = damped(1e-3, 0.5)
    assert sw.data["drag"][0, 1] == pytest.approx(s.drag, rel=1e-10)
    assert sw.data["contact_start"][0, 1] == pytest.approx(s.contact_interval[0])


def test_damped_sweep_gives_the_stress_peaks() -> None:
    # A damped point's sigma_x peaks come from AsymmetricSolution.stress_peaks
    # (equal to the API's), an undamped point's from Solution.stress_peaks.
    scene = Scene(
        params={**FIG4, "vstar": 0.4},
        sweep=Sweep("damping", (0.0, 0.1), quantities=("top_tensile", "centre_top")),
    )
    result = scene.run()
    assert result.ran("stress_peaks")
    sw = result.sweep
    assert sw is not None
    assert sw.data["top_tensile"][0, 0] == undamped(0.4).stress_peaks().top_tensile
    peaks = damped(0.4, 0.1).stress_peaks()
    assert sw.data["top_tensile"][0, 1] == pytest.approx(peaks.top_tensile, rel=1e-12)
    assert sw.data["centre_top"][0, 1] == pytest.approx(peaks.centre_top, rel=1e-12)


@pytest.mark.parametrize(
    ("value", "problem"),
    [
        ("-0.1", "out of range: -0.1"),
        ("nan", "out of range: nan"),
        ("inf", "out of range: inf"),
        ('"abc"', "must be a number, got 'abc'"),
        ("true", "must be a number, got true"),
    ],
)
def test_bad_damping_is_one_line_naming_file_and_key(value: str, problem: str) -> None:
    text = HEAD.format(vstar=0.2) + f"damping = {value}\n[outputs]\npressure = true\n"
    with pytest.raises(SceneError) as info:
        Scene.from_toml(text, "my.toml")
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"my.toml: params.damping: {problem}"), message
    assert info.value.key == "params.damping"
    assert info.value.allowed == (
        "a number, 0 <= damping < inf (0: no dashpots, the paper's model), "
        "damping = c_w c_T/mu"
    )
    assert info.value.parameter == "damping"


def test_bad_damping_in_vary_and_python() -> None:
    with pytest.raises(SceneError, match=r"vary\.values\[1\]: out of range: -1\.0"):
        Scene(
            params=FIG4,
            outputs={"pressure": OutputSpec("pressure")},
            vary=Vary("damping", (0.1, -1.0)),
        )
    with pytest.raises(SceneError, match=r"<Scene>: params\.damping: out of range"):
        Scene(
            params={**FIG4, "damping": math.inf},
            outputs={"pressure": OutputSpec("pressure")},
        )


def test_supercritical_speed_needs_damping() -> None:
    text = HEAD.format(vstar=0.65) + "{}[outputs]\npressure = true\n"
    scene = Scene.from_toml(text.format("damping = 0.1\n"), "ok.toml")
    assert scene.params["damping"] == 0.1
    with pytest.raises(SceneError) as info:
        Scene.from_toml(text.format(""), "no.toml")
    message = str(info.value)
    assert message.startswith("no.toml: params.vstar: vstar = 0.65 is at or above")
    assert "critical speed" in message
    assert "damping > 0" in message
    # A damping-0 curve of a vary over damping is the culprit.
    with pytest.raises(SceneError, match=r"vary\.values\[0\]: .*critical speed"):
        Scene(
            params={**FIG4, "vstar": 0.65},
            outputs={"pressure": OutputSpec("pressure")},
            vary=Vary("damping", (0.0, 0.1)),
        )
    # The Rayleigh speed still bounds a damped solve.
    with pytest.raises(
        SceneError, match=r"params\.vstar: .*Rayleigh speed V\*_R = 0\.8299"
    ):
        Scene.from_toml(
            HEAD.format(vstar=0.9) + "damping = 0.1\n[outputs]\npressure = true\n"
        )


def test_damped_displacement_and_indentation_in_a_scene_match_the_api() -> None:
    """The displacement output and the indentation sweep quantity, once
    refused with damping > 0, now come from the contract's members; a radius
    sweep shares solutions through lambda = R P, so the indentation scales
    with the load (here fixed) and the drag as 1/R."""
    text = (
        HEAD.format(vstar=0.2)
        + "damping = 0.1\n[outputs]\ndisplacement = { points = 7 }\n"
        + '[sweep]\nparam = "radius"\nvalues = [50, 100]\n'
        + 'quantities = ["indentation", "drag"]\n'
    )
    result = Scene.from_toml(text).run()
    curve = result.outputs["displacement"].curves[0]
    s = damped(0.2, 0.1)
    np.testing.assert_allclose(
        curve.y, s.surface_displacement(curve.x), rtol=1e-12, atol=1e-15
    )
    assert result.sweep is not None
    for j, radius in enumerate((50.0, 100.0)):
        direct = mp.solve(vstar=0.2, kw=1.0, radius=radius, load=0.002, damping=0.1)
        ind = result.sweep.data["indentation"][0, j]
        assert ind == pytest.approx(direct.indentation, rel=1e-7)
        assert result.sweep.data["drag"][0, j] == pytest.approx(direct.drag, rel=1e-7)


def test_damping_round_trips_and_stays_out_of_undamped_scenes() -> None:
    scene = Scene(
        params={**FIG4, "damping": 0.25}, outputs={"pressure": OutputSpec("pressure")}
    )
    text = scene.to_toml()
    assert "damping = 0.25" in text
    assert Scene.from_toml(text) == scene
    plain = Scene(params=FIG4, outputs={"pressure": OutputSpec("pressure")})
    assert "damping" not in plain.to_toml()
    assert "damping" not in plain.params
    # Left out of [params], the vary parameter takes its first value.
    varied = Scene.from_toml(
        HEAD.format(vstar=0.2)
        + '[outputs]\npressure = true\n[vary]\nparam = "damping"\nvalues = [0.5, 0.1]\n'
    )
    assert varied.params["damping"] == 0.5
