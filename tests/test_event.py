"""The exact event-driven reference march (unilateral.march.event)."""

import numpy as np
import pytest

import unilateral as ul
from conftest import GRAVITY, MASS, bouncing_exact, rocking_model
from unilateral.initial import static_state
from unilateral.lcp import get_lcp_solver
from unilateral.loads import LoadHistory, Ramp, Rectangular
from unilateral.march.event import march_event

BOUNCE = dict(m=2.0, k=2000.0, g=10.0, V0=1.0)
EX, EY = np.eye(5)[0], np.eye(5)[1]


def rocking_pulses():
    """Gravity and two opposite horizontal pulses: repeated uplift of both edges (test_solve.py)."""
    return LoadHistory(-MASS * GRAVITY * EY, [(300.0 * EX, Rectangular(1.0, t_end=0.1)),
                                             (-300.0 * EX, Rectangular(1.0, t_start=0.5, t_end=0.6))])


def test_bouncing_mass_closed_form():
    m, k, g, V0 = BOUNCE.values()
    model = ul.Model(M=[[m]], K=[[k]], F=[[k]], H=[[k]])
    res = ul.solve(model, LoadHistory([-m * g]), dt=1e-3, t_end=1.0, method="event",
                      initial={"u0": [-m * g / k], "udot0": [V0], "v0": [0.0]})
    exact, info = bouncing_exact(res.t, **BOUNCE)
    assert np.max(np.abs(res.u[:, 0] - exact)) <= 1e-12 * info["peak_uplift"]
    # events: lift-off at t_up, then every period a landing and a lift-off
    T, T_flight = info["period"], 2 * np.sqrt(V0 ** 2 - (m * g / k * np.sqrt(k / m)) ** 2) / g
    lift = info["t_liftoff"] + T * np.arange(4)
    expected = np.sort(np.concatenate([lift, lift[:3] + T_flight]))
    np.testing.assert_allclose(res.stats["event_times"], expected, rtol=0, atol=1e-12)
    assert list(res.stats["event_kinds"]) == ["open", "close"] * 3 + ["open"]
    flying = res.v[:, 0] > 0
    np.testing.assert_allclose(res.v[flying, 0], res.u[flying, 0], rtol=0, atol=1e-15)
    assert np.all(res.psi[flying] == 0.0) and np.all(res.psi <= 0.0)
    np.testing.assert_allclose(res.v.max(), info["peak_uplift"], rtol=1e-6)


def test_event_equals_direct_stepping_as_dt_goes_to_zero():
    model, load = rocking_model(kelvin=False), rocking_pulses()
    T = 1.0
    errors = []
    for dt in (1e-3, 5e-4, 2.5e-4):
        N = int(round(T / dt))
        ref = ul.solve(model, load, dt=dt, t_end=T, method="event")
        Q, q0 = load.grid_samples(dt, N)
        init = static_state(model, q0, get_lcp_solver("bpp"))
        sol = ul.solve(model, Q, dt=dt, t_end=T, method="direct", rule="trapezoidal",
                       initial={"u0": init.u, "v0": init.v})
        assert sol.stats["contact_changes"] == ref.stats["events"] == 4
        errors.append(max(np.max(np.abs(sol.u - ref.u)) / np.max(np.abs(ref.u)),
                          np.max(np.abs(sol.v - ref.v)) / np.max(ref.v)))
    assert errors[-1] < 1e-4
    assert errors[0] / errors[1] > 3.5 and errors[1] / errors[2] > 3.5          # second order
    # the static start is the seed's value and the reference satisfies complementarity exactly
    np.testing.assert_allclose(ref.u[0, 3], -MASS * GRAVITY / (3 * 200e3), rtol=1e-6)
    assert np.all(ref.v >= 0) and np.all(ref.v * ref.psi == 0.0)
    assert np.all(ref.psi <= 1e-9 * np.abs(ref.psi).max())


def single_kelvin_mass(c=5.0):
    m, k = BOUNCE["m"], BOUNCE["k"]
    return ul.Model.from_natural([[1.0]], [[k]], [[1.0]], M=[[m]], E_v=[[c]])


