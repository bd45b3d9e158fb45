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

#: The largest ``K_ii / M_ii`` (a squared frequency, rad^2 per time unit^2) of a DOF with mass that
#: is solved: beyond it ``omega^2``, ``(omega dt)^2`` and the periods are not representable in
#: double precision (``1e-300`` of mass on a ``1e11`` stiffness overflows).
MAX_OMEGA_SQUARED = 1e200


def check_frequency_range(K, M, names) -> None:
    """Refuse a mass too small for its stiffness to be represented (``K_ii / M_ii > 1e200``).

    Parameters
    ----------
    K, M : (n, n) stiffness and (diagonal) mass matrices, dense or sparse
    names : sequence of n DOF names (``"1.ux"``)

    Raises
    ------
    ValueError
        Naming the DOF, its mass, its stiffness and the smallest mass that would be valid.
    """
    k = np.abs(np.asarray(K.diagonal(), dtype=float))
    m = np.asarray(M.diagonal(), dtype=float)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        ratio = np.where(m > 0, k / np.where(m > 0, m, 1.0), 0.0)
    bad = np.flatnonzero(~(ratio <= MAX_OMEGA_SQUARED))
    if bad.size:
        i = int(bad[np.argmax(ratio[bad])])
        raise ValueError(
            f"the mass {float(m[i])!r} of DOF {names[i]} is too small for its stiffness {k[i]:.6g}: the squared "
            f"frequency K_ii/M_ii = {ratio[i]:.3g} exceeds {MAX_OMEGA_SQUARED:g}, beyond what double precision "
            f"carries (periods, time steps); give a mass (or J) >= {k[i] / MAX_OMEGA_SQUARED:.3g} at that DOF, or 0 "
            "for a massless DOF")


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

    A model with penalty-stiff elements is solved in its stiff-separated coordinates
    (:mod:`unilateral.model.stiff`, the same eigenvalues): its assembled ``K`` keeps the soft
    stiffness only to ``eps`` times the stiffness ratio, which made the soft modes' periods infinite.
    """
    from ..model.stiff import StiffCoordinates     # lazily: only models with a natural form

    stiff = StiffCoordinates.of(model) if getattr(model, "natural", None) is not None else None
    if stiff is not None:
        return _modes_separated(stiff, count, influence)
    return _modes(model, count, influence)


def _modes_separated(stiff, count, influence) -> dict:
    """:func:`modes` of the conditioned model ``x = T^-1 u``, the shapes mapped back to ``u = T x``."""
    T, T_inv = stiff.split.T, stiff.split.T_inv
    mapped = {name: T_inv @ np.asarray(r, dtype=float) for name, r in (influence or {}).items()}
    out = _modes(stiff.conditioned, count, mapped)
    shape = out["shape"] @ T.T
    for k in range(shape.shape[0]):
        shape[k] /= shape[k, np.argmax(np.abs(shape[k]))]
    out["shape"] = shape
    return out


def _modes(model, count, influence) -> dict:
    """:func:`modes` of the assembled ``K``, ``M``."""
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


def modal_damping_matrix(K, M, zeta, modes=None) -> np.ndarray:
    """``M_m Phi diag(2 zeta_i w_i) Phi^T M_m`` (n, n) on the DOFs with mass (massless DOFs condensed
    statically, their rows and columns zero); see :meth:`Frame2D.modal_damping`."""
    K = K.toarray() if sp.issparse(K) else np.asarray(K, dtype=float)
    M = M.toarray() if sp.issparse(M) else np.asarray(M, dtype=float)
    n = K.shape[0]
    mass = np.flatnonzero(np.diag(M) > 0)
    zero = np.setdiff1d(np.arange(n), mass)
    C = np.zeros((n, n))
    if mass.size == 0:
        return C
    Kmm = K[np.ix_(mass, mass)]
    if zero.size:
        K0m = K[np.ix_(zero, mass)]
        try:
            Kmm = Kmm - K0m.T @ np.linalg.solve(K[np.ix_(zero, zero)], K0m)
        except np.linalg.LinAlgError:
            raise ValueError("modal_damping: the massless DOFs cannot be condensed (their stiffness is "
                             "singular); give them mass or support them") from None
    Mmm = M[np.ix_(mass, mass)]
    from scipy.linalg import eigh

    w2, phi = eigh(0.5 * (Kmm + Kmm.T), Mmm)               # Phi^T M Phi = I
    count = mass.size if modes is None and isinstance(zeta, float) else (
        len(zeta) if modes is None else modes)
    count = min(count, mass.size)
    z = np.full(count, zeta) if isinstance(zeta, float) else np.asarray(zeta[:count], dtype=float)
    w = np.sqrt(np.clip(w2[:count], 0.0, None))
    MP = Mmm @ phi[:, :count]
    C[np.ix_(mass, mass)] = (MP * (2 * z * w)) @ MP.T
    return 0.5 * (C + C.T)
