"""The FRC battery: one 12 V 18 Ah sealed lead-acid (AGM) battery, as a voltage source behind a
resistance whose voltage falls with the charge drawn.

    V_oc(s) = the table's open-circuit voltage at state of charge s, linear between its rows,
              held at the end rows outside them                                               (M1)
    R = R_internal + R_wiring;   the bus: V = V_oc(s) − R·I  (I the battery current)           (M2)
    s(t) = s₀ − Q(t)/C,   Q = ∫I dt,   C = capacity_ah·3600 C (the capacity at the rated rate)  (M3)
        The open-circuit voltage follows this plain charge: at rest the cells' voltage is set by
        the acid's concentration, which Faraday's law ties to the charge passed, whatever the rate.
    Peukert: at a constant current I a full battery lasts  t = H·(C_Ah/(I·H))^k  hours,
        H = rated_hours, k = the Peukert exponent. Equivalently the charge drawn is weighted:
        dQ_p/dt = I·(I/I_H)^(k−1),  I_H = C_Ah/H (the rated current, 0.9 A for 18 Ah at 20 h), and
        the battery is empty (can no longer hold its voltage at the rates drawn) when Q_p = C, so
        s_p = s₀ − Q_p/C is the charge still available at those rates; it gives back the runtime
        above for constant I:
        C/(I·(I/I_H)^(k−1)) = H·(C_Ah/(I·H))^k · 3600 s.  A charging (negative) current is counted
        plain, dQ_p/dt = I (no charge efficiency is modelled).                                 (M4)
        The plain charge is dQ/dt = I; both are reported (Ah = C/3600).
    Energy: the cells give E_oc = ∫V_oc·I dt, the bus receives E_bus = ∫V·I dt, the resistance
        burns E_R = ∫I²R dt, and by (M2) E_oc = E_bus + E_R at every instant.                  (M5)

Defaults and where each comes from:
  - capacity 18 Ah: frc-docs, Robot Battery Basics ("a single 12V 18Ah SLA ... AGM battery"),
    https://docs.wpilib.org/en/stable/docs/hardware/hardware-basics/robot-battery.html
    (wpilibsuite/frc-docs source/docs/hardware/hardware-basics/robot-battery.rst at 0173fbc); the 20 h rate is
    the rating of the NP18-12 the frc-docs brownout page links (farnell.com/datasheets/575631.pdf:
    its name, 18 Ah, is the 20-hour capacity).
  - internal resistance 0.015 Ω: the same frc-docs page, "Ideal internal resistance should be less
    than 0.015 Ohms. The manufacturer specification for most batteries is 0.011 Ohms. If a battery
    gets higher than 0.020 Ohms it is a good idea to consider not using that battery".
  - wiring resistance 0 Ω: no published figure; the user enters the leads, breaker and PDH.
  - Peukert exponent 1.25: Xantrex LINK 2000 battery monitor manual, p. 24, "a default value of n
    equal to 1.25 which is typical for many batteries"
    (https://manualsdump.com/en/manuals/xantrex_technology-link_2000/272859/25). Cross-check with
    the frc-docs brownout page: the NP18-12 "at 3CA continuous load (54A) ... can be continuously
    run for over 6 minutes" (to 7 V); (M4) with k = 1.25 gives 20·(18/(54·20))^1.25 h = 0.1198 h
    = 7.2 min, and "over 6 minutes" needs k ≤ ln(20/0.1)/ln(54·20/18) = 1.294, so the default is
    consistent with it. Measured FRC values run 1.1-1.25: an input.
  - open-circuit voltage against charge: per cell V = SG + 0.84 (SG the electrolyte's specific
    gravity) with SG 1.280 fully charged, about 1.250 at half charge and 1.150 discharged, all from
    http://electrapk.com/lead-acid-battery-specific-gravity/ ; six cells give
    (0, 11.94 V), (0.5, 12.54 V), (1, 12.72 V). It agrees with frc-docs' "Depleted batteries will
    read between 11.7 and 12.5 volts on an idle robot" (the 13-14 V it quotes for a charged battery
    is surface charge, gone within the first seconds of load). An input: a measured table replaces it.
  - starting charge 1.0 (a freshly charged battery).
"""

