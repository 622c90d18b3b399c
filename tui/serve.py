"""`gearhead serve`: the app in a browser, through textual-serve (Textualize's package).

Each browser tab that opens the page starts its own app process (`python -m gearhead.tui.served`
with Textual's web driver, tui/served.py; its websocket: tui/serve_session.py) and sees the same
cards as the terminal app.

Local only by default (127.0.0.1). There every request must name the loopback and this port in its
Host header: a page of another site whose name was made to resolve to 127.0.0.1 (DNS rebinding)
sends its own name and is refused. Bound to any other address, or behind a --public-url that is
not the loopback, anyone who can reach it could use the app (and its file dialogs), so the server
then asks for an access token: it prints a warning and the URL with `?token=…` once; the page sets
a cookie from it, and the page, the app's websocket and downloads are refused without it (HTTP 403).
At most --max-sessions apps run at once, each with a bounded terminal size and memory, and ended
when its client goes; a served app reads and writes files only in the Gearhead folder unless
--allow-paths adds folders.
"""

from __future__ import annotations

import ipaddress
import os
import secrets
import shlex
import sys
from pathlib import Path
from urllib.parse import urlsplit

TOKEN_COOKIE = "gearhead_token"
OPEN_COOKIE = "gearhead_open"  # the share code of the page's ?p=, for the websocket that follows
MAX_OPEN_COOKIE = 3800  # a cookie holds about 4 KB; a longer code is refused with a notice


def is_loopback(host: str) -> bool:
    if host.lower() in ("localhost", "localhost."):
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:  # a host name other than localhost: may resolve anywhere
        return False


MAX_SESSIONS = 4  # apps at once (each a process of 60-220 MB resident), unless --max-sessions says otherwise
SESSION_MEMORY_MB = 2048  # address space of one app (Linux): normal use peaked at 1.3 GB (221 MB resident)


def host_is_ours(host: str | None, port: int) -> bool:
    """Whether a request's Host header names the loopback and `port` (an absent port is 80)."""
    if not host:
        return False
    try:
        parts = urlsplit(f"//{host}")
        given = parts.port or 80
    except ValueError:  # a port that is not a number, or out of range
        return False
    return given == port and parts.hostname is not None and is_loopback(parts.hostname)


def app_command(memory_mb: int = 0, allow_paths: list[str] = (), open_code: str | None = None) -> str:
    """The shell command textual-serve starts for a browser session (exec: the shell becomes the
    app, so ending the process ends the app)."""
    words = [sys.executable, "-m", "gearhead.tui.served"]
    if memory_mb:
        words += ["--memory", str(memory_mb)]
    for folder in allow_paths:
        words += ["--allow-paths", folder]
    if open_code is not None:
        words += ["--open", open_code]
    return ("exec " if os.name == "posix" else "") + shlex.join(words)


def public_url(host: str, port: int) -> str:
    """The address the page tells the browser to connect back to: a wildcard bind (0.0.0.0, ::)
    is no address a browser can reach, so this machine's name stands for it."""
    import socket

    shown = socket.gethostname() if host in ("0.0.0.0", "::", "") else host
    if ":" in shown and not shown.startswith("["):
        shown = f"[{shown}]"
    return f"http://{shown}:{port}"


def needs_token(host: str, url: str) -> bool:
    """A token unless both the address listened on and the one browsers use are the loopback."""
    return not (is_loopback(host) and is_loopback(urlsplit(url).hostname or ""))


def one_line_for_malformed_requests(record) -> bool:
    """A logging filter: aiohttp logs a request it cannot parse (a bad header, a line over 8 KB)
    with a traceback; it is the client's error, said in one line."""
    from aiohttp.http_exceptions import HttpProcessingError

    error = record.exc_info[1] if record.exc_info else None
    if isinstance(error, HttpProcessingError):
        reason = (error.message or type(error).__name__).splitlines()[0][:100]
        record.msg, record.args, record.exc_info = f"{record.getMessage()}: {error.code} {reason}", (), None
    return True


