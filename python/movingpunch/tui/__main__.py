"""``python -m movingpunch.tui [SCENE]``: the terminal UI."""

import sys

from movingpunch.tui.app import run

if __name__ == "__main__":
    raise SystemExit(run(sys.argv[1:]))
