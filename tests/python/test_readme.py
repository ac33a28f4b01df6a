"""Every command in README.md's code blocks runs, and its output is checked
where the README shows it (issue 25: `movingpunch run fig4 --format json |
jq .outputs.pressure.columns.p` printed `null`).

The commands are extracted from the README: each ``$ `` line of a
``console`` block (the lines under it, up to the next command, are its
output), each line of a ``bash`` block, each ``python`` block (run whole,
in one namespace, as a reader pasting them in order would) and each path of
the Layout block. ``CHECKS`` says how each command is checked; a command
without a check, or a check whose command left the README, fails. Commands
that need a terminal (the TUI) run in a pseudo-terminal and quit with
``q``; ``serve`` runs until it prints its URL; the install and test scripts
and the long runs are checked to exist and parse (``bash -n``), not run.
A tool that may be absent (jq, textual-serve) skips with a reason, except
under CI (``CI`` set), where scripts/setup.sh installs it and its absence
fails.
"""

from __future__ import annotations

import json
import math
import os
import re
import select
import shutil
import signal
import struct
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

import movingpunch as mp

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
BIN = Path(sys.executable).parent
MOVINGPUNCH = BIN / "movingpunch"
TIMEOUT = 180.0
"""Seconds any one command may take (a bound against a hang, not a timing)."""


@dataclass(frozen=True)
class Command:
    """A command of the README: its text (comment dropped), the block's
    language and the output the README shows under it ("" if none)."""

    text: str
    lang: str
    shown: str = ""


def _strip_comment(line: str) -> str:
    """A shell line without its trailing ``# comment`` (outside quotes)."""
    quote = ""
    for i, ch in enumerate(line):
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch == "#" and (i == 0 or line[i - 1] == " "):
            return line[:i].rstrip()
    return line.rstrip()


def blocks() -> list[tuple[str, str]]:
    """(language, body) of every fenced code block of the README."""
    text = README.read_text(encoding="utf-8")
    return re.findall(r"^```(\w*)\n(.*?)^```", text, re.MULTILINE | re.DOTALL)


def commands() -> list[Command]:
    out: list[Command] = []
    for lang, body in blocks():
        if lang == "console":
            for chunk in re.split(r"^\$ ", body, flags=re.MULTILINE)[1:]:
                first, _, rest = chunk.partition("\n")
                out.append(Command(_strip_comment(first), lang, rest.rstrip("\n")))
        elif lang == "bash":
            for line in body.splitlines():
                text = _strip_comment(line)
                if text:
                    out.append(Command(text, lang))
    return out


def python_blocks() -> list[str]:
    return [body for lang, body in blocks() if lang == "python"]


def layout_paths() -> list[str]:
    """The paths of the README's Layout block (its first column)."""
    text = README.read_text(encoding="utf-8")
    section = text.split("\n## Layout\n", 1)[1].split("\n## ", 1)[0]
    body = re.search(r"^```\n(.*?)^```", section, re.MULTILINE | re.DOTALL)
    assert body is not None
    return [line.split()[0] for line in body.group(1).splitlines() if line[:1].strip()]


# -- running --------------------------------------------------------------------


def need(tool: str, present: bool) -> None:
    """Skips when ``tool`` is absent, with the reason; fails under CI,
    where scripts/setup.sh installs it."""
    if present:
        return
    reason = f"{tool} is not installed (scripts/setup.sh installs it)"
    if os.environ.get("CI"):
        pytest.fail(f"{reason}; CI must have it")
    pytest.skip(reason)


def env_in(home: Path) -> dict[str, str]:
    env = dict(os.environ)
    env["HOME"] = str(home)
    env["PATH"] = os.pathsep.join([str(BIN), env.get("PATH", "")])
    env.pop("NO_COLOR", None)
    return env


