"""Media in scenes (issue 26): ``[[layers]]`` and ``[base]`` read, validated,
written back and run, and the bundled media scenes.

Tests named ``..._stack_...`` solve a real stack, a graded layer or a
half-space base: they need the layered medium of the C++ core and fail
(InvalidParameterError "layered media are not built yet") until it is there.
The others run on one homogeneous sublayer on springs, which solves today.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.errors import SceneError
from movingpunch.media import GradedLayer, HalfSpace, Layer, Medium, Winkler
from movingpunch.scene import OutputSpec, Scene, Sweep, Vary
from movingpunch.scene._export import (
    format_json,
    format_summary,
    read_csv,
    render_outputs,
    write_outputs,
)

# docs/theory.md §11 / the paper's Table 1: a/h of the layer (nu = 0.2) on
# k_w h/mu = 1 at V* = 0, R/h = 100, P/(mu h) = 0.002.
TABLE1_KW1 = 0.330419

HEAD = """
[params]
vstar = 0.0
kw = 1.0
radius = 100.0
load = 0.002
"""
OUTPUTS = """
[outputs]
contact_width = true
"""
ONE_LAYER = """
[[layers]]
thickness = 1.0
nu = 0.2
"""
STACK = """
[[layers]]
kind = "layer"
thickness = 0.25
nu = 0.35

