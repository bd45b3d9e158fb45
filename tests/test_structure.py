"""The 2-D frame builder: the seed's example, element stiffnesses, unilateral elements, checks."""


import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import unilateral as ul
from conftest import GRAVITY, K_SOIL, MASS, rocking_load, rocking_model, rocking_natural
from unilateral.structure import Frame2D, liolios1990


def dense(A):
    return A.toarray() if sp.issparse(A) else np.asarray(A)


def static(st, q):
    """Static unilateral state of a built structure under the constant load ``q`` (n,)."""
    sol = ul.solve(st.to_model(), lambda t: q, dt=1e-3, t_end=1e-3)
    assert sol.success, sol.message
    return sol


def linear(st, q):
    """Displacements ``K^-1 q`` of the bilateral structure."""
    return spla.spsolve(sp.csc_matrix(st.to_model().K), q)


# ---------------------------------------------------------------------- the seed's example
@pytest.mark.parametrize("kelvin", [True, False])
def test_example_equals_hand_entered_matrices(kelvin):
    st, _, _ = liolios1990(kelvin)
    model, ref = st.to_model(), rocking_model(kelvin)
    assert model.dof_names == ["1.ux", "1.uy", "1.rz", "2.uy", "2.rz"]      # ref: x1 y1 r1 y2 r2
    assert model.constraint_names == ["soil3", "soil2", "soil4"]
    for name in ("K", "M", "C", "F", "H", "F_v", "H_v"):
        a, b = getattr(model, name), getattr(ref, name)
        assert (a is None) == (b is None), name
        if a is not None:
            np.testing.assert_allclose(dense(a), dense(b), rtol=1e-14, atol=1e-14 * np.abs(dense(b)).max(),
                                       err_msg=name)
    nat = rocking_natural(kelvin)
    for name in ("G", "E", "B"):
        np.testing.assert_allclose(dense(getattr(st.natural, name)), nat[name], rtol=1e-14, atol=1e-9)
    np.testing.assert_array_equal(model.g(0.0), 0.0)


def test_example_load_and_static_displacement():
    st, load, info = liolios1990()
    ref = rocking_load()
    for t in (0.0, 0.05, 0.1, 0.1 + 1e-3):
        np.testing.assert_array_equal(load(t), ref(t))
    assert load(0.0)[0] == 0.0 and load(0.1)[0] == 200.0 and load(0.101)[0] == 0.0
    assert info["units"] == "kN, m, s"
    expected = -MASS * GRAVITY / (3 * K_SOIL)
    assert info["static_displacement"] == expected
    sol = static(st, load(0.0))
    sol_ref = ul.solve(rocking_model(), ref, dt=1e-3, t_end=1e-3)
    fig2 = info["figure2"]
    y3 = st.node_displacement(sol, fig2["node"], fig2["dof"])
    y3_ref = sol_ref.u[0, 3] - 5.0 * sol_ref.u[0, 4]               # y2 + x3 r2 by hand
    assert float(f"{y3[0]:.3g}") == -0.667e-3
    np.testing.assert_allclose([y3[0], y3_ref], expected, rtol=1e-9)
    np.testing.assert_allclose(sol.v[0], 0.0)
    np.testing.assert_allclose(sol.psi[0], -MASS * GRAVITY / 3, rtol=1e-9)


def test_example_rocks_and_element_histories_agree_with_solution():
    st, load, _ = liolios1990(kelvin=False)
    sol = ul.solve(st.to_model(), load, dt=2e-3, t_end=0.4, method="direct")
    assert sol.success
    v3, psi3 = sol.constraint("soil3")
    assert v3.max() > 1e-4                                           # node 3 lifts off
    y3 = st.node_displacement(sol, 3, "uy")
    np.testing.assert_allclose(st.dofs.nodal(sol.u)[:, 2, 1], y3)      # node 3 is third
    e, eps = st.element_deformations(sol.u, sol.v)
    np.testing.assert_allclose(e[:, 0], y3, atol=1e-15)
    np.testing.assert_allclose(eps, e - sol.v, atol=1e-15)
    forces = st.element_forces(sol.t, sol.u, sol.v)
    np.testing.assert_allclose(forces, sol.psi, atol=1e-8 * MASS * GRAVITY)   # psi = sigma (b=1, r=0)
    assert np.all(forces[v3 > 1e-9, 0] > -1e-6)                      # no compression when lifted


