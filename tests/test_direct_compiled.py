"""The compiled direct march performs the Python march's operations: equal to round-off.

``method="direct"`` with ``engine="compiled"`` (the default where it applies) steps the full model
with the rule in numba code, the condensed LCP on ``W0`` solved by warm-started block principal
pivoting; ``engine="python"`` is the reference loop of :func:`unilateral.march.direct.march_direct`.
"""

import numpy as np
import pytest

import unilateral as ul
import unilateral.march.direct as march_direct_module
from conftest import MASS, GRAVITY, rocking_load, rocking_natural
from unilateral.bench.problems import build
from unilateral.methods import Direct

RULES = ("bdf1", "bdf2", "trapezoidal", "newmark", "hht", ul.rules.Newmark(0.6, 0.3025))


def rel(a, b):
    return np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300)


def both(model, load, **kw):
    """The same run with both engines."""
    runs = {e: ul.solve(model, load, method=Direct(engine=e), **kw) for e in ("compiled", "python")}
    assert runs["compiled"].stats["engine"] == "compiled" and runs["python"].stats["engine"] == "python"
    return runs["compiled"], runs["python"]


def assert_same(a, b, tol):
    assert a.success and b.success, (a.message, b.message)
    assert len(a.t) == len(b.t)
    for field in ("v", "psi", "u", "udot"):
        assert rel(getattr(a, field), getattr(b, field)) <= tol, field
    for key in ("contact_changes", "lcp_iterations", "lcp_max_iterations"):
        assert a.stats[key] == b.stats[key], key


def paper_model(kelvin, capacity=0.0):
    """The paper's example (tests/conftest.py), optionally with a tension capacity of the soil."""
    nat = rocking_natural(kelvin)
    return ul.Model.from_natural(nat["G"], nat["E"], nat["B"], M=nat["M"], E_v=nat["E_v"], C=nat["C"],
                                 r=np.full(3, capacity))


def random_model(kelvin, seed=7, n=12, m=4):
    """A random structure: ``n`` DOFs, ``ne = n + m`` strains, the last ``m`` unilateral, capacities."""
    rng = np.random.default_rng(seed)
    ne = n + m
    G = rng.normal(size=(n, ne))
    E = np.diag(rng.uniform(50.0, 200.0, ne))
    B = np.zeros((ne, m))
    B[n:, :] = np.eye(m)
    masses = rng.uniform(0.5, 2.0, n)
    masses[-2:] = 0.0                                   # massless DOFs, as under a foundation
    E_v = np.diag(np.r_[np.zeros(n), rng.uniform(1.0, 3.0, m)]) if kelvin else None
    Q = rng.normal(size=(n, n))
    C = None if kelvin else 0.02 * (Q @ Q.T)
    return ul.Model.from_natural(G, E, B, M=np.diag(masses), C=C, E_v=E_v, r=rng.uniform(0.0, 0.5, m))


def random_load(model, seed=7):
    """A constant load plus two opposite pulses along random directions."""
    rng = np.random.default_rng(seed + 1)
    d0, d1, d2 = (rng.normal(size=model.n) for _ in range(3))
    return lambda t: 2.0 * d0 + 40.0 * d1 * (0.05 < t <= 0.3) - 40.0 * d2 * (0.6 < t <= 0.8)


@pytest.mark.parametrize("kelvin", [False, True])
@pytest.mark.parametrize("rule", RULES, ids=str)
def test_compiled_equals_python_on_the_paper_example(kelvin, rule):
    """Kelvin contacts under the seed's pulse: a harder one makes them chatter, and closed
    contacts then carry round-off times ``W0 ~ c s*`` in psi (see tests/test_solve.py)."""
    model = paper_model(kelvin)
    a, b = both(model, rocking_load(P=200.0 if kelvin else 300.0), dt=2e-3, t_end=1.0, rule=rule)
    assert (a.v[:, 0] > 1e-6).any()                     # the left edge lifts off and lands again
    assert a.stats["contact_changes"] >= 2
    assert_same(a, b, 1e-10 if kelvin else 1e-12)


@pytest.mark.parametrize("kelvin", [False, True])
@pytest.mark.parametrize("rule", RULES, ids=str)
def test_compiled_equals_python_on_a_random_model_with_capacities(kelvin, rule):
    model = random_model(kelvin)
    assert np.all(model.g(0.0) > 0)                     # capacities enter as g = r
    a, b = both(model, random_load(model), dt=5e-3, t_end=1.5, rule=rule)
    assert a.stats["contact_changes"] >= 4
    assert (a.v > 1e-6).any(axis=0).sum() >= 2          # more than one constraint opens
    assert_same(a, b, 1e-10)


