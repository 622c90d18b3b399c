"""The report as PDF: the HTML printed by a headless Chromium (`--headless --print-to-pdf`), the
browser tests/test_serve.py already drives; no PDF library. Where no Chromium is installed,
NoBrowser says so (the CLI exits 69, EX_UNAVAILABLE, with the message)."""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable", "chrome")
TIMEOUT_S = 120


class NoBrowser(RuntimeError):
    """No Chromium to print with, or it failed: the message says which and what to do."""


def browser() -> str | None:
    """The Chromium to print with: $GEARHEAD_CHROMIUM if set, else the first of BROWSERS on PATH."""
    chosen = os.environ.get("GEARHEAD_CHROMIUM")
    if chosen:
        return shutil.which(chosen) or (chosen if os.path.isfile(chosen) else None)
    return next((found for name in BROWSERS if (found := shutil.which(name))), None)


def command(chromium: str, page: Path, out: Path, profile: Path) -> list[str]:
    args = [
        chromium,
        "--headless=new",
        "--disable-gpu",
        "--disable-dev-shm-usage",
        "--no-first-run",
        "--no-pdf-header-footer",
        f"--user-data-dir={profile}",
        f"--print-to-pdf={out}",
        page.as_uri(),
    ]
    if hasattr(os, "geteuid") and os.geteuid() == 0:  # Chromium refuses to run as root in its sandbox
        args.insert(1, "--no-sandbox")
    return args


def from_html(html_text: str) -> bytes:
    """The PDF of an HTML report (bytes); NoBrowser when there is no Chromium or it fails."""
    chromium = browser()
    if chromium is None:
        raise NoBrowser(
            "PDF needs Chromium (or Google Chrome) installed, and none was found on PATH "
            "(set GEARHEAD_CHROMIUM to its path); --format html makes the same report, to print from any browser"
        )
    with tempfile.TemporaryDirectory(prefix="gearhead-report-") as folder:
        page = Path(folder) / "report.html"
        page.write_text(html_text, encoding="utf-8")
        out = Path(folder) / "report.pdf"
        try:
            run = subprocess.run(
                command(chromium, page, out, Path(folder) / "profile"),
                capture_output=True,
                text=True,
                timeout=TIMEOUT_S,
                stdin=subprocess.DEVNULL,
            )
        except subprocess.TimeoutExpired:
            raise NoBrowser(f"{chromium} did not print the report within {TIMEOUT_S} s") from None
        except OSError as exc:
            raise NoBrowser(f"{chromium} could not be started ({exc.strerror or exc})") from None
        if not out.is_file() or out.stat().st_size == 0:
            last = (run.stderr.strip().splitlines() or ["no message"])[-1]
            raise NoBrowser(f"{chromium} made no PDF (exit {run.returncode}: {last[:200]})")
        return out.read_bytes()
