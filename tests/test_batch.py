"""Studies (unilateral.batch) without Dask: the study file, key paths, spectra, fragility, runs in process.

The helpers at the top (the tower as a model-file template, study files) are shared with
test_batch_dask.py, which runs studies on a real LocalCluster.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import get_args

import numpy as np
import pytest

import unilateral as ul
from unilateral.batch import fit_fragility, first_period, load_study, response_spectrum, run_study
from unilateral.batch.keypath import KeyPathError, set_key_path
from unilateral.batch.schema import METHOD, study_file_schema
from unilateral.loads import GroundMotion
from unilateral.modelfile import ModelFileError, build_model_spec, load_model_file

ROOT = Path(__file__).parents[1]
RECORDS = ROOT / "examples" / "records" / "ida"

# The tower of Liolios (1990) (examples/liolios1990.toml) without its pulse; {k3}: the stiffness of
# the left soil element, {ground}: a ground-motion table (or nothing), {analysis}: extra settings.
TOWER = """\
units = {{ length = "m", force = "kN", time = "s" }}
nodes = [
    {{ id = 1, x = 0.0, y = 10.0 }},
    {{ id = 2, x = 0.0, y = 0.0 }},
    {{ id = 3, x = -5.0, y = 0.0 }},
    {{ id = 4, x = 5.0, y = 0.0 }},
]
unilateral = [
    {{ type = "soil", name = "soil3", node = 3, k = {k3!r}, c = 10e3 }},
    {{ type = "soil", name = "soil2", node = 2, k = 200e3, c = 10e3 }},
    {{ type = "soil", name = "soil4", node = 4, k = 200e3, c = 10e3 }},
]
supports = [{{ node = 2, ux = true, uy = false }}]
rigid_links = [{{ master = 2, slave = 3 }}, {{ master = 2, slave = 4 }}]
elements = [{{ type = "beam", name = "column", node_i = 2, node_j = 1, E = 1.0, A = 1e12, I = 1e9 }}]
masses = [{{ node = 1, m = 40.0 }}]

[loads.gravity]
g = 10.0

{ground}

[analysis]
dt = {dt!r}
t_end = {t_end!r}
method = "{method}"
bilateral_reference = false
"""


def tower(k3=200e3, ground="", dt=2e-3, t_end=2.0, method="modal") -> str:
    return TOWER.format(k3=float(k3), ground=ground, dt=float(dt), t_end=float(t_end), method=method)


def ground_motion(file, scale) -> str:
    return f'[[loads.ground_motion]]\nfile = "{Path(file).as_posix()}"\ndirection = "ux"\nscale = {float(scale)!r}\n'


QUANTITIES = """
[[quantities]]
name = "uplift"
type = "uplift"

[[quantities]]
name = "uplift_each"
type = "uplift"
over = "each"

[[quantities]]
name = "force"
type = "contact_force"

[[quantities]]
name = "top"
type = "displacement"
node = 1
dof = "ux"

[[quantities]]
name = "drift"
type = "drift"
pairs = [[1, 2]]

[[quantities]]
name = "residual"
type = "residual"
node = 3
dof = "uy"

[[quantities]]
name = "energy_error"
type = "energy_error"
"""


def write_study(folder: Path, body: str, *, model: str | None = None, name="study.toml") -> Path:
    """``folder/tower.toml`` (the model) and ``folder/<name>`` (the study: ``body`` + quantities)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "tower.toml").write_text(model if model is not None else tower())
    path = folder / name
    path.write_text(body + QUANTITIES)
    return path


def record_files(count):
    return sorted(RECORDS.glob("*.AT2"))[:count]


# ---------------------------------------------------------------------- model files from parsed data
def test_build_model_spec_of_parsed_data_equals_load_model_file():
    import tomllib

    path = ROOT / "examples" / "liolios1990.toml"
    a = load_model_file(path)
    b = build_model_spec(tomllib.loads(path.read_text()), path)
    assert (a.model.K != b.model.K).nnz == 0 and (a.model.M != b.model.M).nnz == 0
    t = np.linspace(0, 1, 11)
    assert np.array_equal(a.load.sample(t), b.load.sample(t))
    assert a.analysis == b.analysis and a.units == b.units
    with pytest.raises(ModelFileError, match=r"^x\.toml: analysis: missing section"):
        build_model_spec({"units": {"length": "m", "force": "kN", "time": "s"}}, "x.toml")


