"""Fast at the prompt: the command line and a wrong model file answer before the heavy imports.

Each check runs in a fresh Python process (``sys.modules`` of this one holds whatever other tests
imported) and lists the modules loaded; no timing is asserted (shared, noisy machines):
``benchmarks/prompt.py`` measures the wall times.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "liolios1990.toml"
#: Imported by neither ``import unilateral.cli`` nor the check of a model file.
HEAVY = ("xarray", "matplotlib", "numba", "dask", "pandas")
#: Not needed by ``run`` and ``example`` either: results.nc is written without them.
NEVER_IN_RUN = ("dask", "pandas", "distributed")


def _in_subprocess(argv: list[str] | None, cwd: Path, blocked=()) -> dict:
    """Import ``unilateral.cli`` in a fresh process and, given ``argv``, run ``main(argv)``: the top-level
    packages then imported, the exit code, and what was printed. The packages ``blocked`` cannot be
    imported there, nor in the processes it forks (an import raises ImportError)."""
    env = dict(os.environ)
    if blocked:
        for name in blocked:
            (cwd / "blocked" / name).mkdir(parents=True, exist_ok=True)
            (cwd / "blocked" / name / "__init__.py").write_text(f"raise ImportError('{name} is blocked')\n")
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(cwd / "blocked"), env.get("PYTHONPATH")]))
    code = textwrap.dedent(f"""
        import contextlib, io, json, sys
        import unilateral.cli
        argv, code, out = {argv!r}, None, io.StringIO()
        if argv is not None:
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(out):
                try:
                    unilateral.cli.main(argv, prog_name="unilateral")
                except SystemExit as exc:
                    code = exc.code
        print(json.dumps({{"modules": sorted({{m.partition(".")[0] for m in sys.modules}}), "code": code,
                          "output": out.getvalue(), "submodules": sorted(sys.modules)}}))
    """)
    done = subprocess.run([sys.executable, "-c", code], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.splitlines()[-1])


def _model_file(tmp_path: Path, old: str, new: str, count: int = 1) -> Path:
    text = EXAMPLE.read_text()
    assert old in text
    path = tmp_path / "model.toml"
    path.write_text(text.replace(old, new, count))
    return path


def test_import_cli_imports_nothing_heavy(tmp_path):
    loaded = _in_subprocess(None, tmp_path)["modules"]
    assert not set(loaded) & {*HEAVY, "numpy", "scipy", "pydantic"}, loaded


#: A wrong model file is reported importing none of these (pydantic checks it; numpy is not needed).
NOT_FOR_A_WRONG_FILE = (*HEAVY, "scipy", "numpy")
RECORD = '[[loads.ground_motion]]\nfile = "records/missing.AT2"\ndirection = "ux"\n\n[analysis]'

#: ``(old, new, expected)``: a change of examples/liolios1990.toml and the start of the message it gives,
#: after ``<file>: ``.
WRONG_FILES = {
    "typo": ("node = 3, k = 200e3", "node = 3, kk = 200e3", 'unilateral[0].kk: unknown key (did you mean "k"?'),
    "negative-stiffness": ("k = 200e3", "k = -200e3", "unilateral[0].k = -200000.0: must be > 0"),
    "wrong-rule": ("rule = \"bdf2\"", "rule = \"bdf3\"", "analysis.rule = \"bdf3\""),
    "not-toml": ("units = {", "units = {{", "line 8, column 10: invalid TOML: "),
    "missing-equals": ("title = \"Liolios", "title \"Liolios",
                       "line 61, column 7: invalid TOML: Expected '=' after a key"),
    "open-string": ('title = "Liolios (1990), Fig. 2: vertical displacement of node 3"',
                    'title = "Liolios (1990), Fig. 2: vertical displacement of node 3',
                    "line 61, column 65: invalid TOML: Illegal character '\\n'; the line reads: title = \"Liolios"),
    "element-node": ("node_j = 1\n", "node_j = 17\n", "elements[0].node_j = 17: no node 17 (nodes are 1..4)"),
    "support-node": ("node = 2\nux = true", "node = 12\nux = true",
                     "supports[0].node = 12: no node 12 (nodes are 1..4)"),
    "load-node": ("node = 1\nux = 200.0", "node = 97\nux = 200.0",
                  "loads.nodal[0].node = 97: no node 97 (nodes are 1..4)"),
    "record-file": ("[analysis]", RECORD, 'loads.ground_motion[0].file = "records/missing.AT2": file not found'),
    "duplicate-name": ('name = "soil2"', 'name = "soil3"',
                       'unilateral[1].name = "soil3": duplicate element name (also unilateral[0].name)'),
    "same-node": ("node_i = 2\nnode_j = 1", "node_i = 1\nnode_j = 1",
                  "elements[0]: node_i and node_j are the same node 1"),
    "slave-twice": ("master = 2\nslave = 4", "master = 1\nslave = 3",
                    "rigid_links[1].slave = 3: node 3 is already a slave of node 2 (rigid_links[0])"),
    "floor-spectra": ("[output]", "[output]\nfloor_spectra = [1, 7]",
                      "output.floor_spectra[1] = 7: no node 7 (nodes are 1..4)"),
    "pulse-order": ('t_end = 0.1 }', 't_start = 0.2, t_end = 0.1 }',
                    "loads.nodal[0].time_function: t_end must be > t_start"),
}


@pytest.mark.parametrize("case", list(WRONG_FILES))
def test_a_wrong_model_file_fails_before_the_heavy_imports(tmp_path, case):
    """Syntax errors, wrong keys and values and the cross checks of the document: all before numpy."""
    old, new, expected = WRONG_FILES[case]
    path = _model_file(tmp_path, old, new)
    done = _in_subprocess(["run", str(path), "--out", str(tmp_path / "out")], tmp_path)
    assert done["code"] == 1, done["output"]
    assert f"{path}: {expected}" in done["output"], done["output"]
    assert not set(done["modules"]) & set(NOT_FOR_A_WRONG_FILE), done["modules"]
    assert not (tmp_path / "out").exists()


def test_plot_model_checks_the_file_first(tmp_path):
    path = _model_file(tmp_path, *WRONG_FILES["element-node"][:2])
    done = _in_subprocess(["plot", "--model", str(path), "--out", str(tmp_path / "out")], tmp_path)
    assert done["code"] == 1 and f"{path}: {WRONG_FILES['element-node'][2]}" in done["output"], done["output"]
    assert not set(done["modules"]) & set(NOT_FOR_A_WRONG_FILE), done["modules"]


@pytest.mark.parametrize("case", list(WRONG_FILES))
def test_the_quick_check_says_what_load_model_file_says(tmp_path, case):
    """The command line's check raises the error of the full reader, word for word (they run the same checks)."""
    from unilateral.cli import check_model_file
    from unilateral.modelfile import ModelFileError, load_model_file

    path = _model_file(tmp_path, *WRONG_FILES[case][:2])
    with pytest.raises(ModelFileError) as quick:
        check_model_file(path)
    with pytest.raises(ModelFileError) as full:
        load_model_file(path)
    assert str(quick.value) == str(full.value)
    assert str(quick.value).startswith(f"{path}: {WRONG_FILES[case][2]}")


