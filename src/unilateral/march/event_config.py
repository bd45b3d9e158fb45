"""One configuration of the event-driven march: an exact linear first-order system.

A configuration says which constraint unknowns are *active*: open contacts, yielding plastic
multipliers, slipping friction multipliers (the set ``O``: their constraint function is held at
zero, the unknown is free), and which are *inactive* (the set ``C``: a closed contact is held at
``v_i = 0``, an inactive rate unknown at its frozen value ``f_i``, the multiplier reached when it
last stopped). With the row map ``P`` of the law (:mod:`unilateral.constraints`; ``P = I`` but for
friction rows), the unknowns ``x = (u, v_O)`` obey the linear system

    M~ x'' + C~ x' + K~ x = (q(t) + F_C f, -(P~ g)_O - (P~ H)_OC f)

    M~ = [[M, 0], [0, 0]],  C~ = [[C, -F_vO], [-(P~ F_v^T)_O, (P~ H_v)_OO]],
    K~ = [[K, -F_O], [-(P~ F^T)_O, (P~ H)_OO]]

(the second block row is ``-(P psi)_O = 0``; ``P~`` is ``P`` with its columns of other active
unknowns dropped, whose ``psi`` is zero; ``f = 0`` for closed contacts). As in
:mod:`unilateral.modal_dense`, orthonormal coordinates split ``x`` by its dynamics: ``T2`` the
range of ``M~`` (second order), ``T1`` the range of ``C~`` without mass (first order: a massless
foundation on dashpots, the gap of an open Kelvin contact), ``T0`` neither (condensed
statically, exactly). The state is ``y = (a2, a1, a2')`` and, with the load generator
``z' = S z`` (:mod:`unilateral.march.event_load`) and the frozen values of the rate unknowns
(``f' = 0``), the augmented system ``Y = (y, z, f)``, ``Y' = A Y`` is integrated exactly by
``expm``. Every output (u, u', v, v', the constraint functions) is a linear map of ``Y``.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

#: Eigenvalues below this fraction of the largest count as zero (mass, damping).
RANK_TOL = 1e-12
#: A condensed stiffness whose scaled condition number exceeds this is singular.
MAX_CONDITION = 1.0 / (64 * np.finfo(float).eps)


class Config:
    """The exact linear system of one configuration.

    Parameters
    ----------
    mats : (M, C, K, F, F_v, H, H_v, g) dense arrays
    gen : LoadGenerator
    open_mask : (m,) bool, the active unknowns
    law : StepLaw, the rate mask and the row map ``P``

    Attributes
    ----------
    open : (m,) bool
    A : (NY, NY) augmented system matrix, ``NY = ny + nz``; ``Y = (y, z, f)`` with ``z`` the
        load generator's state (``Y[ny:ny + gen.size]``) and ``f`` the frozen values of the rate
        unknowns (``Y[ny + gen.size:]``)
    U, UD, V, VD, PSI, E : output maps (rows, NY) of u, u', v, v', the constraint functions
        ``P psi`` and the event functions ``e``: ``P psi`` for inactive unknowns, ``-v_i`` for open
        contacts, ``-v_i'`` for active rate unknowns (``e <= 0`` is admissible)
    """

    def __init__(self, mats, gen, open_mask, law):
        M, C, K, F, Fv, H, Hv, g = mats
        n, m = K.shape[0], F.shape[1]
        self.open = np.asarray(open_mask, dtype=bool).copy()
        self.rate = np.asarray(law.rate, dtype=bool)
        O = np.flatnonzero(self.open)
        Mt, Ct, Kt, R, S = _augmented(mats, gen, self.open, law)
        T = _coordinates(Mt, Ct)
        T2, T1, T0 = T
        solve0 = _condensed_solver(T0.T @ Kt @ T0, law.P is None, O)
        Ta, X0a, X0z, Kc, Rc = _condensation(Kt, R, T, solve0)
        at = _Indices(T2.shape[1], T1.shape[1], S.shape[0])
        A, L1 = _state_matrix(Mt, Ct, (T2, Ta), (Kc, Rc, S), at)
        Xo, Xd = _coordinate_maps(T, (Kt, R, S), (solve0, X0a, X0z, L1), at)
        self.U, self.UD = Xo[:n], Xd[:n]
        self.V = np.zeros((m, at.NY))
        self.VD = np.zeros((m, at.NY))
        self.V[O], self.VD[O] = Xo[n:], Xd[n:]
        self.V[:, at.iz[gen.size:]] += _frozen(self.open, self.rate)
        PSI = F.T @ self.U + Fv.T @ self.UD - H @ self.V - Hv @ self.VD
        PSI[:, at.iz[0]] -= g
        if law.P is not None:
            PSI = law.P @ PSI
        PSI[O] = 0.0
        self.PSI = PSI
        self.E = np.where(self.open[:, None], np.where(self.rate[:, None], -self.VD, -self.V), PSI)
        self.A = A
        self.T2, self.T1 = T2, T1
        self.n, self.ny, self.nz = n, at.ny, at.nz
        self.O = O
        lam = np.linalg.eigvals(A[:at.ny, :at.ny]) if at.ny else np.zeros(0)
        self.max_frequency = float(np.max(np.abs(lam.imag), initial=0.0))
        self.max_rate = float(np.max(np.abs(lam), initial=0.0))
        self._cache = {}
        self._spectral = _UNSET

    def spectral(self):
        """The modal split of ``Y`` used to bound the event functions between sparse samples
        (:class:`Spectral`, computed on first use and kept), or None when the structural block
        ``A[:ny, :ny]`` is not safely diagonalisable (defective, ill-conditioned eigenvectors, an
        eigenvalue shared with the load generator): the march then samples as finely as before."""
        if self._spectral is _UNSET:
            self._spectral = _spectral(self.A, self.E, self.ny)
        return self._spectral

    def state_from(self, u, udot, v, z) -> np.ndarray:
        """``Y`` from the continuous quantities: u, the massive part of u', v, the load state z.

        The rate unknowns are frozen at their values ``v`` (used where they are inactive).
        """
        x = np.concatenate([u, v[self.O]])
        xd = np.concatenate([udot, np.zeros(self.O.size)])
        return np.concatenate([self.T2.T @ x, self.T1.T @ x, self.T2.T @ xd, z, v[self.rate]])

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


_UNSET = object()
#: Largest condition number of the eigenvector matrix for which the modal bounds are used.
MAX_MODAL_CONDITION = 1e8


class Spectral:
    """The exact modal split of a configuration's solution, for bounds of the event functions.

    With ``A = [[Ayy, Ayz], [0, S]]`` (the structure ``y`` driven by the load generator and the
    frozen values ``z``) and ``Ayy = V diag(lam) V^-1``, the solution from ``Y`` is

        Y(t) = sum_k (V_k, 0) c_k exp(lam_k t) + X exp(S t) z,   c = Wy y + Wz z,  X = [[Gamma], [I]]

    (``Ayy Gamma - Gamma S = -Ayz``, so ``A X = X S``; ``Gamma = -V Wz``), and an event function
    ``e_i = E_i Y`` is ``sum_k (E_i V_k) c_k exp(lam_k t) + (E_i X) z(t)``: every mode's share of
    it is bounded by ``|E_i V_k| |c_k|`` (times ``exp(Re lam_k t)`` if that grows), its second
    derivative by ``|lam_k|^2`` times that, and the load's share's second derivative by
    ``|E_i X S^2| |z(t)|``. The modes are sorted by increasing ``|lam|``.

    Attributes
    ----------
    mag2 : (ny,) ``|lam_k|^2``;  growth : (ny,) ``max(Re lam_k, 0)``, max_growth its largest
    W : (ny, NY) complex ``[Wy, Wz]``, the modal coordinates ``c = W Y``; absW its absolute values
        (for the round-off of ``c``)
    absEV : (m, ny) ``|E_y V|``;  absEXS2 : (m, nz) ``|E X S^2|``
    condition : the condition number (1-norm) of ``V``
    """

    def __init__(self, lam, V, Wy, Wz, E, S, condition):
        ny = lam.size
        order = np.argsort(np.abs(lam), kind="stable")
        lam, V, Wy, Wz = lam[order], V[:, order], Wy[order], Wz[order]
        self.mag2 = np.abs(lam) ** 2
        self.growth = np.maximum(lam.real, 0.0)
        self.max_growth = float(self.growth.max(initial=0.0))
        self.W = np.hstack([Wy, Wz])
        self.absW = np.abs(self.W)
        self.absEV = np.abs(E[:, :ny] @ V)
        EX = E[:, :ny] @ (-(V @ Wz)).real + E[:, ny:]
        self.absEXS2 = np.abs(EX @ S @ S)
        self.condition = float(condition)


def _spectral(A, E, ny):
    """:class:`Spectral` of the augmented matrix ``A`` with ``ny`` structural states, or None."""
    if ny == 0 or not np.all(np.isfinite(A)):
        return None
    Ayy, Ayz, S = A[:ny, :ny], A[:ny, ny:], A[ny:, ny:]
    try:
        lam, V = np.linalg.eig(Ayy)
        Wy = np.linalg.inv(V)
    except np.linalg.LinAlgError:
        return None
    condition = np.linalg.norm(V, 1) * np.linalg.norm(Wy, 1)
    if not np.isfinite(condition) or condition > MAX_MODAL_CONDITION:
        return None
    nz = S.shape[0]
    WA = Wy @ Ayz
    Wz = np.zeros((ny, nz), dtype=complex)
    if nz:
        mu = np.linalg.eigvals(S) if np.any(S) else np.zeros(nz)
        size = max(np.abs(lam).max(initial=0.0), np.abs(S).max(initial=0.0), 1e-300)
        # an eigenvalue shared with the load generator (a free body under a constant load): no split
        if np.min(np.abs(lam[:, None] - mu[None, :])) <= 1e-8 * size:
            return None
        eye = np.eye(nz)
        for k in range(ny):
            Wz[k] = np.linalg.solve((lam[k] * eye - S).T, WA[k])
        if not np.all(np.isfinite(Wz)):
            return None
    return Spectral(lam, V, Wy, Wz, E, S, condition)


def _frozen(open_mask, rate) -> np.ndarray:
    """``W`` (m, r): the values ``W f`` of the unknowns held at the frozen values ``f`` of the r rate
    unknowns (the inactive ones; zero rows for the others)."""
    idx = np.flatnonzero(rate)
    W = np.zeros((rate.size, idx.size))
    W[idx, np.arange(idx.size)] = ~open_mask[idx]
    return W


def _active_rows(P, open_mask) -> np.ndarray:
    """``P~_O`` (o, m): the rows of ``P`` of the active unknowns, without the columns of the other
    active unknowns (their ``psi`` is held at zero)."""
    O = np.flatnonzero(open_mask)
    if P is None:
        return np.eye(open_mask.size)[O]
    rows = P[O].copy()
    rows[:, O] = np.eye(O.size)
    return rows


class _Indices:
    """The index maps of ``Y = (a2, a1, w2, z, f)`` (``a2`` the coordinates with mass (n2), ``a1``
    those with damping only (n1), ``w2 = a2'``, ``z`` and ``f`` the load generator's state and the
    frozen rate unknowns (nz)): ``i2``, ``i1``, ``iw``, ``iz``, ``ia = (i2, i1)``; ``ny = 2 n2 + n1``,
    ``NY = ny + nz``."""

    def __init__(self, n2, n1, nz):
        self.n2, self.n1, self.nz = n2, n1, nz
        self.ny = 2 * n2 + n1
        self.NY = self.ny + nz
        self.i2, self.i1, self.iw, self.iz = (np.arange(n2), n2 + np.arange(n1), n2 + n1 + np.arange(n2),
                                              self.ny + np.arange(nz))
        self.ia = np.concatenate([self.i2, self.i1])


def _coordinates(Mt, Ct):
    """Orthonormal bases ``(T2, T1, T0)`` (N, n2), (N, n1), (N, n0) of the coordinates of the
    augmented system with mass, with damping but no mass, and with neither (statically condensed).

    Raises
    ------
    ValueError
        ``M~`` or ``C~`` (with the Kelvin terms of the open contacts) not positive semidefinite.
    """
    N = Mt.shape[0]
    T2, Tn = _split(Mt, np.eye(N), "the mass matrix")
    T1, T0 = _split(Ct, Tn, "the damping matrix with the open Kelvin contacts")
    if T0.shape[1] and np.abs(Ct @ T0).max() > 1e-9 * max(np.abs(Ct).max(), 1e-300):
        raise ValueError("the damping matrix (with the Kelvin terms of the open contacts) is not "
                         "positive semidefinite; method='event' needs C, H_v PSD")
    return T2, T1, T0


def _condensation(Kt, R, T, solve0):
    """The static condensation of the coordinates ``T0``: ``a0 = K00^-1 (T0^T R z - K0a a)`` with
    ``a = (a2, a1)`` on ``Ta = [T2, T1]`` (N, n2 + n1), ``K~`` (N, N) and the load map ``R``
    (N, nz); ``solve0`` is ``X -> K00^-1 X`` (:func:`_condensed_solver`).

    Returns ``(Ta, X0a, X0z, Kc, Rc)``: ``X0a = K00^-1 K0a`` (n0, n2 + n1), ``X0z = K00^-1 T0^T R``
    (n0, nz), the condensed stiffness ``Kc`` (n2 + n1, n2 + n1) and load map ``Rc`` (n2 + n1, nz).
    """
    T2, T1, T0 = T
    Kb = lambda A_, B_: A_.T @ Kt @ B_
    # condensation of T0:  a0 = K00^-1 (T0^T R z - K02 a2 - K01 a1)
    Ta = np.hstack([T2, T1])
    X0a = solve0(Kb(T0, Ta))                                  # (n0, n2+n1)
    X0z = solve0(T0.T @ R)                                    # (n0, nz)
    Kc = Kb(Ta, Ta) - Kb(Ta, T0) @ X0a
    Rc = Ta.T @ R - Kb(Ta, T0) @ X0z
    return Ta, X0a, X0z, Kc, Rc


def _state_matrix(Mt, Ct, bases, condensed, at: _Indices):
    """The system matrix ``A`` (NY, NY) of ``Y' = A Y`` and the map ``L1`` (n1, NY) of ``a1'``.

    ``bases = (T2, Ta)``, ``condensed = (Kc, Rc, S)`` of :func:`_condensation` and the generator's
    ``z' = S z``; ``at`` the index maps. The rows: ``a2' = w2``, ``a1' = C11^-1 (Rc1 z - Kc1a a -
    C12 w2)``, ``w2' = M22^-1 (Rc2 z - Kc2a a - C22 w2 - C21 a1')``, ``z' = S z``, ``f' = 0``.
    """
    T2, Ta = bases
    Kc, Rc, S = condensed
    n2, n1, NY, ia, iw, iz = at.n2, at.n1, at.NY, at.ia, at.iw, at.iz
    Ca = Ta.T @ Ct @ Ta
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
    A[at.i2, iw] = 1.0
    A[at.i1] = L1
    A[iw] = L2
    A[np.ix_(iz, iz)] = S
    return A, L1


def _coordinate_maps(T, system, condensed, at: _Indices):
    """The maps ``Xo``, ``Xd`` (N, NY) of the augmented coordinates and their rates from ``Y``:
    ``T2 a2 + T1 a1 + T0 a0`` and the same of the rates, with ``a0' = K00^-1 (T0^T R S z - K02 w2 -
    K01 a1')``.

    ``T = (T2, T1, T0)``, ``system = (K~, R, S)``, ``condensed = (solve0, X0a, X0z, L1)`` of
    :func:`_condensation` and :func:`_state_matrix`; ``at`` the index maps.
    """
    T2, T1, T0 = T
    Kt, R, S = system
    solve0, X0a, X0z, L1 = condensed
    n0, n2, NY, ia, iz = T0.shape[1], at.n2, at.NY, at.ia, at.iz
    P2, P1, PW = (np.eye(NY)[idx] for idx in (at.i2, at.i1, at.iw))
    L0 = np.zeros((n0, NY))
    L0[:, ia] = -X0a
    L0[:, iz] = X0z
    # a0' = K00^-1 (T0^T R S z - K02 w2 - K01 a1')
    L0d = np.zeros((n0, NY))
    L0d[:, iz] = solve0(T0.T @ R @ S)
    if n0:
        K0a = T0.T @ Kt @ np.hstack([T2, T1])
        L0d -= solve0(K0a[:, :n2] @ PW + K0a[:, n2:] @ L1)
    Xo = T2 @ P2 + T1 @ P1 + T0 @ L0
    Xd = T2 @ PW + T1 @ L1 + T0 @ L0d
    return Xo, Xd


def _augmented(mats, gen, open_mask, law):
    """``M~, C~, K~`` (N, N), the load map ``R`` (N, nz) of ``(z, f)`` and ``S`` (nz, nz) of ``z' = S z``,
    ``f' = 0`` (see the module docstring)."""
    M, C, K, F, Fv, H, Hv, g = mats
    n = K.shape[0]
    O = np.flatnonzero(open_mask)
    N = n + O.size
    Pt = _active_rows(law.P, open_mask)
    W = _frozen(open_mask, law.rate)
    Mt, Ct, Kt = np.zeros((N, N)), np.zeros((N, N)), np.zeros((N, N))
    Mt[:n, :n] = M
    Ct[:n, :n], Ct[:n, n:], Ct[n:, :n], Ct[n:, n:] = C, -Fv[:, O], -Pt @ Fv.T, (Pt @ Hv)[:, O]
    Kt[:n, :n], Kt[:n, n:], Kt[n:, :n], Kt[n:, n:] = K, -F[:, O], -Pt @ F.T, (Pt @ H)[:, O]
    nq, r = gen.size, W.shape[1]
    R = np.zeros((N, nq + r))
    R[:n, :nq], R[:n, nq:] = gen.Gq, F @ W
    R[n:, 0], R[n:, nq:] = -Pt @ g, -Pt @ H @ W
    S = np.zeros((nq + r, nq + r))
    S[:nq, :nq] = gen.S
    return Mt, Ct, Kt, R, S


