"""Every pole and residue of ``Lambda(s)`` of a dense model, through a first-order form.

Orthonormal coordinates split the DOFs by their dynamics (``M`` and ``C`` are PSD, so a vector
without mass has ``M x = 0`` and one without damping ``C x = 0``):

* ``T2``: range of ``M`` (massive): displacement and velocity states;
* ``T1``: no mass, damping (e.g. a massless foundation on soil dashpots): one first-order state;
* ``T0``: no mass, no damping: no dynamics, condensed statically (exactly).

With ``a = (T2, T1)`` and ``K~ = K_aa - K_a0 K_00^-1 K_0a``, ``F~(s) = F_a(s) - K_a0 K_00^-1 F_0``
(``F_v`` on ``T0`` would make ``Lambda`` grow like ``s^2`` and is rejected):

    Lambda(s) = H(s) - F_0^T K_00^-1 F_0 - F~(s)^T S(s)^-1 F~(s),   S(s) = K~ + s C_aa + s^2 M_aa

and ``S(s)^-1`` is the displacement block of ``(s E + A)^-1`` for the symmetric pencil on the
states ``x = (u_a, w = s u_2)``

    E = [[C_aa, P], [P^T, 0]],   A = [[K~, 0], [0, -M_22]],   P = [M_22; 0],

with ``E`` nonsingular (no infinite poles). The poles are the reciprocals of the eigenvalues of
``-A^-1 E`` and, the pencil being symmetric, the left eigenvector of ``p_k`` is ``conj(x_k)``:
``(s E + A)^-1 = sum_k x_k x_k^T / ((s - p_k) x_k^T E x_k)`` (block-normalised within clusters of
equal poles). The Kelvin terms follow from ``(F~ + s F~_v) = (F~ + p F~_v) + (s - p) F~_v``, the
dashpot term ``s P1`` from the expansion ``(s E + A)^-1 = E^-1/s + O(s^-2)``, and the constant
from ``Lambda(0) = H - F^T K^-1 F`` computed directly (the kernel is anchored there: fast poles
with large residues would otherwise cancel a large ``P0`` at low s). The pencil is scaled
symmetrically (``K~`` and ``M_22`` to unit diagonal) and the eigensolver balances ``A^-1 E``.
Working with ``1/p`` resolves the slow poles, which matter at the CQ frequencies, to full
relative accuracy even when stiff parts (an axially rigid column on soil dashpots) add poles many
decades faster; the normwise error then sits on those fast poles, which act quasi-statically.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ..linalg import dense

#: Largest model handled by the dense path (an eigendecomposition of up to 2n states, O(n^3)).
DENSE_MAX_N = 2000
#: Eigenvalues of M (C) below this fraction of the largest count as zero mass (damping).
RANK_TOL = 1e-12
#: Largest accepted eigenvector condition ``|y|^T |E| |x|`` with ``y^H E x = 1``: large when the
#: normalisation cancels, i.e. for a (nearly) defective pole.
EIGVEC_CONDITION_MAX = 1e8
#: Poles closer than this (relative) are treated as one multiple pole (block normalisation).
CLUSTER_TOL = 1e-6
#: Eigenvalues with an imaginary part below this fraction of their modulus are real ones split
#: by rounding (a genuinely complex pole that close to the axis is a critically damped, defective one).
REAL_TOL = 1e-12


def dense_poles(model) -> dict:
    """Poles, residue factors and polynomial part of ``Lambda(s)`` of a matrix model.

    Parameters
    ----------
    model : Model with ``n <= DENSE_MAX_N`` (sparse matrices are densified)

    Returns
    -------
    dict with ``poles`` (r,), ``B``, ``Cf`` (r, m), ``Lambda0``, ``P1`` (m, m) and ``info``: the
    keyword arguments of :class:`~unilateral.kernels.PoleResidueKernel`.
    """
    n, m = model.n, model.m
    if n > DENSE_MAX_N:
        raise ValueError(f"the model has n = {n} DOFs, more than the dense path handles "
                         f"(DENSE_MAX_N = {DENSE_MAX_N}); give modes=k for the truncated modal "
                         "kernel")
    K, M, C, F = dense(model.K), dense(model.M), dense(model.damping()), dense(model.F)
    Fv = np.zeros((n, m)) if model.F_v is None else dense(model.F_v)
    Hv = np.zeros((m, m)) if model.H_v is None else dense(model.H_v)
    T2, T0 = _split(M, np.eye(n), "M")
    T1, T0 = _split(C, T0, "C")
    Ta = np.hstack([T2, T1])
    n2, na = T2.shape[1], Ta.shape[1]
    if np.abs(T0.T @ Fv).max(initial=0.0) > 1e-10 * np.abs(Fv).max(initial=0.0):
        raise ValueError("F_v couples the constraints to DOFs without mass and without damping: "
                         "Lambda(s) would grow like s^2 (add the Kelvin dashpots to C, as "
                         "Model.from_natural does)")
    Kt, Ft = _condense(K, F, Ta, T0)
    Ftv = Ta.T @ Fv
    M2 = T2.T @ M @ T2
    E = np.zeros((na + n2, na + n2))
    E[:na, :na] = Ta.T @ C @ Ta
    E[:n2, na:] = M2
    E[na:, :n2] = M2
    A = sla.block_diag(Kt, -M2)
    scale = 1.0 / np.sqrt(np.concatenate([np.diag(Kt), np.diag(M2)]))
    Es = scale[:, None] * E * scale[None, :]
    As = scale[:, None] * A * scale[None, :]
    p, X, Y, condition = _eigen(As, Es)
    X = (scale[:, None] * X)[:na]
    Y = (scale[:, None] * Y)[:na]
    B = -(X.T @ Ft + p[:, None] * (X.T @ Ftv))
    Cf = Y.conj().T @ Ft + p[:, None] * (Y.conj().T @ Ftv)
    Lambda0 = dense(model.H) - F.T @ sla.cho_solve(_cholesky(K, "K"), F)
    P1 = Hv.copy()
    if np.any(Ftv):                                     # s F~v^T (E^-1)_uu F~v, E^-1 = S Es^-1 S
        rhs = np.vstack([scale[:na, None] * Ftv, np.zeros((n2, m))])
        P1 -= Ftv.T @ (scale[:na, None] * np.linalg.solve(Es, rhs)[:na])
    info = {"path": "dense", "poles": int(np.where(p.imag > 0, 2, 1).sum()),
            "modes": int(np.count_nonzero(p.imag > 0)), "states": na + n2,
            "dofs": {"massive": n2, "first_order": na - n2, "condensed": T0.shape[1]},
            "eigvec_condition": condition}
    return {"poles": p, "B": B, "Cf": Cf, "Lambda0": 0.5 * (Lambda0 + Lambda0.T),
            "P1": 0.5 * (P1 + P1.T), "info": info}


def check_points(poles: np.ndarray) -> np.ndarray:
    """A few s in the right half-plane spanning the pole magnitudes: (3,) complex."""
    mags = np.abs(poles)
    lo, hi = (mags.min(), mags.max()) if mags.size else (1.0, 1.0)
    return np.array([lo, np.sqrt(lo * hi), hi]) * np.exp(0.45j * np.pi)


def _split(A: np.ndarray, basis: np.ndarray, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Orthonormal bases of the range and the null space of ``A`` (PSD) within ``span(basis)``."""
    if basis.shape[1] == 0:
        return basis, basis
    Ar = basis.T @ A @ basis
    size = np.abs(A).max(initial=0.0)
    if np.count_nonzero(Ar - np.diag(np.diag(Ar))) == 0:
        w, V = np.diag(Ar), np.eye(Ar.shape[0])
    else:
        w, V = np.linalg.eigh(0.5 * (Ar + Ar.T))
    if np.any(w < -1e-8 * size):
        raise ValueError(f"{name} is not positive semidefinite (eigenvalue {w.min():.3e}); "
                         f"mass and damping matrices must be PSD")
    keep = w > RANK_TOL * size
    return basis @ V[:, keep], basis @ V[:, ~keep]


