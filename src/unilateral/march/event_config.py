"""One contact configuration of the event-driven march: an exact linear first-order system.

With the constraints of the open set ``O`` open (``psi_O = 0``, ``v_O`` free) and the others
closed (``v_C = 0``), the unknowns ``x = (u, v_O)`` obey the linear system

    M~ x'' + C~ x' + K~ x = (q(t), -g_O)

    M~ = [[M, 0], [0, 0]],  C~ = [[C, -F_vO], [-F_vO^T, H_vOO]],  K~ = [[K, -F_O], [-F_O^T, H_OO]]

(the second block row is ``-psi_O = 0``). As in :mod:`unilateral.modal_dense`, orthonormal
coordinates split ``x`` by its dynamics: ``T2`` the range of ``M~`` (second order), ``T1`` the range
of ``C~`` without mass (first order: a massless foundation on dashpots, the gap of an open Kelvin
contact), ``T0`` neither (condensed statically, exactly). The state is ``y = (a2, a1, a2')`` and,
with the load generator ``z' = S z`` (:mod:`unilateral.march.event_load`), the augmented system
``Y = (y, z)``, ``Y' = A Y`` is integrated exactly by ``expm``. Every output (u, u', v, v', psi)
is a linear map of ``Y``.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

#: Eigenvalues below this fraction of the largest count as zero (mass, damping).
RANK_TOL = 1e-12


class Config:
    """The exact linear system of one contact configuration.

    Attributes
    ----------
    open : (m,) bool
    A : (ny + nz, ny + nz) augmented system matrix
    U, UD, V, VD, PSI, E : output maps (rows, ny + nz) of u, u', v, v', psi and the event
        functions ``e`` (``psi_i`` for closed constraints, ``-v_i`` for open ones; ``e <= 0``
        is admissible)
    """

    def __init__(self, mats, gen, open_mask):
        M, C, K, F, Fv, H, Hv, g = mats
        n, m = K.shape[0], F.shape[1]
        O = np.flatnonzero(open_mask)
        o = O.size
        self.open = np.asarray(open_mask, dtype=bool).copy()
        N = n + o
        Mt = np.zeros((N, N))
        Mt[:n, :n] = M
        Ct = np.zeros((N, N))
        Ct[:n, :n] = C
        Ct[:n, n:] = -Fv[:, O]
        Ct[n:, :n] = -Fv[:, O].T
        Ct[n:, n:] = Hv[np.ix_(O, O)]
        Kt = np.zeros((N, N))
        Kt[:n, :n] = K
        Kt[:n, n:] = -F[:, O]
        Kt[n:, :n] = -F[:, O].T
        Kt[n:, n:] = H[np.ix_(O, O)]
        T2, Tn = _split(Mt, np.eye(N), "the mass matrix")
        T1, T0 = _split(Ct, Tn, "the damping matrix with the open Kelvin contacts")
        n2, n1, n0 = T2.shape[1], T1.shape[1], T0.shape[1]
        if n0 and np.abs(Ct @ T0).max() > 1e-9 * max(np.abs(Ct).max(), 1e-300):
            raise ValueError("the damping matrix (with the Kelvin terms of the open contacts) is not "
                             "positive semidefinite; method='event' needs C, H_v PSD")
        # load of the augmented rows: (q, -g_O) = R z
        nz = gen.size
        R = np.zeros((N, nz))
        R[:n] = gen.Gq
        R[n:, 0] = -g[O]
        Kb = lambda A_, B_: A_.T @ Kt @ B_
        Cb = lambda A_, B_: A_.T @ Ct @ B_
        if n0:
            K00 = Kb(T0, T0)
            try:
                chol = sla.cho_factor(0.5 * (K00 + K00.T))
            except sla.LinAlgError:
                raise ValueError(
                    "a contact configuration leaves coordinates without mass, damping or stiffness "
                    f"(open constraints {O.tolist()}): the structure becomes a mechanism there, or an "
                    "open contact has no stiffness H (a rigid contact); method='event' needs H_OO > 0 "
                    "or a Kelvin dashpot on every open contact") from None
            solve0 = lambda X: sla.cho_solve(chol, X)
        else:
            solve0 = lambda X: np.zeros((0,) + np.shape(X)[1:])
        # condensation of T0:  a0 = K00^-1 (T0^T R z - K02 a2 - K01 a1)
        Ta = np.hstack([T2, T1])
        X0a = solve0(Kb(T0, Ta))                                  # (n0, n2+n1)
        X0z = solve0(T0.T @ R)                                    # (n0, nz)
        Kc = Kb(Ta, Ta) - Kb(Ta, T0) @ X0a
        Rc = Ta.T @ R - Kb(Ta, T0) @ X0z
        ny = 2 * n2 + n1
        NY = ny + nz
        # index maps of Y = (a2, a1, w2, z)
        i2, i1, iw, iz = (np.arange(n2), n2 + np.arange(n1), n2 + n1 + np.arange(n2), ny + np.arange(nz))
        ia = np.concatenate([i2, i1])
        Ca = Cb(Ta, Ta)
        C11, C12, C21, C22 = Ca[n2:, n2:], Ca[n2:, :n2], Ca[:n2, n2:], Ca[:n2, :n2]
        # a1' = C11^-1 (Rc1 z - Kc1a a - C12 w2)
        L1 = np.zeros((n1, NY))
        L1[:, ia] = -Kc[n2:]
        L1[:, iw] = -C12
        L1[:, iz] = Rc[n2:]
        if n1:
            L1 = np.linalg.solve(C11, L1)
        # w2' = M22^-1 (Rc2 z - Kc2a a - C22 w2 - C21 a1')
        M22 = T2.T @ Mt @ T2
        L2 = np.zeros((n2, NY))
        L2[:, ia] = -Kc[:n2]
        L2[:, iw] = -C22
        L2[:, iz] = Rc[:n2]
        L2 -= C21 @ L1
        if n2:
            L2 = np.linalg.solve(M22, L2)
        A = np.zeros((NY, NY))
        A[i2, iw] = 1.0
        A[i1] = L1
        A[iw] = L2
        A[np.ix_(iz, iz)] = gen.S
        # outputs
        P2, P1, PW = (np.eye(NY)[idx] for idx in (i2, i1, iw))
        L0 = np.zeros((n0, NY))
        L0[:, ia] = -X0a
        L0[:, iz] = X0z
        # a0' = K00^-1 (T0^T R S z - K02 w2 - K01 a1')
        L0d = np.zeros((n0, NY))
        L0d[:, iz] = solve0(T0.T @ R @ gen.S)
        if n0:
            K0a = Kb(T0, Ta)
            L0d -= solve0(K0a[:, :n2] @ PW + K0a[:, n2:] @ L1)
        Xo = T2 @ P2 + T1 @ P1 + T0 @ L0
        Xd = T2 @ PW + T1 @ L1 + T0 @ L0d
        self.U, self.UD = Xo[:n], Xd[:n]
        self.V = np.zeros((m, NY))
        self.VD = np.zeros((m, NY))
        self.V[O], self.VD[O] = Xo[n:], Xd[n:]
        PSI = F.T @ self.U + Fv.T @ self.UD - H @ self.V - Hv @ self.VD
        PSI[:, iz[0]] -= g
        PSI[O] = 0.0
        self.PSI = PSI
        self.E = np.where(self.open[:, None], -self.V, PSI)
        self.A = A
        self.T2, self.T1 = T2, T1
        self.n, self.ny, self.nz = n, ny, nz
        self.O = O
        lam = np.linalg.eigvals(A[:ny, :ny]) if ny else np.zeros(0)
        self.max_frequency = float(np.max(np.abs(lam.imag), initial=0.0))
        self.max_rate = float(np.max(np.abs(lam), initial=0.0))
        self._cache = {}

    def state_from(self, u, udot, v, z) -> np.ndarray:
        """``Y`` from the continuous quantities: u, the massive part of u', v on the open set, z."""
        x = np.concatenate([u, v[self.O]])
        xd = np.concatenate([udot, np.zeros(self.O.size)])
        return np.concatenate([self.T2.T @ x, self.T1.T @ x, self.T2.T @ xd, z])

    def propagator(self, h: float) -> np.ndarray:
        """``expm(A h)`` (cached for repeated step sizes)."""
        key = float(h)
        P = self._cache.get(key)
        if P is None:
            P = sla.expm(self.A * h)
            if len(self._cache) > 64:
                self._cache.clear()
            self._cache[key] = P
        return P

    def powers(self, h: float, J: int) -> np.ndarray:
        """Stacked ``expm(A h j)`` for j = 1..J, (J, NY, NY) (cached)."""
        key = ("pow", float(h), int(J))
        P = self._cache.get(key)
        if P is None:
            step = self.propagator(h)
            P = np.empty((J,) + step.shape)
            P[0] = step
            for j in range(1, J):
                P[j] = step @ P[j - 1]
            self._cache[key] = P
        return P


def _split(A, basis, name):
    """Orthonormal bases of the range and the null space of PSD ``A`` within ``span(basis)``."""
    if basis.shape[1] == 0:
        return basis, basis
    Ar = basis.T @ A @ basis
    size = np.abs(A).max(initial=0.0)
    if np.count_nonzero(Ar - np.diag(np.diag(Ar))) == 0:
        w, V = np.diag(Ar).copy(), np.eye(Ar.shape[0])
    else:
        w, V = np.linalg.eigh(0.5 * (Ar + Ar.T))
    if np.any(w < -1e-8 * size):
        raise ValueError(f"{name} is not positive semidefinite (eigenvalue {w.min():.3e})")
    keep = w > RANK_TOL * size
    return basis @ V[:, keep], basis @ V[:, ~keep]