# ---------------------------------------------------------------------- key paths
def test_key_paths_select_by_name_id_node_and_index():
    data = {"nodes": [{"id": 1}, {"id": "top"}], "masses": [{"node": 1, "m": 1.0}, {"node": 2, "m": 2.0}],
            "elements": [{"name": "col", "E": 1.0}], "unilateral": [{"name": "soil3", "k": 1.0}],
            "analysis": {"dt": 0.1}}
    set_key_path(data, "unilateral.soil3.k", 5.0)
    set_key_path(data, "elements.soil3.c", 7.0)             # names are unique over both sections
    set_key_path(data, "masses[1].m", 3.0)
    set_key_path(data, "masses.1.J", 4.0)                   # the mass at node 1
    set_key_path(data, "nodes.top.x", 9.0)
    set_key_path(data, "analysis.dt", 0.5)
    set_key_path(data, "damping.rayleigh.zeta", 0.05)       # tables on the way are created
    set_key_path(data, "loads.nodal", [])
    assert data["unilateral"][0] == {"name": "soil3", "k": 5.0, "c": 7.0}
    assert data["masses"] == [{"node": 1, "m": 1.0, "J": 4.0}, {"node": 2, "m": 3.0}]
    assert data["nodes"][1]["x"] == 9.0 and data["analysis"]["dt"] == 0.5
    assert data["damping"] == {"rayleigh": {"zeta": 0.05}} and data["loads"] == {"nodal": []}
    with pytest.raises(KeyPathError, match=r'no element named "soil9" .*did you mean "soil3"\?'):
        set_key_path(data, "unilateral.soil9.k", 1.0)
    with pytest.raises(KeyPathError, match=r"masses\[5\]: no such entry \(the array has 2 entries\)"):
        set_key_path(data, "masses[5].m", 1.0)
    with pytest.raises(KeyPathError, match=r"analysis.dt is a value \(0.5\), not a table"):
        set_key_path(data, "analysis.dt.x", 1.0)


# ---------------------------------------------------------------------- spectra and periods
def test_spectrum_is_exact_for_a_piecewise_linear_record():
    """A ramp a(t) = c t is piecewise linear: Sa equals the closed-form response at the samples."""
    c, dt, n = 3.0, 0.02, 301
    record = GroundMotion(dt, c * np.arange(n) * dt)
    t = np.arange(n) * dt
    for T, zeta in ((0.3, 0.05), (1.7, 0.02), (0.05, 0.2)):
        w = 2 * np.pi / T
        wd = w * np.sqrt(1 - zeta**2)
        A = -2 * zeta * c / w**3
        B = (c / w**2 + zeta * w * A) / wd
        u = -c / w**2 * (t - 2 * zeta / w) + np.exp(-zeta * w * t) * (A * np.cos(wd * t) + B * np.sin(wd * t))
        exact = w**2 * np.abs(u).max()
        assert response_spectrum(record, T, zeta) == pytest.approx(exact, rel=1e-11)
    Sa = response_spectrum(record, [0.3, 1.7])
    assert Sa.shape == (2,) and Sa[0] == response_spectrum(record, 0.3)


def test_first_period_with_a_massless_dof_is_that_of_the_springs_in_series():
    m, k1, k2 = 2.0, 300.0, 600.0
    K = [[k1, -k1], [-k1, k1 + k2]]
    model = ul.Model(M=[[m, 0.0], [0.0, 0.0]], K=K, F=[[0.0], [k2]], H=[[k2]])
    assert first_period(model) == pytest.approx(2 * np.pi * np.sqrt(m * (k1 + k2) / (k1 * k2)), rel=1e-12)