def _condense(K, F, Ta, T0):
    """Static condensation of the ``T0`` coordinates: ``(K~, F~)``."""
    Kaa, Fa = Ta.T @ K @ Ta, Ta.T @ F
    if T0.shape[1] == 0:
        return Kaa, Fa
    Ka0, F0 = Ta.T @ K @ T0, T0.T @ F
    factor = _cholesky(T0.T @ K @ T0, "K on the DOFs without mass and damping")
    X = sla.cho_solve(factor, np.hstack([Ka0.T, F0]))
    na = Ta.shape[1]
    return Kaa - Ka0 @ X[:, :na], Fa - Ka0 @ X[:, na:]


def _cholesky(A: np.ndarray, what: str):
    try:
        return sla.cho_factor(A)
    except sla.LinAlgError:
        raise ValueError(f"{what} is not positive definite (the bilateral structure is a "
                         "mechanism)") from None


def _eigen(A: np.ndarray, E: np.ndarray):
    """Poles of ``(s E + A)``, one per conjugate pair, with ``E``-normalised eigenvectors.

    ``A`` and ``E`` are symmetric and nonsingular, so the poles are ``1/mu`` for the eigenvalues
    ``mu`` of ``-A^-1 E`` (balanced Hessenberg QR, several times faster than QZ on the pencil) and
    the left eigenvector of ``p`` is ``conj(x)``:
    ``(s E + A)^-1 = sum_k x_k x_k^T / ((s - p_k) x_k^T E x_k)``.
    A multiple but semisimple pole (every massless DOF of a Rayleigh-damped model has ``-1/a1``;
    symmetric structures have repeated frequencies) has no unique eigenvectors: within each cluster
    of nearly equal poles the vectors are normalised as a block, ``X_c <- X_c D^-1`` with
    ``D = X_c^T E X_c``. A defective cluster makes ``D`` singular and is reported.

    Returns
    -------
    p : (r,) complex, ``Im p >= 0``
    X, Y : (ns, r) factors with ``(s E + A)^-1 = sum_k x_k y_k^H / (s - p_k)`` (+ conjugates)
    condition : float, the largest ``|y_k|^T |E| |x_k|`` (1 without cancellation)
    """
    if E.shape[0] == 0:
        return np.zeros(0, complex), np.zeros((0, 0), complex), np.zeros((0, 0), complex), 1.0
    mu, X = sla.eig(np.linalg.solve(A, -E))
    if np.count_nonzero(mu.imag > 0) != np.count_nonzero(mu.imag < 0):
        raise ValueError("the poles of a real model must come in conjugate pairs; the eigensolver "
                         f"returned {np.count_nonzero(mu.imag < 0)} with Im p > 0 and "
                         f"{np.count_nonzero(mu.imag > 0)} with Im p < 0")
    mu, X = _real_pairs(mu, X)
    keep = mu.imag <= 0
    w, X = 1.0 / mu[keep], X[:, keep]
    w, X = _refine_fast(A, E, w, X, mu)
    real = w.imag == 0
    X[:, real] = X[:, real].real
    Y = X.conj()
    with np.errstate(divide="ignore", invalid="ignore"):
        X = X / np.sum(X * (E @ X), axis=0)
        for idx in _clusters(w):
            D = Y[:, idx].conj().T @ E @ X[:, idx]
            try:
                X[:, idx] = np.linalg.solve(D.T, X[:, idx].T).T
            except np.linalg.LinAlgError:
                X[:, idx] = np.inf
    cond = np.sum(np.abs(Y) * (np.abs(E) @ np.abs(X)), axis=0)
    if not np.all(np.isfinite(cond)) or cond.max() > EIGVEC_CONDITION_MAX:
        k = int(np.argmax(np.where(np.isfinite(cond), cond, np.inf)))
        raise ValueError(
            f"the eigenvector basis is defective or badly conditioned: pole {w[k]:.6g} has "
            f"condition {cond[k]:.3e} > {EIGVEC_CONDITION_MAX:.0e} (a multiple pole without a "
            "full set of eigenvectors, e.g. a critically damped mode); the pole-residue form "
            "needs semisimple poles -- perturb the damping slightly or use the Laplace-domain "
            "kernel"
        )
    return w, X, Y, float(cond.max())


