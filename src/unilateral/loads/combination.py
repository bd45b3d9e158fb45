"""A load history ``q(t) = constant + sum_k f_k(t) vector_k`` that can be sampled at many times at once.

:func:`unilateral.solve` evaluates a load at every step. A plain Python callable costs a few
microseconds per call, which dominates the run time of small models stepped by compiled code; a
:class:`LoadHistory` is sampled at all steps in a few vectorised operations instead.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .. import _validate as V


@dataclass(frozen=True, eq=False)
class LoadHistory:
    """The load ``q(t) = constant + sum_k f_k(t) vector_k`` (n,).

    Parameters
    ----------
    constant : (n,) array_like
        The time-independent part (gravity).
    terms : sequence of (vector (n,), f) pairs
        Load patterns and their time functions; ``f(t)`` must accept an array of times and return
        an array of the same shape (every :class:`~unilateral.loads.TimeFunction` and
        :class:`~unilateral.loads.GroundMotion` does). A ground motion enters as ``(-M r, a_g)``.

    Examples
    --------
    >>> import numpy as np
    >>> from unilateral.loads import LoadHistory, Rectangular
    >>> q = LoadHistory([0.0, -400.0], [([1.0, 0.0], Rectangular(200.0, t_end=0.1))])
    >>> q(0.05)
    array([ 200., -400.])
    >>> q.sample(np.array([0.0, 0.2])).shape
    (2, 2)
    """

    constant: np.ndarray
    terms: tuple[tuple[np.ndarray, Callable], ...] = ()

    def __post_init__(self):
        constant = V.as_vector("constant", self.constant, None)
        n = constant.size
        terms = []
        for k, term in enumerate(self.terms):
            if not (isinstance(term, (tuple, list)) and len(term) == 2 and callable(term[1])):
                raise TypeError(f"terms[{k}] must be a pair (vector, f) with f callable; got {V.describe(term)}")
            terms.append((V.as_vector(f"terms[{k}] vector", term[0], n), term[1]))
        object.__setattr__(self, "constant", constant)
        object.__setattr__(self, "terms", tuple(terms))

    @property
    def n(self) -> int:
        """Number of DOFs."""
        return self.constant.size

    def __call__(self, t) -> np.ndarray:
        """``q(t)`` (n,) at one time ``t``."""
        q = self.constant.copy()
        for vector, f in self.terms:
            q += f(t) * vector
        return q

    def sample(self, t) -> np.ndarray:
        """``q`` at every time of ``t`` (N,), as an array (N, n)."""
        t = np.asarray(t, dtype=float)
        q = np.tile(self.constant, (t.size, 1))
        for k, (vector, f) in enumerate(self.terms):
            values = np.asarray(f(t), dtype=float)
            if values.shape != t.shape:
                raise ValueError(f"terms[{k}]: f(t) of {t.size} times returned shape {values.shape}; "
                                 f"a LoadHistory needs time functions that accept arrays")
            q += np.outer(values, vector)
        return q
