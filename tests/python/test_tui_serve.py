"""`movingpunch serve` serves the app over HTTP on localhost behind a token
and an Origin check (the `serve` extra is installed by scripts/setup.sh;
without it the module is skipped, with the reason: extras.py).

One real server (a subprocess on a free port, ``--port 0``) answers the
module's tests; its working folder ``root`` sits inside a scratch directory
so a save that escaped would land next to it.
"""

from __future__ import annotations

import asyncio
import queue
import re
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from extras import module

aiohttp = module("serve", "aiohttp")

ANSI = re.compile(
    r"\x1b\[[0-9;?]*[A-Za-z]|\x1b\][^\x07]*\x07|\x1b[()][A-Z0-9]|\x1b[78=>]"
)
"""Terminal escape sequences (the app's output to the browser)."""


@dataclass(frozen=True)
class Served:
    proc: subprocess.Popen[str]
    url: str  # the one URL printed, with the token
    base: str  # http://127.0.0.1:PORT
    token: str
    root: Path

    @property
    def port(self) -> int:
        return int(self.base.rsplit(":", 1)[1])

    @property
    def ws(self) -> str:
        return "ws" + self.base.removeprefix("http") + "/ws"

    @property
    def cookie(self) -> dict[str, str]:
        return {f"movingpunch_token_{self.port}": self.token}


def read_lines(proc: subprocess.Popen[str], count: int, seconds: float) -> list[str]:
    """The first ``count`` lines of stdout, waiting at most ``seconds``."""
    lines: queue.Queue[str] = queue.Queue()
    assert proc.stdout is not None
    stdout = proc.stdout

    def pump() -> None:
        for _ in range(count):
            lines.put(stdout.readline())

    threading.Thread(target=pump, daemon=True).start()
    out: list[str] = []
    deadline = time.monotonic() + seconds
    while len(out) < count:
        try:
            out.append(lines.get(timeout=max(0.01, deadline - time.monotonic())))
        except queue.Empty:
            break
    return out


