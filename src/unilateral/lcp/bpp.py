"""Block principal pivoting (Judice & Pires 1994) with Murty's fallback."""

from __future__ import annotations

import math

import numpy as np

from .base import LCPSolver, PrincipalSystems, SolverOutcome


class BlockPrincipalPivoting(LCPSolver):
    """Block principal pivoting method for LCPs.

    Each iteration takes the complementary basis of the current active set
    ``F`` (``v_F = -W_FF^-1 q_F``, ``v = 0`` off ``F``, ``w = W v + q``),
    and exchanges all infeasible indices (``v_i < 0`` in ``F``, ``w_i < 0``
    off ``F``) at once. When the number of infeasibilities fails to improve
    on its best value ``max_nonimproving`` times in a row, a single pivot on
    the smallest infeasible index (Murty's least-index rule) is done instead,
    which guarantees termination for P-matrices (Judice & Pires, Computers
    Ops Res 21, 1994). ``v`` is exactly 0 off the final ``F``.

    Requirements: ``W`` a P-matrix (e.g. symmetric positive definite, or
    nonsymmetric P). For singular ``W_FF`` (positive semidefinite ``W``) the
    minimum-norm solution is used, which often works but is not guaranteed;
    use ``solver='lemke'`` if it fails.

    ``iterations`` counts linear solves (= principal pivots + 1): with the
    exact active set as warm start ``active`` the method takes one.

    Parameters
    ----------
    tol : float, default 1e-10
        Success threshold on the LCP error; components of ``w`` above
        ``-tol (1 + ||q||) / (2 sqrt(m))`` count as feasible, and of ``v`` above that divided
        by the largest ``|W_ij|`` (the same threshold in the units of ``v``).
    max_iter : int, optional
        Limit on linear solves; default ``100 + 20 m``.
    max_nonimproving : int, default 3
        Block pivots allowed without reducing the number of infeasibilities
        before falling back to single pivots.
    """

    name = "bpp"

    def __init__(self, *, tol=1e-10, max_iter=None, max_nonimproving=3):
        super().__init__(tol=tol, max_iter=max_iter)
        if int(max_nonimproving) != max_nonimproving or max_nonimproving < 0:
            raise ValueError(f"max_nonimproving must be a non-negative integer, got {max_nonimproving!r}")
        self.max_nonimproving = int(max_nonimproving)

    def default_max_iter(self, m):
        return 100 + 20 * m

    def _solve(self, W, q, active):
        m = q.size
        F = np.zeros(m, dtype=bool) if active is None else active.copy()
        # Thresholds in the units of w and of v: clipping a v component within its threshold
        # changes w by at most |W|_max times it, i.e. by at most the w threshold.
        w_feasibility = -0.5 * self.tol * (1.0 + math.sqrt(q @ q)) / math.sqrt(m)
        v_feasibility = w_feasibility / max(float(np.max(np.abs(W))), np.finfo(float).tiny)
        best, budget = m + 1, self.max_nonimproving
        systems = PrincipalSystems(W, q)
        max_iter = self.iteration_limit(m)
        for solves in range(1, max_iter + 1):
            v = systems.solve(F)
            w = W @ v + q
            infeasible = np.where(F, v < v_feasibility, w < w_feasibility)
            count = int(np.count_nonzero(infeasible))
            if count == 0:
                return SolverOutcome(v, F, solves, True,
                                     f"BPP: feasible complementary basis after {solves} linear solves")
            if solves == max_iter:
                break
            if count < best:
                best, budget = count, self.max_nonimproving
            elif budget > 0:
                budget -= 1
            else:  # Murty's single pivot on the least infeasible index
                F[np.argmax(infeasible)] ^= True
                continue
            F = F ^ infeasible  # block pivot
        return SolverOutcome(
            v, F, max_iter, False,
            f"BPP found no feasible complementary basis in {max_iter} linear solves ({count} "
            "infeasible components left); W may not be a P-matrix: use solver='lemke', or raise max_iter",
        )
