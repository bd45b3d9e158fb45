"""Tests of the LCP solvers (unilateral.lcp)."""

import numpy as np
import pytest

from unilateral.lcp import (
    LCP_SOLVERS,
    BlockPrincipalPivoting,
    Enumeration,
    LCPResult,
    LCPSolver,
    Lemke,
    ProjectedGaussSeidel,
    SemismoothNewton,
    get_lcp_solver,
    lcp_error,
    solve_lcp,
)
from unilateral.lcp.base import CHOLESKY_MIN_SIZE, PrincipalSystems, solve_linear

TOL = 1e-10

# (name, options) of every solver configuration, and the subsets that claim
# nonsymmetric P-matrices / symmetric positive semidefinite matrices.
ALL = [
    ("lemke", {}),
    ("bpp", {}),
    ("pgs", {}),
    ("pgs", {"omega": 1.3}),
    ("newton", {"merit": "fb"}),
    ("newton", {"merit": "min"}),
    ("enumerate", {}),
]
P_MATRIX = [("lemke", {}), ("bpp", {}), ("newton", {"merit": "fb"}), ("enumerate", {})]
PSD = [("lemke", {}), ("bpp", {}), ("pgs", {}), ("newton", {"merit": "fb"}), ("newton", {"merit": "min"})]


def config_id(config):
    name, options = config
    return name + "".join(f"-{key}={value}" for key, value in options.items())


def all_configs(configs):
    return pytest.mark.parametrize("config", configs, ids=[config_id(c) for c in configs])


def config_problem_pairs(configs, problems):
    """Parametrize over (config, problem name); enumeration only gets problems with m <= 8."""
    pairs = [
        pytest.param(config, name, id=f"{config_id(config)}-{name}")
        for config in configs
        for name, (W, q) in sorted(problems.items())
        if config[0] != "enumerate" or q.size <= 8
    ]
    return pytest.mark.parametrize("config, problem", pairs)


# ---------------------------------------------------------------- problems


def spd(m, rng, shift=0.1):
    A = rng.standard_normal((m, m))
    return A @ A.T + shift * np.eye(m)


def nonsymmetric_pd(m, rng):
    """Positive definite (hence P) but nonsymmetric: SPD + skew."""
    K = rng.standard_normal((m, m))
    return spd(m, rng) + 2.0 * (K - K.T)


def triangular_p(m, rng):
    """Lower triangular with positive diagonal: a P-matrix that is not positive definite."""
    return np.tril(3.0 * rng.standard_normal((m, m)), -1) + np.diag(rng.uniform(0.5, 2.0, m))


def from_solution(W, v, w):
    """q such that (v, w) solves LCP(W, q)."""
    return w - W @ v


def degenerate(m, rng, W):
    """Problem whose solution has indices with v_i = w_i = 0."""
    kind = rng.integers(0, 3, m)  # 0: v > 0, 1: w > 0, 2: both zero
    kind[:3] = [0, 1, 2]
    v = np.where(kind == 0, rng.uniform(0.5, 2.0, m), 0.0)
    w = np.where(kind == 1, rng.uniform(0.5, 2.0, m), 0.0)
    return from_solution(W, v, w)


def problems():
    """Named SPD problems (W, q) every solver must solve."""
    rng = np.random.default_rng(20240601)
    out = {}
    for m in (1, 2, 5, 8, 30):
        for k in range(3):
            out[f"spd-m{m}-{k}"] = (spd(m, rng), rng.standard_normal(m))
    for m in (4, 8):
        W = spd(m, rng)
        out[f"degenerate-m{m}"] = (W, degenerate(m, rng, W))
    W = spd(6, rng)
    out["all-active"] = (W, from_solution(W, rng.uniform(0.5, 2.0, 6), np.zeros(6)))
    d = np.logspace(-1.5, 3.0, 8)
    W = d[:, None] * spd(8, rng, shift=1.0) * d
    out["badly-scaled"] = (W, d * rng.standard_normal(8))  # entries of W from ~1e-3 to ~6e6
    out["badly-scaled-q"] = (W, rng.standard_normal(8))
    out["m1-negative"] = (np.array([[2.0]]), np.array([-4.0]))
    out["m1-zero"] = (np.array([[2.0]]), np.array([0.0]))
    out["zero-in-q"] = (spd(5, rng), np.array([-1.0, 0.0, 0.5, 0.0, -0.2]))
    return out


