"""Exact unit factors and constants used inside the equations (SI per unit), defined once.

Inputs and outputs go through pint (core.units); these are for equations that need a fixed
factor (a seed's imperial constant, standard gravity). Values are the exact definitions.
"""

import math

INCH = 0.0254  # m per inch (exact, 1959)
FOOT = 12 * INCH  # m per foot
LB = 0.45359237  # kg per pound (exact, 1959)
G0 = 9.80665  # m/s², standard gravity (exact, CGPM 1901)
LBF = LB * G0  # N per pound-force (4.4482216152605)
PSI = LBF / INCH**2  # Pa per psi (6894.757293168361)
RPM = 2 * math.pi / 60  # rad/s per rpm
