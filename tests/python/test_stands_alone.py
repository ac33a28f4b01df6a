"""The repository stands alone: nothing in it points to a file outside it.

The method's source is cited by title and year (docs/theory.md); the
benchmarks' yardstick is the project's own (benchmarks/baseline_numpy.py). A
reference to a path beyond the checkout works on the machine it was written on
and fails (or silently measures something else) in a clone.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
# Built by concatenation so that this file does not match itself.
OUTSIDE = (
    "../" + "shared",
    "shared/" + "docs",
    "shared/" + "bench",
    "shared/" + "paper",
)
NOTES = "physics" + ".md"
TEXT = {
    ".py",
    ".md",
    ".toml",
    ".txt",
    ".cpp",
    ".hpp",
    ".cfg",
    ".yml",
    ".yaml",
    ".sh",
    ".cff",
}


def _tracked() -> list[Path]:
    try:
        out = subprocess.run(
            ["git", "-C", str(ROOT), "ls-files"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.split()
        files = [ROOT / f for f in out]
    except (OSError, subprocess.CalledProcessError):  # not a checkout: walk the sources
        files = [
            p
            for top in (
                "cpp",
                "python",
                "tests",
                "docs",
                "benchmarks",
                "scripts",
                ".ci",
            )
            for p in (ROOT / top).rglob("*")
        ]
        files += [p for p in ROOT.iterdir() if p.is_file()]
    return [p for p in files if p.is_file() and (p.suffix in TEXT or p.name in {"run"})]


def test_no_file_refers_to_a_path_outside_the_repository() -> None:
    files = _tracked()
    assert len(files) > 100  # the walk found the sources
    hits = []
    for path in files:
        text = path.read_text(encoding="utf-8", errors="replace")
        for n, line in enumerate(text.splitlines(), 1):
            if any(s in line for s in OUTSIDE) or NOTES in line:
                hits.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()[:100]}")
    assert not hits, "references outside the repository:\n" + "\n".join(hits)


def test_the_benchmarks_yardstick_is_in_the_repository() -> None:
    for name in ("bench_vs_peer.py", "bench_profiles.py"):
        text = (ROOT / "benchmarks" / name).read_text()
        assert "baseline_numpy" in text, name
    assert (ROOT / "benchmarks" / "baseline_numpy.py").is_file()
