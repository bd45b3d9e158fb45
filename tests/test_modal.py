"""Pole-residue kernels: exact against MatrixKernel and the FFT weights, the recursive history
against direct summation, modal truncation with static correction, and a CLCP march."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp

import unilateral as ul
from unilateral.march.clcp import march_cq
from unilateral.kernels import cq_weights
from unilateral.history import NaiveHistory
from unilateral.kernels import MatrixKernel
from unilateral.lcp import get_lcp_solver
from unilateral.history import RecursiveHistory
from unilateral.kernels import PoleResidueKernel
from unilateral.kernels.pole_residue import modal_history
from unilateral.rules import get_rule

from conftest import rocking_load, rocking_model, rocking_natural

RULES = ("bdf1", "bdf2", "trapezoidal")


# ---------------------------------------------------------------------- models
def spd(rng, n, shift=1.0):
    A = rng.standard_normal((n, n))
    return A @ A.T + shift * n * np.eye(n)


def random_model(seed=0, n=12, m=3):
    """M positive definite, non-proportional damping of low rank."""
    rng = np.random.default_rng(seed)
    K = 100.0 * spd(rng, n)
    L = rng.standard_normal((n, 3))
    F = 50.0 * rng.standard_normal((n, m))
    H = F.T @ np.linalg.solve(K, F) + 20.0 * np.eye(m)
    return ul.Model(M=spd(rng, n), K=K, F=F, H=H, C=3.0 * L @ L.T)


def massless_model(seed=1, n=10, m=3, free=3):
    """The last ``free`` DOFs have neither mass nor damping (condensed statically)."""
    rng = np.random.default_rng(seed)
    K = 100.0 * spd(rng, n)
    mass = np.r_[rng.uniform(0.5, 2.0, n - free), np.zeros(free)]
    L = np.zeros((n, 2))
    L[: n - free] = rng.standard_normal((n - free, 2))
    F = 50.0 * rng.standard_normal((n, m))
    H = F.T @ np.linalg.solve(K, F) + 20.0 * np.eye(m)
    return ul.Model(M=np.diag(mass), K=K, F=F, H=H, C=L @ L.T)


def consistent_mass_model(seed=2, n=10, m=2):
    """Non-diagonal singular M; Rayleigh damping so that part of null(M) is first order."""
    rng = np.random.default_rng(seed)
    Q = np.linalg.qr(rng.standard_normal((n, n)))[0]
    M = Q @ np.diag(np.r_[rng.uniform(0.5, 2.0, n - 3), np.zeros(3)]) @ Q.T
    M = 0.5 * (M + M.T)
    K = 100.0 * spd(rng, n)
    F = 50.0 * rng.standard_normal((n, m))
    H = F.T @ np.linalg.solve(K, F) + 20.0 * np.eye(m)
    return ul.Model(M=M, K=K, F=F, H=H, C=0.2 * M + 1e-3 * K)


def kelvin_model(seed=3):
    """Natural form with Kelvin contact elements on partly massless DOFs (F_v, H_v, C from E_v)."""
    rng = np.random.default_rng(seed)
    n, ne = 6, 9
    G = rng.standard_normal((n, ne))
    E = np.diag(rng.uniform(1e3, 1e4, ne))
    B = np.zeros((ne, 3))
    B[6:, :] = np.eye(3)
    E_v = np.diag(np.r_[np.zeros(6), rng.uniform(10.0, 50.0, 3)])
    M = np.diag([1.0, 2.0, 1.5, 0.0, 0.0, 0.0])
    return ul.Model.from_natural(G, E, B, M=M, E_v=E_v, A=np.eye(3))


def stiff_rocking_model():
    """The seed's example with soil dashpots 10^6 times weaker: poles from 20 to 3e12 rad/s."""
    nat = rocking_natural(kelvin=True)
    return ul.Model.from_natural(nat["G"], nat["E"], nat["B"], M=nat["M"], E_v=1e-6 * nat["E_v"])