[[layers]]
kind = "graded"
thickness = 0.75
gamma_h = 0.5
mu = 0.1
nu = 0.3
rho = 0.85
"""
HALF_SPACE = """
[base]
kind = "half_space"
mu = 0.1
nu = 0.3
interface = "smooth"
"""


def no_kw(text: str) -> str:
    return text.replace("kw = 1.0\n", "")


# -- reading, writing ----------------------------------------------------------


def test_layers_on_a_half_space_are_read_and_written_back(tmp_path: Path) -> None:
    scene = Scene.from_toml(no_kw(HEAD) + STACK + HALF_SPACE + OUTPUTS)
    assert scene.medium == Medium(
        (
            Layer(0.25, nu=0.35),
            GradedLayer(0.5, nu=0.3, thickness=0.75, mu=0.1, rho=0.85),
        ),
        HalfSpace(0.1, 0.3, interface="smooth"),
    )
    # nu is the top sublayer's; a half-space has no springs.
    assert scene.params == {"vstar": 0.0, "radius": 100.0, "load": 0.002, "nu": 0.35}
    text = scene.to_toml()
    assert "[[layers]]" in text
    assert "[base]" in text
    assert "\nnu = 0.35\n" in text.split("[[layers]]")[1]  # in the layer, not params
    assert "kw" not in text
    assert Scene.from_toml(text) == scene
    path = tmp_path / "s.toml"
    scene.save(path)
    assert Scene.load(path) == dataclasses.replace(scene, name="s")


def test_layers_without_a_base_stand_on_the_springs_of_params() -> None:
    text = HEAD.replace("kw = 1.0", "kw = 2.0\nkp = 0.5") + STACK + OUTPUTS
    scene = Scene.from_toml(text)
    assert scene.medium is not None
    assert scene.medium.base == Winkler(2.0, kp=0.5)
    assert scene.params["kw"] == 2.0
    assert scene.params["kp"] == 0.5
    assert Scene.from_toml(scene.to_toml()) == scene


def test_a_winkler_base_table_is_the_springs_of_params() -> None:
    base = '\n[base]\nkind = "winkler"\nkw = "inf"\nkp = 0.25\n'
    scene = Scene.from_toml(no_kw(HEAD) + STACK + base + OUTPUTS)
    assert scene.medium is not None
    assert scene.medium.base == Winkler(math.inf, kp=0.25)
    assert scene.params["kw"] == math.inf
    assert scene.params["kp"] == 0.25
    assert Scene.from_toml(scene.to_toml()) == scene


def test_a_half_space_under_the_plain_layer_keeps_its_nu() -> None:
    scene = Scene.from_toml(no_kw(HEAD) + "nu = 0.3\n" + HALF_SPACE + OUTPUTS)
    assert scene.medium == Medium(
        (Layer(nu=0.3),), HalfSpace(0.1, 0.3, interface="smooth")
    )
    assert Scene.from_toml(scene.to_toml()) == scene


def test_a_scene_built_in_python_takes_a_medium() -> None:
    medium = Medium((Layer(0.5), Layer(0.5, mu=0.5)), Winkler(3.0))
    params = {"vstar": 0.0, "radius": 100.0, "load": 0.002}
    outputs = {"contact_width": OutputSpec("contact_width")}
    scene = Scene(params=params, outputs=outputs, medium=medium)
    assert scene.params["kw"] == 3.0
    assert scene.params["nu"] == 0.2
    assert Scene.from_toml(scene.to_toml()) == scene
    # The same springs given twice agree; different ones are refused.
    Scene(params={**params, "kw": 3.0}, outputs=outputs, medium=medium)
    with pytest.raises(SceneError, match=r"params\.kw.*differs.*kw = 3"):
        Scene(params={**params, "kw": 2.0}, outputs=outputs, medium=medium)
    with pytest.raises(SceneError, match=r"params\.nu.*together with \[\[layers\]\]"):
        Scene(params={**params, "nu": 0.3}, outputs=outputs, medium=medium)
    with pytest.raises(SceneError, match=r"layers: .*sum to"):
        Scene(
            params=params,
            outputs=outputs,
            medium=Medium((Layer(0.5), Layer(0.4)), Winkler(1.0)),
        )
    with pytest.raises(SceneError, match=r"layers: .*movingpunch.Medium"):
        Scene(params=params, outputs=outputs, medium="two layers")  # type: ignore[arg-type]


# -- refusals: each names the key and what is allowed --------------------------

REFUSED = [
    (HEAD + "nu = 0.2\n" + ONE_LAYER, "params.nu", "give nu in each [[layers]]"),
    (HEAD + HALF_SPACE, "params.kw", "no kw in [params] beside [base]"),
    (
        no_kw(HEAD) + "kp = 0.1\n" + HALF_SPACE,
        "params.kp",
        "no kp in [params] beside [base]",
    ),
    (
        HEAD + '\n[base]\nkind = "winkler"\nkw = 2.0\n',
        "params.kw",
        "no kw in [params] beside [base]",
    ),
    (
        HEAD + "[[layers]]\nthickness = 0.5\n[[layers]]\nthickness = 0.4\n",
        "layers",
        "thicknesses summing to 1",
    ),
    (
        HEAD + "[[layers]]\nthickness = 1.0\nmu = 2.0\n",
        "layers[0]",
        "mu = rho = 1 for the top sublayer",
    ),
    (
        HEAD + "[[layers]]\nthickness = 1.0\ndensity = 2.0\n",
        "layers[0].density",
        "kind, thickness, mu, nu, rho",
    ),
    (
        HEAD + '[[layers]]\nkind = "graded"\nthickness = 1.0\n',
        "layers[0].gamma_h",
        "gamma_h",
    ),
    (
        HEAD + '[[layers]]\nkind = "foam"\nthickness = 1.0\n',
        "layers[0].kind",
        "layer, graded",
    ),
    (
        HEAD + "[[layers]]\nthickness = 0.5\n[[layers]]\nthickness = 0.5\nnu = 0.5\n",
        "layers[1].nu",
        "0 <= nu < 0.5",
    ),
    (HEAD + "layers = 3\n", "params.layers", "unknown key"),
    (HEAD.replace("[params]", "layers = 3\n[params]"), "layers", "list of tables"),
    (no_kw(HEAD) + '\n[base]\nkind = "rock"\n', "base.kind", "winkler, half_space"),
    (no_kw(HEAD) + "\n[base]\nmu = 0.1\n", "base.kind", "missing"),
    (
        no_kw(HEAD) + HALF_SPACE.replace('"smooth"', '"glued"'),
        "base.interface",
        "bonded, smooth",
    ),
    (
        no_kw(HEAD) + HALF_SPACE + "stiffness = 1.0\n",
        "base.stiffness",
        "kind, mu, nu, rho, interface",
    ),
    (no_kw(HEAD) + '\n[base]\nkind = "half_space"\nmu = 0.1\n', "base.nu", "nu"),
    (
        HEAD + ONE_LAYER + '\n[vary]\nparam = "nu"\nvalues = [0.1, 0.3]\n',
        "vary.param",
        "nu cannot vary beside [[layers]]",
    ),
    (
        no_kw(HEAD) + HALF_SPACE + '\n[sweep]\nparam = "kw"\nvalues = [1.0, 2.0]\n',
        "sweep.param",
        "kw cannot vary under a half-space",
    ),
    (
        no_kw(HEAD) + HALF_SPACE + '\n[vary]\nparam = "kp"\nvalues = [1.0, 2.0]\n',
        "vary.param",
        "kp cannot vary under a half-space",
    ),
    (
        HEAD + STACK + "[outputs]\ncritical_speed = true\n"
        '[vary]\nparam = "damping"\nvalues = [0.0, 0.1]\n',
        "vary.param",
        "damping cannot vary beside this medium",
    ),
    (
        HEAD + "damping = 0.1\n" + STACK,
        "params.damping",
        "damping = 0 beside [[layers]]",
    ),
    (
        no_kw(HEAD) + HALF_SPACE + "[outputs]\ncritical_speed = { kw = [0.1, 10.0] }\n",
        "outputs.critical_speed.kw",
        "no kw range beside a half-space",
    ),
]


@pytest.mark.parametrize(
    ("text", "key", "allowed"),
    REFUSED,
    ids=[f"{i}-{r[1]}" for i, r in enumerate(REFUSED)],
)
def test_a_medium_scene_is_refused_naming_the_key(
    text: str, key: str, allowed: str
) -> None:
    if "[outputs]" not in text:
        text += OUTPUTS
    with pytest.raises(SceneError) as info:
        Scene.from_toml(text, "s.toml")
    assert info.value.key == key, str(info.value)
    assert allowed in str(info.value), str(info.value)


def test_punches_under_a_half_space_run_on_the_medium() -> None:
    """[[punches]] beside a half-space [base] (refused before): the scene
    runs the train on its medium, each punch's contact that of the API's
    train (test_media_asymmetric.py anchors the train itself)."""
    text = (
        no_kw(HEAD).replace("radius = 100.0\nload = 0.002\n", "")
        + STACK
        + HALF_SPACE
        + "[[punches]]\nload = 0.002\nradius = 100.0\n"
        + "[[punches]]\nload = 0.002\nradius = 100.0\nat = 4.0\n"
        + OUTPUTS
    )
    scene = Scene.from_toml(text, "s.toml")
    assert scene.medium is not None
    assert len(scene.punches) == 2
    result = scene.run()
    assert result.outputs


IDENTICAL = """
[[layers]]
thickness = 0.4
nu = 0.2

