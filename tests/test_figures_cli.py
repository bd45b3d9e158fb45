"""The command line and the figures: lazy imports, early option errors, run and plot drawing the
same files from results.nc, the structure's results in results.nc, CSV and summary.json, the
Python entry point, progress from the compiled march."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import unilateral
from unilateral.cli import LCP_NAMES, METHOD_NAMES, RULE_NAMES, main
from unilateral.io import load_netcdf

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
HEAVY = ("numpy", "scipy", "xarray", "matplotlib", "numba")


def test_importing_the_command_line_imports_nothing_heavy():
    code = ("import sys, unilateral, unilateral.cli; "
            f"print([m for m in {HEAVY!r} if m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_the_figure_code_does_not_import_scipy():
    """The figure process imports it while the run solves, on the same cores: matplotlib only."""
    code = "import sys, unilateral.figures.results; print(sorted(m for m in sys.modules if m.startswith('scipy')))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_python_dash_m_unilateral():
    out = subprocess.run([sys.executable, "-m", "unilateral", "--help"], capture_output=True, text=True)
    assert out.returncode == 0 and "Usage:" in out.stdout and "run" in out.stdout


def test_the_command_line_lists_the_registries():
    from unilateral.lcp import LCP_SOLVERS
    from unilateral.methods import MATRIX_METHOD_NAMES
    from unilateral.rules import RULES

    assert set(METHOD_NAMES) == set(MATRIX_METHOD_NAMES)          # --help shows every choice
    assert set(RULE_NAMES) == set(RULES)
    assert set(LCP_NAMES) == set(LCP_SOLVERS)


def test_a_bad_lcp_fails_at_once_naming_the_choices():
    result = CliRunner().invoke(main, ["run", str(EXAMPLES / "pounding.toml"), "--lcp", "foo"])
    assert result.exit_code == 2
    assert "--lcp" in result.output and "bpp" in result.output and "lemke" in result.output
    result = CliRunner().invoke(main, ["example", "liolios1990", "--method", "fastest"])
    assert result.exit_code == 2 and "'modal'" in result.output
    result = CliRunner().invoke(main, ["example", "liolios1990", "--figures", "gif"])
    assert result.exit_code == 2 and "png" in result.output


def test_lazy_package_attributes():
    assert callable(unilateral.solve) and unilateral.run is unilateral.analysis.memory.run
    assert "Model" in dir(unilateral)
    with pytest.raises(AttributeError):
        unilateral.no_such_name


@pytest.fixture(scope="module")
def pounding(tmp_path_factory):
    out = tmp_path_factory.mktemp("pounding")
    result = CliRunner().invoke(main, ["run", str(EXAMPLES / "pounding.toml"), "--out", str(out),
                                       "--t-end", "2.0"])
    assert result.exit_code == 0, result.output
    return out, result.output


def test_run_writes_the_structure_results(pounding):
    out, output = pounding
    ds = load_netcdf(out / "results.nc").sel(case="unilateral")      # the only case (no bilateral reference)
    for name in ("end_force", "axial_force", "support_reaction", "base_shear", "overturning_moment",
                 "absolute_acceleration", "ground_acceleration", "storey_drift", "drift_ratio",
                 "energy_kinetic", "energy_input_work", "energy_relative_error", "mode_period", "mode_shape"):
        assert name in ds, name
        assert ds[name].attrs.get("long_name"), name
    assert ds["base_shear"].attrs["units"] == "kN"
    assert ds["absolute_acceleration"].attrs["units"] == "m/s^2"
    # the absolute acceleration is the relative one plus the ground's along x
    ag = ds["ground_acceleration"].values[:, 0]
    k = list(ds["dof"].values).index("7.ux")
    np.testing.assert_allclose(ds["absolute_acceleration"].values[:, k] - ds["acceleration"].values[:, k], ag)
    summary = json.loads((out / "summary.json").read_text())
    peaks = summary["results"]["unilateral"]
    assert set(peaks["base_shear"]) == {"max", "t_max", "min", "t_min"}
    assert peaks["periods"][0] == pytest.approx(float(ds["mode_period"][0]))
    assert peaks["energy"]["max_relative_error"] < 0.05
    assert "peak base shear" in output and "periods" in output
    header = (out / "element_forces.csv").read_text().splitlines()[0].split(",")
    assert "A_col_left:M_i [kN m]" in header and "joint:N_j [kN]" in header
    assert (out / "base.csv").read_text().startswith("time [s],base_shear [kN]")
    # the printed static table is short (the frames have 30 DOFs)
    assert output.count("\n") < 60


def test_plot_redraws_the_same_figures_from_results_nc(pounding, tmp_path):
    out, _ = pounding
    drawn = sorted(p.name for p in out.glob("*.png"))
    assert {"fig2.png", "constraints.png", "gaps.png", "ground_motion.png", "base_forces.png",
            "energy.png"} <= set(drawn)
    assert not list(out.glob("*.pdf"))                              # PNG only by default
    result = CliRunner().invoke(main, ["plot", str(out / "results.nc"), "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in tmp_path.glob("*.png")) == drawn
    for name in drawn:
        assert (tmp_path / name).read_bytes() == (out / name).read_bytes(), name


def test_plot_formats_and_a_file_that_is_not_results_nc(pounding, tmp_path):
    out, _ = pounding
    result = CliRunner().invoke(main, ["plot", str(out / "results.nc"), "--out", str(tmp_path),
                                       "--figures", "pdf"])
    assert result.exit_code == 0 and (tmp_path / "fig2.pdf").exists() and not (tmp_path / "fig2.png").exists()
    result = CliRunner().invoke(main, ["plot", str(out / "summary.json")])
    assert result.exit_code == 2
    assert "not a results.nc" in result.output


def test_run_model_file_from_python(tmp_path):
    result = unilateral.run(EXAMPLES / "liolios1990.toml", out=tmp_path, t_end=0.1, figures=())
    assert result["success"] and result["figures"] == []
    assert (tmp_path / "results.nc").exists() and not list(tmp_path.glob("*.png"))
    assert "base_shear" in result["results"]["unilateral"]


def test_progress_comes_from_the_compiled_march_in_chunks():
    from unilateral.structure.examples import liolios1990

    st, load, _ = liolios1990()
    model = st.to_model()
    calls = []
    plain = unilateral.solve(model, load, dt=1e-3, t_end=1.0, method="modal")
    reported = unilateral.solve(model, load, dt=1e-3, t_end=1.0, method="modal",
                                callback=lambda k, N: calls.append((k, N)))
    assert reported.stats["engine"] == plain.stats["engine"] == "compiled"
    np.testing.assert_array_equal(reported.v, plain.v)
    np.testing.assert_array_equal(reported.u, plain.u)
    assert 2 <= len(calls) < 100 and calls[-1] == (1000, 1000)
    assert [k for k, _ in calls] == sorted(k for k, _ in calls)


def test_run_help_shows_every_method_and_bench_help_agrees_with_the_readme():
    text = CliRunner().invoke(main, ["run", "--help"]).output
    assert "--method [" + "|".join(METHOD_NAMES) + "]" in text and "..." not in text
    from unilateral.bench.__main__ import DEFAULT_OUT, parser

    assert "bench-results/benchmarks.json" in parser().format_help().replace("\n", " ").replace("  ", "")
    readme = (EXAMPLES.parent / "README.md").read_text(encoding="utf-8")
    assert f"`{DEFAULT_OUT.as_posix()}`" in readme and "`bench-results/scaling.png`" in readme
