"""Share codes (core/share.py): `gh1:` + URL-safe base64 of the zlib-compressed preset TOML.

Every built-in preset goes round the code unchanged; the format is checked with the standard
library alone (so the encoder cannot drift from what DESIGN.md and the README promise); every
damaged or foreign code is an InputError with one line, never another exception."""

import base64
import json
import tomllib
import zlib
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core import presets, share
from gearhead.core.errors import InputError
from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]
BUILTINS = presets.listing()
SMALL = 'calculator = "gear_ratio"\nname = "x"\nformat = 1\n\n[inputs]\nload = "31 lbf"\n'


def _body(text: str) -> bytes:
    """The compressed bytes of a code, read with the standard library (the documented format)."""
    body = text.removeprefix("gh1:")
    return base64.urlsafe_b64decode(body + "=" * (-len(body) % 4))


def run(capsys, *args):
    code = main(list(args))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_there_are_builtin_presets_to_check():
    assert len(BUILTINS) >= 30 and len({p.calculator for p in BUILTINS}) >= 15


@pytest.mark.parametrize("preset", BUILTINS, ids=lambda p: f"{p.calculator}/{p.path.stem}")
def test_every_builtin_preset_goes_round_a_share_code(preset):
    code = share.encode(preset)
    assert code.startswith("gh1:") and "=" not in code
    assert set(code[4:]) <= set("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_")
    back = share.decode(code)
    assert (back.calculator, back.name, back.description, back.inputs) == (
        preset.calculator,
        preset.name,
        preset.description,
        preset.inputs,
    )
    # the format, read without Gearhead: the TOML of the preset, zlib-compressed
    assert tomllib.loads(zlib.decompress(_body(code)).decode("utf-8")) == preset.as_toml()
    assert share.encode(back) == code  # stable: the same preset, the same code


def test_a_code_written_by_hand_from_the_documented_format_is_read():
    packed = base64.urlsafe_b64encode(zlib.compress(SMALL.encode(), 1)).decode().rstrip("=")
    preset = share.decode("gh1:" + packed)
    assert (preset.calculator, preset.name, preset.inputs) == ("gear_ratio", "x", {"load": "31 lbf"})


@pytest.mark.parametrize(
    "wrap",
    [
        "{}",
        "  {}\n",
        "gearhead://open?p={}",
        "http://127.0.0.1:8000/?p={}",
        "http://localhost:8000/?x=1&p={}#top",
    ],
)
def test_a_code_is_read_bare_in_a_link_and_wrapped_by_a_chat(wrap):
    code = share.encode_text(SMALL)
    assert share.decode(wrap.format(code)).inputs == {"load": "31 lbf"}
    wrapped = code[:30] + "\n" + code[30:60] + " " + code[60:]  # a chat broke the line
    assert share.decode(wrap.format(wrapped)).inputs == {"load": "31 lbf"}


def _error(text: str) -> str:
    with pytest.raises(InputError) as caught:
        share.decode(text)
    message = str(caught.value)
    assert message and "\n" not in message
    return message


def test_unknown_versions_are_refused_by_name():
    body = share.encode_text(SMALL)[4:]
    assert "version 2 is newer" in _error("gh2:" + body)
    assert "version 0 is not" in _error("gh0:" + body)
    assert "version 99 is newer" in _error("GH99:" + body)


@pytest.mark.parametrize(
    "text,why",
    [
        ("gh1:", "empty"),
        ("gh1:abc$def", "'$'"),
        ("gh1:a", "damaged"),
        ("hello", "not a share code"),
        ("gh1:" + base64.urlsafe_b64encode(b"not zlib at all").decode().rstrip("="), "damaged"),
        ("gh1:" + base64.urlsafe_b64encode(zlib.compress(b"\xff\xfe\x00")).decode(), "does not hold text"),
        ("gh1:" + base64.urlsafe_b64encode(zlib.compress(b" " * 2_000_000)).decode(), "more than"),
        ("gh1:" + base64.urlsafe_b64encode(zlib.compress(SMALL.encode()) + b"xx").decode(), "extra"),
        ("gh1:" + base64.urlsafe_b64encode(zlib.compress(b"x = [")).decode(), "malformed TOML"),
        (
            "gh1:" + base64.urlsafe_b64encode(zlib.compress(SMALL.replace("load", "lode").encode())).decode(),
            "lode",
        ),
    ],
)
def test_corrupt_and_foreign_codes_are_refused_with_a_message(text, why):
    assert why in _error(text)