def shell(text: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    """``text`` run by bash (pipes and ``&&`` as typed) in ``cwd``, with
    this environment's ``movingpunch`` and ``python`` first on PATH."""
    return subprocess.run(
        ["bash", "-o", "pipefail", "-c", text],
        cwd=cwd,
        env=env_in(cwd),
        capture_output=True,
        text=True,
        timeout=TIMEOUT,
        check=False,
    )


def ok(text: str, cwd: Path) -> str:
    proc = shell(text, cwd)
    assert proc.returncode == 0, (text, proc.stdout[-2000:], proc.stderr[-2000:])
    return proc.stdout


def in_terminal(argv: list[str], cwd: Path, ready: bytes) -> tuple[int, bytes]:
    """Runs ``argv`` in a pseudo-terminal of 80x24 in ``cwd``, waits for
    ``ready`` on the screen, presses q; returns (exit status, output)."""
    import fcntl
    import pty
    import termios

    pid, fd = pty.fork()
    if pid == 0:  # the child: the terminal is its stdin
        fcntl.ioctl(0, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 80, 0, 0))
        os.chdir(cwd)
        env = env_in(cwd)
        env["TERM"] = "xterm-256color"
        os.execve(argv[0], argv, env)
    output = b""
    deadline = time.monotonic() + TIMEOUT
    quit_sent = False
    try:
        while time.monotonic() < deadline:
            readable, _, _ = select.select([fd], [], [], 0.2)
            if readable:
                try:
                    chunk = os.read(fd, 65536)
                except OSError:  # the child closed the terminal
                    break
                if not chunk:
                    break
                output += chunk
            if not quit_sent and ready in output:
                time.sleep(0.5)  # let the first solve land
                os.write(fd, b"q")
                quit_sent = True
            done, status = os.waitpid(pid, os.WNOHANG)
            if done:
                return os.waitstatus_to_exitcode(status), output
        else:
            os.kill(pid, signal.SIGKILL)
            pytest.fail(f"{argv} did not quit within {TIMEOUT} s: {output[-500:]!r}")
        _, status = os.waitpid(pid, 0)
        return os.waitstatus_to_exitcode(status), output
    finally:
        os.close(fd)


# -- the checks -------------------------------------------------------------------


def _script(path: str) -> Callable[[Command, Path], None]:
    """An install or test script: it exists and parses (it is not run:
    it installs system packages or runs the whole suite)."""

    def check(_: Command, __: Path) -> None:
        script = ROOT / path
        assert script.is_file(), path
        syntax = subprocess.run(
            ["bash", "-n", str(script)], capture_output=True, text=True, check=False
        )
        assert syntax.returncode == 0, syntax.stderr

    return check


def _python_file(path: str) -> Callable[[Command, Path], None]:
    """A long Python run (a benchmark, the hard-case table): it exists and
    compiles (running it takes minutes)."""

    def check(_: Command, __: Path) -> None:
        source = ROOT / path
        assert source.is_file(), path
        compile(source.read_text(encoding="utf-8"), str(source), "exec")

    return check


def check_tui(command: Command, cwd: Path) -> None:
    """The TUI starts in a terminal on what the README says, and q quits."""
    argv = [str(MOVINGPUNCH), *command.text.split()[1:]]
    status, output = in_terminal(argv, cwd, b"Quit")
    text = output.decode("utf-8", "replace")
    assert status == 0, text[-1000:]
    if command.text == "movingpunch":  # the paper's Fig. 4 case
        assert "0.372881" in text  # a/h at V* 0.2, kw 1, R/h 100, P/(μh) 0.002
        assert "μ/(P/h) 500" in text


def check_serve(command: Command, cwd: Path) -> None:
    """``serve [SCENE]`` prints one 127.0.0.1 URL carrying a fresh token."""
    import importlib.util

    need(
        "textual-serve (extra 'serve')",
        importlib.util.find_spec("textual_serve") is not None,
    )
    urls = []
    for _ in range(2):
        with subprocess.Popen(
            [str(MOVINGPUNCH), "serve", "fig5", "--port", "0"],
            cwd=cwd,
            env=env_in(cwd),
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
        ) as proc:
            try:
                assert proc.stdout is not None
                line = proc.stdout.readline()
            finally:
                proc.send_signal(signal.SIGINT)
                try:
                    proc.wait(timeout=30)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
        match = re.search(r"http://127\.0\.0\.1:\d+/\?token=(\S+)", line)
        assert match, line
        urls.append(match.group(1))
    assert urls[0] != urls[1]  # a fresh token each start


def check_scenes(command: Command, cwd: Path) -> None:
    out = ok(command.text, cwd)
    listed = [line.split()[0] for line in out.splitlines() if line.strip()]
    assert listed == list(mp.bundled_scenes())


def check_table1(command: Command, cwd: Path) -> None:
    """Both columns of Table 1: a/h for V* = 0 and 1e-3 at four kw."""
    out = ok(command.text, cwd)
    assert "a/h (vstar=0)" in out
    assert "a/h (vstar=0.001)" in out
    rows = [line.split() for line in out.splitlines() if line.split()[:1] == ["1"]]
    assert rows
    assert float(rows[0][1]) == pytest.approx(0.3304193, abs=1e-6)


def check_bogie(command: Command, cwd: Path) -> None:
    """A train of four punches: their zones."""
    out = ok(command.text, cwd)
    for k in range(1, 5):
        assert f"punch {k}:" in out
    assert "zones" in out


