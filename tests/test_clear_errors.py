"""Issue "No traceback, no hang, no silent accept": each case ends in a clear message.

An absurd number of steps, an output folder name too long for its staging folder, a damaged
results.nc given to ``unilateral plot``, a failed plot in a run's folder, ``--rule newmark`` with
``--method cq`` and random small models for ``method="event"``. No verdict depends on the time a
test takes: the event march is checked by counting its events and decisions.
"""

from __future__ import annotations

import errno
import json
import os
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import unilateral as ul
from unilateral.cli import main
from unilateral.discretization import MAX_STEPS
from unilateral.io import open_results, save_netcdf
from unilateral.io.folder import MANIFEST
from unilateral.loads import LoadHistory, Rectangular
from unilateral.march.event import default_max_events
from unilateral.methods.event import Event

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "liolios1990.toml"


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def listing(folder: Path) -> dict:
    """name -> bytes of every entry in ``folder`` (hidden ones too; a folder as None)."""
    return {p.name: (p.read_bytes() if p.is_file() else None) for p in sorted(folder.iterdir())}


@pytest.fixture(scope="module")
def example():
    from unilateral.structure.examples import liolios1990

    structure, load, _ = liolios1990()
    return structure.to_model(), load


@pytest.fixture(scope="module")
def run_folder(tmp_path_factory):
    """A run of the paper's example without figures."""
    out = tmp_path_factory.mktemp("run") / "out"
    result = invoke("run", EXAMPLE, "--out", out, "--t-end", "0.05", "--figures", "none")
    assert result.exit_code == 0, result.output
    return out


# ---------------------------------------------------------------------- 1. t_end / dt
@pytest.mark.parametrize("method", ["auto", "cq", "modal", "direct", "event"])
def test_an_absurd_number_of_steps_is_refused_naming_t_end_and_dt(example, method):
    model, load = example
    with pytest.raises(ValueError, match=r"t_end=1e\+308 with dt=0\.001 gives t_end/dt = inf steps, more than "
                                         r"the 1e\+09 an analysis may have: shorten t_end or increase dt"):
        ul.solve(model, load, dt=1e-3, t_end=1e308, method=method)
    with pytest.raises(ValueError, match=r"t_end=2000000\.0 with dt=0\.001 gives t_end/dt = 2e\+09 steps"):
        ul.solve(model, load, dt=1e-3, t_end=2e6, method=method)
    assert MAX_STEPS == 10**9


def test_an_absurd_t_end_on_the_command_line_and_in_a_model_file(tmp_path):
    result = invoke("run", EXAMPLE, "--t-end", "1e308", "--out", tmp_path / "a", "--figures", "none")
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert "Error: t_end=1e+308 with dt=0.001 gives t_end/dt = inf steps, more than the 1e+09" in result.output
    text = EXAMPLE.read_text()
    assert "\nt_end = " in text
    model = tmp_path / "model.toml"
    model.write_text(text.replace("\nt_end = ", "\nt_end = 1e308 # ", 1))
    result = invoke("run", model, "--out", tmp_path / "b", "--figures", "none")
    assert result.exit_code == 1
    assert "Error: t_end=1e+308 with dt=0.001 gives t_end/dt = inf steps" in result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["model.toml"]


# ---------------------------------------------------------------------- 2. --out too long
def test_an_out_name_too_long_for_the_staging_folder_is_refused_before_solving(tmp_path):
    limit = os.pathconf(tmp_path, "PC_NAME_MAX")
    extra = len(".") + len(".staging-") + 7 + len("-") + 8
    result = invoke("run", EXAMPLE, "--out", tmp_path / ("a" * 300), "--figures", "none")
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert "Invalid value for '--out'" in result.output
    assert (f"its name has 300 bytes and the staging folder next to it adds {extra}, more than the {limit} a "
            f"file name may have here: give a name of at most {limit - extra} bytes") in result.output
    assert list(tmp_path.iterdir()) == []
    longest = tmp_path / ("b" * (limit - extra))
    result = invoke("run", EXAMPLE, "--out", longest, "--t-end", "0.005", "--figures", "none")
    assert result.exit_code == 0, result.output
    assert (longest / "results.nc").exists()


# ---------------------------------------------------------------------- 3. plot a damaged results.nc
def damaged(run_folder, tmp_path, change):
    """A copy of the run's results.nc changed by ``change(ds)`` (returns the Dataset to write)."""
    ds = change(open_results(run_folder / "results.nc").copy(deep=True))
    path = tmp_path / "in" / "results.nc"
    path.parent.mkdir()
    save_netcdf(ds, path)
    return path


def with_attrs(**attrs):
    def change(ds):
        ds.attrs.update(attrs)
        return ds
    return change


