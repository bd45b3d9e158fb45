"""Model files of 3-D frames (``[frame] dimensions = 3``): read, checked, solved and written.

The strongest check: a portal frame in the x-z plane, held out of its plane, is the same problem as
the 2-D portal in x-y, so its model file must give the 2-D file's solution to round-off (2-D ``uy``
is 3-D ``uz``, 2-D ``rz`` is 3-D ``-ry``), and its base forces the 2-D base shear and vertical force.
"""

from __future__ import annotations

import copy
import json
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from unilateral.modelfile import ModelFileError, load_model_file

ROOT = Path(__file__).resolve().parents[1]
RECORD = ROOT / "examples" / "records" / "synthetic_0.35g.AT2"
HELD_OUT_OF_PLANE = {"uy": True, "rx": True, "rz": True}


def _inline(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_inline(x) for x in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_inline(x)}" for k, x in value.items()) + "}"
    return repr(value)


def write(tmp_path: Path, document: dict, name="model.toml") -> Path:
    path = tmp_path / name
    path.write_text("".join(f"{key} = {_inline(value)}\n" for key, value in document.items()))
    return path


def portal_2d() -> dict:
    """A portal frame (4 m x 3 m) on two tensionless soil elements, held horizontally at the feet,
    under gravity, a horizontal pulse at the top and a ground motion."""
    column, girder = {"E": 3e7, "A": 0.09, "I": 6.75e-4}, {"E": 3e7, "A": 0.12, "I": 1.6e-3}
    return {
        "units": {"length": "m", "force": "kN", "time": "s"},
        "nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 0.0, "y": 3.0}, {"id": 3, "x": 4.0, "y": 3.0},
                  {"id": 4, "x": 4.0, "y": 0.0}],
        "supports": [{"node": 1, "uy": False}, {"node": 4, "uy": False}],
        "elements": [{"type": "beam", "name": "c1", "node_i": 1, "node_j": 2, **column},
                     {"type": "beam", "name": "g", "node_i": 2, "node_j": 3, **girder},
                     {"type": "beam", "name": "c2", "node_i": 4, "node_j": 3, **column}],
        "unilateral": [{"type": "soil", "name": "s1", "node": 1, "k": 2e4, "c": 50.0},
                       {"type": "soil", "name": "s4", "node": 4, "k": 2e4, "c": 50.0}],
        "masses": [{"node": 2, "m": 10.0, "J": 1.0}, {"node": 3, "m": 10.0, "J": 1.0}],
        "damping": {"rayleigh": {"a0": 0.2}},
        "loads": {"gravity": {"g": 9.81},
                  "nodal": [{"node": 2, "ux": 150.0, "time_function": {"type": "half_sine", "duration": 0.2}}],
                  "ground_motion": [{"file": str(RECORD), "direction": "ux", "scale": 0.5}]},
        "analysis": {"dt": 0.002, "t_end": 0.6, "method": "cq"},
        "output": {"figure": {"node": 2, "dof": "ux"}},
    }


def portal_3d() -> dict:
    """:func:`portal_2d` in the x-z plane of a 3-D frame, every node held out of the plane."""
    d = copy.deepcopy(portal_2d())
    d["frame"] = {"dimensions": 3}
    d["nodes"] = [{"id": n["id"], "x": n["x"], "y": 0.0, "z": n["y"]} for n in d["nodes"]]
    d["supports"] = [{"node": 1, "uz": False, **HELD_OUT_OF_PLANE}, {"node": 4, "uz": False, **HELD_OUT_OF_PLANE},
                     {"node": 2, "ux": False, "uz": False, **HELD_OUT_OF_PLANE},
                     {"node": 3, "ux": False, "uz": False, **HELD_OUT_OF_PLANE}]
    for e in d["elements"]:
        inertia = e.pop("I")
        e.update(Iy=inertia, Iz=inertia, G=1.25e7, J=1e-3)
    d["masses"] = [{"node": m["node"], "m": m["m"], "Jy": m["J"]} for m in d["masses"]]
    d["output"]["figure"]["dof"] = "ux"
    return d


def _solve(spec):
    return ul.solve(spec.model, spec.load, dt=spec.analysis["dt"], t_end=spec.analysis["t_end"], method="cq")


