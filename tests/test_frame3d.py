"""The 3-D frame builder: a plane frame built in 3-D equals the 2-D frame, the closed-form periods of
a torsionally eccentric building on a rigid diaphragm, a skewed cantilever's flexibilities, the
kinematics of rigid links and diaphragms, and clear errors for bad input."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.linalg import eigh

import unilateral as ul
from unilateral.structure import Frame2D, Frame3D

H, L = 3.0, 5.0
E, A, I, I_OUT, G, J = 3e7, 0.16, 2e-3, 1.5e-3, 1.2e7, 3e-3
MASS, K_SOIL, C_SOIL, RHO = 20.0, 1e5, 1e3, 2.5
#: A 2-storey, 1-bay portal in the 2-D x-y plane; in 3-D the same in the x-z plane (y -> z).
NODES = {1: (0.0, 0.0), 2: (L, 0.0), 3: (0.0, H), 4: (L, H), 5: (0.0, 2 * H), 6: (L, 2 * H), "w": (L + 0.3, 2 * H)}
MEMBERS = {"c13": (1, 3), "c24": (2, 4), "c35": (3, 5), "c46": (4, 6), "g34": (3, 4), "g56": (5, 6)}
#: 2-D DOF -> (3-D DOF, sign): the 2-D counter-clockwise rz turns x towards z, a rotation about -y.
IN_PLANE = {"ux": ("ux", 1.0), "uy": ("uz", 1.0), "rz": ("ry", -1.0)}


def dense(a):
    return a.toarray() if sp.issparse(a) else np.asarray(a)


def portal(dim: int, damping="rayleigh"):
    """The portal on tensionless soil under the column bases, with a slack diagonal cable and a
    pounding gap to a wall spring, in 2-D or 3-D."""
    fr = Frame2D() if dim == 2 else Frame3D()
    for node, (x, y) in NODES.items():
        fr.node(node, x, y) if dim == 2 else fr.node(node, x, 0.0, y)
    for base in (1, 2):
        if dim == 2:
            fr.support(base, ux=True, uy=False)
        else:                                   # out of plane: uy, rx, rz held at the bases only
            fr.support(base, ux=True, uy=True, uz=False, rx=True, rz=True)
        fr.soil(f"soil{base}", base, K_SOIL, c=C_SOIL, direction="uy" if dim == 2 else "uz")
    if dim == 2:
        fr.support("w", ux=False, uy=True)
    else:
        fr.support("w", ux=False)
    for name, (i, j) in MEMBERS.items():
        if dim == 2:
            fr.beam(name, i, j, E, A, I, rho=RHO)
        elif name == "g56":                     # an explicit vecxz: z' = -Z, y' = -Y, in-plane bending on Iy
            fr.beam(name, i, j, E=E, A=A, Iy=I, Iz=I_OUT, G=G, J=J, vecxz=(0.3, 0.0, -2.0), rho=RHO)
        else:                                   # default vecxz: z' in the x-z plane
            fr.beam(name, i, j, E=E, A=A, Iy=I, Iz=I_OUT, G=G, J=J, rho=RHO)
    for node in (3, 4, 5, 6):
        fr.mass(node, MASS)
    fr.cable("brace", 1, 4, 2e8, 5e-4, slack=1e-3)
    fr.spring("wall", "w", 1e5, direction="ux")
    fr.gap("pound", 6, "w", 1e6, gap=5e-3)
    if damping == "rayleigh":
        fr.rayleigh_from_ratios(0.05, 1.0, 20.0)
    else:
        fr.modal_damping(0.05)
    return fr.build()


def in_plane_map(st2, st3) -> np.ndarray:
    """``P`` (n2, n3) with ``u2 = P u3`` on the in-plane DOFs."""
    P = np.zeros((st2.n, st3.n))
    for row, (node, dof) in enumerate(st2.dofs.free):
        dof3, sign = IN_PLANE[dof]
        P[row, st3.dofs.index(node, dof3)] = sign
    return P


def condensed_w2(K, M) -> np.ndarray:
    """Squared circular frequencies of ``(K, M)``, the massless DOFs condensed statically."""
    K, M = dense(K), dense(M)
    mass = np.flatnonzero(np.diag(M) > 0)
    zero = np.setdiff1d(np.arange(K.shape[0]), mass)
    Kc = K[np.ix_(mass, mass)] - K[np.ix_(mass, zero)] @ np.linalg.solve(K[np.ix_(zero, zero)], K[np.ix_(zero, mass)])
    return eigh(0.5 * (Kc + Kc.T), M[np.ix_(mass, mass)], eigvals_only=True)


def relative(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / np.max(np.abs(b)))


# ---------------------------------------------------------------------- a plane frame in 3-D
def test_a_plane_frame_built_in_3d_has_the_matrices_of_the_2d_frame_and_decouples_out_of_plane():
    st2, st3 = portal(2), portal(3)
    m2, m3 = st2.to_model(), st3.to_model()
    P = in_plane_map(st2, st3)
    out = np.flatnonzero(~P.any(axis=0))
    assert {dof for node, dof in np.array(st3.dofs.free, dtype=object)[out]} == {"uy", "rx", "rz"}
    for name in ("K", "M", "C"):
        a2, a3 = dense(getattr(m2, name)), dense(getattr(m3, name))
        assert relative(P @ a3 @ P.T, a2) < 1e-12, name
        assert np.max(np.abs((P @ a3)[:, out])) <= 1e-12 * np.max(np.abs(a3)), name    # decoupled
    assert relative(P @ dense(m3.F), dense(m2.F)) < 1e-12
    np.testing.assert_allclose(dense(m3.H), dense(m2.H), rtol=1e-12)
    np.testing.assert_allclose(m3.g(0.0), m2.g(0.0), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(P @ m3.q_imposed(0.0), m2.q_imposed(0.0), rtol=1e-12, atol=1e-12)
    assert st3.constraint_names == st2.constraint_names == ("soil1", "soil2", "brace", "pound")
    # static: gravity and a lateral load, every element bilateral
    f2 = st2.gravity(9.81) + st2.nodal_load(3, ux=150.0) + st2.nodal_load(6, ux=80.0, rz=12.0)
    f3 = st3.gravity(9.81) + st3.nodal_load(3, ux=150.0) + st3.nodal_load(6, ux=80.0, ry=-12.0)
    assert relative(P @ f3, f2) < 1e-15
    u2 = np.linalg.solve(dense(m2.K), f2)
    u3 = np.linalg.solve(dense(m3.K), f3)
    assert relative(P @ u3, u2) < 1e-10
    assert np.max(np.abs(u3[out])) < 1e-12 * np.max(np.abs(u3))
    # the periods: the in-plane ones equal the 2-D ones and are among the 3-D frame's
    w2_2 = condensed_w2(m2.K, m2.M)
    w2_in = condensed_w2(P @ dense(m3.K) @ P.T, P @ dense(m3.M) @ P.T)
    assert relative(w2_in, w2_2) < 1e-10
    w2_3 = condensed_w2(m3.K, m3.M)
    assert len(w2_3) > len(w2_2)
    assert max(np.min(np.abs(w2_3 - w)) / w for w in w2_2) < 1e-9


def test_modal_damping_of_the_plane_frame_in_3d_is_that_of_the_2d_frame():
    st2, st3 = portal(2, damping="modal"), portal(3, damping="modal")
    P = in_plane_map(st2, st3)
    C2, C3 = dense(st2.C), dense(st3.C)
    assert relative(P @ C3 @ P.T, C2) < 1e-8
    out = np.flatnonzero(~P.any(axis=0))
    assert np.max(np.abs((P @ C3)[:, out])) < 1e-8 * np.max(np.abs(C3))


@pytest.mark.parametrize("method", ["direct", "modal", "cq"])
def test_a_plane_frame_built_in_3d_uplifts_and_pounds_as_the_2d_frame(method):
    st2, st3 = portal(2), portal(3)
    P = in_plane_map(st2, st3)
    out = np.flatnonzero(~P.any(axis=0))
    g2, g3 = st2.gravity(9.81), st3.gravity(9.81)
    push2 = st2.nodal_load(3, ux=1.0) + st2.nodal_load(5, ux=1.0)
    push3 = st3.nodal_load(3, ux=1.0) + st3.nodal_load(5, ux=1.0)
    pulse = lambda t: 800.0 * (0.0 < t <= 0.15)                 # noqa: E731
    options = dict(dt=2e-3, t_end=0.6, method=method, rule="trapezoidal")
    sol2 = ul.solve(st2.to_model(), lambda t: g2 + pulse(t) * push2, **options)
    sol3 = ul.solve(st3.to_model(), lambda t: g3 + pulse(t) * push3, **options)
    assert sol2.success and sol3.success
    assert sol3.constraint_names == ["soil1", "soil2", "brace", "pound"]
    v = sol3.v
    assert v[0, 0] == 0.0 and v[0, 1] == 0.0        # both bases on the soil at rest
    assert v[:, :2].max() > 5e-3                    # a column base uplifts
    assert v[0, 3] == pytest.approx(5e-3) and v[:, 3].min() == 0.0      # the gap closes: pounding
    assert v[0, 2] > 1e-3 and v[:, 2].min() == 0.0                      # the slack cable goes taut
    assert relative(sol3.u @ P.T, sol2.u) < 1e-9
    assert np.max(np.abs(sol3.u[:, out])) < 1e-12 * np.max(np.abs(sol3.u))
    assert relative(sol3.v, sol2.v) < 1e-9
    assert relative(sol3.psi, sol2.psi) < 1e-9
    force2 = st2.element_forces(sol2.t, sol2.u, sol2.v, sol2.udot, np.gradient(sol2.v, sol2.t, axis=0))
    force3 = st3.element_forces(sol3.t, sol3.u, sol3.v, sol3.udot, np.gradient(sol3.v, sol3.t, axis=0))
    assert relative(force3, force2) < 1e-9
    for node in (1, 6):
        assert relative(st3.node_displacement(sol3, node, "uz"), st2.node_displacement(sol2, node, "uy")) < 1e-9


def test_a_ground_motion_shakes_the_plane_frame_in_3d_as_in_2d():
    from unilateral.loads import LoadHistory

    st2, st3 = portal(2), portal(3)
    P = in_plane_map(st2, st3)
    a_g = lambda t: 6.0 * np.sin(2 * np.pi * 2.0 * t)          # noqa: E731
    options = dict(dt=2e-3, t_end=0.5, method="direct", rule="trapezoidal")
    sol2 = ul.solve(st2.to_model(), LoadHistory(st2.gravity(9.81), [st2.ground_motion(a_g, "ux")]), **options)
    sol3 = ul.solve(st3.to_model(), LoadHistory(st3.gravity(9.81), [st3.ground_motion(a_g, "ux")]), **options)
    assert sol3.v[:, :2].max() > 1e-3                            # a base uplifts
    assert relative(sol3.u @ P.T, sol2.u) < 1e-9
    assert relative(sol3.psi, sol2.psi) < 1e-9


def test_a_pair_of_records_at_an_angle_is_the_pair_rotated_into_x_and_y():
    """Two components along (cos a, sin a, 0) and (-sin a, cos a, 0) load the structure as their
    projections on x and y do: the same solution to round-off."""
    from unilateral.loads import LoadHistory

    st = building(tops_fixed=False)
    a1 = lambda t: 3.0 * np.sin(2 * np.pi * 1.5 * t)          # noqa: E731
    a2 = lambda t: 2.0 * np.sin(2 * np.pi * 2.5 * t + 0.4)    # noqa: E731
    angle = np.deg2rad(35.0)
    c, s = np.cos(angle), np.sin(angle)
    rotated = LoadHistory(np.zeros(st.n), [st.ground_motion(a1, (c, s, 0.0)), st.ground_motion(a2, (-s, c, 0.0))])
    projected = LoadHistory(np.zeros(st.n), [st.ground_motion(lambda t: c * a1(t) - s * a2(t), "ux"),
                                             st.ground_motion(lambda t: s * a1(t) + c * a2(t), "uy")])
    options = dict(dt=2e-3, t_end=0.4, method="direct", rule="trapezoidal")
    one, two = (ul.solve(st.to_model(), load, **options) for load in (rotated, projected))
    assert np.abs(one.u).max() > 1e-4
    assert relative(one.u, two.u) < 1e-12
    with pytest.raises(ValueError, match="not valid for a ground motion"):
        st.influence("rz")


# ---------------------------------------------------------------------- torsion on a rigid diaphragm
A_HALF, B_HALF, HEIGHT, ECC = 3.0, 2.0, 3.5, 0.8
IY_COL, IZ_COL = 1.2e-3, 0.7e-3
M_FLOOR, J_FLOOR = 60.0, 180.0


def building(mass_at="master", tops_fixed=True):
    """4 columns at (+-a, +-b) fixed at the base; a rigid diaphragm at z = h; the floor mass ``m``,
    ``J`` at ``(e, 0, h)``: on the diaphragm's master (``mass_at="master"``) or on a slave node, the
    master being at the stiffness centre (``"slave"``)."""
    fr = Frame3D()
    corners = {"a": (A_HALF, B_HALF), "b": (-A_HALF, B_HALF), "c": (-A_HALF, -B_HALF), "d": (A_HALF, -B_HALF)}
    for name, (x, y) in corners.items():
        fr.node(f"{name}0", x, y, 0.0)
        fr.node(name, x, y, HEIGHT)
        fr.support(f"{name}0", rx=True, ry=True, rz=True)
        if tops_fixed:
            fr.support(name, ux=False, uy=False, uz=False, rx=True, ry=True)
        fr.beam(f"col_{name}", f"{name}0", name, E=E, A=A, Iy=IY_COL, Iz=IZ_COL, G=G, J=J)
    slaves = list(corners)
    if mass_at == "master":
        fr.node("m", ECC, 0.0, HEIGHT)
        fr.support("m", ux=False, uy=False, uz=True, rx=True, ry=True)
        fr.mass("m", M_FLOOR, Jz=J_FLOOR)
    else:
        fr.node("m", 0.0, 0.0, HEIGHT)
        fr.node("cm", ECC, 0.0, HEIGHT)
        fr.support("m", ux=False, uy=False, uz=True, rx=True, ry=True)
        fr.support("cm", ux=False, uy=False, uz=True, rx=True, ry=True)
        fr.mass("cm", M_FLOOR, Jz=J_FLOOR)
        slaves.append("cm")
    fr.rigid_diaphragm("m", slaves)
    return fr.build()


def closed_form_w2() -> np.ndarray:
    """Lateral-torsional periods: ``(ux, uy, theta)`` at the stiffness centre (the origin), the mass
    at ``(e, 0)``. Column lateral stiffnesses with fixed ends ``12 E I / h^3`` (x: bending about the
    column's local y' = -Y, so ``Iy``; y: ``Iz``); torsion ``sum k r^2`` plus the columns' ``GJ/h``."""
    kx, ky = 12 * E * IY_COL / HEIGHT**3, 12 * E * IZ_COL / HEIGHT**3
    k_theta = 4 * kx * B_HALF**2 + 4 * ky * A_HALF**2 + 4 * G * J / HEIGHT
    K = np.diag([4 * kx, 4 * ky, k_theta])
    m, me = M_FLOOR, M_FLOOR * ECC
    Mm = np.array([[m, 0.0, 0.0], [0.0, m, me], [0.0, me, J_FLOOR + m * ECC**2]])
    # det(K - w2 M) = 0: x alone; y and theta coupled by the eccentricity, a quadratic in w2
    a = Mm[1, 1] * Mm[2, 2] - Mm[1, 2] ** 2
    b = -(K[1, 1] * Mm[2, 2] + K[2, 2] * Mm[1, 1])
    c = K[1, 1] * K[2, 2]
    root = np.sqrt(b * b - 4 * a * c)
    return np.sort([K[0, 0] / M_FLOOR, (-b - root) / (2 * a), (-b + root) / (2 * a)])


