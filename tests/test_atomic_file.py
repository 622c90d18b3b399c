"""Every write goes through core/atomic_file.py (issue 41, item 4): whole or not at all, the old
file kept on any failure, no temporary file left, the mode kept, a symlink written through. Tested
on a full tmpfs and a read-only tmpfs (mounted here when we may: root; skipped with the reason
otherwise), a symlink, bad paths, and kill -9 in a bounded loop of a child process saving."""

import os
import random
import signal
import stat
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pytest

from gearhead.core import atomic_file, presets, workbook
from gearhead.core.atomic_file import WriteError
from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]
BOOK = ROOT / "examples" / "robot_2027.toml"


@pytest.fixture(params=["anonymous", "named"])
def temporaries(request, monkeypatch):
    """Both ways of making the temporary file: O_TMPFILE (Linux) and a hidden name (elsewhere)."""
    if request.param == "anonymous" and not atomic_file._ANONYMOUS["ok"]:
        pytest.skip("O_TMPFILE is not available here")
    monkeypatch.setitem(atomic_file._ANONYMOUS, "ok", request.param == "anonymous")
    return request.param


def run(capsys, *args):
    code = main(list(args))
    out = capsys.readouterr()
    return code, out.out, out.err


def _mount(folder: Path, options: str) -> Path:
    folder.mkdir()
    if os.name != "posix" or os.geteuid() != 0:
        pytest.skip("mounting a tmpfs needs root")
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(folder)], capture_output=True)
    if done.returncode != 0:
        pytest.skip(f"mount not permitted here: {done.stderr.decode(errors='replace').strip()}")
    return folder


@pytest.fixture
def full_disk(tmp_path):
    """A 64 KiB tmpfs holding a preset and a workbook, then filled to the last byte."""
    folder = _mount(tmp_path / "full", "size=64k")
    try:
        (folder / "old.toml").write_bytes((ROOT / "presets/elevator/two_neo.toml").read_bytes())
        (folder / "robot.toml").write_bytes(BOOK.read_bytes())
        try:
            with open(folder / "filler", "wb") as fh:
                while True:
                    fh.write(b"\0" * 1024)
                    fh.flush()
        except OSError:
            pass
        yield folder
    finally:
        subprocess.run(["umount", "-l", str(folder)], check=False)


@pytest.fixture
def read_only(tmp_path):
    """A tmpfs with a preset and a workbook, remounted read-only (root ignores a folder's mode)."""
    folder = _mount(tmp_path / "ro", "size=1m")
    try:
        (folder / "old.toml").write_bytes((ROOT / "presets/elevator/two_neo.toml").read_bytes())
        (folder / "robot.toml").write_bytes(BOOK.read_bytes())
        done = subprocess.run(["mount", "-o", "remount,ro", str(folder)], capture_output=True)
        if done.returncode != 0:
            pytest.skip(f"remount read-only not permitted: {done.stderr.decode(errors='replace').strip()}")
        yield folder
    finally:
        subprocess.run(["umount", "-l", str(folder)], check=False)


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in folder.iterdir() if p.name != "filler"}


def _hidden(folder: Path) -> list[str]:
    return [p.name for p in folder.iterdir() if p.name.startswith(".") or p.name.endswith(".tmp")]


def test_preset_out_on_a_full_disk_leaves_no_file(full_disk, capsys, temporaries):
    """It exited 2 but left a 0-byte file: a retry then said "exists", and the file loaded as
    "calculator: missing"."""
    before = _snapshot(full_disk)
    code, _, err = run(capsys, "solve", "beam", "--preset-out", str(full_disk / "new.toml"))
    assert code == 2 and "No space left on device" in err and "--preset-out" in err
    assert "new.toml" in err and len(err.strip().splitlines()) == 1
    assert _snapshot(full_disk) == before and not _hidden(full_disk)


def test_saves_on_a_full_disk_keep_the_old_file(full_disk, temporaries):
    before = _snapshot(full_disk)
    preset = presets.load(full_disk / "old.toml")
    preset.description = "x" * 100_000  # more than the disk holds
    with pytest.raises(WriteError, match="No space left"):
        presets.save(preset, full_disk / "old.toml", overwrite=True)
    with pytest.raises(WriteError, match="No space left"):
        workbook.save(full_disk / "robot.toml", {"x" * 100: "y" * 100_000})
    assert _snapshot(full_disk) == before and not _hidden(full_disk)


