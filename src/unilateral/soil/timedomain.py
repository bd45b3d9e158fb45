"""Soil kernels in time: step responses by convolution quadrature (:func:`unilateral.kernels.cq_weights`)."""

from __future__ import annotations

import numpy as np

__all__ = ["step_response"]


def step_response(kernel, N, dt, rule="bdf2"):
    """Response ``u(t_n)``, ``t_n = n dt``, to a unit step input through a Laplace kernel ``K(s)``.

    Parameters
    ----------
    kernel : callable
        ``kernel(s)`` for (ns,) complex ``s`` returns (ns,) or (ns, m, m); real for real ``s``.
    N : int, number of steps ; dt : float, s ; rule : ``"bdf1"``, ``"bdf2"`` or ``"trapezoidal"``

    Returns
    -------
    (N+1,) or (N+1, m, m) float
        The CQ approximation of ``L^-1[K(s)/s]`` (the running sum of the CQ weights of ``K``).
    """
    from ..kernels import cq_weights
    from ..rules import get_rule

    def as_matrices(s):
        out = np.asarray(kernel(s))
        return out.reshape(-1, 1, 1) if out.ndim == 1 else out

    W = cq_weights(as_matrices, int(N), dt, get_rule(rule, cq=True))
    u = np.cumsum(W, axis=0)
    return u[:, 0, 0] if np.asarray(kernel(np.array([1.0 / dt + 0j]))).ndim == 1 else u