def test_a_3d_portal_in_its_plane_is_the_2d_portal(tmp_path):
    two, three = (load_model_file(write(tmp_path, d(), f"{d.__name__}.toml")) for d in (portal_2d, portal_3d))
    assert three.structure.dofs.dof_names == ("ux", "uy", "uz", "rx", "ry", "rz")
    assert two.model.n == three.model.n == 10 and three.model.m == 2
    a, b = _solve(two), _solve(three)
    assert a.success and b.success
    for node in (1, 2, 3, 4):
        for dof2, dof3, sign in (("ux", "ux", 1.0), ("uy", "uz", 1.0), ("rz", "ry", -1.0)):
            x = two.structure.node_displacement(a, node, dof2)
            y = sign * three.structure.node_displacement(b, node, dof3)
            assert np.abs(x - y).max() <= 1e-9 * np.abs(a.u).max(), (node, dof2)
    assert np.abs(a.v).max() > 1e-2                                   # a foot lifts off by centimetres
    np.testing.assert_allclose(b.v, a.v, rtol=0, atol=1e-9 * np.abs(a.v).max())
    np.testing.assert_allclose(b.psi, a.psi, rtol=0, atol=1e-9 * np.abs(a.psi).max())


def test_p_delta_of_a_3d_portal_in_its_plane_is_that_of_the_2d_portal(tmp_path):
    with_p_delta = _change(analysis__p_delta=True)
    two, three = (load_model_file(write(tmp_path, with_p_delta(d()), f"{d.__name__}.toml"))
                  for d in (portal_2d, portal_3d))
    assert three.structure.axial_forces == pytest.approx(two.structure.axial_forces, rel=1e-12)
    without = load_model_file(write(tmp_path, portal_3d(), "linear.toml"))
    assert abs(three.model.K - without.model.K).sum() > 0
    a, b = _solve(two), _solve(three)
    assert a.success and b.success
    for node in (2, 3):
        x, y = two.structure.node_displacement(a, node, "ux"), three.structure.node_displacement(b, node, "ux")
        assert np.abs(x - y).max() <= 1e-9 * np.abs(a.u).max(), node
    np.testing.assert_allclose(b.psi, a.psi, rtol=0, atol=1e-9 * np.abs(a.psi).max())


def test_the_run_of_a_3d_portal_writes_the_2d_base_forces(tmp_path):
    """``unilateral.run``: the base shear and vertical force of the 2-D file are Fx and Fz of the 3-D
    file; nothing leaves the plane; the summary says what a 3-D run does not write."""
    from unilateral.io import load_netcdf

    runs = {}
    for make in (portal_2d, portal_3d):
        runs[make.__name__] = ul.run(write(tmp_path, make(), f"{make.__name__}.toml"), tmp_path / make.__name__,
                                     figures=())
        assert runs[make.__name__]["success_all"]
    two, three = (load_netcdf(tmp_path / name / "results.nc") for name in ("portal_2d", "portal_3d"))
    shear = two["base_shear"].values
    np.testing.assert_allclose(three["base_Fx"].values, shear, rtol=0, atol=1e-8 * np.abs(shear).max())
    vertical = two["base_vertical"].values
    np.testing.assert_allclose(three["base_Fz"].values, vertical, rtol=0, atol=1e-8 * np.abs(vertical).max())
    for key in ("Fy", "Mx", "Mz"):
        assert np.abs(three[f"base_{key}"].values).max() <= 1e-8 * np.abs(shear).max()
    assert np.abs(three["base_My"].values).max() > 100.0
    assert list(three["component"].values) == ["ux", "uy", "uz", "rx", "ry", "rz"]
    summary = json.loads((tmp_path / "portal_3d" / "summary.json").read_text())
    assert "element end forces" in summary["notes"][0]
    assert set(summary["results"]["unilateral"]["base_forces"]) == {"Fx", "Fy", "Fz", "Mx", "My", "Mz"}
    header = (tmp_path / "portal_3d" / "base.csv").read_text().splitlines()[0]
    assert header.startswith("time [s],base_Fx [kN],base_Fy [kN],base_Fz [kN],base_Mx [kN m],base_My [kN m],"
                             "base_Mz [kN m],reaction:1.ux [kN],")
    assert header.endswith(",drift_ratio_x:0-3 [1],drift_ratio_y:0-3 [1]") and "reaction:1.rx [kN m]" in header
    # the supports in the plane react as in 2-D (3-D uz is 2-D uy)
    for label2, label3 in (("1.ux", "1.ux"), ("4.ux", "4.ux")):
        if label2 in list(two["support"].values):
            np.testing.assert_allclose(three["support_reaction"].sel(support=label3).values,
                                       two["support_reaction"].sel(support=label2).values, rtol=0,
                                       atol=1e-8 * np.abs(shear).max())
    # the storey's drift along x at its two corners: the largest of the 2-D drifts of the two columns
    u = three["node_displacement"].sel(component="ux").values               # (case, time, node)
    nodes = list(three["node"].values)
    top = [nodes.index(n) for n in ("2", "3")]
    bottom = [nodes.index(n) for n in ("1", "4")]
    corners = np.abs(u[:, :, top] - u[:, :, bottom]).max(axis=2) / 3.0
    np.testing.assert_allclose(three["drift_ratio_x"].values[:, :, 0], corners, rtol=0, atol=1e-12)
    assert np.abs(three["drift_ratio_y"].values).max() <= 1e-12 and corners.max() > 1e-4
    assert "2.ry [rad]" in (tmp_path / "portal_3d" / "displacements.csv").read_text().splitlines()[0]


