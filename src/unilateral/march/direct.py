"""Direct time stepping of the full model: one LCP per step on the condensed matrix.

:func:`march_direct` is the exact reference of the CQ march (the same rule gives the same
discrete solution); :func:`march_direct_compiled` performs its operations in compiled code
(:func:`unilateral.march.compiled.direct_steps`); :func:`sweep_direct` is the linear sweep with
prescribed increments ``dv`` that gives the bilateral response ``psiL`` and recovers ``u`` after
a CLCP march.
"""

from __future__ import annotations

import time

import numpy as np

from .jit import SWEEP_STEP_COST, compiled_pays
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
    law = stepper.model.law
    if bilateral:                           # the same (Python) operations as the LCP march
        du, dud, v, psi, log = sweep_direct(stepper, N, v_b, psi0, callback=callback, compiled=False)
        return du, dud, v, law.rows(psi), log
    du, dud, v, psi, log = direct_outputs(stepper, N, v_b, psi0)
    psi[0] = law.rows(psi0)
    W0 = stepper.W0
    WL = law.matrix(W0)
    base = W0 @ v_b
    for k in range(1, N + 1):
        _, psi_free = stepper.predict()
        o = law.offset(v[k - 1])
        res = solver.solve(WL, law.vector(W0, -(psi_free + base), o), active=log.active)
        if not log.record(k, k * dt, res):
            return du[:k], dud[:k], v[:k], psi[:k], log
        v[k] = res.v + o
        dvk = v[k] - v_b
        du[k], dud[k] = stepper.correct(dvk)
        psi[k] = law.rows(psi_free - W0 @ dvk)
        if callback is not None:
            callback(k, N)
    return du, dud, v, psi, log


#: A compiled march with a progress callback reports after a first chunk of this many steps, then
#: after chunks sized to last about :data:`PROGRESS_SECONDS` each (a call into the compiled loop
#: costs tens of microseconds, the cost of about a hundred steps of a small model).
PROGRESS_CHUNK = 1024
PROGRESS_SECONDS = 0.1


def march_direct_compiled(stepper, N, v_b, psi0, *, dt, max_iter, tol, bilateral=False,
                          callback=None):
    """:func:`march_direct` with block principal pivoting, compiled; None if it does not apply.

    The same operations (:func:`unilateral.march.compiled.direct_steps`): the free step, the
    condensed LCP on ``W0`` (factorised once, warm-started from the previous contact set) and the
    correction, for every rule of :mod:`unilateral.rules`. It applies to a fresh condensed
    ``stepper`` (:meth:`~unilateral.march.stepper.StructureStepper.march_arrays`).

    Parameters
    ----------
    stepper : StructureStepper (condensed, fresh)
    N : int;  v_b : (m,) base deformations;  psi0 : (m,) initial reactions
    dt : float (for messages)
    max_iter : int, linear solves per LCP at most
    tol : float, largest acceptable LCP error of a step
    bilateral : bool, hold every constraint (``dv = 0``)
    callback : callable ``callback(k, N)``, optional
        Progress: the loop runs in chunks of steps (:data:`PROGRESS_CHUNK`, then about
        :data:`PROGRESS_SECONDS` each) with its state carried across, and ``callback`` is called
        after each chunk: the same operations as one call.

    Returns
    -------
    The same ``(du, dudot, v, psi, log)`` as :func:`march_direct`, or None.
    """
    arrays = stepper.march_arrays(N)
    if arrays is None:
        return None
    from . import compiled

    n, m = stepper.model.n, stepper.model.m
    v_b = np.ascontiguousarray(v_b, dtype=float)
    mats = arrays["mats"]
    tables = (arrays["f"], arrays["offset"], mats[-1] @ v_b)
    flags = (float(arrays["c0"]), arrays["alpha"], bool(arrays["viscous"]), bool(bilateral),
             int(max_iter), float(tol))
    law = stepper.model.law
    carry = compiled.direct_start(N + 1, n, m, v_b, np.ascontiguousarray(law.rows(psi0), dtype=float),
                                  arrays["ustart"])
    law_arrays = law.compiled()
    run = lambda n0, n1: compiled.direct_steps(arrays["kind"], arrays["rp"], mats, arrays["sparse"],
                                               tables, v_b, flags, law_arrays, carry, (n0, n1))
    if callback is None:
        failed = run(1, N + 1)
    else:
        failed = _chunked(run, N, callback)
    du, dud, v, psi, stats = carry[:5]
    log = StepLog.of_compiled(v_b, stats, failed, dt=dt, max_iter=max_iter, tol=tol)
    if failed:
        du, dud, v, psi = du[:failed], dud[:failed], v[:failed], psi[:failed]
    log.active = v[-1] > 0
    return du, dud, v, psi, log


def _chunked(run, N, callback):
    """``run(n0, n1)`` over chunks of steps 1..N, ``callback(n1 - 1, N)`` after each; the failed step or 0."""
    n0, chunk = 1, PROGRESS_CHUNK
    while n0 <= N:
        n1 = min(n0 + chunk, N + 1)
        start = time.perf_counter()
        failed = run(n0, n1)
        if failed:
            return failed
        callback(n1 - 1, N)
        elapsed = max(time.perf_counter() - start, 1e-6)
        chunk = int(min(8 * chunk, max(PROGRESS_CHUNK, chunk * PROGRESS_SECONDS / elapsed)))
        n0 = n1
    return 0


def sweep_direct(stepper, N, v_b, psi0, dv=None, *, callback=None, compiled=True):
    """A linear sweep of the full model with prescribed increments ``dv`` (zero by default).

    With ``dv = 0`` it gives the bilateral response ``psiL``; with the increments of a CLCP
    solution it recovers the displacements. Small dense models are swept by compiled code
    (:func:`unilateral.march.compiled.sweep`, the same operations) unless ``compiled`` is False or a
    ``callback`` is given. Same returns as :func:`march_direct`.
    """
    du, dud, v, psi, log = direct_outputs(stepper, N, v_b, psi0)
    m = stepper.model.m
    arrays = (stepper.sweep_arrays(N) if compiled and callback is None and compiled_pays(N, SWEEP_STEP_COST)
              else None)
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
