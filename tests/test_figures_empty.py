"""``unilateral plot`` on a results.nc with an empty dimension (``case``, ``yield_component``,
``friction_component``) or a ``ground_spectrum`` whose ``damping`` is not a number: the figure is
skipped with the reason (exit code 1, no traceback) and the other figures are drawn."""

from __future__ import annotations

import pytest
from click.testing import CliRunner
from test_inelastic3d_outputs import block, cantilever
from test_modelfile3d import write
from test_spectra_run import write_frame

import unilateral as ul
from unilateral.cli import main

xr = pytest.importorskip("xarray")


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The results.nc of a 3-D hinge (yield components), a friction cone (friction components) and a
    frame with response spectra and a figure history."""
    folder = tmp_path_factory.mktemp("empty")
    files = {}
    for name, document in (("hinge", cantilever() | {"analysis": {"dt": 0.05, "t_end": 8.0, "method": "direct"}}),
                           ("cone", block(4) | {"analysis": {"dt": 0.01, "t_end": 2.5, "method": "direct"}})):
        assert ul.run(write(folder, document, f"{name}.toml"), folder / name, figures=())["success_all"]
        files[name] = folder / name / "results.nc"
    (folder / "frame").mkdir()
    ul.run(write_frame(folder / "frame"), folder / "frame" / "out", figures=())
    files["frame"] = folder / "frame" / "out" / "results.nc"
    return files


def _plot(tmp_path, source, change):
    """``unilateral plot`` of ``source`` changed by ``change(ds)``: (exit code, output, figures drawn)."""
    ds = change(xr.load_dataset(source, engine="h5netcdf"))
    path = tmp_path / "changed.nc"
    ds.to_netcdf(path, engine="h5netcdf")
    result = CliRunner().invoke(main, ["plot", str(path), "--out", str(tmp_path / "figures")])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.output
    assert "Traceback" not in result.output
    return result.exit_code, result.output, sorted(p.stem for p in (tmp_path / "figures").glob("*.png"))


def _damping(value):
    def change(ds):
        ds["ground_spectrum"].attrs["damping"] = value
        return ds
    return change


@pytest.mark.parametrize("run, change, message", [
    ("hinge", lambda ds: ds.isel(yield_component=slice(0, 0)),
     "skipped hysteresis: the dimension yield_component has length 0, yet the file has 2 yield element(s)"),
    ("cone", lambda ds: ds.isel(friction_component=slice(0, 0)),
     "skipped hysteresis: the dimension friction_component has length 0, yet the file has 1 friction element(s)"),
    ("frame", _damping("five percent"),
     "skipped spectra: the attribute damping = 'five percent' of ground_spectrum is not a number"),
    ("frame", _damping([0.05, 0.1]), "skipped spectra: the attribute damping = '[0.05 0.1 ]' of ground_spectrum"),
])
def test_a_figure_the_file_cannot_give_is_skipped_and_the_others_drawn(runs, tmp_path, run, change, message):
    code, output, drawn = _plot(tmp_path, runs[run], change)
    assert code == 1, output
    assert message in output
    assert "energy" in drawn                                    # the other figures are drawn


def test_a_file_without_cases_skips_every_figure_of_a_case(runs, tmp_path):
    code, output, drawn = _plot(tmp_path, runs["frame"], lambda ds: ds.isel(case=slice(0, 0)))
    assert code == 1, output
    for figure in ("constraints", "ground_motion", "base_forces", "energy", "spectra"):
        assert f"skipped {figure}: the dimension case has length 0" in output, figure
    assert drawn == ["model"]


def test_the_history_figure_of_a_file_without_cases_is_skipped(runs):
    from unilateral.figures import FigureDataError
    from unilateral.figures.results import history_figure

    ds = xr.load_dataset(runs["frame"], engine="h5netcdf").isel(case=slice(0, 0))
    ds.attrs.update(figure_node="4", figure_dof="ux")
    with pytest.raises(FigureDataError, match="the dimension case has length 0"):
        history_figure(ds)


def test_a_number_as_damping_still_titles_the_spectra(runs, tmp_path):
    code, output, drawn = _plot(tmp_path, runs["frame"], _damping(0.02))
    assert code == 0, output
    assert "spectra" in drawn
