"""A 2-D hinge with an axial force - moment interaction polygon (``Frame2D.hinge(interaction=...)``):
a column under a constant axial force yields at the polygon's moment at that force, flows along the
facet's normal, its yield moment drops as the force grows, and a dynamic run balances its energy."""

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.energy import energy_balance
from unilateral.pushover import pushover
from unilateral.structure import Frame2D
from unilateral.structure import forces as F

H, NY, MP = 3.0, 1000.0, 100.0


def column(interaction="aisc", a0=0.0):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, H)
    fr.support(1, ux=True, uy=True, rz=True)
    fr.beam("col", 1, 2, E=30e6, A=0.02, I=6.75e-4)
    shape = {"Ny": NY, "My": MP} if isinstance(interaction, str) else {}
    fr.hinge("h", "col", "i", interaction=interaction, **shape)
    fr.mass(2, 10.0)
    if a0:
        fr.rayleigh(a0=a0)
    return fr.build()


def plastic_strains(st, v):
    """The plastic elongation and rotation ``sum_k lambda_k n_k`` of the hinge (axial, rot_i)."""
    out = np.zeros(3)
    for value, (_, unknown) in zip(v, st.constraints):
        for row, b in unknown.entries:
            out[row] += b * value
    return out[:2]


@pytest.mark.parametrize("N, moment, normal", [
    (100.0, MP * (1 - 100.0 / (2 * NY)), (-1 / (2 * NY), 1 / MP)),               # H1-1b: |N|/2Ny + M/Mp <= 1
    (500.0, MP * 9 / 8 * (1 - 500.0 / NY), (-1 / NY, 8 / (9 * MP))),             # H1-1a: |N|/Ny + 8/9 M/Mp <= 1
])
def test_a_column_under_axial_compression_yields_at_the_polygon_and_flows_along_its_normal(N, moment, normal):
    st = column()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.05, gravity=st.nodal_load(2, uy=-N),
                 p_delta=False)
    assert r.success, r.message
    assert len(r.events) == 1 and r.events[0].kind == "yield"
    assert abs(r.load_factor[r.events[0].point] * H - moment) <= 1e-9 * MP
    assert abs(r.load_factor[-1] * H - moment) <= 1e-9 * MP                      # perfectly plastic
    elongation, rotation = plastic_strains(st, r.v[-1])
    assert rotation > 0 and elongation / rotation == pytest.approx(normal[0] / normal[1], rel=1e-9)
    forces = st.element_forces(r.load_factor, r.u, r.v)
    axial = [k for k, (_, u) in enumerate(st.constraints) if u.row == 0]
    assert not axial or np.allclose(forces[:, axial], -N, rtol=1e-9)


def test_the_yield_moment_drops_as_the_axial_force_grows():
    yields = []
    for N in (300.0, 700.0):
        st = column()
        r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.05,
                     gravity=st.nodal_load(2, uy=-N), p_delta=False)
        yields.append(r.load_factor[-1] * H)
    assert yields[0] == pytest.approx(MP * 9 / 8 * 0.7, rel=1e-9)
    assert yields[1] == pytest.approx(MP * 9 / 8 * 0.3, rel=1e-9)


def test_a_polygon_given_by_its_vertices_is_the_named_shape():
    vertices = [(NY * n, MP * m) for n, m in ((1.0, 0.0), (0.2, 0.9), (0.0, 1.0), (-0.2, 0.9), (-1.0, 0.0),
                                               (-0.2, -0.9), (0.0, -1.0), (0.2, -0.9))]
    named, given = column(), column(vertices[::-1])                           # either sense
    for st in (named, given):
        r = pushover(st, st.nodal_load(2, ux=-1.0), node=2, dof="ux", target=-0.05,
                     gravity=st.nodal_load(2, uy=400.0), p_delta=False)       # tension
        assert r.load_factor[-1] * H == pytest.approx(MP * 9 / 8 * 0.6, rel=1e-9)


@pytest.mark.parametrize("kwargs, message", [
    ({"interaction": [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0)]}, "even number"),
    ({"interaction": [(1.0, 1.0), (2.0, 1.0), (2.0, 2.0), (1.0, 2.0)]}, "strictly contain"),
    ({"interaction": "rc", "Ny": 1.0, "My": 1.0}, "is not a shape"),
    ({"interaction": "aisc", "My": 1.0}, "needs Ny"),
    ({"interaction": "aisc", "Ny": 1.0, "My": 1.0, "k": 1e4}, "rigid-plastic"),
])
def test_bad_polygons_are_refused_naming_the_argument(kwargs, message):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, H)
    fr.beam("col", 1, 2, E=30e6, A=0.02, I=6.75e-4)
    with pytest.raises(ValueError, match=message):
        fr.hinge("h", "col", "i", **kwargs)


def test_a_dynamic_run_under_axial_load_balances_its_energy():
    st = column(a0=0.5)
    dt, steps = 2e-3, 1000
    t = dt * np.arange(steps + 1)
    Q = (st.nodal_load(2, uy=-400.0)[None, :]
         + (60.0 * np.sin(2 * np.pi * t / 0.4) * (t < 1.2))[:, None] * st.nodal_load(2, ux=1.0)[None, :])
    sol = ul.solve(st.to_model(), Q, dt=dt, t_end=steps * dt, method="direct", rule="trapezoidal")
    assert sol.success, sol.message
    h = F.Histories.from_solution(st, sol, "trapezoidal", load0=Q[0])
    energy = energy_balance(st, h, Q)
    assert energy["plastic_work"][-1] > 0.05 * energy["input_work"].max()
    assert energy["max_relative_error"] < 1e-9
    elongation, rotation = plastic_strains(st, sol.v[-1])
    assert elongation < 0                                                      # compression: the column shortens


def test_model_file_hinges_with_a_backbone_and_an_interaction_are_the_builders():
    import tomllib

    from yield_portal import PORTAL_TOML

    from unilateral.modelfile import build_model_spec

    data = tomllib.loads(PORTAL_TOML + "[analysis]\ndt = 1e-3\nt_end = 0.1\n")
    backbone = [[0.002, 30.0], [0.01, 40.0], [-0.003, -45.0], [-0.011, -55.0]]
    data["unilateral"][0] = {"type": "hinge", "name": "h1", "beam": "c1", "end": "j", "backbone": backbone}
    data["unilateral"][2] = {"type": "hinge", "name": "h3", "beam": "c2", "end": "i", "interaction": "aisc",
                             "Ny": 2000.0, "My": 60.0}
    spec = build_model_spec(data, "model.toml")
    fr = Frame2D()
    for node, x, y in ((1, 0.0, 0.0), (2, 0.0, 3.0), (3, 4.0, 3.0), (4, 4.0, 0.0)):
        fr.node(node, x, y)
    for name, i, j in (("c1", 1, 2), ("c2", 4, 3), ("g", 2, 3)):
        fr.beam(name, i, j, E=30e6, A=0.09, I=6.75e-4)
    fr.hinge("h1", "c1", "j", backbone=backbone)
    fr.hinge("h3", "c2", "i", interaction="aisc", Ny=2000.0, My=60.0)
    built = {e.name: e for e in fr.build().elements}
    for name in ("c1", "c2"):
        ours = next(e for e in spec.structure.elements if e.name == name)
        assert ours.unknowns == built[name].unknowns
        np.testing.assert_array_equal(ours.A, built[name].A)
        np.testing.assert_array_equal(ours.E, built[name].E)