def test_the_quick_check_reports_every_problem(tmp_path):
    from unilateral.cli import check_model_file
    from unilateral.modelfile import ModelFileError

    path = _model_file(tmp_path, "k = 200e3", "k = -200e3", count=2)
    path.write_text(path.read_text().replace("A = 1e12", "Area = 1e12"))
    with pytest.raises(ModelFileError) as quick:
        check_model_file(path)
    assert [p.partition(":")[0] for p in quick.value.problems] == [
        "elements[0].A", "elements[0].Area", "unilateral[0].k = -200000.0", "unilateral[1].k = -200000.0"]
    path = _model_file(tmp_path, "node_j = 1\n", "node_j = 17\n")
    path.write_text(path.read_text().replace("slave = 4", "slave = 44").replace('"soil2"', '"soil3"'))
    with pytest.raises(ModelFileError) as quick:
        check_model_file(path)
    assert [p.partition(":")[0] for p in quick.value.problems] == [
        'unilateral[1].name = "soil3"', "rigid_links[1].slave = 44", "elements[0].node_j = 17"]
    for name in ("liolios1990", "pounding", "winkler_beam", "yielding_frame"):    # (ida.toml is a study file)
        check_model_file(ROOT / "examples" / f"{name}.toml")                    # the valid files pass


