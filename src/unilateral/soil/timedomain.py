"""Minimal convolution quadrature (Lubich 1988) for Laplace-domain soil kernels.

``(K * f)(t_n) ~ sum_{j=0..n} W_j f_{n-j}`` with ``sum_j W_j zeta^j = K(delta(zeta)/dt)``; the weights
are Taylor coefficients obtained by the trapezoidal rule on the circle ``|zeta| = rho``,
``rho^L = 1e-15``, ``L = 8 (N+1)`` (aliasing ~1e-15, round-off amplification ``rho^-N < 75``).
Self-contained here so that the soil tests do not depend on the rest of the package.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V

__all__ = ["DELTAS", "cq_points", "cq_weights", "step_response"]

DELTAS = {
    "bdf1": lambda z: 1.0 - z,
    "bdf2": lambda z: (1.0 - z) + 0.5 * (1.0 - z) ** 2,
}


def cq_points(N, dt, rule="bdf2"):
    """Circle points ``zeta_l`` (l = 0..L/2) and the Laplace points ``s_l = delta(zeta_l)/dt``."""
    N = int(N)
    dt = V.positive_float("dt", dt)
    rule = V.choice("rule", rule, DELTAS)
    L = 8 * (N + 1)
    rho = 1e-15 ** (1.0 / L)
    zeta = rho * np.exp(2j * np.pi * np.arange(L // 2 + 1) / L)
    return zeta, DELTAS[rule](zeta) / dt, L, rho


def cq_weights(values, N, L, rho):
    """Weights ``W_0..W_N`` (real) from kernel values on the half circle.

    ``values``: (L/2+1, ...) complex, the kernel at ``cq_points`` (conjugate symmetry supplies the rest).
    """
    values = np.asarray(values)
    full = np.concatenate([values, np.conj(values[-2:0:-1])], axis=0)     # (L, ...)
    coef = np.fft.fft(full, axis=0) / L
    j = np.arange(N + 1).reshape((-1,) + (1,) * (values.ndim - 1))
    return (coef[: N + 1] * rho ** (-j)).real


def step_response(kernel, N, dt, rule="bdf2"):
    """Response ``u(t_n)``, ``t_n = n dt``, to a unit step input through a Laplace kernel ``K(s)``.

    ``kernel(s)`` for (ns,) complex ``s`` returns (ns, ...). Returns (N+1, ...) real, the CQ
    approximation of ``L^{-1}[K(s)/s]``.
    """
    zeta, s, L, rho = cq_points(N, dt, rule)
    W = cq_weights(kernel(s), N, L, rho)
    return np.cumsum(W, axis=0)
