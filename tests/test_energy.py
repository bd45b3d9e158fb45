"""The energy balance W_in = dT + dU + D_damping + D_contact (unilateral.analysis.energy).

* The trapezoidal rule conserves the discrete energy exactly for linear structures, with the
  trapezoidal quadrature of the work terms: the balance closes to round-off, with contact,
  Kelvin dashpots, Rayleigh damping and attached dashpots.
* BDF2 and BDF1 dissipate numerically: on a smooth undamped bilateral run the balance error
  falls with the order of the rule (the slope of log error against log dt is fitted).
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.energy import energy_balance
from unilateral.structure import Frame2D
from unilateral.structure import forces as F


def frame(*, damped=True, soil=True):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 3.0)
    fr.node(3, 4.0, 3.0)
    fr.node(4, 4.0, 0.0)
    fr.support(4, ux=True, uy=True, rz=True)
    if soil:
        fr.support(1, ux=True, uy=False, rz=True)
        fr.soil("soil", 1, 2e4, c=200.0 if damped else 0.0)
    else:
        fr.support(1, ux=True, uy=True, rz=True)
    fr.beam("c1", 1, 2, E=30e6, A=0.09, I=6.75e-4)
    fr.beam("c2", 4, 3, E=30e6, A=0.09, I=6.75e-4)
    fr.beam("g", 2, 3, E=30e6, A=0.09, I=6.75e-4)
    fr.mass(2, 10.0)
    fr.mass(3, 10.0)
    if damped:
        fr.rayleigh(a0=0.3, a1=1e-4)
        fr.dashpot("dp", 3, 20.0, direction="ux")
    return fr.build()


def run(st, rule, dt, t_end=0.6, amplitude=150.0, omega=12.0):
    N = int(round(t_end / dt))
    t = dt * np.arange(N + 1)
    Q = np.tile(st.gravity(10.0), (N + 1, 1)) + np.outer(amplitude * np.sin(omega * t) ** 2,
                                                         st.nodal_load(2, ux=1.0))
    sol = ul.solve(st.to_model(), Q, dt=dt, t_end=t_end, method="direct", rule=rule)
    assert sol.success
    h = F.Histories.from_solution(st, sol, rule, load0=Q[0])
    return sol, energy_balance(st, h, Q)


def test_trapezoidal_rule_closes_the_balance_exactly_with_contact_and_damping():
    st = frame()
    sol, e = run(st, "trapezoidal", 1e-3, amplitude=2000.0)
    assert sol.stats["contact_changes"] > 0                 # the column base lifts off and lands
    assert e["contact_dissipated"][-1] > 0 and e["damping_dissipated"][-1] > 0
    assert e["max_relative_error"] < 1e-10
    assert np.all(np.diff(e["damping_dissipated"]) >= -1e-12)


def test_trapezoidal_rule_conserves_energy_of_an_undamped_bilateral_structure():
    st = frame(damped=False, soil=False)
    sol, e = run(st, "trapezoidal", 2e-3)
    total = e["kinetic"] + e["elastic_structure"] + e["elastic_unilateral"]
    np.testing.assert_allclose(total - total[0], e["input_work"], atol=1e-11 * np.abs(e["input_work"]).max())
    assert e["damping_dissipated"].max() == 0 and e["contact_dissipated"].max() == 0


@pytest.mark.parametrize("rule, order", [("bdf2", 2), ("bdf1", 1)])
def test_balance_error_falls_with_the_order_of_the_rule(rule, order):
    st = frame(damped=False, soil=False)
    dts = np.array([4e-3, 2e-3, 1e-3, 5e-4])
    errors = np.array([run(st, rule, dt)[1]["max_relative_error"] for dt in dts])
    slope = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert abs(slope - order) < 0.35, (slope, errors)
