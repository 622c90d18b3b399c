"""A match integrated over loads in time, on one battery and one bus, with the roboRIO's brownout
and the breakers' thermal states: the outputs of issue 43 that need no mechanism scene.

A load gives, at each time t, its supply current as a function of the bus voltage (bus.py, M6):
I(t, V) = a(t) + b(t)·V + p(t)/V, from `start` to `stop`. The state integrated (scipy solve_ivp, RK45,
between every load's start and stop, so no step straddles a switch) is

    y = [Q, Q_p, E_oc, E_bus, E_R, ∫I²dt, q_1 … q_n, θ_main, θ_1 … θ_m]                     (M16)

with dQ/dt = I, dQ_p/dt by (M4), dE_oc/dt = V_oc·I, dE_bus/dt = V·I, dE_R/dt = I²·R (M5),
dq_i/dt = I_i (each load's charge), dθ/dt by (M12) for the main breaker (the battery current) and
each load's channel breaker that has a trip table. At each (t, y): s = s₀ − Q/C (M3),
V_oc = V_oc(s) (M1), the bus from the loads running (M7-M9), I_i = a_i + b_i·V + p_i/V,
I = I_base + Σ I_i.

Mode switches are located by the integrator's events, not by sampling:
  - brownout (M10): while the outputs are enabled, V − V_brownout falling through 0 ends the piece;
    the loads that brownout disables (motor controllers) then draw nothing for at least the dwell
    and until V − V_recovery rises through 0; a piece that starts already past its threshold
    switches at once (a load switched on that pulls the bus under the brownout voltage);
  - the branch of (M8) (M9): chosen at the start of each piece as the root nearest the last bus
    voltage, then held while the roots stay apart;
  - breakers: θ rising through 1 is recorded as the time a trip would happen (the load is not cut:
    these foundations report, they do not yet act).
Where the loads ask more power than the battery can give (D < 0 in M8) the bus sits at the vertex
V* = W/(2α) and the battery gives its most, I = (V_oc − V*)/R, shared among the loads in proportion
to what they asked at V*: the energy balance (M5) still holds; the time spent so is reported.

Outputs (`MatchResult`): the lowest bus voltage and when, the time below the brownout voltage, the
brownouts (start, length, the loads running), charge plain and Peukert-weighted (Ah), energy (Wh:
from the cells, to the bus, burnt in R), end state of charge and open-circuit voltage (and the
charge still available at the rates drawn, s_p of M4), peak and RMS
battery current, each load's share of the charge, each breaker's worst margin (1 − θ_max) and trip
time. The trace (t, V, I) is sampled at the solver's steps, every `trace_step` (20 ms by default,
a robot loop) and at each switch; the lowest voltage, the time below the brownout voltage, the peak
current and θ_max are read from it (a load step and a switch are in it exactly).

    RMS current = √(∫I²dt / length)                                                          (M17)
    share_i = q_i / Q                                                                         (M18)

Bounded work: at most MAX_LOADS loads, MAX_SWITCHES brownout switches and MAX_EVALS evaluations;
every input checked (InputError names it), and a load function that returns a non-finite or
non-numeric current is named with the time it did.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from numbers import Real

from gearhead.core.errors import InputError, shown
from gearhead.core.match.battery import AH, Battery
from gearhead.core.match.breaker import MAIN_RATING, Breaker
from gearhead.core.match.brownout import Controller
from gearhead.core.match.bus import solve_bus
from gearhead.core.match.checks import number

MAX_LOADS = 1000
MAX_SWITCHES = 20_000
MAX_EVALS = 2_000_000
MAX_LENGTH = 3600.0  # s

Terms = Callable[[float], tuple[float, float, float]]


def constant_current(amps: float) -> Terms:
    """A load drawing `amps` whatever the bus voltage."""
    return lambda t: (amps, 0.0, 0.0)


def constant_power(watts: float) -> Terms:
    """A load drawing `watts` whatever the bus voltage (a stator-limited motor, bus.py)."""
    return lambda t: (0.0, 0.0, watts)


def affine(a: float, b: float) -> Terms:
    """A load drawing a + b·V (a motor at a fixed duty and speed, bus.motor_terms)."""
    return lambda t: (a, b, 0.0)


@dataclass(frozen=True)
class Load:
    """One mechanism's supply current `terms(t) -> (a, b, p)` (M6) from `start` to `stop` (s)."""

    name: str
    terms: Terms
    start: float = 0.0
    stop: float = MAX_LENGTH
    brownout_disables: bool = True
    breaker: Breaker | None = None


