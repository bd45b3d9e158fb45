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
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V


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
    """
    N = int(N)
    if N < 0:
        raise ValueError(f"N must be >= 0, got {N}")
    dt = V.positive_float("dt", dt)
    if L is None:
        L = 8 * (N + 1)
    L = int(L) + (int(L) % 2)
    if L < N + 1:
        raise ValueError(f"L={L} must be at least N + 1 = {N + 1}")
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
