"""Step-by-step solution of the convolutional LCP (eq. 27): one small LCP per time step.

Both marches work on increments about a base state ``(v_b, psi_b)``:

* :func:`march_cq` -- the paper's method. ``psi_n = a_n - W_0 dv_n`` with the known term
  ``a_n = psi_affine_n - sum_{j>=1} W_j dv_{n-j}`` (eq. 27a), where ``psi_affine`` is the base
  reaction plus the bilateral response increment and ``W_j`` the convolution-quadrature weights.
* :func:`march_direct` -- the full model stepped with the same rule, one LCP per step on the
  condensed matrix; the exact reference for the CQ march.
"""

from __future__ import annotations

import numpy as np


class StepLog:
    """LCP statistics over a march, and the first failure."""

    def __init__(self, m: int, active0: np.ndarray):
        self.iterations = 0
        self.max_iterations = 0
        self.max_error = 0.0
        self.contact_changes = 0
        self.active = active0.copy()
        self.failure = ""

    def record(self, k: int, t: float, res) -> bool:
        """Account for the LCP of step k; return False (and keep a message) on failure."""
        self.iterations += res.iterations
        self.max_iterations = max(self.max_iterations, res.iterations)
        self.max_error = max(self.max_error, res.error)
        active = res.v > 0
        self.contact_changes += int(np.count_nonzero(active != self.active))
        self.active = active
        if not res.success:
            self.failure = f"the LCP of step {k} (t = {t:.6g}) failed: {res.message}"
            return False
        return True

    def stats(self) -> dict:
        return {"lcp_iterations": self.iterations, "lcp_max_iterations": self.max_iterations,
                "max_lcp_error": self.max_error, "contact_changes": self.contact_changes}


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


def direct_outputs(stepper, N, v_b, psi0):
    """Histories of a direct march, initialised at step 0: ``du, dudot, v, psi, log``."""
    n, m = stepper.model.n, stepper.model.m
    du = np.zeros((N + 1, n))
    dud = np.zeros((N + 1, n))
    v = np.empty((N + 1, m))
    psi = np.empty((N + 1, m))
    dud[0] = stepper.ud
    v[0] = v_b
    psi[0] = psi0
    return du, dud, v, psi, StepLog(m, v_b > 0)


def march_direct(stepper, N, v_b, psi0, solver, *, dt, bilateral=False, callback=None):
    """March the full model: per step a free prediction, an LCP on ``W0``, a correction.

    Parameters
    ----------
    stepper : StructureStepper (condensed)
    N : int, number of steps
    v_b : (m,) base deformations
    psi0 : (m,) initial reactions
    solver : LCPSolver
    dt : float
    bilateral : bool
        Hold every constraint (``dv = 0``): see :func:`sweep_direct`.
    callback : callable ``callback(k, N)``, optional

    Returns
    -------
    du, dudot : (K+1, n) ; v, psi : (K+1, m) ; log : StepLog
    """
    if bilateral:                           # the same (Python) operations as the LCP march
        return sweep_direct(stepper, N, v_b, psi0, callback=callback, compiled=False)
    du, dud, v, psi, log = direct_outputs(stepper, N, v_b, psi0)
    W0 = stepper.W0
    base = W0 @ v_b
    for k in range(1, N + 1):
        _, psi_free = stepper.predict()
        res = solver.solve(W0, -(psi_free + base), active=log.active)
        if not log.record(k, k * dt, res):
            return du[:k], dud[:k], v[:k], psi[:k], log
        dvk = res.v - v_b
        du[k], dud[k] = stepper.correct(dvk)
        v[k] = res.v
        psi[k] = psi_free - W0 @ dvk
        if callback is not None:
            callback(k, N)
    return du, dud, v, psi, log


def sweep_direct(stepper, N, v_b, psi0, dv=None, *, callback=None, compiled=True):
    """A linear sweep of the full model with prescribed increments ``dv`` (zero by default).

    With ``dv = 0`` it gives the bilateral response ``psiL``; with the increments of a CLCP
    solution it recovers the displacements. Small dense models are swept by compiled code
    (:func:`unilateral.compiled.sweep`, the same operations) unless ``compiled`` is False or a
    ``callback`` is given. Same returns as :func:`march_direct`.
    """
    du, dud, v, psi, log = direct_outputs(stepper, N, v_b, psi0)
    m = stepper.model.m
    arrays = stepper.sweep_arrays(N) if compiled and callback is None else None
    if arrays is not None:                  # compiled: the same operations, in machine code
        from .compiled import sweep

        increments = np.zeros((N + 1, m)) if dv is None else np.ascontiguousarray(dv[: N + 1], dtype=float)
        du, dud, psi_all = sweep(*arrays[:-3], arrays[-3], arrays[-2], increments, arrays[-1])
        psi[1:] = psi_all[1:]
        v[1:] = v_b + increments[1:]
        return du, dud, v, psi, log
    zero = np.zeros(m)
    for k in range(1, N + 1):
        dvk = zero if dv is None else dv[k]
        du[k], psi[k] = stepper.step_with(dvk)
        dud[k] = stepper.correct(dvk, du=du[k])[1]
        v[k] = v_b + dvk
        if callback is not None:
            callback(k, N)
    return du, dud, v, psi, log


def march_cq_compiled(kind, args, v_b, *, dt, max_iter, tol):
    """:func:`march_cq` with block principal pivoting, compiled (:mod:`unilateral.compiled`).

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
