"""The step solver of a law with faces: block principal pivoting with the face rules, Lemke's
method where it fails.

The two faces of a two-sided yield or slip pair have opposite columns, and the facets of a
polygon of more than four facets (a friction cone in plan, a 3-D hinge's interaction polygon) have
linearly dependent columns (more than two facets on two tangential strains): the step LCP is
not a P-matrix, and plain block principal pivoting may meet a singular principal submatrix or
cycle. :class:`FaceSetPivoting` treats the faces of one pair and the facets of one polygon as one
face set (never both faces of a pair, at most two facets of a polygon active) and falls back on
Lemke's method (which keeps a nonsingular basis, so never three dependent facets) where that
fails. It runs the compiled kernel :func:`unilateral.march.pivoting.solve_step` that the compiled
marches run, so that the Python and the compiled engines solve each step alike.
"""

from __future__ import annotations

import numpy as np

from .base import LCPResult, check_lcp


class FaceSetPivoting:
    """Step LCPs of a law with faces, solved as the compiled marches solve them.

    Parameters
    ----------
    partner : (m,) int
        The opposite face of each unknown of a two-sided pair, -1 for none.
    group : (m,) int
        The polygon (of more than four facets) each unknown is a facet of, -1 for none.
    symmetric : bool
        The LCP matrix is symmetric (principal systems by Cholesky, else by LU).
    tol : float, default 1e-10
        Largest acceptable LCP error (:func:`~unilateral.lcp.base.lcp_error`).
    max_iter : int, optional
        Linear solves of block principal pivoting at most, and pivots of Lemke's method; default
        ``10 m + 10`` (as the compiled marches).

    Attributes
    ----------
    fallbacks : int, the solves that needed Lemke's method so far
    """

    #: The compiled block principal pivoting it runs (:class:`~unilateral.constraints.law.FreeCondensation`
    #: recognises it by this name).
    name = "bpp"

    def __init__(self, partner, group, *, symmetric, tol=1e-10, max_iter=None):
        partner = np.asarray(partner)
        group = np.asarray(group)
        for arg, value in (("partner", partner), ("group", group)):
            if value.ndim != 1 or not np.issubdtype(value.dtype, np.integer):
                raise ValueError(f"{arg} must be a 1-D integer array (-1: none), got dtype {value.dtype} and "
                                 f"shape {value.shape}")
        if group.shape != partner.shape:
            raise ValueError(f"group must have the shape of partner {partner.shape}, got shape {group.shape}")
        m = partner.size
        bad = np.flatnonzero((partner < -1) | (partner >= m))
        if bad.size:
            raise ValueError(f"partner[{bad[0]}] = {partner[bad[0]]} is not an unknown: valid are -1 (none) and "
                             f"0 .. {m - 1}")
        if not tol > 0:
            raise ValueError(f"tol must be positive, got tol={tol!r}")
        if max_iter is not None and (int(max_iter) != max_iter or max_iter < 1):
            raise ValueError(f"max_iter must be a positive integer or None, got max_iter={max_iter!r}")
        self.partner = np.ascontiguousarray(partner, dtype=np.int64)
        self.group = np.ascontiguousarray(group, dtype=np.int64)
        self.symmetric = bool(symmetric)
        self.tol = float(tol)
        self.max_iter = None if max_iter is None else int(max_iter)
        self.fallbacks = 0

    @classmethod
    def of(cls, solver, partner, group, *, symmetric):
        """The step solver with the ``tol`` and ``max_iter`` of ``solver`` (block principal pivoting)."""
        return cls(partner, group, symmetric=symmetric, tol=solver.tol, max_iter=solver.max_iter)

    def __repr__(self):
        return (f"FaceSetPivoting(m={self.partner.size}, symmetric={self.symmetric}, tol={self.tol!r}, "
                f"max_iter={self.max_iter!r})")

    def solve(self, W, q, active=None) -> LCPResult:
        """Solve LCP(W, q) warm-started from ``active``; never raises on failure (see ``success``).

        Raises
        ------
        ValueError
            Malformed ``W``, ``q`` or ``active`` (:func:`~unilateral.lcp.base.check_lcp`), or an
            ``m`` other than that of ``partner``.
        """
        from . import pivoting                          # lazily: numba

        W, q, active = check_lcp(W, q, active)
        m = q.size
        if m != self.partner.size:
            raise ValueError(f"q has m = {m} unknowns but the faces (partner, group) are of m = {self.partner.size}")
        act = np.zeros(m, dtype=bool) if active is None else active.copy()
        v, w = np.empty(m), np.empty(m)
        work = (np.empty(m, dtype=np.int64), np.empty((m, m)), np.empty(m), np.empty(m))
        max_iter = self.max_iter or 10 * m + 10
        it, error, fallback = pivoting.solve_step(np.ascontiguousarray(W), q, act, v, w, max_iter, self.tol, work,
                                                  self.symmetric, (self.partner, self.group))
        self.fallbacks += int(fallback)
        success = it >= 0 and error <= self.tol
        how = "block principal pivoting failed, Lemke's method" if fallback else "block principal pivoting"
        message = (f"{how} (pairs one face at a time, at most two facets of a polygon) solved it in {abs(it)} "
                   "linear solves and pivots" if success else
                   f"{how} (pairs one face at a time, at most two facets of a polygon) failed after {abs(it)} "
                   f"linear solves and pivots, LCP error {error:.3g} (tol {self.tol:g}): the step LCP is not a "
                   "P-matrix here")
        return LCPResult(v=v, w=w, active=act, iterations=abs(it), error=float(error), success=success,
                         message=message, fallback=bool(fallback))
