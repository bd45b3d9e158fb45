"""Studies whose records are pairs (``[records] pairs``): two horizontal components, or a horizontal
and a vertical one, and optionally a third, in one analysis.

The main check: a study's analysis under a pair is the model file run with those components as its
``[[loads.ground_motion]]`` entries, bit for bit; a pair rotated in plan by ``angle`` is the run
with the rotated influence vectors; ``pga`` and ``sa`` scale a pair by its larger horizontal PGA and
by the geometric mean of its horizontal Sa; bad inputs are refused when the study is read; the
components reach remote workers through Dask like single records.
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from test_batch import record_files, tower
from unilateral.batch import first_period, load_study, response_spectrum, run_study
from unilateral.loads import LoadHistory, Tabulated, read_record
from unilateral.modelfile import ModelFileError, load_model_file

try:                                   # the scheduler and two workers of test_batch_remote (module-scoped)
    from test_batch_remote import hand_started  # noqa: F401
except pytest.skip.Exception:          # no distributed: only the test on remote workers is skipped
    @pytest.fixture
    def hand_started():
        pytest.skip("distributed is not installed")

G = 9.80665

# A one-storey 3-D frame, 4 m x 3 m in plan and 3 m high, on four tensionless soil elements: a rigid
# floor (master node 9 at the centre) and an eccentric mass at the corner node 7, so it sways along
# x and y and twists. {ground}: ground-motion tables (or nothing).
FRAME3D = """\
units = {{ length = "m", force = "kN", time = "s" }}
frame = {{ dimensions = 3 }}
nodes = [
    {{ id = 1, x = 0.0, y = 0.0, z = 0.0 }}, {{ id = 2, x = 4.0, y = 0.0, z = 0.0 }},
    {{ id = 3, x = 4.0, y = 3.0, z = 0.0 }}, {{ id = 4, x = 0.0, y = 3.0, z = 0.0 }},
    {{ id = 5, x = 0.0, y = 0.0, z = 3.0 }}, {{ id = 6, x = 4.0, y = 0.0, z = 3.0 }},
    {{ id = 7, x = 4.0, y = 3.0, z = 3.0 }}, {{ id = 8, x = 0.0, y = 3.0, z = 3.0 }},
    {{ id = 9, x = 2.0, y = 1.5, z = 3.0 }},
]
supports = [
    {{ node = 1, uz = false, rx = true, ry = true, rz = true }},
    {{ node = 2, uz = false, rx = true, ry = true, rz = true }},
    {{ node = 3, uz = false, rx = true, ry = true, rz = true }},
    {{ node = 4, uz = false, rx = true, ry = true, rz = true }},
    {{ node = 9, ux = false, uy = false, uz = true, rx = true, ry = true, rz = false }},
]
rigid_diaphragms = [{{ master = 9, slaves = [5, 6, 7, 8] }}]
elements = [
{elements}
]
unilateral = [
    {{ type = "soil", name = "s1", node = 1, k = 2e4, c = 50.0 }},
    {{ type = "soil", name = "s2", node = 2, k = 2e4, c = 50.0 }},
    {{ type = "soil", name = "s3", node = 3, k = 2e4, c = 50.0 }},
    {{ type = "soil", name = "s4", node = 4, k = 2e4, c = 50.0 }},
]
masses = [{{ node = 9, m = 20.0, Jz = 30.0 }}, {{ node = 7, m = 10.0 }}]
damping = {{ rayleigh = {{ a0 = 0.2 }} }}

[loads.gravity]
g = 9.81

{ground}

