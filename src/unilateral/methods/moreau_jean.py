"""``method="moreau-jean"``: rigid contacts with Newton's impact law at the velocity level,
impacts located within the step (:mod:`unilateral.march.impact`)."""

from __future__ import annotations

import numpy as np

from .. import _validate as V
from ..march.impact import WORK_TERMS, MoreauJeanMarch, forces_at_rest, system_of
from .base import Method
from .common import finish

#: The rules of the theta-method: the rule's name -> theta.
THETA = {"trapezoidal": 0.5, "bdf1": 1.0}


class MoreauJean(Method):
    """The Moreau-Jean time stepping of rigid contacts (``H = 0``, :mod:`unilateral.structure.rigid`)
    with Newton's impact law, each impact located within its step by the root of the contact's
    opening and applied there as a jump of the velocity (:mod:`unilateral.march.impact`).

    For models whose every unknown is a rigid contact (``Frame2D.contact``, ``Frame2D.rigid_block``,
    ``Frame3D.contact``, ``Frame3D.rigid_box``: a box on four corners, :mod:`unilateral.structure.rigid3d`;
    the family :class:`~unilateral.constraints.RigidContact`, whose ``restitution`` is Newton's
    ``e`` of each contact). The rule is the theta-method's weight: ``rule="trapezoidal"``
    (``theta = 1/2``: second order between impacts, no numerical dissipation: the energy balance
    closes with the energy lost at impacts alone) or ``"bdf1"`` (``theta = 1``, first order,
    dissipative). A rigid rocking block then follows Housner's law at every impact to round-off
    (``docs/rocking.md``).

    ``initial``: ``"rest"`` (``u = 0`` at rest), a dict of ``u0``, ``udot0`` (``v0`` is not needed:
    the contact forces are outputs), or ``"static"``: the static state where ``K`` is definite,
    else the static state with the rigid contacts that touch at ``u = 0`` held closed, if they hold
    the structure and are compressed (a block standing on its base, a column on it).

    The solution's ``v`` is the mean contact force of each step (impulse / dt, force; at step 0 the
    forces of the acceleration-level LCP at the initial state), ``psi``
    ``P psi = -opening``; ``stats`` has ``impulses`` (N+1, m), ``impacts`` (the located impacts:
    time, contacts struck, impulses, normal velocities before and after, energy lost, the
    velocities ``udot_before``, ``udot_after``), ``unlocated_steps``
    (steps whose impacts accumulated beyond ``max_events``, taken by the plain rule), ``theta``
    and ``energy`` (cumulative ``external_work``, ``damping``, ``impact_loss``,
    ``numerical_dissipation``, (N+1,) each; :func:`unilateral.analysis.rigid.energy_balance`).

    ``bilateral=True`` holds every contact at its initial opening (impulses of either sign): the
    "without uplift" reference of a model file.

    Options
    -------
    locate : bool, locate the impacts within the step (default True; False: the plain
        Moreau-Jean scheme, the impact at the end of the step in which it occurs)
    max_events : int, the most impacts located in one step (default 16)
    """

    name = "moreau-jean"
    options = ("locate", "max_events")
    cq_rules_only = False

    def applies(self, model, rule) -> str | None:
        reason = super().applies(model, rule)
        if reason is not None:
            return reason
        others = _not_rigid(model)
        if not model.m:
            return ("method='moreau-jean' is for rigid contacts (Frame2D/Frame3D.contact, rigid_block, rigid_box); "
                    "this model has no unknowns: use method='direct'")
        if others:
            return (f"method='moreau-jean' solves models whose every unknown is a rigid contact (H = 0: "
                    f"Frame2D.contact, rigid_block); {len(others)} are not ({', '.join(map(repr, others[:4]))}"
                    f"{', ...' if len(others) > 4 else ''}): use method='direct'")
        massless = _massless_contact_dofs(model)
        if massless:
            return (f"method='moreau-jean': rigid contacts move DOFs without mass ({', '.join(massless[:4])}"
                    f"{', ...' if len(massless) > 4 else ''}), whose velocity the velocity-level impact law does "
                    "not define (their velocities are not held by their inertia: the march's impacts go wrong); give "
                    "them mass (Frame2D.mass(node, m, J=...): a floor node's rotary inertia J) or use method='direct'")
        if rule.name not in THETA:
            return (f"rule={rule.name!r}: method='moreau-jean' is the theta-method; valid rules: 'trapezoidal' "
                    "(theta = 1/2) or 'bdf1' (theta = 1)")
        return None

    def solve(self, model, load, initial, disc, run):
        march = self.start(model, load, initial, disc, run)
        return march.solution(march.extend(disc.N))

    def start(self, model, load, initial, disc, run):
        """The march begun at the initial state; it steps as it is asked to (``stats["stepping"]``
        ``"step"``)."""
        locate = self.config.get("locate", True)
        if not isinstance(locate, bool):
            raise TypeError(f"{self.option_name}['locate'] must be True or False, got {V.describe(locate)}")
        max_events = self.config.get("max_events", 16)
        if isinstance(max_events, bool) or not isinstance(max_events, (int, np.integer)) or max_events < 0:
            raise ValueError(f"{self.option_name}['max_events'] must be an integer >= 0, got {V.describe(max_events)}")
        system = system_of(model, load, disc.dt)
        u0, udot0, message = start_state(model, system, initial)
        run.stats.update(n=model.n, theta=THETA[disc.rule.name], locate=locate, stepping="step")
        if message:
            raise ValueError(f"initial={initial!r}: {message}")
        run.timer.lap("initial")
        march = MoreauJeanMarch(system, disc.dt, disc.N, u0, udot0, theta=THETA[disc.rule.name],
                                solver=run.solver, locate=locate, max_events=max_events, bilateral=run.bilateral)
        return MoreauJeanRun(model, march, disc, run)


