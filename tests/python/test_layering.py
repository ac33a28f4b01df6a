"""Architecture: every module of movingpunch sits in a declared layer and
imports only from its own layer or the ones below; the numerical modules never
import Textual; the compiled core releases the GIL while it computes (what
keeps a UI responsive).

The layers, lowest first (``LAYERS`` below; a module may import modules of its
own layer or of lower layers, never a higher one, and no import cycle may form).
docs/architecture.md lists the same layers with the same modules, in the same
order (``test_architecture_doc_lists_the_layers`` compares them):

1. ``errors``: the exception family (imports nothing of movingpunch).
   ``params``: the table of parameter specs (pure Python, on ``errors``).
2. ``core``: the compiled extension ``movingpunch._core``.
3. ``helpers``: pure-Python numerics and files on top of the core results:
   ``fields`` (stress fields), ``peaks`` (peak search), ``profiles`` (the
   punch shapes), ``outputs`` (writing result files), ``contract`` (the result
   contract every solution satisfies), ``regime`` (plausibility hints),
   ``_evaluate`` (checking inputs and evaluating at points), ``_version``
   (the package version, read without importing the package), ``_display``
   (how a number is shown: round-off as 0), ``_textplot`` (text plots where
   no curve hides another) and ``cancel`` (cancellation tokens bound to a
   thread).
4. ``evaluations``: what every solution computes alike (``_evaluations``).
   ``zones``: several contact zones and trains of punches (``zones``: the
   contact-set search and the superposed result, on the core and the shared
   evaluations; ``solver.solve`` and ``solver.solve_punches`` call it).
   ``solve``: the solves, ``solver`` and ``asymmetric`` (neither imports the
   other at module level; ``solver.solve`` hands damping, friction and
   asymmetric profiles to ``asymmetric``); ``damped``, the deprecated old
   name of ``asymmetric``, only re-exports it.
5. ``scene``: scene files, their runs and exports (``movingpunch.scene.*``), in
   three sub-layers: the model (the parts, validation, TOML reading and
   writing, the bundled files), the run (results, solving points, the sweep's
   plan, the executors, the output evaluators, the run), and ``Scene`` with its
   exports and the package's public names.
6. ``api``: the package itself (``movingpunch/__init__.py``, the public names).
7. ``accuracy``: convergence studies of a scene (``movingpunch.accuracy``).
8. ``tui``: the Textual app, in four sub-layers: its model (plain Python, what
   the workers compute), its widgets, its screens, the app and its entry points.
9. ``cli``: the command line, which dispatches to everything (``cli``,
   ``__main__``).

Every import counts: at module level, inside a function (lazy) or under
``TYPE_CHECKING``, since each is a dependency a reader must follow. The graph
is read from the source files (``ast``), so the test needs no import. A module
missing from ``LAYERS`` fails the test (no module escapes), and so does a stale
entry. No import cycle is allowed, within a layer either.
"""

from __future__ import annotations

import ast
import subprocess
import sys
import threading
from collections.abc import Callable, Iterator
from pathlib import Path

import movingpunch as mp
from movingpunch import _core

PACKAGE = "movingpunch"
SOURCE = Path(__file__).resolve().parents[2] / "python" / PACKAGE

