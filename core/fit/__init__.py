"""Fitting a card's model from the robot's own logs (issue 44): read a WPILog or an AdvantageScope
CSV (logs), find a SysId routine's signals (signals), fit kS, kV, kA, kG as SysId does (sysid_fit),
turn the gains into the card's entries (entries) and replay the logged voltage through the card's
model (replay)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..errors import InputError

KINDS = ("elevator", "arm", "flywheel", "sprint")  # the cards the app offers "Fit from log" on
CARDS = KINDS  # `gearhead fit --card` (sprint: a drivetrain, linear, no gravity)


@dataclass
class Report:
    """Everything `gearhead fit` shows: the signals, the two fits, the favoured one (favour()), the
    entries from it and the replays."""

    source: str
    kind: str
    card: object  # entries.Card
    picked: object  # signals.Picked
    info: dict
    fits: dict  # form -> sysid_fit.Fit
    favoured: str
    entries: list
    replays: dict  # "design" and each form -> replay.Replay
    notes: list = field(default_factory=list)
    moves: dict = field(default_factory=dict)  # "design"/"fitted" -> the card's move outputs (SI)
    dm: float = math.nan  # favour()'s Diebold-Mariano statistic, continuous against discrete

    def as_json(self) -> dict:
        def clean(x):
            return (
                x
                if isinstance(x, str) or (isinstance(x, float) and math.isfinite(x)) or isinstance(x, int)
                else None
            )

        return {
            "log": self.source,
            "card": self.kind,
            "card_source": self.card.label,
            "signals": self.picked.names,
            "units": self.picked.units,
            "samples": {s: len(r.t_voltage) for s, r in self.picked.runs.items()},
            "preparation": {k: clean(v) for k, v in self.info.items()},
            "fits": {
                form: {
                    "method": f.method,
                    "gains": {k: clean(v) for k, v in f.gains.items()},
                    "sigma": {k: clean(v) for k, v in f.sigma.items()},
                    "adjusted_r2": clean(f.adj_r2),
                    "rmse": clean(f.rmse),
                    "samples": f.samples,
                    "insufficient": f.bad,
                }
                for form, f in self.fits.items()
            },
            "favoured": self.favoured,
            "favoured_dm": clean(self.dm),
            "design_gains": {k: clean(v) for k, v in self.card.design.items()},
            "entries": [
                {"entry": e, "card": clean(c), "fitted": clean(x), "sigma": clean(s), "unit": u}
                for e, c, x, s, u in self.entries
            ],
            "replay": {
                k: {"position_rmse": clean(r.position_rmse), "velocity_rmse": clean(r.velocity_rmse)}
                for k, r in self.replays.items()
            },
            "moves": {k: {o: clean(x) for o, x in m.items()} for k, m in self.moves.items()},
            "notes": self.notes,
        }


def favour(fits: dict, replays: dict) -> str | None:
    """The favoured form (None when neither gives a model that runs). The discrete form by
    instrumental variables is consistent under velocity noise and exact between samples (core/fit/
    sysid_fit.py (F9)-(F13)); the continuous (SysId's least squares) is biased by the noise in v and
    by its central difference (x/sinh x of kA). So the discrete is favoured unless the log shows the
    continuous form's replay following the measured velocity better beyond what the noise can do:
    the Diebold-Mariano test (Diebold & Mariano 1995, J. Bus. Econ. Stat. 13(3)) of the two
    replays' squared velocity errors,
        d_k = (v̂c_k − v_k)² − (v̂d_k − v_k)²,  DM = d̄/√(λ̂/n),
        λ̂ = γ̂_0 + 2·Σ_(ℓ=1..L) (1 − ℓ/(L + 1))·γ̂_ℓ (Bartlett, Newey & West 1987), γ̂_ℓ within tests,
    L = ⌊√n⌋ (d's smooth part, the two models' difference, is correlated over many samples),
    continuous if DM < −1.645 (one-sided 5 %). The smaller replay RMSE alone (before) favoured the
    continuous form at seeds 0-4 of bench/fit_recovery.py's arm at 2 % noise behind a 4-sample
    velocity filter, its kA 12-24 % off against the discrete IV's 0.2-7.6 % (DM −0.9 to −1.3)."""
    good = [f for f in fits if fits[f].usable and math.isfinite(replays[f].velocity_rmse)]
    if not good:
        return None
    if len(good) == 1:
        return good[0]
    if getattr(fits.get("discrete"), "method", "ols") != "iv":  # both least squares: the closer replay
        return min(good, key=lambda f: replays[f].velocity_rmse)
    return (
        "continuous" if diebold_mariano(replays["continuous"], replays["discrete"]) < -1.645 else "discrete"
    )


def favoured_reason(r: Report) -> str:
    """Why the favoured form is favoured, in words (`gearhead fit` and the app say the same)."""
    good = [f for f in r.fits if r.fits[f].usable and math.isfinite(r.replays[f].velocity_rmse)]
    if len(good) == 1:
        return "the only form whose gains give a model that runs"
    if getattr(r.fits.get("discrete"), "method", "ols") == "iv" and math.isfinite(r.dm):
        return (
            "discrete unless the continuous form's replay is significantly closer: "
            f"Diebold-Mariano {r.dm:.3g}, continuous below -1.645"
        )
    return "the smaller velocity error when the log is replayed"


def diebold_mariano(a, b) -> float:
    """favour()'s DM statistic of replay a against replay b (negative: a's velocity errors smaller)."""
    import numpy as np

    parts = []
    for s, (_, _, v, _, va) in a.traces.items():
        if s in b.traces:
            vb = b.traces[s][4]
            parts.append((va - v) ** 2 - (vb - v) ** 2)
    if not parts:
        return 0.0
    d = np.concatenate(parts)
    n = len(d)
    mean = float(np.mean(d))
    L = int(math.sqrt(n))
    lam = 0.0
    for p in parts:
        x = p - mean
        lam += float(x @ x)
        for ell in range(1, min(L + 1, len(x))):
            lam += 2 * (1 - ell / (L + 1)) * float(x[ell:] @ x[:-ell])
    lam /= n
    if not (lam > 0 and math.isfinite(lam)):
        return 0.0 if mean == 0 else math.copysign(math.inf, mean)
    return mean / math.sqrt(lam / n)


def fit_log(path, kind: str, card=None, **pick) -> Report:
    """Read the log, pick the routine's signals, fit both forms, derive the card's entries from
    the favoured fit and replay the design's and the fitted gains."""
    from . import entries as ent
    from . import iv, signals, sysid_fit
    from . import replay as rp

    if card is None:
        card = ent.load_card(kind)
    spool = None
    if kind == "elevator":
        from ..calculators.elevator import spool_factor

        spool = spool_factor(card.values)
    elif kind == "sprint":  # wheel rotations to metres: the wheel's radius per radian
        from ..calculators.sprint import geometry

        spool = geometry(card.values)[2] / 2
    picked = signals.pick(path, kind, spool=spool, **pick)
    prepared, info = sysid_fit.prepare(picked)
    source = str(path)
    fits = {
        "continuous": sysid_fit.fit_continuous(prepared, kind, info["dt"], source),
        "discrete": iv.fit_discrete(prepared, kind, info["dt"], source),
    }
    replays = {"design": rp.replay(kind, card.design, picked.runs)}
    for form, f in fits.items():
        replays[form] = rp.replay(kind, f.gains, picked.runs)
    favoured = favour(fits, replays)
    both = all(fits[f].usable and math.isfinite(replays[f].velocity_rmse) for f in ("continuous", "discrete"))
    dm = diebold_mariano(replays["continuous"], replays["discrete"]) if both else math.nan
    if favoured is None:
        raise InputError(
            "log",
            "neither form of the fit gives a model that runs (finite gains, kA > 0): "
            + "; ".join(w for f in fits.values() for w in f.warnings),
            source,
        )
    for role, rmse in (
        ("position", replays[favoured].position_rmse),
        ("velocity", replays[favoured].velocity_rmse),
    ):
        if not math.isfinite(rmse):  # the squared error overflowed: a value near the float limit
            top = max(float(abs(getattr(r, role)).max(initial=0.0)) for r in picked.runs.values())
            picked.notes.append(
                f"{picked.names.get(role, role)}: the replay's {role} error is beyond the float range "
                f"(the log's {role} reaches {top:.3g} in SI units): not shown"
            )
    best = fits[favoured]
    notes = list(picked.notes) + [w for f in fits.values() for w in f.warnings]
    slow = sysid_fit.ka_note(best.gains, info["dt"])
    if slow:
        notes.append(slow)
    moved, more = ent.moves(card, best.gains)
    rows = ent.entries(card, best.gains, best.sigma)
    from .battery import fit_battery

    battery = fit_battery(picked, int(card.values["motor_count"]))
    if isinstance(battery, tuple):
        R, sR, E, n = battery
        rows.append(
            ("battery + wiring resistance", card.values.get("battery_resistance", math.nan), R, sR, "Ω")
        )
        more.append(f"battery: {n} current samples, open-circuit {E:.4g} V")
    elif picked.current is not None or picked.bus is not None:
        more.append(f"battery resistance not fitted: {battery}")
    return Report(
        source,
        kind,
        card,
        picked,
        info,
        fits,
        favoured,
        rows,
        replays,
        notes + more,
        moved,
        dm,
    )
