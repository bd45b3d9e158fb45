"""Penalty-stiff models: solve in coordinates that separate the stiff strains, report in ``u``.

A rigid part modelled by penalty-stiff elements (beams with ``EI = 1e18``, ``cond(K) ~ 1e13``)
leaves the assembled ``K = G E G^T`` with the soft stiffness (soil, columns) only to ``eps`` times the
stiffness ratio: 2e-4 relative errors in the response, an asymmetric static state under a symmetric
load, and a pole-residue form that cannot be checked. With the natural form at hand
(:meth:`Model.from_natural`), :func:`unilateral.linalg.stiff_split` gives coordinates ``u = T x``
in which the stiff strains are coordinates of their own; the model in ``x``
(``T^T M T, T^T C T, K_x, T^T F, ...``) is an exact congruence of the given one, assembled without
mixing stiff and soft terms, and every method solves it to round-off. ``v``, ``psi`` and
``Lambda(s)`` are the same in both coordinates; ``u`` and ``udot`` are mapped back.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V
from ..linalg import dense, stiff_split
from . import Model, NaturalForm


#: Attribute set on a model in separated coordinates (:func:`_conditioned_model`).
CONDITIONED_MARK = "_stiff_conditioned"


class StiffCoordinates:
    """A model in stiff-separated coordinates and the maps of loads, initial values and results.

    Build with :meth:`of`; ``None`` means the model needs no split.

    Attributes
    ----------
    model : Model, the given one;  split : StiffSplit;  conditioned : Model (in ``x``)
    """

    def __init__(self, model, split):
        self.model, self.split = model, split
        self.conditioned = _conditioned_model(model, split)

    @classmethod
    def of(cls, model) -> StiffCoordinates | None:
        """The split of a model with a natural form (a :class:`Model` built from elements), or None
        if it has none or needs none.

        A model this class conditioned is already in separated coordinates: it needs no split
        (conditioning is idempotent), so its static state and its solution do not condition it again.
        """
        nat = getattr(model, "natural", None)
        if nat is None or getattr(model, CONDITIONED_MARK, False):
            return None
        massless = dense_diagonal(model.M) == 0
        split = stiff_split(nat.G, nat.E, nat.B, nat.E_v, massless=massless)
        if split is None:
            return None
        coordinates = cls(model, split)
        # a split whose stiff strains move DOFs with mass (every element "stiff" beside one negligible
        # one, e.g. a yield link of k = 1e-8) spreads the mass over more coordinates than it has rank:
        # the assembled model is then the better conditioned one (its K is not stiff beside anything
        # that matters)
        return coordinates if _mass_well_posed(coordinates.conditioned.M) else None

    # ------------------------------------------------------------------ into x
    def load(self, load, N):
        """The load in ``x``: ``T^T q`` for a LoadHistory, a callable or an array (N+1, n)."""
        if load is None:
            return None
        n, Tt = self.model.n, self.split.T.T
        if callable(getattr(load, "grid_factors", None)):
            from ..loads import LoadHistory

            if load.n != n:
                raise ValueError(f"load has {load.n} DOFs but the model has n = {n}")
            return LoadHistory(Tt @ load.constant, [(Tt @ vector, f) for vector, f in load.terms],
                               sampling=getattr(load, "sampling", "hat"))
        if callable(load):
            def q(t):
                value = np.asarray(load(t), dtype=float)
                if value.shape != (n,):
                    raise ValueError(f"load(t) must return shape ({n},), got shape {value.shape} at t={t}")
                return Tt @ value
            return q
        arr = V.as_matrix("load", load, (None, n), allow_sparse=False)
        return arr[: N + 1] @ self.split.T

    def initial(self, initial):
        """Given initial values in ``x`` (``u0``, ``udot0``); ``"static"``/``"rest"`` unchanged."""
        if not isinstance(initial, dict):
            return initial
        out = dict(initial)
        for key in ("u0", "udot0"):
            if key in initial:
                out[key] = self.split.T_inv @ V.as_vector(f"initial[{key!r}]", initial[key], self.model.n)
        return out

    # ------------------------------------------------------------------ back to u
    def solution(self, sol):
        """``sol`` of the conditioned model with ``u = T x``, ``udot = T xdot`` and the DOF names."""
        T = self.split.T
        if sol.u is not None:
            sol.u = sol.u @ T.T
        if sol.udot is not None:
            sol.udot = sol.udot @ T.T
        sol.dof_names = list(self.model.dof_names)
        sol.stats["stiff_coordinates"] = {
            "stiff_rows": int(self.split.stiff_rows.size), "soft_coordinates": int(self.split.n_soft),
            "stiffness_ratio": float(self.split.ratio),
            "cond_K": float(np.linalg.cond(dense(self.conditioned.K))),
        }
        return sol


def _conditioned_model(model, split) -> Model:
    """The congruent model in ``x = T^-1 u`` (same ``Lambda(s)``, ``H``, ``g``)."""
    nat, T, Gt = model.natural, split.T, split.Gt
    congruent = lambda A: None if A is None else _clip_round_off(T.T @ (dense(A) @ T))
    EB = dense(nat.E @ nat.B)
    F = Gt.T @ EB                     # the stiff rows of E B are zero: no stiff term enters
    F_v = None if model.F_v is None else Gt.T @ dense(nat.E_v @ nat.B)
    q_imposed = _imposed(model, nat, Gt)
    g = model.g(0.0) if model.g_is_constant else model.g
    K_geometric = congruent(nat.K_geometric)        # P-Delta: not in G E G^T, added to the split's K
    conditioned_nat = NaturalForm(G=Gt.T, E=nat.E, B=nat.B, A=nat.A, r=nat.r, theta=nat.theta,
                                  E_v=nat.E_v, theta_rate=nat.theta_rate, K_geometric=K_geometric)
    K = split.K if K_geometric is None else split.K + K_geometric
    conditioned = Model(M=congruent(model.M), K=K, F=F, H=model.H, C=congruent(model.C), g=g,
                        F_v=F_v, H_v=model.H_v, q_imposed=q_imposed,
                        dof_names=_names(model, split),
                        constraint_names=list(model.constraint_names), natural=conditioned_nat,
                        families=model.families)
    setattr(conditioned, CONDITIONED_MARK, True)
    return conditioned


def _names(model, split):
    """The masters keep their names; the stiff strains are ``"stiff:<strain row>"``."""
    names = [model.dof_names[i] for i in split.masters]
    return names + [f"stiff:{i}" for i in split.stiff_rows[: model.n - split.n_soft]]


def _imposed(model, nat, Gt):
    """``Gt^T (E theta + E_v theta')``: the imposed-strain load in ``x`` without stiff round-off."""
    def at(t):
        out = Gt.T @ np.asarray(nat.E @ nat.theta(t)).ravel()
        if nat.E_v is not None and nat.theta_rate is not None:
            out = out + Gt.T @ np.asarray(nat.E_v @ nat.theta_rate(t)).ravel()
        return out
    return at(0.0) if model.q_imposed_is_constant else at


def _mass_well_posed(M) -> bool:
    """Whether ``M`` is positive definite on its coordinates with mass (a positive diagonal).

    The time-stepping schemes factorise that block for the initial acceleration.
    """
    M = dense(M)
    massive = np.flatnonzero(np.diag(M) > 0)
    if massive.size == 0:
        return True
    block = M[np.ix_(massive, massive)]
    eig = np.linalg.eigvalsh(0.5 * (block + block.T))
    return bool(eig[0] > 1e-12 * eig[-1])


def dense_diagonal(A) -> np.ndarray:
    """The diagonal (n,) of a dense or sparse matrix."""
    return np.asarray(A.diagonal() if hasattr(A, "tocsr") else np.diag(A), dtype=float)


#: A congruent mass or damping matrix's diagonal within this fraction of its largest is round-off.
ROUND_OFF = 1e-12


def _clip_round_off(A) -> np.ndarray:
    """The congruence ``T^T A T`` symmetrised, its round-off on massless coordinates made zero.

    A coordinate whose diagonal is within :data:`ROUND_OFF` of the largest (``|A_ii| <= 1e-12 max|A_jj|``,
    e.g. ``-9.7e-17`` where a stiff strain moves only massless DOFs) and whose row is within
    ``sqrt(ROUND_OFF)`` of it (as a positive semidefinite matrix's row is) is zero in exact arithmetic:
    its row and column are set to zero, so that a mass matrix keeps a non-negative diagonal.

    Parameters
    ----------
    A : (n, n) ndarray

    Returns
    -------
    (n, n) ndarray, symmetric
    """
    A = 0.5 * (A + A.T)
    diag = np.diag(A)
    scale = float(np.max(np.abs(diag), initial=0.0))
    if scale == 0.0 or not np.isfinite(scale):
        return A
    tiny = (np.abs(diag) <= ROUND_OFF * scale) & (np.max(np.abs(A), axis=1) <= np.sqrt(ROUND_OFF) * scale)
    if np.any(tiny):
        A = A.copy()
        A[tiny, :] = 0.0
        A[:, tiny] = 0.0
    return A
