"""The example SysId log shipped in examples/ (issue 44, README "Fitting the model from the robot's
logs"): it installs with the package, examples/make_sysid_log.py writes it again byte for byte, its
fit gives the plant's gains back, and the README shows what `gearhead fit` prints for it."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]
LOG = ROOT / "examples" / "elevator_sysid.wpilog"
COMMAND = "gearhead fit examples/elevator_sysid.wpilog --card elevator"
sys.path.insert(0, str(ROOT / "examples"))
import make_sysid_log  # noqa: E402


def test_the_log_is_small_and_packaged():
    assert LOG.stat().st_size <= 300_000
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert '"gearhead.examples" = ["*.toml", "*.wpilog"]' in text


def test_the_script_writes_the_shipped_log_again_byte_for_byte(tmp_path):
    pytest.importorskip("wpiutil")
    again = make_sysid_log.write(tmp_path / "again.wpilog")
    assert again.read_bytes() == LOG.read_bytes()


def test_its_fit_gives_the_plant_back():
    from gearhead.core import fit

    plant = make_sysid_log.plant()
    report = fit.fit_log(LOG, "elevator")
    assert report.favoured == "discrete"
    for form, f in report.fits.items():
        for k in ("kV", "kG"):
            assert f.gains[k] == pytest.approx(plant[k], rel=0.01), (form, k)
    best = report.fits["discrete"].gains
    for k in ("kS", "kA"):
        assert best[k] == pytest.approx(plant[k], rel=0.01), k


def test_the_readme_prints_what_the_command_prints(capsys, monkeypatch):
    monkeypatch.chdir(ROOT)  # the README's path is a clone's
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert readme.count(COMMAND + "\n") == 1
    shown = readme.split(COMMAND + "\n", 1)[1].split("```", 1)[0]
    assert main(COMMAND.split()[1:]) == 0
    out = capsys.readouterr().out
    assert rounding_masked(out) == rounding_masked(shown)
    assert out.count("\n") == shown.count("\n")


# The log has no noise: the discrete fit's ± and RMSEs are the solves' rounding (1e-16 to 1e-13),
# whose digits follow the CPU's BLAS kernel (1.332e-15 on one machine, 3.758e-15 on another).
ROUNDING_LEVEL = re.compile(r" *\b\d(?:\.\d+)?e-(?:1[2-9]|[2-9]\d)\b")


def rounding_masked(text: str) -> str:
    """`text` with rounding-level figures masked and runs of spaces as one (a column's width
    follows its widest figure)."""
    return re.sub(r" +", " ", ROUNDING_LEVEL.sub(" (rounding)", text))
