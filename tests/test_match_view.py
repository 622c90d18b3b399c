"""The workbook's Match card in the app (tui/components/match_view.py): ctrl+t opens it, it shows the
outputs `gearhead match --json` gives (the same values and units), the brownouts and three charts
(textual-plot) drawn from core/match/series.py; a match that cannot run shows its message; while a
newer solve runs it says so; at 80x24 it scrolls. A snapshot, and the real terminal (tmux) at
140x45 and 80x24, with and without NO_COLOR."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

from gearhead.core import units, workbook
from gearhead.core.workbook.match import output_info
from gearhead.tui import cli
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.match_view import MatchView
from tests.test_workbook_app import opened, settled
from tests.tui_helpers import keys_of

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "robot_2027.toml"


@pytest.fixture(autouse=True)
def no_guarded_errors(monkeypatch):
    """A bug caught by a @guarded handler is only a notification on screen: here it fails the test."""
    from gearhead.tui import guard

    caught = []
    monkeypatch.setattr(guard, "report", lambda node, exc, where: caught.append((where, exc)))
    yield
    assert not caught, caught


async def match_drawn(pilot, view: MatchView) -> float:
    """Until the view's charts show its latest result; the seconds it took."""
    start = time.perf_counter()
    for _ in range(1000):
        await pilot.pause(0.01)
        if view.request is not None and view.drawn == view.request:
            await pilot.pause()
            return time.perf_counter() - start
    raise AssertionError("the match's charts were never drawn")


async def match_drawn_of(pilot, view: MatchView, request: int | None) -> None:
    """Until the view's charts show the match of `request`."""
    for _ in range(1000):
        await pilot.pause(0.01)
        if view.drawn == request:
            return
    raise AssertionError(f"the charts of request {request} were never drawn")


def summary(view: MatchView) -> str:
    return str(view.summary.render())


async def test_ctrl_t_shows_the_match_as_gearhead_match_json_gives_it(capsys):
    code = cli.main(["match", str(EXAMPLE), "--json"])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(EXAMPLE))
    async with app.run_test(size=(140, 45)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        view = screen.match_view
        assert view is not None
        started = time.perf_counter()
        await pilot.press("ctrl+t")
        took = await match_drawn(pilot, view)
        print(
            f"ctrl+t to the match's charts drawn: {time.perf_counter() - started:.3f} s (wait {took:.3f} s)"
        )
        assert screen.query_one("#workbook-tabs").active == "wbtab-match"
        assert app.focused is view
        text = summary(view)
        assert data["outputs"], data
        cards = set(data["channel_peak_supply_current"])
        for key, out in data["outputs"].items():
            label, unit = output_info(key, cards)  # the channel breakers' too: `lift_breaker_load`
            assert unit == out["unit"]
            value = out["value"]
            shown = (
                f"{value:d}" if isinstance(value, int) else f"{units.format_number(value)} {unit}".rstrip()
            )
            line = next(line for line in text.splitlines() if line.startswith(f"  {label} "))
            assert line.split()[len(label.split()) :][: len(shown.split())] == shown.split(), (line, shown)
            assert f"match.{key}" in line
        running = ", ".join(data["min_bus_running"])
        assert f"({running} running)" in text and "Brownouts: none" in text
        for card, share in data["shares"].items():
            assert f"{share * 100:6.3g} %" in text and card in text
        # three charts, drawn with what the series holds
        from textual_plot import PlotWidget

        assert len(view.query(PlotWidget)) == 3
        # ctrl+t again: back to the card it was opened from
        await pilot.press("ctrl+t")
        await pilot.pause()
        assert screen.query_one("#workbook-tabs").active == "wbtab-robot"
        assert app.focused is screen.robot.sheet


BAD = """
format = 1
name = "bad match"

[variables]
ratio = 9

[cards.lift]
calculator = "elevator"
[cards.lift.inputs]
motor_count = 2
ratio = "= ratio"
load_mass = "15 lb"
travel = "48 in"

[match]
length = "20 s"

[[match.events]]
at = "1 s"
card = "lift"
"""


async def test_a_match_that_cannot_run_shows_its_message_and_a_fix_brings_the_charts_back():
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.from_text(BAD, "bad.toml"))
    async with app.run_test(size=(140, 45)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        assert screen.robot.sheet.move_to_field("ratio")
        screen.robot.sheet.focus()
        await pilot.press(*keys_of("-3"), "enter")  # the card cannot be solved at a ratio of -3
        await settled(pilot, screen)
        await pilot.press("ctrl+t")
        await pilot.pause(0.2)
        view = screen.match_view
        status = str(view.status.render())
        assert status.startswith("✗ bad.toml: match: match.events[1] (lift at 1 s): the card lift"), status
        assert view.sheet.errors["e1_card"].startswith("match.events[1] (lift at 1 s): the card lift")
        # the last match that ran (ratio 9) stays below, dimmed, with its charts, as a card keeps
        # its last results while an entry is wrong
        assert "Traceback" not in status and "dimmed: the last match that ran" in status
        assert view.match is None and view.good is not None
        assert "Lowest bus voltage" in summary(view)
        shown = view.summary.render()
        assert any(
            sp.start == 0 and sp.end >= len(str(shown)) and str(sp.style) == "dim" for sp in shown.spans
        )
        await match_drawn_of(pilot, view, view.good_request)
        await pilot.press("ctrl+t")
        assert screen.robot.sheet.move_to_field("ratio")
        await pilot.press(*keys_of("9"), "enter")
        await settled(pilot, screen)
        await pilot.press("ctrl+t")
        await match_drawn(pilot, view)
        assert str(view.status.render()).startswith("✓ the match")
        assert "Lowest bus voltage" in summary(view)
        assert all(node.display for node in view.query(".match-heading, .match-plot"))


async def test_while_a_newer_solve_runs_the_match_card_says_so(monkeypatch):
    import threading

    from gearhead.core.sim.integrate import Cancelled, charge

    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.from_text(BAD, "bad.toml"))
    async with app.run_test(size=(140, 45)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        await pilot.press("ctrl+t")
        view = screen.match_view
        await match_drawn(pilot, view)
        before = summary(view)
        release = threading.Event()
        real = workbook.solve

        def slow(book):
            try:
                while not release.wait(0.005):
                    charge(0)
            except Cancelled:
                raise
            return real(book)

        monkeypatch.setattr(workbook, "solve", slow)
        screen.robot._take_entry("ratio", "10")  # as typed on the Robot card
        await pilot.pause(0.3)
        assert str(view.status.render()).startswith("… running the match"), str(view.status.render())
        assert summary(view) == before  # the last entries' match stays on screen meanwhile
        release.set()
        await settled(pilot, screen)
        await match_drawn(pilot, view)
        assert str(view.status.render()).startswith("✓ the match")
        assert summary(view) != before


async def test_a_workbook_without_a_match_has_no_match_card():
    text = BAD.split("[match]")[0]
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.from_text(text, "plain.toml"))
    async with app.run_test(size=(140, 45)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        assert screen.match_view is None
        assert "ctrl+t" not in screen.active_bindings  # nor in the key bar
        await pilot.press("ctrl+t")
        await pilot.pause()
        assert screen.query_one("#workbook-tabs").active == "wbtab-robot"


async def test_at_80x24_the_match_card_scrolls_to_its_last_chart():
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(EXAMPLE))
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        await pilot.press("ctrl+t")
        view = screen.match_view
        await match_drawn(pilot, view)
        from gearhead.tui.components.key_bar import KeyBar

        bar = screen.query_one(KeyBar)
        assert view.region.bottom <= bar.region.y
        assert view.max_scroll_y > 0
        assert view.virtual_size.width <= view.region.width  # wrapped, never cut on the right
        await pilot.press("end")
        await pilot.pause(0.2)
        assert view.scroll_y == view.max_scroll_y
        charge = view.query_one("#match-charge")
        assert view.region.contains_region(charge.region), (view.region, charge.region)


