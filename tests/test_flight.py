"""Flight effects: each against a closed form of its own (drag alone, Magnus alone, vacuum)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core.sim.flight import aim, fly
from gearhead.core.sim.flight import air_with as Air

G = 9.80665


def vacuum_height(h, th, v, d, g=G):
    return h + d * math.tan(th) - g * d * d / (2 * v * v * math.cos(th) ** 2)  # seed (61)


def test_tiny_drag_reproduces_the_vacuum_closed_form():
    f = fly(Air(G, 1e-12, 0.0), 0.5, math.radians(50), 9.0, 5.0, 1e-10)
    assert f.height == pytest.approx(vacuum_height(0.5, math.radians(50), 9.0, 5.0), rel=1e-9)


def test_drag_alone_horizontal_closed_form():
    """g = 0: vx = v0/(1 + k v0 t), so the time to reach d is (e^{kd} − 1)/(k v0)."""
    k, v0, d = 0.05, 12.0, 8.0
    f = fly(Air(0.0, k, 0.0), 1.0, 0.0, v0, d, 1e-11)
    assert f.t == pytest.approx((math.exp(k * d) - 1) / (k * v0), rel=1e-9)
    assert f.speed == pytest.approx(v0 * math.exp(-k * d), rel=1e-9)
    assert f.height == pytest.approx(1.0, abs=1e-12)


def test_magnus_alone_is_a_circle():
    """g = 0, no drag: constant speed, curvature k_m, so a circle of radius 1/k_m; backspin curves up."""
    km, v0, d = 0.1, 10.0, 4.0
    R = 1 / km
    f = fly(Air(0.0, 0.0, km), 0.0, 0.0, v0, d, 1e-11)
    assert f.height == pytest.approx(R - math.sqrt(R * R - d * d), rel=1e-9)
    assert f.angle == pytest.approx(math.asin(d / R), rel=1e-9)
    assert f.speed == pytest.approx(v0, rel=1e-10)


def test_drag_lowers_and_backspin_raises_the_ball():
    base = fly(Air(G, 0.0, 0.0), 0.5, 0.8, 9.0, 5.0, 1e-9).height
    assert fly(Air(G, 0.03, 0.0), 0.5, 0.8, 9.0, 5.0, 1e-9).height < base
    assert fly(Air(G, 0.0, 0.02), 0.5, 0.8, 9.0, 5.0, 1e-9).height > base
    assert fly(Air(G, 0.0, -0.02), 0.5, 0.8, 9.0, 5.0, 1e-9).height < base


def test_falling_short_is_reported_not_extrapolated():
    f = fly(Air(G, 0.5, 0.0), 0.5, 0.3, 3.0, 50.0, 1e-8)
    assert not f.reached and f.x_end < 50.0 and f.height == pytest.approx(0.0, abs=1e-9)


@settings(max_examples=25, deadline=None)
@given(th=st.floats(0.3, 1.1), v=st.floats(7, 15), kd=st.floats(0, 0.04), km=st.floats(-0.01, 0.02))
def test_aim_inverts_fly(th, v, kd, km):
    a = Air(G, kd, km)
    f = fly(a, 0.6, th, v, 4.0, 1e-11)
    if not f.reached or f.angle > th - 0.05:
        return
    th2, v2, _ = aim(a, 0.6, f.height, 4.0, f.angle, 1e-11, (th + 0.05, v * 1.05))
    assert th2 == pytest.approx(th, abs=1e-7) and v2 == pytest.approx(v, rel=1e-7)


def test_landing_time_over_a_batch_is_the_scalar_one_element_by_element():
    """The batch (trebuchet's 1640 throws) and a single throw use one (V3): each element of the array
    form takes the branch the scalar takes, bit for bit, falling throws included (there the textbook
    (q + √(q² + 2gh))/g cancels: q = −100 m/s from 1 µm up lands after 1e-8 s, not after 0)."""
    import numpy as np

    from gearhead.core.sim.flight import landing_time

    q = np.array([30.0, 0.0, -0.5, -100.0, -100.0, 3.0])
    h = np.array([2.0, 1.0, 0.25, 1e-6, 50.0, 0.0])
    batch = landing_time(q, h, 9.81)
    for k in range(len(q)):
        assert batch[k] == landing_time(float(q[k]), float(h[k]), 9.81)
    # the falling throw from 1 µm: t = h/|q| to first order (t = 2h/(√(q² + 2gh) − q))
    assert batch[3] == pytest.approx(1e-8, rel=1e-9)
    # and a throw up lands when y(t) = h + q·t − g·t²/2 = 0
    t = batch[0]
    assert 2.0 + 30.0 * t - 9.81 * t * t / 2 == pytest.approx(0.0, abs=1e-12)