def infinite_v(rows):
    def change(ds):
        ds["v"][{"time": rows}] = np.inf
        return ds
    return change


@pytest.mark.parametrize("change, skipped", [
    (lambda ds: ds.drop_vars("energy_relative_error"),
     ["skipped energy: the figure needs what the file lacks: No variable named 'energy_relative_error'"]),
    (with_attrs(figure_node="99"),
     ["skipped fig2: the attribute figure_node = '99' names no node of node_displacement; valid: '1', '2', '3', '4'"]),
    (with_attrs(figure_dof="uz"),
     ["skipped fig2: the attribute figure_dof = 'uz' names no component of node_displacement; valid: 'ux', 'uy', "
      "'rz'"]),
    (with_attrs(case_labels="not json"),
     [f"skipped {name}: the attribute case_labels = 'not json' (8 characters) is not a JSON object of case "
      'names to labels, e.g. {"unilateral": "with uplift"}' for name in ("fig2", "base_forces")]),
    (with_attrs(case_labels="[1, 2]"), ["skipped fig2: the attribute case_labels = '[1, 2]' (6 characters)"]),
    (with_attrs(case_labels="[" * 100_000 + "]" * 100_000),
     ["skipped fig2: the attribute case_labels = '[[[[", "(200000 characters) is not a JSON object"]),
    (with_attrs(case_labels="[" * 20_000 + "]" * 20_000),       # short enough to parse: too deep
     ["skipped fig2: the attribute case_labels = '[[[[", "(40000 characters) is not a JSON object"]),
], ids=["variable-missing", "figure-node", "figure-dof", "labels-not-json", "labels-a-list", "labels-100000-deep",
        "labels-20000-deep"])
def test_plot_draws_what_it_can_and_says_what_it_skipped(run_folder, tmp_path, change, skipped):
    path = damaged(run_folder, tmp_path, change)
    result = invoke("plot", path)
    assert result.exit_code == 1 and "Traceback" not in result.output
    for text in skipped:
        assert text in result.output
    assert (path.parent / "constraints.png").exists()           # the others are drawn


@pytest.mark.parametrize("change, message", [
    (infinite_v(slice(None)), "the variable v is not finite (inf or NaN) at t = 0: there is nothing to draw"),
    (lambda ds: ds.isel(time=slice(0, 0)), "the dimension time has length 0: there is no time step to draw"),
], ids=["v-infinite", "no-time-step"])
def test_plot_of_a_results_nc_with_nothing_to_draw(run_folder, tmp_path, change, message):
    path = damaged(run_folder, tmp_path, change)
    result = invoke("plot", path)
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert f"Error: cannot draw the figures of {path}: {message}" in result.output
    assert sorted(p.name for p in path.parent.iterdir()) == ["results.nc"]


def test_plot_stops_where_v_becomes_infinite_and_says_so(run_folder, tmp_path):
    path = damaged(run_folder, tmp_path, infinite_v(slice(20, None)))
    result = invoke("plot", path)
    assert result.exit_code == 0, result.output
    assert "drawn up to t = 0.019: after it u or v are not finite" in result.output


def test_a_megabyte_title_is_cut_before_it_is_laid_out(run_folder, tmp_path, monkeypatch):
    from matplotlib.axes import Axes

    from unilateral.figures.results import MAX_TEXT

    path = damaged(run_folder, tmp_path, with_attrs(title="x" * 1_000_000, figure_text="y" * 100_000))
    drawn = []
    def recording(original):
        def method(self, text, *args, **kwargs):
            drawn.append(text)
            return original(self, text, *args, **kwargs)
        return method

    for name in ("set_title", "set_ylabel"):
        monkeypatch.setattr(Axes, name, recording(getattr(Axes, name)))
    result = invoke("plot", path)
    assert result.exit_code == 0, result.output
    assert max(map(len, drawn)) <= MAX_TEXT + len(" [mm]")
    assert "x" * (MAX_TEXT - 1) + "\u2026" in drawn


# ---------------------------------------------------------------------- 4. plot into a run's folder
def test_plot_into_a_run_folder_keeps_its_manifest_true(run_folder, tmp_path):
    import shutil

    out = tmp_path / "copy"
    shutil.copytree(run_folder, out)
    result = invoke("plot", out / "results.nc", "--figures", "png,svg")
    assert result.exit_code == 0, result.output
    listed = json.loads((out / MANIFEST).read_text())["files"]
    assert sorted(p.name for p in out.iterdir() if p.name != MANIFEST) == listed
    assert {"fig2.png", "fig2.svg", "energy.png"} <= set(listed)
    # a later run accepts the folder (every file is listed) and replaces it
    result = invoke("run", EXAMPLE, "--out", out, "--t-end", "0.01", "--figures", "none")
    assert result.exit_code == 0, result.output