@pytest.mark.parametrize("mass_at", ["master", "slave"])
def test_an_eccentric_floor_on_a_rigid_diaphragm_has_the_closed_form_lateral_torsional_periods(mass_at):
    st = building(mass_at)
    model = st.to_model()
    w2 = condensed_w2(model.K, model.M)
    assert len(w2) == 3
    assert relative(w2, closed_form_w2()) < 1e-9
    # the eccentricity couples: the torsional period is not that of the uncoupled floor
    kx = 12 * E * IY_COL / HEIGHT**3
    assert abs(w2[0] - 4 * kx / M_FLOOR) > 1e-3 * w2[0] or abs(w2[1] - 4 * kx / M_FLOOR) > 1e-3 * w2[1]


def test_the_slaves_of_a_rigid_diaphragm_follow_the_master_in_plane_and_keep_uz_rx_ry():
    st = building(tops_fixed=False)
    f = (st.nodal_load("a", ux=40.0, uz=-25.0) + st.nodal_load("c", uy=-30.0, rx=3.0)
         + st.nodal_load("m", rz=15.0))
    u = np.linalg.solve(dense(st.to_model().K), f)
    nodal = st.dofs.nodal(u)
    at = {node: p for p, node in enumerate(st.dofs.nodes)}
    master = nodal[at["m"]]
    assert abs(master[5]) > 1e-6 and abs(master[0]) > 1e-6
    xm = st.coords["m"]
    for slave in "abcd":
        dx, dy, _ = st.coords[slave] - xm
        s = nodal[at[slave]]
        expected = [master[0] - dy * master[5], master[1] + dx * master[5], master[5]]
        np.testing.assert_allclose(s[[0, 1, 5]], expected, rtol=1e-12, atol=1e-15)
    uz = nodal[[at[s] for s in "abcd"], 2]
    assert uz[0] < 0 and np.ptp(uz) > 1e-7                   # own uz: the loaded column shortens most
    assert abs(nodal[at["c"], 3]) > 1e-9                      # own rx
    assert st.dofs.index("a", "uz") >= 0
    with pytest.raises(ValueError, match="a.ux is not a free DOF: node 'a' is in a rigid diaphragm of node 'm'"):
        st.dofs.index("a", "ux")
    # a rigid ground translation: every node that is not supported moves by one unit
    r = st.influence("uy")
    moved = st.dofs.nodal(r)
    free_nodes = [at[n] for n in "abcdm"]
    np.testing.assert_allclose(moved[free_nodes, 1], 1.0)
    np.testing.assert_allclose(moved[:, [0, 2, 3, 4, 5]], 0.0)
    term, a_g = st.ground_motion(np.sin, "uy")
    assert term @ r == pytest.approx(-M_FLOOR)


