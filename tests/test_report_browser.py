"""The HTML report in a real headless Chromium (driven over the DevTools protocol, as
tests/test_serve.py drives it): it opens without an error and without one network request, its
title and every chart are there, and a screenshot is not blank; the PDF has its pages. Skipped,
with the reason, where no chromium is installed (.ci/run installs it)."""

from __future__ import annotations

import asyncio
import base64
import io
import json
import re
import shutil
import socket
import subprocess
import time
import urllib.request
from contextlib import contextmanager
from pathlib import Path

import pytest

from gearhead.core.report import document, html
from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = str(ROOT / "examples" / "robot_2027.toml")
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
needs_chromium = pytest.mark.skipif(
    CHROMIUM is None, reason="no chromium installed (apt-get install chromium; .ci/run does)"
)


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextmanager
def chromium(profile: Path, port: int):
    """A headless Chromium for the test's duration, stopped (by its id) however the test ends."""
    process = subprocess.Popen(
        [CHROMIUM, "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
         f"--user-data-dir={profile}", f"--remote-debugging-port={port}", "--window-size=1000,1400",
         "about:blank"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + 30
        while True:
            try:
                urllib.request.urlopen(f"http://127.0.0.1:{port}/json/version", timeout=2).close()
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.2)
        yield
    finally:
        process.terminate()
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(10)


class Tab:
    """One tab over the DevTools protocol; every event it sends is kept in `events`."""

    def __init__(self, ws):
        self.ws, self.next_id, self.events = ws, 0, []

    async def send(self, method: str, **params):
        self.next_id += 1
        await self.ws.send_json({"id": self.next_id, "method": method, "params": params})
        while True:
            message = json.loads((await self.ws.receive()).data)
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError(message["error"])
                return message.get("result", {})
            if "method" in message:
                self.events.append(message)

    async def until(self, method: str, timeout: float = 60) -> None:
        deadline = time.monotonic() + timeout
        while not any(e["method"] == method for e in self.events):
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise AssertionError(f"no {method} within {timeout} s")
            message = json.loads((await asyncio.wait_for(self.ws.receive(), remaining)).data)
            if "method" in message:
                self.events.append(message)

    async def evaluate(self, expression: str):
        result = await self.send("Runtime.evaluate", expression=expression, returnByValue=True)
        return result["result"]["value"]


def open_in_chromium(tmp_path: Path, page: Path) -> dict:
    """Load `page` in headless Chromium: its title, charts, requests, errors and a screenshot."""
    import aiohttp

    port = free_port()
    with chromium(tmp_path / "profile", port):

        async def drive() -> dict:
            async with aiohttp.ClientSession() as session:
                async with session.get(f"http://127.0.0.1:{port}/json/list") as response:
                    target = next(t for t in await response.json() if t["type"] == "page")
                async with session.ws_connect(target["webSocketDebuggerUrl"], max_msg_size=0) as ws:
                    tab = Tab(ws)
                    for domain in ("Page", "Network", "Runtime", "Log"):
                        await tab.send(f"{domain}.enable")
                    tab.events.clear()
                    await tab.send("Page.navigate", url=page.as_uri())
                    await tab.until("Page.loadEventFired")
                    await asyncio.sleep(0.5)  # anything the page would fetch late
                    shot = await tab.send("Page.captureScreenshot", format="png")
                    return {
                        "title": await tab.evaluate("document.title"),
                        "h1": await tab.evaluate("document.querySelector('h1').textContent"),
                        "svgs": await tab.evaluate("document.querySelectorAll('figure svg').length"),
                        "drawn": await tab.evaluate(
                            "[...document.querySelectorAll('figure svg')].every(s => s.getBBox().width > 100)"
                        ),
                        "events": tab.events,
                        "png": base64.b64decode(shot["data"]),
                    }

        return asyncio.run(asyncio.wait_for(drive(), 120))


@needs_chromium
def test_the_example_report_opens_in_chromium_with_no_error_and_no_network(tmp_path):
    report = document.build(EXAMPLE)
    page = tmp_path / "robot_2027.html"
    page.write_text(html.write(report), encoding="utf-8")
    seen = open_in_chromium(tmp_path, page)
    assert seen["title"] == "2027 robot · Gearhead design report"
    assert seen["h1"] == "2027 robot"
    assert seen["svgs"] == len(report.charts()) > 10 and seen["drawn"]
    requests = [
        e["params"]["request"]["url"] for e in seen["events"] if e["method"] == "Network.requestWillBeSent"
    ]
    assert requests == [page.as_uri()], "the report asked for more than itself"
    errors = [
        e
        for e in seen["events"]
        if e["method"] == "Runtime.exceptionThrown"
        or (e["method"] == "Log.entryAdded" and e["params"]["entry"]["level"] == "error")
        or (e["method"] == "Runtime.consoleAPICalled" and e["params"]["type"] == "error")
    ]
    assert errors == []
    from PIL import Image

    image = Image.open(io.BytesIO(seen["png"])).convert("L")
    histogram = image.histogram()
    dark = sum(histogram[:128]) / (image.width * image.height)
    assert 0.01 < dark < 0.5, f"the screenshot is blank or black ({dark:.3f} of it dark)"


@needs_chromium
def test_a_blocked_fetch_would_be_seen(tmp_path):
    """The check above can fail: a page that asks for an image over the network is caught."""
    page = tmp_path / "leaky.html"
    text = html.write(document.build("builtin:elevator/two_neo"))
    page.write_text(text.replace("</h1>", '</h1><img src="http://127.0.0.1:9/x.png">'), encoding="utf-8")
    seen = open_in_chromium(tmp_path, page)
    requests = [
        e["params"]["request"]["url"] for e in seen["events"] if e["method"] == "Network.requestWillBeSent"
    ]
    csp = [
        e
        for e in seen["events"]
        if e["method"] == "Log.entryAdded" and e["params"]["entry"]["level"] == "error"
    ]
    assert len(requests) > 1 or csp  # asked for it, or the policy refused it out loud


@needs_chromium
def test_the_pdf_has_its_pages(tmp_path, capsys):
    out = tmp_path / "robot.pdf"
    assert main(["report", EXAMPLE, "--out", str(out)]) == 0
    data = out.read_bytes()
    assert data.startswith(b"%PDF-")
    pages = len(re.findall(rb"/Type\s*/Page\b", data))
    # the title and requirements, then a page per card (8) and the match, at least
    assert pages >= 10, pages
