"""A history on the unknowns its weights couple: zero rows and columns of ``W_1 .. W_N`` left out.

Footings that slide carry slip unknowns whose weights are constant (``W_0`` only: the coupling of a
shear to its slips), so half of the unknowns of such a model take no part in the convolution sum:
summing it over the others alone gives the same values with a quarter of the products and of the
memory of the weight spectra.
"""

from __future__ import annotations

import numpy as np

#: Steps of ``W`` scanned at a time for nonzero entries (bounds the temporary boolean array).
_SCAN = 256


def coupled_unknowns(W: np.ndarray) -> np.ndarray:
    """Indices of the unknowns with a nonzero entry in a row or column of ``W_1 .. W_N`` (N+1, m, m)."""
    m = W.shape[1]
    nonzero = np.zeros((m, m), dtype=bool)
    for start in range(1, W.shape[0], _SCAN):
        nonzero |= np.any(W[start:start + _SCAN] != 0.0, axis=0)
    return np.flatnonzero(nonzero.any(axis=0) | nonzero.any(axis=1))


class RestrictedHistory:
    """``history_class`` on the unknowns ``support`` only; same interface and the same values.

    The history of the other unknowns is zero and their increments enter no history (their rows and
    columns of ``W_1 .. W_N`` are zero), so the sum over ``support`` is the whole sum.

    Parameters
    ----------
    history_class : a history built from stored weights (:data:`unilateral.history.HISTORIES`)
    W : (N+1, m, m) weights
    support : (s,) int, the unknowns of :func:`coupled_unknowns`
    """

    def __init__(self, history_class, W: np.ndarray, support: np.ndarray):
        self.m, self.support = W.shape[1], support
        self.inner = history_class(W[:, support[:, None], support[None, :]])
        self.name = self.inner.name

    def value(self, n: int) -> np.ndarray:
        out = np.zeros(self.m)
        out[self.support] = self.inner.value(n)
        return out

    def push(self, n: int, dv_n: np.ndarray) -> None:
        self.inner.push(n, np.asarray(dv_n)[self.support])


def history_on_coupled_unknowns(history_class, W: np.ndarray, support=None):
    """``history_class(W)``, or a :class:`RestrictedHistory` when ``W_1 .. W_N`` leave unknowns out
    (``support``: :func:`coupled_unknowns` of ``W`` if already known; a scan of all weights)."""
    support = coupled_unknowns(W) if support is None else support
    if support.size == W.shape[1]:
        return history_class(W)
    return RestrictedHistory(history_class, W, support)
