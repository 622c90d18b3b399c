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
Written back (fitted_raw): elevator, arm as (E2); a flywheel's wheel inertia entered as a moment of
inertia, J = kA·f less the rotors' and a secondary wheel's, over the wheels (no friction entry:
shown, not written)                                                                              (E5)
a sprint's robot mass m = kA·f and rolling resistance C_rr = (kS − R·i_f)/(g·kA) at the card's
efficiency, so the card's (S9) gives the fitted kA and kS back                                  (E6)
a fitted value the card's field refuses is not written, with a note                              (E7)
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


def _a(word: str) -> str:
    """'a gear_ratio', 'an arm'."""
    return ("an " if word[:1] in "aeiou" else "a ") + word


def load_card(
    kind: str, preset: str | None = None, workbook: str | None = None, name: str | None = None
) -> Card:
    """The card's values (its defaults, a preset, or a workbook's card) and its model's figures."""
    from .. import registry
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
                "--name", f"{name!r} is {_a(wb.cards[name].calculator)} card, not {kind}", workbook
            )
        result = wbmod.solve(wb).cards[name]
        if result.error is not None and not result.entries:
            raise InputError("--name", f"card {name!r} could not be read: {result.error}", workbook)
        raw, label = result.entries, f"{workbook}: {name}"
    elif preset is not None:
        from .. import share

        if not preset.strip():  # `--preset ""` (an unset shell variable)
            raise InputError("--preset", "is empty; give a preset file")
        p = share.load_any(preset)  # as every --preset: a file, builtin:CALC/NAME, a share code
        if p.calculator != kind:
            raise InputError("--preset", f"is {_a(p.calculator)} preset, not {kind}", preset)
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


# the move the card solves, per card: its outputs shown with the design's and the fitted entries
MOVE_OUTPUTS = {
    "elevator": ("time_to_goal", "peak_stator_current", "max_speed"),
    "arm": ("time_to_goal", "peak_stator_current", "max_speed"),
    "flywheel": ("spin_up_time", "recovery_time", "slowest_ball_speed", "peak_stator_current"),
    "sprint": ("time_to_distance", "speed_at_distance", "top_speed", "peak_stator_current"),
}
# a fitted entry the card refuses (out of its field's range) is not written, nor what goes with it
TOGETHER = {
    "friction_force": ("effects",),
    "friction_torque": ("effects",),
    "rolling_coefficient": ("effects",),
    "moment_of_inertia": ("inertia_model",),
    "wheel_inertia": ("mode", "secondary_inertia"),
}


def fitted_raw(card: Card, gains: dict[str, float], held=()) -> tuple[dict, list[str]]:
    """The card's entries with the fitted ones in, and notes saying what was chosen (E5)-(E7):
    elevator: the moving mass from kA (its one mass serves gravity too, so its kG follows from it)
    and the friction force from kS; arm: the entered inertia from kA, the mass from kG, the
    friction torque from kS (E2); flywheel (E5); sprint (E6). A fitted value the card's field
    refuses (out of its range) is left as the card has it, with a note (E7)."""
    raw, notes = dict(card.raw), []
    f = card.f
    friction = gains["kS"] * f - card.loss
    if card.kind == "flywheel":
        _flywheel(card, gains, raw, notes, friction)
    elif card.kind == "sprint":
        _sprint(card, gains, raw, notes, friction, held)
    else:
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
    return _valid(card, raw, notes), notes


def _flywheel(card: Card, gains: dict[str, float], raw: dict, notes: list[str], friction: float) -> None:
    """(E5) The flywheel's kA = R·J/k (VL2), J = n_w·I_w + N·J_r·G² + G₂₁²·n₂·I₂ (the wheels, the
    motors' rotors and a secondary wheel, shooter (4), (D1)), so J = kA·f gives one wheel's
        I_w = (kA·f − N·J_r·G² − G₂₁²·n₂·I₂)/n_w
    written as an entered moment of inertia (mode = moment_of_inertia: mass and radius of
    gyration cannot both come from one number); a secondary wheel given by its mass and radius of
    gyration is entered as its moment of inertia m₂·(k₂·r₂)², unchanged, since the mode covers
    both. The card holds no friction torque (its kS is the motors' own R·i_f; loss_fraction is the
    shot's): the friction the fit gives is shown, not written, and kV is n/Kv (E3)."""
    from ..sim.shooter import SECONDARY, rotor_reflected, secondary_reflected

    v = card.values
    J = gains["kA"] * card.f
    others = rotor_reflected(v) + secondary_reflected(v)
    each = (J - others) / v["wheel_count"]
    if not (math.isfinite(each) and each > 0):
        notes.append(
            f"the fitted inertia {J:.4g} kg·m² is not above the rotors' and secondary wheels' "
            f"{others:.4g} kg·m²: the wheel inertia is not written"
        )
    else:
        if v["mode"] != "moment_of_inertia":
            raw["mode"] = "moment_of_inertia"
            if v["shooter"] in SECONDARY:
                I2 = (
                    v["secondary_mass"]
                    * (v["secondary_gyration_fraction"] * v["secondary_diameter"] / 2) ** 2
                )
                raw["secondary_inertia"] = f"{I2!r} kg*m**2"
            notes.append(
                "wheel inertia now entered as a moment of inertia (was: mass and radius of gyration): "
                f"the fitted {J:.4g} kg·m² at the wheel"
                + (f", less the rotors' and secondary wheels' {others:.4g}," if others > 0 else "")
                + f" over {v['wheel_count']} wheel{'s' if v['wheel_count'] > 1 else ''}"
            )
        raw["wheel_inertia"] = f"{each!r} kg*m**2"
    if friction > 0:
        notes.append(
            f"the flywheel card holds no friction torque: the fitted {friction:.4g} N·m beyond the "
            "motors' own loss is not written (the card's kS stays R·i_f)"
        )


