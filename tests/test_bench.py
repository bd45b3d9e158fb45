"""The benchmark suite: synthetic accelerogram, problems, the command line and the figure."""

import json
import subprocess
import sys

import numpy as np
import pytest

import unilateral as ul
from unilateral.bench import PROBLEMS, ScalingConfig, build, run_one, run_scaling
from unilateral.bench.report import save_scaling_figure
from unilateral.bench.suite import Limits, infeasible
from unilateral.loads.synthetic import ENVELOPES, synthetic_accelerogram


def final_velocity(gm):
    a = gm.acceleration
    return gm.dt * (a.sum() - 0.5 * (a[0] + a[-1]))


@pytest.mark.parametrize("envelope", ENVELOPES)
def test_synthetic_accelerogram(envelope):
    gm = synthetic_accelerogram(10.0, 0.01, 2.5, seed=3, envelope=envelope)
    again = synthetic_accelerogram(10.0, 0.01, 2.5, seed=3, envelope=envelope)
    other = synthetic_accelerogram(10.0, 0.01, 2.5, seed=4, envelope=envelope)
    np.testing.assert_array_equal(gm.acceleration, again.acceleration)
    assert not np.allclose(gm.acceleration, other.acceleration)
    assert gm.npts == 1001 and gm.dt == 0.01
    assert gm.pga == pytest.approx(2.5, rel=1e-12)
    assert gm.name == "synthetic (Kanai-Tajimi, seed 3)"
    peak_velocity = np.max(np.abs(np.cumsum(gm.acceleration) * gm.dt))
    assert abs(final_velocity(gm)) < 1e-12 * peak_velocity
    a = np.abs(gm.acceleration)
    assert a[0] == 0.0
    assert a[:20].max() < 0.3 * gm.pga and a[-20:].max() < 0.3 * gm.pga     # starts and ends small
    assert 50 < np.argmax(a) < 600                                          # strong motion inside


def test_synthetic_accelerogram_bad_input():
    with pytest.raises(ValueError, match="pga"):
        synthetic_accelerogram(pga=-1.0)
    with pytest.raises(ValueError, match="envelope"):
        synthetic_accelerogram(envelope="boxcar")
    with pytest.raises(TypeError, match="seed"):
        synthetic_accelerogram(seed=1.5)


@pytest.mark.parametrize("name", PROBLEMS)
def test_problem_solves_20_steps(name):
    problem = build(name, quick=True)
    assert problem.N >= 200 and problem.dt > 0 and problem.description
    sol = ul.solve(problem.model, problem.load, dt=problem.dt, t_end=20 * problem.dt, method="direct")
    assert sol.success, sol.message
    y = problem.output(sol)
    assert y.shape == (21,) and np.all(np.isfinite(y))


def test_problem_names():
    assert build("winkler10", steps=30).model.m == 10
    with pytest.raises(ValueError, match="winkler<m>"):
        build("bridge")
    with pytest.raises(ValueError, match="steps"):
        build("paper", steps=0)


def test_cq_estimates_skip_large_runs():
    limits = Limits()
    assert infeasible("cq naive", 3000, 1000, 10_000, limits).startswith("estimated")
    assert infeasible("cq fft", 5, 3, 100_000, limits) == ""
    assert infeasible("direct", 3000, 1000, 10_000, limits) == ""


@pytest.mark.parametrize("method", ["modal", "cq fft"])
def test_run_one(tmp_path, method):
    """In-process run; a method that solve() rejects (no "modal" yet) is skipped with the reason."""
    record = run_one("winkler10", method, steps=30, output=tmp_path / "y.npz")
    assert (record["N"], record["n"], record["m"]) == (30, 29, 10)
    if method.split()[0] in ul.METHODS:
        assert record["status"] == "ok" and record["peak_mib"] > 0
        with np.load(tmp_path / "y.npz") as out:
            assert out["t"].shape == out["y"].shape == (31,)
    else:
        assert record["status"] == "skipped" and "modal" in record["reason"]


def test_direct_and_event_rows(tmp_path):
    """``direct`` runs compiled, ``direct python`` the Python loop (the same numbers), and
    ``event`` the exact reference; the event method refuses the Winkler problems' plain-function
    load, and the run is skipped with the reason."""
    runs = {method: run_one("paper", method, steps=100, output=tmp_path / f"{method}.npz")
            for method in ("direct", "direct python", "event")}
    assert all(r["status"] == "ok" and r["N"] == 100 and r["steps_s"] > 0 for r in runs.values())
    assert runs["direct"]["engine"] == "compiled" and runs["direct python"]["engine"] == "python"
    y = {method: np.load(tmp_path / f"{method}.npz")["y"] for method in runs}
    assert np.max(np.abs(y["direct"] - y["direct python"])) <= 1e-12 * np.max(np.abs(y["direct"]))
    assert 0 < np.max(np.abs(y["event"] - y["direct"])) < 0.05 * np.max(np.abs(y["event"]))
    assert runs["event"]["contact_changes"] == 8                # the exact events of the example
    skipped = run_one("winkler10", "event", steps=30)
    assert skipped["status"] == "skipped" and "plain callable" in skipped["reason"]


def test_command_line(tmp_path):
    out = tmp_path / "b.json"
    args = [sys.executable, "-m", "unilateral.bench", "--quick", "--problems", "paper",
            "--methods", "direct", "cq fft", "--no-figure", "--out", str(out)]
    proc = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    results = json.loads(out.read_text())
    assert results["machine"]["cpu_count"] >= 1 and results["machine"]["versions"]["numpy"]
    runs = {r["method"]: r for r in results["runs"]}
    assert set(runs) == {"reference", "direct", "cq fft"}
    for method in ("direct", "cq fft"):
        run = runs[method]
        assert run["status"] == "ok" and run["N"] == 2000 and (run["n"], run["m"]) == (5, 3)
        assert run["steps_s"] > 0 and run["total_s"] > 0 and run["peak_mib"] > 0
        assert np.isfinite(run["error"]) and run["error"] < 0.05
    assert "cq fft" in proc.stdout and "us/step" in proc.stdout

    # an impossible memory limit: the CQ run is skipped with its reason, and so is the reference
    skip = [sys.executable, "-m", "unilateral.bench", "--quick", "--problems", "winkler10",
            "--methods", "cq naive", "--no-figure", "--out", str(out), "--max-memory-gib", "1e-6"]
    proc = subprocess.run(skip, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    runs = {r["method"]: r for r in json.loads(out.read_text())["runs"]}
    assert runs["cq naive"]["status"] == "skipped" and "GiB" in runs["cq naive"]["reason"]
    assert runs["reference"]["status"] == "skipped"
    assert "skipped: estimated" in proc.stdout


def test_scaling_figure(tmp_path):
    # the Python loop: these short runs in fresh processes would mostly time numba's start
    config = ScalingConfig(steps=(32, 64), steps_methods=("direct python",), sizes=(4, 8),
                           sizes_steps=20, sizes_methods=("direct python",))
    records = run_scaling(config, limits=Limits(timeout=600.0))    # a hang guard: the runs take seconds
    assert [(r["sweep"], r["N"], r["m"]) for r in records] == [("N", 32, 3), ("N", 64, 3),
                                                                ("m", 20, 4), ("m", 20, 8)]
    assert all(r["status"] == "ok" and r["total_s"] > 0 for r in records)
    paths = save_scaling_figure(records, tmp_path / "scaling")
    assert [p.suffix for p in paths] == [".png", ".pdf"]
    assert all(p.stat().st_size > 1000 for p in paths)
