"""A load history ``q(t) = constant + sum_k f_k(t) vector_k`` that can be sampled at many times at once.

:func:`unilateral.solve` evaluates a load at every step. A plain Python callable costs a few
microseconds per call, which dominates the run time of small models stepped by compiled code; a
:class:`LoadHistory` is sampled at all steps in a few vectorised operations instead.

:meth:`LoadHistory.grid_samples` gives the samples a time-stepping run should use: hat-function
averages that keep second order across pulse edges, one-sided data at t = 0 for the dynamic run,
and the load ``q(0-)`` for the static preload (see :mod:`unilateral.loads.piecewise`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .. import _validate as V
from .piecewise import SAMPLINGS


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
    sampling : {"hat", "box", "point"}, optional
        How a time-stepping run samples the load on its grid (:meth:`grid_samples`): ``"hat"``
        (default) hat-function averages, ``"point"`` the values at the step times, as OpenSees's
        Path series are read (a model file's ``[analysis] load_sampling``). Every quantity derived
        after the run (accelerations, base shear, input work) takes the same samples.

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
    sampling: str = "hat"

    def __post_init__(self):
        if self.sampling not in SAMPLINGS:
            raise ValueError(f"sampling={self.sampling!r} is not valid; valid: {', '.join(map(repr, SAMPLINGS))}")
        constant = V.as_vector("constant", self.constant, None)
        n = constant.size
        terms = []
        for k, term in enumerate(self.terms):
            if not (isinstance(term, (tuple, list)) and len(term) == 2 and callable(term[1])):
                raise TypeError(f"terms[{k}] must be a pair (vector, f) with f callable; got {V.describe(term)}")
            terms.append((V.as_vector(f"terms[{k}] vector", term[0], n), term[1]))
        object.__setattr__(self, "constant", constant)
        object.__setattr__(self, "terms", tuple(terms))
        object.__setattr__(self, "_last_grid", None)     # the last grid_factors: ((dt, N, sampling), result)

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

    def piecewise_terms(self, what: str = "load") -> list:
        """``[(vector, Piecewise)]`` of the terms; raise ValueError for a term without a piecewise form."""
        out = []
        for k, (vector, f) in enumerate(self.terms):
            piecewise = _piecewise(f)
            if piecewise is None:
                raise ValueError(
                    f"{what}: terms[{k}] has a time function {V.describe(f)} without a piecewise form; "
                    "use the time functions of unilateral.loads (Rectangular, Triangular, HalfSine, Ramp, "
                    "Constant, Tabulated) or a GroundMotion"
                )
            out.append((vector, piecewise))
        return out

    def grid_samples(self, dt: float, N: int, sampling: str | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Load samples for a dynamic run on ``t_k = k dt`` (k = 0..N) and the static preload.

        Parameters
        ----------
        dt : float
            Time step, s.
        N : int
            Number of steps.
        sampling : {"hat", "box", "point"}, optional
            Default: the history's own :attr:`sampling`. ``"hat"``: hat-function averages ``(1/dt) int q phi_k``, which keep BDF2 and
            the trapezoidal rule second order across jumps anywhere (measured, see
            ``tests/test_convergence.py`` and ``docs/theory.md``); ``"box"``: averages over
            ``[t_k - dt/2, t_k + dt/2]``; ``"point"``: point values, the mean of both sides at a
            jump on the grid (second order only if every jump is on the grid).

        Returns
        -------
        Q : (N+1, n)
            Row k is the load the dynamic run uses at ``t_k``; row 0 is one-sided (``t = 0+``).
        q0_static : (n,)
            ``q(0-)``, the load of the static equilibrium the run starts from.
        """
        factors, before = self.grid_factors(dt, N, sampling)
        vectors = self.vectors()
        return self.constant + factors @ vectors, self.constant + before @ vectors

    def vectors(self) -> np.ndarray:
        """The load patterns of the terms, (number of terms, n)."""
        return np.array([vector for vector, _ in self.terms], dtype=float).reshape(len(self.terms), self.n)

    def grid_factors(self, dt: float, N: int, sampling: str | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The time functions' samples of :meth:`grid_samples`, one column per term.

        ``Q = constant + factors @ vectors()``: for large models the load of a step is formed
        from its row without storing ``Q``.

        Returns
        -------
        factors : (N+1, number of terms) ; before : (number of terms,) values at ``t = 0-``

        Terms whose time function has no piecewise form (a plain callable) are point-sampled, and
        their value at t = 0 is taken as the value before it. The last result is kept (read-only
        arrays): the post-processing of a run asks for the samples the solve used.
        """
        dt = V.positive_float("dt", dt)
        if isinstance(N, bool) or not isinstance(N, (int, np.integer)) or N < 0:
            raise ValueError(f"N must be an integer >= 0, got {N!r}")
        N = int(N)
        sampling = self.sampling if sampling is None else sampling
        key = (dt, N, sampling)
        if self._last_grid is not None and self._last_grid[0] == key:
            return self._last_grid[1]
        t = dt * np.arange(N + 1)
        factors = np.empty((N + 1, len(self.terms)))
        before = np.empty(len(self.terms))
        for k, (_, f) in enumerate(self.terms):
            piecewise = _piecewise(f)
            if piecewise is None:
                values = np.asarray(f(t), dtype=float)
                if values.shape != t.shape:
                    raise ValueError(f"terms[{k}]: f(t) of {t.size} times returned shape {values.shape}")
                factors[:, k], before[k] = values, values[0]
            else:
                factors[:, k] = piecewise.grid_samples(dt, N, sampling)
                before[k] = float(piecewise.evaluate(0.0, "left"))
        factors.flags.writeable = before.flags.writeable = False
        object.__setattr__(self, "_last_grid", (key, (factors, before)))
        return factors, before


def _piecewise(f):
    """The exact piecewise form of a time function, or None (a plain callable)."""
    form = getattr(f, "piecewise", None)
    return form() if callable(form) else None
