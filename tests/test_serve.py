"""`gearhead serve` (tui/serve.py): loopback by default, a token beyond it, and the app working in
a real headless browser (Debian's chromium, driven over the DevTools protocol with aiohttp, which
textual-serve already installs). The browser test is skipped, with the reason, where no chromium
is installed (.ci/run installs it)."""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from contextlib import contextmanager
from pathlib import Path

import pytest

from gearhead.tui import serve

GEARHEAD = str(Path(sys.executable).with_name("gearhead"))
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextmanager
def running(*args: str):
    """A process for the test's duration, stopped (by its id) however the test ends."""
    process = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        yield process
    finally:
        process.terminate()
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(10)


def wait_for(url: str, timeout: float = 30) -> int:
    """The HTTP status of `url` once the server answers."""
    deadline = time.monotonic() + timeout
    while True:
        try:
            with urllib.request.urlopen(url, timeout=5) as response:
                return response.status
        except urllib.error.HTTPError as exc:
            return exc.code
        except OSError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.2)


@pytest.mark.parametrize(
    "host,loopback",
    [("127.0.0.1", True), ("localhost", True), ("::1", True), ("[::1]", True), ("127.5.0.1", True),
     ("0.0.0.0", False), ("192.168.1.4", False), ("::", False), ("example.org", False)],
)  # fmt: skip
def test_only_loopback_addresses_are_local(host, loopback):
    assert serve.is_loopback(host) is loopback


def test_local_by_default_and_a_token_beyond_loopback():
    port = free_port()
    with running(GEARHEAD, "serve", "--port", str(port)) as server:
        assert wait_for(f"http://127.0.0.1:{port}/") == 200  # loopback: no token asked
        assert "this machine only" in server.stderr.readline()
    port = free_port()
    with running(GEARHEAD, "serve", "--host", "0.0.0.0", "--port", str(port)) as server:
        warning, opening = server.stderr.readline(), server.stderr.readline()
        assert "warning" in warning and "beyond this machine" in warning
        token = re.search(r"\?token=([\w-]+)", opening)[1]
        assert len(token) >= 20
        assert wait_for(f"http://127.0.0.1:{port}/") == 403
        assert wait_for(f"http://127.0.0.1:{port}/ws") == 403
        assert wait_for(f"http://127.0.0.1:{port}/?token=wrong") == 403
        assert wait_for(f"http://127.0.0.1:{port}/?token={token}") == 200
        request = urllib.request.Request(
            f"http://127.0.0.1:{port}/", headers={"Cookie": f"gearhead_token={token}"}
        )
        with urllib.request.urlopen(request, timeout=5) as response:  # the cookie the page set
            assert response.status == 200


def test_a_bad_port_is_refused_in_one_line():
    out = subprocess.run([GEARHEAD, "serve", "--port", "70000"], capture_output=True, text=True, timeout=60)
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and "--port" in out.stderr


# The page's own script keeps the terminal to itself; this one, added before the page loads,
# records what the server streams to it (the app's screen as terminal bytes).
RECORDER = """
window.__screen = "";
const Native = window.WebSocket;
window.WebSocket = function (url, protocols) {
  window.__socket_url = url;
  const socket = protocols === undefined ? new Native(url) : new Native(url, protocols);
  const decoder = new TextDecoder();
  socket.addEventListener("message", (event) => {
    if (typeof event.data !== "string") window.__screen += decoder.decode(new Uint8Array(event.data), {stream: true});
  });
  return socket;
};
window.WebSocket.prototype = Native.prototype;
"""

CURSOR_AND_TEXT = re.compile(r"\x1b\[(\d+);(\d+)H((?:[^\x1b]|\x1b\[[0-9;]*m)*)")
ANSI = re.compile(r"\x1b\[[0-9;?<>=]*[A-Za-z~]|\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)|\x1b[()][A-Z0-9]|\x1b[=>78]")


