"""Defects an independent review of issues 40-41's work found, each with a test that failed before
its fix."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from gearhead.core import atomic_file
from gearhead.core.errors import InputError
from gearhead.core.model import solve


def test_a_hidden_stator_limit_changes_nothing_in_the_derived_profile():
    """The derived profile read stator_current_limit with the stator_limit effect off, while the
    CLI said a value set there 'changes nothing' and the card hid its row."""
    base = {"mode": "profiled", "effects": "gravity"}
    hidden = [
        solve("elevator", {**base, "stator_current_limit": f"{amps} A"})
        .outputs["profile_max_acceleration"]
        .value
        for amps in (20, 40, 80)
    ]
    assert hidden[0] == hidden[1] == hidden[2]
    shown = [
        solve("elevator", {**base, "effects": "gravity, stator_limit", "stator_current_limit": f"{a} A"})
        .outputs["profile_max_acceleration"]
        .value
        for a in (20, 40)
    ]
    assert shown[0] < shown[1] and shown[1] == pytest.approx(hidden[0])  # 40 A either way


@pytest.mark.parametrize("unit", ["5 degC/s", "5 degC*m", "5 1/degC", "5 degC**2", "5 degC + 1 degC"])
def test_an_offset_unit_inside_a_compound_is_refused_not_misread(tmp_path, unit):
    """pint read degC inside a compound as an absolute temperature: '5 degC/s' was 278.15 K/s."""
    book = tmp_path / "wb.toml"
    book.write_text(
        f'name = "t"\n[variables]\nx = "{unit}"\n[cards.motor1]\ncalculator = "motor"\n'
        '[[requirements]]\nname = "r"\ncheck = "x >= x"\n',
        encoding="utf-8",
    )
    out = subprocess.run(
        [sys.executable, "-m", "gearhead.tui", "check", str(book)], capture_output=True, text=True, timeout=60
    )
    assert out.returncode == 2 and "offset" in out.stderr and "variables.x" in out.stderr, out.stderr


@pytest.mark.parametrize("unit,kelvin", [("20 degC", 293.15), ("-5 degC", 268.15), ("(20 degC)", 293.15)])
def test_a_temperature_alone_in_degc_still_reads(tmp_path, unit, kelvin):
    from gearhead.core import workbook

    book = workbook.from_text(
        f'name = "t"\n[variables]\nx = "{unit}"\n[cards.motor1]\ncalculator = "motor"\n'
        f'[[requirements]]\nname = "r"\ncheck = "x > {kelvin - 1} K"\n',
        "t.toml",
    )
    assert workbook.solve(book).checks[0].holds is True


@pytest.mark.skipif(not hasattr(os, "geteuid"), reason="POSIX permissions")
def test_a_read_only_file_is_not_replaced(tmp_path):
    """A rename needs only the folder's permission: a 0444 file was silently rewritten (opening it
    for writing, before the helper, refused). Root may write anything: checked as root too, since
    os.access says root may (so the write goes ahead only for root)."""
    import tempfile

    # a folder another user can reach (pytest's tmp_path sits under a 0700 folder of root's)
    folder = Path(tempfile.mkdtemp(prefix="gearhead-ro-", dir="/tmp" if os.path.isdir("/tmp") else None))
    target = folder / "ro.toml"
    target.write_text("old", encoding="utf-8")
    target.chmod(0o444)
    if os.geteuid() == 0:
        code = (
            "import os, sys; from gearhead.core import atomic_file; os.setuid(65534)\n"
            "try:\n atomic_file.write_text(sys.argv[1], 'new', overwrite=True)\n"
            "except atomic_file.WriteError as e:\n print('refused', e); sys.exit(3)\n"
        )
        os.chmod(folder, 0o777)
        out = subprocess.run(
            [sys.executable, "-c", code, str(target)], capture_output=True, text=True, timeout=60
        )
        assert out.returncode == 3 and "Permission denied" in out.stdout, (out.stdout, out.stderr)
    else:
        with pytest.raises(atomic_file.WriteError, match="Permission denied"):
            atomic_file.write_text(target, "new", overwrite=True)
    try:
        assert target.read_text(encoding="utf-8") == "old"
    finally:
        import shutil

        shutil.rmtree(folder, ignore_errors=True)


async def test_ctrl_s_never_rewrites_the_shipped_example_workbook(tmp_path, monkeypatch):
    """ctrl+o builtin:robot_2027, an edit, ctrl+s rewrote the example inside the installed package."""
    from gearhead.core import builtin, workbook
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.workbook_screen import WorkbookScreen
    from tests.tui_helpers import keys_of, started

    shipped = tmp_path / "examples"
    shipped.mkdir()
    copy = shipped / "robot_2027.toml"
    copy.write_bytes((builtin.examples_dir() / "robot_2027.toml").read_bytes())
    monkeypatch.setattr(builtin, "examples_dir", lambda: shipped)
    before = copy.read_bytes()
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(copy))
    async with app.run_test(size=(140, 45)) as pilot:
        await started(pilot)
        for _ in range(200):
            if isinstance(app.screen, WorkbookScreen):
                break
            await pilot.pause()
        screen = app.screen
        screen.robot.sheet.focus()
        assert screen.robot.sheet.move_to_field("carriage_mass")
        await pilot.press(*keys_of("15"), "enter")
        await pilot.pause(0.3)
        assert screen.action_save() is False
    assert copy.read_bytes() == before


async def test_ctrl_q_twice_on_an_edited_workbook_asks_once(tmp_path):
    from gearhead.core import workbook
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.leave_screen import LeaveScreen
    from tests.test_workbook_app import TEXT, opened, settled
    from tests.tui_helpers import keys_of

    path = tmp_path / "robot.toml"
    path.write_text(TEXT, encoding="utf-8")
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        screen.robot.sheet.focus()
        assert screen.robot.sheet.move_to_field("mass")
        await pilot.press(*keys_of("40"), "enter")
        await settled(pilot, screen)
        await pilot.press("ctrl+q")
        await pilot.pause()
        await pilot.press("ctrl+q")
        await pilot.pause()
        assert sum(isinstance(s, LeaveScreen) for s in app.screen_stack) == 1
        await pilot.press("escape")
        await pilot.pause()
        assert app.screen is screen


def test_quit_is_guarded():
    """@guarded had slipped from action_quit to the palette action inserted above it."""
    from gearhead.tui.app import GearheadApp

    assert getattr(GearheadApp.action_quit, "__wrapped__", None) is not None
    assert getattr(GearheadApp._quit_now, "__wrapped__", None) is not None


def test_the_served_load_dialog_cannot_browse(monkeypatch):
    from gearhead.tui import served_paths

    monkeypatch.setattr(served_paths, "_allowed", (Path("/nowhere"),))
    assert served_paths.confined()
    import asyncio

    from textual.widgets import Button

    from gearhead.tui.app import GearheadApp
    from tests.tui_helpers import settle

    async def run() -> bool:
        app = GearheadApp(blink=False, hide_timings=True, initial="motor")
        async with app.run_test(size=(140, 45)) as pilot:
            await settle(pilot)
            await pilot.press("ctrl+o")
            await settle(pilot)
            return app.screen.query_one("#browse", Button).disabled

    assert asyncio.run(run())


_ = InputError  # (the API's error type: imported for readers of this file)
