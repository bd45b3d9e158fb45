"""The lowest modes of a classically damped model plus the static correction of the others.

With ``K phi_k = w_k^2 M phi_k`` (``M``-normalised, the ``q`` lowest by shift-invert Lanczos on
one sparse LU of ``K``) and modal damping ``C phi_k = c_k M phi_k`` (checked),

    D(s)^-1 ~ sum_{k<=q} phi_k phi_k^T / (s^2 + c_k s + w_k^2) + R,
    R = K^-1 - sum_{k<=q} phi_k phi_k^T / w_k^2

so ``Lambda(s) ~ H + s H_v - F^T R F - sum_k f_k f_k^T / ((s - p_k)(s - p'_k))`` with
``f_k = F^T phi_k``.
The static correction ``F^T R F`` (from ``K^-1 F``, m right-hand sides) makes ``Lambda(0)`` exact
and is the quasi-static response of the truncated modes. The retained modes decouple exactly from
the rest only if they diagonalise ``C``; Kelvin coupling ``F_v`` is not supported here (the
truncated modes would contribute an ``s^2`` term): use the dense path.

Each mode is one conjugate pair ``p = -c/2 + i sqrt(w^2 - c^2/4)`` (stored once) or, overdamped,
two real poles.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..linalg import Factorization, dense, transpose_times

#: Modes with ``|c^2/4 - w^2| < (CRITICAL_TOL w)^2`` are (nearly) critically damped: a double pole.
CRITICAL_TOL = 1e-7


def truncated_poles(model, modes: int, tol: float) -> dict:
    """Pole-residue form of the ``modes`` lowest modes with the static correction.

    Parameters
    ----------
    model : Model (dense or sparse), ``C`` diagonalised by the modes, no ``F_v``
    modes : int, ``1 <= modes <`` number of DOFs with mass
    tol : float, largest accepted relative residual ``||C phi_k - c_k M phi_k||``

    Returns
    -------
    dict: the keyword arguments of :class:`~unilateral.kernels.PoleResidueKernel`.
    """
    if model.F_v is not None and np.any(dense(model.F_v)):
        raise ValueError("the truncated modal kernel does not support Kelvin constraints (F_v): "
                         "the truncated modes would add an s^2 term; use modes=None (dense path)")
    n, m = model.n, model.m
    diag = model.M.diagonal() if sp.issparse(model.M) else np.diag(model.M)
    massive = int(np.count_nonzero(diag))
    if modes >= massive:
        raise ValueError(f"modes={modes} must be less than the {massive} DOFs with mass "
                         "(the Lanczos solver needs modes < n); use modes=None for every pole")
    lu = Factorization(model.K, what="K")
    OPinv = spla.LinearOperator((n, n), matvec=lu.solve, dtype=float)
    ncv = min(max(2 * modes + 1, 20), massive)          # the Krylov space lives in range(M)
    try:
        w2, Phi = spla.eigsh(model.K, k=modes, M=model.M, sigma=0.0, which="LM", OPinv=OPinv,
                             ncv=ncv)
    except (spla.ArpackError, spla.ArpackNoConvergence) as exc:
        raise ValueError(f"the Lanczos solver found no {modes} lowest modes ({exc}); try fewer "
                         "modes, or modes=None for the dense path") from None
    order = np.argsort(w2)
    w2, Phi = w2[order], Phi[:, order]
    if np.any(w2 <= 0):
        raise ValueError(f"K phi = w^2 M phi has a nonpositive eigenvalue {w2.min():.3e}: "
                         "K must be positive definite")
    # Purify: phi = w^2 K^-1 M phi removes the null(M) components Lanczos leaves when M is singular.
    Phi = lu.solve(model.M @ Phi) * w2
    MPhi = model.M @ Phi
    scale = np.sqrt(np.einsum("ik,ik->k", Phi, MPhi))
    Phi, MPhi = Phi / scale, MPhi / scale
    c, residual = _modal_damping(model.C, Phi, MPhi)
    if residual > tol:
        raise ValueError(
            f"C is not diagonalised by the modes (non-classical damping): "
            f"max_k ||C phi_k - c_k M phi_k|| / ||C phi_k|| = {residual:.2e} > tol = {tol:.0e}; "
            "the truncated modal kernel needs classical damping (e.g. C = a0 M + a1 K); "
            "use modes=None for the exact dense kernel")
    f = transpose_times(model.F, Phi).T                                   # (q, m)
    poles, B, Cf = _mode_poles(w2, c, f)
    FKF = transpose_times(model.F, lu.solve(dense(model.F)))
    correction = FKF - (f.T / w2) @ f
    Lambda0 = dense(model.H) - FKF                  # anchors the kernel: P0 = H - correction
    P1 = np.zeros((m, m)) if model.H_v is None else dense(model.H_v)
    info = {"path": "truncated", "poles": int(np.where(poles.imag > 0, 2, 1).sum()),
            "modes": modes, "omega": np.sqrt(w2), "damping_residual": residual,
            "static_correction": float(np.abs(correction).max() / max(np.abs(FKF).max(), 1e-300))}
    return {"poles": poles, "B": B, "Cf": Cf, "Lambda0": 0.5 * (Lambda0 + Lambda0.T), "P1": P1,
            "info": info}


def _modal_damping(C, Phi, MPhi) -> tuple[np.ndarray, float]:
    """Modal damping ``c_k = phi_k^T C phi_k`` (q,) and the largest relative residual."""
    if C is None:
        return np.zeros(Phi.shape[1]), 0.0
    CPhi = C @ Phi
    c = np.einsum("ik,ik->k", Phi, CPhi)
    size = np.linalg.norm(CPhi, axis=0) + np.abs(c) * np.linalg.norm(MPhi, axis=0)
    res = np.linalg.norm(CPhi - c * MPhi, axis=0) / np.where(size > 0, size, 1.0)
    return c, float(res.max(initial=0.0))


def _mode_poles(w2, c, f):
    """Poles and residue factors of ``-f_k f_k^T / (s^2 + c_k s + w_k^2)``.

    Returns
    -------
    poles : (r,) complex, one per underdamped mode, two per overdamped mode
    B, Cf : (r, m)
    """
    half = 0.5 * c
    disc = half * half - w2
    if np.any(np.abs(disc) < (CRITICAL_TOL ** 2) * w2):
        k = int(np.argmin(np.abs(disc) / w2))
        raise ValueError(f"mode {k} (w = {np.sqrt(w2[k]):.6g}) is critically damped: a double pole "
                         "that the pole-residue form cannot hold; change the damping slightly")
    under = disc < 0
    pu = -half[under] + 1j * np.sqrt(-disc[under])
    fu = f[under]
    root = np.sqrt(disc[~under])
    p1 = -half[~under] - root
    p2 = w2[~under] / p1
    fo = f[~under]
    gap = (p1 - p2)[:, None]
    poles = np.concatenate([pu, p1, p2])
    B = np.vstack([-fu / (2j * pu.imag[:, None]), -fo / gap, fo / gap])
    Cf = np.vstack([fu, fo, fo]).astype(complex)
    return poles, B, Cf
