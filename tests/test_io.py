"""unilateral.io: atomic files, netCDF round trips, CSV tables and run summaries."""

import json
import os

import numpy as np
import pytest
import xarray as xr

import unilateral as ul
from conftest import rocking_load, rocking_model
from unilateral import io as uio

UNITS = {"length": "m", "force": "kN", "time": "s"}
ARRAYS = ("t", "v", "psi", "psiL", "u", "udot")


@pytest.fixture(scope="module")
def runs():
    """The paper's example with (unilateral) and without (bilateral) uplift."""
    kw = dict(dt=2e-3, t_end=0.6, method="cq")
    return {"unilateral": ul.solve(rocking_model(), rocking_load(), **kw),
            "bilateral": ul.solve(rocking_model(), rocking_load(), bilateral=True, **kw)}


@pytest.fixture
def sol(runs):
    return runs["unilateral"]


def kernel_only(sol):
    """The same histories without displacements, as from a KernelModel."""
    return ul.Solution(t=sol.t, v=sol.v, psi=sol.psi, psiL=sol.psiL, success=sol.success,
                       message=sol.message, stats=sol.stats, constraint_names=sol.constraint_names)


def assert_same_solution(a, b):
    for name in ARRAYS:
        x, y = getattr(a, name), getattr(b, name)
        assert (x is None) == (y is None), name
        if x is not None:
            assert x.dtype == y.dtype and np.array_equal(x, y), name
    assert (a.success, a.message, a.stats) == (b.success, b.message, b.stats)
    assert (a.dof_names, a.constraint_names) == (b.dof_names, b.constraint_names)


def listing(directory):
    return sorted(os.listdir(directory))


# ---------------------------------------------------------------------- atomic files
def half_then_fail(path):
    with open(path, "wb") as f:
        f.write(b"half a fi")
    raise RuntimeError("disk on fire")