def test_a_read_only_folder_is_exit_2_and_changes_nothing(read_only, capsys, temporaries):
    before = _snapshot(read_only)
    code, _, err = run(capsys, "solve", "beam", "--preset-out", str(read_only / "new.toml"))
    assert code == 2 and "Read-only file system" in err
    code, _, err = run(capsys, "import", str(read_only / "old.toml"), "--out", str(read_only / "n.toml"))
    assert code == 2 and "Read-only file system" in err and "--out" in err
    with pytest.raises(WriteError, match="Read-only"):
        workbook.save(read_only / "robot.toml", {"mass": "12 lb"})
    with pytest.raises(WriteError, match="Read-only"):
        presets.save(presets.load(read_only / "old.toml"), read_only / "old.toml", overwrite=True)
    assert _snapshot(read_only) == before


@pytest.mark.parametrize(
    "target",
    ["/proc/foo.toml", "/dev/null/x.toml", "x" * 300 + ".toml", "~nosuchuser/x.toml"],
)
def test_import_and_preset_out_to_an_unwritable_path_are_exit_2(target, tmp_path, capsys, monkeypatch):
    """`gearhead import CODE --out /proc/foo.toml` (and /dev/null/x, a 300-character name,
    ~nosuchuser) exited 70; --preset-out to ~nosuchuser too (pathlib's expanduser raised)."""
    from gearhead.core import share

    monkeypatch.chdir(tmp_path)
    code_text = share.encode(presets.load(ROOT / "presets/elevator/two_neo.toml"))
    for args in (["import", code_text, "--out", target], ["solve", "beam", "--preset-out", target]):
        code, _, err = run(capsys, *args)
        assert code == 2, err
        assert "cannot write" in err and args[-2] in err and len(err.strip().splitlines()) == 1
    assert os.listdir(tmp_path) == []


def test_a_workbook_save_keeps_the_mode_and_writes_through_a_symlink(tmp_path, temporaries):
    """A save changed 0664 to 0600 (mkstemp's mode) and replaced a symlinked workbook with a
    regular file, so the link's target never got the edits."""
    real = tmp_path / "real" / "robot.toml"
    real.parent.mkdir()
    real.write_bytes(BOOK.read_bytes())
    os.chmod(real, 0o664)
    link = tmp_path / "robot.toml"
    link.symlink_to(real)
    workbook.save(link, {"mass": "123 lb"})
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert tomllib.loads(real.read_text())["variables"]["mass"] == "123 lb"
    assert stat.S_IMODE(real.stat().st_mode) == 0o664
    assert sorted(os.listdir(real.parent)) == ["robot.toml"]


def test_a_preset_overwrite_writes_through_a_symlink(tmp_path, temporaries):
    real = tmp_path / "real.toml"
    real.write_bytes((ROOT / "presets/elevator/two_neo.toml").read_bytes())
    os.chmod(real, 0o640)
    link = tmp_path / "link.toml"
    link.symlink_to(real.name)  # relative, as `ln -s real.toml link.toml` makes it
    preset = presets.load(link)
    preset.description = "edited"
    presets.save(preset, link, overwrite=True)
    assert link.is_symlink() and presets.load(real).description == "edited"
    assert stat.S_IMODE(real.stat().st_mode) == 0o640
    with pytest.raises(WriteError, match="exists"):
        presets.save(preset, link)  # a link to an existing file is an existing file


def test_settings_keep_their_mode(tmp_path, monkeypatch, temporaries):
    from gearhead.tui import settings

    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    path = settings.save({"units": "metric"})
    os.chmod(path, 0o644)
    settings.save({"units": "imperial"})
    assert stat.S_IMODE(path.stat().st_mode) == 0o644 and settings.load() == {"units": "imperial"}
    assert sorted(os.listdir(path.parent)) == [path.name]


def test_an_existing_special_file_is_never_replaced(tmp_path, temporaries):
    with pytest.raises(WriteError, match="not a regular file"):
        atomic_file.write_text("/dev/null", "x", overwrite=True)
    with pytest.raises(WriteError, match="not a regular file"):
        atomic_file.write_text(tmp_path, "x", overwrite=True)
    with pytest.raises(WriteError, match="exists"):
        atomic_file.write_text(tmp_path, "x")


