"""Coulomb friction on 3-D rigid contacts (Frame3D.contact(mu, facets), Frame3D.rigid_box(mu)): the
polygonal cone of ``facets`` facets circumscribing Coulomb's circle in the velocity-level LCP of
method="moreau-jean" (march/impact.py; docs/rocking.md, "Friction in 3-D").

The box: plan 2bx x 2by = 1.2 x 1.0 m, height 2h = 0.6 m (bx/h = 2: it slides, it does not rock),
m = 1 t (kN, m, s), mu = 0.3, on a floor accelerating at a = 0.5 g in plan from rest. Newmark's
sliding block: relative to the floor the block accelerates by -(a - mu g) along the floor's
acceleration, u = -(a - mu g) t^2 / 2. With the polygon the friction force is the projection of the
driving force m a on the polygon (the maximal dissipation): u = -(a e - proj(a e)) t^2 / 2, exact
along a facet normal (x; y for facets a multiple of 4).
"""

import math

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.rigid import energy_balance
from unilateral.constraints.families import friction_polygon
from unilateral.loads import LoadHistory
from unilateral.structure import Frame2D, Frame3D, rigid, rigid3d

G, MU, A = 9.81, 0.3, 0.5 * 9.81


def _box(mu=MU, facets=8, width_x=1.2, width_y=1.0, height=0.6, **kw):
    fr = Frame3D()
    fr.node("c", 0.0, 0.0, height / 2)
    box = fr.rigid_box("B", "c", width_x=width_x, width_y=width_y, height=height, mass=1.0, mu=mu, g=G,
                       facets=facets, **kw)
    st = fr.build()
    return st, st.to_model(), box


def _run(st, model, extra=(), dt=5e-3, t_end=0.4, initial="rest"):
    load = LoadHistory(st.gravity(G), list(extra))
    sol = ul.solve(model, load, dt=dt, t_end=t_end, method="moreau-jean", rule="trapezoidal", initial=initial)
    assert sol.success, sol.message
    return sol


def _slide(phi, a=A, facets=8, **kw):
    st, model, box = _box(facets=facets)
    e = (math.cos(phi), math.sin(phi), 0.0)
    sol = _run(st, model, [rigid3d.ground_motion(st, lambda t: a, e)], **kw)
    return st, model, sol


def _plan(sol):
    return np.column_stack([sol.dof("B.base.ux"), sol.dof("B.base.uy")])