[analysis]
dt = 0.005
t_end = 1.0
method = "cq"
"""
COLUMN = "E = 3e7, A = 0.09, Iy = 6.75e-4, Iz = 6.75e-4, G = 1.25e7, J = 1e-3"
BEAM = "E = 3e7, A = 0.12, Iy = 1.6e-3, Iz = 1.6e-3, G = 1.25e7, J = 1e-3"
MEMBERS = ([(f"c{k}", k, k + 4, COLUMN) for k in (1, 2, 3, 4)]
           + [(f"b{k}", k + 4, k % 4 + 5, BEAM) for k in (1, 2, 3, 4)])

QUANTITIES = """
[[quantities]]
name = "roof_ux"
type = "displacement"
node = 9
dof = "ux"
[[quantities]]
name = "roof_uy"
type = "displacement"
node = 9
dof = "uy"
[[quantities]]
name = "roof_rz"
type = "displacement"
node = 9
dof = "rz"
[[quantities]]
name = "uplift"
type = "uplift"
"""
UPLIFT = '[[quantities]]\nname = "uplift"\ntype = "uplift"\n'
PEAKS = (("roof_ux", 9, "ux"), ("roof_uy", 9, "uy"), ("roof_rz", 9, "rz"))


def frame3d(ground: str = "") -> str:
    elements = ",\n".join(f'    {{ type = "beam", name = "{name}", node_i = {i}, node_j = {j}, {props} }}'
                          for name, i, j, props in MEMBERS)
    return FRAME3D.format(elements=elements, ground=ground)


def motions(*entries) -> str:
    """``[[loads.ground_motion]]`` tables of ``(file, direction, scale)``."""
    return "".join(f'[[loads.ground_motion]]\nfile = "{file}"\ndirection = "{direction}"\nscale = {float(scale)!r}\n'
                   for file, direction, scale in entries)


def resampled(source: Path, target: Path, dt: float, npts: int, factor: float = 1.0) -> Path:
    """A PEER .AT2 file of ``source`` times ``factor`` sampled at ``dt`` (linear interpolation), ``npts``
    samples, in g."""
    record = read_record(source)
    t = np.arange(npts) * dt
    values = factor * np.interp(t, record.time, record.acceleration, right=0.0) / G
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD (FORMAT ONLY)", f"RESAMPLED {source.name} (a test)",
             "ACCELERATION TIME SERIES IN UNITS OF G", f"NPTS= {npts:7d}, DT= {dt:.4f} SEC"]
    lines += ["".join(f"{v:15.7E}" for v in values[k:k + 5]) for k in range(0, npts, 5)]
    target.write_text("\n".join(lines) + "\n")
    return target


@pytest.fixture
def folder(tmp_path):
    """``tmp_path`` with the 3-D frame (``frame.toml``) and the records ``x.AT2`` (a record of the IDA
    example: 1201 samples at 0.01 s, PGA 0.3 g), ``y.AT2`` (another times 1.2: PGA 0.36 g), ``y2.AT2``
    (that resampled: 801 samples at 0.004 s, shorter) and ``z.AT2`` (a third times 1.5: PGA 0.45 g)."""
    records = record_files(3)
    shutil.copy(records[0], tmp_path / "x.AT2")
    resampled(records[1], tmp_path / "y.AT2", 0.01, 1201, 1.2)
    resampled(records[1], tmp_path / "y2.AT2", 0.004, 801, 1.2)
    resampled(records[2], tmp_path / "z.AT2", 0.01, 1201, 1.5)
    (tmp_path / "frame.toml").write_text(frame3d())
    return tmp_path


def write(folder: Path, records: str, *, scaling="values = [1.0]", model="frame.toml", analysis="",
          name="study.toml", quantities=QUANTITIES) -> Path:
    path = folder / name
    path.write_text(f'[[models]]\nfile = "{model}"\n[records]\n{records}\n[scaling]\n{scaling}\n'
                    f"[analysis]\n{analysis}\n{quantities}")
    return path


def run(path: Path, out: str = "out"):
    result = run_study(path, path.parent / out, synchronous=True, progress=False, figures=False)
    table = result.table
    assert (table["status"].values == "ok").all(), table["message"].values
    return table


def alone(folder: Path, ground: str, *, model=frame3d, load=None):
    """``(spec, Solution)`` of the model file with the ground motions ``ground`` run on its own, as
    ``unilateral run`` does (``load``: a function of the spec giving another load)."""
    path = folder / "alone.toml"
    path.write_text(model(ground))
    spec = load_model_file(path)
    a = spec.analysis
    sol = ul.solve(spec.model, spec.load if load is None else load(spec), dt=a["dt"], t_end=a["t_end"],
                   method=a["method"], rule=a["rule"], lcp=a["lcp"], initial=a["initial"])
    assert sol.success
    return spec, sol


def peaks(spec, sol, quantities=PEAKS) -> dict:
    out = {name: float(np.max(np.abs(spec.structure.node_displacement(sol, node, dof))))
           for name, node, dof in quantities}
    out["uplift"] = float(sol.v.max())
    return out


def row(table, k: int, names) -> dict:
    return {name: float(table[name].values[k]) for name in names}


# ---------------------------------------------------------------------- 1. a pair = the model file
@pytest.mark.parametrize("second", ["y.AT2", "y2.AT2"])
def test_a_pair_equals_the_model_file_with_its_two_ground_motions_bit_for_bit(folder, second):
    """Factor 1 and 2: the peaks of each analysis are those of the model file with the two records as
    [[loads.ground_motion]] along ux and uy (scale 1 and 2), exactly; with components of different dt
    and lengths too (y2.AT2: 0.004 s, 3.2 s against 0.01 s, 12 s), and t_end = "record" is the longer."""
    path = write(folder, f'pairs = [["x.AT2", "{second}"]]', scaling="values = [1.0, 2.0]")
    table = run(path)
    assert list(table["record"].values) == ["x", "x"]
    assert list(table["record_files"].values) == [f"x.AT2; {second}"] * 2
    assert list(table["directions"].values) == ["ux uy"] * 2 and list(table["angle"].values) == [0.0, 0.0]
    names = ["roof_ux", "roof_uy", "roof_rz", "uplift"]
    for k, scale in enumerate((1.0, 2.0)):
        spec, sol = alone(folder, motions(("x.AT2", "ux", scale), (second, "uy", scale)))
        expected = peaks(spec, sol)
        assert row(table, k, names) == expected, (scale, row(table, k, names), expected)
        assert expected["roof_ux"] > 1e-3 and expected["roof_uy"] > 1e-3 and expected["uplift"] > 1e-3
    # one component alone is another analysis: the pair is not a record along x
    _, sol = alone(folder, motions(("x.AT2", "ux", 1.0)))
    assert peaks(spec, sol)["roof_uy"] < 0.5 * float(table["roof_uy"].values[0])
    # t_end = "record": the longer component's duration (x: 12 s, y2: 3.2 s) plus t_after
    study = load_study(write(folder, f'pairs = [["x.AT2", "{second}"]]', analysis="t_end = \"record\"\n"
                             "t_after = 0.5", name="record.toml"))
    assert study.analyses[0].settings["t_end"] == pytest.approx(12.0 + 0.5, rel=1e-12)


def test_a_pair_and_a_vertical_component_equal_the_model_file(folder):
    """Three files along ux, uy, uz of a 3-D frame, and a 2-D frame's pair (horizontal ux and vertical
    uy): the model file with those ground motions, bit for bit."""
    path = write(folder, 'pairs = [["x.AT2", "y.AT2", "z.AT2"]]', scaling="values = [1.5]")
    table = run(path)
    assert table["directions"].values[0] == "ux uy uz"
    spec, sol = alone(folder, motions(("x.AT2", "ux", 1.5), ("y.AT2", "uy", 1.5), ("z.AT2", "uz", 1.5)))
    assert row(table, 0, ["roof_ux", "roof_uy", "roof_rz", "uplift"]) == peaks(spec, sol)
    # a 2-D frame: the tower of test_batch, horizontal x.AT2 and vertical y.AT2
    (folder / "tower.toml").write_text(tower(t_end=1.0))
    tower_quantities = ('\n[[quantities]]\nname = "top"\ntype = "displacement"\nnode = 1\ndof = "ux"\n'
                        '[[quantities]]\nname = "uplift"\ntype = "uplift"\n')
    path = write(folder, 'pairs = [["x.AT2", "y.AT2"]]', scaling="values = [3.0]", model="tower.toml",
                 name="tower-study.toml", quantities=tower_quantities)
    table = run(path, "tower-out")
    spec, sol = alone(folder, motions(("x.AT2", "ux", 3.0), ("y.AT2", "uy", 3.0)),
                      model=lambda ground: tower(ground=ground, t_end=1.0))
    expected = peaks(spec, sol, [("top", 1, "ux")])
    assert row(table, 0, ["top", "uplift"]) == expected and expected["uplift"] > 0


# ---------------------------------------------------------------------- 2. the angle
def test_a_pair_at_90_degrees_is_the_pair_swapped_with_a_sign(folder):
    """angle = 90: component 1 along +y, component 2 along -x: the model file with x.AT2 along uy and
    y.AT2 along ux with scale -1 (the cosine and sine of 90 degrees are taken exact: bit for bit)."""
    path = write(folder, 'pairs = [["x.AT2", "y.AT2"]]\nangle = 90', scaling="values = [2.0]")
    table = run(path)
    assert table["angle"].values[0] == 90.0
    spec, sol = alone(folder, motions(("x.AT2", "uy", 2.0), ("y.AT2", "ux", -2.0)))
    names = ["roof_ux", "roof_uy", "roof_rz", "uplift"]
    got, expected = row(table, 0, names), peaks(spec, sol)
    for name in names:
        assert got[name] == pytest.approx(expected[name], rel=1e-12, abs=0), name
    assert got == expected                                          # in fact bit for bit


def test_a_pair_at_35_degrees_is_the_run_with_the_rotated_influence_vectors(folder):
    """angle = 35: the frame's load with -M r(cos a, sin a, 0) a_1 and -M r(-sin a, cos a, 0) a_2
    (Frame3D.influence of those vectors), solved alone; a sweep of angles gives one record per angle,
    whose samples go to the workers once."""
    from unilateral.batch.inputs import study_inputs

    a = math.radians(35.0)
    c, s = math.cos(a), math.sin(a)
    path = write(folder, 'pairs = [["x.AT2", "y.AT2"]]\nangle = [0.0, 35.0]')
    study = load_study(path)
    assert [r.name for r in study.records] == ["x@0", "x@35"]
    assert len(study_inputs(study.analyses).records) == 1           # one pair of samples for both angles
    table = run(path)

    def rotated(spec):
        st = spec.structure
        terms = tuple((-np.asarray(spec.model.M @ st.influence(d)).ravel(),
                       Tabulated(r.time, r.acceleration * 1.0))
                      for d, r in (((c, s, 0.0), read_record(folder / "x.AT2")),
                                   ((-s, c, 0.0), read_record(folder / "y.AT2"))))
        return LoadHistory(spec.load.constant, tuple(spec.load.terms) + terms)

    spec, sol = alone(folder, "", load=rotated)
    names = ["roof_ux", "roof_uy", "roof_rz", "uplift"]
    got, expected = row(table, 1, names), peaks(spec, sol)
    for name in names:
        assert got[name] == pytest.approx(expected[name], rel=1e-12, abs=0), name
    straight = row(table, 0, names)
    spec, sol = alone(folder, motions(("x.AT2", "ux", 1.0), ("y.AT2", "uy", 1.0)))
    assert straight == peaks(spec, sol)
    assert abs(straight["roof_ux"] - got["roof_ux"]) > 1e-4 * straight["roof_ux"]    # the angle matters


# ---------------------------------------------------------------------- 3. scaling
def test_pga_and_sa_scale_a_pair_by_its_horizontal_components(folder):
    """pga: target / the larger PGA of the two horizontal components; sa: target / the geometric mean
    of their Sa(T1, 5 %) (Sa_GM); the vertical component of a 3-file pair does not count, and the
    angle does not change the factor (the components as recorded)."""
    x, y, z = (read_record(folder / f"{n}.AT2") for n in "xyz")
    pga = max(float(np.abs(x.acceleration).max()), float(np.abs(y.acceleration).max()))
    assert pga == float(np.abs(y.acceleration).max()) > float(np.abs(x.acceleration).max())
    assert float(np.abs(z.acceleration).max()) > pga                # the vertical component is not counted
    study = load_study(write(folder, 'pairs = [["x.AT2", "y.AT2", "z.AT2"], ["x.AT2", "y2.AT2"]]\nangle = [0, 30]',
                             scaling='measure = "pga"\nvalues = [0.3, 0.6]'))
    y2 = read_record(folder / "y2.AT2")
    pga2 = max(float(np.abs(x.acceleration).max()), float(np.abs(y2.acceleration).max()))
    for analysis in study.analyses:
        expected = pga2 if "y2" in analysis.record.name else pga
        assert analysis.scale == pytest.approx(analysis.intensity * G / expected, rel=1e-14)
        assert analysis.record_intensity == pytest.approx(expected / G, rel=1e-14)
    # two pairs that start with the same file: named by their stems joined, and the angle
    assert [r.name for r in study.records] == ["x+y+z@0", "x+y+z@30", "x+y2@0", "x+y2@30"]

    study = load_study(write(folder, 'pairs = [["x.AT2", "y.AT2", "z.AT2"]]',
                             scaling='measure = "sa"\nvalues = [0.5]\nunits = "m/s2"', name="sa.toml"))
    T1 = first_period(load_model_file(folder / "frame.toml").model)
    assert study.variants[0].T1 == pytest.approx(T1, rel=1e-12)
    gm = math.sqrt(response_spectrum(x, T1, 0.05) * response_spectrum(y, T1, 0.05))
    analysis, = study.analyses
    assert analysis.scale == pytest.approx(0.5 / gm, rel=1e-12)
    assert analysis.scale != pytest.approx(0.5 / response_spectrum(x, T1, 0.05), rel=1e-3)


def test_pga_of_a_2d_pair_is_that_of_its_horizontal_component(folder):
    (folder / "tower.toml").write_text(tower())
    study = load_study(write(folder, 'pairs = [["x.AT2", "y.AT2"]]', model="tower.toml",
                             scaling='measure = "pga"\nvalues = [0.4]', quantities=UPLIFT))
    x = read_record(folder / "x.AT2")
    assert study.analyses[0].scale == pytest.approx(0.4 * G / float(np.abs(x.acceleration).max()), rel=1e-14)


# ---------------------------------------------------------------------- 4. bad inputs
BAD = {
    "one file": ('pairs = [["x.AT2"]]', 'records.pairs[0] = ["x.AT2"]: 1 file: a pair holds 2 or 3 files '
                                        "(x, y[, vertical])"),
    "four files": ('pairs = [["x.AT2", "y.AT2", "y2.AT2", "x.AT2"]]',
                   'records.pairs[0] = ["x.AT2", "y.AT2", "y2.AT2", "x.AT2"]: 4 files: a pair holds 2 or 3 files'),
    "missing file": ('pairs = [["x.AT2", "nope.AT2"]]', 'records.pairs[0][1] = "nope.AT2": file not found'),
    "same file": ('pairs = [["x.AT2", "x.AT2"]]', 'records.pairs[0] = ["x.AT2", "x.AT2"]: the same file twice'),
    "directions length": ('pairs = [["x.AT2", "y.AT2"]]\ndirections = ["ux"]',
                          'records.directions = ["ux"]: 1 direction for the 2 files of pairs[0] (one direction '
                          "per file, in the order of the files)"),
    "direction name": ('pairs = [["x.AT2", "y.AT2"]]\ndirections = ["ux", "rz"]',
                       'records.directions[1] = "rz": unknown ground motion direction (valid: ux, uy, uz)'),
    "repeated direction": ('pairs = [["x.AT2", "y.AT2"]]\ndirections = ["uy", "uy"]',
                           'records.directions = ["uy", "uy"]: "uy" twice (each component along a direction of '
                           "its own: ux, uy, uz)"),
    "with files": ('pairs = [["x.AT2", "y.AT2"]]\nfiles = ["x.AT2"]',
                   'records.files = ["x.AT2"]: not with pairs (a study of pairs takes its records from pairs only'),
    "with synthetic": ('pairs = [["x.AT2", "y.AT2"]]\nsynthetic = { seeds = [1] }',
                       "records.synthetic: not with pairs"),
    "with direction": ('pairs = [["x.AT2", "y.AT2"]]\ndirection = "ux"',
                       'records.direction = "ux": not with pairs (give the direction of each component with '
                       "directions = [...])"),
    "angle without pairs": ('files = ["x.AT2"]\ndirection = "ux"\nangle = 30',
                            "records.angle = 30.0: only with pairs"),
    "angle twice": ('pairs = [["x.AT2", "y.AT2"]]\nangle = [0, 0]', "records.angle = [0.0, 0.0]: an angle twice"),
}
BAD_2D = {
    "angle in 2-D": ('pairs = [["x.AT2", "y.AT2"]]\nangle = 30',
                     "records.angle = 30.0: a rotation in plan needs a 3-D frame (model tower.toml is a 2-D frame: "
                     "its pair is horizontal ux and vertical uy; leave angle out)"),
    "uz in 2-D": ('pairs = [["x.AT2", "y.AT2"]]\ndirections = ["ux", "uz"]',
                  'records.directions = ["ux", "uz"]: "uz" is not a ground motion direction of a 2-D frame (model '
                  "tower.toml is a 2-D frame; valid: ux, uy: horizontal and vertical)"),
    "3 files in 2-D": ('pairs = [["x.AT2", "y.AT2", "y2.AT2"]]',
                       'records.pairs[0] = ["x.AT2", "y.AT2", "y2.AT2"]: 3 files, but model tower.toml is a 2-D frame '
                       "with 2 ground motion directions (ux, uy): give 2 files"),
}


@pytest.mark.parametrize("case", list(BAD) + list(BAD_2D))
def test_bad_pairs_are_refused_when_the_study_is_read(folder, case):
    records, expected = BAD.get(case) or BAD_2D[case]
    model = "frame.toml"
    if case in BAD_2D:
        (folder / "tower.toml").write_text(tower())
        model = "tower.toml"
    path = write(folder, records, model=model, quantities=UPLIFT)
    with pytest.raises(ModelFileError) as info:
        load_study(path)
    assert f"{path}: {expected}" in str(info.value)


def test_pairs_for_a_matrix_level_model_are_refused(folder):
    from test_batch_remote import _matrix_study

    path = _matrix_study(folder / "matrix")
    shutil.copy(folder / "x.AT2", folder / "matrix" / "x.AT2")
    shutil.copy(folder / "y.AT2", folder / "matrix" / "y.AT2")
    text = path.read_text().replace('folder = "records"\ninfluence = "r.mtx"', 'pairs = [["x.AT2", "y.AT2"]]')
    path.write_text(text)
    with pytest.raises(ModelFileError) as info:
        load_study(path)
    assert (f'{path}: records.pairs = [["x.AT2", "y.AT2"]]: the matrix-level model matrix.toml has no directions to '
            "apply the components of a pair along (pairs are for frames; give files with influence)") in str(info.value)


# ---------------------------------------------------------------------- resume
def test_a_study_of_pairs_resumes_and_a_changed_angle_is_a_new_analysis(folder):
    path = write(folder, 'pairs = [["x.AT2", "y.AT2"]]', scaling="values = [1.0, 2.0]")
    run(path)
    again = run_study(path, folder / "out", synchronous=True, progress=False, figures=False)
    assert (again.ran, again.skipped) == (0, 2)
    path.write_text(path.read_text().replace('"y.AT2"]]', '"y.AT2"]]\nangle = 10'))
    turned = run_study(path, folder / "out", synchronous=True, progress=False, figures=False)
    assert (turned.ran, turned.skipped) == (2, 0)


# ---------------------------------------------------------------------- 5. remote workers
def test_pairs_reach_workers_that_cannot_read_the_study_folder(folder, hand_started):
    """The components of the pairs go to the workers through Dask (the workers of test_batch_remote's
    ``hand_started`` cluster cannot read the study's folder): the table equals the synchronous one."""
    from test_batch_remote import _hide_from_workers, _same_tables

    path = write(folder, 'pairs = [["x.AT2", "y.AT2"], ["y2.AT2", "z.AT2"]]\nangle = [0, 35]',
                 scaling="values = [1.0, 2.0]")
    _hide_from_workers(hand_started, folder, "x.AT2")
    remote = run_study(path, folder / "remote", scheduler=hand_started, progress=False, figures=False)
    assert remote.counts["ok"] == 8, remote.table["message"].values
    _same_tables(remote.table, run(path, "alone"))
