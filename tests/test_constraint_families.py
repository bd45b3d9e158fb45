"""Constraint families: contact, yield and friction in one convolutional LCP (every method).

Defining properties: the step LCP of the law (increments of the rate unknowns complementary to
the constraint functions ``P psi``), every method equal to direct stepping with the same rule on
random models that mix the three laws, Newmark's sliding block, and a block that lifts off while
sliding (no tangential force while open; friction work = mu N |slip|).
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.constraints import Contact, Friction, StepLaw, Yield, step_law
from unilateral.methods import CQ, Direct, Modal


# ---------------------------------------------------------------------- the law
def test_step_law_assembles_rate_mask_and_row_map():
    law = step_law([Contact([0]), Yield([3, 4]), Friction([1, 2], normal=[0, 0], mu=0.3)], 5)
    assert law.rate.tolist() == [False, True, True, True, True]
    assert law.kinds == ("contact", "friction", "friction", "yield", "yield")
    expected = np.eye(5)
    expected[1, 0] = expected[2, 0] = 0.3
    np.testing.assert_array_equal(law.P, expected)
    psi = np.arange(5.0)
    np.testing.assert_array_equal(law.rows(psi), expected @ psi)
    assert not law.trivial and not law.symmetric
    assert step_law(None, 3).trivial


@pytest.mark.parametrize("families, message", [
    ([Contact([0, 1]), Yield([1], two_sided=False)], "two families"),
    ([Yield([0, 5])], "m = 3"),
    ([Yield([0], two_sided=False), Friction([1, 2], normal=[0, 0], mu=0.2)], "not a contact"),
    (["contact"], "ConstraintFamily"),
])
def test_step_law_refuses_inconsistent_families(families, message):
    with pytest.raises((ValueError, TypeError), match=message):
        step_law(families, 3)


def test_families_refuse_bad_arguments():
    with pytest.raises(ValueError, match="mu must be"):
        Friction([0, 1], normal=[2, 2], mu=-0.1)
    with pytest.raises(ValueError, match="pairs"):
        Friction([0], normal=[2], mu=0.1)
    with pytest.raises(ValueError, match="pairs"):
        Yield([0, 1, 2])


def test_pairs_are_partners():
    law = step_law([Contact([0]), Yield([3, 4]), Friction([1, 2], normal=[0, 0], mu=0.3)], 5)
    assert law.partner.tolist() == [-1, 2, 1, 4, 3]


# ---------------------------------------------------------------------- random mixed models
def mixed_model(seed, *, kelvin=False):
    """A random structure with one contact, one yield pair and one friction pair on the contact.

    Strains: 0 normal contact spring, 1 tangential stick spring (friction), 2 a yielding spring,
    3.. elastic members. Unknowns: 0 contact, 1-2 slips (+, -), 3-4 plastic (+, -).
    """
    rng = np.random.default_rng(seed)
    n, ne = 3, 6
    G = rng.normal(size=(n, ne))
    E = np.diag(rng.uniform(50.0, 150.0, ne))
    B = np.zeros((ne, 5))
    B[0, 0] = 1.0
    B[1, 1], B[1, 2] = 1.0, -1.0
    B[2, 3], B[2, 4] = 1.0, -1.0
    hk = 10.0
    A = np.zeros((5, 5))
    A[3:, 3:] = hk * np.array([[1.0, -1.0], [-1.0, 1.0]])
    r = np.array([0.0, 0.0, 0.0, 4.0, 6.0])
    M = np.diag(rng.uniform(0.5, 1.5, n))
    C = 0.02 * (G @ E @ G.T)
    E_v = np.diag([2.0, 1.0] + [0.0] * (ne - 2)) if kelvin else None
    families = [Contact([0]), Friction([1, 2], normal=[0, 0], mu=0.4), Yield([3, 4])]
    model = ul.Model.from_natural(G, E, B, M=M, A=A, r=r, C=C, E_v=E_v, families=families)
    q0 = -0.05 * (G[:, 0] * E[0, 0])                    # presses the contact
    shape = rng.normal(size=n)
    load = ul.LoadHistory(q0, [(20.0 * shape, ul.loads.HalfSine(1.0, duration=0.4)),
                               (-15.0 * shape, ul.loads.Rectangular(1.0, t_start=0.5, t_end=0.7))])
    return model, load


def every_law_active(sol, law):
    """The run yields, slips and opens (else the test would prove little)."""
    inc = np.diff(sol.v, axis=0)
    return bool((sol.v[:, 0] > 0).any() and (inc[:, 1:3] > 0).any() and (inc[:, 3:] > 0).any())


@pytest.mark.parametrize("rule", ["bdf1", "bdf2", "trapezoidal"])
@pytest.mark.parametrize("seed", [2, 3])
def test_every_method_equals_direct_stepping_on_mixed_models(rule, seed):
    model, load = mixed_model(seed)
    kw = dict(dt=2e-3, t_end=1.0, rule=rule)
    ref = ul.solve(model, load, method=Direct(engine="python"), **kw)
    assert ref.success, ref.message
    assert every_law_active(ref, model.law)
    scale_u, scale_psi = np.abs(ref.u).max(), np.abs(ref.psi).max()
    for method in (Direct(engine="compiled"), CQ(engine="python", history="naive"),
                   CQ(engine="compiled", history="naive"), CQ(history="fft"),
                   Modal(engine="python"), Modal(engine="compiled")):
        sol = ul.solve(model, load, method=method, **kw)
        assert sol.success, (method, sol.message)
        assert np.abs(sol.u - ref.u).max() <= 1e-9 * scale_u, method
        assert np.abs(sol.v - ref.v).max() <= 1e-9 * max(np.abs(ref.v).max(), 1e-300), method
        assert np.abs(sol.psi - ref.psi).max() <= 1e-8 * scale_psi, method


@pytest.mark.parametrize("rule", ["newmark", "hht"])
def test_compiled_direct_equals_python_with_newmark_and_hht(rule):
    model, load = mixed_model(5, kelvin=True)
    kw = dict(dt=2e-3, t_end=1.0, rule=rule)
    ref = ul.solve(model, load, method=Direct(engine="python"), **kw)
    sol = ul.solve(model, load, method=Direct(engine="compiled"), **kw)
    assert ref.success and sol.success
    assert every_law_active(ref, model.law)
    np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-10 * np.abs(ref.u).max())
    np.testing.assert_allclose(sol.psi, ref.psi, rtol=0, atol=1e-9 * np.abs(ref.psi).max())


def test_kelvin_mixed_models_cq_equals_direct():
    model, load = mixed_model(4, kelvin=True)
    kw = dict(dt=2e-3, t_end=1.0, rule="bdf2")
    ref = ul.solve(model, load, method="direct", **kw)
    sol = ul.solve(model, load, method="cq", **kw)
    assert ref.success and sol.success
    np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-9 * np.abs(ref.u).max())


def test_each_step_solves_the_lcp_of_the_law():
    """z = [v (contact); increments (rate)] >= 0, P psi <= 0, z . P psi = 0 at every step."""
    model, load = mixed_model(2)
    sol = ul.solve(model, load, dt=2e-3, t_end=1.0, method="modal", rule="bdf2")
    rate = model.law.rate
    z = np.where(rate, np.diff(sol.v, axis=0, prepend=sol.v[:1]), sol.v)[1:]
    phi = sol.psi[1:]
    scale = np.abs(phi).max()
    assert z.min() >= -1e-12 * np.abs(sol.v).max()
    assert phi.max() <= 1e-9 * scale
    assert np.abs(z * phi).max() <= 1e-9 * scale * np.abs(sol.v).max()
    # psi is the constraint function P psi: friction rows are +-T - mu N
    T = sol.psi[:, 1] - 0.4 * sol.psi[:, 0]                       # psi(s+) = T
    np.testing.assert_allclose(sol.psi[:, 2], -T + 0.4 * sol.psi[:, 0], atol=1e-9 * scale)


def test_bilateral_run_holds_every_multiplier():
    model, load = mixed_model(0)
    sol = ul.solve(model, load, dt=2e-3, t_end=1.0, method="cq", bilateral=True)
    assert np.all(sol.v == sol.v[0])


# ---------------------------------------------------------------------- friction
def block(mu, *, m=1.0, kN=1e8, kt=1e10, zeta=0.05):
    """A rigid block on the ground: DOFs (ux, uy); normal contact (0), slips s+ (1) and s- (2)."""
    return ul.Model.from_natural(
        G=np.eye(2), E=np.diag([kt, kN]), B=[[0.0, 1.0, -1.0], [1.0, 0.0, 0.0]], M=m * np.eye(2),
        C=np.diag([0.0, 2 * zeta * np.sqrt(kN * m)]),
        families=[Contact([0]), Friction([1, 2], normal=[0, 0], mu=mu)])


def test_newmark_sliding_block_permanent_slip():
    """Base acceleration pulse a > mu g for t_p: slip (a - mu g) t_p^2/2 + ((a - mu g) t_p)^2/(2 mu g)."""
    m, g, mu, a, tp = 1.0, 9.81, 0.2, 4.0, 0.5
    load = ul.LoadHistory([0.0, -m * g], [([-m, 0.0], ul.loads.Rectangular(a, t_end=tp))])
    exact = (a - mu * g) * tp ** 2 / 2 + ((a - mu * g) * tp) ** 2 / (2 * mu * g)
    sol = ul.solve(block(mu), load, dt=1e-5, t_end=1.3, method="direct", rule="bdf2")
    assert sol.success, sol.message
    slip = sol.v[:, 2] - sol.v[:, 1]                   # the load pushes the block towards -x
    assert abs(slip[-1] - exact) <= 1e-4 * exact
    assert np.all(np.diff(slip) >= -1e-15)             # it never slides back
    # stuck again at the end: no slip over the last 0.1 s
    assert slip[-1] - slip[-10001] == pytest.approx(0.0, abs=1e-12)


def test_block_that_lifts_off_while_sliding():
    """No tangential force while open; friction work equals mu N |d slip| step by step."""
    m, g, mu, kt = 1.0, 9.81, 0.3, 1e8
    load = ul.LoadHistory([0.0, -m * g], [([-m, 0.0], ul.loads.Rectangular(5.0, t_end=0.6)),
                                          ([0.0, m], ul.loads.Rectangular(15.0, t_start=0.2, t_end=0.3))])
    model = block(mu, kt=kt)
    sol = ul.solve(model, load, dt=1e-4, t_end=1.0, method="cq", rule="bdf2")
    assert sol.success, sol.message
    s = sol.v[:, 1] - sol.v[:, 2]
    T = kt * (sol.u[:, 0] - s)                         # the tangential (stick spring) force
    N = -(sol.psi[:, 0])                               # the compressive normal force
    open_ = sol.v[:, 0] > 0
    assert open_.sum() > 100                           # airborne for a while
    assert np.abs(T[open_]).max() <= 1e-6 * mu * m * g        # kt |u| eps: round-off of T
    assert np.all(np.abs(T) <= mu * N + 1e-6 * mu * m * g)
    ds = np.diff(s)
    work = np.sum(T[1:] * ds)                          # friction work on the slip increments
    assert np.sum(np.abs(ds)[~open_[1:]]) > 0.05       # it slides in contact too
    assert work == pytest.approx(np.sum(mu * N[1:] * np.abs(ds)), rel=1e-6)     # T from kt (u - s): 1e-8


def test_a_failed_friction_step_says_what_to_change():
    model, load = mixed_model(2)
    sol = ul.solve(model, load, dt=2e-3, t_end=1.0, method="direct", lcp_options={"max_iter": 1})
    assert not sol.success
    assert "stopped after" in sol.message and "friction constraints ['c1', 'c2']" in sol.message
    assert "lcp='lemke'" in sol.message and "kt" in sol.message
    assert sol.v.shape[0] < 501                       # the steps before the failure are kept


def test_pgs_is_refused_for_friction():
    model, load = mixed_model(2)
    with pytest.raises(ValueError, match="lcp='pgs' needs a symmetric step LCP"):
        ul.solve(model, load, dt=2e-3, t_end=0.1, lcp="pgs")


def test_lemke_solves_the_friction_steps_as_pivoting_does():
    model, load = mixed_model(3)
    kw = dict(dt=2e-3, t_end=1.0, method=Direct(engine="python"))
    ref = ul.solve(model, load, **kw)
    sol = ul.solve(model, load, lcp="lemke", **kw)
    assert ref.success and sol.success
    np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-9 * np.abs(ref.u).max())


def test_a_run_that_blows_up_is_not_a_success():
    """F too large for K and H (every unknown open: an indefinite stiffness): direct stepping diverges
    to inf; the solution says so instead of reporting success."""
    H = [[49.1175, -11.5071, -20.0633], [-11.5071, 21.6064, -3.9226], [-20.0633, -3.9226, 12.1345]]
    model = ul.Model(M=[[1.0]], K=[[147.8449]], F=[[40.6907, -35.1318, -54.5204]], H=H, g=[0.6292, 0.9018, 0.1077])
    load = ul.LoadHistory([0.0], [([-29.4706], ul.loads.Rectangular(1.0, t_end=0.4272))])
    rest = {"u0": [0.0], "udot0": [0.0], "v0": [0.0] * 3}
    messages = []
    for method in (Direct(engine="python"), Direct(engine="compiled"), "cq", "modal"):
        sol = ul.solve(model, load, dt=1e-3, t_end=5.0, method=method, initial=rest)
        assert not sol.success, method                 # it diverges: never a success
        messages.append(sol.message)
    assert any("not finite from step" in text for text in messages), messages
