"""Rigid footings in plan under a Frame3D: rocking about both axes on the elastic half-space.

A footing with one row of patches under a frame in the x-z plane is the 2-D footing of the same
strips (the same soil flexibility, the same CLCP): equal to round-off. A square footing under a
load along its diagonal rocks about the diagonal: mirror symmetry to round-off, with uplift.
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.loads import LoadHistory, Rectangular
from unilateral.structure import Frame2D, Frame3D

HALF = {"model": "halfspace", "Vs": 97.0, "nu": 1 / 3, "rho": 2.0}
COLUMN = dict(E=3e7, A=1.0, Iy=1.0, Iz=1.0, G=1.2e7, J=1.5)
DT, T_END = 2e-3, 0.6


def _load(gravity, vector, P):
    """Gravity, then a horizontal rectangular pulse ``P`` along ``vector`` for 0.1 s."""
    return LoadHistory(gravity, [(P * vector, Rectangular(1.0, t_end=0.1))])


def tower3d(patches, *, width=6.0, length=6.0):
    fr = Frame3D()
    fr.node("top", 0.0, 0.0, 8.0)
    fr.node("base", 0.0, 0.0, 0.0)
    fr.beam("column", "base", "top", **COLUMN)
    fr.mass("top", 40.0)
    fr.foundation("footing", "base", width=width, length=length, patches=patches, soil=HALF)
    return fr


def test_a_row_of_patches_under_a_plane_frame_is_the_2d_footing():
    fr3 = tower3d((5, 1), length=3.0)
    fr3.support("base", ux=False, uy=False, uz=False, rx=True)   # one row of patches: no soil about x
    st3 = fr3.build()
    fr2 = Frame2D()
    fr2.node("top", 0.0, 8.0)
    fr2.node("base", 0.0, 0.0)
    fr2.beam("column", "base", "top", E=3e7, A=1.0, I=1.0)
    fr2.mass("top", 40.0)
    fr2.foundation("footing", "base", width=6.0, length=3.0, patches=5, soil=HALF)
    st2 = fr2.build()
    gravity3, gravity2 = st3.gravity(10.0), st2.gravity(10.0)
    q3 = _load(gravity3, st3.nodal_load("top", ux=1.0), 400.0)
    q2 = _load(gravity2, st2.nodal_load("top", ux=1.0), 400.0)
    s3 = ul.solve(st3.to_model(), q3, dt=DT, t_end=T_END, method="cq")
    s2 = ul.solve(st2.to_model(), q2, dt=DT, t_end=T_END, method="cq")
    assert s3.success and s2.success
    assert s2.v.max() > 1e-5                                   # the footing lifts off
    np.testing.assert_allclose(s3.v, s2.v, rtol=0, atol=1e-9 * np.abs(s2.v).max())
    np.testing.assert_allclose(s3.psi, s2.psi, rtol=0, atol=1e-9 * np.abs(s2.psi).max())
    # the footing's rocking: ry in 3-D (about +y) is -rz in 2-D (about +z of the x-y plane)
    ry = st3.node_displacement(s3, "base", "ry")
    rz = st2.node_displacement(s2, "base", "rz")
    np.testing.assert_allclose(ry, -rz, rtol=0, atol=1e-9 * np.abs(rz).max())


def test_a_square_footing_loaded_along_its_diagonal_rocks_about_the_diagonal():
    fr = tower3d((4, 4))
    st = fr.build()
    d = (st.nodal_load("top", ux=1.0) + st.nodal_load("top", uy=1.0)) / np.sqrt(2.0)
    q = _load(st.gravity(10.0), d, 150.0)
    sol = ul.solve(st.to_model(), q, dt=DT, t_end=T_END, method="cq")
    assert sol.success
    rx, ry = (st.node_displacement(sol, "base", r) for r in ("rx", "ry"))
    ux, uy = (st.node_displacement(sol, "top", r) for r in ("ux", "uy"))
    scale = np.abs(rx).max()
    assert scale > 1e-4
    np.testing.assert_allclose(rx, -ry, rtol=0, atol=1e-10 * scale)      # the axis is (1, -1, 0)
    np.testing.assert_allclose(ux, uy, rtol=0, atol=1e-10 * np.abs(ux).max())
    # the patch forces are mirror images across the diagonal x = y (patch i + 4 j <-> j + 4 i)
    mirror = np.array([j + 4 * i for j in range(4) for i in range(4)])       # at i + 4 j: j + 4 i
    assert not np.array_equal(mirror, np.arange(16))
    c = -sol.psi
    np.testing.assert_allclose(c, c[:, mirror], rtol=0, atol=1e-10 * np.abs(c).max())
    opening = sol.v
    first = [np.argmax(opening[:, j] > 1e-9) if np.any(opening[:, j] > 1e-9) else len(sol.t) for j in range(16)]
    assert opening.max() > 1e-3 and first[0] == min(first)   # the corner behind the load lifts first
    assert np.all(opening[sol.t <= 0.1, 15] <= 1e-12)          # the corner ahead stays down under the pulse


def test_bad_3d_footings_are_refused_naming_the_argument():
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="patches=.*nx, ny"):
        fr.foundation("f", 1, width=2.0, length=2.0, patches=(2, 0), soil=HALF)
    with pytest.raises(ValueError, match="horizontal='soil' needs mu"):
        fr.foundation("f", 1, width=2.0, length=2.0, patches=2, soil=HALF, horizontal="soil")
    with pytest.raises(ValueError, match="width"):
        fr.foundation("f", 1, width=-2.0, length=2.0, patches=2, soil=HALF)
    fr.support(1, ux=False, uy=False, uz=True)
    with pytest.raises(ValueError, match="uz of node 1 is supported"):
        fr.foundation("f", 1, width=2.0, length=2.0, patches=2, soil=HALF)


def test_a_load_on_one_footing_settles_and_tilts_the_other_by_the_cross_flexibility():
    """Two footings diagonal to each other in plan on one half-space: the static coupling through the
    ground moves footing A by the rigid footings' cross-flexibility, built here from the patches."""
    fr = Frame3D()
    fr.node("a", 0.0, 0.0, 0.0)
    fr.node("b", 3.0, 2.5, 0.0)
    for name, node in (("A", "a"), ("B", "b")):
        fr.foundation(name, node, width=2.0, length=1.6, soil=HALF, patches=(3, 2), mass=1.0, Jx=0.2, Jy=0.2)
    st = fr.build()
    model = st.to_model()
    # T (m, 6): uz, rx, ry of A then of B to the upward displacement of each patch
    Tr = np.zeros((12, 6))
    for f, (fnd, node) in enumerate(zip(st.foundation.footings, ("a", "b"))):
        x0, y0, _ = st.coords[node]
        for j, (x, y) in enumerate(fnd.patches.centres):
            Tr[6 * f + j, 3 * f:3 * f + 3] = (1.0, y - y0, -(x - x0))
    Fr = np.linalg.inv(Tr.T @ np.linalg.solve(st.foundation.soil.static(), Tr))
    assert abs(Fr[0, 3]) > 0.05 * Fr[0, 0] and abs(Fr[1, 3]) > 0 and abs(Fr[2, 3]) > 0
    index = {name: st.dofs.names.index(name) for name in ("a.uz", "a.rx", "a.ry", "b.uz")}

    def settle(PA, PB):
        q = np.zeros(st.n)
        q[index["a.uz"]], q[index["b.uz"]] = -PA, -PB
        sol = ul.solve(model, lambda t: q, dt=1e-3, t_end=1e-3, initial="static", method="cq")
        assert sol.success and np.all(-sol.psi[0] > 0)             # every patch in contact
        return sol.u[0]

    du = settle(100.0, 400.0) - settle(100.0, 100.0)
    for k, dof in enumerate(("a.uz", "a.rx", "a.ry")):
        assert du[index[dof]] == pytest.approx(-300.0 * Fr[k, 3], rel=1e-8)