def test_a_code_cut_short_or_with_a_character_changed_is_refused():
    code = share.encode(BUILTINS[0])
    for cut in range(5, len(code) - 1, 7):
        _error(code[:cut])
    for at in range(4, len(code), 5):
        changed = code[:at] + ("A" if code[at] != "A" else "B") + code[at + 1 :]
        _error(changed)  # Adler-32 (or the TOML, or the preset's checks) catches every one


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=300))
def test_any_text_after_the_prefix_is_a_preset_or_an_input_error(tail):
    try:
        share.decode("gh1:" + tail)
    except InputError as exc:
        assert "\n" not in str(exc)


def test_cli_share_prints_a_code_that_solves_as_the_file_does(capsys):
    path = str(ROOT / "presets/gear_ratio/elevator_neo.toml")  # closed form: no wall time in it
    code, out, _ = run(capsys, "share", path)
    assert code == 0 and out.startswith("gh1:") and len(out.splitlines()) == 1
    share_code = out.strip()
    _, from_file, _ = run(capsys, "solve", "gear_ratio", "--preset", path, "--json")
    _, from_code, _ = run(capsys, "solve", "gear_ratio", "--preset", share_code, "--json")
    assert json.loads(from_code) == json.loads(from_file)
    code, out, _ = run(capsys, "share", path, "--link")
    assert out.strip() == f"gearhead://open?p={share_code}"
    code, out, _ = run(capsys, "import", share_code)  # a code back to its TOML
    assert code == 0 and presets.from_dict(tomllib.loads(out)).inputs == presets.load(path).inputs


def test_cli_refuses_a_bad_code_in_one_line_with_exit_2(capsys):
    code, out, err = run(capsys, "solve", "elevator", "--preset", "gh7:abc")
    assert code == 2 and out == "" and err.count("\n") == 1 and "version 7" in err
    code, out, err = run(capsys, "share", "gh1:zzzz")
    assert code == 2 and err.count("\n") == 1 and "damaged" in err
    code, out, err = run(
        capsys,
        "solve",
        "beam",
        "--preset",
        share.encode(presets.load(ROOT / "presets/elevator/two_neo.toml")),
    )
    assert code == 2 and "elevator" in err


def test_cli_import_writes_a_new_file_and_never_replaces_one(tmp_path, capsys):
    target = tmp_path / "x.toml"
    code_text = share.encode_text(SMALL)
    assert run(capsys, "import", code_text, "--out", str(target))[0] == 0
    assert presets.load(target).inputs == {"load": "31 lbf"}
    code, _, err = run(capsys, "import", code_text, "--out", str(target))
    assert code == 2 and "exists" in err


def test_a_preset_name_with_a_control_character_is_shown_escaped(tmp_path, capsys):
    """`gearhead import CODE --out FILE` printed a shared preset's name raw: an escape sequence in
    it acted on the terminal. Shown escaped, as `gearhead presets` lists names."""
    from gearhead.core.presets import Preset
    from gearhead.tui.cli import main

    code = share.encode(Preset("motor", "x\x1b[31mRED\x1b[0m", "", {"motor_count": 2}))
    assert main(["import", code, "--out", str(tmp_path / "p.toml")]) == 0
    err = capsys.readouterr().err
    assert "RED" in err and "\x1b" not in err and "\\x1b[31m" in err
