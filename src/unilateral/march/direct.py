"""Direct time stepping of the full model: one LCP per step on the condensed matrix.

:func:`march_direct` is the exact reference of the CQ march (the same rule gives the same
discrete solution); :func:`march_direct_compiled` performs its operations in compiled code
(:func:`unilateral.march.compiled.direct_steps`); :func:`sweep_direct` is the linear sweep with
prescribed increments ``dv`` that gives the bilateral response ``psiL`` and recovers ``u`` after
a CLCP march.
"""

from __future__ import annotations

import time
from abc import ABC, abstractmethod

import numpy as np

from .policy import current_policy
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
        du, dud, v, psi, log = sweep_direct(stepper, N, v_b, psi0, callback=callback, compiled=False)
        return du, dud, v, stepper.model.law.rows(psi), log
    march = DirectMarch(stepper, N, v_b, psi0, solver, dt=dt, callback=callback)
    march.extend(N)
    return march.outputs()


class DirectMarch:
    """The direct march of :func:`march_direct`, advanced on request (a step at a time).

    The histories of all N steps are allocated at once and filled as the march advances;
    :meth:`extend` performs the steps up to a given one, :meth:`outputs` returns those done.
    Stepping in any pieces performs the same operations as one call of :func:`march_direct`.

    Parameters
    ----------
    stepper : StructureStepper (condensed, fresh)
    N : int, number of steps;  v_b : (m,) base deformations;  psi0 : (m,) initial reactions
    solver : LCPSolver;  dt : float
    callback : callable ``callback(k, N)``, optional, called after every step

    Attributes
    ----------
    done : int, the last step done (0 before the first)
    failure : str, why step ``done + 1`` failed ("" if none did)
    """

    def __init__(self, stepper, N, v_b, psi0, solver, *, dt, callback=None):
        law = stepper.model.law
        self.stepper, self.N, self.dt, self.callback = stepper, N, dt, callback
        self.du, self.dud, self.v, self.psi, self.log = direct_outputs(stepper, N, v_b, psi0)
        self.psi[0] = law.rows(psi0)
        self.v_b = v_b
        self.WL = law.matrix(stepper.W0)
        self.solver = law.step_solver(solver, self.WL)  # with faces: the compiled marches' step solver
        self.base = stepper.W0 @ v_b
        self.done, self.failure = 0, ""

    def extend(self, k: int) -> int:
        """Perform the steps up to ``k`` (at most N), or up to the one that fails; the last step done."""
        stepper, law, log, W0 = self.stepper, self.stepper.model.law, self.log, self.stepper.W0
        while self.done < min(k, self.N) and not self.failure:
            j = self.done + 1
            _, psi_free = stepper.predict()
            o = law.offset(self.v[j - 1])
            res = self.solver.solve(self.WL, law.vector(W0, -(psi_free + self.base), o), active=log.active)
            if not log.record(j, j * self.dt, res):
                self.failure = log.failure
                break
            self.v[j] = res.v + o
            dvk = self.v[j] - self.v_b
            self.du[j], self.dud[j] = stepper.correct(dvk)
            self.psi[j] = law.rows(psi_free - W0 @ dvk)
            self.done = j
            if self.callback is not None:
                self.callback(j, self.N)
        return self.done

    def outputs(self):
        """``(du, dudot, v, psi, log)`` of the steps done (``done + 1`` rows)."""
        K = self.done + 1
        return self.du[:K], self.dud[:K], self.v[:K], self.psi[:K], self.log


#: A compiled march with a progress callback reports after a first chunk of this many steps, then
#: after chunks sized to last about :data:`PROGRESS_SECONDS` each (a call into the compiled loop
#: costs tens of microseconds, the cost of about a hundred steps of a small model).
PROGRESS_CHUNK = 1024
PROGRESS_SECONDS = 0.1
#: A compiled march advanced a step at a time (:meth:`CompiledDirectMarch.extend`) computes ahead
#: in chunks that grow from this many steps by doubling up to :data:`AHEAD_MAX` (the march is
#: deterministic: steps computed ahead are the ones the next requests would compute).
AHEAD_MIN = 16
AHEAD_MAX = 4096


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
    march = CompiledDirectMarch.of(stepper, N, v_b, psi0, dt=dt, max_iter=max_iter, tol=tol,
                                   bilateral=bilateral, callback=callback)
    if march is None:
        return None
    march.extend(N)
    return march.outputs()