# ---------------------------------------------------------------------- fragility
def test_fragility_mle_recovers_the_parameters_and_maximises_the_likelihood():
    from scipy.stats import binom, norm

    levels = np.array([0.2, 0.4, 0.6, 0.8, 1.0, 1.4, 2.0])
    n = np.full(levels.size, 4000)
    z = np.round(n * norm.cdf(np.log(levels / 0.7) / 0.45)).astype(int)
    fit = fit_fragility(levels, n, z)
    assert fit.theta == pytest.approx(0.7, rel=2e-3) and fit.beta == pytest.approx(0.45, rel=5e-3)
    # small samples: the fit is the maximum of the binomial likelihood over a fine grid
    n = np.array([10, 10, 10, 10, 10])
    z = np.array([0, 2, 5, 6, 9])
    fit = fit_fragility([0.5, 1.0, 1.5, 2.0, 2.5], n, z)
    thetas, betas = np.meshgrid(np.linspace(1.0, 2.2, 121), np.linspace(0.2, 1.2, 101))
    x = np.array([0.5, 1.0, 1.5, 2.0, 2.5])[:, None, None]
    ll = binom.logpmf(z[:, None, None], n[:, None, None], norm.cdf(np.log(x / thetas) / betas)).sum(axis=0)
    i = np.unravel_index(np.argmax(ll), ll.shape)
    assert fit.theta == pytest.approx(thetas[i], abs=0.02) and fit.beta == pytest.approx(betas[i], abs=0.02)
    lnL = binom.logpmf(z, n, fit(np.array([0.5, 1.0, 1.5, 2.0, 2.5]))).sum()
    assert lnL >= ll.max() - 1e-9
    none = fit_fragility([1.0, 2.0], [10, 10], [0, 0])
    assert math.isnan(none.theta) and "never exceeded" in none.note


# ---------------------------------------------------------------------- study files
def _errors(tmp_path, body, model=None):
    path = write_study(tmp_path, body, model=model)
    with pytest.raises(ModelFileError) as info:
        load_study(path)
    return str(info.value).replace(str(path), "study.toml").splitlines()


def test_study_file_errors_name_the_key_path_the_value_and_what_is_valid(tmp_path):
    lines = _errors(tmp_path, """
[[models]]
file = "tower.toml"
[records]
folder = "nowhere"
direction = "uz"
[scaling]
measure = "sax"
values = [1.0, -2.0]
[analysis]
method = "modall"
dt = "0.01"
timout = 5
""")
    assert lines == [
        'study.toml: records.direction = "uz": unknown ground motion direction (valid: ux, uy)',
        'study.toml: scaling.measure = "sax": unknown intensity measure (valid: factor, pga, sa); did you mean "sa"?',
        "study.toml: scaling.values[1] = -2.0: must be > 0",
        'study.toml: analysis.dt = "0.01": expected a number',
        f'study.toml: analysis.method = "modall": unknown method (valid: {", ".join(get_args(METHOD))}); '
        'did you mean "modal"?',
        'study.toml: analysis.timout: unknown key (did you mean "timeout"? valid keys: dt, t_end, t_after, '
        "method, rule, lcp, lcp_options, initial, timeout)",
    ]
    lines = _errors(tmp_path, """
[[models]]
file = "tower.toml"
set = { "unilateral.soil9.c" = 400.0 }
[[models]]
file = "missing.toml"
[records]
files = ["nothing.AT2"]
direction = "ux"
""")
    assert lines[0] == 'study.toml: models[1].file = "missing.toml": file not found (looked for ' \
                       f'{tmp_path / "missing.toml"})'
    assert lines[1].startswith('study.toml: records.files[0] = "nothing.AT2": file not found')
    lines = _errors(tmp_path, """
[[models]]
file = "tower.toml"
set = { "unilateral.soil9.c" = 400.0 }
[records]
synthetic = { seeds = [1] }
direction = "ux"
[[parameters]]
key = "unilateral.soil3.k"
values = [1e5, -3.0]
""")
    assert lines == ['study.toml: models[0].set."unilateral.soil9.c": unilateral: no element named "soil9" '
                     '(names: column, soil3, soil2, soil4); did you mean "soil4"?']
    lines = _errors(tmp_path, """
[[models]]
file = "tower.toml"
[records]
synthetic = { seeds = [1] }
direction = "ux"
[[parameters]]
key = "unilateral.soil3.k"
values = [1e5, -3.0]
""")
    assert lines == ['study.toml: parameters[0].values[1] = -3.0: models[0] (tower.toml): unilateral[0].k = -3.0: '
                     "must be > 0"]
    path = write_study(tmp_path, '[[models]]\nfile = "tower.toml"\n[records]\nsynthetic = { seeds = [1] }\n')
    with pytest.raises(ModelFileError, match=r"records.direction: missing key \(model tower.toml has no ground "
                                             r'motion to take the direction from; give direction = "ux" or "uy"\)'):
        load_study(path)


