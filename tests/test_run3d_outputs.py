"""The outputs of a 3-D run (``[frame] dimensions = 3``) that 2-D runs had alone: accelerations, element
end forces, the energy balance, the response spectra and the model figure.

Each is checked by a defining property on a small frame that is 3-D in earnest (four columns on
tensionless soil, beams around the top, shaken along x and y):

* the accelerations of ``results.nc`` are the rule's (BDF2: ``a_n = (3 v_n - 4 v_{n-1} + v_{n-2}) / (2 dt)``)
  and satisfy the equations of motion ``M u'' + C u' + G sigma(u, v, u', v') = q`` at every step;
* the end forces, carried back to the global axes (with the local axes of
  :func:`unilateral.structure.elements3d.local_axes`), add up at every node to the load minus the
  inertia and the damping forces (free DOFs) and to the support reactions (supported DOFs);
* with the trapezoidal rule the energy balance closes to round-off;
* a floor spectrum is the spectrum of the node's absolute acceleration in ``results.nc``;

and, for the portal of ``tests/test_modelfile3d.py`` in the x-z plane, each output equals the 2-D
file's (2-D ``uy`` is 3-D ``uz``, 2-D ``rz`` is 3-D ``-ry``).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from test_modelfile3d import RECORD, portal_2d, portal_3d, write

from unilateral.analysis.outputs import NOT_IN_3D
from unilateral.io import load_netcdf
from unilateral.modelfile import load_model_file
from unilateral.structure import elements3d as el3

A0 = 0.3
PLAN = {1: (0.0, 0.0), 2: (5.0, 0.0), 3: (5.0, 4.0), 4: (0.0, 4.0)}
MASS = {1: 6.0, 2: 4.0, 3: 9.0, 4: 5.0}
SECTION = {"E": 3e7, "A": 0.09, "Iy": 6.75e-4, "Iz": 9e-4, "G": 1.25e7, "J": 1e-3}


def table(rule="bdf2", kelvin=50.0) -> dict:
    """Four columns (3 m) on tensionless soil (Kelvin ``kelvin``) under their bases, held in plan and
    against rotation (free to lift); beams around the top; unequal masses with rotary inertias; a diagonal spring
    to the ground at a corner; gravity, a push along x and y at a corner and a ground motion along x
    and y."""
    nodes, supports, elements, soil, masses = [], [], [], [], []
    for k, (x, y) in PLAN.items():
        nodes += [{"id": k, "x": x, "y": y, "z": 0.0}, {"id": 10 + k, "x": x, "y": y, "z": 3.0}]
        supports.append({"node": k, "uz": False, "rx": True, "ry": True, "rz": True})
        elements.append({"type": "beam", "name": f"c{k}", "node_i": k, "node_j": 10 + k, **SECTION})
        soil.append({"type": "soil", "name": f"s{k}", "node": k, "k": 2e4, "c": kelvin})
        masses.append({"node": 10 + k, "m": MASS[k], "Jx": 2.0, "Jy": 3.0, "Jz": 4.0})
    for i, j in ((1, 2), (2, 3), (3, 4), (4, 1)):
        elements.append({"type": "beam", "name": f"g{i}{j}", "node_i": 10 + i, "node_j": 10 + j, **SECTION})
    elements.append({"type": "spring", "name": "hold", "node_i": 13, "k": 5e2, "direction": [1.0, 1.0, 0.0]})
    return {
        "units": {"length": "m", "force": "kN", "time": "s"},
        "frame": {"dimensions": 3},
        "nodes": nodes, "supports": supports, "elements": elements, "unilateral": soil, "masses": masses,
        "damping": {"rayleigh": {"a0": A0}},
        "loads": {"gravity": {"g": 9.81},
                  "nodal": [{"node": 13, "ux": 150.0, "uy": 100.0,
                             "time_function": {"type": "half_sine", "duration": 0.15}}],
                  "ground_motion": [{"file": str(RECORD), "direction": "ux", "scale": 0.6},
                                    {"file": str(RECORD), "direction": "uy", "scale": 0.4}]},
        "analysis": {"dt": 0.002, "t_end": 0.4, "method": "cq", "rule": rule},
        "output": {"figure": {"node": 13, "dof": "ux"}},
    }


def _run(folder: Path, document: dict, name: str, *, nodes=None, figures=()):
    """Run a model file as ``unilateral run`` does; with ``nodes`` its ``[output] floor_spectra``."""
    from unilateral.analysis.run import analyse, case_labels, settings_of, spectra_settings, structure_kinds

    if nodes is not None:
        document = {**document, "output": {**document.get("output", {}), "floor_spectra": list(nodes)}}
    path = write(folder, document, f"{name}.toml")
    spec = load_model_file(path)
    spectra = spectra_settings(spec)
    result = analyse(spec.model, spec.load, settings_of(spec.analysis), folder / name, structure=spec.structure,
                     units=spec.units, figure=spec.figure, title=name, meta={"model_file": str(path)},
                     cases=("unilateral", "bilateral"), labels=case_labels(structure_kinds(spec.structure)),
                     formats=figures, spectra=spectra, model_figure=True)
    assert result["success_all"]
    return spec, load_netcdf(folder / name / "results.nc"), result


@pytest.fixture(scope="module")
def table_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("table3d")
    return (folder / "table", *_run(folder, table(), "table", nodes=(13, 1), figures=("png",)))


@pytest.fixture(scope="module")
def portals(tmp_path_factory):
    """The 2-D portal (floor spectra of nodes 2 and 1) and the 3-D portal in the x-z plane."""
    folder = tmp_path_factory.mktemp("portals")
    two = portal_2d()
    two["output"]["floor_spectra"] = [2, 1]
    return _run(folder, two, "portal_2d")[1], _run(folder, portal_3d(), "portal_3d", nodes=(2, 1))[1]


def _load(spec, t) -> np.ndarray:
    """The load (N+1, n) the run used: the hat averages of the LoadHistory (row 0 one-sided at 0+)."""
    return spec.load.grid_samples(float(t[1] - t[0]), len(t) - 1)[0]


def _sigma(spec, ds, case="unilateral"):
    """The natural stresses (N+1, ne) of ``case`` from ``results.nc`` (``v'`` of the BDF2 rule)."""
    from unilateral.rules import get_rule
    from unilateral.structure.forces import rates

    st = spec.structure
    t = ds["time"].values
    u, ud, v = (ds[name].sel(case=case).values for name in ("u", "udot", "v"))
    vdot, _ = rates(v, get_rule("bdf2"), float(t[1] - t[0]))
    return st.natural.stresses(t, u, v, ud, vdot)


# ---------------------------------------------------------------------- accelerations
def test_the_accelerations_are_the_rules_and_satisfy_the_equations_of_motion(table_run):
    _, spec, ds, _ = table_run
    st = spec.structure
    assert ds["v"].sel(case="unilateral").values.max() > 1e-4          # the feet lift off
    assert ds["acceleration"].dims == ("case", "time", "dof") and ds["acceleration"].attrs["units"] == "m/s^2"
    assert ds.sizes["dof"] == st.n
    t = ds["time"].values
    dt = float(t[1] - t[0])
    q = _load(spec, t)
    worst = {}
    for case in ("unilateral", "bilateral"):
        a, ud, u = (ds[name].sel(case=case).values for name in ("acceleration", "udot", "u"))
        assert np.abs(a).max() > 1.0
        bdf2 = (3 * ud[2:] - 4 * ud[1:-1] + ud[:-2]) / (2 * dt)
        np.testing.assert_allclose(a[2:], bdf2, rtol=0, atol=1e-9 * np.abs(a).max())
        residual = st.M @ a.T + st.C @ ud.T + st.natural.G @ _sigma(spec, ds, case).T - q.T     # (n, N+1)
        worst[case] = np.abs(residual).max() / np.abs(q).max()
    assert max(worst.values()) < 1e-9, worst
    # absolute = relative + the ground's acceleration along each DOF's direction
    a_g = ds["ground_acceleration"].sel(case="unilateral").values
    assert list(ds["excitation"].values) == ["0:ux", "1:uy"] and np.abs(a_g).max() > 0.1
    r = np.column_stack([st.influence("ux"), st.influence("uy")])
    np.testing.assert_allclose(ds["absolute_acceleration"].sel(case="unilateral").values,
                               ds["acceleration"].sel(case="unilateral").values + a_g @ r.T, rtol=0, atol=1e-12)
    # every node's six DOFs: a free DOF's is its acceleration; a node held in plan moves with the ground
    nodal = ds["node_absolute_acceleration"].sel(case="unilateral")
    assert nodal.dims == ("time", "node", "component") and ds.sizes["node"] == 8
    dofs = list(ds["dof"].values)
    absolute = ds["absolute_acceleration"].sel(case="unilateral").values
    for dof in ("ux", "uy", "uz", "rx", "ry", "rz"):
        np.testing.assert_array_equal(nodal.sel(node="13", component=dof).values, absolute[:, dofs.index(f"13.{dof}")])
    np.testing.assert_allclose(nodal.sel(node="1", component="ux").values, a_g[:, 0], rtol=0, atol=0)
    np.testing.assert_allclose(nodal.sel(node="1", component="uy").values, a_g[:, 1], rtol=0, atol=0)
    np.testing.assert_array_equal(ds["node_acceleration"].sel(case="unilateral", node="1", component="uz").values,
                                  ds["acceleration"].sel(case="unilateral").values[:, dofs.index("1.uz")])
    assert np.abs(ds["node_acceleration"].sel(node="1", component="ux").values).max() == 0.0


# ---------------------------------------------------------------------- element end forces
def _global_ends(spec, ds, case="unilateral") -> np.ndarray:
    """The end forces of ``results.nc`` carried back to the global axes and added up per node:
    (N+1, 6 n_nodes), the forces the nodes exert on the elements."""
    st = spec.structure
    end = ds["end_force"].sel(case=case).values                   # (N+1, element, 12)
    out = np.zeros((end.shape[0], st.dofs.T.shape[0]))
    for k, name in enumerate(ds["element"].values):
        e = next(e for e in st.elements if e.name == str(name))
        nodes = list(dict.fromkeys(node for node, _ in e.dofs))
        if e.kind == "beam3d":
            _, R = el3.local_axes("", nodes[0], st.coords[nodes[0]], nodes[1], st.coords[nodes[1]])
            for node, first in zip(nodes, (0, 6)):
                row = st.dofs.full_index(node, "ux")
                out[:, row:row + 3] += end[:, k, first:first + 3] @ R
                out[:, row + 3:row + 6] += end[:, k, first + 3:first + 6] @ R
        else:                                                   # along d, from the ground to its node
            row = dict(zip((dof for _, dof in e.dofs), e.a[0]))
            d = np.array([row.get(dof, 0.0) for dof in ("ux", "uy", "uz")])
            row = st.dofs.full_index(nodes[0], "ux")
            out[:, row:row + 3] += np.outer(end[:, k, 6], d)
            assert np.abs(end[:, k, 6] + end[:, k, 0]).max() == 0.0
    return out


def test_the_end_forces_balance_the_loads_inertia_damping_and_reactions_at_every_node(table_run):
    _, spec, ds, _ = table_run
    st = spec.structure
    assert ds["end_force"].dims == ("case", "time", "element", "end_component")
    assert list(ds["end_component"].values) == ["N_i", "Vy_i", "Vz_i", "T_i", "My_i", "Mz_i",
                                                "N_j", "Vy_j", "Vz_j", "T_j", "My_j", "Mz_j"]
    assert ds["end_force"].attrs["units"] == "kN (N, V); kN m (T, M)"
    q = _load(spec, ds["time"].values)
    for case in ("unilateral", "bilateral"):
        nodal = _global_ends(spec, ds, case)
        a, ud = (ds[name].sel(case=case).values for name in ("acceleration", "udot"))
        free = np.asarray(st.dofs.T.T @ nodal.T)                            # (n, N+1)
        expected = q.T - st.M @ a.T - st.C @ ud.T
        scale = np.abs(expected).max()
        np.testing.assert_allclose(free, expected, rtol=0, atol=1e-9 * scale, err_msg=case)
        for k, label in enumerate(ds["support"].values):
            node, dof = str(label).split(".")
            np.testing.assert_allclose(nodal[:, st.dofs.full_index(int(node), dof)],
                                       ds["support_reaction"].sel(case=case).values[:, k], rtol=0,
                                       atol=1e-9 * scale, err_msg=f"{case} {label}")
    # a beam's natural stresses: the axial force, the torque and the end moments; its shears from them
    end = ds["end_force"].sel(case="unilateral", element="c3").values
    first = 0
    for e in st.elements:
        if e.name == "c3":
            break
        first += e.a.shape[0]
    sigma = _sigma(spec, ds)[:, first:first + 6]
    np.testing.assert_allclose(end[:, [6, 9, 5, 11, 4, 10]], sigma, rtol=0, atol=1e-9 * np.abs(sigma).max())
    np.testing.assert_allclose(end[:, 7], -(end[:, 5] + end[:, 11]) / 3.0, rtol=0, atol=1e-9 * np.abs(sigma).max())
    np.testing.assert_allclose(end[:, 8], (end[:, 4] + end[:, 10]) / 3.0, rtol=0, atol=1e-9 * np.abs(sigma).max())
    assert np.abs(end[:, [1, 2, 3, 4, 5]]).max(axis=0).min() > 1e-3       # out of plane: every component acts
    # axial_force is N_j; the soil's force is its compression (negative)
    np.testing.assert_array_equal(ds["axial_force"].sel(case="unilateral", element="c3").values, end[:, 6])
    assert ds["axial_force"].sel(case="unilateral", element="s3").values.max() <= 1e-9


def test_the_element_forces_csv_of_a_3d_run(table_run):
    out, _, ds, result = table_run
    header, *rows = (out / "element_forces.csv").read_text().splitlines()
    names = header.split(",")
    assert names[:13] == ["time [s]"] + [f"c1:{c} [{'kN m' if c[0] in 'TM' else 'kN'}]"
                                         for c in ds["end_component"].values]
    assert len(names) == 1 + 12 * ds.sizes["element"] and len(rows) == ds.sizes["time"]
    column = names.index("g23:My_j [kN m]")
    values = np.array([float(row.split(",")[column]) for row in rows])
    np.testing.assert_allclose(values, ds["end_force"].sel(case="unilateral", element="g23", end_component="My_j"),
                               rtol=1e-12, atol=1e-12)
    assert (out / "bilateral_element_forces.csv").exists()
    peaks = result["results"]["unilateral"]["end_forces"]["c1"]
    assert set(peaks) == set(ds["end_component"].values)


# ---------------------------------------------------------------------- energy
def test_the_trapezoidal_rule_closes_the_energy_balance_of_a_3d_frame(tmp_path):
    _, ds, result = _run(tmp_path, table(rule="trapezoidal"), "trapezoidal")
    error = result["results"]["unilateral"]["energy"]["max_relative_error"]
    assert error < 1e-9, error
    assert ds["energy_relative_error"].values.max() < 1e-9
    unilateral = ds.sel(case="unilateral")
    assert unilateral["energy_contact_dissipated"].values[-1] > 0.0
    assert unilateral["energy_damping_dissipated"].values[-1] > 0.0
    assert float(unilateral["energy_input_work"].values[-1]) == pytest.approx(
        result["results"]["unilateral"]["energy"]["input_work"])
    header = (tmp_path / "trapezoidal" / "base.csv").read_text().splitlines()[0]
    assert "energy_kinetic [kN m]" in header and "energy_relative_error [1]" in header


def test_energy_accelerations_and_end_forces_of_the_3d_portal_are_the_2d_ones(portals):
    two, three = portals
    for key in [name for name in two.data_vars if str(name).startswith("energy_")]:
        scale = max(np.abs(two[key].values).max(), 1e-300)
        np.testing.assert_allclose(three[key].values, two[key].values, rtol=0, atol=1e-9 * scale, err_msg=key)
    assert two["energy_input_work"].values.max() > 1.0
    # the accelerations: 2-D (node.ux, node.uy, node.rz) are 3-D (node.ux, node.uz, -node.ry)
    dofs3 = list(three["dof"].values)
    for k, name in enumerate(two["dof"].values):
        node, dof = str(name).split(".")
        dof3, sign = {"ux": ("ux", 1.0), "uy": ("uz", 1.0), "rz": ("ry", -1.0)}[dof]
        for key in ("acceleration", "absolute_acceleration"):
            a2 = two[key].values[..., k]
            a3 = sign * three[key].values[..., dofs3.index(f"{node}.{dof3}")]
            np.testing.assert_allclose(a3, a2, rtol=0, atol=1e-8 * np.abs(two[key].values).max(), err_msg=name)
    # the end forces: N and, in the plane, V and M
    coords = {1: (0.0, 0.0), 2: (0.0, 3.0), 3: (4.0, 3.0), 4: (4.0, 0.0)}
    ends = {"c1": (1, 2), "g": (2, 3), "c2": (4, 3)}
    scale = np.abs(two["end_force"].values).max()
    for name, (i, j) in ends.items():
        e2 = two["end_force"].sel(element=name).values                  # (case, time, 6)
        e3 = three["end_force"].sel(element=name).values                # (case, time, 12)
        _, R = el3.local_axes("", i, (*coords[i][:1], 0.0, coords[i][1]), j, (*coords[j][:1], 0.0, coords[j][1]))
        c = np.subtract(coords[j], coords[i]) / np.hypot(*np.subtract(coords[j], coords[i]))
        normal = np.array([-c[1], 0.0, c[0]])                           # the 2-D local y in the x-z plane
        for end2, end3 in ((0, 0), (3, 6)):
            f = e3[..., end3:end3 + 3] @ R                              # global force
            m = e3[..., end3 + 3:end3 + 6] @ R                          # global moment
            np.testing.assert_allclose(e3[..., end3], e2[..., end2], rtol=0, atol=1e-8 * scale)
            np.testing.assert_allclose(f @ normal, e2[..., end2 + 1], rtol=0, atol=1e-8 * scale)
            np.testing.assert_allclose(-m[..., 1], e2[..., end2 + 2], rtol=0, atol=1e-8 * scale)
    np.testing.assert_allclose(three["axial_force"].sel(element="s1").values,
                               two["axial_force"].sel(element="s1").values, rtol=0, atol=1e-8 * scale)


# ---------------------------------------------------------------------- spectra
def test_the_floor_spectra_of_the_3d_portal_are_the_2d_ones(portals):
    two, three = portals
    np.testing.assert_allclose(three["ground_spectrum"].values, two["ground_spectrum"].values, rtol=1e-12)
    assert three["floor_spectrum"].dims == ("case", "period", "floor")
    assert list(three["floor"].values) == ["2", "1"]
    scale = two["floor_spectrum"].values.max()
    np.testing.assert_allclose(three["floor_spectrum"].values, two["floor_spectrum"].values, rtol=0,
                               atol=1e-8 * scale)
    assert "ground_spectrum_uy" not in three                        # a ground motion along x alone


def test_a_3d_run_writes_the_spectra_along_x_and_y(table_run):
    from unilateral.analysis.spectra import pseudo_acceleration

    out, spec, ds, result = table_run
    periods = ds["period"].values
    dt = float(ds["time"].values[1] - ds["time"].values[0])
    dofs = list(ds["dof"].values)
    for direction, suffix, k in (("ux", "", 0), ("uy", "_uy", 1)):
        assert ds[f"ground_spectrum{suffix}"].attrs["direction"] == direction
        a_g = ds["ground_acceleration"].sel(case="unilateral").values[:, k]
        np.testing.assert_allclose(ds[f"ground_spectrum{suffix}"].values, pseudo_acceleration(a_g, dt, periods),
                                   rtol=1e-12)
        for case in ("unilateral", "bilateral"):
            absolute = ds["absolute_acceleration"].sel(case=case).values[:, dofs.index(f"13.{direction}")]
            floors = ds[f"floor_spectrum{suffix}"].sel(case=case)
            np.testing.assert_allclose(floors.sel(floor="13").values, pseudo_acceleration(absolute, dt, periods),
                                       rtol=1e-12)
            # node 1 is held in plan: it moves with the ground
            np.testing.assert_allclose(floors.sel(floor="1").values, ds[f"ground_spectrum{suffix}"].values,
                                       rtol=1e-12)
    header = (out / "spectra.csv").read_text().splitlines()[0].split(",")
    assert header == ["period [s]", "Sa:ground:ux [m/s^2]", "Sa:unilateral:13:ux [m/s^2]", "Sa:unilateral:1:ux [m/s^2]",
                      "Sa:bilateral:13:ux [m/s^2]", "Sa:bilateral:1:ux [m/s^2]", "Sa:ground:uy [m/s^2]",
                      "Sa:unilateral:13:uy [m/s^2]", "Sa:unilateral:1:uy [m/s^2]", "Sa:bilateral:13:uy [m/s^2]",
                      "Sa:bilateral:1:uy [m/s^2]"]
    spectra = result["spectra"]
    assert spectra["direction"] == "ux" and set(spectra["by_direction"]) == {"ux", "uy"}
    assert spectra["by_direction"]["uy"]["floors"]["unilateral"]["13"]["Sa"] == pytest.approx(
        ds["floor_spectrum_uy"].sel(case="unilateral", floor="13").values.max())


# ---------------------------------------------------------------------- the model figure and the note
def test_a_3d_run_draws_its_model_and_says_what_it_does_not_write(table_run):
    out, _, _, result = table_run
    assert (out / "model.png").stat().st_size > 10_000
    assert str(out / "model.png") in result["figures"]
    manifest = json.loads((out / "manifest.json").read_text())["files"]
    assert {"model.png", "spectra.png", "energy.png", "element_forces.csv", "spectra.csv"} <= set(manifest)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["notes"] == [NOT_IN_3D]
    for written in ("accelerations", "element end forces", "energy balance", "spectra", "model.png"):
        assert written in NOT_IN_3D.partition("Not written")[0], written
    assert "absolute_acceleration" in summary["results"]["unilateral"]
    assert set(summary["results"]["unilateral"]["absolute_acceleration"]) >= {"13.ux", "13.uy", "13.uz"}


@pytest.mark.slow
def test_the_energy_balance_of_the_building_on_footings_closes_with_the_trapezoidal_rule(tmp_path):
    """examples/building3d.toml (four footings on a half-space, a rigid diaphragm per floor, ground motions
    along x and y): with the trapezoidal rule the balance, the soil's work included, closes to round-off."""
    from unilateral.analysis.run import run_model_file

    example = Path(__file__).resolve().parents[1] / "examples" / "building3d.toml"
    result = run_model_file(example, tmp_path / "building", figures=(), t_end=0.1, rule="trapezoidal")
    assert result["success_all"]
    for case in ("unilateral", "bilateral"):
        energy = result["results"][case]["energy"]
        assert energy["max_relative_error"] < 1e-9, (case, energy)
        assert energy["damping_dissipated"] > 0.0 and energy["kinetic_max"] > 0.0
    ds = load_netcdf(tmp_path / "building" / "results.nc")
    assert ds["end_force"].sizes["element"] == len(load_model_file(example).structure.elements)


def test_a_pair_of_records_rotated_in_plan_by_vector_directions(tmp_path):
    """``[[loads.ground_motion]] direction = [dx, dy, dz]``: the pair of records of :func:`table`
    rotated by 35 degrees in plan (``[cos a, sin a, 0]`` and ``[-sin a, cos a, 0]``). The model file's
    load equals ``Frame3D.ground_motion`` along those vectors; the run's absolute accelerations add
    the ground's acceleration along x and y from the samples the run used (hat averages), each record's share being
    the cosine of its direction with the axis."""
    from unilateral.loads import read_record

    a = np.radians(35.0)
    document = table()
    document["loads"] = dict(document["loads"], ground_motion=[
        {"file": str(RECORD), "direction": [float(np.cos(a)), float(np.sin(a)), 0.0], "scale": 0.6},
        {"file": str(RECORD), "direction": [float(-np.sin(a)), float(np.cos(a)), 0.0], "scale": 0.4}])
    spec, ds, result = _run(tmp_path, document, "rotated")
    st = spec.structure
    record = read_record(RECORD)
    api = [-(st.M @ st.influence((np.cos(a), np.sin(a), 0.0))), -(st.M @ st.influence((-np.sin(a), np.cos(a), 0.0)))]
    for (vector, f), expected, scale in zip(spec.load.terms[-2:], api, (0.6, 0.4)):
        np.testing.assert_allclose(vector, expected, rtol=1e-14, atol=1e-14 * np.abs(expected).max())
        np.testing.assert_allclose(f(record.time[:50]), scale * record.acceleration[:50], rtol=1e-14)
    t = ds["time"].values
    # the records as the run sampled them (hat-function averages over the steps), not their point values
    first, second = spec.load.grid_factors(float(t[1] - t[0]), len(t) - 1)[0][:, -2:].T
    assert np.abs(first - 0.6 * np.interp(t, record.time, record.acceleration)).max() > 1e-9 * np.abs(first).max()
    node = list(ds["node"].values).index("13")
    for component, expected in (("ux", np.cos(a) * first - np.sin(a) * second),
                                ("uy", np.sin(a) * first + np.cos(a) * second)):
        c = list(ds["component"].values).index(component)
        ground = (ds["node_absolute_acceleration"].sel(case="unilateral").values[:, node, c]
                  - ds["node_acceleration"].sel(case="unilateral").values[:, node, c])
        np.testing.assert_allclose(ground, expected, rtol=0, atol=1e-9 * np.abs(expected).max())
    assert set(result["spectra"]["by_direction"]) >= {"uy"} and "ground_spectrum_uy" in ds