def make_server(
    host: str,
    port: int,
    token: str | None,
    url: str | None = None,
    max_sessions: int = MAX_SESSIONS,
    memory_mb: int = SESSION_MEMORY_MB,
    allow_paths: list[str] = (),
):
    """A textual-serve Server for the app; with `token`, every page, websocket and download needs
    it (as ?token= or the cookie the page sets)."""
    import asyncio
    import logging

    import aiohttp_jinja2
    import jinja2
    from aiohttp import web
    from rich.logging import RichHandler
    from textual_serve.server import Server

    from gearhead.core import share

    from . import serve_session

    log = logging.getLogger("gearhead.serve")
    loopback = is_loopback(host)
    live: set = set()  # the sessions' tasks, to count and to end with the server

    class GearheadServer(Server):
        """textual-serve's server, with the checks above, the access token and ?p= (the page's
        share code goes in a short-lived cookie, and the websocket that follows starts its app
        with `--open CODE`). Its own application (`serve`): textual-serve's routes list
        /static/'s folder and have no hook for a check on every request."""

        def initialize_logging(self) -> None:
            # no local variables in a traceback: they hold the token and whatever a request sent
            handler = RichHandler(show_path=False, show_time=False, console=self.console)
            handler.addFilter(one_line_for_malformed_requests)
            logging.basicConfig(
                level="DEBUG" if self.debug else "INFO", format="%(message)s", handlers=[handler]
            )

        def _allowed(self, request) -> bool:
            ours = request.headers.get("Host")
            public = urlsplit(self.public_url).netloc.lower()
            # the loopback: the Host must name it (or the public URL); elsewhere the token guards
            if loopback and not host_is_ours(ours, port) and (ours or "").lower() != public:
                return False
            # a page of another site may open a websocket to this machine (browsers let it): a
            # request a browser marks as from another origin is refused, on the loopback too
            origin = request.headers.get("Origin")
            if origin is not None:
                netloc = urlsplit(origin).netloc.lower()
                if netloc not in ((ours or "").lower(), public) and not (
                    loopback and host_is_ours(netloc, port)
                ):
                    return False
            if token is None or (loopback and host_is_ours(ours, port)):  # the loopback needs none
                return True
            given = request.query.get("token") or request.cookies.get(TOKEN_COOKIE) or ""
            # bytes: compare_digest refuses a str with non-ASCII characters (a 500 for '?token=é')
            return secrets.compare_digest(given.encode("utf-8", "replace"), token.encode())

        @web.middleware
        async def guard(self, request, handler):
            if not self._allowed(request):
                return web.Response(
                    status=403,
                    text="Gearhead: refused (a request naming another site, from another site's page, "
                    "or without the access token: the URL the server printed, with ?token=).",
                )
            if request.path.startswith("/static/"):
                try:
                    return await handler(request)
                except (OSError, ValueError):  # a name the file system refuses (too long): none such
                    raise web.HTTPNotFound() from None
            return await handler(request)

        async def handle_index(self, request):
            response = await super().handle_index(request)
            if token is not None:
                response.set_cookie(TOKEN_COOKIE, token, httponly=True, samesite="Strict")
            code = share.find_code(request.query.get("p", ""))
            if code is not None and len(code) <= MAX_OPEN_COOKIE:
                response.set_cookie(OPEN_COOKIE, code, httponly=True, samesite="Strict", max_age=120)
            else:  # a page without ?p= opens the default card, whatever an earlier page carried
                response.del_cookie(OPEN_COOKIE)
            return response

        async def handle_websocket(self, request):
            if len(live) >= max_sessions:
                log.info("gearhead: a session refused: %d open (--max-sessions)", len(live))
                return web.Response(
                    status=503,
                    text=f"Gearhead: {len(live)} sessions are open, the most this server allows "
                    "(gearhead serve --max-sessions): close a tab, or try again shortly.",
                )
            code = share.find_code(request.cookies.get(OPEN_COOKIE, ""))
            command = app_command(memory_mb, allow_paths, code)
            task = asyncio.current_task()
            live.add(task)
            try:  # counted until its app's process has ended
                return await serve_session.run_session(request, command, self.download_manager, self.debug)
            finally:
                live.discard(task)

        def make_app(self) -> web.Application:
            app = web.Application(middlewares=[self.guard])
            aiohttp_jinja2.setup(app, loader=jinja2.FileSystemLoader(self.templates_path))
            app.add_routes(
                [
                    web.get("/", self.handle_index, name="index"),
                    web.get("/ws", self.handle_websocket, name="websocket"),
                    web.get("/download/{key}", self.handle_download, name="download"),
                    web.static("/static", self.statics_path, show_index=False, name="static"),
                ]
            )
            app.on_startup.append(self.on_startup)
            app.on_shutdown.append(self.end_sessions)
            return app

        async def end_sessions(self, app) -> None:
            for task in list(live):  # each session's handler kills its app as it ends
                task.cancel()
            if live:
                await asyncio.wait(list(live), timeout=serve_session.STOP_GRACE + 5)

        def serve(self, debug: bool = False) -> None:
            self.debug = debug
            self.initialize_logging()
            web.run_app(
                self.make_app(), host=self.host, port=self.port, print=lambda *a: None, shutdown_timeout=5
            )

    return GearheadServer(
        app_command(memory_mb, allow_paths), host=host, port=port, title="Gearhead", public_url=url
    )