def test_capacity_changes_the_answer_and_both_engines_follow():
    """A tension capacity keeps the edge in contact longer: a different history, same in both."""
    plain, strong = paper_model(True), paper_model(True, capacity=50.0)
    a0, _ = both(plain, rocking_load(), dt=2e-3, t_end=0.6)
    a1, b1 = both(strong, rocking_load(), dt=2e-3, t_end=0.6)
    assert a1.v[:, 0].max() < a0.v[:, 0].max()
    assert_same(a1, b1, 1e-10)


def test_sparse_model_is_stepped_with_dense_factors():
    """A beam on 41 springs (sparse, n = 122): the compiled march factorises D_eff densely."""
    p = build("winkler41", steps=200)
    a, b = both(p.model, p.load, dt=p.dt, t_end=p.N * p.dt)
    assert p.model.sparse and a.stats["contact_changes"] > 20
    assert_same(a, b, 1e-10)


def test_bilateral_and_model_without_constraints():
    model = paper_model(True)
    a, b = both(model, rocking_load(), dt=2e-3, t_end=0.6, bilateral=True)
    assert_same(a, b, 1e-12)
    np.testing.assert_array_equal(a.v, np.repeat(a.v[:1], len(a.t), axis=0))
    free = ul.Model(M=[[1.0]], K=[[100.0]], C=[[2.0]], F=np.zeros((1, 0)), H=np.zeros((0, 0)))
    step = lambda t: np.array([1.0 if t > 0 else 0.0])
    a, b = both(free, step, dt=1e-3, t_end=1.0, rule="hht")
    assert a.v.shape == (1001, 0)
    assert rel(a.u, b.u) <= 1e-11 and a.stats["lcp_iterations"] == 0


def test_progress_in_chunks_gives_the_same_result(monkeypatch):
    monkeypatch.setattr(march_direct_module, "PROGRESS_CHUNK", 50)
    monkeypatch.setattr(march_direct_module, "PROGRESS_SECONDS", 1e-9)      # every chunk 50 steps
    calls = []
    model = paper_model(True)
    with_callback = ul.solve(model, rocking_load(), dt=2e-3, t_end=1.0, method="direct",
                             callback=lambda k, N: calls.append((k, N)))
    without = ul.solve(model, rocking_load(), dt=2e-3, t_end=1.0, method="direct")
    assert with_callback.stats["engine"] == "compiled"
    for field in ("v", "psi", "u", "udot"):
        np.testing.assert_array_equal(getattr(with_callback, field), getattr(without, field))
    assert calls == [(k, 500) for k in range(50, 501, 50)]


def test_a_failed_lcp_stops_both_engines_at_the_same_step():
    model = paper_model(False)
    kw = dict(dt=2e-3, t_end=1.0, rule="bdf2", lcp_options={"max_iter": 1})
    a, b = (ul.solve(model, rocking_load(P=300.0), method=Direct(engine=e), **kw) for e in ("compiled", "python"))
    assert not a.success and not b.success
    assert "LCP of step" in a.message and "lcp='lemke'" in a.message
    assert a.stats["steps_done"] == b.stats["steps_done"] < 500
    np.testing.assert_allclose(a.v, b.v, rtol=0, atol=1e-14)


def test_engine_choice_and_bad_engine():
    model = paper_model(True)
    kw = dict(dt=2e-3, t_end=0.1)
    assert ul.solve(model, rocking_load(), method="direct", **kw).stats["engine"] == "compiled"
    assert ul.solve(model, rocking_load(), method="direct", lcp="lemke", **kw).stats["engine"] == "python"
    with pytest.raises(ValueError, match=r"direct_options\['engine'\]='fast' is not valid"):
        ul.solve(model, rocking_load(), method=Direct(engine="fast"), **kw)
    with pytest.raises(ValueError, match=r"engine'\]='compiled': no direct march applies.*need lcp='bpp'.*got lcp='lemke'"):
        ul.solve(model, rocking_load(), method=Direct(engine="compiled"), lcp="lemke", **kw)
    with pytest.raises(ValueError, match=r"direct_options has unknown keys \['history'\]"):
        Direct(history="fft")


def test_the_paper_example_steps_in_the_compiled_march():
    """The paper's example (n = 5, m = 3) is stepped by the compiled condensed march, in chunks, every
    step in compiled code; its time per step against the Python loop is a benchmark row
    (``benchmarks/compiled_march.py``), not a verdict: it depends on the machine and its load."""
    p = build("paper", steps=2_000)
    sol = ul.solve(p.model, p.load, dt=p.dt, t_end=p.N * p.dt, method="direct")
    s = sol.stats
    assert (s["engine"], s["march"], s["stepping"]) == ("compiled", "compiled condensed", "chunk")
    assert sol.success and s["steps_done"] == p.N and s["lcp_fallbacks"] == 0


