"""Convolution quadrature weights (Lubich 1988) by FFT on a circle.

``(Lambda * v)(t_n) ~ sum_{j=0..n} W_j v_{n-j}`` with ``sum_j W_j zeta^j = Lambda(delta(zeta)/dt)``.
The weights are the Taylor coefficients of that function, obtained by the trapezoidal rule for
Cauchy's integral on the circle ``|zeta| = rho``:

    W_j ~ rho^-j / L  sum_l Lambda(delta(rho e^{2 pi i l/L}) / dt) e^{-2 pi i j l/L}

The error is aliasing ``~ rho^L`` plus round-off ``~ eps max|Lambda| rho^-N``. The default
``L = 8 (N+1)`` with ``rho^L = 1e-15`` keeps the round-off amplification ``rho^-N`` below 75
(``L = 4 (N+1)`` would give 5600). For a real kernel ``Lambda(conj s) = conj Lambda(s)``, so only
``L/2 + 1`` evaluations are needed.

Kelvin dashpots make ``Lambda(s)`` grow like ``s``, so that ``max|Lambda|`` on the circle, and
with it the round-off, can exceed the weights by orders of magnitude. The asymptote
``A0 + s A1`` (a least-squares fit on the circle) is therefore subtracted
before the transform and its weights, known exactly, added afterwards; it is kept only where it
shrinks the values on the circle.

The trapezoidal rule's ``delta(zeta) = 2 (1-zeta)/(1+zeta)`` has a pole at ``zeta = -1``: a kernel
that grows like ``s`` (Kelvin dashpots) is huge on the circle there and round-off would swamp the
weights. The transform is therefore taken of ``(1 + zeta) Lambda(delta(zeta)/dt)``, which stays
bounded, and the factor is divided out exactly afterwards (``W_j = g_j - W_{j-1}``).

**Large matrix models.** For a :class:`~unilateral.kernels.MatrixKernel` of more than
:data:`~unilateral.kernels.matrix.DENSE_BATCH_MAX_N` DOFs every point on the circle costs a sparse
factorisation of ``D(s)`` (``L/2 + 1 = 4 N + 5`` of them, about a millisecond each with SciPy's
overheads, and far more where multithreaded BLAS fights over the cores for the small products):
a beam on 41 springs took 80 to 130 s of weights for 2000 steps on a busy 2-core machine. Its
weights are then computed exactly by the rule's own recursion instead (:func:`matrix_model_weights`,
about 1 s there):
``Lambda(delta(zeta)/dt)`` is the transfer function of the rule applied to the structure, so its
Taylor coefficients are the impulse responses of the stepped structure, ``N + 1`` steps with one
factorisation of ``D(s*)`` (``docs/theory.md``, sections 5 and 6). Giving ``L`` or ``rho`` keeps
the FFT.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .. import _validate as V
from ..linalg import Factorization, transpose_times
from ..rules import BDF, Newmark
from .matrix import DENSE_BATCH_MAX_N, MatrixKernel


def cq_weights(kernel, N: int, dt: float, rule, *, L: int | None = None,
               rho: float | None = None) -> np.ndarray:
    """Convolution quadrature weights ``W_0 .. W_N`` of a real kernel.

    Parameters
    ----------
    kernel : callable
        ``kernel(s)`` for complex ``s`` of shape (L,) returns ``(L, m, m)``
        (a :class:`~unilateral.kernels.Kernel`).
    N : int
        Highest weight index (number of time steps).
    dt : float
        Time step.
    rule : Rule
        A rule with a generating function ``delta(zeta)`` (BDF1, BDF2, trapezoidal).
    L : int, optional
        Number of points on the circle (even); default ``8 (N + 1)``.
    rho : float, optional
        Radius of the circle; default ``1e-15 ** (1 / L)``.

    Returns
    -------
    W : (N + 1, m, m) float

    Notes
    -----
    A :class:`~unilateral.kernels.MatrixKernel` of more than
    :data:`~unilateral.kernels.matrix.DENSE_BATCH_MAX_N` DOFs, with neither ``L`` nor ``rho``
    given, gets the same weights from :func:`matrix_model_weights` (exact, one factorisation).
    """
    N = int(N)
    if N < 0:
        raise ValueError(f"N must be >= 0, got {N}")
    dt = V.positive_float("dt", dt)
    by_recursion = (L is None and rho is None and isinstance(kernel, MatrixKernel)
                    and kernel.n > DENSE_BATCH_MAX_N and type(rule) in (BDF, Newmark) and rule.supports_cq)
    if L is None:
        L = 8 * (N + 1)
    L = int(L) + (int(L) % 2)
    if L < N + 1:
        raise ValueError(f"L={L} must be at least N + 1 = {N + 1}")
    if by_recursion:
        return matrix_model_weights(kernel.model, N, dt, rule)
    if rho is None:
        rho = 1e-15 ** (1.0 / L)
    if not 0.0 < rho < 1.0:
        raise ValueError(f"rho must lie in (0, 1), got {rho!r}")
    zeta = rho * np.exp(2j * np.pi * np.arange(L // 2 + 1) / L)
    s = rule.delta(zeta) / dt
    values = kernel(s)                          # (L/2+1, m, m) complex
    if values.shape[1] == 0:
        return np.zeros((N + 1, 0, 0))
    A0, A1 = _asymptote(s, values)
    if A0 is not None:
        values = values - A0[None] - s[:, None, None] * A1[None]
    pole = rule.name == "trapezoidal"
    if pole:
        values = values * (1.0 + zeta)[:, None, None]
    # sum_l Lambda_l e^{-2 pi i j l/L} / L = irfft(conj(Lambda_half))[j] for Hermitian data.
    scaled = np.fft.irfft(np.conj(values), n=L, axis=0)[: N + 1]
    W = scaled * (rho ** -np.arange(N + 1))[:, None, None]
    if pole:
        # divide by (1 + zeta): W_j = g_j - W_{j-1} = (-1)^j sum_{k<=j} (-1)^k g_k
        sign = (-1.0) ** np.arange(N + 1)
        W = sign[:, None, None] * np.cumsum(sign[:, None, None] * W, axis=0)
    if A0 is not None:
        W[0] += A0
        W += (rule.delta_coefficients(N) / dt)[:, None, None] * A1[None]
    return W


def _asymptote(s, values):
    """Real ``(A0, A1)`` fitting ``Lambda(s) ~ A0 + s A1`` on the circle, or ``(None, None)``.

    Least squares over the sampled values (real and imaginary parts), so that the remainder the
    FFT sees is as small as a linear function of ``s`` can make it. Returned only if it shrinks
    the largest value on the circle at least twofold (it is an accuracy device; the weights are
    exact either way).
    """
    x, y = s.real, s.imag
    a11, a12, a22 = x.size, x.sum(), (x * x + y * y).sum()
    vr, vi = values.real, values.imag
    b1 = vr.sum(axis=0)
    b2 = np.tensordot(x, vr, axes=1) + np.tensordot(y, vi, axes=1)
    det = a11 * a22 - a12 * a12
    if det <= 0:
        return None, None
    A0 = (a22 * b1 - a12 * b2) / det
    A1 = (a11 * b2 - a12 * b1) / det
    before = np.max(np.abs(values))
    after = np.max(np.abs(values - A0[None] - s[:, None, None] * A1[None]))
    if not np.isfinite(after) or after >= 0.5 * before:
        return None, None
    return A0, A1


def matrix_model_weights(model, N: int, dt: float, rule) -> np.ndarray:
    """Convolution quadrature weights of ``Lambda(s)`` of a matrix model, by the rule's recursion.

    With ``delta(zeta)`` the generating function of a linear multistep rule, the rule applied to
    the structure with zero initial data maps a sequence ``dv`` to ``psi_n = -sum_j W_j dv_{n-j}``
    with exactly the weights of ``Lambda(delta(zeta)/dt)`` (both are the coefficients of the same
    power series in ``zeta``, ``docs/theory.md`` section 6). The ``m`` impulse responses
    ``dv_j = e_b delta_j0``, stepped together as an ``(n, m)`` block with the rule's formulas of
    :class:`~unilateral.march.stepper.StructureStepper` and one factorisation of
    ``D(s*) = c0 M + c1 C + K``, give ``W_j = -psi_j``. No aliasing and no FFT: ``O(N m nnz)``
    work against ``4 N + 5`` factorisations of ``D(s)`` on the circle.

    Parameters
    ----------
    model : Model
    N : int, highest weight index
    dt : float, time step
    rule : BDF or Newmark(1/2, 1/4) (the rules with a convolution-quadrature form)

    Returns
    -------
    W : (N + 1, m, m) float
    """
    if not (type(rule) in (BDF, Newmark) and rule.supports_cq):
        raise ValueError(f"rule={rule!r} has no recursion for convolution-quadrature weights; "
                         "valid: BDF(1), BDF(2), Newmark(0.5, 0.25) (rule='bdf1', 'bdf2', 'trapezoidal')")
    n, m = model.n, model.m
    c1, c0 = rule.coefficients(dt)
    # sparse operands keep the small products out of multithreaded BLAS
    as_op = (lambda A: None if A is None else sp.csr_matrix(A)) if model.sparse else (lambda A: A)
    M, C, K = as_op(model.M), as_op(model.damping()), as_op(model.K)
    F, F_v, H_v = as_op(model.F), as_op(model.F_v), model.H_v
    lu = Factorization(c0 * M + c1 * C + K, what=f"D(s*) = c0 M + c1 C + K at s* = {c1}")
    Fp = F if F_v is None else F + c1 * F_v
    Hs = model.H_of(c1)
    zeros = lambda rows: np.zeros((rows, m))
    state = rule.start(zeros(n), zeros(n), zeros(n), dt)
    vstate = rule.start(zeros(m), zeros(m), zeros(m), dt) if model.viscous else None
    W = np.empty((N + 1, m, m))
    impulse = np.eye(m)
    for k in range(N + 1):
        dv = impulse if k == 0 else zeros(m)
        h1, h2 = rule.history(state, dt)
        rhs = np.asarray(M @ h2) + np.asarray(C @ h1)
        psi = -Hs @ dv
        if k == 0:
            rhs = rhs + np.asarray(Fp @ dv)
        if vstate is not None:
            k1, k2 = rule.history(vstate, dt)
            if F_v is not None:
                rhs = rhs - np.asarray(F_v @ k1)
                psi = psi - transpose_times(F_v, h1)
            if H_v is not None:
                psi = psi + H_v @ k1
        du = lu.solve(rhs)
        W[k] = -(psi + transpose_times(Fp, du))
        state = rule.advance(state, du, c1 * du - h1, c0 * du - h2)
        if vstate is not None:
            vstate = rule.advance(vstate, dv, c1 * dv - k1, c0 * dv - k2)
    return W