def test_kelvin_forces_need_rates():
    st, load, _ = liolios1990(kelvin=True)
    sol = static(st, load(0.0))
    with pytest.raises(ValueError, match="udot and vdot are required"):
        st.element_forces(sol.t, sol.u, sol.v)
    forces = st.element_forces(sol.t, sol.u, sol.v, sol.udot, np.zeros_like(sol.v))
    np.testing.assert_allclose(forces, sol.psi, rtol=1e-9)


# ---------------------------------------------------------------------- bilateral elements
@pytest.mark.parametrize("angle", [0.0, 30.0])
def test_cantilever_tip_deflection_and_rotation(angle):
    L, E, A, I, P = 3.0, 2e8, 1e-2, 1e-4, 10.0
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    fr = Frame2D()
    fr.node("base", 0.0, 0.0)
    fr.node("tip", L * c, L * s)
    fr.support("base", rz=True)
    fr.beam("b", "base", "tip", E, A, I)
    st = fr.build()
    assert st.dofs.names == ["tip.ux", "tip.uy", "tip.rz"] and st.m == 0
    u = linear(st, st.nodal_load("tip", ux=-P * s, uy=P * c))         # P across the axis (to the left)
    np.testing.assert_allclose(-s * u[0] + c * u[1], P * L**3 / (3 * E * I), rtol=1e-12)
    np.testing.assert_allclose(u[2], P * L**2 / (2 * E * I), rtol=1e-12)
    np.testing.assert_allclose(c * u[0] + s * u[1], 0.0, atol=1e-18)
    u = linear(st, st.nodal_load("tip", ux=P * c, uy=P * s))          # along the axis
    np.testing.assert_allclose(c * u[0] + s * u[1], P * L / (E * A), rtol=1e-12)
    u = linear(st, st.nodal_load("tip", rz=P))                        # end moment
    np.testing.assert_allclose([-s * u[0] + c * u[1], u[2]], [P * L**2 / (2 * E * I), P * L / (E * I)],
                               rtol=1e-12)


def test_cantilever_without_unilateral_elements_solves_directly():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 3.0, 0.0)
    fr.support(1, rz=True)
    fr.beam("b", 1, 2, 2e8, 1e-2, 1e-4)
    fr.mass(2, 1.0)
    st = fr.build()
    sol = ul.solve(st.to_model(), lambda t: st.nodal_load(2, uy=-10.0), dt=1e-3, t_end=1e-3, method="direct")
    np.testing.assert_allclose(sol.u[0, 1], -10.0 * 27 / (3 * 2e4), rtol=1e-12)
    assert sol.v.shape == (2, 0)


def test_beam_imposed_strain_and_curvature():
    L, E, A, I, eps0, kappa = 4.0, 2e8, 1e-2, 1e-4, 1e-3, 2e-3
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, L, 0.0)
    fr.support(1, rz=True)
    fr.beam("b", 1, 2, E, A, I, axial_strain=eps0, curvature=kappa)
    st = fr.build()
    model = st.to_model()
    u = spla.spsolve(sp.csc_matrix(model.K), model.q_imposed(0.0))    # free thermal deformation
    np.testing.assert_allclose(u, [eps0 * L, kappa * L**2 / 2, kappa * L], rtol=1e-12)
    sigma = st.natural.stresses(np.zeros(1), u[None], np.zeros((1, 0)))
    np.testing.assert_allclose(sigma, 0.0, atol=1e-6)                 # statically determinate: no stress


