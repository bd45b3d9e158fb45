"""Model files: the examples, the error messages, matrix-level models, loads and the JSON schema."""

import json
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

import unilateral as ul
from unilateral.loads import STANDARD_GRAVITY, force_factor, length_factor, read_at2, read_text_record
from unilateral.modelfile import ModelFileError, load_model_file, model_file_schema
from unilateral.modelfile.errors import compact_ids
from unilateral.modelfile.schema import FORCE_UNITS, LENGTH_UNITS
from unilateral.structure import liolios1990

ROOT = Path(__file__).parents[1]
EXAMPLES = ROOT / "examples"
DATA = Path(__file__).parent / "data"
MATRIX_KEYS = ("K", "M", "C", "F", "H", "F_v", "H_v")


def dense(a):
    return a.toarray() if sp.issparse(a) else np.asarray(a)


def toml_text(document: dict) -> str:
    """A TOML document with every section written inline (enough for the tests)."""
    def inline(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, list):
            return "[" + ", ".join(inline(x) for x in v) + "]"
        if isinstance(v, dict):
            return "{" + ", ".join(f"{k} = {inline(x)}" for k, x in v.items()) + "}"
        return repr(v)
    return "".join(f"{key} = {inline(value)}\n" for key, value in document.items())


def write(tmp_path, document, name="model.toml") -> Path:
    path = tmp_path / name
    path.write_text(document if isinstance(document, str) else toml_text(document))
    return path


def beam_on_soil(n=12) -> dict:
    """A valid model: a beam on n nodes 1..n, each on a tensionless soil element."""
    return {
        "units": {"length": "m", "force": "kN", "time": "s"},
        "nodes": [{"id": i, "x": float(i - 1), "y": 0.0} for i in range(1, n + 1)],
        "supports": [{"node": 1, "ux": True, "uy": False}],
        "elements": [{"type": "beam", "name": f"b{i}", "node_i": i, "node_j": i + 1, "E": 30e6, "A": 0.5,
                      "I": 0.01} for i in range(1, n)],
        "unilateral": [{"type": "soil", "name": f"s{i}", "node": i, "k": 1e4} for i in range(1, n + 1)],
        "masses": [{"node": i, "m": 1.0} for i in range(1, n + 1)],
        "loads": {"gravity": {"g": 10.0}},
        "analysis": {"dt": 1e-3, "t_end": 0.01},
    }


def raises(tmp_path, document, message):
    with pytest.raises(ModelFileError, match=re.escape(message)):
        load_model_file(write(tmp_path, document))


# ---------------------------------------------------------------------- the examples
def test_liolios1990_file_equals_the_builder():
    spec = load_model_file(EXAMPLES / "liolios1990.toml")
    structure, load, info = liolios1990()
    reference = structure.to_model()
    for key in MATRIX_KEYS:
        np.testing.assert_allclose(dense(getattr(spec.model, key)), dense(getattr(reference, key)),
                                   rtol=1e-14, atol=0, err_msg=key)
    assert spec.model.dof_names == reference.dof_names
    assert spec.model.constraint_names == reference.constraint_names
    for t in (0.0, 0.001, 0.05, 0.1, 0.1005, 0.3):
        np.testing.assert_array_equal(spec.load(t), load(t))
    assert spec.units == {"length": "m", "force": "kN", "time": "s", "mass": "kN s^2/m"}
    assert spec.figure == {"node": 3, "dof": "uy", "label": "vertical displacement of node 3 (m)"}
    assert spec.analysis == {"type": "transient", "dt": 1e-3, "t_end": 1.0, "t_after": 0.0, "method": "cq", "rule": "bdf2",
                             "lcp": "bpp",
                             "initial": "static", "load_sampling": "average", "bilateral_reference": True, "p_delta": False,
                             "title": "Liolios (1990), Fig. 2: vertical displacement of node 3"}
    assert spec.source == EXAMPLES / "liolios1990.toml"