def p_problems():
    """Named nonsymmetric P-matrix problems."""
    rng = np.random.default_rng(7)
    out = {}
    for m in (2, 5, 8, 20):
        out[f"nonsym-pd-m{m}"] = (nonsymmetric_pd(m, rng), rng.standard_normal(m))
        out[f"triangular-m{m}"] = (triangular_p(m, rng), rng.standard_normal(m))
    # pure block pivoting cycles on this one (found by search); Murty's fallback is needed
    out["bpp-cycle"] = (np.array([[1.0, 1, -2], [0, 1, -2], [2, 0, 1]]), np.array([-1.0, -3, 2]))
    out["cyclic-ties"] = (np.array([[1.0, 2, 0], [0, 1, 2], [2, 0, 1]]), -np.ones(3))
    return out


def integer_degenerate():
    """Small integer SPD problems with many ties in the ratio tests."""
    rng = np.random.default_rng(3)
    out = []
    for _ in range(40):
        m = int(rng.integers(2, 7))
        B = rng.integers(-1, 2, (m, m)).astype(float)
        out.append((B @ B.T + np.eye(m), rng.integers(-1, 2, m).astype(float)))
    return out


PROBLEMS = problems()
P_PROBLEMS = p_problems()


# ---------------------------------------------------------------- checks


def assert_solves(result, W, q, tol=TOL):
    """The defining properties of an LCP solution, plus the result's own consistency."""
    assert isinstance(result, LCPResult)
    assert result.success, result.message
    v, w = result.v, result.w
    scale = 1.0 + np.linalg.norm(q)
    assert v.shape == w.shape == result.active.shape == q.shape
    assert result.active.dtype == bool
    assert np.array_equal(w, W @ v + q)
    assert v.min(initial=0.0) >= -tol * scale
    assert w.min(initial=0.0) >= -tol * scale
    assert abs(v @ w) <= tol * scale * (1.0 + np.linalg.norm(v) + np.linalg.norm(w))
    assert result.error == lcp_error(v, w, q) <= tol


def reference(W, q):
    result = Enumeration().solve(W, q)
    assert result.success, result.message
    return result.v


def assert_matches_reference(result, W, q):
    if q.size <= 8:
        ref = reference(W, q)
        np.testing.assert_allclose(result.v, ref, rtol=1e-7, atol=1e-8 * (1.0 + np.abs(ref).max()))


# ---------------------------------------------------------------- solutions


@config_problem_pairs(ALL, PROBLEMS)
def test_spd_problems(config, problem):
    W, q = PROBLEMS[problem]
    name, options = config
    result = solve_lcp(W, q, name, **options)
    assert_solves(result, W, q)
    assert_matches_reference(result, W, q)


@config_problem_pairs(P_MATRIX, P_PROBLEMS)
def test_nonsymmetric_p_matrices(config, problem):
    W, q = P_PROBLEMS[problem]
    result = solve_lcp(W, q, config[0], **config[1])
    assert_solves(result, W, q)
    assert_matches_reference(result, W, q)


@all_configs(ALL)
def test_integer_degenerate_problems(config):
    for W, q in integer_degenerate():
        result = solve_lcp(W, q, config[0], **config[1])
        assert_solves(result, W, q)
        assert_matches_reference(result, W, q)