def _change(**changes):
    """A change of :func:`portal_3d`: ``section__index__key=value`` (None removes the key)."""
    def apply(d):
        for path, value in changes.items():
            *parents, last = [int(p) if p.isdigit() else p for p in path.split("__")]
            target = d
            for p in parents:
                target = target[p]
            if value is None:
                target.pop(last, None)
            else:
                target[last] = value
        return d
    return apply


#: ``(change of portal_3d, the message after "<file>: ")``.
WRONG_3D = {
    "2-D key": (_change(elements__0__I=1e-3),
                "elements[0].I = 0.001: a key of 2-D frames only (this file declares [frame] dimensions = 3; valid "
                "keys here: type, name, node_i, node_j, E, A, Iy, Iz, G, J, vecxz, axial_strain, rho)"),
    "missing 3-D key": (_change(elements__1__G=None),
                        "elements[1].G: missing key (required keys: type, name, node_i, node_j, E, A, Iy, Iz, G, J)"),
    "2-D mass": (_change(masses__0__J=1.0), "masses[0].J = 1.0: a key of 2-D frames only"),
    "hinge without Mz": (lambda d: d | {"unilateral": d["unilateral"] + [{"type": "hinge", "name": "h", "beam": "g",
                                                                           "end": "i", "My": 100.0}]},
                         "unilateral[2].Mz: missing key (required keys: type, name, beam, end, My, Mz)"),
    "2-D type": (lambda d: d | {"unilateral": d["unilateral"] + [{"type": "hing", "name": "h"}]},
                 'unilateral[2].type = "hing": unknown unilateral element type (valid: cable, gap, hinge, slider, '
                 "soil, yield)"),
    "p-delta without gravity": (_change(analysis__p_delta=True, loads__gravity=None),
                                "analysis.p_delta = true: needs [loads.gravity]"),
    "dimensions": (_change(frame__dimensions=4),
                   "frame.dimensions = 4: unknown number of dimensions (valid: 2, 3)"),
    "direction": (_change(loads__ground_motion__0__direction="rz"),
                  'loads.ground_motion[0].direction = "rz": unknown ground motion direction (valid: ux, uy, uz or a '
                  'vector [dx, dy, dz])'),
    "vector at depth": (lambda d: d | {"site": {"layers": [{"thickness": 5.0, "Vs": 150.0, "rho": 1.9}],
                                                "base": {"Vs": 400.0, "rho": 2.1}}}
                        | {"loads": d["loads"] | {"ground_motion": [{"file": str(RECORD), "direction": [1.0, 1.0, 0.0],
                                                                      "at": "outcrop"}]}},
                        'loads.ground_motion[0].direction = [1.0, 1.0, 0.0]: a vector with at = "outcrop"'),
    "2-D vector": (_change(unilateral__0__direction=[0.0, 1.0]),
                   "unilateral[0].direction = [0.0, 1.0]: expected a nonzero vector [dx, dy, dz] of three numbers"),
    "figure dof": (_change(output__figure__dof="rw"),
                   'output.figure.dof = "rw": unknown DOF (valid: ux, uy, uz, rx, ry, rz)'),
    "diaphragm node": (lambda d: d | {"rigid_diaphragms": [{"master": 2, "slaves": [3, 9]}]},
                       "rigid_diaphragms[0].slaves[1] = 9: no node 9 (nodes are 1..4)"),
    "diaphragm plane": (lambda d: d | {"rigid_diaphragms": [{"master": 2, "slaves": [1]}]},
                        "rigid_diaphragms[0]: rigid_diaphragm(2, ...): slaves[0]=1 is at z=0, not in the plane z=3"),
    "nothing held": (_change(supports__0={"node": 1, "ux": False, "uy": False, "uz": False}),
                     "supports[0]: ux, uy, uz, rx, ry and rz are all false: the support restrains nothing"),
    "spectra": (_change(output__floor_spectra=[9]), "output.floor_spectra[0] = 9: no node 9 (nodes are 1..4)"),
}


