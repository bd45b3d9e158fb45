"""A Frame2D footing on a soil medium (Frame2D.foundation): the paper's example, convergence, results,
model files and the ``halfspace`` example."""

from __future__ import annotations

import json

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.results import structure_results
from unilateral.loads import HalfSine, LoadHistory, Rectangular
from unilateral.modelfile import ModelFileError, load_model_file
from unilateral.structure import Frame2D
from unilateral.structure.examples import C_SOIL, EA_RIGID, EI, K_SOIL, MASS, halfspace_tower, liolios1990


def rel(a, b):
    return float(np.abs(a - b).max() / np.abs(b).max())


def paper_frame_on(soil, *, width=15.0, length=1.0, patches=3, horizontal="support"):
    """The paper's tower (liolios1990) with its soil elements replaced by Frame2D.foundation."""
    fr = Frame2D()
    fr.node(1, 0.0, 10.0)
    fr.node(2, 0.0, 0.0)
    fr.beam("column", 2, 1, E=1.0, A=EA_RIGID, I=EI)
    fr.mass(1, MASS)
    fr.foundation("footing", 2, width=width, length=length, patches=patches, soil=soil, horizontal=horizontal)
    st = fr.build()
    load = LoadHistory(st.gravity(10.0), [(st.nodal_load(1, ux=1.0), Rectangular(200.0, t_end=0.1))])
    return st, load


# ---------------------------------------------------------------------- the paper's example
def test_rigid_footing_on_winkler_kelvin_is_the_papers_example():
    # three strips of a 15 m footing: contacts at x = -5, 0, +5, the paper's soil elements
    st, load = paper_frame_on({"model": "winkler-kelvin", "k": K_SOIL, "c": C_SOIL})
    ref_st, ref_load, _ = liolios1990()
    assert st.dofs.names == ref_st.dofs.names
    model, paper = st.to_model(), ref_st.to_model()
    assert type(model).__name__ == "FoundationModel" and model.contact_names == ["footing.1", "footing.2", "footing.3"]
    np.testing.assert_allclose(model.T[:, 0], [0, 0, 0, 1.0, -5.0])             # uy - 5 rz of node 2
    kw = dict(dt=1e-3, t_end=1.0, rule="bdf2")
    # modal: the footing's Kelvin soil is solved as the paper's primal model: the same discrete problem
    modal, paper_modal = ul.solve(model, load, method="modal", **kw), ul.solve(paper, ref_load, method="modal", **kw)
    assert paper_modal.v.max() > 2e-3 and paper_modal.stats["contact_changes"] >= 8      # node 3 lifts off
    for name in ("u", "v", "psi"):
        assert rel(getattr(modal, name), getattr(paper_modal, name)) < 1e-9, name  # measured 0.0
    # cq: the dual march in the contact forces against the paper's model stepped directly
    dual, direct = ul.solve(model, load, method="cq", **kw), ul.solve(paper, ref_load, method="direct", **kw)
    assert dual.stats["contact_changes"] == direct.stats["contact_changes"]
    assert rel(dual.u, direct.u) < 1e-9 and rel(dual.v, direct.v) < 1e-9               # measured 5.5e-11, 5.6e-11
    assert rel(dual.psi, direct.psi) < 5e-9                                             # measured 1.8e-9
    assert dual.u[0, 3] == pytest.approx(-MASS * 10.0 / (3 * K_SOIL), rel=1e-9)          # the paper's -0.667 mm


def test_footing_on_the_halfspace_converges_at_order_two():
    st, _ = paper_frame_on({"model": "halfspace", "Vs": 97.0, "nu": 1 / 3, "rho": 2.0}, width=10.0,
                           length=10.0, patches=3)
    model = st.to_model()
    load = LoadHistory(st.gravity(10.0), [(st.nodal_load(1, ux=1.0), HalfSine(60.0, duration=0.1))])
    dts = [6e-3, 3e-3, 1.5e-3, 7.5e-4]
    sols = [ul.solve(model, load, dt=dt, t_end=0.36, method="cq", rule="bdf2") for dt in dts]
    assert all(s.success and s.stats["contact_changes"] == 0 for s in sols)      # smooth: no lift-off
    # differences of successive runs at the coarser grid, u and psi = -c: ~ C dt^p
    errors = [max(rel(c.u, f.u[::2]), rel(c.psi, f.psi[::2])) for c, f in zip(sols[:-1], sols[1:])]
    slope = np.polyfit(np.log(dts[:-1]), np.log(errors), 1)[0]
    # measured: 2.3e-2, 6.2e-3, 1.6e-3, slope 1.95 (dt = 4e-3 ... 5e-4: 1.98)
    assert slope >= 1.9, (errors, slope)


