#!/usr/bin/env bash
# Installs everything movingpunch needs on a Debian machine, then the package
# itself (editable, with all its extras) into .venv. Idempotent: system
# packages are installed only if missing, and the package is reinstalled only
# when a C++ build input changed or a Python file was added or removed
# (MOVINGPUNCH_FORCE_INSTALL=1 forces it). The C++ objects and the GoogleTest
# executable live in build/<cache_tag> (e.g. build/cpython-311), kept between runs.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

log() { printf '[setup] %s\n' "$*"; }

# --- System packages ---------------------------------------------------------
packages=(libeigen3-dev libgtest-dev cmake g++ ninja-build tmux jq python3-venv)
missing=()
for pkg in "${packages[@]}"; do
  if ! dpkg -s "$pkg" 2>/dev/null | grep -q '^Status: install ok installed'; then
    missing+=("$pkg")
  fi
done
# The extension needs the headers of the Python that builds it.
if ! command -v python3 >/dev/null 2>&1; then
  missing+=(python3 python3-dev)
elif ! python3 - <<'PY' >/dev/null 2>&1
import os, sys, sysconfig
sys.exit(0 if os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h")) else 1)
PY
then
  missing+=(python3-dev)
fi
if ((${#missing[@]})); then
  sudo=()
  if [[ $(id -u) -ne 0 ]]; then sudo=(sudo); fi
  log "installing ${missing[*]}"
  "${sudo[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y "${missing[@]}"
fi

# --- Virtual environment -----------------------------------------------------
if ! .venv/bin/python -c 'import sys' >/dev/null 2>&1; then
  log "creating .venv"
  rm -rf .venv
  python3 -m venv .venv
  .venv/bin/python -m pip install --quiet --upgrade pip
fi

# --- The package: editable, with a persistent build folder ------------------
# `pip install -e` (scikit-build-core, build-dir build/<cache_tag> from
# pyproject.toml) compiles _core and the C++ tests once; Python files are then
# served from python/movingpunch, so a Python edit needs nothing here. It runs
# again only when a C++ build input changed (CMake/ninja then recompile only
# what changed) or a Python file was added or removed: scripts/build_stamp.py.
py=.venv/bin/python
stamp=.venv/.movingpunch-editable
current=0
if [[ "${MOVINGPUNCH_FORCE_INSTALL:-0}" == 1 ]]; then
  why="forced (MOVINGPUNCH_FORCE_INSTALL=1)"
elif why=$("$py" scripts/build_stamp.py check "$stamp"); then
  if "$py" -c 'import movingpunch._core' >/dev/null 2>&1; then
    current=1
  else
    why="movingpunch._core does not import from .venv"
  fi
fi
if ((current)); then
  log "movingpunch is up to date in .venv: $why"
else
  log "installing movingpunch (editable) into .venv: ${why:-no working install}"
  if ! compgen -G 'build/*/CMakeCache.txt' >/dev/null; then
    log "(the first build compiles the C++ core: a few minutes; later ones only what changed)"
  fi
  rm -f "$stamp"
  # The build requirements, as in [build-system].requires of pyproject.toml
  # (tests/python/test_dev_loop.py checks they agree): without build isolation
  # they come from .venv, so the build folder's CMake cache stays valid.
  "$py" -m pip install --progress-bar off "scikit-build-core>=0.10" "pybind11>=2.13"
  "$py" -m pip install --progress-bar off --no-build-isolation \
    -Ccmake.define.MOVINGPUNCH_BUILD_TESTS=ON \
    -e ".[test,dev,dask,png,serve]"
  "$py" scripts/build_stamp.py write "$stamp"
fi
