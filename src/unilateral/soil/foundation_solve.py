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
from ..methods.common import failed_at_start, finish, step_loads
from ..linalg import transpose_times

__all__ = ["foundation_base_state", "hold_openings", "solve_foundation"]


def foundation_base_state(model, q_static, initial, solver) -> InitialState:
    """Base state of a foundation model: ``v`` openings, ``psi = -c``, ``u``, ``udot``.

    ``"static"``: the static unilateral equilibrium under ``q_static`` with the soil's static
    flexibility (:meth:`FoundationModel.static_model`). ``"rest"``: ``u = 0``, soil unloaded
    (``gap >= 0``). A dict of ``u0``, ``udot0``: given values with the soil unloaded
    (``T^T u0 + gap >= 0``).
    """
    if isinstance(initial, str) and V.choice("initial", initial, ("static", "rest")) == "static":
        primal = model.static_model()
        return static_state(primal, q_static + primal.q_imposed(0.0), solver)
    if isinstance(initial, str):
        initial = {}
    if not isinstance(initial, dict):
        raise TypeError(f"initial must be 'static', 'rest' or a dict of u0, udot0; got {V.describe(initial)}")
    unknown = set(initial) - {"u0", "udot0"}
    if unknown:
        raise ValueError(f"initial for a FoundationModel takes 'u0' and 'udot0' (the soil starts "
                         f"unloaded, c = 0); got unknown keys {sorted(unknown)}")
    u0 = V.as_vector("initial['u0']", initial.get("u0", 0.0), model.n)
    udot0 = V.as_vector("initial['udot0']", initial.get("udot0", 0.0), model.n)
    v0 = transpose_times(model.T, u0) + model.gap
    scale = 1.0 + float(np.abs(transpose_times(model.T, u0)).max(initial=0.0) + np.abs(model.gap).max())
    if np.any(v0 < -1e-12 * scale):
        i = int(np.argmin(v0))
        raise ValueError(f"the initial state penetrates the unloaded soil at contact {model.constraint_names[i]!r}: "
                         f"opening T^T u0 + gap = {v0[i]:.6g} < 0; start from initial='static', or give u0 "
                         "with the foundation on or above the soil")
    return InitialState(v=np.maximum(v0, 0.0), psi=np.zeros(model.m), u=u0, udot=udot0)


def hold_openings(W0, history, psi_affine, c_b, *, callback=None):
    """Contact forces that hold every opening at its initial value: the bilateral dual CLCP.

    Solves ``-psi_affine_n + sum_j W_j (c_{n-j} - c_b) = v_b`` (``v_b = -psi_affine_0``) step by
    step; ``history`` sums ``sum_{j>=1} W_j dc_{n-j}`` (stored weights or pole recursions).

    Returns
    -------
    c : (N+1, m)
    """
    N, m = psi_affine.shape[0] - 1, psi_affine.shape[1]
    factor = sla.cho_factor(0.5 * (W0 + W0.T))
    v_b = -psi_affine[0]
    c = np.empty((N + 1, m))
    c[0] = c_b
    for k in range(1, N + 1):
        dc = sla.cho_solve(factor, v_b + psi_affine[k] - history.value(k))
        history.push(k, dc)
        c[k] = c_b + dc
        if callback is not None:
            callback(k, N)
    return c


def solve_foundation(model, load, initial, disc, run, *, operators):
    """The route of ``method="cq"`` and ``"modal"`` for a foundation model.

    Parameters
    ----------
    model : FoundationModel
    load, initial, disc, run : as for :meth:`unilateral.methods.base.Method.solve`
    operators : callable ``operators() -> (W0, new_history, march)``
        ``W0`` (m, m) the first weight ``Lambda_D(s*)``; ``new_history()`` a fresh history of the
        convolution sum; ``march(psi_affine, c_b) -> (c, psi, log)`` the unilateral march.

    Returns
    -------
    Solution
        ``v`` openings (>= 0), ``psi = -c`` (<= 0), ``psiL = -c`` with every contact held at its
        initial opening, ``u``, ``udot``; ``stats["formulation"]``.
    """
    loads = step_loads(model, load, disc)
    init = foundation_base_state(model, loads.q_static, initial, run.solver)
    if init.message:
        return failed_at_start(model, init, run)
    run.stats["static_lcp_iterations"] = init.lcp_iterations
    run.stats["n"] = model.n
    run.stats["formulation"] = "dual CLCP in the contact forces c = -psi (docs/theory.md, section 12)"
    run.timer.lap("initial")
    u_b, v_b, c_b = init.u, init.v, -init.psi
    N, m = disc.N, model.m
    free = model.stepping_model()
    # the increments obey M du'' + C du' + K du = q - K u_b + T c_b + T dc (zero for the static base)
    load_inc = loads.table() + np.asarray(model.T @ c_b).ravel() - np.asarray(model.K @ u_b).ravel()
    offset = np.tile(v_b, (N + 1, 1))

    def stepper():
        return StructureStepper(free, disc.rule, disc.dt, load_inc, offset, init.udot, condensed=False)

    _, _, _, opening_free, _ = sweep_direct(stepper(), N, c_b, v_b)
    psi_affine = -opening_free
    run.timer.lap("bilateral")
    W0, new_history, march = operators()
    run.timer.lap("weights")
    held = hold_openings(W0, new_history(), psi_affine, c_b)
    psiL = -held
    run.timer.lap("held")
    if run.bilateral:
        c, opening, log = held, np.tile(v_b, (N + 1, 1)), StepLog(m, c_b > 0)
    else:
        c, psi_dual, log = march(psi_affine, c_b)
        # w of the LCP: round-off (+-1e-20) where the contact carries a force; exactly 0 there, as
        # the primal form's v (a contact is open where v > 0)
        opening = np.where(c > 0, 0.0, -psi_dual)
    run.timer.lap("steps")
    K = c.shape[0] - 1
    du, dud, _, _, _ = sweep_direct(stepper(), K, c_b, v_b, c - c_b)
    run.timer.lap("recover")
    return finish(model, run, log, t=disc.t[: K + 1], v=opening, psi=-c, psiL=psiL[: K + 1],
                  u=u_b + du, udot=dud)
