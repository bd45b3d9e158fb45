"""Loads as exact generators for the event-driven march: ``q(t) = Gq z(t)``, ``z' = S z``.

On every piece of the load's time functions the load is the output of a small linear system (the
"exosystem"): a polynomial of degree p is carried by its p+1 derivatives (a nilpotent Jordan
block), a sinusoid ``s = a cos(omega t) + b sin(omega t)`` by ``(s, s'/omega)`` (a 2x2 rotation
block), a constant by one state with ``z' = 0``. ``S`` is the same on every piece; at a
breakpoint the state is re-initialised from the right limits of the next piece. The augmented
system ``(structure, exosystem)`` is therefore integrated exactly by matrix exponentials.
"""

from __future__ import annotations

import numpy as np

from unilateral.loads.combination import LoadHistory
from unilateral.loads.piecewise import Piecewise, linear_table

#: Relative size (to the largest singular value) below which an array load's SVD is truncated.
SVD_RTOL = 1e-15

VALID_LOADS = ("a LoadHistory whose time functions are unilateral.loads time functions "
               "(Rectangular, Triangular, HalfSine, Ramp, Constant, Tabulated) or GroundMotion "
               "records, an array (N+1, n) of samples at the output times (taken as piecewise "
               "linear between them), or None")


class LoadGenerator:
    """``q(t) = Gq z(t)`` (n,) with ``z' = S z`` on each piece, re-initialised at breakpoints.

    Parameters
    ----------
    constant : (n,) time-independent load
    terms : list of (vector (n,), Piecewise)
    """

    def __init__(self, constant, terms):
        self.constant = np.asarray(constant, dtype=float)
        self.terms = list(terms)
        n = self.constant.size
        blocks = []                     # (offset, degree, has_trig) per term
        size = 1                        # state 0 is the constant 1
        for _, f in self.terms:
            blocks.append((size, f.degree, f.has_trig))
            size += f.degree + 1 + (2 if f.has_trig else 0)
        self.size = size
        self.blocks = blocks
        S = np.zeros((size, size))
        Gq = np.zeros((n, size))
        Gq[:, 0] = self.constant
        for (vector, f), (off, d, trig) in zip(self.terms, blocks):
            for i in range(d):
                S[off + i, off + i + 1] = 1.0
            Gq[:, off] += vector
            if trig:
                k = off + d + 1
                S[k, k + 1], S[k + 1, k] = f.omega, -f.omega
                Gq[:, k] += vector
        self.S, self.Gq = S, Gq
        edges = [f.edges for _, f in self.terms]
        self.breakpoints = np.unique(np.concatenate(edges)) if edges else np.zeros(0)

    def state(self, t: float, side: str = "right") -> np.ndarray:
        """``z(t+)`` (or ``z(t-)``)."""
        z = np.zeros(self.size)
        z[0] = 1.0
        for (_, f), (off, d, trig) in zip(self.terms, self.blocks):
            z[off: off + d + 1] = f.poly_state(t, side)
            if trig:
                z[off + d + 1: off + d + 3] = f.trig_state(t, side)
        return z

    def value(self, t: float, side: str = "right") -> np.ndarray:
        return self.Gq @ self.state(t, side)


def load_generator(model, load, t_grid) -> LoadGenerator:
    """The generator of ``load`` plus the model's (constant) imposed-strain load.

    Raises ValueError for a load that cannot be integrated exactly (a plain callable, a
    LoadHistory with a plain callable term, a callable imposed load).
    """
    n = model.n
    if not model.q_imposed_is_constant:
        raise ValueError("method='event' needs a constant q_imposed (imposed strains constant in time); "
                         "this model's q_imposed is a function of time")
    imposed = np.asarray(model.q_imposed(0.0), dtype=float)
    if load is None:
        return LoadGenerator(imposed, [])
    if isinstance(load, LoadHistory):
        if load.n != n:
            raise ValueError(f"load: the LoadHistory has n = {load.n} DOFs, the model {n}")
        if load.sampling != "hat":
            raise ValueError(f"load: sampling={load.sampling!r} (a model file's [analysis] load_sampling) cannot be "
                             "honoured by method='event', which integrates the load exactly between events; "
                             "use method='direct' (or 'cq', 'modal'), or the default sampling 'hat'")
        return LoadGenerator(load.constant + imposed, load.piecewise_terms("load"))
    if isinstance(load, np.ndarray) or (isinstance(load, (list, tuple)) and not callable(load)):
        Q = np.asarray(load, dtype=float)
        t = np.asarray(t_grid, dtype=float)
        if Q.ndim != 2 or Q.shape[1] != n or Q.shape[0] < t.size:
            raise ValueError(f"load: an array load must have shape ({t.size}, {n}) (one row per output "
                             f"time), got shape {Q.shape}")
        if not np.all(np.isfinite(Q)):
            raise ValueError("load: the array holds non-finite values")
        Q = Q[: t.size]
        return LoadGenerator(Q[0] + imposed, _array_terms(t, Q - Q[0]))
    if callable(load):
        raise ValueError(
            f"load: a plain callable ({type(load).__name__}) cannot be integrated exactly by the "
            f"event-driven method, which needs the load's pieces; valid: {VALID_LOADS}"
        )
    raise ValueError(f"load: {type(load).__name__} is not a valid load; valid: {VALID_LOADS}")


def _array_terms(t, D):
    """Piecewise-linear terms of the samples ``D`` (N+1, n), compressed by an SVD to their rank."""
    if not np.any(D):
        return []
    U, s, Vt = np.linalg.svd(D, full_matrices=False)
    r = int(np.count_nonzero(s > SVD_RTOL * s[0] * max(D.shape)))
    terms = []
    for j in range(r):
        values = U[:, j] * s[j]
        f = linear_table(t, values, values[0], values[-1]) if t.size > 1 else Piecewise(
            np.zeros(0), [[values[0]]])
        terms.append((Vt[j], f))
    return terms