class MoreauJeanRun:
    """The run of a :class:`~unilateral.march.impact.MoreauJeanMarch` (the interface of
    :mod:`unilateral.methods.stepping`): ``extend(k)``, ``state(k)``, ``solution(K)``."""

    def __init__(self, model, march, disc, run):
        self.model, self.march, self.disc, self.run, self.N = model, march, disc, run, disc.N

    @property
    def done(self) -> int:
        return self.march.done

    @property
    def failure(self) -> str:
        return self.march.log.failure

    def extend(self, k: int) -> int:
        march, callback = self.march, self.run.callback
        while march.done < min(k, self.N) and not march.log.failure:
            march.run(march.done + 1)
            if callback is not None:
                callback(march.done, self.N)
        if march.done >= self.N or march.log.failure:
            self.run.timer.lap("steps")
        return march.done

    def state(self, k: int):
        from ..result import State

        m = self.march
        v = m.P[k] / self.disc.dt if k else forces_at_rest(m.s, m.u[0], m.udot[0])[0]
        return State(t=float(self.disc.t[k]), k=k, u=m.u[k].copy(), udot=m.udot[k].copy(), v=v,
                     psi=-m.s.opening(m.u[k], float(self.disc.t[k])))

    def solution(self, K: int):
        import copy

        run = copy.copy(self.run)
        run.stats = dict(self.run.stats)
        if K < self.march.done:
            log = copy.copy(self.march.log)
            log.failure = ""
        else:
            log = self.march.log
        return _solution(self.model, self.march, self.disc, run, K, log)


def _not_rigid(model) -> list:
    """Names of the unknowns of ``model`` that are not rigid contacts."""
    rigid = np.zeros(model.m, dtype=bool)
    for family in getattr(model, "families", ()):
        if family.impact_law:
            rigid[family.indices] = True
    return [model.constraint_names[i] for i in np.flatnonzero(~rigid)]


def _massless_contact_dofs(model) -> list:
    """Names of the DOFs without mass that a rigid contact's column moves (``F``'s rows of the
    unknowns with an impact law; a floor node's rotation under a block standing on it)."""
    from ..linalg import dense

    rigid = [f for f in getattr(model, "families", ()) if f.impact_law]
    cols = np.concatenate([f.indices for f in rigid] or [[]]).astype(int)
    if cols.size == 0:
        return []
    moved = np.any(dense(model.F)[:, cols] != 0.0, axis=1)
    for f in rigid:                                 # the tangents of the contacts with friction
        if getattr(f, "tangent", None) is not None:
            tangent = np.asarray(f.tangent)                # (n, mr) in 2-D, (n, mr, 2) in 3-D
            moved |= np.any(tangent.reshape(tangent.shape[0], -1) != 0.0, axis=1)
    return [model.dof_names[i] for i in np.flatnonzero(moved & ~(np.diag(dense(model.M)) > 0))]


