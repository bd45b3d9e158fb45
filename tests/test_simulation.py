"""``Simulation``: an analysis advanced step by step equals ``solve`` (the same operations).

Stepping one step at a time, in uneven pieces, or stopped and resumed gives the solution of one
call to ``solve`` to round-off (bit for bit where the march is the same code), for the tower, a
yielding frame, a frame on footings on a soil medium and a 3-D frame; the bad-input cases of the
stepping API give clear errors; a failed step leaves the state at the last good step.
"""

import dataclasses

import numpy as np
import pytest

import unilateral as ul
from unilateral.bench.problems import build
from unilateral.methods import Direct
from unilateral import Simulation

import yield_portal
from test_frame3d import portal


def rel(a, b):
    return np.max(np.abs(np.asarray(a) - np.asarray(b))) / max(np.max(np.abs(b)), 1e-300)


def tower(steps=600):
    p = build("tower", steps=steps)
    return p.model, p.load, dict(dt=p.dt, t_end=p.N * p.dt)


def yielding_frame():
    st = yield_portal.frame()
    g = st.gravity(9.81)
    push = st.nodal_load(2, ux=1.0) + st.nodal_load(3, ux=1.0)
    return st.to_model(), (lambda t: g + 60.0 * np.sin(8.0 * t) * push), dict(dt=2e-3, t_end=1.0)


def frame3d():
    st = portal(3)
    g = st.gravity(9.81)
    push = st.nodal_load(3, ux=1.0) + st.nodal_load(5, ux=1.0)
    return st.to_model(), (lambda t: g + 800.0 * (0.0 < t <= 0.15) * push), dict(dt=2e-3, t_end=0.6,
                                                                                  rule="trapezoidal")


def footings():
    from unilateral.structure.examples import two_bay_on_footings

    st, load, _ = two_bay_on_footings(duration=0.4)
    return st.to_model(), load, dict(dt=0.01, t_end=0.4)


def winkler():
    p = build("winkler100", steps=300)                 # 299 DOFs, 100 springs: the full sparse space
    return p.model, p.load, dict(dt=p.dt, t_end=p.N * p.dt)


CASES = {"tower": tower, "yielding frame": yielding_frame, "3-D frame": frame3d, "winkler": winkler}


def stepped(model, load, pieces=None, **kw):
    """A simulation stepped one step at a time (or in the given pieces) to its end."""
    sim = Simulation(model, load, **kw)
    if pieces is None:
        while sim.status == "running":
            assert sim.step() is None
    else:
        for k in pieces:
            assert sim.advance(k) is None
        sim.advance_to(sim.t_end)
    assert sim.status == "finished" and sim.n == sim.N
    return sim


def assert_equal_solutions(a, b, tol):
    assert a.success and b.success, (a.message, b.message)
    np.testing.assert_array_equal(a.t, b.t)
    for field in ("u", "udot", "v", "psi"):
        assert rel(getattr(a, field), getattr(b, field)) <= tol, field


@pytest.mark.parametrize("engine", ["compiled", "python"])
@pytest.mark.parametrize("case", sorted(CASES))
def test_stepping_one_step_at_a_time_equals_solve(case, engine):
    model, load, kw = CASES[case]()
    method = Direct(engine=engine)
    whole = ul.solve(model, load, method=method, **kw)
    sim = stepped(model, load, method=method, **kw)
    assert sim.stats["engine"] == engine
    assert sim.stats["stepping"] == ("chunk" if engine == "compiled" else "step")
    assert sim.stats["lcp_space"] == ("full" if case == "winkler" else "condensed")
    assert_equal_solutions(sim.solution(), whole, 0.0)       # the same operations: bit for bit
    assert sim.solution().message == whole.message


