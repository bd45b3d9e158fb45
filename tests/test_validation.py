"""Bad input gets a clear error naming the argument, the value and what would be valid."""

import numpy as np
import pytest

import unilateral as ul
from conftest import rocking_load, rocking_model

ONE = dict(M=[[1.0]], K=[[100.0]], F=[[100.0]], H=[[100.0]])


def run(model=None, load=None, **kw):
    args = dict(dt=0.01, t_end=0.1, method="cq")
    args.update(kw)
    return ul.solve(model or rocking_model(), rocking_load() if load is None else load, **args)


@pytest.mark.parametrize("kw, exc, match", [
    (dict(K=[[1.0, 2.0], [0.0, 1.0]], M=np.eye(2), F=[[1.0], [0.0]]), ValueError, "K must be symmetric"),
    (dict(H=[[1.0, 0.5], [0.0, 1.0]], F=[[1.0, 1.0]]), ValueError, "H must be symmetric"),
    (dict(H=[[1.0, 0.0], [0.0, -2.0]], F=[[1.0, 1.0]]), ValueError, "H must be symmetric positive semidefinite; its smallest eigenvalue is -2"),
    (dict(M=np.eye(2)), ValueError, r"M has shape \(2, 2\), expected \(1, 1\)"),
    (dict(F=[[1.0], [2.0]]), ValueError, r"F has shape \(2, 1\), expected \(1, any\)"),
    (dict(K=[[np.nan]]), ValueError, "K contains nan at index"),
    (dict(K=[[-1.0]]), ValueError, r"K must have a positive diagonal .* K\[0, 0\] = -1.0"),
    (dict(M=None), TypeError, "M is required"),
    (dict(g=[1.0, 2.0]), ValueError, r"g must have shape \(1,\), got shape \(2,\)"),
])
def test_model_errors(kw, exc, match):
    args = dict(ONE)
    args.update(kw)
    with pytest.raises(exc, match=match):
        ul.Model(**args)


def test_natural_form_errors():
    with pytest.raises(ValueError, match=r"r must be >= 0 \(resistances\); r\[0\] = -1.0"):
        ul.Model.from_natural(G=[[1.0]], E=[[1.0]], B=[[1.0]], M=[[1.0]], r=[-1.0])
    with pytest.raises(ValueError, match="theta_rate is required"):
        ul.Model.from_natural(G=[[1.0]], E=[[1.0]], B=[[1.0]], M=[[1.0]], E_v=[[1.0]], theta=lambda t: [t])
    with pytest.raises(ValueError, match="A must be symmetric positive semidefinite"):
        ul.Model.from_natural(G=[[1.0]], E=[[1.0]], B=[[1.0]], M=[[1.0]], A=[[-1.0]])


@pytest.mark.parametrize("kw, match", [
    (dict(dt=0.0), "dt must be a positive finite number, got 0.0"),
    (dict(dt=-0.1), "dt must be a positive finite number, got -0.1"),
    (dict(t_end=0.001), r"t_end=0.001 must be >= dt=0.01"),
    (dict(rule="rk4"), r"rule='rk4' is not valid; valid names: 'bdf1', 'bdf2', 'hht', 'newmark', 'trapezoidal'"),
    (dict(rule="hht"), r"rule='hht' has no convolution-quadrature form.*method='direct'"),
    (dict(method="explicit"), r"method='explicit' is not valid; valid names: 'auto', 'cq', 'direct', 'event', 'modal', 'moreau-jean', 'time-kernel'"),
    (dict(lcp="simplex"), r"lcp='simplex' is not a known LCP solver; valid names: .*'bpp'.*'lemke'"),
    (dict(initial="moving"), r"initial='moving' is not valid; valid names: 'rest', 'static'"),
    (dict(initial={"x0": 1}), r"initial has unknown keys \['x0'\]"),
    (dict(initial={"v0": [-1.0, 0, 0]}), r"initial\['v0'\] must be >= 0"),
    (dict(cq_options={"L": 2}, method="direct"), "cq_options apply to method='cq' only"),
])
def test_solve_argument_errors(kw, match):
    with pytest.raises((ValueError, TypeError), match=match):
        run(**kw)