class Page:
    """One browser tab over the DevTools protocol."""

    def __init__(self, ws):
        self.ws, self.next_id = ws, 0

    async def send(self, method: str, **params):
        self.next_id += 1
        await self.ws.send_json({"id": self.next_id, "method": method, "params": params})
        while True:
            message = json.loads((await self.ws.receive()).data)
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError(message["error"])
                return message.get("result", {})

    async def screen(self) -> str:
        return ANSI.sub("", await self.evaluate("window.__screen || ''"))

    async def wait_for_text(self, text: str, timeout: float = 60, after: int = 0) -> str:
        deadline = time.monotonic() + timeout
        while True:
            screen = await self.screen()
            if text in screen[after:]:
                return screen
            if time.monotonic() > deadline:
                raise AssertionError(f"{text!r} never shown; the last screen text: {screen[-600:]!r}")
            await asyncio.sleep(0.25)

    async def evaluate(self, expression: str):
        result = await self.send("Runtime.evaluate", expression=expression, returnByValue=True)
        return result["result"]["value"]


def in_browser(tmp_path, scenario) -> None:
    """`gearhead serve` and headless chromium; `scenario(page, base)` drives one tab (a Page over
    the DevTools protocol, the recorder installed) against the server at `base`."""
    import aiohttp

    port, debug_port = free_port(), free_port()
    with (
        running(GEARHEAD, "serve", "--port", str(port)),
        running(
            CHROMIUM, "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
            f"--user-data-dir={tmp_path / 'profile'}", f"--remote-debugging-port={debug_port}",
            "--window-size=1600,1000", "about:blank",
        ),
    ):  # fmt: skip
        assert wait_for(f"http://127.0.0.1:{port}/") == 200
        wait_for(f"http://127.0.0.1:{debug_port}/json/version")

        async def drive():
            async with aiohttp.ClientSession() as session:
                async with session.get(f"http://127.0.0.1:{debug_port}/json/list") as response:
                    target = next(t for t in await response.json() if t["type"] == "page")
                async with session.ws_connect(target["webSocketDebuggerUrl"], max_msg_size=0) as ws:
                    page = Page(ws)
                    await page.send("Page.enable")
                    await page.send("Page.addScriptToEvaluateOnNewDocument", source=RECORDER)
                    await scenario(page, f"http://127.0.0.1:{port}")

        asyncio.run(asyncio.wait_for(drive(), 150))


@pytest.mark.skipif(CHROMIUM is None, reason="no chromium installed (apt-get install chromium; .ci/run does)")
def test_the_app_in_a_headless_browser_shows_a_card_and_updates_a_result(tmp_path):
    """The page loads, the first card (Motor) shows its results, and a value typed into it (two
    motors, then three) changes a result on screen to what the core computes for it."""
    from gearhead.core.model import solve

    def stall_text(count: int) -> str:
        """The stall torque's number as the card shows it (its unit is drawn N·m there)."""
        return solve("motor", {"motor_count": count}).outputs["stall_torque"].text.split()[0]

    async def scenario(page: Page, base: str) -> None:
        await page.send("Page.navigate", url=f"{base}/")
        await page.wait_for_text("Stall torque")  # the Motor card and its results
        before = await page.wait_for_text(stall_text(1))
        # where the "Motors" row is drawn (Textual places each line with ESC[row;colH): a click on
        # its label selects the row, and typing replaces its value
        raw = await page.evaluate("window.__screen")
        row, col = next(
            (int(m[1]), int(m[2]))
            for m in CURSOR_AND_TEXT.finditer(raw)
            if ANSI.sub("", m[3]).startswith(" Motors ")
        )
        box = json.loads(
            await page.evaluate(
                "JSON.stringify(document.querySelector('.xterm-screen').getBoundingClientRect())"
            )
        )
        size = re.search(r"width=(\d+)&height=(\d+)", await page.evaluate("window.__socket_url"))
        x = box["left"] + (col + 2.5) * box["width"] / int(size[1])
        y = box["top"] + (row - 0.5) * box["height"] / int(size[2])
        for kind in ("mousePressed", "mouseReleased"):
            await page.send("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left", clickCount=1)
        await page.send("Input.insertText", text="3")  # what a key press sends the terminal
        await page.send("Input.insertText", text="\r")
        await page.wait_for_text(stall_text(3), after=len(before))

    in_browser(tmp_path, scenario)


