"""Result files: names from user text stay inside ``--out``, output problems
end in one line (exit 2) before the work where possible, a run's files are
published all at once or not at all, modes follow the umask, and a closed
stdout ends quietly (movingpunch.outputs, ``run`` and ``accuracy``).

Most cases run ``movingpunch.cli.main`` in this process (fast, and the
writer can be patched to simulate a full disk); the pipe cases run the
command in a subprocess. The tests run as root here, where a chmod-ed folder
stays writable: a refused permission is simulated by patching ``os.open`` /
``os.access``; an existing file, a file as parent and a missing folder are
real.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import re
import stat
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import movingpunch as mp
from extras import need
from movingpunch import accuracy, outputs
from movingpunch.cli import main
from movingpunch.scene import Scene, read_csv

PARAMS = (
    "[params]\nvstar = 0.2\nkw = 1.0\nradius = 100.0\nload = 0.002\n"
    "[outputs]\ncontact_width = true\n"
)
ENOSPC = OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def cli(*args: str) -> int:
    """``movingpunch ARGS`` in this process: its exit status."""
    try:
        return main(list(args))
    except SystemExit as exc:
        code = exc.code
    assert isinstance(code, int)
    return code


def tree(root: Path) -> set[str]:
    """Every file and folder under ``root`` (hidden ones included)."""
    return {str(p.relative_to(root)) for p in root.rglob("*")}


def scene_file(folder: Path, name: str, stem: str = "scene") -> Path:
    """A one-point scene (contact width only) whose ``name`` is ``name``."""
    path = folder / f"{stem}.toml"
    path.write_text(f"name = {json.dumps(name)}\n{PARAMS}", encoding="utf-8")
    return path


def one_error_line(err: str) -> str:
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("movingpunch: error: "), err
    return lines[0]


@contextlib.contextmanager
def umask(mask: int) -> Iterator[None]:
    old = os.umask(mask)
    try:
        yield
    finally:
        os.umask(old)


# ----------------------------------------------------------------------------
# Names
# ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "stem"),
    [
        ("fig4", "fig4"),
        ("near-critical", "near-critical"),
        ("../../x", "x"),
        ("/tmp/evil", "tmp-evil"),
        ("a/b\\c", "a-b-c"),
        ("..", "scene"),
        (".", "scene"),
        ("", "scene"),
        ("σσ", "scene"),
        ("Crème Brûlée", "creme-brulee"),
        ("C:\\Windows\\x", "c-windows-x"),
        ("a\0b\nc", "a-b-c"),
        ("-x-", "x"),
        ("x" * 300, "x" * outputs.MAX_STEM),
    ],
)
def test_safe_name(text: str, stem: str, tmp_path: Path) -> None:
    assert outputs.safe_name(text) == stem
    assert re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", stem)
    assert (tmp_path / f"{stem}-x.csv").resolve().parent == tmp_path.resolve()


@pytest.mark.parametrize("name", ["../x", "/abs", ".hidden", "a/b", "", "..", "a\0"])
def test_publish_refuses_a_name_that_is_not_plain(name: str, tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="not a plain file name"):
        outputs.publish(tmp_path / "out", [("ok.csv", b"1"), (name, b"2")])
    assert tree(tmp_path) == set()


TRAVERSALS = ["../../x", "..", "a/b\\c", "Crème/../..", "", "σσ", "ABSOLUTE"]


def traversal_name(name: str, tmp_path: Path) -> str:
    """``ABSOLUTE`` stands for an absolute path to an existing folder of the
    test's tree (where the unslugged name used to write)."""
    if name != "ABSOLUTE":
        return name
    victim = tmp_path / "victim"
    victim.mkdir()
    return str(victim / "evil")