def project(p, facets, r):
    """The projection of ``p`` (2,) on the polygon of ``facets`` facets at distance ``r``
    (facet normals at 2 pi k / facets): the nearest of its vertices and of the feet on its edges."""
    normals, vertices = friction_polygon(facets)
    if np.all(normals @ p <= r):
        return p
    vertices = r * vertices
    best = min(vertices, key=lambda v: np.linalg.norm(p - v))
    for k in range(facets):
        a, b = vertices[k - 1], vertices[k]          # the edge of facet k: vertices k - 1 and k
        s = np.clip((p - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0)
        foot = a + s * (b - a)
        if np.linalg.norm(p - foot) < np.linalg.norm(p - best):
            best = foot
    return best


# ---------------------------------------------------------------------- (a) sliding, Newmark's block
@pytest.mark.parametrize("phi", [0.0, math.pi / 2, math.pi])
def test_a_box_slides_along_x_and_y_by_newmarks_closed_form(phi):
    """Along x, y and -x (facet normals of the 8-facet polygon): u = -(a - mu g) e t^2 / 2 to 1e-9,
    no tilt, no twist; the friction work mu W |u|; the balance closes to round-off."""
    st, model, sol = _slide(phi)
    e = np.array([math.cos(phi), math.sin(phi)])
    exact = -0.5 * (A - MU * G) * np.outer(sol.t ** 2, e)
    np.testing.assert_allclose(_plan(sol), exact, rtol=0, atol=1e-9 * np.abs(exact).max())
    assert np.abs(sol.u[:, 2:]).max() < 1e-12                      # uz, rx, ry, rz
    energy = energy_balance(model, sol)
    assert energy["relative_error"] < 1e-12
    assert energy["friction_work"][-1] == pytest.approx(MU * G * np.linalg.norm(_plan(sol)[-1]), rel=1e-9)
    np.testing.assert_allclose(sol.v[1:], G / 4, rtol=0, atol=0.3 * G)        # every corner carries
    np.testing.assert_allclose(sol.v[1:].sum(axis=1), G, rtol=1e-9)


def test_a_skew_slide_is_the_polygons_projection_and_converges_to_coulombs_cone():
    """Along 30 degrees: the slip is the polygon's closed form (a e - proj(a e)) t^2 / 2 to 1e-9 for
    every facets; its error from Coulomb's circle falls as 1/facets (the direction of the slip,
    which leaves e by up to pi/facets) and the slip along e as 1/facets^2 (fitted on 16, 32, 64;
    measured 1.035 and 2.01; 54 %, 24 %, 10 %, 5.0 %, 2.5 % for 4 .. 64 facets)."""
    phi = math.pi / 6
    e = np.array([math.cos(phi), math.sin(phi)])
    circle = -0.5 * (A - MU * G) * e
    facets, error, along = (4, 8, 16, 32, 64), [], []
    for f in facets:
        st, model, sol = _slide(phi, facets=f, dt=0.02, t_end=0.2)
        polygon = -0.5 * (A * e - project(A * e, f, MU * G))
        np.testing.assert_allclose(_plan(sol), np.outer(sol.t ** 2, polygon), rtol=0, atol=1e-9 * 0.04)
        assert energy_balance(model, sol)["relative_error"] < 1e-12
        error.append(np.linalg.norm(polygon - circle) / np.linalg.norm(circle))
        along.append(abs((polygon - circle) @ e) / np.linalg.norm(circle))
    order = -np.polyfit(np.log(facets[2:]), np.log(error[2:]), 1)[0]        # asymptotic: 16, 32, 64
    order_along = -np.polyfit(np.log(facets[2:]), np.log(along[2:]), 1)[0]
    print(f"skew 30 deg: relative error vs facets {dict(zip(facets, np.round(error, 6)))}, order {order:.3f}; "
          f"along e {dict(zip(facets, np.round(along, 8)))}, order {order_along:.3f}")
    assert error[-1] < 0.03 and np.all(np.diff(error) < 0) and np.all(np.diff(along) < 0)
    assert order == pytest.approx(1.0, abs=0.05) and order_along == pytest.approx(2.0, abs=0.1)


# ---------------------------------------------------------------------- (b) the plane case
@pytest.mark.parametrize("width, height, mu, a", [(1.2, 0.6, 0.3, 0.5), (0.4, 1.2, 0.5, 0.45)])
def test_a_box_on_a_floor_moving_along_x_is_the_2d_block_with_friction(width, height, mu, a):
    """Sliding (a wide box, mu < a) and rocking (a slender one, mu > b/h, a > b/h): the 3-D box's ux and
    ry equal the 2-D block's ux and -rz (J = Jy) to 1e-12, the other DOFs stay 0."""
    st, model, box = _box(mu=mu, width_x=width, width_y=0.8, height=height)
    sol = _run(st, model, [rigid3d.ground_motion(st, lambda t: a * G, "ux")], dt=1e-3, t_end=0.5)
    fr = Frame2D()
    fr.node("c", 0.0, height / 2)
    fr.rigid_block("B", "c", width=width, height=height, mass=1.0, J=box.Jy, mu=mu, g=G)
    st2 = fr.build()
    sol2 = _run(st2, st2.to_model(), [rigid.ground_motion(st2, lambda t: a * G)], dt=1e-3, t_end=0.5)
    np.testing.assert_allclose(sol.dof("B.base.ux"), sol2.dof("B.base.ux"), rtol=0, atol=1e-12)
    np.testing.assert_allclose(sol.dof("B.base.ry"), -sol2.dof("B.base.rz"), rtol=0, atol=1e-12)
    np.testing.assert_allclose(sol.dof("B.base.uz"), sol2.dof("B.base.uy"), rtol=0, atol=1e-12)
    for dof in ("uy", "rx", "rz"):
        assert np.abs(sol.dof(f"B.base.{dof}")).max() < 1e-12
    assert max(np.abs(sol.dof("B.base.ux")).max(), np.abs(sol.dof("B.base.ry")).max()) > 1e-3


# ---------------------------------------------------------------------- (c) below mu g
@pytest.mark.parametrize("phi", [0.0, math.pi / 2, 0.3, 2.0])
def test_below_mu_g_nothing_slides(phi):
    """a = 0.95 mu g in any direction: within the polygon (it contains the circle): no slip."""
    st, model, sol = _slide(phi, a=0.95 * MU * G)
    assert np.abs(sol.u).max() < 1e-13
    assert np.abs(energy_balance(model, sol)["friction_work"]).max() < 1e-15


# ---------------------------------------------------------------------- (d) energy
def test_a_box_dropped_skew_and_spinning_loses_its_energy_to_impacts_and_friction():
    """Released 1 cm above the floor, tilted, moving in plan at 0.5 m/s along 40 degrees and spinning
    (e = 0.5): the impacts with friction and the sliding bring it to rest; the balance closes to
    round-off and the energy above the rest went to the impact losses and the friction work."""
    st, model, box = _box(width_x=0.8, width_y=0.6, height=0.6, restitution=0.5)
    u0, v0 = np.zeros(st.n), np.zeros(st.n)
    for dof, value in (("uz", 0.01 + 0.3 * 0.01), ("ry", 0.01)):
        u0[st.dofs.index("B.base", dof)] = value
    for dof, value in (("ux", 0.5 * math.cos(0.7)), ("uy", 0.5 * math.sin(0.7)), ("rz", 0.8)):
        v0[st.dofs.index("B.base", dof)] = value
    sol = _run(st, model, dt=1e-3, t_end=1.0, initial={"u0": u0, "udot0": v0})
    energy = energy_balance(model, sol)
    print(f"energy: relative error {energy['relative_error']:.2e}, impacts {len(sol.stats['impacts'])}, "
          f"impact loss {energy['impact_loss'][-1]:.6g}, friction work {energy['friction_work'][-1]:.6g}")
    assert energy["relative_error"] < 1e-12
    assert energy["impact_loss"][-1] > 0 and energy["friction_work"][-1] > 0
    assert np.abs(sol.udot[-50:]).max() < 1e-12
    e0 = rigid3d.box_energy(st, sol, "B")
    assert energy["impact_loss"][-1] + energy["friction_work"][-1] == pytest.approx(e0[0] - e0[-1], rel=1e-9)


# ---------------------------------------------------------------------- (e) twist
def _twist_factor(box, facets):
    """The polygon's frictional torque over Coulomb's mu W r for a box spinning about its centre: the
    corner (bx, by) slides along phi = atan2(bx, -by); on a facet normal 1, else the vertex between
    the normals around phi, cos(phi - vertex) / cos(pi / facets)."""
    phi = math.atan2(box.bx, -box.by) % (2 * math.pi)
    sector = 2 * math.pi / facets
    k = math.floor(phi / sector + 1e-12)
    if abs(phi - k * sector) < 1e-12:
        return 1.0
    return math.cos(phi - (k + 0.5) * sector) / math.cos(math.pi / facets)


@pytest.mark.parametrize("width_x, width_y, facets, factor", [(0.8, 0.8, 8, 1.0), (0.8, 0.8, 4, math.sqrt(2)),
                                                               (1.2, 0.8, 16, None), (1.2, 0.8, 64, None)])
def test_a_spinning_box_is_stopped_by_the_frictional_torque_of_its_corners(width_x, width_y, facets, factor):
    """An initial spin w0 about the vertical: the four corners slide on circles of radius r and their
    friction is a torque mu W r c (c = 1: Coulomb's, a square box on 8 facets, whose corners slide
    along facet normals; sqrt(2) on 4 facets, along the vertices; else the polygon's c in [1,
    sec(pi/facets)]): rz = w0 t - alpha t^2 / 2 with alpha = mu W r c / Jz to 1e-12 until the box
    stops at w0 / alpha, then it stays; the centre does not move."""
    st, model, box = _box(width_x=width_x, width_y=width_y, facets=facets)
    c = _twist_factor(box, facets)
    if factor is not None:
        assert c == pytest.approx(factor, rel=1e-12)
    r = math.hypot(box.bx, box.by)
    alpha = MU * box.W * r * c / box.Jz
    w0 = 0.2 * alpha                                       # stops at t = 0.2, on the grid
    v0 = np.zeros(st.n)
    v0[st.dofs.index("B.base", "rz")] = w0
    sol = _run(st, model, dt=5e-3, t_end=0.3, initial={"u0": np.zeros(st.n), "udot0": v0})
    t = np.minimum(sol.t, 0.2)
    np.testing.assert_allclose(sol.dof("B.base.rz"), w0 * t - 0.5 * alpha * t ** 2, rtol=0, atol=1e-12)
    assert np.abs(np.delete(sol.u, st.dofs.index("B.base", "rz"), axis=1)).max() < 1e-12
    assert 1.0 <= c <= 1.0 / math.cos(math.pi / facets) + 1e-15
    assert energy_balance(model, sol)["relative_error"] < 1e-12


def test_a_torque_below_the_frictional_torque_does_not_twist_the_box_and_one_above_does():
    """A constant torque Mz on the box: below mu W r (facets = 8, a square box) nothing moves; at 1.5
    times it the box twists with (Mz - mu W r) / Jz."""
    st, model, box = _box(width_x=0.8, width_y=0.8)
    strength = MU * box.W * math.hypot(box.bx, box.by)
    for ratio in (0.95, 1.5):
        torque = np.zeros(st.n)
        torque[st.dofs.index("B.base", "rz")] = ratio * strength
        sol = _run(st, model, [(torque, lambda t: 1.0)], t_end=0.2)
        expected = 0.5 * max(0.0, (ratio - 1.0) * strength) / box.Jz * sol.t ** 2
        np.testing.assert_allclose(sol.dof("B.base.rz"), expected, rtol=0, atol=1e-12)


# ---------------------------------------------------------------------- (f) bad input
def test_bad_friction_input_is_refused_by_name():
    fr = Frame3D()
    fr.node("c", 0.0, 0.0, 0.3)
    fr.node(1, 0.0, 0.0, 0.0)
    fr.mass(1, 1.0)
    box = dict(width_x=0.4, width_y=0.4, height=0.6, mass=1.0)
    for kw, message in [(dict(mu=-0.1), "mu=-0.1 must be finite and >= 0"),
                        (dict(mu=0.3, facets=3), "facets=3 is not valid.*even int >= 4"),
                        (dict(mu=0.3, facets=2), "facets=2 is not valid"),
                        (dict(mu=0.3, facets=5), "facets=5 is not valid"),
                        (dict(mu=0.3, facets=8.0), "facets=8.0 is not valid"),
                        (dict(facets=8), "facets=8 is a friction parameter; give the friction coefficient mu")]:
        with pytest.raises(ValueError, match=message):
            fr.rigid_box("B", "c", **box, **kw)
        with pytest.raises(ValueError, match=message):
            fr.contact("k", 1, **kw)
    with pytest.raises(ValueError, match="tangent=.*is a friction parameter"):
        fr.contact("k", 1, tangent=(1.0, 1.0, 0.0))
    with pytest.raises(ValueError, match="tangent=.*along the contact's direction"):
        fr.contact("k", 1, mu=0.3, tangent=(0.0, 0.0, 1.0))


@pytest.mark.parametrize("method, rule", [("direct", "bdf1"), ("cq", "trapezoidal"), ("event", "trapezoidal")])
def test_methods_without_friction_on_rigid_contacts_name_the_one_that_has_it(method, rule):
    st, model, box = _box()
    with pytest.raises(ValueError, match=r"friction \(mu > 0\), which only method='moreau-jean' takes"):
        ul.solve(model, LoadHistory(st.gravity(G)), dt=1e-3, t_end=0.01, method=method, rule=rule, initial="rest")


def test_a_contact_with_a_turned_polygon_slides_along_its_facet_normal(tmp_path):
    """Frame3D.contact(mu, facets=4, tangent=(1, 1, 0)): a mass on a floor pushed along the diagonal
    (a facet normal of the turned pyramid) slides by Coulomb's closed form; the model-file keys
    mu and facets of a 3-D [[contacts]] build the same contact."""
    from unilateral.modelfile import load_model_file

    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.support(1, ux=False, uy=False, uz=False, rx=True, ry=True, rz=True)
    fr.mass(1, 1.0)
    fr.contact("floor", 1, mu=MU, facets=4, tangent=(1.0, 1.0, 0.0))
    st = fr.build()
    e = np.array([1.0, 1.0, 0.0]) / math.sqrt(2)
    sol = _run(st, st.to_model(), [rigid3d.ground_motion(st, lambda t: A, tuple(e))])
    slip = np.column_stack([sol.dof("1.ux"), sol.dof("1.uy")])
    np.testing.assert_allclose(slip, -0.5 * (A - MU * G) * np.outer(sol.t ** 2, e[:2]), rtol=0, atol=1e-12)
    text = ('[units]\nlength = "m"\nforce = "kN"\ntime = "s"\n\n[frame]\ndimensions = 3\n\n'
            '[[nodes]]\nid = 1\nx = 0.0\ny = 0.0\nz = 0.3\n\n[[rigid_blocks]]\nname = "B"\nnode = 1\nwidth = 1.2\n'
            'width_y = 1.0\nheight = 0.6\nmass = 1.0\nmu = 0.3\nfacets = 16\n\n[loads.gravity]\ng = 9.81\n\n'
            '[analysis]\ndt = 0.005\nt_end = 0.2\nmethod = "moreau-jean"\nrule = "trapezoidal"\ninitial = "rest"\n')
    (tmp_path / "m.toml").write_text(text)
    spec = load_model_file(tmp_path / "m.toml")
    family = [f for f in spec.model.families if f.impact_law][0]
    assert family.facets.tolist() == [16] * 4 and family.mu.tolist() == [0.3] * 4
    assert spec.model.dof_names[:2] == ["B.base.ux", "B.base.uy"]
