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
from yield_portal import frame as portal


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


def reference_energies(st, h, Q):
    """The balance's terms step by step, as the module's docstring defines them (no vectorisation)."""
    nat = st.natural
    G, B, E, Ev = (np.asarray(a.toarray()) for a in (nat.G, nat.B, nat.E, nat.E_v))
    M, C = st.M.toarray(), st.C.toarray()
    b = B.sum(axis=0)
    cs = st.constraint_strains
    uni = np.isin(np.arange(E.shape[0]), cs)
    out = {k: np.zeros(len(h.t)) for k in ("kinetic", "elastic_structure", "elastic_unilateral",
                                           "damping_dissipated", "contact_dissipated", "input_work")}
    previous = None
    for k in range(len(h.t)):
        eps = G.T @ h.u[k] - B @ h.v[k] - nat.theta(0.0)
        viscous = Ev @ (G.T @ h.udot[k] - B @ h.vdot[k])
        now = {"eps": eps, "q": Q[k], "Cu": C @ h.udot[k], "visc": viscous, "sb": b * (E @ eps + viscous)[cs]}
        out["kinetic"][k] = 0.5 * h.udot[k] @ M @ h.udot[k]
        out["elastic_structure"][k] = 0.5 * (eps * (E @ eps))[~uni].sum()
        out["elastic_unilateral"][k] = 0.5 * (eps * (E @ eps))[uni].sum()
        if previous is not None:
            du, dv = h.u[k] - h.u[k - 1], h.v[k] - h.v[k - 1]
            mid = {key: 0.5 * (now[key] + previous[key]) for key in now}
            out["input_work"][k] = out["input_work"][k - 1] + mid["q"] @ du
            out["damping_dissipated"][k] = out["damping_dissipated"][k - 1] + mid["Cu"] @ du
            out["contact_dissipated"][k] = (out["contact_dissipated"][k - 1] + mid["visc"] @ (eps - previous["eps"])
                                            + mid["sb"] @ dv)
        previous = now
    return out


@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_energies_equal_their_definition_step_by_step(rule):
    """The vectorised balance (prepared matrices, strains reordered) against a plain loop over the
    steps, on the frame with soil (Kelvin), Rayleigh damping and a dashpot, the column base lifting off."""
    st = frame()
    sol, e = run(st, rule, 1e-3, t_end=0.3, amplitude=2000.0)
    assert sol.stats["contact_changes"] > 0
    N = len(sol.t) - 1
    t = 1e-3 * np.arange(N + 1)
    Q = np.tile(st.gravity(10.0), (N + 1, 1)) + np.outer(2000.0 * np.sin(12.0 * t) ** 2, st.nodal_load(2, ux=1.0))
    h = F.Histories.from_solution(st, sol, rule, load0=Q[0])
    expected = reference_energies(st, h, Q)
    scale = max(np.abs(v).max() for v in expected.values())
    for key, value in expected.items():
        assert np.abs(value).max() > 0 or key == "elastic_unilateral", key
        np.testing.assert_allclose(e[key], value, rtol=0, atol=1e-12 * scale, err_msg=key)


def test_energy_balance_of_load_factors_equals_that_of_the_samples():
    """q = constant + factors @ vectors given unformed (a LoadHistory's grid factors) does the same work."""
    from unilateral.analysis.energy import EnergyBalance, LoadFactors
    from unilateral.loads import LoadHistory

    st = frame()
    load = LoadHistory(st.gravity(10.0), [(st.nodal_load(2, ux=1.0), lambda t: 900.0 * np.sin(12.0 * t)),
                                          (st.nodal_load(3, uy=-1.0), lambda t: 300.0 * np.cos(7.0 * t))])
    dt, N = 1e-3, 400
    sol = ul.solve(st.to_model(), load, dt=dt, t_end=N * dt, method="direct", rule="bdf2")
    samples = load.grid_samples(dt, N)[0]
    h = F.Histories.from_solution(st, sol, "bdf2", load0=samples[0])
    state = F.StateRows.of(h.u, h.udot, h.v, h.vdot)
    balance = EnergyBalance(st)
    by_samples = balance(state, samples)
    by_factors = balance(state, LoadFactors(load.constant, load.vectors(), load.grid_factors(dt, N)[0]))
    scale = np.abs(by_samples["input_work"]).max()
    np.testing.assert_allclose(by_factors["input_work"], by_samples["input_work"], rtol=0, atol=1e-12 * scale)
    assert by_factors["max_relative_error"] == pytest.approx(by_samples["max_relative_error"], rel=1e-9)
    assert by_samples["max_relative_error"] > 1e-6                  # bdf2: a real error, not round-off


def test_trapezoidal_rule_closes_the_balance_with_plastic_and_friction_work():
    """Plastic work and friction work are their own terms; with the contact term they are the work
    of B^T sigma on v' of their families, and the trapezoidal balance still closes to round-off."""
    st = portal()
    dt, t_end = 1e-3, 1.2
    N = int(round(t_end / dt))
    t = dt * np.arange(N + 1)
    Q = (np.tile(st.gravity(10.0), (N + 1, 1)) + np.outer(160.0 * np.sin(np.pi * t / 0.5) * (t <= 0.5),
                                                           st.nodal_load(2, ux=1.0))
         + np.outer(120.0 * np.sin(np.pi * (t - 0.6) / 0.4) * ((t >= 0.6) & (t <= 1.0)), st.nodal_load(3, ux=-1.0)))
    sol = ul.solve(st.to_model(), Q, dt=dt, t_end=t_end, method="direct", rule="trapezoidal")
    assert sol.success, sol.message
    h = F.Histories.from_solution(st, sol, "trapezoidal", load0=Q[0])
    e = energy_balance(st, h, Q)
    assert e["max_relative_error"] < 1e-9
    kinds = np.array([u.kind for _, u in st.constraints])
    assert e["plastic_work"][-1] > 0.05 * e["input_work"].max() and e["friction_work"][-1] > 0
    for key, kind in (("plastic_work", "yield"), ("friction_work", "friction")):
        assert e[key][-1] == pytest.approx(e["unknown_work"][kinds == kind].sum(), rel=1e-12)
    # the plastic work of a pair is the work of its force on its plastic deformation v+ - v-
    names = st.constraint_names
    plus, minus = names.index("h2.plastic+"), names.index("h2.plastic-")
    moment = F.stresses(st, h)[:, st.constraint_strains[plus]]
    plastic = sol.v[:, plus] - sol.v[:, minus]
    expected = np.sum(0.5 * (moment[1:] + moment[:-1]) * np.diff(plastic))
    assert e["unknown_work"][plus] + e["unknown_work"][minus] == pytest.approx(expected, rel=1e-10)
    assert expected > 0
