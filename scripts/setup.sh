#!/usr/bin/env bash
# Installs everything movingpunch needs on a Debian machine, then the package
# itself (non-editable, with its test extras) into .venv. Idempotent: system
# packages are installed only if missing, and the package is rebuilt only when
# its sources changed (MOVINGPUNCH_FORCE_INSTALL=1 forces a rebuild).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

log() { printf '[setup] %s\n' "$*"; }

# --- System packages ---------------------------------------------------------
packages=(libeigen3-dev libgtest-dev cmake g++ ninja-build tmux python3-venv)
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

# --- The package (rebuilt only when its sources change) ----------------------
stamp=.venv/.movingpunch-sources
digest=$(
  {
    for f in pyproject.toml CMakeLists.txt README.md; do [[ -f $f ]] && echo "$f"; done
    find cpp python -type f -not -path '*/__pycache__/*'
  } | LC_ALL=C sort | xargs sha256sum | sha256sum | cut -d' ' -f1
)
if [[ "${MOVINGPUNCH_FORCE_INSTALL:-0}" != 1 && -f $stamp && $(<"$stamp") == "$digest" ]] \
  && .venv/bin/python -c 'import movingpunch' >/dev/null 2>&1; then
  log "movingpunch is up to date in .venv"
else
  log "building and installing movingpunch into .venv (first build takes a few minutes)"
  rm -f "$stamp"
  .venv/bin/python -m pip install --progress-bar off ".[test,dev,dask,png,serve]"
  printf '%s\n' "$digest" >"$stamp"
fi
