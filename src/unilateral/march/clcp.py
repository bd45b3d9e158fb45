"""Step-by-step solution of the convolutional LCP (eq. 27): one small LCP per time step.

The march works on increments about a base state ``(v_b, psi_b)``:
``psi_n = a_n - W_0 dv_n`` with the known term ``a_n = psi_affine_n - sum_{j>=1} W_j dv_{n-j}``
(eq. 27a), where ``psi_affine`` is the base reaction plus the bilateral response increment and
``W_j`` the convolution weights; the history sum comes from :mod:`unilateral.history`.
:func:`march_cq` runs in Python with any history and LCP solver; :func:`march_cq_compiled` runs
the naive or the recursive history with block principal pivoting in compiled code.
"""

from __future__ import annotations

import numpy as np

from .step_log import StepLog


def march_cq(W0, history, psi_affine, v_b, solver, *, dt, bilateral=False, callback=None):
    """March the CLCP ``psi_n = psi_affine_n - sum_{j=0..n} W_j (v_{n-j} - v_b)``.

    Parameters
    ----------
    W0 : (m, m) the weight ``W_0``, symmetric positive definite
    history : object with ``value(n) -> (m,)`` (``sum_{j>=1} W_j dv_{n-j}``) and ``push(n, dv_n)``
    psi_affine : (N+1, m)
    v_b : (m,) base deformations (``v_0``)
    solver : LCPSolver
    dt : float (for messages)
    bilateral : bool
        Hold every constraint (``dv = 0``): then ``psi = psi_affine``.
    callback : callable ``callback(k, N)``, optional (progress)

    Returns
    -------
    v, psi : (K+1, m) with K the last step solved; log : StepLog
    """
    N = psi_affine.shape[0] - 1
    m = psi_affine.shape[1]
    v = np.empty((N + 1, m))
    psi = np.empty((N + 1, m))
    v[0] = v_b
    psi[0] = psi_affine[0]
    log = StepLog(m, v_b > 0)
    if bilateral:
        v[:] = v_b
        return v, psi_affine.copy(), log
    base = W0 @ v_b
    for k in range(1, N + 1):
        q = history.value(k) - psi_affine[k] - base
        res = solver.solve(W0, q, active=log.active)
        if not log.record(k, k * dt, res):
            return v[:k], psi[:k], log
        v[k] = res.v
        psi[k] = -res.w
        history.push(k, res.v - v_b)
        if callback is not None:
            callback(k, N)
    return v, psi, log


def march_cq_compiled(kind, args, v_b, *, dt, max_iter, tol):
    """:func:`march_cq` with block principal pivoting, compiled (:mod:`unilateral.march.compiled`).

    Parameters
    ----------
    kind : "naive" (``args = (W, psi_affine)``) or "recursive"
        (``args = (W0, coef, gain, out, inp, psi_affine)``, see :func:`compiled.march_recursive`)

    Returns the same ``(v, psi, log)`` as :func:`march_cq`.
    """
    from . import compiled

    march = compiled.march_naive if kind == "naive" else compiled.march_recursive
    v, psi, stats, failed = march(*args, v_b, max_iter, tol)
    log = StepLog(v_b.shape[0], v_b > 0)
    log.iterations, log.max_iterations = int(stats[0]), int(stats[1])
    log.contact_changes, log.max_error = int(stats[2]), float(stats[3])
    if failed:
        log.failure = (
            f"the LCP of step {failed} (t = {failed * dt:.6g}) failed: block principal pivoting "
            f"found a principal submatrix of W0 that is not positive definite, did not converge in "
            f"{max_iter} solves, or left an LCP error above tol = {tol:g}; try lcp='lemke'"
        )
    if len(v):
        log.active = v[-1] > 0
    return v, psi, log
