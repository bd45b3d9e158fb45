"""Factorised linear solves for dense or sparse, real or complex matrices.

One wrapper so that kernels and steppers never care whether the model is dense or sparse.
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla


class SingularMatrixError(ValueError):
    """The matrix to factorise is singular (or numerically so)."""


class Factorization:
    """LU factorisation of a square matrix, reused across right-hand sides.

    Parameters
    ----------
    A : (n, n) ndarray or sparse matrix, real or complex
    what : str
        Description used in the error message if ``A`` is singular.
    """

    def __init__(self, A, what: str = "matrix"):
        self.shape = A.shape
        self.sparse = sp.issparse(A)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error", sla.LinAlgWarning)
                warnings.simplefilter("error", spla.MatrixRankWarning)
                if self.sparse:
                    self._lu = spla.splu(sp.csc_matrix(A))
                    diag = np.abs(self._lu.U.diagonal())
                else:
                    self._lu = sla.lu_factor(np.asarray(A))
                    self._getrs, = sla.get_lapack_funcs(("getrs",), (self._lu[0],))
                    diag = np.abs(np.diag(self._lu[0]))
        except (RuntimeError, sla.LinAlgError, sla.LinAlgWarning, spla.MatrixRankWarning) as exc:
            raise SingularMatrixError(f"{what} is singular ({exc})") from None
        if diag.size and diag.min() <= 1e-13 * diag.max():
            raise SingularMatrixError(
                f"{what} is singular or nearly so (pivot ratio {diag.min() / diag.max():.2e})"
            )

    @property
    def dense_factors(self):
        """``(lu, piv)`` of a dense factorisation (LAPACK convention), or None if sparse."""
        return None if self.sparse else self._lu

    def solve(self, b: np.ndarray) -> np.ndarray:
        """Solve ``A x = b`` for ``b`` of shape (n,) or (n, k)."""
        if self.sparse:
            if sp.issparse(b):
                b = b.toarray()
            return self._lu.solve(np.asarray(b, dtype=np.result_type(b, self._lu.U.dtype)))
        lu, piv = self._lu
        if np.iscomplexobj(b) and not np.iscomplexobj(lu):
            return self.solve(b.real) + 1j * self.solve(b.imag)
        # LAPACK getrs directly: scipy's lu_solve wrapper costs more than the solve for small n
        x, info = self._getrs(lu, piv, b)
        return x


def dense(A) -> np.ndarray:
    """Return ``A`` as a dense ndarray (for small matrices such as F^T X)."""
    return A.toarray() if sp.issparse(A) else np.asarray(A)


def transpose_times(F, X) -> np.ndarray:
    """``F^T X`` as a dense array, for F (n, m) dense or sparse and X (n,) or (n, k)."""
    out = F.T @ X
    return out.toarray() if sp.issparse(out) else np.asarray(out)


#: Up to this many DOFs a singular stiffness is explained by its zero-energy mode.
MECHANISM_CHECK_MAX_N = 2000


def mechanism_dofs(K, names=None, limit=10) -> list | None:
    """The DOFs a zero-energy mode of the symmetric ``K`` moves most, or None if there is none.

    ``K`` is scaled by its diagonal and its lowest eigenvector taken (dense, up to
    :data:`MECHANISM_CHECK_MAX_N` DOFs; None above). ``names`` labels the DOFs (default: indices).
    """
    n = K.shape[0]
    if n == 0 or n > MECHANISM_CHECK_MAX_N:
        return None
    A = dense(K).astype(float)
    d = np.diag(A).copy()
    scale = 1.0 / np.sqrt(np.where(d > 0, d, 1.0))
    A = 0.5 * (A + A.T) * scale[:, None] * scale[None, :]
    w, V = np.linalg.eigh(A)
    if w[0] > 1e-11 * max(w[-1], 1.0):
        return None
    mode = V[:, 0] * scale
    order = np.argsort(-np.abs(mode))
    moved = [i for i in order if abs(mode[i]) > 1e-3 * abs(mode[order[0]])][:limit]
    return [names[i] if names is not None else str(i) for i in moved]