@pytest.mark.parametrize("case", sorted(CASES))
def test_a_run_stopped_and_resumed_equals_an_uninterrupted_one(case):
    model, load, kw = CASES[case]()
    whole = ul.solve(model, load, **kw)
    sim = Simulation(model, load, **kw)
    N = sim.N
    sim.advance(N // 3)
    assert sim.n == N // 3 and sim.t == pytest.approx(sim.n * kw["dt"])
    middle = sim.solution()
    assert len(middle.t) == N // 3 + 1 and middle.success and "so far" in middle.message
    assert_equal_solutions(middle, _cut(whole, N // 3), 0.0)
    sim.step()
    sim.advance_to(0.5 * kw["t_end"] + 0.3 * kw["dt"])          # between grid times: the next one
    assert sim.n == int(np.ceil(0.5 * N + 0.3))
    sim.advance_to(kw["t_end"])
    assert_equal_solutions(sim.solution(), whole, 0.0)


def test_the_state_is_the_solution_at_the_current_step():
    model, load, kw = yielding_frame()
    whole = ul.solve(model, load, **kw)
    sim = Simulation(model, load, **kw)
    for k in (0, 1, 7, 200):
        sim.advance_to(k * kw["dt"])
        s = sim.state
        assert s.k == k and s.t == pytest.approx(k * kw["dt"])
        for field in ("u", "udot", "v", "psi"):
            np.testing.assert_array_equal(getattr(s, field), getattr(whole, field)[k])
        s.u[:] = 1e9                                               # a copy: the run is not touched
    assert_equal_solutions(sim.run_to_end(), whole, 0.0)


def test_a_frame_on_footings_on_a_soil_steps_to_the_solution_of_solve():
    model, load, kw = footings()
    whole = ul.solve(model, load, **kw)
    sim = Simulation(model, load, **kw)
    assert sim.method.name == whole.stats["method"]
    half = sim.N // 2
    sim.advance(half)
    assert rel(sim.state.u, whole.u[half]) <= 1e-12
    assert_equal_solutions(sim.run_to_end(), whole, 1e-12)
    assert sim.stats["stepping"] == "whole"                     # the CLCP marches in one call


def test_the_cost_of_a_step_from_python_is_counted_in_calls_into_compiled_code(monkeypatch):
    """One ``sim.step()`` of a compiled march calls the compiled loop once per chunk, not per step."""
    import unilateral.march.direct as march_direct

    calls = []
    original = march_direct.CompiledDirectMarch.run_steps

    def counting(self, n0, n1):
        calls.append((n0, n1))
        return original(self, n0, n1)

    monkeypatch.setattr(march_direct.CompiledDirectMarch, "run_steps", counting)
    model, load, kw = tower(2000)
    sim = stepped(model, load, method=Direct(engine="compiled"), **kw)
    assert sim.n == 2000
    sizes = [n1 - n0 for n0, n1 in calls]
    assert sum(sizes) == 2000 and len(calls) <= 10, sizes          # chunks of 16, 32, ... 4096
    assert sizes[0] == march_direct.AHEAD_MIN and sizes[1] == 2 * march_direct.AHEAD_MIN


def test_the_event_march_steps_to_the_solution_of_solve():
    """``method="event"`` is pulled as far as it is asked for: the same events and outputs."""
    from conftest import rocking_model
    from test_event import rocking_pulses

    model, load = rocking_model(kelvin=False), rocking_pulses()
    kw = dict(dt=2e-3, t_end=1.0, method="event")
    whole = ul.solve(model, load, **kw)
    sim = Simulation(model, load, **kw)
    assert sim.stats["stepping"] == "step"
    sim.advance(200)
    assert sim.state.k == 200 and sim.solution().stats["events"] < whole.stats["events"]
    while sim.status == "running":
        sim.step()
    sol = sim.solution()
    assert_equal_solutions(sol, whole, 0.0)
    assert sol.stats["event_times"] == whole.stats["event_times"] and sol.message == whole.message


# ---------------------------------------------------------------------- bad input
def test_stepping_after_the_end_is_a_clear_error():
    model, load, kw = yielding_frame()
    sim = Simulation(model, load, **dict(kw, t_end=0.01))
    sim.advance_to(0.01)
    assert sim.status == "finished"
    with pytest.raises(RuntimeError, match=r"at its end, t_end = 0.01 s \(step 5\).*no step is left"):
        sim.step()
    assert sim.advance_to(0.01) is None                            # already there: nothing to do


@pytest.mark.parametrize("bad, match", [
    (dict(t=-1.0), r"t = -1 s is before the current time 0.01 s \(step 5\)"),
    (dict(t=5.0), r"t = 5 s is after t_end = 1 s"),
    (dict(t=float("nan")), r"t must be a finite time"),
    (dict(t="1"), r"t must be a finite time"),
    (dict(steps=0), r"steps must be an integer >= 1, got 0"),
    (dict(steps=2.5), r"steps must be an integer >= 1"),
    (dict(steps=True), r"steps must be an integer >= 1"),
    (dict(steps=10_000), r"steps = 10000 goes past t_end = 1 s: 495 step\(s\) are left"),
])
def test_bad_stepping_requests_name_the_argument_and_what_is_valid(bad, match):
    model, load, kw = yielding_frame()
    sim = Simulation(model, load, **kw)
    sim.advance(5)
    with pytest.raises(ValueError, match=match):
        sim.advance_to(bad["t"]) if "t" in bad else sim.advance(bad["steps"])
    assert sim.n == 5 and sim.status == "running"


def test_a_method_that_does_not_apply_says_why():
    model, load, kw = yielding_frame()
    with pytest.raises(ValueError, match=r"rule='hht' has no convolution-quadrature form.*method='direct'"):
        Simulation(model, load, method="cq", **dict(kw, rule="hht"))
    with pytest.raises(ValueError, match=r"valid keys: 'cq', 'modal', 'direct'"):
        Simulation(model, load, options={"newmark": {}}, **kw)


@pytest.mark.parametrize("engine", ["compiled", "python"])
def test_a_failed_step_leaves_the_state_at_the_last_good_step(engine):
    model, load, kw = tower(400)
    # block principal pivoting allowed one linear solve fails at step 93 (t = 2.325 s)
    whole = ul.solve(model, load, method=Direct(engine=engine), lcp_options={"max_iter": 1}, **kw)
    sim = Simulation(model, load, method=Direct(engine=engine), lcp_options={"max_iter": 1}, **kw)
    message = None
    while sim.status == "running":
        message = sim.step()
    assert sim.status == "failed" and message and message == sim.message
    k = sim.n
    sol = sim.solution()
    assert not sol.success and len(sol.t) == k + 1 and "failed" in sol.message
    assert sol.message == whole.message and k == len(whole.t) - 1 < sim.N
    assert_equal_solutions(dataclasses.replace(sol, success=True), dataclasses.replace(whole, success=True), 0.0)
    np.testing.assert_array_equal(sim.state.u, sol.u[k])
    with pytest.raises(RuntimeError, match=rf"failed at step {k + 1}.*solution\(\) holds steps 0..{k}"):
        sim.step()


def _cut(sol, K):
    return ul.Solution(t=sol.t[:K + 1], v=sol.v[:K + 1], psi=sol.psi[:K + 1], psiL=None, u=sol.u[:K + 1],
                       udot=sol.udot[:K + 1])


def test_the_stepping_benchmark_runs_and_reports_the_overhead(tmp_path):
    """``benchmarks/simulation_step.py`` at a small size: its table and JSON (no timing asserted)."""
    import json
    import os
    import subprocess
    import sys
    from pathlib import Path

    script = Path(__file__).resolve().parents[1] / "benchmarks" / "simulation_step.py"
    out = tmp_path / "simulation_step.json"
    proc = subprocess.run([sys.executable, str(script), "--repeats", "1", "--steps", "200", "--out", str(out)],
                          capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    assert "overhead us/step" in proc.stdout and "load average" in proc.stdout
    rows = {r["engine"]: r for r in json.loads(out.read_text())["rows"]}
    assert rows["compiled"]["stepping"] == "chunk" and rows["python"]["stepping"] == "step"
    assert all(r["max_difference"] == 0.0 and r["steps"] == 200 for r in rows.values())


def test_a_method_that_does_not_apply_names_those_that_do():
    m, k, g = 2.0, 2000.0, 10.0
    model = ul.Model(M=[[m]], K=[[k]], F=[[k]], H=[[k]])
    load = lambda t: np.array([-m * g])                         # noqa: E731
    with pytest.raises(ValueError, match=r"method=.time-kernel. solves a KernelModel of a TimeKernel, not a Model; "
                                         r"the methods that apply to this problem: 'cq', 'modal', 'direct', 'event'"):
        Simulation(model, load, dt=1e-3, t_end=0.01, method="time-kernel")
    with pytest.raises(ValueError, match=r"the methods that apply to this problem: 'direct', 'event'$"):
        Simulation(model, load, dt=1e-3, t_end=0.01, method="modal", rule="hht")
    auto = Simulation(model, load, dt=1e-3, t_end=0.01)
    others = auto.stats["method_alternatives"]
    assert auto.method.name == "direct" and set(others) == {"cq", "modal", "time-kernel", "event", "moreau-jean"}
    assert others["time-kernel"].startswith("method='time-kernel' solves a KernelModel of a TimeKernel")
    assert others["moreau-jean"].startswith("method='moreau-jean' solves models whose every unknown is a rigid")
    assert others["cq"].startswith("applies")


def test_a_small_model_runs_with_one_blas_thread_and_the_process_keeps_its_own():
    """The threads of OpenBLAS are set to one while a small model is solved (its products are too
    small to share), and given back afterwards; the answer does not depend on it."""
    from threadpoolctl import threadpool_info, threadpool_limits

    blas = lambda: {i["filepath"]: i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"}  # noqa: E731
    model, load, kw = yielding_frame()
    seen = []

    def recording(t):
        seen.append(max(blas().values()))
        return load(t)

    with threadpool_limits(limits=2, user_api="blas"):
        before = blas()
        sol = ul.solve(model, recording, **kw)
        assert blas() == before
    assert seen and set(seen) == {1}
    assert_equal_solutions(sol, ul.solve(model, load, **kw), 0.0)