[[layers]]
thickness = 0.6
nu = 0.2
"""


@pytest.mark.parametrize(
    "extra",
    [
        "friction = 0.3\n",
        "",  # a train (below)
    ],
    ids=["friction", "train"],
)
def test_friction_and_trains_on_identical_sublayers_are_the_layer(extra: str) -> None:
    """Friction and a train of punches run on a layered medium in a scene
    (the asymmetric solver reads the medium); two identical sublayers give
    the homogeneous layer's contact (the anchor: one material, cut in two)."""
    if extra:
        head = HEAD.replace("vstar = 0.0", "vstar = 0.1") + extra
        punches = ""
    else:
        head = HEAD.replace("radius = 100.0\nload = 0.002\n", "")
        punches = (
            "[[punches]]\nload = 0.002\nradius = 100.0\n"
            "[[punches]]\nload = 0.002\nradius = 100.0\nat = 3.0\n"
        )
    stack = Scene.from_toml(head + IDENTICAL + punches + OUTPUTS)
    plain = Scene.from_toml(head + "nu = 0.2\n" + punches + OUTPUTS)
    got = stack.run().outputs["contact_width"].columns
    want = plain.run().outputs["contact_width"].columns
    for name in ("contact_start", "contact_end", "drag"):
        np.testing.assert_allclose(got[name], want[name], rtol=1e-8, atol=1e-12)
    if extra:
        # friction: an asymmetric contact, with a drag of its own
        assert float(got["drag"][0]) != 0.0
        assert float(got["contact_start"][0]) != -float(got["contact_end"][0])


# -- runs that solve today: one homogeneous sublayer on springs ----------------


