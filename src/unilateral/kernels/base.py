"""The kernel interface: anything that maps Laplace arguments ``s`` to ``(m, m)`` matrices.

* :class:`Kernel`: the base class; ``kernel(s)`` for ``s`` of shape (L,) returns ``(L, m, m)``.
* :class:`CallableKernel`: a user's function ``Lambda(s)``; the Laplace-domain route needs no
  matrices at all (e.g. the impedance of an unbounded soil).
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V


class Kernel:
    """Base class: ``kernel(s)`` for ``s`` of shape (L,) returns ``(L, m, m)``."""

    m: int

    def __call__(self, s) -> np.ndarray:
        s = np.asarray(s)
        scalar = s.ndim == 0
        out = self.evaluate(np.atleast_1d(s))
        return out[0] if scalar else out

    def evaluate(self, s: np.ndarray) -> np.ndarray:  # pragma: no cover - interface
        raise TypeError(f"{type(self).__name__} does not define evaluate(s)")


class CallableKernel(Kernel):
    """A user's ``Lambda(s)`` as a kernel.

    Parameters
    ----------
    func : callable
        ``func(s) -> (m, m)`` for a complex scalar ``s`` (a scalar if m = 1); if it also accepts
        an array of shape (L,) and returns (L, m, m) it is called once per batch (much faster).
    m : int
        Number of unilateral unknowns.
    vectorized : bool
        Whether ``func`` accepts arrays of s.
    """

    def __init__(self, func, m: int, *, vectorized: bool = False):
        if not callable(func):
            raise TypeError(f"Lambda must be callable Lambda(s) -> (m, m), got {V.describe(func)}")
        self.func = func
        self.m = int(m)
        self.vectorized = vectorized

    def evaluate(self, s: np.ndarray) -> np.ndarray:
        if self.vectorized:
            out = np.asarray(self.func(s))
            if self.m == 1 and out.shape == s.shape:
                out = out.reshape(-1, 1, 1)
        else:
            out = np.array([np.atleast_2d(self.func(sk)) for sk in s])
        if out.shape != (s.shape[0], self.m, self.m):
            raise ValueError(
                f"Lambda(s) must return shape ({self.m}, {self.m}) per s, got {out.shape[1:]} "
                f"for {s.shape[0]} values of s"
            )
        V.check_finite("Lambda(s)", out)
        return out
