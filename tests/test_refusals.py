"""No traceback, no hang, no silent accept: inputs that overflow, allocate too much or would run for
ever are refused with a message naming the file, the key (or argument), the value and what is valid."""

from __future__ import annotations

import re
from types import SimpleNamespace

import numpy as np
import pytest
from click.testing import CliRunner

from test_batch import record_files, write_study
from test_foundation_frame import MODEL
from test_modelfile import matrix_document, write, write_matrices
from unilateral.batch import load_study
from unilateral.batch.cli import batch
from unilateral.batch.worker import _non_finite
from unilateral.modelfile import ModelFileError, load_model_file
from unilateral.structure import liolios1990
from unilateral.structure.foundation import to_foundation_model


def model_error(path) -> str:
    with pytest.raises(ModelFileError) as info:
        load_model_file(path)
    return str(info.value)


def footing(tmp_path, soil='{ model = "cones", Vs = 97.0, nu = 0.3, rho = 2.0 }', replace=("", "")):
    path = tmp_path / "footing.toml"
    path.write_text(MODEL.format(soil=soil).replace(*replace))
    return path


# ---------------------------------------------------------------------- model files
@pytest.mark.parametrize("soil, expected", [
    ('{ model = "halfspace", Vs = 1e308, nu = 0.3, rho = 2.0 }',
     "footing.toml: foundation.soil.Vs = 1e+308: with rho = 2.0 and the footing's area A = 100 gives the shear "
     "modulus G = rho Vs^2 = inf; give values for which it is a finite number > 0"),
    ('{ model = "halfspace", Vs = 1e-300, nu = 0.3, rho = 2.0 }', "foundation.soil.Vs = 1e-300: with rho = 2.0"),
    ('{ model = "cones", G = 1e308, nu = 0.3, rho = 2.0 }',
     "foundation.soil.G = 1e+308: with rho = 2.0 and the footing's area A = 100 gives the footing's stiffness "
     "G sqrt(A) = inf"),
])
def test_soil_moduli_that_overflow_are_refused_with_the_key(tmp_path, soil, expected):
    assert expected in model_error(footing(tmp_path, soil))


def test_an_integer_too_long_to_read_names_the_file_and_the_key(tmp_path):
    path = footing(tmp_path, replace=("length = 10.0", "length = " + "9" * 5000))
    assert model_error(path) == (f"{path}: foundation.length = 99999999999999999999... (5000 digits): an integer "
                                 "too large to be read (at most 4300 digits; a model value is at most about 1.8e308)")


def test_an_integer_too_long_in_an_array_of_tables_names_its_index(tmp_path):
    long = f"masses = [{{ node = 1, m = -{'1' * 4400} }}]"
    path = footing(tmp_path, replace=("masses = [{ node = 1, m = 40.0 }]", long))
    expected = "footing.toml: masses[0].m = -1111111111111111111... (4400 digits): an integer too large"
    assert expected in model_error(path)


def header_only(path, header: str) -> str:
    path.write_text(f"%%MatrixMarket matrix {header}\n")
    return path.name


@pytest.mark.parametrize("header, expected", [
    ("array real general\n100000 100000",
     'matrices.C = "C.mtx": a dense 100000 x 100000 matrix (74.5 GiB): more than the 2 GiB read'),
    ("coordinate real general\n2000000000 2000000000 1\n1 1 1.0",
     'matrices.C = "C.mtx": a 2000000000 x 2000000000 matrix: more than the 10,000,000 rows or columns read'),
    ("array complex general\n5 5", 'matrices.C = "C.mtx": a array complex matrix: the matrices of a model are real'),
    ("coordinate complex general\n5 5 1\n1 1 1.0 2.0",
     'matrices.C = "C.mtx": a coordinate complex matrix: the matrices of a model are real'),
    ("coordinate pattern general\n5 5 1\n1 1",
     'matrices.C = "C.mtx": a coordinate pattern matrix: the matrices of a model are real (write the file with '
     'field "real" or "integer", with every value)'),
])
def test_matrix_market_files_are_refused_from_their_header(tmp_path, header, expected):
    write_matrices(tmp_path, liolios1990()[0].to_model())
    header_only(tmp_path / "C.mtx", header)
    message = model_error(write(tmp_path, matrix_document(C="C.mtx")))
    assert message.startswith(f"{tmp_path / 'model.toml'}: ") and expected in message


def test_many_nodal_loads_are_one_term_per_time_function(tmp_path):
    pulse = '{ type = "rectangular", t_end = 0.1 }'
    entries = "".join(f"\n[[loads.nodal]]\nnode = 1\nux = {k % 7 + 1.0!r}\n"
                      + ("" if k % 2 else f"time_function = {pulse}\n") for k in range(2000))
    path = footing(tmp_path, replace=('nodal = [{ node = 1, ux = 200.0, time_function = '
                                      '{ type = "rectangular", t_end = 0.1 } }]', ""))
    path.write_text(path.read_text() + entries)
    spec = load_model_file(path)
    assert len(spec.load.terms) == 2                    # constant and rectangular
    one = spec.structure.nodal_load(1, ux=1.0)
    total = sum(k % 7 + 1.0 for k in range(2000))
    np.testing.assert_allclose(spec.load(0.05) - spec.load.constant, total * one, rtol=1e-12)
    np.testing.assert_allclose(spec.load(0.2) - spec.load.constant,
                               sum(k % 7 + 1.0 for k in range(1, 2000, 2)) * one, rtol=1e-12)


