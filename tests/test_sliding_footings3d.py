"""Rigid footings of a Frame3D that slide in plan and twist through the horizontal soil.

Each patch of a footing with ``horizontal="soil"`` carries ``(fx, fy)`` through the soil's x-y-z
flexibility, limited by a polygonal Coulomb cone of ``facets`` facets (``d_k . f <= mu c``); the
footing's horizontal displacement at a patch includes its twist. Checked against the 2-D sliding
footing (one row of patches under a plane frame), the paper's primal form (Kelvin soil stepped
directly) and the modal route, the friction law step by step, a footing twisted by a torque
(rigid-body torsional stiffness of the patches against published values), the point contact
with a friction cone of the same facets and springs, and the model file.
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.loads import LoadHistory, Rectangular
from unilateral.soil.flexibility import facet_normals
from unilateral.methods.foundation_solve import primal_columns
from unilateral.structure import Frame2D, Frame3D

HALF = {"model": "halfspace", "Vs": 97.0, "nu": 1 / 3, "rho": 2.0}
KELVIN = {"model": "winkler-kelvin", "k": 2e5, "c": 2e3, "kx": 1.5e5, "cx": 1.5e3}
COLUMN = dict(E=3e7, A=0.5, Iy=0.05, Iz=0.05, G=1.2e7, J=0.08)


def rel(a, b):
    return float(np.abs(a - b).max() / np.abs(b).max())


def tower(soil, mu, *, facets=4, patches=(2, 2), amplitude=8.0, angle=0.5):
    """A column with a top mass on a rigid footing that slides in plan, under a horizontal pulse at
    ``angle`` from x (a ground acceleration)."""
    fr = Frame3D()
    fr.node("base", 0.0, 0.0, 0.0)
    fr.node("top", 0.0, 0.0, 6.0)
    fr.beam("col", "base", "top", **COLUMN)
    fr.mass("top", 40.0, Jz=10.0)
    fr.foundation("F", "base", width=4.0, length=4.0, soil=soil, patches=patches, horizontal="soil", mu=mu,
                  facets=facets, mass=20.0, Jx=30.0, Jy=30.0, Jz=30.0)
    st = fr.build()
    gravity = st.gravity(9.81)
    d = np.cos(angle) * st.influence("ux") + np.sin(angle) * st.influence("uy")

    def load(t):
        return gravity - st.M @ d * (amplitude * np.sin(2 * np.pi * t) * (t < 1.0))

    return st, load


# ---------------------------------------------------------------------- the model
def test_the_model_of_a_footing_that_slides_in_plan():
    st, _ = tower(KELVIN, 0.3, facets=8)
    model = st.to_model()
    ms = 4
    assert model.sliding and model.horizontal == 2 and model.facets == 8 and model.m == ms * (3 + 8)
    assert model.soil.m == 3 * ms
    assert model.constraint_names[ms:ms + 2] == ["F.1.shear_x", "F.2.shear_x"]
    assert model.constraint_names[3 * ms:3 * ms + 3] == ["F.1.facet0", "F.1.facet4", "F.1.facet1"]
    d = facet_normals(2, 8)
    np.testing.assert_allclose(d[:, 0] ** 2 + d[:, 1] ** 2, 1.0)
    np.testing.assert_array_equal(d[0::2], -d[1::2])                    # opposite facets in pairs
    law = model.law
    assert law.free[model.shears].all() and law.rate[model.slips].all() and not law.free[model.slips].any()
    assert law.Q[model.slips[0], model.contacts[0]] == 0.3
    assert law.partner[model.slips[0]] == model.slips[1]
    # the twist: x = ux - (y_j - y_0) rz, y = uy + (x_j - x_0) rz
    fnd = st.foundation.footings[0]
    rz = st.dofs.names.index("base.rz")
    np.testing.assert_allclose(model.Tx[rz], -fnd.patches.centres[:, 1])
    np.testing.assert_allclose(model.Ty[rz], fnd.patches.centres[:, 0])
    # the weights' constant coupling: the facet rows hold d_k . f, the shear rows the slip
    W = model.weights(4, 1e-3, "bdf2")
    np.testing.assert_array_equal(W[0, model.shears[[0, ms]], model.slips[2]], -d[2])


@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_a_footing_that_rocks_lifts_slides_and_twists_equals_the_papers_kelvin_elements(rule):
    """Kelvin soil: the mixed CLCP (cq, shears eliminated) equals direct stepping of the primal form
    (springs in series with the facets' sliders), and the modal route takes that form."""
    st, load = tower(KELVIN, 0.2)
    model = st.to_model()
    kw = dict(dt=2e-3, t_end=2.0, rule=rule)
    dual = ul.solve(model, load, method="cq", **kw)
    primal = ul.solve(model.kelvin_model(), load, method="direct", **kw)
    assert dual.success and primal.success, dual.message
    v, psi = primal_columns(model, primal.v, primal.psi)
    assert rel(dual.u, primal.u) < 1e-8
    assert rel(dual.psi, psi) < 1e-7 and rel(dual.v, v) < 1e-7
    slips = st.foundation.slips(dual)
    assert np.abs(slips[-1]).min() > 1e-2 and dual.v[:, :4].max() > 1e-2      # it slid both ways and lifted
    assert abs(st.node_displacement(dual, "base", "rz")[-1]) > 1e-3            # and twisted
    if rule == "bdf2":
        modal = ul.solve(model, load, method="modal", **kw)
        assert modal.success and modal.constraint_names == dual.constraint_names
        assert rel(modal.u, dual.u) < 1e-8 and rel(modal.psi, dual.psi) < 1e-7


# ---------------------------------------------------------------------- against the 2-D footing
def test_a_row_of_patches_that_slides_is_the_2d_sliding_footing():
    """nx x 1 patches under a frame in the x-z plane, 4 facets: the facet pair (+x, -x) is the 2-D
    slip pair, the y facets never slip, and the run equals the 2-D sliding footing of the same
    strips on the same half-space (its x-z block of the x-y-z tensor)."""
    n, mu = 5, 0.3
    fr3 = Frame3D()
    fr3.node("top", 0.0, 0.0, 8.0)
    fr3.node("base", 0.0, 0.0, 0.0)
    fr3.beam("column", "base", "top", E=3e7, A=1.0, Iy=1.0, Iz=1.0, G=1.2e7, J=1.5)
    fr3.mass("top", 40.0)
    fr3.foundation("footing", "base", width=6.0, length=3.0, patches=(n, 1), soil=HALF, horizontal="soil", mu=mu,
                   facets=4, mass=2.0, Jz=5.0)
    fr3.support("base", ux=False, uy=False, uz=False, rx=True)    # one row of patches: no soil about x
    st3 = fr3.build()
    fr2 = Frame2D()
    fr2.node("top", 0.0, 8.0)
    fr2.node("base", 0.0, 0.0)
    fr2.beam("column", "base", "top", E=3e7, A=1.0, I=1.0)
    fr2.mass("top", 40.0)
    fr2.foundation("footing", "base", width=6.0, length=3.0, patches=n, soil=HALF, horizontal="soil", mu=mu,
                   mass=2.0)
    st2 = fr2.build()
    def pulse(st, P):
        return LoadHistory(st.gravity(10.0), [(P * st.nodal_load("top", ux=1.0), Rectangular(1.0, t_end=0.1))])
    s3 = ul.solve(st3.to_model(), pulse(st3, 400.0), dt=2e-3, t_end=0.6, method="cq")
    s2 = ul.solve(st2.to_model(), pulse(st2, 400.0), dt=2e-3, t_end=0.6, method="cq")
    assert s3.success and s2.success, s3.message
    assert s2.v[:, :n].max() > 1e-3 and np.abs(s2.v[:, n:2 * n]).max() > 1e-2      # it lifts and slides
    close = lambda a, b: np.testing.assert_allclose(a, b, rtol=0, atol=1e-8 * np.abs(b).max())
    close(s3.psi[:, :n], s2.psi[:, :n])                                          # contact forces
    close(s3.v[:, :n], s2.v[:, :n])                                              # openings
    close(s3.psi[:, n:2 * n], s2.psi[:, n:2 * n])                                # shears along x
    close(s3.v[:, n:2 * n], s2.v[:, n:2 * n])                                    # net slips along x
    facets3 = s3.v[:, 3 * n:].reshape(-1, n, 4)
    close(facets3[..., :2], s2.v[:, 2 * n:].reshape(-1, n, 2))                   # the (+x, -x) pair
    assert np.abs(facets3[..., 2:]).max() == 0.0 and np.abs(s3.psi[:, 2 * n:3 * n]).max() == 0.0
    for d3, d2, sign in (("ux", "ux", 1.0), ("uz", "uy", 1.0), ("ry", "rz", -1.0)):
        close(st3.node_displacement(s3, "base", d3), sign * st2.node_displacement(s2, "base", d2))
    assert np.abs(st3.node_displacement(s3, "base", "rz")).max() == 0.0


# ---------------------------------------------------------------------- the friction law
def test_the_friction_cone_holds_at_every_step_for_every_patch():
    """3 x 3 patches on the half-space, 8 facets, a pulse at 0.5 rad from x: c >= 0; every facet
    function d_k . f - mu c <= 0; a facet's multiplier grows only where its function is 0;
    complementarity of the increments; at most two (adjacent) facets of a patch slip in a step."""
    mu, N = 0.25, 8
    st, load = tower(HALF | {"Vs": 120.0}, mu, facets=N, patches=(3, 3), amplitude=6.0)
    model = st.to_model()
    sol = ul.solve(model, load, method="cq", dt=4e-3, t_end=1.2)
    assert sol.success, sol.message
    ms = 9
    fnd = st.foundation
    c = fnd.contact_forces(sol)
    h = fnd.shear_forces(sol)                                # the soil's force on the footing: -f
    f = -h
    lam = fnd.facet_slips(sol)                               # (N+1, ms, N)
    d = model.directions
    scale = c.max()
    tol = 1e-9 * scale
    assert c.min() >= 0.0
    phi = f @ d.T - mu * c[..., None]                        # the facet functions
    assert phi.max() < tol
    np.testing.assert_allclose(sol.psi[:, 3 * ms:].reshape(-1, ms, N), phi, rtol=0, atol=tol)
    dlam = np.diff(lam, axis=0)
    assert dlam.min() >= -1e-14
    moving = dlam > 1e-12
    assert moving.sum() > 50                                 # it slid
    assert np.abs(phi[1:][moving]).max() < 1e-8 * scale      # only on facets at the limit
    assert np.abs(dlam * phi[1:]).max() < 1e-9 * scale * np.abs(lam).max()
    assert moving.sum(axis=-1).max() <= 2                    # a facet or a vertex
    assert np.abs(np.hypot(f[..., 0], f[..., 1])[c <= 0]).max(initial=0.0) < tol     # open: no shear
    # the net slip is the facets' sum_k lambda_k d_k
    np.testing.assert_allclose(fnd.slips(sol), lam @ d, rtol=0, atol=1e-12 * np.abs(lam).max())
    assert sol.v[:, :ms].max() > 1e-3 and np.abs(fnd.slips(sol)[-1]).max() > 1e-2


# ---------------------------------------------------------------------- torsion
def rigid_stiffness(soil, patches):
    """(3, 3) static stiffness of a rigid footing in ``(ux, uy, rz)`` about its centre from the
    patches' x-y-z flexibility: ``A^T Phi(0)^-1 A``."""
    m = patches.m
    x, y = (patches.centres - patches.centres.mean(axis=0)).T
    A = np.zeros((3 * m, 3))
    A[:m, 0], A[m:2 * m, 1], A[:m, 2], A[m:2 * m, 2] = 1.0, 1.0, -y, x
    return A.T @ np.linalg.solve(soil.static(), A)


def test_the_torsional_stiffness_of_the_patches_converges_to_the_rigid_square():
    """A rigid square footing (side a) on the elastic half-space (nu = 1/4) twisted about z: its
    stiffness from n x n patches grows with n and tends to the published values: Gazetas (1991)
    ``K_t = 4 G J_t^0.75`` with the polar moment ``J_t = a^4 / 6`` (1.0434 G a^3), and the rigid
    disc of the same J_t, ``16 G r^3 / 3`` (0.9915 G a^3). Measured: 0.717, 0.899, 0.983, 1.011
    G a^3 for n = 2, 4, 8, 12; extrapolated (error ~1/n, from 6 and 12) 1.066."""
    from unilateral.soil import HalfSpace, SoilFlexibility
    from unilateral.soil.patches import grid

    G, a = 1.0, 2.0
    gazetas = 4.0 * G * (a ** 4 / 6.0) ** 0.75
    Kt = {}
    for n in (2, 4, 6, 8, 12):
        p = grid(a, a, n, n)
        K = rigid_stiffness(SoilFlexibility.halfspace(HalfSpace(G, 0.25, 1.0), p, components="xyz"), p)
        assert abs(K[0, 2]) < 1e-12 * K[2, 2] and abs(K[1, 2]) < 1e-12 * K[2, 2]    # twist uncoupled from sway
        Kt[n] = K[2, 2]
    values = [Kt[n] for n in sorted(Kt)]
    assert np.all(np.diff(values) > 0)
    assert 0.96 < Kt[12] / gazetas < 0.98
    extrapolated = 2.0 * Kt[12] - Kt[6]
    assert abs(extrapolated / gazetas - 1.0) < 0.03


def test_a_square_footing_under_a_torque_rotates_about_its_centre():
    """A torque about z only on a square footing of 4 x 4 patches (gravity holds every patch down,
    mu large: no slip): the static state rotates it about its centre by T / K_t (K_t from the
    patches), without sway; the patches' shear forces have no resultant, their moment is the
    torque, and on the grid's diagonals they are tangential to round-off (off them the rigid
    square's tractions have a radial part: up to 9 % of the patch's force here). The shears of the
    weight alone (radial: the soil's surface drawn inward, nu < 1/2) are taken off first."""
    fr = Frame3D()
    fr.node("base", 0.0, 0.0, 0.0)
    fr.foundation("F", "base", width=4.0, length=4.0, patches=(4, 4), soil=HALF, horizontal="soil", mu=10.0,
                  mass=100.0, Jx=100.0, Jy=100.0, Jz=100.0)
    st = fr.build()
    model = st.to_model()
    torque = 500.0
    q = st.gravity(10.0) + st.nodal_load("base", rz=torque)
    sol = ul.solve(model, lambda t: q, dt=2e-3, t_end=0.1, method="cq", initial="static")
    assert sol.success, sol.message
    fnd = st.foundation
    patches = fnd.footings[0].patches
    Kt = rigid_stiffness(fnd.soil, patches)[2, 2]
    u = {dof: st.node_displacement(sol, "base", dof) for dof in ("ux", "uy", "uz", "rx", "ry", "rz")}
    assert u["rz"][0] == pytest.approx(torque / Kt, rel=1e-9)
    for dof in ("ux", "uy", "rx", "ry"):
        assert np.abs(u[dof]).max() < 1e-9 * np.abs(u["rz"]).max() * 4.0
    np.testing.assert_allclose(u["rz"], u["rz"][0], rtol=1e-9)              # a constant load: it stays
    # the vertical load alone draws the surface inward under a compressible soil (Cerruti): radial
    # shears of its own; the torque's are the difference
    weight = ul.solve(model, lambda t: st.gravity(10.0), dt=2e-3, t_end=2e-3, method="cq", initial="static")
    h = fnd.shear_forces(sol)[0] - fnd.shear_forces(weight)[0]               # (16, 2) on the footing
    x, y = (patches.centres - patches.centres.mean(axis=0)).T
    assert np.abs(h.sum(axis=0)).max() < 1e-9 * np.abs(h).max()
    assert (x * h[:, 1] - y * h[:, 0]).sum() == pytest.approx(-torque, rel=1e-9)
    radial = (h[:, 0] * x + h[:, 1] * y) / np.hypot(x, y) / np.hypot(*h.T)
    symmetric = np.isclose(np.abs(x), np.abs(y))                             # the diagonals (4 x 4: no axes)
    assert symmetric.sum() == 8
    assert np.abs(radial[symmetric]).max() < 1e-10
    assert 0.01 < np.abs(radial).max() < 0.15
    assert np.all(fnd.facet_slips(sol) == 0.0) and (-sol.psi[:, :16]).min() > 0


# ---------------------------------------------------------------------- the polygon's slip direction
MU, GRAVITY, KT = 0.5, 10.0, 1e5


def pushed(frame, P, alpha, node):
    st = frame.build()
    weight = st.gravity(GRAVITY, (0.0, 0.0, -1.0))
    unit = st.nodal_load(node, ux=np.cos(alpha), uy=np.sin(alpha))
    return st, lambda t: weight + P * min(t, 1.0) * unit


def projection(P, N):
    """The point of the polygon (strength mu W along its facet normals) nearest to ``P`` (2,)."""
    th = 2 * np.pi * np.arange(N) / N
    vertices = MU * GRAVITY / np.cos(np.pi / N) * np.column_stack([np.cos(th + np.pi / N), np.sin(th + np.pi / N)])
    best = None
    for a, b in zip(vertices, np.roll(vertices, -1, axis=0)):
        s = np.clip((P - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0)
        x = a + s * (b - a)
        if best is None or np.linalg.norm(P - x) < np.linalg.norm(P - best):
            best = x
    return best


@pytest.mark.parametrize("N", [4, 8])
def test_a_footing_pushed_between_two_facets_slides_as_the_point_contact_with_a_friction_cone(N):
    """A unit mass on a footing of 2 x 2 Winkler-Kelvin patches (k/4, kx/4 each) pushed at its base
    neither rocks nor twists: it is the block on a point contact with a friction cone of the same
    facets (k, kt = kx). Pushed at 0.3 rad from x (between facets 0 and 1) the two runs agree, and
    in steady sliding the footing moves along ``P - proj(P)`` (the polygon's normal cone), within
    pi/N of the push."""
    alpha, P, dt = 0.3, 2 * MU * GRAVITY, 0.005
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.foundation("F", 1, width=1.0, length=1.0, patches=2, horizontal="soil", mu=MU, facets=N, mass=1.0,
                  Jx=1.0, Jy=1.0, Jz=1.0, soil={"model": "winkler-kelvin", "k": 1e6 / 4, "kx": KT / 4})
    fr.rayleigh(a0=20.0)
    st, load = pushed(fr, P, alpha, 1)
    sol = ul.solve(st.to_model(), load, dt=dt, t_end=2.5, method="cq", rule="trapezoidal")
    assert sol.success, sol.message
    block = Frame3D()
    block.node(1, 0.0, 0.0, 0.0)
    block.mass(1, 1.0)
    block.soil("s", 1, 1e6, mu=MU, kt=KT, facets=N)
    block.rayleigh(a0=20.0)
    stb, loadb = pushed(block, P, alpha, 1)
    ref = ul.solve(stb.to_model(), loadb, dt=dt, t_end=2.5, method="direct", rule="trapezoidal")
    assert ref.success
    ours = np.column_stack([st.node_displacement(sol, 1, dof) for dof in ("ux", "uy", "uz")])
    theirs = np.column_stack([stb.node_displacement(ref, 1, dof) for dof in ("ux", "uy", "uz")])
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-7 * np.abs(theirs).max())
    tail = int(round(0.5 / dt))
    du = ours[-1, :2] - ours[-1 - tail, :2]
    direction = np.arctan2(du[1], du[0])
    Pv = P * np.array([np.cos(alpha), np.sin(alpha)])
    expected = Pv - projection(Pv, N)
    assert direction == pytest.approx(np.arctan2(expected[1], expected[0]), abs=1e-6)
    assert abs(direction - alpha) <= np.pi / N
    assert np.hypot(*du) > 0.1


# ---------------------------------------------------------------------- bad input
@pytest.mark.parametrize("kwargs, match", [
    (dict(horizontal="soil"), "needs mu"),
    (dict(horizontal="soil", mu=0.0), "needs mu"),
    (dict(horizontal="support", mu=0.3), "mu=0.3 is for a footing that slides"),
    (dict(horizontal="none", facets=8), "facets=8 is for a footing that slides"),
    (dict(horizontal="soil", mu=0.3, facets=5), "facets=5 is not valid; .*even int >= 4"),
    (dict(horizontal="soil", mu=0.3, facets=2), "facets=2 is not valid"),
    (dict(horizontal="soil", mu=0.3, soil={"model": "winkler-kelvin", "k": 1e5}), "needs kx"),
    (dict(horizontal="soil", mu=0.3, soil=HALF | {"kx": 1.0}), "kx and cx are for model='winkler-kelvin'"),
    (dict(horizontal="sliding"), "horizontal='sliding' is not valid for a 3-D footing; valid: 'support', 'none', "
                                 "'soil'"),
])
def test_bad_3d_sliding_footings_are_refused(kwargs, match):
    fr = Frame3D()
    fr.node("a", 0.0, 0.0, 0.0)
    args = dict(width=2.0, length=2.0, soil=KELVIN, patches=2) | kwargs
    with pytest.raises(ValueError, match=match):
        fr.foundation("F", "a", **args)


def test_a_held_dof_cannot_slide_and_footings_slide_together():
    fr = Frame3D()
    fr.node("a", 0.0, 0.0, 0.0)
    fr.support("a", ux=False, uy=False, uz=False, rz=True)
    with pytest.raises(ValueError, match="rz of node 'a' is supported"):
        fr.foundation("F", "a", width=2.0, length=2.0, soil=KELVIN, patches=2, horizontal="soil", mu=0.3)
    fr = Frame3D()
    fr.node("a", 0.0, 0.0, 0.0)
    fr.node("b", 5.0, 0.0, 0.0)
    fr.foundation("A", "a", width=2.0, length=2.0, soil=KELVIN, patches=2, horizontal="soil", mu=0.3, Jz=1.0)
    with pytest.raises(ValueError, match="cannot be mixed"):
        fr.foundation("B", "b", width=2.0, length=2.0, soil={"model": "winkler-kelvin", "k": 2e5}, patches=2)
    with pytest.raises(ValueError, match="the same facets"):
        fr.foundation("B", "b", width=2.0, length=2.0, soil=KELVIN, patches=2, horizontal="soil", mu=0.3, facets=4)


def test_two_footings_slide_on_one_half_space_coupled_in_plan():
    """Two footings that slide on one half-space: one x-y-z flexibility of all their patches (all x
    rows, all y rows, all z rows), the cross-footing blocks nonzero; the same on Kelvin beds is
    block-diagonal in that order."""
    def frame(soil):
        fr = Frame3D()
        fr.node("a", 0.0, 0.0, 0.0)
        fr.node("b", 4.0, 1.0, 0.0)
        for name, node in (("A", "a"), ("B", "b")):
            fr.foundation(name, node, width=2.0, length=2.0, soil=soil, patches=(2, 1), horizontal="soil", mu=0.4,
                          mass=1.0, Jx=1.0, Jy=1.0, Jz=1.0)
        return fr.build()

    st = frame(HALF)
    F = st.foundation.soil.static()
    assert F.shape == (12, 12)
    from unilateral.soil import HalfSpace, SoilFlexibility

    G = 2.0 * 97.0 ** 2
    direct = SoilFlexibility.halfspace(HalfSpace(G, 1 / 3, 2.0), st.foundation.patches, components="xyz").static()
    np.testing.assert_allclose(F, direct, rtol=1e-12)
    assert abs(F[0, 2]) > 0 and abs(F[4, 6]) > 0                 # x of A from x of B, y of A from y of B
    K = frame(KELVIN).foundation.soil.static()
    np.testing.assert_allclose(np.diag(K), 1 / np.array([1.5e5] * 8 + [2e5] * 4))
    model = st.to_model()
    assert model.m == 4 * (3 + 8) and model.facets == 8 and model.Tx.shape == model.Ty.shape == (st.n, 4)


# ---------------------------------------------------------------------- model file
MODEL_FILE = """
[units]
length = "m"
force = "kN"
time = "s"
[frame]
dimensions = 3
[[nodes]]
id = 1
x = 0.0
y = 0.0
z = 0.0
[[nodes]]
id = 2
x = 0.0
y = 0.0
z = 6.0
[[elements]]
type = "beam"
name = "col"
node_i = 1
node_j = 2
E = 3e7
A = 0.5
Iy = 0.05
Iz = 0.05
G = 1.2e7
J = 0.08
[[masses]]
node = 2
m = 40.0
Jz = 10.0
[[foundations]]
name = "F"
node = 1
width = 4.0
length = 4.0
patches = [2, 2]
horizontal = "soil"
mu = 0.3
facets = 8
mass = 20.0
Jx = 30.0
Jy = 30.0
Jz = 30.0
soil = { model = "winkler-kelvin", k = 2e5, c = 2e3, kx = 1.5e5, cx = 1.5e3 }
[loads.gravity]
g = "standard"
[[loads.nodal]]
node = 2
ux = 250.0
uy = 150.0
time_function = { type = "half_sine", duration = 1.0 }
[analysis]
dt = 0.004
t_end = 1.0
"""


def test_model_file_footing_that_slides_in_plan(tmp_path):
    from unilateral.modelfile import ModelFileError, load_model_file

    path = tmp_path / "slide3d.toml"
    path.write_text(MODEL_FILE)
    spec = load_model_file(path)
    model = spec.model
    st, _ = tower(KELVIN, 0.3, facets=8)
    api = st.to_model()
    assert model.m == api.m == 4 * (3 + 8) and model.facets == 8
    assert model.constraint_names == api.constraint_names and len(model.dof_names) == len(api.dof_names)
    for name in ("K", "M", "T", "Tx", "Ty"):
        np.testing.assert_array_equal(getattr(model, name), getattr(api, name))
    np.testing.assert_array_equal(model.soil.static(), api.soil.static())
    np.testing.assert_array_equal(model.mu, api.mu)
    sol = ul.solve(model, spec.load, method="cq", dt=0.004, t_end=1.0)
    ref = ul.solve(api, spec.load, method="cq", dt=0.004, t_end=1.0)
    assert sol.success and np.array_equal(sol.u, ref.u) and np.abs(spec.structure.foundation.slips(sol)).max() > 1e-3
    for old, new, match in (("mu = 0.3\n", "", "mu: missing key"),
                            ('horizontal = "soil"\n', "", "mu = 0.3: only for horizontal"),
                            ("facets = 8\n", "facets = 7\n", "facets = 7: give an even number >= 4"),
                            ("facets = 8\n", "facets = 2\n", "facets"),
                            ("mu = 0.3\n", "mu = 0.0\n", "mu"),
                            ("kx = 1.5e5, ", "", "kx: missing key")):
        path.write_text(MODEL_FILE.replace(old, new, 1))
        with pytest.raises(ModelFileError, match=match):
            load_model_file(path)


def test_the_methods_that_take_footings_that_slide_in_plan():
    """``method="auto"``: the modal route on Kelvin beds (the primal form), CQ on the half-space,
    where ``method="modal"`` is refused (no pole-residue form) with the reason and the methods that apply."""
    st, load = tower(KELVIN, 0.2)
    model = st.to_model()
    kw = dict(dt=2e-3, t_end=0.5)
    auto, cq = ul.solve(model, load, method="auto", **kw), ul.solve(model, load, method="cq", **kw)
    assert auto.success and auto.stats["method"] == "modal" and rel(auto.u, cq.u) < 1e-10
    st, load = tower(HALF, 0.2)
    model = st.to_model()
    auto, cq = ul.solve(model, load, method="auto", **kw), ul.solve(model, load, method="cq", **kw)
    assert auto.success and auto.stats["method"] == "cq" and np.array_equal(auto.u, cq.u)
    with pytest.raises(ValueError, match="footings that slide.*the methods that apply to this problem: 'cq'"):
        ul.solve(model, load, method="modal", **kw)


def test_the_ground_reactions_of_a_footing_that_slides_balance_the_load():
    """Static state of a footing (3 x 3 Kelvin patches) under its weight, a horizontal force and a
    torque: the soil's forces on it (``ground_reactions``: fx, fy, fz and the moments of each
    patch) sum to minus the load about the footing's node, and ``contact_load`` is their load."""
    from unilateral.structure import forces3d

    fr = Frame3D()
    fr.node("base", 0.0, 0.0, 0.0)
    fr.foundation("F", "base", width=4.0, length=4.0, patches=(3, 3), soil=KELVIN, horizontal="soil", mu=10.0,
                  mass=100.0, Jx=100.0, Jy=100.0, Jz=100.0)
    st = fr.build()
    q = st.gravity(10.0) + st.nodal_load("base", ux=30.0, uy=-20.0, rz=500.0)
    sol = ul.solve(st.to_model(), lambda t: q, dt=2e-3, t_end=4e-3, method="cq", initial="static")
    assert sol.success
    base = forces3d.base_forces(st, forces3d.reactions(st, forces3d.histories(st, sol, "bdf2"), sol))
    expected = dict(Fx=-30.0, Fy=20.0, Fz=1000.0, Mx=0.0, My=0.0, Mz=-500.0)
    for key, value in expected.items():
        np.testing.assert_allclose(base[key], value, rtol=0, atol=1e-9 * 1000.0)
    np.testing.assert_allclose(st.foundation.contact_load(st, sol), np.tile(-q, (len(sol.t), 1)), atol=1e-8)


def test_a_large_mu_without_uplift_is_the_bilateral_run():
    """mu = 1000 and a pulse that lifts no patch: no facet slips, and the run equals the bilateral one
    (contacts and both shears held) to round-off."""
    st, load = tower(KELVIN, 1e3, facets=8, amplitude=0.5)
    model = st.to_model()
    kw = dict(dt=2e-3, t_end=1.5)
    sol = ul.solve(model, load, method="cq", **kw)
    held = ul.solve(model, load, method="cq", bilateral=True, **kw)
    assert sol.success and held.success
    assert sol.v[:, :4].max() == 0.0 and np.abs(st.foundation.facet_slips(sol)).max() == 0.0
    assert rel(sol.u, held.u) < 1e-10
    assert rel(st.foundation.shear_forces(sol), st.foundation.shear_forces(held)) < 1e-9
    assert np.abs(st.foundation.shear_forces(sol)[..., 1]).max() > 1.0          # both directions carry shear


def test_unilateral_run_writes_a_footing_that_slides_in_plan(tmp_path):
    """`unilateral run` of the file: results.nc places every patch's constraints (contact, shears x
    and y, facets) on its footing, and the run succeeds with and without uplift."""
    from unilateral.io import load_netcdf

    path = tmp_path / "slide3d.toml"
    path.write_text(MODEL_FILE)
    result = ul.run(path, tmp_path / "out", figures=())
    assert result["success_all"]
    ds = load_netcdf(tmp_path / "out" / "results.nc")
    footing = [str(x) for x in ds["footing"].values]
    assert footing.count("F") == 4                              # one contact per patch carries the patch
    assert ds["v"].shape[-1] == len(footing) == 4 * (3 + 8) + len(footing) - 44