def test_a_rigid_link_carries_the_rigid_body_motion_in_3d():
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 4.0, 0.0, 0.0)
    fr.node(3, 4.5, -0.7, 1.2)
    fr.support(1, rx=True, ry=True, rz=True)
    fr.beam("b", 1, 2, E=E, A=A, Iy=I, Iz=I_OUT, G=G, J=J)
    fr.rigid_link(2, 3)
    st = fr.build()
    force = np.array([10.0, -20.0, 15.0])
    d = st.coords[3] - st.coords[2]
    u_slave = np.linalg.solve(dense(st.to_model().K), st.nodal_load(3, *force))
    u_master = np.linalg.solve(dense(st.to_model().K), st.nodal_load(2, *force, *np.cross(d, force)))
    np.testing.assert_allclose(u_slave, u_master, rtol=1e-12)
    n2, n3 = st.dofs.nodal(u_slave)[1:]
    np.testing.assert_allclose(n3[:3], n2[:3] + np.cross(n2[3:], d), rtol=1e-12)
    np.testing.assert_allclose(n3[3:], n2[3:], rtol=1e-12)
    with pytest.raises(ValueError, match="3.ux is not a free DOF: node 3 is rigidly linked to node 2"):
        st.dofs.index(3, "ux")


# ---------------------------------------------------------------------- the beam element
def test_a_skewed_cantilever_has_the_beam_flexibilities_along_its_local_axes():
    length, Iy, Iz = 4.0, 2.5e-3, 0.9e-3
    x = np.array([1.0, 2.0, 2.0]) / 3.0
    vecxz = np.array([0.2, -0.5, 1.0])
    y = np.cross(vecxz, x)
    y /= np.linalg.norm(y)
    z = np.cross(x, y)
    start = np.array([0.3, -0.2, 0.1])
    fr = Frame3D()
    fr.node("fixed", *start)
    fr.node("tip", *(start + length * x))
    fr.support("fixed", rx=True, ry=True, rz=True)
    fr.beam("cantilever", "fixed", "tip", E=E, A=A, Iy=Iy, Iz=Iz, G=G, J=J, vecxz=tuple(vecxz))
    st = fr.build()
    K = dense(st.to_model().K)

    def tip(force=(0.0, 0.0, 0.0), moment=(0.0, 0.0, 0.0)):
        u = np.linalg.solve(K, st.nodal_load("tip", *force, *moment))
        n = st.dofs.nodal(u)[1]
        return n[:3] @ np.vstack([x, y, z]).T, n[3:] @ np.vstack([x, y, z]).T   # local components

    P, T = 7.0, 3.0
    disp, rot = tip(force=P * y)                # bending about z': Iz
    np.testing.assert_allclose(disp, [0.0, P * length**3 / (3 * E * Iz), 0.0], rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(rot, [0.0, 0.0, P * length**2 / (2 * E * Iz)], rtol=1e-10, atol=1e-14)
    disp, rot = tip(force=P * z)                # bending about y': Iy
    np.testing.assert_allclose(disp, [0.0, 0.0, P * length**3 / (3 * E * Iy)], rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(rot, [0.0, -P * length**2 / (2 * E * Iy), 0.0], rtol=1e-10, atol=1e-14)
    disp, rot = tip(moment=T * x)               # torsion
    np.testing.assert_allclose(rot, [T * length / (G * J), 0.0, 0.0], rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(disp, 0.0, atol=1e-14)
    disp, rot = tip(force=P * x)                # axial
    np.testing.assert_allclose(disp, [P * length / (E * A), 0.0, 0.0], rtol=1e-10, atol=1e-14)
    assert st.strain_names[:2] == ("cantilever.axial", "cantilever.twist")


@pytest.mark.parametrize("axis, vecxz, stiff", [((0.0, 0.0, 1.0), None, "Iy"),      # vertical: z' = X
                                                  ((1.0, 0.0, 0.0), None, "Iz"),      # horizontal: y' = Y
                                                  ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), "Iy")])
def test_the_default_and_given_vecxz_choose_the_bending_axis(axis, vecxz, stiff):
    length, Iy, Iz = 3.0, 2.5e-3, 0.9e-3
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, *(length * np.array(axis)))
    fr.support(1, rx=True, ry=True, rz=True)
    fr.beam("b", 1, 2, E=E, A=A, Iy=Iy, Iz=Iz, G=G, J=J, vecxz=vecxz)
    st = fr.build()
    load = {"ux": 0.0, "uy": 5.0, "uz": 0.0} if axis[0] else {"ux": 5.0, "uy": 0.0, "uz": 0.0}
    u = np.linalg.solve(dense(st.to_model().K), st.nodal_load(2, **load))
    moved = st.dofs.nodal(u)[1, :3] @ np.array(list(load.values())) / 5.0
    I_used = {"Iy": Iy, "Iz": Iz}[stiff]
    assert moved == pytest.approx(5.0 * length**3 / (3 * E * I_used), rel=1e-10)


