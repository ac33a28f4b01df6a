#!/usr/bin/env bash
# Installs everything (scripts/setup.sh), builds and runs the C++ tests with
# ctest, then runs pytest on the installed package. Extra arguments go to
# pytest (e.g. `bash scripts/test.sh -m "not slow"`). Exits non-zero if either
# suite fails.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh

status=0
echo "[test] C++: configure, build, ctest (build/ctest)"
if cmake -S . -B build/ctest -G Ninja \
  -DMOVINGPUNCH_BUILD_TESTS=ON -DMOVINGPUNCH_BUILD_PYTHON=OFF \
  && cmake --build build/ctest -j2 \
  && ctest --test-dir build/ctest --output-on-failure -j2; then
  echo "[test] C++ tests passed"
else
  echo "[test] C++ tests FAILED" >&2
  status=1
fi

echo "[test] Lint and types: ruff, mypy --strict"
if .venv/bin/python -m ruff check python tests benchmarks \
  && .venv/bin/python -m ruff format --check python tests benchmarks \
  && .venv/bin/python -m mypy --strict python; then
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
