"""Brute-force enumeration of complementary bases (reference solver)."""

from __future__ import annotations

from itertools import combinations

import numpy as np

from .base import LCPSolver, PrincipalSystems, SolverOutcome, lcp_error


def _subsets(m, first):
    """Active sets to try: ``first`` (if given), then all subsets of range(m) by size.

    Parameters
    ----------
    m : int
    first : ndarray of bool, shape (m,), or None

    Yields
    ------
    ndarray of bool, shape (m,)
    """
    if first is not None:
        yield first.copy()
    for size in range(m + 1):
        for subset in combinations(range(m), size):
            active = np.zeros(m, dtype=bool)
            active[list(subset)] = True
            yield active


class Enumeration(LCPSolver):
    """Try every principal subset: the reference solver for small problems.

    For each candidate active set ``F`` (smallest first) the complementary
    solution ``v_F = -W_FF^-1 q_F`` is formed and accepted if its LCP error
    is ``<= tol``. Cost O(2^m m^3): only for ``m <= 20`` (larger ``m``
    raises ValueError). ``v`` is exactly 0 off the returned set.

    Requirements: none for correctness of an accepted answer; a P-matrix
    guarantees exactly one solution (so the method finds it). If no subset
    qualifies the one with the smallest error is returned with
    ``success=False``.

    ``iterations`` counts subsets tried. A warm start ``active`` is tried
    first (an exact active set needs 1).

    Parameters
    ----------
    tol : float, default 1e-10
        Acceptance and success threshold on the LCP error.
    max_iter : int, optional
        Limit on subsets tried; default all ``2^m`` (plus the warm start).
    """

    name = "enumerate"
    max_size = 20

    def default_max_iter(self, m):
        return 2**m + 1

    def _solve(self, W, q, active):
        max_iter = self.iteration_limit(q.size)
        systems = PrincipalSystems(W, q)
        best = (np.inf, None, None)
        for tried, subset in enumerate(_subsets(q.size, active), start=1):
            v = systems.solve(subset)
            error = lcp_error(v, W @ v + q, q)
            if error <= self.tol:
                return SolverOutcome(v, subset, tried, True, f"enumeration: solved after {tried} subsets")
            if error < best[0]:
                best = (error, v, subset)
            if tried == max_iter:
                break
        error, v, subset = best
        return SolverOutcome(
            v, subset, tried, False,
            f"enumeration tried {tried} principal subsets and none solves the LCP to tol {self.tol:.1e} "
            f"(best error {error:.1e}): the LCP has no solution (W is not a P-matrix?) or is too "
            "ill-conditioned for tol; loosen tol or check W",
        )
