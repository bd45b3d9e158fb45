"""Factorised linear solves for dense or sparse, real or complex matrices.

One wrapper so that kernels and steppers never care whether the model is dense or sparse.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla


class SingularMatrixError(ValueError):
    """The matrix to factorise is singular (or numerically so)."""


class Factorization:
    """LU factorisation of a square matrix, reused across right-hand sides.

    Parameters
    ----------
    A : (n, n) ndarray or sparse matrix, real or complex
    what : str
        Description used in the error message if ``A`` is singular.
    """

    def __init__(self, A, what: str = "matrix"):
        self.shape = A.shape
        self.sparse = sp.issparse(A)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error", sla.LinAlgWarning)
                warnings.simplefilter("error", spla.MatrixRankWarning)
                if self.sparse:
                    self._lu = spla.splu(sp.csc_matrix(A))
                    U = self._lu.U                  # built anew at each access: read once
                    self._dtype = U.dtype
                    diag = np.abs(U.diagonal())
                else:
                    self._lu = sla.lu_factor(np.asarray(A))
                    self._getrs, = sla.get_lapack_funcs(("getrs",), (self._lu[0],))
                    diag = np.abs(np.diag(self._lu[0]))
        except (RuntimeError, sla.LinAlgError, sla.LinAlgWarning, spla.MatrixRankWarning) as exc:
            raise SingularMatrixError(f"{what} is singular ({exc})") from None
        if diag.size and diag.min() <= 1e-13 * diag.max():
            raise SingularMatrixError(
                f"{what} is singular or nearly so (pivot ratio {diag.min() / diag.max():.2e})"
            )

    @property
    def dense_factors(self):
        """``(lu, piv)`` of a dense factorisation (LAPACK convention), or None if sparse."""
        return None if self.sparse else self._lu

    def solve(self, b: np.ndarray) -> np.ndarray:
        """Solve ``A x = b`` for ``b`` of shape (n,) or (n, k)."""
        if self.sparse:
            if sp.issparse(b):
                b = b.toarray()
            return self._lu.solve(np.asarray(b, dtype=np.result_type(b, self._dtype)))
        lu, piv = self._lu
        if np.iscomplexobj(b) and not np.iscomplexobj(lu):
            return self.solve(b.real) + 1j * self.solve(b.imag)
        # LAPACK getrs directly: scipy's lu_solve wrapper costs more than the solve for small n
        x, info = self._getrs(lu, piv, b)
        return x


def dense(A) -> np.ndarray:
    """Return ``A`` as a dense ndarray (for small matrices such as F^T X)."""
    return A.toarray() if sp.issparse(A) else np.asarray(A)


def is_diagonal(A) -> bool:
    """True if every nonzero entry of ``A`` (dense or sparse, square) is on its diagonal (one count
    of the nonzeros: no temporary matrix)."""
    if sp.issparse(A):
        C = A.tocoo()
        return not np.any(C.data[C.row != C.col])
    A = np.asarray(A)
    return np.count_nonzero(A) == np.count_nonzero(np.diagonal(A))


def transpose_times(F, X) -> np.ndarray:
    """``F^T X`` as a dense array, for F (n, m) dense or sparse and X (n,) or (n, k)."""
    out = F.T @ X
    return out.toarray() if sp.issparse(out) else np.asarray(out)


#: Up to this many DOFs a singular stiffness is explained by its zero-energy mode.
MECHANISM_CHECK_MAX_N = 2000


def mechanism_dofs(K, names=None, limit=10) -> list | None:
    """The DOFs a zero-energy mode of the symmetric ``K`` moves most, or None if there is none.

    ``K`` is scaled by its diagonal and its lowest eigenvector taken (dense, up to
    :data:`MECHANISM_CHECK_MAX_N` DOFs; None above). ``names`` labels the DOFs (default: indices).
    """
    n = K.shape[0]
    if n == 0 or n > MECHANISM_CHECK_MAX_N:
        return None
    A = dense(K).astype(float)
    d = np.diag(A).copy()
    scale = 1.0 / np.sqrt(np.where(d > 0, d, 1.0))
    A = 0.5 * (A + A.T) * scale[:, None] * scale[None, :]
    w, V = np.linalg.eigh(A)
    if w[0] > 1e-11 * max(w[-1], 1.0):
        return None
    mode = V[:, 0] * scale
    order = np.argsort(-np.abs(mode))
    moved = [i for i in order if abs(mode[i]) > 1e-3 * abs(mode[order[0]])][:limit]
    return [names[i] if names is not None else str(i) for i in moved]


# ---------------------------------------------------------------------- penalty-stiff elements
#: A model is split into stiff and soft coordinates when its stiffest strain row is this many times
#: stiffer than its softest: the assembled ``K = G E G^T`` then keeps the soft stiffness only to
#: ``eps`` times this ratio (2e-6 relative at 1e10), and every solve with it inherits the error.
STIFF_APPLY_RATIO = 1e10
#: Strain rows (groups of rows coupled by ``E``) at least this many times stiffer than the softest
#: row become coordinates of their own; the rest of the model keeps ``eps`` times this ratio.
STIFF_ROW_RATIO = 1e4
#: Models up to this many DOFs are split (the coordinates are dense).
STIFF_SPLIT_MAX_N = 1000


@dataclass(frozen=True)
class StiffSplit:
    """Coordinates that separate penalty-stiff strains from the rest of a structure.

    ``u = T x`` with ``x = (y, z)``: ``y`` (``n - p``) are the "master" DOFs of ``u`` themselves;
    ``z`` (``p``) are the independent stiff strains ``e_S = G_S^T u``, scaled by ``d`` (``z = d e_S``),
    and the ``p`` "slave" DOFs (massless where possible) follow from both, as with a rigid link.
    In these coordinates the stiff strains' energy is an exact ``p x p`` block that never meets the
    soft stiffness, so ``K_x = T^T K T`` keeps the soft stiffness to round-off
    (``docs/theory.md``, stiff models).

    Attributes
    ----------
    T : (n, n) the coordinates: ``u = T x``
    T_inv : (n, n) ``x = T_inv u``
    Gt : (ne, n) strains of the coordinates, ``e = Gt x``; the stiff rows are exact (zeros, ``d``
        on the diagonal and the coefficients of dependent stiff rows)
    K : (n, n) ``Gt^T E Gt`` assembled without mixing stiff and soft terms, symmetric, N/m
    stiff_rows : (q,) the separated strain rows (independent ones first)
    n_soft : int, ``n - p``
    ratio : float, stiffest over softest strain row (``E_ii |G_i|^2``)
    masters : (n - p,) the DOFs of ``u`` that are the coordinates ``y``
    """

    T: np.ndarray
    T_inv: np.ndarray
    Gt: np.ndarray
    K: np.ndarray
    stiff_rows: np.ndarray
    n_soft: int
    ratio: float
    masters: np.ndarray


def row_stiffness(G, E) -> np.ndarray:
    """``E_ii |G_:,i|^2`` (ne,): the stiffness each strain row adds to the diagonal of ``K``, N/m."""
    Gd = dense(G)
    return np.abs(np.diag(dense(E))) * np.einsum("ij,ij->j", Gd, Gd)


def _stiff_rows(Ed, B, E_v, k, limit) -> np.ndarray:
    """The rows of :func:`stiff_split` to separate.

    Parameters
    ----------
    Ed : (ne, ne) dense elasticity;  B : (ne, m) unilateral rows;  E_v : (ne, ne) viscosities or None
    k : (ne,) row stiffnesses;  limit : the row stiffness that makes a group of rows stiff

    Returns
    -------
    (ne,) bool
        The rows of every group that ``E`` (and ``E_v``) couple whose stiffest row reaches ``limit``
        and none of whose rows carries a unilateral unknown or a dashpot.
    """
    from scipy.sparse.csgraph import connected_components

    coupled = Ed != 0
    free = np.asarray(abs(B).sum(axis=1)).ravel() == 0
    if E_v is not None:
        Evd = dense(E_v)
        coupled |= Evd != 0
        free &= ~np.any(Evd != 0, axis=1)
    n_groups, group = connected_components(sp.csr_matrix(coupled), directed=False)
    stiff = np.zeros(Ed.shape[0], dtype=bool)
    for g in range(n_groups):
        rows = group == g
        if k[rows].max() >= limit and np.all(free[rows]):
            stiff |= rows
    return stiff


def _independent_rows(Gd, k, stiff) -> tuple[list, list]:
    """The stiff rows whose columns of ``Gd`` (n, ne) are independent, stiffest first, and the others.

    Parameters
    ----------
    Gd : (n, ne) dense equilibrium matrix;  k : (ne,) row stiffnesses;  stiff : (ne,) bool rows

    Returns
    -------
    independent, dependent : lists of row indices (a softer row in a stiff loop is carried by the
        others: dependent), at most ``n`` independent ones
    """
    n = Gd.shape[0]
    order = np.flatnonzero(stiff)[np.argsort(-k[stiff], kind="stable")]
    basis, independent, dependent = np.zeros((n, 0)), [], []
    for i in order:
        g = Gd[:, i]
        r = g - basis @ (basis.T @ g)
        r = r - basis @ (basis.T @ r)
        norm = np.linalg.norm(r)
        if norm > 1e-10 * np.linalg.norm(g) and len(independent) < n:
            basis = np.column_stack([basis, r / norm])
            independent.append(i)
        else:
            dependent.append(i)
    return independent, dependent


def stiff_split(G, E, B, E_v=None, *, massless=None, apply_ratio=STIFF_APPLY_RATIO, row_ratio=STIFF_ROW_RATIO,
                max_n=STIFF_SPLIT_MAX_N) -> StiffSplit | None:
    """Split the natural form ``K = G E G^T`` into stiff and soft coordinates, or None if not needed.

    Parameters
    ----------
    G : (n, ne) equilibrium matrix; E : (ne, ne) elasticity; B : (ne, m) unilateral rows;
    E_v : (ne, ne) Kelvin viscosities or None
    massless : (n,) bool, DOFs without mass; the stiff strains are solved for these first
    apply_ratio : split only if the stiffest over the softest row stiffness reaches this
    row_ratio : rows (with the rows ``E`` couples them to) this many times stiffer than the softest
        row are separated, unless they carry a unilateral unknown (``B``) or a dashpot (``E_v``)
    max_n : split only models with at most this many DOFs

    Returns
    -------
    StiffSplit or None
        None when the model is well conditioned, too large, or no row qualifies.
    """
    n, ne = G.shape
    if n == 0 or ne == 0 or n > max_n:
        return None
    k = row_stiffness(G, E)
    positive = k[k > 0]
    if positive.size == 0:
        return None
    k_min = float(positive.min())
    ratio = float(k.max()) / k_min
    if ratio < apply_ratio:
        return None
    Ed = dense(E)
    stiff = _stiff_rows(Ed, B, E_v, k, row_ratio * k_min)
    if not stiff.any():
        return None
    Gd = dense(G).astype(float)
    massless = np.zeros(n, dtype=bool) if massless is None else np.asarray(massless, dtype=bool)
    independent, dependent = _independent_rows(Gd, k, stiff)
    p = len(independent)
    if p == n:
        return None                     # nothing soft is left to protect
    Gs = Gd[:, independent]                         # (n, p): e_S = Gs^T u
    slaves = _slave_dofs(Gs, massless)
    masters = np.setdiff1d(np.arange(n), slaves)
    # u_slaves = A^-1 (e_S - Bm u_masters): x = (u_masters, e_S), like a rigid link's master and slave
    A_inv = np.linalg.inv(Gs[slaves].T)
    T0 = np.zeros((n, n))
    T0[masters, np.arange(n - p)] = 1.0
    T0[np.ix_(slaves, np.arange(n - p))] = -A_inv @ Gs[masters].T
    T0[np.ix_(slaves, np.arange(n - p, n))] = A_inv
    soft = np.flatnonzero(~stiff)
    Gt = np.zeros((ne, n))
    Gt[soft] = Gd[:, soft].T @ T0
    Gt[independent, n - p:] = np.eye(p)
    if dependent:
        Gt[dependent, n - p:] = Gd[:, dependent].T @ T0[:, n - p:]
    S = np.asarray(independent + dependent)
    Gs_t = Gt[S][:, n - p:]                         # (q, p), exact or coefficients
    K_stiff = Gs_t.T @ Ed[np.ix_(S, S)] @ Gs_t
    Gn = Gt[soft]
    K = Gn.T @ (Ed[np.ix_(soft, soft)] @ Gn)
    K[n - p:, n - p:] += K_stiff
    # scale the stiff coordinates to the soft stiffness: K_x is then well scaled for every solver
    k_ref = float(np.max(np.diag(K)[: n - p]))
    k_ref = k_ref if k_ref > 0 else 1.0
    d = np.sqrt(np.diag(K_stiff) / k_ref)
    scale = np.concatenate([np.ones(n - p), 1.0 / d])
    K = K * scale[:, None] * scale[None, :]
    K = 0.5 * (K + K.T)
    T = T0 * scale[None, :]
    Gt = Gt * scale[None, :]
    T_inv = np.zeros((n, n))
    T_inv[np.arange(n - p), masters] = 1.0
    T_inv[n - p:] = d[:, None] * Gs.T
    return StiffSplit(T=T, T_inv=T_inv, Gt=Gt, K=K, stiff_rows=S, n_soft=n - p, ratio=ratio,
                      masters=masters)


def _slave_dofs(Gs, massless):
    """``p`` DOFs that the ``p`` independent stiff strains ``Gs^T u`` determine, massless ones first.

    QR with column pivoting of ``Gs^T`` picks a well-conditioned square block; taking the slaves
    among massless DOFs where possible keeps the mass matrix in the new coordinates diagonal.
    """
    import scipy.linalg as la

    n, p = Gs.shape
    for candidates in (np.flatnonzero(massless), np.arange(n)):
        if candidates.size < p:
            continue
        _, R, piv = la.qr(Gs[candidates].T, pivoting=True, mode="economic")
        diag = np.abs(np.diag(R))
        if diag.size >= p and diag[p - 1] > 1e-8 * diag[0]:
            return np.sort(candidates[piv[:p]])
    raise ValueError("the stiff strains are not independent")   # excluded by the caller's selection
