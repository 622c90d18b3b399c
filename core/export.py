"""Results to take away: the results table as CSV or Markdown, a plot's data as CSV, a tab as
preset TOML. Pure text builders; the app and the CLI decide where the text goes."""

from __future__ import annotations

import csv
import io

from . import units
from .model import Calculator, HeatMap, Plot, Solution


def _rows(calc: Calculator, solution: Solution) -> list[tuple[str, str, str, str, str, str]]:
    """(name, label, shown value, value in SI, SI unit, equation number) for each output, in
    table order."""
    rows = []
    for name, value in solution.outputs.items():
        out = calc.output(name)
        rows.append(
            (
                name,
                out.label,
                value.text,
                repr(value.value) if isinstance(value.value, float) else str(value.value),
                value.unit,
                out.equation,
            )
        )
    return rows


def results_csv(calc: Calculator, solution: Solution) -> str:
    """One row per output: the shown text and the full-precision SI value, for a spreadsheet, and
    the seed's equation number it comes from."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["output", "label", "shown", "value_si", "unit_si", "equation"])
    writer.writerows(_rows(calc, solution))
    return out.getvalue()


def _md_cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def results_markdown(calc: Calculator, solution: Solution) -> str:
    """The results table as shown, with the warnings under it (for a wiki or a design review)."""
    lines = [f"**{_md_cell(calc.title)}**", "", "| Result | Value | Eq. |", "|---|---|---|"]
    lines += [
        f"| {_md_cell(label)} | {_md_cell(shown)} | {_md_cell(equation)} |"
        for _, label, shown, _, _, equation in _rows(calc, solution)
    ]
    if solution.warnings:
        lines.append("")
        lines += [f"- {_md_cell(w)}" for w in solution.warnings]
    for table in calc.tables:  # e.g. the ratio finder's combinations and their part numbers
        columns = [c for c in table.columns if not c.hidden]
        lines += [
            "",
            f"**{_md_cell(table.title)}**",
            "",
            "| "
            + " | ".join(_md_cell(f"{c.label} [{c.unit}]" if c.unit else c.label) for c in columns)
            + " |",
            "|" + "---|" * len(columns),
        ]
        lines += [
            "| " + " | ".join(_md_cell(row[c.name].text) if c.name in row else "" for c in columns) + " |"
            for row in solution.tables.get(table.name, [])
        ]
    return "\n".join(lines) + "\n"


def plot_csv(plot: Plot, solution: Solution) -> str:
    """A plot's series in its display units, one (series, x, y) row per point."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    x_head = f"{plot.x_label} [{plot.x_unit}]" if plot.x_unit else plot.x_label
    y_head = f"{plot.y_label} [{plot.y_unit}]" if plot.y_unit else plot.y_label
    writer.writerow(["series", x_head, y_head])
    fx = units.factor(plot.x_unit, plot.x_quantity)
    fy = units.factor(plot.y_unit, plot.y_quantity)
    for name in plot.series:
        xs, ys = solution.series.get(name, ([], []))
        label = solution.series_label(name)
        writer.writerows((label, repr(x / fx), repr(y / fy)) for x, y in zip(xs, ys))
    return out.getvalue()


def heat_map_csv(plot: HeatMap, solution: Solution) -> str:
    """A heat map's cells in its display units, one (x, y, z, note, pick) row per cell."""
    data = solution.heat_maps[plot.name]
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    heads = [
        f"{label} [{unit}]" if unit else label
        for label, unit in (
            (plot.x_label, plot.x_unit),
            (plot.y_label, plot.y_unit),
            (plot.z_label, plot.z_unit),
        )
    ]
    writer.writerow(heads + ["note", "pick"])
    fx = units.factor(plot.x_unit, plot.x_quantity)
    fy = units.factor(plot.y_unit, plot.y_quantity)
    fz = units.factor(plot.z_unit, plot.z_quantity)
    for j, y in enumerate(data.y):
        for i, x in enumerate(data.x):
            z = data.z[j][i]
            note = data.notes[j][i] if j < len(data.notes) and i < len(data.notes[j]) else ""
            writer.writerow(
                [
                    repr(x / fx),
                    repr(y / fy),
                    "" if z is None else repr(z / fz),
                    note,
                    "1" if data.pick == (j, i) else "",
                ]
            )
    return out.getvalue()


def preset_toml(calc_id: str, inputs: dict, name: str = "", description: str = "") -> str:
    """The preset file for these inputs (DESIGN.md "Presets"), as text to share."""
    import tomli_w

    from .presets import Preset

    return tomli_w.dumps(Preset(calc_id, name or f"{calc_id} design", description, dict(inputs)).as_toml())