@pytest.mark.parametrize("name", TRAVERSALS)
def test_run_names_never_leave_out(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    work = tmp_path / "a" / "b"
    work.mkdir(parents=True)
    path = scene_file(work, traversal_name(name, tmp_path))
    before = tree(tmp_path)
    out = work / "out"
    assert cli("run", str(path), "--out", str(out), "--no-plot") == 0
    new = tree(tmp_path) - before
    assert all(p.startswith(str(out.relative_to(tmp_path))) for p in new), new
    (written,) = out.iterdir()
    stem = outputs.safe_name(Scene.load(path).name)
    assert written.name == f"{stem}-contact_width.csv"
    assert str(written) in capsys.readouterr().out


@pytest.mark.parametrize("name", TRAVERSALS)
def test_accuracy_names_never_leave_out(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    work = tmp_path / "a" / "b"
    work.mkdir(parents=True)
    path = scene_file(work, traversal_name(name, tmp_path))
    before = tree(tmp_path)
    out = work / "out"
    status = cli(
        "accuracy", str(path), "--tols", "1e-3", "--no-plot", "--out", str(out)
    )
    assert status == 0
    new = tree(tmp_path) - before
    assert all(p.startswith(str(out.relative_to(tmp_path))) for p in new), new
    (written,) = out.iterdir()
    assert written.name == f"{outputs.safe_name(Scene.load(path).name)}-accuracy.csv"
    assert str(written) in capsys.readouterr().out
    meta, _ = read_csv(written)
    assert meta["scene"].name == Scene.load(path).name  # the name itself is kept


# ----------------------------------------------------------------------------
# Modes
# ----------------------------------------------------------------------------


@pytest.mark.parametrize(("mask", "mode"), [(0o022, 0o644), (0o077, 0o600)])
def test_new_files_get_the_umask_mode(
    mask: int, mode: int, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = scene_file(tmp_path, "m")
    with umask(mask):
        assert cli("run", "fig4", "--out", str(tmp_path / "run"), "--no-plot") == 0
        out = tmp_path / "acc"
        assert cli("accuracy", str(path), "--tols", "1e-3", "--out", str(out)) == 0
        Scene.bundled("table1").save(tmp_path / "saved.toml")
        outputs.atomic_write(tmp_path / "atomic.bin", b"x")
    files = [
        *(tmp_path / "run").iterdir(),
        *(tmp_path / "acc").iterdir(),
        tmp_path / "saved.toml",
        tmp_path / "atomic.bin",
    ]
    assert len(files) == 4 + 1 + 2
    for f in files:
        assert stat.S_IMODE(f.stat().st_mode) == mode, f
    # The folders --out created: 0o777 & ~umask.
    for d in (tmp_path / "run", tmp_path / "acc"):
        assert stat.S_IMODE(d.stat().st_mode) == 0o777 & ~mask, d
    assert not [p for p in tree(tmp_path) if "/." in p or p.startswith(".")]


@pytest.mark.parametrize("mask", [0o022, 0o077])
def test_a_file_written_over_keeps_its_mode(
    mask: int, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "out"
    assert cli("run", "fig4", "--out", str(out), "--no-plot") == 0
    modes = dict(zip(sorted(out.iterdir()), (0o664, 0o640, 0o604, 0o600), strict=True))
    for f, mode in modes.items():
        f.write_text("old\n", encoding="utf-8")
        f.chmod(mode)
    saved = tmp_path / "saved.toml"
    saved.write_text("old\n", encoding="utf-8")
    saved.chmod(0o666)
    with umask(mask):
        assert cli("run", "fig4", "--out", str(out), "--no-plot") == 0
        Scene.bundled("table1").save(saved)
    for f, mode in modes.items():
        assert stat.S_IMODE(f.stat().st_mode) == mode, f
        assert f.read_text(encoding="utf-8") != "old\n"
    assert stat.S_IMODE(saved.stat().st_mode) == 0o666
    assert Scene.load(saved) == Scene.bundled("table1")


# ----------------------------------------------------------------------------
# The output folder, checked before the work
# ----------------------------------------------------------------------------


@pytest.fixture
def no_work(monkeypatch: pytest.MonkeyPatch) -> None:
    """Fails the test if a scene or a ladder is computed."""

    def forbidden(*args: object, **kwargs: object) -> None:
        raise AssertionError("computed before the output folder was checked")

    monkeypatch.setattr(Scene, "run", forbidden)
    monkeypatch.setattr(accuracy, "accuracy_report", forbidden)


COMMANDS = {
    "run": ("run", "fig4", "--no-plot", "--out"),
    "accuracy": ("accuracy", "--tols", "1e-3", "--no-plot", "--out"),
}


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.usefixtures("no_work")
def test_out_an_existing_file(
    command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    target = tmp_path / "results"
    target.write_text("mine\n", encoding="utf-8")
    assert cli(*COMMANDS[command], str(target)) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    line = one_error_line(captured.err)
    assert line == (
        f"movingpunch: error: cannot write into {target}: exists and is not a directory"
    )
    assert target.read_text(encoding="utf-8") == "mine\n"
    assert tree(tmp_path) == {"results"}


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.usefixtures("no_work")
def test_out_under_a_file(
    command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "results").write_text("mine\n", encoding="utf-8")
    target = tmp_path / "results" / "sub"
    assert cli(*COMMANDS[command], str(target)) == 2
    line = one_error_line(capsys.readouterr().err)
    assert line == f"movingpunch: error: cannot write into {target}: Not a directory"
    assert tree(tmp_path) == {"results"}


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.usefixtures("no_work")
def test_out_in_a_folder_that_refuses_files(
    command: str,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    """An existing folder we may not write into (root writes anywhere: the
    refusal is the kernel's answer to the probe file, simulated)."""
    target = tmp_path / "results"
    target.mkdir()
    real_open = os.open

    def refusing_open(path: Any, *args: Any, **kwargs: Any) -> int:
        if Path(path).parent == target:
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(path))
        return real_open(path, *args, **kwargs)

    monkeypatch.setattr(os, "open", refusing_open)
    assert cli(*COMMANDS[command], str(target)) == 2
    line = one_error_line(capsys.readouterr().err)
    assert line == f"movingpunch: error: cannot write into {target}: Permission denied"
    assert tree(tmp_path) == {"results"}


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.usefixtures("no_work")
def test_out_missing_under_a_folder_that_refuses_it(
    command: str,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    target = tmp_path / "new" / "results"
    real_access = os.access

    def access(path: Any, mode: int, **kwargs: Any) -> bool:
        if Path(path) == tmp_path and mode & os.W_OK:
            return False
        return real_access(path, mode, **kwargs)

    monkeypatch.setattr(os, "access", access)
    assert cli(*COMMANDS[command], str(target)) == 2
    line = one_error_line(capsys.readouterr().err)
    assert line == (
        f"movingpunch: error: cannot create {target}: {tmp_path} is not writable"
    )
    assert tree(tmp_path) == set()


@pytest.mark.parametrize("command", COMMANDS)
def test_missing_parents_are_created_after_the_work(
    command: str,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    """``--out a/b/c`` creates the folders (like ``mkdir -p``), but only
    once there are results: a run that fails creates nothing."""
    target = tmp_path / "a" / "b" / "c"
    assert cli(*COMMANDS[command], str(target)) == 0
    assert len(list(target.iterdir())) == (4 if command == "run" else 1)

    def failing(*args: object, **kwargs: object) -> None:
        raise mp.ConvergenceError("no luck")

    monkeypatch.setattr(Scene, "run", failing)
    monkeypatch.setattr(accuracy, "accuracy_report", failing)
    other = tmp_path / "x" / "y"
    assert cli(*COMMANDS[command], str(other)) == 2
    assert one_error_line(capsys.readouterr().err) == "movingpunch: error: no luck"
    assert not (tmp_path / "x").exists()


def test_save_to_a_missing_folder_is_one_line(tmp_path: Path) -> None:
    target = tmp_path / "missing" / "s.toml"
    with pytest.raises(mp.OutputError) as info:
        Scene.bundled("fig4").save(target)
    assert str(info.value) == f"cannot write {target}: No such file or directory"
    assert isinstance(info.value, OSError)  # callers catching OSError still do
    assert info.value.errno == errno.ENOENT
    assert tree(tmp_path) == set()


# ----------------------------------------------------------------------------
# All at once or not at all
# ----------------------------------------------------------------------------


def stale_results(out: Path, capsys: pytest.CaptureFixture[str]) -> dict[Path, str]:
    """fig4's files (and PNGs) in ``out``, each rewritten with a marker
    that a new run would replace."""
    need("png")  # skipped without matplotlib (a failure under scripts/test.sh)
    assert cli("run", "fig4", "--png", "--no-plot", "--out", str(out)) == 0
    capsys.readouterr()
    old = {}
    for f in sorted(out.iterdir()):
        old[f] = f"previous {f.name}\n"
        f.write_text(old[f], encoding="utf-8")
    return old


def assert_unchanged(out: Path, old: dict[Path, str]) -> None:
    assert sorted(out.iterdir()) == sorted(old)  # no temp folder left
    for f, text in old.items():
        assert f.read_text(encoding="utf-8") == text, f


def failing_on(
    nth: int, error: BaseException, real: Callable[..., None]
) -> Callable[..., None]:
    calls = [0]

    def patched(*args: Any) -> None:
        calls[0] += 1
        if calls[0] == nth:
            raise error
        real(*args)

    return patched


def full_disk_on(nth: int) -> Callable[[Path, outputs.Content, int | None], None]:
    """``outputs._write_file`` whose nth call writes half of its data and
    then fails with ENOSPC, as a disk that fills up does."""
    real = outputs._write_file
    calls = [0]

    def write(path: Path, data: outputs.Content, mode: int | None) -> None:
        calls[0] += 1
        if not isinstance(data, bytes):  # a table in pieces
            data = b"".join(data)
        if calls[0] == nth:
            real(path, data[: len(data) // 2], mode)
            raise ENOSPC
        real(path, data, mode)

    return write


@pytest.mark.parametrize("nth", [1, 3, 7])
def test_a_full_disk_leaves_the_previous_results(
    nth: int,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    """ENOSPC on the nth file written (the 7th: the last PNG, after every
    CSV and the other PNGs)."""
    out = tmp_path / "out"
    old = stale_results(out, capsys)
    assert len(old) == 7  # 4 CSV, 3 PNG
    monkeypatch.setattr(outputs, "_write_file", full_disk_on(nth))
    assert cli("run", "fig4", "--png", "--no-plot", "--out", str(out)) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    line = one_error_line(captured.err)
    assert re.fullmatch(
        rf"movingpunch: error: cannot write {re.escape(str(out))}/fig4-\S+\.(csv|png):"
        " No space left on device",
        line,
    ), line
    assert_unchanged(out, old)


def test_save_on_a_full_disk_keeps_the_previous_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    target = tmp_path / "s.toml"
    Scene.bundled("fig4").save(target)
    before = target.read_bytes()
    monkeypatch.setattr(outputs, "_write_file", full_disk_on(1))
    with pytest.raises(mp.OutputError) as info:
        Scene.bundled("table1").save(target)
    assert str(info.value) == f"cannot write {target}: No space left on device"
    assert target.read_bytes() == before
    assert tree(tmp_path) == {"s.toml"}


def test_a_full_disk_in_accuracy_leaves_the_previous_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "out"
    args = ("accuracy", "--tols", "1e-3", "--no-plot", "--out", str(out))
    assert cli(*args) == 0
    (f,) = out.iterdir()
    f.write_text("previous\n", encoding="utf-8")
    capsys.readouterr()
    monkeypatch.setattr(outputs, "_write_file", full_disk_on(1))
    assert cli(*args) == 2
    line = one_error_line(capsys.readouterr().err)
    assert line == f"movingpunch: error: cannot write {f}: No space left on device"
    assert_unchanged(out, {f: "previous\n"})


@pytest.mark.parametrize("nth", [1, 2, 4])
def test_a_failed_rename_puts_the_previous_files_back(
    nth: int,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    """The rename phase fails on the nth file: the files already renamed are
    put back (the previous version where there was one, removed where the
    run added it)."""
    out = tmp_path / "out"
    old = stale_results(out, capsys)
    added = out / "fig4-pressure.csv"  # the second file a run writes
    del old[added]
    added.unlink()
    io_error = OSError(errno.EIO, os.strerror(errno.EIO))
    monkeypatch.setattr(outputs, "_replace", failing_on(nth, io_error, os.replace))
    assert cli("run", "fig4", "--png", "--no-plot", "--out", str(out)) == 2
    line = one_error_line(capsys.readouterr().err)
    assert line.endswith(": Input/output error"), line
    assert_unchanged(out, old)


def test_an_interrupt_while_renaming_puts_the_previous_files_back(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    out = tmp_path / "out"
    out.mkdir()
    old = {out / "a.csv": "old a\n", out / "b.csv": "old b\n"}
    for f, text in old.items():
        f.write_text(text, encoding="utf-8")
    files = [("a.csv", b"new a"), ("new.csv", b"new"), ("b.csv", b"new b")]
    monkeypatch.setattr(
        outputs, "_replace", failing_on(3, KeyboardInterrupt(), os.replace)
    )
    with pytest.raises(KeyboardInterrupt):
        outputs.publish(out, files)
    assert_unchanged(out, old)
    monkeypatch.setattr(
        outputs, "_write_file", failing_on(2, KeyboardInterrupt(), outputs._write_file)
    )
    with pytest.raises(KeyboardInterrupt):
        outputs.publish(out, files)
    assert_unchanged(out, old)


def test_a_successful_publish_replaces_every_file(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.csv").write_text("old a\n", encoding="utf-8")
    (out / "other.txt").write_text("not ours\n", encoding="utf-8")
    written = outputs.publish(out, [("a.csv", b"new a\n"), ("b.csv", b"new b\n")])
    assert written == [out / "a.csv", out / "b.csv"]
    assert tree(out) == {"a.csv", "b.csv", "other.txt"}
    assert (out / "a.csv").read_bytes() == b"new a\n"
    assert (out / "b.csv").read_bytes() == b"new b\n"
    assert (out / "other.txt").read_text(encoding="utf-8") == "not ours\n"


def test_a_symbolic_link_target_is_replaced_not_followed(tmp_path: Path) -> None:
    """A link planted where a result goes cannot redirect the write outside
    the folder: the link itself is replaced."""
    outside = tmp_path / "outside.txt"
    outside.write_text("precious\n", encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.csv").symlink_to(outside)
    outputs.publish(out, [("a.csv", b"new\n")])
    assert outside.read_text(encoding="utf-8") == "precious\n"
    assert not (out / "a.csv").is_symlink()
    assert (out / "a.csv").read_bytes() == b"new\n"


def test_the_written_numbers_read_back(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """What ``publish`` wrote is what ``render_outputs`` made (the staging
    and renames change no byte): the contact width against an independent
    solve."""
    out = tmp_path / "out"
    assert cli("run", "fig4", "--no-plot", "--out", str(out)) == 0
    _, cols = read_csv(out / "fig4-contact_width.csv")
    for vstar, a in zip(cols["vstar"], cols["a"], strict=True):
        s = mp.solve(vstar=float(vstar), kw=1.0, radius=100.0, load=0.002, tol=1e-8)
        assert a == pytest.approx(s.a, rel=1e-7)
    np.testing.assert_array_equal(cols["vstar"], [0.0, 0.2, 0.4, 0.5])


# ----------------------------------------------------------------------------
# A closed stdout
# ----------------------------------------------------------------------------


def closed_stdout(*args: str, cwd: Path | None = None) -> tuple[int, str]:
    """Runs ``movingpunch ARGS`` with stdout a pipe whose reader is gone
    before the command writes: (status, stderr)."""
    with subprocess.Popen(
        [sys.executable, "-m", "movingpunch", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        cwd=cwd,
    ) as proc:
        assert proc.stdout is not None
        assert proc.stderr is not None
        proc.stdout.close()
        err = proc.stderr.read().decode()
        return proc.wait(timeout=300), err


@pytest.mark.parametrize(
    "args",
    [
        ("run", "fig4"),
        ("solve", "--vstar", "0.2", "--kw", "1", "--radius", "100", "--load", "0.002"),
        ("scenes",),
        ("accuracy", "--tols", "1e-3"),
    ],
)
def test_a_closed_stdout_ends_quietly(args: tuple[str, ...]) -> None:
    status, err = closed_stdout(*args)
    assert err == ""
    assert status == 141


def test_help_into_a_closed_stdout_ends_quietly() -> None:
    """argparse drops a failed write of its help itself (status 0); what is
    left in the buffer fails at our flush (141). Either way: no traceback."""
    status, err = closed_stdout("run", "--help")
    assert err == ""
    assert status in (0, 141)


def test_a_closed_stdout_still_writes_the_files(tmp_path: Path) -> None:
    status, err = closed_stdout("run", "fig4", "--out", "out", cwd=tmp_path)
    assert (status, err) == (141, "")
    assert len(list((tmp_path / "out").glob("fig4-*.csv"))) == 4


def test_head_reads_the_first_line_quietly() -> None:
    """``movingpunch run fig4 | head -1`` through a real shell: the first
    line, nothing on stderr, and 0 or 141 (whether head was gone when the
    command flushed)."""
    script = (
        f"{sys.executable} -m movingpunch run fig4 | head -1; "
        'echo "status ${PIPESTATUS[0]}" >&2'
    )
    proc = subprocess.run(
        ["bash", "-c", script], capture_output=True, text=True, timeout=300
    )
    assert proc.stdout.startswith("Scene fig4:")
    assert proc.stdout.count("\n") == 1
    assert re.fullmatch(r"status (0|141)\n", proc.stderr), proc.stderr


def test_a_stdout_closed_from_the_start_is_no_error(tmp_path: Path) -> None:
    """``movingpunch run fig4 --out out >&-``: Python starts with no
    sys.stdout; the command still writes its files and ends with 0."""
    script = f"{sys.executable} -m movingpunch run fig4 --out out >&-"
    proc = subprocess.run(
        ["bash", "-c", script],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=tmp_path,
    )
    assert (proc.returncode, proc.stderr) == (0, "")
    assert len(list((tmp_path / "out").glob("fig4-*.csv"))) == 4