def test_truncated_soil_weights_equal_the_full_fft():
    from unilateral.rules import get_rule
    from unilateral.soil import HalfSpace, SoilFlexibility, strips

    soil = SoilFlexibility.halfspace(HalfSpace(2.0 * 97.0 ** 2, 1 / 3, 2.0), strips(10.0, 10.0, 3))
    rule = get_rule("bdf2", cq=True)
    N, dt = 400, 2e-3
    full = soil.cq_weights(N, dt, rule, L=8 * (N + 1))                # the plain FFT of N + 1 weights
    short = soil.cq_weights(N, dt, rule)                               # truncated after ~3 travel times
    J = int(np.ceil(soil.memory / dt)) + 64
    assert J < N and np.all(short[J + 1:] == 0.0)
    # 6 (J + 1) points on the circle (8 (N + 1) for the full FFT): measured 7.5e-9 of the largest weight
    assert np.abs(short - full).max() <= 3e-8 * np.abs(full).max()
    assert soil.cq_weights(N, dt, rule) is not short and np.array_equal(soil.cq_weights(N, dt, rule), short)


def test_algebraic_tail_of_the_soil_weights_against_all_weights():
    """Two footings of 3 strips, x and z (the coupled Green's tensor, nu = 1/3): the weights decay as
    j^-3 and never fall below 1e-8, so the computed ones are extended by ``A j^-3`` with all weights
    summing to the static flexibility. Against the plain FFT of all N + 1 weights: the step
    responses (partial sums) agree to 2e-5 of the static flexibility (measured 8.2e-6), each weight
    to 5e-6 of the largest (1.7e-6), from a third of the kernel's evaluations."""
    from scipy.special import zeta

    from unilateral.rules import get_rule
    from unilateral.soil import HalfSpace, RectangularPatches, SoilFlexibility, strips
    from unilateral.soil.flexibility import TAIL_POWER

    a = strips(10.0, 10.0, 3)
    patches = RectangularPatches(np.vstack([a.centres, a.centres + [15.0, 0.0]]), np.vstack([a.sizes, a.sizes]))
    soil = SoilFlexibility.halfspace(HalfSpace(2.0 * 97.0 ** 2, 1 / 3, 2.0), patches, components="xz")
    rule = get_rule("bdf2", cq=True)
    N, dt = 1500, 2e-3
    short = soil.cq_weights(N, dt, rule)
    known = soil._weights_cache[(dt, "bdf2")]
    J = known.W.shape[0] - 1
    assert known.tail is not None and 2 * J < N
    static = soil.static()
    beyond = known.tail * zeta(TAIL_POWER, N + 1)                      # the tail past N, summed
    assert np.abs(short.sum(axis=0) + beyond - static).max() <= 1e-12 * np.abs(static).max()
    full = soil.cq_weights(N, dt, rule, L=6 * (N + 1))
    assert np.abs(np.cumsum(short - full, axis=0)).max() <= 2e-5 * np.abs(static).max()
    assert np.abs(short - full).max() <= 5e-6 * np.abs(full).max()