def test_match_card_snapshot(snap_compare):
    async def open_match(pilot):
        screen = await opened(pilot, pilot.app)
        await settled(pilot, screen)
        await pilot.press("ctrl+t")
        await match_drawn(pilot, screen.match_view)
        await pilot.pause()

    assert snap_compare(
        GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(EXAMPLE)),
        terminal_size=(140, 45),
        run_before=open_match,
    )


# ---- the real terminal ---------------------------------------------------------------------

TMUX = shutil.which("tmux")


class Terminal:
    """The app on the example workbook in a tmux pane of its own server (never the user's tmux)."""

    def __init__(self, tmp: Path, size: tuple[int, int], **env_extra: str) -> None:
        self.socket = f"gearhead-match-{uuid.uuid4().hex[:8]}"
        env = {
            k: v
            for k, v in os.environ.items()
            if k not in ("NO_COLOR", "TEXTUAL_THEME", "TMUX", "COLUMNS", "LINES")
        }
        env["XDG_CONFIG_HOME"] = str(tmp / "config")
        env.update(env_extra)
        self.env = env
        # the pane stays after the app ends (remain-on-exit): a crash leaves its last words on screen
        self.tmux(
            "new-session", "-d", "-s", "app", "-x", str(size[0]), "-y", str(size[1]),
            f"cd {ROOT} && {sys.executable} -m gearhead.tui {EXAMPLE}",
        )  # fmt: skip
        self.tmux("set-option", "-t", "app", "remain-on-exit", "on")

    def tmux(self, *args: str) -> str:
        out = subprocess.run(
            [TMUX, "-L", self.socket, *args], capture_output=True, text=True, env=self.env, timeout=20
        )
        return out.stdout

    def keys(self, *keys: str, gap: float = 0.08) -> None:
        for k in keys:
            self.tmux("send-keys", "-t", "app", k)
            time.sleep(gap)

    def screen(self) -> str:
        return self.tmux("capture-pane", "-p", "-t", "app")

    def alive(self) -> bool:
        return self.tmux("list-panes", "-t", "app", "-F", "#{pane_dead}").strip() == "0"

    def wait_for(self, ready, what: str, timeout: float = 30.0) -> str:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            screen = self.screen()
            if ready(screen):
                return screen
            time.sleep(0.1)
        raise AssertionError(f"timed out waiting for {what}; screen:\n{self.screen()}")

    def close(self) -> None:
        self.tmux("kill-server")


