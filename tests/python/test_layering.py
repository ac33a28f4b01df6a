"""Architecture: the numerical modules never import Textual, and the compiled
core releases the GIL while it computes (what keeps a UI responsive)."""

from __future__ import annotations

import subprocess
import sys
import threading

import movingpunch as mp
from movingpunch import _core


def test_numerical_modules_do_not_import_textual() -> None:
    code = (
        "import sys\n"
        "import movingpunch, movingpunch.solver, movingpunch.errors, movingpunch.cli\n"
        "bad = sorted(m for m in sys.modules if m == 'textual' or "
        "m.startswith('textual.'))\n"
        "print(bad)\n"
        "sys.exit(1 if bad else 0)\n"
    )
    proc = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_errors_module_does_not_import_core() -> None:
    code = (
        "import importlib.util, sys\n"
        "spec = importlib.util.find_spec('movingpunch')\n"
        "path = spec.submodule_search_locations[0] + '/errors.py'\n"
        "s = importlib.util.spec_from_file_location('mp_errors', path)\n"
        "m = importlib.util.module_from_spec(s); s.loader.exec_module(m)\n"
        "sys.exit(1 if 'movingpunch._core' in sys.modules else 0)\n"
    )
    proc = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
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
                assert isinstance(solution, _core.ContactSolution)
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
