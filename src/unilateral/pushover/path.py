"""Path-following of the parametric LCP: from event to event, exactly (Maier's incremental analysis).

With contacts and piecewise-linear yield and friction laws (perfectly plastic or linearly
hardening), the static path is piecewise linear in the path parameter ``t``: between two events
the sets of open, loading and inactive constraints are fixed and ``v``, ``lambda``, ``u`` and
``psi`` are linear in ``t`` (their rates solve :func:`~unilateral.pushover.rates.solve_rates`). The
next event is the smallest step at which

* an inactive constraint's function ``phi`` reaches 0 (a hinge or a link yields, a contact's
  force vanishes and it lifts off, a slip starts), or
* an open contact's opening ``v`` reaches 0 (it closes: contact),

and at the event the rate problem is solved anew: it decides which constraints on their surface
keep loading and which unload (``v' = 0``, ``phi' < 0``). Each event is found exactly, by the
ratio of a value to its constant rate, so the path has no step-size error.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .rates import RateForm, solve_rates

#: Events closer than this fraction of the target's parameter are one event.
TIE_TOL = 1e-12
#: Rates of ``phi`` within this fraction of the rates' size are zero (a neutral constraint stays on
#: its surface).
RATE_TOL = 1e-10


@dataclass
class PathState:
    """The state at one point of the path.

    Attributes
    ----------
    t : float, the path parameter (load factor, or distance of the control DOF from the gravity state)
    lam : float, the load factor
    v : (m,) constraint unknowns
    touch : (m,) bool, constraints on their surface (``phi = 0``)
    opened : (m,) bool, open contacts (``v > 0``; ``touch`` too)
    was_open, was_loading : (m,) bool or None, the open contacts and loading multipliers of the last
        segment (None at the start: the events of the next point are those against them)
    just_touched : (m,) bool or None, the constraints that reached their surface at this point
    """

    t: float
    lam: float
    v: np.ndarray
    touch: np.ndarray
    opened: np.ndarray
    was_open: np.ndarray | None = None
    was_loading: np.ndarray | None = None
    just_touched: np.ndarray | None = None


@dataclass
class PathOutcome:
    """What :func:`follow_path` found.

    Attributes
    ----------
    points : list of (t, lam, v (m,)), the start, every event and the end
    events : list of (point index, constraint index, kind)
    success : bool, the target was reached
    message : str
    mechanism : bool, the path ended at a mechanism (load control) or a singular tangent
    iterations : int, pivots of all rate LCPs
    rate_problems : int, rate LCPs solved
    state : PathState or None, the state at the last point
    """

    points: list = field(default_factory=list)
    events: list = field(default_factory=list)
    success: bool = False
    message: str = ""
    mechanism: bool = False
    iterations: int = 0
    rate_problems: int = 0
    state: PathState | None = None


def initial_state(problem, tol=1e-9) -> PathState:
    """The gravity state as the path's start: which constraints are on their surface or open.

    A constraint is on its surface where ``|phi| <= tol`` times the size of the constraint
    functions and offsets; a contact is open where also ``v > 0``.
    """
    v = problem.v0.copy()
    phi = problem.phi(problem.u0, v)
    size = max(float(np.max(np.abs(phi), initial=0.0)), float(np.max(np.abs(problem.model.g(0.0)), initial=0.0)),
               np.finfo(float).tiny)
    touch = np.abs(phi) <= tol * size
    opened = touch & ~problem.rate & (v > 0.0)
    return PathState(t=0.0, lam=0.0, v=v, touch=touch, opened=opened)


def follow_path(problem, form: RateForm, t_end: float, *, control: str, max_events: int,
                solver="bpp", state: PathState | None = None, out: PathOutcome | None = None) -> PathOutcome:
    """Follow the path from the gravity state (or from ``state``) to ``t = t_end``, event by event.

    Parameters
    ----------
    problem : ParametricLCP
    form : RateForm, the rates per unit ``t``
    t_end : float, the path parameter to reach (load factor, or distance travelled by the control
        DOF), ``> state.t``
    control : ``"load"`` or ``"displacement"`` (for the message of a singular tangent)
    max_events : int, the most event points followed (in all) before giving up
    solver : str or LCPSolver, the solver of the rate LCPs
    state, out : a :class:`PathState` and the :class:`PathOutcome` it ends, to go on from (a
        reversal of a cyclic history: ``form`` then has the other sense); None: the gravity state

    Returns
    -------
    PathOutcome (``out`` extended, with the final state in ``out.state``)
    """
    if state is None:
        state = initial_state(problem)
        out = PathOutcome(points=[(0.0, 0.0, state.v.copy())])
    rate = problem.rate
    m = rate.size
    was_open = state.opened.copy() if state.was_open is None else state.was_open
    was_loading = np.zeros(m, dtype=bool) if state.was_loading is None else state.was_loading
    just_touched = np.zeros(m, dtype=bool) if state.just_touched is None else state.just_touched
    out.state = state
    while True:
        rates = solve_rates(form, state.opened, state.touch & ~state.opened, solver)
        out.iterations += rates.iterations
        out.rate_problems += 1
        if rates.singular or rates.failure:
            _record(out, just_touched & ~was_loading, rate, kinds=problem.model.law.kinds)
            out.mechanism, out.success = True, False
            out.message = _singular_message(problem, state, rates, control)
            return out
        now_open = ~rate & rates.active
        now_loading = rate & rates.active
        _record_changes(out, (was_open, was_loading), (now_open, now_loading), problem.model.law.kinds)
        was_open, was_loading = now_open, now_loading
        ds, hits, end = _next_event(problem, state, rates, t_end)
        just_touched = _advance(state, rates, ds, hits, rate)
        state.was_open, state.was_loading, state.just_touched = was_open, was_loading, just_touched
        out.points.append((state.t, state.lam, state.v.copy()))
        if end:
            out.success, out.message = True, f"target reached at t = {state.t:.6g} ({len(out.events)} events)"
            return out
        if len(out.points) - 1 >= max_events:
            out.success = False
            out.message = (f"max_events={max_events} reached at load factor {state.lam:.6g} before the target; "
                           "give a larger max_events")
            return out


def _next_event(problem, state, rates, t_end):
    """``(ds, hits (m,) bool, end)``: the step to the next event, the constraints it changes, and
    whether the target is reached first (or with it)."""
    u = problem.u(state.lam, state.v)
    phi = problem.phi(u, state.v)
    size = max(float(np.max(np.abs(rates.phidot))), np.finfo(float).tiny)
    step = np.full(phi.size, np.inf)
    rising = ~state.touch & (rates.phidot > RATE_TOL * size)
    step[rising] = np.maximum(-phi[rising], 0.0) / rates.phidot[rising]
    closing = state.opened & (rates.vdot < 0.0)
    step[closing] = state.v[closing] / -rates.vdot[closing]
    to_end = t_end - state.t
    ds = min(float(step.min(initial=np.inf)), to_end)
    tie = TIE_TOL * t_end
    hits = step <= ds + tie
    return ds, hits, to_end <= ds + tie


def _advance(state: PathState, rates, ds: float, hits, rate) -> np.ndarray:
    """Move ``state`` by ``ds`` along ``rates`` and apply the events ``hits`` ((m,) bool; ``rate``
    (m,) bool: the rate-law constraints, which never open); returns the constraints that reached
    their surface."""
    state.t += ds
    state.lam += ds * rates.lamdot
    state.v = state.v + ds * rates.vdot
    size = max(float(np.max(np.abs(rates.phidot))), np.finfo(float).tiny)
    on_surface = state.touch & ~state.opened
    if ds > 0.0:
        leaving = on_surface & (rates.vdot <= 0.0) & (rates.phidot < -RATE_TOL * size)
        state.touch = state.touch & ~leaving
        state.opened = state.opened | (on_surface & ~leaving & (rates.vdot > 0.0) & ~rate)
    closed = hits & state.opened
    state.v[closed] = 0.0
    state.opened = state.opened & ~closed
    reached = hits & ~state.touch
    state.touch = state.touch | reached
    return reached


def _record_changes(out, before, after, kinds) -> None:
    """Append the events between the sets ``(open, loading)`` before and after a point."""
    (open0, loading0), (open1, loading1) = before, after
    point = len(out.points) - 1
    for i in np.flatnonzero(open1 & ~open0):
        out.events.append((point, int(i), "uplift"))
    for i in np.flatnonzero(open0 & ~open1):
        out.events.append((point, int(i), "contact"))
    for i in np.flatnonzero(loading1 & ~loading0):
        out.events.append((point, int(i), "slip" if kinds[i] == "friction" else "yield"))
    for i in np.flatnonzero(loading0 & ~loading1):
        out.events.append((point, int(i), "unload"))


def _record(out, rows, rate, *, kinds) -> None:
    """Append the activation events of ``rows`` at the last point (the point of a mechanism)."""
    point = len(out.points) - 1
    for i in np.flatnonzero(rows):
        kind = ("slip" if kinds[i] == "friction" else "yield") if rate[i] else "uplift"
        out.events.append((point, int(i), kind))


def _singular_message(problem, state, rates, control) -> str:
    """Why the path stops where the rate problem has no regular solution."""
    names = [problem.names[i] for i in np.flatnonzero(rates.active | state.touch)]
    listed = ", ".join(names[:12]) + (" ..." if len(names) > 12 else "")
    if control == "load":
        return (f"mechanism at load factor {state.lam:.10g}: the tangent stiffness with the constraints on their "
                f"surface ({listed}) is singular ({rates.failure}); the load cannot increase. Use "
                "control='displacement' to follow the plateau or the softening branch")
    return (f"the tangent is singular at load factor {state.lam:.10g} with the constraints {listed} on their "
            f"surface ({rates.failure}): the control DOF does not move in the mechanism; control another DOF")