def test_study_file_errors_of_quantities_and_limit_states(tmp_path):
    path = tmp_path / "q.toml"
    (tmp_path / "tower.toml").write_text(tower())
    path.write_text("""
[[models]]
file = "tower.toml"
[records]
synthetic = { seeds = [1] }
direction = "ux"
[scaling]
values = [1.0]
[[quantities]]
name = "uplift"
type = "uplift"
elements = ["soil9"]
[[quantities]]
name = "d"
type = "displacement"
node = 17
dof = "uz"
[[quantities]]
name = "r"
type = "residual"
[[limit_states]]
name = "x"
quantity = "upflit"
threshold = 0.01
""")
    with pytest.raises(ModelFileError) as info:
        load_study(path)
    assert str(info.value).replace(str(path), "q.toml").splitlines() == [
        "q.toml: quantities[2].dof: missing key (a residual quantity needs dof, and node for a frame)"]
    path.write_text(path.read_text().replace('type = "residual"', 'type = "residual"\nnode = 3\ndof = "uy"'))
    with pytest.raises(ModelFileError) as info:
        load_study(path)
    assert str(info.value).replace(str(path), "q.toml").splitlines() == [
        'q.toml: quantities[0].elements[0] = "soil9": no unilateral element "soil9" in model tower (tower.toml) '
        '(valid: soil3, soil2, soil4); did you mean "soil4"?',
        "q.toml: quantities[1].node = 17: no node 17 in model tower (tower.toml) (nodes are 1..4)",
        'q.toml: quantities[1].dof = "uz": unknown DOF of a frame node (valid: ux, uy, rz)',
        'q.toml: limit_states[0].quantity = "upflit": no such quantity (valid: uplift, d, r); did you mean "uplift"?',
    ]
    (tmp_path / "broken.toml").write_text("[[models]]\nfile = 3\n")
    with pytest.raises(ModelFileError) as info:
        load_study(tmp_path / "broken.toml")
    assert str(info.value).endswith("broken.toml: models[0].file = 3: expected a string\n"
                                    f"{tmp_path / 'broken.toml'}: quantities: missing section (declare e.g. "
                                    '[[quantities]] name = "uplift", type = "uplift")')


def test_study_schema_in_docs_is_up_to_date():
    stored = json.loads((ROOT / "docs" / "study-file.schema.json").read_text())
    assert stored == study_file_schema()


def test_importing_unilateral_and_reading_a_study_does_not_import_dask():
    code = ("import sys, unilateral, unilateral.batch\n"
            "from unilateral.batch import load_study\n"
            f"load_study({str(ROOT / 'examples' / 'ida.toml')!r})\n"
            "assert 'dask' not in sys.modules and 'distributed' not in sys.modules, 'dask imported'\n")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_the_ida_example_has_ten_records_at_ten_intensities():
    study = load_study(ROOT / "examples" / "ida.toml")
    assert len(study.records) >= 10 and len(study.document.scaling.values) >= 10
    assert len(study.analyses) == len(study.records) * len(study.document.scaling.values)
    assert study.variants[0].T1 == pytest.approx(0.1277, abs=1e-4)
    # every record is scaled so that its Sa(T1, 5%) is the level
    a = study.analyses[13]
    Sa = response_spectrum(a.record.motion.scaled(a.scale), study.variants[0].T1, 0.05) / 9.80665
    assert Sa == pytest.approx(a.intensity, rel=1e-12)
    assert len({a.key for a in study.analyses}) == len(study.analyses)


