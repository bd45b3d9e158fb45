"""The kernel of a matrix model: ``Lambda(s) = H(s) - F(s)^T D(s)^-1 F(s)`` (eq. 23, sign corrected).

:class:`MatrixKernel` evaluates it from a :class:`~unilateral.model.Model`, reusing one
factorisation of ``D(s) = K + s C + s^2 M`` for all right-hand sides, and also gives the transfer
``F(s)^T D(s)^-1`` of loads to constraint reactions (eq. 22).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..linalg import Factorization, transpose_times
from .base import Kernel

#: Models with at most this many DOFs are evaluated by batched dense solves (also when stored
#: sparse); larger ones by one sparse LU per Laplace argument.
DENSE_BATCH_MAX_N = 64
_BATCH = 2048


class MatrixKernel(Kernel):
    """``Lambda(s)`` and the load transfer of a matrix :class:`~unilateral.model.Model`.

    Parameters
    ----------
    model : Model
    """

    def __init__(self, model):
        self.model = model
        self.m = model.m
        self.n = model.n
        self._batched = model.n <= DENSE_BATCH_MAX_N          # dense or sparse storage alike
        if self._batched:
            dense = lambda A: None if A is None else (A.toarray() if sp.issparse(A) else np.asarray(A))
            self._K, self._M = dense(model.K), dense(model.M)
            self._C = dense(model.C)
            self._F, self._F_v = dense(model.F), dense(model.F_v)

    def evaluate(self, s: np.ndarray) -> np.ndarray:
        """``Lambda(s)`` for ``s`` of shape (L,); returns (L, m, m), real if every s is real."""
        dtype = float if np.isrealobj(s) else complex
        out = np.empty((s.shape[0], self.m, self.m), dtype=dtype)
        if self._batched:
            for lo in range(0, s.shape[0], _BATCH):
                sl = s[lo:lo + _BATCH]
                D = self._D_batch(sl)
                Fs = self._F_batch(sl)
                X = np.linalg.solve(D, Fs)
                out[lo:lo + _BATCH] = self._H_batch(sl) - np.swapaxes(Fs, 1, 2) @ X
            return out
        model = self.model
        for k, sk in enumerate(s):
            sk = sk if dtype is complex else float(sk)
            Fs = model.F_of(sk)
            lu = Factorization(model.D(sk), what=f"D(s) = K + s C + s^2 M at s = {sk}")
            X = lu.solve(Fs.toarray() if sp.issparse(Fs) else Fs)
            out[k] = model.H_of(sk) - transpose_times(Fs, X)
        return out

    def transfer(self, s, d) -> np.ndarray:
        """``F(s)^T D(s)^-1 d(s)``: constraint reactions of the bilateral structure (eq. 22).

        Parameters
        ----------
        s : (L,) complex
        d : (L, n) complex, transformed generalised loads ``d(s)`` (eq. 21)

        Returns
        -------
        (L, m) complex
        """
        s = np.atleast_1d(np.asarray(s))
        d = np.asarray(d)
        if d.shape != (s.shape[0], self.n):
            raise ValueError(f"d must have shape ({s.shape[0]}, {self.n}), got {d.shape}")
        out = np.empty((s.shape[0], self.m), dtype=complex)
        model = self.model
        for k, sk in enumerate(s):
            lu = Factorization(model.D(sk), what=f"D(s) at s = {sk}")
            out[k] = transpose_times(model.F_of(sk), lu.solve(d[k]))
        return out

    # ----------------------------------------------------------------- batched dense pieces
    def _D_batch(self, s):
        D = self._K[None] + (s * s)[:, None, None] * self._M[None]
        if self._C is not None:
            D = D + s[:, None, None] * self._C[None]
        return D

    def _F_batch(self, s):
        F = np.broadcast_to(self._F, (s.shape[0],) + self._F.shape)
        if self._F_v is not None:
            F = F + s[:, None, None] * self._F_v[None]
        return F

    def _H_batch(self, s):
        H = self.model.H[None]
        if self.model.H_v is not None:
            H = H + s[:, None, None] * self.model.H_v[None]
        return H
