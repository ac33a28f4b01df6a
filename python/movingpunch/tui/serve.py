"""``movingpunch serve``: the terminal UI in a web browser (textual-serve),
behind a per-start token and an Origin check.

Every start makes a random token and prints the one URL that carries it,
``http://HOST:PORT/?token=...``. Each request (the page, its static files,
downloads, the WebSocket that drives the app) needs the token, either in the
query (``?token=``) or in the cookie the page sets on its first authorised
load (HttpOnly, SameSite=Strict); without it the answer is 403. A request
that carries an Origin (always the WebSocket, which must) is refused with 403
unless the Origin is this server as the browser reached it
(``http://HOST:PORT`` with HOST the served host or, on a loopback bind, one
of its loopback names). Host headers naming another server are refused too
(DNS rebinding).

The socket is bound before anything is printed: a busy port is one line and
exit status 2 (``ServeError``), never a "Serving" line and a traceback.

Imports textual-serve (and aiohttp): load only for ``movingpunch serve``.
"""

from __future__ import annotations

import asyncio
import contextlib
import errno
import hmac
import ipaddress
import logging
import os
import secrets
import signal
import socket
import sys
from collections.abc import Awaitable, Callable
from typing import Any

import aiohttp_jinja2
from aiohttp import web
from textual_serve.server import Server, to_int

from movingpunch.errors import ServeError

TOKEN_BYTES = 24
"""``secrets.token_urlsafe(TOKEN_BYTES)``: 192 random bits per start."""

LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")
"""Host names a loopback bind also answers to (same machine)."""

SHUTDOWN_SECONDS = 3.0
"""How long open sessions get to end on Ctrl+C / SIGTERM."""

Handler = Callable[[web.Request], Awaitable[web.StreamResponse]]


def _url_host(host: str) -> str:
    """``host`` as it goes in a URL (IPv6 literals in brackets)."""
    return f"[{host}]" if ":" in host and not host.startswith("[") else host


def resolve(host: str, port: int) -> list[tuple[Any, ...]]:
    """The addresses ``host:port`` binds to (getaddrinfo, passive)."""
    try:
        return socket.getaddrinfo(
            host or None, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE
        )
    except socket.gaierror as exc:
        raise ServeError(f"host: cannot resolve {host!r}: {exc.strerror}") from None


def is_loopback(infos: list[tuple[Any, ...]]) -> bool:
    """True if every address is a loopback address (this machine only)."""
    if not infos:
        return False
    for info in infos:
        address = str(info[4][0]).split("%", 1)[0]
        try:
            if not ipaddress.ip_address(address).is_loopback:
                return False
        except ValueError:
            return False
    return True


def bind(host: str, port: int, infos: list[tuple[Any, ...]]) -> socket.socket:
    """A listening socket on the first address of ``infos``; a busy port or
    any other refusal is a ServeError (one line)."""
    family, kind, proto, _, address = infos[0]
    sock = socket.socket(family, kind, proto)
    try:
        if os.name == "posix":  # restart quickly; never share a live port
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(address)
        sock.listen(128)
    except OSError as exc:
        sock.close()
        if exc.errno == errno.EADDRINUSE:
            raise ServeError(f"port {port} on {host} is in use") from None
        reason = exc.strerror or type(exc).__name__
        raise ServeError(f"cannot listen on {host} port {port}: {reason}") from None
    sock.setblocking(False)
    return sock