@pytest.mark.skipif(CHROMIUM is None, reason="no chromium installed (apt-get install chromium; .ci/run does)")
def test_a_served_link_with_a_share_code_opens_its_design(tmp_path):
    """http://host:port/?p=gh1:… (gearhead share FILE --link URL): the page's session starts with
    that preset (three motors on the Motor card: its stall torque tripled), and a page opened
    after it without ?p= starts with the defaults again."""
    from gearhead.core import share
    from gearhead.core.model import solve
    from gearhead.core.presets import Preset

    code = share.encode(Preset("motor", "three motors", "", {"motor_count": 3}))
    three, one = (solve("motor", {"motor_count": n}).outputs["stall_torque"].text.split()[0] for n in (3, 1))

    async def scenario(page: Page, base: str) -> None:
        await page.send("Page.navigate", url=share.link(code, f"{base}/"))
        await page.wait_for_text("Preset loaded")
        await page.wait_for_text(three)
        await page.send("Page.navigate", url=f"{base}/")
        await page.evaluate("window.__screen = ''")
        screen = await page.wait_for_text(one)
        assert "Preset loaded" not in screen

    in_browser(tmp_path, scenario)


def test_a_request_from_another_sites_page_is_refused():
    """Browsers let any page open a websocket to this machine: one marked as from another origin
    is refused (403), on the loopback too, and a non-ASCII token is a 403, not a 500."""

    def status(url: str, **headers) -> int:
        try:
            with urllib.request.urlopen(urllib.request.Request(url, headers=headers), timeout=5) as r:
                return r.status
        except urllib.error.HTTPError as e:
            return e.code

    port = free_port()
    with running(GEARHEAD, "serve", "--port", str(port)):
        base = f"http://127.0.0.1:{port}"
        assert wait_for(f"{base}/") == 200
        assert status(f"{base}/", Origin=base) == 200  # the page's own
        assert status(f"{base}/", Origin="https://evil.example") == 403
        assert status(f"{base}/ws", Origin="https://evil.example") == 403
    port = free_port()
    with running(GEARHEAD, "serve", "--host", "0.0.0.0", "--port", str(port)):
        assert wait_for(f"http://127.0.0.1:{port}/") == 403
        assert status(f"http://127.0.0.1:{port}/?token=%C3%A9") == 403


# Hostile clients (issue 41): real HTTP and websocket clients on 127.0.0.1, every wait bounded.


def first_lines(process, count: int, timeout: float = 30) -> list[str]:
    """The first `count` lines of the process's stderr ("" for each it has not written in time)."""
    import queue
    import threading

    lines: queue.Queue[str] = queue.Queue()
    threading.Thread(
        target=lambda: [lines.put(process.stderr.readline()) for _ in range(count)], daemon=True
    ).start()
    deadline, got = time.monotonic() + timeout, []
    for _ in range(count):
        try:
            got.append(lines.get(timeout=max(0.0, deadline - time.monotonic())))
        except queue.Empty:
            got.append("")
    return got


def status(url: str, **headers) -> int:
    try:
        with urllib.request.urlopen(urllib.request.Request(url, headers=headers), timeout=5) as r:
            return r.status
    except urllib.error.HTTPError as e:
        return e.code


def ws_status(url: str, **headers) -> int:
    """The status of a websocket opening (101: a session started; it is closed at once)."""
    import aiohttp

    async def attempt() -> int:
        async with aiohttp.ClientSession() as session:
            try:
                async with session.ws_connect(url, headers=headers):
                    return 101
            except aiohttp.WSServerHandshakeError as exc:
                return exc.status

    return asyncio.run(asyncio.wait_for(attempt(), 30))


