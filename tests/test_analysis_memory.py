"""``unilateral.run`` in memory: an ``Analysis`` (summary, solutions, datasets, figures) that writes
nothing until ``save``, and then the same files as ``unilateral run``."""

from __future__ import annotations

from pathlib import Path

import h5py
import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis import run_model_file

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "liolios1990.toml"


@pytest.fixture(scope="module")
def analysis(tmp_path_factory):
    folder = tmp_path_factory.mktemp("memory")
    import os

    before = os.getcwd()
    os.chdir(folder)
    try:
        a = ul.run(EXAMPLE, t_end=0.1, figures=())
    finally:
        os.chdir(before)
    assert not list(folder.iterdir())                      # nothing written, not even in the current folder
    return a


def test_the_analysis_is_the_summary_with_the_solutions_and_datasets(analysis):
    assert analysis["success_all"] and set(analysis.solutions) == {"unilateral", "bilateral"}
    ds = analysis.dataset
    assert list(ds["case"].values) == ["unilateral", "bilateral"]
    np.testing.assert_array_equal(ds["u"].sel(case="bilateral").values, analysis.solutions["bilateral"].u)
    assert analysis.datasets["unilateral"]["base_shear"].shape == (len(analysis.solutions["unilateral"].t),)
    peak = analysis["results"]["unilateral"]["base_shear"]["max"]
    assert peak == float(ds["base_shear"].sel(case="unilateral").max())


def test_save_writes_what_the_command_line_writes(analysis, tmp_path):
    saved = analysis.save(tmp_path / "saved")
    reference = run_model_file(EXAMPLE, tmp_path / "cli", figures=(), t_end=0.1)
    assert sorted(p.name for p in (tmp_path / "saved").iterdir()) == sorted(p.name for p in (tmp_path / "cli").iterdir())
    with h5py.File(tmp_path / "saved" / "results.nc") as a, h5py.File(tmp_path / "cli" / "results.nc") as b:
        assert set(a) == set(b)
        for name in a:
            if a[name].dtype.kind == "f" and not name.startswith("time_"):
                np.testing.assert_array_equal(a[name][()], b[name][()], err_msg=name)
    assert saved["output"] == reference["output"] and saved["results"] == reference["results"]
    assert (tmp_path / "saved" / "displacements.csv").read_text() == (tmp_path / "cli" / "displacements.csv").read_text()


def test_a_failed_save_leaves_the_previous_folder(analysis, tmp_path):
    target = tmp_path / "out"
    analysis.save(target)
    before = sorted(p.name for p in target.iterdir())
    (tmp_path / "file").write_text("x")
    with pytest.raises(Exception):
        analysis.save(tmp_path / "file" / "below")
    assert sorted(p.name for p in target.iterdir()) == before


def test_figures_on_demand_and_html(analysis):
    import matplotlib

    matplotlib.use("Agg")
    fig = analysis.figure("fig2")
    assert fig.axes
    with pytest.raises(ValueError, match="valid: fig2"):
        analysis.figure("nope")
    html = analysis._repr_html_()
    assert html.startswith("<b>") and "contact changes" in html and "<pre" in html


def test_results_dataset_of_a_solution_and_its_structure(analysis):
    from unilateral.structure.examples import liolios1990

    structure, load, _ = liolios1990()
    sol = analysis.solutions["unilateral"]
    ds = ul.results_dataset(sol, structure, load=load)
    assert "base_shear" in ds and "end_force" in ds and ds.sizes["time"] == len(sol.t)
    np.testing.assert_array_equal(ds["u"].values, sol.u)