def test_a_plot_that_fills_the_disk_leaves_the_run_folder_as_it_was(run_folder, tmp_path, monkeypatch):
    import shutil

    from matplotlib.figure import Figure

    out = tmp_path / "copy"
    shutil.copytree(run_folder, out)
    before = listing(out)
    saved = []

    def half_then_enospc(self, fname, **kwargs):
        saved.append(fname)
        if len(saved) < 3:                     # two figures complete, the third fills the disk
            return original(self, fname, **kwargs)
        Path(fname).write_bytes(b"\x89PNG half")
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    original = Figure.savefig
    monkeypatch.setattr(Figure, "savefig", half_then_enospc)
    result = invoke("plot", out / "results.nc")
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert f"Error: cannot write the figures to {out}: could not write" in result.output
    assert f"No space left on device; {out} is unchanged" in result.output
    assert len(saved) == 3 and listing(out) == before


# ---------------------------------------------------------------------- 5. --rule newmark --method cq
def test_newmark_with_cq_runs_as_trapezoidal_and_says_so(tmp_path, example):
    note = ("rule 'newmark' without parameters is Newmark(gamma=0.5, beta=0.25), the trapezoidal rule: it ran "
            "as rule 'trapezoidal'")
    result = invoke("run", EXAMPLE, "--out", tmp_path / "o", "--t-end", "0.01", "--figures", "none",
                    "--rule", "newmark", "--method", "cq")
    assert result.exit_code == 0, result.output
    assert "method cq, rule trapezoidal" in result.output and f"note: {note}" in result.output
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["rule"] == "trapezoidal" and summary["rule_note"] == note
    model, load = example
    sol = ul.solve(model, load, dt=1e-3, t_end=0.01, method="cq", rule="newmark")
    ref = ul.solve(model, load, dt=1e-3, t_end=0.01, method="cq", rule="trapezoidal")
    assert sol.stats["rule_note"] == note and "rule_note" not in ref.stats
    np.testing.assert_array_equal(sol.v, ref.v)
    result = invoke("run", EXAMPLE, "--out", tmp_path / "p", "--t-end", "0.01", "--figures", "none")
    assert "note:" not in result.output and "rule_note" not in (tmp_path / "p" / "summary.json").read_text()


# ---------------------------------------------------------------------- 6. method="event" on random models
def random_model(seed, rank=3):
    """n = 1, m = 3: a unit mass on a spring, three unilateral unknowns coupled through H (PSD of
    ``rank``; 3: positive definite, with [[K, -F], [-F^T, H]] positive definite), capacities g > 0,
    from rest under a rectangular pulse of random sign, size and length."""
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(4, 4))
    S = A @ A.T + 0.1 * np.eye(4)
    S *= 100.0 / S[0, 0]
    K, F, H = S[:1, :1], -S[:1, 1:], S[1:, 1:]
    if rank < 3:
        B = rng.normal(size=(3, rank))
        H = 10.0 * B @ B.T
    model = ul.Model(M=[[1.0]], K=K, F=F, H=H, g=rng.uniform(0.1, 2.0, 3))
    pulse = Rectangular(1.0, t_end=rng.uniform(0.05, 0.5))
    return model, LoadHistory([0.0], [([rng.normal() * rng.uniform(5.0, 50.0)], pulse)])


REST = {"u0": [0.0], "udot0": [0.0], "v0": [0.0] * 3}
DT, T_END = 1e-3, 2.0


def test_event_on_random_coupled_models_ends_with_a_solution_and_few_decisions():
    limit = default_max_events(round(T_END / DT), 3)
    for seed in range(40):
        model, load = random_model(seed)
        sol = ul.solve(model, load, dt=DT, t_end=T_END, method="event", initial=REST)
        assert sol.success, (seed, sol.message)
        assert np.isfinite(sol.u).all() and np.all(sol.v >= 0.0)
        assert sol.stats["events"] <= 60 and sol.stats["decisions"] <= sol.stats["events"] + 5, seed
        assert sol.stats["events"] < limit


def test_event_on_a_mechanism_stops_with_the_reason():
    """H of rank 1 (coupled, singular): once two unknowns open, the structure is a mechanism; cq's step
    LCP has no solution there either. The decisions kept coming back to that time (a hang)."""
    stopped = 0
    for seed in range(12):
        model, load = random_model(seed, rank=1)
        sol = ul.solve(model, load, dt=DT, t_end=T_END, method="event", initial=REST)
        if sol.success:
            continue
        stopped += 1
        assert sol.message.startswith(f"stopped after {len(sol.t) - 1} of 2000 steps: the decisions keep coming "
                                      "back to t = ")
        assert "candidates skipped there: a configuration leaves coordinates without mass, damping or " \
               "stiffness (active constraints [" in sol.message
        assert sol.stats["decisions"] <= sol.stats["events"] + 4 * 3 + 20
    assert stopped >= 6


