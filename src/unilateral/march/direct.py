"""Direct time stepping of the full model: one LCP per step on the condensed matrix.

:func:`march_direct` is the exact reference of the CQ march (the same rule gives the same
discrete solution); :func:`sweep_direct` is the linear sweep with prescribed increments ``dv``
that gives the bilateral response ``psiL`` and recovers ``u`` after a CLCP march.
"""

from __future__ import annotations

import numpy as np

from .step_log import StepLog


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
    (:func:`unilateral.march.compiled.sweep`, the same operations) unless ``compiled`` is False or a
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
