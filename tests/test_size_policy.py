"""The size policy (every threshold of the choice of a march in one object) and the registry of
direct marches: the choice depends on the policy in force, never on what the process imported."""

import numpy as np
import pytest

import unilateral as ul
from unilateral.bench.problems import build
from unilateral.march.policy import COMMAND_LINE, LIBRARY, SizePolicy, current_policy, size_policy
from unilateral.methods import Direct
from unilateral.methods.direct import MARCHES


def tower(steps=200):
    p = build("tower", steps=steps)
    return p.model, p.load, dict(dt=p.dt, t_end=p.N * p.dt)


def winkler():
    p = build("winkler100", steps=100)                 # 299 DOFs, 100 springs (sparse)
    return p.model, p.load, dict(dt=p.dt, t_end=p.N * p.dt)


def test_the_policy_in_force_is_scoped_and_restored_after_an_error():
    assert current_policy() is LIBRARY
    with pytest.raises(RuntimeError), size_policy(COMMAND_LINE):
        assert current_policy() is COMMAND_LINE
        raise RuntimeError("inside")
    assert current_policy() is LIBRARY


def test_the_policy_chooses_the_engine_and_the_space_and_both_give_the_same_solution():
    model, load, kw = tower()
    library = ul.solve(model, load, method="direct", **kw)
    short = ul.solve(model, load, method="direct", policy=COMMAND_LINE, **kw)
    assert (library.stats["engine"], short.stats["engine"]) == ("compiled", "python")
    assert library.stats["march"] == "compiled condensed" and short.stats["march"] == "python condensed"
    assert "compile_min_steps = 2000" in short.stats["march_alternatives"]["compiled condensed"]
    peak = np.max(np.abs(library.u))
    assert np.max(np.abs(library.u - short.u)) <= 1e-10 * peak
    model, load, kw = winkler()
    full = ul.solve(model, load, method="direct", **kw)
    condensed = ul.solve(model, load, method="direct", policy=LIBRARY.replace(full_space_min_m=1000), **kw)
    assert (full.stats["lcp_space"], condensed.stats["lcp_space"]) == ("full", "condensed")
    assert np.max(np.abs(full.v - condensed.v)) <= 1e-9 * np.max(np.abs(full.v))


def test_a_simulation_keeps_its_policy_while_it_steps():
    model, load, kw = tower()
    sim = ul.Simulation(model, load, method="direct", policy=COMMAND_LINE, **kw)
    assert sim.policy is COMMAND_LINE and current_policy() is LIBRARY
    sim.advance(5)
    assert sim.stats["engine"] == "python" and current_policy() is LIBRARY
    np.testing.assert_array_equal(sim.run_to_end().u, ul.solve(model, load, method="direct", policy=COMMAND_LINE,
                                                               **kw).u)


def test_every_march_of_the_registry_says_why_it_does_not_apply():
    model, load, kw = tower()
    sol = ul.solve(model, load, method=Direct(engine="python"), **kw)
    reasons = sol.stats["march_alternatives"]
    assert sol.stats["march"] == "python condensed"
    assert set(reasons) == {m.name for m in MARCHES} - {"python condensed"}
    assert all(isinstance(why, str) and why for why in reasons.values())
    assert "engine='python'" in reasons["compiled condensed"]


def test_engine_compiled_with_a_solver_it_cannot_use_is_refused_with_every_reason():
    model, load, kw = tower()
    with pytest.raises(ValueError, match=r"direct_options\['engine'\]='compiled': no direct march applies.*"
                                         r"lcp='bpp'"):
        ul.solve(model, load, method="direct", lcp="lemke", direct_options={"engine": "compiled"}, **kw)


@pytest.mark.parametrize("changes, match", [
    ({"compiled_max_n": -1}, "compiled_max_n must be an integer >= 0, got -1"),
    ({"full_space_min_m": 2.5}, "full_space_min_m must be an integer >= 0, got 2.5"),
    ({"sweep_step_cost": float("nan")}, "sweep_step_cost must be a number >= 0"),
    ({"compile_min_steps": True}, "compile_min_steps must be an integer >= 0, got True"),
    ({"dense_max": 3}, "SizePolicy has no field 'dense_max'; valid: compile_min_steps"),
])
def test_a_bad_policy_names_the_field_and_what_is_valid(changes, match):
    with pytest.raises(ValueError, match=match):
        LIBRARY.replace(**changes)


def test_a_policy_that_is_not_one_is_refused():
    model, load, kw = tower()
    with pytest.raises(TypeError, match="policy must be a unilateral.SizePolicy or None, got"):
        ul.Simulation(model, load, policy={"compiled_max_n": 10}, **kw)
    assert isinstance(ul.SizePolicy(), SizePolicy)