def test_atomic_write_replaces_on_success(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old")
    assert uio.atomic_write(target, lambda tmp: tmp.write_text("new")) == target
    assert target.read_text() == "new"
    assert listing(tmp_path) == ["a.txt"]


@pytest.mark.parametrize("existing", [True, False])
def test_atomic_write_failure_keeps_previous_file(tmp_path, existing):
    target = tmp_path / "a.bin"
    old = bytes(range(256)) * 3
    if existing:
        target.write_bytes(old)
    with pytest.raises(RuntimeError, match="disk on fire"):
        uio.atomic_write(target, half_then_fail)
    assert listing(tmp_path) == (["a.bin"] if existing else [])
    if existing:
        assert target.read_bytes() == old


def test_atomic_path_keeps_suffix_and_directory(tmp_path):
    with uio.atomic_path(tmp_path / "fig.png") as tmp:
        assert tmp.parent == tmp_path and tmp.suffix == ".png" and tmp.exists()
        tmp.write_bytes(b"x")
    assert listing(tmp_path) == ["fig.png"]


def test_write_json_converts_numpy(tmp_path):
    obj = {"a": np.float64(1.5), "b": np.arange(3), "c": (np.int32(2), None, np.bool_(True)), 4: "x"}
    path = uio.write_json_atomic(tmp_path / "s.json", obj)
    assert json.loads(path.read_text()) == {"a": 1.5, "b": [0, 1, 2], "c": [2, None, True], "4": "x"}
    uio.write_text_atomic(path, "line\r\n")
    assert path.read_bytes() == b"line\r\n"              # no newline translation
    with pytest.raises(TypeError, match="object"):
        uio.to_jsonable({"bad": object()})


# ---------------------------------------------------------------------- netCDF
def test_netcdf_round_trip(tmp_path, sol):
    ds = uio.to_dataset(sol, units=UNITS, attrs={"model": {"name": "seed example", "mass": 40.0}})
    path = uio.save_netcdf(ds, tmp_path / "run.nc")
    loaded = uio.load_netcdf(path)
    os.remove(path)                                      # loaded into memory, file closed
    assert_same_solution(uio.from_dataset(loaded), sol)
    assert dict(loaded.sizes) == {"time": len(sol.t), "dof": 5, "constraint": 3}
    units = {name: loaded[name].attrs.get("units") for name in ["time", "u", "udot", "v", "psi", "psiL"]}
    assert units == {"time": "s", "u": "m", "udot": "m/s", "v": "m", "psi": "kN", "psiL": "kN"}
    attrs = loaded.attrs
    assert attrs["success"] == 1 and attrs["message"] == sol.message
    assert attrs["method"] == sol.stats["method"] and attrs["rule"] == sol.stats["rule"]
    assert attrs["time_total"] == sol.stats["time"]["total"]
    assert attrs["model_name"] == "seed example" and attrs["model_mass"] == 40.0


def test_the_netcdf_writer_writes_what_xarray_writes(tmp_path, runs):
    ds = uio.to_dataset(runs, units=UNITS, attrs={"model": {"name": "seed", "mass": 40.0}})
    ds = ds.assign_coords(constraint_kind=("constraint", ["soil", "soil", "gap"]))      # a non-index coordinate
    ours = uio.load_netcdf(uio.save_netcdf(ds, tmp_path / "ours.nc"))
    ds.to_netcdf(tmp_path / "xarray.nc", engine="h5netcdf")
    theirs = uio.load_netcdf(tmp_path / "xarray.nc")
    xr.testing.assert_identical(ours, ds)
    xr.testing.assert_identical(ours, theirs)
    assert "constraint_kind" in ours.coords and ours["u"].encoding["dtype"] == np.float64


def test_writing_results_imports_neither_dask_array_nor_distributed(tmp_path):
    """The command line's run, example and plot hold no Dask arrays: xarray is told so."""
    import subprocess
    import sys

    code = ("import sys; import numpy as np; import xarray as xr; "
            "from xarray.namedarray import pycompat; "
            "from unilateral.io.results import without_dask_arrays, write_netcdf; "
            "ds = None\n"
            "with without_dask_arrays():\n"
            "    ds = xr.Dataset({'x': ('t', np.arange(3.0))}, coords={'t': np.arange(3.0)})\n"
            f"    write_netcdf(ds, {str(tmp_path / 'x.nc')!r})\n"
            "    inside = [m in sys.modules for m in ('dask.array', 'distributed')]\n"
            "print(inside, 'dask' in pycompat._cached_duck_array_modules, "
            "pycompat.array_type('dask')[0].__module__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["[False,", "False]", "False", "dask.array.core"]   # restored afterwards


def test_save_netcdf_from_solution(tmp_path, sol):
    path = uio.save_netcdf(sol, tmp_path / "run.nc", units=UNITS, attrs={"method": sol.stats["method"]})
    assert_same_solution(uio.from_dataset(uio.load_netcdf(path)), sol)
    with pytest.raises(TypeError, match="Dataset"):
        uio.save_netcdf(uio.to_dataset(sol), tmp_path / "x.nc", units=UNITS)


def test_attrs_must_not_contradict_stats(sol):
    with pytest.raises(ValueError, match="method"):
        uio.to_dataset(sol, attrs={"method": "something else"})


def test_kernel_only_solution_has_no_dof_dimension(tmp_path, sol):
    ker = kernel_only(sol)
    ds = uio.to_dataset(ker)
    assert "dof" not in ds.dims and "u" not in ds and "units" not in ds["v"].attrs
    assert_same_solution(uio.from_dataset(uio.load_netcdf(uio.save_netcdf(ds, tmp_path / "k.nc"))), ker)


def test_cases_share_one_dataset(tmp_path, runs):
    path = uio.save_netcdf(runs, tmp_path / "cases.nc", units=UNITS)
    ds = uio.load_netcdf(path)
    assert ds["u"].dims == ("case", "time", "dof") and list(ds["case"].values) == list(runs)
    assert ds["u"].attrs["units"] == "m"
    assert ds.attrs["method"] == "cq"                    # equal in both cases: an attribute
    assert list(ds["message"].values) == [s.message for s in runs.values()]      # differing: per case
    for label, run in runs.items():
        assert_same_solution(uio.from_dataset(ds.sel(case=label)), run)
    with pytest.raises(ValueError, match="case"):
        uio.from_dataset(ds)


def test_cases_need_a_common_time_axis(runs):
    short = ul.solve(rocking_model(), rocking_load(), dt=2e-3, t_end=0.3, method="cq")
    with pytest.raises(ValueError, match="common time axis"):
        uio.to_dataset({"long": runs["unilateral"], "short": short})


def test_save_netcdf_is_atomic(tmp_path, sol, monkeypatch):
    target = tmp_path / "run.nc"
    uio.save_netcdf(sol, target)
    good = target.read_bytes()

    def broken(path, data):                     # the netCDF bytes are encoded in memory, then written
        half_then_fail(path)

    monkeypatch.setattr("unilateral.io.results._write_bytes", broken)
    with pytest.raises(RuntimeError):
        uio.save_netcdf(uio.to_dataset(sol, units=UNITS), target)
    assert target.read_bytes() == good and listing(tmp_path) == ["run.nc"]
    monkeypatch.undo()
    uio.save_netcdf(sol, target, units=UNITS)
    assert uio.load_netcdf(target)["u"].attrs["units"] == "m"


# ---------------------------------------------------------------------- CSV
def test_csv_reads_back_at_full_precision(tmp_path, sol):
    paths = uio.save_csv(sol, tmp_path / "out", prefix="seed_")
    assert [p.name for p in paths] == ["seed_displacements.csv", "seed_constraints.csv"]
    disp, cons = paths
    assert disp.read_text().splitlines()[0] == "time,x1,y1,r1,y2,r2"
    header = cons.read_text().splitlines()[0].split(",")
    assert header[:4] == ["time", "v:soil3", "v:soil2", "v:soil4"] and header[4] == "psi:soil3"
    table = np.loadtxt(disp, delimiter=",", skiprows=1)
    assert np.array_equal(table, np.column_stack([sol.t, sol.u]))           # exact, not approximate
    table = np.loadtxt(cons, delimiter=",", skiprows=1)
    assert np.array_equal(table, np.column_stack([sol.t, sol.v, sol.psi, sol.psiL]))


def test_csv_without_displacements(tmp_path, sol):
    paths = uio.save_csv(kernel_only(sol), tmp_path)
    assert [p.name for p in paths] == ["constraints.csv"] and listing(tmp_path) == ["constraints.csv"]


# ---------------------------------------------------------------------- summary
def test_summary_peaks(sol):
    s = uio.summary(sol, units=UNITS, extra={"load": "pulse", "P": np.float64(200.0)})
    json.dumps(s, allow_nan=False)
    for i, name in enumerate(sol.constraint_names):
        c = s["constraints"][name]
        assert c["max_v"] == sol.v[:, i].max() and c["t_max_v"] == sol.t[np.argmax(sol.v[:, i])]
        assert c["min_psi"] == sol.psi[:, i].min() and c["t_min_psi"] == sol.t[np.argmin(sol.psi[:, i])]
    assert s["constraints"]["soil3"]["max_v"] > 1e-3                 # node 3 lifts off by ~3 mm
    assert s["static"] == dict(zip(sol.dof_names, sol.u[0].tolist()))
    assert s["steps"] == len(sol.t) - 1 and s["run_time"] == sol.stats["time"]["total"]
    assert (s["method"], s["rule"], s["success"]) == (sol.stats["method"], sol.stats["rule"], True)
    assert s["extra"] == {"load": "pulse", "P": 200.0}
    text = uio.format_summary(s)
    assert all(name in text for name in sol.constraint_names + s["static_shown"])
    # the printed static state is the few DOFs that matter: those that move, largest first
    assert s["static_shown"] and set(s["static_shown"]) <= set(sol.dof_names)
    assert all(abs(s["static"][name]) > 0 for name in s["static_shown"])
    assert "max v [m]" in text and "min psi [kN]" in text and "pulse" in text


def test_summary_of_a_sparse_failed_run(sol):
    failed = ul.Solution(t=sol.t[:1], v=sol.v[:1], psi=sol.psi[:1], psiL=sol.psiL[:1], success=False,
                         message="the static LCP failed", stats={}, constraint_names=sol.constraint_names)
    s = uio.summary(failed)
    assert s["run_time"] is None and s["static"] == {} and s["units"] == {}
    text = uio.format_summary(s)
    assert text.startswith("FAILED: the static LCP failed") and "n/a" in text and "soil4" in text