def test_liolios1990_file_starts_from_the_static_displacement():
    spec = load_model_file(EXAMPLES / "liolios1990.toml")
    sol = ul.solve(spec.model, spec.load, dt=1e-3, t_end=0.05)
    assert sol.success
    uy3 = spec.structure.node_displacement(sol, 3, "uy")
    assert uy3[0] == pytest.approx(-0.667e-3, rel=1e-3)
    assert uy3[0] == pytest.approx(-40.0 * 10.0 / (3 * 200e3), rel=1e-9)


@pytest.mark.parametrize("name, m", [("winkler_beam", 21), ("pounding", 1), ("yielding_frame", 48)])
def test_examples_load_and_solve(name, m):
    spec = load_model_file(EXAMPLES / f"{name}.toml")
    assert spec.model.m == m
    dt = spec.analysis["dt"]
    sol = ul.solve(spec.model, spec.load, dt=dt, t_end=10 * dt)
    assert sol.success and sol.t.size == 11
    node = spec.figure["node"]
    assert np.all(np.isfinite(spec.structure.node_displacement(sol, node, spec.figure["dof"])))


def test_pounding_example_is_loaded_by_the_record():
    spec = load_model_file(EXAMPLES / "pounding.toml")
    record = read_at2(EXAMPLES / "records" / "synthetic_0.35g.AT2")     # in g, converted to m/s^2
    r = np.array([name.endswith(".ux") for name in spec.model.dof_names], dtype=float)
    for t in (0.5, 1.234, 6.0):
        np.testing.assert_allclose(spec.load(t) - spec.load.constant, -(spec.model.M @ r) * record(t),
                                   rtol=1e-13, atol=1e-12)


# ---------------------------------------------------------------------- error messages
def test_the_base_model_of_the_error_tests_is_valid(tmp_path):
    spec = load_model_file(write(tmp_path, beam_on_soil()))
    assert (spec.model.n, spec.model.m) == (3 * 12 - 1, 12)


def modify(**changes):
    """A function that applies ``changes`` (key path -> value; None deletes) to beam_on_soil()."""
    def apply(document):
        for path, value in changes.items():
            *parents, last = [int(p) if p.isdigit() else p for p in path.split("__")]
            target = document
            for p in parents:
                target = target[p]
            if value is None:
                del target[last]
            else:
                target[last] = value
        return document
    return apply