def test_a_rigid_footing_on_many_patches_sweeps_the_structure_twice_and_keeps_its_weights(tmp_path):
    spec = load_model_file(footing(tmp_path, replace=("patches = 3", "patches = 40")))
    fm = to_foundation_model(spec.structure)
    assert fm.impulse_basis().shape == (40, 2)
    W = fm.weights(60, 0.004, "bdf2")
    fm.impulse_basis = lambda: np.eye(fm.m)                        # one sweep per patch, as before
    fm.soil.__dict__.pop("_weights_cache", None)
    fm.soil._diagonal = None                                       # the dense m x m soil weights
    np.testing.assert_allclose(W, fm.weights(60, 0.004, "bdf2"), rtol=0, atol=1e-11 * np.abs(W).max())


# ---------------------------------------------------------------------- studies
def study_errors(tmp_path, body) -> list[str]:
    path = write_study(tmp_path, body)
    with pytest.raises(ModelFileError) as info:
        load_study(path)
    return str(info.value).replace(str(path), "study.toml").splitlines()


def test_a_synthetic_record_too_long_is_refused_with_its_size(tmp_path):
    lines = study_errors(tmp_path, """
[[models]]
file = "tower.toml"
[records]
synthetic = { seeds = [1], duration = 1e9, dt = 0.01, pga = 1.0 }
""")
    assert lines == ["study.toml: records.synthetic.duration = 1000000000.0: with dt = 0.01 a record of 1e+11 "
                     "samples (at least 745 GiB per array of it): more than the 10,000,000 samples allowed; "
                     "shorten the duration or increase dt"]


def test_absurd_intensities_are_refused(tmp_path):
    lines = study_errors(tmp_path, """
[[models]]
file = "tower.toml"
[records]
synthetic = { seeds = [1] }
[scaling]
measure = "pga"
values = [0.5, 1e300]
""")
    assert lines == ["study.toml: scaling.values[1] = 1e+300: an acceleration above 100 g (100 g) is not a ground "
                     "motion of this world; check the value and scaling.units"]


@pytest.mark.parametrize("options, expected", [
    ("{ max_iter = -1 }", 'study.toml: analysis.lcp_options = {max_iter = -1}: not options of the LCP solver '
                          '"bpp" (max_iter must be a positive integer or None, got max_iter=-1)'),
    ("{ bogus = 1 }", 'study.toml: analysis.lcp_options = {bogus = 1}: not options of the LCP solver "bpp" '
                      "(BlockPrincipalPivoting.__init__() got an unexpected keyword argument 'bogus')"),
])
def test_lcp_options_are_checked_before_the_study_starts(tmp_path, options, expected):
    body = f'[[models]]\nfile = "tower.toml"\n[analysis]\nlcp_options = {options}\n'
    assert study_errors(tmp_path, body) == [expected]


def run_batch(tmp_path, *options, records=None):
    files = ", ".join(f'"{r}"' for r in records or [record_files(1)[0].as_posix()])
    path = write_study(tmp_path, f'[[models]]\nfile = "tower.toml"\n[records]\nfiles = [{files}]\n'
                                 'direction = "ux"\nunits = "g"\n[analysis]\nt_end = 0.2\n')
    return CliRunner().invoke(batch, [str(path), "--out", str(tmp_path / "out"), "--no-figures", "-q", *options])


def test_too_many_workers_are_refused_before_the_study_starts(tmp_path):
    result = run_batch(tmp_path, "--workers", "100000")
    assert result.exit_code == 2 and result.exception is not None and "Traceback" not in result.output
    assert re.search(r"Invalid value for --workers: workers=100000: more than 4 per core of this machine "
                     r"\(\d+ cores: at most \d+\)", result.output), result.output
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("address, expected", [
    ("garbage://x", "Invalid value for --scheduler: scheduler='garbage://x': unknown address scheme 'garbage' "
                    "(valid: inproc, tcp, tls, ucx, ws, wss, e.g. tcp://host:8786)"),
    ("tcp://127.0.0.1:1", "Invalid value for --scheduler: scheduler='tcp://127.0.0.1:1': cannot connect to a Dask "
                          "scheduler there"),
])
def test_a_scheduler_that_cannot_be_reached_is_a_clear_error(tmp_path, address, expected):
    pytest.importorskip("distributed")
    result = run_batch(tmp_path, "--scheduler", address)
    assert result.exit_code == 2 and expected in " ".join(result.output.split()), result.output
    assert "Traceback" not in result.output
    assert not (tmp_path / "out").exists()              # reached first: nothing written


def test_batch_exits_non_zero_and_counts_the_failed_analyses(tmp_path):
    (tmp_path / "empty.txt").write_text("")
    (tmp_path / "nan.txt").write_text("0.0 0.0\n0.01 nan\n0.02 0.0\n")
    (tmp_path / "zeros.txt").write_text("0.0 0.0\n0.01 0.0\n0.02 0.0\n")
    records = [record_files(1)[0].as_posix(), "empty.txt", "nan.txt", "zeros.txt"]
    result = run_batch(tmp_path, "--synchronous", records=records)
    assert result.exit_code == 1, result.output
    assert "2 of 4 analyses failed: see the status and message columns of" in result.output   # empty, nan


def test_a_run_with_a_non_finite_solution_is_a_failure():
    finite = SimpleNamespace(u=np.zeros((3, 2)), v=np.zeros((3, 1)))
    assert _non_finite(finite, {"top": 1.0, "residual": float("nan")}) == ""
    overflow = SimpleNamespace(u=np.array([[0.0, np.inf]]), v=np.zeros((1, 1)))
    assert _non_finite(overflow, {}).startswith("the solution u is not finite (an overflow")
    assert _non_finite(finite, {"top": float("inf")}) == "the peak quantities top are infinite (an overflow)"
