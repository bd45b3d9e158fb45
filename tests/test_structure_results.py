"""Results of a solved frame: equilibrium of the whole and of each element, accelerations, modes.

The identity tested for the base forces (``unilateral.structure.forces``): the forces the ground
exerts on the structure (supports, soil, springs and dashpots to the ground) balance the inertia
of the masses, the mass-proportional damping and the applied loads at every step,

    base_shear = r_x^T (M (u'' + a0 u') - q),  base_vertical = r_y^T (M (u'' + a0 u') - q),
    overturning_moment(about p) = r_p^T (M (u'' + a0 u') - q)

with ``r_x``, ``r_y`` rigid translations and ``r_p`` the rigid rotation about ``p``.
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.structure.modes import modes
from unilateral.rules import Newmark
from unilateral.structure import Frame2D
from unilateral.structure import forces as F

A0 = 0.5


def portal(kelvin=True):
    """A portal frame on a rigid footing (rigid link) on two soil elements, a fixed column base,
    a horizontal spring, a dashpot, Rayleigh damping."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 3.0)
    fr.node(3, 4.0, 3.0)
    fr.node(4, 4.0, 0.0)
    fr.node(5, -1.0, 0.0)
    fr.node(6, 2.0, 6.0)
    fr.support(1, ux=True, uy=False, rz=False)
    fr.rigid_link(1, 5)
    fr.support(4, ux=True, uy=True, rz=True)
    for name, i, j in (("c1", 1, 2), ("c2", 4, 3), ("g", 2, 3), ("f", 5, 1), ("r1", 2, 6), ("r2", 3, 6)):
        fr.beam(name, i, j, E=30e6, A=0.09, I=6.75e-4)
    c = 500.0 if kelvin else 0.0
    fr.soil("s5", 5, 1e5, c=c)
    fr.soil("s1", 1, 1e5, c=c)
    fr.spring("hold", 2, 1e3, direction="ux")
    fr.dashpot("dp", 3, 50.0, direction="ux")
    fr.mass(2, 10.0)
    fr.mass(3, 10.0)
    fr.mass(6, 5.0, J=1.0)
    fr.rayleigh(a0=A0, a1=0.001)
    return fr.build()


def rotation(st, point):
    """Free-DOF vector of a unit rigid rotation about ``point``."""
    x0, y0 = point
    r = np.zeros(st.n)
    for k, (node, dof) in enumerate(st.dofs.free):
        x, y = st.coords[node]
        r[k] = {"ux": -(y - y0), "uy": x - x0, "rz": 1.0}[dof]
    return r


@pytest.fixture(scope="module", params=["bdf2", "trapezoidal"])
def solved(request):
    st = portal()
    dt, N = 1e-3, 400
    t = dt * np.arange(N + 1)
    Q = np.tile(st.gravity(10.0), (N + 1, 1)) + np.outer(300 * np.sin(20 * t), st.nodal_load(2, ux=1.0))
    sol = ul.solve(st.to_model(), Q, dt=dt, t_end=N * dt, method="cq", rule=request.param)
    assert sol.success and sol.stats["contact_changes"] > 0         # the footing lifts off and lands
    return st, sol, Q, F.Histories.from_solution(st, sol, request.param, load0=Q[0])


def test_rates_of_the_rule_give_back_the_velocities_and_satisfy_the_equations_of_motion(solved):
    st, sol, Q, h = solved
    np.testing.assert_allclose(h.udot, sol.udot, atol=1e-12 * np.abs(sol.udot).max())
    sigma = F.stresses(st, h)
    residual = st.M @ h.uddot.T + st.C @ h.udot.T + st.natural.G @ sigma.T - Q.T
    assert np.abs(residual).max() < 1e-7 * np.abs(Q).max()      # round-off of the rule's recursion


def test_base_forces_balance_inertia_damping_and_loads_at_every_step(solved):
    st, sol, Q, h = solved
    reaction = F.reactions(st, h)
    assert set(reaction["support"]) == {"1.ux", "4.ux", "4.uy", "4.rz"}
    assert set(reaction["ground_elements"]) == {"s5", "s1", "hold", "dp"}
    point = (4.0, 0.0)
    base = F.base_forces(st, reaction, point)
    inertia = st.M @ (h.uddot + A0 * h.udot).T                       # (n, N+1)
    for key, r in (("base_shear", st.influence("ux")), ("base_vertical", st.influence("uy")),
                   ("overturning_moment", rotation(st, point))):
        expected = r @ inertia - Q @ r
        scale = np.abs(expected).max()
        assert scale > 1.0
        np.testing.assert_allclose(base[key], expected, atol=1e-7 * scale, err_msg=key)