class ChunkedMarch(ABC):
    """A compiled march whose state is carried across calls, advanced on request.

    ``call(n0, n1)`` performs the steps ``n0 <= k < n1`` and returns the failed step or 0; any
    split of the steps performs the same operations as one call. :meth:`extend` computes ahead in
    chunks (:data:`AHEAD_MIN` .. :data:`AHEAD_MAX` steps) when one step is asked for, so that a
    step at a time costs no call into compiled code per step; with a progress ``callback``, a
    request of several steps runs in the chunks of :data:`PROGRESS_CHUNK`. Subclasses give the
    march's :meth:`log`. Same attributes as :class:`DirectMarch`.

    Parameters
    ----------
    call : callable ``call(n0, n1) -> int``
    histories : ``(du, dudot, v, psi)``, (N+1, n) and (N+1, m), filled by ``call``
    N : int;  callback : callable ``callback(k, N)``, optional
    """

    def __init__(self, call, histories, N, *, callback=None):
        self._call, self.histories, self.N, self.callback = call, histories, N, callback
        self.done, self.failure, self.ahead = 0, "", AHEAD_MIN

    def run_steps(self, n0: int, n1: int) -> int:
        """Steps ``n0 <= k < n1`` (``n0 = done + 1``); the failed step or 0."""
        failed = self._call(n0, n1)
        self.done = failed - 1 if failed else n1 - 1
        if failed:
            self.failure = self.log(failed).failure
        return failed

    def extend(self, k: int) -> int:
        """Perform the steps up to ``k`` at least (up to N, or the one that fails); the last step done."""
        k = min(k, self.N)
        if self.done < k and not self.failure:
            last = k
            if k == self.done + 1:                  # one step asked for: compute a chunk ahead
                last = min(self.N, self.done + self.ahead)
                self.ahead = min(2 * self.ahead, AHEAD_MAX)
            if self.callback is None:
                self.run_steps(self.done + 1, last + 1)
            else:
                _chunked(self.run_steps, self.done + 1, last, self.callback, self.N)
        return self.done

    @abstractmethod
    def log(self, failed: int = 0) -> StepLog:
        """The :class:`StepLog` of the steps done, with the step that ``failed`` (0: none)."""

    def outputs(self):
        """``(du, dudot, v, psi, log)`` of the steps done (``done + 1`` rows)."""
        K = self.done + 1
        du, dud, v, psi = (h[:K] for h in self.histories)
        log = self.log(K if self.failure else 0)
        log.active = v[-1] > 0
        return du, dud, v, psi, log


class CompiledDirectMarch(ChunkedMarch):
    """The compiled direct march (:func:`march_direct_compiled`) as a :class:`ChunkedMarch`."""

    def __init__(self, call, carry, N, v_b, *, dt, max_iter, tol, callback=None):
        super().__init__(call, carry[:4], N, callback=callback)
        self.carry, self.v_b, self.dt, self.max_iter, self.tol = carry, v_b, dt, max_iter, tol

    @classmethod
    def of(cls, stepper, N, v_b, psi0, *, dt, max_iter, tol, bilateral=False, callback=None):
        """The march of a fresh condensed ``stepper``, or None if the compiled loop does not apply."""
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
        call = lambda n0, n1: compiled.direct_steps(arrays["kind"], arrays["rp"], mats, arrays["sparse"],
                                                    tables, v_b, flags, law_arrays, carry, (n0, n1))
        return cls(call, carry, N, v_b, dt=dt, max_iter=max_iter, tol=tol, callback=callback)

    def log(self, failed=0):
        return StepLog.of_compiled(self.v_b, self.carry[4], failed, dt=self.dt, max_iter=self.max_iter,
                                   tol=self.tol)


def _chunked(run, n0, last, callback, N):
    """``run(n0, n1)`` over chunks of steps n0..last, ``callback(n1 - 1, N)`` after each; the failed
    step or 0."""
    chunk = PROGRESS_CHUNK
    while n0 <= last:
        n1 = min(n0 + chunk, last + 1)
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
    policy = current_policy()
    arrays = (stepper.sweep_arrays(N) if compiled and callback is None
              and policy.compiled_pays(N, policy.sweep_step_cost) else None)
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