def check_scene_show_and_run(command: Command, cwd: Path) -> None:
    ok(command.text, cwd)
    assert (cwd / "my.toml").is_file()
    assert mp.Scene.load(cwd / "my.toml").name == mp.Scene.bundled("fig3").name
    assert list((cwd / "results").glob("*.csv"))


def check_run(command: Command, cwd: Path) -> None:
    ok(command.text, cwd)


def check_jq(command: Command, cwd: Path) -> None:
    """The JSON on stdout, filtered by jq, prints what the README shows;
    the same filter in Python gives it too (so the README's claim is
    checked even where jq is absent)."""
    data = json.loads(ok("movingpunch run fig4 --format json", cwd))
    assert json.dumps(
        sorted(data["outputs"]["pressure"]["columns"]), separators=(",", ":")
    ) == (command.shown)
    curve = data["outputs"]["pressure"]["columns"]["p[vstar=0.2]"]
    assert max(curve) == pytest.approx(1.699, abs=1e-3)  # p0 of Fig. 4's V* 0.2
    need("jq", shutil.which("jq") is not None)
    assert ok(command.text, cwd).strip() == command.shown


def _synopsis(text: str) -> tuple[str, list[str]]:
    """A usage line: (the command with its ``[...]`` options dropped, the
    option names inside the brackets)."""
    options = re.findall(r"--[a-z-]+", " ".join(re.findall(r"\[([^\]]*)\]", text)))
    return re.sub(r"\s*\[[^\]]*\]", "", text), options


def check_solve(command: Command, cwd: Path) -> None:
    """The synopsis runs without its optional parts (the paper's case) and
    every option it lists is one ``solve`` takes."""
    bare, options = _synopsis(command.text)
    out = ok(bare, cwd)
    assert re.search(r"\ba/h\s+0\.37288", out), out
    usage = ok("movingpunch solve --help", cwd)
    for option in options:
        assert option in usage, option


def check_train(command: Command, cwd: Path) -> None:
    out = ok(command.text, cwd)
    assert "Punches" in out
    assert (
        len(re.findall(r"@ ?-?1\.5|at x/h = -?1\.5", out)) >= 2 or out.count("1.5") >= 2
    )


def check_critical(command: Command, cwd: Path) -> None:
    bare, options = _synopsis(command.text)
    assert "0.5716928" in ok(bare, cwd)
    with_all = (
        bare + " " + " ".join(o + (" 0.2" if o == "--nu" else "") for o in options)
    )
    data = json.loads(ok(with_all, cwd))
    assert math.isclose(data["critical_vstar"], mp.critical_vstar(1.0), rel_tol=1e-9)


def check_python_m(command: Command, cwd: Path) -> None:
    """``python -m movingpunch ...`` is the same as ``movingpunch ...``."""
    args = "critical --kw 1"
    assert ok(f"{sys.executable} -m movingpunch {args}", cwd) == ok(
        f"movingpunch {args}", cwd
    )
    assert command.text.startswith("python -m movingpunch")


def check_slow_marker(command: Command, cwd: Path) -> None:
    """``-m slow`` selects the marker the long tests carry (not run: it
    takes many minutes)."""
    pyproject = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert re.search(r"""['"]slow:""", pyproject)
    marked = [
        p.name
        for p in (ROOT / "tests" / "python").glob("test_*.py")
        if "pytest.mark.slow" in p.read_text(encoding="utf-8")
    ]
    assert {"test_hard_cases.py", "test_fuzz.py"} <= set(marked)


def check_pre_commit(command: Command, cwd: Path) -> None:
    assert (ROOT / ".pre-commit-config.yaml").is_file()
    assert "pre-commit" in (ROOT / "pyproject.toml").read_text(encoding="utf-8")


