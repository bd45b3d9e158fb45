"""Several footings on one soil, beside the frame's other unilateral, yielding and friction elements.

The soil contacts are a constraint family (:class:`unilateral.constraints.SoilContact`) of one
mixed CLCP (:meth:`unilateral.soil.FoundationModel.on`): the frame's own constraints in the
paper's form, the contacts in the contact forces. Checked against exact identities: a Kelvin soil
is the paper's Kelvin elements (direct stepping of the primal model), the static settlement of one
footing under the other's load is the rigid footings' cross-flexibility, and footings far apart
decouple as Boussinesq's static term.
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.constraints import SoilContact, step_law, Friction, Contact
from unilateral.soil import FoundationModel, SoilFlexibility
from unilateral.structure import Frame2D

HALF = {"model": "halfspace", "G": 4e4, "nu": 1 / 3, "rho": 2.0}


def rel(a, b):
    return float(np.abs(a - b).max() / np.abs(b).max())


def portal(soil, *, spacing=8.0, gap_link=True, yielding=True, width=2.0, patches=2, piles=False):
    """A portal frame on two rigid footings, a pounding gap to a stop and a yielding brace
    (``piles``: a vertical and a rotational spring under each footing, K definite)."""
    fr = Frame2D()
    fr.node("a", 0.0, 0.0)
    fr.node("b", spacing, 0.0)
    fr.node("c", 0.0, 4.0)
    fr.node("d", spacing, 4.0)
    for name, i, j in (("colL", "a", "c"), ("colR", "b", "d"), ("beam", "c", "d")):
        fr.beam(name, i, j, E=3e7, A=0.2, I=2e-3)
    fr.mass("c", 20.0)
    fr.mass("d", 20.0)
    fr.foundation("left", "a", width=width, length=2.0, soil=soil, patches=patches, mass=2.0, J=1.0)
    fr.foundation("right", "b", width=width, length=2.0, soil=soil, patches=patches, mass=2.0, J=1.0)
    if piles:
        for node in ("a", "b"):
            fr.spring(f"pile_{node}", node, 1e4, direction="uy")
            fr.spring(f"pile_{node}_rz", node, 1e4, direction="rz")
    if gap_link:
        fr.node("stop", spacing + 0.5, 4.0)
        fr.support("stop")
        fr.gap("pound", "d", "stop", k=2e5, gap=0.002)
    if yielding:
        fr.yield_link("brace", "a", "d", k=5e4, Fy=60.0)
    st = fr.build()
    x = st.influence("ux")
    gravity = -9.81 * (st.M @ st.influence("uy"))

    def load(t):
        return gravity - st.M @ x * (6.0 * np.sin(2 * np.pi * 1.5 * t) * (t < 2.0))

    return st, load


def test_the_soil_is_a_constraint_family_with_dual_rows():
    law = step_law([Contact([0]), SoilContact([1, 2])], 3)
    assert law.P is not None and np.array_equal(np.diag(law.P), [1.0, -1.0, -1.0]) and not law.symmetric
    with pytest.raises(ValueError, match="horizontal='soil'"):
        step_law([Friction([0, 1], normal=[2, 2], mu=0.3), SoilContact([2])], 3)


@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_footings_beside_gaps_and_yield_links_equal_the_papers_kelvin_elements(rule):
    """Winkler-Kelvin footings + a pounding gap + a yielding brace: the mixed CLCP (cq) equals direct
    stepping of the same problem in the paper's primal form (the Kelvin soil elements)."""
    st, load = portal({"model": "winkler-kelvin", "k": 4e4, "c": 4e2})
    model = st.to_model()
    assert isinstance(model, FoundationModel) and model.mixed and model.ms == 4
    assert model.constraint_names[-4:] == ["left.1", "left.2", "right.1", "right.2"]
    kw = dict(dt=2e-3, t_end=3.0, rule=rule)
    mixed = ul.solve(model, load, method="cq", **kw)
    direct = ul.solve(model.kelvin_model(), load, method="direct", **kw)
    assert mixed.success and direct.success, mixed.message
    assert "mixed CLCP" in mixed.stats["formulation"]
    c = -mixed.psi[:, -4:]
    assert mixed.v[:, -4:].max() > 1e-4 and c.min() == 0.0               # the footings lift off
    assert (mixed.v[:, model.constraint_names.index("pound")] == 0).any()     # the gap closes
    plastic = mixed.v[:, model.constraint_names.index("brace.plastic+")] + \
        mixed.v[:, model.constraint_names.index("brace.plastic-")]
    assert plastic[-1] > 1e-4                                                # the brace yields
    # measured: u 1e-10, v 3e-10, psi 3e-9 (bdf2)
    assert rel(mixed.u, direct.u) < 1e-8
    assert rel(mixed.v, direct.v) < 1e-8
    assert rel(mixed.psi, direct.psi) < 1e-7
    # each step's LCP: the contacts' complementarity
    assert np.all(c >= 0) and np.all(mixed.v[:, -4:] >= 0)
    assert np.abs(c * mixed.v[:, -4:]).max() < 1e-12 * c.max() * mixed.v[:, -4:].max() + 1e-300
    # modal takes the same problem through the Kelvin elements
    modal = ul.solve(model, load, method="modal", **kw)
    assert rel(modal.u, direct.u) < 1e-8


