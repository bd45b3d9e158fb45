"""The rate problem at a point of the path: which constraints keep loading, which unload.

Along the path parameter ``t`` (the load factor under load control, the control displacement's
distance from the gravity state under displacement control) the rates per unit ``t`` are

    psi' = b - W v',        lambda' = alpha - beta . v',

with, under load control (``lambda' = s``, the sense ``s = +-1``), ``b = s F^T K^-1 p``,
``W = Lambda0``, and under
displacement control (``u_c' = s``, the sense ``s = +-1``, ``u_c' = lambda' dp + c . v'``)

    lambda' = (s - c . v') / dp,    b = s F^T K^-1 p / dp,    W = Lambda0 + (F^T K^-1 p) c^T / dp.

The constraint functions are ``phi = P psi``, so ``phi' = P b - P W v'``. A constraint is *open*
(a contact with ``v > 0``, ``phi = 0``: its rate ``v'`` is free and ``phi' = 0``), *on its surface*
(``phi = 0`` and, for a contact, ``v = 0``: ``v' >= 0``, ``-phi' >= 0``, ``v' phi' = 0``) or
*inactive* (``phi < 0``: ``v' = 0``). Eliminating the open rates leaves a small LCP in the rates of
the constraints on their surface (Maier's incremental problem), solved by the library's LCP
solvers (block principal pivoting, Lemke as the fallback).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..lcp import get_lcp_solver

#: The tangent is singular (a mechanism) when the smallest eigenvalue (singular value) of the
#: active block of ``P W`` is below this fraction of the size of the terms that cancel in it.
MECHANISM_TOL = 1e-9


@dataclass(frozen=True)
class RateForm:
    """The rates per unit of the path parameter: ``psi' = b - W v'``, ``lambda' = alpha - beta . v'``.

    Attributes
    ----------
    b : (m,) force units per unit t
    W : (m, m) force units per unit of v
    alpha : float, load factor per unit t at fixed v
    beta : (m,) load factor per unit of v
    P : (m, m) row map of the constraint functions
    scale : (m, m) nonnegative, the size of the terms that cancel in ``P W`` (for the mechanism test)
    symmetric : bool, ``P W`` is symmetric (load control without friction)
    """

    b: np.ndarray
    W: np.ndarray
    alpha: float
    beta: np.ndarray
    P: np.ndarray
    scale: np.ndarray
    symmetric: bool


def rate_form(problem, control: str, sense: float) -> RateForm:
    """The :class:`RateForm` of a :class:`~unilateral.pushover.problem.ParametricLCP`.

    Parameters
    ----------
    problem : ParametricLCP
    control : ``"load"`` or ``"displacement"``
    sense : +1.0 or -1.0, the sense of the control displacement (displacement control) or of the
        load factor (load control)
    """
    m = problem.Lambda0.shape[0]
    size = np.abs(problem.model.H) + np.abs(problem.flexibility)
    identity = np.array_equal(problem.P, np.eye(m))
    if control == "load":
        b, W, alpha, beta = sense * problem.psiP, problem.Lambda0, sense, np.zeros(m)
    else:
        coupling = np.outer(problem.psiP, problem.c) / problem.dp
        b, W = sense * problem.psiP / problem.dp, problem.Lambda0 + coupling
        alpha, beta = sense / problem.dp, problem.c / problem.dp
        size = size + np.abs(coupling)
    scale = np.abs(problem.P) @ size
    return RateForm(b=b, W=W, alpha=float(alpha), beta=beta, P=problem.P, scale=scale,
                    symmetric=identity and control == "load")


@dataclass
class Rates:
    """Solution of the rate problem at one point.

    Attributes
    ----------
    vdot : (m,) rates of the constraint unknowns per unit t
    phidot : (m,) rates of the constraint functions per unit t
    lamdot : float, rate of the load factor per unit t
    active : (m,) bool, the open constraints and those on their surface with ``v' > 0``
    iterations : int, pivots of the rate LCP
    failure : str, empty on success; else why the rate problem has no (regular) solution
    singular : bool, the tangent of the active set is singular or not positive (a mechanism)
    """

    vdot: np.ndarray
    phidot: np.ndarray
    lamdot: float
    active: np.ndarray
    iterations: int = 0
    failure: str = ""
    singular: bool = False


def solve_rates(form: RateForm, opened, touching, solver="bpp") -> Rates:
    """Solve the rate problem for the open constraints ``opened`` and those on their surface ``touching``.

    Parameters
    ----------
    form : RateForm
    opened : (m,) bool, open contacts (free rates, ``phi' = 0``)
    touching : (m,) bool, constraints on their surface (complementary rates), disjoint from ``opened``
    solver : str or LCPSolver, the solver of the rate LCP (Lemke is tried if it fails)

    Returns
    -------
    Rates
    """
    A, r = form.P @ form.W, form.P @ form.b
    m = r.size
    O, T = np.flatnonzero(opened), np.flatnonzero(touching)
    vdot = np.zeros(m)
    XT, Xr = np.zeros((O.size, T.size)), np.zeros(O.size)
    if O.size:
        AOO = A[np.ix_(O, O)]
        if _smallest(AOO, form.scale[np.ix_(O, O)], form.symmetric) <= MECHANISM_TOL:
            return Rates(vdot, r.copy(), form.alpha, opened.copy(), failure="the open contacts' block is singular",
                         singular=True)
        X = np.linalg.solve(AOO, np.column_stack([A[np.ix_(O, T)], r[O]]))
        XT, Xr = X[:, :T.size], X[:, T.size]
    iterations = 0
    if T.size:
        Ms = A[np.ix_(T, T)] - A[np.ix_(T, O)] @ XT
        q = A[np.ix_(T, O)] @ Xr - r[T]
        res = get_lcp_solver(solver).solve(Ms, q)
        iterations = res.iterations
        if not res.success:
            res = get_lcp_solver("lemke").solve(Ms, q)
            iterations += res.iterations
        if not res.success:
            return Rates(vdot, r.copy(), form.alpha, opened.copy(), iterations,
                         failure="the rate LCP has no solution", singular=True)
        vdot[T] = res.v
    if O.size:
        vdot[O] = Xr - XT @ vdot[T]
    active = opened | (touching & (vdot > 0.0))
    idx = np.flatnonzero(active)
    singular = bool(idx.size) and _smallest(A[np.ix_(idx, idx)], form.scale[np.ix_(idx, idx)],
                                             form.symmetric) <= MECHANISM_TOL
    return Rates(vdot=vdot, phidot=r - A @ vdot, lamdot=float(form.alpha - form.beta @ vdot), active=active,
                 iterations=iterations, failure="the tangent is singular" if singular else "", singular=singular)


def _smallest(block, scale, symmetric) -> float:
    """The smallest eigenvalue (``symmetric``) or singular value of ``block`` over the size of its terms."""
    size = max(float(np.max(scale)), np.finfo(float).tiny)
    if symmetric:
        return float(np.linalg.eigvalsh(0.5 * (block + block.T))[0]) / size
    return float(np.linalg.svd(block, compute_uv=False)[-1]) / size