def session_apps(server_pid: int) -> list[int]:
    """The pids of the served apps under the server (Linux: /proc)."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(ppid, []).append(int(entry.name))
    found, todo = [], [server_pid]
    while todo:
        for child in children.get(todo.pop(), []):
            todo.append(child)
            try:
                if b"gearhead.tui.served" in Path(f"/proc/{child}/cmdline").read_bytes():
                    found.append(child)
            except OSError:
                pass
    return found


def rss_mb(pid: int) -> float:
    try:
        line = next(x for x in Path(f"/proc/{pid}/status").read_text().splitlines() if x.startswith("VmRSS"))
    except (OSError, StopIteration):
        return 0.0
    return int(line.split()[1]) / 1024


def until(condition, timeout: float, step: float = 0.2) -> float | None:
    """Seconds until `condition()` holds, or None if it never did within `timeout`."""
    start = time.monotonic()
    while time.monotonic() - start < timeout:
        if condition():
            return time.monotonic() - start
        time.sleep(step)
    return None


LINUX = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc (Linux)")


@contextmanager
def server(*flags: str):
    port = free_port()
    with running(GEARHEAD, "serve", "--port", str(port), *flags) as process:
        assert wait_for(f"http://127.0.0.1:{port}/") in (200, 403)
        yield process, port


def test_a_rebound_host_name_is_refused_on_the_loopback():
    """DNS rebinding: a page of evil.example whose name now resolves to 127.0.0.1 sends its own name
    as Host (and Origin); the page, its websocket and the static files are refused (the websocket
    was a 101: a session that could export anywhere). The loopback by any name, on this port, is
    served."""
    with server() as (_, port):
        base, evil = f"http://127.0.0.1:{port}", f"evil.example:{port}"
        assert status(f"{base}/", Host=evil, Origin=f"http://{evil}") == 403
        assert ws_status(f"{base}/ws", Host=evil, Origin=f"http://{evil}") == 403
        assert status(f"{base}/", Host=evil) == 403
        assert status(f"{base}/static/js/textual.js", Host=evil) == 403
        assert status(f"{base}/", Host=f"127.0.0.1:{port + 1}") == 403  # another port: another server
        assert status(f"{base}/", Host=f"127.0.0.1:{port}x") == 403
        for name in ("127.0.0.1", "localhost", "[::1]", "127.1.2.3", "LOCALHOST"):
            assert status(f"{base}/", Host=f"{name}:{port}") == 200, name
        assert status(f"{base}/", Host=f"127.0.0.1:{port}", Origin=f"http://localhost:{port}") == 200


def test_a_token_whenever_the_host_is_not_the_loopback():
    """On the loopback behind a --public-url naming another host (a proxy), that Host is served
    but only with the token, which the server prints; the loopback itself needs none."""
    port = free_port()
    url = f"http://gearhead.example:{port}"
    with running(GEARHEAD, "serve", "--port", str(port), "--public-url", url) as process:
        assert wait_for(f"http://127.0.0.1:{port}/") == 200
        warning, opening = first_lines(process, 2)
        assert "warning" in warning
        token = re.search(r"\?token=([\w-]+)", opening)[1]
        base, named = f"http://127.0.0.1:{port}", f"gearhead.example:{port}"
        assert status(f"{base}/", Host=named) == 403
        assert ws_status(f"{base}/ws", Host=named) == 403
        assert status(f"{base}/?token={token}", Host=named) == 200
        assert ws_status(f"{base}/ws", Host=named, Cookie=f"gearhead_token={token}") == 101
        assert ws_status(f"{base}/ws") == 101  # the loopback


def test_sessions_are_capped_and_a_closed_one_frees_its_place():
    import aiohttp

    async def scenario(port: int) -> None:
        base = f"http://127.0.0.1:{port}/ws"
        async with aiohttp.ClientSession() as session:
            first = await session.ws_connect(base)
            second = await session.ws_connect(base)
            with pytest.raises(aiohttp.WSServerHandshakeError) as refused:
                await session.ws_connect(base)
            assert refused.value.status == 503
            await first.close()
            deadline = time.monotonic() + 20
            while True:  # its app ends, then a new session is let in
                try:
                    third = await session.ws_connect(base)
                    break
                except aiohttp.WSServerHandshakeError:
                    assert time.monotonic() < deadline, "a closed session never freed its place"
                    await asyncio.sleep(0.3)
            await third.close()
            await second.close()

    assert serve.MAX_SESSIONS == 4
    with server("--max-sessions", "2") as (_, port):
        asyncio.run(asyncio.wait_for(scenario(port), 60))


CURSOR = re.compile(rb"\x1b\[(\d+);(\d+)H")


@LINUX
def test_a_huge_terminal_is_capped():
    """/ws?width=100000&height=100000 drove one session past 3.5 GB in 40 s: the app gets at most
    MAX_WIDTH x MAX_HEIGHT (its screen, drawn with ESC[row;colH, stays inside), at its usual
    memory; a resize message is capped alike, and one that is no size is ignored."""
    import aiohttp

    async def scenario(server_pid: int, port: int) -> None:
        url = f"http://127.0.0.1:{port}/ws?width=100000&height=100000"
        async with aiohttp.ClientSession() as session, session.ws_connect(url, max_msg_size=0) as ws:

            async def screen(seconds: float) -> bytes:
                got, deadline = b"", time.monotonic() + seconds
                while time.monotonic() < deadline:
                    try:
                        message = await asyncio.wait_for(ws.receive(), 1)
                    except TimeoutError:
                        continue
                    if message.type == aiohttp.WSMsgType.BINARY:
                        got += message.data
                    elif message.type != aiohttp.WSMsgType.TEXT:
                        break
                return got

            first = await screen(25)
            assert b"Stall torque" in first, "the first card was never drawn"
            for data in ({"width": 100000, "height": 100000}, {"width": "x"}, {"width": None, "height": []}):
                await ws.send_json(["resize", data])
            drawn = first + await screen(5)
            rows = [int(m[1]) for m in CURSOR.finditer(drawn)]
            cols = [int(m[2]) for m in CURSOR.finditer(drawn)]
            from gearhead.tui import serve_session

            assert max(rows) <= serve_session.MAX_HEIGHT and max(cols) <= serve_session.MAX_WIDTH
            (app,) = session_apps(server_pid)
            memory = rss_mb(app)
            print(f"a 100000 x 100000 session: {memory:.0f} MB after its first screen")
            assert memory < 400

    with server() as (process, port):
        asyncio.run(asyncio.wait_for(scenario(process.pid, port), 90))


@LINUX
def test_a_session_has_a_memory_bound():
    """Each app's address space is bounded (RLIMIT_AS; --session-memory, 0 for none)."""

    def limit(pid: int) -> str:
        line = next(x for x in Path(f"/proc/{pid}/limits").read_text().splitlines() if "address space" in x)
        return line.split()[3]

    import aiohttp

    async def one_session(server_pid: int, port: int) -> str:
        url = f"http://127.0.0.1:{port}/ws"
        async with aiohttp.ClientSession() as session, session.ws_connect(url, max_msg_size=0) as ws:
            while (await asyncio.wait_for(ws.receive(), 30)).type != aiohttp.WSMsgType.BINARY:
                pass  # until the app draws: it has set its bound by then
            (app,) = session_apps(server_pid)
            return limit(app)

    with server() as (process, port):
        assert asyncio.run(one_session(process.pid, port)) == str(serve.SESSION_MEMORY_MB * 1024 * 1024)
    with server("--session-memory", "512") as (process, port):
        assert asyncio.run(one_session(process.pid, port)) == str(512 * 1024 * 1024)
    with server("--session-memory", "0") as (process, port):
        assert asyncio.run(one_session(process.pid, port)) == "unlimited"


def raw_websocket(port: int) -> socket.socket:
    """A websocket opened by hand, its 101 read: the test then reads nothing more."""
    sock = socket.create_connection(("127.0.0.1", port))
    sock.sendall(
        f"GET /ws HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
        "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n".encode()
    )
    assert sock.recv(100).startswith(b"HTTP/1.1 101")
    return sock


def alive(pids: list[int]) -> bool:
    for pid in pids:
        try:
            if b"gearhead.tui.served" in Path(f"/proc/{pid}/cmdline").read_bytes():
                return True
        except OSError:
            pass
    return False


@LINUX
def test_a_session_ends_when_its_client_goes():
    """A client that opens the websocket then stops reading (and answering pings) left its app
    alive 20 s and more: it ends within HEARTBEAT and a half, and the rest of the grace. A client
    that closes its socket ends its app at once; a server killed with SIGKILL takes its apps along
    (an orphaned app with a huge terminal grew to 12.8 GB)."""
    with server() as (process, port):
        with raw_websocket(port):
            quiet = time.monotonic()
            assert until(lambda: session_apps(process.pid), 20) is not None
            assert until(lambda: not session_apps(process.pid), 40) is not None, "the app outlived its client"
            lived = time.monotonic() - quiet
        print(f"an abandoned session's app lived {lived:.1f} s")
        assert lived < 15

        with raw_websocket(port):
            assert until(lambda: session_apps(process.pid), 20) is not None
        gone = until(lambda: not session_apps(process.pid), 20)
        print(f"a closed session's app ended in {gone} s")
        assert gone is not None and gone < 5

        with raw_websocket(port):
            assert until(lambda: session_apps(process.pid), 20) is not None
            apps = session_apps(process.pid)
            time.sleep(3)  # the app has started (and set its parent-death signal)
            process.kill()
            process.wait(10)
            try:
                assert until(lambda: not alive(apps), 15) is not None, "an app outlived its server"
            finally:
                for pid in apps:  # this test's own processes, should they remain
                    with contextlib.suppress(OSError):
                        os.kill(pid, signal.SIGKILL)


def test_static_lists_nothing_and_a_long_name_is_a_404():
    with server() as (process, port):
        base = f"http://127.0.0.1:{port}"
        assert status(f"{base}/static/js/textual.js") == 200  # the page's own files
        assert status(f"{base}/static/") in (403, 404)
        assert status(f"{base}/static/js/") in (403, 404)
        assert status(f"{base}/static/" + "a" * 5000) == 404
        assert status(f"{base}/static/" + "a/" * 2000) == 404
        process.terminate()
        out, err = process.communicate(timeout=20)
    assert "Traceback" not in out + err
    assert "textual.js" not in out + err or "Index of" not in out + err


def test_malformed_websocket_messages_are_ignored_without_a_traceback():
    """Each of these printed a traceback with local variables to the console and ended the
    session; now they are ignored and the session still answers a ping. A malformed HTTP request
    is a 400 and one line."""
    import aiohttp

    bad = ['not json', '[]', '{}', '[1]', '["stdin", 5]', '["stdin", "\\ud800"]', '["resize", {}]',
           '["resize", "x"]', '["resize", {"width": 1e999, "height": 3}]', "[" * 100_000 + "]" * 100_000]  # fmt: skip

    async def scenario(port: int) -> None:
        async with aiohttp.ClientSession() as session:
            async with session.ws_connect(f"http://127.0.0.1:{port}/ws", max_msg_size=0) as ws:
                for text in bad:
                    await ws.send_str(text)
                await ws.send_json(["ping", "still here"])
                deadline = time.monotonic() + 30
                while time.monotonic() < deadline:
                    message = await asyncio.wait_for(ws.receive(), 30)
                    if message.type == aiohttp.WSMsgType.TEXT and message.json() == ["pong", "still here"]:
                        return
                    assert message.type in (aiohttp.WSMsgType.TEXT, aiohttp.WSMsgType.BINARY), message
                raise AssertionError("no pong")

    with server() as (process, port):
        asyncio.run(asyncio.wait_for(scenario(port), 60))
        for raw in (  # HTTP that aiohttp cannot parse: a 400, said in one line
            b"GARBAGE\r\n\r\n",
            b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nX: \x00\x01\r\n\r\n",
            b"GET /" + b"a" * 20000 + b" HTTP/1.1\r\n\r\n",
        ):
            with socket.create_connection(("127.0.0.1", port)) as sock:
                sock.sendall(raw)
                sock.settimeout(10)
                assert b" 400 " in sock.recv(100)
        time.sleep(1)
        process.terminate()
        out, err = process.communicate(timeout=20)
    assert "Traceback" not in out + err and "locals" not in out + err, out + err


def test_bad_serve_options_are_refused_by_name(tmp_path):
    for flags, name in [
        (["--max-sessions", "0"], "--max-sessions"),
        (["--session-memory", "10"], "--session-memory"),
        (["--allow-paths", str(tmp_path / "none")], "--allow-paths"),
    ]:
        out = subprocess.run([GEARHEAD, "serve", *flags], capture_output=True, text=True, timeout=60)
        assert out.returncode == 2 and name in out.stderr, (flags, out.stderr)


def test_a_served_session_reads_and_writes_only_in_the_gearhead_folder(tmp_path, monkeypatch):
    """tui/served_paths.check, which the export and load dialogs call: in the terminal app every
    path; in a served session (confined) the Gearhead folder, its exports/ working folder, and
    what --allow-paths adds; '..' and a symlink out of the folder are outside."""
    from gearhead.core.errors import InputError
    from gearhead.tui import served_paths

    monkeypatch.setattr(served_paths, "_allowed", None)
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    assert served_paths.check(str(outside / "x.md")) == outside / "x.md"  # the terminal app
    monkeypatch.chdir(served_paths.confine())
    folder = served_paths.gearhead_folder()
    assert served_paths.check("motor_results.md").resolve() == folder / "exports" / "motor_results.md"
    assert served_paths.check(str(folder / "presets" / "motor" / "a.toml"))
    (folder / "link").symlink_to(outside)
    for bad in (str(outside / "x.md"), "/etc/passwd", "../../x.md", str(folder / "link" / "x.md"), "~/x.md"):
        with pytest.raises(InputError, match="served session reads and writes only in"):
            served_paths.check(bad)
    served_paths.confine([str(outside)])
    assert served_paths.check(str(outside / "x.md")) == outside / "x.md"
    monkeypatch.setattr(served_paths, "_allowed", None)


async def test_the_export_and_load_dialogs_refuse_a_path_outside(tmp_path, monkeypatch):
    """A served session's ctrl+e (Save to file) and ctrl+o (a path, Enter) outside the folder:
    the dialog says why, and nothing is written or read."""
    from textual.app import App
    from textual.widgets import Input, Static

    from gearhead.core.model import solve
    from gearhead.core.presets import Preset, save
    from gearhead.core.registry import get
    from gearhead.tui import served_paths
    from gearhead.tui.components.export_screen import ExportScreen
    from gearhead.tui.components.preset_screens import LoadPresetScreen

    # recorded first, so the teardown puts back "not confined": setattr in `finally` recorded the
    # confined value as the original and restored it, confining every later test in this process
    monkeypatch.setattr(served_paths, "_allowed", None)
    monkeypatch.chdir(served_paths.confine())
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    preset = save(Preset("motor", "two", "", {"motor_count": 2}), outside / "two.toml")
    try:
        async with App().run_test(size=(120, 40)) as pilot:
            pilot.app.push_screen(ExportScreen(get("motor"), solve("motor", {}), None, blink=False))
            await pilot.pause()
            path = pilot.app.screen.query_one("#export-path", Input)
            path.value = str(outside / "out.md")
            path.focus()
            await pilot.press("enter")
            await pilot.pause()
            error = str(pilot.app.screen.query_one("#export-error", Static).render())
            assert "served session" in error and not (outside / "out.md").exists()
            path.value = "out.md"
            await pilot.press("enter")
            await pilot.pause()
            assert (served_paths.gearhead_folder() / "exports" / "out.md").exists()

            pilot.app.push_screen(LoadPresetScreen("motor", blink=False))
            await pilot.pause()
            pilot.app.screen.query_one("#preset-path", Input).value = str(preset)
            pilot.app.screen.query_one("#preset-path", Input).focus()
            await pilot.press("enter")
            await pilot.pause()
            error = str(pilot.app.screen.query_one("#load-error", Static).render())
            assert "served session" in error and isinstance(pilot.app.screen, LoadPresetScreen)
    finally:
        monkeypatch.setattr(served_paths, "_allowed", None)
