"""Every example of examples/ runs and prints or writes what it says, so that no example can rot.

The Python scripts run as users run them (a subprocess, ``MPLBACKEND=Agg``, in a temporary working
directory), two at a time, and their output is parsed; the model files run through
``unilateral.run`` for a short time without figures; the study file is read and expanded. Each
check is on a number that a broken example or a broken library would change: an identity that
holds to round-off, a closed form, a fitted order, or a value the model file states.
"""

import json
import os
import re
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import unilateral

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SCRIPTS = ("bouncing_mass.py", "rocking_tower.py", "pounding_frames.py", "convergence_bdf2.py", "soil_kernels.py",
           "sliding_block.py", "rocking_pier.py")
MODEL_FILES = ("liolios1990.toml", "pounding.toml", "winkler_beam.toml", "yielding_frame.toml", "building3d.toml")
NUMBER = r"([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)"


def _run_script(name: str, cwd: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "MPLBACKEND": "Agg"}
    return subprocess.run([sys.executable, str(EXAMPLES / name)], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=300)


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    """Stdout of every Python example (run two at a time, each in its own working directory)."""
    # the folders are made here, in one thread: pytest's temporary-folder factory is not thread-safe
    folders = {name: tmp_path_factory.mktemp(name.removesuffix(".py")) for name in SCRIPTS}

    def run(name):
        return name, _run_script(name, folders[name])

    with ThreadPoolExecutor(max_workers=2) as pool:
        done = dict(pool.map(run, SCRIPTS))
    for name, proc in done.items():
        assert proc.returncode == 0, f"{name} failed:\n{proc.stdout}\n{proc.stderr}"
    return {name: proc.stdout for name, proc in done.items()}


def _numbers(text: str, pattern: str) -> list[float]:
    """The numbers of the first line matching ``pattern`` (a regex with NUMBER groups)."""
    match = re.search(pattern.replace("{N}", NUMBER), text)
    assert match, f"no line matching {pattern!r} in:\n{text}"
    return [float(x) for x in match.groups()]


def test_every_example_is_listed_in_the_readme_and_tested():
    readme = (EXAMPLES / "README.md").read_text(encoding="utf-8")
    files = sorted(p.name for p in EXAMPLES.iterdir() if p.suffix in (".py", ".toml"))
    # ida.toml: tests/test_batch.py; building3d.py: tests/test_example_building3d.py; rocking_block.py:
    # tests/test_rocking_block.py; pushover_portal.py, pushover_cyclic.py: tests/test_pushover_example.py;
    # pushover_portal.toml: tests/test_pushover_files.py; overturning_map.py, rocking_block.toml: tests/test_moreau_jean.py;
    # support_motion.toml: tests/test_support_motion.py; rocking_box.toml: tests/test_rigid_box3d.py
    assert files == sorted((*SCRIPTS, *MODEL_FILES, "ida.toml", "make_ida_records.py", "building3d.py",
                            "rocking_block.py", "pushover_portal.py", "pushover_cyclic.py", "pushover_portal.toml",
                            "overturning_map.py", "rocking_block.toml", "support_motion.toml", "rocking_box.toml"))
    for name in files:
        assert f"[{name}]({name})" in readme, f"{name} is not listed in examples/README.md"
        assert f"examples/{name}" in readme, f"examples/README.md gives no command for {name}"


def test_bouncing_mass_event_is_exact_and_cq_converges(outputs):
    out = outputs["bouncing_mass.py"]
    liftoff, peak = _numbers(out, r"closed form: lift-off at t = {N} s, peak uplift {N} m")
    assert peak == pytest.approx(0.045, rel=1e-9)                      # u'^2 / (2 g) with u'^2 = 0.9
    event_liftoff, = _numbers(out, r"method=event: first event at t = {N} s")
    assert event_liftoff == pytest.approx(liftoff, abs=1e-12)
    assert _numbers(out, r"(?m)^event error {N}$")[0] < 1e-12
    coarse, = _numbers(out, r"dt = 0.001 s: peak uplift [\d.]+ m, largest error {N} m")
    fine, = _numbers(out, r"dt = 0.0005 s: peak uplift [\d.]+ m, largest error {N} m")
    assert 1e-7 < fine < coarse < 1e-4