_SCENE = "movingpunch.scene"
_TUI = "movingpunch.tui"
LAYERS: tuple[tuple[str, frozenset[str]], ...] = (
    ("errors", frozenset({"movingpunch.errors"})),
    ("params", frozenset({"movingpunch.params"})),
    ("core", frozenset({"movingpunch._core"})),
    (
        "helpers",
        frozenset(
            {
                "movingpunch.fields",
                "movingpunch.peaks",
                "movingpunch.profiles",
                "movingpunch.media",
                "movingpunch.outputs",
                "movingpunch.contract",
                "movingpunch.regime",
                "movingpunch._evaluate",
                "movingpunch._version",
                "movingpunch._display",
                "movingpunch._textplot",
                "movingpunch.cancel",
            }
        ),
    ),
    ("evaluations", frozenset({"movingpunch._evaluations"})),
    ("zones", frozenset({"movingpunch.zones"})),
    (
        "solve",
        frozenset(
            {"movingpunch.solver", "movingpunch.asymmetric", "movingpunch.damped"}
        ),
    ),
    (
        "scene model",
        frozenset(
            {
                f"{_SCENE}._model",
                f"{_SCENE}._validate",
                f"{_SCENE}._toml",
                f"{_SCENE}._bundled",
            }
        ),
    ),
    (
        "scene run",
        frozenset(
            {
                f"{_SCENE}._result",
                f"{_SCENE}._solve",
                f"{_SCENE}._plan",
                f"{_SCENE}._executors",
                f"{_SCENE}._outputs",
                f"{_SCENE}._run",
            }
        ),
    ),
    (
        "scene",
        frozenset({_SCENE, f"{_SCENE}._scene", f"{_SCENE}._export"}),
    ),
    ("api", frozenset({"movingpunch"})),
    ("accuracy", frozenset({"movingpunch.accuracy"})),
    (
        "tui model",
        frozenset(
            {
                f"{_TUI}.model",
                f"{_TUI}.paths",
                f"{_TUI}.messages",
                f"{_TUI}.scene_files",
            }
        ),
    ),
    (
        "tui widgets",
        frozenset(
            {
                f"{_TUI}.widgets",
                f"{_TUI}.widgets.accuracy",
                f"{_TUI}.widgets.fields",
                f"{_TUI}.widgets.params",
                f"{_TUI}.widgets.plots",
            }
        ),
    ),
    (
        "tui screens",
        frozenset(
            {
                f"{_TUI}.screens",
                f"{_TUI}.screens.help",
                f"{_TUI}.screens.main",
                f"{_TUI}.screens.prompts",
                f"{_TUI}.screens.medium",
            }
        ),
    ),
    (
        "tui app",
        frozenset(
            {
                _TUI,
                f"{_TUI}.app",
                f"{_TUI}.__main__",
                f"{_TUI}.serve",
                f"{_TUI}.screenshots",
            }
        ),
    ),
    (
        "cli",
        frozenset(
            {"movingpunch.cli", "movingpunch._cli_media", "movingpunch.__main__"}
        ),
    ),
)