def _real_pairs(mu: np.ndarray, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Conjugate pairs of eigenvalues with ``|Im mu| <= REAL_TOL |mu|`` made two real ones.

    A multiple real eigenvalue (the ``-1/a1`` of the massless DOFs of a Rayleigh-damped model)
    may come out of the eigensolver as a real one and a pair split by rounding into ``+-i 1e-18``,
    whose complex vectors are not ``E``-orthogonal to the real one's: the pair would not be
    normalised with its cluster. Its vectors span a real subspace, spanned as well by ``Re x`` and
    ``Im x``, which replace them. LAPACK returns each pair consecutively, ``Im mu > 0`` first.
    """
    pairs = np.flatnonzero((mu.imag > 0) & (np.abs(mu.imag) <= REAL_TOL * np.abs(mu)))
    if pairs.size == 0:
        return mu, X
    mu, X = mu.copy(), X.copy()
    for j in pairs:
        x = X[:, j].copy()
        mu[j] = mu[j + 1] = mu[j].real
        X[:, j], X[:, j + 1] = x.real, x.imag
    return mu, X


def _refine_fast(A, E, p, X, mu, *, iterations=4):
    """Rayleigh-quotient iteration on the poles many decades faster than the slowest ones.

    The eigensolver works on ``-A^-1 E`` (eigenvalues ``1/p``) with an absolute error of about
    ``eps max|1/p|``: a pole ``FAST_POLE_RATIO`` times faster than the slowest is then known only
    to ``eps / FAST_POLE_RATIO`` relative, and its residue with it (penalty-stiff elements on
    dashpots give poles 1e10 times faster than the structure's). For each such pole, inverse
    iteration ``(p E + A) y = E x`` with the Rayleigh quotient of the symmetric pencil
    ``p = -x^T A x / x^T E x`` restores full relative accuracy in a few steps. Poles within
    ``CLUSTER_TOL`` of another are left alone (their eigenvectors are not unique).
    """
    size = np.abs(mu).max(initial=0.0)
    fast = np.flatnonzero(np.abs(1.0 / p) < size / FAST_POLE_RATIO)
    if fast.size == 0 or fast.size > FAST_POLES_REFINED_MAX:
        return p, X
    p, X = p.copy(), X.astype(complex)
    clustered = {int(i) for idx in _clusters(p) for i in idx}
    for k in fast:
        if k in clustered:
            continue
        pk, x = p[k], X[:, k]
        for _ in range(iterations):
            try:
                y = np.linalg.solve(pk * E + A, E @ x)
            except np.linalg.LinAlgError:
                break                               # pk is an eigenvalue to machine precision
            if not np.all(np.isfinite(y)):
                break
            x = y / np.linalg.norm(y)
            denom = x @ (E @ x)
            if denom == 0:
                break
            new = -(x @ (A @ x)) / denom
            done = abs(new - pk) <= 4 * np.finfo(float).eps * abs(pk)
            pk = new
            if done:
                break
        if pk.imag != 0 and p[k].imag == 0 and abs(pk.imag) <= 1e-12 * abs(pk):
            pk, x = complex(pk.real), x.real.astype(complex)
        p[k], X[:, k] = pk, x
    return p, X


#: Poles this many times faster than the slowest are refined by Rayleigh-quotient iteration.
FAST_POLE_RATIO = 1e6
#: At most this many poles are refined (each costs a dense solve of the state-space size).
FAST_POLES_REFINED_MAX = 64


def _clusters(p: np.ndarray) -> list[np.ndarray]:
    """Index groups (two or more) of poles of one kind (real or complex) within CLUSTER_TOL."""
    mag = np.abs(p)
    real = p.imag == 0
    near = np.abs(p[:, None] - p[None, :]) <= CLUSTER_TOL * np.maximum(mag[:, None], mag[None, :])
    close = near & (real[:, None] == real[None, :])
    from scipy.sparse.csgraph import connected_components   # here: importing the kernels does not load it

    count, labels = connected_components(sp.csr_matrix(close), directed=False)
    sizes = np.bincount(labels, minlength=count)
    return [np.flatnonzero(labels == c) for c in np.flatnonzero(sizes > 1)]