@pytest.mark.parametrize("case", list(WRONG_3D))
def test_a_wrong_3d_model_file_names_the_key(tmp_path, case):
    change, expected = WRONG_3D[case]
    path = write(tmp_path, change(portal_3d()))
    with pytest.raises(ModelFileError) as info:
        load_model_file(path)
    assert f"{path}: {expected}" in str(info.value)


#: ``(change of portal_2d, the message)``: keys of 3-D frames in a 2-D file.
WRONG_2D = {
    "z": (_change(nodes__0__z=0.0), "nodes[0].z = 0.0: a key of 3-D frames only (declare [frame] dimensions = 3; "
                                    "valid keys of a 2-D frame here: id, x, y)"),
    "diaphragms": (lambda d: d | {"rigid_diaphragms": [{"master": 2, "slaves": [3]}]},
                   "rigid_diaphragms: a key of 3-D frames only (declare [frame] dimensions = 3"),
    "Iy": (_change(elements__0__Iy=1e-3), "elements[0].Iy = 0.001: a key of 3-D frames only"),
    "uz": (_change(loads__ground_motion__0__direction="uz"),
           'loads.ground_motion[0].direction = "uz": unknown ground motion direction (valid: ux, uy)'),
}


@pytest.mark.parametrize("case", list(WRONG_2D))
def test_a_3d_key_in_a_2d_model_file_is_refused(tmp_path, case):
    change, expected = WRONG_2D[case]
    path = write(tmp_path, change(portal_2d()))
    with pytest.raises(ModelFileError) as info:
        load_model_file(path)
    assert f"{path}: {expected}" in str(info.value)


def test_a_wrong_3d_model_file_fails_before_numpy(tmp_path):
    """The command line reports a wrong 3-D file importing neither numpy nor scipy (as tests/test_prompt.py)."""
    change, expected = WRONG_3D["2-D key"]
    path = write(tmp_path, change(portal_3d()))
    code = textwrap.dedent(f"""
        import contextlib, io, json, sys
        import unilateral.cli
        out, code = io.StringIO(), None
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(out):
            try:
                unilateral.cli.main(["run", {str(path)!r}, "--out", {str(tmp_path / "out")!r}], prog_name="unilateral")
            except SystemExit as exc:
                code = exc.code
        print(json.dumps({{"modules": sorted({{m.partition(".")[0] for m in sys.modules}}), "code": code,
                          "output": out.getvalue()}}))
    """)
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout.splitlines()[-1])
    assert result["code"] == 1 and f"{path}: {expected}" in result["output"], result["output"]
    assert not set(result["modules"]) & {"numpy", "scipy", "xarray", "matplotlib"}, result["modules"]
    assert not (tmp_path / "out").exists()


