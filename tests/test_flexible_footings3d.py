"""Flexible footings in plan under a Frame3D (``Frame3D.foundation(nodes=[[...], ...])``).

One patch under each node of a rectilinear grid, its contact on that node's ``uz``; the structure the
user builds on the nodes is the footing's stiffness. Checked: rigidly linked grid nodes are the rigid
footing of the same patches (to round-off, statically and through uplift), stiff beams approach it as
the soil-to-beam stiffness ratio, a row of nodes under a plane frame is the 2-D flexible footing, a
slab under a central load (equilibrium, symmetry, soft versus stiff), the friction polygon of a
flexible footing that slides, the results of ``unilateral run``, and the model file.
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.loads import LoadHistory, Rectangular
from unilateral.structure import Frame2D, Frame3D

HALF = {"model": "halfspace", "Vs": 97.0, "nu": 1 / 3, "rho": 2.0}
COLUMN = dict(E=3e7, A=1.0, Iy=1.0, Iz=1.0, G=1.2e7, J=1.5)
DT, T_END = 2e-3, 0.6
XS, YS = (-2.0, 0.0, 2.0), (-1.0, 1.0)                  # the 3 x 2 grid: 2 m x 2 m patches, 6 m x 4 m


def _grid(fr, xs=XS, ys=YS, z=0.0, prefix="n"):
    """Nodes ``prefix<i><j>`` at ``(xs[j], ys[i], z)``; the grid of ids (rows along x)."""
    grid = []
    for i, y in enumerate(ys):
        grid.append([])
        for j, x in enumerate(xs):
            fr.node(f"{prefix}{i}{j}", x, y, z)
            grid[-1].append(f"{prefix}{i}{j}")
    return grid


def _grillage(fr, grid, section, prefix="g"):
    """Beams between neighbouring nodes of ``grid`` along x and along y."""
    for i, row in enumerate(grid):
        for j, node in enumerate(row):
            if j + 1 < len(row):
                fr.beam(f"{prefix}x{i}{j}", node, row[j + 1], **section)
            if i + 1 < len(grid):
                fr.beam(f"{prefix}y{i}{j}", node, grid[i + 1][j], **section)


def tower(kind, *, section=None, soil=HALF, **kwargs):
    """A column with a top mass on the 6 m x 4 m footing: ``"rigid"`` (3 x 2 patches), ``"links"`` (a
    flexible footing whose grid nodes are rigidly linked to the column's base) or ``"beams"`` (a
    grillage of ``section``; the column's base at (0, 0), between the rows, tied to the two nearest
    nodes by beams of ``section``)."""
    fr = Frame3D()
    fr.node("top", 0.0, 0.0, 8.0)
    fr.node("base", 0.0, 0.0, 0.0)
    fr.beam("column", "base", "top", **COLUMN)
    fr.mass("top", 40.0)
    if kind == "rigid":
        fr.foundation("f", "base", width=6.0, length=4.0, patches=(3, 2), soil=soil, **kwargs)
        return fr
    grid = _grid(fr)
    if kind == "links":
        for row in grid:
            for node in row:
                fr.rigid_link("base", node)
    else:
        _grillage(fr, grid, section)
        fr.beam("tie0", "base", grid[0][1], **section)
        fr.beam("tie1", "base", grid[1][1], **section)
    fr.foundation("f", "base", nodes=grid, soil=soil, **kwargs)
    return fr


def _pulse(st, vector, P):
    return LoadHistory(st.gravity(10.0), [(P * vector, Rectangular(1.0, t_end=0.1))])


def _diagonal(st):
    return (st.nodal_load("top", ux=1.0) + st.nodal_load("top", uy=0.6)) / np.hypot(1.0, 0.6)


# ---------------------------------------------------------------------- 1. rigid grid = rigid footing
def test_the_patch_rule_matches_the_rigid_footing_on_equally_spaced_nodes():
    st = tower("links").build()
    fnd = st.foundation.footings[0]
    ref = tower("rigid").build().foundation.footings[0]
    np.testing.assert_array_equal(fnd.patches.centres, ref.patches.centres)
    np.testing.assert_allclose(fnd.patches.sizes, ref.patches.sizes, rtol=1e-15)
    assert fnd.contact_names == ("f.n00", "f.n01", "f.n02", "f.n10", "f.n11", "f.n12")
    assert (fnd.width, fnd.length) == (6.0, 4.0) and not fnd.rigid
    # uneven spacing, given extents: centred patches, twice the nearer end of the tributary strip
    fr = Frame3D()
    grid = _grid(fr, xs=(0.0, 1.0, 3.0), ys=(0.0, 2.0))
    _grillage(fr, grid, COLUMN)
    fr.foundation("f", nodes=grid, width=4.0, length=3.0, soil=HALF)
    fnd = fr.build().foundation.footings[0]
    # x: footing from -0.5 to 3.5, strips [-0.5, 0.5], [0.5, 2], [2, 3.5] -> widths 1, 1, 1
    # y: footing from -0.5 to 2.5, strips [-0.5, 1], [1, 2.5] -> lengths 1, 1
    np.testing.assert_allclose(fnd.patches.sizes[:, 0], [1.0, 1.0, 1.0] * 2)
    np.testing.assert_allclose(fnd.patches.sizes[:, 1], [1.0] * 6)
    assert fnd.node == grid[0][1]                 # the reference node: row (2 - 1) // 2, column (3 - 1) // 2


def test_rigidly_linked_grid_nodes_are_the_rigid_footing_statically_and_through_uplift():
    """Rigid links make the flexible footing's ``T`` the rigid footing's: equal to round-off."""
    rigid, links = tower("rigid").build(), tower("links").build()
    models = [st.to_model() for st in (rigid, links)]
    assert rigid.dofs.names == links.dofs.names
    np.testing.assert_allclose(models[1].T, models[0].T, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(models[1].soil.static(), models[0].soil.static())
    sols = [ul.solve(model, _pulse(st, _diagonal(st), 160.0), dt=DT, t_end=T_END, method="cq", initial="static")
            for st, model in zip((rigid, links), models)]
    assert all(s.success for s in sols)
    a, b = sols
    assert a.v.max() > 1e-4                                   # the footing lifts off
    assert np.all(-a.psi[0] > 0)                              # statically every patch in contact
    np.testing.assert_allclose(b.psi, a.psi, rtol=0, atol=1e-9 * np.abs(a.psi).max())
    np.testing.assert_allclose(b.v, a.v, rtol=0, atol=1e-9 * np.abs(a.v).max())
    np.testing.assert_allclose(b.u, a.u, rtol=0, atol=1e-9 * np.abs(a.u).max())


def test_stiff_beams_approach_the_rigid_footing_as_the_stiffness_ratio():
    """A grillage of stiff beams: the static contact forces under the weight and a small horizontal
    force (every patch in contact: a linear problem) differ from the rigid footing's by
    O(k_soil / k_beam), the ratio of a patch's soil stiffness to a beam's transverse stiffness
    (measured: 2.6 times the ratio, at 3.7e-5 and at 3.7e-7)."""
    st = tower("rigid").build()
    q = st.gravity(10.0) + 10.0 * _diagonal(st)
    ref = -ul.solve(st.to_model(), lambda t: q, dt=DT, t_end=DT, method="cq", initial="static").psi[0]
    k_soil = float(np.max(np.diag(np.linalg.inv(st.foundation.soil.static()))))
    errors = []
    for scale in (1e2, 1e4):
        section = dict(E=3e7 * scale, A=1.0, Iy=1.0, Iz=1.0, G=1.2e7 * scale, J=1.5)
        fl = tower("beams", section=section).build()
        q = fl.gravity(10.0) + 10.0 * _diagonal(fl)
        c = -ul.solve(fl.to_model(), lambda t: q, dt=DT, t_end=DT, method="cq", initial="static").psi[0]
        k_beam = 12 * section["E"] * section["Iy"] / 2.0 ** 3     # a 2 m beam's transverse stiffness
        ratio = k_soil / k_beam
        errors.append(np.abs(c - ref).max() / np.abs(ref).max())
        assert c.min() > 0.2 * c.max()                        # every patch in contact
        assert errors[-1] < 5 * ratio, (errors[-1], ratio)
    assert errors[1] < 3e-2 * errors[0]                       # it converges as the ratio (1e-2)


# ---------------------------------------------------------------------- 2. a row = the 2-D footing
def test_a_row_of_nodes_under_a_plane_frame_is_the_2d_flexible_footing():
    xs = (-3.0, -1.5, 0.0, 1.5, 3.0)
    beam2 = dict(E=3e7, A=0.5, I=0.01)
    beam3 = dict(E=3e7, A=0.5, Iy=0.01, Iz=0.01, G=1.2e7, J=0.02)
    fr3, fr2 = Frame3D(), Frame2D()
    fr3.node("top", 0.0, 0.0, 8.0)
    fr2.node("top", 0.0, 8.0)
    for k, x in enumerate(xs):
        fr3.node(k, x, 0.0, 0.0)
        fr2.node(k, x, 0.0)
        fr3.support(k, ux=False, uy=True, uz=False, rx=True, rz=True)      # the plane frame: out of plane held
    for k in range(len(xs) - 1):
        fr3.beam(f"b{k}", k, k + 1, **beam3)
        fr2.beam(f"b{k}", k, k + 1, **beam2)
    fr3.beam("column", 2, "top", **COLUMN)
    fr2.beam("column", 2, "top", E=3e7, A=1.0, I=1.0)
    fr3.support("top", ux=False, uy=True, uz=False, rx=True, rz=True)
    fr3.mass("top", 40.0)
    fr2.mass("top", 40.0)
    fr3.foundation("f", 2, nodes=[list(range(len(xs)))], length=3.0, soil=HALF)
    fr2.foundation("f", 2, nodes=list(range(len(xs))), length=3.0, soil=HALF)
    st3, st2 = fr3.build(), fr2.build()
    f3, f2 = st3.foundation.footings[0], st2.foundation.footings[0]
    np.testing.assert_array_equal(f3.patches.sizes, f2.patches.sizes)
    np.testing.assert_array_equal(f3.patches.centres[:, 0], f2.patches.centres[:, 0])
    q3 = _pulse(st3, st3.nodal_load("top", ux=1.0), 300.0)
    q2 = LoadHistory(st2.gravity(10.0), [(300.0 * st2.nodal_load("top", ux=1.0), Rectangular(1.0, t_end=0.1))])
    s3 = ul.solve(st3.to_model(), q3, dt=DT, t_end=T_END, method="cq")
    s2 = ul.solve(st2.to_model(), q2, dt=DT, t_end=T_END, method="cq")
    assert s3.success and s2.success
    assert s2.v.max() > 1e-5                                   # the footing lifts off
    np.testing.assert_allclose(s3.v, s2.v, rtol=0, atol=1e-9 * np.abs(s2.v).max())
    np.testing.assert_allclose(s3.psi, s2.psi, rtol=0, atol=1e-9 * np.abs(s2.psi).max())
    for node in ["top", *range(len(xs))]:
        for d3, d2, sign in (("ux", "ux", 1.0), ("uz", "uy", 1.0), ("ry", "rz", -1.0)):
            a, b = st3.node_displacement(s3, node, d3), st2.node_displacement(s2, node, d2)
            np.testing.assert_allclose(a, sign * b, rtol=0, atol=1e-9 * max(np.abs(b).max(), 1e-12))


# ---------------------------------------------------------------------- 3. a slab under a central load
def slab(EI_scale, n=5, P=500.0):
    """An ``n x n`` grillage (1 m spacing) on the half-space, held in plan at its middle node, under
    ``P`` down at its middle node: the static contact forces as an (n, n) array (rows along y)."""
    fr = Frame3D()
    coords = [float(k) - (n - 1) / 2 for k in range(n)]
    grid = _grid(fr, xs=coords, ys=coords)
    section = dict(E=3e7 * EI_scale, A=0.3, Iy=0.3 * 0.09 / 12, Iz=0.09 * 0.3 / 12, G=1.2e7 * EI_scale, J=2e-3)
    _grillage(fr, grid, section)
    for row in grid:
        for node in row:
            fr.mass(node, 1.0, Jx=0.1, Jy=0.1)
    fr.foundation("slab", nodes=grid, soil=HALF)
    st = fr.build()
    middle = grid[n // 2][n // 2]
    q = st.nodal_load(middle, uz=-P)
    sol = ul.solve(st.to_model(), lambda t: q, dt=DT, t_end=DT, method="cq", initial="static")
    assert sol.success
    return st, (-sol.psi[0]).reshape(n, n)


def test_a_slab_under_a_central_load_carries_it_symmetrically():
    st, c = slab(1.0)
    assert st.foundation.footings[0].node == "n22"               # held in plan at the middle node
    np.testing.assert_allclose(c.sum(), 500.0, rtol=1e-10)
    tol = 1e-10 * np.abs(c).max()
    np.testing.assert_allclose(c, c[::-1, :], rtol=0, atol=tol)
    np.testing.assert_allclose(c, c[:, ::-1], rtol=0, atol=tol)
    np.testing.assert_allclose(c, c.T, rtol=0, atol=tol)
    assert c.min() >= 0.0
    _, stiff = slab(1e3)
    _, soft = slab(1e-2)
    np.testing.assert_allclose([stiff.sum(), soft.sum()], 500.0, rtol=1e-10)
    # a soft slab concentrates the load under it, a stiff one spreads it to the edges
    assert soft[2, 2] / soft.sum() > c[2, 2] / c.sum() > stiff[2, 2] / stiff.sum()
    assert stiff[0, 0] > soft[0, 0]


# ---------------------------------------------------------------------- 4. sliding
def test_a_flexible_footing_that_slides_keeps_the_friction_polygon():
    """A 3 x 3 grillage under a tower, ``horizontal="soil"``, 8 facets, a ground pulse at 0.5 rad from
    x: c >= 0 and every facet function ``d_k . f - mu c <= 0`` at every patch and step; each patch's
    shears act on its own node (``Tx``, ``Ty`` unit columns on ``ux``, ``uy``)."""
    mu, N = 0.25, 8
    fr = Frame3D()
    fr.node("top", 0.0, 0.0, 6.0)
    grid = _grid(fr, xs=(-2.0, 0.0, 2.0), ys=(-2.0, 0.0, 2.0))
    section = dict(E=3e7, A=0.5, Iy=0.05, Iz=0.05, G=1.2e7, J=0.08)
    _grillage(fr, grid, section)
    fr.beam("column", "n11", "top", E=3e7, A=0.5, Iy=0.05, Iz=0.05, G=1.2e7, J=0.08)
    fr.mass("top", 40.0, Jz=10.0)
    for row in grid:
        for node in row:
            fr.mass(node, 2.0, Jx=0.5, Jy=0.5, Jz=0.5)
    fr.foundation("F", nodes=grid, soil=HALF | {"Vs": 120.0}, horizontal="soil", mu=mu, facets=N)
    st = fr.build()
    model = st.to_model()
    flat = [n for row in grid for n in row]
    for j, node in enumerate(flat):
        assert model.Tx[st.dofs.names.index(f"{node}.ux"), j] == 1.0 and np.count_nonzero(model.Tx[:, j]) == 1
        assert model.Ty[st.dofs.names.index(f"{node}.uy"), j] == 1.0 and np.count_nonzero(model.Ty[:, j]) == 1
    gravity = st.gravity(9.81)
    d = np.cos(0.5) * st.influence("ux") + np.sin(0.5) * st.influence("uy")

    def load(t):
        return gravity - st.M @ d * (6.0 * np.sin(2 * np.pi * t) * (t < 1.0))

    sol = ul.solve(model, load, method="cq", dt=4e-3, t_end=1.2)
    assert sol.success, sol.message
    fnd = st.foundation
    c, f = fnd.contact_forces(sol), -fnd.shear_forces(sol)
    scale = c.max()
    tol = 1e-9 * scale
    assert c.min() >= 0.0
    phi = f @ model.directions.T - mu * c[..., None]
    assert phi.max() < tol
    dlam = np.diff(fnd.facet_slips(sol), axis=0)
    assert dlam.min() >= -1e-14 and (dlam > 1e-12).sum() > 20          # it slid
    assert np.abs(phi[1:][dlam > 1e-12]).max() < 1e-8 * scale          # only on facets at the limit
    # the ground reactions of the patches balance the load in the static state at t = 0
    from unilateral.structure import forces3d

    base = forces3d.base_forces(st, forces3d.reactions(st, forces3d.histories(st, sol, "bdf2"), sol))
    assert base["Fz"][0] == pytest.approx(9.81 * (40.0 + 9 * 2.0), rel=1e-9)


# ---------------------------------------------------------------------- reactions, run and model file
MODEL_FILE = """
units = {{ length = "m", force = "kN", time = "s" }}
frame = {{ dimensions = 3 }}

