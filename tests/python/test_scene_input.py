"""Hostile scene input: only regular files are read, within a size and a
nesting cap; a sweep is capped in size and validated in O(1) critical-speed
evaluations (its extremes, by the monotonicity checked here on dense grids);
values that would overflow downstream are refused at validation; ``--dask``
is bounded in time. Each refusal is one line naming the file and the key."""

from __future__ import annotations

import functools
import math
import os
import random
import socket
import subprocess
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import movingpunch as mp
from movingpunch.scene import (
    ClusterError,
    OutputSpec,
    Scene,
    SceneError,
    Sweep,
    _executors,
    _model,
    _toml,
    _validate,
    load_scene,
)
from movingpunch.scene._toml import tomllib
from movingpunch.tui import scene_files

BASE = {"vstar": 0.2, "kw": 1.0, "radius": 100.0, "load": 0.002}
VALID = "[params]\nvstar = 0.2\nkw = 1\nradius = 100\nload = 0.002\n"
LOAD_DEADLINE = 2.0  # hang guard of an in-process load (it takes milliseconds)
CLI_TIMEOUT = 60.0  # hang guard of a CLI subprocess (imports included)


def _load_within_deadline(
    load: Callable[[], object], deadline: float = LOAD_DEADLINE
) -> BaseException:
    """The exception ``load()`` raises, which it must do within ``deadline``
    seconds (run in a thread: a hang fails the test, it does not block the
    suite)."""
    caught: list[BaseException] = []

    def target() -> None:
        try:
            load()
        except BaseException as exc:  # handed to the test
            caught.append(exc)

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    thread.join(deadline)
    assert not thread.is_alive(), f"still loading after {deadline} s"
    assert caught, "no error"
    return caught[0]


@pytest.fixture
def special_files(tmp_path: Path) -> dict[str, Path]:
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    big = tmp_path / "big.toml"
    with big.open("wb") as f:
        f.write(VALID.encode())
        f.write(b"# " + b"x" * (10 * 2**20) + b"\n")  # 10 MiB of comment
    deep_array = tmp_path / "deep_array.toml"
    deep_array.write_text("x = " + "[" * 10**5 + "]" * 10**5 + "\n")
    deep_table = tmp_path / "deep_table.toml"
    deep_table.write_text("x = " + "{a = " * 10**5 + "1" + "}" * 10**5 + "\n")
    folder = tmp_path / "folder.toml"
    folder.mkdir()
    return {
        "dev_zero": Path("/dev/zero"),
        "fifo": fifo,
        "directory": folder,
        "10MiB": big,
        "deep_array": deep_array,
        "deep_table": deep_table,
    }


WHY = {
    "dev_zero": "cannot read a character device",
    "fifo": "cannot read a FIFO",
    "directory": "cannot read a directory",
    "10MiB": "too large",
    "deep_array": "nested more than 32 deep",
    "deep_table": "nested more than 32 deep",
}


@pytest.mark.parametrize("kind", sorted(WHY))
def test_special_files_are_refused_promptly(
    kind: str, special_files: dict[str, Path]
) -> None:
    path = special_files[kind]
    loaders: list[Callable[[Path], object]] = [
        Scene.load,
        load_scene,
        scene_files.load,  # the terminal UI's Open dialog
    ]
    for load in loaders:
        exc = _load_within_deadline(functools.partial(load, path))
        assert isinstance(exc, SceneError), exc
        assert exc.key == "(file)"
        assert str(exc).startswith(f"{path}: (file): {WHY[kind]}"), exc
        assert "\n" not in str(exc)