def _sprint(
    card: Card, gains: dict[str, float], raw: dict, notes: list[str], friction: float, held=()
) -> None:
    """(E6) The sprint card's kA = m·R/(η·N·Kt·n) = m/f, kS = R·i_f + C_rr·m·g/f, kV = n/Kv (S9).
    With the card's efficiency kept (E2: m and η enter kA only as m/η), the card reproduces the
    fitted kA and kS with
        m = kA·f,   C_rr = (kS·f − R·i_f·f)/(m·g) = (kS − R·i_f)/(g·kA)
    (C_rr does not depend on η: kS and kA scale alike), the rolling_resistance effect on; below
    the motors' own loss it is turned off. The fitted mass holds the wheels' and motors' rotating
    inertia then follow that mass. A mass `held` (a workbook links it: not written) keeps the
    card's m, and C_rr = (kS·f − R·i_f·f)/(m·g) at that m, so the card still gives the fitted kS."""
    v = card.values
    m = gains["kA"] * card.f
    if "robot_mass" in held:
        m = v["robot_mass"]
        notes.append(
            f"the robot mass is held at the card's {m:.4g} kg: rolling resistance taken at it, so the "
            "card keeps the fitted kS (its kA stays the card's)"
        )
    else:
        raw["robot_mass"] = f"{m!r} kg"
    effects = {e for e in v["effects"] if e != "rolling_resistance"}
    if friction > 0:
        effects.add("rolling_resistance")
        c_rr = friction / (G0 * m)
        raw["rolling_coefficient"] = repr(c_rr)
    else:
        notes.append(
            f"fitted kS is below the motors' own loss: rolling resistance turned off ({friction:.3g} N)"
        )
    raw["effects"] = ", ".join(sorted(effects))
    notes.append(
        f"efficiency kept at {v['efficiency']:.4g}: the robot mass is kA's at it (mass and efficiency "
        "enter kA only as mass/efficiency), rotating parts included; the efficiency that would explain "
        "kA at the card's mass is in the table"
    )


def _valid(card: Card, raw: dict, notes: list[str]) -> dict:
    """(E7) The card's own reading of the fitted entries: a written field it refuses goes back to
    the card's entry (with what goes with it, TOGETHER), named in a note."""
    from .. import registry
    from ..model import parse_inputs

    calc = registry.get(card.kind)
    for _ in range(len(raw) + 1):
        try:
            parse_inputs(calc, raw)
            return raw
        except InputError as exc:
            bad = [e for e in exc.errors if raw.get(e.field) != card.raw.get(e.field)]
            if not bad:
                raise
            for e in bad:
                notes.append(
                    f"{e.field}: the fitted {raw.get(e.field)} is refused by the card ({e.message}): not written"
                )
                for k in (e.field, *TOGETHER.get(e.field, ())):
                    if k in card.raw:
                        raw[k] = card.raw[k]
                    else:
                        raw.pop(k, None)
    return raw


def moves(card: Card, gains: dict[str, float]) -> tuple[dict, list[str]]:
    """The move the card solves, with its entries and with the fitted ones: {"design": {output:
    value}, "fitted": {...}} (SI), and notes (a solve that fails says why)."""
    from ..model import solve

    raw, notes = fitted_raw(card, gains)
    out = {}
    for label, entries_ in (("design", card.raw), ("fitted", raw)):
        try:
            sol = solve(card.kind, entries_)
        except InputError as exc:
            notes.append(
                f"the card's move with the {label} entries cannot be solved: {exc.field}: {exc.message}"
            )
            continue
        out[label] = {k: sol.outputs[k].value for k in MOVE_OUTPUTS[card.kind] if k in sol.outputs}
    return out, notes