@dataclass(frozen=True)
class BreakerResult:
    name: str
    rating: float
    calibrated: bool
    peak_multiple: float  # peak |I| / rating
    theta_max: float | None  # None without a trip table
    trip_time: float | None  # the first time θ reached 1

    @property
    def margin(self) -> float | None:
        """1 − θ_max: how far the worst moment stayed from a trip (None without a table)."""
        return None if self.theta_max is None else 1.0 - self.theta_max


@dataclass(frozen=True)
class BrownoutResult:
    start: float
    end: float
    loads_running: tuple[str, ...]

    @property
    def length(self) -> float:
        return self.end - self.start


@dataclass(frozen=True)
class MatchResult:
    length: float
    min_voltage: float
    min_voltage_time: float
    time_below_brownout: float
    brownouts: tuple[BrownoutResult, ...]
    charge_ah: float
    peukert_charge_ah: float
    energy_cells_wh: float
    energy_bus_wh: float
    energy_loss_wh: float
    end_soc: float  # s (M3), from the plain charge
    end_available: float  # s_p (M4), from the Peukert-weighted charge: ≤ 0 means empty at these rates
    end_ocv: float
    peak_current: float
    rms_current: float
    shares: dict[str, float]
    breakers: tuple[BreakerResult, ...]
    collapsed_time: float
    times: tuple[float, ...] = field(repr=False)
    volts: tuple[float, ...] = field(repr=False)
    amps: tuple[float, ...] = field(repr=False)


@dataclass(frozen=True)
class Match:
    """A match: a battery, a controller, a base load (A, never disabled) and the loads."""

    battery: Battery = Battery()
    controller: Controller = Controller()
    length: float = 150.0
    base_load: float = 0.0
    loads: tuple[Load, ...] = ()
    main_breaker: Breaker = Breaker(MAIN_RATING, name="main_breaker")
    trace_step: float = 0.02  # s: the robot loop's 20 ms; switches and trips are events, not this grid
    rtol: float = 1e-9

    def __post_init__(self):
        if not isinstance(self.battery, Battery):
            raise InputError("battery", f"must be a Battery, got {shown(self.battery)}")
        if not isinstance(self.controller, Controller):
            raise InputError("controller", f"must be a Controller, got {shown(self.controller)}")
        if not isinstance(self.main_breaker, Breaker):
            raise InputError("main_breaker", f"must be a Breaker, got {shown(self.main_breaker)}")
        length = number("length", self.length, low=0.0, low_open=True, high=MAX_LENGTH)
        object.__setattr__(self, "length", length)
        object.__setattr__(self, "base_load", number("base_load", self.base_load, low=0.0, high=1000.0))
        object.__setattr__(
            self, "trace_step", number("trace_step", self.trace_step, low=length * 1e-6, high=length)
        )
        object.__setattr__(self, "rtol", number("rtol", self.rtol, low=1e-12, high=1e-3))
        loads = self.loads
        if isinstance(loads, (str, bytes)) or not hasattr(loads, "__len__"):
            raise InputError("loads", f"must be a list of loads, got {shown(loads)}")
        if len(loads) > MAX_LOADS:
            raise InputError("loads", f"has {len(loads)} loads; at most {MAX_LOADS}")
        names = set()
        for i, load in enumerate(loads):
            where = f"loads[{i}]"
            if not isinstance(load, Load):
                raise InputError(where, f"must be a Load, got {shown(load)}")
            if not isinstance(load.name, str) or not load.name or load.name == "base":
                raise InputError(
                    f"{where}.name", f"must be a non-empty name other than 'base', got {shown(load.name)}"
                )
            if load.name in names:
                raise InputError(f"{where}.name", f"{shown(load.name)} names two loads")
            names.add(load.name)
            if not callable(load.terms):
                raise InputError(f"{where}.terms", "must be a function of time giving (a, b, p)")
            start = number(f"{where}.start", load.start, low=0.0, high=length)
            stop = number(f"{where}.stop", load.stop, low=0.0, high=MAX_LENGTH)
            if stop <= start:
                raise InputError(f"{where}.stop", f"must be after the start {start:g} s, got {stop:g} s")
            if not isinstance(load.brownout_disables, bool):
                raise InputError(
                    f"{where}.brownout_disables",
                    f"must be true or false, got {shown(load.brownout_disables)}",
                )
            if load.breaker is not None and not isinstance(load.breaker, Breaker):
                raise InputError(f"{where}.breaker", f"must be a Breaker, got {shown(load.breaker)}")
        object.__setattr__(self, "loads", tuple(loads))

    def run(self) -> MatchResult:
        return _Run(self).result()


