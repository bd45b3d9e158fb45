"""The engine chosen by cost (SizePolicy.engine_choice="cost"): the Python loops against the compiled
ones plus their compile or load, numba's cache read only when the answer depends on it; the engine
a caller pins is kept; both engines give the same solution."""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from unilateral.bench.problems import build
from unilateral.march import loops, policy
from unilateral.march.policy import LIBRARY, SizePolicy
from unilateral.methods import Direct

SRC = Path(__file__).resolve().parents[1] / "src"
COST = LIBRARY.replace(engine_choice="cost")


@pytest.fixture(autouse=True)
def nothing_spent(monkeypatch):
    """Every test starts as a fresh process: no Python seconds spent for lack of compiled loops."""
    monkeypatch.setattr(policy, "_SPENT", [0.0])


def never_read():
    raise AssertionError("the cache was read though the choice did not depend on it")


def test_a_short_run_goes_to_python_and_a_long_one_compiles_without_reading_the_cache():
    short, reason, state = COST.engine_cost(100, 17, 3, never_read)
    assert (short, state) == (False, None) and "less than loading" in reason
    long, reason, state = COST.engine_cost(10**6, 17, 3, never_read)
    assert (long, state) == (True, None) and "more than compiling" in reason


@pytest.mark.parametrize("state, compiled", [("cold", False), ("cached", True), ("loaded", True),
                                             ("unknown", True)])
def test_between_the_two_the_cache_decides(state, compiled):
    steps = 10_000                          # Python about 2 s: above the load, below the compile
    assert COST.load_s < COST.python_seconds(steps, 17, 3) < COST.compile_s
    chosen, reason, read = COST.engine_cost(steps, 17, 3, lambda: state)
    assert (chosen, read) == (compiled, state)
    assert ("compiled" if compiled else "Python") in reason.rsplit(":", 1)[-1]


def test_a_process_that_keeps_choosing_python_compiles_once_it_has_spent_the_compile_cost():
    steps, choices = 10_000, []
    python = COST.python_seconds(steps, 17, 3)
    for _ in range(10):
        choices.append(COST.engine_cost(steps, 17, 3, lambda: "cold")[0])
    first = choices.index(True)
    # ski rental: Python until the seconds spent plus this run reach the compile cost, then compiled
    assert first == int(np.ceil(COST.compile_s / python)) - 1
    assert not any(choices[:first]) and policy.python_seconds_spent() == pytest.approx(first * python)


def test_the_steps_rule_never_reads_the_cache_and_validation_names_the_field():
    steps_rule = LIBRARY.replace(engine_choice="steps")
    assert steps_rule.compiled_pays(10) and steps_rule.engine_choice == "steps"
    with pytest.raises(ValueError, match="engine_choice must be one of 'cost', 'steps', got 'fast'"):
        SizePolicy(engine_choice="fast")
    with pytest.raises(ValueError, match=r"python_step_s must be a tuple of 3 finite numbers >= 0, got \(1.0,\)"):
        SizePolicy(python_step_s=(1.0,))
    with pytest.raises(ValueError, match="compile_s must be a number >= 0"):
        SizePolicy(compile_s=float("nan"))


def tower(steps):
    p = build("tower", steps=steps)
    return p.model, p.load, dict(dt=p.dt, t_end=p.N * p.dt)


def test_the_solve_says_which_engine_the_cost_chose_and_why_and_both_agree(monkeypatch):
    model, load, kw = tower(10_000)
    monkeypatch.setattr(loops, "cache_state", lambda functions: "cold")
    cold = ul.solve(model, load, method="direct", policy=COST, **kw)
    assert cold.stats["engine"] == "python" and cold.stats["numba_cache"] == "cold"
    assert "cold numba cache" in cold.stats["engine_reason"]
    assert "cold numba cache" in cold.stats["march_alternatives"]["compiled condensed"]
    pinned = ul.solve(model, load, method=Direct(engine="compiled"), policy=COST, **kw)
    assert pinned.stats["engine"] == "compiled" and "numba_cache" not in pinned.stats
    monkeypatch.setattr(policy, "_SPENT", [0.0])
    monkeypatch.setattr(loops, "cache_state", lambda functions: "cached")
    cached = ul.solve(model, load, method="direct", policy=COST, **kw)
    assert cached.stats["engine"] == "compiled" and cached.stats["numba_cache"] == "cached"
    peak = np.abs(cold.u).max()
    assert np.abs(cold.u - cached.u).max() <= 1e-10 * peak
    np.testing.assert_array_equal(cached.u, pinned.u)


def test_the_loops_of_a_compiled_run_are_loaded_in_its_process():
    model, load, kw = tower(50)
    ul.solve(model, load, method=Direct(engine="compiled"), **kw)
    assert loops.cache_state(loops.CONDENSED) == "loaded"


def run_python(code, env):
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(SRC), **env}, timeout=600)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_the_cache_state_of_a_loop_is_cold_then_cached_then_loaded(tmp_path):
    (tmp_path / "tiny_loop.py").write_text("from numba import njit\n\n@njit(cache=True)\ndef f(x):\n    return x + 1.0\n")
    code = f"""
        import json, sys
        sys.path.insert(0, {str(tmp_path)!r})
        import tiny_loop
        from unilateral.march.loops import cache_state
        before = cache_state([tiny_loop.f])
        tiny_loop.f(1.0)
        print(json.dumps([before, cache_state([tiny_loop.f])]))
    """
    env = {"NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    assert run_python(code, env) == ["cold", "loaded"]
    assert run_python(code, env) == ["cached", "loaded"]


def test_a_short_run_in_a_fresh_process_never_imports_numba(tmp_path):
    code = """
        import json, sys
        import unilateral as ul
        from unilateral.bench.problems import build
        p = build("tower", steps=200)
        sol = ul.solve(p.model, p.load, dt=p.dt, t_end=p.N * p.dt)
        print(json.dumps([sol.stats["engine"], "numba" in sys.modules]))
    """
    assert run_python(code, {"UNILATERAL_ENGINE_CHOICE": "cost", "NUMBA_CACHE_DIR": str(tmp_path)}) == ["python", False]


def test_a_wrong_engine_choice_in_the_environment_is_refused_by_name():
    done = subprocess.run([sys.executable, "-c", "import unilateral.march.policy"], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(SRC), "UNILATERAL_ENGINE_CHOICE": "fast"}, timeout=300)
    assert done.returncode != 0
    assert "UNILATERAL_ENGINE_CHOICE='fast' is not valid: set it to 'cost' or 'steps'" in done.stderr
