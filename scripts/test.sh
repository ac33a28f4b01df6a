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
# ctest's verdict depends only on the C++ inputs: outside CI, a run that passed
# on exactly these inputs is not repeated (MOVINGPUNCH_CTEST=always repeats it).
ctest_stamp=$build_dir/.movingpunch-ctest-passed
cxx=$(.venv/bin/python scripts/build_stamp.py show | sed -n 's/^cxx //p')
if ! cmake --build "$build_dir" -j2; then
  echo "[test] C++ build FAILED" >&2
  status=1
elif [[ -z "${CI:-}" && "${MOVINGPUNCH_CTEST:-auto}" != always && -f $ctest_stamp \
  && $(<"$ctest_stamp") == "$cxx" ]]; then
  echo "[test] C++ tests passed before on these exact C++ inputs: not rerun" \
    "(MOVINGPUNCH_CTEST=always reruns them; CI always does)"
elif rm -f "$ctest_stamp" && ctest --test-dir "$build_dir" --output-on-failure -j2; then
  printf '%s\n' "$cxx" >"$ctest_stamp"
  echo "[test] C++ tests passed"
else
  echo "[test] C++ tests FAILED" >&2
  status=1
fi

echo "[test] Lint and types: ruff, clang-format, mypy --strict, stubtest (_core.pyi against the built module)"
if .venv/bin/python -m ruff check python tests benchmarks scripts \
  && .venv/bin/python -m ruff format --check python tests benchmarks scripts \
  && bash scripts/format.sh --check --cpp \
  && .venv/bin/python -m mypy --strict python \
  && bash scripts/stubtest.sh; then
  echo "[test] lint and types clean"
else
  echo "[test] lint or type check FAILED" >&2
  status=1
fi

# pytest-xdist: one worker per core (MOVINGPUNCH_PYTEST_WORKERS=0 runs in
# this process, e.g. to debug; arguments after the script's go to pytest).
# --dist loadgroup: the tests of one @pytest.mark.xdist_group run on one
# worker (they share a costly module-level reference, computed once).
workers=${MOVINGPUNCH_PYTEST_WORKERS:-auto}
# setup.sh installed every extra (and tmux): a test that needs one and finds
# it missing fails here instead of skipping (tests/python/extras.py), so this
# run cannot go green by skipping. A plain `pytest` after `pip install
# '.[test]'` skips those tests, naming the extra.
export MOVINGPUNCH_REQUIRE_EXTRAS=${MOVINGPUNCH_REQUIRE_EXTRAS:-1}
echo "[test] Python: pytest (workers: $workers; extras required: $MOVINGPUNCH_REQUIRE_EXTRAS)"
if .venv/bin/python -m pytest -n "$workers" --dist loadgroup "$@"; then
  echo "[test] Python tests passed"
else
  echo "[test] Python tests FAILED" >&2
  status=1
fi
exit "$status"