class _Run:
    """One integration of a Match (M16-M18)."""

    def __init__(self, match: Match):
        self.m = match
        self.bat = match.battery
        self.R = match.battery.R
        self.n = len(match.loads)
        self.channel = [
            i for i, ld in enumerate(match.loads) if ld.breaker is not None and ld.breaker.calibrated
        ]
        self.evals = 0
        self.enabled = True
        self.branch_upper = True

    # --- the bus at one instant ---------------------------------------------------------------
    def terms(self, i: int, t: float) -> tuple[float, float, float]:
        load = self.m.loads[i]
        where = f"loads[{i}] {load.name!r}"
        try:
            a, b, p = load.terms(t)
        except InputError:
            raise
        except Exception as exc:  # a user's function: say which and when, never a traceback
            raise InputError(
                where, f"could not give its current at t = {t:.6g} s ({type(exc).__name__})"
            ) from None
        out = []
        for name, x in (("a", a), ("b", b), ("p", p)):
            if isinstance(x, bool) or not isinstance(x, Real) or not math.isfinite(x):
                raise InputError(where, f"gave {name} = {shown(x)} at t = {t:.6g} s; must be a finite number")
            out.append(float(x))
        if out[1] < 0:
            raise InputError(where, f"gave b = {out[1]:g} at t = {t:.6g} s; must be ≥ 0 (M6)")
        return out[0], out[1], out[2]

    def point(self, t: float, y, active: list[int]):
        """(V_oc, V, [I_i], I, collapsed) at (t, y)."""
        self.evals += 1
        if self.evals > MAX_EVALS:
            raise InputError(
                "loads", f"the match needs more than {MAX_EVALS} evaluations (loads too fast-varying?)"
            )
        voc = self.bat.ocv(self.bat.soc(y[0]))  # (M3): the plain charge sets V_oc
        on = [i for i in active if self.enabled or not self.m.loads[i].brownout_disables]
        terms = {i: self.terms(i, t) for i in on}
        A = self.m.base_load + sum(a for a, _, _ in terms.values())
        B = sum(b for _, b, _ in terms.values())
        P = sum(p for _, _, p in terms.values())
        pt = solve_bus(voc, self.R, A, B, P)
        if pt.collapsed:
            v = pt.voltage
            total = (voc - v) / self.R
            asked = {i: (a + b * v + (p / v if v > 0 else 0.0)) for i, (a, b, p) in terms.items()}
            rest = total - self.m.base_load
            s = sum(asked.values())
            cur = [0.0] * self.n
            for i, x in asked.items():
                cur[i] = rest * x / s if s else rest / len(asked)
            return voc, v, cur, total, True
        v = pt.upper if (self.branch_upper or pt.lower is None) else pt.lower
        cur = [0.0] * self.n
        for i, (a, b, p) in terms.items():
            cur[i] = a + b * v + p / v
        return voc, v, cur, self.m.base_load + sum(cur), False

    def rhs(self, t, y, active):
        voc, v, cur, I, _ = self.point(t, y, active)
        m = self.m
        dy = [I, self.bat.peukert_rate(I), voc * I, v * I, I * I * self.R, I * I]
        dy.extend(cur)
        dy.append(m.main_breaker.rate(y[6 + self.n], I) if m.main_breaker.calibrated else 0.0)
        for k, i in enumerate(self.channel):
            dy.append(m.loads[i].breaker.rate(y[7 + self.n + k], cur[i]))
        return dy

    # --- the match ----------------------------------------------------------------------------
    def result(self) -> MatchResult:
        from scipy.integrate import solve_ivp  # lazily: scipy's import is ~0.4 s

        m = self.m
        ctl = m.controller
        L = m.length
        cuts = sorted({0.0, L} | {x for ld in m.loads for x in (ld.start, ld.stop) if x < L})
        th0 = 6 + self.n  # θ_main's index in y; the channels' follow
        nb = 1 + len(self.channel)
        y = [0.0] * (th0 + nb)
        times, volts, amps, cols = [], [], [], []
        load_peak = [0.0] * self.n
        theta_max = [0.0] * nb
        trips: list[float | None] = [None] * nb
        brownouts: list[BrownoutResult] = []
        self.switches = 0
        bo_start, bo_loads = 0.0, ()
        last_v = None
        ready = 0.0  # the earliest re-enable time (the dwell)

        def sample(t, yy, active):
            _, v, cur, I, col = self.point(t, yy, active)
            times.append(t)
            volts.append(v)
            amps.append(I)
            cols.append(col)
            for i in active:
                load_peak[i] = max(load_peak[i], abs(cur[i]))
            for k in range(nb):
                theta_max[k] = max(theta_max[k], float(yy[th0 + k]))
            return v

        for c0, c1 in zip(cuts, cuts[1:]):
            active = [i for i, ld in enumerate(m.loads) if ld.start <= c0 < ld.stop]
            t = c0
            while t < c1:
                self._choose_branch(t, y, active, last_v)  # (M9)
                v_now = sample(t, y, active)
                last_v = v_now
                # a piece that starts past its threshold switches at once (M10)
                if self.enabled and v_now < ctl.brownout:
                    self._switched()
                    self.enabled, bo_start, ready = False, t, t + ctl.dwell
                    bo_loads = tuple(m.loads[i].name for i in active)
                    continue
                if not self.enabled and t >= ready and v_now > ctl.recovery:
                    self._switched()
                    brownouts.append(BrownoutResult(bo_start, t, bo_loads))
                    self.enabled = True
                    continue
                waiting = not self.enabled and t < ready
                t_end = min(c1, ready) if waiting else c1
                events = []
                if not waiting:
                    level, direction = (ctl.brownout, -1) if self.enabled else (ctl.recovery, 1)
                    ev = lambda tt, yy, a=active, lv=level: self.point(tt, yy, a)[1] - lv  # noqa: E731
                    ev.terminal, ev.direction = True, direction
                    events.append(ev)
                first_breaker = len(events)
                for k in range(nb):
                    evb = lambda tt, yy, k=k: yy[th0 + k] - 1.0  # noqa: E731
                    evb.terminal, evb.direction = False, 1
                    events.append(evb)
                sol = solve_ivp(
                    lambda tt, yy, a=active: self.rhs(tt, yy, a),
                    (t, t_end),
                    y,
                    method="RK45",
                    rtol=m.rtol,
                    atol=1e-12,
                    events=events,
                    dense_output=True,
                )
                if sol.status == -1:
                    raise InputError("loads", f"the integration failed at t = {t:.6g} s: {sol.message}")
                t_stop = float(sol.t[-1])
                steps = int((t_stop - t) / m.trace_step)
                grid = sorted(
                    {float(x) for x in sol.t[1:]} | {t + k * m.trace_step for k in range(1, steps + 1)}
                )
                for tt in grid:
                    if tt <= t_stop:
                        last_v = sample(tt, sol.sol(tt), active)
                for k in range(nb):
                    hits = sol.t_events[first_breaker + k]
                    if trips[k] is None and len(hits):
                        trips[k] = float(hits[0])
                y = [float(x) for x in sol.y[:, -1]]
                if sol.status == 1:  # the brownout or recovery event ended the piece
                    self._switched()
                    if self.enabled:
                        self.enabled, bo_start, ready = False, t_stop, t_stop + ctl.dwell
                        bo_loads = tuple(m.loads[i].name for i in active)
                    else:
                        brownouts.append(BrownoutResult(bo_start, t_stop, bo_loads))
                        self.enabled = True
                t = t_stop
        if not self.enabled:
            brownouts.append(BrownoutResult(bo_start, L, bo_loads))
        return self._result(y, times, volts, amps, cols, load_peak, theta_max, trips, brownouts)

    def _choose_branch(self, t, y, active, last_v) -> None:
        """(M9): the root of (M8) nearest the last bus voltage (the upper one at the start)."""
        self.branch_upper = True
        if last_v is None:
            return
        v_up = self.point(t, y, active)[1]
        self.branch_upper = False
        v_lo = self.point(t, y, active)[1]
        self.branch_upper = abs(v_up - last_v) <= abs(v_lo - last_v)

    def _switched(self) -> None:
        self.switches += 1
        if self.switches > MAX_SWITCHES:
            raise InputError(
                "controller.dwell",
                f"the bus switched brownout more than {MAX_SWITCHES} times; a longer dwell bounds it",
            )

    def _result(self, y, times, volts, amps, cols, load_peak, theta_max, trips, brownouts) -> MatchResult:
        from gearhead.core.match.brownout import time_below

        m = self.m
        order = sorted(range(len(times)), key=lambda k: (times[k], k))  # stable: a switch keeps its order
        times = [times[k] for k in order]
        volts = [volts[k] for k in order]
        amps = [amps[k] for k in order]
        cols = [cols[k] for k in order]
        k_min = min(range(len(volts)), key=lambda k: volts[k])
        collapsed = sum(t1 - t0 for t0, t1, c in zip(times, times[1:], cols) if c)
        Q = y[0]
        shares = {"base": m.base_load * m.length / Q if Q else 0.0}
        for i, ld in enumerate(m.loads):
            shares[ld.name] = y[6 + i] / Q if Q else 0.0
        soc = self.bat.soc(y[0])
        out = [_breaker(m.main_breaker, max(abs(a) for a in amps), theta_max[0], trips[0])]
        for i, ld in enumerate(m.loads):
            if ld.breaker is None:
                continue
            if ld.breaker.calibrated:
                k = 1 + self.channel.index(i)
                out.append(_breaker(ld.breaker, load_peak[i], theta_max[k], trips[k]))
            else:
                out.append(_breaker(ld.breaker, load_peak[i], None, None))
        if not m.main_breaker.calibrated:
            out[0] = _breaker(m.main_breaker, max(abs(a) for a in amps), None, None)
        return MatchResult(
            length=m.length,
            min_voltage=volts[k_min],
            min_voltage_time=times[k_min],
            time_below_brownout=time_below(times, volts, m.controller.brownout),
            brownouts=tuple(brownouts),
            charge_ah=Q / AH,
            peukert_charge_ah=y[1] / AH,
            energy_cells_wh=y[2] / 3600.0,
            energy_bus_wh=y[3] / 3600.0,
            energy_loss_wh=y[4] / 3600.0,
            end_soc=soc,
            end_available=self.bat.soc(y[1]),
            end_ocv=self.bat.ocv(soc),
            peak_current=max(amps),
            rms_current=math.sqrt(max(y[5], 0.0) / m.length),
            shares=shares,
            breakers=tuple(out),
            collapsed_time=collapsed,
            times=tuple(times),
            volts=tuple(volts),
            amps=tuple(amps),
        )


def _breaker(b: Breaker, peak: float, theta: float | None, trip: float | None) -> BreakerResult:
    return BreakerResult(b.name, b.rating, b.calibrated, peak / b.rating, theta, trip)
