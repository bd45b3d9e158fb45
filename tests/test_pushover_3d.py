"""Pushover of 3-D frames (Frame3D): the portal of tests/pushover_frames.py built in the x-z plane with
polygonal hinges, pushed in its plane (the 2-D events, exactly, with P-Delta too) and out of it (two
cantilevers; with P-Delta the mechanism softens by the gravity over the height)."""

import numpy as np
import pytest
from pushover_frames import A, E, HINGES, I_BEAM, I_COL, H, L, independent_events, portal

from unilateral.pushover import pushover
from unilateral.structure import Frame3D

G = 12.5e6


def portal3d(shape="box", facets=None):
    """The portal (columns 1-2 and 4-3, beam 2-3) in the x-z plane, z up, fixed bases, hinges of
    ``shape`` with the same plastic moment about both axes."""
    fr = Frame3D()
    for n, (x, z) in {1: (0.0, 0.0), 2: (0.0, H), 3: (L, H), 4: (L, 0.0)}.items():
        fr.node(n, x, 0.0, z)
    fr.support(1, rx=True, ry=True, rz=True)
    fr.support(4, rx=True, ry=True, rz=True)
    for name, (i, j, inertia) in {"c1": (1, 2, I_COL), "c2": (4, 3, I_COL), "g": (2, 3, I_BEAM)}.items():
        fr.beam(name, i, j, E=E, A=A, Iy=inertia, Iz=inertia, G=G, J=2 * inertia)
    for name, beam, end, mp in HINGES:
        fr.hinge(name, beam, end, My=mp, Mz=mp, shape=shape, **({} if facets is None else {"facets": facets}))
    fr.mass(2, 10.0)
    fr.mass(3, 10.0)
    return fr.build()


@pytest.mark.parametrize("shape, facets", [("box", None), ("ellipse", 16)])
def test_in_plane_pushover_of_a_3d_portal_is_the_2d_one(shape, facets):
    st = portal3d(shape, facets)
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81)
    assert r.success, r.message
    assert r.load_factor[-1] == pytest.approx(2 * (100.0 + 80.0) / H, rel=1e-9)
    expected = independent_events()
    assert [e.name.split(".")[0] for e in r.events] == [name for name, _, _ in expected]
    for event, (_, P, d) in zip(r.events, expected):
        assert event.load_factor == pytest.approx(P, rel=1e-9)
        assert event.displacement == pytest.approx(d, rel=1e-9)
    assert r.stats["max_residual"] < 1e-10 and r.stats["max_lcp_error"] < 1e-10


def test_out_of_plane_pushover_is_two_cantilevers():
    # pushed along y, both column tops turn alike about x: the beam turns about its axis without
    # twisting, so each column is a cantilever (3 EI / h^3) until its base yields at Mp / h
    st = portal3d()
    r = pushover(st, "triangular", node=2, dof="uy", target=0.1, gravity=9.81)
    assert r.success and [e.name for e in r.events] == ["hb1.facet1", "hb2.facet1"]
    assert r.base_shear[-1] == pytest.approx(2 * 100.0 / H, rel=1e-9)
    k = 2 * 3 * E * I_COL / H ** 3
    assert r.events[0].displacement == pytest.approx(2 * 100.0 / H / k, rel=1e-9)
    ry = st.influence("uy")
    assert ry @ r.pattern == pytest.approx(20.0, rel=1e-12)              # the base shear per unit mass


@pytest.mark.parametrize("form", ["consistent", "string"])
def test_in_plane_pushover_with_p_delta_of_a_3d_portal_is_the_2d_one(form):
    st, plane = portal3d(), portal()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81, p_delta=form)
    r2 = pushover(plane, plane.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81, p_delta=form)
    assert r.success and r2.success and len(r.events) == len(r2.events) == 4
    for event, expected in zip(r.events, r2.events):
        assert event.name.split(".")[0] == expected.name.split(".")[0]
        assert event.load_factor == pytest.approx(expected.load_factor, rel=1e-9)
        assert event.displacement == pytest.approx(expected.displacement, rel=1e-9)
    np.testing.assert_allclose(r.load_factor, r2.load_factor, rtol=0, atol=1e-9 * np.abs(r2.load_factor).max())
    np.testing.assert_allclose(r.displacement, r2.displacement, rtol=0, atol=1e-12)


def test_out_of_plane_pushover_with_p_delta_softens_by_the_gravity_over_the_height():
    st = portal3d()
    N = sum(st.static_axial_forces(st.gravity(9.81))[c] for c in ("c1", "c2"))      # compression, < 0
    k = 2 * 3 * E * I_COL / H ** 3
    string = pushover(st, "triangular", node=2, dof="uy", target=0.1, gravity=9.81, p_delta="string")
    assert string.success and [e.name for e in string.events] == ["hb1.facet1", "hb2.facet1"]
    d = string.events[0].displacement
    assert d == pytest.approx(2 * 100.0 / H / k, rel=1e-9)                  # the elastic base moment reaches Mp
    assert string.base_shear[1] == pytest.approx((k + N / H) * d, rel=1e-9)
    slope = np.diff(string.base_shear)[-1] / np.diff(string.displacement)[-1]
    assert slope == pytest.approx(N / H, rel=1e-9)                          # the leaning columns: sum N / h
    consistent = pushover(st, "triangular", node=2, dof="uy", target=0.1, gravity=9.81, p_delta="consistent")
    slope = np.diff(consistent.base_shear)[-1] / np.diff(consistent.displacement)[-1]
    assert slope == pytest.approx(N / H * 34 / 30, rel=1e-4)                # the nodal cubic (0, 0, d, d/h)


def test_3d_refusals():
    st = portal3d()
    with pytest.raises(ValueError, match="dof='rq' is not valid; use one of 'ux', 'uy', 'uz', 'rx', 'ry', 'rz'"):
        pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="rq", target=0.1)
    with pytest.raises(ValueError, match="dof='rx', which is not a translation; use dof='ux' or 'uy' or 'uz'"):
        pushover(st, "uniform", node=2, dof="rx", target=0.1)
    assert np.all(np.isfinite(pushover(st, "uniform", node=2, dof="ux", target=0.01).base_shear))
