"""The study quantity ``type = "footing"``: each measure of each footing equals the run's per-footing
results of the same analysis (:mod:`unilateral.analysis.footing_results`), a measure a footing does
not have is NaN with its reason, and bad footing quantities are refused naming the key."""

import math

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.results import ground_motions_of, structure_results
from unilateral.batch import run_study
from unilateral.batch.footing_quantity import FOOTING_MEASURES
from unilateral.modelfile import load_model_file

from test_batch import ground_motion, record_files, tower

MODEL = """
units = {{ length = "m", force = "kN", time = "s" }}
nodes = [ {{ id = 1, x = 0.0, y = 0.0 }}, {{ id = 2, x = 6.0, y = 0.0 }}, {{ id = 11, x = 0.0, y = 3.0 }},
          {{ id = 12, x = 6.0, y = 3.0 }} ]
elements = [
  {{ type = "beam", name = "c1", node_i = 1, node_j = 11, E = 3e7, A = 0.2, I = 2e-3 }},
  {{ type = "beam", name = "c2", node_i = 2, node_j = 12, E = 3e7, A = 0.2, I = 2e-3 }},
  {{ type = "beam", name = "b", node_i = 11, node_j = 12, E = 3e7, A = 0.2, I = 2e-3 }},
]
masses = [ {{ node = 11, m = 60.0 }}, {{ node = 12, m = 60.0 }} ]
[[foundations]]
name = "A"
node = 1
width = 1.5
length = 1.5
patches = 4
mass = 2.0
J = 0.5
horizontal = "soil"
mu = 0.4
soil = {{ model = "cones", G = 2e4, nu = 0.3, rho = 2.0 }}
[[foundations]]
name = "B"
node = 2
width = 1.5
length = 1.5
patches = 4
mass = 2.0
J = 0.5
horizontal = "soil"
mu = 0.4
soil = {{ model = "cones", G = 2e4, nu = 0.3, rho = 2.0 }}
[loads.gravity]
g = "standard"
{ground}
[analysis]
dt = 0.005
t_end = 2.0
method = "cq"
"""

SCALE = 6.0


def study_text(record, quantities):
    return f"""
[[models]]
file = "model.toml"
[records]
files = ["{record.as_posix()}"]
direction = "ux"
[scaling]
values = [{SCALE!r}]
[analysis]
t_end = 2.0
{quantities}"""


def quantities():
    return "".join(f'[[quantities]]\nname = "{m}"\ntype = "footing"\nmeasure = "{m}"\nover = "each"\n'
                   for m in FOOTING_MEASURES) + '[[quantities]]\nname = "peak_uplift"\ntype = "footing"\n' \
                                                'measure = "uplift"\n'


def test_each_footing_measure_of_a_study_equals_the_runs_footing_results(tmp_path):
    record = record_files(1)[0]
    (tmp_path / "model.toml").write_text(MODEL.format(ground=""))
    (tmp_path / "study.toml").write_text(study_text(record, quantities()))
    table = run_study(tmp_path / "study.toml", tmp_path / "out", synchronous=True, progress=False,
                      figures=False).table
    assert table["status"].values[0] == "ok", table["message"].values[0]
    (tmp_path / "alone.toml").write_text(MODEL.format(ground=ground_motion(record, SCALE)))
    spec = load_model_file(tmp_path / "alone.toml")
    a = spec.analysis
    sol = ul.solve(spec.model, spec.load, dt=a["dt"], t_end=a["t_end"], method=a["method"], rule=a["rule"])
    res = structure_results(spec.structure, spec.model, {"u": sol}, rule=a["rule"],
                            ground_motions=ground_motions_of(spec.structure, spec.load))
    peaks = res["peaks"]["u"]["footings"]
    uy0 = {f: res["variables"]["footing_uy"][1]["u"][0, k] for k, f in enumerate("AB")}
    expected = {}
    for f, p in peaks.items():
        expected |= {f"uplift.{f}": p["uplift"]["max"], f"peak_pressure.{f}": p["peak_pressure"]["max"],
                     f"contact_ratio.{f}": p["contact_ratio"]["min"],
                     f"rotation.{f}": max(abs(p["rz"]["max"]), abs(p["rz"]["min"])),
                     f"residual_rotation.{f}": abs(p["rz"]["final"]),
                     f"settlement.{f}": uy0[f] - p["uy"]["min"], f"residual_settlement.{f}": uy0[f] - p["uy"]["final"],
                     f"slip.{f}": max(abs(p["slip"]["max"]), abs(p["slip"]["min"])),
                     f"residual_slip.{f}": abs(p["slip"]["final"])}
    for column, value in expected.items():
        got = float(table[column].values[0])
        assert got == pytest.approx(value, rel=1e-9, abs=1e-12 * max(1.0, abs(value))), column
    assert float(table["peak_uplift"].values[0]) == max(expected["uplift.A"], expected["uplift.B"])
    assert expected["uplift.A"] + expected["uplift.B"] > 1e-4, "the record must lift a footing"
    assert expected["slip.A"] > 1e-5, "the record must slide the footings"


def test_bad_footing_quantities_are_refused_naming_the_key(tmp_path):
    record = record_files(1)[0]
    (tmp_path / "model.toml").write_text(MODEL.format(ground=""))
    cases = {
        'name = "q"\ntype = "footing"\nmeasure = "uplift"\nelements = ["C"]\n': ["quantities[0].elements[0]",
                                                                                 "no footing", "A, B"],
        'name = "q"\ntype = "footing"\n': ["quantities[0].measure", "missing key"],
        'name = "q"\ntype = "footing"\nmeasure = "tilt"\n': ["measure", "rotation"],
        'name = "q"\ntype = "drift"\npairs = [[12, 2]]\nmeasure = "uplift"\n': ["quantities[0].measure", "not used"],
    }
    for k, (body, words) in enumerate(cases.items()):
        path = tmp_path / f"bad{k}.toml"
        path.write_text(study_text(record, "[[quantities]]\n" + body))
        with pytest.raises(Exception) as info:
            run_study(path, tmp_path / f"out{k}", synchronous=True, progress=False, figures=False)
        for word in words:
            assert word in str(info.value), (body, str(info.value))


def test_a_model_without_footings_is_refused_and_a_missing_measure_is_nan_with_its_reason(tmp_path):
    from unilateral.batch.footing_quantity import _measure

    record = record_files(1)[0]
    (tmp_path / "model.toml").write_text(tower())
    (tmp_path / "study.toml").write_text(study_text(record, '[[quantities]]\nname = "q"\ntype = "footing"\n'
                                                            'measure = "uplift"\n'))
    with pytest.raises(Exception, match=r"quantities\[0\]\.type.*no footings on a soil medium"):
        run_study(tmp_path / "study.toml", tmp_path / "out", synchronous=True, progress=False, figures=False)

    value, why = _measure({"uplift": np.zeros(3), "uy": np.zeros(3)}, "slip", three_d=False)
    assert math.isnan(value) and "does not slide" in why
    value, why = _measure({"uplift": np.zeros(3), "uy": np.zeros(3)}, "rotation", three_d=False)
    assert math.isnan(value) and "span no axis" in why
