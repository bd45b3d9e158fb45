"""The entry point of dynamic analyses: :class:`Simulation`, advanced step by step, and :func:`solve`,
a simulation advanced to its end.

``sim = Simulation(model, load, dt=..., t_end=...)`` checks the problem, chooses the method and
finds the initial state; ``sim.step()``, ``sim.advance(n)`` and ``sim.advance_to(t)`` perform
steps (the shape of scipy's ``OdeSolver``); ``sim.t``, ``sim.n`` and ``sim.state`` tell where it
is; ``sim.solution()`` is the :class:`~unilateral.result.Solution` of the steps so far. A step
performs the operations of a whole run: stepping in any pieces gives the same solution.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import math
import os
import warnings

import numpy as np

from . import _validate as V
from .discretization import Discretization
from .kernels import KernelModel
from .march.policy import SizePolicy, current_policy, size_policy
from .methods import METHODS, choose_method, get_method
from .methods.rigid import rule_warning
from .model.stiff import StiffCoordinates
from .model import Model
from .result import Solution, State
from .rules import alias_note
from .run_context import RunContext
from .soil.foundation_model import FoundationModel

__all__ = ["METHODS", "MODEL_CLASSES", "Simulation", "solve"]

#: The problems a simulation takes.
MODEL_CLASSES = (Model, KernelModel, FoundationModel)
#: A run may use at most this fraction of the machine's memory.
MEMORY_FRACTION = 0.5


def solve(model, load=None, *, dt, t_end, method="auto", rule="bdf2", initial="static",
          lcp="bpp", lcp_options=None, bilateral=False, cq_options=None, modal_options=None,
          direct_options=None, callback=None, policy=None) -> Solution:
    """Dynamic response of a structure with unilateral constraints.

    Parameters
    ----------
    model : Model or KernelModel (a kernel in the Laplace or the time domain), or FoundationModel
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
        ``"time-kernel"`` for a :class:`KernelModel` of a time-domain kernel.
        ``"cq"``: the convolutional LCP of Liolios (1990), eq. (27), with convolution-quadrature
        weights of ``Lambda(s)``, one LCP per step. ``"modal"``: the same CLCP with the history
        evaluated recursively from the poles and residues of ``Lambda(s)``, O(r m) per step.
        ``"direct"``: the full model stepped with the same rule and one LCP per step (also
        Newmark and HHT). ``"moreau-jean"``: rigid contacts with Newton's impact law, impacts
        located within the step (``rule="trapezoidal"`` or ``"bdf1"``; ``docs/rocking.md``).
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
    policy : SizePolicy, optional
        The size thresholds that choose the march and the BLAS threads
        (:class:`~unilateral.march.policy.SizePolicy`; default: the policy in force,
        :func:`~unilateral.march.policy.current_policy`).

    Returns
    -------
    Solution
    """
    options = {name: value for name, value in (("cq", cq_options), ("modal", modal_options),
                                               ("direct", direct_options)) if value is not None}
    return Simulation(model, load, dt=dt, t_end=t_end, method=method, rule=rule, initial=initial, lcp=lcp,
                      lcp_options=lcp_options, bilateral=bilateral, options=options,
                      callback=callback, policy=policy).run_to_end()


class Simulation:
    """A dynamic analysis of a structure with unilateral constraints, advanced on request.

    Parameters
    ----------
    model, load, dt, t_end, method, rule, initial, lcp, lcp_options, bilateral, callback, policy
        As for :func:`unilateral.solve`.
    options : dict, optional
        The options of the method by its name (``{"cq": {...}}``, ``{"direct": {"engine": ...}}``):
        what :func:`unilateral.solve` takes as ``cq_options``, ``modal_options``, ``direct_options``.

    Attributes
    ----------
    n : int, the last step performed (0 at the start);  N : int, the steps of the grid
    t : float, ``n dt`` (s);  dt, t_end : float (s)
    status : ``"running"``, ``"finished"`` (step N performed) or ``"failed"``
    message : str, why the last step failed ("" otherwise)
    method : Method, the method chosen;  stats : dict, the run's statistics so far

    Notes
    -----
    ``method="direct"`` steps one step at a time in Python and in chunks computed ahead in
    compiled code (a call into compiled code per step would cost more than a small model's step;
    the march is deterministic, so the chunk holds the steps the next calls ask for). Methods
    that march in one call (``cq``, ``modal``, ``event``, the full sparse space) march all their
    steps at the first step asked for and then hand them out: ``stats["stepping"]`` says which
    (``"step"``, ``"chunk"``, ``"whole"``).
    """

    def __init__(self, model, load=None, *, dt, t_end, method="auto", rule="bdf2", initial="static",
                 lcp="bpp", lcp_options=None, bilateral=False, options=None, callback=None, policy=None):
        if policy is not None and not isinstance(policy, SizePolicy):
            raise TypeError(f"policy must be a unilateral.SizePolicy or None, got {V.describe(policy)}")
        self.policy = current_policy() if policy is None else policy
        with size_policy(self.policy):
            self._set_up(model, load, initial, grid=(dt, t_end, rule), method=(method, options),
                         run_args=(lcp, lcp_options, bilateral, callback))

    def _set_up(self, model, load, initial, *, grid, method, run_args):
        """Check the problem, choose the method and start it (under the simulation's policy)."""
        (dt, t_end, rule), (method, options) = grid, method
        disc = Discretization.from_user(dt, t_end, rule)
        if not isinstance(model, MODEL_CLASSES):          # the boundary: what a simulation takes
            raise TypeError("model must be a unilateral.Model, KernelModel or FoundationModel, got "
                            f"{V.describe(model)}")
        options = _method_options(options)
        time_kernel = model.kind == "time kernel"
        if time_kernel and (method not in ("auto", "time-kernel") or load is not None or options
                            or disc.rule.name != "bdf2"):
            raise ValueError(
                "a KernelModel of a TimeKernel (TimeKernelModel) is solved by product integration of its "
                "time-domain kernel: pass only dt, t_end, initial, lcp, lcp_options, bilateral "
                "(method='auto', load=None)")
        run = RunContext.from_user(*run_args)
        if run.solver.symmetric_only and not model.law.symmetric:
            raise ValueError(f"lcp={run.solver.name!r} needs a symmetric step LCP, but the friction constraints "
                             "make it nonsymmetric (rows +-T - mu N): use lcp='bpp' (the default) or 'lemke'")
        self.model, self.disc, self.dt, self.t_end, self.N = model, disc, disc.dt, disc.N * disc.dt, disc.N
        self._stiff = StiffCoordinates.of(model)      # penalty-stiff elements: separated coordinates
        if self._stiff is not None:
            model, load, initial = (self._stiff.conditioned, self._stiff.load(load, disc.N),
                                    self._stiff.initial(initial))
        self._problem = (model, load, initial)
        self._auto = isinstance(method, str) and method.lower() == "auto"
        reason = None
        if self._auto:
            chosen, reason = choose_method(model, disc.rule, run.solver, options)
        else:
            chosen = _given_method(method, options)
        self._begin(chosen, run, reason, rule)

    def _begin(self, chosen, run, reason, rule):
        """Check ``chosen`` and start its run at step 0."""
        model, load, initial = self._problem
        disc = self.disc
        why_not = chosen.applies(model, disc.rule) or chosen.refusal(model)
        if why_not is not None:
            raise ValueError(f"{why_not}; the methods that apply to this problem: "
                             + (", ".join(map(repr, _applicable(model, disc.rule))) or "none"))
        _check_memory(chosen, model, disc)
        if (note := rule_warning(model, chosen.name, disc.rule)) is not None:   # rigid contacts, position level
            warnings.warn(note, stacklevel=4)
            run.stats["rigid_contact_warning"] = note
        run.stats.update(method=chosen.name, rule=disc.rule.name, lcp_solver=run.solver.name, steps=disc.N,
                         dt=disc.dt, m=model.m)
        if reason is not None:                  # method="auto": the choice, and what the others say
            run.stats["method_reason"] = reason
            run.stats["method_alternatives"] = {
                name: cls().applies(model, disc.rule) or "applies; not the fastest for this problem"
                for name, cls in METHODS.items() if name != chosen.name}
        note = alias_note(rule, disc.rule)
        if note:
            run.stats["rule_note"] = note
        run.timer.lap("setup")
        self.method, self._context = chosen, run
        self._scope = functools.partial(_scope, model, self.policy)
        with self._scope():
            self._run = chosen.start(model, load, initial, disc, run)
        self.n, self._state = 0, None
        self.status, self.message = ("failed", self._run.failure) if self._run.failure else ("running", "")

    # ------------------------------------------------------------------ where it is
    @property
    def t(self) -> float:
        """The time of the last step performed, ``n dt`` (s)."""
        return self.n * self.dt

    @property
    def stats(self) -> dict:
        return self._context.stats

    @property
    def state(self) -> State:
        """The state after step :attr:`n`: ``t``, ``k``, ``u``, ``udot``, ``v``, ``psi`` (copies)."""
        if self._state is None or self._state.k != self.n:
            state = self._run.state(self.n)
            if self._stiff is not None and state.u is not None:
                T = self._stiff.split.T
                state = dataclasses.replace(state, u=T @ state.u, udot=T @ state.udot)
            self._state = state
        return self._state

    def solution(self) -> Solution:
        """The :class:`~unilateral.result.Solution` of the steps ``0..n`` (a new object at each call)."""
        with self._scope():
            sol = self._run.solution(self.n)
        return sol if self._stiff is None else self._stiff.solution(sol)

    # ------------------------------------------------------------------ stepping
    def step(self):
        """Perform the next step; None on success, the reason if it failed (then :attr:`status`
        is ``"failed"`` and :attr:`state` stays at the last good step)."""
        return self.advance(1)

    def advance(self, steps: int = 1):
        """Perform the next ``steps`` steps (>= 1, at most those left); None, or why a step failed."""
        steps = _step_count(steps)
        self._check_can_step()
        left = self.N - self.n
        if steps > left:
            raise ValueError(f"steps = {steps} goes past t_end = {self.t_end:g} s: {left} step(s) are left "
                             f"(n = {self.n} of N = {self.N}); use advance_to(t_end) to finish")
        return self._advance_to_step(self.n + steps)

    def advance_to(self, t: float):
        """Perform the steps up to time ``t`` (the first grid time ``k dt >= t``); None, or why a
        step failed."""
        if isinstance(t, (str, bytes, bool)) or t is None or not np.isfinite(_as_float(t)):
            raise ValueError(f"t must be a finite time in s, got {V.describe(t)}")
        t = float(t)
        eps = 1e-9 * self.dt
        if t < self.t - eps:
            raise ValueError(f"t = {t:g} s is before the current time {self.t:g} s (step {self.n}): a "
                             "simulation only goes forward; start a new Simulation to go back")
        if t > self.t_end + eps:
            raise ValueError(f"t = {t:g} s is after t_end = {self.t_end:g} s: valid is {self.t:g} <= t <= "
                             f"{self.t_end:g}")
        self._check_can_step(allow_finished=True)
        k = min(self.N, max(self.n, math.ceil(t / self.dt - 1e-9)))
        return None if k == self.n else self._advance_to_step(k)

    def _check_can_step(self, allow_finished=False):
        if self.status == "failed":
            raise RuntimeError(f"the simulation failed at step {self.n + 1} (t = {self.t + self.dt:g} s): "
                               f"{self.message}; nothing more can be stepped (solution() holds steps 0..{self.n})")
        if self.status == "finished" and not allow_finished:
            raise RuntimeError(f"the simulation is at its end, t_end = {self.t_end:g} s (step {self.N}): "
                               "no step is left; start a new Simulation with a larger t_end to go further")

    def _advance_to_step(self, k: int):
        if k <= self._run.done:                 # computed ahead (a compiled chunk): no work to do
            done = self._run.done
        else:
            with self._scope(blas=k - self._run.done > 1):   # one step: setting the threads costs more
                done = self._run.extend(k)
        self.n = min(done, k)
        if done >= k:
            self.status = "finished" if self.n == self.N else "running"
            return None
        self.status, self.message = "failed", self._run.failure
        return self.message

    def run_to_end(self) -> Solution:
        """Perform every step left (or up to the one that fails); the solution."""
        if self.status == "running":
            self._advance_to_step(self.N)
        return self.solution()

    def __repr__(self) -> str:
        return (f"Simulation({self.status}: step {self.n} of {self.N}, t = {self.t:g} s, "
                f"method={self.method.name!r})")


@contextlib.contextmanager
def _scope(model, policy, blas=True):
    """A context in which ``policy`` is in force and, with ``blas``, BLAS runs with one thread if
    ``model`` is small (the policy's ``blas_one_thread_max_n``; 20 us to set and restore); the
    threads are left as they are for larger models."""
    n = getattr(model, "n", None)
    with size_policy(policy):
        if not blas or n is None or n > policy.blas_one_thread_max_n:
            yield
        else:
            with _blas_controller().limit(limits=1, user_api="blas"):
                yield


def small_model_blas(model):
    """A context in which BLAS runs with one thread if ``model`` is small (the policy in force's
    ``blas_one_thread_max_n``, as while it is solved): the results and spectra of a small model
    are made of many tiny products, which threads slow down (a 4 x 4 ``expm`` takes 5 ms with
    the threads of a loaded 2-core machine, 17 us with one)."""
    return _scope(model, current_policy())


@functools.cache
def _blas_controller():
    """The BLAS libraries of numpy and scipy (scipy's is loaded first, so that both are found)."""
    import scipy.linalg  # noqa: F401
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


def _applicable(model, rule) -> list:
    """The names of the registered methods that apply to ``model`` with ``rule``."""
    return [name for name, cls in METHODS.items()
            if cls().applies(model, rule) is None and cls().refusal(model) is None]


def _step_count(steps) -> int:
    """``steps`` as an int >= 1 (an integral number; booleans and strings are refused)."""
    if isinstance(steps, (bool, str, bytes)) or not isinstance(steps, (int, np.integer)) or steps < 1:
        raise ValueError(f"steps must be an integer >= 1, got {V.describe(steps)}")
    return int(steps)


def _as_float(x) -> float:
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


def _method_options(options) -> dict:
    """``{"cq": {...}, ...}``: the options by method name, checked."""
    if options is None:
        return {}
    if not isinstance(options, dict):
        raise TypeError(f"options must be a dict of method name -> options, got {V.describe(options)}")
    valid = ("cq", "modal", "direct")
    for name, value in options.items():
        if name not in valid:
            raise ValueError(f"options has the key {name!r}; valid keys: {', '.join(map(repr, valid))}")
        if not isinstance(value, dict):
            raise TypeError(f"options[{name!r}] must be a dict, got {V.describe(value)}")
    return dict(options)


def _given_method(method, options):
    """The method instance of a name, class or instance, with its options applied."""
    chosen = get_method(method)
    for name, value in options.items():
        if name != chosen.name:
            raise ValueError(f"{name}_options apply to method={name!r} only (method={chosen.name!r})")
        chosen = type(chosen)(**value)
    return chosen


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
