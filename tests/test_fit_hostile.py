"""`gearhead fit` against a hostile user (issue 44's attack): paths that are not log files (a FIFO must
not hang, a device must not be read forever), logs whose values overflow the replay, --apply to
files that cannot take it. Each case: a message naming the field and what is wrong, exit 2, no
traceback, nothing written."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from gearhead.core.errors import InputError
from gearhead.core.fit import logs


def _gearhead(*args, timeout=60):
    return subprocess.run(
        [sys.executable, "-m", "gearhead.tui", *args], capture_output=True, text=True, timeout=timeout
    )


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
@pytest.mark.parametrize("name", ["pipe.wpilog", "pipe.csv"])
def test_fifo_is_refused_not_waited_on(tmp_path, name):
    # open() of a FIFO with no writer blocks forever: the CLI hung, and the app's fit worker thread
    # with it (the app could not even quit: Python waits for the thread)
    path = tmp_path / name
    os.mkfifo(path)
    r = _gearhead("fit", str(path), "--card", "elevator", timeout=30)
    assert r.returncode == 2, r.stderr
    assert f"{path}: log: is a pipe (FIFO), not a log file" in r.stderr
    assert "Traceback" not in r.stderr


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_device_is_refused(device):
    if not os.path.exists(device):
        pytest.skip(f"no {device}")
    for name in (device,):
        with pytest.raises(InputError, match=f"{device}: log: is a device, not a log file"):
            logs.read(name, lambda n: True)


def test_directory_is_named(tmp_path):
    for suffix in ("", ".csv"):
        d = tmp_path / f"logs{suffix}"
        d.mkdir()
        with pytest.raises(InputError, match="log: is a directory, not a log file"):
            logs.read(d, lambda n: True)
