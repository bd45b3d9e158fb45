"""Kelvin contacts under the trapezoidal rule: chatter is reported, and so is a non-unique step LCP.

The trapezoidal rule has no numerical damping: after a contact change the rate of a Kelvin dashpot
in series with a contact alternates in sign from step to step and the contact opens and closes on
consecutive steps. On a single Kelvin mass the number of contact changes grows as dt shrinks
(10, 18, 20, 38, 112 for dt = 1e-3 ... 6.25e-5; exact: 8) while BDF2 gives 8 at every dt. Every
run reports it in ``stats["chatter"]`` and, from two alternations of a constraint on, in its message
with the fix (``rule='bdf2'``). The step LCP matrix ``W0 = Lambda(s*)`` is checked for the P-matrix
property (``stats["step_lcp"]``): it is symmetric positive definite for every model and rule with a
CQ form, so the step LCP has one solution, and differences between methods under the trapezoidal
rule come from the chatter's sensitivity to round-off, not from several solutions.
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.loads import LoadHistory, Rectangular
from unilateral.methods.common import contact_alternations, p_matrix_check, step_lcp_matrix

M_, K_, G_, V0, C_ = 2.0, 2000.0, 10.0, 1.0, 5.0


def kelvin_mass():
    """A mass on a spring + dashpot in series with a contact, thrown up from static rest."""
    model = ul.Model.from_natural([[1.0]], [[K_]], [[1.0]], M=[[M_]], E_v=[[C_]])
    return model, {"u0": [-M_ * G_ / K_], "udot0": [V0]}


def random_kelvin_model(seed, *, n=4, m=3, dashpots=1.0):
    """Random SPD M, n random bilateral springs and m Kelvin contacts with capacities r > 0."""
    rng = np.random.default_rng(seed)
    ne = n + m
    G = rng.normal(size=(n, ne))
    E = np.diag(rng.uniform(0.5, 2.0, ne) * 1e3)
    B = np.zeros((ne, m))
    B[n:, :] = np.eye(m)
    E_v = np.zeros((ne, ne))
    E_v[n:, n:] = np.diag(rng.uniform(5.0, 20.0, m) * dashpots)
    A = rng.normal(size=(n, n))
    M = A @ A.T / n + 0.05 * np.eye(n)
    model = ul.Model.from_natural(G, E, B, M=M, E_v=E_v, r=rng.uniform(1.0, 5.0, m))
    load = LoadHistory(10.0 * rng.normal(size=n), [(100.0 * rng.normal(size=n), Rectangular(1.0, t_end=0.1))])
    return model, load


def test_alternations_count_switch_and_switch_back():
    v = np.array([[0, 0], [1, 0], [0, 0], [1, 1], [1, 1], [0, 1], [0, 0]], dtype=float)
    # constraint 0: open at 1, closed at 2 (back), open at 3 (back): 2; constraint 1: none
    np.testing.assert_array_equal(contact_alternations(v), [2, 0])


@pytest.mark.parametrize("method", ["direct", "cq", "modal"])
def test_trapezoidal_chatter_is_reported_and_bdf2_is_not(method):
    model, init = kelvin_mass()
    dt = 1.25e-4
    N = int(round(1.0 / dt))
    q = np.full((N + 1, 1), -M_ * G_)
    trap = ul.solve(model, q, dt=dt, t_end=1.0, method=method, rule="trapezoidal", initial=init)
    bdf2 = ul.solve(model, q, dt=dt, t_end=1.0, method=method, rule="bdf2", initial=init)
    assert trap.stats["contact_changes"] == 38 and bdf2.stats["contact_changes"] == 8
    assert trap.stats["chatter"]["alternations"]["c0"] == 30
    assert "contact chatter" in trap.message and "rule='bdf2'" in trap.message
    assert trap.stats["warnings"]
    assert bdf2.stats["chatter"] == {"alternations": {}, "total": 0}
    assert "WARNING" not in bdf2.message and "warnings" not in bdf2.stats


def test_chatter_grows_as_dt_shrinks_under_the_trapezoidal_rule_only():
    model, init = kelvin_mass()
    counts = {}
    for rule in ("trapezoidal", "bdf2"):
        for dt in (1e-3, 2.5e-4):
            N = int(round(1.0 / dt))
            sol = ul.solve(model, np.full((N + 1, 1), -M_ * G_), dt=dt, t_end=1.0, method="direct",
                           rule=rule, initial=init)
            counts[rule, dt] = sol.stats["chatter"]["total"]
    assert counts["trapezoidal", 1e-3] == 2 and counts["trapezoidal", 2.5e-4] == 12
    assert counts["bdf2", 1e-3] == counts["bdf2", 2.5e-4] == 0


def test_p_matrix_check_finds_a_non_p_matrix():
    ok = p_matrix_check(np.array([[2.0, 1.0], [1.0, 2.0]]))
    assert ok["P_matrix"] and ok["min_principal_minor"] == pytest.approx(0.75)
    bad = p_matrix_check(np.array([[1.0, 2.0], [2.0, 1.0]]))
    assert not bad["P_matrix"] and bad["worst_minor_rows"] == [0, 1]
    assert bad["min_principal_minor"] == pytest.approx(-3.0)


@pytest.mark.parametrize("rule", ["trapezoidal", "bdf2", "bdf1"])
def test_step_lcp_matrix_of_kelvin_models_is_a_p_matrix(rule):
    """Not the cause of the disagreement: W0 = Lambda(s*) is SPD, every principal minor > 0."""
    for seed in range(4):
        for dashpots in (1.0, 100.0):
            model, _ = random_kelvin_model(seed, dashpots=dashpots)
            W0 = step_lcp_matrix(model, rule, 1.0 / 202)
            check = p_matrix_check(W0)
            assert check["P_matrix"] and check["min_principal_minor"] > 1e-3
            assert np.linalg.eigvalsh(W0).min() > 0


def test_random_kelvin_model_methods_agree_or_the_run_says_why():
    """BDF1/BDF2: cq, modal, direct agree to round-off. Trapezoidal with strong dashpots: they do not
    (the chattering march amplifies round-off), and every run carries the chatter warning."""
    model, load = random_kelvin_model(0)
    N = 202
    for rule in ("bdf1", "bdf2"):
        sols = [ul.solve(model, load, dt=1.0 / N, t_end=1.0, method=me, rule=rule) for me in ("cq", "modal", "direct")]
        scale = np.abs(sols[2].u).max()
        for sol in sols[:2]:
            assert np.abs(sol.u - sols[2].u).max() <= 1e-10 * scale
    model, load = random_kelvin_model(0, dashpots=100.0)
    sols = [ul.solve(model, load, dt=1.0 / N, t_end=1.0, method=me, rule="trapezoidal") for me in ("cq", "modal", "direct")]
    spread = max(np.abs(sol.u - sols[2].u).max() for sol in sols) / np.abs(sols[2].u).max()
    assert spread > 1e-6                        # the methods disagree ...
    for sol in sols:                            # ... and each run says why and what to do
        assert sol.stats["step_lcp"]["P_matrix"]
        assert "contact chatter" in sol.message and "rule='bdf2'" in sol.message