def test_the_layer_given_as_layers_is_the_paper_layer(tmp_path: Path) -> None:
    """One [[layers]] table on the springs of [params] is the paper's layer:
    Table 1's a/h, and the plain scene's every number."""
    with_layers = Scene.from_toml(HEAD + ONE_LAYER + OUTPUTS + "pressure = true\n")
    plain = Scene.from_toml(HEAD + "nu = 0.2\n" + OUTPUTS + "pressure = true\n")
    assert with_layers.medium is not None
    assert with_layers.medium.homogeneous
    got, want = with_layers.run(), plain.run()
    a = float(got.outputs["contact_width"].columns["a"][0])
    assert a == pytest.approx(TABLE1_KW1, abs=1e-6)
    for kind in ("contact_width", "pressure"):
        for name, column in want.outputs[kind].columns.items():
            np.testing.assert_array_equal(got.outputs[kind].columns[name], column)
    assert "medium: layer h_i/h = 1, mu 1, nu 0.2, rho 1 on kw = 1" in format_summary(
        got
    )
    assert '"medium"' in format_json(got)
    files = dict(render_outputs(got))
    assert "# medium: layer h_i/h = 1" in files["scene-contact_width.csv"].decode()
    written = write_outputs(got, tmp_path)
    meta, _ = read_csv(next(p for p in written if p.name.endswith("width.csv")))
    assert meta["scene"] == with_layers  # the medium comes back from the file


def test_a_sweep_over_the_springs_under_layers_is_the_plain_sweep() -> None:
    """A sweep over kw with [[layers]] changes the springs of each point (the
    worker tasks carry the medium); it equals the plain scene's sweep."""
    sweep = Sweep("kw", (0.1, 1.0, 10.0), ("a", "p0", "critical_vstar"))
    medium = Medium((Layer(nu=0.3),), Winkler(0.1))
    params = {"vstar": 0.2, "radius": 100.0, "load": 0.002}
    layered = Scene(params={**params}, sweep=sweep, medium=medium)
    plain = Scene(params={**params, "kw": 0.1, "nu": 0.3}, sweep=sweep)
    got, want = layered.run(), plain.run()
    assert got.sweep is not None
    assert want.sweep is not None
    for q in sweep.quantities:
        np.testing.assert_array_equal(got.sweep.data[q], want.sweep.data[q])
    # V*_cr grows with kw (a stiffer foundation): the three springs were used.
    vcr = got.sweep.data["critical_vstar"][0]
    assert vcr[0] < vcr[1] < vcr[2]


def test_a_vary_over_kw_under_one_layer_runs_each_spring() -> None:
    scene = Scene(
        params={"vstar": 0.0, "radius": 100.0, "load": 0.002},
        outputs={"contact_width": OutputSpec("contact_width")},
        vary=Vary("kw", (1.0, math.inf)),
        medium=Medium((Layer(),), Winkler(1.0)),
    )
    a = scene.run().outputs["contact_width"].columns["a"]
    # Table 1 at V* = 0: kw = 1 and the rigid base.
    np.testing.assert_allclose(a, [TABLE1_KW1, 0.311557], atol=1e-6)


# -- the bundled scenes ----------------------------------------------------------

MEDIA_SCENES = ("pavement", "graded-coating", "half-space-vs-winkler")


@pytest.mark.parametrize("name", MEDIA_SCENES)
def test_the_bundled_media_scenes_load(name: str) -> None:
    scenes = mp.bundled_scenes()
    assert name in scenes
    assert scenes[name]
    scene = Scene.bundled(name)
    assert scene.medium is not None
    assert not scene.medium.homogeneous
    assert Scene.from_toml(scene.to_toml()) == scene


def test_the_bundled_media_are_what_they_say() -> None:
    pavement = Scene.bundled("pavement").medium
    assert pavement is not None
    assert [s.thickness for s in pavement.layers] == [0.25, 0.75]
    assert pavement.layers[1].mu == 0.1
    assert isinstance(pavement.base, Winkler)
    graded = Scene.bundled("graded-coating").medium
    assert graded is not None
    assert isinstance(graded.layers[0], Layer)
    assert isinstance(graded.layers[1], GradedLayer)
    assert graded.base == Winkler(1.0)
    half = Scene.bundled("half-space-vs-winkler").medium
    assert half == Medium((Layer(),), HalfSpace(0.1, 0.3, interface="smooth"))


