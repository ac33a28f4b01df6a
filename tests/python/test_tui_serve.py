"""`movingpunch serve` really serves the app over HTTP on localhost (the
`serve` extra is installed by scripts/setup.sh)."""

from __future__ import annotations

import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port: int = s.getsockname()[1]
        return port


def test_serve_answers_on_localhost() -> None:
    port = free_port()
    proc = subprocess.Popen(
        [sys.executable, "-m", "movingpunch", "serve", "fig4", "--port", str(port)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        page = ""
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and proc.poll() is None:
            try:
                with urllib.request.urlopen(
                    f"http://localhost:{port}/", timeout=5
                ) as response:
                    assert response.status == 200
                    page = response.read().decode("utf-8", "replace")
                    break
            except (urllib.error.URLError, ConnectionError):
                time.sleep(0.3)
        assert proc.poll() is None, proc.communicate()
        # textual-serve's page: a terminal in the browser, connected back by a
        # websocket to the app it starts per visitor.
        assert "<html" in page.lower()
        assert "movingpunch" in page
    finally:
        proc.terminate()
        try:
            proc.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
