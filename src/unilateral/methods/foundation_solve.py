"""Solving a :class:`~unilateral.soil.foundation_model.FoundationModel`: the dual CLCP in the contact forces.

``method="cq"`` and ``method="modal"`` share this route and differ only in how the convolution with
``Lambda_D(s) = T^T D(s)^-1 T + Phi(s)`` is summed (stored CQ weights or pole recursions):

1. the base state (static, at rest or given) in openings ``v_b``, contact forces ``c_b``, ``u_b``;
2. one linear sweep of the structure alone under the load increment gives the free opening
   ``v_b + T^T du_free``; the CLCP is ``psi = psi_affine - Lambda_D * (c - c_b)`` with
   ``psi = -opening``, ``psi_affine = -(v_b + T^T du_free)``, unknown ``c`` (the shape of eq. 27);
3. the march (one LCP per step, or the held-contact linear solve for ``bilateral=True`` and for
   ``psiL``);
4. one more sweep of the structure under ``q + T c_n`` recovers ``u``.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from .. import _validate as V
from ..initial import InitialState, static_state
from ..march.direct import sweep_direct
from ..march.step_log import StepLog
from ..march.stepper import StructureStepper
from .common import failed_at_start, finish, step_loads
from ..linalg import transpose_times

__all__ = ["foundation_base_state", "hold_openings", "primal_columns", "solve_foundation"]


def foundation_base_state(model, q_static, initial, solver) -> InitialState:
    """Base state of a foundation model: ``v`` openings, ``psi = -c``, ``u``, ``udot``.

    ``"static"``: the static unilateral equilibrium under ``q_static`` with the soil's static
    flexibility (:meth:`FoundationModel.static_model`). ``"rest"``: ``u = 0``, soil unloaded
    (``gap >= 0``; a mixed model's own constraints at ``v = 0`` need ``g >= 0``). A dict of ``u0``,
    ``udot0`` (plain models): given values with the soil unloaded (``T^T u0 + gap >= 0``).
    The rows are those of :meth:`FoundationModel.static_model`: a mixed model's own constraints
    (``v``, ``psi`` of the paper), the soil contacts, and for footings that slide their slip pairs
    (``v`` the slips, ``psi = +-f``).
    """
    if isinstance(initial, str) and V.choice("initial", initial, ("static", "rest")) == "static":
        primal = model.static_model()
        # q_static holds the structure's own imposed-strain load; the soil's springs add theirs
        return static_state(primal, q_static + primal.q_imposed(0.0) - model.q_imposed(0.0), solver)
    if isinstance(initial, str):
        initial = {}
    if not isinstance(initial, dict):
        raise TypeError(f"initial must be 'static', 'rest' or a dict of u0, udot0; got {V.describe(initial)}")
    unknown = set(initial) - {"u0", "udot0"}
    if unknown:
        raise ValueError(f"initial for a FoundationModel takes 'u0' and 'udot0' (the soil starts "
                         f"unloaded, c = 0); got unknown keys {sorted(unknown)}")
    if model.mixed and initial:
        raise ValueError("initial: a structure with constraints of its own on the soil starts from 'static' or "
                         "'rest'; given u0, udot0 are for a FoundationModel without them")
    u0 = V.as_vector("initial['u0']", initial.get("u0", 0.0), model.n)
    udot0 = V.as_vector("initial['udot0']", initial.get("udot0", 0.0), model.n)
    v0 = transpose_times(model.T, u0) + model.gap
    scale = 1.0 + float(np.abs(transpose_times(model.T, u0)).max(initial=0.0) + np.abs(model.gap).max())
    if np.any(v0 < -1e-12 * scale):
        i = int(np.argmin(v0))
        raise ValueError(f"the initial state penetrates the unloaded soil at contact {model.contact_names[i]!r}: "
                         f"opening T^T u0 + gap = {v0[i]:.6g} < 0; start from initial='static', or give u0 "
                         "with the foundation on or above the soil")
    slips = np.zeros(len(model.slips))
    psi = np.zeros(model.mp + model.ms + slips.size)
    if model.structure is not None:
        psi[: model.mp] = -model.structure.g(0.0)
        if np.any(psi > 0):
            i = int(np.argmax(psi))
            raise ValueError(f"initial='rest': constraint {model.constraint_names[i]!r} is violated at u = 0 "
                             f"(g = {-psi[i]:.6g} < 0); start from initial='static'")
    return InitialState(v=np.concatenate([np.zeros(model.mp), np.maximum(v0, 0.0), slips]), psi=psi, u=u0,
                        udot=udot0)


def primal_columns(model, v, psi):
    """The solution's columns of a foundation model from those of its primal form (..., m_p + m_s
    [+ 2 m_s]): the model's own, then per contact ``v`` opening and ``psi = -c``; footings that slide
    then the shears (``v`` net slip ``s+ - s-``, ``psi = -f``, the soil's horizontal force on the
    footing) and the slips (``v`` the slips, ``psi = +-f - mu c``) (:class:`FoundationModel`).

    ``psi`` of the slips may be their associated values ``+-f`` or the friction functions: ``f``
    is half their difference either way.

    Footings that slide in plan: the facets' ``v`` (the multipliers ``lambda_k``) and ``psi``
    (``d_k . f`` or ``d_k . f - mu c``) per patch give the shears' columns (x block, y block): ``v``
    the net slip ``sum_k lambda_k d_k``, ``psi = -f`` with ``f`` the least-squares solution of the
    facets' ``d_k . f`` (exact either way: opposite facets cancel ``mu c``), and the facets' columns
    ``v = lambda_k``, ``psi = d_k . f - mu c``.
    """
    mp, ms = model.mp, model.ms
    if not model.sliding:
        return v, psi
    if model.horizontal == 2:
        return _plan_columns(model, v, psi)
    c = -psi[..., mp:mp + ms]
    f = 0.5 * (psi[..., mp + ms::2] - psi[..., mp + ms + 1::2])
    slips = v[..., mp + ms:]
    friction = np.stack([f - model.mu * c, -f - model.mu * c], axis=-1).reshape(slips.shape)
    return (np.concatenate([v[..., :mp + ms], slips[..., 0::2] - slips[..., 1::2], slips], axis=-1),
            np.concatenate([psi[..., :mp + ms], -f, friction], axis=-1))


def _plan_columns(model, v, psi):
    """:func:`primal_columns` of footings that slide in plan (``facets`` multipliers per patch)."""
    mp, ms = model.mp, model.ms
    D = model.directions                                   # (facets, 2)
    c = -psi[..., mp:mp + ms]
    lam = v[..., mp + ms:].reshape(v.shape[:-1] + (ms, D.shape[0]))
    rows = psi[..., mp + ms:].reshape(lam.shape)
    f = (rows @ D) @ np.linalg.inv(D.T @ D)                 # (..., ms, 2)
    net = lam @ D
    blocks = lambda a: np.swapaxes(a, -1, -2).reshape(a.shape[:-2] + (2 * ms,))
    friction = (f @ D.T - model.mu[:, None] * c[..., None]).reshape(lam.shape[:-2] + (-1,))
    return (np.concatenate([v[..., :mp + ms], blocks(net), v[..., mp + ms:]], axis=-1),
            np.concatenate([psi[..., :mp + ms], -blocks(f), friction], axis=-1))


def plan_forces(model, psi_slips):
    """``f`` (..., 2 m_s), the x block then the y block, from the facets' rows ``d_k . f`` (or the facet
    functions ``d_k . f - mu c``) (..., facets m_s) of footings that slide in plan (least squares)."""
    D = model.directions
    rows = psi_slips.reshape(psi_slips.shape[:-1] + (model.ms, D.shape[0]))
    f = (rows @ D) @ np.linalg.inv(D.T @ D)
    return np.swapaxes(f, -1, -2).reshape(psi_slips.shape[:-1] + (2 * model.ms,))


def hold_openings(W0, history, psi_affine, z_b, held, *, callback=None):
    """Soil forces that hold every opening (and every patch's shear) at its initial value: the
    bilateral CLCP.

    The unknowns ``held`` (the soil contacts' forces, and the shears of footings that slide) move to
    hold their rows of ``psi_affine_n - sum_j W_j (z_{n-j} - z_b) = psi_affine_0`` step by step; the
    others (the structure's own constraints, the slips) stay at their base values. ``history`` sums
    ``sum_{j>=1} W_j dz_{n-j}`` (stored weights or pole recursions). ``W0``'s block of ``held`` is
    definite (positive for a plain model, negative in a mixed one).

    Returns
    -------
    z : (N+1, len(held)) the held unknowns
    psi : (N+1, m - len(held)) the other rows with every contact held
    """
    N, m = psi_affine.shape[0] - 1, psi_affine.shape[1]
    held = np.asarray(held)
    rest = np.setdiff1d(np.arange(m), held)
    Wss = W0[np.ix_(held, held)]
    sign = 1.0 if Wss.trace() > 0 else -1.0
    # the inverse of the (small) definite block, once: a product per step instead of a solve
    inverse = sign * sla.cho_solve(sla.cho_factor(sign * 0.5 * (Wss + Wss.T)), np.eye(held.size))
    coupling = W0[np.ix_(rest, held)]
    dz = np.zeros(m)
    z = np.empty((N + 1, held.size))
    psi = np.empty((N + 1, rest.size))
    z[0], psi[0] = z_b[held], psi_affine[0, rest]
    for k in range(1, N + 1):
        h = history.value(k)
        dz[held] = inverse @ (psi_affine[k, held] - psi_affine[0, held] - h[held])
        history.push(k, dz)
        z[k] = z_b[held] + dz[held]
        psi[k] = psi_affine[k, rest] - h[rest] - coupling @ dz[held]
        if callback is not None:
            callback(k, N)
    return z, psi


def solve_foundation(model, load, initial, disc, run, *, operators):
    """The route of ``method="cq"`` and ``"modal"`` for a foundation model.

    Parameters
    ----------
    model : FoundationModel
    load, initial, disc, run : as for :meth:`unilateral.methods.base.Method.solve`
    operators : callable ``operators() -> (W0, new_history, march)``
        ``W0`` (m, m) the first weight of the model's kernel; ``new_history()`` a fresh history of
        the convolution sum; ``march(psi_affine, z_b) -> (z, psi, log)`` the march of the CLCP.

    Returns
    -------
    Solution
        ``v`` openings (>= 0), ``psi = -c`` (<= 0), ``psiL = -c`` with every contact held at its
        initial opening, ``u``, ``udot``; ``stats["formulation"]``. A mixed model's own
        constraints first, with the paper's ``v`` and ``psi``.
    """
    loads = step_loads(model, load, disc)
    init = foundation_base_state(model, loads.q_static, initial, run.solver)
    if init.message:
        return failed_at_start(model, init, run)
    run.stats["static_lcp_iterations"] = init.lcp_iterations
    run.stats["n"] = model.n
    run.stats["formulation"] = ("dual CLCP in the contact forces c = -psi (docs/theory.md, section 12)"
                                if not model.mixed else
                                "mixed CLCP: the structure's constraints in the paper's form, the soil contacts "
                                "in the contact forces (docs/theory.md, section 12)")
    run.timer.lap("initial")
    mp, ms = model.mp, model.ms
    # unknowns z: the structure's v, the contact forces c (sliding: the shears f, the slips); rows: the
    # structure's psi, the openings (sliding: the shear equations, 0 at the base, and +-f)
    opening_b = init.v[mp:mp + ms]
    # an open contact carries no force: exactly 0, not the static LCP's round-off (which _columns
    # would read as a closed contact)
    c_b = np.where(opening_b > 0, 0.0, -init.psi[mp:mp + ms])
    z_b = np.concatenate([init.v[:mp], c_b])
    row_b = np.concatenate([init.psi[:mp], opening_b])
    if model.sliding:
        f_b = init.psi[mp + ms::2] if model.horizontal == 1 else plan_forces(model, init.psi[mp + ms:])
        slip_b = init.v[mp + ms:]
        z_b = np.concatenate([z_b, f_b, slip_b])
        row_b = np.concatenate([row_b, np.zeros(f_b.size), init.psi[mp + ms:]])
    u_b = init.u
    N, m = disc.N, model.m
    free = model.stepping_model()
    # the increments obey M du'' + C du' + K du = q + q_imposed - K u_b + F_a z_b + F_a dz (the table
    # holds q + q_imposed)
    load_inc = loads.table() + np.asarray(free.F @ z_b).ravel() - np.asarray(model.K @ u_b).ravel()
    offset = np.tile(row_b, (N + 1, 1))

    def stepper():
        return StructureStepper(free, disc.rule, disc.dt, load_inc, offset, init.udot, condensed=False)

    _, _, _, rows_free, _ = sweep_direct(stepper(), N, z_b, row_b)
    # a plain model marches -opening (its kernel Lambda_D is positive definite); a mixed one the rows
    psi_affine = rows_free if model.mixed else -rows_free
    run.timer.lap("bilateral")
    W0, new_history, march = operators()
    run.timer.lap("weights")
    soil = model.soil_rows
    rest = np.setdiff1d(np.arange(m), soil)
    held, psi_held = hold_openings(W0, new_history(), psi_affine, z_b, soil)
    z_held = np.tile(z_b, (N + 1, 1))
    z_held[:, soil] = held
    rows_held = np.tile(-row_b, (N + 1, 1))      # -opening: the held rows are the march's -w
    rows_held[:, rest] = psi_held
    psiL = _columns(model, z_held, rows_held)[1]
    run.timer.lap("held")
    if run.bilateral:
        z, rows = z_held, rows_held
        log = StepLog(m, z_b > 0)
    else:
        z, rows, log = march(psi_affine, z_b)
    run.timer.lap("steps")
    K = z.shape[0] - 1
    du, dud, _, _, _ = sweep_direct(stepper(), K, z_b, row_b, z - z_b)
    run.timer.lap("recover")
    v, psi = _columns(model, z, rows)
    return finish(model, run, log, t=disc.t[: K + 1], v=v, psi=psi, psiL=psiL[: K + 1], u=u_b + du, udot=dud)


def _columns(model, z, rows):
    """The solution's columns (:func:`primal_columns`) from the march's unknowns ``z`` and rows
    ``rows`` (``-w``: the structure's ``psi``, ``-opening``, 0 for shears, friction functions)."""
    mp, ms = model.mp, model.ms
    c = z[:, mp:mp + ms]
    # the LCP's w of a contact: round-off (+-1e-20) where it carries a force; exactly 0 there, as the
    # primal form's v (a contact is open where v > 0)
    opening = np.where(c > 0, 0.0, -rows[:, mp:mp + ms])
    v = np.hstack([z[:, :mp], opening])
    psi = np.hstack([rows[:, :mp], -c])
    if model.horizontal == 1:
        v = np.hstack([v, z[:, mp + 2 * ms:]])
        psi = np.hstack([psi, np.repeat(z[:, mp + ms:mp + 2 * ms], 2, axis=1) * np.tile([1.0, -1.0], ms)])
    elif model.horizontal == 2:         # the facets' associated values d_k . f
        v = np.hstack([v, z[:, mp + 3 * ms:]])
        f = np.swapaxes(z[:, mp + ms:mp + 3 * ms].reshape(-1, 2, ms), 1, 2)       # (N+1, ms, 2)
        psi = np.hstack([psi, (f @ model.directions.T).reshape(z.shape[0], -1)])
    return primal_columns(model, v, psi)