@pytest.fixture(scope="module")
def served(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Served]:
    root = tmp_path_factory.mktemp("serve") / "root"
    root.mkdir()
    command = [sys.executable, "-m", "movingpunch", "serve", "fig4", "--port", "0"]
    proc = subprocess.Popen(
        [*command, "--root", str(root)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        lines = read_lines(proc, 2, 60)
        assert lines, "no output within 60 s"
        # Exactly one URL, carrying a fresh token.
        urls = re.findall(r"https?://\S+", "".join(lines))
        assert len(urls) == 1, lines
        url = urls[0]
        match = re.fullmatch(r"(http://127\.0\.0\.1:\d+)/\?token=([\w-]{32})", url)
        assert match is not None, url
        yield Served(proc, url, match[1], match[2], root)
    finally:
        proc.terminate()  # SIGTERM: the server stops cleanly, quickly
        try:
            _, err = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
            raise AssertionError("serve did not stop within 30 s of SIGTERM") from None
    assert proc.returncode == 0, err
    assert "Traceback" not in err, err


def get(url: str, headers: dict[str, str] | None = None) -> tuple[int, str, str]:
    """(status, body, Set-Cookie) of a GET; errors are statuses too."""
    request = urllib.request.Request(url, headers=headers or {})
    try:
        with urllib.request.urlopen(request, timeout=30) as response:
            body = response.read().decode("utf-8", "replace")
            return response.status, body, response.headers.get("Set-Cookie", "")
    except urllib.error.HTTPError as error:
        return error.code, error.read().decode("utf-8", "replace"), ""


def test_the_page_and_its_files_need_the_token(served: Served) -> None:
    status, body, _ = get(served.base + "/")
    assert status == 403
    assert "token" in body
    assert get(served.base + "/?token=" + served.token[:-1] + "x")[0] == 403
    assert get(served.base + "/?token=")[0] == 403
    status, page, cookie = get(served.url)
    assert status == 200
    assert "<html" in page.lower()
    assert "movingpunch" in page
    # The page connects its WebSocket and loads its files on the same host;
    # the cookie it sets is what authorises them (the token stays out of
    # scripts' reach and off other sites' requests).
    assert f'data-session-websocket-url="ws://127.0.0.1:{served.port}/ws"' in page
    assert f"movingpunch_token_{served.port}={served.token}" in cookie
    assert "HttpOnly" in cookie
    assert "SameSite=Strict" in cookie
    script = served.base + "/static/js/textual.js"
    assert get(script)[0] == 403
    assert get(script + "?token=nope")[0] == 403
    assert get(script + "?token=" + served.token)[0] == 200
    cookie_header = f"movingpunch_token_{served.port}={served.token}"
    assert get(script, {"Cookie": cookie_header})[0] == 200
    assert get(served.base + "/download/x")[0] == 403
    # The loopback aliases of the served host work too.
    assert get(served.url.replace("127.0.0.1", "localhost"))[0] == 200


def test_a_foreign_host_or_origin_is_refused(served: Served) -> None:
    # A page of another site (or a rebound DNS name) gets nothing, token or not.
    evil = {"Origin": "http://evil.example"}
    assert get(served.url, evil)[0] == 403
    assert get(served.url, {"Host": f"evil.example:{served.port}"})[0] == 403
    same = {"Origin": served.base}
    assert get(served.url, same)[0] == 200


async def handshake(
    served: Served,
    *,
    query: str = "",
    origin: str | None = None,
    cookies: dict[str, str] | None = None,
) -> int:
    """The HTTP status of a WebSocket handshake (101: upgraded)."""
    async with aiohttp.ClientSession(cookies=cookies) as session:
        try:
            ws = await session.ws_connect(served.ws + query, origin=origin)
        except aiohttp.WSServerHandshakeError as error:
            return error.status
        await ws.close()
        return 101


def test_the_websocket_needs_the_token_and_this_origin(served: Served) -> None:
    async def statuses() -> list[int]:
        token = f"?token={served.token}"
        return [
            await handshake(served, origin=served.base),
            await handshake(served, query="?token=wrong", origin=served.base),
            await handshake(served, query=token, origin="http://evil.example"),
            await handshake(served, query=token, origin="null"),
            await handshake(served, query=token),  # no Origin at all
            await handshake(
                served, cookies=served.cookie, origin="http://evil.example"
            ),
        ]

    assert asyncio.run(statuses()) == [403] * 6


class Session:
    """A browser's side of the app: keys in, screen text out."""

    def __init__(self, ws: aiohttp.ClientWebSocketResponse) -> None:
        self.ws = ws
        self.text = ""

    async def wait_for(self, phrase: str, seconds: float = 60) -> bool:
        """Reads the app's output until ``phrase`` appears (escape
        sequences removed) or ``seconds`` pass."""
        raw = ""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            try:
                msg = await asyncio.wait_for(
                    self.ws.receive(), max(0.05, deadline - time.monotonic())
                )
            except asyncio.TimeoutError:
                break
            if msg.type == aiohttp.WSMsgType.BINARY:
                raw += msg.data.decode("utf-8", "replace")
            elif msg.type != aiohttp.WSMsgType.TEXT:
                break  # closed
            self.text = ANSI.sub("", raw)
            if phrase in self.text:
                return True
        return False

    async def keys(self, *keys: str) -> None:
        for key in keys:  # one key per message, as the browser sends them
            await self.ws.send_json(["stdin", key])
            await asyncio.sleep(0.02)

    async def replace_path(self, path: str) -> None:
        """Clears the prompt's path (backspaces), types ``path``, enter."""
        await self.keys(*"\x7f" * 40, *path, "\r")


def test_the_app_answers_and_stays_in_its_folder(served: Served) -> None:
    """With the token and this Origin (as the browser sends them: the cookie
    of the page) the app runs, and its Save stays in the working folder."""
    escaped = served.root.parent / "escaped.toml"

    async def drive() -> tuple[bool, bool, bool, bool]:
        async with aiohttp.ClientSession(cookies=served.cookie) as session:
            ws = await session.ws_connect(
                served.ws + "?width=100&height=30", origin=served.base
            )
            app = Session(ws)
            await ws.send_json(["resize", {"width": 100, "height": 30}])
            ready = await app.wait_for("Recompute")
            await app.keys("s")
            prompt = await app.wait_for("Save the scene to")
            await app.replace_path("../escaped.toml")
            refused = await app.wait_for("../escaped.toml: outside the working")
            await app.replace_path("inside.toml")
            saved = await app.wait_for("saved inside.toml")
            await ws.close()
            return ready, prompt, refused, saved

    ready, prompt, refused, saved = asyncio.run(drive())
    assert ready, "the app sent no screen within 60 s"
    assert prompt
    assert refused
    assert saved
    assert not escaped.exists()
    assert (served.root / "inside.toml").is_file()


def run_serve(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "movingpunch", "serve", *args],
        capture_output=True,
        text=True,
        timeout=60,
    )


def test_a_busy_port_is_one_line_and_exit_2() -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        proc = run_serve("--port", str(port))
    assert proc.returncode == 2
    assert proc.stdout == ""  # nothing as if serving
    assert proc.stderr == f"movingpunch: error: port {port} on 127.0.0.1 is in use\n"


def test_a_remote_host_needs_allow_remote() -> None:
    proc = run_serve("--host", "0.0.0.0", "--port", "0")
    assert proc.returncode == 2
    assert proc.stdout == ""
    lines = proc.stderr.splitlines()
    assert len(lines) == 1, proc.stderr
    assert "0.0.0.0 is reachable from other machines" in lines[0]
    assert "--allow-remote" in lines[0]
    # With the flag: a one-line warning first (here the port is taken, so it
    # stops there without serving).
    with socket.socket() as taken:
        taken.bind(("0.0.0.0", 0))
        taken.listen()
        port = taken.getsockname()[1]
        proc = run_serve("--host", "0.0.0.0", "--allow-remote", "--port", str(port))
    assert proc.returncode == 2
    assert proc.stdout == ""
    warning, error = proc.stderr.splitlines()
    assert warning.startswith("movingpunch: warning: serving on 0.0.0.0")
    assert error == f"movingpunch: error: port {port} on 0.0.0.0 is in use"


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("--port", "70000"), "port: 70000 is out of range (allowed: 0 to 65535)"),
        (("--port", "-1"), "port: -1 is out of range"),
        (("--root", "/no/such/dir"), "root: /no/such/dir is not an existing"),
        (("no-such-scene",), "no-such-scene"),
    ],
)
def test_bad_serve_arguments_are_one_line(args: tuple[str, ...], message: str) -> None:
    proc = run_serve(*args)
    assert proc.returncode == 2
    assert proc.stdout == ""
    lines = proc.stderr.splitlines()
    assert len(lines) == 1, proc.stderr
    assert message in lines[0]