def test_sliding_block_matches_newmarks_closed_form(outputs):
    out = outputs["sliding_block.py"]
    exact, t_stop = _numbers(out, r"closed form: permanent slip {N} m, block stops at t = {N} s")
    assert exact == pytest.approx(0.519368, abs=1e-6)                   # printed to 6 decimals
    errors = [abs(float(x)) for x in re.findall(r"relative error ([-+][\d.e+-]+)", out)]
    assert len(errors) == 3 and errors[0] > errors[1] > errors[2]      # converges as dt shrinks
    assert _numbers(out, r"(?m)^slip error {N} at dt")[0] < 1e-4
    stops = [float(x) for x in re.findall(r"stops at t = ([\d.]+) s", out)]
    assert stops[-1] == pytest.approx(t_stop, abs=2e-4)


def test_rocking_tower_equilibrium_and_energy(outputs):
    out = outputs["rocking_tower.py"]
    assert re.search(r"^method: (modal|cq|direct) \(.+\)$", out, re.M), out
    uplift, _ = _numbers(out, r"peak uplift of the left edge: {N} mm at t = {N} s")
    assert uplift > 1.0
    vertical, weight = _numbers(out, r"vertical base force {N} kN, weight {N} kN")
    assert weight == pytest.approx(3 * 20.0 * 9.81) and vertical == pytest.approx(weight, rel=1e-9)
    moment, _ = _numbers(out, r"foot of the tower: {N} kN m at t = {N} s")
    overturning, _ = _numbers(out, r"peak overturning moment: {N} kN m at t = {N} s")
    assert abs(overturning) == pytest.approx(moment, rel=1e-9)      # the column's foot is the only path
    residual, = _numbers(out, r"max \|base shear - \(r\^T M u'' - r\^T q\)\| = {N} kN")
    shear, _ = _numbers(out, r"peak base shear: {N} kN at t = {N} s")
    assert residual < 1e-8 * abs(shear)
    assert _numbers(out, r"energy balance: largest relative error {N}")[0] < 1e-2


def test_rocking_pier_base_forces_bound_and_energy(outputs):
    out = outputs["rocking_pier.py"]
    W, Wb = _numbers(out, r"pier: W = {N} kN .* W b = {N} kN m")
    assert Wb == pytest.approx(2.5 * W, rel=1e-4)
    least, impacts, steps = _numbers(out, r"contact forces: least {N} kN \(>= 0\); {N} located impacts in {N} steps")
    assert least >= -1e-9 * W and impacts >= 5 and steps >= 1
    bound, low, high = _numbers(out, r"max \|M\| / \(b \(R_L \+ R_R\)\) = {N} \(<= 1\); .* from {N} to {N}")
    assert bound <= 1.0 + 1e-12 and 0.0 < low < 1.0 < high     # the deck's vertical inertia on the bound
    assert _numbers(out, r"vertical equilibrium: max \|R_L \+ R_R - \(W \+ sum m a_y\)\| = {N} kN")[0] < 1e-10 * W
    smooth, at_impacts, peak = _numbers(out, r"overturning moment\| = {N} kN m without impact, {N} kN m at the "
                                             r"impact steps \(peak {N} kN m\)")
    assert smooth < 1e-10 * peak and at_impacts < 1e-4 * peak
    relative, dissipated, located, difference = _numbers(
        out, r"energy balance: relative error {N}; contacts dissipated {N} kN m, located impacts {N} kN m \(difference {N}\)")
    assert relative < 1e-12 and dissipated > 0 and difference < 1e-10 * dissipated
    rocking, = _numbers(out, r"rocking \(between impacts\): .* base moment [\d.]+ kN m = {N} W b")
    fixed, = _numbers(out, r"fixed base: .* base moment [\d.]+ kN m = {N} W b")
    assert rocking <= high * bound + 1e-9 and rocking < fixed          # within b (R_L + R_R); below the fixed base
    for name in ("rocking_pier.png", "rocking_pier_shape.png", "rocking_pier.gif"):
        path, = re.findall(rf"wrote (.*{re.escape(name)})$", out, re.M)
        assert Path(path).stat().st_size > 1000, path


def test_pounding_frames_contact_follows_the_gap(outputs):
    out = outputs["pounding_frames.py"]
    impacts, = _numbers(out, r"impacts: {N}")
    forces = [float(x) for x in re.findall(r"peak force (\d+) kN", out)]
    assert impacts == len(forces) == 3 and min(forces) > 100.0
    closest, gap = _numbers(out, r"min e = {N} mm against -gap = {N} mm")
    assert gap == -40.0 and closest < gap                            # contact only once the gap has closed
    assert _numbers(out, r"largest difference {N} kN")[0] < 1e-6 * max(forces)