from __future__ import annotations

from dataclasses import dataclass

from gearhead.core.errors import InputError
from gearhead.core.match.checks import number, rows

AH = 3600.0  # coulombs per amp-hour
OCV_TABLE = ((0.0, 11.94), (0.5, 12.54), (1.0, 12.72))  # (state of charge, V): see the docstring


@dataclass(frozen=True)
class Battery:
    """A lead-acid battery (M1-M5). Every field is checked when it is made (InputError names it)."""

    ocv_table: tuple[tuple[float, float], ...] = OCV_TABLE
    resistance: float = 0.015  # Ω, the battery's own
    wiring_resistance: float = 0.0  # Ω, leads, main breaker, PDH
    capacity_ah: float = 18.0
    rated_hours: float = 20.0
    peukert: float = 1.25
    start_soc: float = 1.0

    def __post_init__(self):
        table = rows("battery.ocv_table", self.ocv_table)
        if len(table) < 1:
            raise InputError("battery.ocv_table", "needs at least one row (state of charge, volts)")
        clean = []
        for i, (s, v) in enumerate(table):
            clean.append(
                (
                    number(f"battery.ocv_table[{i}].soc", s, low=0.0, high=1.0),
                    number(f"battery.ocv_table[{i}].volts", v, low=0.0, low_open=True, high=100.0),
                )
            )
        for i in range(1, len(clean)):
            if clean[i][0] <= clean[i - 1][0]:
                raise InputError("battery.ocv_table", f"row {i}: states of charge must increase")
            if clean[i][1] < clean[i - 1][1]:
                raise InputError(
                    "battery.ocv_table", f"row {i}: the voltage must not fall as the charge rises"
                )
        object.__setattr__(self, "ocv_table", tuple(clean))
        for name, low, low_open, high in (
            ("resistance", 0.0, False, 10.0),
            ("wiring_resistance", 0.0, False, 10.0),
            ("capacity_ah", 0.0, True, 1e4),
            ("rated_hours", 0.0, True, 1e4),
            ("peukert", 1.0, False, 2.0),
            ("start_soc", 0.0, False, 1.0),
        ):
            object.__setattr__(
                self,
                name,
                number(f"battery.{name}", getattr(self, name), low=low, low_open=low_open, high=high),
            )
        if self.resistance + self.wiring_resistance <= 0:
            raise InputError("battery.resistance", "the battery and wiring resistances cannot both be 0")

    @property
    def R(self) -> float:
        """The total series resistance (M2), Ω."""
        return self.resistance + self.wiring_resistance

    @property
    def capacity(self) -> float:
        """C of (M3), coulombs."""
        return self.capacity_ah * AH

    @property
    def rated_current(self) -> float:
        """I_H of (M4), A."""
        return self.capacity_ah / self.rated_hours

    def ocv(self, soc: float) -> float:
        """V_oc(s) (M1): linear between the table's rows, the end rows held outside."""
        table = self.ocv_table
        if soc <= table[0][0]:
            return table[0][1]
        if soc >= table[-1][0]:
            return table[-1][1]
        for (s0, v0), (s1, v1) in zip(table, table[1:]):
            if soc <= s1:
                return v0 + (v1 - v0) * (soc - s0) / (s1 - s0)
        return table[-1][1]  # not reached: soc < table[-1][0] here

    def peukert_rate(self, current: float) -> float:
        """dQ_p/dt (M4) at battery current `current` (A); a charging current counts plain."""
        if current <= 0:
            return current
        return current * (current / self.rated_current) ** (self.peukert - 1.0)

    def soc(self, charge: float) -> float:
        """s₀ − charge/C: the state of charge s (M3) after the plain charge `charge` (C) was drawn,
        or the available fraction s_p (M4) after the Peukert-weighted one."""
        return self.start_soc - charge / self.capacity

    def runtime(self, current: float) -> float:
        """Seconds a full battery lasts at a constant `current` (M4): H·(C_Ah/(I·H))^k hours."""
        i = number("current", current, low=0.0, low_open=True)
        return self.rated_hours * (self.capacity_ah / (i * self.rated_hours)) ** self.peukert * AH
