"""Lemke's complementary pivoting method with a lexicographic ratio test."""

from __future__ import annotations

import numpy as np

from .base import LCPSolver, PrincipalSystems, SolverOutcome

#: Entries of the entering column below this fraction of its largest entry
#: do not qualify as pivots.
PIVOT_TOL = 1e-12
#: Ratios within this fraction of the largest candidate ratio count as tied.
TIE_TOL = 1e-12


def _lexmin_rows(values, rows):
    """Rows (subset of ``rows``) attaining the minimum of ``values`` up to ``TIE_TOL``."""
    return rows[values <= values.min() + TIE_TOL * np.abs(values).max()]


def _leaving_row(T, d, basis, z0):
    """Lexicographic minimum ratio test.

    Parameters
    ----------
    T : ndarray, shape (m, m + 1)
        ``[x_B, B^-1]``: basic values and inverse basis.
    d : ndarray, shape (m,)
        Entering column ``B^-1 a``.
    basis : ndarray of int, shape (m,)
        Basic variable per row.
    z0 : int
        Id of the artificial variable; it leaves whenever it ties for the
        minimum ratio (which ends the method).

    Returns
    -------
    int
        The pivot row, or -1 if no entry of ``d`` is positive (ray).
    """
    rows = (d > PIVOT_TOL * np.abs(d).max()).nonzero()[0]
    if rows.size == 0:
        return -1
    rows = _lexmin_rows(T[rows, 0] / d[rows], rows)
    if rows.size == 1:
        return int(rows[0])
    artificial = rows[basis[rows] == z0]
    if artificial.size:
        return int(artificial[0])
    column = 1
    while rows.size > 1 and column < T.shape[1]:
        rows = _lexmin_rows(T[rows, column] / d[rows], rows)
        column += 1
    return int(rows[0])


def _pivot(T, d, r):
    """Pivot the tableau ``T`` (in place) on row ``r`` of the entering column ``d``."""
    T[r] /= d[r]
    d[r] = 0.0
    T -= d[:, None] * T[r]


class Lemke(LCPSolver):
    """Lemke's method (covering vector of ones, lexicographic ratio test).

    Works on ``w - W z - e z0 = q`` with a revised tableau ``[x_B, B^-1]``
    (O(m^2) per pivot). The lexicographic rule (equivalent to perturbing
    ``q`` by ``(eps, eps^2, ...)``) prevents cycling on degenerate problems.
    At termination the basic values are recomputed from the final basis by a
    direct solve, so the result is accurate to round-off and ``v`` is
    exactly 0 off the basis.

    Requirements: processes any LCP; it is guaranteed to find a solution
    when ``W`` is a P-matrix (also nonsymmetric), or copositive-plus (e.g.
    symmetric positive semidefinite) and the LCP is feasible. Otherwise it
    may end on a secondary ray, reported as ``success=False``.

    ``iterations`` counts pivots, including the initial one that brings in
    the artificial variable; the warm start ``active`` is ignored.

    Parameters
    ----------
    tol : float, default 1e-10
        Success threshold on the LCP error.
    max_iter : int, optional
        Pivot limit; default ``100 + 20 m``.
    """

    name = "lemke"

    def default_max_iter(self, m):
        return 100 + 20 * m

    def _solve(self, W, q, active):
        m = q.size
        z0 = 2 * m  # variable ids: w_i -> i, z_i -> m + i, z0 -> 2m
        T = np.zeros((m, m + 1))
        T[:, 0] = q
        T[:, 1:] = np.eye(m)
        basis = np.arange(m)
        # The artificial variable replaces the lexicographically smallest row
        # of [q, I]: the last index attaining min(q).
        r = m - 1 - int(np.argmin(q[::-1]))
        _pivot(T, -np.ones(m), r)
        entering, basis[r] = m + r, z0
        max_iter = self.iteration_limit(m)
        for pivots in range(2, max_iter + 1):
            if entering < m:
                d = T[:, 1 + entering].copy()
            else:
                d = -(T[:, 1:] @ W[:, entering - m])
            r = _leaving_row(T, d, basis, z0)
            if r < 0:
                return SolverOutcome(
                    np.zeros(m), np.zeros(m, dtype=bool), pivots - 1, False,
                    f"Lemke terminated on a secondary ray after {pivots - 1} pivots: the LCP has no "
                    "solution, or W is not copositive-plus (e.g. not positive semidefinite and not a "
                    "P-matrix); check that W is positive semidefinite",
                )
            leaving = basis[r]
            _pivot(T, d, r)
            basis[r] = entering
            if leaving == z0:
                active = np.zeros(m, dtype=bool)
                active[basis[basis >= m] - m] = True
                return SolverOutcome(PrincipalSystems(W, q).solve(active), active, pivots, True,
                                     f"Lemke: solved in {pivots} pivots")
            entering = leaving + m if leaving < m else leaving - m
        return SolverOutcome(
            np.zeros(m), np.zeros(m, dtype=bool), max_iter, False,
            f"Lemke did not terminate in {max_iter} pivots; raise max_iter or use solver='bpp'",
        )
