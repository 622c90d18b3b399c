"""`gearhead serve` (tui/serve.py): loopback by default, a token beyond it, and the app working in
a real headless browser (Debian's chromium, driven over the DevTools protocol with aiohttp, which
textual-serve already installs). The browser test is skipped, with the reason, where no chromium
is installed (.ci/run installs it)."""

from __future__ import annotations

import asyncio
import json
import re
import shutil
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
