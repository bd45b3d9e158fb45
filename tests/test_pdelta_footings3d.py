"""P-Delta on footings on a soil medium in 3-D: the gravity's axial forces of the static state on the
soil's static springs (as in 2-D, tests/test_pdelta_footings.py), their geometric stiffness in both
bending planes of the frame's beams.

A tower in the x-z plane on one row of footing patches (the rotation about x held) is the 2-D tower
on the same footing: with P-Delta on both, the 3-D run equals the 2-D run to round-off, the axial
forces are the same, and the P-Delta effect is there; the energy balance closes with the geometric
term. Footings that slide in plan take P-Delta the same way; a gravity at the overturning load is
refused."""

import numpy as np
import pytest

import unilateral as ul
from unilateral.loads import LoadHistory, Rectangular
from unilateral.soil import FoundationModel
from unilateral.structure import Frame2D, Frame3D

SOIL = {"model": "winkler-kelvin", "k": 3e4, "c": 3e2}
H, MASS, DT, T_END = 8.0, 40.0, 2e-3, 1.0


def tower3d(p_delta=True, *, horizontal="support", mu=None):
    fr = Frame3D()
    fr.node("top", 0.0, 0.0, H)
    fr.node("base", 0.0, 0.0, 0.0)
    fr.beam("column", "base", "top", E=3e7, A=1.0, Iy=0.02, Iz=0.02, G=1.2e7, J=0.04)
    fr.mass("top", MASS)
    soil = SOIL if horizontal == "support" else dict(SOIL, kx=2e4, cx=2e2)
    fr.foundation("footing", "base", width=4.0, length=2.0, patches=(5, 1), soil=soil, mass=10.0,
                  Jx=10.0, Jy=10.0, Jz=10.0, horizontal=horizontal, mu=mu)
    fr.support("base", ux=horizontal == "support", uy=True, uz=False, rx=True, rz=True)
    if p_delta:
        fr.p_delta(g=10.0)
    return fr.build()


def tower2d(p_delta=True):
    fr = Frame2D()
    fr.node("top", 0.0, H)
    fr.node("base", 0.0, 0.0)
    fr.beam("column", "base", "top", E=3e7, A=1.0, I=0.02)
    fr.mass("top", MASS)
    fr.foundation("footing", "base", width=4.0, length=2.0, patches=5, soil=SOIL, mass=10.0, J=10.0)
    if p_delta:
        fr.p_delta(g=10.0)
    return fr.build()


def run(st, gravity, push):
    load = LoadHistory(gravity, [(push, Rectangular(1.0, t_end=0.2))])
    sol = ul.solve(st.to_model(), load, dt=DT, t_end=T_END, method="cq", rule="trapezoidal")
    assert sol.success, sol.message
    return sol, load


def test_a_plane_tower_on_a_footing_with_p_delta_is_the_2d_one():
    st3, st2 = tower3d(), tower2d()
    assert isinstance(st3.to_model(), FoundationModel)
    assert st3.axial_forces["column"] == pytest.approx(st2.axial_forces["column"], rel=1e-12)
    assert st3.axial_forces["column"] == pytest.approx(-MASS * 10.0, rel=1e-12)
    s3, _ = run(st3, st3.gravity(10.0), 60.0 * st3.nodal_load("top", ux=1.0))
    s2, _ = run(st2, st2.gravity(10.0), 60.0 * st2.nodal_load("top", ux=1.0))
    assert s2.v.max() > 1e-4, "the footing must lift for this test to mean something"
    np.testing.assert_allclose(s3.v, s2.v, rtol=0, atol=1e-9 * np.abs(s2.v).max())
    top3 = st3.node_displacement(s3, "top", "ux")
    top2 = st2.node_displacement(s2, "top", "ux")
    assert np.abs(top3 - top2).max() <= 1e-9 * np.abs(top2).max()


def test_the_p_delta_effect_on_a_3d_footing_and_its_energy_balance():
    st, plain = tower3d(), tower3d(p_delta=False)
    push = 60.0 * st.nodal_load("top", ux=1.0)
    with_pd, load = run(st, st.gravity(10.0), push)
    without, _ = run(plain, plain.gravity(10.0), push)
    a, b = st.node_displacement(with_pd, "top", "ux"), plain.node_displacement(without, "top", "ux")
    assert np.abs(a - b).max() >= 0.05 * np.abs(b).max()
    ds = ul.results_dataset(with_pd, st, load=load)
    assert float(np.abs(ds["energy_relative_error"]).max()) <= 1e-9
    assert float(np.abs(ds["energy_geometric"]).max()) > 0


def test_footings_that_slide_in_plan_take_p_delta():
    st, plain = tower3d(horizontal="soil", mu=0.6), tower3d(p_delta=False, horizontal="soil", mu=0.6)
    dense = lambda K: K.toarray() if hasattr(K, "toarray") else np.asarray(K)  # noqa: E731
    np.testing.assert_allclose(dense(st.to_model().K) - dense(plain.to_model().K), st.geometric.toarray(), atol=1e-9)
    push = 60.0 * st.nodal_load("top", ux=1.0)
    a, load = run(st, st.gravity(10.0), push)
    b, _ = run(plain, plain.gravity(10.0), push)
    ua, ub = st.node_displacement(a, "top", "ux"), plain.node_displacement(b, "top", "ux")
    assert np.abs(ua - ub).max() >= 0.05 * np.abs(ub).max()
    ds = ul.results_dataset(a, st, load=load)
    assert float(np.abs(ds["energy_relative_error"]).max()) <= 1e-8


def test_a_3d_footing_at_its_overturning_load_is_refused():
    fr = Frame3D()
    fr.node("top", 0.0, 0.0, H)
    fr.node("base", 0.0, 0.0, 0.0)
    fr.beam("column", "base", "top", E=3e7, A=1.0, Iy=0.02, Iz=0.02, G=1.2e7, J=0.04)
    fr.mass("top", 5e4)
    fr.foundation("footing", "base", width=4.0, length=2.0, patches=(5, 1), soil=SOIL, mass=10.0, Jy=10.0)
    fr.support("base", ux=True, uy=True, uz=False, rx=True, rz=True)
    fr.p_delta(g=10.0)
    with pytest.raises(ValueError, match="p_delta"):
        fr.build().to_model()
