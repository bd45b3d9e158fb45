"""One entry point for dynamic analyses: :func:`solve` checks, chooses a method and calls it."""

from __future__ import annotations

import os

from . import _validate as V
from .discretization import Discretization
from .rules import alias_note
from .kernels import KernelModel, TimeKernelModel
from .methods import METHODS, choose_method, fallback, get_method
from .methods.stiff import StiffCoordinates
from .model import Model
from .result import Solution
from .soil.foundation_model import FoundationModel
from .run_context import RunContext

__all__ = ["METHODS", "solve"]

#: The problems :func:`solve` takes.
MODEL_CLASSES = (Model, KernelModel, TimeKernelModel, FoundationModel)


def solve(model, load=None, *, dt, t_end, method="auto", rule="bdf2", initial="static",
          lcp="bpp", lcp_options=None, bilateral=False, cq_options=None, modal_options=None,
          direct_options=None, callback=None) -> Solution:
    """Dynamic response of a structure with unilateral constraints.

    Parameters
    ----------
    model : Model, KernelModel or TimeKernelModel
    load : callable ``q(t) -> (n,)``, array (N+1, n) or LoadHistory, optional
        Total applied load (gravity included) at ``t_k = k dt``; ``N = round(t_end / dt)``.
        Not used by kernel models (their ``psiL`` carries the loading).
    dt : float
        Time step, > 0.
    t_end : float
        End time, >= dt.
    method : str, Method subclass or Method instance
        A name of :data:`unilateral.methods.METHODS`, or ``"auto"`` (default): the fastest
        correct method for the model at hand, reported in ``stats["method"]`` with the reason in
        ``stats["method_reason"]`` (:func:`unilateral.methods.choose_method`): ``"direct"`` for a
        :class:`Model` (compiled stepping: dense for small models, in the full sparse space for
        large ones; ``"modal"`` for a small model with a rule object of the user's own),
        ``"modal"`` or ``"cq"`` for a foundation on a soil, ``"cq"`` for a :class:`KernelModel`,
        ``"time-kernel"`` for a :class:`TimeKernelModel`.
        ``"cq"``: the convolutional LCP of Liolios (1990), eq. (27), with convolution-quadrature
        weights of ``Lambda(s)``, one LCP per step. ``"modal"``: the same CLCP with the history
        evaluated recursively from the poles and residues of ``Lambda(s)``, O(r m) per step.
        ``"direct"``: the full model stepped with the same rule and one LCP per step (also
        Newmark and HHT).
    rule : str or Rule
        ``"bdf1"``, ``"bdf2"`` (default), ``"trapezoidal"``; ``"newmark"`` is Newmark(1/2, 1/4),
        the trapezoidal rule, with every method (recorded as ``"trapezoidal"``, with the
        statistic ``rule_note`` saying so); with ``method="direct"`` also ``"hht"`` or a
        :class:`~unilateral.rules.Newmark` instance.
    initial : "static", "rest" or dict
        ``"static"``: start at rest from the static unilateral equilibrium under ``q(0)``.
        ``"rest"`` (kernel models): ``v(0) = 0``. A dict with ``u0``, ``udot0``, ``v0``
        (kernel models: ``v0`` only) gives the initial conditions, eqs. (10)-(12).
    lcp : str or LCPSolver
        ``"bpp"`` (block principal pivoting, default), ``"lemke"``, ``"pgs"``, ``"newton"``,
        ``"enumerate"``, or a solver instance.
    lcp_options : dict, optional
        Options for a named solver (e.g. ``{"tol": 1e-12}``).
    bilateral : bool
        Hold every constraint at its initial state (``v = v(0)``, e.g. the static one): the
        paper's "without uplift" case. A gap that is open statically stays open by as much.
    cq_options, modal_options, direct_options : dict, optional
        Options of ``method="cq"`` (``L``, ``rho``, ``history``, ``engine``),
        ``method="modal"`` (``modes``, ``engine``) and ``method="direct"`` (``engine``); see
        :class:`~unilateral.methods.CQ`, :class:`~unilateral.methods.Modal` and
        :class:`~unilateral.methods.Direct`.
    callback : callable ``callback(k, N)``, optional
        Called after every step (progress bars).

    Returns
    -------
    Solution
    """
    disc = Discretization.from_user(dt, t_end, rule)
    if not isinstance(model, MODEL_CLASSES):          # the boundary: what solve() takes
        raise TypeError(f"model must be a unilateral.Model, KernelModel, TimeKernelModel or FoundationModel, "
                        f"got {V.describe(model)}")
    options = {name: value for name, value in (("cq", cq_options), ("modal", modal_options),
                                               ("direct", direct_options)) if value is not None}
    if isinstance(model, TimeKernelModel) and (method != "auto" or load is not None or options
                                               or disc.rule.name != "bdf2"):
        raise ValueError(
            "a TimeKernelModel is solved by product integration of its time-domain kernel: "
            "pass only dt, t_end, initial, lcp, lcp_options, bilateral (method='auto', load=None)")
    run = RunContext.from_user(lcp, lcp_options, bilateral, callback)
    if run.solver.symmetric_only and not model.law.symmetric:
        raise ValueError(f"lcp={run.solver.name!r} needs a symmetric step LCP, but the friction constraints make "
                         "it nonsymmetric (rows +-T - mu N): use lcp='bpp' (the default) or 'lemke'")
    stiff = StiffCoordinates.of(model)      # penalty-stiff elements: solve in separated coordinates
    if stiff is not None:
        model, load, initial = stiff.conditioned, stiff.load(load, disc.N), stiff.initial(initial)
    auto = isinstance(method, str) and method.lower() == "auto"
    if auto:
        chosen, reason = choose_method(model, disc.rule, run.solver, options)
    else:
        chosen = get_method(method)
        for name, value in options.items():
            if name != chosen.name:
                raise ValueError(f"{name}_options apply to method={name!r} only (method={chosen.name!r})")
            chosen = type(chosen)(**value)
    chosen.check(model, disc.rule)
    _check_memory(chosen, model, disc)
    run.stats.update(method=chosen.name, rule=disc.rule.name, lcp_solver=run.solver.name, steps=disc.N,
                     dt=disc.dt, m=model.m)
    if auto:
        run.stats["method_reason"] = reason
    note = alias_note(rule, disc.rule)
    if note:
        run.stats["rule_note"] = note
    run.timer.lap("setup")
    try:
        sol = chosen.solve(model, load, initial, disc, run)
    except ValueError as exc:
        other = fallback(exc) if auto else None
        if other is None:
            raise
        chosen, run.stats["method_reason"] = other[0], f"{reason}; {other[1]}"
        run.stats["method"] = chosen.name
        sol = chosen.solve(model, load, initial, disc, run)
    return sol if stiff is None else stiff.solution(sol)