def start_state(model, system, initial):
    """``(u0, udot0, message)`` of ``initial`` (see :class:`MoreauJean`); ``message`` says why a
    static state was not found ("" otherwise)."""
    from ..initial import static_state
    from ..lcp import get_lcp_solver
    from ..model import check_definite

    n = model.n
    if isinstance(initial, dict):
        unknown = set(initial) - {"u0", "udot0", "v0"}
        if unknown:
            raise ValueError(f"initial has unknown keys {sorted(unknown)}; valid keys: 'u0', 'udot0', 'v0'")
        return (V.as_vector("initial['u0']", initial.get("u0", 0.0), n),
                V.as_vector("initial['udot0']", initial.get("udot0", 0.0), n), "")
    if not isinstance(initial, str):
        raise TypeError(f"initial must be 'static', 'rest' or a dict of u0, udot0; got {V.describe(initial)}")
    if V.choice("initial", initial, ("static", "rest")) == "rest":
        return np.zeros(n), np.zeros(n), ""
    try:
        check_definite("K", model.K, strict=True)
        definite = True
    except ValueError:
        definite = False
    if definite:
        init = static_state(model, system.q(0.0), get_lcp_solver("bpp"))
        return init.u, np.zeros(n), init.message
    return _held_static(system, n)


def _held_static(system, n):
    """``(u, udot = 0, message)``: the static state with the rigid contacts that touch at ``u = 0``
    held closed, ``K u = q(0) + N_A lam``, ``N_A^T u = g_A``, accepted where the held structure is
    stable (``Z^T K Z`` positive definite on the motions ``Z`` the held contacts allow) and every
    held contact is compressed (``lam >= 0``)."""
    import scipy.linalg as sla

    s = system
    A = np.flatnonzero(s.opening(np.zeros(n), 0.0) <= 0.0)
    F = A[s.mu[A] > 0]                              # with friction: held tangentially too (sticking)
    axes = np.flatnonzero(np.isin(s.cones.axis_of, F))
    NA = np.hstack([s.N[:, A], s.T[:, axes]])
    Z = sla.null_space(NA.T) if A.size else np.eye(n)
    if Z.shape[1] and np.linalg.eigvalsh(Z.T @ s.K @ Z).min() <= 0:
        return None, None, ("K is not definite (a free or rocking body) and the rigid contacts that touch at u = 0 "
                            f"({A.size} of them) do not hold it: no static state; give initial='rest' or "
                            "{'u0': ..., 'udot0': ...}")
    k = NA.shape[1]
    saddle = np.block([[s.K, -NA], [NA.T, np.zeros((k, k))]])
    rhs = np.concatenate([np.asarray(s.q(0.0), dtype=float), s.g(0.0)[A], np.zeros(axes.size)])
    if k and np.linalg.matrix_rank(NA) < k:            # redundant held rows (two corners' tangents, a 3-D box's
        x = np.linalg.lstsq(saddle, rhs, rcond=None)[0]     # four corners on uz, rx, ry): the least-norm forces
    else:
        x = np.linalg.solve(saddle, rhs)
    lam, shear = x[n:n + A.size], np.zeros(s.T.shape[1])
    shear[axes] = x[n + A.size:]
    normal = np.zeros(s.N.shape[1])
    normal[A] = lam
    if s.cones.outside(shear, normal, s.mu):
        return None, None, ("the static state with the touching rigid contacts held needs more friction than mu "
                            "gives (it slides at once); give initial='rest' or {'u0': ..., 'udot0': ...}")
    if np.any(lam < -1e-9 * (1.0 + np.abs(lam).max(initial=0.0))):
        bad = int(A[np.argmin(lam)])
        return None, None, (f"the static state with the touching rigid contacts held pulls contact {bad} "
                            f"(force {lam.min():.3g} < 0); give initial='rest' or {{'u0': ..., 'udot0': ...}}")
    return x[:n], np.zeros(n), ""


def _solution(model, march, disc, run, K, log):
    """The :class:`~unilateral.result.Solution` of the steps ``0..K``."""
    u, ud, P = march.u[:K + 1], march.udot[:K + 1], march.P[:K + 1]
    t = disc.t[:K + 1]
    opening = u @ march.s.N - np.array([march.s.g(tk) for tk in t])
    names = list(model.constraint_names)
    impacts = [{**ev, "contacts": [names[j] for j in ev["contacts"]], "udot_before": ev["udot_before"].tolist(),
                "udot_after": ev["udot_after"].tolist()} for ev in march.events if ev["time"] <= t[-1]]
    run.stats.update(impulses=P, impacts=impacts, unlocated_steps=march.unlocated_steps,
                     energy={name: march.work[:K + 1, i].copy() for i, name in enumerate(WORK_TERMS)})
    v = P / disc.dt
    v[0] = forces_at_rest(march.s, u[0], ud[0])[0]
    return finish(model, run, log, t=t, v=v, psi=-opening, psiL=np.zeros_like(v), u=u, udot=ud)
