"""The edit-test loop: scripts/setup.sh reinstalls (and so runs CMake) only
when a C++ build input changed or the Python file list changed; a Python edit
reaches pytest with nothing compiled. The decision is scripts/build_stamp.py,
tested here on a made-up tree and checked against the real CMake inputs."""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import pytest

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "build_stamp.py"


def _load_stamp_module() -> ModuleType:
    spec = importlib.util.spec_from_file_location("build_stamp", SCRIPT)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


stamp = _load_stamp_module()

TREE = {
    "CMakeLists.txt": "project(x)\n",
    "pyproject.toml": "[project]\nname = 'x'\n",
    "README.md": "# x\n",
    "cpp/src/core.cpp": "int f() { return 1; }\n",
    "cpp/include/movingpunch/core.hpp": "int f();\n",
    "cpp/bindings/module.cpp": "// bind\n",
    "tests/cpp/test_core.cpp": "// test\n",
    "tests/python/test_x.py": "def test_x() -> None: ...\n",
    "python/movingpunch/__init__.py": "X = 1\n",
    "python/movingpunch/solver.py": "Y = 2\n",
}


@pytest.fixture
def tree(tmp_path: Path) -> Path:
    for name, text in TREE.items():
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return tmp_path


def _recorded(tree: Path) -> Path:
    path = tree / "stamp"
    path.write_text(stamp.stamp_text(tree), encoding="utf-8")
    return path


CXX = ["C++ build inputs changed"]


@pytest.mark.parametrize(
    ("edit", "needs"),
    [
        ("python/movingpunch/solver.py", []),  # a one-line Python edit
        ("python/movingpunch/__init__.py", []),
        ("tests/python/test_x.py", []),
        ("README.md", []),
        ("cpp/src/core.cpp", CXX),
        ("cpp/include/movingpunch/core.hpp", CXX),
        ("cpp/bindings/module.cpp", CXX),
        ("tests/cpp/test_core.cpp", CXX),
        ("CMakeLists.txt", CXX),
        ("pyproject.toml", CXX),
    ],
)
def test_only_a_cpp_build_input_edit_needs_a_rebuild(
    tree: Path, edit: str, needs: list[str]
) -> None:
    recorded = _recorded(tree)
    with (tree / edit).open("a", encoding="utf-8") as f:
        f.write("one more line\n")
    # Bytecode caches and a compiled module beside the sources do not count.
    (tree / "python/movingpunch/__pycache__").mkdir()
    (tree / "python/movingpunch/__pycache__/solver.cpython-311.pyc").write_bytes(b"x")
    (tree / "python/movingpunch/_core.cpython-311-x86_64-linux-gnu.so").write_bytes(
        b"x"
    )
    assert stamp.stale_parts(tree, recorded) == needs


def test_a_new_cpp_file_needs_a_rebuild(tree: Path) -> None:
    recorded = _recorded(tree)
    (tree / "cpp/src/new.cpp").write_text("int g();\n", encoding="utf-8")
    assert stamp.stale_parts(tree, recorded) == CXX


@pytest.mark.parametrize("change", ["add", "remove", "rename"])
def test_a_python_file_added_or_removed_needs_a_reinstall(
    tree: Path, change: str
) -> None:
    # The editable install records the package's files: re-register them.
    recorded = _recorded(tree)
    solver = tree / "python/movingpunch/solver.py"
    if change == "add":
        (tree / "python/movingpunch/scene").mkdir()
        (tree / "python/movingpunch/scene/__init__.py").write_text("")
    elif change == "remove":
        solver.unlink()
    else:
        solver.rename(solver.with_name("solve.py"))
    assert stamp.stale_parts(tree, recorded) == ["Python files added or removed"]


def test_no_or_broken_stamp_means_install(tree: Path) -> None:
    assert stamp.stale_parts(tree, tree / "missing") == ["no install recorded"]
    (tree / "broken").write_text("garbage\n", encoding="utf-8")
    assert stamp.stale_parts(tree, tree / "broken") == ["no install recorded"]


def test_the_command_setup_runs_says_no_cpp_rebuild_after_a_python_edit(
    tree: Path,
) -> None:
    # The exact command scripts/setup.sh runs, on the made-up tree.
    def check() -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, str(SCRIPT), "--root", str(tree), "check", "st"],
            capture_output=True,
            text=True,
            timeout=60,
            check=False,
            cwd=tree,
        )

    assert check().returncode == 1
    written = subprocess.run(
        [sys.executable, str(SCRIPT), "--root", str(tree), "write", "st"],
        timeout=60,
        check=False,
        cwd=tree,
    )
    assert written.returncode == 0
    (tree / "python/movingpunch/solver.py").write_text("Y = 3\n", encoding="utf-8")
    ok = check()
    assert (ok.returncode, ok.stdout.strip()) == (
        0,
        "no C++ rebuild needed (C++ inputs and Python file list unchanged)",
    )
    (tree / "cpp/src/core.cpp").write_text("int f() { return 2; }\n")
    stale = check()
    assert (stale.returncode, stale.stdout.strip()) == (
        1,
        "reinstall needed: C++ build inputs changed",
    )


def test_the_stamp_covers_every_cmake_input_of_this_repository() -> None:
    # Every file CMake is told about, and every folder it adds or globs, is
    # under a stamped path; no Python source is.
    inputs = {p.relative_to(ROOT).as_posix() for p in stamp.cxx_inputs(ROOT)}
    cmake_text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    named = set(re.findall(r"\b((?:cpp|tests)/[\w./*-]+)", cmake_text))
    assert named, "no source paths found in CMakeLists.txt"
    for entry in named:
        if "*" in entry:
            matched = {p.relative_to(ROOT).as_posix() for p in ROOT.glob(entry)}
            assert matched, entry
            assert matched <= inputs, entry
        elif (ROOT / entry).is_dir():
            assert any(i.startswith(entry + "/") for i in inputs), entry
        else:
            assert entry in inputs, entry
    sub_lists = [ROOT / d / "CMakeLists.txt" for d in stamp.CXX_DIRS]
    assert {p.relative_to(ROOT).as_posix() for p in sub_lists if p.exists()} <= inputs
    headers = {p.relative_to(ROOT).as_posix() for p in ROOT.glob("cpp/**/*.hpp")}
    assert headers
    assert headers <= inputs
    assert not [i for i in inputs if i.startswith("python/")]


def test_setup_installs_the_build_requirements_of_pyproject() -> None:
    # Without build isolation setup.sh installs them itself: the same list.
    with (ROOT / "pyproject.toml").open("rb") as f:
        requires = tomllib.load(f)["build-system"]["requires"]
    setup = (ROOT / "scripts" / "setup.sh").read_text(encoding="utf-8")
    line = next(
        ln
        for ln in setup.splitlines()
        if "pip install" in ln and "scikit" in ln and not ln.lstrip().startswith("#")
    )
    quoted = [q for q in re.findall(r'"([^"]+)"', line) if not q.startswith("$")]
    assert sorted(quoted) == sorted(requires)
