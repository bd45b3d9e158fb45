"""FFTBlockedHistory against direct summation, and its operation count."""

from __future__ import annotations

import numpy as np
import pytest

from unilateral.march.clcp import march_cq
from unilateral.history import NaiveHistory
from unilateral.history import FFTBlockedHistory
from unilateral.lcp import get_lcp_solver

RTOL = 1e-10


def random_weights(rng, N, m):
    """Unstructured weights with a dominant ``W_0`` (which the history never uses)."""
    W = rng.standard_normal((N + 1, m, m))
    W[0] = 1e8 * np.eye(m)
    return W


def oscillator_weights(rng, N, m, dt=0.01):
    """Modal sum of damped oscillator responses, ``W_0`` SPD and large: (N+1, m, m)."""
    modes = np.linalg.qr(rng.standard_normal((m, m)))[0]
    omega = rng.uniform(5.0, 60.0, m)
    zeta = rng.uniform(0.005, 0.05, m)
    t = dt * np.arange(N + 1)[:, None]
    g = dt * np.exp(-zeta * omega * t) * np.sin(omega * np.sqrt(1 - zeta**2) * t)
    W = np.einsum("ak,jk,bk->jab", modes, g, modes)
    W[0] = 1e6 * np.eye(m) + modes @ modes.T
    return W