def test_a_write_error_is_an_input_error_and_an_os_error():
    """The CLI's InputError handler makes it exit 2; callers that catch OSError (the app's
    settings, the workbook's ctrl+s) keep catching it."""
    from gearhead.core.errors import InputError

    with pytest.raises(InputError) as caught:
        atomic_file.write_text("/dev/null/x", "x", field="--out")
    assert isinstance(caught.value, OSError) and caught.value.strerror == "Not a directory"
    assert str(caught.value) == "/dev/null/x: --out: cannot write (Not a directory)"


_SAVER = """
import sys
from gearhead.core import workbook
path, stop = sys.argv[1], sys.argv[2]
n = 0
open(stop, "w").close()  # started: the parent may kill from now on
while True:
    n += 1
    workbook.save(path, {"mass": f"{n} lb", "pad": "p" * 200_000})
"""


def test_kill_9_during_saves_leaves_a_whole_file_and_no_temporary(tmp_path):
    """Saves killed mid-way left hidden .tmp files behind. The temporary file is now anonymous
    (O_TMPFILE) until it is whole, so a kill -9 cannot leave it (only the two-call window of
    link-then-rename could; a named temporary, used where O_TMPFILE is not, can be left). 25 kills
    at random moments; after each the workbook reads whole and the folder holds only it."""
    if not atomic_file._ANONYMOUS["ok"]:
        pytest.skip("O_TMPFILE is not available here: a kill -9 can leave a named temporary")
    path = tmp_path / "book" / "robot.toml"
    path.parent.mkdir()
    path.write_bytes(BOOK.read_bytes())
    env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}
    script = _SAVER
    rng = random.Random(41)
    for i in range(25):
        stop = tmp_path / f"started{i}"
        child = subprocess.Popen([sys.executable, "-c", script, str(path), str(stop)], env=env)
        deadline = time.monotonic() + 30
        while not stop.exists() and time.monotonic() < deadline and child.poll() is None:
            time.sleep(0.005)
        time.sleep(rng.uniform(0.01, 0.15))
        child.send_signal(signal.SIGKILL)
        child.wait()
        data = tomllib.loads(path.read_text())  # whole: the old file or a complete new one
        assert "cards" in data
        assert os.listdir(path.parent) == ["robot.toml"], os.listdir(path.parent)


@pytest.mark.parametrize("target", ["~nosuchuser/x.csv", "/dev/null/x.csv", "x" * 300 + ".csv"])
async def test_the_export_dialog_shows_why_a_path_cannot_be_written(target, tmp_path, monkeypatch):
    """ctrl+e, the path `~nosuchuser/x.csv`, Enter ended the app (pathlib's expanduser raised
    RuntimeError); now the dialog says why and stays open."""
    from textual.widgets import Button, Input, Static

    from gearhead.tui.app import GearheadApp
    from tests.tui_helpers import settle

    monkeypatch.chdir(tmp_path)
    app = GearheadApp(blink=False, initial="beam")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+e")
        await settle(pilot)
        app.screen.query_one("#export-path", Input).value = target
        app.screen.query_one("#save", Button).press()
        await settle(pilot)
        shown = str(app.screen.query_one("#export-error", Static).render())
        # said by the write, or first by the path check every dialog path goes through (served)
        assert ("cannot write" in shown or "not a usable file path" in shown) and app.is_running
    assert os.listdir(tmp_path) == []


def test_a_replaced_file_keeps_its_owner_where_we_may_set_it(tmp_path, temporaries):
    """Root saving a user's workbook made it root's (and, with mkstemp, 0600): the user lost it."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        pytest.skip("changing a file's owner needs root")
    path = tmp_path / "robot.toml"
    path.write_bytes(BOOK.read_bytes())
    os.chown(path, 1234, 2345)
    os.chmod(path, 0o664)
    workbook.save(path, {"mass": "12 lb"})
    info = path.stat()
    assert (info.st_uid, info.st_gid, stat.S_IMODE(info.st_mode)) == (1234, 2345, 0o664)


def test_where_proc_cannot_name_the_file_a_named_temporary_serves(tmp_path, monkeypatch):
    """A locked-down /proc (linkat refused): the write falls back to a named temporary file."""
    if not atomic_file._ANONYMOUS["ok"]:
        pytest.skip("O_TMPFILE is not available here")

    def refused(fd):
        def link(name):
            raise PermissionError(1, "Operation not permitted")

        return link

    monkeypatch.setattr(atomic_file, "_linker", refused)
    path = tmp_path / "x.txt"
    atomic_file.write_text(path, "one")
    atomic_file.write_text(path, "two", overwrite=True)
    assert path.read_text() == "two" and os.listdir(tmp_path) == ["x.txt"]
