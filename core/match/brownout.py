"""The roboRIO's brownout, as the robot does it: a state machine with hysteresis.

From frc-docs, "roboRIO Brownout and Understanding Current Draw"
(https://docs.wpilib.org/en/stable/docs/software/roborio-info/roborio-brownouts.html; source
wpilibsuite/frc-docs source/docs/software/roborio-info/roborio-brownouts.rst at commit c6315dc):
  - Stage 2, output disable: "When the voltage drops below 6.3V, the controller will enter the
    brownout protection state": PWM outputs disabled, "CAN-based motor controllers are sent an
    explicit disable command", relays driven low, the 6 V/5 V/3.3 V user rails and the pneumatics
    disabled. "The controller will remain in this state until the voltage rises to greater than
    7.5V or drops below the trigger for the next stage" (stage 3, blackout, below 4.5 V).
  - "Settable Brownout": the roboRIO 1.0 is fixed at 6.3 V; "The default brownout level (Stage 2)
    of the roboRIO 2.0 is 6.75V" (settable with RobotController.setBrownoutVoltage).
So between the brownout and the recovery voltage the outputs stay disabled: the motors coast, a
mechanism nothing holds falls, and only the controller's own (base) load draws until the bus,
relieved of the motors, rises past 7.5 V; then the outputs come back, the current with them, and the
bus may fall again: the oscillation is the state machine below, not assumed away.

    enabled  → disabled  when V < V_brownout
    disabled → enabled   when V > V_recovery and at least `dwell` after the outputs were disabled   (M10)

`dwell` (default 0.02 s) is this model's assumption, not a published figure: the outputs come back
no sooner than the next control packet (a robot program's loop runs every 20 ms, WPILib TimedRobot's
default period). It also keeps the oscillation bounded where the bus would otherwise switch in zero
time (a bus with no dynamics of its own: loads on → below 6.75 V at once, off → above 7.5 V at once).

On a trace sampled at times t_k, the voltage is taken linear between samples, so a crossing of the
threshold V_x between (t₀, v₀) and (t₁, v₁) is located at

    t* = t₀ + (V_x − v₀)·(t₁ − t₀)/(v₁ − v₀)                                                   (M11)

not at a sample. The timeline (timeline.py) locates its crossings with the integrator's events instead.
"""

from __future__ import annotations

from dataclasses import dataclass

from gearhead.core.errors import InputError
from gearhead.core.match.checks import number

BROWNOUT_VOLTS = {"roborio2": 6.75, "roborio1": 6.3}  # frc-docs, see the docstring
RECOVERY_VOLTS = 7.5  # frc-docs: "until the voltage rises to greater than 7.5V"
DWELL = 0.02  # s, this model's assumption (see the docstring)


@dataclass(frozen=True)
class Controller:
    """The brownout thresholds (M10): `brownout` < `recovery`, volts; `dwell` s."""

    brownout: float = BROWNOUT_VOLTS["roborio2"]
    recovery: float = RECOVERY_VOLTS
    dwell: float = DWELL

    def __post_init__(self):
        b = number("controller.brownout", self.brownout, low=0.0, low_open=True, high=30.0)
        r = number("controller.recovery", self.recovery, low=0.0, low_open=True, high=30.0)
        d = number("controller.dwell", self.dwell, low=0.0, low_open=True, high=10.0)
        if r <= b:
            raise InputError(
                "controller.recovery", f"must be above the brownout voltage {b:g} V, got {r:g} V"
            )
        object.__setattr__(self, "brownout", b)
        object.__setattr__(self, "recovery", r)
        object.__setattr__(self, "dwell", d)

    @classmethod
    def named(cls, name: object) -> Controller:
        """The controller `roborio2` (6.75 V) or `roborio1` (6.3 V), recovering at 7.5 V."""
        if name not in BROWNOUT_VOLTS:
            raise InputError("controller", f"must be one of {', '.join(BROWNOUT_VOLTS)}")
        return cls(brownout=BROWNOUT_VOLTS[name])


@dataclass(frozen=True)
class Brownout:
    """One brownout: the outputs disabled from `start` to `end` (s)."""

    start: float
    end: float

    @property
    def length(self) -> float:
        return self.end - self.start


def _crossing(t0: float, v0: float, t1: float, v1: float, level: float) -> float:
    """(M11): where the segment (t0, v0)-(t1, v1) meets `level`."""
    if v1 == v0:
        return t0
    return t0 + (level - v0) * (t1 - t0) / (v1 - v0)


def brownouts(times, volts, controller: Controller) -> list[Brownout]:
    """The brownouts (M10) of a bus-voltage trace, linear between its samples (M11). A brownout
    still running at the trace's end ends there."""
    t = [float(x) for x in times]
    v = [float(x) for x in volts]
    if len(t) != len(v):
        raise InputError("volts", "needs one voltage per time")
    out: list[Brownout] = []
    enabled = True
    start = 0.0
    k = 0
    n = len(t)
    while k < n - 1:
        t0, v0, t1, v1 = t[k], v[k], t[k + 1], v[k + 1]
        if enabled:
            if v0 < controller.brownout:  # already below at a sample (the trace's first)
                enabled, start = False, t0
                continue
            if v1 < controller.brownout:
                enabled, start = False, _crossing(t0, v0, t1, v1, controller.brownout)
                continue
            k += 1
            continue
        # disabled: the earliest time ≥ start + dwell where the bus is above the recovery voltage
        ready = start + controller.dwell
        if t1 < ready:
            k += 1
            continue
        lo = max(t0, ready)
        v_lo = v0 if lo == t0 else v0 + (v1 - v0) * (lo - t0) / (t1 - t0)
        if v_lo > controller.recovery:
            end = lo
        elif v1 > controller.recovery:
            end = _crossing(t0, v0, t1, v1, controller.recovery)
        else:
            k += 1
            continue
        out.append(Brownout(start, end))
        enabled = True
        # go on from `end` inside this segment: the bus may fall again before t1
        t[k], v[k] = end, v0 + (v1 - v0) * (end - t0) / (t1 - t0) if t1 != t0 else v1
        if t[k] >= t1:
            k += 1
    if not enabled:
        out.append(Brownout(start, t[-1]))
    return out


def time_below(times, volts, level: float) -> float:
    """The time a trace, linear between its samples, spends below `level` (s)."""
    total = 0.0
    for t0, v0, t1, v1 in zip(times, volts, times[1:], volts[1:]):
        if v0 < level and v1 < level:
            total += t1 - t0
        elif v0 < level <= v1:
            total += _crossing(t0, v0, t1, v1, level) - t0
        elif v1 < level <= v0:
            total += t1 - _crossing(t0, v0, t1, v1, level)
    return total
