"""`gearhead serve`: the app in a browser, through textual-serve (Textualize's package).

Each browser tab that opens the page starts its own app process (textual-serve runs `python -m
gearhead.tui.served` with Textual's web driver) and sees the same cards as the terminal app.

Local only by default (127.0.0.1). Bound to any other address, anyone who can reach it could use
the app (and its file dialogs, which browse this machine's files), so the server then asks for an
access token: it prints a warning and the URL with `?token=…` once; the page sets a cookie from it,
and the app's websocket and downloads are refused without it (HTTP 403).
"""

from __future__ import annotations

import ipaddress
import secrets
import shlex
import sys
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


def app_command() -> str:
    """The shell command textual-serve starts for each browser session."""
    return f"{shlex.quote(sys.executable)} -m gearhead.tui.served"


def public_url(host: str, port: int) -> str:
    """The address the page tells the browser to connect back to: a wildcard bind (0.0.0.0, ::)
    is no address a browser can reach, so this machine's name stands for it."""
    import socket

    shown = socket.gethostname() if host in ("0.0.0.0", "::", "") else host
    if ":" in shown and not shown.startswith("["):
        shown = f"[{shown}]"
    return f"http://{shown}:{port}"


def make_server(host: str, port: int, token: str | None, url: str | None = None):
    """A textual-serve Server for the app; with `token`, every page, websocket and download needs
    it (as ?token= or the cookie the page sets)."""
    from contextvars import ContextVar

    from aiohttp import web
    from textual_serve.server import Server

    from gearhead.core import share

    session_command: ContextVar[str | None] = ContextVar("session_command", default=None)

    class GearheadServer(Server):
        """textual-serve's server, with the access token and ?p=: the page's share code goes in a
        short-lived cookie, and the websocket that follows starts its app with `--open CODE`
        (textual-serve reads `self.command` when it starts a session; here it is per request,
        through a context variable, so two sessions starting at once cannot swap codes)."""

        @property
        def command(self) -> str:
            return session_command.get() or self._base_command

        @command.setter
        def command(self, value: str) -> None:
            self._base_command = value

        def _allowed(self, request) -> bool:
            # a page of another site may open a websocket to this machine (browsers let it): a
            # request a browser marks as from another origin is refused, on the loopback too
            origin = request.headers.get("Origin")
            if origin is not None and urlsplit(origin).netloc not in (
                request.host,
                urlsplit(self.public_url).netloc,
            ):
                return False
            if token is None:
                return True
            given = request.query.get("token") or request.cookies.get(TOKEN_COOKIE) or ""
            # bytes: compare_digest refuses a str with non-ASCII characters (a 500 for '?token=é')
            return secrets.compare_digest(given.encode("utf-8", "replace"), token.encode())

        def _refuse(self):
            return web.Response(
                status=403,
                text="Gearhead: refused (a request from another site's page, or without the access "
                "token: the URL the server printed, with ?token=).",
            )

        async def handle_index(self, request):
            if not self._allowed(request):
                return self._refuse()
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
            if not self._allowed(request):
                return self._refuse()
            code = share.find_code(request.cookies.get(OPEN_COOKIE, ""))
            if code is not None:
                session_command.set(f"{self._base_command} --open {shlex.quote(code)}")
            return await super().handle_websocket(request)

        async def handle_download(self, request):
            if not self._allowed(request):
                return self._refuse()
            return await super().handle_download(request)

    return GearheadServer(app_command(), host=host, port=port, title="Gearhead", public_url=url)


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


def run(args) -> int:
    from gearhead.core.errors import InputError

    if not 0 < args.port < 65536:
        raise InputError("--port", f"must be from 1 to 65535, got {args.port}")
    try:
        import textual_serve  # noqa: F401
    except ImportError:
        raise InputError("serve", "needs the textual-serve package (pip install textual-serve)") from None
    token = None
    url = args.public_url or public_url(args.host, args.port)
    if not is_loopback(args.host):
        token = secrets.token_urlsafe(18)
        print(
            f"gearhead: warning: serving on {args.host}, beyond this machine: anyone who can reach it and has "
            f"the token can use the app, including its file dialogs (which browse this machine's files).\n"
            f"gearhead: open {url}/?token={token}",
            file=sys.stderr,
        )
    else:
        print(f"gearhead: open {url}/ (this machine only; Ctrl+C stops)", file=sys.stderr)
    make_server(args.host, args.port, token, url).serve()
    return 0