ERRORS = {
    "no node": (modify(elements__3__node_j=17),
                "model.toml: elements[3].node_j = 17: no node 17 (nodes are 1..12)"),
    "unknown type": (modify(elements__0__type="bem"),
                     'model.toml: elements[0].type = "bem": unknown element type (valid: bar, beam, dashpot, '
                     'spring); did you mean "beam"?'),
    "typo in a key": (modify(unilateral__1__k=None, unilateral__1__stifness=200.0),
                      'model.toml: unilateral[1].stifness: unknown key (did you mean "k"? valid keys: type, name, '
                      "node, k, c, direction, gap, capacity, mu, kt, ct, bearing)"),
    "EI for I": (modify(elements__0__I=None, elements__0__EI=3e5),
                 'model.toml: elements[0].EI: unknown key (did you mean "I"?'),
    "E for e": (modify(elements__0__E=None, elements__0__e=3e5),
                'model.toml: elements[0].e: unknown key (did you mean "E"?'),
    "negative stiffness": (modify(unilateral__0__k=-200.0), "model.toml: unilateral[0].k = -200.0: must be > 0"),
    "missing units": (modify(units=None),
                      'model.toml: units: missing section (declare e.g. [units] length = "m", force = "kN", '
                      'time = "s")'),
    "unknown unit": (modify(units__length="furlong"),
                     'model.toml: units.length = "furlong": unknown length unit (valid: m, cm, mm, in, ft)'),
    "wrong type": (modify(elements__2__E="abc"), 'model.toml: elements[2].E = "abc": expected a number'),
    "duplicate node": (modify(nodes__5__id=3), "model.toml: nodes[5].id = 3: duplicate node id (also nodes[2].id)"),
    "duplicate name": (modify(unilateral__2__name="b1"),
                       'model.toml: unilateral[2].name = "b1": duplicate element name (also elements[0].name)'),
    "missing key": (modify(elements__1__A=None),
                    "model.toml: elements[1].A: missing key (required keys: type, name, node_i, node_j, E, A, I)"),
    "missing type": (modify(unilateral__0__type=None),
                     "model.toml: unilateral[0].type: missing key (valid unilateral element types: cable, gap, hinge, "
                     "slider, soil, yield)"),
    "unknown section": (modify(analysis=None, analysys={"dt": 0.1, "t_end": 1.0}),
                        'model.toml: analysys: unknown section (did you mean "analysis"?'),
    "unknown choice": (modify(analysis__lcp="lemk"),
                       'model.toml: analysis.lcp = "lemk": unknown LCP solver (valid: bpp, enumerate, lemke, newton, '
                       'pgs); did you mean "lemke"?'),
    "not finite": (modify(masses__0__m=float("inf")), "model.toml: masses[0].m = inf: must be finite"),
    "bool for a number": (modify(masses__0__m=True), "model.toml: masses[0].m = true: expected a number"),
    "bad direction": (modify(unilateral__0__direction="uz"),
                      'model.toml: unilateral[0].direction = "uz": expected "ux", "uy", "rz" or a vector [dx, dy]'),
    "rayleigh forms": (modify(damping={"rayleigh": {"zeta": 0.05, "a0": 1.0}}),
                       "model.toml: damping.rayleigh: give either zeta, f1 and f2, or a0 and/or a1"),
    "time function type": (modify(loads__nodal=[{"node": 2, "uy": 1.0, "time_function": {"type": "pulse"}}]),
                           'model.toml: loads.nodal[0].time_function.type = "pulse": unknown time function type '
                           "(valid: constant, half_sine, ramp, rectangular, table, triangular)"),
    "time function values": (
        modify(loads__nodal=[{"node": 2, "uy": 1.0, "time_function": {"type": "rectangular", "t_start": 0.2,
                                                                        "t_end": 0.1}}]),
        "model.toml: loads.nodal[0].time_function: t_end must be > t_start, got t_end=0.1 and t_start=0.2"),
    "node and dof": (modify(loads__nodal=[{"node": 2, "uy": 1.0, "dof": 3}]),
                     "model.toml: loads.nodal[0]: give either node with ux, uy, rz, or dof with value"),
    "dof in a frame": (modify(loads__nodal=[{"dof": "2.uy", "value": 1.0}]),
                       'model.toml: loads.nodal[0].dof = "2.uy": DOF loads are for matrix-level models'),
    "missing record": (modify(loads__ground_motion=[{"file": "records/missing.AT2", "direction": "ux"}]),
                       'model.toml: loads.ground_motion[0].file = "records/missing.AT2": file not found (looked for '),
    "missing table": (modify(loads__nodal=[{"node": 2, "uy": 1.0, "time_function": {"type": "table",
                                                                                    "file": "f.csv"}}]),
                      'model.toml: loads.nodal[0].time_function.file = "f.csv": file not found'),
    "text record units": (modify(loads__ground_motion=[{"file": "model.toml", "direction": "ux"}]),
                          "model.toml: loads.ground_motion[0].units: missing key (a plain-text record needs the "
                          'units of its values, e.g. units = "g" or "cm/s2")'),
    "dt of an AT2 record": (modify(loads__ground_motion=[{"file": "x.AT2", "direction": "ux", "dt": 0.01}]),
                            "model.toml: loads.ground_motion[0].dt = 0.01: only for plain-text records"),
    "missing direction": (modify(loads__ground_motion=[{"file": "model.toml", "units": "g"}]),
                          'model.toml: loads.ground_motion[0].direction: missing key (a frame needs direction = '
                          '"ux" or "uy")'),
    "missing nodes": (modify(nodes=None, elements=None, unilateral=None, masses=None, supports=None, loads=None),
                      "model.toml: nodes: missing section (declare e.g. [[nodes]] id = 1, x = 0.0, y = 0.0; "
                      "or give [matrices])"),
    "frame and matrices": (modify(matrices={"M": "model.toml", "K": "model.toml", "F": "model.toml",
                                            "H": "model.toml"}),
                           "model.toml: nodes: not allowed with [matrices] (a matrix-level model has no frame)"),
    # errors of the Frame2D builder and of the loads, with the key path of the entry
    "zero-length element": (modify(nodes__1__x=0.0),
                            "model.toml: elements[0]: beam 'b1': nodes i=1 and j=2 are both at (0, 0): "
                            "zero-length element"),
    "supported slave": (modify(rigid_links=[{"master": 2, "slave": 1}]),
                        "model.toml: rigid_links[0]: rigid_link(2, 1): slave node 1 is supported (ux)"),
    "mechanism": (lambda d: d | {"nodes": d["nodes"] + [{"id": 13, "x": 20.0, "y": 0.0}]},
                  "model.toml: structure: no element gives stiffness to DOF(s) 13.ux, 13.uy"),
    "load on a support": (modify(loads__nodal=[{"node": 1, "ux": 1.0}]),
                          "model.toml: loads.nodal[0]: nodal_load at node 1: ux=1.0 acts on a DOF that cannot move"),
}


