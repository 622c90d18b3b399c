"""The design report (core/report/, `gearhead report`): every input and result the CLI's `--json`
has, formatted as the CLI formats it; charts drawn from the series the cards plot; the same bytes
for the same file; hostile text escaped; a bad file refused as the other commands refuse it."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from gearhead.core import presets, units
from gearhead.core.registry import get
from gearhead.core.report import document, html, markdown
from gearhead.core.sim.scene import VOLATILE
from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = str(ROOT / "examples" / "robot_2027.toml")
BUILTINS = [p for p in presets.listing() if p.builtin]


def cli_json(capsys, *argv: str) -> dict:
    capsys.readouterr()
    code = main(list(argv))
    out = capsys.readouterr().out
    assert code in (0, 1), out
    return json.loads(out)


def _value_cell(text: str) -> str:
    """How the HTML shows a value: its own table cell, the CLI's text escaped."""
    return f'<td class="value">{html.esc(text)}</td>'


def _card_html(page: str, key: str) -> str:
    start = page.index(f'id="card-{html.esc(key)}"')
    end = page.find("</section>", start)
    return page[start:end]


@pytest.mark.parametrize("preset", BUILTINS, ids=[f"{p.calculator}/{p.path.stem}" for p in BUILTINS])
def test_each_builtin_preset_report_has_every_input_and_result_of_solve_json(preset, capsys):
    data = cli_json(capsys, "solve", preset.calculator, "--preset", str(preset.path), "--json")
    report = document.build(str(preset.path))
    page = _card_html(html.write(report), preset.calculator)
    for name, value in data["inputs"].items():
        assert _value_cell(value["text"]) in page, f"input {name}: {value['text']!r}"
    for name, value in data["outputs"].items():
        if name in VOLATILE:  # the wall time differs run to run: not recorded without --date
            assert _value_cell(document.NOT_RECORDED_VALUE) in page
            continue
        assert _value_cell(value["text"]) in page, f"output {name}: {value['text']!r}"
        label = get(preset.calculator).output(name).label
        assert f"<td>{html.esc(label)}</td>" in page
    for warning in data["warnings"]:
        assert f"<li>{html.esc(warning)}</li>" in page
    calc = get(preset.calculator)
    for table, rows in data.get("tables", {}).items():
        shown = {col.name for t in calc.tables if t.name == table for col in t.columns if not col.hidden}
        for row in rows:  # the columns the card and `solve` show (a hidden one is for sending a row)
            for cell in (row[name] for name in row if name in shown):
                assert f"<td>{html.esc(cell['text'])}</td>" in page, f"table {table}: {cell['text']!r}"


def test_the_example_workbook_report_has_every_card_requirement_and_match_value(capsys):
    solved = cli_json(capsys, "solve", EXAMPLE, "--json")
    checked = cli_json(capsys, "check", EXAMPLE, "--json")
    matched = cli_json(capsys, "match", EXAMPLE, "--json")
    report = document.build(EXAMPLE)
    page = html.write(report)
    md = markdown.write(report, "robot")
    assert solved["cards"], "the example has cards"
    for card, data in solved["cards"].items():
        section = _card_html(page, card)
        for name, value in data["solution"]["inputs"].items():
            assert _value_cell(value["text"]) in section, f"{card}.{name}: {value['text']!r}"
            assert markdown.esc(value["text"]) in md
        for name, value in data["solution"]["outputs"].items():
            if name not in VOLATILE:
                assert _value_cell(value["text"]) in section, f"{card}.{name}: {value['text']!r}"
                assert markdown.esc(value["text"]) in md
        for link in data["links"].values():
            assert f"<td>{html.esc(link)}</td>" in section
    for r in checked["requirements"]:
        for side in r["values"]:
            assert html.esc(side) in page
        margin = f"(margin {units.format_number(r['margin'])}{(' ' + r['unit']) if r['unit'] else ''})"
        assert html.esc(margin) in page, margin
        assert html.esc(r["name"]) in page and html.esc(r["check"]) in page
    for name, value in matched["outputs"].items():
        assert _has_match_value(page, value), name


def _match_text(value: dict) -> str:
    """A `gearhead match --json` output as the report shows it."""
    v = value["value"]
    return f"{v:d}" if isinstance(v, int) else f"{units.format_number(v)} {value['unit']}".rstrip()


