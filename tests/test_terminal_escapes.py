"""Text from files reaches the terminal escaped (issue 41, item 5): a workbook's name, description,
requirement names and notes, and text variables reached the terminal raw from `check`, `solve`
and `--worst-case` (an ESC in `name` cleared the screen). Every CLI print of file text goes
through core.errors.printable; these tests grep the output for raw control characters, over a
hand-made hostile workbook and over fuzzed ones (hypothesis, bounded)."""

import contextlib
import io
import unicodedata

import pytest
import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearhead.tui.cli import main

# what must never reach the terminal raw: C0 and C1 controls (ESC, CSI \x9b, BEL, BS, CR, NUL...),
# and the invisible format and separator characters (bidi overrides, U+2028)
NASTY = [
    "\x1b",
    "\x1b[2J",
    "\x1b]0;t\x07",
    "\x07",
    "\x08",
    "\r",
    "\x9b31m",
    "\x00",
    "\x7f",
    "\u202e",
    "\u2028",
    "\t",
    "\n",
]


def raw_controls(text: str) -> list[str]:
    """The characters of `text` a terminal would act on (a line break ends a line: allowed)."""
    return sorted({ch for ch in text if ch != "\n" and unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp")})


def run(*args) -> tuple[int, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(args))
    return code, out.getvalue() + err.getvalue()


def book(name="n", description="", motor="NEO", word="w", rname="r", note="", check="lift.ratio > 1") -> dict:
    return {
        "format": 1,
        "name": name,
        "description": description,
        "variables": {"mass": "10 lb ± 1 lb", "motor_name": motor, "word": word},
        "cards": {
            "lift": {
                "calculator": "gear_ratio",
                "inputs": {"motor": "= motor_name", "load": "= mass * 9.80665 m/s**2", "radius": "0.75 in"},
            }
        },
        "requirements": [
            {"name": rname, "check": "lift.ratio > 1", "note": note},
            {"name": rname + "2", "check": check},
        ],
    }


COMMANDS = (("check",), ("check", "--worst-case"), ("solve",), ("sweep", "--vary", "mass=5..10:2"))


def test_printable_makes_every_control_character_visible():
    from gearhead.core.errors import printable

    assert printable("a\x1b[2Jb") == "a\\x1b[2Jb" and printable("x\ny") == "x\\ny"
    assert printable("x\ny\x07", keep_newlines=True) == "x\ny\\x07"
    assert printable("✔ → é 日本") == "✔ → é 日本"
    assert not raw_controls(printable("".join(NASTY)))


@pytest.mark.parametrize("command", COMMANDS, ids=" ".join)
def test_a_hostile_workbook_prints_no_raw_control_character(command, tmp_path):
    """The issue's reproducer: an ESC sequence in every text of the file."""
    path = tmp_path / "book.toml"
    esc = "\x1b[2J\x1b]0;title\x07\x9b31m\r\x08"
    data = book(name=f"N{esc}", description=f"D{esc}", motor=f"NEO{esc}", word=f"W{esc}", rname=f"R{esc}")
    data["requirements"][0]["note"] = f"note{esc}"
    path.write_text(tomli_w.dumps(data))
    code, text = run(command[0], str(path), *command[1:])
    assert code in (0, 1, 2) and text
    assert raw_controls(text) == [], text
    # and with a motor that solves, so names and notes print beside results
    data["variables"]["motor_name"] = "NEO"
    path.write_text(tomli_w.dumps(data))
    code, text = run(command[0], str(path), *command[1:])
    assert code in (0, 1) and "N\\x1b[2J" in text and raw_controls(text) == [], text


def test_a_preset_with_control_characters_prints_none(tmp_path):
    """`solve CALC --preset FILE`: a preset's unknown keys and names reach only escaped warnings."""
    path = tmp_path / "p.toml"
    path.write_text(
        tomli_w.dumps(
            {
                "calculator": "motor",
                "name": "x\x1b[2J",
                "description": "d\x1b[31m",
                "inputs": {"motor_count": 2, "bogus\x1b[2J": "1", "motor": "NEO"},
            }
        )
    )
    for args in (["solve", "motor", "--preset", str(path)], ["presets", "motor"], ["share", str(path)]):
        code, text = run(*args)
        assert raw_controls(text) == [], (args, text)


hostile = st.lists(
    st.one_of(st.sampled_from(NASTY), st.text(st.characters(codec="utf-8"), max_size=3)), max_size=6
).map("".join)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    name=hostile,
    description=hostile,
    motor=st.one_of(st.just("NEO"), hostile),
    word=hostile,
    rname=hostile,
    note=hostile,
    check=st.one_of(st.just("lift.ratio < 1000"), hostile),
    command=st.sampled_from(COMMANDS),
)
def test_fuzzed_workbooks_print_no_raw_control_character(
    tmp_path, name, description, motor, word, rname, note, check, command
):
    path = tmp_path / "fuzz.toml"
    path.write_text(tomli_w.dumps(book(name, description, motor, word, rname, note, check)))
    code, text = run(command[0], str(path), *command[1:])
    assert code in (0, 1, 2), text  # never 70
    assert raw_controls(text) == [], text


def test_share_import_and_preset_out_print_file_text_escaped(tmp_path):
    """`share`/`import` printed a preset's warnings (which quote the file) and `--preset-out` its
    path as they were."""
    from gearhead.core import share
    from gearhead.core.presets import Preset

    code = share.encode(Preset("motor", "x\x1b[2J", "", {"motor_count": 2}))
    out = tmp_path / "p\x1b[2J.toml"
    for args in (
        ["import", code, "--out", str(out)],
        ["solve", "motor", "--preset-out", str(tmp_path / "q\x1b[2J.toml")],
    ):
        status, text = run(*args)
        assert status == 0 and "\\x1b[2J" in text and raw_controls(text) == [], (args, text)
