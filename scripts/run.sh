#!/usr/bin/env bash
# Installs everything (scripts/setup.sh) and runs the main job: the terminal UI
# on the paper's Fig. 4 case (V* = 0.2, k_w h/mu = 1, R/h = 100, mu/(P/h) = 500,
# nu = 0.2). Extra arguments go to `movingpunch` instead, e.g.
# `bash scripts/run.sh run fig4` or `bash scripts/run.sh critical --kw 1`.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
if (($#)); then
  exec .venv/bin/movingpunch "$@"
fi
exec .venv/bin/movingpunch tui