# ---------------------------------------------------------------------- runs in this process
def test_synchronous_study_records_failures_and_resumes(tmp_path):
    """pgs with one sweep fails once the soil lifts off; a broken record is an error; the rest finish."""
    records = record_files(2)
    (tmp_path / "broken.txt").write_text("0.0 1.0\n0.1 oops\n")
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = ["{records[0].as_posix()}", "{records[1].as_posix()}", "broken.txt"]
direction = "ux"
units = "g"
[scaling]
values = [0.1, 8.0]
[analysis]
t_end = 4.0
method = "cq"
lcp = "pgs"
lcp_options = {{ max_iter = 1 }}
""")
    result = run_study(path, tmp_path / "out", synchronous=True, progress=False)
    table = result.table
    status = dict(zip(zip(table["record"].values, table["intensity"].values), table["status"].values))
    assert status[(records[0].stem, 0.1)] == "ok" and status[(records[1].stem, 0.1)] == "ok"
    assert status[(records[0].stem, 8.0)] == "failed" and status[(records[1].stem, 8.0)] == "failed"
    assert status[("broken", 0.1)] == "error" == status[("broken", 8.0)]
    messages = dict(zip(table["status"].values, table["message"].values))
    assert "PGS did not converge" in messages["failed"] and "RecordFormatError" in messages["error"]
    assert np.isnan(table["uplift"].values[table["status"].values == "failed"]).all()
    assert np.isfinite(table["energy_error"].values[table["status"].values == "ok"]).all()
    files = sorted((tmp_path / "out" / "results").glob("*.json"))
    assert len(files) == 6
    before = {p.name: p.read_text() for p in files}
    again = run_study(path, tmp_path / "out", synchronous=True, progress=False)
    assert again.ran == 0 and again.skipped == 6
    assert {p.name: p.read_text() for p in (tmp_path / "out" / "results").glob("*.json")} == before
    retried = run_study(path, tmp_path / "out", synchronous=True, progress=False, retry_failed=True, figures=False)
    assert retried.ran == 4 and retried.counts == result.counts


def test_each_model_variant_is_built_once_per_process(tmp_path, monkeypatch):
    """Analyses of one variant (other records, other scale factors) reuse its build: 2 variants x
    2 records x 2 levels build 2 models (counted by the calls of build_model_spec), not 8."""
    from unilateral import modelfile
    from unilateral.batch.worker import clear_caches

    records = record_files(2)
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = ["{records[0].as_posix()}", "{records[1].as_posix()}"]
direction = "ux"
[scaling]
values = [0.5, 1.0]
[[parameters]]
key = "unilateral.soil3.k"
values = [150e3, 200e3]
[analysis]
t_end = 0.5
""")
    study = load_study(path)                                    # builds every variant here: not counted
    clear_caches()
    built, build = [], modelfile.build_model_spec
    monkeypatch.setattr(modelfile, "build_model_spec", lambda data, source: built.append(data) or build(data, source))
    result = run_study(study, tmp_path / "out", synchronous=True, progress=False, figures=False)
    assert result.counts["ok"] == 8
    assert sorted(data["unilateral"][0]["k"] for data in built) == [150e3, 200e3]
    caches = [json.loads(p.read_text())["cache"]["model"] for p in (tmp_path / "out" / "results").glob("*.json")]
    assert sorted(caches) == ["hit"] * 6 + ["miss"] * 2


def test_a_model_file_changed_after_the_study_was_read_fails_its_analyses(tmp_path):
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = ["{record_files(1)[0].as_posix()}"]
direction = "ux"
[analysis]
t_end = 0.5
""")
    study = load_study(path)
    (tmp_path / "tower.toml").write_text(tower(k3=1e5))
    result = run_study(study, tmp_path / "out", synchronous=True, progress=False, figures=False)
    assert list(result.table["status"].values) == ["error"]
    assert "has changed since the study was read" in result.table["message"].values[0]


def test_a_timed_out_analysis_is_recorded(tmp_path):
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = ["{record_files(1)[0].as_posix()}"]
direction = "ux"
[analysis]
method = "direct"
lcp = "lemke"
t_end = 6.0
timeout = 0.001
""")                # Lemke: the Python march, about 0.3 s even with numba loaded: 300 times the limit, so
                    # the verdict does not depend on the machine (a limit of 0.05 s was 6 times)
    result = run_study(path, tmp_path / "out", synchronous=True, progress=False, figures=False)
    assert list(result.table["status"].values) == ["timeout"]
    assert "stopped after 0.001 s" in result.table["message"].values[0]


def study_against_structure_results(folder: Path, model, scale=3.0):
    """A one-record study of ``model(ground)`` (model-file text; ``ground``: a ground-motion section
    or "") asking for base_shear and energy_error, and the same analysis run alone.

    Returns
    -------
    (peaks, sol, results): the study's row (dict), the lone run's Solution and its
    ``analysis.structure_results``
    """
    from unilateral.analysis.results import ground_motions_of, structure_results

    record = record_files(1)[0]
    (folder / "model.toml").write_text(model(""))
    path = folder / "study.toml"
    path.write_text(f"""
[[models]]
file = "model.toml"
[records]
files = ["{record.as_posix()}"]
direction = "ux"
[scaling]
values = [{scale!r}]
[analysis]
t_end = 1.0
[[quantities]]
name = "base_shear"
type = "base_shear"
[[quantities]]
name = "energy_error"
type = "energy_error"
""")
    table = run_study(path, folder / "out", synchronous=True, progress=False, figures=False).table
    assert table["status"].values[0] == "ok", table["message"].values[0]
    alone = folder / "alone.toml"
    alone.write_text(model(ground_motion(record, scale)))
    spec = load_model_file(alone)
    a = spec.analysis
    sol = ul.solve(spec.model, spec.load, dt=a["dt"], t_end=a["t_end"], method=a["method"], rule=a["rule"])
    samples = spec.load.grid_samples(a["dt"], len(sol.t) - 1)[0]
    res = structure_results(spec.structure, spec.model, {"u": sol}, rule=a["rule"], load_samples=samples,
                            ground_motions=ground_motions_of(spec.structure, spec.load))
    peaks = {name: float(table[name].values[0]) for name in ("base_shear", "energy_error")}
    return peaks, sol, res