nodes = [{nodes}
         {{ id = "top", x = 0.0, y = 0.0, z = 6.0 }}]
elements = [{beams}
    {{ type = "beam", name = "column", node_i = 5, node_j = "top", {section} }},
]
masses = [{{ node = "top", m = 40.0 }}]

[[foundations]]
name = "F"
nodes = [[1, 2, 3], [4, 5, 6], [7, 8, 9]]
soil = {{ model = "halfspace", Vs = 120.0, nu = 0.33, rho = 2.0 }}

[loads]
gravity = {{ g = 9.81 }}
nodal = [{{ node = "top", ux = 60.0, uy = 30.0, time_function = {{ type = "rectangular", t_end = 0.1 }} }}]

[analysis]
dt = 0.004
t_end = 0.4
method = "cq"
"""
SECTION = "E = 3e7, A = 0.5, Iy = 0.05, Iz = 0.05, G = 1.2e7, J = 0.08"


def _file_text():
    nodes = "".join(f"{{ id = {3 * i + j + 1}, x = {2.0 * (j - 1)}, y = {2.0 * (i - 1)}, z = 0.0 }},\n         "
                    for i in range(3) for j in range(3))
    beams = []
    for i in range(3):
        for j in range(3):
            k = 3 * i + j + 1
            if j < 2:
                beams.append(f'{{ type = "beam", name = "x{k}", node_i = {k}, node_j = {k + 1}, {SECTION} }},')
            if i < 2:
                beams.append(f'{{ type = "beam", name = "y{k}", node_i = {k}, node_j = {k + 3}, {SECTION} }},')
    return MODEL_FILE.format(nodes=nodes, beams="\n    " + "\n    ".join(beams), section=SECTION)


def _api():
    fr = Frame3D()
    for i in range(3):
        for j in range(3):
            fr.node(3 * i + j + 1, 2.0 * (j - 1), 2.0 * (i - 1), 0.0)
    fr.node("top", 0.0, 0.0, 6.0)
    section = dict(E=3e7, A=0.5, Iy=0.05, Iz=0.05, G=1.2e7, J=0.08)
    for i in range(3):
        for j in range(3):
            k = 3 * i + j + 1
            if j < 2:
                fr.beam(f"x{k}", k, k + 1, **section)
            if i < 2:
                fr.beam(f"y{k}", k, k + 3, **section)
    fr.beam("column", 5, "top", **section)
    fr.mass("top", 40.0)
    fr.foundation("F", nodes=[[1, 2, 3], [4, 5, 6], [7, 8, 9]], soil={"model": "halfspace", "Vs": 120.0,
                                                                        "nu": 0.33, "rho": 2.0})
    return fr.build()


def test_model_file_flexible_footing_equals_the_api_and_runs(tmp_path):
    from unilateral.io import load_netcdf
    from unilateral.modelfile import load_model_file
    from unilateral.structure import forces3d

    path = tmp_path / "flex3d.toml"
    path.write_text(_file_text())
    spec = load_model_file(path)
    st = _api()
    api = st.to_model()
    model = spec.model
    assert model.constraint_names == api.constraint_names == [f"F.{k}" for k in range(1, 10)]
    for name in ("K", "M", "T"):
        np.testing.assert_array_equal(getattr(model, name), getattr(api, name))
    np.testing.assert_array_equal(model.soil.static(), api.soil.static())
    # reactions: each patch's force at its own node, and they balance the weight
    sol = ul.solve(api, spec.load, method="cq", dt=0.004, t_end=0.4, initial="static")
    assert sol.success and sol.v.max() > 0.0
    react = forces3d.reactions(st, forces3d.histories(st, sol, "bdf2"), sol)
    assert react["at"]["F.1"] == 1 and react["at"]["F.9"] == 9
    np.testing.assert_allclose(react["footings"]["F.5"][:, 2], -sol.psi[:, 4])
    np.testing.assert_allclose(np.abs(react["footings"]["F.5"][:, 3:]).max(), 0.0)     # centred: no moments
    base = forces3d.base_forces(st, react)
    np.testing.assert_allclose(base["Fz"][0], 40.0 * 9.81, rtol=1e-9)
    # the run writes the patches of the flexible footing
    result = ul.run(path, tmp_path / "out", figures=())
    assert result["success_all"]
    ds = load_netcdf(tmp_path / "out" / "results.nc")
    assert [str(x) for x in ds["footing"].values] == ["F"] * 9
    assert [str(x) for x in ds["patch_node"].values] == [str(k) for k in range(1, 10)]
    np.testing.assert_allclose(ds["patch_width"].values, 2.0)
    np.testing.assert_allclose(ds["patch_length"].values, 2.0)
    assert "base_Fz" in ds
    np.testing.assert_allclose(ds["base_Fz"].sel(case="unilateral").values[0], 40.0 * 9.81, rtol=1e-9)
    # the model figure draws the nine patches
    from unilateral.figures.model3d import model_drawing_3d

    drawing = model_drawing_3d(spec.structure)
    assert [(name, len(centres)) for name, _, centres, _ in drawing.footings] == [("F", 9)]


@pytest.mark.parametrize("old, new, match", [
    ("[[1, 2, 3], [4, 5, 6], [7, 8, 9]]", "[[1, 2, 3], [4, 5, 6], [7, 8, 3]]",
     r"foundations\[0\]\.nodes\[2\]\[2\] = 3: .*given twice"),
    ("[[1, 2, 3], [4, 5, 6], [7, 8, 9]]", "[[1, 2, 3], [4, 5, 6], [7, 8, 99]]",
     r"foundations\[0\]\.nodes\[2\]\[2\] = 99: no node 99 \(nodes are"),
    ("[[1, 2, 3], [4, 5, 6], [7, 8, 9]]", "[[1, 2, 3], [4, 5, 6], [7, 8]]",
     r"foundations\[0\]\.nodes = .*the rows have 3, 3, 2 nodes"),
    ("[[1, 2, 3], [4, 5, 6], [7, 8, 9]]", "[[1, 2, 3], [4, 6, 5], [7, 8, 9]]",
     r"foundations\[0\]\.nodes\[1\]\[1\] = 6: at x = 2.*rectilinear grid"),
    ('{ id = 9, x = 2.0, y = 2.0, z = 0.0 }', '{ id = 9, x = 2.0, y = 2.0, z = 0.5 }',
     r"foundations\[0\]\.nodes\[2\]\[2\] = 9: at z = 0\.5.*one elevation"),
    ('name = "F"\n', 'name = "F"\npatches = [3, 3]\n', r"foundations\[0\]\.patches = \[3, 3\]: only for a rigid"),
    ('name = "F"\n', 'name = "F"\nmass = 3.0\n', r"foundations\[0\]\.mass = 3\.0: only for a rigid"),
    ('name = "F"\n', 'name = "F"\nwidth = 3.0\n', r"foundations\[0\]: foundation 'F': width=3\.0 is not larger"),
])
def test_model_file_bad_flexible_footings_are_refused(tmp_path, old, new, match):
    from unilateral.modelfile import ModelFileError, load_model_file

    text = _file_text()
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(ModelFileError, match=match):
        load_model_file(path)


def test_model_file_footings_sharing_a_node_or_overlapping_are_refused(tmp_path):
    from unilateral.modelfile import ModelFileError, load_model_file

    second = ('\n[[foundations]]\nname = "G"\nnodes = [[{a}, {b}]]\nlength = 1.0\n'
              'soil = {{ model = "halfspace", Vs = 120.0, nu = 0.33, rho = 2.0 }}\n')
    text = _file_text().replace("\n[loads]", second.format(a=3, b=10) + "\n[loads]")
    text = text.replace('{ id = "top"', '{ id = 10, x = 5.0, y = -2.0, z = 0.0 },\n         { id = "top"')
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ModelFileError, match=r"foundations\[1\]\.nodes\[0\]\[0\] = 3: .*also in foundations\[0\]"):
        load_model_file(path)
    text = text.replace('{ id = 10, x = 5.0', '{ id = 11, x = 2.5, y = -2.0, z = 0.0 },\n         { id = 10, x = 5.0')
    path.write_text(text.replace("nodes = [[3, 10]]", "nodes = [[11, 10]]"))
    with pytest.raises(ModelFileError, match=r"foundations\[1\]: foundation 'G': the footing .* overlaps footing 'F'"):
        load_model_file(path)


def test_bad_flexible_footings_are_refused_naming_the_argument():
    fr = Frame3D()
    grid = _grid(fr)
    fr.node("x", 5.0, 0.5, 0.0)
    fr.node("high", 9.0, 9.0, 1.0)
    cases = [
        (dict(nodes=[["n00", "n01"], ["n10", "n00"]]),
         r"nodes\[1\]\[1\]='n00' is given twice \(also nodes\[0\]\[0\]\)"),
        (dict(nodes=[["n00", "n01"], ["n10", "x"]]), r"nodes\[1\]\[1\]='x' is at x=5.*rectilinear grid"),
        (dict(nodes=[["n00", "n01"], ["n11", "n10"]]), r"is at x=.*rectilinear grid"),
        (dict(nodes=[["n00", "high"]]), r"nodes\[0\]\[1\]='high' is at z=1.*one elevation"),
        (dict(nodes=[["n00", "n01"], ["n10"]]), r"the rows have \[2, 1\] nodes"),
        (dict(nodes=["n00", "n01"]), r"nodes=\['n00', 'n01'\] is not valid; give a grid"),
        (dict(nodes=[["n00", "nope"]]), r"nodes\[0\]\[1\]"),
        (dict(nodes=[["n00"]]), r"at least two nodes"),
        (dict(nodes=[["n00", "n01"]]), r"give length"),
        (dict(nodes=[["n00", "n01"]], length=1.0, width=1.0), r"width=1\.0 is not larger than the span"),
        (dict(nodes=grid, patches=(3, 2)), r"patches=\(3, 2\): a flexible footing has one patch per node"),
        (dict(nodes=grid, mass=2.0), r"mass=2\.0.*are for a rigid footing"),
        (dict(nodes=grid, horizontal="cone"), r"horizontal='cone' is not valid for a 3-D footing"),
        (dict(), r"give node .* or nodes"),
    ]
    for kwargs, match in cases:
        with pytest.raises((ValueError, KeyError, TypeError), match=match):
            fr.foundation("f", soil=HALF, **kwargs)
    fr.foundation("A", nodes=[["n00", "n01"]], length=1.0, soil=HALF)
    with pytest.raises(ValueError, match=r"node 'n01' already rests on footing 'A'"):
        fr.foundation("B", nodes=[["n01", "n02"]], length=1.0, soil=HALF)
    with pytest.raises(ValueError, match=r"node 'n00' already rests on footing 'A'"):
        fr.foundation("B", "n00", width=1.0, length=1.0, patches=1, soil=HALF)
    with pytest.raises(ValueError, match=r"overlaps footing 'A'"):
        fr.foundation("B", nodes=[["n10", "n11"]], length=4.0, soil=HALF)
    fr.support("n12", ux=False, uy=False, uz=True)
    with pytest.raises(ValueError, match=r"uz of node 'n12' is supported"):
        fr.foundation("B", nodes=[["n11", "n12"]], length=1.0, soil=HALF)


def test_grid_nodes_linked_to_a_bare_master_build_as_the_rigid_footing():
    """Nothing but the soil stiffens the master of rigidly linked grid nodes: it builds (the soil's
    DOFs through the links are exempt from the stiffness check) and settles and tilts as the rigid
    footing, to round-off."""
    out = []
    for flexible in (False, True):
        fr = Frame3D()
        fr.node("base", 0.0, 0.0, 0.0)
        fr.mass("base", 10.0, Jx=1.0, Jy=1.0)
        if flexible:
            grid = _grid(fr)
            for row in grid:
                for node in row:
                    fr.rigid_link("base", node)
            fr.foundation("f", "base", nodes=grid, soil=HALF)
        else:
            fr.foundation("f", "base", width=6.0, length=4.0, patches=(3, 2), soil=HALF)
        st = fr.build()
        assert st.dofs.names == ["base.uz", "base.rx", "base.ry"]
        q = st.nodal_load("base", uz=-100.0, rx=30.0)
        sol = ul.solve(st.to_model(), lambda t: q, dt=DT, t_end=0.1, method="cq", initial="static")
        assert sol.success
        out.append(sol.u)
    np.testing.assert_allclose(out[1], out[0], rtol=0, atol=1e-12 * np.abs(out[0]).max())