def add_parser(sub) -> None:
    sv = sub.add_parser(
        "serve", help="the app in a browser (textual-serve); local only unless --host says otherwise"
    )
    sv.add_argument(
        "--host", default="127.0.0.1", help="address to listen on (default 127.0.0.1: this machine only)"
    )
    sv.add_argument("--port", type=int, default=8000, help="port (default 8000)")
    sv.add_argument(
        "--public-url",
        metavar="URL",
        help="the address browsers reach this server by, if not http://HOST:PORT (e.g. behind a proxy)",
    )
    sv.add_argument(
        "--max-sessions",
        type=int,
        default=MAX_SESSIONS,
        metavar="N",
        help=f"browser sessions (apps) at once; more are refused until one ends (default {MAX_SESSIONS})",
    )
    sv.add_argument(
        "--session-memory",
        type=int,
        default=SESSION_MEMORY_MB,
        metavar="MB",
        help=f"address space of each session's app, Linux only; 0: no bound (default {SESSION_MEMORY_MB})",
    )
    sv.add_argument(
        "--allow-paths",
        action="append",
        default=[],
        metavar="DIR",
        help="a folder a session's file dialogs may use beside the Gearhead folder (repeatable; / for any)",
    )


def run(args) -> int:
    from gearhead.core.errors import InputError

    if not 0 < args.port < 65536:
        raise InputError("--port", f"must be from 1 to 65535, got {args.port}")
    try:
        import textual_serve  # noqa: F401
    except ImportError:
        raise InputError("serve", "needs the textual-serve package (pip install textual-serve)") from None
    if not 1 <= args.max_sessions <= 1000:
        raise InputError("--max-sessions", f"must be from 1 to 1000, got {args.max_sessions}")
    if args.session_memory != 0 and not 256 <= args.session_memory <= 1 << 20:
        raise InputError(
            "--session-memory", f"must be 0 (no bound) or from 256 to 1048576 MB, got {args.session_memory}"
        )
    for folder in args.allow_paths:
        if not Path(folder).expanduser().is_dir():
            raise InputError("--allow-paths", "not a folder", folder)
    allow = [str(Path(folder).expanduser().resolve()) for folder in args.allow_paths]
    token = None
    url = args.public_url or public_url(args.host, args.port)
    if needs_token(args.host, url):
        token = secrets.token_urlsafe(18)
        print(
            f"gearhead: warning: serving on {url if is_loopback(args.host) else args.host}, beyond this machine: anyone who can reach it and has "
            f"the token can use the app, including its file dialogs (which reach this machine's files).\n"
            f"gearhead: open {url}/?token={token}",
            file=sys.stderr,
        )
    else:
        print(f"gearhead: open {url}/ (this machine only; Ctrl+C stops)", file=sys.stderr)
    make_server(args.host, args.port, token, url, args.max_sessions, args.session_memory, allow).serve()
    return 0
