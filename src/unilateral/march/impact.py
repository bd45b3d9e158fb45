"""A velocity-level impact law for rigid contacts: the Moreau-Jean time stepping with Newton's law.

The position-level LCP of ``method="direct"`` holds the opening of a rigid contact at zero at the
end of a step, and what that does to the velocity depends on the rule (BDF1: a plastic impact,
the trapezoidal rule: a bounce; ``docs/rocking.md``). Here the contacts act on the *velocity*
(Moreau 1988, Jean 1999): with the theta-method on ``M u'' + C u' + K u = q + N lambda``,

    W v_{k+1} = M v_k - dt C (1 - th) v_k - dt K (u_k + th (1 - th) dt v_k) + dt q(t_k + th dt) + N P
    W = M + th dt C + th^2 dt^2 K,        u_{k+1} = u_k + dt ((1 - th) v_k + th v_{k+1})

(``P = dt lambda`` the impulses of the step), and every contact ``j`` whose opening predicted at
mid-step, ``N_j^T (u_k + dt v_k / 2) - g_j``, is not positive obeys Newton's impact law in
complementarity with its impulse:

    U_j = N_j^T v_{k+1} + e N_j^T v_k >= 0,   P_j >= 0,   U_j P_j = 0

(``e`` the coefficient of restitution, 0 for Housner's rocking). A persistent contact keeps
``N^T v = 0``, so its opening does not drift (linear constraints); an impact maps the velocity by
the LCP's projection exactly, whatever the step. For models whose every unknown is a rigid contact
(:class:`~unilateral.constraints.RigidContact`); not a registered method: call
:func:`moreau_jean`.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from ..linalg import dense
from ..result import Solution


def moreau_jean(model, load, *, dt, t_end, u0, udot0=None, e=0.0, theta=0.5) -> Solution:
    """March ``model`` with rigid contacts by the Moreau-Jean scheme with Newton's impact law.

    Parameters
    ----------
    model : Model whose unknowns are all rigid contacts (the family
        :class:`~unilateral.constraints.RigidContact`, ``H = 0``)
    load : callable ``q(t) -> (n,)`` (a :class:`~unilateral.loads.LoadHistory`), force
    dt, t_end : time step and duration, s
    u0, udot0 : (n,) initial displacements (length) and velocities (length/s; default 0)
    e : coefficient of restitution, 0 <= e <= 1
    theta : the theta-method's weight, 1/2 <= theta <= 1 (1/2: second order between impacts)

    Returns
    -------
    Solution
        ``v`` (N+1, m): the mean contact force of each step ``P / dt`` (force), ``psi`` ``P psi``
        ``= -opening`` (length), ``psiL`` zeros; ``stats["impulses"]`` (N+1, m) the impulses ``P``
        (force s).
    """
    from ..constraints import RigidContact

    rigid = np.zeros(model.m, dtype=bool)
    for family in model.families:
        rigid[family.indices] |= isinstance(family, RigidContact)
    if not rigid.all():
        raise ValueError("moreau_jean: every unknown of the model must be a rigid contact (RigidContact family); "
                         f"{int((~rigid).sum())} are not")
    if not (0.0 <= e <= 1.0 and 0.5 <= theta <= 1.0):
        raise ValueError(f"moreau_jean: e={e!r} must lie in [0, 1] and theta={theta!r} in [1/2, 1]")
    N_steps = int(round(t_end / dt))
    M, K, C, N = (dense(A) for A in (model.M, model.K, model.damping(), model.F))
    n, m = N.shape
    W = sla.lu_factor(M + theta * dt * C + theta ** 2 * dt * dt * K)
    WN = sla.lu_solve(W, N)
    u = np.zeros((N_steps + 1, n))
    ud = np.zeros((N_steps + 1, n))
    P = np.zeros((N_steps + 1, m))
    u[0] = u0
    ud[0] = 0.0 if udot0 is None else udot0
    g = lambda t: model.g(t)
    for k in range(N_steps):
        t = k * dt
        u_k, v_k = u[k], ud[k]
        rhs = (M @ v_k - dt * (1 - theta) * (C @ v_k) - dt * (K @ (u_k + theta * (1 - theta) * dt * v_k))
               + dt * np.asarray(load(t + theta * dt), dtype=float))
        v_free = sla.lu_solve(W, rhs)
        active = np.flatnonzero(N.T @ (u_k + 0.5 * dt * v_k) - g(t + dt) <= 0.0)
        v_new = v_free
        if active.size:
            NA = N[:, active]
            impulse, message = _impulses(NA.T @ WN[:, active], NA.T @ v_free + e * (NA.T @ v_k))
            if message:
                return _solution(model, dt, k, u, ud, P, f"the impact LCP of step {k + 1} failed: {message}")
            P[k + 1, active] = impulse
            v_new = v_free + WN[:, active] @ impulse
        ud[k + 1] = v_new
        u[k + 1] = u_k + dt * ((1 - theta) * v_k + theta * v_new)
    return _solution(model, dt, N_steps, u, ud, P, "")


def _impulses(A, b):
    """``(P, message)`` of the LCP ``U = A P + b >= 0, P >= 0, U^T P = 0`` (block principal pivoting,
    Lemke's method where it fails; ``message`` empty on success)."""
    from ..lcp import get_lcp_solver

    res = get_lcp_solver("bpp").solve(A, b)
    if not res.success:
        res = get_lcp_solver("lemke").solve(A, b)
    return res.v, "" if res.success else res.message


def _solution(model, dt, K, u, ud, P, failure) -> Solution:
    """The Solution of steps ``0 .. K``."""
    t = np.arange(K + 1) * dt
    u, ud, P = u[:K + 1], ud[:K + 1], P[:K + 1]
    opening = u @ dense(model.F) - np.array([model.g(tk) for tk in t])
    N = u.shape[0] - 1
    message = f"stopped after {K} steps: {failure}" if failure else f"{N} steps (Moreau-Jean, Newton's impact law)"
    return Solution(t=t, v=P / dt, psi=-opening, psiL=np.zeros_like(P), u=u, udot=ud, success=not failure,
                    message=message, stats={"method": "moreau-jean", "impulses": P, "dt": dt},
                    dof_names=list(model.dof_names), constraint_names=list(model.constraint_names))