MODELS = {
    "rocking_kelvin": (lambda: rocking_model(kelvin=True), 1e-3),
    "rocking_stiff": (stiff_rocking_model, 1e-3),
    "rocking": (lambda: rocking_model(kelvin=False), 1e-3),
    "random": (random_model, 2e-2),
    "massless": (massless_model, 2e-2),
    "consistent_mass": (consistent_mass_model, 2e-2),
    "kelvin_random": (kelvin_model, 2e-2),
}


@pytest.fixture(scope="module")
def kernels():
    """``{name: (model, PoleResidueKernel, dt)}``, built once."""
    out = {}
    for name, (make, dt) in MODELS.items():
        model = make()
        out[name] = (model, PoleResidueKernel.from_model(model), dt)
    return out


def sample_points(kernel, dt):
    """Complex s from low frequency to beyond the CQ range and the pole magnitudes: (9,)."""
    mags = np.abs(kernel.poles)
    base = np.array([0.3, 2j / dt, 0.5 / dt + 3j / dt, 40j / dt])
    return np.r_[base, mags.min() * (0.5 + 1j), mags.max() * np.array([0.3j, 1 + 1j, 5j]),
                 np.sqrt(mags.min() * mags.max()) * (1 + 2j)]


# ---------------------------------------------------------------------- exactness
@pytest.mark.parametrize("name", MODELS)
def test_kernel_equals_matrix_kernel(kernels, name):
    model, kernel, dt = kernels[name]
    s = sample_points(kernel, dt)
    assert kernel.relative_error(MatrixKernel(model), s) <= 1e-10
    assert kernel.info["reconstruction_error"] <= 1e-10
    assert np.isrealobj(kernel(np.array([0.5, 2.0])))
    conj_gap = np.linalg.norm(kernel(np.conj(s)) - np.conj(kernel(s)), axis=(1, 2))
    assert np.all(conj_gap <= 1e-13 * np.linalg.norm(kernel(s), axis=(1, 2)))


def test_rocking_state_space_structure(kernels):
    """x1, y1 massive; y2, r2 massless on soil dashpots (first order); r1 condensed."""
    for name in ("rocking_kelvin", "rocking"):
        info = kernels[name][1].info
        assert info["dofs"] == {"massive": 2, "first_order": 2, "condensed": 1}
        assert info["poles"] == info["states"] == 6
    assert np.any(kernels["rocking_kelvin"][1].P1)          # Kelvin dashpots: Lambda ~ s P1
    assert not np.any(kernels["rocking"][1].P1)


def test_a_multiple_real_pole_split_by_rounding_into_a_pair(monkeypatch):
    """The triple pole -1/a1 of the Rayleigh-damped massless DOFs as some LAPACK builds return it:
    one real eigenvalue and a conjugate pair +-1e-18 i with complex vectors. Made real again, the
    three are normalised as one cluster and the kernel is exact."""
    real_eig = sla.eig

    def split(a):
        mu, X = real_eig(a)
        target = -1e-3                                      # -1 / (1/a1) of consistent_mass_model
        idx = np.flatnonzero(np.abs(mu - target) <= 1e-9 * abs(target))
        assert idx.size == 3
        V = np.linalg.svd(np.hstack([X[:, idx].real, X[:, idx].imag]))[0][:, :3]
        pair = (V[:, 1] + 1j * V[:, 2]) / np.sqrt(2.0)
        rest = np.setdiff1d(np.arange(mu.size), idx)
        mu = np.r_[mu[rest], target, target + 1e-18j, target - 1e-18j]
        return mu, np.column_stack([X[:, rest], V[:, 0], pair, pair.conj()])

    monkeypatch.setattr(sla, "eig", split)
    model = consistent_mass_model()
    kernel = PoleResidueKernel.from_model(model)
    assert np.count_nonzero(kernel.poles == -1e3) == 3
    assert kernel.relative_error(MatrixKernel(model), sample_points(kernel, 2e-2)) <= 1e-10