def test_bar_stiffness_is_EA_over_L_along_its_axis():
    E, A = 2e8, 5e-4
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 3.0, 4.0)
    fr.support(1)
    fr.bar("bar", 1, 2, E, A)
    fr.spring("hold", 2, 1.0, direction=(4.0, -3.0))                 # across the bar, keeps K regular
    st = fr.build()
    assert st.dofs.names == ["2.ux", "2.uy"]                          # no rotation for a truss node
    with pytest.raises(ValueError, match="node 2 has no rz DOF: no element rotates it"):
        st.dofs.index(2, "rz")
    with pytest.raises(ValueError, match="cannot move"):
        st.nodal_load(2, rz=1.0)
    d = np.array([0.6, 0.8])
    t = np.array([0.8, -0.6])
    np.testing.assert_allclose(dense(st.to_model().K), E * A / 5.0 * np.outer(d, d) + np.outer(t, t),
                               rtol=1e-12)


def test_skew_springs_to_ground_and_between_nodes():
    k1, k2, P = 100.0, 300.0, 5.0
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.spring("s1", 1, k1, direction=(1.0, 1.0))                      # normalised
    fr.spring("s2", 1, k2, direction=(1.0, -1.0))
    st = fr.build()
    d1 = np.array([1.0, 1.0]) / np.sqrt(2)
    u = linear(st, P * d1)
    np.testing.assert_allclose(u, P / k1 * d1, rtol=1e-12)
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 0.0)
    fr.support(1)
    fr.spring("link", 1, k1, j=2, direction="ux")
    fr.spring("vert", 2, k2)
    st = fr.build()
    np.testing.assert_allclose(dense(st.to_model().K), np.diag([k1, k2]))
    np.testing.assert_array_equal(st.natural.G.T @ [1.0, 0.0], [1.0, 0.0])   # extension = u_j - u_i


def test_rigid_link_carries_moment_into_rotation():
    kr, Mz, F = 1e3, 2.0, 3.0
    fr = Frame2D()
    fr.node("m", 1.0, 1.0)
    fr.node("s", 4.0, 5.0)                                            # offset (3, 4)
    fr.node("s2", 4.0, 0.0)                                           # linked to the slave: a chain
    fr.support("m")
    fr.spring("rot", "m", kr, direction="rz")
    fr.rigid_link("m", "s")
    fr.rigid_link("s", "s2")
    st = fr.build()
    assert st.dofs.names == ["m.rz"] and st.dofs.masters == {"s": "m", "s2": "m"}
    r = linear(st, st.nodal_load("s", rz=Mz))
    np.testing.assert_allclose(r, Mz / kr, rtol=1e-12)
    r = linear(st, st.nodal_load("s", uy=F))                          # moment arm 3
    np.testing.assert_allclose(r, 3 * F / kr, rtol=1e-12)
    nodal = st.dofs.nodal(r)
    np.testing.assert_allclose(nodal[0], [0.0, 0.0, r[0]])
    np.testing.assert_allclose(nodal[1], [-4 * r[0], 3 * r[0], r[0]])
    np.testing.assert_allclose(nodal[2], [1 * r[0], 3 * r[0], r[0]])  # offset (3, -1) from "m"


def test_dof_map_and_loads():
    st, _, _ = liolios1990()
    dofs = st.dofs
    assert dofs.nodes == [1, 2, 3, 4] and dofs.index(2, "rz") == 4
    with pytest.raises(ValueError, match="rigidly linked to node 2"):
        dofs.index(3, "uy")
    with pytest.raises(ValueError, match="ux of node 2 is supported"):
        dofs.index(2, "ux")
    with pytest.raises(ValueError, match="node 9 is not defined"):
        dofs.index(9, "ux")
    u = np.arange(1.0, 6.0)
    nodal = dofs.nodal(np.stack([u, 2 * u]))
    assert nodal.shape == (2, 4, 3)
    np.testing.assert_allclose(nodal[0], [[1, 2, 3], [0, 4, 5], [0, 4 - 5 * 5, 5], [0, 4 + 5 * 5, 5]])
    np.testing.assert_allclose(st.gravity(10.0), [0, -400.0, 0, 0, 0])
    np.testing.assert_allclose(st.gravity(10.0, direction=(1.0, 0.0)), [400.0, 0, 0, 0, 0])
    np.testing.assert_allclose(st.nodal_load(4, uy=1.0), [0, 0, 0, 1.0, 5.0])    # via T^T
    with pytest.raises(ValueError, match="cannot move"):
        st.nodal_load(2, ux=1.0)


