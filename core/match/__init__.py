"""The match: a whole robot on one battery (issue 43), the foundations in pure computation.

    battery.py   the lead-acid battery: open-circuit voltage against state of charge, resistance,
                 capacity, Peukert-weighted charge, energy                              (M1-M5)
    bus.py       the bus voltage from every supply current together: affine (motor) loads in closed
                 form, constant-power (stator-limited) loads as a quadratic whose branch is followed
                 continuously in time                                                  (M6-M9)
    brownout.py  the roboRIO's brownout as a state machine with hysteresis, crossings located in
                 time                                                                 (M10-M11)
    breaker.py   breakers: a trip-time table and a first-order thermal state calibrated to reproduce
                 it exactly from cold                                                 (M12-M15)
    timeline.py  a match integrated over synthetic loads, and its outputs             (M16-M18)
    mechanisms.py  the elevator's and arm's moves (core.sim.motion), the sprint, the flywheel's
                 spin-up and burst integrated together on one bus: the duty rule as affine,
                 constant-power or constant-current loads, the sprint's slip, brownout coasting
                 inside their equations, channel breakers, holding at the goal, hard stops; one
                 alone is its card                                                     (B1-B12)

SI inside: volts, amperes, ohms, seconds, coulombs, joules (amp-hours and watt-hours only in the
outputs that name them). The workbook's [match] table (core/workbook/match.py) and `gearhead match`
run mechanisms.py; not yet in the app.
"""