def test_the_building_model_file_runs_from_the_command_line(tmp_path):
    """examples/building3d.toml: six DOFs per node in results.nc, the weight on the ground at rest, both
    horizontal components shake the building and twist it."""
    from click.testing import CliRunner

    from unilateral.cli import main
    from unilateral.io import load_netcdf

    example = ROOT / "examples" / "building3d.toml"
    out = tmp_path / "building3d"
    result = CliRunner().invoke(main, ["run", str(example), "--t-end", "0.2", "--figures", "none", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "peak base forces Fx" in result.output
    ds = load_netcdf(out / "results.nc")
    assert ds["node_displacement"].dims == ("case", "time", "node", "component")
    assert list(ds["component"].values) == ["ux", "uy", "uz", "rx", "ry", "rz"]
    assert ds.sizes["time"] == 41 and ds.sizes["constraint"] == 36
    spec = load_model_file(example)
    weight = -float(spec.structure.gravity(9.81) @ spec.structure.influence("uz"))
    assert float(ds["base_Fz"].sel(case="unilateral")[0]) == pytest.approx(weight, rel=1e-8)
    for key in ("base_Fx", "base_Fy", "base_Mz"):
        assert np.abs(ds[key].sel(case="unilateral").values).max() > 1.0, key
    roof = ds["node_displacement"].sel(case="unilateral", node="1003", component="rz").values
    assert np.abs(roof).max() > 0.0
    # drift ratios per storey and direction, the largest over the plan's corners: the roof's corner
    # (12, 12) against the floor below, along y, is one of them
    assert list(ds["storey"].values) == ["0-3.5", "3.5-7", "7-10.5"]
    u = ds["node_displacement"].sel(case="unilateral", component="uy")
    corner = np.abs(u.sel(node="322").values - u.sel(node="222").values) / 3.5
    drift_y = ds["drift_ratio_y"].sel(case="unilateral", storey="7-10.5").values
    assert np.all(drift_y >= corner - 1e-15) and drift_y.max() > 0
    assert "peak drift ratio" in result.output
    # the bilateral periods: those the example script computes by its own static condensation (the file's
    # sections are written to 6 digits)
    import importlib.util

    module = importlib.util.spec_from_file_location("building3d_script", ROOT / "examples" / "building3d.py")
    script = importlib.util.module_from_spec(module)
    module.loader.exec_module(script)
    periods, _ = script.modes(spec.structure, spec.model)
    np.testing.assert_allclose(ds["mode_period"].values[:6], periods[:6], rtol=1e-5)
    assert "periods of the bilateral structure" in result.output
    # the reactions: the ground's forces through the footing patches and the supports sum to the base forces
    ground = ds["ground_reaction"].sel(case="unilateral")
    support = ds["support_reaction"].sel(case="unilateral")
    labels = [str(label) for label in ds["support"].values]
    for component, dof in (("Fx", "ux"), ("Fy", "uy"), ("Fz", "uz")):
        total = ground.sel(force_component=component).values.sum(axis=1)
        total = total + sum(support.values[:, k] for k, label in enumerate(labels) if label.endswith("." + dof))
        expected = ds[f"base_{component}"].sel(case="unilateral").values
        np.testing.assert_allclose(total, expected, rtol=0, atol=1e-9 * max(1.0, np.abs(expected).max()))


def test_the_model_figure_of_a_3d_file_draws_its_members_ties_and_footings(tmp_path):
    """``unilateral plot --model`` on a 3-D file: model.png in perspective, from a drawing that holds
    every member, the diaphragms' ties, the supports and the footings' patches."""
    from click.testing import CliRunner

    from unilateral.cli import main
    from unilateral.figures.model import model_file_drawing

    example = ROOT / "examples" / "building3d.toml"
    drawing = model_file_drawing(example)
    spec = load_model_file(example)
    st = spec.structure
    beams = [e for e in st.elements if e.kind.startswith("beam")]
    assert len([m for m in drawing.members if m[0] == "beam"]) == len(beams) > 0
    assert len(drawing.ties) == len(st.dofs.ties) > 0
    assert [name for name, *_ in drawing.footings] == [f.name for f in st.foundation.footings]
    assert sum(len(centres) for _, _, centres, _ in drawing.footings) == st.foundation.m == 36
    result = CliRunner().invoke(main, ["plot", "--model", str(example), "--out", str(tmp_path / "fig")])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "fig" / "model.png").stat().st_size > 10_000


def test_yield_links_and_sliders_in_a_3d_file(tmp_path):
    """A 3-D file's yielding link and slider build the Frame3D elements along their directions; the run
    yields and slides."""
    text = """
units = { length = "m", force = "kN", time = "s" }
frame = { dimensions = 3 }
nodes = [{ id = 1, x = 0.0, y = 0.0, z = 0.0 }, { id = 2, x = 2.0, y = 0.0, z = 0.0 }]
supports = [{ node = 1, ux = false, uy = false }, { node = 2, ux = false, uy = false }]
masses = [{ node = 1, m = 2.0 }, { node = 2, m = 1.0 }]
elements = [
    { type = "spring", name = "keep1", node_i = 1, k = 1e3, direction = [1.0, -1.0, 0.0] },
    { type = "spring", name = "keep2", node_i = 2, k = 1e3, direction = "ux" },
]
unilateral = [
    { type = "yield", name = "y", node = 1, k = 1e3, Fy = 50.0, hardening = 0.05, direction = [1.0, 1.0, 0.0] },
    { type = "slider", name = "s", node = 2, mu = 0.3, N = 100.0, k = 2e3, direction = "uy" },
]
loads.nodal = [
    { node = 1, ux = 80.0, uy = 80.0, time_function = { type = "ramp", t_ramp = 1.0 } },
    { node = 2, uy = 60.0, time_function = { type = "ramp", t_ramp = 1.0 } },
]
analysis = { t_end = 1.0, dt = 0.005, method = "direct" }
"""
    path = tmp_path / "yield3d.toml"
    path.write_text(text)
    spec = load_model_file(path)
    assert spec.structure.constraint_names == ("y.plastic+", "y.plastic-", "s.slip+", "s.slip-")
    sol = ul.solve(spec.model, spec.load, dt=0.005, t_end=1.0, method="direct")
    assert sol.success and sol.v[:, :2].max() > 1e-3 and sol.v[:, 2:].max() > 1e-3
