"""Mass units (``[units] mass = "t"``) and header lines of text records (``skip_header``)."""

import numpy as np
import pytest

from unilateral.loads import read_text_record
from unilateral.loads.records import RecordFormatError, read_record, read_table
from unilateral.loads.units import STANDARD_GRAVITY, mass_factor
from unilateral.modelfile import ModelFileError, load_model_file

FRAME = """
units = {{ length = "m", force = "{force}", time = "s"{mass} }}
nodes = [{{ id = 1, x = 0.0, y = 0.0 }}, {{ id = 2, x = 0.0, y = 3.0 }}]
supports = [{{ node = 1, rz = true }}]
elements = [{{ type = "beam", name = "col", node_i = 1, node_j = 2, E = 3e10, A = 0.09, I = 6.75e-4 }}]
unilateral = [{{ type = "soil", name = "s", node = 2, k = 1e6, direction = "ux" }}]
masses = [{{ node = 2, m = {m}, J = {J} }}]
[analysis]
dt = 0.01
t_end = 0.1
"""


def _frame(tmp_path, name, *, force="N", mass=None, m, J=0.0, extra=""):
    unit = "" if mass is None else f', mass = "{mass}"'
    path = tmp_path / f"{name}.toml"
    path.write_text(FRAME.format(force=force, mass=unit, m=m, J=J) + extra, encoding="utf-8")
    return load_model_file(path)


# ---------------------------------------------------------------------- mass units
def test_mass_factor_values_and_refusals():
    assert mass_factor("kg") == 1.0
    assert mass_factor("t") == 1000.0
    assert mass_factor("Mg") == mass_factor("t")
    assert mass_factor(" t ") == 1000.0
    with pytest.raises(ValueError, match=r"unknown mass unit 'mg'; valid units: kg, t, Mg"):
        mass_factor("mg")                     # a milligram, not a megagram: refused
    with pytest.raises(TypeError, match="mass unit must be a string"):
        mass_factor(1000)


def test_tonnes_in_a_newton_model_are_converted_to_kg(tmp_path):
    in_kg = _frame(tmp_path, "kg", m=60000.0, J=12000.0)                  # N, m, s: masses in kg
    in_t = _frame(tmp_path, "t", mass="t", m=60.0, J=12.0)
    in_mg = _frame(tmp_path, "Mg", mass="Mg", m=60.0, J=12.0)
    M = in_kg.model.M.toarray() if hasattr(in_kg.model.M, "toarray") else np.asarray(in_kg.model.M)
    assert M.max() == 60000.0                                           # the mass is there at all
    for spec in (in_t, in_mg):
        other = spec.model.M.toarray() if hasattr(spec.model.M, "toarray") else np.asarray(spec.model.M)
        np.testing.assert_array_equal(other, M)
    # and gravity acts on the converted mass: the weight is m g in N
    weight = _frame(tmp_path, "tw", mass="t", m=60.0,
                    extra='[loads.gravity]\ng = "standard"\n').load(0.0)
    assert abs(weight.sum()) == pytest.approx(60000.0 * STANDARD_GRAVITY, rel=1e-12)


def test_tonne_is_the_consistent_unit_with_kilonewtons(tmp_path):
    plain = _frame(tmp_path, "plain", force="kN", m=40.0)                # kN s^2/m = t
    tonnes = _frame(tmp_path, "tonnes", force="kN", mass="t", m=40.0)
    kilograms = _frame(tmp_path, "kilograms", force="kN", mass="kg", m=40000.0)
    M = np.asarray(plain.model.M.todense() if hasattr(plain.model.M, "todense") else plain.model.M)
    for spec in (tonnes, kilograms):
        other = spec.model.M.todense() if hasattr(spec.model.M, "todense") else spec.model.M
        np.testing.assert_allclose(np.asarray(other), M, rtol=1e-15, atol=0)


def test_unknown_mass_unit_is_refused_with_the_valid_ones(tmp_path):
    with pytest.raises(ModelFileError, match=r"units\.mass.*'kg', 't' or 'Mg'|units\.mass.*kg.*t.*Mg"):
        _frame(tmp_path, "bad", mass="tonne", m=1.0)


# ---------------------------------------------------------------------- header lines of text records
def _records(tmp_path):
    body = "0.00 0.10\n0.01 -0.20\n0.02 0.05\n0.03 0.00\n"
    plain = tmp_path / "plain.txt"
    plain.write_text(body, encoding="utf-8")
    headed = tmp_path / "headed.txt"
    headed.write_text("Station XYZ, component 090\ntime[s] acc[g]\n" + body, encoding="utf-8")
    return plain, headed


