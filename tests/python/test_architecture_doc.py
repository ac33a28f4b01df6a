"""docs/architecture.md's map names every layer and module that exists.

The Python part follows ``LAYERS`` of test_layering.py (which the import
graph is checked against): each layer has a line of its own, in that order,
and its modules are named in its part of the map. The C++ part names every
source file, header and binding of the core. A module added without a place
on the map fails here.
"""

from __future__ import annotations

import re
from pathlib import Path

from test_layering import LAYERS

ROOT = Path(__file__).resolve().parents[2]


def _map() -> str:
    """The map: the fenced block that starts with the C++ layer."""
    text = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    start = text.index("```\nC++")
    return text[start : text.index("```", start + 3)]


def _words(text: str) -> set[str]:
    return set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", text))


def test_the_map_names_every_python_layer_and_its_modules() -> None:
    block = _map()
    py = block[block.index("\nPy ") :]
    starts = []
    at = 0
    for name, _ in LAYERS:
        # A layer's line: its name, then ":" or a column gap ("scene model:"
        # is not the line of "scene").
        found = re.compile(rf"^\s*{re.escape(name)}(:\s|\s\s)", re.M).search(py, at)
        assert found is not None, f"layer {name!r} has no line of its own (in order)"
        starts.append(found.start())
        at = found.end()
    starts.append(len(py))
    for (name, members), lo, hi in zip(LAYERS, starts, starts[1:], strict=False):
        words = _words(py[lo:hi])
        for module in sorted(members):
            last = module.rpartition(".")[2]
            assert last in words, f"{module} is not named in layer {name!r}"


def test_the_map_names_every_core_file() -> None:
    block = _map()
    words = _words(block[: block.index("\nPy ")])
    files = [
        *(ROOT / "cpp" / "src").glob("*.[ch]pp"),
        *(ROOT / "cpp" / "include" / "movingpunch").glob("*.hpp"),
        *(ROOT / "cpp" / "bindings").glob("*.[ch]pp"),
    ]
    assert len(files) > 20
    missing = sorted({f.stem for f in files} - words)
    assert missing == [], f"C++ files the map does not name: {missing}"
