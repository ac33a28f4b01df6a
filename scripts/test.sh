#!/usr/bin/env bash
# Installs everything (scripts/setup.sh: an editable install whose C++ build
# folder build/<cache_tag> holds _core and the GoogleTest executable), runs the
# C++ tests with ctest, lint and types (ruff, mypy --strict, mypy.stubtest on
# _core.pyi), then pytest on the editable install. Extra arguments go to pytest
# (e.g. `bash scripts/test.sh -m "not slow"`). Exits non-zero if any step fails.
# After a Python-only edit nothing is compiled: setup prints "no C++ rebuild
# needed" and the build step "ninja: no work to do".
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh

status=0
# The build folder of the editable install (build-dir in pyproject.toml).
build_dir=build/$(.venv/bin/python -c 'import sys; print(sys.implementation.cache_tag)')
echo "[test] C++: build (up to date after setup), ctest ($build_dir)"
if cmake --build "$build_dir" -j2 \
  && ctest --test-dir "$build_dir" --output-on-failure -j2; then
  echo "[test] C++ tests passed"
else
  echo "[test] C++ tests FAILED" >&2
  status=1
fi

echo "[test] Lint and types: ruff, mypy --strict, stubtest (_core.pyi against the built module)"
if .venv/bin/python -m ruff check python tests benchmarks scripts \
  && .venv/bin/python -m ruff format --check python tests benchmarks scripts \
  && .venv/bin/python -m mypy --strict python \
  && bash scripts/stubtest.sh; then
  echo "[test] lint and types clean"
else
  echo "[test] lint or type check FAILED" >&2
  status=1
fi

echo "[test] Python: pytest"
if .venv/bin/python -m pytest "$@"; then
  echo "[test] Python tests passed"
else
  echo "[test] Python tests FAILED" >&2
  status=1
fi
exit "$status"