@pytest.mark.parametrize("kind", sorted(WHY))
def test_cli_refuses_special_files_in_one_line(
    kind: str,
    special_files: dict[str, Path],
    run_cli: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    path = special_files[kind]
    proc = run_cli("run", str(path), timeout=CLI_TIMEOUT)
    assert proc.returncode == 2, proc
    assert proc.stdout == ""
    assert proc.stderr.startswith(f"movingpunch: error: {path}: (file): {WHY[kind]}")
    assert proc.stderr.count("\n") == 1, proc.stderr
    assert proc.stderr.endswith(")\n")  # (allowed: ...)


def test_a_file_at_the_size_cap_is_read(tmp_path: Path) -> None:
    path = tmp_path / "padded.toml"
    text = VALID + "[outputs]\ncontact_width = true\n"
    pad = _model.MAX_SCENE_BYTES - len(text.encode()) - 3
    path.write_text(text + "# " + "x" * pad + "\n", encoding="utf-8")
    assert path.stat().st_size == _model.MAX_SCENE_BYTES
    assert Scene.load(path).params["vstar"] == 0.2
    with path.open("a") as f:
        f.write("\n")
    with pytest.raises(SceneError, match="too large"):
        Scene.load(path)


# -- the nesting scan -------------------------------------------------------------

TRICKY_STRINGS = [
    '"a ] b"',
    '"[[["',
    '"esc \\" ] ["',
    '"back\\\\"',
    "'lit ]] \\'",
    '"""multi\n ] "" [\n"""',
    '"""ends in quotes""""',
    "'''lit\n]]]'''",
    "'''x'''''",
    '"# not a comment ["',
]


def _random_value(rng: random.Random, depth: int) -> str:
    choice = rng.random()
    if depth <= 0 or choice < 0.3:
        return rng.choice(["1", "2.5", "true", *TRICKY_STRINGS])
    n = rng.randint(0, 3)
    if choice < 0.65:
        items = [_random_value(rng, depth - 1) for _ in range(n)]
        return (
            "[" + ", ".join(items) + (" # c ]]\n" if rng.random() < 0.2 else "") + "]"
        )
    items = [f"k{i} = {_random_value(rng, depth - 1)}" for i in range(n)]
    return "{" + ", ".join(items).replace("\n", " ").replace('"""', '"') + "}"


def _object_depth(value: Any) -> int:
    """The nesting of arrays and tables of a parsed TOML value (independent
    of the scan: it walks what tomllib built)."""
    if isinstance(value, dict):
        return 1 + max((_object_depth(v) for v in value.values()), default=0)
    if isinstance(value, list):
        return 1 + max((_object_depth(v) for v in value), default=0)
    return 0


def test_nesting_scan_agrees_with_the_parsed_document() -> None:
    rng = random.Random(12)
    checked = 0
    for _ in range(400):
        lines = [f"v{i} = {_random_value(rng, 6)}" for i in range(rng.randint(1, 4))]
        text = "\n".join(lines) + "\n"
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError:
            continue  # an inline table's string lost its newline: not TOML
        expected = max(_object_depth(v) for v in data.values())
        assert _toml._nesting_depth(text, 1000) == expected, text
        checked += 1
    assert checked > 200


def test_brackets_in_strings_and_comments_do_not_count(tmp_path: Path) -> None:
    text = (
        f'description = "{"[" * 100}"\n'
        f"# {'[' * 100}\n"
        f"name = '''{'{' * 100}'''\n" + VALID + "[outputs]\ncontact_width = true\n"
    )
    path = tmp_path / "strings.toml"
    path.write_text(text, encoding="utf-8")
    assert Scene.load(path).description == "[" * 100


@pytest.mark.parametrize(
    "body",
    [
        '"' + '\\"' * 400_000 + '"',  # a basic string of escaped quotes
        '"""' + '\\"' * 400_000 + '"""',
        "'" + "x" * 900_000 + "'",
        "[" + '"]",' * 200_000 + "]",
    ],
    ids=["escaped-quotes", "multiline-escapes", "long-literal", "many-strings"],
)
def test_the_scan_is_linear_on_hostile_strings(body: str, tmp_path: Path) -> None:
    path = tmp_path / "strings.toml"
    path.write_text(VALID + "[outputs]\ncontact_width = true\nx = " + body + "\n")
    assert path.stat().st_size <= _model.MAX_SCENE_BYTES
    # About 1 s of parsing; a scan quadratic in the text takes minutes.
    exc = _load_within_deadline(functools.partial(Scene.load, path), 5.0)
    assert isinstance(exc, SceneError)
    assert exc.key == "outputs.x"  # parsed whole, then refused as a scene


def test_nesting_at_the_cap_passes_the_scan() -> None:
    n = _model.MAX_NESTING
    text = "x = " + "[" * n + "]" * n + "\n"
    assert _toml._nesting_depth(text, n) == n
    with pytest.raises(SceneError, match=r"^<string>: x: unknown key"):
        Scene.from_toml(text)  # parsed, then refused as a scene
    deeper = "x = " + "[" * (n + 1) + "]" * (n + 1) + "\n"
    with pytest.raises(SceneError, match="nested more than"):
        Scene.from_toml(deeper)


# -- sweeps: size cap and O(1) validation ---------------------------------------


def _sweep_toml(**sweep: object) -> str:
    body = "\n".join(f"{k} = {v!r}".replace("'", '"') for k, v in sweep.items())
    return VALID + "[sweep]\n" + body + "\n"


def test_sweep_points_are_capped() -> None:
    text = _sweep_toml(param="load", start=1e-3, stop=2e-3, points=2_000_001)
    with pytest.raises(SceneError, match=r"sweep\.points: out of range: 2000001"):
        Scene.from_toml(text)


def test_sweep_times_vary_is_capped() -> None:
    text = (
        _sweep_toml(param="load", start=1e-3, stop=2e-3, points=100_001)
        + "[vary]\nparam = 'vstar'\nvalues = ["
        + ", ".join(str(0.01 * i) for i in range(20))
        + "]\n"
    )
    with pytest.raises(
        SceneError, match=r"sweep\.points: 100001 sweep values times 20"
    ):
        Scene.from_toml(text)


class _Counted:
    def __init__(self, f: Callable[..., Any]) -> None:
        self.f, self.calls = f, 0

    def __call__(self, *args: Any) -> Any:
        self.calls += 1
        return self.f(*args)


@pytest.mark.parametrize(
    "sweep",
    [
        {
            "param": "kw",
            "start": 0.5,
            "stop": 50.0,
            "points": 100_000,
            "spacing": "log",
        },
        {"param": "nu", "start": 0.0, "stop": 0.49, "points": 100_000},
        {"param": "vstar", "start": 0.0, "stop": 0.3, "points": 100_000},
        {"param": "damping", "start": 0.0, "stop": 2.0, "points": 100_000},
    ],
    ids=lambda s: s["param"],
)
def test_validating_a_sweep_costs_o1_critical_speeds(
    sweep: dict[str, Any], monkeypatch: pytest.MonkeyPatch
) -> None:
    vcr = _Counted(_validate.critical_speed)
    vr = _Counted(_validate.rayleigh_speed)
    monkeypatch.setattr(_validate, "critical_speed", vcr)
    monkeypatch.setattr(_validate, "rayleigh_speed", vr)
    params = {k: v for k, v in BASE.items() if k != sweep["param"]}
    body = "\n".join(f"{k} = {v}" for k, v in params.items())
    text = "[params]\n" + body + "\n" + _sweep_toml(**sweep).split(VALID, 1)[1]
    scene = Scene.from_toml(text)
    assert scene.sweep is not None
    assert len(scene.sweep.values) == 100_000
    assert vcr.calls + vr.calls <= 4, (vcr.calls, vr.calls)
    explicit = Scene(
        params=scene.params,
        sweep=Sweep(sweep["param"], scene.sweep.values[::-1][:50_000]),
    )
    assert explicit.sweep is not None
    assert vcr.calls + vr.calls <= 12, (vcr.calls, vr.calls)


def test_v_cr_grows_with_kw_and_nu_and_v_r_with_nu() -> None:
    """What checking a sweep's extremes relies on, on dense grids."""
    kws = np.geomspace(1e-12, 1e12, 97)
    nus = np.linspace(0.0, 0.4999, 61)
    for nu in (0.0, 0.2, 0.35, 0.4999):
        v = np.array([mp.critical_vstar(float(k), float(nu)) for k in kws])
        assert np.all(np.diff(v) >= 0.0), nu
        assert v[-1] == pytest.approx(mp.rayleigh_vstar(float(nu)), rel=1e-12)
    for kw in (1e-12, 1e-2, 1.0, 1e3, math.inf):
        v = np.array([mp.critical_vstar(kw, float(nu)) for nu in nus])
        assert np.all(np.diff(v) > 0.0), kw
    vr = np.array([mp.rayleigh_vstar(float(nu)) for nu in nus])
    assert np.all(np.diff(vr) > 0.0)


@pytest.mark.parametrize(
    ("sweep", "key"),
    [
        # vstar = 0.2 is above V*_cr(0.01) = 0.087: the smallest kw fails.
        ({"param": "kw", "start": 1.0, "stop": 0.01, "points": 50}, "sweep.stop"),
        ({"param": "kw", "values": [1.0, 0.01, 10.0]}, "sweep.values[1]"),
        ({"param": "vstar", "values": [0.1, 0.7, 0.2]}, "sweep.values[1]"),
        # vstar 0.6 > V*_cr(1) = 0.57 but < V*_R: only the undamped point fails.
        ({"param": "damping", "values": [0.5, 0.0, 1.0]}, "sweep.values[1]"),
    ],
)
def test_the_failing_extreme_of_a_sweep_is_named(
    sweep: dict[str, Any], key: str
) -> None:
    vstar = 0.6 if sweep["param"] == "damping" else 0.2
    params = {**BASE, "vstar": vstar}
    params.pop(sweep["param"], None)
    body = "\n".join(f"{k} = {v}" for k, v in params.items())
    sw = "\n".join(f"{k} = {v!r}".replace("'", '"') for k, v in sweep.items())
    with pytest.raises(SceneError) as info:
        Scene.from_toml(f"[params]\n{body}\n[sweep]\n{sw}\n")
    assert info.value.key == key, info.value
    assert "critical speed" in str(info.value)


def test_every_point_of_a_sweep_is_below_the_bound_it_checks() -> None:
    """The extremes stand for the whole sweep: a kw sweep accepted by
    validation has vstar < V*_cr at each of its points (dense check)."""
    vcr_lo = mp.critical_vstar(0.3, 0.2)
    vstar = 0.999 * vcr_lo
    scene = Scene(
        params={**BASE, "vstar": vstar},
        sweep=Sweep.range("kw", 0.3, 30.0, 200, spacing="log"),
    )
    assert scene.sweep is not None
    assert all(vstar < mp.critical_vstar(kw, 0.2) for kw in scene.sweep.values)
    with pytest.raises(SceneError, match=r"sweep\.start"):
        Scene(
            params={**BASE, "vstar": 1.001 * vcr_lo},
            sweep=Sweep.range("kw", 0.3, 30.0, 200, spacing="log"),
        )


# -- values that overflow downstream ----------------------------------------------


@pytest.mark.parametrize(
    ("text", "key"),
    [
        (
            VALID + "[outputs]\npressure = { x = [-1e308, 1e308] }\n",
            "outputs.pressure.x",
        ),
        (
            VALID + "[outputs]\ndisplacement = { x = [-1.7e308, 1.7e308] }\n",
            "outputs.displacement.x",
        ),
        (VALID.replace("radius = 100", f"radius = {2**63}"), "params.radius"),
        (VALID.replace("radius = 100", "radius = 1e300"), "params.radius"),
        (VALID.replace("load = 0.002", "load = 1e200"), "params.load"),
        (
            VALID + "[sweep]\nparam = 'radius'\nstart = 1\nstop = 1e13\npoints = 3\n",
            "sweep.stop",
        ),
        (
            VALID + "[vary]\nparam = 'load'\nvalues = [0.002, 2e6]\n",
            "vary.values[1]",
        ),
    ],
)
def test_values_that_overflow_downstream_are_refused(text: str, key: str) -> None:
    if "[outputs]" not in text:
        text += "[outputs]\ncontact_width = true\n"
    with pytest.raises(SceneError) as info:
        Scene.from_toml(text, "scene.toml")
    assert info.value.key == key, info.value
    assert str(info.value).startswith(f"scene.toml: {key}: ")


def test_radius_and_load_limits_are_the_solvers() -> None:
    """The scene's limits are those of the core's validation: the largest
    radius and load solve; the next float up is refused by the solver too."""
    assert mp.solve(vstar=0.0, kw=1.0, radius=_model.RADIUS_MAX, load=1e-13).valid
    assert mp.solve(vstar=0.0, kw=1.0, radius=1e-7, load=_model.LOAD_MAX).valid
    with pytest.raises(mp.InvalidParameterError, match="radius"):
        mp.solve(
            vstar=0.0,
            kw=1.0,
            radius=math.nextafter(_model.RADIUS_MAX, 2e12),
            load=1e-13,
        )
    with pytest.raises(mp.InvalidParameterError, match="load"):
        mp.solve(
            vstar=0.0, kw=1.0, radius=1e-7, load=math.nextafter(_model.LOAD_MAX, 2e6)
        )
    Scene(
        params={**BASE, "radius": _model.RADIUS_MAX, "load": 1e-13},
        outputs={"contact_width": OutputSpec("contact_width")},
    )


# -- Dask ---------------------------------------------------------------------------


@pytest.fixture
def mute_listener() -> Iterator[str]:
    """A TCP listener on loopback that accepts connections and never says a
    word (as a hung scheduler would)."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    accepted: list[socket.socket] = []
    stop = threading.Event()

    def serve() -> None:
        server.settimeout(0.1)
        while not stop.is_set():
            try:
                accepted.append(server.accept()[0])
            except OSError:
                continue

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield f"tcp://127.0.0.1:{server.getsockname()[1]}"
    stop.set()
    thread.join(5)
    for conn in accepted:
        conn.close()
    server.close()


@pytest.mark.needs("dask")
def test_a_mute_scheduler_is_a_clear_error_within_the_timeout(
    mute_listener: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(_executors, "DASK_CONNECT_TIMEOUT", 1.5)
    scene = Scene(params=BASE, sweep=Sweep("load", (0.001, 0.002, 0.003)))
    t0 = time.monotonic()
    with pytest.raises(
        ClusterError, match=r"cannot reach the scheduler .* within 1\.5 s"
    ):
        scene.run(dask=mute_listener)
    assert time.monotonic() - t0 < 10 * 1.5  # hang guard, generous


def test_dask_without_a_sweep_says_so_and_runs_here(
    mute_listener: str, run_cli: Callable[..., subprocess.CompletedProcess[str]]
) -> None:
    proc = run_cli(
        "run", "fig4", "--dask", mute_listener, "--no-plot", timeout=CLI_TIMEOUT
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == (
        "movingpunch: note: --dask: the scene has no [sweep], nothing to "
        "distribute: running here\n"
    )
    assert "a/h" in proc.stdout


def test_a_scheduler_without_workers_is_a_clear_error(
    monkeypatch: pytest.MonkeyPatch, local_cluster: Callable[..., Any]
) -> None:
    monkeypatch.setattr(_executors, "DASK_CONNECT_TIMEOUT", 1.0)
    scene = Scene(params=BASE, sweep=Sweep("load", (0.001, 0.002, 0.003)))
    with local_cluster(n_workers=0, processes=False) as cluster:
        t0 = time.monotonic()
        with pytest.raises(ClusterError, match="has no workers"):
            scene.run(dask=cluster.scheduler_address)
        assert time.monotonic() - t0 < 10 * 1.0  # hang guard, generous