def test_the_compiled_march_benchmark_writes_its_row(tmp_path):
    import json
    import subprocess
    import sys
    from pathlib import Path

    out = tmp_path / "compiled_march.json"
    script = Path(__file__).resolve().parents[1] / "benchmarks" / "compiled_march.py"
    done = subprocess.run([sys.executable, str(script), "--steps", "300", "--repeats", "1", "--out", str(out)],
                          capture_output=True, text=True, timeout=600)         # a hang guard, not a verdict
    assert done.returncode == 0, done.stderr[-2000:]
    data = json.loads(out.read_text())
    assert [r["engine"] for r in data["rows"]] == ["compiled", "python"] and data["max_difference"] < 1e-12
    assert all(r["steps"] == 300 and r["per_step_us"] > 0 for r in data["rows"])


# ---------------------------------------------------------------------- CQ weights of large models
@pytest.mark.parametrize("kelvin", [False, True])
@pytest.mark.parametrize("rule", ["bdf1", "bdf2", "trapezoidal"])
def test_cq_weights_of_a_large_model_by_the_rules_recursion_equal_the_fft_weights(kelvin, rule):
    """Above DENSE_BATCH_MAX_N DOFs cq_weights steps the structure with the rule (the impulse
    responses) instead of factorising D(s) at 4N+5 points: the same Taylor coefficients."""
    from unilateral.kernels import MatrixKernel, cq_weights
    from unilateral.kernels.cq_weights import matrix_model_weights
    from unilateral.kernels.matrix import DENSE_BATCH_MAX_N
    from unilateral.structure import winkler_beam

    structure, _, _ = winkler_beam(24, c_soil=50.0 if kelvin else 0.0)
    model = structure.to_model()
    assert model.n > DENSE_BATCH_MAX_N and model.sparse and model.viscous == kelvin
    N, dt, r = 120, 1e-3, ul.get_rule(rule)
    kernel = MatrixKernel(model)
    default = cq_weights(kernel, N, dt, r)
    np.testing.assert_array_equal(default, matrix_model_weights(model, N, dt, r))
    by_fft = cq_weights(kernel, N, dt, r, L=8 * (N + 1))            # L given: the FFT on a circle
    assert rel(default, by_fft) <= 1e-11
    assert rel(default[0], kernel(np.array([r.s_star(dt)]))[0]) <= 1e-13     # W_0 = Lambda(s*)
    assert np.abs(default[-1]).max() > 1e-6 * np.abs(default[1]).max()      # the tail is not trivial
    with pytest.raises(ValueError, match="rule=.*no recursion.*valid: BDF"):
        matrix_model_weights(model, N, dt, ul.get_rule("hht"))


def test_cq_on_a_beam_with_41_springs_equals_direct_stepping():
    """The user's case of issue 9 (m = 41, sparse), shortened: the same discrete problem."""
    p = build("winkler41", steps=300)
    kw = dict(dt=p.dt, t_end=p.N * p.dt)
    cq = ul.solve(p.model, p.load, method="cq", **kw)
    direct = ul.solve(p.model, p.load, method="direct", **kw)
    assert cq.success and direct.stats["contact_changes"] > 20
    for field in ("v", "psi", "u"):
        assert rel(getattr(cq, field), getattr(direct, field)) <= 1e-8, field


def test_direct_options_choose_the_engine_through_solve():
    """``solve(..., direct_options={"engine": ...})`` reaches the method; both engines agree."""
    import unilateral as ul
    from unilateral.structure.examples import liolios1990

    structure, load, _ = liolios1990()
    model = structure.to_model()
    a = ul.solve(model, load, dt=1e-3, t_end=0.3, method="direct", direct_options={"engine": "python"})
    b = ul.solve(model, load, dt=1e-3, t_end=0.3, direct_options={"engine": "compiled"})
    assert b.stats["method"] == "direct" and "direct_options" in b.stats["method_reason"]
    assert np.abs(a.u - b.u).max() <= 1e-12 * np.abs(a.u).max()
    with pytest.raises(ValueError, match="direct_options apply to method='direct' only"):
        ul.solve(model, load, dt=1e-3, t_end=0.3, method="cq", direct_options={"engine": "python"})


@pytest.mark.parametrize("method", ["direct", "modal", "cq"])
def test_a_failed_compiled_step_is_reported_alike_by_every_compiled_march(method):
    """One BPP solve per step is not enough once the soil lifts off: the run stops and says where."""
    from unilateral.structure.examples import liolios1990

    structure, load, _ = liolios1990()
    options = {"cq_options": {"history": "naive"}} if method == "cq" else {}
    sol = ul.solve(structure.to_model(), load, dt=1e-3, t_end=0.3, method=method, lcp_options={"max_iter": 1},
                   **options)
    assert sol.stats["engine"] == "compiled" and not sol.success and len(sol.t) == 9
    assert "the LCP of step 9 (t = 0.009) failed: block principal pivoting" in sol.message
    assert "did not converge in 1 solves" in sol.message and "try lcp='lemke'" in sol.message