@all_configs(PSD)
def test_semidefinite_with_repeated_constraints(config):
    # two identical constraints: W singular, the solution set is a segment
    B = np.array([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    W = B @ B.T
    q = np.array([-1.0, -1.0, -0.5, 0.5])
    result = solve_lcp(W, q, config[0], **config[1])
    assert_solves(result, W, q)


@all_configs(ALL)
def test_no_contact_gives_exact_zero(config):
    rng = np.random.default_rng(11)
    W, q = spd(6, rng), rng.uniform(0.0, 2.0, 6)
    q[2] = 0.0
    result = solve_lcp(W, q, config[0], **config[1])
    assert result.success and result.iterations == 0
    assert np.array_equal(result.v, np.zeros(6)) and np.array_equal(result.w, q)
    assert not result.active.any() and result.error == 0.0


@all_configs(ALL)
def test_all_constraints_active(config):
    W, q = PROBLEMS["all-active"]
    result = solve_lcp(W, q, config[0], **config[1])
    assert_solves(result, W, q)
    assert (result.v > 0).all()


@all_configs(ALL)
def test_empty_problem(config):
    result = solve_lcp(np.zeros((0, 0)), np.zeros(0), config[0], **config[1])
    assert result.success and result.v.shape == (0,)


@pytest.mark.parametrize("name", ["lemke", "bpp", "enumerate"])
def test_pivoting_solvers_give_exact_zeros_off_the_active_set(name):
    W, q = PROBLEMS["spd-m30-0"] if name != "enumerate" else PROBLEMS["spd-m8-0"]
    result = solve_lcp(W, q, name)
    assert_solves(result, W, q)
    assert np.all(result.v[~result.active] == 0.0)


def test_m1_closed_form():
    for name in LCP_SOLVERS:
        result = solve_lcp([[2.0]], [-4.0], name)
        np.testing.assert_allclose(result.v, [2.0], rtol=1e-14)
        assert result.active.tolist() == [True]


@pytest.mark.parametrize(
    "W, q, merit",
    [
        # the identified active sets have singular W_AA whose minimum-norm solutions are not
        # feasible: the converged (unpolished) iterate is returned
        (
            [[3, 0, 1, 0, 1, 0], [0, 2, 2, -2, -1, 1], [1, 2, 3, -2, -1, 0],
             [0, -2, -2, 2, 1, -1], [1, -1, -1, 1, 1, 0], [0, 1, 0, -1, 0, 2]],
            [-5, -10, -11, 11, 3, -6],
            "fb",
        ),
        # singular Newton matrix: steepest-descent fallback
        ([[2, 1, 2, 0], [1, 2, 0, 1], [2, 0, 3, 0], [0, 1, 0, 2]], [-4, -3, -3, -2], "min"),
    ],
    ids=["unpolished", "descent-fallback"],
)
def test_newton_on_semidefinite_problems(W, q, merit):
    W, q = np.array(W, dtype=float), np.array(q, dtype=float)
    assert np.linalg.eigvalsh(W).min() > -1e-12
    assert_solves(SemismoothNewton(merit=merit).solve(W, q), W, q)


def test_linear_solves():
    rng = np.random.default_rng(2)
    A = rng.standard_normal((5, 5))
    b = rng.standard_normal(5)
    for M, symmetric in ((A @ A.T + np.eye(5), True), (A + A.T, True), (A, False)):
        # Cholesky; Cholesky failing -> LU; LU
        np.testing.assert_allclose(M @ solve_linear(M, b, symmetric), b, atol=1e-9)
    singular = np.ones((2, 2))  # consistent singular system: minimum-norm solution
    np.testing.assert_allclose(solve_linear(singular, np.array([2.0, 2.0])), [1.0, 1.0])


def test_principal_systems():
    systems = PrincipalSystems(np.eye(3) * 2.0, np.array([-2.0, 5.0, -4.0]))
    assert systems.solve(np.array([True, False, True])).tolist() == [1.0, 0.0, 2.0]
    assert systems.start(np.array([True, True, False])).tolist() == [1.0, 0.0, 0.0]
    assert systems.start(None).tolist() == [0.0, 0.0, 0.0]
    assert not systems.symmetric  # too small to bother
    n = CHOLESKY_MIN_SIZE
    assert PrincipalSystems(np.eye(n), np.ones(n)).symmetric
    assert not PrincipalSystems(np.eye(n) + np.eye(n, k=1), np.ones(n)).symmetric


def test_large_spd_problem():
    rng = np.random.default_rng(5)
    m = 150
    W = spd(m, rng, shift=float(m))
    contact = rng.random(m) < 0.6
    q = from_solution(W, np.where(contact, rng.uniform(0.5, 1.0, m), 0.0), np.where(contact, 0.0, 1.0))
    assert PrincipalSystems(W, q).symmetric  # Cholesky path
    for solver in (BlockPrincipalPivoting(), Lemke(), SemismoothNewton(), ProjectedGaussSeidel()):
        result = solver.solve(W, q)
        assert_solves(result, W, q)
    result = BlockPrincipalPivoting().solve(W, q, active=result.active)
    assert result.iterations == 1 and result.success


# ---------------------------------------------------------------- warm start


# solver, linear solves / subsets / sweeps / iterations needed from the exact active set
WARM = [
    (BlockPrincipalPivoting(), 1),
    (Enumeration(), 1),
    (ProjectedGaussSeidel(), 0),
    (SemismoothNewton(), 0),
]


@pytest.mark.parametrize(
    "solver, expected, problem",
    [
        pytest.param(solver, expected, problem, id=f"{solver.name}-{problem}")
        for solver, expected in WARM
        for problem in ("spd-m5-0", "spd-m30-1", "degenerate-m8", "badly-scaled")
        if solver.max_size is None or PROBLEMS[problem][1].size <= solver.max_size
    ],
)
def test_warm_start_from_exact_active_set(solver, expected, problem):
    W, q = PROBLEMS[problem]
    cold = solver.solve(W, q)
    warm = solver.solve(W, q, active=cold.active)
    assert_solves(warm, W, q)
    assert warm.iterations == expected
    np.testing.assert_allclose(warm.v, cold.v, rtol=1e-6, atol=1e-7 * (1.0 + np.abs(cold.v).max()))


def test_warm_start_from_wrong_active_set():
    W, q = PROBLEMS["spd-m30-2"]
    wrong = np.ones(30, dtype=bool)
    for name in ("bpp", "pgs", "newton", "lemke"):
        result = solve_lcp(W, q, name, active=wrong)
        assert_solves(result, W, q)


def test_warm_start_is_not_modified():
    W, q = PROBLEMS["spd-m8-1"]
    active = np.zeros(8, dtype=bool)
    solve_lcp(W, q, "bpp", active=active)
    assert not active.any()


# Degenerate LCPs (not P-matrices) on which Lemke's method with a smallest-row-index tie
# rule instead of the lexicographic one cycles (found by search).
LEMKE_CYCLING = [
    (
        [[-1.0, 0, -1, 1], [0, 1, -1, 1], [-1, -1, 0, -2], [-1, 2, 1, 0]],
        [0.0, -1, 1, -1],
    ),
    (
        [[-1.0, 0, 2, 1], [0, 0, 2, -1], [1, 0, 2, -1], [-2, -2, 1, 2]],
        [-1.0, -1, -1, -1],
    ),
]


@pytest.mark.parametrize("name", ["lemke", "enumerate"])
@pytest.mark.parametrize("W, q", LEMKE_CYCLING, ids=["a", "b"])
def test_lexicographic_rule_prevents_cycling(name, W, q):
    W, q = np.array(W), np.array(q)
    assert_solves(solve_lcp(W, q, name), W, q)


def test_bpp_needs_murty_fallback_on_cycling_example():
    W, q = P_PROBLEMS["bpp-cycle"]
    pure = BlockPrincipalPivoting(max_nonimproving=10**6, max_iter=50).solve(W, q)
    assert not pure.success and "max_iter" in pure.message
    assert_solves(BlockPrincipalPivoting().solve(W, q), W, q)


# ---------------------------------------------------------------- failures


@all_configs(ALL)
def test_lcp_without_solution_fails_gracefully(config):
    result = solve_lcp([[-1.0]], [-1.0], config[0], **config[1])
    assert not result.success
    assert result.message and result.error > TOL
    assert result.error == lcp_error(result.v, result.w, np.array([-1.0]))


def test_lemke_ray_message():
    result = Lemke().solve([[-1.0]], [-1.0])
    assert not result.success and "ray" in result.message and "positive semidefinite" in result.message


def test_lemke_iteration_limit():
    W, q = PROBLEMS["spd-m30-0"]
    result = Lemke(max_iter=2).solve(W, q)
    assert not result.success and "max_iter" in result.message


def test_pgs_iteration_limit():
    W, q = PROBLEMS["badly-scaled"]
    result = ProjectedGaussSeidel(max_iter=1).solve(W, q)
    assert not result.success and result.iterations == 1
    assert "did not converge in 1 sweeps" in result.message and "solver='bpp'" in result.message


def test_pgs_needs_positive_diagonal():
    result = ProjectedGaussSeidel().solve([[0.0, 1.0], [1.0, 2.0]], [-1.0, -1.0])
    assert not result.success and "W[0, 0]" in result.message


def test_pgs_divergence_is_reported():
    result = ProjectedGaussSeidel().solve([[1.0, -2.0], [-2.0, 1.0]], [-1.0, -1.0])
    assert not result.success and "diverged" in result.message


def test_newton_iteration_limit():
    W, q = PROBLEMS["spd-m30-0"]
    result = SemismoothNewton(max_iter=1).solve(W, q)
    assert not result.success and "did not converge in 1 iterations" in result.message


def test_enumeration_limit():
    result = Enumeration(max_iter=1).solve(*PROBLEMS["spd-m8-0"])
    assert not result.success and result.iterations == 1 and "1 principal subsets" in result.message


def test_ill_conditioned_reports_tolerance():
    W, q = PROBLEMS["spd-m8-0"]
    result = BlockPrincipalPivoting(tol=1e-300).solve(W, q)
    assert result.error > 1e-300 and not result.success and "exceeds tol" in result.message


# ---------------------------------------------------------------- API


def test_registry_and_factory():
    assert set(LCP_SOLVERS) == {"lemke", "bpp", "pgs", "newton", "enumerate"}
    assert isinstance(get_lcp_solver(), BlockPrincipalPivoting)
    solver = get_lcp_solver("PGS", omega=1.5, tol=1e-8)
    assert isinstance(solver, ProjectedGaussSeidel) and solver.omega == 1.5 and solver.tol == 1e-8
    assert get_lcp_solver(solver) is solver
    assert "omega=1.5" in repr(solver)
    assert all(issubclass(cls, LCPSolver) and cls.name == key for key, cls in LCP_SOLVERS.items())


def test_solver_is_callable():
    W, q = PROBLEMS["spd-m5-1"]
    assert np.array_equal(Lemke()(W, q).v, Lemke().solve(W, q).v)


def test_bad_solver_name():
    with pytest.raises(ValueError, match="lcp='foo' is not a known LCP solver") as info:
        get_lcp_solver("foo")
    for name in LCP_SOLVERS:
        assert repr(name) in str(info.value)


def test_bad_solver_spec_type_and_options():
    with pytest.raises(TypeError, match="lcp"):
        get_lcp_solver(3)
    with pytest.raises(TypeError, match="options"):
        get_lcp_solver(Lemke(), tol=1e-3)
    with pytest.raises(TypeError):
        get_lcp_solver("lemke", omega=1.2)


@pytest.mark.parametrize(
    "cls, options, match",
    [
        (ProjectedGaussSeidel, {"omega": 2.5}, "omega"),
        (SemismoothNewton, {"merit": "foo"}, "merit"),
        (BlockPrincipalPivoting, {"max_nonimproving": -1}, "max_nonimproving"),
        (Lemke, {"tol": 0.0}, "tol"),
        (Lemke, {"max_iter": 0}, "max_iter"),
    ],
)
def test_bad_options(cls, options, match):
    with pytest.raises(ValueError, match=match):
        cls(**options)


@pytest.mark.parametrize(
    "W, q, active, match",
    [
        (np.eye(2)[:, :1], [-1.0, -1.0], None, r"W must be a square 2-D array, got shape \(2, 1\)"),
        (np.eye(2), [-1.0, -1.0, 0.0], None, r"q must have shape \(2,\).*got shape \(3,\)"),
        (np.eye(2), [[-1.0, -1.0]], None, r"q must have shape \(2,\)"),
        (np.eye(2), [-1.0, np.nan], None, r"q must be finite, got q\[1\] = nan"),
        ([[1.0, np.inf], [0.0, 1.0]], [-1.0, -1.0], None, r"W must be finite, got W\[0, 1\] = inf"),
        (np.eye(2), [-1.0, -1.0], [True], "active"),
        (np.eye(2), [-1.0, -1.0], [1, 0], "active"),
    ],
)
def test_malformed_input(W, q, active, match):
    with pytest.raises(ValueError, match=match):
        solve_lcp(W, q, active=active)


def test_enumeration_refuses_large_m():
    W = np.eye(21)
    with pytest.raises(ValueError, match="m=21"):
        Enumeration().solve(W, -np.ones(21))


def test_lcp_error():
    assert lcp_error([0.0, 2.0], [3.0, 0.0], [0.0, 0.0]) == 0.0
    # min(v, w) = (-1, 1), ||q|| = 3
    assert lcp_error([-1.0, 2.0], [3.0, 1.0], [0.0, 3.0]) == pytest.approx(np.sqrt(2.0) / 4.0)
