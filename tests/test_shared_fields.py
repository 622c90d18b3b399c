"""One field name, one declaration: a field that two calculators both declare has the same label,
quantity and unit, limits, help and choices in both (issue 42 item 3: the flywheel's LQR and loop
fields had drifted from core.sim.motion.feedback_fields: r_volts at most 1000 V there against 100,
q_velocity 1e6 against 3.9e5, other labels and help). The names that differ are listed below, each
with why; the lists only shrink (a listed name that comes to agree fails here until removed)."""

from collections import defaultdict

from gearhead.core import registry

# Declared once by a shared function that takes the calculator's own coordinate (a length or an
# angle, a speed or an angular speed): quantity, unit and default follow the coordinate, the
# label, limits (as numbers in that unit) and help do not.
PER_COORDINATE = {
    "q_position",  # core.sim.motion.feedback_fields
    "q_velocity",  # core.sim.motion.feedback_fields (the flywheel's velocity loop too)
    "feedback_kd",  # core.sim.profiled.profile_fields
    "max_velocity",  # core.sim.profiled.profile_fields
    "max_acceleration",  # core.sim.profiled.profile_fields
    "settle_tolerance",  # core.sim.profiled.profile_fields
}

# The same name for different things in different calculators: each its own declaration.
DIFFERENT_MEANING = {
    "mode": "each calculator's own choice of what to solve (the flywheel's: how the inertia is given)",
    "effects": "each scene's own set of effects",
    "feedback": "the flywheel's velocity loop has one gain (kP), the mechanisms' position loop kP and kD",
    "feedback_kp": "volts per speed error in the flywheel's velocity loop, per position error in a position loop",
    "inertia_model": "the sprint's yaw inertia against the arm's about its pivot (other choices)",
    "moment_of_inertia": "the sprint's robot yaw inertia against the arm's about its pivot",
    "arm_mass": "the arm mechanism's arm against the trebuchet's throwing arm",
    "force": "the beam's load against the lead screw's axial load",
    "torque": "the motor's operating torque against the beam's torsion",
    "friction": "the lead screw's thread friction coefficient against the drivetrain's wheel friction",
    "pitch": "the lead screw's thread pitch against a chain or belt pitch",
    "teeth_1": "a sprocket or pulley against a gear",
    "teeth_2": "a sprocket or pulley against a gear",
    "distance": "the sprint's run against the projectile's distance to the target",
    "wheel_diameter": "a drive wheel (drivetrain, sprint) against a flywheel",
    "ratio": "each calculator's reduction, over the range its mechanism uses",
    "voltage": "the applied voltage (each calculator's default and help) against the battery's at rest",
    "ball_diameter": "the projectile's ball (any size) against a flywheel's game piece",
    "ball_mass": "the projectile's ball against a flywheel's game piece (0: no ball)",
    "release_height": "the projectile's release height against the flywheel's above the target",
    "release_angle": "the projectile's any angle against the trebuchet's release (0-89 deg)",
}

# The same meaning, declared apart in calculators outside issue 42 item 3's flywheel change (for
# whoever owns them to bring together): the test fails on any other name that drifts.
DRIFT_ELSEWHERE = {
    "battery_resistance": "label 'Battery resistance' and no max in drivetrain",
    "efficiency": "help worded per calculator",
    "motor_count": "label per calculator",
    "air_density": "unit spelt kg/m^3 and kg/m**3, max 2 and 20 (projectile, trebuchet)",
    "drag_coefficient": "help worded per calculator (projectile, trebuchet)",
}


def signature(f, per_coordinate: bool) -> dict:
    """What must agree between two declarations of one name."""
    out = {
        "label": f.label,
        "min": f.min,
        "max": f.max,
        "min_exclusive": f.min_exclusive,
        "max_exclusive": f.max_exclusive,
        "integer": f.integer,
        "boolean": f.boolean,
        "flags": f.flags,
        "choices": f.choices,
        "choice_labels": f.choice_labels,
        "help": f.help,
    }
    if not per_coordinate:
        out.update(quantity=f.quantity, unit=f.unit)
    return out


def disagreements() -> dict[str, dict[str, dict]]:
    """name -> {what differs: {calculator: its value}} over every registered calculator."""
    declared: dict[str, dict[str, object]] = defaultdict(dict)
    for cid, calc in registry.calculators().items():
        for f in calc.fields:
            declared[f.name][cid] = f
    out = {}
    for name, by in declared.items():
        if len(by) < 2:
            continue
        sigs = {cid: signature(f, name in PER_COORDINATE) for cid, f in by.items()}
        first = next(iter(sigs.values()))
        differ = {
            k: {cid: s[k] for cid, s in sigs.items()}
            for k in first
            if len({repr(s[k]) for s in sigs.values()}) > 1
        }
        if differ:
            out[name] = differ
    return out


def test_no_field_name_is_declared_two_ways():
    listed = set(DIFFERENT_MEANING) | set(DRIFT_ELSEWHERE)
    drifted = {name: d for name, d in disagreements().items() if name not in listed}
    assert not drifted, "declared with different words or limits in two calculators: " + "; ".join(
        f"{name}: {d}" for name, d in sorted(drifted.items())
    )


def test_the_lists_only_name_fields_that_still_differ():
    differ = disagreements()
    stale = sorted(n for n in set(DIFFERENT_MEANING) | set(DRIFT_ELSEWHERE) if n not in differ)
    assert not stale, f"these now agree everywhere: remove them from the lists: {stale}"
    assert not PER_COORDINATE & (set(DIFFERENT_MEANING) | set(DRIFT_ELSEWHERE))


def test_the_flywheel_declares_the_loop_fields_motion_does():
    """The flywheel's period, delay and LQR tolerances are core.sim.motion.feedback_fields' (its
    speed in rpm), shown with the velocity loop; LQR's only with feedback = lqr."""
    from gearhead.core.sim import motion

    fly = {f.name: f for f in registry.get("flywheel").fields}
    elevator = {f.name: f for f in registry.get("elevator").fields}
    for name in ("q_velocity", "r_volts", "control_period", "sensor_delay"):
        assert signature(fly[name], True) == signature(elevator[name], True), name
    assert fly["r_volts"].max == 100 and fly["q_velocity"].max == 3.9e5 and fly["q_velocity"].unit == "rpm"
    assert fly["control_period"].when == (("control", ("velocity_loop",)),)
    assert fly["r_volts"].when == (("control", ("velocity_loop",)), ("feedback", ("lqr",)))
    shared = {f.name for f in motion.feedback_fields(None, "", 0, "angular_speed", "rpm", 100)}
    assert shared == {"q_velocity", "r_volts", "control_period", "sensor_delay"}