class GuardedServer(Server):
    """textual-serve's server with a token, an Origin check and a Host check.

    ``allowed_hosts``: the ``host:port`` values a request's Host may name
    (None: any, for a wildcard bind); the Origin must then be
    ``http://`` + that Host.
    """

    def __init__(
        self,
        command: str,
        *,
        token: str,
        port: int,
        url_host: str,
        allowed_hosts: frozenset[str] | None,
        title: str,
    ) -> None:
        super().__init__(command, host=url_host, port=port, title=title)
        self.token = token
        self.allowed_hosts = allowed_hosts
        self.cookie_name = f"movingpunch_token_{port}"
        self.url = f"http://{url_host}:{port}/?token={token}"

    # -- checks ---------------------------------------------------------------

    def _token_ok(self, request: web.Request) -> bool:
        expected = self.token.encode("ascii")
        for given in (
            request.query.get("token"),
            request.cookies.get(self.cookie_name),
        ):
            if given is not None and hmac.compare_digest(
                given.encode("utf-8", "replace"), expected
            ):
                return True
        return False

    def _host_ok(self, request: web.Request) -> bool:
        host = request.headers.get("Host", "")
        return self.allowed_hosts is None or host.lower() in self.allowed_hosts

    def _origin_ok(self, request: web.Request) -> bool:
        origin = request.headers.get("Origin")
        host = request.headers.get("Host", "")
        return origin is not None and origin.lower() == f"http://{host}".lower()

    @web.middleware
    async def guard(self, request: web.Request, handler: Handler) -> web.StreamResponse:
        """403 for a missing or wrong token, a foreign Host or Origin, and a
        WebSocket without an Origin."""
        if not self._host_ok(request):
            raise web.HTTPForbidden(text="unknown host\n")
        wants_socket = request.headers.get("Upgrade", "").lower() == "websocket"
        if (wants_socket or "Origin" in request.headers) and not self._origin_ok(
            request
        ):
            raise web.HTTPForbidden(text="cross-origin request refused\n")
        if not self._token_ok(request):
            raise web.HTTPForbidden(
                text="this server needs the token: open the URL it printed\n"
            )
        return await handler(request)

    # -- textual-serve overrides ----------------------------------------------

    async def _make_app(self) -> web.Application:
        app = await super()._make_app()
        app.middlewares.append(self.guard)
        return app

    def initialize_logging(self) -> None:
        logging.basicConfig(
            level=logging.WARNING,
            format="movingpunch serve: %(message)s",
            stream=sys.stderr,
        )

    async def on_startup(self, app: web.Application) -> None:
        """Nothing: the URL is printed once the socket listens."""

    async def handle_index(self, request: web.Request) -> web.Response:
        """The page, with its static files and WebSocket on the host the
        browser used (already checked), and the token cookie set."""
        base = f"http://{request.host}"
        context = {
            "font_size": to_int(request.query.get("fontsize", "16"), 16),
            "app_websocket_url": f"ws://{request.host}/ws",
            "config": {"static": {"url": f"{base}/static/"}},
            "application": {"name": self.title},
        }
        response = aiohttp_jinja2.render_template("app_index.html", request, context)
        response.set_cookie(
            self.cookie_name,
            self.token,
            httponly=True,
            samesite="Strict",
            path="/",
        )
        response.headers["Cache-Control"] = "no-store"
        response.headers["Referrer-Policy"] = "no-referrer"
        return response

    # -- running --------------------------------------------------------------

    async def run(self, sock: socket.socket) -> None:
        """Serves on ``sock`` until SIGINT or SIGTERM."""
        app = await self._make_app()
        runner = web.AppRunner(
            app,
            handle_signals=False,
            access_log=None,
            shutdown_timeout=SHUTDOWN_SECONDS,
        )
        await runner.setup()
        try:
            site = web.SockSite(runner, sock, shutdown_timeout=SHUTDOWN_SECONDS)
            await site.start()
            print(f"Serving movingpunch on {self.url}", flush=True)
            print("Open that URL in a browser; Ctrl+C stops.", flush=True)
            stop = asyncio.Event()
            loop = asyncio.get_running_loop()
            for sig in (signal.SIGINT, signal.SIGTERM):
                # Not on Windows: there Ctrl+C is a KeyboardInterrupt.
                with contextlib.suppress(NotImplementedError, RuntimeError):
                    loop.add_signal_handler(sig, stop.set)
            await stop.wait()
        finally:
            await runner.cleanup()


def serve(
    command: list[str],
    *,
    host: str,
    port: int,
    allow_remote: bool,
    title: str,
) -> None:
    """Binds ``host:port`` (0: any free port), prints the token URL, serves
    ``command`` (one app per visitor) until interrupted.

    Raises ServeError (busy port, unresolvable host, a non-loopback host
    without ``allow_remote``) before printing anything.
    """
    import shlex

    if not 0 <= port <= 65535:
        raise ServeError(f"port: {port} is out of range (allowed: 0 to 65535)")
    infos = resolve(host, port)
    loopback = is_loopback(infos)
    if not loopback and not allow_remote:
        raise ServeError(
            f"host: {host or '(all interfaces)'} is reachable from other "
            "machines; pass --allow-remote to serve on it anyway "
            "(allowed without it: a loopback host such as 127.0.0.1)"
        )
    if not loopback:
        sys.stderr.write(
            f"movingpunch: warning: serving on {host or '(all interfaces)'}: "
            "anyone who can reach this port and has the token drives the app "
            "and its files (no TLS: the token travels in clear)\n"
        )
    sock = bind(host, port, infos)
    bound_port = int(sock.getsockname()[1])
    shown = _url_host(host) if host else "0.0.0.0"
    wildcard = host in ("", "0.0.0.0", "::", "[::]")
    allowed: frozenset[str] | None
    if wildcard:
        allowed = None
    else:
        names = {shown, *LOOPBACK_NAMES} if loopback else {shown}
        hosts = {f"{name}:{bound_port}" for name in names}
        if bound_port == 80:  # browsers leave the default port out of Host
            hosts |= names
        allowed = frozenset(h.lower() for h in hosts)
    server = GuardedServer(
        shlex.join(command),
        token=secrets.token_urlsafe(TOKEN_BYTES),
        port=bound_port,
        url_host=shown,
        allowed_hosts=allowed,
        title=title,
    )
    server.initialize_logging()
    try:
        asyncio.run(server.run(sock))
    finally:
        sock.close()
