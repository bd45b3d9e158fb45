"""What the examples ``halfspace`` and ``footings`` write: every run in a results file of its own, the
manifest true to the folder, the comparison figure redrawn by ``unilateral plot``, and the patch
extents of the footings in ``results.nc`` (the same by xarray and without it)."""

import json

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from unilateral.analysis import run_example
from unilateral.analysis.halfspace_example import LOADS, SOIL_LABELS, solve_all
from unilateral.cli import main
from unilateral.io import from_dataset, open_results, to_dataset
from unilateral.io.dataset import cases_dataset
from unilateral.io.dataset import write_netcdf as lean_write
from unilateral.io.results import load_netcdf, patch_coords
from unilateral.io.results import write_netcdf as xarray_write
from unilateral.solve import solve
from unilateral.structure import Frame2D

SHORT = {"halfspace": dict(dt=1e-2, t_end=0.3), "footings": dict(dt=0.02, t_end=0.3)}
HALFSPACE_RUNS = [f"results_{soil}_{load}.nc" for soil in SOIL_LABELS for load in LOADS]
FOOTINGS_RUNS = ["results_one_soil.nc", "results_own_soils.nc", "results_sliding.nc"]


@pytest.fixture(scope="module")
def halfspace(tmp_path_factory):
    out = tmp_path_factory.mktemp("examples") / "hs"
    return out, run_example("halfspace", out, **SHORT["halfspace"])


@pytest.fixture(scope="module")
def footings(tmp_path_factory):
    out = tmp_path_factory.mktemp("examples") / "fo"
    return out, run_example("footings", out, **SHORT["footings"])


def manifest_files(folder):
    return set(json.loads((folder / "manifest.json").read_text())["files"])


def folder_files(folder):
    return {p.name for p in folder.iterdir() if p.name != "manifest.json"}


@pytest.mark.parametrize("example, runs", [("halfspace", HALFSPACE_RUNS), ("footings", FOOTINGS_RUNS)])
def test_the_manifest_lists_every_file_and_every_run(example, runs, request):
    out, result = request.getfixturevalue(example)
    assert result["success_all"]
    assert manifest_files(out) == folder_files(out)
    assert set(runs) <= manifest_files(out) and f"{example}.png" in manifest_files(out)
    assert json.loads(open_results(out / "results.nc").attrs["run_files"]) == runs
    assert json.loads((out / "summary.json").read_text())["extra"]["run_files"] == runs


def test_each_soil_reopens_as_its_solution(halfspace):
    out, _ = halfspace
    runs = solve_all(**SHORT["halfspace"])
    for (soil, load), (_, _, _, cases, _) in runs.items():
        ds = open_results(out / f"results_{soil}_{load}.nc")
        assert (ds.attrs["soil"], ds.attrs["load"]) == (soil, load)
        assert [str(c) for c in ds["case"].values] == ["unilateral", "bilateral"]
        for case, sol in cases.items():
            back = from_dataset(ds.sel(case=case))
            for name in ("t", "u", "v", "psi"):
                np.testing.assert_array_equal(getattr(back, name), getattr(sol, name), err_msg=f"{soil}/{load} {name}")


def test_the_main_run_is_results_nc(halfspace):
    out, _ = halfspace
    main_ds, run = (open_results(out / name) for name in ("results.nc", "results_halfspace_earthquake.nc"))
    for name in ("u", "v", "psi", "node_displacement", "base_shear"):
        np.testing.assert_array_equal(main_ds[name].values, run[name].values, err_msg=name)


@pytest.mark.parametrize("example, widths", [("halfspace", None), ("footings", {"A": 8.0, "B": 3.0})])
def test_patch_extents_tile_each_footing(example, widths, request):
    out, _ = request.getfixturevalue(example)
    for path in sorted(out.glob("results_*.nc")):
        ds = open_results(path)
        for name in {str(f) for f in ds["footing"].values if str(f)}:
            patches = ds["footing"].values == name
            x, w = ds["patch_x"].values[patches], ds["patch_width"].values[patches]
            assert np.all(np.abs(x[1:] - 0.5 * w[1:] - (x[:-1] + 0.5 * w[:-1])) < 1e-12)   # side by side
            expected = widths[name] if widths else (15.0 if "winkler" in path.name else 10.0)
            assert w.sum() == pytest.approx(expected, rel=1e-12), (path.name, name)
            assert np.all(ds["patch_length"].values[patches] > 0)
        assert np.isnan(ds["patch_x"].values[ds["footing"].values == ""]).all()


@pytest.mark.parametrize("example", ["halfspace", "footings"])
def test_plot_redraws_the_comparison_from_the_run_files(example, request, tmp_path):
    out, _ = request.getfixturevalue(example)
    result = CliRunner().invoke(main, ["plot", str(out / "results.nc"), "--out", str(tmp_path / "again")])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "again" / f"{example}.png").stat().st_size > 10_000
    assert "skipped" not in result.output


