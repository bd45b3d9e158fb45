"""Recorders: ``[output]`` says what a run writes (histories, nodes, elements, every, precision, csv).

The written values are those of the full run (selected, decimated, rounded to float32): compared
exactly with ``histories = "full"``; the summary is of every step whatever is written; bad keys are
refused with the key and what is valid.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest
import xarray as xr

from unilateral.analysis import run_model_file
from unilateral.io.recorders import AUTO_LIMIT, HISTORY_VARIABLES, KEY_VARIABLES, Recorders, select
from unilateral.modelfile import ModelFileError, load_model_file

sys.path.insert(0, str(Path(__file__).resolve().parent))
from yield_portal import PORTAL_TOML  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

LOADS = """
[loads.gravity]
g = 9.81

[[loads.nodal]]
node = 2
ux = 80.0
time_function = { type = "half_sine", duration = 0.3 }

[analysis]
dt = 0.005
t_end = 0.6
method = "direct"
"""


def write(tmp_path, lines="", name="portal.toml") -> Path:
    path = tmp_path / name
    path.write_text(PORTAL_TOML + LOADS + "\n[output]\nfigure = { node = 3, dof = \"ux\" }\n" + lines)
    return path


def run(tmp_path, lines="", folder="out", **kw):
    out = tmp_path / folder
    summary = run_model_file(write(tmp_path, lines, name=f"{folder}.toml"), out, figures=(), **kw)
    return out, summary


def read(path) -> dict:
    with h5py.File(path) as f:
        return {name: f[name][()] for name in f if f[name].dtype.kind in "fi"}


def timed_names(path) -> set:
    """The variables of ``results.nc`` along ``time``."""
    with xr.open_dataset(path) as ds:
        return {name for name, var in ds.data_vars.items() if "time" in var.dims}


@pytest.fixture(scope="module")
def full(tmp_path_factory):
    return run(tmp_path_factory.mktemp("full"), 'histories = "full"')


def test_a_small_run_writes_every_history_by_default(tmp_path, full):
    out, summary = run(tmp_path)
    assert summary["output"]["histories"] == "full" and summary["output"]["left_out"] == []
    assert sorted(p.name for p in out.iterdir()) == sorted(p.name for p in full[0].iterdir())
    for name, values in read(full[0] / "results.nc").items():
        if not name.startswith("time_"):            # run times differ
            np.testing.assert_array_equal(read(out / "results.nc")[name], values, err_msg=name)


def test_key_histories_are_the_base_the_drifts_the_energies_and_the_figure_node(tmp_path, full):
    out, summary = run(tmp_path, 'histories = "key"')
    info = summary["output"]
    assert info["histories"] == "key" and "note" in info and info["nodes"] == ["3"]
    with h5py.File(out / "results.nc") as f:
        assert "u" not in f and "end_force" not in f and "v" not in f
        assert [n.decode() for n in f["node"][()]] == ["3"]
        np.testing.assert_array_equal(f["node_displacement"][()],
                                      _full(full, "node_displacement")[:, :, [_node_index(full, "3")]])
    timed = timed_names(out / "results.nc")
    assert timed == set(info["written"])
    assert timed <= set(KEY_VARIABLES) | {"node_displacement"} | {n for n in timed if n.startswith("energy_")}
    assert {"base_shear", "energy_input_work"} <= timed
    assert sorted(p.name for p in out.glob("*.csv")) == ["base.csv", "bilateral_base.csv"]
    assert summary["results"] == full[1]["results"]                # the summary is of every result


def test_nodes_and_elements_restrict_what_is_written(tmp_path, full):
    out, summary = run(tmp_path, 'histories = "key"\nnodes = [2]\nelements = ["g", "h2", "s1"]')
    with h5py.File(out / "results.nc") as f:
        assert [x.decode() for x in f["dof"][()]] == ["2.ux", "2.uy", "2.rz"]
        assert [x.decode() for x in f["element"][()]] == ["g", "s1"]
        assert [x.decode() for x in f["yield_element"][()]] == ["h2"]
        constraints = [x.decode() for x in f["constraint"][()]]
        assert constraints and all(c.split(".")[0] in ("h2", "s1") for c in constraints)
        full_constraints = list(_coord(full, "constraint"))
        picked = [full_constraints.index(c) for c in constraints]
        np.testing.assert_array_equal(f["v"][()], _full(full, "v")[:, :, picked])
        dofs = [_coord(full, "dof").index(d) for d in ("2.ux", "2.uy", "2.rz")]
        np.testing.assert_array_equal(f["u"][()], _full(full, "u")[:, :, dofs])
    header = (out / "element_forces.csv").read_text().splitlines()[0]
    assert header.startswith("time [s],g:N_i") and "c1:" not in header


def test_every_k_keeps_the_steps_0_k_2k(tmp_path, full):
    out, summary = run(tmp_path, "every = 4")
    with h5py.File(out / "results.nc") as f:
        np.testing.assert_array_equal(f["time"][()], _full(full, "time")[::4])
        np.testing.assert_array_equal(f["u"][()], _full(full, "u")[:, ::4])
    rows = np.loadtxt(out / "displacements.csv", delimiter=",", skiprows=1)
    np.testing.assert_array_equal(rows[:, 0], _full(full, "time")[::4])
    assert summary["results"] == full[1]["results"]                # peaks over every step


def test_float32_histories_are_the_full_values_rounded(tmp_path, full):
    out, _ = run(tmp_path, 'precision = "float32"')
    with h5py.File(out / "results.nc") as f:
        assert f["u"].dtype == np.float32 and f["time"].dtype == np.float64
        np.testing.assert_array_equal(f["u"][()], _full(full, "u").astype(np.float32))
    rows = np.loadtxt(out / "displacements.csv", delimiter=",", skiprows=1)
    np.testing.assert_array_equal(rows[:, 1:].astype(np.float32), _full(full, "u")[0].astype(np.float32))
    assert (out / "displacements.csv").stat().st_size < (full[0] / "displacements.csv").stat().st_size


def test_csv_off_writes_results_nc_and_summary_only(tmp_path):
    out, _ = run(tmp_path, "csv = false")
    assert not list(out.glob("*.csv")) and (out / "results.nc").exists() and (out / "summary.json").exists()


def test_the_csv_tables_read_back_to_the_same_floats(full):
    rows = np.loadtxt(full[0] / "displacements.csv", delimiter=",", skiprows=1)
    np.testing.assert_array_equal(rows[:, 1:], _full(full, "u")[0])


def test_the_python_api_replaces_keys_of_the_file(tmp_path):
    out, summary = run(tmp_path, 'histories = "full"', output={"histories": "key", "every": 2})
    assert summary["output"]["histories"] == "key" and summary["output"]["every"] == 2


@pytest.mark.parametrize("line, words", [
    ('variables = ["uu"]', ["output.variables", "'uu'", "base_shear"]),
    ("nodes = [99]", ["output.nodes[0]", "99", "no such node"]),
    ('elements = ["g2"]', ["output.elements[0]", "'g2'", "no such element", "c1"]),
    ("every = 0", ["output.every", "0"]),
    ('precision = "float16"', ["output.precision", "float16", "float32"]),
    ('histories = "all"', ["output.histories", "auto", "key", "full"]),
])
def test_bad_recorder_keys_are_named_with_what_is_valid(tmp_path, line, words):
    with pytest.raises(ModelFileError) as info:
        load_model_file(write(tmp_path, line))
    assert all(word in str(info.value) for word in words), str(info.value)


@pytest.mark.parametrize("kwargs, words", [
    ({"every": 0}, ["every=0", ">= 1"]), ({"precision": "half"}, ["precision", "float32"]),
    ({"variables": ["nope"]}, ["nope", "base_shear"]), ({"histories": "some"}, ["histories", "full"]),
])
def test_recorders_refuse_bad_values(kwargs, words):
    with pytest.raises(ValueError) as info:
        Recorders(**kwargs)
    assert all(word in str(info.value) for word in words), str(info.value)


def test_every_history_of_a_frame_run_is_a_known_variable(full):
    timed = timed_names(full[0] / "results.nc")
    assert {n for n in timed if not n.startswith("energy_")} <= set(HISTORY_VARIABLES)


def test_auto_chooses_key_above_the_limit():
    from unilateral.io.dataset import Dataset

    n = AUTO_LIMIT // 8 // 10 + 1
    ds = Dataset({"u": (("time", "dof"), np.zeros((n, 10))), "base_shear": (("time",), np.zeros(n))},
                 coords={"time": np.arange(n, dtype=float), "dof": [f"{k}.ux" for k in range(10)],
                         "node": [str(k) for k in range(10)]})
    written, info = select(ds, Recorders())
    assert info["histories"] == "key" and list(written.data_vars) == ["base_shear"]
    small, info = select(ds.isel(time=slice(0, 10)), Recorders())
    assert info["histories"] == "full" and set(small.data_vars) == {"u", "base_shear"}


def test_a_very_long_run_writes_its_key_histories_decimated_under_the_limit():
    from unilateral.io.dataset import Dataset
    from unilateral.io.recorders import WRITE_LIMIT

    n = 10**6 + 1                                       # 10^6 steps of a small model, six key histories
    ds = Dataset({f"energy_{k}": (("time",), np.arange(n, dtype=float)) for k in range(6)} |
                 {"u": (("time", "dof"), np.zeros((n, 3)))},
                 coords={"time": np.arange(n, dtype=float), "dof": ["1.ux", "1.uy", "1.rz"], "node": ["1"]})
    written, info = select(ds, Recorders())
    size = sum(var.values.nbytes for name, var in written.data_vars.items())
    assert info["histories"] == "key" and info["every"] == 2 and size <= WRITE_LIMIT and "note_every" in info
    np.testing.assert_array_equal(written["time"].values, np.arange(0, n, 2, dtype=float))
    assert select(ds, Recorders(every=1))[1]["every"] == 1
    assert select(ds, Recorders(histories="full"))[1]["every"] == 1


def test_a_run_without_spectra_does_not_import_scipy_signal(tmp_path):
    import subprocess

    path = write(tmp_path)
    code = ("import sys; from unilateral.analysis import run_model_file; "
            f"run_model_file({str(path)!r}, {str(tmp_path / 'o')!r}, figures=()); print('scipy.signal' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip().splitlines()[-1] == "False", done.stderr


@pytest.mark.slow
def test_the_nine_storey_frame_at_one_millisecond_writes_at_most_50_mb(tmp_path):
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from frame9 import write as write_frame

    path = write_frame(tmp_path, dt=0.001, t_end=15.0)
    summary = run_model_file(path, tmp_path / "out", figures=())
    size = sum(p.stat().st_size for p in (tmp_path / "out").iterdir())
    assert summary["output"]["histories"] == "key" and size <= 50e6, size


# ---------------------------------------------------------------------- helpers
def _full(full, name):
    with h5py.File(full[0] / "results.nc") as f:
        return f[name][()]


def _coord(full, name):
    with h5py.File(full[0] / "results.nc") as f:
        return [x.decode() for x in f[name][()]]


def _node_index(full, node):
    return _coord(full, "node").index(node)


def test_summary_json_says_what_was_written(full):
    info = json.loads((full[0] / "summary.json").read_text())["output"]
    assert info["histories"] == "full" and info["every"] == 1 and info["precision"] == "float64"


def test_plot_redraws_what_a_key_file_gives_and_names_what_it_skips(tmp_path):
    from click.testing import CliRunner

    from unilateral.cli import main

    out, _ = run(tmp_path, 'histories = "key"')
    done = CliRunner().invoke(main, ["plot", str(out / "results.nc"), "--out", str(tmp_path / "figs")])
    assert "Traceback" not in done.output and (tmp_path / "figs" / "fig2.png").exists(), done.output
    assert (tmp_path / "figs" / "energy.png").exists()