#: A run may use at most this fraction of the machine's memory.
MEMORY_FRACTION = 0.5


def _check_memory(method, model, disc) -> None:
    """Refuse a run whose arrays would not fit, with the estimate and what to change."""
    parts = method.memory_estimate(model, disc)
    need = sum(parts.values())
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):         # not a POSIX system
        return
    if need > MEMORY_FRACTION * total:
        what = "; ".join(f"{text}: {size / 2**30:.3g} GiB" for text, size in parts.items())
        raise MemoryError(
            f"t_end/dt = {disc.N} steps with method={method.name!r} would need about {need / 2**30:.3g} GiB "
            f"({what}), more than {MEMORY_FRACTION:.0%} of this machine's {total / 2**30:.3g} GiB: "
            "increase dt, shorten t_end" + _memory_hint(method, model))


def _memory_hint(method, model) -> str:
    """What else lowers the memory of ``method`` on ``model``: the methods without stored weights,
    where they apply; fewer patches for a soil that only ``cq`` takes."""
    if method.name != "cq":
        return ""
    soil = getattr(model, "soil", None)
    if soil is not None and not (soil.is_rational or soil.kelvin is not None):
        return (f", or cut the footings into fewer patches (the weights grow as the square of the "
                f"{model.m} soil unknowns; this soil is solved by method='cq' only)")
    return " or use method='modal' or 'direct' (no stored weights)"