def _condensed_solver(K00, symmetric, O):
    """``X -> K00^-1 X`` for the statically condensed coordinates.

    Raises
    ------
    ValueError
        ``K00`` is singular: coordinates without mass, damping or stiffness, or two dependent
        active unknowns (both faces of a yield or slip pair).
    """
    if K00.shape[0] == 0:
        return lambda X: np.zeros((0,) + np.shape(X)[1:])
    message = ("a configuration leaves coordinates without mass, damping or stiffness (active constraints "
               f"{O.tolist()}): the structure becomes a mechanism there, an open contact has no stiffness H "
               "(a rigid contact), or two active unknowns are dependent; method='event' needs H_OO > 0 or a "
               "Kelvin dashpot on every open contact")
    row = np.abs(K00).max(axis=1)
    if not np.all(row > 0):
        raise ValueError(message)
    s = 1.0 / np.sqrt(row)
    if np.linalg.cond(s[:, None] * K00 * s[None, :]) > MAX_CONDITION:
        raise ValueError(message)
    if not symmetric:
        lu = sla.lu_factor(K00)
        return lambda X: sla.lu_solve(lu, X)
    try:
        chol = sla.cho_factor(0.5 * (K00 + K00.T))
    except sla.LinAlgError:
        raise ValueError(message) from None
    return lambda X: sla.cho_solve(chol, X)


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
