"""Golden file of every built-in preset's outputs: refactors must keep them (to 1e-12 relative).

    python -m tests.golden_outputs          # rewrite tests/golden/<calculator>.json

Regenerate only when an output is meant to change, and say why in the commit.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from gearhead.core import presets
from gearhead.core.model import solve
from gearhead.core.sim.scene import VOLATILE

GOLDEN_DIR = Path(__file__).with_name("golden")


def current() -> dict[str, dict[str, dict]]:
    """{calculator: {preset file name: {"outputs": {name: value}, "warnings": [...]}}}."""
    out: dict[str, dict[str, dict]] = {}
    for p in presets.listing():
        if not p.builtin:
            continue
        sol = solve(p.calculator, p.inputs)
        values = {k: v.value for k, v in sol.outputs.items() if k not in VOLATILE}
        record = {"outputs": values, "warnings": sol.warnings}
        if sol.tables:  # e.g. the ratio finder's combinations, cell by cell (SI values)
            record["tables"] = {
                name: [{k: v.value for k, v in row.items()} for row in rows]
                for name, rows in sol.tables.items()
            }
        out.setdefault(p.calculator, {})[p.path.name] = record
    return out


def write() -> None:
    GOLDEN_DIR.mkdir(exist_ok=True)
    for calc, table in sorted(current().items()):
        text = json.dumps(dict(sorted(table.items())), indent=1, sort_keys=True, ensure_ascii=False)
        (GOLDEN_DIR / f"{calc}.json").write_text(text + "\n", encoding="utf-8")


def stored() -> dict[str, dict[str, dict]]:
    return {p.stem: json.loads(p.read_text(encoding="utf-8")) for p in sorted(GOLDEN_DIR.glob("*.json"))}


if __name__ == "__main__":
    write()
    print(f"wrote {len(list(GOLDEN_DIR.glob('*.json')))} files to {GOLDEN_DIR}", file=sys.stderr)
