"""Issue 40's smaller things, each pinned by a test that failed before its fix."""

from pathlib import Path

from gearhead.core import sweep

ROOT = Path(__file__).resolve().parents[1]


def test_sweep_status_is_ok_where_every_point_gives_the_same_note():
    # the elevator's default move is closed form: solve notes it; a sweep said it in every row's status
    result = sweep.run("elevator", {}, ["voltage=10..12:3"])
    assert all(p.error is None and p.warnings == [] for p in result.points)
    shared = [n for n in result.notes if "closed form, no integration" in n]
    assert len(shared) == 1 and shared[0].startswith("at every point: ")
    assert "warning:" not in sweep.text_table(result)
    # a warning particular to a point stays in that point's row
    varied = sweep.run("flywheel", {}, ["voltage=10..12:3"])
    assert all(len(p.warnings) == 1 and "VEX 393" in p.warnings[0] for p in varied.points)
