"""Regenerates the screenshot gallery of docs/tui.md: SVG screenshots of
every tab and the help of the terminal UI at 80x24 and 120x40, on the
paper's Fig. 4 scene, into docs/images/ (``tui-<tab>-<W>x<H>.svg``).

    .venv/bin/python scripts/gallery.py

``tests/python/test_tui_snapshots.py`` compares the app's screens with these
files: run this after an intended change of the screen, and review the diff.
"""

from __future__ import annotations

import sys
from pathlib import Path

from movingpunch.tui.screenshots import write_gallery

ROOT = Path(__file__).resolve().parents[1]


def main() -> int:
    for path in write_gallery(ROOT / "docs" / "images"):
        print(path.relative_to(ROOT))
    return 0


if __name__ == "__main__":
    sys.exit(main())
