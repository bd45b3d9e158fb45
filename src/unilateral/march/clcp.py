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

from ..constraints import contact_law
from .step_log import StepLog


def march_cq(W0, history, psi_affine, v_b, solver, *, dt, bilateral=False, callback=None, law=None):
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
    law : StepLaw, optional
        The constraint families' law (:mod:`unilateral.constraints`); default: contact only.
        ``psi`` holds the constraint functions ``P psi`` of the law.

    Returns
    -------
    v, psi : (K+1, m) with K the last step solved; log : StepLog
    """
    N = psi_affine.shape[0] - 1
    m = psi_affine.shape[1]
    law = contact_law(m) if law is None else law
    v = np.empty((N + 1, m))
    psi = np.empty((N + 1, m))
    v[0] = v_b
    psi[0] = law.rows(psi_affine[0], v_b)
    log = StepLog(m, (v_b > 0) & ~law.rate)      # the warm start: the holonomic unknowns that are active
    if bilateral:
        v[:] = v_b
        return v, law.rows(psi_affine, v), log
    base = W0 @ v_b
    WL = law.matrix(W0)
    step = law.step_solver(solver, WL)
    for k in range(1, N + 1):
        o = law.offset(v[k - 1])
        q = law.vector(W0, history.value(k) - psi_affine[k] - base, o)
        res = step.solve(WL, q, active=log.active)
        if not log.record(k, k * dt, res):
            return v[:k], psi[:k], log
        v[k] = res.v + o
        psi[k] = -res.w
        history.push(k, v[k] - v_b)
        if callback is not None:
            callback(k, N)
    return v, psi, log


#: A compiled march with a progress callback reports after chunks of about this many steps (or
#: a 200th of the run, whichever is larger).
PROGRESS_CHUNK = 256


def march_cq_compiled(kind, args, v_b, *, dt, max_iter, tol, callback=None, law=None):
    """:func:`march_cq` with block principal pivoting, compiled (:mod:`unilateral.march.compiled`).

    Parameters
    ----------
    kind : "naive" (``args = (W, psi_affine)``) or "recursive"
        (``args = (W0, coef, gain, out, inp, psi_affine)``, see :func:`compiled.march_recursive`)
    callback : callable ``callback(k, N)``, optional
        Progress: the compiled loop runs in chunks of steps, with its state carried across, and
        ``callback`` is called after each chunk (the same operations as one call).
    law : StepLaw, optional (default: contact only)

    Returns the same ``(v, psi, log)`` as :func:`march_cq`.
    """
    from . import compiled

    law = contact_law(v_b.shape[0]) if law is None else law
    arrays = law.compiled()
    if callback is None:
        march = compiled.march_naive if kind == "naive" else compiled.march_recursive
        v, psi, stats, failed = march(*args, v_b, max_iter, tol, arrays)
    else:
        v, psi, stats, failed = _chunked(compiled, kind, args, v_b, max_iter, tol, callback, law=arrays)
    psi[0] = law.rows(args[-1][0])
    log = StepLog.of_compiled(v_b, stats, failed, dt=dt, max_iter=max_iter, tol=tol)
    if len(v):
        log.active = v[-1] > 0
    return v, psi, log


def _chunked(compiled, kind, args, v_b, max_iter, tol, callback, *, law):
    """The compiled march over chunks of steps, calling ``callback(k, N)`` after each."""
    psi_affine = args[-1]
    N = psi_affine.shape[0] - 1
    chunk = max(PROGRESS_CHUNK, N // 200)
    if kind == "naive":
        W = args[0]
        carry = compiled.naive_start(W[0], psi_affine, v_b)
        step = lambda n0, n1: compiled.naive_steps(W, psi_affine, v_b, max_iter, tol, law, carry, n0, n1)
    else:
        W0, filters = args[0], tuple(args[1:5])
        carry = compiled.recursive_start(W0, filters[0], psi_affine, v_b)
        step = lambda n0, n1: compiled.recursive_steps(W0, filters, psi_affine, v_b, max_iter, tol, law,
                                                       carry, (n0, n1))
    failed = 0
    for n0 in range(1, N + 1, chunk):
        n1 = min(n0 + chunk, N + 1)
        failed = step(n0, n1)
        if failed:
            break
        callback(n1 - 1, N)
    v, psi, stats = carry[0], carry[1], carry[3]
    if failed:
        return v[:failed], psi[:failed], stats, failed
    return v, psi, stats, 0
