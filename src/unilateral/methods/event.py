"""``method="event"``: the exact event-driven reference for small models."""

from __future__ import annotations

import numpy as np

from ..march.event import EventMarch
from ..march.event_load import load_generator
from ..result import Solution, State
from .base import Method
from .common import failed_at_start, initial_state, step_loads
from .stepping import SolvedRun
from .rigid import refusal as rigid_refusal


class Event(Method):
    """Exact integration between contact changes, events located by root finding.

    Between two contact changes the model is linear: it is integrated exactly with matrix
    exponentials of the load-augmented first-order system (:mod:`unilateral.march.event`), and
    the changes are located on the exact solution to ``tol`` (1e-13 s by default). The loads must
    have an exact piecewise form: a :class:`~unilateral.loads.LoadHistory` of the package's time
    functions and records, an array (taken as piecewise linear between the grid samples) or None.
    The output on the grid is the left limit at each ``t_k``; the rule is not used. For small
    models (n up to a few hundred): it is the yardstick of the convergence tests. The events are
    bracketed on a sub-grid at half a radian of the fastest oscillation, evaluated only where a
    modal bound cannot rule out a crossing: a stiff structure (axially rigid columns) costs about
    one matrix-vector product per output step away from the events, not ``duration x fastest
    frequency`` sub-steps (``benchmarks/event_speed.py``).

    Yield and friction families (:mod:`unilateral.constraints`) are followed the same way: a
    yielding or slipping multiplier is free with its constraint function held at zero, an
    inactive one is held at its frozen value; friction whose normal contact is a Kelvin element
    is refused (use ``cq``, ``modal`` or ``direct``).

    The bilateral case (``bilateral=True``, the reference of a model file's
    ``bilateral_reference``) has no contact change to follow: it is solved by ``method="direct"``
    with the run's rule, and ``stats["bilateral_method"]`` is ``"direct"``.

    ``stats`` has ``event_times``, ``event_constraints``, ``event_kinds`` ("open"/"close",
    "yield"/"unload", "slip"/"stick") and ``contact_changes``.

    The march stops, and the Solution has ``success=False``, a message saying why and the grid up
    to there, when it makes more than ``max_events`` contact changes, finds no admissible contact
    set, or the motion grows without bound (a configuration whose stiffness is not positive
    semidefinite).

    Options
    -------
    tol : float, the accuracy of the event times, s
    max_events : int, the most contact changes (chattering, changes accumulating at one time),
        allowed in proportion to the time reached; default 100 per output step and unknown,
        ``100 (N + 1) m``, proportional to the duration ``t_end``
        (:func:`unilateral.march.event.default_max_events`)
    """

    name = "event"
    options = ("tol", "max_events")
    cq_rules_only = False

    def refusal(self, model) -> str | None:
        """None, or why not: rigid contacts (no impact law, :mod:`.rigid`)."""
        return rigid_refusal(model, self.name)

    def solve(self, model, load, initial, disc, run):
        march = self.start(model, load, initial, disc, run)
        return march.solution(march.extend(disc.N))

    def start(self, model, load, initial, disc, run):
        """The event march begun at the initial state, followed as far as it is asked for."""
        if run.bilateral:
            return _bilateral(model, load, initial, disc, run)
        run.stats.pop("rule", None)
        run.stats["n"] = model.n
        load_generator(model, load, disc.t)           # refuses loads without an exact form, clearly
        loads = step_loads(model, load, disc)
        init = initial_state(model, loads.q_static, initial, run.solver)
        if init.message:
            return SolvedRun.of(failed_at_start(model, init, run), disc.N)
        run.timer.lap("initial")
        march = EventMarch.of(model, load, disc.t, init.u, init.udot, init.v,
                              tol=self.config.get("tol", 1e-13), max_events=self.config.get("max_events"))
        return EventRun(model, run, disc, march, self.config.get("tol", 1e-13))


def _bilateral(model, load, initial, disc, run):
    """The bilateral case (every constraint held, ``bilateral=True``): no contact change to follow,
    so it is solved by ``method="direct"`` (its bilateral sweep, with the run's rule); the
    statistics say so (``bilateral_method``)."""
    from .direct import Direct

    run.stats["bilateral_method"] = "direct"
    run.stats["method_note"] = (f"method='event' follows contact changes, which a bilateral case has none of: "
                                f"solved by method='direct' (rule={disc.rule.name!r})")
    return Direct().start(model, load, initial, disc, run)


class EventRun:
    """The event march as a run (:mod:`unilateral.methods.stepping`): pulled step by step."""

    def __init__(self, model, run, disc, march, tol):
        self.model, self.run, self.disc, self.march, self.tol = model, run, disc, march, tol
        self.N = disc.N
        run.stats["stepping"] = "step"

    @property
    def done(self) -> int:
        return self.march.done

    @property
    def failure(self) -> str:
        return self.march.failure

    def extend(self, k: int) -> int:
        return self.march.extend(k)

    def state(self, k: int) -> State:
        u, ud, v, psi = (array[k].copy() for array in self.march.out)
        return State(t=float(self.disc.t[k]), k=k, u=u, udot=ud, v=v, psi=psi)

    def solution(self, K: int) -> Solution:
        u, udot, v, psi, info = self.march.outputs()
        u, udot, v, psi = u[:K + 1], udot[:K + 1], v[:K + 1], psi[:K + 1]
        self.run.timer.lap("steps")
        failure = info.pop("failure") if K == self.done else None     # before the failed step: none yet
        info.pop("failure", None)
        stats = dict(self.run.stats)
        stats.update({key: (value.tolist() if isinstance(value, np.ndarray) else value)
                      for key, value in info.items()})
        stats.update(contact_changes=int(info["events"]), steps_done=K, time=self.run.timer.laps())
        N = self.N
        if failure:
            message = f"stopped after {K} of {N} steps: {failure}"
        else:
            so_far = f"{K} of {N} steps so far" if K < N else f"{N} steps"
            message = f"{so_far}, {info['events']} contact changes (exact, events to {self.tol:g} s)"
        return Solution(t=self.disc.t[:K + 1], v=v, psi=psi, psiL=None, u=u, udot=udot, success=failure is None,
                        message=message, stats=stats, dof_names=list(self.model.dof_names),
                        constraint_names=list(self.model.constraint_names))