def test_what_the_quick_check_leaves_to_the_full_reader(tmp_path):
    """What needs the structure (here a nodal load on a supported DOF) passes the quick check;
    ``load_model_file`` reports it."""
    from unilateral.cli import check_model_file

    path = _model_file(tmp_path, "node = 1\nux = 200.0", "node = 2\nux = 200.0")
    check_model_file(path)
    done = _in_subprocess(["run", str(path), "--figures", "none", "--out", str(tmp_path / "out")], tmp_path)
    assert done["code"] == 1 and f"{path}: loads.nodal[0]" in done["output"], done["output"]


def test_the_registry_names_match_the_registries():
    """The schema and the command line list the names without importing the registries."""
    from unilateral import _LCP_NAMES, _MATRIX_METHOD_NAMES, _RULE_NAMES
    from unilateral.lcp import LCP_SOLVERS
    from unilateral.methods import MATRIX_METHOD_NAMES
    from unilateral.rules import RULES

    assert _MATRIX_METHOD_NAMES == MATRIX_METHOD_NAMES
    assert _RULE_NAMES == tuple(RULES)                  # the order of the schema's enum
    assert _LCP_NAMES == tuple(sorted(LCP_SOLVERS))


@pytest.mark.parametrize("formats", ["none", "png"])
def test_example_imports_neither_dask_nor_pandas(tmp_path, formats):
    """Nor xarray, in the figure processes too (forked; they cannot import what is blocked)."""
    done = _in_subprocess(["example", "liolios1990", "--t-end", "0.05", "--figures", formats,
                           "--out", str(tmp_path / "out")], tmp_path, blocked=(*NEVER_IN_RUN, "xarray"))
    assert done["code"] in (None, 0), done["output"]
    assert not set(done["modules"]) & {*NEVER_IN_RUN, "xarray"}, done["modules"]
    assert (tmp_path / "out" / "results.nc").is_file()
    figures = sorted(path.name for path in (tmp_path / "out").glob("*.png"))
    assert figures == ([] if formats == "none" else
                       ["base_forces.png", "constraints.png", "energy.png", "fig2.png", "force_deformation.png"])


def test_run_imports_neither_dask_nor_pandas(tmp_path):
    done = _in_subprocess(["run", str(ROOT / "examples" / "yielding_frame.toml"), "--t-end", "0.05",
                           "--out", str(tmp_path / "out")], tmp_path, blocked=(*NEVER_IN_RUN, "xarray"))
    assert done["code"] in (None, 0), done["output"]
    assert "hysteresis.png" in {path.name for path in (tmp_path / "out").glob("*.png")}


#: Not imported by a run of a frame without figures: the Matrix Market reader (a model file without
#: matrices), the figure code, and the module of the one-thread BLAS limit's own (threadpoolctl is).
NOT_IN_A_RUN_WITHOUT_FIGURES = ("scipy.io", "matplotlib", "PIL", "unilateral.figures.results",
                                "unilateral.figures.plots", "xarray")


