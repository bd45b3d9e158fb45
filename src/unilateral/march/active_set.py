"""Direct stepping of large sparse models with the LCP solved in the full space.

The condensed LCP of :func:`~unilateral.march.direct.march_direct` has a dense ``m x m`` matrix ``W0``:
for a beam on a tensionless Winkler foundation with a thousand springs every change of the
contact set costs O(m^3). Here each step is solved by block principal pivoting on the *sparse*
equations instead. With the rule's ``D_eff du = r + a Fp (v - v_b)`` and
``psi = Fp^T du + c - Hs (v - v_b)`` (``a = 1 - alpha``, ``Fp = F(c1)``, ``Hs = H(c1)``), a
trial set ``A`` of open constraints (``psi_A = 0``, ``v_N = 0``) gives

    (D_eff - a Fp_A Hs_AA^-1 Fp_A^T) du = r' + a Fp_A Hs_AA^-1 c'_A
    v_A = Hs_AA^-1 (Fp_A^T du + c'_A),      psi_N = Fp_N^T du + c'_N - Hs_NA v_A

with ``r' = r - a Fp v_b`` and ``c' = c + Hs v_b``: the structure with the open constraints
removed, a sparse matrix whose LU is cached per active set (contact sets recur). The pivoting
rule is that of Judice & Pires with Murty's fallback, so the solution equals the condensed
method's; only the linear algebra differs.
"""

from __future__ import annotations

from collections import OrderedDict

import numpy as np
import scipy.sparse as sp

from ..linalg import Factorization, is_diagonal
from .direct import direct_outputs
from .policy import current_policy


def full_space_applies(model) -> bool:
    """The full-space LCP applies to a sparse ``model`` with more constraints than the policy's
    :attr:`~unilateral.march.policy.SizePolicy.full_space_min_m`, all of the trivial law, whose
    ``H`` has no zero on its diagonal (the open constraints' ``H_AA`` are inverted; a rigid
    contact, ``H = 0``, needs the condensed LCP): the condensed ``W0`` would be large and dense."""
    if not (model.sparse and model.m > current_policy().full_space_min_m and model.law.trivial):
        return False
    H = model.H
    diagonal = H.diagonal() if hasattr(H, "diagonal") and not isinstance(H, np.ndarray) else np.diag(H)
    return bool(np.all(diagonal != 0.0))


#: Factorisations kept (least recently used first out).
CACHE_SIZE = 16
#: Non-improving block pivots before Murty's single pivot (as :data:`unilateral.lcp.pivoting.BLOCK_TRIES`).
_BLOCK_TRIES = 3


class ActiveSetSolver:
    """The LCP of one step (or of the static state) in the full space.

    Parameters
    ----------
    D : (n, n) sparse, the effective stiffness (``K`` for the static state)
    Fp : (n, m) sparse or dense;  Hs : (m, m) dense;  a : float, ``1 - alpha`` (1 for statics)
    v_b : (m,) base deformations
    max_iter : int, trial active sets per step at most
    """

    def __init__(self, D, Fp, Hs, a, v_b, max_iter=50):
        self.a = a
        self.Fp = sp.csc_matrix(Fp)
        self.Hs = np.asarray(Hs)
        self.diagonal = is_diagonal(self.Hs)
        self.D_eff = sp.csc_matrix(D)
        self.v_b = v_b
        self.shift = self.a * (self.Fp @ v_b)
        self.Hv_b = self.Hs @ v_b
        self.max_iter = max_iter
        self._cache = OrderedDict()
        self.factorizations = 0

    @classmethod
    def of_stepper(cls, stepper, v_b, max_iter=50):
        """For the steps of a :class:`~unilateral.march.stepper.StructureStepper` (``condensed=False``)."""
        return cls(stepper.D_eff, stepper.Fp, stepper.Hs, 1.0 - stepper.alpha, v_b, max_iter)

    def solve(self, rhs, c, active):
        """Return ``(v, psi, du, active, iterations)``; ``iterations < 0`` on failure."""
        r = rhs - self.shift
        cp = c + self.Hv_b
        m = cp.shape[0]
        active = active.copy()
        best, tries = m + 1, _BLOCK_TRIES
        for it in range(1, self.max_iter + 1):
            A = np.flatnonzero(active)
            lu, FA, HA_inv = self._factor(A)
            rhs_A = r.copy()
            if A.size:
                rhs_A += self.a * (FA @ (HA_inv @ cp[A]))
            du = lu.solve(rhs_A)
            v = np.zeros(m)
            if A.size:
                v[A] = HA_inv @ (FA.T @ du + cp[A])
            psi = self.Fp.T @ du + cp - self.Hs @ v
            psi[A] = 0.0
            scale = 1e-13 * max(1.0, np.max(np.abs(cp)))
            bad = (active & (v < -scale)) | (~active & (psi > scale))
            count = int(bad.sum())
            if count == 0:
                v[v < 0] = 0.0
                return v, psi, du, active, it
            if count < best:
                best, tries = count, _BLOCK_TRIES
            elif tries > 0:
                tries -= 1
            else:
                last = int(np.flatnonzero(bad)[-1])
                bad[:] = False
                bad[last] = True
            active ^= bad
        return v, psi, du, active, -self.max_iter

    def _factor(self, A):
        key = A.tobytes()
        hit = self._cache.get(key)
        if hit is not None:
            self._cache.move_to_end(key)
            return hit
        FA = self.Fp[:, A]
        HA = self.Hs[np.ix_(A, A)]
        HA_inv = np.diag(1.0 / np.diag(HA)) if self.diagonal else np.linalg.inv(HA)
        D = self.D_eff
        if A.size:
            D = D - self.a * (FA @ sp.csr_matrix(HA_inv) @ FA.T)
        lu = Factorization(D, what="the effective stiffness without the open constraints")
        self.factorizations += 1
        self._cache[key] = (lu, FA, HA_inv)
        if len(self._cache) > CACHE_SIZE:
            self._cache.popitem(last=False)
        return self._cache[key]


