"""Load samples that keep a rule's order: piecewise forms, hat averages, one-sided data at t = 0."""

import numpy as np
import pytest

from unilateral.loads import (
    Constant,
    GroundMotion,
    HalfSine,
    LoadHistory,
    Ramp,
    Rectangular,
    Tabulated,
    Triangular,
)

FUNCTIONS = [
    Rectangular(2.0, t_start=0.1, t_end=0.3),
    Triangular(1.0, t_start=0.1, t_peak=0.2, t_end=0.4),
    Triangular(-2.0, t_peak=0.0, t_end=1.0),
    Triangular(1.0, t_start=0.2, t_peak=1.0, t_end=1.0),
    HalfSine(3.0, t_start=0.05, duration=0.2),
    Constant(4.0),
    Ramp(0.5, 2.0),
    Tabulated([0.0, 1.0, 2.0], [1.0, 1.0, 0.5]),
    Tabulated([0.0, 1.0, 2.0], [1.0, 1.0, 0.5], outside="hold"),
    GroundMotion(0.01, np.sin(0.1 * np.arange(150)) + 0.5),
]


@pytest.mark.parametrize("f", FUNCTIONS, ids=lambda f: type(f).__name__)
def test_piecewise_form_equals_the_function_away_from_breakpoints(f):
    p = f.piecewise()
    t = np.linspace(-0.5, 2.5, 20001)
    t = t[np.min(np.abs(t[:, None] - p.edges[None, :]), axis=1, initial=1.0) > 1e-9]
    np.testing.assert_allclose(p.evaluate(t), f(t), rtol=0, atol=1e-12)
    # the derivative of the form is that of the function (central differences)
    h = 1e-6
    fd = (f(t + h) - f(t - h)) / (2 * h)
    smooth = np.min(np.abs(t[:, None] - p.edges[None, :]), axis=1, initial=1.0) > 2 * h
    np.testing.assert_allclose(p.evaluate(t[smooth], derivative=1), fd[smooth], rtol=1e-6, atol=1e-5)


def test_breakpoints_and_one_sided_limits():
    rect = Rectangular(2.0, t_start=0.1, t_end=0.3)
    np.testing.assert_array_equal(rect.breakpoints, [0.1, 0.3])
    assert rect.limits(0.1) == (0.0, 2.0) and rect.limits(0.3) == (2.0, 0.0)
    assert Triangular(1.0, t_start=0.1, t_peak=0.2, t_end=0.4).limits(0.2) == pytest.approx((1.0, 1.0))
    assert Constant(4.0).limits(0.0) == (4.0, 4.0) and Constant(4.0).breakpoints.size == 0
    assert Tabulated([0.0, 1.0], [1.0, 2.0]).limits(0.0) == (0.0, 1.0)          # jumps at 0
    assert Tabulated([0.0, 1.0], [1.0, 2.0], outside="hold").limits(0.0) == (1.0, 1.0)
    gm = GroundMotion(0.01, [0.3, 0.1, -0.2])
    assert gm.limits(0.0) == (0.0, 0.3)
    assert gm.limits(0.02) == pytest.approx((-0.2, 0.0), abs=1e-15)


def test_hat_samples_are_exact_for_piecewise_linear_loads_and_average_jumps_on_the_grid():
    dt, N = 0.01, 100
    t = dt * np.arange(N + 1)
    ramp = Ramp(0.5, 2.0)                                  # kink at 0.5 = grid point 50
    Q = ramp.grid_samples(dt, N)
    smooth = np.ones(N + 1, bool)
    smooth[[0, 50]] = False
    np.testing.assert_allclose(Q[smooth], ramp(t)[smooth], atol=1e-13)
    # at a kink the hat average is off by dt * (slope jump) / 6: an O(dt^2) impulse, local
    assert Q[50] == pytest.approx(2.0 - dt * 4.0 / 6, abs=1e-13)
    assert Q[0] == pytest.approx(4.0 * dt / 3, abs=1e-13)  # one-sided half hat over [0, dt]
    rect = Rectangular(2.0, t_start=0.2, t_end=0.5)        # both edges on the grid
    Q = rect.grid_samples(dt, N)
    assert Q[20] == pytest.approx(1.0) and Q[50] == pytest.approx(1.0)
    np.testing.assert_allclose(Q[21:50], 2.0, atol=1e-13)
    np.testing.assert_allclose(rect.grid_samples(dt, N, "point")[[20, 50]], [1.0, 1.0])


