"""From fitted gains to the card's entries (issue 44 item 4), in Gearhead's model (core.sim.motion
(M1)-(M4); elevator (EL10), arm (AR9), flywheel (VL2)). With f = η·N·Kt·n/R the force (torque) per
volt at stall, the card's model gives V = kS·sgn q̇ + kG(q) + kV·q̇ + kA·q̈ with
    kA = M/f,  kV = n/Kv,  kS = R·i_f + F_f/f,  kG = m·g·cos(incline)/f (elevator),
    kG = (m·g·L − τ_cb)/f at horizontal (arm)                                                 (E1)
so, from the fitted gains (the card's motor, count, ratio, geometry and efficiency held):
    M = kA·f  (moving mass, kg, or inertia about the pivot or the wheel, kg·m²)
    F_f = kS·f − R·i_f·(η·N·Kt·n)  (friction beyond the motors' own loss, N or N·m)
    elevator: m_g = kG·f/(g·cos incline) + F_cb/(g·cos incline)  (the mass gravity sees)
    arm: m = (kG·f + τ_cb)/(g·L)  (the arm's mass at the card's centre of mass L)               (E2)
Mass and efficiency enter kA and kG only as M/η: they cannot be told apart from a SysId log. The
card's efficiency is kept; the efficiency that would explain kA at the card's mass is shown beside
it, η·kA_card/kA_fit. Gearhead's kV is n/Kv whatever η: a fitted kV above it is a loss the model
does not hold (viscous drag, a wrong ratio or motor): its ratio kV_fit/(n/Kv) is shown         (E3)
Each entry's standard deviation is its gain's (the fit's covariance) times the same factor      (E4)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..constants import G0
from ..errors import InputError


@dataclass
class Card:
    kind: str
    values: dict
    label: str
    design: dict[str, float]  # the card's own kS, kV, kA, kG (E1)
    f: float  # force (torque) per volt at stall
    loss: float  # the motors' own loss force R·i_f·f (N or N·m)
    n_over_kv: float
    raw: dict = field(default_factory=dict)  # the card's entries as written (a preset's, a workbook card's)
    notes: list[str] = field(default_factory=list)


def load_card(
    kind: str, preset: str | None = None, workbook: str | None = None, name: str | None = None
) -> Card:
    """The card's values (its defaults, a preset, or a workbook's card) and its model's figures."""
    from .. import presets, registry
    from ..model import parse_inputs

    calc = registry.get(kind)
    if workbook is not None:
        from .. import workbook as wbmod

        wb = wbmod.load(workbook)
        if not name:
            cards = [c for c, card in wb.cards.items() if card.calculator == kind]
            if len(cards) != 1:
                raise InputError(
                    "--name", f"give the card ({kind} cards: {', '.join(cards) or 'none'})", workbook
                )
            name = cards[0]
        if name not in wb.cards:
            raise InputError("--name", f"no card {name!r} in the workbook", workbook)
        if wb.cards[name].calculator != kind:
            raise InputError(
                "--name", f"{name!r} is a {wb.cards[name].calculator} card, not {kind}", workbook
            )
        result = wbmod.solve(wb).cards[name]
        if result.error is not None and not result.entries:
            raise InputError("--name", f"card {name!r} could not be read: {result.error}", workbook)
        raw, label = result.entries, f"{workbook}: {name}"
    elif preset is not None:
        p = presets.load(preset)
        if p.calculator != kind:
            raise InputError("--preset", f"is a {p.calculator} preset, not {kind}", preset)
        raw, label = p.inputs, f"{preset}"
    else:
        raw, label = {}, f"the {kind} card's defaults"
    values, _ = parse_inputs(calc, raw)
    card = _model(kind, values, label)
    card.raw = dict(raw)
    return card


def card_from_entries(kind: str, raw: dict, label: str) -> Card:
    """The card of these entries as written (the app's card on screen), as load_card gives a file's."""
    from .. import registry
    from ..model import parse_inputs

    values, _ = parse_inputs(registry.get(kind), raw)
    card = _model(kind, values, label)
    card.raw = dict(raw)
    return card


def _model(kind: str, v: dict, label: str) -> Card:
    from ..sim import motion

    if kind in ("elevator", "arm"):
        from ..calculators import arm, elevator

        mod = elevator if kind == "elevator" else arm
        s = mod.setup(v)
        m = s.mech
        ff = motion.feedforward(s, 0.0 if kind == "arm" else m.q1)
        f = m.force_per_volt
        return Card(kind, v, label, ff, f, m.loss_force, m.n / m.Kv)
    if kind == "sprint":  # (S9): kA = m/f, kV = n/Kv, kS = R·i_f + F_rr/f, f = η·N·Kt·n/R
        from ..calculators import sprint

        s = sprint.setup(v)
        dr = s.drive
        f = dr.force_per_amp / dr.R
        F_rr = s.resist()(0.0)  # the rolling resistance, as the card's kS holds it
        ff = {"kS": dr.R * dr.free_current + F_rr / f, "kV": dr.n / dr.Kv, "kA": dr.mass / f}
        return Card(kind, v, label, ff, f, dr.R * dr.free_current * f, dr.n / dr.Kv)
    from ..calculators.flywheel import loop_wheel
    from ..sim import shooter, velocity_loop

    sc, _ = shooter.scene_from(v)
    w = loop_wheel(sc, v)
    ff = velocity_loop.feedforward_gains(w)
    f = w.k / w.R
    return Card(kind, v, label, ff, f, w.R * w.i_f * f, w.G / w.Kv)


