"""Envelope (skyline) Cholesky factorisation of sparse symmetric positive definite matrices.

The effective stiffness of a structure ``D = c0 M + c1 C + K`` is sparse, symmetric and, numbered
along the structure (reverse Cuthill-McKee), banded: row ``i`` of its lower triangle holds the
entries from a first column ``first[i]`` to the diagonal. Stored row after row in that envelope,
its Cholesky factor ``L`` (``D = L L^T``) has the same envelope (no fill outside it), so the
factorisation costs ``O(n b^2)`` and a solve ``O(n b)`` for a half-bandwidth ``b``, and both run in
compiled code without allocation. Row ``i`` of ``L`` depends only on the rows above it: after a
change of the rows from ``r0`` on, only those rows are factorised again (:func:`cholesky_rows`),
which the full-space LCP uses when a contact opens or closes (:mod:`unilateral.march.full_space`).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numba import njit

from .compiled import REASSOCIATE

#: A pivot below this fraction of its diagonal entry makes the matrix not positive definite.
PIVOT_RATIO = 1e-13


class Envelope:
    """A symmetric sparse pattern numbered by reverse Cuthill-McKee, in envelope storage.

    Parameters
    ----------
    pattern : (n, n) sparse matrix whose nonzeros (and those of its transpose) may be nonzero in
        the matrices to factorise

    Attributes
    ----------
    perm : (n,) int, ``perm[i]`` is the original index of row ``i`` of the envelope numbering
    first : (n,) int, first column of row ``i`` (lower triangle, envelope numbering)
    ptr : (n + 1,) int, row ``i`` is stored at ``ptr[i] .. ptr[i + 1] - 1`` (columns ``first[i] .. i``)
    """

    def __init__(self, pattern):
        from scipy.sparse.csgraph import reverse_cuthill_mckee

        S = sp.csr_matrix(pattern, dtype=float)
        S = (abs(S) + abs(S.T)).tocsr()
        S.setdiag(1.0)
        self.n = S.shape[0]
        self.perm = np.asarray(reverse_cuthill_mckee(S, symmetric_mode=True), dtype=np.int64)
        self.inverse = np.empty_like(self.perm)
        self.inverse[self.perm] = np.arange(self.n)
        P = S[self.perm][:, self.perm].tocsr()
        # every row holds its diagonal: the first column of row i is the least of its columns
        first = np.minimum.reduceat(P.indices, P.indptr[:-1]) if self.n else np.zeros(0)
        self.first = first.astype(np.int64)
        self.ptr = np.zeros(self.n + 1, dtype=np.int64)
        np.cumsum(np.arange(self.n) - self.first + 1, out=self.ptr[1:])

    @property
    def size(self) -> int:
        """Number of stored entries."""
        return int(self.ptr[-1])

    def values(self, A) -> np.ndarray:
        """The lower triangle of ``A`` (n, n) in envelope storage (entries outside it are an error)."""
        P = sp.coo_matrix(sp.csr_matrix(A)[self.perm][:, self.perm])
        keep = P.row >= P.col
        r, c, x = P.row[keep], P.col[keep], P.data[keep]
        if np.any(c < self.first[r]):
            raise ValueError("the matrix has entries outside the envelope of its pattern")
        # (the sums of np.add.at, in the same order, without its per-entry dispatch)
        return np.bincount(self.ptr[r] + c - self.first[r], weights=x, minlength=self.size)

    def position(self, i, j) -> np.ndarray:
        """Storage positions of the entries ``(i, j)`` (envelope numbering, ``i >= j``)."""
        return self.ptr[i] + j - self.first[i]


@njit(cache=True, fastmath=REASSOCIATE)
def cholesky_rows(ptr, first, A, L, r0):
    """Factorise rows ``r0 .. n-1`` of ``A = L L^T`` in envelope storage (rows above ``r0`` of ``L``
    kept); return -1, or the first row whose pivot shows ``A`` not positive definite."""
    n = first.shape[0]
    for i in range(r0, n):
        fi, pi = first[i], ptr[i]
        for j in range(fi, i):
            fj, pj = first[j], ptr[j]
            k0 = max(fi, fj)
            s = A[pi + j - fi]
            for k in range(k0, j):
                s -= L[pi + k - fi] * L[pj + k - fj]
            L[pi + j - fi] = s / L[pj + j - fj]
        d = A[pi + i - fi]
        s = d
        for k in range(fi, i):
            s -= L[pi + k - fi] * L[pi + k - fi]
        if not s > PIVOT_RATIO * abs(d):
            return i
        L[pi + i - fi] = np.sqrt(s)
    return -1


@njit(cache=True, fastmath=REASSOCIATE)
def solve(ptr, first, L, b, x):
    """Solve ``L L^T x = b`` (envelope numbering) into ``x``."""
    n = first.shape[0]
    for i in range(n):                      # L y = b
        fi, pi = first[i], ptr[i]
        s = b[i]
        for k in range(fi, i):
            s -= L[pi + k - fi] * x[k]
        x[i] = s / L[pi + i - fi]
    for i in range(n - 1, -1, -1):          # L^T x = y
        fi, pi = first[i], ptr[i]
        xi = x[i] / L[pi + i - fi]
        x[i] = xi
        for k in range(fi, i):
            x[k] -= L[pi + k - fi] * xi