# -- runs that need the stack medium of the core -------------------------------


def _pressure_checks(result: object, load_norm: float = 1.0) -> None:
    """int p dx/(P) = 1 and p >= 0 on each curve of a pressure output."""
    out = result.outputs["pressure"]  # type: ignore[attr-defined]
    for curve in out.curves:
        x, p = np.asarray(curve.x), np.asarray(curve.y)
        assert np.all(p >= -1e-9 * np.max(p))
        inside = p > 0
        # p ~ sqrt(a^2 - x^2): the trapezoid's error is O(dx^1.5).
        assert np.trapezoid(p[inside], x[inside]) == pytest.approx(load_norm, rel=5e-3)


def test_identical_sublayers_stack_give_the_paper_layer() -> None:
    """Two identical bonded sublayers are the homogeneous layer (Table 1)."""
    scene = Scene.from_toml(
        HEAD
        + "[[layers]]\nthickness = 0.4\n[[layers]]\nthickness = 0.6\n"
        + OUTPUTS
        + "pressure = true\n"
    )
    result = scene.run()
    a = float(result.outputs["contact_width"].columns["a"][0])
    assert a == pytest.approx(TABLE1_KW1, abs=1e-6)
    _pressure_checks(result)


def test_pavement_stack_runs_with_the_pressure_balanced() -> None:
    scene = dataclasses.replace(
        Scene.bundled("pavement"),
        outputs={
            "contact_width": OutputSpec("contact_width"),
            "pressure": OutputSpec("pressure", points=401),
        },
        vary=Vary("vstar", (0.0, 0.001)),
    )
    result = scene.run()
    _pressure_checks(result)
    a = result.outputs["contact_width"].columns["a"]
    assert np.all(np.isfinite(a))
    assert np.all(a > 0)
    medium = scene.medium
    assert medium is not None
    direct = mp.solve(
        vstar=0.0,
        radius=100.0,
        load=0.002,
        layers=list(medium.layers),
        base=medium.base,
        tol=scene.tol,
    )
    assert a[0] == direct.a


def test_graded_coating_stack_tends_to_the_homogeneous_layer() -> None:
    """gamma h -> 0 is the paper's layer (Table 1); gamma h = 1 (softer with
    depth) sinks more: a wider contact."""
    scene = Scene.bundled("graded-coating")
    assert scene.medium is not None
    coat = scene.medium.layers[0]
    near = Medium((coat, GradedLayer(1e-9, nu=0.2, thickness=0.95)), scene.medium.base)
    flat = dataclasses.replace(scene, medium=near, vary=Vary("vstar", (0.0,)))
    a0 = float(flat.run().outputs["contact_width"].columns["a"][0])
    assert a0 == pytest.approx(TABLE1_KW1, abs=1e-6)
    graded = dataclasses.replace(scene, vary=Vary("vstar", (0.0,)))
    a1 = float(graded.run().outputs["contact_width"].columns["a"][0])
    assert a1 > a0


def test_half_space_stack_scene_runs() -> None:
    scene = dataclasses.replace(
        Scene.bundled("half-space-vs-winkler"),
        outputs={
            "contact_width": OutputSpec("contact_width"),
            "pressure": OutputSpec("pressure", points=401),
        },
    )
    result = scene.run()
    _pressure_checks(result)
    assert "smooth half-space" in format_summary(result)


def test_a_sweep_on_a_half_space_stack_solves_each_point_on_it() -> None:
    """The sweep's tasks carry the medium (no springs under a half-space):
    each point is the API's solve on that medium."""
    scene = dataclasses.replace(
        Scene.bundled("half-space-vs-winkler"),
        outputs={},
        vary=None,
        sweep=Sweep("vstar", (0.0, 0.02), ("a", "p0")),
    )
    table = scene.run().sweep
    assert table is not None
    medium = scene.medium
    assert medium is not None
    for j, vstar in enumerate((0.0, 0.02)):
        direct = mp.solve(
            vstar=vstar,
            radius=100.0,
            load=0.002,
            layers=list(medium.layers),
            base=medium.base,
            tol=scene.tol,
        )
        assert table.data["a"][0, j] == direct.a
        assert table.data["p0"][0, j] == direct.p0