def test_a_run_without_figures_imports_only_what_it_uses(tmp_path):
    done = _in_subprocess(["run", str(ROOT / "examples" / "yielding_frame.toml"), "--t-end", "0.05",
                           "--figures", "none", "--out", str(tmp_path / "out")], tmp_path)
    assert done["code"] in (None, 0), done["output"]
    loaded = set(done["submodules"])
    assert not loaded & set(NOT_IN_A_RUN_WITHOUT_FIGURES), sorted(loaded & set(NOT_IN_A_RUN_WITHOUT_FIGURES))
    assert (tmp_path / "out" / "results.nc").is_file()


def _without_timings(ds):
    """``ds`` without what differs between two runs of the same analysis: the run times."""
    timed = [name for name in ds.data_vars if (name.startswith("time_") or name.endswith("_time")
                                                or name in ("stats", "modal"))]
    ds = ds.drop_vars(timed)
    ds.attrs = {key: value for key, value in ds.attrs.items()
                if not (key.startswith("time_") or key.endswith("_time") or key in ("stats", "modal"))}
    return ds


def test_results_nc_without_xarray_is_the_file_xarray_writes(tmp_path):
    """``run`` and ``example`` write results.nc without xarray: the file reads back as the one xarray
    writes for the same run (variables, coordinates, attributes, dtypes, _FillValue)."""
    import xarray as xr
    from click.testing import CliRunner

    from unilateral.cli import main
    from unilateral.io import load_netcdf

    args = ["example", "liolios1990", "--t-end", "0.05", "--figures", "none"]
    lean = _in_subprocess([*args, "--out", str(tmp_path / "lean")], tmp_path)
    assert lean["code"] in (None, 0) and "xarray" not in lean["modules"], lean["output"]
    result = CliRunner().invoke(main, [*args, "--out", str(tmp_path / "xarray")])   # xarray is imported here
    assert result.exit_code == 0, result.output
    a, b = (load_netcdf(tmp_path / name / "results.nc") for name in ("xarray", "lean"))
    xr.testing.assert_identical(_without_timings(a), _without_timings(b))
    assert len(a.data_vars) > 40 and "node_displacement" in b and "constraint_kind" in b.coords
    for name, variable in _without_timings(a).variables.items():
        assert b[name].dtype == variable.dtype, name
        assert str(b[name].encoding.get("_FillValue")) == str(variable.encoding.get("_FillValue")), name
    for name in ("displacements.csv", "constraints.csv", "base.csv", "bilateral_element_forces.csv"):
        assert (tmp_path / "lean" / name).read_bytes() == (tmp_path / "xarray" / name).read_bytes(), name
    opened = xr.open_dataset(tmp_path / "lean" / "results.nc")          # xarray's defaults read it too
    assert opened["u"].shape == a["u"].shape
    opened.close()


def test_the_small_dataset_matches_to_dataset():
    import xarray as xr

    from unilateral.io import to_dataset
    from unilateral.io.dataset import cases_dataset
    from unilateral.solve import solve
    from unilateral.structure.examples import liolios1990

    structure, load, _ = liolios1990()
    model = structure.to_model()
    cases = {name: solve(model, load, dt=1e-3, t_end=0.02, bilateral=name == "bilateral")
             for name in ("unilateral", "bilateral")}
    units, attrs = {"length": "m", "force": "kN", "time": "s"}, {"model": {"name": "liolios"}, "flag": True}
    xr.testing.assert_identical(cases_dataset(cases, units=units, attrs=attrs).to_xarray(),
                                to_dataset(cases, units=units, attrs=attrs))
    one = cases_dataset(cases["unilateral"], units=units)
    xr.testing.assert_identical(one.to_xarray(), to_dataset(cases["unilateral"], units=units))
    assert one.sizes == {"time": 21, "constraint": 3, "dof": model.n}
    view = one.isel(time=slice(0, 5))
    assert view["u"].transpose("dof", ...).values.shape == (model.n, 5)
