#!/usr/bin/env bash
# Installs everything (scripts/setup.sh) and runs the main job: the paper's case
# (V* = 0.2, k_w h/mu = 1, R/h = 100, mu/(P/h) = 500). Extra arguments replace
# the defaults and go to `movingpunch`, e.g. `bash scripts/run.sh critical --kw 1`.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
if (($#)); then
  exec .venv/bin/movingpunch "$@"
fi
exec .venv/bin/movingpunch solve --vstar 0.2 --kw 1 --radius 100 --load 0.002
