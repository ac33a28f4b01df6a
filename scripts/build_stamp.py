"""Decide whether scripts/setup.sh must (re)install movingpunch into .venv.

The package is installed editable (scikit-build-core, persistent build folder
build/<cache_tag>): Python files are served from python/movingpunch, so editing
one needs nothing. Only two things need `pip install -e`:

* a C++ build input changed (cpp/, tests/cpp/, CMakeLists.txt, pyproject.toml):
  the install runs CMake in the kept build folder, which recompiles only what
  changed (ninja);
* the set of Python files changed (a module added, removed or renamed): the
  editable install records which files make up the package, so it is
  re-registered (CMake then finds nothing to compile).

Usage (stdlib only, any Python >= 3.8; --root defaults to this repository):
    python scripts/build_stamp.py [--root DIR] check STAMP   exit 0 if current
    python scripts/build_stamp.py [--root DIR] write STAMP   record the state
    python scripts/build_stamp.py [--root DIR] show          print the digests
"""

from __future__ import annotations

import hashlib
import sys
from pathlib import Path

#: Files and folders whose contents the compiled extension and the C++ tests
#: are built from (relative to the repository root).
CXX_FILES = ("CMakeLists.txt", "pyproject.toml")
CXX_DIRS = ("cpp", "tests/cpp")
#: The Python package served by the editable install: only its file *list*
#: matters, never the contents.
PY_DIR = "python/movingpunch"
_SKIP_PARTS = {"__pycache__"}


def _files_under(root: Path, rel: str) -> list[Path]:
    base = root / rel
    if not base.is_dir():
        return []
    return [
        p
        for p in base.rglob("*")
        if p.is_file() and not _SKIP_PARTS.intersection(p.relative_to(root).parts)
    ]


def cxx_inputs(root: Path) -> list[Path]:
    """Every file a change to which needs CMake to run again, sorted."""
    files = [root / f for f in CXX_FILES if (root / f).is_file()]
    for d in CXX_DIRS:
        files += _files_under(root, d)
    return sorted(files)


def python_layout(root: Path) -> list[str]:
    """The Python package's files (relative paths), without compiled modules."""
    return sorted(
        p.relative_to(root).as_posix()
        for p in _files_under(root, PY_DIR)
        if p.suffix not in {".so", ".pyd", ".pyc"}
    )


def cxx_digest(root: Path) -> str:
    h = hashlib.sha256()
    for p in cxx_inputs(root):
        h.update(p.relative_to(root).as_posix().encode() + b"\0")
        h.update(hashlib.sha256(p.read_bytes()).digest())
    return h.hexdigest()


def layout_digest(root: Path) -> str:
    return hashlib.sha256("\n".join(python_layout(root)).encode()).hexdigest()


def stamp_text(root: Path) -> str:
    return f"cxx {cxx_digest(root)}\npython-files {layout_digest(root)}\n"


def stale_parts(root: Path, stamp: Path) -> list[str]:
    """What changed since STAMP was written: [] when nothing needs a reinstall."""
    try:
        old = dict(line.split(" ", 1) for line in stamp.read_text().splitlines())
    except (OSError, ValueError):
        return ["no install recorded"]
    why = []
    if old.get("cxx") != cxx_digest(root):
        why.append("C++ build inputs changed")
    if old.get("python-files") != layout_digest(root):
        why.append("Python files added or removed")
    return why


def main(argv: list[str]) -> int:
    root = Path(__file__).resolve().parent.parent
    if argv[:1] == ["--root"] and len(argv) >= 2:
        root, argv = Path(argv[1]), argv[2:]
    if argv[:1] == ["show"]:
        sys.stdout.write(stamp_text(root))
        return 0
    if len(argv) != 2 or argv[0] not in {"check", "write"}:
        sys.stderr.write(__doc__ or "")
        return 2
    stamp = Path(argv[1])
    if argv[0] == "write":
        stamp.write_text(stamp_text(root))
        return 0
    why = stale_parts(root, stamp)
    if why:
        print("reinstall needed: " + "; ".join(why))
        return 1
    print("no C++ rebuild needed (C++ inputs and Python file list unchanged)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
