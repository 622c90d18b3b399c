"""The sprint's robot config for PathPlanner and Choreo through the CLI (`solve sprint --document`) and
the app's export dialog (ctrl+e): the values are the solved sprint's (hand-checked), a robot the other
tool cannot take is refused with the reason (exit 2, or a message in the dialog), never a traceback.
The formats themselves are tests/test_robot_config.py's."""

import json

import pytest

from gearhead.tui.app import GearheadApp
from gearhead.tui.cli import main
from tests.tui_helpers import settle

INCH, LB = 0.0254, 0.45359237


def document(capsys, *args):
    code = main(["solve", "sprint", *args])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_pathplanner_settings_carry_the_sprints_numbers(capsys):
    code, text, _ = document(capsys, "--document", "pathplanner")
    assert code == 0
    pp = json.loads(text)
    m, side = 135 * LB, 34 * INCH
    assert pp["robotMass"] == pytest.approx(m, rel=1e-12)
    assert pp["robotMOI"] == pytest.approx(m * (side**2 + side**2) / 12, rel=1e-12)  # (S13) estimate
    assert pp["driveGearing"] == 6.75 and pp["driveWheelRadius"] == pytest.approx(2 * INCH, rel=1e-12)
    assert pp["driveCurrentLimit"] == 80 and pp["driveMotorType"] == "krakenX60" and pp["holonomicMode"]
    assert pp["flModuleX"] == pytest.approx(22.75 / 2 * INCH, rel=1e-12)
    code, text, _ = document(capsys, "--json")
    top = json.loads(text)["outputs"]["top_speed"]["value"]
    assert pp["maxDriveSpeed"] == pytest.approx(top, rel=1e-12)


def test_optimise_exports_the_fastest_ratio(capsys):
    code, text, _ = document(capsys, "--set", "mode=optimise", "--document", "choreo")
    chor = json.loads(text)
    code, out, _ = document(capsys, "--set", "mode=optimise", "--json")
    best = json.loads(out)["outputs"]["best_ratio"]["value"]
    assert chor["version"] == 2 and chor["config"]["gearing"]["val"] == pytest.approx(best, rel=1e-12)


@pytest.mark.parametrize(
    "args,says",
    [
        (["--set", "motor=Kraken X44", "--document", "pathplanner"], "PathPlanner has no drive motor type"),
        (["--set", "drive=mecanum", "--document", "choreo"], "mecanum"),
        (["--document", "solidworks"], "is not a document of sprint"),
        (["--set", "trackwidth=40 in", "--document", "pathplanner"], "inside the bumpers"),
    ],
)
def test_what_cannot_be_exported_is_refused_with_the_reason(capsys, args, says):
    code, out, err = document(capsys, *args)
    assert code == 2 and out == "" and "--document" in err and says in err and "Traceback" not in err


def test_calculators_lists_the_documents(capsys):
    assert main(["calculators", "--json"]) == 0
    listed = {c["id"]: c["documents"] for c in json.loads(capsys.readouterr().out)}
    assert [d["name"] for d in listed["sprint"]] == ["pathplanner", "choreo"] and listed["beam"] == []


async def test_the_export_dialog_saves_the_pathplanner_file(tmp_path, monkeypatch):
    from textual.widgets import Button, Input, OptionList

    monkeypatch.chdir(tmp_path)
    app = GearheadApp(blink=False, initial="sprint")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+e")
        await settle(pilot)
        options = app.screen.query_one(OptionList)
        labels = [str(options.get_option_at_index(i).prompt) for i in range(options.option_count)]
        index = next(i for i, label in enumerate(labels) if label.startswith("PathPlanner"))
        options.highlighted = index
        await settle(pilot)
        assert app.screen.query_one("#export-path", Input).value == "settings.json"
        dialog = app.screen
        dialog.query_one("#save", Button).press()
        for _ in range(100):  # the press is a message: on a loaded machine settle may return first
            await settle(pilot)
            if (tmp_path / "settings.json").exists():
                break
        saved = tmp_path / "settings.json"
        assert saved.exists(), f"not saved; the dialog says: {dialog.query_one('#export-error').render()}"
        assert json.loads(saved.read_text())["driveMotorType"] == "krakenX60"
