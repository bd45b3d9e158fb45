"""The cost of ``method="event"`` without a clock: what the march evaluates, not how long it takes.

The event march brackets events on a sub-grid at half a radian of the fastest oscillation of the
configuration. On the benchmark tower (axially rigid columns, 1.7e5 rad/s) that grid has 3.5
million points over the 10 s record whatever the output step: a fixed cost of seconds. The grid is
now sampled sparsely where a modal bound rules out a crossing (``_March._plan``). These tests count
the states the march evaluates, check that the bound is a bound, that the sparse sampling finds the
events of the full sub-grid, and that the root finder locates roots without importing
``scipy.optimize``. No verdict depends on a wall-clock time.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from unilateral.bench.problems import build
from unilateral.loads import LoadHistory, Rectangular
from unilateral.march import event
from unilateral.march.event import _March, _matrices
from unilateral.march.event_search import _slack, find_root
from unilateral.march.event_config import Config
from unilateral.march.event_load import load_generator

T_TOWER = 1.5           # s: the tower's first two events (uplift at 1.420 s and 1.461 s)


@pytest.fixture(scope="module")
def tower():
    return build("tower", steps=1000)       # dt = 0.01 s


def fine_grid_size(march_model, load, t_end):
    """The number of points of the full bracketing sub-grid over ``t_end`` (all contacts closed)."""
    gen = load_generator(march_model, load, [0.0, t_end])
    cfg = Config(_matrices(march_model), gen, np.zeros(march_model.m, dtype=bool), march_model.law)
    return t_end * cfg.max_frequency / event.SUBSTEP_RADIANS


def test_the_tower_no_longer_evaluates_the_full_sub_grid(tower, monkeypatch):
    """The full sub-grid over 1.5 s has 5e5 points (3.5e6 over the record); the march evaluates a
    few thousand states around each event and about one per output step elsewhere (under 2 % of
    the grid), and never asks for the powers of the fine step over a whole output step."""
    requested = []
    powers = Config.powers

    def counting(self, h, J):
        requested.append(J)
        return powers(self, h, J)

    monkeypatch.setattr(Config, "powers", counting)
    sol = ul.solve(tower.model, tower.load, dt=tower.dt, t_end=T_TOWER, method="event")
    assert sol.success and sol.stats["events"] == 2
    N = round(T_TOWER / tower.dt)
    fine = fine_grid_size(tower.model, tower.load, T_TOWER)
    assert fine > 4e5
    assert sol.stats["substeps"] < 0.02 * fine
    per_step = fine / N                                         # about 3500 fine points per step
    assert max(requested) < 0.25 * per_step


def test_cleared_output_steps_are_taken_together(tower, monkeypatch):
    """At dt = 1 ms the record's breakpoints (every 10 ms) are the only steps taken one by one
    before the first uplift; the outputs are those of the step-by-step march."""
    calls = []
    advance = _March.advance

    def counting(self, *args, **kwargs):
        calls.append(args[2])
        return advance(self, *args, **kwargs)

    monkeypatch.setattr(_March, "advance", counting)
    together = ul.solve(tower.model, tower.load, dt=1e-3, t_end=1.0, method="event")
    assert together.success and together.stats["events"] == 0
    assert len(calls) <= 110                                    # 100 breakpoints, 1000 steps
    monkeypatch.setattr(_March, "_glide", lambda self, cfg, Y, *args: (0, Y))
    calls.clear()
    alone = ul.solve(tower.model, tower.load, dt=1e-3, t_end=1.0, method="event")
    assert len(calls) == 1000
    # to the stiff tower's round-off floor (psi = K u with an axial stiffness of 1e12)
    np.testing.assert_allclose(together.u, alone.u, rtol=0, atol=1e-10 * np.abs(alone.u).max())
    np.testing.assert_allclose(together.psi, alone.psi, rtol=0, atol=1e-7 * np.abs(alone.psi).max())


def test_the_first_plan_of_the_tower_takes_the_whole_output_step(tower):
    """From the static state under gravity, the bound clears a whole output step at once."""
    t = np.arange(11) * tower.dt
    gen = load_generator(tower.model, tower.load, t)
    u0, udot0, v0 = static(tower)
    march = _March(tower.model.law, _matrices(tower.model), gen, t, (u0, udot0, v0), tol=1e-13,
                   max_events=1000)
    cfg = march.config(np.zeros(tower.model.m, dtype=bool))
    Y = cfg.state_from(u0, udot0, v0, gen.state(0.0, "right"))
    J = int(np.ceil(tower.dt / cfg.hmax))
    plan = march._plan(cfg, Y, 0.0, J, tower.dt / J)
    assert J > 1000 and plan[4] == J


def static(problem):
    from unilateral.initial import static_state
    from unilateral.lcp import get_lcp_solver

    init = static_state(problem.model, problem.load(0.0), get_lcp_solver("bpp"))
    return init.u, np.zeros(problem.model.n), init.v


@pytest.mark.parametrize("mask", [(False, False, False), (True, False, False), (False, False, True)])
def test_the_bound_holds_on_the_fine_grid(tower, mask):
    """``e_i(t) <= max(e_i(a), e_i(b)) + slack(b - a)`` at every point of the fine grid, for states
    far from equilibrium (random displacements and velocities, every mode excited) and widths from
    the whole stretch down to a few fine steps."""
    rng = np.random.default_rng(sum(mask))
    t = np.linspace(0.0, 0.05, 6)
    gen = load_generator(tower.model, tower.load, t)
    u0, udot0, v0 = static(tower)
    march = _March(tower.model.law, _matrices(tower.model), gen, t, (u0, udot0, v0), tol=1e-13,
                   max_events=1000)
    cfg = march.config(np.array(mask))
    sp = cfg.spectral()
    assert sp is not None
    L = 0.01                                                      # the first load piece
    J = 2048
    h = L / J
    for trial in range(3):
        Y = cfg.state_from(u0 * (1 + 0.05 * rng.standard_normal(u0.size)),
                           0.01 * rng.standard_normal(u0.size), v0 + 1e-4 * rng.random(v0.size),
                           gen.state(0.0, "right"))
        bounds = march._bounds(cfg, sp, Y, L)
        plan = (cfg, (J, h), L, 0.0, 2, *bounds, {})
        Ys = np.vstack([Y, cfg.powers(h, J) @ Y])
        e = Ys @ cfg.E.T                                          # (J + 1, m)
        noise = 2 * event.ROUNDOFF * (np.abs(Ys) @ cfg.absE.T).max(axis=0)    # round-off of e
        above = False
        for r in (J, 256, 16, 4):
            inside = np.array([e[q * r:(q + 1) * r + 1].max(axis=0) for q in range(J // r)])
            ends = np.maximum(e[0:J:r], e[r::r])
            assert np.all(inside <= ends + _slack(plan, r * h) + noise)
            above |= bool(np.any(inside > ends + noise))
        assert above                                              # the samples alone miss maxima


def two_masses():
    """A mass on a contact spring (2000) carrying a second mass on a stiff spring (1e6, 1414 rad/s),
    thrown up, landing and bouncing, kicked at 0.2 s: the stiff mode rings after every landing."""
    m, kc, ks, g = 1.0, 2000.0, 1e6, 10.0
    model = ul.Model(M=np.eye(2) * m, K=[[kc + ks, -ks], [-ks, ks]], F=[[kc], [0.0]], H=[[kc]])
    load = LoadHistory([-m * g, -m * g], [([0.0, 30.0], Rectangular(1.0, t_start=0.2, t_end=0.25))])
    u0 = -2 * m * g / kc
    return model, load, {"u0": [u0, u0 - m * g / ks], "udot0": [1.0, 1.0], "v0": [0.0]}


def test_sparse_sampling_finds_the_events_of_the_full_sub_grid(monkeypatch):
    """The same events and motion as the full sub-grid (the march before the sparse sampling), to
    round-off, with fewer states evaluated."""
    model, load, initial = two_masses()
    sparse = ul.solve(model, load, dt=1e-2, t_end=2.0, method="event", initial=initial)
    monkeypatch.setattr(_March, "_plan_for", lambda self, cfg, Y, t, J, h: None)
    full = ul.solve(model, load, dt=1e-2, t_end=2.0, method="event", initial=initial)
    assert sparse.stats["events"] == full.stats["events"] == 18
    assert sparse.stats["substeps"] < 0.6 * full.stats["substeps"]
    np.testing.assert_allclose(sparse.stats["event_times"], full.stats["event_times"], rtol=0, atol=1e-12)
    assert list(sparse.stats["event_kinds"]) == list(full.stats["event_kinds"])
    for a, b in ((sparse.u, full.u), (sparse.udot, full.udot), (sparse.v, full.v), (sparse.psi, full.psi)):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-10 * np.abs(b).max())


def test_sparse_sampling_finds_the_tower_events_of_the_full_sub_grid(tower, monkeypatch):
    sparse = ul.solve(tower.model, tower.load, dt=tower.dt, t_end=T_TOWER, method="event")
    monkeypatch.setattr(_March, "_plan_for", lambda self, cfg, Y, t, J, h: None)
    full = ul.solve(tower.model, tower.load, dt=tower.dt, t_end=T_TOWER, method="event")
    assert list(sparse.stats["event_constraints"]) == list(full.stats["event_constraints"])
    # the stiff tower's round-off floor (the full sub-grid's results move by 1e-10 with dt)
    np.testing.assert_allclose(sparse.stats["event_times"], full.stats["event_times"], rtol=0, atol=1e-9)
    for a, b in ((sparse.u, full.u), (sparse.v, full.v), (sparse.psi, full.psi)):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-7 * np.abs(b).max())


def test_find_root_locates_the_root_to_the_tolerance():
    rng = np.random.default_rng(0)
    done, evaluations = 0, []
    while done < 200:
        c = rng.standard_normal(4)
        w = rng.uniform(0.5, 30.0)
        calls = [0]

        def f(s):
            calls[0] += 1
            return c[0] + c[1] * s + c[2] * np.sin(w * s) + c[3] * np.exp(-s)

        b = rng.uniform(0.01, 2.0)
        if f(0.0) * f(b) >= 0:
            continue
        for xtol in (2.5e-14, 1e-6):
            calls[0] = 0
            r = find_root(f, 0.0, b, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=200)
            evaluations.append(calls[0])
            # a sign change within the tolerance of r (the root it located)
            tol = xtol + 4 * np.finfo(float).eps * abs(r)
            lo, hi = max(r - tol, 0.0), min(r + tol, b)
            assert f(lo) * f(hi) <= 0 or abs(f(r)) < 1e-14, (r, f(lo), f(hi))
        done += 1
    assert np.median(evaluations) < 20          # superlinear: far fewer than bisection's ~47
    with pytest.raises(ValueError, match="different signs"):
        find_root(lambda s: 1.0 + s, 0.0, 1.0, xtol=1e-12, rtol=1e-15, maxiter=10)
    with pytest.raises(RuntimeError, match="not located"):
        find_root(lambda s: np.tanh(100 * (s - 0.3)), 0.0, 1.0, xtol=1e-15, rtol=1e-15, maxiter=3)


def test_the_event_march_does_not_import_scipy_optimize():
    """``scipy.optimize`` takes 0.2-0.5 s to import: the event march uses its own root finder."""
    code = ("import sys, unilateral as ul\n"
            "from unilateral.loads import LoadHistory\n"
            "model = ul.Model(M=[[2.0]], K=[[2000.0]], F=[[2000.0]], H=[[2000.0]])\n"
            "sol = ul.solve(model, LoadHistory([-20.0]), dt=1e-3, t_end=0.5, method='event',\n"
            "               initial={'u0': [-0.01], 'udot0': [1.0], 'v0': [0.0]})\n"
            "assert sol.stats['events'] >= 3, sol.stats['events']\n"
            "print('scipy.optimize' in sys.modules)\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "False"


def test_benchmark_smoke(tmp_path):
    """``benchmarks/event_speed.py --quick`` prints its table and writes its JSON (no timing asserted)."""
    out = tmp_path / "event_speed.json"
    script = Path(__file__).resolve().parents[1] / "benchmarks" / "event_speed.py"
    proc = subprocess.run([sys.executable, str(script), "--quick", "--out", str(out)],
                          capture_output=True, text=True, timeout=900, env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    assert "per event ms" in proc.stdout and "load average" in proc.stdout
    report = json.loads(out.read_text())
    assert len(report["load_average"]) == 3
    rows = {r["model"].split()[0] + " " + r["model"].split()[1]: r for r in report["rows"]}
    assert set(rows) == {"tower dt=0.1", "paper dt=0.0025", "epp sdof"}
    assert rows["tower dt=0.1"]["events"] == 12 and rows["paper dt=0.0025"]["events"] == 8
    for r in report["rows"]:
        assert r["setup_s"] >= 0 and r["per_step_us"] > 0 and r["total_s"] > 0