def _has_match_value(page: str, value: dict) -> bool:
    text = _match_text(value)
    # the lowest voltage's time names what was running: "138.5 s (arm move running)"
    return _value_cell(text) in page or f'<td class="value">{html.esc(text)} (' in page


def test_set_replaces_a_variable_as_match_set_does_and_the_title_block_says_so(tmp_path, capsys):
    sets = ["--set", "battery_resistance=0.025 ohm"]
    tired = cli_json(capsys, "match", EXAMPLE, *sets, "--json")
    nominal = cli_json(capsys, "match", EXAMPLE, "--json")
    solved = cli_json(capsys, "solve", EXAMPLE, *sets, "--json")
    out = tmp_path / "tired.html"
    assert main(["report", EXAMPLE, *sets, "--out", str(out)]) == 0
    page = out.read_text(encoding="utf-8")
    header = page.split("</header>")[0]
    # a reader is told what the report shows: the variable set, and what the file says
    assert "<th>Set for this report (--set)</th>" in header
    assert html.esc("battery_resistance = 0.025 ohm (the file: 0.02 ohm ± 0.005 ohm)") in header
    changed = []
    for name, value in tired["outputs"].items():
        assert _has_match_value(page, value), (name, _match_text(value))
        if _match_text(value) != _match_text(nominal["outputs"][name]):
            changed.append(name)
    assert changed, "the tired battery changes the match"
    lift = _card_html(page, "lift")
    text = solved["cards"]["lift"]["solution"]["inputs"]["battery_resistance"]["text"]
    assert _value_cell(text) in lift and "0.025" in text
    assert main(["report", EXAMPLE, *sets, "--out", str(tmp_path / "tired.md")]) == 0
    md = (tmp_path / "tired.md").read_text(encoding="utf-8")
    head = md.split("## Requirements")[0]
    assert markdown.esc("Set for this report (--set): battery_resistance = 0.025 ohm") in head
    for value in tired["outputs"].values():
        assert markdown.esc(_match_text(value)) in md


def test_set_is_refused_as_check_refuses_it(tmp_path, capsys):
    for bad in ("no_such_variable=3", "battery_resistance", "=3"):
        code, err = _stderr_of(capsys, "report", EXAMPLE, "--set", bad, "--out", str(tmp_path / "x.html"))
        assert code == 2 and err == _stderr_of(capsys, "check", EXAMPLE, "--set", bad)[1], bad
    code, err = _stderr_of(
        capsys, "report", "builtin:elevator/two_neo", "--set", "a=1", "--out", str(tmp_path / "y.html")
    )
    assert code == 2 and "--set" in err and err.count("\n") == 1
    assert not list(tmp_path.glob("*.html"))


def test_the_charts_are_the_series_the_cards_plot():
    """Each chart is a Plot the calculator declares (what the app's card draws), its points the
    solution's series in the plot's display units."""
    from gearhead.core import workbook

    wb = workbook.load(EXAMPLE)
    outcome = workbook.solve(wb)
    lift = outcome.cards["lift"]
    calc = get("elevator")
    charts = {c.title: c for c in document.charts_of(calc, lift.solution, "lift")}
    spec = next(p for p in calc.plots if p.title == "Position")
    xs, ys = lift.solution.series[spec.series[0]]
    fx, fy = units.factor(spec.x_unit, spec.x_quantity), units.factor(spec.y_unit, spec.y_quantity)
    chart = charts["Position"]
    assert chart.series[0].x == [x / fx for x in xs] and chart.series[0].y == [y / fy for y in ys]
    # only the charts with data, and each of them
    with_data = [
        p.title for p in calc.plots if any(lift.solution.series.get(s, ([], []))[0] for s in p.series)
    ]
    assert list(charts) == with_data