def test_poles_spanning_many_decades(kernels):
    poles = np.abs(kernels["rocking_stiff"][1].poles)
    assert poles.max() / poles.min() > 1e10
    assert kernels["rocking_stiff"][1].info["eigvec_condition"] < 1e3


def test_kernel_static_value(kernels):
    """``Lambda(0) = H - F^T K^-1 F``; ``P0 = Lambda0 + sum_k R_k / p_k`` is the large-s limit."""
    model, kernel, _ = kernels["random"]
    exact0 = model.H - model.F.T @ np.linalg.solve(model.K, model.F)
    np.testing.assert_allclose(kernel(0.0), exact0, rtol=1e-11, atol=1e-11 * np.abs(exact0).max())
    big = 1e9j
    np.testing.assert_allclose(kernel(big), kernel.P0, rtol=1e-6)
    again = PoleResidueKernel(kernel.poles, kernel.B, kernel.Cf, P0=kernel.P0, P1=kernel.P1)
    np.testing.assert_allclose(again.Lambda0, kernel.Lambda0, rtol=1e-9,
                               atol=1e-9 * np.abs(exact0).max())


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("name", ["rocking_kelvin", "rocking", "rocking_stiff", "random",
                                  "massless", "kelvin_random"])
def test_weights_equal_fft_weights(kernels, name, rule):
    model, kernel, dt = kernels[name]
    N = 200
    W = kernel.weights(N, dt, rule)
    ref = cq_weights(MatrixKernel(model), N, dt, get_rule(rule))
    scale = np.abs(ref).max()
    assert np.abs(W - ref).max() <= 1e-9 * scale
    W0 = kernel.W0(dt, rule)
    np.testing.assert_array_equal(W0, W0.T)
    np.testing.assert_allclose(W0, W[0], rtol=0, atol=1e-12 * scale)


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("name", ["rocking_kelvin", "random", "massless", "kelvin_random"])
def test_recursive_history_equals_naive(kernels, name, rule):
    model, kernel, dt = kernels[name]
    N = 150
    rng = np.random.default_rng(7)
    dv = rng.standard_normal((N + 1, model.m)) * 1e-3
    dv[: N // 4] = 0.0
    naive, rec = NaiveHistory(kernel.weights(N, dt, rule)), kernel.history(N, dt, rule)
    assert isinstance(rec, RecursiveHistory) and rec.name == "modal"
    a, b = np.empty((N, model.m)), np.empty((N, model.m))
    for n in range(1, N + 1):
        a[n - 1], b[n - 1] = naive.value(n), rec.value(n)
        naive.push(n, dv[n])
        rec.push(n, dv[n])
    assert np.abs(a).max() > 0
    assert np.abs(a - b).max() <= 1e-10 * np.abs(a).max()


@pytest.mark.parametrize("rule", RULES)
def test_kernel_feeds_fft_weights(kernels, rule):
    """The kernel is a Kernel: the FFT weights of its evaluations equal its exact weights."""
    _, kernel, dt = kernels["rocking_kelvin"]
    W = kernel.weights(200, dt, rule)
    assert np.abs(cq_weights(kernel, 200, dt, get_rule(rule)) - W).max() <= 1e-12 * np.abs(W).max()


def test_history_cost_is_order_r_m(kernels):
    """Multiply-adds per step: ``2 c m + (2 q + 1) c`` with c = r channels (+ m for Kelvin
    dashpots), q = 2 for BDF2: O(r m), independent of the step n and of N."""
    for name in ("rocking", "rocking_kelvin", "random"):
        model, kernel, dt = kernels[name]
        m = model.m
        c = kernel.poles.size + (m if np.any(kernel.P1) else 0)
        short, long = kernel.history(10, dt, "bdf2"), kernel.history(2000, dt, "bdf2")
        assert short.work_per_step == long.work_per_step == 2 * c * m + 5 * c
        for n in range(1, 51):
            long.value(n)
            long.push(n, np.ones(m))
        assert long.stats == {"steps": 50, "multiply_adds": 50 * long.work_per_step}


def test_history_steps_in_order(kernels):
    _, kernel, dt = kernels["random"]
    h = kernel.history(5, dt, "bdf2")
    h.value(1)
    h.push(1, np.zeros(kernel.m))
    with pytest.raises(ValueError, match="out of order"):
        h.value(3)
    with pytest.raises(ValueError, match="rule"):
        kernel.history(5, dt, "hht")


# ---------------------------------------------------------------------- truncated modes
def chain_model(n=200, supports=(60, 140), massless_every=0):
    """Sparse chain of masses and springs, fixed at one end, on unilateral supports; Rayleigh C."""
    k, kc = 1e4, 5e3
    main = np.full(n, 2 * k)
    main[-1] = k
    K = sp.diags([main, -k * np.ones(n - 1), -k * np.ones(n - 1)], [0, 1, -1]).tolil()
    F = sp.lil_matrix((n, len(supports)))
    for j, i in enumerate(supports):
        K[i, i] += kc
        F[i, j] = kc
    mass = np.ones(n)
    if massless_every:
        mass[::massless_every] = 0.0
    M = sp.diags(mass).tocsr()
    K = K.tocsr()
    return ul.Model(M=M, K=K, F=F.tocsr(), H=kc * np.eye(len(supports)), C=0.5 * M + 2e-4 * K)


@pytest.mark.parametrize("massless_every", [0, 3])
def test_truncation_converges_with_static_correction(massless_every):
    model = chain_model(massless_every=massless_every)
    dt, N = 5e-2, 200
    rule = get_rule("bdf2")
    L = 16
    rho = 1e-15 ** (1.0 / (8 * (N + 1)))
    s = rule.delta(rho * np.exp(2j * np.pi * np.arange(L) / L)) / dt       # on the CQ circle
    ref = MatrixKernel(model)
    errors, corrections = [], []
    for modes in (5, 10, 20, 40):
        kernel = PoleResidueKernel.from_model(model, modes=modes)
        assert kernel.info["path"] == "truncated" and kernel.info["modes"] == modes
        assert kernel.info["poles"] == 2 * modes
        assert kernel.info["static_error"] <= 1e-12                      # Lambda(0) exact
        assert kernel.relative_error(ref, np.zeros(1)) <= 1e-12
        errors.append(kernel.relative_error(ref, s))
        corrections.append(kernel.info["static_correction"])
    assert np.all(np.diff(errors) < 0) and errors[-1] < errors[0] / 5
    assert np.all(np.diff(corrections) < 0) and corrections[0] > 0.1      # the correction matters


def test_truncation_exact_when_loads_lie_in_retained_modes():
    """If F = M Phi_q G, the truncated modes are not excited: the modal kernel is exact."""
    rng = np.random.default_rng(4)
    n, q, m = 30, 6, 2
    K, M = 100.0 * spd(rng, n), np.diag(rng.uniform(0.5, 2.0, n))
    Phi = sla.eigh(K, M)[1][:, :q]
    F = M @ Phi @ rng.standard_normal((q, m)) * 50.0
    model = ul.Model(M=M, K=K, F=F, H=20.0 * np.eye(m), C=0.3 * M + 2e-3 * K)
    kernel = PoleResidueKernel.from_model(model, modes=q)
    s = np.array([0.5, 3j, 10 + 40j, 1e3j])
    assert kernel.relative_error(MatrixKernel(model), s) <= 1e-10
    assert kernel.info["static_correction"] <= 1e-10
    W = kernel.weights(100, 0.02, "trapezoidal")
    ref = cq_weights(MatrixKernel(model), 100, 0.02, get_rule("trapezoidal"))
    assert np.abs(W - ref).max() <= 1e-9 * np.abs(ref).max()


@pytest.mark.parametrize("damped", [True, False])
def test_repeated_poles(damped):
    """Three identical substructures: every pole is triple, eigenvectors are not unique."""
    rng = np.random.default_rng(8)
    K1 = spd(rng, 5)
    K, M = 100.0 * sla.block_diag(K1, K1, K1), np.eye(15)
    F = 30.0 * rng.standard_normal((15, 3))
    H = F.T @ np.linalg.solve(K, F) + 10.0 * np.eye(3)
    model = ul.Model(M=M, K=K, F=F, H=H, C=0.2 * M + 1e-3 * K if damped else None)
    kernel = PoleResidueKernel.from_model(model)
    assert kernel.relative_error(MatrixKernel(model), np.array([0.3, 5j, 20 + 30j, 300j])) <= 1e-12
    p = kernel.poles[np.argsort(kernel.poles.imag)]
    assert np.allclose(p[::3], p[2::3], rtol=1e-9)


# ---------------------------------------------------------------------- errors
def test_defective_pole_is_reported():
    critical = ul.Model(M=[[1.0]], K=[[1.0]], C=[[2.0]], F=[[1.0]], H=[[2.0]])
    with pytest.raises(ValueError, match="defective"):
        PoleResidueKernel.from_model(critical)


def test_truncated_path_checks():
    rng = np.random.default_rng(5)
    n = 20
    K, M = 100.0 * spd(rng, n), np.eye(n)
    L = rng.standard_normal((n, 2))
    F = rng.standard_normal((n, 2))
    nonclassical = ul.Model(M=M, K=K, F=F, H=np.eye(2) * 1e3, C=L @ L.T)
    with pytest.raises(ValueError, match="not diagonalised"):
        PoleResidueKernel.from_model(nonclassical, modes=4)
    with pytest.raises(ValueError, match="Kelvin"):
        PoleResidueKernel.from_model(rocking_model(kelvin=True), modes=1)
    with pytest.raises(ValueError, match="less than"):
        PoleResidueKernel.from_model(nonclassical, modes=n)
    with pytest.raises(ValueError, match="positive integer"):
        PoleResidueKernel.from_model(nonclassical, modes=0)


def test_constructor_checks():
    with pytest.raises(ValueError, match="Im p < 0"):
        PoleResidueKernel([-1.0 - 2.0j], [[1.0]], [[1.0]], P0=[[1.0]])
    with pytest.raises(ValueError, match="real residues"):
        PoleResidueKernel([-1.0], [[1.0j]], [[1.0]], P0=[[1.0]])
    with pytest.raises(ValueError, match="exactly one"):
        PoleResidueKernel([-1.0], [[1.0]], [[1.0]])


# ---------------------------------------------------------------------- march
@pytest.mark.parametrize("rule", RULES)
def test_march_with_modal_history_matches_direct(rule):
    """The paper's example with uplift: CLCP march with the recursive history == direct stepping."""
    model, load = rocking_model(kelvin=True), rocking_load()
    dt, t_end = 1e-3, 0.5
    ref = ul.solve(model, load, dt=dt, t_end=t_end, method="direct", rule=rule)
    bil = ul.solve(model, load, dt=dt, t_end=t_end, method="direct", rule=rule, bilateral=True)
    assert ref.success and np.max(ref.v) > 1e-3                              # it does lift off
    np.testing.assert_array_equal(ref.v[0], bil.v[0])                        # same static base
    N = len(ref.t) - 1
    W0, history = modal_history(model, N, dt, rule)
    v, psi, log = march_cq(W0, history, bil.psi, ref.v[0], get_lcp_solver("bpp"), dt=dt)
    assert not log.failure
    assert np.abs(v - ref.v).max() <= 1e-8 * np.abs(ref.v).max()
    assert np.abs(psi - ref.psi).max() <= 1e-6 * np.abs(ref.psi).max()
    assert history.stats["steps"] == N
