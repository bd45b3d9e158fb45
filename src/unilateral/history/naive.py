"""Evaluation of the convolution history ``sum_{j=1..n} W_j dv_{n-j}`` of the CLCP."""

from __future__ import annotations

import numpy as np


class NaiveHistory:
    """Direct summation: O(n m^2) work at step n, O(N^2 m^2) in all.

    Parameters
    ----------
    W : (N+1, m, m) convolution weights
    """

    name = "naive"

    def __init__(self, W: np.ndarray):
        self.W = W
        self.dv = np.zeros((W.shape[0], W.shape[1]))
        self._first = None          # first step with a nonzero increment

    def value(self, n: int) -> np.ndarray:
        """``sum_{j=1..n} W_j dv_{n-j}``, shape (m,)."""
        if self._first is None or self._first >= n:
            return np.zeros(self.W.shape[1])
        lo = self._first
        # j runs over 1..n-lo, pairing W_j with dv_{n-j}, i.e. dv indices n-1 down to lo.
        return np.einsum("jab,jb->a", self.W[1:n - lo + 1], self.dv[n - 1:lo - 1 if lo else None:-1])

    def push(self, n: int, dv_n: np.ndarray) -> None:
        self.dv[n] = dv_n
        if self._first is None and np.any(dv_n):
            self._first = n