def test_convergence_order_of_bdf2_is_two(outputs):
    out = outputs["convergence_bdf2.py"]
    lift_offs, closures = _numbers(out, r"{N} lift-offs, {N} closures, airborne: True")
    assert lift_offs >= 4 and closures >= 4
    orders = _numbers(out, r"orders u v psi: {N} {N} {N}")
    assert all(1.8 < p < 2.2 for p in orders), orders


def test_soil_kernels_far_field_static_disc_and_veletsos_verbic(outputs):
    out = outputs["soil_kernels.py"]
    assert _numbers(out, r"far field: .* relative difference {N}")[0] < 5e-3
    static, = _numbers(out, r"static disc: rigorous K\(0\)/K0 = {N}")
    assert 0.98 < static < 1.0                                      # patches: O(h) short of the disc
    assert _numbers(out, r"largest difference for a0 <= 1: {N} K0")[0] < 0.1


def test_make_ida_records_writes_the_stored_records(tmp_path):
    shutil.copy(EXAMPLES / "make_ida_records.py", tmp_path)
    proc = _run_script_at(tmp_path / "make_ida_records.py", tmp_path)
    assert proc.returncode == 0, proc.stderr
    made = sorted((tmp_path / "records" / "ida").glob("*.AT2"))
    stored = sorted((EXAMPLES / "records" / "ida").glob("*.AT2"))
    assert [p.name for p in made] == [p.name for p in stored] and len(made) == 10
    for new, old in zip(made, stored):
        assert new.read_bytes() == old.read_bytes(), f"{new.name} differs from examples/records/ida/"


def _run_script_at(script: Path, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(script)], cwd=cwd, capture_output=True, text=True, timeout=600,
                          env={**os.environ, "MPLBACKEND": "Agg"})


def test_ida_study_expands_to_its_hundred_analyses():
    from unilateral.batch import load_study
    from unilateral.loads import STANDARD_GRAVITY

    study = load_study(EXAMPLES / "ida.toml")
    assert len(study.records) == 10 and len(study.analyses) == 100
    for record in study.records:
        assert record.error is None, record.error
        assert record.motion.duration == pytest.approx(12.0, abs=0.011)
        assert record.motion.pga == pytest.approx(0.3 * STANDARD_GRAVITY, rel=1e-6)


# ---------------------------------------------------------------------- model files
def _run_model(name, tmp_path, t_end):
    summary = unilateral.run(EXAMPLES / name, tmp_path / name, figures=(), t_end=t_end)
    assert summary["success"], summary["message"]
    written = json.loads((tmp_path / name / "summary.json").read_text())
    assert written["steps"] == summary["steps"]
    assert (tmp_path / name / "results.nc").stat().st_size > 0
    return summary


def test_liolios1990_model_file(tmp_path):
    s = _run_model("liolios1990.toml", tmp_path, 0.25)
    assert s["steps"] == 250
    figure = s["extra"]["figure"]
    assert figure["static"] == pytest.approx(-400.0 / (3 * 200e3), rel=1e-8)        # -M g / (3 k)
    assert figure["peak"]["unilateral"] > 10 * figure["peak"]["bilateral"] > 0      # README: 2.75 and 0.23 mm
    assert s["constraints"]["soil3"]["max_v"] > 2e-3                               # the left edge lifts off


def test_pounding_model_file(tmp_path):
    s = _run_model("pounding.toml", tmp_path, 1.6)
    joint = s["constraints"]["joint"]
    assert joint["t_min_psi"] == pytest.approx(1.45, abs=0.03)      # the first impact (pounding_frames.py)
    assert -joint["min_psi"] > 100.0


def test_winkler_beam_model_file(tmp_path):
    s = _run_model("winkler_beam.toml", tmp_path, 0.01)
    settlement = 0.625 * 9.80665 / 20e3                              # m g / k per node: uniform
    assert s["extra"]["figure"]["static"] == pytest.approx(-settlement, rel=1e-9)
    assert np.isfinite(s["max_lcp_error"]) and s["max_lcp_error"] < 1e-9