def test_base_shear_and_energy_error_of_a_study_equal_the_frame_results_of_the_same_run(tmp_path):
    """The study's peak base shear and energy error are those of analysis.structure_results."""
    peaks, sol, res = study_against_structure_results(tmp_path, lambda ground: tower(ground=ground, t_end=1.0))
    shear = res["variables"]["base_shear"][1]["u"]
    assert sol.v.max() > 0                                    # it lifts off
    assert peaks["base_shear"] == pytest.approx(np.abs(shear).max(), rel=1e-12)
    assert np.abs(shear).max() > 10.0                          # kN: a real response, not a zero column
    error = res["peaks"]["u"]["energy"]["max_relative_error"]
    assert peaks["energy_error"] == pytest.approx(error, rel=1e-12)
    assert 0 < error < 0.05


@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_frame_results_equal_the_full_reactions_and_energy_balance(rule):
    """The worker's base shear and energy error (operators of the variant, no element forces)
    against ``base_forces(reactions(...))`` and ``energy_balance`` of the full histories, on a frame
    with soil springs (Kelvin), a spring and a dashpot to the ground and Rayleigh damping, under a
    load history (its grid factors) and under the same load as an array of samples."""
    from test_structure_results import portal

    from unilateral.analysis.energy import energy_balance
    from unilateral.batch.worker import FrameOperators, FrameResults
    from unilateral.loads import LoadHistory
    from unilateral.structure import forces as F

    st = portal()
    dt, N = 1e-3, 400
    load = LoadHistory(st.gravity(10.0), [(st.nodal_load(2, ux=1.0), lambda t: 300.0 * np.sin(20.0 * t))])
    sol = ul.solve(st.to_model(), load, dt=dt, t_end=N * dt, method="cq", rule=rule)
    assert sol.stats["contact_changes"] > 0
    samples = load.grid_samples(dt, N)[0]
    h = F.Histories.from_solution(st, sol, rule, load0=samples[0])
    shear = np.abs(F.base_forces(st, F.reactions(st, h))["base_shear"]).max()
    error = energy_balance(st, h, samples, rule=rule)["max_relative_error"]       # paired as the rule: exact
    operators = FrameOperators(st)
    for q in (load, samples):
        frame = FrameResults(sol, operators, q, rule)
        assert frame.peak_base_shear() == pytest.approx(shear, rel=1e-12)
        assert frame.energy_error() == pytest.approx(error, rel=0, abs=1e-12)
    assert shear > 10.0 and error < 1e-10


def test_base_shear_and_energy_error_of_a_footing_on_a_soil_medium_equal_the_frame_results(tmp_path):
    """A model with a [foundation]: the frame alone loaded by the contact forces too, as
    analysis.structure_results has it (the analysis used to fail on the soil's extra unknowns)."""
    model = """
units = { length = "m", force = "kN", time = "s" }
nodes = [{ id = 1, x = 0.0, y = 10.0 }, { id = 2, x = 0.0, y = 0.0 }]
elements = [{ type = "beam", name = "column", node_i = 2, node_j = 1, E = 1.0, A = 1e12, I = 1e9 }]
masses = [{ node = 1, m = 40.0 }]
[foundation]
node = 2
width = 10.0
length = 10.0
soil = { model = "winkler-kelvin", k = 200e3, c = 10e3 }
[loads]
gravity = { g = 10.0 }
"""
    analysis = '[analysis]\ndt = 0.002\nt_end = 1.0\nmethod = "cq"\n'
    peaks, sol, res = study_against_structure_results(tmp_path, lambda ground: model + ground + analysis)
    shear = np.abs(res["variables"]["base_shear"][1]["u"]).max()
    assert sol.v.max() > 0 and shear > 10.0                    # it rocks
    assert peaks["base_shear"] == pytest.approx(shear, rel=1e-12)
    error = res["peaks"]["u"]["energy"]["max_relative_error"]
    assert peaks["energy_error"] == pytest.approx(error, rel=1e-9)