@pytest.mark.parametrize("point", [(0.0, 0.0), (1.5, -2.0)])
def test_base_force_operator_equals_the_base_forces_of_the_reactions(solved, point):
    """Supports, soil (Kelvin), a spring and a dashpot to the ground, Rayleigh a1 on the beams."""
    st, sol, Q, h = solved
    full = F.base_forces(st, F.reactions(st, h), point)
    operator, state = F.BaseForceOperator.of(st, point), F.StateRows.of(h.u, h.udot, h.v, h.vdot)
    fast = operator(state)
    for key, expected in full.items():
        np.testing.assert_allclose(fast[key], expected, rtol=0, atol=1e-12 * np.abs(expected).max(), err_msg=key)
    np.testing.assert_allclose(operator.base_shear(state), full["base_shear"], rtol=0,
                               atol=1e-12 * np.abs(full["base_shear"]).max())


def test_state_rows_of_a_solution_are_its_histories_without_accelerations(solved):
    st, sol, Q, _ = solved
    for rule in ("bdf2", "trapezoidal"):
        h = F.Histories.from_solution(st, sol, rule)
        state = F.StateRows.of_solution(sol, rule)
        assert state.n == st.n
        assert np.array_equal(state.x, np.vstack([h.u.T, h.v.T]))
        assert np.array_equal(state.xdot, np.vstack([h.udot.T, h.vdot.T]))


@pytest.mark.parametrize("rule", ["bdf1", "bdf2", "trapezoidal", Newmark(0.6, 0.3)])
def test_rate_is_the_first_rate_of_rates_in_any_layout(rule):
    from unilateral.rules import get_rule

    rule = get_rule(rule) if isinstance(rule, str) else rule
    y = np.cumsum(np.random.default_rng(1).standard_normal((40, 3)), axis=0)
    y0d, y0dd = np.array([0.5, -1.0, 2.0]), np.array([3.0, 0.0, -4.0])
    first, _ = F.rates(y, rule, 1e-2, rate0=y0d, second0=y0dd)
    assert np.array_equal(F.rate(y, rule, 1e-2, rate0=y0d, second0=y0dd), first)
    assert np.array_equal(F.rate(np.asfortranarray(y), rule, 1e-2, rate0=y0d, second0=y0dd), first)


def test_beam_end_forces_are_in_equilibrium(solved):
    st, sol, Q, h = solved
    ends = F.end_forces(st, h)
    assert F.END_COMPONENTS == ("N_i", "V_i", "M_i", "N_j", "V_j", "M_j")
    for e in st.elements:
        if e.kind != "beam":
            continue
        (i, _), (j, _) = e.dofs[0], e.dofs[3]
        L = np.hypot(*(st.coords[j] - st.coords[i]))
        f = ends[e.name]
        scale = max(np.abs(f).max(), 1.0)
        np.testing.assert_allclose(f[:, 0] + f[:, 3], 0.0, atol=1e-12 * scale)
        np.testing.assert_allclose(f[:, 1] + f[:, 4], 0.0, atol=1e-12 * scale)
        np.testing.assert_allclose(f[:, 2] + f[:, 5] + f[:, 4] * L, 0.0, atol=1e-10 * scale)
    # the loaded column carries bending; N_j is the axial force, tension positive (gravity: compression)
    assert np.abs(ends["c1"][:, 5]).max() > 1.0
    assert ends["c2"][0, 3] < 0


