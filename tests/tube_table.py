"""The common rectangular tubes whose torsion-constant bounds core/beams.py ships (TUBE_TABLE).

    python -m tests.tube_table      # print TUBE_REFERENCE (this machine's _spectral_reference) and
                                    # TUBE_TABLE's rows (beams._tube_torsion_bounds, from TUBE_REFERENCE)

J = t⁴·f(W/t, H/t): one row per side/wall ratio pair, so a 2×2×1/8 in tube shares the 1×1×1/16
in row. Both orientations are listed (height × width and width × height: the two solves differ by
rounding). tests/test_beam_table.py recomputes every row and checks every tube below hits one.
"""

from __future__ import annotations

MM = 1 / 25.4  # in

# (name, height, width, wall), inches
TUBES = (
    ("1 x 1 x 1/16 in", 1.0, 1.0, 1 / 16),
    ("1 x 1 x 1/8 in", 1.0, 1.0, 1 / 8),
    ("2 x 1 x 1/16 in", 2.0, 1.0, 1 / 16),  # the calculator's default and the 1x2 frame rail preset
    ("2 x 1 x 1/8 in", 2.0, 1.0, 1 / 8),
    ("2 x 2 x 1/16 in", 2.0, 2.0, 1 / 16),
    ("2 x 2 x 1/8 in", 2.0, 2.0, 1 / 8),
    ("1/2 x 1/2 x 1/16 in", 0.5, 0.5, 1 / 16),
    ("3/4 x 3/4 x 1/16 in", 0.75, 0.75, 1 / 16),
    ("1.5 x 1.5 x 1/16 in", 1.5, 1.5, 1 / 16),
    ("1.5 x 1.5 x 1/8 in", 1.5, 1.5, 1 / 8),
    ("3 x 1 x 1/8 in", 3.0, 1.0, 1 / 8),
    ("1 x 1 x 0.040 in", 1.0, 1.0, 0.040),
    ("2 x 1 x 0.040 in", 2.0, 1.0, 0.040),
    ("1 x 1/2 x 0.046 in", 1.0, 0.5, 0.046),  # a VEX C-channel's outline as a closed box
    ("1 x 1/2 x 0.063 in", 1.0, 0.5, 0.063),  # the same, a thicker wall
    ("1 x 1/2 x 1/16 in", 1.0, 0.5, 1 / 16),
    ("20 x 20 x 1.5 mm", 20 * MM, 20 * MM, 1.5 * MM),
    ("20 x 20 x 2 mm", 20 * MM, 20 * MM, 2 * MM),
    ("25 x 25 x 1.5 mm", 25 * MM, 25 * MM, 1.5 * MM),
    ("25 x 25 x 2 mm", 25 * MM, 25 * MM, 2 * MM),
    ("30 x 30 x 2 mm", 30 * MM, 30 * MM, 2 * MM),
    ("40 x 20 x 2 mm", 40 * MM, 20 * MM, 2 * MM),
    ("40 x 40 x 2 mm", 40 * MM, 40 * MM, 2 * MM),
)


def ratios() -> dict[tuple[float, float], str]:
    """{(W/t, H/t): the tubes it serves}, both orientations, one key per ratio pair (to 1e-12)."""
    out: dict[tuple[float, float], str] = {}
    for name, x, y, t in TUBES:
        for W, H in ((x / t, y / t), (y / t, x / t)):
            W, H = _exact(W), _exact(H)
            same = [k for k in out if abs(k[0] - W) <= 1e-12 * W and abs(k[1] - H) <= 1e-12 * H]
            if same:
                if name not in out[same[0]]:
                    out[same[0]] += f"; {name}"
            else:
                out[(W, H)] = name
    return out


def _exact(r: float) -> float:
    """A ratio that is a whole number or a half (32, 12.5) to rounding, as that number."""
    return round(r * 2) / 2 if abs(r * 2 - round(r * 2)) < 1e-9 else r


def rows() -> list[tuple[float, float, float, float, str]]:
    from gearhead.core import beams

    return [(W, H, *beams._tube_torsion_bounds(W, H), name) for (W, H), name in sorted(ratios().items())]


def reference_text() -> str:
    """beams._spectral_reference(TUBE_DEGREE) as TUBE_REFERENCE's text: labelled, 4 numbers a line."""
    from gearhead.core import beams

    out = []
    names = ("nodes", "stiffness", "mass", "weights", "moments")
    for name, values in zip(names, beams._spectral_reference.__wrapped__(beams.TUBE_DEGREE)):
        numbers = [repr(float(v)) for v in values.ravel()]
        out.append(f"{name}:")
        out += [" ".join(numbers[i : i + 4]) for i in range(0, len(numbers), 4)]
    return "\n".join(out)


if __name__ == "__main__":
    print(f'TUBE_REFERENCE = """\n{reference_text()}\n"""\n')
    for W, H, lower, upper, name in rows():
        print(f"    ({W!r}, {H!r}, {lower!r}, {upper!r}),  # {name}")