def test_kelvin_mass_event_count_and_closure_jump():
    """A mass on a spring + dashpot in series with the contact, thrown up from static rest.

    The exact motion has 8 contact changes in 1 s; the trapezoidal rule chatters more and more
    as dt decreases (10 at dt = 1e-3, 112 at 6.25e-5, see the report), BDF2 finds the 8.
    """
    m, k, g, V0 = BOUNCE.values()
    model = single_kelvin_mass()
    init = {"u0": [-m * g / k], "udot0": [V0]}
    res = ul.solve(model, LoadHistory([-m * g]), dt=1e-3, t_end=1.0, initial=init, method="event")
    assert res.stats["events"] == 8
    assert list(res.stats["event_kinds"]) == ["open", "close"] * 4
    # at closure v' jumps to 0: the reaction jumps from 0 to -c v'(t-) < 0
    t_close = res.stats["event_times"][1]
    k_after = int(np.ceil(t_close / 1e-3))
    assert res.psi[k_after, 0] < -0.5 * 5.0 * 0.5 and res.psi[k_after - 1, 0] == 0.0
    bdf2 = ul.solve(model, np.full((1001, 1), -m * g), dt=1e-3, t_end=1.0, method="direct",
                    rule="bdf2", initial=init)
    assert bdf2.stats["contact_changes"] == 8
    assert np.max(np.abs(bdf2.u - res.u)) < 5e-3 * np.max(np.abs(res.u))


def test_kelvin_rocking_event_equals_direct_stepping_in_displacements():
    model = rocking_model(kelvin=True)
    load = LoadHistory(-MASS * GRAVITY * EY, [(200.0 * EX, Rectangular(1.0, t_end=0.1))])
    T, errors = 0.6, []
    for dt in (1e-3, 2.5e-4):
        N = int(round(T / dt))
        ref = ul.solve(model, load, dt=dt, t_end=T, method="event")
        Q, q0 = load.grid_samples(dt, N)
        init = static_state(model, q0, get_lcp_solver("bpp"))
        sol = ul.solve(model, Q, dt=dt, t_end=T, method="direct", rule="bdf2",
                       initial={"u0": init.u, "v0": init.v})
        errors.append(np.max(np.abs(sol.u - ref.u)) / np.max(np.abs(ref.u)))
    assert ref.stats["events"] == 8 and ref.stats["undecided"] == 0
    assert errors[1] < 5e-4 and errors[0] / errors[1] > 3.0
    # Kelvin closures: the reaction jumps, so psi of closed constraints is strictly negative
    closed = ref.v == 0
    assert np.all(ref.psi[closed] < 0.0)


def test_array_load_is_piecewise_linear_between_samples():
    model = rocking_model(kelvin=False)
    dt, N = 1e-3, 400
    history = LoadHistory(-MASS * GRAVITY * EY, [(300.0 * EX, Ramp(0.1, 1.0))])   # kinks on the grid
    Q = history.sample(dt * np.arange(N + 1))
    a = ul.solve(model, history, dt=dt, t_end=N * dt, method="event")
    b = ul.solve(model, Q, dt=dt, t_end=N * dt, method="event")
    assert a.stats["events"] == b.stats["events"] >= 1
    np.testing.assert_allclose(b.u, a.u, rtol=0, atol=1e-12 * np.abs(a.u).max())
    np.testing.assert_allclose(b.psi, a.psi, rtol=0, atol=1e-9 * np.abs(a.psi).max())


def test_march_event_on_a_given_grid_from_given_state():
    m, k, g, V0 = BOUNCE.values()
    model = ul.Model(M=[[m]], K=[[k]], F=[[k]], H=[[k]])
    t = np.linspace(0.0, 0.5, 37)                                   # any increasing grid
    u, udot, v, psi, info = march_event(model, LoadHistory([-m * g]), t, [-m * g / k], [V0], [0.0])
    exact, _ = bouncing_exact(t, **BOUNCE)
    assert np.max(np.abs(u[:, 0] - exact)) < 1e-14
    assert info["events"] == 3 and udot[0, 0] == V0


@pytest.mark.parametrize("load", [lambda t: np.zeros(5), np.sin],
                         ids=["lambda", "ufunc"])
def test_a_plain_callable_load_is_refused(load):
    model = rocking_model(kelvin=False)
    with pytest.raises(ValueError, match=r"load: a plain callable .* cannot be integrated exactly.*"
                                         r"LoadHistory.*array \(N\+1, n\).*None"):
        ul.solve(model, load, dt=1e-3, t_end=0.01, initial={"u0": np.zeros(5)}, method="event")


def test_a_load_history_with_a_plain_callable_term_is_refused():
    model = rocking_model(kelvin=False)
    load = LoadHistory(np.zeros(5), [(EX, lambda t: np.sin(t))])
    with pytest.raises(ValueError, match=r"load: terms\[0\] has a time function .* without a piecewise form"):
        ul.solve(model, load, dt=1e-3, t_end=0.01, method="event")