def test_end_forces_of_a_cantilever_match_statics():
    """A horizontal force P at the tip of a vertical cantilever of height L: at the base (end i)
    the element is pushed back (local y of a chord pointing up is -x: V_i = P) and held by the
    counter-clockwise moment M_i = P L."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 2.0)
    fr.support(1, ux=True, uy=True, rz=True)
    fr.beam("col", 1, 2, E=1e6, A=1.0, I=1.0)
    fr.mass(2, 1.0)
    st = fr.build()
    P, L = 10.0, 2.0
    u = np.linalg.solve(st.to_model().K.toarray(), st.nodal_load(2, ux=P))
    h = F.Histories(t=np.zeros(1), u=u[None], udot=np.zeros((1, st.n)), uddot=np.zeros((1, st.n)),
                    v=np.zeros((1, 0)), vdot=np.zeros((1, 0)))
    N_i, V_i, M_i, N_j, V_j, M_j = F.end_forces(st, h)["col"][0]
    assert V_j == pytest.approx(-P) and V_i == pytest.approx(P)     # local y = (-1, 0): force +P along x at j
    assert M_j == pytest.approx(0.0, abs=1e-9) and M_i == pytest.approx(P * L)     # the support's moment
    base = F.base_forces(st, F.reactions(st, h), (0.0, 0.0))
    assert base["base_shear"][0] == pytest.approx(-P)
    assert base["overturning_moment"][0] == pytest.approx(P * L)


def test_absolute_acceleration_under_a_ground_motion():
    st = portal(kelvin=False)
    dt, N = 2e-3, 300
    a_g = lambda t: 2.0 * np.sin(15.0 * np.asarray(t))
    pattern, f = st.ground_motion(a_g, "ux")
    np.testing.assert_allclose(pattern, -(st.M @ st.influence("ux")))
    load = ul.LoadHistory(st.gravity(10.0), [(pattern, f)])
    sol = ul.solve(st.to_model(), load, dt=dt, t_end=N * dt, method="cq", rule="bdf2")
    Q = load.sample(sol.t)
    h = F.Histories.from_solution(st, sol, "bdf2", load0=Q[0])
    acc = F.absolute_acceleration(st, h, [("ux", a_g)])
    r = st.influence("ux")
    np.testing.assert_allclose(acc - h.uddot, np.outer(a_g(sol.t), r))
    base = F.base_forces(st, F.reactions(st, h))
    expected = r @ (st.M @ (acc + A0 * h.udot).T)                    # the masses' absolute inertia
    np.testing.assert_allclose(base["base_shear"], expected, atol=1e-9 * np.abs(expected).max())


def test_influence_vector_is_a_rigid_translation():
    st = portal()
    r = st.influence("ux")
    nodal = st.dofs.nodal(r)
    free_nodes = [p for p, node in enumerate(st.dofs.nodes) if node not in (1, 4, 5)]
    np.testing.assert_allclose(nodal[free_nodes, 0], 1.0)
    np.testing.assert_allclose(nodal[:, 1:], 0.0)
    with pytest.raises(ValueError, match="valid: 'ux', 'uy'"):
        st.influence("rz")


def test_storey_drifts_by_levels_and_pairs(solved):
    st, sol, Q, h = solved
    drifts = F.storey_drifts(st, h)
    assert list(drifts) == ["0-3", "3-6"]
    nodal = st.dofs.nodal(h.u)
    pos = {node: p for p, node in enumerate(st.dofs.nodes)}
    level3 = (nodal[:, pos[2], 0] + nodal[:, pos[3], 0]) / 2
    level0 = nodal[:, [pos[n] for n in (1, 4, 5)], 0].mean(axis=1)
    np.testing.assert_allclose(drifts["0-3"][0], level3 - level0)
    np.testing.assert_allclose(drifts["0-3"][1], (level3 - level0) / 3.0)
    pairs = F.storey_drifts(st, h, pairs=[(3, 6)])
    np.testing.assert_allclose(pairs["3-6"][0], nodal[:, pos[6], 0] - nodal[:, pos[3], 0])


def test_modes_solve_the_generalised_eigenproblem_with_massless_dofs_condensed():
    st = portal()
    model = st.to_model()
    info = modes(model, count=4, influence={"x": st.influence("ux")})
    K, M = model.K.toarray(), model.M.toarray()
    assert np.all(np.diff(info["omega"]) >= 0)
    for w, phi in zip(info["omega"], info["shape"]):
        residual = K @ phi - w ** 2 * M @ phi                        # massless rows: K_0 phi = 0
        assert np.abs(residual).max() < 1e-8 * np.abs(K @ phi).max()
        assert np.abs(phi).max() == pytest.approx(1.0)
    np.testing.assert_allclose(info["period"], 2 * np.pi / info["omega"])
    # all modes together carry the total mass
    full = modes(model, count=100, influence={"x": st.influence("ux")})
    assert full["effective_mass"]["x"].sum() == pytest.approx(full["total_mass"]["x"], rel=1e-8)


def test_modes_of_a_two_storey_shear_frame():
    k, m = 1000.0, 2.0
    model = ul.Model(M=np.diag([m, m]), K=[[2 * k, -k], [-k, k]], F=np.zeros((2, 0)), H=np.zeros((0, 0)))
    w = modes(model)["omega"]
    exact = np.sqrt(k / m * np.array([(3 - np.sqrt(5)) / 2, (3 + np.sqrt(5)) / 2]))
    np.testing.assert_allclose(w, exact, rtol=1e-12)


def test_singular_stiffness_names_the_free_dofs_of_the_mechanism():
    fr = Frame2D()
    for node, x, y in ((1, 0, 0), (2, 0, 3), (3, 4, 3), (4, 4, 0)):
        fr.node(node, x, y)
    fr.support(1)
    fr.support(4)
    fr.bar("c1", 1, 2, E=1.0, A=1.0)
    fr.bar("c2", 4, 3, E=1.0, A=1.0)
    fr.bar("g", 2, 3, E=1.0, A=1.0)
    fr.mass(2, 1.0)
    st = fr.build()                 # the sway mode has mass: dynamics is posed, statics is not
    with pytest.raises(ValueError, match=r"mechanism.*2\.ux, 3\.ux"):
        ul.solve(st.to_model(), lambda t: np.zeros(st.n), dt=0.01, t_end=0.02, method="direct")


def test_rayleigh_takes_either_coefficient():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 1.0)
    fr.support(1, rz=True)
    fr.beam("b", 1, 2, E=1.0, A=1.0, I=1.0)
    fr.mass(2, 2.0)
    fr.rayleigh(a0=0.5)
    st = fr.build()
    np.testing.assert_allclose(st.C.toarray(), 0.5 * st.M.toarray())
    assert st.rayleigh == (0.5, 0.0)


def test_a_support_of_a_master_node_carries_its_rigidly_linked_slaves():
    """Column bases rigidly linked to one supported node (a footing's reference node): the support's
    reaction is the force on the whole base (equilibrium with the applied load and the inertia),
    not just the elements attached to the master itself."""
    import unilateral as ul
    from unilateral.structure import Frame2D
    from unilateral.structure import forces as F

    fr = Frame2D()
    for n, x, y in ((0, 3.0, 0.0), (1, 0.0, 0.0), (2, 6.0, 0.0), (11, 0.0, 3.0), (12, 6.0, 3.0)):
        fr.node(n, x, y)
    fr.rigid_link(0, 1)
    fr.rigid_link(0, 2)
    fr.support(0, ux=True, uy=True, rz=True)
    for name, i, j in (("c1", 1, 11), ("c2", 2, 12), ("b", 11, 12)):
        fr.beam(name, i, j, E=3e7, A=0.1, I=1e-3)
    fr.mass(11, 10.0)
    fr.mass(12, 10.0)
    fr.spring("s", 12, 1e3, direction="uy")
    st = fr.build()
    r = np.asarray(st.M @ st.influence("ux")).ravel()
    sol = ul.solve(st.to_model(), lambda t: 5.0 * r * (t > 0), method="direct", dt=1e-3, t_end=0.3)
    h = F.Histories.from_solution(st, sol, "bdf2")
    support = F.reactions(st, h)["support"]
    inertia = h.uddot @ r
    applied = 5.0 * r.sum()
    # the ground's force plus the applied load accelerates the masses
    assert np.abs(support["0.ux"][1:] + applied - inertia[1:]).max() < 1e-8 * applied
    # the fast operator carries the slaves' forces to the master's support as reactions does
    full = F.base_forces(st, F.reactions(st, h), (1.0, 0.5))
    fast = F.BaseForceOperator.of(st, (1.0, 0.5))(F.StateRows.of(h.u, h.udot, h.v, h.vdot))
    for key, expected in full.items():
        np.testing.assert_allclose(fast[key], expected, rtol=0, atol=1e-10 * np.abs(expected).max(), err_msg=key)
    assert np.abs(full["base_shear"]).max() > 0.5 * applied


def test_a_slaves_ground_spring_loads_the_masters_support_through_the_link():
    """A master supported in ux and rz, a slave 2 m away on a vertical spring, 100 down on the
    master: the spring carries the 100 and the link brings its moment to the master's rz support
    (-200); the overturning moment of all the ground's forces about the master vanishes."""
    import unilateral as ul
    from unilateral.structure import Frame2D
    from unilateral.structure import forces as F

    fr = Frame2D()
    fr.node(0, 0.0, 0.0)
    fr.node(1, 2.0, 0.0)
    fr.node(2, 0.0, 3.0)
    fr.support(0, ux=True, uy=False, rz=True)
    fr.rigid_link(0, 1)
    fr.beam("column", 0, 2, E=3e7, A=0.1, I=1e-3)
    fr.mass(2, 1.0)
    fr.spring("s", 1, 1e4, direction="uy")
    st = fr.build()
    q = 100.0 * st.nodal_load(2, uy=-1.0)
    sol = ul.solve(st.to_model(), lambda t: q, dt=1e-3, t_end=2e-3)         # the static state throughout
    h = F.Histories.from_solution(st, sol, "bdf2")
    r = F.reactions(st, h)
    assert r["support"]["0.rz"][0] == pytest.approx(-200.0, rel=1e-9)
    assert r["ground_elements"]["s"][0, 1] == pytest.approx(100.0, rel=1e-9)
    base = F.base_forces(st, r, point=(0.0, 0.0))
    assert base["base_vertical"][0] == pytest.approx(100.0, rel=1e-9)
    assert abs(base["overturning_moment"][0]) < 1e-9 * 200.0
    fast = F.BaseForceOperator.of(st, (0.0, 0.0))(F.StateRows.of(h.u, h.udot, h.v, h.vdot))
    for key, expected in base.items():
        np.testing.assert_allclose(fast[key], expected, rtol=0, atol=1e-9 * 200.0, err_msg=key)
