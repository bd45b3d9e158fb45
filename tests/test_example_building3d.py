"""examples/building3d.py: the 3-storey building with an eccentric mass on four footings on a half-space.

The script's ``main`` runs for the first 3 s of the records (the light corner footing lifts off
entirely at 2.5 s) into a temporary folder; the same building with the extra mass at the centre of
the plan is the symmetric reference: it does not twist under one component (to round-off) and
twists by far less than the eccentric building under both; with the extra mass on the diagonal and one
record along x and y, two footings are mirror images; the script also runs from the command line.
"""

import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "examples" / "building3d.py"
T_END = 3.0


@pytest.fixture(scope="module")
def example():
    spec = importlib.util.spec_from_file_location("building3d_example", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def summary(example, tmp_path_factory):
    out = tmp_path_factory.mktemp("building3d")
    return example.main(["--out", str(out), "--t-end", str(T_END)]), out


def test_the_outputs_are_written_and_the_solves_succeed(summary):
    s, out = summary
    png, js = out / "building3d.png", out / "building3d.json"
    assert png.stat().st_size > 10_000 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    written = json.loads(js.read_text(encoding="utf-8"))
    assert written["steps"] == s["steps"] == round(T_END / 0.005)
    assert written["success"] and written["bilateral"]["success"]
    assert not [p for p in out.iterdir() if p.name not in ("building3d.png", "building3d.json")]   # no temp files
    assert s["model"]["m"] == 36 and set(s["footings"]) == {"F00", "F20", "F02", "F22"}


def test_the_static_state_carries_the_weight_and_the_heavy_corner_most(summary):
    s, _ = summary
    assert s["static_soil_force_kN"] == pytest.approx(s["weight_kN"], rel=1e-9)
    loads = {name: f["static_load_kN"] for name, f in s["footings"].items()}
    assert max(loads, key=loads.get) == "F22"                     # under the extra mass
    assert loads["F20"] == pytest.approx(loads["F02"], rel=1e-9)  # mirror images across the diagonal
    tilted = {name: f["statically_open_patches"] for name, f in s["footings"].items()}
    assert tilted["F20"] == tilted["F02"] > 0 and tilted["F22"] == 0 and s["statically_open_patches"] == 5
    cm, cs = s["centre_of_mass_m"], s["centre_of_stiffness_m"]
    assert cm == pytest.approx([6.0 + 43.2 * 6.0 / 187.2] * 2, rel=1e-12)
    assert cs == pytest.approx([6.0, 6.0], abs=1e-9)              # a symmetric frame and foundation


def test_patches_open_and_the_light_corner_footing_lifts_off(summary):
    s, _ = summary
    assert s["patches_that_open_in_the_shaking"] > 0
    f = s["footings"]["F00"]                                      # the corner opposite the extra mass
    assert f["first_lift_off_s"] is not None and f["peak_lift_off_mm"] > 0.5
    assert f["peak_opening_mm"] == max(g["peak_opening_mm"] for g in s["footings"].values())
    assert s["contact_changes"] > 0
    assert s["bilateral"]["peak_patch_tension_kN"] > 0            # held, the soil would pull


def test_the_eccentric_mass_twists_the_building(example, summary):
    s, _ = summary
    twist = s["peak_roof_twist_rad"]
    assert twist > 1e-3
    # the extra mass at the centre of the plan: a doubly symmetric building
    both = example.analyse(t_end=T_END, extra_at="centre", bilateral=False)
    st, sol = both["structure"], both["sol"]
    assert sol.success and sol.v.max() > 1e-3                    # it rocks and lifts too
    symmetric = np.abs(st.node_displacement(sol, example.ROOF, "rz")).max()
    assert symmetric < 0.01 * twist          # only the uplift's coupling of x and y twists it at all
    one = example.analyse(t_end=T_END, extra_at="centre", components=("ux",), bilateral=False)
    st, sol = one["structure"], one["sol"]
    ux = np.abs(st.node_displacement(sol, example.ROOF, "ux")).max()
    assert sol.success and ux > 0.01
    assert np.abs(st.node_displacement(sol, example.ROOF, "rz")).max() * 12.0 < 1e-10 * ux   # twist: round-off


def test_the_building_is_a_mirror_image_of_itself_across_its_diagonal(example):
    """The extra mass on the diagonal x = y and the same record along x and y: the footings F20 and
    F02 are mirror images (patch (i, j) of one is patch (j, i) of the other), with uplift."""
    import unilateral as ul

    st = example.build(rayleigh=(1.75, 6.25))
    model = st.to_model()
    gm = example.records(T_END, ("ux",))["ux"]
    q = example.LoadHistory(st.gravity(example.GRAVITY), [st.ground_motion(gm, "ux"), st.ground_motion(gm, "uy")])
    sol = ul.solve(model, q, dt=example.DT, t_end=T_END, method="cq")
    cols = example.footing_columns(st)
    mirror = np.array([j + 3 * i for j in range(3) for i in range(3)])       # position i + 3 j holds (j, i)
    c, v = -sol.psi, sol.v
    assert sol.success and v[1:, cols["F20"]].max() > 1e-3
    np.testing.assert_allclose(c[:, cols["F20"]], c[:, cols["F02"][mirror]], rtol=0, atol=1e-10 * np.abs(c).max())
    np.testing.assert_allclose(v[:, cols["F20"]], v[:, cols["F02"][mirror]], rtol=0, atol=1e-10 * v.max())
    # the static openings are those of the geometry: T^T u0 + Phi(0) c0 + gap (open patches carry no force)
    T = model.T.toarray() if hasattr(model.T, "toarray") else np.asarray(model.T)
    geometric = T.T @ sol.u[0] + model.soil.static() @ c[0] + model.gap
    np.testing.assert_allclose(v[0], np.where(geometric > 1e-12, geometric, 0.0), rtol=0, atol=1e-15)


def test_the_script_runs_from_the_command_line(tmp_path):
    env = {**os.environ, "MPLBACKEND": "Agg"}
    proc = subprocess.run([sys.executable, str(SCRIPT), "--out", str(tmp_path / "out"), "--t-end", "0.5"],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "T1 = " in proc.stdout and "peak roof twist rz" in proc.stdout and "footings held (bilateral)" in proc.stdout
    assert (tmp_path / "out" / "building3d.png").stat().st_size > 0
    assert json.loads((tmp_path / "out" / "building3d.json").read_text(encoding="utf-8"))["success"]
