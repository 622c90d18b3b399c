"""Time to read one entry (core.units.parse via Field.parse): everyday entries and hostile ones.

    .venv/bin/python bench/bench_parse.py

Before the bounded parser, 9**9**9 hung (a 370-million-digit integer), an 8 000-character entry
took 0.5-2 s and a 100 000-character one over a minute.
"""

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from gearhead.core.errors import InputError  # noqa: E402
from gearhead.core.model import Field  # noqa: E402
from gearhead.core.units import registry  # noqa: E402

FIELD = Field("load", "Load", "force", "lbf", default=25, min=0)
ENTRIES = [
    "25",
    "25 lbf",
    "110 N",
    "2*12.5 lbf",
    "(25)",
    "25 lbf + 3 N",
    "9**9**9",
    "2**9**9 lbf",
    "x" * 199,
    "(" * 100 + "1" + ")" * 100,
    "-" * 199 + "1",
    "1" + "*1" * 99,
    "9" * 8_000,
    "9" * 100_000,
    "６ ㎜",
    "3,5",
    "１２ lbf",
]


def main() -> None:
    registry()  # built once per process (~0.2 s); not part of any one entry
    print(f"{'entry':<34}{'result':<42}{'time per parse':>16}")
    for text in ENTRIES:
        runs, start = 0, time.perf_counter()
        while True:
            try:
                result = f"{FIELD.parse(text):.6g} N"
            except InputError as exc:
                result = exc.message
            runs += 1
            if time.perf_counter() - start > 0.2:
                break
        per = (time.perf_counter() - start) / runs
        shown = repr(text) if len(text) < 30 else f"{text[:12]!r}… ({len(text)} chars)"
        print(f"{shown:<34}{result[:40]:<42}{per * 1e6:>13.1f} µs")


if __name__ == "__main__":
    main()
