"""One browser session of `gearhead serve` (tui/serve.py): the websocket and the app process behind it.

Our own websocket handler in place of textual-serve's `Server.handle_websocket` (1.1.3), which has
no hook to bound the terminal's size, to end the app when its client goes quiet, or to read a
malformed message without a traceback. It still starts and talks to the app through textual-serve's
AppService (the packet protocol Textual's web driver speaks)."""

from __future__ import annotations

import asyncio
import json
import logging
from contextlib import suppress

from aiohttp import WSMsgType, web
from textual_serve.app_service import AppService

log = logging.getLogger("gearhead.serve")

MAX_WIDTH, MAX_HEIGHT = 500, 200  # cells: a 4K screen at the page's font is about 400 x 130
HEARTBEAT = 5.0  # s between pings; no pong within half of it ends the session (aiohttp)
SEND_TIMEOUT = 10.0  # s a client may take to accept the screen's bytes before its session ends
STOP_GRACE = 3.0  # s for an app to quit once asked, before it is killed
MAX_MESSAGE = 1 << 20  # bytes in one websocket message (a paste is at most 100 000 characters)


def terminal_size(width: object, height: object) -> tuple[int, int] | None:
    """A size the client asked for, within 1..MAX_WIDTH x 1..MAX_HEIGHT; None if it is not two
    whole numbers."""
    try:
        w, h = int(width), int(height)  # type: ignore[call-overload]
    except (TypeError, ValueError, OverflowError):
        return None
    return min(max(w, 1), MAX_WIDTH), min(max(h, 1), MAX_HEIGHT)


async def run_session(request: web.Request, command: str, download_manager, debug: bool = False):
    """Serve one websocket: start the app (`command`), pass keys and sizes to it and its screen
    back, and make sure the app's process has ended when this returns."""
    websocket = web.WebSocketResponse(heartbeat=HEARTBEAT, max_msg_size=MAX_MESSAGE)
    width, height = terminal_size(request.query.get("width", 80), request.query.get("height", 24)) or (80, 24)
    await websocket.prepare(request)

    async def write_bytes(data: bytes) -> None:
        await write(websocket.send_bytes, data)

    async def write_str(data: str) -> None:
        await write(websocket.send_str, data)

    async def write(send, data) -> None:
        # a client that stops reading would hold the app's output (and the app) forever: after
        # SEND_TIMEOUT its connection is dropped; what the app still writes is discarded
        if websocket.closed:
            return
        try:
            await asyncio.wait_for(send(data), SEND_TIMEOUT)
        except (TimeoutError, ConnectionError, RuntimeError):
            if request.transport is not None:
                request.transport.abort()

    app_service = AppService(
        command,
        write_bytes=write_bytes,
        write_str=write_str,
        close=websocket.close,
        download_manager=download_manager,
        debug=debug,
    )
    try:
        await app_service.start(width, height)
        try:
            await _messages(websocket, app_service)
        except (ConnectionError, RuntimeError) as exc:  # the client went mid-reply: one line, no traceback
            log.info("gearhead: a session ended: %s", exc)
        with suppress(TimeoutError):
            await asyncio.wait_for(app_service.stop(), STOP_GRACE)
    finally:
        await _end(app_service)
        if not websocket.closed:
            with suppress(Exception):
                await asyncio.wait_for(websocket.close(), 1)
    return websocket


async def _messages(websocket: web.WebSocketResponse, app_service: AppService) -> None:
    """The client's messages until it goes (closes, or misses a heartbeat); one that is not
    textual-serve's ["stdin"|"resize"|"ping"|"blur"|"focus", data] is ignored."""
    async for message in websocket:
        if message.type != WSMsgType.TEXT:
            continue
        try:
            envelope = json.loads(message.data)
        except (ValueError, RecursionError):  # not JSON, or nested past Python's limit
            continue
        if not isinstance(envelope, list) or not envelope or not isinstance(envelope[0], str):
            continue
        kind, data = envelope[0], envelope[1] if len(envelope) > 1 else None
        if kind == "stdin" and isinstance(data, str):
            # errors="replace": a lone surrogate ("\ud800" in JSON) cannot be encoded as UTF-8
            await app_service.send_bytes(data.encode("utf-8", "replace"))
        elif kind == "resize" and isinstance(data, dict):
            size = terminal_size(data.get("width"), data.get("height"))
            if size is not None:
                await app_service.set_terminal_size(*size)
        elif kind == "ping":
            await websocket.send_json(["pong", data])
        elif kind == "blur":
            await app_service.blur()
        elif kind == "focus":
            await app_service.focus()


async def _end(app_service: AppService) -> None:
    """Kill the app's process if it has not quit (a long computation, or a full pipe)."""
    # textual-serve 1.1.3 gives no public handle to the process it started: its attribute is read here
    process = getattr(app_service, "_process", None)
    if process is None:
        return
    if process.returncode is None:
        with suppress(ProcessLookupError):
            process.kill()
        with suppress(TimeoutError):
            await asyncio.wait_for(process.wait(), 5)
    if process.returncode not in (0, None):  # e.g. -9 (killed), or out of its memory bound
        log.info("gearhead: a session's app ended with status %s", process.returncode)