@pytest.mark.parametrize("change, message", ERRORS.values(), ids=ERRORS.keys())
def test_error_message(tmp_path, change, message):
    raises(tmp_path, change(beam_on_soil()), message)


def test_several_problems_are_reported_together(tmp_path):
    document = modify(elements__3__node_j=17, unilateral__4__node=0, elements__5__E=-1.0)(beam_on_soil())
    with pytest.raises(ModelFileError) as info:
        load_model_file(write(tmp_path, document))
    assert info.value.problems == ["elements[5].E = -1.0: must be > 0"]
    document["elements"][5]["E"] = 1.0
    with pytest.raises(ModelFileError) as info:
        load_model_file(write(tmp_path, document))
    assert info.value.problems == ["elements[3].node_j = 17: no node 17 (nodes are 1..12)",
                                   "unilateral[4].node = 0: no node 0 (nodes are 1..12)"]
    assert str(info.value).splitlines()[1].endswith("model.toml: unilateral[4].node = 0: no node 0 (nodes are 1..12)")
    assert isinstance(info.value, ValueError)


def test_string_node_ids_are_suggested(tmp_path):
    document = beam_on_soil(3)
    for node in document["nodes"]:
        node["id"] = {1: "left", 2: "middle", 3: "right"}[node["id"]]
    document = modify(supports__0__node="left", elements__0__node_i="left", elements__0__node_j="middle",
                      elements__1__node_i="midle", elements__1__node_j="right", unilateral=[], masses=[],
                      loads=None)(document)
    raises(tmp_path, document, 'elements[1].node_i = "midle": no node "midle" (nodes are "left", "middle", '
                               '"right"); did you mean "middle"?')


def test_toml_syntax_error_gives_the_line(tmp_path):
    text = 'units = { length = "m", force = "kN", time = "s" }\n[analysis]\ndt = = 0.1\n'
    raises(tmp_path, text, "model.toml: line 3, column 6: invalid TOML: Invalid value")


def test_key_after_a_table_header_is_explained(tmp_path):
    text = '[units]\nlength = "m"\nforce = "kN"\ntime = "s"\nnodes = [{id = 1, x = 0.0, y = 0.0}]\n'
    raises(tmp_path, text, "model.toml: units.nodes: unknown key (nodes is a top-level section, but in TOML a key "
                           "after a table header belongs to that table (units)")


def test_missing_model_file(tmp_path):
    with pytest.raises(ModelFileError, match=re.escape("nowhere.toml: file not found")):
        load_model_file(tmp_path / "nowhere.toml")


