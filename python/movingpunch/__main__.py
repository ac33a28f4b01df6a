"""``python -m movingpunch``: the command-line interface."""

from movingpunch.cli import main

if __name__ == "__main__":
    raise SystemExit(main())
