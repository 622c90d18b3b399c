"""Presets: TOML round trip, atomic and non-clobbering save, and clear errors naming file and field."""

import tomllib

import pytest

from core import presets
from core.errors import InputError
from core.model import solve


def write(tmp_path, text, name="p.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


GOOD = '''calculator = "gear_ratio"
name = "Lift"
description = "test"
format = 1

[inputs]
load = "25 lbf"
radius = 1.5
motor_count = 2
mode = "max_power"
'''


def test_builtin_presets_load_and_solve():
    found = presets.listing()
    assert {p.calculator for p in found} >= {"motor", "gear_ratio"}
    assert presets.problems() == []
    for p in found:
        assert p.builtin
        solve(p.calculator, p.inputs)


def test_round_trip_changes_nothing_typed(tmp_path):
    src = write(tmp_path, GOOD)
    p = presets.load(src)
    out = presets.save(p, tmp_path / "copy.toml")
    assert tomllib.loads(out.read_text()) == tomllib.loads(GOOD)
    assert presets.load(out).inputs == {"load": "25 lbf", "radius": 1.5, "motor_count": 2, "mode": "max_power"}


def test_save_never_overwrites_silently_and_leaves_no_temp_files(tmp_path):
    p = presets.load(write(tmp_path, GOOD))
    target = tmp_path / "out" / "lift.toml"
    presets.save(p, target)
    with pytest.raises(InputError) as e:
        presets.save(p, target)
    assert "exists" in e.value.message
    presets.save(p, target, overwrite=True)
    assert sorted(x.name for x in target.parent.iterdir()) == ["lift.toml"]


def test_user_presets_go_to_xdg_config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "cfg"))
    p = presets.load(write(tmp_path, GOOD))
    path = presets.save(p)
    assert path == tmp_path / "cfg" / "gearhead" / "presets" / "gear_ratio" / "lift.toml"
    assert any(not q.builtin and q.name == "Lift" for q in presets.listing("gear_ratio"))


@pytest.mark.parametrize("text,field,words", [
    (GOOD.replace('"gear_ratio"', '"warp_drive"'), "calculator", "unknown calculator"),
    (GOOD.replace("load =", "lode ="), "lode", "unknown field"),
    (GOOD.replace('"25 lbf"', '"25 kg"'), "load", "not a force"),
    (GOOD.replace('"25 lbf"', '"-25 lbf"'), "load", "too small"),
    (GOOD.replace("motor_count = 2", "motor_count = [2]"), "motor_count", "wrong type"),
    (GOOD.replace("format = 1", "format = 9"), "format", "newer"),
    (GOOD.replace('mode = "max_power"', 'mode = "fastest"'), "mode", "not one of"),
    (GOOD + "\n[inputs\n", "preset", "malformed TOML"),
])
def test_bad_presets_name_file_and_field(tmp_path, text, field, words):
    path = write(tmp_path, text)
    with pytest.raises(InputError) as e:
        presets.load(path)
    assert e.value.field == field
    assert words in e.value.message
    assert str(path) in str(e.value)


def test_broken_user_preset_is_reported_not_fatal(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "cfg"))
    d = presets.user_dir() / "gear_ratio"
    d.mkdir(parents=True)
    (d / "bad.toml").write_text("this is not toml =")
    assert presets.listing("gear_ratio")  # built-ins still listed
    assert len(presets.problems("gear_ratio")) == 1