CHECKS: dict[str, Callable[[Command, Path], None]] = {
    "bash scripts/run.sh": _script("scripts/run.sh"),
    "bash scripts/test.sh": _script("scripts/test.sh"),
    "movingpunch": check_tui,
    "movingpunch tui fig5": check_tui,
    "movingpunch serve [SCENE]": check_serve,
    "movingpunch scenes": check_scenes,
    "movingpunch run table1": check_table1,
    "movingpunch run bogie": check_bogie,
    "movingpunch scene show fig3 > my.toml && movingpunch run my.toml --out "
    "results --format csv --plot": check_scene_show_and_run,
    "movingpunch run fig2 --jobs 2": check_run,
    "movingpunch run fig4 --format json | jq -c '.outputs.pressure.columns | "
    "keys'": check_jq,
    "movingpunch solve --vstar 0.2 --kw 1 --radius 100 --load 0.002 [--nu 0.2] "
    "[--tol 1e-8|draft|precise] [--damping D] [--kp KP] [--friction F] "
    "[--profile cylinder|flat|rounded_flat|table --half-width B --table FILE] "
    "[--allow-unphysical] [--contact auto|single] [--stress] [--json]": check_solve,
    "movingpunch solve --vstar 0.5 --kw 1 --radius 100 --punch 0.002@-1.5 "
    "--punch 0.002@1.5": check_train,
    "movingpunch critical --kw 1 [--nu 0.2] [--json]": check_critical,
    "python -m movingpunch ...": check_python_m,
    ".venv/bin/python -m pytest tests/python -m slow": check_slow_marker,
    ".venv/bin/python tests/python/test_hard_cases.py": _python_file(
        "tests/python/test_hard_cases.py"
    ),
    "bash scripts/setup.sh": _script("scripts/setup.sh"),
    "bash scripts/test.sh [PYTEST ARGS]": _script("scripts/test.sh"),
    'bash scripts/test.sh -m "not slow"': _script("scripts/test.sh"),
    "MOVINGPUNCH_PYTEST_WORKERS=0 bash scripts/test.sh": _script("scripts/test.sh"),
    "bash scripts/format.sh": _script("scripts/format.sh"),
    ".venv/bin/pre-commit install": check_pre_commit,
    ".venv/bin/python benchmarks/bench_vs_peer.py": _python_file(
        "benchmarks/bench_vs_peer.py"
    ),
    ".venv/bin/python benchmarks/bench_scenes.py": _python_file(
        "benchmarks/bench_scenes.py"
    ),
    ".venv/bin/python benchmarks/bench_jobs.py": _python_file(
        "benchmarks/bench_jobs.py"
    ),
    ".venv/bin/python benchmarks/bench_damped.py": _python_file(
        "benchmarks/bench_damped.py"
    ),
}
"""How each README command is checked."""


def test_every_readme_command_has_a_check() -> None:
    found = [c.text for c in commands()]
    assert len(found) == len(set(found)), found
    assert set(found) == set(CHECKS), (
        f"without a check: {set(found) - set(CHECKS)}; "
        f"no longer in the README: {set(CHECKS) - set(found)}"
    )


def test_outputs_are_shown_only_where_checked() -> None:
    """A console block shows output only under the jq command (checked
    there); the serve URL and the docs' screens are checked elsewhere."""
    shown = {c.text for c in commands() if c.shown.strip()}
    assert shown == {next(t for t, f in CHECKS.items() if f is check_jq)}


@pytest.mark.parametrize("command", commands(), ids=lambda c: c.text[:60])
def test_readme_command(command: Command, tmp_path: Path) -> None:
    CHECKS[command.text](command, tmp_path)


def test_readme_python_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The Python blocks run in order in one namespace, and the values the
    README's comments state are what they give."""
    monkeypatch.chdir(tmp_path)
    space: dict[str, object] = {}
    for body in python_blocks():
        exec(compile(body, "README.md", "exec"), space)
    s = mp.solve(vstar=0.2, kw=1.0, radius=100.0, load=0.002)
    assert f"{s.a:.6f}" == "0.372881"
    assert f"{mp.critical_vstar(kw=1.0):.7f}" == "0.5716928"
    assert f"{mp.rayleigh_vstar(nu=0.2):.7f}" == "0.8299135"
    separated: Any = space["s"]
    zones = [(round(a, 4), round(b, 4)) for a, b in separated.contact_zones]
    assert zones == [(-1.7826, -0.7224), (0.7224, 1.7826)]
    assert separated.validity.startswith("valid: separated contact of 2 zones")
    single: Any = space["single"]
    assert single.valid is False
    x, y = space["x"], space["y"]
    table = mp.solve(vstar=0.2, kw=1, load=0.002, profile=mp.Profile(x, y))  # type: ignore[arg-type]
    assert f"{table.a:.5f}" == "0.37288"
    visco: Any = space["visco"]
    assert [round(e, 4) for e in visco.contact_interval] == [-0.2507, 0.3186]
    assert f"{visco.drag:.4g}" == "0.0005424"
    assert abs(visco.drag - visco.dissipation) < 1e-10 * visco.drag
    pave: Any = space["pave"]
    assert f"{pave.drag:.4g}" == "0.01088"
    assert abs(pave.drag - pave.dissipation) < 1e-10 * pave.drag
    assert f"{pave.indentation:.4g}" == "0.04484"
    bogie: Any = space["bogie"]
    rear, front = (p.drag for p in bogie.punches)
    assert (f"{rear:.4g}", f"{front:.4g}") == ("4.994e-05", "0.01984")


def test_layout_paths_exist() -> None:
    paths = layout_paths()
    assert len(paths) > 8
    for path in paths:
        assert list(ROOT.glob(path)), path