def test_compact_ids():
    assert compact_ids([3, 1, 2, 5, 7, 8, 9, "top"]) == '1..3, 5, 7..9, "top"'
    assert compact_ids([1, 2]) == "1, 2"
    assert compact_ids([]) == "none"


# ---------------------------------------------------------------------- matrix-level models
def write_matrices(folder: Path, model: ul.Model) -> None:
    for key in MATRIX_KEYS:
        scipy.io.mmwrite(folder / f"{key}.mtx", getattr(model, key))
    (folder / "dofs.txt").write_text("# DOF names\n" + "\n".join(model.dof_names) + "\n")


def matrix_document(**extra) -> dict:
    return {"units": {"length": "m", "force": "kN", "time": "s"},
            "matrices": {key: f"{key}.mtx" for key in MATRIX_KEYS} | {"dofs": "dofs.txt"} | extra,
            "loads": {"nodal": [{"dof": "1.uy", "value": -400.0},
                                {"dof": 0, "value": 200.0,
                                 "time_function": {"type": "rectangular", "t_end": 0.1}}]},
            "analysis": {"dt": 1e-3, "t_end": 0.02}}


def test_matrix_market_round_trip(tmp_path):
    structure, load, _ = liolios1990()
    reference = structure.to_model()
    write_matrices(tmp_path, reference)
    spec = load_model_file(write(tmp_path, matrix_document(constraints=["soil3", "soil2", "soil4"])))
    assert spec.structure is None and spec.figure is None
    for key in MATRIX_KEYS:
        np.testing.assert_array_equal(dense(getattr(spec.model, key)), dense(getattr(reference, key)), err_msg=key)
    assert spec.model.dof_names == reference.dof_names
    assert spec.model.constraint_names == ["soil3", "soil2", "soil4"]
    for t in (0.0, 0.05, 0.1, 0.2):
        np.testing.assert_array_equal(spec.load(t), load(t))
    sol = ul.solve(spec.model, spec.load, dt=1e-3, t_end=0.02)
    np.testing.assert_allclose(sol.u, ul.solve(reference, load, dt=1e-3, t_end=0.02).u, rtol=1e-12, atol=1e-15)


def test_matrix_model_errors(tmp_path):
    write_matrices(tmp_path, liolios1990()[0].to_model())
    document = matrix_document()
    document["loads"]["nodal"][0]["dof"] = "1.uz"
    raises(tmp_path, document, 'model.toml: loads.nodal[0].dof = "1.uz": no DOF "1.uz" (DOFs are 1.ux, 1.uy, 1.rz, '
                               '2.uy, 2.rz); did you mean "1.uy"?')
    document["loads"]["nodal"][0]["dof"] = 5
    raises(tmp_path, document, "model.toml: loads.nodal[0].dof = 5: no DOF 5 (indices are 0..4)")
    document = matrix_document(M="K.mtx", H="missing.mtx")
    raises(tmp_path, document, 'model.toml: matrices.H = "missing.mtx": file not found')
    (tmp_path / "bad.mtx").write_text("not a matrix\n")
    raises(tmp_path, matrix_document(C="bad.mtx"), 'model.toml: matrices.C = "bad.mtx": not a readable Matrix Market')
    scipy.io.mmwrite(tmp_path / "M3.mtx", np.eye(3))
    raises(tmp_path, matrix_document(M="M3.mtx"), "model.toml: matrices: M has shape (3, 3), expected (5, 5)")
    document = matrix_document()
    document["loads"]["gravity"] = {"g": 10.0}
    raises(tmp_path, document, "model.toml: loads.gravity: needs a frame")