# ---------------------------------------------------------------------- the frame's results
def test_frame_results_put_the_contact_forces_among_the_ground_reactions():
    st, load = paper_frame_on({"model": "winkler-kelvin", "k": K_SOIL, "c": C_SOIL})
    model = st.to_model()
    sol = ul.solve(model, load, dt=1e-3, t_end=0.5, method="cq")
    q = load.sample(sol.t)
    res = structure_results(st, model, {"unilateral": sol}, rule="bdf2", load_samples=q)
    peaks = res["peaks"]["unilateral"]
    assert set(peaks["ground_reactions"]) == {"footing.1", "footing.2", "footing.3"}
    (_, per_case, _) = res["variables"]["base_vertical"]
    (_, acc, _) = res["variables"]["acceleration"]
    (_, moment, _) = res["variables"]["overturning_moment"]
    c = -sol.psi
    # vertical equilibrium of the whole frame: ground forces = r_y^T (M u'' - q)
    r_y = st.influence("uy")
    expected = (acc["unilateral"] @ st.M.toarray() @ r_y) - q @ r_y
    assert np.abs(per_case["unilateral"] - expected).max() < 1e-8 * np.abs(expected).max()
    assert np.allclose(per_case["unilateral"], c.sum(axis=1), rtol=0, atol=1e-9 * c.max())
    # overturning moment about the lowest, leftmost node (node 2 at the origin): sum x_j c_j + support
    x = st.foundation.patches.centres[:, 0]
    assert np.allclose(moment["unilateral"], c @ x, rtol=0, atol=1e-9 * np.abs(c @ x).max())
    assert "mode_period" in res["static"]                          # on the soil's static springs


def test_horizontal_cone_restrains_the_footing_with_wolfs_horizontal_cone():
    soil = {"model": "halfspace", "G": 2e4, "nu": 0.25, "rho": 2.0}
    st, load = paper_frame_on(soil, width=10.0, length=10.0, patches=2, horizontal="cone")
    r0 = np.sqrt(100.0 / np.pi)
    by_name = {e.name: e for e in list(st.elements) + list(st.dashpots)}
    assert by_name["footing.horizontal_spring"].E[0, 0] == pytest.approx(8 * 2e4 * r0 / (2 - 0.25), rel=1e-12)
    assert by_name["footing.horizontal_dashpot"].E[0, 0] == pytest.approx(2.0 * np.sqrt(1e4) * np.pi * r0 ** 2,
                                                                          rel=1e-12)
    assert "2.ux" in st.dofs.names                                   # not supported: the cone holds it
    with pytest.raises(ValueError, match="horizontal='cone' needs the soil's G"):
        paper_frame_on({"model": "winkler-kelvin", "k": 1e5}, horizontal="cone")


def test_frame_foundation_refuses_bad_input_naming_the_argument():
    def frame():
        fr = Frame2D()
        fr.node(1, 0.0, 10.0)
        fr.node(2, 0.0, 0.0)
        fr.beam("column", 2, 1, E=1.0, A=1e3, I=1e3)
        fr.mass(1, 1.0)
        return fr

    soil = {"model": "halfspace", "Vs": 100.0, "nu": 0.3, "rho": 2.0}
    cases = [
        (dict(width=10.0, length=10.0, soil=soil, patches=0), "patches=0"),
        (dict(width=-1.0, length=10.0, soil=soil), "width=-1.0"),
        (dict(width=10.0, length=10.0, soil={**soil, "model": "clay"}), "model='clay'"),
        (dict(width=10.0, length=10.0, soil={**soil, "G": 1e4}), "either G or Vs"),
        (dict(width=10.0, length=10.0, soil={**soil, "Vs": None}), "either G or Vs"),
        (dict(width=10.0, length=10.0, soil={**soil, "E": 1.0}), "unknown key(s) 'E'"),
        (dict(width=10.0, length=10.0, soil={"model": "winkler-kelvin"}), "needs k"),
        (dict(width=10.0, length=10.0, soil={"model": "winkler-kelvin", "k": [1.0, 2.0]}), "list of 3 numbers"),
        (dict(width=10.0, length=10.0, soil={**soil, "model": "cones", "damping": 0.05}), "no material damping"),
        (dict(width=10.0, length=10.0, soil=soil, horizontal="friction"), "horizontal='friction'"),
        (dict(width=10.0, length=10.0, soil=soil, nodes=[1]), "at least two nodes"),
    ]
    for kwargs, text in cases:
        with pytest.raises(ValueError, match=None) as info:
            frame().foundation("footing", 2, **kwargs)
        assert text in str(info.value), (kwargs, str(info.value))
    fr = frame()
    fr.foundation("footing", 2, width=10.0, length=10.0, soil=soil)
    with pytest.raises(ValueError, match="already rest on another footing"):
        fr.foundation("other", 2, width=10.0, length=10.0, soil=soil)
    fr.node(5, 8.0, 0.0)
    with pytest.raises(ValueError, match="overlaps footing 'footing' .* by 2"):
        fr.foundation("other", 5, width=10.0, length=10.0, soil=soil)
    fr.foundation("other", 5, width=2.0, length=10.0, soil={**soil, "G": None, "Vs": 300.0})
    with pytest.raises(ValueError, match="share that soil"):
        fr.build()