def test_building3d_model_file(tmp_path):
    """The building of building3d.py as a 3-D model file: the corner footings' outer patches open under
    gravity (building3d.py: about 0.3 mm), both horizontal components load the base, the eccentric
    mass twists it (tests/test_modelfile3d.py checks the file further)."""
    s = _run_model("building3d.toml", tmp_path, 0.2)
    assert s["steps"] == 40 and len(s["constraints"]) == 36
    assert 2e-4 < max(c["max_v"] for c in s["constraints"].values()) < 5e-4
    base = s["results"]["unilateral"]["base_forces"]
    for key in ("Fx", "Fy", "Mz"):
        assert max(abs(base[key]["max"]), abs(base[key]["min"])) > 1.0, key


def test_yielding_frame_model_file(tmp_path):
    """The frame's beams yield, a footing lifts off and its edges slip, the drifts are 1-3 %; the run
    prints a line per family and writes the plastic deformations, the hysteresis figure and the
    ductilities."""
    from click.testing import CliRunner

    from unilateral.cli import main
    from unilateral.io import load_netcdf

    out = tmp_path / "yielding_frame"
    result = CliRunner().invoke(main, ["run", str(EXAMPLES / "yielding_frame.toml"), "--out", str(out),
                                       "--t-end", "1.5"])
    assert result.exit_code == 0, result.output
    yielded, total = _numbers(result.output, r"yield: {N} of {N} hinges yielded, peak ductility")
    assert total == 15 and yielded >= 12
    assert re.search(r"friction: \d+ of 6 friction elements slid", result.output)
    assert "with yield, slip and uplift" in result.output and "linear (constraints held)" in result.output
    ds = load_netcdf(out / "results.nc")
    assert ds["plastic_deformation"].dims == ("case", "time", "yield_element")
    assert ds["plastic_deformation"].sizes["yield_element"] == 15 and "rad" in ds["plastic_deformation"].attrs["units"]
    assert (out / "hysteresis.png").stat().st_size > 0
    peaks = json.loads((out / "summary.json").read_text())["results"]["unilateral"]
    hinges = peaks["yield_elements"]
    assert all(hinges[f"B{f}_{b}.{end}"]["yielded"] for f in (1, 2, 3) for b in (1, 2) for end in "ij")
    assert all(hinges[f"C{line}_1.base"]["ductility"]["value"] > 1.0 for line in (1, 2, 3))
    assert 0.01 < max(abs(d["value"]) for d in peaks["drift_ratio"].values()) < 0.03
    summary = json.loads((out / "summary.json").read_text())
    assert max(c["max_v"] for c in summary["constraints"].values()) > 1e-3          # an edge lifts off
    assert any(f["slid"] for f in peaks["friction_elements"].values())


def test_winkler_beam_says_there_is_no_base_shear_and_writes_units_and_both_cases(tmp_path):
    """Vertical loads only: the terminal says there is no base shear and gives the vertical ground force
    (the soil springs' reactions: the weight at rest), the figure draws that force, not an empty panel;
    every CSV header states its unit and the result tables are written for both cases."""
    from click.testing import CliRunner

    from unilateral.cli import main
    from unilateral.figures.results import base_forces_figure
    from unilateral.io import load_netcdf

    out = tmp_path / "winkler"
    result = CliRunner().invoke(main, ["run", str(EXAMPLES / "winkler_beam.toml"), "--out", str(out),
                                       "--t-end", "0.03"])
    assert result.exit_code == 0, result.output
    assert "peak base shear 0" not in result.output
    assert "no base shear (no horizontal force on the ground); peak vertical ground force" in result.output
    ds = load_netcdf(out / "results.nc")
    weight = 12.5 * 9.80665                                          # 1.25 t/m over 10 m
    assert float(ds["base_vertical"].sel(case="unilateral")[0]) == pytest.approx(weight, rel=1e-6)
    fig = base_forces_figure(ds)
    top = fig.axes[0]
    assert top.get_ylabel() == "vertical ground force [kN]" and "no base shear" in top.get_title(loc="left")
    headers = {p.name: p.read_text().splitlines()[0].split(",") for p in out.glob("*.csv")}
    assert {"base.csv", "bilateral_base.csv", "element_forces.csv", "bilateral_element_forces.csv"} <= set(headers)
    for name, header in headers.items():
        assert header[0] == "time [s]" and all(h.endswith("]") for h in header), (name, header)
    assert "21.uy [m]" in headers["displacements.csv"] and "21.rz [rad]" in headers["bilateral_displacements.csv"]
    assert "psi:soil21 [kN]" in headers["constraints.csv"] and "beam1:M_i [kN m]" in headers["element_forces.csv"]
    assert "energy_relative_error [1]" in headers["base.csv"]