def source_modules() -> dict[str, Path]:
    """Every module of the package: dotted name -> file (``_core``: its stub)."""
    modules: dict[str, Path] = {}
    for path in sorted(SOURCE.rglob("*.py*")):
        if path.suffix not in {".py", ".pyi"} or "__pycache__" in path.parts:
            continue
        parts = (PACKAGE, *path.relative_to(SOURCE).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        name = ".".join(parts)
        if path.suffix == ".pyi" and (
            name in modules or path.with_suffix(".py").exists()
        ):
            continue  # a stub beside its source: the source counts
        modules[name] = path
    return modules


def _resolve(name: str, modules: dict[str, Path]) -> str:
    """The module an import of ``name`` depends on: the longest known prefix."""
    while name not in modules:
        name = name.rpartition(".")[0]
    return name


def package_imports(module: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """The package modules that ``module`` imports anywhere in its file."""
    is_package = path.name.startswith("__init__.")
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == PACKAGE:
                    found.add(_resolve(alias.name, modules))
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = module.split(".")
                if not is_package:
                    anchor = anchor[:-1]
                anchor = anchor[: len(anchor) - (node.level - 1)]
                base = ".".join([*anchor, base] if base else anchor)
            if base.split(".")[0] != PACKAGE:
                continue
            for alias in node.names:
                target = f"{base}.{alias.name}"
                found.add(target if target in modules else _resolve(base, modules))
    found.discard(module)
    return found


def import_graph() -> dict[str, set[str]]:
    modules = source_modules()
    return {m: package_imports(m, p, modules) for m, p in modules.items()}


def cycles(graph: dict[str, set[str]]) -> set[frozenset[str]]:
    """The strongly connected groups of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    groups: set[frozenset[str]] = set()

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                group.add(w)
                if w == v:
                    break
            if len(group) > 1:
                groups.add(frozenset(group))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return groups


def layer_of() -> dict[str, int]:
    ranks: dict[str, int] = {}
    for rank, (_, members) in enumerate(LAYERS):
        for m in members:
            assert m not in ranks, f"{m} is in two layers"
            ranks[m] = rank
    return ranks


def upward_imports(graph: dict[str, set[str]]) -> Iterator[str]:
    ranks = layer_of()
    for module, targets in sorted(graph.items()):
        for target in sorted(targets):
            if module not in ranks or target not in ranks:
                continue  # test_every_module_has_a_layer reports it
            if ranks[target] <= ranks[module]:
                continue
            yield (
                f"{module} ({LAYERS[ranks[module]][0]}) imports {target} "
                f"({LAYERS[ranks[target]][0]}), a higher layer"
            )


def test_every_module_has_a_layer() -> None:
    modules = set(source_modules())
    declared = set(layer_of())
    assert modules - declared == set(), "modules missing from LAYERS"
    assert declared - modules == set(), "LAYERS names modules that do not exist"


def test_imports_go_down_the_layers() -> None:
    graph = import_graph()
    assert list(upward_imports(graph)) == []


def test_no_import_cycles() -> None:
    # Within a layer modules may import each other, but never in a circle:
    # lazy and TYPE_CHECKING imports count too.
    assert cycles(import_graph()) == set()


def test_the_graph_reader_sees_every_kind_of_import(tmp_path: Path) -> None:
    # The reader itself, on a made-up package: absolute, relative, lazy and
    # TYPE_CHECKING imports, a name imported from a package (an edge to the
    # package) and a submodule imported from one (an edge to the submodule).
    pkg = tmp_path / PACKAGE
    (pkg / "sub").mkdir(parents=True)
    files = {
        "__init__.py": "from movingpunch.low import X\n",
        "low.py": "X = 1\n",
        "sub/__init__.py": "from . import leaf\n",
        "sub/leaf.py": (
            "from typing import TYPE_CHECKING\n"
            "if TYPE_CHECKING:\n    from ..low import X\n"
            "def f():\n    import movingpunch.top\n"
        ),
        "top.py": "from movingpunch.sub import leaf\nfrom movingpunch import X\n",
    }
    for name, text in files.items():
        (pkg / name).write_text(text, encoding="utf-8")
    modules = {
        ".".join((PACKAGE, *Path(n).with_suffix("").parts)).removesuffix(
            ".__init__"
        ): pkg / n
        for n in files
    }
    graph = {m: package_imports(m, p, modules) for m, p in modules.items()}
    assert graph == {
        "movingpunch": {"movingpunch.low"},
        "movingpunch.low": set(),
        "movingpunch.sub": {"movingpunch.sub.leaf"},
        "movingpunch.sub.leaf": {"movingpunch.low", "movingpunch.top"},
        "movingpunch.top": {"movingpunch.sub.leaf", "movingpunch"},
    }
    assert cycles(graph) == {frozenset({"movingpunch.sub.leaf", "movingpunch.top"})}


ARCHITECTURE = SOURCE.parents[1] / "docs" / "architecture.md"


def documented_layers(text: str) -> list[tuple[str, list[str]]]:
    """The Python layer list of docs/architecture.md: (layer, modules) in
    the order written. It is the code block's lines after the one starting
    ``Py``: a layer is a line indented by exactly 5 spaces, ``layer:
    modules`` (names below ``movingpunch.``; ``movingpunch``: the package),
    the modules ending at two spaces or the line's end and continued on the
    next line while the list ends with a comma; deeper lines describe."""
    lines = text.splitlines()
    start = next((i for i, line in enumerate(lines) if line.startswith("Py ")), None)
    assert start is not None, "docs/architecture.md has no 'Py ' layer list"
    end = lines.index("```", start)
    layers: list[tuple[str, list[str]]] = []
    i = start + 1
    while i < end:
        line = lines[i]
        i += 1
        if not line.startswith("     ") or line.startswith("      "):
            continue  # a description or the heading's continuation
        name, colon, rest = line[5:].partition(": ")
        assert colon, f"docs/architecture.md: not 'layer: modules': {line!r}"
        listed = rest.split("  ")[0].strip()
        while listed.endswith(",") and i < end:
            listed += " " + lines[i].strip().split("  ")[0]
            i += 1
        modules = [m.strip() for m in listed.split(",") if m.strip()]
        layers.append((name.strip(), modules))
    return layers


def _full_name(module: str) -> str:
    return module if module == PACKAGE else f"{PACKAGE}.{module}"


def layer_differences(
    documented: list[tuple[str, list[str]]],
    table: tuple[tuple[str, frozenset[str]], ...],
) -> list[str]:
    """Every difference between the documented layers and ``table``, one
    sentence each (empty: they agree)."""
    out: list[str] = []
    doc_names = [name for name, _ in documented]
    table_names = [name for name, _ in table]
    for name in sorted(set(table_names) - set(doc_names)):
        out.append(f"layer {name!r} is in LAYERS, not in docs/architecture.md")
    for name in sorted(set(doc_names) - set(table_names)):
        out.append(f"layer {name!r} is in docs/architecture.md, not in LAYERS")
    both = [n for n in doc_names if n in table_names]
    if both != [n for n in table_names if n in doc_names]:
        out.append(
            f"the layers' order differs: docs/architecture.md {doc_names}, "
            f"LAYERS {table_names}"
        )
    doc_layer: dict[str, str] = {}
    for name, modules in documented:
        for m in modules:
            full = _full_name(m)
            if full in doc_layer:
                out.append(f"{full} is listed twice in docs/architecture.md")
            doc_layer[full] = name
    table_layer = {m: name for name, members in table for m in members}
    for m in sorted(set(table_layer) - set(doc_layer)):
        out.append(
            f"{m} (layer {table_layer[m]!r} in LAYERS) is missing from "
            "docs/architecture.md"
        )
    for m in sorted(set(doc_layer) - set(table_layer)):
        out.append(
            f"{m} (layer {doc_layer[m]!r} in docs/architecture.md) is not in LAYERS"
        )
    for m in sorted(set(doc_layer) & set(table_layer)):
        if doc_layer[m] != table_layer[m]:
            out.append(
                f"{m} is in layer {doc_layer[m]!r} in docs/architecture.md but "
                f"{table_layer[m]!r} in LAYERS"
            )
    return out


def test_architecture_doc_lists_the_layers() -> None:
    # The map cannot drift from the table (it once left out zones).
    documented = documented_layers(ARCHITECTURE.read_text(encoding="utf-8"))
    problems = layer_differences(documented, LAYERS)
    assert problems == [], "docs/architecture.md and LAYERS differ:\n" + "\n".join(
        problems
    )


def test_the_layer_comparison_names_each_difference() -> None:
    # The comparison itself, on a made-up document and table.
    text = (
        "```\nC++  ignored: not, this\n"
        "Py   the layers\n       one per line\n"
        "     low: a, b,\n       c         described\n"
        "                             more description: with a colon\n"
        "     high: movingpunch\n"
        "     extra: d\n```\n"
    )
    documented = documented_layers(text)
    assert documented == [
        ("low", ["a", "b", "c"]),
        ("high", ["movingpunch"]),
        ("extra", ["d"]),
    ]
    table = (
        ("low", frozenset({"movingpunch.a", "movingpunch.b", "movingpunch.c"})),
        ("high", frozenset({"movingpunch"})),
        ("extra", frozenset({"movingpunch.d"})),
    )
    assert layer_differences(documented, table) == []
    moved = (
        ("low", frozenset({"movingpunch.a", "movingpunch.b"})),
        ("high", frozenset({"movingpunch", "movingpunch.c", "movingpunch.e"})),
        ("other", frozenset({"movingpunch.d"})),
    )
    assert layer_differences(documented, moved) == [
        "layer 'other' is in LAYERS, not in docs/architecture.md",
        "layer 'extra' is in docs/architecture.md, not in LAYERS",
        "movingpunch.e (layer 'high' in LAYERS) is missing from docs/architecture.md",
        "movingpunch.c is in layer 'low' in docs/architecture.md but 'high' in LAYERS",
        "movingpunch.d is in layer 'extra' in docs/architecture.md but 'other' "
        "in LAYERS",
    ]
    swapped = (table[1], table[0], table[2])
    assert layer_differences(documented, swapped) == [
        "the layers' order differs: docs/architecture.md ['low', 'high', "
        "'extra'], LAYERS ['high', 'low', 'extra']"
    ]


def test_numerical_modules_do_not_import_textual(
    modules_loaded_by: Callable[[str], set[str]],
) -> None:
    loaded = modules_loaded_by(
        "import movingpunch, movingpunch.solver, movingpunch.errors, movingpunch.cli"
    )
    assert "movingpunch.cli" in loaded
    assert sorted(m for m in loaded if m.split(".")[0] == "textual") == []


def test_every_exception_class_is_in_the_errors_module() -> None:
    # One home for the error family: a class deriving from an error (a base
    # named ...Error) anywhere else fails, and so does a re-export that is not
    # the same class.
    import movingpunch.errors as errors
    import movingpunch.scene as scene
    import movingpunch.tui.paths as paths

    elsewhere = []
    for module, path in source_modules().items():
        if module == "movingpunch.errors" or path.suffix != ".py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef) and any(
                ast.unparse(base).endswith("Error") for base in node.bases
            ):
                elsewhere.append(f"{module}.{node.name}")
    assert elsewhere == []
    for name in ("SceneError", "ClusterError", "WorkerError", "MissingExtraError"):
        assert getattr(scene, name) is getattr(errors, name), name
        assert name in errors.__all__
        assert name in scene.__all__
    assert paths.OutsideFolderError is errors.OutsideFolderError


def test_errors_module_does_not_import_core(
    run_python: Callable[..., subprocess.CompletedProcess[str]],
) -> None:
    code = (
        "import importlib.util, os, sys\n"
        "spec = importlib.util.find_spec('movingpunch')\n"
        # Beside the package's __init__.py: in an editable install the first
        # search location holds only the compiled _core.
        "path = os.path.join(os.path.dirname(spec.origin), 'errors.py')\n"
        "s = importlib.util.spec_from_file_location('mp_errors', path)\n"
        "m = importlib.util.module_from_spec(s); s.loader.exec_module(m)\n"
        "sys.exit(1 if 'movingpunch._core' in sys.modules else 0)\n"
    )
    proc = run_python(code)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_solve_releases_the_gil() -> None:
    """While a slow solve runs in a worker thread, the main thread runs Python.

    With the switch interval raised far above the solve time, the interpreter
    never forces the worker to hand over the GIL: the main thread can run only
    while the worker has released it. The worker reads the main thread's
    counter right before and right after each call into the core; any advance
    in between happened while the core ran without the GIL. If the GIL were
    held, no call could ever see an advance. Nothing is timed; a few solves
    (each with a fresh kernel: nu differs) make a scheduling hiccup harmless.
    """
    counter = [0]
    advances: list[int] = []
    errors: list[BaseException] = []
    done = threading.Event()

    def work() -> None:
        try:
            for attempt in range(8):
                before = counter[0]
                # Near V*_cr on a soft foundation, tight tolerance: a wide
                # contact and a large collocation size.
                solution = _core.solve_contact(
                    vstar=0.08,
                    kw=0.01,
                    radius=100.0,
                    load=0.002,
                    nu=0.2 + 0.001 * attempt,
                    tol=1e-13,
                    allow_unphysical=True,
                )
                advances.append(counter[0] - before)
                assert isinstance(solution, _core.SymmetricSolution)
                if advances[-1] > 0:
                    break
        except BaseException as exc:  # reported below, in the main thread
            errors.append(exc)
        finally:
            done.set()

    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        worker = threading.Thread(target=work, daemon=True)
        worker.start()
        while not done.is_set():
            counter[0] += 1
            # Blocks with the GIL released, so the worker can run Python when
            # it needs to; it does not let the worker run *without* the GIL.
            done.wait(0.001)
        worker.join()
    finally:
        sys.setswitchinterval(old)

    assert not errors, errors
    assert any(n > 0 for n in advances), (
        f"the main thread never ran while the core solved ({advances}): "
        "the GIL was held"
    )


def test_public_solve_runs_in_threads() -> None:
    # Concurrent solves from threads (as the UI's workers do) agree.
    results: list[float] = []
    lock = threading.Lock()

    def work() -> None:
        a = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002).a
        with lock:
            results.append(a)

    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(results) == 4
    assert max(results) - min(results) <= 1e-12 * max(results)