def test_a_header_line_is_refused_with_a_hint_and_skipped_on_request(tmp_path):
    plain, headed = _records(tmp_path)
    with pytest.raises(RecordFormatError, match=r"headed\.txt, line 1: 'Station' is not a number: is "
                                                r"'Station XYZ, component 090' a header\? Skip it with skip_header=1"):
        read_text_record(headed, units="g")
    with pytest.raises(RecordFormatError, match=r"line 2: 'time\[s\]' is not a number: is 'time\[s\] acc\[g\]' "
                                                r"\(after skipping 1 line\(s\)\) a header\? Skip it with skip_header=2"):
        read_text_record(headed, units="g", skip_header=1)
    reference = read_text_record(plain, units="g")
    for skip in (2, None):
        motion = read_text_record(headed, units="g", skip_header=skip)
        np.testing.assert_array_equal(motion.acceleration, reference.acceleration)
        assert motion.dt == reference.dt
        assert motion.header == ("Station XYZ, component 090", "time[s] acc[g]")
    # a numeric line after the data has started is data, not a header: a bad token there stays an error
    assert read_table(headed, skip_header=2).values.shape == (4, 2)


def test_skip_header_is_refused_for_at2_records(tmp_path):
    at2 = tmp_path / "r.AT2"
    at2.write_text("title\nevent\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   2, DT= .0100 SEC\n0.1 0.2\n",
                   encoding="utf-8")
    assert read_record(at2).npts == 2
    with pytest.raises(ValueError, match=r"skip_header is for plain-text records only"):
        read_record(at2, skip_header=1)


GROUND = """
[[loads.ground_motion]]
file = "{file}"
direction = "ux"
units = "g"{skip}
"""


def test_model_file_ground_motion_takes_skip_header(tmp_path):
    plain, headed = _records(tmp_path)
    reference = _frame(tmp_path, "ref", m=1000.0, extra=GROUND.format(file=plain.name, skip=""))
    skipped = _frame(tmp_path, "skip", m=1000.0, extra=GROUND.format(file=headed.name, skip="\nskip_header = 2"))
    t = np.linspace(0.0, 0.03, 7)
    q_ref = np.array([reference.load(x) for x in t])
    assert np.abs(q_ref).max() > 0                                          # the record acts at all
    np.testing.assert_array_equal(np.array([skipped.load(x) for x in t]), q_ref)
    with pytest.raises(ModelFileError, match=r"loads\.ground_motion\[0\]\.file.*Skip it with skip_header=1 "
                                             r"\(in a model file: skip_header = 1\)"):
        _frame(tmp_path, "noskip", m=1000.0, extra=GROUND.format(file=headed.name, skip=""))
    with pytest.raises(ModelFileError, match=r"skip_header.*-1"):
        _frame(tmp_path, "negative", m=1000.0, extra=GROUND.format(file=headed.name, skip="\nskip_header = -1"))


def test_model_file_table_load_takes_skip_header(tmp_path):
    (tmp_path / "table.csv").write_text("# load factor\nt f\n0 0\n0.05 1\n0.1 0\n", encoding="utf-8")
    nodal = ('[[loads.nodal]]\nnode = 2\nux = 10.0\n'
             'time_function = {{ type = "table", file = "table.csv"{skip} }}\n')
    auto = _frame(tmp_path, "auto", m=1.0, extra=nodal.format(skip=""))
    exact = _frame(tmp_path, "exact", m=1.0, extra=nodal.format(skip=", skip_header = 2"))
    for spec in (auto, exact):
        assert spec.load(0.05).sum() == pytest.approx(10.0, rel=1e-14)
        assert spec.load(0.025).sum() == pytest.approx(5.0, rel=1e-14)
    with pytest.raises(ModelFileError, match=r"line 2: 't' is not a number.*skip_header = 2"):
        _frame(tmp_path, "short", m=1.0, extra=nodal.format(skip=", skip_header = 1"))


def test_mass_unit_is_refused_for_matrix_models(tmp_path):
    for name, text in (("M", "1 1 1\n1 1 2.0\n"), ("K", "1 1 1\n1 1 100.0\n"), ("F", "1 1 1\n1 1 100.0\n"),
                       ("H", "1 1 1\n1 1 100.0\n")):
        (tmp_path / f"{name}.mtx").write_text("%%MatrixMarket matrix coordinate real general\n" + text)
    path = tmp_path / "matrices.toml"
    path.write_text('units = { length = "m", force = "N", time = "s", mass = "t" }\n'
                    '[matrices]\nM = "M.mtx"\nK = "K.mtx"\nF = "F.mtx"\nH = "H.mtx"\n'
                    '[analysis]\ndt = 0.01\nt_end = 0.1\n', encoding="utf-8")
    with pytest.raises(ModelFileError, match=r"units\.mass applies to the \[\[masses\]\] of a frame"):
        load_model_file(path)
