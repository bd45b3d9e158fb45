"""Periods and mode shapes of the bilateral structure: ``K phi = w^2 M phi``.

The stiffness is that of the model with every unilateral element held bilateral (closed, bonded):
``K`` of :class:`unilateral.Model`. DOFs without mass are condensed statically,
``K* = K_mm - K_m0 K_00^-1 K_0m``, the generalised eigenproblem is solved on the DOFs with mass and
the shapes are expanded back, ``phi_0 = -K_00^-1 K_0m phi_m``. Shapes are normalised to a largest
component of 1 (sign: that component positive); the effective modal masses along ``x`` and ``y``
(for an influence vector ``r``: ``(phi^T M r)^2 / (phi^T M phi)``) say how much each mode
takes part in a ground motion.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

#: Dense eigenproblems up to this many DOFs with mass; above it the lowest modes by ARPACK.
DENSE_MAX = 1500


def modes(model, *, count=10, influence=None) -> dict:
    """The lowest ``count`` modes of the bilateral structure.

    Parameters
    ----------
    model : Model
    count : int
        Number of modes (at most the number of DOFs with mass).
    influence : dict name -> (n,) influence vectors, optional
        E.g. ``{"x": st.influence("ux"), "y": st.influence("uy")}``: effective modal masses are
        given for each.

    Returns
    -------
    dict with ``omega`` (rad per time unit), ``frequency`` (cycles per time unit), ``period``
    (count,), ``shape`` (count, n), ``effective_mass`` (name -> (count,)), ``total_mass``
    (name -> float, ``r^T M r``). Empty arrays if nothing has mass.
    """
    K = _dense(model.K)
    M = _dense(model.M)
    n = K.shape[0]
    mass = np.flatnonzero(np.diag(M) > 0)
    zero = np.setdiff1d(np.arange(n), mass)
    if mass.size == 0:
        return {"omega": np.zeros(0), "frequency": np.zeros(0), "period": np.zeros(0),
                "shape": np.zeros((0, n)), "effective_mass": {}, "total_mass": {}}
    count = int(min(count, mass.size))
    Kmm = K[np.ix_(mass, mass)]
    if zero.size:
        K00, K0m = K[np.ix_(zero, zero)], K[np.ix_(zero, mass)]
        expand = -np.linalg.solve(K00, K0m)                          # phi_0 = expand @ phi_m
        Kmm = Kmm + K0m.T @ expand
    Mmm = M[np.ix_(mass, mass)]
    Kmm = 0.5 * (Kmm + Kmm.T)
    if mass.size <= DENSE_MAX:
        w2, phi_m = sla.eigh(Kmm, Mmm, subset_by_index=(0, count - 1))
    else:                                                            # pragma: no cover - large models
        from scipy.sparse.linalg import eigsh

        w2, phi_m = eigsh(sp.csr_matrix(Kmm), k=count, M=sp.csr_matrix(Mmm), sigma=0.0, which="LM")
        order = np.argsort(w2)
        w2, phi_m = w2[order], phi_m[:, order]
    shape = np.zeros((count, n))
    shape[:, mass] = phi_m.T
    if zero.size:
        shape[:, zero] = (expand @ phi_m).T
    for k in range(count):
        big = np.argmax(np.abs(shape[k]))
        shape[k] /= shape[k, big]
    omega = np.sqrt(np.clip(w2, 0.0, None))
    with np.errstate(divide="ignore"):
        period = np.where(omega > 0, 2 * np.pi / np.where(omega > 0, omega, 1.0), np.inf)
    effective, total = {}, {}
    for name, r in (influence or {}).items():
        r = np.asarray(r, dtype=float)
        Mr = M @ r
        gamma = shape @ Mr
        generalised = np.einsum("ki,ij,kj->k", shape, M, shape)
        effective[name] = gamma ** 2 / generalised
        total[name] = float(r @ Mr)
    return {"omega": omega, "frequency": omega / (2 * np.pi), "period": period, "shape": shape,
            "effective_mass": effective, "total_mass": total}


def _dense(A) -> np.ndarray:
    return A.toarray() if sp.issparse(A) else np.asarray(A, dtype=float)