def test_two_footings_on_cones_cq_equals_modal():
    """Footings on cones are uncoupled rational soils: modal (the poles of the footings' cones and of
    the structure, here on piles that make K definite) equals cq."""
    st, load = portal({"model": "cones", "G": 4e4, "nu": 0.3, "rho": 2.0}, gap_link=False, yielding=False,
                      piles=True)
    model = st.to_model()
    assert not model.mixed and model.soil.is_rational and model.m == 4
    kw = dict(dt=2e-3, t_end=2.0)
    cq = ul.solve(model, load, method="cq", **kw)
    modal = ul.solve(model, load, method="modal", **kw)
    assert cq.success and modal.success
    assert cq.stats["contact_changes"] > 0
    assert rel(modal.u, cq.u) < 1e-7 and rel(modal.psi, cq.psi) < 1e-6


def rigid_cross_flexibility(fnd, structure):
    """Static flexibility of the rigid footings (uy, rz of each) from the patches' Phi(0)."""
    A = fnd.T(structure.dofs, structure.coords)
    names = [f"{f.node}.{d}" for f in fnd.footings for d in ("uy", "rz")
             if f"{f.node}.{d}" in structure.dofs.names]
    rows = [structure.dofs.names.index(n) for n in names]
    A = A[rows]                                       # (2 footings x (uy, rz), patches)
    K = A @ np.linalg.solve(fnd.soil.static(), A.T)
    return np.linalg.inv(K), names


def test_settlement_of_one_footing_under_the_others_load_is_the_cross_flexibility():
    fr = Frame2D()
    fr.node("a", 0.0, 0.0)
    fr.node("b", 3.0, 0.0)
    fr.foundation("A", "a", width=2.0, length=2.0, soil=HALF, patches=4, mass=1.0, J=0.2)
    fr.foundation("B", "b", width=2.0, length=2.0, soil=HALF, patches=4, mass=1.0, J=0.2)
    st = fr.build()
    model = st.to_model()
    Fr, names = rigid_cross_flexibility(st.foundation, st)
    assert abs(Fr[0, 2]) > 0.05 * Fr[0, 0]              # close footings interact through the ground
    uy = {n: st.dofs.names.index(n) for n in ("a.uy", "b.uy")}

    def settle(PA, PB):
        q = np.zeros(st.n)
        q[uy["a.uy"]], q[uy["b.uy"]] = -PA, -PB
        sol = ul.solve(model, lambda t: q, dt=1e-3, t_end=1e-3, initial="static", method="cq")
        assert sol.success and np.all(-sol.psi[0] > 0)             # every patch in contact
        return sol.u[0]

    u1, u2 = settle(100.0, 100.0), settle(100.0, 400.0)
    # the load on B moves A by the cross-flexibility (downward: negative uy)
    assert (u2 - u1)[uy["a.uy"]] == pytest.approx(-300.0 * Fr[0, 2], rel=1e-8)
    assert (u2 - u1)[uy["b.uy"]] == pytest.approx(-300.0 * Fr[2, 2], rel=1e-8)