def lowest_bus_voltage() -> str:
    """The example's lowest bus voltage as the card prints it, from the match core (not a copy)."""
    return units.format_number(workbook.solve(workbook.load(EXAMPLE)).match.outputs["min_bus_voltage"])


@pytest.mark.parametrize(
    "size,no_color", [((140, 45), False), ((80, 24), False), ((140, 45), True), ((80, 24), True)]
)
def test_match_card_in_a_real_terminal(tmp_path, size, no_color):
    if TMUX is None:
        pytest.skip("tmux is not installed (.ci/run installs it)")
    term = Terminal(tmp_path, size, **({"NO_COLOR": "1"} if no_color else {}))
    try:
        term.wait_for(lambda s: "requirements hold" in s, "the workbook solved (its match too)")
        term.keys("C-t", gap=0.15)
        # (the Robot card's requirements name match.min_bus_voltage too: wait for the card's own line)
        screen = term.wait_for(lambda s: "Lowest bus voltage" in s, "ctrl+t: the Match card")
        assert "Lowest bus voltage" in screen and f"{lowest_bus_voltage()} V" in screen, screen
        assert all(len(line) <= size[0] for line in screen.splitlines())
        # down through the card to its charts, keys 30 to 150 ms apart
        for gap in (0.03, 0.15, 0.08):
            term.keys("PageDown", "PageDown", gap=gap)
        term.keys("End", gap=0.15)
        screen = term.wait_for(lambda s: "Charge [%]" in s and "Time [s]" in s, "the last chart")
        term.keys("Home", gap=0.05)
        term.wait_for(lambda s: "Lowest bus voltage" in s, "Home: the top of the Match card")
        term.keys("Down", "Up", "PageDown", "C-right", gap=0.05)  # ctrl+→ from the last tab: the Robot card
        term.wait_for(lambda s: "requirements hold" in s, "ctrl+→: round to the Robot card")
        term.keys("C-left", "Home", gap=0.05)
        term.wait_for(lambda s: "Lowest bus voltage" in s, "ctrl+← then Home: the Match card's top")
        term.keys("C-t", gap=0.15)
        term.wait_for(lambda s: "requirements hold" in s, "ctrl+t: back on the Robot card")
        assert term.alive(), term.screen()
        assert "Traceback" not in term.screen()
        term.keys("C-q", gap=0.3)
        term.wait_for(lambda s: not term.alive(), "ctrl+q: the app quits", timeout=10)
        assert "Traceback" not in term.screen() and "Error" not in term.screen(), term.screen()
    finally:
        term.close()


async def test_brownouts_are_listed_as_gearhead_match_gives_them(capsys):
    """A battery of 0.035 ohm browns the example out hundreds of times (the outputs switch off and
    on): the card lists the first ones (time, length, moves running) and says how many more."""
    code = cli.main(["match", str(EXAMPLE), "--json", "--set", "battery_resistance=0.035 ohm"])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["brownouts"]) > 200
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(EXAMPLE))
    async with app.run_test(size=(140, 45)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        screen.robot._take_entry("battery_resistance", "0.035 ohm")  # as typed on the Robot card
        await settled(pilot, screen)
        started = time.perf_counter()
        await pilot.press("ctrl+t")
        view = screen.match_view
        await match_drawn(pilot, view)
        print(f"{len(view.match.bus.trace)} samples: ctrl+t to drawn {time.perf_counter() - started:.3f} s")
        lines = summary(view).splitlines()
        at = lines.index(f"Brownouts ({len(data['brownouts'])}): start, length, moves running")
        for b, line in zip(data["brownouts"][:200], lines[at + 1 :]):
            assert line.split() == [
                f"{b['start']:.3f}",
                "s",
                f"{b['length'] * 1000:.1f}",
                "ms",
                *", ".join(b["running"]).split(),
            ]
        assert lines[at + 201].strip().startswith(f"... {len(data['brownouts']) - 200} more")
        assert "Outputs disabled for" in summary(view)


async def test_a_match_with_no_moves_and_no_load_draws_flat_charts():
    """Nothing drawn from the battery: every series is flat (a chart of one value), no error."""
    text = BAD.split("[[match.events]]")[0]
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.from_text(text, "idle.toml"))
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        await pilot.press("ctrl+t")
        view = screen.match_view
        await match_drawn(pilot, view)
        assert str(view.status.render()).startswith("✓ the match")
        assert "Peak battery current            0 A" in summary(view)
        await pilot.press("end")
        await pilot.pause(0.2)
        assert app.is_running
