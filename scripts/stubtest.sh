#!/usr/bin/env bash
# Checks the hand-written stub python/movingpunch/_core.pyi against the compiled
# module movingpunch._core (mypy.stubtest imports the built extension and
# compares every name, signature and type it can see at run time). Entries in
# scripts/stubtest-allowlist.txt are pybind11 artefacts only, each commented.
# Uses .venv's Python, or $PY if set (e.g. a worktree using /work/main/.venv).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
py=${PY:-.venv/bin/python}
# mypy_path = "python" (pyproject.toml) lets mypy find the stub in the source
# tree; the editable install's import hook serves the compiled module.
exec "$py" -m mypy.stubtest movingpunch._core \
  --mypy-config-file pyproject.toml \
  --allowlist scripts/stubtest-allowlist.txt "$@"