def dense_increments(rng, N, m):
    """Random increments after a stretch of zeros: (N+1, m), ``dv_0 = 0``."""
    dv = rng.standard_normal((N + 1, m))
    dv[: N // 3 + 1] = 0.0
    return dv


def sparse_increments(rng, N, m):
    """Mostly zero, with isolated nonzeros and one burst: (N+1, m), ``dv_0 = 0``."""
    dv = np.where(rng.random((N + 1, m)) < 0.02, rng.standard_normal((N + 1, m)), 0.0)
    start = rng.integers(0, N + 1)
    dv[start:start + 40] = rng.standard_normal(dv[start:start + 40].shape)
    dv[0] = 0.0
    return dv


def sweep(history, dv, steps):
    """Drive ``history`` as march_cq does for n = 1..steps: (steps, m) of values."""
    out = np.empty((steps, dv.shape[1]))
    for n in range(1, steps + 1):
        out[n - 1] = history.value(n)
        history.push(n, dv[n])
    return out


def term_scale(W, dv):
    """``max_n sum_{j>=1} ||W_j|| ||dv_{n-j}||``: the size of the summed terms."""
    w = np.linalg.norm(W, ord=2, axis=(1, 2))
    w[0] = 0.0
    return np.convolve(w, np.linalg.norm(dv, axis=1))[: W.shape[0]].max()


def assert_matches_naive(W, dv, steps=None, **options):
    steps = W.shape[0] - 1 if steps is None else steps
    fast = FFTBlockedHistory(W, **options)
    got = sweep(fast, dv, steps)
    expected = sweep(NaiveHistory(W), dv, steps)
    assert np.abs(got - expected).max() <= RTOL * term_scale(W, dv)
    return fast


@pytest.mark.parametrize("N", [1, 2, 7, 64, 65, 1000, 3000])
@pytest.mark.parametrize("m", [1, 3, 5])
@pytest.mark.parametrize("weights", [random_weights, oscillator_weights])
@pytest.mark.parametrize("increments", [dense_increments, sparse_increments])
def test_matches_naive(N, m, weights, increments):
    rng = np.random.default_rng([N, m])
    W = weights(rng, N, m)
    assert_matches_naive(W, increments(rng, N, m))


@pytest.mark.parametrize("base_block", [1, 2, 3, 5, 64, 200, 10**9])
def test_base_block_edge_cases(base_block):
    rng = np.random.default_rng(base_block % 1000)
    N, m = 200, 3
    fast = assert_matches_naive(oscillator_weights(rng, N, m), dense_increments(rng, N, m),
                                base_block=base_block)
    assert fast.base_block == min(base_block, N + 1)
    if base_block > N:
        assert fast.stats["fft_sizes"] == {}


@pytest.mark.parametrize("steps", [1, 63, 64, 65, 500, 511, 777])
def test_early_stop(steps):
    """A march that fails at step ``steps + 1`` has used exact values up to there."""
    rng = np.random.default_rng(steps)
    N, m = 1023, 3
    W = oscillator_weights(rng, N, m)
    dv = rng.standard_normal((N + 1, m))
    dv[0] = 0.0
    assert_matches_naive(W, dv, steps=steps, base_block=16)


def test_W0_is_ignored():
    rng = np.random.default_rng(1)
    W = random_weights(rng, 300, 2)
    dv = dense_increments(rng, 300, 2)
    ref = sweep(FFTBlockedHistory(W, base_block=4), dv, 300)
    W[0] = -3e12
    assert np.array_equal(sweep(FFTBlockedHistory(W, base_block=4), dv, 300), ref)


def test_zero_increments_skip_the_ffts():
    rng = np.random.default_rng(2)
    N = 4096
    W = random_weights(rng, N, 2)
    dv = np.zeros((N + 1, 2))
    dv[3000:] = rng.standard_normal((N + 1 - 3000, 2))
    fast = assert_matches_naive(W, dv)
    skipped = fast.stats["skipped_blocks"]
    assert skipped >= 3000 // fast.base_block
    done = sum(fast.stats["fft_sizes"].values())
    assert skipped + done == N // fast.base_block


def test_value_returns_a_fresh_array():
    rng = np.random.default_rng(3)
    W = random_weights(rng, 10, 2)
    fast = FFTBlockedHistory(W, base_block=2)
    fast.push(1, np.ones(2))
    fast.push(2, np.ones(2))
    fast.push(3, np.zeros(2))
    h = fast.value(4)
    h[:] = np.nan
    assert np.allclose(fast.value(4), W[2] @ np.ones(2) + W[3] @ np.ones(2))
    assert fast.name == "fft"


def test_same_march_as_naive():
    """march_cq with either history: the same solution (the history is as large as the load)."""
    rng = np.random.default_rng(4)
    N, m = 2000, 3
    W = oscillator_weights(rng, N, m)
    W[0] = W0 = 0.02 * np.eye(m)
    t = 0.01 * np.arange(N + 1)
    psi_affine = np.sin(np.outer(t, [3.0, 4.1, 5.3]) + rng.uniform(0, 6, m)) * 1e3 + 200.0
    v_b = np.zeros(m)
    runs = [march_cq(W0, history, psi_affine, v_b, get_lcp_solver("bpp"), dt=0.01)
            for history in (NaiveHistory(W), FFTBlockedHistory(W))]
    (v_ref, psi_ref, log_ref), (v, psi, log) = runs
    assert log_ref.contact_changes > 10 and not log.failure
    assert log.contact_changes == log_ref.contact_changes
    assert np.allclose(v, v_ref, rtol=0, atol=RTOL * np.abs(v_ref).max())
    assert np.allclose(psi, psi_ref, rtol=0, atol=RTOL * np.abs(psi_ref).max())


def fft_work(stats):
    return sum(count * size * np.log2(size) for size, count in stats["fft_sizes"].items())


def test_tiling_covers_every_pair_once():
    """Direct products plus square areas count each pair (i, n), i < n <= N, exactly once."""
    N, b = 2**10 - 1, 32
    fast = FFTBlockedHistory(np.ones((N + 1, 1, 1)), base_block=b)
    sweep(fast, np.ones((N + 1, 1)), N)
    squares = sum(count * (size // 2) ** 2 for size, count in fast.stats["fft_sizes"].items())
    assert fast.stats["direct_terms"] + squares == N * (N + 1) // 2
    assert fast.stats["direct_terms"] == sum(n % b for n in range(N + 1))


def test_work_grows_like_n_log2_n():
    Ns = 2 ** np.arange(10, 15)
    work = []
    for N in Ns:
        fast = FFTBlockedHistory(np.ones((N + 1, 1, 1)))
        sweep(fast, np.ones((N + 1, 1)), N)
        assert fast.stats["direct_terms"] <= fast.base_block * N
        work.append(fast.stats["direct_terms"] + fft_work(fast.stats))
    work = np.array(work, dtype=float)
    slope = np.polyfit(np.log(Ns), np.log(work), 1)[0]
    assert slope < 1.35                              # N^2 would give 2, N log^2 N about 1.25
    per_unit = work / (Ns * np.log2(Ns) ** 2)
    assert per_unit.max() / per_unit.min() < 1.5


@pytest.mark.parametrize("W", [np.zeros((5, 2)), np.zeros((5, 2, 3)), np.zeros((0, 2, 2))])
def test_rejects_bad_W(W):
    with pytest.raises(ValueError, match="W must have shape"):
        FFTBlockedHistory(W)


@pytest.mark.parametrize("base_block", [0, -4, 2.5, True, "8"])
def test_rejects_bad_base_block(base_block):
    with pytest.raises(ValueError, match="base_block"):
        FFTBlockedHistory(np.zeros((5, 2, 2)), base_block=base_block)
