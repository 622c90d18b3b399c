"""The fit's recovery table (issue 44, "Done when"): how far each form lands from a known plant as
the log gets worse. Figures only, never asserted (tests/test_fit_sysid.py holds the bounds).

For the plants of tests/test_fit_sysid.py (an elevator, an arm with a 0.3 rad offset, a flywheel:
time constants kA/kV of 0.1-0.2 s, which a 10 ms log resolves), each log written by
tests/fit_plants.py with WPILib's DataLogWriter (a 10 ms loop, the quasistatic tests 6 s at 1 V/s,
the dynamic ones 2 s at 7 V), read and fitted as `gearhead fit` does (core.fit.signals.pick,
sysid_fit.prepare, fit_continuous, fit_discrete), at
- velocity noise 0, 0.1 %, 0.5 % and 2 % of the top speed at 12 V (Gaussian; the position's a tenth
  of it, in the plant's units), and
- three logs: steps of exactly 10 ms; ± 1 ms of timestamp jitter (uniform); that jitter and the
  velocity a moving average of the last 4 samples (a motor controller's filter: 30 ms of lag);
- over seeds 0-4 (the noise and jitter drawn again): the WORST of the five, per gain: the
  relative error |fitted/plant − 1| in % for kS, kV, kA, kG, the absolute error of the arm's offset
  in mrad. "fail": the fit refused the log (a message, as `gearhead fit` exits 2), or gave no
  finite value for that gain.
Forms: "continuous (SysId)", SysId's least squares (F1); "discrete OLS", SysId's discrete least
squares (F5), sysid_fit.fit_discrete; "discrete IV", the discrete form by instrumental variables
(core/fit/iv.py (F9)-(F13), iv.fit_discrete), what `gearhead fit` shows as discrete; "favoured",
the form core.fit.favour picks between the continuous and the discrete IV (their replays through
core.fit.replay), per seed, and "picks": how many seeds it picked each.

    .venv/bin/python bench/fit_recovery.py [--seeds N]
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from fit_plants import simulate  # noqa: E402

from gearhead.core import fit  # noqa: E402
from gearhead.core.errors import InputError  # noqa: E402
from gearhead.core.fit import iv, replay, signals, sysid_fit  # noqa: E402

SEEDS = int(sys.argv[sys.argv.index("--seeds") + 1]) if "--seeds" in sys.argv else 5
# tests/test_fit_sysid.py's PLANTS
PLANTS = {
    "elevator": {"kS": 0.2, "kV": 10.0, "kA": 1.2, "kG": 0.6},
    "arm": {"kS": 0.15, "kV": 2.0, "kA": 0.2, "kG": 0.8, "offset": 0.3},
    "flywheel": {"kS": 0.1, "kV": 0.02, "kA": 0.004},
}
NOISE = (0.0, 0.001, 0.005, 0.02)  # of the top speed at 12 V
LOGS = {  # label -> fit_plants.simulate settings
    "10 ms": {"jitter": 0.0, "velocity_filter": 1},
    "±1 ms": {"jitter": 0.001, "velocity_filter": 1},
    "±1 ms, filter 4": {"jitter": 0.001, "velocity_filter": 4},
}
GAINS = ("kS", "kV", "kA", "kG", "offset")
FORMS = ("continuous", "discrete OLS", "discrete IV", "favoured")


def errors(kind: str, plant: dict, fitted: dict) -> dict[str, float]:
    """|relative error| (%) per gain; the offset's |error| in mrad."""
    out = {}
    for k in plant:
        x = fitted.get(k, math.nan)
        if not math.isfinite(x):
            out[k] = math.inf
        elif k == "offset":
            out[k] = abs(math.remainder(x - plant[k], 2 * math.pi)) * 1000
        else:
            out[k] = abs(x / plant[k] - 1) * 100
    return out


def recover(folder: Path, kind: str, noise: float, settings: dict, seed: int) -> tuple[dict[str, dict], str]:
    """Each form's errors for one log and the form `gearhead fit` favours; a refused log: every gain inf."""
    g = PLANTS[kind]
    sigma_v = noise * 12 / g["kV"]
    path = simulate(folder / f"{kind}.wpilog", kind, g, noise=sigma_v, seed=seed, **settings)
    try:
        picked = signals.pick(path, kind)
        prepared, info = sysid_fit.prepare(picked)
        fits = {
            "continuous": sysid_fit.fit_continuous(prepared, kind, info["dt"], str(path)),
            "discrete OLS": sysid_fit.fit_discrete(prepared, kind, info["dt"], str(path)),
            "discrete IV": iv.fit_discrete(prepared, kind, info["dt"], str(path)),
        }
    except InputError:
        return {f: {k: math.inf for k in g} for f in FORMS}, "fail"
    shown = {"continuous": fits["continuous"], "discrete": fits["discrete IV"]}  # what `gearhead fit` shows
    favoured = fit.favour(shown, {f: replay.replay(kind, x.gains, picked.runs) for f, x in shown.items()})
    out = {f: errors(kind, g, fits[f].gains) for f in FORMS if f != "favoured"}
    out["favoured"] = errors(kind, g, shown[favoured].gains) if favoured else {k: math.inf for k in g}
    return out, favoured or "fail"


def cell(x: float | None) -> str:
    if x is None:
        return "-"
    if not math.isfinite(x):
        return "fail"
    return f"{x:.2f}" if x < 10 else f"{x:.3g}" if x < 1000 else f"{x:.0f}"


def main() -> None:
    t0 = time.perf_counter()
    seeds = list(range(SEEDS))
    head = " ".join(f"{k:>6}" for k in GAINS)
    print(
        f"worst over seeds {seeds[0]}-{seeds[-1]} of |fitted/plant - 1| in % (offset: |error| in mrad); "
        "noise: velocity, of the top speed; picks: how many seeds `gearhead fit` favoured the "
        "continuous (c) or the discrete IV (d) form"
    )
    titles = ("continuous (SysId)", "discrete OLS", "discrete IV", "favoured")
    print(f"{'':<8} {'':<15} {'':>5}  " + "  ".join(f"{t:^{len(head)}}" for t in titles) + "  picks")
    print(f"{'plant':<8} {'log':<15} {'noise':>5}  " + "  ".join(head for _ in titles))
    with tempfile.TemporaryDirectory(prefix="fit_recovery_") as tmp:
        folder = Path(tmp)
        for kind in PLANTS:
            for label, settings in LOGS.items():
                for noise in NOISE:
                    worst = {f: {} for f in FORMS}
                    picks = {"continuous": 0, "discrete": 0, "fail": 0}
                    for seed in seeds:
                        got, favoured = recover(folder, kind, noise, settings, seed)
                        picks[favoured] += 1
                        for f in FORMS:
                            for k, x in got[f].items():
                                worst[f][k] = max(worst[f].get(k, 0.0), x)
                        if noise == 0 and not settings["jitter"]:
                            break  # nothing random: every seed writes the same log
                    cells = [" ".join(f"{cell(worst[f].get(k)):>6}" for k in GAINS) for f in FORMS]
                    said = "".join(f"{k[0]}{n}" for k, n in picks.items() if n)
                    print(f"{kind:<8} {label:<15} {noise * 100:4.1f}%  " + "  ".join(cells) + f"  {said}")
    print(f"({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