@pytest.mark.parametrize("sampling", ["hat", "box"])
def test_samples_deliver_the_exact_impulse_of_a_pulse_between_grid_points(sampling):
    """Trapezoidal sums of the samples reproduce int q to every grid point past the pulse."""
    dt, N = 0.01, 60
    rect = Rectangular(2.0, t_start=0.1234, t_end=0.3417)
    Q = rect.grid_samples(dt, N, sampling)
    trapezoid = dt * (np.cumsum(Q) - 0.5 * (Q[0] + Q))
    assert trapezoid[-1] == pytest.approx(2.0 * (0.3417 - 0.1234), rel=1e-13)
    point = rect.sample if hasattr(rect, "sample") else rect
    P = point(dt * np.arange(N + 1))
    assert abs(dt * (P.sum() - 0.5 * (P[0] + P[-1])) - 2.0 * 0.2183) > 1e-3   # point values do not


def test_hat_samples_are_second_order_for_smooth_loads():
    f = HalfSine(1.0, duration=1.0)
    errs = []
    for N in (50, 100, 200):
        dt = 1.0 / N
        t = dt * np.arange(N + 1)
        errs.append(np.max(np.abs(f.grid_samples(dt, N)[1:-1] - f(t)[1:-1])))   # off the kinks
    assert np.log2(errs[0] / errs[1]) == pytest.approx(2.0, abs=0.1)
    assert np.log2(errs[1] / errs[2]) == pytest.approx(2.0, abs=0.1)


def test_one_sided_start_and_static_preload():
    q = LoadHistory([0.0, -400.0], [([1.0, 0.0], Rectangular(200.0, t_end=0.1)),
                                    ([0.0, 1.0], Constant(-100.0)),
                                    ([1.0, 1.0], Tabulated([0.0, 1.0], [5.0, 5.0]))])
    Q, q0 = q.grid_samples(1e-3, 200)
    np.testing.assert_allclose(q0, [0.0, -500.0])                      # q(0-): pulses off
    np.testing.assert_allclose(Q[0], [205.0, -495.0])                   # q(0+)
    np.testing.assert_allclose(Q[50], [205.0, -495.0])
    np.testing.assert_allclose(Q[100], [105.0, -495.0])                 # mean at the end t = 0.1
    np.testing.assert_allclose(Q[150], [5.0, -495.0])
    # __call__ and sample() keep the point values
    np.testing.assert_allclose(q(0.0), [5.0, -495.0])
    np.testing.assert_allclose(q.sample(np.array([0.0, 0.1]))[1], [205.0, -495.0])


def test_a_plain_callable_term_is_point_sampled():
    q = LoadHistory([0.0], [([1.0], lambda t: np.cos(t))])
    Q, q0 = q.grid_samples(0.1, 10)
    np.testing.assert_allclose(Q[:, 0], np.cos(0.1 * np.arange(11)))
    assert q0[0] == 1.0
    with pytest.raises(ValueError, match=r"terms\[0\].*without a piecewise form"):
        q.piecewise_terms()


def test_ground_motion_samples_are_exact_between_record_samples():
    gm = GroundMotion(0.01, np.sin(0.1 * np.arange(300)))
    dt, N = 0.005, 600                                 # the record's kinks are on the grid
    Q = gm.grid_samples(dt, N)
    t = dt * np.arange(N + 1)
    inner = (t > 0.0) & (t < gm.duration - 1e-12)
    # hat averages of a piecewise-linear function at its kinks differ by the curvature term only
    kinks = inner & (np.arange(N + 1) % 2 == 0)
    between = inner & (np.arange(N + 1) % 2 == 1)
    np.testing.assert_allclose(Q[between], gm(t[between]), atol=1e-13)     # exact between kinks
    # at a kink: off by dt * (slope jump) / 6
    slopes = np.diff(gm.acceleration) / gm.dt
    jump = np.diff(slopes)[: kinks.sum()]
    np.testing.assert_allclose(Q[kinks] - gm(t[kinks]), dt * jump / 6, atol=1e-12)
