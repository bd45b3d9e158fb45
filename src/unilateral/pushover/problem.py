"""The parametric static LCP of a pushover: the structure under gravity plus ``lambda`` times a pattern.

Statics of the model (Liolios 1990, eqs. 15-16 without inertia):

    K u = q0 + lambda p + F v,        psi = F^T u - H v - g,

``q0`` the gravity load (plus the load ``q_imposed`` of imposed strains, gaps), ``p`` the lateral
pattern and ``lambda`` the load factor. With ``u`` eliminated about the gravity state
``(u0, v0)`` (``K u0 = q0 + F v0``),

    u   = u0 + lambda K^-1 p + K^-1 F (v - v0),
    psi = psi0 + lambda F^T K^-1 p - Lambda0 (v - v0),      Lambda0 = H - F^T K^-1 F,

so ``psi`` is affine in ``(lambda, v)``; the constraint functions are ``phi = P psi`` (``P`` the row
map of friction, identity otherwise). A control DOF ``u_c = e^T u`` is affine too:
``u_c = u_c0 + lambda e^T K^-1 p + (K^-1 F)^T e . (v - v0)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..initial import static_state
from ..lcp import get_lcp_solver
from ..linalg import Factorization, dense, transpose_times


@dataclass
class ParametricLCP:
    """The pushover's static problem, condensed on the constraint unknowns.

    Attributes
    ----------
    model : Model
        The problem (``K``, ``F``, ``H``, ``g`` and the constraint law ``model.law``).
    p : (n,) lateral load pattern (force units; the load is ``lambda p``)
    q0 : (n,) gravity load plus ``q_imposed`` (force units)
    e : (n,) control vector: the control displacement is ``u_c = e . u`` (length or rad)
    u0 : (n,) displacements of the gravity state
    v0 : (m,) constraint unknowns of the gravity state
    up : (n,) ``K^-1 p``, displacements per unit load factor
    KiF : (n, m) ``K^-1 F``
    Lambda0 : (m, m) ``H - F^T K^-1 F`` (symmetric)
    flexibility : (m, m) ``F^T K^-1 F`` (the scale of the cancellation in ``Lambda0``)
    psiP : (m,) ``F^T K^-1 p``, ``psi`` per unit load factor at fixed ``v``
    c : (m,) ``(K^-1 F)^T e``, control displacement per unit of ``v``
    dp : float, ``e^T K^-1 p``, control displacement per unit load factor at fixed ``v``
    P : (m, m) row map of the constraint functions (identity without friction)
    gravity_iterations : int, pivots of the static LCP of the gravity state
    """

    model: object
    p: np.ndarray
    q0: np.ndarray
    e: np.ndarray
    u0: np.ndarray
    v0: np.ndarray
    up: np.ndarray
    KiF: np.ndarray
    Lambda0: np.ndarray
    flexibility: np.ndarray
    psiP: np.ndarray
    c: np.ndarray
    dp: float
    P: np.ndarray
    gravity_iterations: int = 0

    @property
    def rate(self) -> np.ndarray:
        """(m,) bool: unknowns of rate law (plastic multipliers, slips); the others are contacts."""
        return self.model.law.rate

    @property
    def names(self) -> list:
        """(m,) constraint names of the model."""
        return list(self.model.constraint_names)

    def u(self, lam, v) -> np.ndarray:
        """Displacements (n,) at load factor ``lam`` and constraint unknowns ``v`` (m,)."""
        return self.u0 + lam * self.up + self.KiF @ (np.asarray(v) - self.v0)

    def psi(self, u, v) -> np.ndarray:
        """Associated constraint values ``psi = F^T u - H v - g`` (m,) (force units)."""
        return transpose_times(self.model.F, u) - self.model.H @ v - self.model.g(0.0)

    def phi(self, u, v) -> np.ndarray:
        """Constraint functions ``P psi`` (m,): contact reactions, yield and friction functions (<= 0)."""
        return self.P @ self.psi(u, v)

    def control(self, u) -> float:
        """Control displacement ``e . u``."""
        return float(self.e @ u)

    def residual(self, lam, u, v) -> float:
        """Relative equilibrium error ``|K u - q0 - lam p - F v| / max(|K u|, |q0 + lam p + F v|)``."""
        Ku = np.asarray(self.model.K @ u).ravel()
        rhs = self.q0 + lam * self.p + np.asarray(self.model.F @ v).ravel()
        scale = max(np.linalg.norm(Ku), np.linalg.norm(rhs), np.finfo(float).tiny)
        return float(np.linalg.norm(Ku - rhs) / scale)


def parametric_lcp(model, p, q_gravity, e, solver="bpp") -> ParametricLCP:
    """Factorise ``K``, solve the gravity state and form the condensed parametric LCP.

    Parameters
    ----------
    model : Model
        A matrix model (:class:`unilateral.Model`) with constant ``g`` and ``q_imposed``.
    p : (n,) lateral load pattern, force units
    q_gravity : (n,) gravity load, force units (zeros for none)
    e : (n,) control vector (``u_c = e . u``)
    solver : str or LCPSolver, the LCP solver of the gravity state

    Returns
    -------
    ParametricLCP

    Raises
    ------
    ValueError
        No static equilibrium under gravity (the static LCP has no solution).
    """
    if not (model.g_is_constant and model.q_imposed_is_constant):
        raise ValueError("pushover: the model's gaps or imposed-strain loads vary in time (support motions); "
                         "a pushover needs them constant")
    q0 = np.asarray(q_gravity, dtype=float) + model.q_imposed(0.0)
    lcp = get_lcp_solver(solver)
    state = static_state(model, q0, lcp)
    if state.message:
        raise ValueError(f"gravity: {state.message}")
    K = Factorization(model.K, what="K (the structure with every constraint held bilateral must be stable)")
    KiF = np.asarray(K.solve(dense(model.F)), dtype=float).reshape(model.n, model.m)
    up = np.asarray(K.solve(np.asarray(p, dtype=float)), dtype=float).ravel()
    flexibility = transpose_times(model.F, KiF)
    flexibility = 0.5 * (flexibility + flexibility.T)
    Lambda0 = model.H - flexibility
    Lambda0 = 0.5 * (Lambda0 + Lambda0.T)
    P = np.eye(model.m) if model.law.P is None else np.asarray(model.law.P, dtype=float)
    v0 = np.asarray(state.v, dtype=float)
    u0 = np.asarray(K.solve(q0 + np.asarray(model.F @ v0).ravel()), dtype=float).ravel()
    return ParametricLCP(model=model, p=np.asarray(p, dtype=float), q0=q0, e=np.asarray(e, dtype=float), u0=u0,
                         v0=v0, up=up, KiF=KiF, Lambda0=Lambda0, flexibility=flexibility,
                         psiP=transpose_times(model.F, up), c=KiF.T @ e, dp=float(e @ up), P=P,
                         gravity_iterations=int(state.lcp_iterations))
