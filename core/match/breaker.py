"""Breakers: the 120 A main and each mechanism's channel (40 A by default), each with a trip-time
table (multiple of the rating → seconds to trip from cold) and a thermal state calibrated to it.

The model is a first-order thermal state θ (θ = 1 trips), heated by a calibrated function of the
current's multiple of the rating x = |I|/I_r:

    dθ/dt = (g(x) − θ)/τ,   the breaker trips when θ reaches 1                                (M12)

Why this and not a plain I²t accumulator: a thermal breaker's bimetal both heats and cools, so a
breaker that carried 150 % for a while and then rests must recover; an accumulator that only sums
never recovers, and one that sums 1/T(x) (Miner's rule) has no cooling law at all. (M12) is the
bimetal's own lumped heat balance (heat in ∝ g, loss ∝ θ), with g calibrated so the table holds
exactly. From cold (θ = 0) at a constant x:

    θ(t) = g(x)·(1 − e^{−t/τ}),   so it trips at  t_trip = −τ·ln(1 − 1/g(x))  where g(x) > 1   (M13)

Calibration: for the table's rows (x_i, T_i) (x_i > 1 rising, T_i falling), between rows T(x) is
linear in log x–log T, and beyond the last row T ∝ x⁻² (adiabatic: I²t constant). Setting t_trip = T:

    g(x) = 1/(1 − e^{−T(x)/τ})   for x ≥ x₀ (the first row),                                  (M14)

which reproduces every row exactly whatever τ is. Below the first row the breaker is pure Joule
heating, g(x) = x² (so θ → x², and a current at or under the rating, x ≤ 1, never trips), and τ is
the one that joins the two at x₀ (g(x₀) = x₀²):

    τ = T₀ / (−ln(1 − 1/x₀²))                                                                  (M15)

A constant piece of current of length Δt moves θ exactly: θ ← g + (θ − g)·e^{−Δt/τ} (`advance`),
which is how a varying load's state is worked by hand in the tests.

Defaults: ratings 120 A (main) and 40 A (channel), the issue's (the FRC robot rules' main and
branch breakers). Trip tables: none. The corpora searched (frc-docs, the Eaton/Bussmann automotive
catalogues at dtsheet.com/doc/1425909 and datasheet.wiki's 32006-B22 transportation catalogue, the
Bussmann series 120 SHORTSTOP sheet, and searches for the Snap Action MX5 and VB3-A) hold no curve
with numbers for the FRC breakers (the series 120 sheet draws a "time vs. percent of rated current"
chart with no readable values), so the default table is empty and a breaker is checked only on a
table the user enters (`Breaker.calibrated` is False without one).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gearhead.core.errors import InputError
from gearhead.core.match.checks import number, rows

MAIN_RATING = 120.0  # A
CHANNEL_RATING = 40.0  # A


@dataclass(frozen=True)
class Breaker:
    """A breaker of `rating` A with a trip table ((multiple, seconds), ...) (M12-M15)."""

    rating: float = CHANNEL_RATING
    table: tuple[tuple[float, float], ...] = ()
    name: str = "breaker"

    def __post_init__(self):
        field = f"{self.name}"
        object.__setattr__(
            self, "rating", number(f"{field}.rating", self.rating, low=0.0, low_open=True, high=1e5)
        )
        clean = []
        for i, (x, t) in enumerate(rows(f"{field}.trip_table", self.table)):
            clean.append(
                (
                    number(f"{field}.trip_table[{i}].multiple", x, low=1.0, low_open=True, high=1e3),
                    number(f"{field}.trip_table[{i}].seconds", t, low=0.0, low_open=True, high=1e7),
                )
            )
        for i in range(1, len(clean)):
            if clean[i][0] <= clean[i - 1][0]:
                raise InputError(f"{field}.trip_table", f"row {i}: the multiples of the rating must rise")
            if clean[i][1] >= clean[i - 1][1]:
                raise InputError(f"{field}.trip_table", f"row {i}: a larger current must trip sooner")
        object.__setattr__(self, "table", tuple(clean))

    @property
    def calibrated(self) -> bool:
        """Whether there is a table to check against (else no trip is predicted)."""
        return bool(self.table)

    @property
    def tau(self) -> float:
        """τ (M15), s."""
        x0, t0 = self.table[0]
        return t0 / -math.log1p(-1.0 / (x0 * x0))

    def table_time(self, x: float) -> float:
        """T(x) for x ≥ the first row: log-log between rows, x⁻² beyond the last (M14)."""
        tab = self.table
        if x >= tab[-1][0]:
            xl, tl = tab[-1]
            return tl * (xl / x) ** 2
        for (x0, t0), (x1, t1) in zip(tab, tab[1:]):
            if x <= x1:
                f = math.log(x / x0) / math.log(x1 / x0)
                return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
        return tab[0][1]  # x == the first row

    def heating(self, current: float) -> float:
        """g(x) of (M12), x = |current|/rating: x² below the first row, (M14) from it."""
        x = abs(current) / self.rating
        x0 = self.table[0][0]
        if x < x0:
            return x * x
        return -1.0 / math.expm1(-self.table_time(x) / self.tau)

    def rate(self, theta: float, current: float) -> float:
        """dθ/dt (M12)."""
        return (self.heating(current) - theta) / self.tau

    def advance(self, theta: float, current: float, dt: float) -> float:
        """θ after `dt` s at a constant `current` (the exact solution of M12)."""
        g = self.heating(current)
        return g + (theta - g) * math.exp(-dt / self.tau)

    def trip_time(self, current: float) -> float:
        """Seconds to trip from cold at a constant `current` (M13); math.inf if it never does."""
        g = self.heating(current)
        if g <= 1.0:
            return math.inf
        return -self.tau * math.log1p(-1.0 / g)
