"""``pushover(...)``: a static pushover of a structure by path-following of its parametric LCP."""

from __future__ import annotations

import math
import numbers
import time

import numpy as np

from .control import as_structure_and_model, control_vector, static_model_of
from .geometry import with_p_delta
from .path import follow_path
from .patterns import direction_vector, load_pattern
from .problem import parametric_lcp
from .rates import rate_form
from .result import Event, PushoverResult

#: The ways of driving the path.
CONTROLS = ("displacement", "load")


def pushover(structure_or_model, pattern, *, node, dof="ux", target, gravity=None, control="displacement",
             p_delta=None, max_events=200, lcp="bpp") -> PushoverResult:
    """Static pushover: gravity first, then ``lambda`` times a lateral pattern, followed exactly.

    The static problem ``K u = q_g + lambda p + F v``, ``psi = F^T u - H v - g`` with the model's
    constraint laws (contacts, plastic multipliers of perfectly plastic or linearly hardening
    hinges and links, friction slips) is piecewise linear in ``lambda``; the path is followed from
    event to event (:mod:`unilateral.pushover.path`), each event found exactly.

    Parameters
    ----------
    structure_or_model : Frame2D (built here), Structure, or unilateral.Model
    pattern : (n,) array_like (force), or ``"uniform"``, ``"triangular"`` (not for a bare Model),
        ``"mode"`` (:mod:`unilateral.pushover.patterns`; scaled so that the load factor is the base
        shear per unit mass)
    node : the control node (a bare Model: a DOF index or name, see :mod:`unilateral.pushover.control`)
    dof : ``"ux"``, ``"uy"`` or ``"rz"``: the control DOF of ``node`` and the direction of a named
        pattern and of the base shear
    target : float, or a sequence of floats (a cyclic history: the path reverses at each)
        ``control="displacement"``: the control DOF's displacement to reach (length or rad, total:
        gravity's part included), the first beyond the gravity state in the sense the pattern
        pushes it; ``control="load"``: the load factor to reach (the first > 0)
    gravity : None, a float ``g`` (a structure: :meth:`Structure.gravity` on its masses, length/time^2)
        or a load vector (n,) (force): the static state the pattern starts from
    control : ``"displacement"`` (the load factor is free and the control DOF prescribed: plateaus
        and softening are followed) or ``"load"`` (stops at a mechanism)
    p_delta : None (the structure's ``K`` as built, with ``Frame2D.p_delta`` if it was set),
        ``False`` (without), ``"consistent"`` or ``"string"``: the geometric stiffness of the
        axial forces of ``gravity`` (:mod:`unilateral.pushover.geometry`)
    max_events : int, the most event points before giving up (> 0)
    lcp : str or LCPSolver, the LCP solver of the gravity state and of the rate problems

    Returns
    -------
    PushoverResult

    Raises
    ------
    ValueError
        A bad argument (the message names it, its value and what is valid), or no static
        equilibrium under gravity.
    """
    start = time.perf_counter()
    if control not in CONTROLS:
        raise ValueError(f"control={control!r} is not valid; use 'displacement' or 'load'")
    if not isinstance(max_events, numbers.Integral) or isinstance(max_events, bool) or max_events < 1:
        raise ValueError(f"max_events={max_events!r} is not valid; give a positive integer")
    targets = _targets(target)
    structure, model = as_structure_and_model(structure_or_model)
    q_g = _gravity(structure, model, gravity)
    if p_delta is not None:
        if structure is None:
            raise ValueError(f"p_delta={p_delta!r} needs the beams' axial forces: give a structure (Frame2D or "
                             "Structure), not a bare Model (or put the geometric stiffness in the model's K)")
        structure = with_p_delta(structure, p_delta, q_g)
        model = static_model_of(structure)
    e, label = control_vector(structure, model, node, dof)
    p = load_pattern(structure, model, pattern, dof)
    problem = parametric_lcp(model, p, q_g, e, solver=lcp)
    outcome, state = None, None
    for k, (t_end, sense) in enumerate(_segments(problem, control, targets, label)):
        outcome = follow_path(problem, rate_form(problem, control, sense), t_end, control=control,
                              max_events=int(max_events), solver=lcp, state=state, out=outcome)
        state = outcome.state
        if not outcome.success:
            break
    if outcome.success and len(targets) > 1:
        outcome.message = f"history of {len(targets)} targets followed ({len(outcome.events)} events)"
    elif not outcome.success and len(targets) > 1:
        outcome.message = f"target {k} of {len(targets)} ({targets[k]:.6g}) not reached: {outcome.message}"
    r = direction_vector(structure, model, dof) if dof in ("ux", "uy", "uz") else np.ones(model.n)
    return _result(problem, outcome, float(r @ p), label, start, control)


def _targets(target) -> list:
    """``target`` as a list of finite floats (one, or a cyclic history)."""
    if np.ndim(target) == 0:
        return [_real("target", target)]
    values = list(np.asarray(target, dtype=object).ravel()) if np.ndim(target) == 1 else None
    if not values:
        raise ValueError(f"target={target!r} is not valid; give a number or a nonempty list of numbers")
    out = [_real(f"target[{k}]", value) for k, value in enumerate(values)]
    for k in range(1, len(out)):
        if out[k] == out[k - 1]:
            raise ValueError(f"target[{k}]={out[k]!r} repeats target[{k - 1}]: consecutive targets of a history "
                             "must differ")
    return out