def test_flexible_footing_has_one_patch_per_node():
    fr = Frame2D()
    for k, x in enumerate([-4.0, 0.0, 4.0]):
        fr.node(k, x, 0.0)
    fr.node(9, 0.0, 6.0)
    fr.beam("b0", 0, 1, E=3e7, A=1.0, I=0.1)
    fr.beam("b1", 1, 2, E=3e7, A=1.0, I=0.1)
    fr.beam("col", 1, 9, E=3e7, A=1.0, I=0.1)
    fr.mass(9, 30.0)
    for k in range(3):
        fr.mass(k, 5.0)
    fr.foundation("beam", 1, nodes=[2, 0, 1], width=10.0, length=2.0,
                  soil={"model": "winkler-kelvin", "k": 1e4, "c": 10.0})
    st = fr.build()
    fnd = st.foundation
    np.testing.assert_allclose(fnd.patches.centres[:, 0], [-4.0, 0.0, 4.0])
    np.testing.assert_allclose(fnd.patches.sizes[:, 0], [2.0, 4.0, 2.0])    # centred on the nodes
    model = st.to_model()
    assert model.contact_names == ["beam.0", "beam.1", "beam.2"]
    for j, node in enumerate((0, 1, 2)):
        assert model.T[st.dofs.index(node, "uy"), j] == 1.0 and np.count_nonzero(model.T[:, j]) == 1
    load = LoadHistory(st.gravity(10.0), [(st.nodal_load(9, ux=1.0), Rectangular(300.0, t_end=0.2))])
    sol = ul.solve(model, load, dt=2e-3, t_end=0.6, method="cq")
    assert sol.success and sol.v.max() > 0          # an end lifts off
    c = -sol.psi
    assert c[0].sum() == pytest.approx(10.0 * 45.0, rel=1e-9)               # the weight rests on the soil


# ---------------------------------------------------------------------- ground motion
def test_ground_motion_is_the_load_minus_M_r_ag_and_the_footing_rocks():
    from unilateral.loads import synthetic_accelerogram

    record = synthetic_accelerogram(3.0, 0.01, 5.0, seed=1, f_g=4.0)
    st, load, _ = halfspace_tower("winkler-kelvin", load="earthquake", record=record)
    model = st.to_model()
    r = st.influence("ux")
    t = np.linspace(0.0, 3.0, 31)
    expected = st.gravity(10.0)[None, :] - np.outer(record(t), np.asarray(st.M @ r).ravel())
    assert np.allclose(load.sample(t), expected, rtol=0, atol=1e-12)
    sol = ul.solve(model, load, dt=2e-3, t_end=3.0, method="cq")
    assert sol.success and sol.v.max() > 0


# ---------------------------------------------------------------------- model files
MODEL = """
units = {{ length = "m", force = "kN", time = "s" }}
nodes = [{{ id = 1, x = 0.0, y = 10.0 }}, {{ id = 2, x = 0.0, y = 0.0 }}]
elements = [{{ type = "beam", name = "column", node_i = 2, node_j = 1, E = 1.0, A = 1e12, I = 1e9 }}]
masses = [{{ node = 1, m = 40.0 }}]

[foundation]
node = 2
width = 10.0
length = 10.0
patches = 3
soil = {soil}

[loads]
gravity = {{ g = 10.0 }}
nodal = [{{ node = 1, ux = 200.0, time_function = {{ type = "rectangular", t_end = 0.1 }} }}]

[analysis]
dt = 0.004
t_end = 0.4
method = "cq"

[output]
figure = {{ node = 2, dof = "rz" }}
"""