def test_masses_of_slave_nodes_act_on_the_master():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 2.0, 0.0)
    fr.support(1, ux=False, uy=False, rz=True)
    fr.spring("x", 1, 1.0, direction="ux")
    fr.spring("y", 1, 1.0)
    fr.rigid_link(1, 2)
    fr.mass(2, 3.0, J=0.5)
    st = fr.build()
    assert st.dofs.names == ["1.ux", "1.uy"]                          # rz restrained at the master
    np.testing.assert_allclose(dense(st.M), 3.0 * np.eye(2))
    np.testing.assert_allclose(st.gravity(), [0.0, -3.0 * 9.80665])     # standard gravity by default


# ---------------------------------------------------------------------- unilateral elements
def soil_column(k=1000.0, k2=10.0, m=1.0, **soil):
    """A mass on a soil element (vertical) and a soft bilateral spring k2."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=True, uy=False)
    fr.mass(1, m)
    fr.soil("s", 1, k, **soil)
    fr.spring("hold", 1, k2)
    return fr.build()


def test_soil_lifts_off_under_an_upward_force_larger_than_the_weight():
    k, k2, m, g = 1000.0, 10.0, 1.0, 10.0
    st = soil_column(k, k2, m)
    sol = static(st, st.gravity(g) + st.nodal_load(1, uy=5.0))       # F < m g: contact
    np.testing.assert_allclose(sol.u[0], -5.0 / (k + k2), rtol=1e-9)
    np.testing.assert_allclose([sol.v[0, 0], sol.psi[0, 0]], [0.0, -5.0 * k / (k + k2)], atol=1e-12)
    sol = static(st, st.gravity(g) + st.nodal_load(1, uy=15.0))      # F > m g: lift-off
    np.testing.assert_allclose(sol.u[0], 5.0 / k2, rtol=1e-9)
    np.testing.assert_allclose(sol.v[0], 5.0 / k2, rtol=1e-9)          # separation
    np.testing.assert_allclose(sol.psi[0], 0.0, atol=1e-9)
    e, eps = st.element_deformations(sol.u[0], sol.v[0])
    np.testing.assert_allclose([e[0], eps[0]], [5.0 / k2, 0.0], atol=1e-12)


def test_soil_capacity_carries_tension_up_to_r():
    k, k2, r = 1000.0, 10.0, 4.0
    st = soil_column(k, k2, m=0.0, capacity=r)
    P = 3.0                                                           # soil tension k P/(k+k2) < r
    sol = static(st, st.nodal_load(1, uy=P))
    np.testing.assert_allclose(sol.v[0], 0.0, atol=1e-12)
    np.testing.assert_allclose(sol.psi[0], k * P / (k + k2) - r, rtol=1e-9)
    P = 10.0                                                          # exceeds r: separates at force r
    sol = static(st, st.nodal_load(1, uy=P))
    np.testing.assert_allclose(sol.u[0], (P - r) / k2, rtol=1e-9)
    np.testing.assert_allclose(sol.v[0], (P - r) / k2 - r / k, rtol=1e-9)
    np.testing.assert_allclose(sol.psi[0], 0.0, atol=1e-9)
    np.testing.assert_allclose(st.element_forces(sol.t, sol.u, sol.v), r, rtol=1e-9)


def test_soil_with_initial_gap_and_skew_direction():
    k, k2, g = 1000.0, 10.0, 0.05
    st = soil_column(k, k2, m=1.0, gap=g)
    sol = static(st, st.gravity(g * k2 / 2))                          # sinks g/2: no contact
    np.testing.assert_allclose([sol.v[0, 0], sol.psi[0, 0]], [g / 2, 0.0], atol=1e-12)
    sol = static(st, st.gravity(2 * g * k2))                          # force 2 g k2 > g k2: contact
    u = -(2 * g * k2 + k * g) / (k + k2)
    np.testing.assert_allclose([sol.u[0, 0], sol.v[0, 0], sol.psi[0, 0]], [u, 0.0, k * (u + g)], atol=1e-12)
    fr = Frame2D()                                                    # a wall on the right: d = -x
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=False)
    fr.spring("hold", 1, k2, direction="ux")
    fr.soil("wall", 1, k, direction=(-1.0, 0.0))
    st = fr.build()
    sol = static(st, st.nodal_load(1, ux=1.0))                        # pushed into the wall
    np.testing.assert_allclose([sol.u[0, 0], sol.psi[0, 0]], [1.0 / (k + k2), -k / (k + k2)], rtol=1e-9)
    sol = static(st, st.nodal_load(1, ux=-1.0))                       # pulled away
    np.testing.assert_allclose([sol.v[0, 0], sol.psi[0, 0]], [1.0 / k2, 0.0], atol=1e-12)


def cable_stay(slack=0.0, EA=2000.0, ks=10.0):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 2.0, 0.0)
    fr.support(1)
    fr.support(2, ux=False)
    fr.spring("hold", 2, ks, direction="ux")
    fr.cable("c", 1, 2, E=EA, A=1.0, slack=slack)
    return fr.build()


def test_cable_carries_tension_and_goes_slack_in_compression():
    EA, L, ks, P = 2000.0, 2.0, 10.0, 5.0
    st = cable_stay(EA=EA, ks=ks)
    sol = static(st, st.nodal_load(2, ux=P))                          # pulled: taut
    u = P / (EA / L + ks)
    np.testing.assert_allclose([sol.u[0, 0], sol.v[0, 0]], [u, 0.0], atol=1e-12)
    np.testing.assert_allclose(sol.psi[0], -EA / L * u, rtol=1e-9)   # psi = -sigma (b = -1)
    np.testing.assert_allclose(st.element_forces(sol.t, sol.u, sol.v), EA / L * u, rtol=1e-9)
    sol = static(st, st.nodal_load(2, ux=-P))                         # pushed: slack
    np.testing.assert_allclose([sol.u[0, 0], sol.v[0, 0], sol.psi[0, 0]], [-P / ks, P / ks, 0.0], atol=1e-12)
    np.testing.assert_allclose(st.element_forces(sol.t, sol.u, sol.v), 0.0, atol=1e-9)
    s = 0.1
    st = cable_stay(slack=s, EA=EA, ks=ks)
    sol = static(st, st.nodal_load(2, ux=0.5 * s * ks))               # takes up half the slack
    np.testing.assert_allclose([sol.v[0, 0], sol.psi[0, 0]], [0.5 * s, 0.0], atol=1e-12)


def test_gap_link_transmits_nothing_until_the_gap_closes():
    k, ks, g = 1000.0, 10.0, 0.02
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 1.0, 0.0)
    fr.support(1)
    fr.support(2, ux=False)
    fr.spring("hold", 2, ks, direction="ux")
    fr.gap("pound", 1, 2, k, gap=g)
    st = fr.build()
    sol = static(st, st.nodal_load(2, ux=-0.5 * g * ks))              # closes half the gap
    np.testing.assert_allclose([sol.u[0, 0], sol.v[0, 0], sol.psi[0, 0]], [-g / 2, g / 2, 0.0], atol=1e-12)
    P = 3 * g * ks
    sol = static(st, st.nodal_load(2, ux=-P))                         # closes it: contact force
    u = -(P + k * g) / (ks + k)
    np.testing.assert_allclose([sol.u[0, 0], sol.v[0, 0]], [u, 0.0], atol=1e-12)
    np.testing.assert_allclose(sol.psi[0], k * (u + g), rtol=1e-9)
    assert sol.psi[0, 0] < 0
    e, eps = st.element_deformations(sol.u[0], sol.v[0])
    np.testing.assert_allclose([e[0], eps[0]], [u, u + g], rtol=1e-12)


def test_kelvin_soil_and_attached_dashpots():
    k, c = 1000.0, 50.0
    st = soil_column(k, c=c)
    model = st.to_model()
    assert st.natural.E_v is not None and st.C is None
    np.testing.assert_allclose(dense(model.F_v), [[c]])
    np.testing.assert_allclose(model.H_v, [[c]])
    np.testing.assert_allclose(dense(model.C), [[c]])                 # G E_v G^T
    st = soil_column(k)
    assert st.natural.E_v is None and st.to_model().F_v is None
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 1.0, 0.0)
    for node in (1, 2):
        fr.spring(f"k{node}", node, k, direction="ux")
    fr.support(1, ux=False)
    fr.support(2, ux=False)
    fr.dashpot("d", 1, c, j=2, direction="ux")
    fr.soil("s", 2, k, direction="ux")
    st = fr.build()
    np.testing.assert_allclose(dense(st.C), c * np.array([[1, -1], [-1, 1]]))
    assert st.natural.E_v is None
    np.testing.assert_allclose(dense(st.to_model().C), dense(st.C))


def test_rayleigh_damping():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 3.0)
    fr.support(1, rz=True)
    fr.beam("b", 1, 2, 2e8, 1e-2, 1e-4)
    fr.mass(2, 2.0, J=0.1)
    fr.rayleigh_from_ratios(0.05, 1.0, 10.0)
    st = fr.build()
    w = 2 * np.pi * np.array([1.0, 10.0])
    a0, a1 = 2 * 0.05 * w[0] * w[1] / w.sum(), 2 * 0.05 / w.sum()
    np.testing.assert_allclose(dense(st.C), a0 * dense(st.M) + a1 * dense(st.to_model().K))
    np.testing.assert_allclose(a0 / (2 * w) + a1 * w / 2, 0.05)
    with pytest.raises(ValueError, match="already set"):
        fr.rayleigh(0.1, 0.0)


def test_large_frame_builds_sparse_and_fast():
    """Fast as sparse: the build never holds a dense ``n x n`` array (its quadratic memory and time);
    measured by the memory allocated, not by a clock (which a loaded machine slows)."""
    import tracemalloc

    n_nodes = 2000
    tracemalloc.start()
    fr = Frame2D()
    for p in range(n_nodes):
        fr.node(p, float(p), 0.0)
        fr.mass(p, 1.0)
    for p in range(n_nodes - 1):
        fr.beam(f"b{p}", p, p + 1, 3e7, 0.5, 0.02)
    for p in range(0, n_nodes, 10):
        fr.soil(f"s{p}", p, 1e4, c=10.0)
    fr.support(0, ux=True, uy=False)
    st = fr.build()
    model = st.to_model()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert (st.n, st.m) == (3 * n_nodes - 1, n_nodes // 10)
    assert peak < 0.5 * 8 * st.n ** 2, f"{peak / 1e6:.0f} MB allocated: a dense {st.n} x {st.n} matrix is formed"
    assert all(sp.issparse(x) for x in (st.natural.G, st.natural.E, st.natural.B, st.M, model.K, model.C))


# ---------------------------------------------------------------------- validation
def small_frame():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 3.0)
    fr.node(3, 4.0, 3.0)
    return fr


@pytest.mark.parametrize("call, error, match", [
    (lambda fr: fr.node(1, 5.0, 5.0), ValueError, r"node 1 is already defined \(at \(0, 0\)\)"),
    (lambda fr: fr.node(1.5, 0.0, 0.0), TypeError, "node id must be an int or a str"),
    (lambda fr: fr.node(4, float("nan"), 0.0), ValueError, "node 4: x=nan must be finite"),
    (lambda fr: fr.beam("col", 1, 17, 1.0, 1.0, 1.0), ValueError,
     r"beam 'col': j=17 is not defined \(nodes: 1, 2, 3\)"),
    (lambda fr: fr.beam("col", 1, 2, 1.0, -1.0, 1.0), ValueError, "beam 'col': A=-1.0 must be > 0"),
    (lambda fr: fr.beam("col", 1, 1, 1.0, 1.0, 1.0), ValueError, "beam 'col': i and j are the same node 1"),
    (lambda fr: fr.beam(7, 1, 2, 1.0, 1.0, 1.0), TypeError, "beam name must be a non-empty str"),
    (lambda fr: fr.bar("b", 1, 2, "steel", 1.0), TypeError, "bar 'b': E must be a real number"),
    (lambda fr: fr.soil("s1", 1, -5.0), ValueError, r"soil 's1': k=-5.0 must be > 0"),
    (lambda fr: fr.soil("s1", 1, 5.0, c=-1.0), ValueError, r"soil 's1': c=-1.0 must be >= 0"),
    (lambda fr: fr.soil("s1", 1, 5.0, capacity=-1.0), ValueError, r"soil 's1': capacity=-1.0 must be >= 0"),
    (lambda fr: fr.soil("s1", 1, 5.0, direction="uz"), ValueError, r"soil 's1': direction='uz' is not valid"),
    (lambda fr: fr.spring("k", 1, 5.0, direction=(0.0, 0.0)), ValueError, "must be a finite nonzero vector"),
    (lambda fr: fr.cable("c", 1, 2, 1.0, 1.0, capacity=-2), ValueError,
     "cable 'c': capacity=-2 must be >= 0"),
    (lambda fr: fr.gap("g", 1, 7, 1.0), ValueError, "gap 'g': j=7 is not defined"),
    (lambda fr: fr.dashpot("d", 1, 0.0), ValueError, r"dashpot 'd': c=0.0 must be > 0"),
    (lambda fr: fr.support(9), ValueError, r"support at node 9: node=9 is not defined"),
    (lambda fr: fr.support(1, ux=1), TypeError, "ux=1 must be True or False"),
    (lambda fr: fr.support(1, ux=False, uy=False), ValueError, "restrains nothing"),
    (lambda fr: fr.mass(2, -1.0), ValueError, r"mass at node 2: m=-1.0 must be >= 0"),
    (lambda fr: fr.rigid_link(2, 2), ValueError, "master and slave are the same node"),
    (lambda fr: fr.rayleigh_from_ratios(0.05, 0.0, 1.0), ValueError, "f1=0.0 must be > 0"),
])
def test_argument_errors_name_the_element_argument_and_value(call, error, match):
    with pytest.raises(error, match=match):
        call(small_frame())


def test_zero_length_and_duplicate_names():
    fr = small_frame()
    fr.node(4, 4.0, 3.0)
    with pytest.raises(ValueError, match=r"beam 'b': nodes i=3 and j=4 are both at \(4, 3\): zero-length"):
        fr.beam("b", 3, 4, 1.0, 1.0, 1.0)
    with pytest.raises(ValueError, match="gap 'g': nodes i=3 and j=4 are both at"):
        fr.gap("g", 3, 4, 1.0)
    fr.gap("g", 3, 4, 1.0, direction="ux")                            # coincident nodes need a direction
    with pytest.raises(ValueError, match="soil 'g': the name is already used"):
        fr.soil("g", 1, 1.0)


def test_rigid_link_and_support_conflicts():
    fr = small_frame()
    fr.support(1)
    with pytest.raises(ValueError, match=r"slave node 1 is supported \(ux, uy\); support the master"):
        fr.rigid_link(2, 1)
    fr.rigid_link(2, 3)
    with pytest.raises(ValueError, match="node 3 is rigidly linked to node 2; support the master"):
        fr.support(3)
    with pytest.raises(ValueError, match="node 3 is already a slave of node 2"):
        fr.rigid_link(1, 3)
    with pytest.raises(ValueError, match="loop of rigid links"):
        fr.rigid_link(3, 2)


def test_build_errors():
    with pytest.raises(ValueError, match="the frame has no nodes"):
        Frame2D().build()
    fr = small_frame()
    fr.bar("b", 1, 2, 1.0, 1.0)
    fr.support(1)
    with pytest.raises(ValueError, match=r"no element gives stiffness to DOF\(s\) 2.ux, 3.ux, 3.uy"):
        fr.build()
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1)
    with pytest.raises(ValueError, match="no free DOF"):
        fr.build()