def design_inertia(card: Card) -> float:
    return card.design["kA"] * card.f


def entries(
    card: Card, gains: dict[str, float], sigma: dict[str, float]
) -> list[tuple[str, float, float, float, str]]:
    """(E2)-(E4): rows of (what, card's value, fitted value, its standard deviation, unit)."""
    v, f = card.values, card.f
    rows = []
    linear = card.kind in ("elevator", "sprint")
    M_unit = "kg" if linear else "kg·m²"
    rows.append(
        (
            "moving mass" if linear else "inertia",
            design_inertia(card),
            gains["kA"] * f,
            sigma["kA"] * f,
            M_unit,
        )
    )
    design_fric = card.design["kS"] * f - card.loss
    rows.append(
        (
            "friction",
            design_fric,
            gains["kS"] * f - card.loss,
            sigma["kS"] * f,
            "N" if linear else "N·m",
        )
    )
    if card.kind == "elevator" and "kG" in gains:
        c = math.cos(v["incline"])
        if abs(c) > 1e-9:
            fcb = v["counterbalance_force"] if "counterbalance" in v["effects"] else 0.0
            rows.append(
                (
                    "mass (gravity)",
                    v["load_mass"],
                    (gains["kG"] * f + fcb) / (G0 * c),
                    sigma["kG"] * f / (G0 * abs(c)),
                    "kg",
                )
            )
    if card.kind == "arm" and "kG" in gains:
        tcb = v["counterbalance_torque"] if "counterbalance" in v["effects"] else 0.0
        L = v["com_distance"]
        rows.append(
            (
                "arm mass (gravity)",
                v["arm_mass"],
                (gains["kG"] * f + tcb) / (G0 * L),
                sigma["kG"] * f / (G0 * L),
                "kg",
            )
        )
        rows.append(
            ("angle offset", 0.0, math.degrees(gains["offset"]), math.degrees(sigma["offset"]), "deg")
        )
    eta = v["efficiency"]
    ka = gains["kA"]
    rows.append(
        (
            "efficiency at the card's mass",
            eta,
            eta * card.design["kA"] / ka,
            eta * card.design["kA"] * sigma["kA"] / ka**2,
            "",
        )
    )
    rows.append(("kV / (n/Kv)", 1.0, gains["kV"] / card.n_over_kv, sigma["kV"] / card.n_over_kv, ""))
    return rows


MOVE_OUTPUTS = ("time_to_goal", "peak_stator_current", "max_speed")


def fitted_raw(card: Card, gains: dict[str, float]) -> tuple[dict, list[str]] | None:
    """The card's entries with the fitted ones in (elevator, arm; None for a flywheel, whose inertia
    is entered several ways): the moving mass from kA (an elevator's one mass serves gravity too, so
    its kG follows from it), an arm's entered inertia from kA and mass from kG, friction from kS (E2)."""
    if card.kind not in ("elevator", "arm"):
        return None
    raw, notes = dict(card.raw), []
    f = card.f
    friction = gains["kS"] * f - card.loss
    effects = {e for e in card.values["effects"] if e != "friction"}
    name = "friction_force" if card.kind == "elevator" else "friction_torque"
    if friction > 0:
        effects.add("friction")
        raw[name] = f"{friction!r} {'N' if card.kind == 'elevator' else 'N*m'}"
    else:
        notes.append(f"fitted kS is below the motors' own loss: no friction added ({friction:.3g})")
    raw["effects"] = ", ".join(sorted(effects))
    if card.kind == "elevator":
        raw["load_mass"] = f"{gains['kA'] * f!r} kg"
    else:
        tcb = card.values["counterbalance_torque"] if "counterbalance" in card.values["effects"] else 0.0
        m = (gains["kG"] * f + tcb) / (G0 * card.values["com_distance"])
        raw["arm_mass"] = f"{m!r} kg"
        raw["inertia_model"] = "entered"
        raw["moment_of_inertia"] = f"{gains['kA'] * f!r} kg*m**2"
    return raw, notes


def moves(card: Card, gains: dict[str, float]) -> tuple[dict, list[str]]:
    """The move the card solves, with its entries and with the fitted ones: {"design": {output:
    value}, "fitted": {...}} (SI), and notes (a solve that fails says why)."""
    from ..model import solve

    got = fitted_raw(card, gains)
    if got is None:
        return {}, []
    raw, notes = got
    out = {}
    for label, entries_ in (("design", card.raw), ("fitted", raw)):
        try:
            sol = solve(card.kind, entries_)
        except InputError as exc:
            notes.append(
                f"the card's move with the {label} entries cannot be solved: {exc.field}: {exc.message}"
            )
            continue
        out[label] = {k: sol.outputs[k].value for k in MOVE_OUTPUTS if k in sol.outputs}
    return out, notes