def test_plain_text_records_with_a_header_line_are_read_with_skip_header(tmp_path):
    """[records] skip_header reaches the reader; without it the header is refused with the hint."""
    t = np.arange(0.0, 2.0, 0.01)
    lines = "\n".join(f"{a:.6f}" for a in 0.2 * np.sin(2 * np.pi * 2.0 * t))
    (tmp_path / "rec.txt").write_text("acceleration [g]\n" + lines + "\n")
    body = """
[[models]]
file = "tower.toml"
[records]
files = ["rec.txt"]
units = "g"
dt = 0.01
direction = "ux"
{skip}
[scaling]
values = [1.0]
[analysis]
t_end = 2.0
"""
    path = write_study(tmp_path, body.format(skip="skip_header = 1"))
    table = run_study(path, tmp_path / "out", synchronous=True, progress=False, figures=False).table
    assert table["status"].values[0] == "ok", table["message"].values[0]
    assert table["top"].values[0] > 0
    bad = write_study(tmp_path, body.format(skip=""), name="bad.toml")
    table = run_study(bad, tmp_path / "out_bad", synchronous=True, progress=False, figures=False).table
    assert table["status"].values[0] == "error" and "skip_header" in table["message"].values[0]


def test_a_study_of_a_3d_frame(tmp_path):
    """A 3-D model file in a study: uplift, a roof displacement along y, the storey drift ratio between
    two floors (elevations along z), the base shear as the peak horizontal resultant of
    ``forces3d.base_forces`` and the energy error, both equal to the run's."""
    import shutil

    from unilateral.batch.worker import FrameOperators, FrameResults
    from unilateral.structure import forces3d as F3

    shutil.copy(ROOT / "examples" / "building3d.toml", tmp_path / "building3d.toml")
    (tmp_path / "records" / "ida").mkdir(parents=True)
    for record in record_files(2):
        shutil.copy(record, tmp_path / "records" / "ida" / record.name)
    record = record_files(1)[0]
    study = tmp_path / "study.toml"
    study.write_text(f"""
[[models]]
file = "building3d.toml"
[records]
files = ["{record.as_posix()}"]
direction = "ux"
[scaling]
values = [1.0]
[analysis]
t_end = 0.6
[[quantities]]
name = "uplift"
type = "uplift"
[[quantities]]
name = "roof_uy"
type = "displacement"
node = 1003
dof = "uy"
[[quantities]]
name = "drift"
type = "drift"
pairs = [[1003, 1002]]
[[quantities]]
name = "shear"
type = "base_shear"
[[quantities]]
name = "energy"
type = "energy_error"
""")
    result = run_study(study, tmp_path / "out", synchronous=True, progress=False, figures=False)
    table = result.table
    assert list(table["status"].values) == ["ok"], table["message"].values
    assert float(table["shear"].values[0]) > 0 and float(table["drift"].values[0]) > 0
    assert 0 < float(table["energy"].values[0]) < 0.1
    # the base shear of the study is the peak horizontal resultant of the 3-D base forces
    spec = load_model_file(tmp_path / "building3d.toml")
    st = spec.structure
    sol = ul.solve(spec.model, spec.load, dt=spec.analysis["dt"], t_end=0.2, method="cq")
    h = F3.histories(st, sol, "bdf2", load0=spec.load.sample(sol.t[:1])[0])
    base = F3.base_forces(st, F3.reactions(st, h, sol), F3.base_point(st))
    frame = FrameResults(sol, FrameOperators(st), spec.load, "bdf2")
    assert frame.three_d and frame.peak_base_shear() == pytest.approx(np.abs(np.hypot(base["Fx"], base["Fy"])).max(),
                                                                      rel=1e-12)
    # the energy error of the study is the run's (results.nc, summary.json) to round-off
    from unilateral.analysis.outputs import _structure_results_3d

    run = _structure_results_3d(st, spec.model, {"c": sol}, load=spec.load, units=spec.units, rule="bdf2", point=None)
    assert frame.energy_error() == pytest.approx(run["peaks"]["c"]["energy"]["max_relative_error"], rel=1e-12)
