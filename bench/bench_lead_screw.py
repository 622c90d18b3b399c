"""Lead screw figures (printed, never asserted): warm solve time, and
the accuracy of the near-locking raise torque against a 40-digit reference."""

from __future__ import annotations

import math

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)


def main() -> None:
    import mpmath as mp

    from gearhead.core.model import parse_inputs, solve
    from gearhead.core.registry import get

    print(
        f"  lead_screw default           {median_seconds(lambda: solve('lead_screw', {}), 300) * 1e6:8.1f} µs"
    )
    print(
        f"  lead_screw locked            {median_seconds(lambda: solve('lead_screw', {'starts': 16, 'friction': 1}), 300) * 1e6:8.1f} µs"
    )
    # near-locking: the denominator of (31) is 10^-k of its terms; error grows like 10^k·ulp
    mp.mp.dps = 40
    mu_lock = math.pi * (0.0127 - 0.00127) / (16 * 0.00254)
    base = dict(diameter="0.0127 m", pitch="0.00254 m", starts=16, thread_angle=0, force="1000 N")
    for k in (3, 6, 9, 12):
        raw = dict(base, friction=repr(mu_lock * (1 - 10.0**-k)))
        v = parse_inputs(get("lead_screw"), raw)[0]
        F, d, p, mu = (mp.mpf(v[x]) for x in ("force", "diameter", "pitch", "friction"))
        dm, l = d - p / 2, 16 * p
        ref = F * dm / 2 * (mp.pi * mu * dm + l) / (mp.pi * dm - mu * l)
        got = solve("lead_screw", raw).outputs["raise_torque"].value
        print(f"  raise torque 1e-{k:<2} from locking: rel. error {float(abs(got - ref) / ref):.1e}")
