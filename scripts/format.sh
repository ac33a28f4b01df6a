#!/usr/bin/env bash
# Formats the project's code in place: C++ (cpp/, tests/cpp/) with clang-format
# (.clang-format: Google-based, 100 columns) and Python (python/, tests/,
# benchmarks/, scripts/) with ruff format. `--check` changes nothing and exits
# non-zero if a file is not formatted. `--cpp` or `--python` limits it to one
# language. Tools come from .venv (the `dev` extra, clang-format pinned there);
# $CLANG_FORMAT and $PY override them.
#   bash scripts/format.sh            # format everything
#   bash scripts/format.sh --check    # what CI-style checks would say
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

check=0
langs=(cpp python)
for arg in "$@"; do
  case $arg in
    --check) check=1 ;;
    --cpp) langs=(cpp) ;;
    --python) langs=(python) ;;
    *) echo "usage: bash scripts/format.sh [--check] [--cpp|--python]" >&2; exit 2 ;;
  esac
done
py=${PY:-.venv/bin/python}
clang_format=${CLANG_FORMAT:-.venv/bin/clang-format}

for tool in "$py" "$clang_format"; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "[format] $tool not found: run \`bash scripts/setup.sh\` (the dev extra brings ruff and a pinned clang-format)" >&2
    exit 2
  fi
done

status=0
for lang in "${langs[@]}"; do
  if [[ $lang == cpp ]]; then
    mapfile -t files < <(git ls-files -- 'cpp/*.cpp' 'cpp/*.hpp' 'tests/cpp/*.cpp' 'tests/cpp/*.hpp')
    if ((check)); then
      "$clang_format" --dry-run --Werror "${files[@]}" || status=1
    else
      "$clang_format" -i "${files[@]}"
      echo "[format] clang-format: ${#files[@]} C++ files"
    fi
  else
    if ((check)); then
      "$py" -m ruff format --check python tests benchmarks scripts || status=1
    else
      "$py" -m ruff format python tests benchmarks scripts
    fi
  fi
done
exit "$status"
