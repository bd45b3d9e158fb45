"""Convergence order of BDF2 and the trapezoidal rule against the exact event-driven march.

What users run: ``unilateral.solve`` (direct stepping and CQ) with the consistent load samples of
``LoadHistory.grid_samples`` (hat averages, one-sided at t = 0, static preload under q(0-)) passed
as the load array, on models with repeated lift-off and an airborne phase. The error is the
largest deviation over the whole run from the exact solution on the same grid (relative to the
largest value), the order the slope of a least-squares fit of log(error) against log(dt).
"""

import numpy as np
import pytest

import unilateral as ul
from conftest import GRAVITY, MASS, rocking_model
from unilateral.initial import static_state
from unilateral.lcp import get_lcp_solver
from unilateral.loads import HalfSine, LoadHistory, Rectangular

DTS = (1e-3, 5e-4, 2.5e-4)
T_END = 1.0

# a rigid block (mass m, rotational inertia I) on two tensionless soil springs at x = +-b with the
# soil dashpots attached; u = (y, theta). Pulse edges fall between grid points for every dt.
m_, I_, k_, c_, b_, g_ = 10.0, 5.0, 1e5, 200.0, 1.0, 10.0
W = m_ * g_


def block():
    G = np.array([[1.0, 1.0], [-b_, b_]])
    return ul.Model.from_natural(G, k_ * np.eye(2), np.eye(2), M=np.diag([m_, I_]), C=c_ * G @ G.T)


LOADS = {
    # rock onto each edge (lift-off of both), a jump with a twist (airborne), rock back
    "rectangular": LoadHistory([-W, 0.0], [
        ([0.0, 1.0], Rectangular(1.3 * W * b_, t_start=0.0113, t_end=0.1237)),
        ([1.0, 0.3], Rectangular(1.6 * W, t_start=0.3031, t_end=0.3717)),
        ([0.0, 1.0], Rectangular(-1.3 * W * b_, t_start=0.6071, t_end=0.7093))]),
    "half-sine": LoadHistory([-W, 0.0], [
        ([0.0, 1.0], HalfSine(1.6 * W * b_, t_start=0.0113, duration=0.1237)),
        ([1.0, 0.3], HalfSine(2.5 * W, t_start=0.3031, duration=0.0717))]),
}


@pytest.fixture(scope="module")
def references():
    out = {}
    for name, load in LOADS.items():
        out[name] = ul.solve(block(), load, dt=DTS[-1], t_end=T_END, method="event")
    return out


def errors(model, load, ref, method, rule, sampling="hat"):
    """Relative max errors of (u, v, psi) on the grids of DTS; ``sampling="old"``: point values."""
    out = []
    for dt in DTS:
        N = int(round(T_END / dt))
        every = int(round(dt / DTS[-1]))
        if sampling == "hat":             # what solve does with a LoadHistory
            sol = ul.solve(model, load, dt=dt, t_end=T_END, method=method, rule=rule)
        else:
            if sampling == "old":
                Q, q0 = load.sample(dt * np.arange(N + 1)), load(0.0)
            else:
                Q, q0 = load.grid_samples(dt, N, sampling)
            init = static_state(model, q0, get_lcp_solver("bpp"))
            sol = ul.solve(model, Q, dt=dt, t_end=T_END, method=method, rule=rule,
                           initial={"u0": init.u, "v0": init.v})
        assert sol.success, sol.message
        out.append([np.max(np.abs(sol.u - ref.u[::every])) / np.max(np.abs(ref.u)),
                    np.max(np.abs(sol.v - ref.v[::every])) / np.max(ref.v),
                    np.max(np.abs(sol.psi - ref.psi[::every])) / np.max(np.abs(ref.psi))])
    return np.array(out)


def orders(errs):
    return np.array([np.polyfit(np.log(DTS), np.log(errs[:, j]), 1)[0] for j in range(errs.shape[1])])


def test_the_reference_has_repeated_lift_off_and_an_airborne_phase(references):
    for ref in references.values():
        kinds = list(ref.stats["event_kinds"])
        assert kinds.count("open") >= 4 and ref.stats["undecided"] == 0
        assert set(ref.stats["event_constraints"]) == {0, 1}
        assert np.any(np.all(ref.v > 0, axis=1))                          # airborne


@pytest.mark.parametrize("load", LOADS)
@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
@pytest.mark.parametrize("method", ["direct", pytest.param("cq", marks=pytest.mark.slow)])
def test_second_order_with_consistent_samples(references, load, rule, method):
    errs = errors(block(), LOADS[load], references[load], method, rule)
    assert np.all(orders(errs) >= 1.9), (orders(errs), errs)


@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_point_samples_give_first_order_with_pulse_edges_between_grid_points(references, rule):
    """The old behaviour (point values, q(0) = 0 for the static start) fails the test above."""
    errs = errors(block(), LOADS["rectangular"], references["rectangular"], "direct", rule, "old")
    assert np.all(orders(errs) < 1.5), (orders(errs), errs)


@pytest.mark.slow
@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_kelvin_contacts_first_order_in_displacements_reaction_does_not_converge(rule):
    """Kelvin contacts: at closure v' jumps to 0 and the reaction jumps by H_v v'(t-). The rules
    place that jump on the grid (an O(dt) timing error of a force jump). Measured here (dt 1e-3 to
    2.5e-4): displacement orders 1.4 (BDF2) and 2.0 (trapezoidal, which chatters instead); the max
    error of psi stays O(0.1-1) (a jump misplaced by O(dt) in time is an O(1) error at a grid
    point), so no order is claimed for the reaction."""
    ex, ey = np.eye(5)[0], np.eye(5)[1]
    model = rocking_model(kelvin=True)
    load = LoadHistory(-MASS * GRAVITY * ey, [(200.0 * ex, Rectangular(1.0, t_start=0.0113, t_end=0.1237))])
    ref = ul.solve(model, load, dt=DTS[-1], t_end=T_END, method="event")
    errs = errors(model, load, ref, "direct", rule)
    p = orders(errs)
    assert p[0] > 0.8, (p, errs)
    assert errs[-1, 2] > 0.05, errs