def test_matrix_model_ground_motion_uses_the_influence_vector(tmp_path):
    model = liolios1990()[0].to_model()
    write_matrices(tmp_path, model)
    r = np.array([1.0, 0.0, 0.0, 0.0, 0.0])
    scipy.io.mmwrite(tmp_path / "r.mtx", r[:, None])
    shutil.copy(DATA / "records" / "standard.AT2", tmp_path)
    document = matrix_document()
    document["loads"] = {"ground_motion": [{"file": "standard.AT2", "influence": "r.mtx"}]}
    spec = load_model_file(write(tmp_path, document))
    record = read_at2(tmp_path / "standard.AT2")
    np.testing.assert_allclose(spec.load(0.07), -(model.M @ r) * record(0.07), rtol=1e-14)


# ---------------------------------------------------------------------- loads
def column_in(tmp_path, units, masses, E, I, y, x3):
    """tests/data/modelfiles/column.toml in other units (geometry, masses, E and I converted)."""
    text = (DATA / "modelfiles" / "column.toml").read_text()
    text = text.replace('units = { length = "m", force = "kN", time = "s" }', units)
    text = text.replace("y = 3.0", f"y = {y[0]!r}").replace("y = 4.0", f"y = {y[1]!r}")
    text = text.replace("x = 2.0", f"x = {x3!r}").replace("E = 30e6", f"E = {E!r}").replace("I = 2e-3", f"I = {I!r}")
    text = text.replace("m = 40.0", f"m = {masses[0]!r}").replace("m = 10.0, J = 1.0", f"m = {masses[1]!r}, J = 0.0")
    text = text.replace('"../records/standard.AT2"', json.dumps(str(DATA / "records" / "standard.AT2")))
    return load_model_file(write(tmp_path, text))


def test_ground_motion_is_minus_M_r_ag_through_rigid_links():
    spec = load_model_file(DATA / "modelfiles" / "column.toml")
    assert spec.model.dof_names == ["2.ux", "2.uy", "2.rz"]
    record = read_at2(DATA / "records" / "standard.AT2")            # in g, converted to m/s^2
    for t in (0.0, 0.03, 0.045, 0.11, 0.2):
        a = 2.0 * record(t)                                          # scale = 2
        # the offset mass (10 at dx = 2, dy = 1 from node 2) translates with node 2: a moment dy m a
        np.testing.assert_allclose(spec.load(t), [-(40.0 + 10.0) * a, 0.0, 1.0 * 10.0 * a], rtol=1e-13, atol=1e-12)
    assert record(0.02) == pytest.approx(0.003456789 * STANDARD_GRAVITY)


def test_text_record(tmp_path):
    document = modify(loads__ground_motion=[{"file": str(DATA / "records" / "one_column.txt"), "direction": "uy",
                                             "units": "cm/s2", "dt": 0.02}])(beam_on_soil(3))
    spec = load_model_file(write(tmp_path, document))
    record = read_text_record(DATA / "records" / "one_column.txt", units="cm/s2", dt=0.02)
    uy = np.array([name.endswith(".uy") for name in spec.model.dof_names], dtype=float)
    for t in (0.01, 0.03):
        np.testing.assert_allclose(spec.load(t) - spec.load.constant, -(spec.model.M @ uy) * record(t), rtol=1e-12)


@pytest.mark.parametrize("units, length, force, seconds", [
    ('{ length = "m", force = "kN", time = "s" }', "m", "kN", 1.0),
    ('{ length = "mm", force = "N", time = "s" }', "mm", "N", 1.0),
    ('{ length = "m", force = "kN", time = "ms" }', "m", "kN", 1e-3),
])
def test_ground_motion_unit_conversion(tmp_path, units, length, force, seconds):
    # the same column in other units: masses (force time^2/length), E (force/length^2), I (length^4)
    L, F = length_factor(length), force_factor(force)
    mass = F * seconds ** 2 / L                          # one model mass unit in kg
    spec = column_in(tmp_path, f"units = {units}", masses=(40e3 / mass, 10e3 / mass), E=30e9 / (F / L ** 2),
                     I=2e-3 / L ** 4, y=(3.0 / L, 4.0 / L), x3=2.0 / L)
    record = read_at2(DATA / "records" / "standard.AT2")
    t_model = np.array([0.03, 0.045]) / seconds
    expected_N = -(40e3 + 10e3) * 2.0 * record(t_model * seconds)    # inertia force in N
    ux = spec.model.dof_names.index("2.ux")
    forces = np.array([spec.load(tk)[ux] for tk in t_model])
    np.testing.assert_allclose(forces * F, expected_N, rtol=1e-12)