def _path_points(svg: str, gid: str) -> list[tuple[float, float]]:
    group = re.search(rf'<g id="{re.escape(gid)}">\s*<path d="([^"]+)"', svg)
    assert group, f"no path in group {gid}"
    numbers = [float(n) for n in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", group.group(1))]
    return list(zip(numbers[0::2], numbers[1::2]))


def test_a_charts_svg_path_maps_back_to_its_data():
    from gearhead.core.report import charts

    report = document.build(EXAMPLE)
    chart = next(
        c for card in report.cards if card.key == "lift" for c in card.charts if c.title == "Position"
    )
    fig = charts.figure(chart)
    svg = charts.svg_of(fig)
    points = _path_points(svg, f"{chart.key}-s0")
    s = chart.series[0]
    assert len(points) == len(s.x)
    height = charts.HEIGHT_IN * charts.DPI
    ax = fig.axes[0]
    for k in (0, len(s.x) // 3, len(s.x) // 2, len(s.x) - 1):
        px, py = ax.transData.transform((s.x[k], s.y[k]))
        sx, sy = points[k]
        assert abs(sx - px) < 0.01 and abs(sy - (height - py)) < 0.01, (k, (sx, sy), (px, height - py))
    # and back: the file's coordinates give the data
    inverse = ax.transData.inverted()
    x, y = inverse.transform((points[-1][0], height - points[-1][1]))
    assert x == pytest.approx(s.x[-1], rel=1e-4, abs=1e-6) and y == pytest.approx(s.y[-1], rel=1e-4, abs=1e-6)


def test_the_same_file_gives_the_same_bytes_and_no_date():
    one = html.write(document.build(EXAMPLE))
    two = html.write(document.build(EXAMPLE))
    assert one == two
    assert "<dc:date>" not in one and "Date" not in one.split("</header>")[0]
    md1 = markdown.write(document.build("builtin:flywheel/frc_two_kraken_limits"), "x")
    files1 = markdown.chart_files(document.build("builtin:flywheel/frc_two_kraken_limits"), "x")
    md2 = markdown.write(document.build("builtin:flywheel/frc_two_kraken_limits"), "x")
    files2 = markdown.chart_files(document.build("builtin:flywheel/frc_two_kraken_limits"), "x")
    assert md1 == md2 and files1 == files2 and files1


def test_a_date_only_when_asked():
    report = document.build("builtin:elevator/two_neo", date="2027-03-01")
    page = html.write(report)
    assert "<th>Date</th><td>2027-03-01</td>" in page
    assert document.NOT_RECORDED not in page and _value_cell(document.NOT_RECORDED_VALUE) not in page


def test_the_html_is_self_contained():
    page = html.write(document.build(EXAMPLE))
    assert "<script" not in page.lower()
    assert not re.search(r"""(src|href)=["']?(https?:|//)""", page)
    assert "@import" not in page and "url(http" not in page
    assert "Content-Security-Policy" in page and "default-src 'none'" in page
    assert page.count("<svg") == len(document.build(EXAMPLE).charts())
    ids = re.findall(r'id="([^"]+)"', page)
    assert len(ids) == len(set(ids)), "two inline charts share an id"


HOSTILE = "<script>alert(1)</script> [x](javascript:alert(1)) ](javascript: & &amp; | `code` $a$ \x1b[2J\x07"


def test_hostile_names_and_notes_are_escaped(tmp_path):
    preset = tmp_path / "hostile.toml"
    import tomli_w

    preset.write_text(
        tomli_w.dumps(
            {
                "calculator": "motor",
                "name": HOSTILE,
                "description": "# heading\n- list " + HOSTILE,
                "format": 1,
                "inputs": {},
            }
        ),
        encoding="utf-8",
    )
    book = tmp_path / "hostile_book.toml"
    book.write_text(
        tomli_w.dumps(
            {
                "format": 1,
                "name": HOSTILE,
                "description": HOSTILE,
                "variables": {"label_text": HOSTILE, "mass": "2 lb"},
                "cards": {"drive_motor": {"calculator": "motor", "inputs": {}}},
                "requirements": [
                    {"name": HOSTILE, "note": HOSTILE, "check": "drive_motor.free_speed > 1 rpm"}
                ],
            }
        ),
        encoding="utf-8",
    )
    for path in (preset, book):
        report = document.build(str(path))
        page = html.write(report)
        body = page.split("<style>")[0] + page.split("</style>")[1]
        assert "<script>" not in body and "\x1b" not in page and "\x07" not in page
        assert "&lt;script&gt;alert(1)&lt;/script&gt;" in page
        assert 'href="javascript' not in page
        assert "\\x1b[2J\\x07" in page  # the control characters shown, not sent
        md = markdown.write(report, "hostile")
        assert "<script>" not in md and "\x1b" not in md and "\x07" not in md
        assert not re.search(r"(?<!\\)\]\(", md.replace("](hostile_charts/", "")), "a link made of a name"
        assert "[x](" not in md
        assert "\\<script\\>" in md and "\\&amp;" in md
        if path == preset:  # the description's own '# heading' and '- list' stay text
            assert "\n\\# heading \\- list" in md or "\n\\# heading - list" in md


def _stderr_of(capsys, *argv: str) -> tuple[int, str]:
    capsys.readouterr()
    code = main(list(argv))
    return code, capsys.readouterr().err


def test_a_bad_file_exits_2_with_the_message_the_other_commands_give(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("garbage [\n", encoding="utf-8")
    code, err = _stderr_of(capsys, "report", str(bad))
    assert code == 2
    assert err == _stderr_of(capsys, "solve", "motor", "--preset", str(bad))[1]
    cycle = tmp_path / "cycle.toml"
    cycle.write_text('format = 1\n[variables]\na = "= b"\nb = "= a"\n', encoding="utf-8")
    code, err = _stderr_of(capsys, "report", str(cycle))
    assert code == 2 and "cycle" in err
    assert err == _stderr_of(capsys, "check", str(cycle))[1]
    code, err = _stderr_of(capsys, "report", str(tmp_path / "missing.toml"))
    assert code == 2 and err == _stderr_of(capsys, "share", str(tmp_path / "missing.toml"))[1]
    code, err = _stderr_of(capsys, "report", "builtin:no_such_thing")
    assert code == 2 and err.count("\n") == 1
    assert not list(tmp_path.glob("*.html"))


def test_the_cli_writes_html_md_and_never_over_a_file(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["report", "builtin:elevator/two_neo"]) == 0
    assert (tmp_path / "two_neo.html").read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    code, err = _stderr_of(capsys, "report", "builtin:elevator/two_neo")
    assert code == 2 and "exists" in err
    assert main(["report", "builtin:elevator/two_neo", "--overwrite"]) == 0
    assert main(["report", "builtin:elevator/two_neo", "--out", "lift.md"]) == 0
    md = (tmp_path / "lift.md").read_text(encoding="utf-8")
    svgs = sorted((tmp_path / "lift_charts").glob("*.svg"))
    assert svgs and all(f"(lift_charts/{p.name})" in md for p in svgs)


def test_pdf_without_chromium_says_so(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("GEARHEAD_CHROMIUM", str(tmp_path / "no-chromium"))
    code, err = _stderr_of(capsys, "report", "builtin:elevator/two_neo", "--out", str(tmp_path / "x.pdf"))
    assert code == 69 and "Chromium" in err and err.count("\n") == 1
    assert not (tmp_path / "x.pdf").exists()


def test_importing_the_cli_and_the_app_never_loads_matplotlib():
    code = (
        "import sys\n"
        "import gearhead.tui.cli, gearhead.tui.app, gearhead.tui.report_cli\n"
        "from gearhead.core.report import document\n"
        "document.build('builtin:elevator/two_neo')\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    assert out.stdout.strip() == "[]"


def test_the_readme_shows_page_1_of_the_examples_report():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "## The design report" in readme
    picture = re.search(r"!\[[^\]]*\]\((docs/report_page1\.png)\)", readme)
    assert picture, "the README's section shows the picture"
    data = (ROOT / picture.group(1)).read_bytes()
    assert data.startswith(b"\x89PNG\r\n\x1a\n")
    width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
    assert (width, height) == (816, 1056)  # one Letter page at 96 px per inch


def test_a_tolerance_is_shown_as_entered_with_each_results_spread(tmp_path, capsys):
    preset = tmp_path / "tol.toml"
    preset.write_text(
        'calculator = "gear_ratio"\nname = "tol"\nformat = 1\n[inputs]\nload = "150 lbf ± 10 %"\n',
        encoding="utf-8",
    )
    data = cli_json(capsys, "solve", "gear_ratio", "--preset", str(preset), "--json")
    page = html.write(document.build(str(preset)))
    assert _value_cell("150 lbf ± 10 %") in page
    assert "<th>Spread</th>" in page
    from gearhead.core import solving, tolerance

    solved = solving.solve(get("gear_ratio"), {"load": "150 lbf ± 10 %"})
    for name, value in data["outputs"].items():
        s = solved.spread.outputs.get(name)
        if s is not None and name not in VOLATILE:
            spread = tolerance.spread_text(get("gear_ratio"), solved.solution, s)
            assert f"{_value_cell(value['text'])}<td>{html.esc(spread)}</td>" in page, name


def test_a_card_that_cannot_be_solved_shows_its_entries_and_why(tmp_path):
    book = tmp_path / "fails.toml"
    book.write_text(
        'format = 1\nname = "fails"\n[cards.lift]\ncalculator = "elevator"\n'
        'inputs = { load_mass = "500 lb", motor_count = 1 }\n'
        '[[requirements]]\nname = "fast"\ncheck = "lift.time_to_goal < 1 s"\n',
        encoding="utf-8",
    )
    page = html.write(document.build(str(book)))
    lift = _card_html(page, "lift")
    assert '<p class="fails">Not solved: ratio: is too low' in lift
    assert _value_cell("500 lb") in lift
    assert '<span class="unknown">not evaluated</span>' in page


def test_the_worst_case_is_the_one_check_finds(capsys):
    data = cli_json(capsys, "check", EXAMPLE, "--worst-case", "--json")
    report = document.build(EXAMPLE, worst_case=True)
    page = html.write(report)
    assert "<th>Worst case</th>" in page
    for line in report.requirements:
        assert line.worst.startswith("margin "), line
    from gearhead.core import workbook

    calc = workbook.as_calculator(workbook.load(EXAMPLE))
    for key, r in data["worst_case"]["requirements"].items():
        o = calc.output(key)
        shown = units.format_quantity(r["worst_margin"], o.unit, o.quantity)
        assert html.esc(f"margin {shown} (") in page, key
    assert "Worst case: tolerances: 125 lb ± 5 lb, 0.02 ohm ± 0.005 ohm; 13 solves" in page


def test_the_match_has_its_state_of_charge_and_stacked_current_per_card(capsys):
    """The match's state of charge (and the charge available at the rates drawn) and the battery
    current stacked by card over the match, from core.match.series as the app's Match card draws
    them: the state of charge ends at `gearhead match`'s end_charge, and each stacked column is the
    battery current at the sample it shows (S1: base load + each card's moves)."""
    from gearhead.core import workbook
    from gearhead.core.match.series import peak_bins, series

    matched = cli_json(capsys, "match", EXAMPLE, "--json")
    wb = workbook.load(EXAMPLE)
    m = workbook.solve(wb).match
    s = series(m)
    report = document.from_workbook(wb)
    charts = {c.key: c for c in report.match.charts}
    soc = charts["match-state-of-charge"]
    assert [x.label for x in soc.series] == ["state of charge", "charge available at the rates drawn"]
    end = matched["outputs"]["end_charge"]["value"]
    assert soc.series[0].y[-1] == pytest.approx(end, abs=1e-9) and soc.series[0].x[-1] == s.t[-1]
    assert soc.series[1].y[-1] == pytest.approx(matched["outputs"]["end_available"]["value"], abs=1e-9)
    assert min(soc.series[0].y) == pytest.approx(100 * min(s.soc))  # the envelope keeps the extremes
    stacked = charts["match-current-by-card"]
    assert stacked.stacked
    assert [x.label for x in stacked.series] == ["base load", *s.by_card]
    bins = peak_bins(s, document.STACK_BINS)
    assert stacked.series[0].x == [x for x, _ in bins]
    for k, (_, i) in enumerate(bins):  # each column: the sample of the bin's highest battery current
        total = sum(layer.y[k] for layer in stacked.series)
        assert total == pytest.approx(s.battery_current[i], rel=1e-6, abs=1e-6), k
    top = max(sum(layer.y[k] for layer in stacked.series) for k in range(len(bins)))
    assert top == pytest.approx(max(s.battery_current), rel=1e-6)  # the match's peak is never averaged away
    page = html.write(report)
    for i in range(len(stacked.series)):
        assert f'id="match-current-by-card-s{i}"' in page
    assert 'id="match-state-of-charge-s1"' in page
    md_files = markdown.chart_files(report, "x")
    assert (
        "x_charts/match-current-by-card.svg" in md_files and "x_charts/match-state-of-charge.svg" in md_files
    )


def test_charts_drawn_from_several_threads_are_the_same_bytes():
    """The app builds a report in a thread worker: charts drawn at once from several threads (one
    Figure is reused, rcParams are set while drawing) are the bytes drawn one after another."""
    import threading

    from gearhead.core.report import charts

    cs = document.build("builtin:elevator/two_neo").charts()
    alone = [charts.svg(c) for c in cs]
    results: list[list[str]] = []

    def draw() -> None:
        results.append([charts.svg(c) for c in cs * 2])

    threads = [threading.Thread(target=draw) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(results) == 4 and all(r == alone * 2 for r in results)