def test_a_model_file_with_a_foundation_runs(tmp_path):
    path = tmp_path / "footing.toml"
    path.write_text(MODEL.format(soil='{ model = "halfspace", Vs = 97.0, nu = 0.3333, rho = 2.0 }'))
    spec = load_model_file(path)
    assert spec.structure.foundation is not None and spec.model.m == 3
    summary = ul.run(path, tmp_path / "out", figures=("png",))
    assert summary["success_all"]
    assert (tmp_path / "out" / "results.nc").exists() and (tmp_path / "out" / "constraints.csv").exists()
    stored = json.loads((tmp_path / "out" / "summary.json").read_text())
    ground = stored["results"]["unilateral"]["ground_reactions"]
    assert set(ground) == {"footing.1", "footing.2", "footing.3"}
    assert max(ground["footing.1"]["fy"]["max"], ground["footing.3"]["fy"]["max"]) > 400.0 / 3


@pytest.mark.parametrize("soil, expected", [
    ('{ model = "halfspce", Vs = 97.0, nu = 0.3, rho = 2.0 }',
     'foundation.soil.model = "halfspce": unknown soil model (valid: halfspace, layered, cones, winkler-kelvin)'),
    ('{ model = "halfspace", G = 1e4, Vs = 97.0, nu = 0.3, rho = 2.0 }',
     "foundation.soil.Vs = 97.0: give either G or Vs, not both"),
    ('{ model = "halfspace", Vs = 97.0, nu = 0.6, rho = 2.0 }', "foundation.soil.nu = 0.6"),
    ('{ model = "winkler-kelvin", k = [1e5, 2e5] }',
     "foundation.soil.k = [100000.0, 200000.0]: give one number or a list of 3 numbers"),
    ('{ model = "winkler-kelvin", c = 1.0 }', "foundation.soil.k: missing key"),
    ('{ model = "cones", Vs = 97.0, nu = 0.3, rho = 2.0, damping = 0.05 }',
     "foundation.soil.damping = 0.05: the cones have no material damping"),
])
def test_a_malformed_foundation_section_names_the_key_the_value_and_what_is_valid(tmp_path, soil, expected):
    path = tmp_path / "bad.toml"
    path.write_text(MODEL.format(soil=soil))
    with pytest.raises(ModelFileError) as info:
        load_model_file(path)
    assert expected in str(info.value), str(info.value)


def test_a_foundation_node_that_does_not_exist_is_named(tmp_path):
    path = tmp_path / "bad.toml"
    text = MODEL.format(soil='{ model = "winkler-kelvin", k = 2e5 }').replace("node = 2\nwidth", "node = 7\nwidth")
    path.write_text(text)
    with pytest.raises(ModelFileError, match=r"foundation.node = 7: no node 7 \(nodes are 1, 2\)"):
        load_model_file(path)


# ---------------------------------------------------------------------- the example
def test_the_halfspace_example_runs_and_draws_its_comparison(tmp_path):
    result = ul.analysis.run_example("halfspace", tmp_path / "hs", figures=("png",), dt=4e-3, t_end=1.0)
    assert result["success_all"]
    assert (tmp_path / "hs" / "halfspace.png").exists() and (tmp_path / "hs" / "results.nc").exists()
    comparison = result["comparison"]
    assert set(comparison) == {f"{s}/{l}" for s in ("winkler-kelvin", "cones", "halfspace")
                               for l in ("pulse", "earthquake")}
    for soil in ("winkler-kelvin", "cones", "halfspace"):
        pulse = comparison[f"{soil}/pulse"]
        assert pulse["unilateral"]["max_uplift"] > 1e-3                  # the left edge lifts off
        assert pulse["bilateral"]["max_uplift"] == 0.0


def test_the_halfspace_figure_is_in_the_manifest(tmp_path):
    import json

    ul.analysis.run_example("halfspace", tmp_path / "hs", figures=("png",), dt=1e-2, t_end=0.3)
    files = json.loads((tmp_path / "hs" / "manifest.json").read_text())["files"]
    assert "halfspace.png" in files and "results.nc" in files