def test_a_run_files_figures_do_not_replace_those_of_results_nc(halfspace, tmp_path):
    out, _ = halfspace
    folder = tmp_path / "copy"
    folder.mkdir()
    for name in ("results.nc", "results_cones_pulse.nc"):
        (folder / name).write_bytes((out / name).read_bytes())
    result = CliRunner().invoke(main, ["plot", str(folder / "results_cones_pulse.nc")])
    assert result.exit_code == 0, result.output
    drawn = {p.name for p in folder.glob("*.png")}
    assert "cones_pulse_fig2.png" in drawn and "fig2.png" not in drawn


def test_a_missing_run_file_skips_the_comparison_only(halfspace, tmp_path):
    out, _ = halfspace
    folder = tmp_path / "partial"
    folder.mkdir()
    (folder / "results.nc").write_bytes((out / "results.nc").read_bytes())
    result = CliRunner().invoke(main, ["plot", str(folder / "results.nc")])
    assert result.exit_code == 1
    assert "skipped halfspace: " in result.output and "results_winkler-kelvin_pulse.nc" in result.output
    assert (folder / "fig2.png").exists() and not (folder / "halfspace.png").exists()


@pytest.mark.parametrize("example", ["halfspace", "footings"])
def test_element_forces_and_base_of_both_cases_carry_units(example, request):
    out, _ = request.getfixturevalue(example)
    for case in ("", "bilateral_"):
        for table in ("element_forces.csv", "base.csv"):
            header = (out / f"{case}{table}").read_text().splitlines()[0].split(",")
            assert header[0] == "time [s]" and all(column.endswith("]") for column in header), (case, table)


def test_comparison_and_labels_use_the_case_keys(halfspace, footings):
    for out, result in (halfspace, footings):
        for run in result["comparison"].values():
            assert set(run) <= {"unilateral", "bilateral"} and "unilateral" in run
        labels = json.loads(open_results(out / "results.nc").attrs["case_labels"])
        assert set(labels) == {"unilateral", "bilateral"}


# ---------------------------------------------------------------------- patch extents, both writers
def frame_on_two_footings():
    """A portal on a rigid footing (3 strips) and a flexible one (nodes 1 m apart, half a spacing
    beyond the end nodes), beside a gap, on Winkler-Kelvin soil."""
    fr = Frame2D()
    for node, x, y in ((1, 0.0, 0.0), (2, 6.0, 0.0), (3, 7.0, 0.0), (4, 8.0, 0.0), (5, 0.0, 3.0), (6, 7.0, 3.0)):
        fr.node(node, x, y)
    beam = dict(E=30e6, A=0.1, I=1e-3)
    fr.beam("C1", 1, 5, **beam)
    fr.beam("C2", 3, 6, **beam)
    fr.beam("B", 5, 6, **beam)
    fr.beam("F1", 2, 3, **beam)
    fr.beam("F2", 3, 4, **beam)
    fr.mass(5, 10.0)
    fr.mass(6, 10.0)
    fr.node(7, -1.0, 3.0)
    fr.support(7)
    fr.gap("stop", 7, 5, k=1e5, gap=0.01)
    soil = {"model": "winkler-kelvin", "k": 1e5, "c": 100.0}
    fr.foundation("R", 1, width=2.0, length=1.0, patches=3, soil=soil)
    fr.foundation("F", 3, nodes=[2, 3, 4], width=3.0, length=1.5, soil=soil, horizontal="none")
    return fr.build()


def test_patch_extents_are_the_same_by_xarray_and_without_it(tmp_path):
    structure = frame_on_two_footings()
    model = structure.to_model()
    load = structure.gravity(9.81)
    cases = {c: solve(model, lambda t: load, dt=1e-3, t_end=0.01, bilateral=c == "bilateral")
             for c in ("unilateral", "bilateral")}
    units = {"length": "m", "force": "kN", "time": "s"}
    lean = cases_dataset(cases, units=units, footings=structure.foundation)
    full = to_dataset(cases, units=units, footings=structure.foundation)
    xr.testing.assert_identical(lean.to_xarray(), full)
    lean_write(lean, tmp_path / "lean.nc")
    xarray_write(full, tmp_path / "xarray.nc")
    xr.testing.assert_identical(load_netcdf(tmp_path / "lean.nc"), load_netcdf(tmp_path / "xarray.nc"))

    assert list(full["footing"].values) == ["", "R", "R", "R", "F", "F", "F"]
    assert list(full["patch_node"].values) == ["", "1", "1", "1", "2", "3", "4"]
    np.testing.assert_allclose(full["patch_x"].values[1:], [-2 / 3, 0.0, 2 / 3, 6.0, 7.0, 8.0])
    np.testing.assert_allclose(full["patch_width"].values[1:], [2 / 3] * 3 + [1.0] * 3)
    np.testing.assert_allclose(full["patch_length"].values[1:], [1.0] * 3 + [1.5] * 3)
    for name, width in (("R", 2.0), ("F", 3.0)):
        assert full["patch_width"].values[full["footing"].values == name].sum() == pytest.approx(width)
    assert full["patch_width"].attrs == {"long_name": "width of the contact patch along x", "units": "m"}


def test_patch_coords_refuse_another_structures_constraints():
    structure = frame_on_two_footings()
    with pytest.raises(ValueError, match="the footings have 6 patches after 1 constraints of the frame, but the "
                                         "solution has 4 constraints"):
        patch_coords(structure.foundation, 4)