def test_footings_far_apart_decouple_as_boussinesq():
    """The static coupling of two footings decays as the point-load term (1 - nu)/(2 pi G r)."""
    G, nu = HALF["G"], HALF["nu"]
    for r in (20.0, 40.0, 80.0):
        fr = Frame2D()
        fr.node("a", 0.0, 0.0)
        fr.node("b", r, 0.0)
        fr.foundation("A", "a", width=1.0, length=1.0, soil=HALF, patches=1)
        fr.foundation("B", "b", width=1.0, length=1.0, soil=HALF, patches=1)
        st = fr.build()
        Phi0 = st.foundation.soil.static()
        # Boussinesq's point term, with the patches' size correction (a/r)^2 / 12 = 2e-4 at r = 20
        assert Phi0[0, 1] == pytest.approx((1 - nu) / (2 * np.pi * G * r), rel=3e-4)
        Fr, _ = rigid_cross_flexibility(st.foundation, st)
        assert Fr[0, 1] / Fr[0, 0] == pytest.approx(Phi0[0, 1] / Phi0[0, 0], rel=1e-12)   # one patch each


def test_far_footings_move_as_single_footings():
    """Two identical footings 200 m apart under equal loads: each moves as one footing alone."""
    def one(nodes):
        fr = Frame2D()
        for k, x in enumerate(nodes):
            fr.node(k, x, 0.0)
            fr.node(10 + k, x, 3.0)
            fr.beam(f"col{k}", k, 10 + k, E=3e7, A=0.1, I=1e-3)
            fr.mass(10 + k, 10.0)
            fr.foundation(f"F{k}", k, width=2.0, length=2.0, soil=HALF, patches=2)
        st = fr.build()
        x = st.influence("ux")
        g = -9.81 * (st.M @ st.influence("uy"))
        sol = ul.solve(st.to_model(), lambda t: g - st.M @ x * 4.0 * np.sin(8 * t), dt=4e-3, t_end=1.0)
        assert sol.success, sol.message
        return st, sol

    st1, s1 = one([0.0])
    st2, s2 = one([0.0, 200.0])
    i1 = st1.dofs.names.index("10.ux")
    for k in (0, 1):
        i2 = st2.dofs.names.index(f"{10 + k}.ux")
        assert rel(s2.u[:, i2], s1.u[:, i1]) < 2e-3


def test_bad_footings_are_refused_naming_the_argument():
    fr = Frame2D()
    fr.node("a", 0.0, 0.0)
    fr.node("b", 1.5, 0.0)
    fr.foundation("A", "a", width=2.0, length=2.0, soil=HALF)
    with pytest.raises(ValueError, match="overlaps footing 'A'"):
        fr.foundation("B", "b", width=2.0, length=2.0, soil=HALF)
    fr.node("c", 0.0, 3.0)
    fr.node("d", 1.0, 3.0)
    with pytest.raises(ValueError, match="mass=5.0, J=0.0 are for a rigid footing"):
        fr.foundation("C", "c", nodes=["c", "d"], width=2.0, length=2.0, soil=HALF, mass=5.0)
    fr = Frame2D()
    fr.node("a", 0.0, 0.0)
    fr.node("e", 10.0, 0.0)
    fr.foundation("A", "a", width=2.0, length=2.0, soil=HALF, mass=1.0)
    fr.foundation("E", "e", width=2.0, length=2.0, soil={**HALF, "G": 5e4}, mass=1.0)
    with pytest.raises(ValueError, match="share that soil"):
        fr.build()


MODEL_FILE = """
units = {{ length = "m", force = "kN", time = "s" }}
nodes = [ {{ id = 1, x = 0.0, y = 0.0 }}, {{ id = 2, x = 6.0, y = 0.0 }}, {{ id = 11, x = 0.0, y = 3.0 }},
          {{ id = 12, x = 6.0, y = 3.0 }}, {{ id = 9, x = 6.3, y = 3.0 }} ]
supports = [ {{ node = 9 }} ]
elements = [
  {{ type = "beam", name = "c1", node_i = 1, node_j = 11, E = 3e7, A = 0.2, I = 2e-3 }},
  {{ type = "beam", name = "c2", node_i = 2, node_j = 12, E = 3e7, A = 0.2, I = 2e-3 }},
  {{ type = "beam", name = "b", node_i = 11, node_j = 12, E = 3e7, A = 0.2, I = 2e-3 }},
]
unilateral = [ {{ type = "gap", name = "pound", node_i = 12, node_j = 9, k = 2e5, gap = 0.002 }} ]
masses = [ {{ node = 11, m = 20.0 }}, {{ node = 12, m = 20.0 }} ]
{footings}
[loads.gravity]
g = "standard"
[[loads.nodal]]
node = 11
ux = 50.0
[analysis]
dt = 5e-3
t_end = 0.2
method = "cq"
"""