def test_standard_gravity_is_converted(tmp_path):
    document = modify(units__length="mm", units__force="N", loads__gravity__g="standard")(beam_on_soil(3))
    spec = load_model_file(write(tmp_path, document))
    mass = spec.structure.M.diagonal()
    uy = [k for k, name in enumerate(spec.model.dof_names) if name.endswith(".uy")]
    np.testing.assert_allclose(spec.load(0.0)[uy], -mass[uy] * STANDARD_GRAVITY * 1e3, rtol=1e-14)
    assert spec.units["mass"] == "N s^2/mm"


TIME_FUNCTIONS = [
    ({"type": "constant"}, [0.0, 1.0, 5.0], [1.0, 1.0, 1.0]),
    ({"type": "ramp", "t_ramp": 0.2}, [0.0, 0.1, 0.5], [0.0, 0.5, 1.0]),
    ({"type": "rectangular", "t_start": 0.1, "t_end": 0.3}, [0.1, 0.2, 0.3, 0.30001], [0.0, 1.0, 1.0, 0.0]),
    ({"type": "half_sine", "duration": 0.2, "t_start": 0.1}, [0.1, 0.2, 0.25, 0.3], [0.0, 1.0, np.sqrt(0.5), 0.0]),
    ({"type": "triangular", "t_peak": 0.1, "t_end": 0.3}, [0.0, 0.05, 0.1, 0.2, 0.3], [0.0, 0.5, 1.0, 0.5, 0.0]),
    ({"type": "table", "file": "load_factors.csv"}, [0.05, 0.2, 0.35, 0.5], [0.5, 1.0, 0.25, 0.0]),
    ({"type": "table", "file": "load_factors.csv", "outside": "hold"}, [0.5], [-0.5]),
]


@pytest.mark.parametrize("function, t, values", TIME_FUNCTIONS, ids=[f["type"] for f, _, _ in TIME_FUNCTIONS])
def test_time_functions(tmp_path, function, t, values):
    shutil.copy(DATA / "modelfiles" / "load_factors.csv", tmp_path)
    document = modify(loads__nodal=[{"node": 3, "uy": -2.0, "time_function": function}])(beam_on_soil(3))
    spec = load_model_file(write(tmp_path, document))
    uy3 = spec.model.dof_names.index("3.uy")
    gravity = spec.load.constant[uy3]
    np.testing.assert_allclose([spec.load(tk)[uy3] - gravity for tk in t], -2.0 * np.array(values), atol=1e-12)


def test_rectangular_pulse_end_is_kept_despite_round_off(tmp_path):
    document = modify(loads__nodal=[{"node": 3, "uy": -1.0, "time_function": {"type": "rectangular",
                                                                               "t_end": 0.3}}])(beam_on_soil(3))
    spec = load_model_file(write(tmp_path, document))
    assert 3 * 0.1 > 0.3
    q = spec.load(3 * 0.1) - spec.load.constant
    assert q[spec.model.dof_names.index("3.uy")] == -1.0


# ---------------------------------------------------------------------- schema
def test_json_schema_file_is_up_to_date():
    on_disk = json.loads((ROOT / "docs" / "model-file.schema.json").read_text())
    assert on_disk == model_file_schema(), (
        "docs/model-file.schema.json is out of date; regenerate it with "
        "python -c \"from unilateral.modelfile import write_schema; write_schema('docs/model-file.schema.json')\"")


def test_unit_names_are_those_of_the_unit_factors():
    for unit in LENGTH_UNITS:
        length_factor(unit)
    for unit in FORCE_UNITS:
        force_factor(unit)
