"""The rule's numerical dissipation is a term of the energy balance (unilateral.rules.EnergyPairing).

Paired as the rule that made the steps, the balance is an exact identity: the trapezoidal rule with
the mean of two steps' equations (no numerical dissipation), BDF1 and BDF2 with the equation at the
step and ``dt u'_n`` (their dissipation a quadratic form in the first and second differences of
the state, Dahlquist's G-stability). So ``balance_error`` is round-off for each rule, on a linear
frame and on a yielding one, and ``numerical_dissipation`` tells how much the rule removed: on the
undamped 3-storey hinge frame BDF2 at dt = T1/147 removes 0.32 % of the input work and its peak
base shear is 3.4 % off the converged one, which is warned about; at T1/588 it is not.
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.energy import energy_balance
from unilateral.analysis.outputs import load_samples_of
from unilateral.analysis.terminal import NUMERICAL_WARNING, energy_warnings
from unilateral.structure import forces as F
from hinge_frame import hinge_frame
from test_energy import frame
from yield_portal import frame as portal

RULES = ("bdf1", "bdf2", "trapezoidal")


def pulse_run(st, rule, dt, method="direct", amplitude=2000.0, t_end=0.6):
    N = int(round(t_end / dt))
    t = dt * np.arange(N + 1)
    Q = np.tile(st.gravity(10.0), (N + 1, 1)) + np.outer(amplitude * np.sin(12.0 * t) ** 2, st.nodal_load(2, ux=1.0))
    sol = ul.solve(st.to_model(), Q, dt=dt, t_end=t_end, method=method, rule=rule)
    assert sol.success, sol.message
    h = F.Histories.from_solution(st, sol, rule, load0=Q[0])
    return sol, h, Q


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("case", ["linear", "soil", "yielding"])
def test_the_balance_paired_as_the_rule_closes_to_round_off(rule, case):
    """Linear undamped frame; frame lifting off Kelvin soil with Rayleigh damping and a dashpot; the
    portal with hinges, a yield link, a slider and a frictional soil contact. The numerical
    dissipation is >= 0 and grows (BDF), zero for the trapezoidal rule; left out, the balance is off."""
    st = {"linear": lambda: frame(damped=False, soil=False), "soil": frame, "yielding": portal}[case]()
    sol, h, Q = pulse_run(st, rule, 1e-3, amplitude=160.0 if case == "yielding" else 2000.0)
    e = energy_balance(st, h, Q, rule=rule)
    assert e["exact"] and e["max_relative_error"] < 1e-11, e["max_relative_error"]
    numerical = e["numerical_dissipation"]
    if case == "yielding":
        assert e["plastic_work"][-1] > 0.05 * e["input_work"].max()
    if rule == "trapezoidal":
        assert not numerical.any() and not e["numerical_storage"].any()
        return
    assert np.all(np.diff(numerical) >= -1e-12 * numerical[-1]) and numerical[-1] > 0
    if rule == "bdf1":                       # its energy is that at the step: nothing stored
        assert not e["numerical_storage"].any()
    without = np.abs(e["balance_error"] + numerical + e["numerical_storage"]).max() / np.abs(e["input_work"]).max()
    assert without > 1e-6                    # the rule's terms are what closes it


@pytest.mark.parametrize("method", ["cq", "modal"])
def test_the_identity_holds_for_every_method_that_steps_by_the_rule(method):
    st = portal()
    sol, h, Q = pulse_run(st, "bdf2", 1e-3, method=method, amplitude=160.0)
    assert energy_balance(st, h, Q, rule="bdf2")["max_relative_error"] < 1e-11


def solve_frame(spec, rule, dt, t_end=8.0):
    from unilateral.analysis.results import ground_motions_of, structure_results

    sol = ul.solve(spec.model, spec.load, dt=dt, t_end=t_end, rule=rule)        # method "auto"
    assert sol.success, sol.message
    samples = load_samples_of(spec.load, sol.t, dt)
    res = structure_results(spec.structure, spec.model, {"u": sol}, rule=rule, load_samples=samples,
                            ground_motions=ground_motions_of(spec.structure, spec.load))
    return res["peaks"]["u"]


def peak_shear(p):
    return max(abs(p["base_shear"]["max"]), abs(p["base_shear"]["min"]))


@pytest.mark.slow
def test_the_default_rule_on_the_hinge_frame_is_warned_about_and_the_advice_removes_the_warning(tmp_path):
    spec, _ = hinge_frame(tmp_path)
    reference = solve_frame(spec, "trapezoidal", 3.125e-4)
    coarse = solve_frame(spec, "bdf2", 5e-3)                    # T1/147, the default rule
    error = abs(peak_shear(coarse) - peak_shear(reference)) / peak_shear(reference)
    assert error > 0.02                                         # measured 3.4 %
    assert coarse["energy"]["max_relative_error"] < 1e-11       # the balance closes: no balance warning
    share = coarse["energy"]["numerical_share"]
    assert NUMERICAL_WARNING < share < 10 * NUMERICAL_WARNING  # measured 0.32 %
    period = coarse["periods"][0]
    assert period == pytest.approx(0.7354, abs=1e-3)
    (warning,) = energy_warnings({"unilateral": coarse}, rule="bdf2", dt=5e-3)
    assert "--rule trapezoidal" in warning and "T1/" in warning and "0.32 %" in warning
    advised = float(warning.split("--dt ")[1].split()[0])
    assert advised < 5e-3
    fine = solve_frame(spec, "bdf2", advised)
    assert fine["energy"]["numerical_share"] < NUMERICAL_WARNING
    assert not energy_warnings({"unilateral": fine}, rule="bdf2", dt=advised)
    assert abs(peak_shear(fine) - peak_shear(reference)) < 0.01 * peak_shear(reference)
    trapezoidal = solve_frame(spec, "trapezoidal", 5e-3)
    assert not energy_warnings({"unilateral": trapezoidal}, rule="trapezoidal", dt=5e-3)
    converged = solve_frame(spec, "bdf2", 1.25e-3)                # T1/588
    assert not energy_warnings({"unilateral": converged}, rule="bdf2", dt=1.25e-3)


@pytest.mark.slow
def test_the_numerical_dissipation_of_bdf2_falls_at_second_order_on_the_hinge_frame(tmp_path):
    """Fitted over five steps T1/147 ... T1/2353: the share of BDF2 at 2.27 (BDF1: 0.81); the
    balance summed as the trapezoidal rule (no dissipation term, what the README's 2.14 measured on
    a smooth bilateral frame) at 2.47 here."""
    spec, _ = hinge_frame(tmp_path)
    st = spec.structure
    dts = np.array([5e-3, 2.5e-3, 1.25e-3, 6.25e-4, 3.125e-4])
    shares, trapezoidal_sums = [], []
    for dt in dts:
        sol = ul.solve(spec.model, spec.load, dt=dt, t_end=8.0, rule="bdf2")
        q = load_samples_of(spec.load, sol.t, dt)
        h = F.Histories.from_solution(st, sol, "bdf2", load0=q[0])
        e = energy_balance(st, h, q, rule="bdf2")
        assert e["max_relative_error"] < 1e-10
        shares.append(e["numerical_share"])
        trapezoidal_sums.append(energy_balance(st, h, q)["max_relative_error"])
    slope = np.polyfit(np.log(dts), np.log(shares), 1)[0]
    assert 1.9 < slope < 2.6, (slope, shares)
    slope_sums = np.polyfit(np.log(dts), np.log(trapezoidal_sums), 1)[0]
    assert 1.9 < slope_sums < 2.8, (slope_sums, trapezoidal_sums)


@pytest.mark.parametrize("rule", RULES)
def test_p_delta_work_closes_the_balance_of_a_hinged_frame(tmp_path, rule):
    """The geometric stiffness' energy u^T K_G u / 2 is a term: the balance of the P-Delta hinge
    frame closes to round-off (under the trapezoidal rule to 1e-9 as issue 33 asks; BDF too);
    without the term it is off by 0.76 %."""
    spec, _ = hinge_frame(tmp_path, p_delta=True)
    st = spec.structure
    assert st.geometric is not None
    dt = 5e-3
    sol = ul.solve(spec.model, spec.load, dt=dt, t_end=8.0, rule=rule)
    q = load_samples_of(spec.load, sol.t, dt)
    h = F.Histories.from_solution(st, sol, rule, load0=q[0])
    e = energy_balance(st, h, q, rule=rule)
    assert e["max_relative_error"] < 1e-9
    geometric = e["geometric"] - e["geometric"][0]
    assert geometric.min() < -0.5                                # kN m: gravity works through the sway
    off = np.abs(e["balance_error"] + geometric).max() / np.abs(e["input_work"]).max()
    assert off > 5e-3
    if rule == "trapezoidal":
        assert not e["numerical_dissipation"].any()


def test_the_balance_warning_of_an_exact_pairing_does_not_advise_a_change_that_cannot_help():
    peaks = {"unilateral": {"energy": {"max_relative_error": 0.05, "t_max_relative_error": 1.0,
                                       "numerical_share": 0.0, "rule_identity": True}}}
    (warning,) = energy_warnings(peaks, rule="trapezoidal", dt=0.01)
    assert "neither the rule nor the time step" in warning and "smaller --dt" not in warning
