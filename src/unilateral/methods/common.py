"""Pieces every method shares: loads at the steps, the initial state, the base state, the result."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as V
from ..initial import InitialState, given_state, static_state
from ..linalg import transpose_times
from ..march.direct import sweep_direct
from ..march.policy import current_policy
from ..march.stepper import StructureStepper
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
    none_imposed = model.q_imposed_is_constant and not model.q_imposed(0.0).any()
    with_imposed = lambda Q: Q if none_imposed else Q + (
        model.q_imposed(0.0) if model.q_imposed_is_constant else np.array([imposed(k * dt) for k in range(N + 1)]))
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
        if tables and model.n <= current_policy().compiled_max_n:
            # small and medium models: the compiled loops take every step's load and offset as arrays
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
    return finish(model, run, log, t=disc.t[: K + 1], v=v, psi=psi, psiL=model.law.rows(psiL[: K + 1]),
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
    if log.failure:
        success = False
        message = f"stopped after {len(t) - 1} of {N} steps: {log.failure}" + _friction_hint(model)
    elif len(t) - 1 < N:                    # a simulation's solution so far
        success = True
        message = f"{len(t) - 1} of {N} steps so far, {stats['contact_changes']} contact changes"
    else:
        success = True
        message = f"{N} steps, {stats['contact_changes']} contact changes"
    blown = _first_non_finite(t, u, v, psi)
    if blown is not None:
        success = False
        message = (f"the solution is not finite from step {blown} (t = {t[blown]:.6g}) on: the motion grows "
                   "without bound (an unstable model: check that K is stable with the constraints held and "
                   "that F, H and the loads have the sizes meant) or the time step is too large; " + message)
    warnings = _step_lcp_warnings(model, stats) + _chatter_warnings(model, stats, v)
    if warnings:
        stats["warnings"] = warnings
        message = message + "; WARNING: " + "; ".join(warnings)
    run.timer.lap("results")                # the histories formed and checked after the last lap
    stats["time"] = run.timer.laps()
    return Solution(t=t, v=v, psi=psi, psiL=psiL, u=u, udot=udot, success=success,
                    message=message, stats=stats, dof_names=list(getattr(model, "dof_names", [])),
                    constraint_names=list(model.constraint_names))


def _first_non_finite(t, *histories):
    """The first step at which any of the histories (K+1, .) holds inf or NaN, or None."""
    present = [h for h in histories if h is not None]
    if all(np.isfinite(np.sum(h)) for h in present):    # an inf or NaN anywhere makes its sum one
        return None
    bad = np.zeros(len(t), dtype=bool)
    for h in present:
        bad |= ~np.all(np.isfinite(h), axis=1)
    return int(np.argmax(bad)) if bad.any() else None


def _friction_hint(model) -> str:
    """What to change when a step LCP with friction rows (nonsymmetric) could not be solved."""
    law = model.law
    if law.P is None:
        return ""
    names = [model.constraint_names[i] for i in np.flatnonzero(np.any(law.P != np.eye(law.m), axis=1))]
    return (f"; the step LCP of the friction constraints {names[:6]} is nonsymmetric and a P-matrix only "
            "while mu |W_ns| < W_ss (docs/theory.md, section 13): use lcp='lemke', a smaller dt, a stiffer "
            "tangential stiffness kt or a smaller mu")


#: A constraint that switches and switches back on consecutive steps this often is chattering.
CHATTER_MIN_ALTERNATIONS = 2
#: Largest m whose every principal minor of the step LCP matrix is checked (2^m minors).
PRINCIPAL_MINORS_MAX_M = 12


def contact_alternations(v) -> np.ndarray:
    """Per constraint (m,), how often its contact state changed at a step and back at the next.

    ``v`` (N+1, m): a constraint is open where ``v > 0``. A genuine short flight gives one such
    alternation; contact chatter (a dashpot rate that flips sign step to step) gives many.
    """
    open_ = np.asarray(v) > 0
    if open_.shape[0] < 3:
        return np.zeros(open_.shape[1], dtype=int)
    flip = open_[1:] != open_[:-1]
    return np.sum(flip[1:] & flip[:-1], axis=0).astype(int)


def _chatter_warnings(model, stats, v) -> list:
    """``stats["chatter"]`` and a warning when contacts switch back and forth step to step."""
    counts = contact_alternations(v) * ~model.law.rate       # yield and slip accumulate: not contacts
    names = list(model.constraint_names)
    stats["chatter"] = {"alternations": {names[i]: int(c) for i, c in enumerate(counts) if c},
                        "total": int(counts.sum())}
    bad = np.flatnonzero(counts >= CHATTER_MIN_ALTERNATIONS)
    if bad.size == 0:
        return []
    which = ", ".join(f"{names[i]!r} ({counts[i]} times)" for i in bad[:5]) + (", ..." if bad.size > 5 else "")
    rule = stats.get("rule", "")
    kelvin = bool(getattr(model, "viscous", False))
    if rule == "trapezoidal":
        why = ("the trapezoidal rule has no numerical damping" + (
            ": the dashpot rate of a Kelvin contact alternates in sign step to step after a contact "
            "change" if kelvin else "") + "; the contact changes are artefacts that grow as dt "
            "shrinks: use rule='bdf2' (L-stable)")
    elif rule == "bdf2":
        why = "the contact changes may be artefacts of the step: check them with a smaller dt"
    else:
        why = "the contact changes may be artefacts of the step: check with a smaller dt or rule='bdf2'"
    return [f"contact chatter: constraint(s) {which} opened and closed again on consecutive steps; {why}"]


def step_lcp_matrix(model, rule, dt):
    """``W0 = Lambda(s*)`` (m, m) of a matrix model and a CQ rule, or None if it does not apply."""
    from ..kernels import MatrixKernel
    from ..rules import get_rule

    try:
        rule = get_rule(rule, cq=True)
    except (ValueError, TypeError):
        return None
    if not hasattr(model, "K") or not model.m:
        return None
    W0 = MatrixKernel(model)(np.array([rule.s_star(dt)]))[0]
    return 0.5 * (W0 + W0.T)


def p_matrix_check(W) -> dict:
    """Whether ``W`` (m, m) is a P-matrix (every principal minor > 0: each LCP has one solution).

    Every principal minor for ``m <= PRINCIPAL_MINORS_MAX_M``; above, for the symmetric ``W`` only,
    its smallest eigenvalue (P-matrix = positive definite). Returns ``P_matrix``, the smallest
    relative principal minor or eigenvalue, and the rows of the worst minor.
    """
    m = W.shape[0]
    scale = float(np.max(np.abs(np.diag(W)))) or 1.0
    eig = float(np.linalg.eigvalsh(0.5 * (W + W.T)).min()) / scale
    out = {"min_eigenvalue": eig}
    if m <= PRINCIPAL_MINORS_MAX_M:
        from itertools import combinations

        worst, rows = np.inf, ()
        d = np.sqrt(np.abs(np.diag(W)))
        Ws = W / np.where(d > 0, d, 1.0)[:, None] / np.where(d > 0, d, 1.0)[None, :]
        for size in range(1, m + 1):
            for idx in combinations(range(m), size):
                minor = float(np.linalg.det(Ws[np.ix_(idx, idx)]))
                if minor < worst:
                    worst, rows = minor, idx
        out.update(min_principal_minor=worst, worst_minor_rows=list(rows))
        out["P_matrix"] = bool(worst > 1e-12)
    else:
        out["P_matrix"] = bool(eig > 1e-12)
    return out


def _step_lcp_warnings(model, stats) -> list:
    """``stats["step_lcp"]``: is the step LCP uniquely solvable (W0 a P-matrix)? Kelvin models only.

    With Kelvin contacts the claim that cq, modal and direct solve the same discrete problem rests on
    each step's LCP having one solution; it is checked here for the rules with a CQ form.
    """
    if not getattr(model, "viscous", False) or "dt" not in stats:
        return []
    W0 = step_lcp_matrix(model, stats.get("rule"), stats["dt"])
    if W0 is None:
        return []
    # the contacts' block (a slip or yield pair has opposite columns: never a P-matrix, one solution)
    contacts = np.flatnonzero(~model.law.rate)
    if contacts.size == 0:
        return []
    check = p_matrix_check(W0[np.ix_(contacts, contacts)])
    check["worst_minor_rows"] = [int(contacts[i]) for i in check.get("worst_minor_rows", [])]
    stats["step_lcp"] = check
    if check["P_matrix"]:
        return []
    names = list(model.constraint_names)
    rows = [names[i] for i in check.get("worst_minor_rows", [])]
    return [f"the step LCP matrix W0 = Lambda(s*) is not a P-matrix (smallest scaled principal minor "
            f"{check.get('min_principal_minor', check['min_eigenvalue']):.3g}"
            + (f", constraints {rows}" if rows else "") + "): a step's LCP may have several "
            "solutions and the methods may pick different ones; use rule='bdf2' or a smaller dt"]


def failed_at_start(model, init, run) -> Solution:
    """The one-sample :class:`Solution` of a run whose initial state could not be found."""
    run.stats["time"] = run.timer.laps()
    run.stats["steps_done"] = 0
    n_u = None if init.u is None else init.u[None]
    psi = model.law.rows(init.psi)[None]
    return Solution(t=np.zeros(1), v=init.v[None], psi=psi, psiL=psi,
                    u=n_u, udot=None if init.udot is None else init.udot[None], success=False,
                    message=init.message, stats=run.stats,
                    dof_names=list(getattr(model, "dof_names", [])),
                    constraint_names=list(model.constraint_names))