def test_load_errors():
    with pytest.raises(ValueError, match=r"load\(t\) returned a non-finite value at t=0.05"):
        run(load=lambda t: np.full(5, np.nan) if t > 0.04 else np.zeros(5))
    with pytest.raises(ValueError, match=r"load\(t\) must return shape \(5,\), got shape \(3,\)"):
        run(load=lambda t: np.zeros(3))
    with pytest.raises(ValueError, match=r"load has 4 rows but t_end/dt = 10 steps need 11"):
        run(load=np.zeros((4, 5)))
    with pytest.raises(ValueError, match=r"load has shape \(11, 2\), expected \(any, 5\)"):
        run(load=np.zeros((11, 2)))
    bad = np.zeros((11, 5))
    bad[3, 1] = np.inf
    with pytest.raises(ValueError, match=r"load contains inf at index \(3, 1\)"):
        run(load=bad)


def test_no_static_equilibrium_is_a_failure_with_a_message():
    model = ul.Model(**ONE)
    sol = ul.solve(model, lambda t: np.array([+10.0]), dt=0.01, t_end=0.1)   # gravity upwards
    assert not sol.success
    assert "no static equilibrium" in sol.message and "sign of gravity" in sol.message


def test_load_history_errors_name_the_step():
    from unilateral.loads import LoadHistory
    bad = LoadHistory(np.zeros(5), [(np.ones(5), lambda t: np.where(t > 0.04, np.nan, 0.0))])
    with pytest.raises(ValueError, match=r"load\(t\) returned a non-finite value at t=0.05 \(step 5\)"):
        run(load=bad)


@pytest.mark.parametrize("kw, what", [
    (dict(dt=1e-9, t_end=1.0), "the histories of u, udot"),      # 1e9 steps: the most allowed (MAX_STEPS)
    (dict(dt=1e-6, t_end=100.0, method="cq"), "the FFT of the weights"),
])
def test_a_run_that_cannot_fit_in_memory_is_refused_before_it_allocates(kw, what):
    eye = np.eye(100)                                               # 1e9 steps of n = m = 100: terabytes
    model = ul.Model(M=eye, K=eye, F=eye, H=eye)
    with pytest.raises(MemoryError, match=rf"steps with method='\w+' would need about .* GiB \(.*{what}.*"
                                          r"more than 50% of this machine's .*increase dt, shorten t_end"):
        ul.solve(model, lambda t: np.zeros(100), **kw)


def test_check_psd_of_a_large_block_diagonal_matrix_checks_its_blocks():
    """Above PSD_BLOCKS_MIN_M rows the uncoupled blocks are checked one by one: the same verdict and
    smallest eigenvalue as the full eigendecomposition."""
    import scipy.linalg as sla

    from unilateral import _validate as V

    rng = np.random.default_rng(1)
    blocks = [np.diag(rng.uniform(1.0, 2.0, 150))]
    for size in (2, 3, 5):
        A = rng.standard_normal((size, size))
        blocks.append(A @ A.T + 0.1 * np.eye(size))
    H = sla.block_diag(*blocks)
    perm = rng.permutation(H.shape[0])
    H = H[np.ix_(perm, perm)]                            # blocks scattered over the rows
    V.check_psd("H", H, strict=True)
    i = int(np.flatnonzero(perm < 150)[0])                # an entry of the diagonal block
    H[i, i] = -0.5
    with pytest.raises(ValueError, match="smallest eigenvalue is -0.5 "):
        V.check_psd("H", H)
    assert np.linalg.eigvalsh(H)[0] == pytest.approx(-0.5)
