"""The command line: help, the paper's example end to end, plotting, atomic outputs."""

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from unilateral.cli import main
from unilateral.io import load_netcdf

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.fixture(scope="module")
def example_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("runs") / "liolios1990"
    result = CliRunner().invoke(main, ["example", "liolios1990", "--out", str(out), "--t-end", "0.3"])
    assert result.exit_code == 0, result.output
    return out, result.output


@pytest.mark.parametrize("args", [[], ["example"], ["run"], ["plot"], ["bench"]])
def test_help(args):
    result = CliRunner().invoke(main, args + ["--help"])
    assert result.exit_code == 0
    assert "usage:" in result.output.lower()
    assert "--help" in result.output


def test_version():
    result = CliRunner().invoke(main, ["--version"])
    assert result.exit_code == 0 and "unilateral" in result.output


def test_example_prints_and_writes_the_paper_values(example_run):
    out, output = example_run
    assert "-0.0006667" in output                        # static foundation displacement
    summary = json.loads((out / "summary.json").read_text())
    assert summary["success"] is True
    np.testing.assert_allclose(summary["static"]["2.uy"], -0.667e-3, rtol=1e-3)
    fig = summary["extra"]["figure"]
    np.testing.assert_allclose(fig["static"], -0.667e-3, rtol=1e-3)
    # with uplift node 3 rises many times higher than without (the paper's Fig. 2)
    assert fig["peak"]["unilateral"] > 5 * fig["peak"]["bilateral"] > 0
    assert summary["case_labels"] == {"unilateral": "with uplift", "bilateral": "without uplift"}
    for name in ("results.nc", "fig2.png", "constraints.png", "force_deformation.png", "base_forces.png",
                 "energy.png", "element_forces.csv", "base.csv",
                 "displacements.csv", "constraints.csv", "bilateral_displacements.csv"):
        assert (out / name).stat().st_size > 0, name
    assert (out / "fig2.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    ds = load_netcdf(out / "results.nc")
    assert list(ds["case"].values) == ["unilateral", "bilateral"]
    node3 = ds["node_displacement"].sel(node="3", component="uy")
    np.testing.assert_allclose(float(node3.sel(case="unilateral").max()), fig["peak"]["unilateral"])


def test_plot_command_redraws_the_figures(example_run, tmp_path):
    out, _ = example_run
    result = CliRunner().invoke(main, ["plot", str(out / "results.nc"), "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "fig2.png").stat().st_size > 0
    assert (tmp_path / "constraints.png").stat().st_size > 0


def test_an_interrupted_run_keeps_the_previous_results(example_run, monkeypatch):
    out, _ = example_run
    before = (out / "results.nc").read_bytes()
    import xarray as xr

    def broken(self, store, *args, **kwargs):      # the netCDF writer fails half-way
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "dump_to_store", broken)
    result = CliRunner().invoke(main, ["example", "liolios1990", "--out", str(out), "--t-end", "0.05"])
    assert result.exit_code != 0
    assert (out / "results.nc").read_bytes() == before
    assert not [p for p in out.iterdir() if p.name.startswith(".") or "tmp" in p.name]


def test_bad_options_name_the_option():
    result = CliRunner().invoke(main, ["example", "liolios1990", "--rule", "rk4"])
    assert result.exit_code == 2 and "--rule" in result.output
    result = CliRunner().invoke(main, ["example", "liolios1990", "--dt", "-1", "--out", "/tmp/unused-unilateral"])
    assert result.exit_code == 2 and "Invalid value for '--dt': -1 is not a positive finite number" in result.output


def test_a_short_cli_run_stays_in_python_and_leaves_the_library_policy_alone(tmp_path):
    """A CLI run (in its own process or in this one) runs short analyses in the Python loops, whatever
    the process imported before; the library's policy is in force again afterwards."""
    import subprocess
    import sys

    import numba  # noqa: F401  (imported: it no longer changes the choice)

    from unilateral.march.policy import COMMAND_LINE, LIBRARY, current_policy

    out = tmp_path / "ex"
    subprocess.run([sys.executable, "-m", "unilateral", "example", "liolios1990", "--out", str(out), "--t-end",
                    "0.2", "--figures", "none", "--method", "modal"], check=True, capture_output=True)
    stats = [json.loads(text) for text in load_netcdf(out / "results.nc")["stats"].values]
    assert [s["engine"] for s in stats] == ["python", "python"]
    result = CliRunner().invoke(main, ["example", "liolios1990", "--out", str(tmp_path / "in"), "--t-end", "0.2",
                                       "--figures", "none", "--method", "modal"])
    assert result.exit_code == 0, result.output
    stats = [json.loads(text) for text in load_netcdf(tmp_path / "in" / "results.nc")["stats"].values]
    assert [s["engine"] for s in stats] == ["python", "python"]
    assert current_policy() is LIBRARY and LIBRARY.compiled_pays(10)
    assert not COMMAND_LINE.compiled_pays(10) and COMMAND_LINE.compiled_pays(2000)


def test_an_energy_balance_off_by_more_than_one_percent_is_warned_about_with_what_to_change():
    from unilateral.analysis.outputs import ENERGY_WARNING, energy_warnings, report

    peaks = {"unilateral": {"energy": {"max_relative_error": 0.046, "t_max_relative_error": 4.9}},
             "bilateral": {"energy": {"max_relative_error": 0.5 * ENERGY_WARNING}}}
    warnings = energy_warnings(peaks, rule="bdf2", dt=0.002)
    assert len(warnings) == 1
    assert "unilateral case" in warnings[0] and "4.6 %" in warnings[0]
    assert "--rule trapezoidal" in warnings[0] and "smaller --dt (now 0.002" in warnings[0]
    assert "--rule" not in energy_warnings(peaks, rule="trapezoidal", dt=0.002)[0]
    result = {"success": True, "message": "ok", "method": "cq", "rule": "bdf2", "lcp_solver": "bpp", "steps": 1,
              "dt": 0.002, "t_end": 0.002, "run_time": 0.1, "max_lcp_error": 0.0, "contact_changes": 0,
              "units": {}, "static": {}, "constraints": {}, "extra": {}, "warnings": warnings}
    assert f"WARNING: {warnings[0]}" in report(result)


def test_the_pounding_example_warns_about_its_numerical_dissipation(tmp_path):
    """examples/pounding.toml with its settings: bdf2 at dt = 2 ms dissipates 5.7 % of the input work
    numerically; the balance, with that term, closes."""
    out = tmp_path / "pounding"
    result = CliRunner().invoke(main, ["run", str(EXAMPLES / "pounding.toml"), "--out", str(out), "--figures", "none"])
    assert result.exit_code == 0, result.output
    assert ("WARNING: unilateral (with pounding) case: the bdf2 rule dissipated 5.7 % of the input work "
            "numerically") in result.output
    assert "the energy balance is off by" not in result.output
    summary = json.loads((out / "summary.json").read_text())
    assert any("--rule trapezoidal" in w and "T1/" in w for w in summary["warnings"])
    assert summary["results"]["unilateral"]["energy"]["max_relative_error"] < 1e-10


def test_the_progress_bar_gives_no_eta_from_the_set_up_time(capsys):
    """A run whose set-up takes 2 s before the first step reports: no ETA at 0 %, then the rate of
    the steps (1 000 steps per second here, on a clock the test drives)."""
    from unilateral.cli import _ProgressBar

    now = [0.0]
    bar = _ProgressBar(clock=lambda: now[0])
    now[0] = 2.0
    bar(0, 10_000)                      # the first report after the set-up: nothing timed yet
    assert "ETA     ?" in capsys.readouterr().err
    now[0] = 4.0
    bar(2_000, 10_000)                  # 2 000 steps in 2 s: 8 000 left, 8 s
    err = capsys.readouterr().err
    assert " 20.0%" in err and "ETA   8.0 s" in err, err