def test_springs_dashpots_bars_and_rotary_masses_act_along_their_3d_directions():
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 1.0, 1.0, 1.0)
    fr.support(1)
    d = np.array([1.0, -2.0, 2.0]) / 3.0
    fr.spring("s", 2, 300.0, direction=tuple(3 * d))
    fr.bar("bar", 1, 2, E=2e5, A=1e-3)
    fr.spring("third", 2, 50.0, direction="uz")
    fr.spring("twist", 2, 80.0, direction="rx")
    fr.dashpot("damper", 2, 7.0, direction=tuple(d))
    fr.mass(2, 2.0, Jx=0.5)
    st = fr.build()
    model = st.to_model()
    assert st.dofs.names == ["2.ux", "2.uy", "2.uz", "2.rx"]
    e = np.ones(3) / np.sqrt(3.0)
    K = 300.0 * np.outer(d, d) + 2e5 * 1e-3 / np.sqrt(3.0) * np.outer(e, e) + np.diag([0.0, 0.0, 50.0])
    np.testing.assert_allclose(dense(model.K), np.block([[K, np.zeros((3, 1))], [np.zeros((1, 3)), 80.0]]),
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(dense(model.C)[:3, :3], 7.0 * np.outer(d, d), rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(dense(model.M), np.diag([2.0, 2.0, 2.0, 0.5]))
    np.testing.assert_allclose(st.gravity(10.0, (0.0, 0.0, -1.0)), [0.0, 0.0, -20.0, 0.0])


def test_a_3d_cable_goes_slack_and_a_soil_contact_lifts_off():
    fr = Frame3D()
    fr.node("anchor", 0.0, 0.0, 0.0)
    fr.node("top", 2.0, 1.0, 2.0)
    fr.support("anchor")
    fr.soil("soil", "top", 1e4, direction=(0.0, 0.0, 1.0))
    fr.spring("hx", "top", 1e3, direction="ux")
    fr.spring("hy", "top", 1e3, direction="uy")
    fr.cable("stay", "anchor", "top", E=1e6, A=1e-3)          # EA/L = 1e6 1e-3 / 3
    fr.mass("top", 1.0)
    st = fr.build()
    assert [type(f).__name__ for f in st.families()] == ["Contact"]
    up = st.nodal_load("top", uz=30.0)
    sol = ul.solve(st.to_model(), lambda t: up, dt=1e-3, t_end=2e-3, method="direct")
    soil, stay = sol.v[0]
    assert soil > 0.0 and stay == 0.0                      # lifted off, the cable taut
    down = st.nodal_load("top", uz=-30.0)
    sol = ul.solve(st.to_model(), lambda t: down, dt=1e-3, t_end=2e-3, method="direct")
    soil, stay = sol.v[0]
    assert soil == 0.0 and stay > 0.0                      # on the soil, the cable slack
    assert sol.u[0, st.dofs.index("top", "uz")] == pytest.approx(-30.0 / 1e4, rel=1e-9)


def test_a_uniform_load_on_a_skewed_fixed_fixed_beam_gives_the_exact_midspan_deflection():
    span, Iy, Iz, w = 6.0, 2.5e-3, 0.9e-3, 4.0
    x = np.array([3.0, 4.0, 0.0]) / 5.0                   # horizontal, skewed in plan
    fr = Frame3D()
    for k in range(3):
        fr.node(k, *(k * span / 2 * x))
    for end in (0, 2):
        fr.support(end, rx=True, ry=True, rz=True)
    for k in range(2):
        fr.beam(f"b{k}", k, k + 1, E=E, A=A, Iy=Iy, Iz=Iz, G=G, J=J)   # default vecxz: z' = Z, y' = Z x x'
    st = fr.build()
    K = dense(st.to_model().K)
    vertical = st.distributed_load("b0", wz=-w) + st.distributed_load("b1", wz=-w)
    mid = st.dofs.nodal(np.linalg.solve(K, vertical))[1]
    assert mid[2] == pytest.approx(-w * span**4 / (384 * E * Iy), rel=1e-10)          # about y': Iy
    np.testing.assert_allclose(mid[[0, 1, 3, 4, 5]], 0.0, atol=1e-14)
    y = np.cross((0.0, 0.0, 1.0), x)
    across = sum(st.distributed_load(b, *(w * y)) for b in ("b0", "b1"))
    mid = st.dofs.nodal(np.linalg.solve(K, across))[1]
    assert mid[:3] @ y == pytest.approx(w * span**4 / (384 * E * Iz), rel=1e-10)      # about z': Iz
    # in the plane of the 2-D portal: the 2-D load
    st2, st3 = portal(2), portal(3)
    P = in_plane_map(st2, st3)
    w3, w2 = st3.distributed_load("g56", wx=2.0, wz=-9.0), st2.distributed_load("g56", wx=2.0, wy=-9.0)
    assert relative(P @ w3, w2) < 1e-14


# ---------------------------------------------------------------------- friction pyramid
MU, GRAVITY, RAMP = 0.5, 10.0, 4.0


def block(dim: int, **friction):
    """A unit mass on a tensionless soil with friction, in 2-D (soil along y) or 3-D (along z)."""
    fr = Frame2D() if dim == 2 else Frame3D()
    fr.node(1, 0.0, 0.0) if dim == 2 else fr.node(1, 0.0, 0.0, 0.0)
    fr.mass(1, 1.0)
    fr.soil("s", 1, 1e4, mu=MU, kt=1e3, direction="uy" if dim == 2 else "uz", **friction)
    fr.rayleigh(a0=20.0)
    return fr.build()


def slide(st, push, method="direct"):
    """The block under its weight and a horizontal push ramped from 0 to ``push`` (n,) in RAMP."""
    down = (0.0, -1.0) if len(st.coords[1]) == 2 else (0.0, 0.0, -1.0)
    weight = st.gravity(GRAVITY, down)
    return ul.solve(st.to_model(), lambda t: weight + min(t / RAMP, 1.0) * push, dt=0.01, t_end=RAMP,
                    method=method, rule="trapezoidal")


@pytest.mark.parametrize("method", ["direct", "cq"])
def test_a_block_sliding_along_a_tangent_axis_slides_as_in_2d(method):
    st2, st3 = block(2), block(3)
    assert st3.constraint_names == ("s", "s.slip+", "s.slip-", "s.slip2+", "s.slip2-")
    assert st3.strain_names == ("s", "s.tangential", "s.tangential2")
    assert st3.to_model().law.kinds == ("contact",) + ("friction",) * 4
    H = 2 * MU * GRAVITY
    sol2 = slide(st2, st2.nodal_load(1, ux=H), method)
    sol3 = slide(st3, st3.nodal_load(1, ux=H), method)
    P = np.zeros((2, 3))
    P[0, 0] = P[1, 2] = 1.0                              # (ux, uy) in 2-D = (ux, uz) in 3-D
    assert relative(sol3.u @ P.T, sol2.u) < 1e-9
    assert relative(sol3.v[:, :3], sol2.v) < 1e-9
    assert relative(sol3.psi[:, :3], sol2.psi) < 1e-9
    np.testing.assert_array_equal(sol3.v[:, 3:], 0.0)   # no slip across
    assert sol3.u[:, 1].max() == 0.0 and sol3.v[-1, 1] > 0.1
    forces = st3.element_forces(sol3.t, sol3.u, sol3.v)
    N, T = -forces[:, 0], forces[:, 1]
    sliding = sol3.v[:, 1] > 0
    np.testing.assert_allclose(T[sliding], MU * N[sliding], rtol=1e-9)


def test_the_friction_pyramid_is_exact_along_its_tangent_axes_and_sqrt2_stronger_across():
    H = 2 * MU * GRAVITY
    q = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
    st2 = block(2)
    sol2 = slide(st2, st2.nodal_load(1, ux=H))
    turned = block(3, tangent=(2.0, 2.0, 5.0))          # t1 = q once projected on the tangent plane
    sol = slide(turned, turned.nodal_load(1, *(H * q)))
    along = sol.u[:, :2] @ q[:2]
    assert relative(along, sol2.u[:, 0]) < 1e-9            # slides along q as the 2-D block along x
    assert np.max(np.abs(sol.u[:, :2] @ (q[1], -q[0]))) < 1e-12 * np.max(np.abs(along))
    assert relative(sol.v[:, 1], sol2.v[:, 1]) < 1e-9
    square = block(3)                                   # t1 = x, t2 = y: q is a diagonal of the pyramid
    sol = slide(square, square.nodal_load(1, *(H * q)))
    slipping = sol.v[:, 1] > 0
    np.testing.assert_allclose(sol.v[:, 3], sol.v[:, 1], rtol=1e-9, atol=1e-15)   # both faces slip alike
    onset = H * sol.t[np.argmax(slipping)] / RAMP
    assert onset == pytest.approx(np.sqrt(2.0) * MU * GRAVITY, rel=2e-2)           # sqrt(2) mu N, not mu N
    assert H * sol2.t[np.argmax(sol2.v[:, 1] > 0)] / RAMP == pytest.approx(MU * GRAVITY, rel=2e-2)


# ---------------------------------------------------------------------- clear errors
def _frame():
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 0.0, 0.0, 3.0)
    fr.node(3, 0.0, 0.0, 3.0)
    fr.node(4, 2.0, 0.0, 3.0)
    fr.beam("col", 1, 2, E=E, A=A, Iy=I, Iz=I, G=G, J=J)
    return fr


SECTION = dict(E=E, A=A, Iy=I, Iz=I, G=G, J=J)


@pytest.mark.parametrize("call, error, message", [
    (lambda fr: fr.beam("b", 1, 9, **SECTION), ValueError, r"beam 'b': j=9 is not defined \(nodes: 1, 2, 3, 4\)"),
    (lambda fr: fr.beam("b", 2, 3, **SECTION), ValueError, r"beam 'b': nodes i=2 and j=3 are both at \(0, 0, 3\): "
                                                           "zero-length element"),
    (lambda fr: fr.beam("b", 1, 2, vecxz=(0.0, 0.0, -4.0), **SECTION), ValueError,
     r"beam 'b': vecxz=\(0.0, 0.0, -4.0\) is parallel to the member axis 1 -> 2"),
    (lambda fr: fr.beam("b", 1, 4, vecxz=(1.0, 0.0), **SECTION), ValueError, r"beam 'b': vecxz=\(1.0, 0.0\) must be"),
    (lambda fr: fr.beam("col", 2, 4, **SECTION), ValueError, "beam 'col': the name is already used"),
    (lambda fr: fr.soil("col", 2, 1e3), ValueError, "soil 'col': the name is already used"),
    (lambda fr: fr.beam("b", 2, 4, E=E, A=A, Iy=I, Iz=0.0, G=G, J=J), ValueError, r"beam 'b': Iz=0.0 must be > 0"),
    (lambda fr: fr.spring("s", 2, 1.0, direction="uw"), ValueError, "spring 's': direction='uw' is not valid; use"),
    (lambda fr: fr.spring("s", 2, 1.0, direction=(1.0, 0.0)), ValueError,
     r"spring 's': direction=\(1.0, 0.0\) must be a finite nonzero vector \(x, y, z\)"),
    (lambda fr: fr.soil("s", 2, 1.0, direction="rz"), ValueError,
     "soil 's': direction='rz' is not valid for a contact"),
    (lambda fr: fr.gap("g", 2, 2, 1.0), ValueError, "gap 'g': i and j are the same node 2"),
    (lambda fr: fr.soil("s", 2, 1.0, mu=0.3), ValueError, r"soil 's': friction \(mu=0.3\) needs the stick stiffness kt"),
    (lambda fr: fr.soil("s", 2, 1.0, tangent=(1.0, 0.0, 0.0)), ValueError, "soil 's': tangent is a friction parameter"),
    (lambda fr: fr.gap("g", 2, 4, 1.0, mu=0.3, kt=1.0, tangent=(-3.0, 0.0, 0.0)), ValueError,
     r"gap 'g': tangent=\(-3.0, 0.0, 0.0\) is along the contact's direction"),
    (lambda fr: fr.cable("c", 2, 7, E=1.0, A=1.0), ValueError, r"cable 'c': j=7 is not defined"),
    (lambda fr: fr.node(2, 1.0, 1.0, 1.0), ValueError, r"node 2 is already defined \(at \(0, 0, 3\)\)"),
    (lambda fr: fr.node(5, 1.0, float("nan"), 1.0), ValueError, "node 5: y=nan must be finite"),
    (lambda fr: fr.support(2, ux=False, uy=False, uz=False), ValueError, "support at node 2: ux, uy, uz, rx, ry and rz "
                                                                        "are all False"),
    (lambda fr: fr.support(2, rx=1), TypeError, "support at node 2: rx=1 must be True or False"),
    (lambda fr: fr.mass(9, 1.0), ValueError, r"mass at node 9: node=9 is not defined"),
    (lambda fr: fr.mass(2, 1.0, Jz=-1.0), ValueError, r"mass at node 2: Jz=-1.0 must be >= 0"),
    (lambda fr: fr.rigid_link(2, 2), ValueError, r"rigid_link\(2, 2\): master and slave are the same node 2"),
    (lambda fr: fr.rigid_diaphragm(2, [4, 1]), ValueError, r"rigid_diaphragm\(2, ...\): slaves\[1\]=1 is at z=0, "
                                                           "not in the plane z=3 of the master"),
    (lambda fr: fr.rigid_diaphragm(2, []), ValueError, r"slaves is empty"),
    (lambda fr: fr.rigid_diaphragm(2, [4, 4]), ValueError, r"slaves\[1\]=4 is given twice"),
])
def test_bad_input_is_refused_naming_the_argument(call, error, message):
    with pytest.raises(error, match=message):
        call(_frame())


def test_ties_and_supports_are_checked_against_each_other():
    fr = _frame()
    fr.rigid_diaphragm(2, [3, 4])
    with pytest.raises(ValueError, match=r"support at node 4: ux, rz of node 4 follow node 2"):
        fr.support(4, uy=False, uz=False, rz=True)
    fr.support(4, ux=False, uy=False, uz=True)             # its own uz may be supported
    with pytest.raises(ValueError, match="node 4 is already a slave of node 2"):
        fr.rigid_link(1, 4)
    with pytest.raises(ValueError, match="would close a loop of rigid links through node 2"):
        fr.rigid_link(3, 2)
    fr3 = _frame()
    fr3.rigid_link(2, 4)
    with pytest.raises(ValueError, match="node 4 is already a slave of node 2"):
        fr3.rigid_diaphragm(3, [2, 4])
    assert fr3._ties == {4: (2, ("ux", "uy", "uz", "rx", "ry", "rz"))}      # all the slaves or none
    fr2 = _frame()
    fr2.support(4)
    with pytest.raises(ValueError, match=r"slave node 4 is supported \(ux, uy, uz\)"):
        fr2.rigid_link(2, 4)


def test_a_mechanism_names_the_dofs_without_stiffness():
    fr = _frame()
    fr.support(1, rx=True, ry=True, rz=True)
    with pytest.raises(ValueError, match=r"no element gives stiffness to DOF\(s\) 3.ux, 3.uy, 3.uz, 4.ux"):
        fr.build()
    fr = Frame3D()
    with pytest.raises(ValueError, match=r"the frame has no nodes; add nodes with Frame3D.node\(\)"):
        fr.build()


def test_loads_of_the_3d_structure_check_their_arguments():
    fr = _frame()
    fr.support(1, rx=True, ry=True, rz=True)
    fr.support(3)
    fr.support(4)
    st = fr.build()
    with pytest.raises(ValueError, match="nodal_load at node 1: uz=2.0 acts on a DOF that cannot move"):
        st.nodal_load(1, uz=2.0)
    with pytest.raises(ValueError, match="direction='rz' is not valid for a ground motion; valid: 'ux', 'uy', 'uz'"):
        st.influence("rz")
    with pytest.raises(ValueError, match="gravity: direction='rx' is not a direction of gravity"):
        st.gravity(9.81, "rx")
    with pytest.raises(ValueError, match=r"distributed_load on beam 'girder': no beam 'girder' \(beams: 'col'\)"):
        st.distributed_load("girder", wx=1.0)
    with pytest.raises(TypeError, match="distributed_load on beam 'col': wz must be a real number"):
        st.distributed_load("col", wz="1")
    with pytest.raises(ValueError, match="dof='uw' is not valid"):
        st.dofs.full_index(2, "uw")


def test_a_yielding_link_and_a_slider_in_3d_act_as_in_2d():
    """A mass on a yielding link (hardening) and one on a slider, pushed along x beyond yield and
    beyond the friction force: the same plastic and slip histories in 2-D and 3-D."""
    def frame(dim):
        fr = Frame2D() if dim == 2 else Frame3D()
        xyz = (lambda x: (x, 0.0)) if dim == 2 else (lambda x: (x, 0.0, 0.0))
        fr.node("a", *xyz(0.0))
        fr.node("b", *xyz(2.0))
        fr.support("a", **({"ux": False, "uy": True} if dim == 2 else {"ux": False, "uy": True, "uz": True}))
        fr.support("b", **({"ux": False, "uy": True} if dim == 2 else {"ux": False, "uy": True, "uz": True}))
        fr.mass("a", 2.0)
        fr.mass("b", 1.0)
        fr.yield_link("y", "a", k=1e3, Fy=50.0, hardening=0.05, direction="ux")
        fr.slider("s", "b", mu=0.3, N=100.0, k=2e3, direction="ux")
        return fr.build()

    st2, st3 = frame(2), frame(3)
    assert st3.constraint_names == st2.constraint_names == ("y.plastic+", "y.plastic-", "s.slip+", "s.slip-")
    runs = []
    for st in (st2, st3):
        push = st.nodal_load("a", ux=1.0) * 120.0 + st.nodal_load("b", ux=1.0) * 60.0
        q = lambda t, push=push: push * np.sin(2 * np.pi * 1.0 * t)     # noqa: E731
        runs.append(ul.solve(st.to_model(), q, dt=2e-3, t_end=1.5, method="direct", rule="trapezoidal"))
    two, three = runs
    assert two.v.max() > 1e-3                                   # it yields and slides
    np.testing.assert_allclose(three.v, two.v, rtol=0, atol=1e-12 * np.abs(two.v).max())
    np.testing.assert_allclose(three.psi, two.psi, rtol=0, atol=1e-12 * np.abs(two.psi).max())
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="not a sliding direction"):
        fr.slider("s", 1, mu=0.3, N=10.0, k=1.0, direction="rx")
