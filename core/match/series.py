"""The match's series on one time base, for plots: the bus voltage, the battery current (in total, and
by card plus the base load), and the state of charge, at every sample of the bus trace
(core.match.mechanisms.BusResult.trace: every accepted step and switch).

    I(t_i) = I_base + Σ_cards Σ_its moves N·I_s(t_i)                                           (S1)
        each move's supply current is recorded at the same samples as the bus (its supply_trace
        carries the sample's index), 0 outside its start..goal: it draws nothing there
    s(t_i) = s₀ − Q_i/C,   Q_i = Σ_{j≤i} ΔQ_j,  ΔQ_j = ½(I_{j−1} + I_j)(t_j − t_{j−1})          (S2)
        the trapezoid on the trace differs from the integrated charge Q (the run's state, which
        gives match.end_charge) by the rule's error (~0.1 % of the charge used on the example);
        that difference c = Q − ΣΔQ is spread over the steps in proportion to |ΔQ_j|, so the last
        point is the output exactly and no step changes sign (a step drawing charge keeps drawing:
        |c| is far below Σ|ΔQ|). The charge still available at the rates drawn (Peukert,
        battery (M4)) is formed alike from dQ_p/dt = I·(I/I_H)^(k−1) and ends at end_available.
A battery current below zero (a motor driven past its free speed, gravity lowering the arm, pushes
current back) raises the state of charge over that step: the model counts it plain (battery (M4)).
Pure logic: the workbook's MatchOutcome is read by its attributes (bus, battery, controller,
base_load, moves), never imported, so this module sits below core.workbook.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any


@dataclass
class MatchSeries:
    t: list[float]  # s, the bus trace's samples
    bus_voltage: list[float]  # V
    battery_current: list[float]  # A, the bus trace's own (S1's left side)
    base: list[float]  # A, the base load (never disabled)
    by_card: dict[str, list[float]] = field(default_factory=dict)  # card -> A, its moves summed (S1)
    soc: list[float] = field(default_factory=list)  # state of charge, a fraction (S2)
    available: list[float] = field(default_factory=list)  # charge available (Peukert), a fraction
    brownout: float = 0.0  # V, the controller's levels
    recovery: float = 0.0
    length: float = 0.0  # s


def series(outcome: Any) -> MatchSeries:
    """The series of a core.workbook.match.MatchOutcome (S1, S2)."""
    bus, battery = outcome.bus, outcome.battery
    trace = bus.trace
    n = len(trace)
    t = [float(s[0]) for s in trace]
    by_card: dict[str, list[float]] = {}
    for _, ev, r in outcome.moves:
        amps = by_card.setdefault(ev.card, [0.0] * n)
        for i, _t, a in getattr(r, "supply_trace", ()):
            if 0 <= i < n:
                amps[i] += a
    current = [float(s[2]) for s in trace]
    soc = _charge_curve(t, current, bus.charge, battery)
    rate = getattr(battery, "peukert_rate", None)
    if rate is not None:
        available = _charge_curve(t, [rate(i) for i in current], bus.peukert_charge, battery)
    else:  # a fixed source (no battery): nothing drawn from any charge
        available = list(soc)
    length = float(outcome.spec.values["length"]) if hasattr(outcome, "spec") else (t[-1] if t else 0.0)
    return MatchSeries(
        t,
        [float(s[1]) for s in trace],
        current,
        [float(outcome.base_load)] * n,
        by_card,
        soc,
        available,
        float(outcome.controller.brownout),
        float(outcome.controller.recovery),
        length,
    )


def _charge_curve(t: list[float], rate: list[float], total: float, battery: Any) -> list[float]:
    """s₀ − Q_i/C along the trace (S2): the trapezoid's steps, corrected to end at `total` (C).
    numpy: a brownout-ridden match has ~10⁵ samples (0.26 s in a Python loop, 2 curves)."""
    import numpy as np

    if not t:
        return []
    tt, rr = np.asarray(t, dtype=float), np.asarray(rate, dtype=float)
    steps = np.concatenate(([0.0], 0.5 * (rr[:-1] + rr[1:]) * np.diff(tt)))
    spread = float(np.abs(steps).sum())
    c = total - float(steps.sum())
    if spread > 0 and math.isfinite(c):
        steps = steps + c * np.abs(steps) / spread
    q = np.cumsum(steps)
    out = np.broadcast_to(np.asarray(battery.soc(q), dtype=float), q.shape).tolist()
    out[-1] = float(battery.soc(total))  # the output itself, not the sum's rounding
    return out


def peak_bins(s: MatchSeries, bins: int) -> list[tuple[float, int]]:
    """For a stacked chart `bins` columns wide: each equal time bin's middle and the sample it
    shows, the one with the highest battery current in it (a move's peak is never averaged away);
    a bin with no sample shows the last sample before it (the current carried on: the trace's
    steps are long only where nothing changes)."""
    if not s.t or bins < 1:
        return []
    length = s.length if s.length > 0 else (s.t[-1] or 1.0)
    width = length / bins
    best: list[int | None] = [None] * bins
    for i, (ti, ii) in enumerate(zip(s.t, s.battery_current)):
        b = min(bins - 1, max(0, int(ti / width)))
        if best[b] is None or ii > s.battery_current[best[b]]:
            best[b] = i
    out, last = [], 0
    for b in range(bins):
        if best[b] is None:
            # the last sample at or before the bin's start
            while last + 1 < len(s.t) and s.t[last + 1] <= b * width:
                last += 1
            idx = last
        else:
            idx = best[b]
            last = max(last, idx)
        out.append(((b + 0.5) * width, idx))
    return out


def envelope(t: list[float], y: list[float], length: float, bins: int) -> tuple[list[float], list[float]]:
    """The samples a line chart `bins` pixels wide needs (M4 thinning): in each equal time bin its
    first, lowest, highest and last sample, in time order (the first of equal lowest or highest).
    Every extreme is kept where it was (a brownout's dip, a move's peak) and the line is exact at
    each bin's edges (a jump back up at a move's end stays a jump, not a slope to the next bin's
    peak), so at that width it looks as the whole trace does, with at most 4·bins points (a
    brownout-ridden match has ~10⁵ samples: too many to draw at each change). numpy, on the trace's
    order in time (its samples never go back)."""
    import numpy as np

    if not t or bins < 1:
        return [], []
    width = (length if length > 0 else (t[-1] or 1.0)) / bins
    tt, yy = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    b = np.clip((tt / width).astype(np.int64), 0, bins - 1)
    n = len(tt)
    starts = np.flatnonzero(np.concatenate(([True], b[1:] != b[:-1])))
    if np.any(np.diff(b) < 0):  # not in time order: no trace of the bus, but bins by their own
        order = np.argsort(b, kind="stable")
        xs, ys = envelope([t[i] for i in order], [y[i] for i in order], length, bins)
        return xs, ys
    lengths = np.diff(np.concatenate((starts, [n])))
    seg = np.repeat(np.arange(len(starts)), lengths)
    keep = [starts, starts + lengths - 1]
    for reduce in (np.minimum, np.maximum):
        extreme = reduce.reduceat(yy, starts)
        hit = np.flatnonzero(yy == extreme[seg])
        _, first = np.unique(seg[hit], return_index=True)  # the first hit in each bin
        keep.append(hit[first])
    idx = np.unique(np.concatenate(keep))
    return tt[idx].tolist(), yy[idx].tolist()
