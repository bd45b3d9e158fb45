"""Pieces every method shares: loads at the steps, the initial state, the base state, the result."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as V
from ..initial import InitialState, given_state, static_state
from ..linalg import transpose_times
from ..march.direct import sweep_direct
from ..march.stepper import DENSE_STEPPING_MAX_N, StructureStepper
from ..result import Solution


# ---------------------------------------------------------------------- loads
@dataclass
class StepLoads:
    """The load of every step of a run, and the load of the static state it starts from.

    Attributes
    ----------
    q : callable ``q(k) -> (n,)``
        Applied load plus the load of imposed strains used at step ``k``.
    q_static : (n,)
        The load of the static preload (``q(0-)``: a pulse starting at t = 0 is still off).
    table : callable ``table() -> (N+1, n)``
        Every step's ``q`` at once (vectorised where the load allows it).
    """

    q: object
    q_static: np.ndarray
    table: object


def step_loads(model, load, disc) -> StepLoads:
    """How ``load`` is sampled on the grid of ``disc``.

    A :class:`~unilateral.loads.LoadHistory` gives hat-function averages that keep second order
    across pulse edges, one-sided at ``t = 0`` (:meth:`~unilateral.loads.LoadHistory.grid_samples`,
    ``docs/theory.md``), and ``q(0-)`` for the static preload. A callable is sampled at the grid
    points (``q_static = q(0)``); an array (N+1, n) is used as given (``q_static`` its first row).
    """
    n, dt, N = model.n, disc.dt, disc.N
    imposed = model.q_imposed
    with_imposed = lambda Q: Q + (model.q_imposed(0.0) if model.q_imposed_is_constant
                                  else np.array([imposed(k * dt) for k in range(N + 1)]))
    if load is None:
        q = lambda k: imposed(k * dt)
        return StepLoads(q, q(0), lambda: with_imposed(np.zeros((N + 1, n))))
    if callable(getattr(load, "grid_factors", None)):
        if load.n != n:
            raise ValueError(f"load has {load.n} DOFs but the model has n = {n}")
        factors, before = load.grid_factors(dt, N)
        vectors = load.vectors()
        bad = np.flatnonzero(~np.all(np.isfinite(factors), axis=1))
        if bad.size:
            raise ValueError(f"load(t) returned a non-finite value at t={bad[0] * dt} (step {bad[0]})")
        q = lambda k: load.constant + factors[k] @ vectors + imposed(k * dt)
        return StepLoads(q, load.constant + before @ vectors + imposed(0.0),
                         lambda: with_imposed(load.constant + factors @ vectors))
    if callable(load):
        def q(k):
            try:
                value = np.asarray(load(k * dt), dtype=float)
            except Exception as exc:
                raise ValueError(f"the load raised {type(exc).__name__} at t={k * dt:.6g} (step {k}): {exc}") from exc
            if value.shape != (n,):
                raise ValueError(f"load(t) must return shape ({n},), got shape {value.shape} at t={k * dt}")
            if not np.all(np.isfinite(value)):
                raise ValueError(f"load(t) returned a non-finite value at t={k * dt} (step {k})")
            return value + imposed(k * dt)
        return StepLoads(q, q(0), lambda: np.array([q(k) for k in range(N + 1)], dtype=float).reshape(N + 1, n))
    arr = V.as_matrix("load", load, (None, n), allow_sparse=False)
    if arr.shape[0] < N + 1:
        raise ValueError(
            f"load has {arr.shape[0]} rows but t_end/dt = {N} steps need {N + 1} (rows at t = k dt)"
        )
    q = lambda k: arr[k] + imposed(k * dt)
    return StepLoads(q, q(0), lambda: with_imposed(arr[: N + 1]))


# ---------------------------------------------------------------------- the base state
def initial_state(model, q_static, initial, solver) -> InitialState:
    """The base state of a matrix model: ``"static"`` (under ``q_static``), ``"rest"`` or given."""
    if isinstance(initial, str) and V.choice("initial", initial, ("static", "rest")) == "static":
        return static_state(model, q_static, solver)
    if isinstance(initial, str):                              # "rest"
        return given_state(model, {}, solver)
    if isinstance(initial, dict):
        return given_state(model, initial, solver)
    raise TypeError(f"initial must be 'static', 'rest' or a dict of u0, udot0, v0; got {V.describe(initial)}")


@dataclass
class BaseState:
    """A matrix model's initial state and the load and offset of its increments.

    ``du = u - u_b`` and ``dv = v - v_b`` obey the equations of motion with the load increment
    ``f_k = q(t_k) + F v_b - K u_b`` and the reaction offset ``F^T u_b - H v_b - g(t_k)``, given
    as arrays (N+1, n) and (N+1, m) for small dense models or as functions of the step.
    """

    model: object
    init: InitialState
    load_inc: object
    offset: object

    @classmethod
    def prepare(cls, model, load, initial, disc, run, *, tables: bool) -> BaseState:
        loads = step_loads(model, load, disc)
        q = loads.q
        init = initial_state(model, loads.q_static, initial, run.solver)
        if init.message:
            return cls(model, init, None, None)
        run.stats["static_lcp_iterations"] = init.lcp_iterations
        u_b, v_b = init.u, init.v
        K_ub = model.K @ u_b
        F_vb = model.F @ v_b
        HFu = transpose_times(model.F, u_b) - model.H @ v_b
        if tables and model.n <= DENSE_STEPPING_MAX_N:
            # small models: the compiled sweeps take every step's load and offset as arrays
            load_inc = loads.table() + (F_vb - K_ub)
            g = (model.g(0.0) if model.g_is_constant
                 else np.array([model.g(k * disc.dt) for k in range(disc.N + 1)]))
            offset = np.tile(HFu, (disc.N + 1, 1)) - g
        else:
            dt = disc.dt
            load_inc = lambda k: q(k) + F_vb - K_ub
            offset = lambda k: HFu - model.g(k * dt)
        return cls(model, init, load_inc, offset)

    def stepper(self, disc, *, condensed: bool) -> StructureStepper:
        """A fresh stepper of the increments with the rule of ``disc``."""
        return StructureStepper(self.model, disc.rule, disc.dt, self.load_inc, self.offset,
                                self.init.udot, condensed=condensed)


def clcp_on_matrix_model(model, load, initial, disc, run, march):
    """The CLCP route for a matrix model: base state, bilateral sweep, ``march``, recovery of ``u``.

    ``march(psi_affine (N+1, m), v_b (m,)) -> (v, psi, log)`` steps the CLCP; this function gives
    it the bilateral response and recovers the displacements with one more linear sweep.
    """
    base = BaseState.prepare(model, load, initial, disc, run, tables=True)
    if base.init.message:
        return failed_at_start(model, base.init, run)
    run.timer.lap("initial")
    v_b = base.init.v
    _, _, _, psiL, _ = sweep_direct(base.stepper(disc, condensed=False), disc.N, v_b, base.init.psi)
    run.timer.lap("bilateral")
    v, psi, log = march(psiL, v_b)
    run.timer.lap("steps")
    K = v.shape[0] - 1
    du, dud, _, _, _ = sweep_direct(base.stepper(disc, condensed=False), K, v_b, base.init.psi, v - v_b)
    run.timer.lap("recover")
    return finish(model, run, log, t=disc.t[: K + 1], v=v, psi=psi, psiL=psiL[: K + 1],
                  u=base.init.u + du, udot=dud)


# ---------------------------------------------------------------------- the result
def finish(model, run, log, *, t, v, psi, psiL=None, u=None, udot=None) -> Solution:
    """The :class:`Solution` of a march, with ``success`` and ``message`` from its log."""
    stats = run.stats
    N = stats["steps"]
    stats.update(log.stats())
    if hasattr(log, "factorizations"):
        stats["factorizations"] = log.factorizations
    stats["steps_done"] = len(t) - 1
    stats["time"] = run.timer.laps()
    if log.failure:
        success = False
        message = f"stopped after {len(t) - 1} of {N} steps: {log.failure}"
    else:
        success = True
        message = f"{N} steps, {stats['contact_changes']} contact changes"
    return Solution(t=t, v=v, psi=psi, psiL=psiL, u=u, udot=udot, success=success,
                    message=message, stats=stats, dof_names=list(getattr(model, "dof_names", [])),
                    constraint_names=list(model.constraint_names))


def failed_at_start(model, init, run) -> Solution:
    """The one-sample :class:`Solution` of a run whose initial state could not be found."""
    run.stats["time"] = run.timer.laps()
    run.stats["steps_done"] = 0
    n_u = None if init.u is None else init.u[None]
    return Solution(t=np.zeros(1), v=init.v[None], psi=init.psi[None], psiL=init.psi[None],
                    u=n_u, udot=None if init.udot is None else init.udot[None], success=False,
                    message=init.message, stats=run.stats,
                    dof_names=list(getattr(model, "dof_names", [])),
                    constraint_names=list(model.constraint_names))