def march_direct_active_set(stepper, N, v_b, psi0, *, dt, bilateral=False, callback=None,
                            max_iter=50):
    """:func:`~unilateral.march.direct.march_direct` for large sparse models (same returns)."""
    march = ActiveSetMarch(stepper, N, v_b, psi0, dt=dt, bilateral=bilateral, callback=callback,
                           max_iter=max_iter)
    march.extend(N)
    return march.outputs()


class ActiveSetMarch:
    """The march of :func:`march_direct_active_set`, advanced a step at a time on request.

    Same interface as :class:`~unilateral.march.direct.DirectMarch` (``done``, ``failure``,
    ``extend(k)``, ``outputs()``); stepping in any pieces performs the same operations.
    """

    def __init__(self, stepper, N, v_b, psi0, *, dt, bilateral=False, callback=None, max_iter=50):
        self.stepper, self.N, self.v_b, self.dt = stepper, N, v_b, dt
        self.bilateral, self.callback = bilateral, callback
        self.du, self.dud, self.v, self.psi, self.log = direct_outputs(stepper, N, v_b, psi0)
        self.solver = ActiveSetSolver.of_stepper(stepper, v_b, max_iter)
        self.active = v_b > 0
        self.done, self.failure = 0, ""

    def extend(self, k: int) -> int:
        """Perform the steps up to ``k`` (at most N), or up to the one that fails; the last step done."""
        stepper, v_b, log = self.stepper, self.v_b, self.log
        while self.done < min(k, self.N) and not self.failure:
            j = self.done + 1
            rhs, c = stepper.free_terms()
            if self.bilateral:                  # v held at v_b: the plain effective stiffness
                duk = stepper.lu.solve(rhs)
                vk, psik, it = v_b, c + stepper.Fp.T @ duk, 1
            else:
                vk, psik, duk, self.active, it = self.solver.solve(rhs, c, self.active)
            res = _Result(vk, -psik, it, scale=1.0 + np.linalg.norm(c))
            if not log.record(j, j * self.dt, res):
                self.failure = log.failure
                break
            self.du[j], self.dud[j] = stepper.correct(vk - v_b, du=duk)
            self.v[j], self.psi[j] = vk, psik
            self.done = j
            if self.callback is not None:
                self.callback(j, self.N)
        return self.done

    def outputs(self):
        """``(du, dudot, v, psi, log)`` of the steps done (``done + 1`` rows)."""
        K = self.done + 1
        self.log.factorizations = self.solver.factorizations
        return self.du[:K], self.dud[:K], self.v[:K], self.psi[:K], self.log


class _Result:
    """The fields of an LCPResult that :class:`StepLog` reads."""

    def __init__(self, v, w, iterations, scale):
        self.v, self.w = v, w
        self.iterations = abs(iterations)
        self.success = iterations > 0
        self.error = float(np.linalg.norm(np.minimum(v, w)) / scale)
        self.message = ("block principal pivoting in the full space did not converge in "
                        f"{abs(iterations)} trial contact sets; try lcp='lemke' with a condensed "
                        "method (method='direct' on a model with fewer constraints, or method='cq')")