def _real(name, value) -> float:
    """``value`` as a finite float, or a ValueError naming ``name``."""
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} is not valid; give a finite number") from None
    if not math.isfinite(out):
        raise ValueError(f"{name}={value!r} is not valid; give a finite number")
    return out


def _gravity(structure, model, gravity) -> np.ndarray:
    """The gravity load (n,): none, ``g`` on a structure's masses, or a given vector."""
    if gravity is None:
        return np.zeros(model.n)
    if isinstance(gravity, numbers.Real) and not isinstance(gravity, bool):
        if structure is None:
            raise ValueError(f"gravity={gravity!r}: a bare Model has no masses to weigh; give the gravity load as "
                             f"a vector of shape ({model.n},)")
        return structure.gravity(_real("gravity", gravity))
    q = np.asarray(gravity, dtype=float)
    if q.shape != (model.n,) or not np.all(np.isfinite(q)):
        raise ValueError(f"gravity must be None, g (a number) or a finite load vector of shape ({model.n},); got "
                         f"{'an array of shape ' + str(q.shape) if q.shape != (model.n,) else 'non-finite entries'}")
    return q


def _segments(problem, control, targets, label) -> list:
    """``[(t_end, sense), ...]``: the cumulative path parameter at each target and the sense of
    each segment (``+-1``: of the control displacement, or of the load factor)."""
    if control == "load":
        if not targets[0] > 0.0:
            raise ValueError(f"target={targets[0]!r} is not valid under control='load': give the load factor to "
                             "reach, > 0 (reverse the pattern to push the other way)")
        start, sense = 0.0, 1.0
    else:
        if problem.dp == 0.0:
            raise ValueError(f"the pattern does not move the control DOF {label} (its elastic displacement is 0); "
                             "choose another control DOF or use control='load'")
        start = problem.control(problem.u0)
        sense = math.copysign(1.0, problem.dp)
        if not (targets[0] - start) * sense > 0.0:
            side = ">" if sense > 0 else "<"
            raise ValueError(f"target={targets[0]!r} is of the wrong sign: the pattern pushes {label} in the "
                             f"{'positive' if sense > 0 else 'negative'} sense from its gravity value {start:.6g}; "
                             f"give a target {side} {start:.6g} (or reverse the pattern)")
    out, t, here = [], 0.0, start
    for value in targets:
        t += abs(value - here)
        out.append((t, math.copysign(1.0, value - here)))
        here = value
    return out


def _result(problem, outcome, resultant, label, start, control) -> PushoverResult:
    """Assemble the :class:`PushoverResult` of a followed path."""
    t = np.array([pt[0] for pt in outcome.points])
    lam = np.array([pt[1] for pt in outcome.points])
    v = np.array([pt[2] for pt in outcome.points])
    u = np.array([problem.u(lk, vk) for lk, vk in zip(lam, v)])
    psi = np.array([problem.phi(uk, vk) for uk, vk in zip(u, v)])
    d = u @ problem.e
    names = problem.names
    events = [Event(float(lam[k]), float(d[k]), names[i], kind, int(k)) for k, i, kind in outcome.events]
    stats = {"events": len(events), "points": len(t), "rate_problems": outcome.rate_problems,
             "lcp_iterations": outcome.iterations + problem.gravity_iterations,
             "max_residual": max(problem.residual(lk, uk, vk) for lk, uk, vk in zip(lam, u, v)),
             "max_lcp_error": _lcp_error(problem, v, psi), "mechanism": outcome.mechanism, "control": control,
             "time": time.perf_counter() - start}
    return PushoverResult(success=outcome.success, message=outcome.message, stats=stats, parameter=t,
                          load_factor=lam, displacement=d, base_shear=lam * resultant, u=u, v=v, psi=psi,
                          events=events, pattern=problem.p, gravity=problem.q0 - problem.model.q_imposed(0.0),
                          dof_names=tuple(problem.model.dof_names), constraint_names=tuple(names),
                          control_dof=label)


def _lcp_error(problem, v, psi) -> float:
    """The largest violation of the constraint laws along the path, relative to the sizes of ``psi``
    and ``v``: ``psi <= 0``, ``v >= 0``; contacts ``v psi = 0`` at each point; rate unknowns grow
    only where ``psi = 0`` at both ends of a segment."""
    if v.shape[1] == 0:
        return 0.0
    ps = max(float(np.max(np.abs(psi))), float(np.max(np.abs(problem.model.g(0.0)), initial=0.0)),
             np.finfo(float).tiny)
    vs = max(float(np.max(np.abs(v))), np.finfo(float).tiny)
    err = max(float(np.max(psi)) / ps, float(np.max(-v)) / vs, 0.0)
    rate = problem.rate
    contact = np.minimum(v[:, ~rate] / vs, -psi[:, ~rate] / ps)
    err = max(err, float(np.max(np.abs(contact), initial=0.0)))
    if len(v) > 1 and rate.any():
        grow = np.diff(v[:, rate], axis=0) / vs
        for end in (psi[:-1, rate], psi[1:, rate]):
            err = max(err, float(np.max(np.abs(np.minimum(grow, -end / ps)), initial=0.0)))
    return err
