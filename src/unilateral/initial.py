"""Initial states: the static unilateral problem, or given initial conditions (eqs. 10-12).

Statics: ``K u = q(0) + F v``, ``psi = F^T u - H v - g(0)``, complementarity. Eliminating u gives
the LCP ``w = Lambda(0) v - psiL_0 >= 0`` with ``Lambda(0) = H - F^T K^-1 F`` (positive
semidefinite) and ``psiL_0 = F^T K^-1 q(0) - g(0)``. Yield and friction unknowns
(:mod:`unilateral.constraints`) start from zero and take the static load in one increment (the
holonomic form of the rate law, exact for proportional loading); friction rows are the
constraint functions ``P psi``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _validate as V
from .lcp import BlockPrincipalPivoting, get_lcp_solver
from .linalg import Factorization, SingularMatrixError, dense, mechanism_dofs, transpose_times
from .model.stiff import StiffCoordinates


@dataclass
class InitialState:
    """Base state of the increments.

    Attributes
    ----------
    v : (m,) unilateral deformations
    psi : (m,) reactions
    u : (n,) displacements (None for kernel-only models)
    udot : (n,) velocities (None for kernel-only models)
    lcp_iterations : int
    message : str
        Empty on success; otherwise why no static equilibrium was found.
    """

    v: np.ndarray
    psi: np.ndarray
    u: np.ndarray | None = None
    udot: np.ndarray | None = None
    lcp_iterations: int = 0
    message: str = ""


def static_lcp(Lambda0, psiL0, solver) -> tuple[np.ndarray, int, str]:
    """Solve ``w = Lambda0 v - psiL0 >= 0, v >= 0, v.w = 0`` with a fallback to Lemke.

    ``Lambda0`` is only positive semidefinite when a constraint is attached to a part that
    becomes a mechanism once it opens; principal pivoting may then fail where Lemke does not.

    Returns
    -------
    v : (m,) ; iterations : int ; message : str (empty on success)
    """
    m = psiL0.shape[0]
    if m == 0:
        return np.zeros(m), 0, ""
    res = solver.solve(Lambda0, -psiL0)
    iterations = res.iterations
    if not res.success and solver.name != "lemke":
        res = get_lcp_solver("lemke", tol=solver.tol).solve(Lambda0, -psiL0)
        iterations += res.iterations
    if not res.success:
        return res.v, iterations, (
            "no static equilibrium under the load at t = 0: the static LCP has no solution "
            f"({res.message}). The load at t = 0 probably lifts the structure off all its "
            "supports; check the sign of gravity, or start from given initial conditions"
        )
    return res.v, iterations, ""


def static_state(model, q0, solver) -> InitialState:
    """Static unilateral equilibrium of a matrix model under the total load ``q0`` (n,).

    A model with penalty-stiff elements (known from its natural form) is solved in coordinates that
    separate the stiff strains (:mod:`unilateral.model.stiff`): the assembled ``K`` would keep the
    soft stiffness only to ``eps`` times the stiffness ratio. The state is kept on the model per
    ``q0`` and solver settings (:func:`unilateral.model.remembered`): a batch's analyses of one model variant
    solve it once; each call returns its own copy.
    """
    from dataclasses import replace

    from .model import remembered

    q0 = np.asarray(q0, dtype=float)
    key = ("static", q0.tobytes(), getattr(solver, "name", type(solver).__name__), getattr(solver, "tol", None),
           getattr(solver, "max_iter", None))
    state = remembered(model, key, lambda: _static_state(model, q0, solver))
    return replace(state, **{name: None if getattr(state, name) is None else getattr(state, name).copy()
                             for name in ("v", "psi", "u", "udot")})


def _static_state(model, q0, solver) -> InitialState:
    """:func:`static_state`, computed."""
    stiff = StiffCoordinates.of(model)
    if stiff is not None:
        T = stiff.split.T
        state = static_state(stiff.conditioned, T.T @ np.asarray(q0, dtype=float), solver)
        state.u, state.udot = T @ state.u, np.zeros(model.n)
        return state
    state = _static_full_space(model, q0, solver)
    if state is not None:
        return state
    try:
        K = Factorization(
            model.K, what="K (the structure with every constraint held bilateral must be stable)"
        )
    except SingularMatrixError as exc:
        moved = mechanism_dofs(model.K, list(getattr(model, "dof_names", None) or []) or None)
        if moved is None:
            raise
        raise SingularMatrixError(
            f"{exc}: the structure is a mechanism; a zero-energy mode moves the free DOFs "
            f"{', '.join(moved)} without deforming any element; add supports, bracing or rotational "
            "restraints there (or start from given initial values instead of the static state)") from None
    uq = K.solve(q0)
    Lambda0 = model.H - _flexibility(K, model.F)
    Lambda0 = 0.5 * (Lambda0 + Lambda0.T)
    psiL0 = transpose_times(model.F, uq) - model.g(0.0)
    # yield and friction from the virgin state: one increment from zero (the law of the families)
    v, iters, message = static_lcp(model.law.matrix(Lambda0), model.law.rows(psiL0), solver)
    u = uq + (K.solve(np.asarray(model.F @ v).ravel()) if np.any(v) else 0.0)
    return InitialState(v=v, psi=psiL0 - Lambda0 @ v, u=u, udot=np.zeros(model.n),
                        lcp_iterations=iters, message=message)


def _static_full_space(model, q0, solver):
    """The static state of a large sparse model with contacts by pivoting in the full space, or None.

    Where :func:`~unilateral.march.active_set.full_space_applies` and ``lcp="bpp"``: ``K u = q0 + F v`` with ``psi = F^T u - H v - g`` solved on the sparse
    ``K`` without the open constraints (:class:`~unilateral.march.active_set.ActiveSetSolver`,
    the same solution as the condensed LCP), so that ``F^T K^-1 F`` is never formed. None where
    it does not apply or does not converge (the condensed LCP then gives the solution or the
    reason there is none).
    """
    from .march.active_set import ActiveSetSolver, full_space_applies

    if not (full_space_applies(model) and isinstance(solver, BlockPrincipalPivoting)):
        return None
    zero = np.zeros(model.m)
    try:
        lcp = ActiveSetSolver(model.K, model.F, dense(model.H), 1.0, zero, max_iter=solver.max_iter or 50)
        v, psi, u, _, iterations = lcp.solve(q0, -model.g(0.0), np.zeros(model.m, dtype=bool))
    except SingularMatrixError:
        return None
    if iterations < 0:
        return None
    return InitialState(v=v, psi=psi, u=u, udot=np.zeros(model.n), lcp_iterations=iterations)


#: Right-hand sides of at most this many entries are solved at once (a large sparse model's
#: ``K^-1 F`` is formed block by block, never as a dense n x m matrix).
SOLVE_BLOCK_ENTRIES = 2_000_000


def _flexibility(K, F) -> np.ndarray:
    """``F^T K^-1 F`` (m, m) with the factorised ``K``, in blocks of columns of ``F``."""
    n, m = F.shape
    step = max(1, SOLVE_BLOCK_ENTRIES // max(n, 1))
    if step >= m:
        return transpose_times(F, K.solve(dense(F)))
    out = np.empty((m, m))
    for lo in range(0, m, step):
        out[:, lo:lo + step] = transpose_times(F, K.solve(dense(F[:, lo:lo + step])))
    return out


def given_state(model, initial: dict, solver=None) -> InitialState:
    """Initial conditions ``u0``, ``udot0``, ``v0`` (eqs. 10-12); missing ``u0``, ``udot0`` are zero.

    Without ``v0`` the unilateral unknowns consistent with ``u0`` are computed: with ``u`` held,
    ``psi = c - H v`` (``c = F^T u0 + F_v^T udot0 - g(0)``) and complementarity make an LCP in
    ``v`` with the positive definite ``H`` (one solution). A given ``v0`` must be consistent:
    no constraint in tension (``psi > 0``) and none open (``v > 0``) while carrying a force.

    Raises
    ------
    ValueError
        Naming the first inconsistent constraint, its ``psi`` and ``v``, and what to do.
    """
    unknown = set(initial) - {"u0", "udot0", "v0"}
    if unknown:
        raise ValueError(
            f"initial has unknown keys {sorted(unknown)}; valid keys: 'u0', 'udot0', 'v0'"
        )
    n, m = model.n, model.m
    u0 = V.as_vector("initial['u0']", initial.get("u0", 0.0), n)
    udot0 = V.as_vector("initial['udot0']", initial.get("udot0", 0.0), n)
    c = transpose_times(model.F, u0) - model.g(0.0)
    if model.F_v is not None:
        c = c + transpose_times(model.F_v, udot0)
    if "v0" in initial:
        v0 = V.as_vector("initial['v0']", initial["v0"], m)
        if np.any(v0 < 0):
            i = int(np.argmax(v0 < 0))
            raise ValueError(f"initial['v0'] must be >= 0; v0[{i}] = {float(v0[i])!r}")
    else:
        law = model.law
        v0, _, message = static_lcp(law.matrix(model.H), law.rows(c), solver or get_lcp_solver("bpp"))
        if message:
            raise ValueError("no unilateral unknowns v0 are consistent with initial['u0']: " + message)
    psi0 = c - model.H @ v0
    _check_consistent(model, v0, model.law.rows(psi0), scale=1.0 + float(np.max(np.abs(c), initial=0.0)))
    return InitialState(v=v0, psi=psi0, u=u0, udot=udot0)


def _check_consistent(model, v0, psi0, *, scale, rtol=1e-9):
    """Raise if ``(v0, psi0)`` violates ``psi <= 0``, or ``psi = 0`` where ``v > 0``."""
    names = model.constraint_names
    holonomic = ~model.law.rate                 # a plastic multiplier may be > 0 inside the surface
    tension = psi0 > rtol * scale
    if np.any(tension):
        i = int(np.argmax(psi0))
        raise ValueError(
            f"the initial state puts constraint {names[i]!r} in tension: psi = {psi0[i]:.6g} > 0 with "
            f"v0 = {v0[i]:.6g}; a unilateral constraint cannot pull. Give the opening consistent with "
            "u0 in initial['v0'], or leave v0 out to have it computed")
    open_loaded = (v0 > 0) & (psi0 < -rtol * scale) & holonomic
    if np.any(open_loaded):
        i = int(np.flatnonzero(open_loaded)[0])
        raise ValueError(
            f"the initial state has constraint {names[i]!r} open (v0 = {v0[i]:.6g} > 0) while it carries "
            f"psi = {psi0[i]:.6g} < 0; an open constraint carries no force. Fix initial['v0'] or leave "
            "it out to have it computed")