FOOTING = """
[[foundations]]
name = "{name}"
node = {node}
width = 2.0
length = 2.0
patches = 2
mass = {mass}
J = 0.5
soil = {soil}
"""


def model_file(tmp_path, soil, *, mass=2.0, extra=""):
    text = MODEL_FILE.format(footings="".join(FOOTING.format(name=n, node=k, soil=soil, mass=mass)
                                              for n, k in (("A", 1), ("B", 2))) + extra)
    path = tmp_path / "footings.toml"
    path.write_text(text)
    return path


def test_model_file_footings_beside_a_gap(tmp_path):
    from unilateral.modelfile import load_model_file

    spec = load_model_file(model_file(tmp_path, '{ model = "winkler-kelvin", k = 4e4, c = 4e2 }'))
    model = spec.model
    assert isinstance(model, FoundationModel) and model.mixed
    assert model.constraint_names == ["pound", "A.1", "A.2", "B.1", "B.2"]
    # the footings' own masses (kN s^2/m) on their nodes
    names = spec.structure.dofs.names
    M = spec.structure.M.toarray()
    assert M[names.index("1.uy"), names.index("1.uy")] == pytest.approx(2.0)
    assert M[names.index("1.rz"), names.index("1.rz")] == pytest.approx(0.5)
    sol = ul.solve(model, spec.load, dt=5e-3, t_end=0.2)
    assert sol.success, sol.message


def test_model_file_layered_soil_and_bad_footings(tmp_path):
    from unilateral.modelfile import ModelFileError, load_model_file

    layered = ('{ model = "layered", layers = [{ thickness = 3.0, Vs = 120.0, nu = 0.35, rho = 1.8 }], '
               'Vs = 300.0, nu = 0.3, rho = 2.0 }')
    spec = load_model_file(model_file(tmp_path, layered))
    soil = spec.model.soil
    assert "Layered" in soil.description and soil.m == 4
    assert abs(soil.static()[0, 2]) > 0                  # one soil: the footings are coupled
    cases = [
        (dict(soil=layered.replace("Vs = 300.0, ", "")), "foundations[0].soil.G: missing key"),
        (dict(soil='{ model = "layered", Vs = 300.0, nu = 0.3, rho = 2.0 }'), "foundations[0].soil.layers: missing"),
        (dict(soil=layered.replace('model = "layered"', 'model = "halfspace"')), 'only for model = "layered"'),
        (dict(soil='{ model = "layered", base = "rigid", Vs = 300.0, layers = [{ thickness = 3.0, Vs = 120.0, '
                   'nu = 0.35, rho = 1.8 }] }'), 'not used with base = "rigid"'),
        (dict(soil='{ model = "layered", base = "rigid", layers = [{ thickness = -3.0, Vs = 120.0, '
                   'nu = 0.35, rho = 1.8 }] }'), "thickness"),
        (dict(soil=layered, extra='\n[foundation]\nnode = 1\nwidth = 1.0\nlength = 1.0\nsoil = ' + layered),
         "either as [foundation] (one) or as [[foundations]]"),
    ]
    for kwargs, text in cases:
        with pytest.raises(ModelFileError) as info:
            load_model_file(model_file(tmp_path, **kwargs))
        assert text in str(info.value), (kwargs, str(info.value))


def test_footings_example_writes_its_figure_and_results(tmp_path):
    """A short run of ``unilateral example footings``: outputs, the comparison and the manifest."""
    import json

    import xarray as xr

    from unilateral.analysis import run_example

    result = run_example("footings", tmp_path / "out", dt=0.02, t_end=0.6)
    assert result["success_all"]
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    assert "footings.png" in json.dumps(manifest)
    assert set(result["comparison"]) == {"one soil", "each footing on its own soil", "one soil, sliding"}
    assert result["comparison"]["one soil, sliding"]["unilateral"]["max_slip"] >= 0.0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["extra"]["comparison"] == result["comparison"]
    with xr.open_dataset(tmp_path / "out" / "results.nc") as ds:
        kinds = list(ds["constraint_kind"].values)
        assert kinds.count("foundation") == 11 and kinds[:4] == ["yield"] * 4