def test_event_stops_a_motion_that_grows_without_bound():
    """F too large for K and H: with every unknown open the stiffness is indefinite and the motion
    diverges; it was returned as a success full of inf and NaN."""
    H = [[49.1175, -11.5071, -20.0633], [-11.5071, 21.6064, -3.9226], [-20.0633, -3.9226, 12.1345]]
    model = ul.Model(M=[[1.0]], K=[[147.8449]], F=[[40.6907, -35.1318, -54.5204]], H=H, g=[0.6292, 0.9018, 0.1077])
    load = LoadHistory([0.0], [([-29.4706], Rectangular(1.0, t_end=0.4272))])
    sol = ul.solve(model, load, dt=DT, t_end=T_END, method="event", initial=REST)
    assert not sol.success and np.isfinite(sol.u).all() and len(sol.t) < 2001
    assert "the motion grows without bound: u, v are not finite at t = " in sol.message
    assert ("the configuration with unknowns [0, 1, 2] open (active) has a growing mode, rate" in sol.message
            and "not positive semidefinite; check K, F and H" in sol.message)


def test_event_limits_the_contact_changes_in_proportion_to_the_time_reached():
    m, k, g, V0 = 2.0, 2000.0, 10.0, 1.0                           # a bouncing mass: 7 changes in 1 s
    model = ul.Model(M=[[m]], K=[[k]], F=[[k]], H=[[k]])
    init = {"u0": [-m * g / k], "udot0": [V0], "v0": [0.0]}
    full = ul.solve(model, LoadHistory([-m * g]), dt=1e-3, t_end=1.0, method="event", initial=init)
    assert full.success and full.stats["events"] == 7
    times = full.stats["event_times"]
    allowed = [int(np.ceil(3 * (t + 1e-3) / (1.0 + 1e-3))) for t in times]
    first = next(i for i in range(7) if i + 1 > allowed[i])    # the first change beyond the allowance
    sol = ul.solve(model, LoadHistory([-m * g]), dt=1e-3, t_end=1.0, method=Event(max_events=3), initial=init)
    assert not sol.success and sol.stats["events"] == first + 1 < 7
    t = times[first]
    assert sol.message == (f"stopped after {len(sol.t) - 1} of 1000 steps: more than {allowed[first]} contact "
                           f"changes by t = {t:.6g} (max_events = 3 over the run, allowed in proportion to the "
                           "time reached): chattering, or changes accumulating at one time; raise max_events if "
                           "this is expected, or use method='cq' or 'direct'")
    np.testing.assert_array_equal(sol.u, full.u[:len(sol.t)])
    assert default_max_events(1000, 1) == 100 * 1001


def test_a_synthetic_record_too_long_to_generate_is_refused_before_allocating():
    from unilateral.loads import synthetic_accelerogram

    for duration, dt in ((1e9, 0.01), (1e308, 1e-308)):
        with pytest.raises(ValueError, match=r"samples: the record and its filtering would need about .* GiB"):
            synthetic_accelerogram(duration, dt)
    assert synthetic_accelerogram(2.0, 0.01).dt == 0.01


def test_a_study_influence_vector_is_checked_from_its_header(tmp_path):
    """The influence vector of a matrix-level study is read as the model files' matrices are: a
    complex or wrongly sized file is refused naming it, before its values are used."""
    from types import SimpleNamespace

    import numpy as np
    import scipy.io

    from unilateral.batch.worker import _ground_vector

    spec = SimpleNamespace(model=SimpleNamespace(n=3, M=np.diag([1.0, 2.0, 3.0])))
    for name, values in (("r.mtx", np.ones((3, 1))), ("c.mtx", np.ones((3, 1)) * (1 + 1j)),
                         ("w.mtx", np.ones((4, 1)))):
        scipy.io.mmwrite(tmp_path / name, values)
    def vector(name):        # the client sends the file's bytes; the worker reads its own copy
        return _ground_vector(spec, {"influence": str(tmp_path / name)}, (tmp_path / name).read_bytes())

    assert np.allclose(vector("r.mtx"), [-1.0, -2.0, -3.0])
    with pytest.raises(ValueError, match=r"\.mtx.*complex matrix"):
        vector("c.mtx")
    with pytest.raises(ValueError, match=r"\.mtx.*expected a vector of 3 entries"):
        vector("w.mtx")
