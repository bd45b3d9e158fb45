"""``method="direct"``: the full model stepped with the rule, one LCP per step."""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass

from .. import _validate as V
from ..lcp import BlockPrincipalPivoting
from ..march.active_set import ActiveSetMarch, full_space_applies
from ..march.direct import ChunkedMarch, CompiledDirectMarch, DirectMarch, march_direct
from ..march.policy import current_policy
from .base import Method
from .clcp_march import ENGINES
from .common import BaseState, failed_at_start
from .rigid import refusal as rigid_refusal
from .stepping import MarchRun, SolvedRun, WholeMarch


class Direct(Method):
    """Direct time stepping of the full model with one LCP per step.

    Every rule (BDF1, BDF2, trapezoidal, Newmark, HHT). With a rule that has a
    convolution-quadrature form, one step is one step of the CLCP with the same rule: the exact
    reference of ``cq`` and ``modal``. The LCP is solved on the condensed ``m x m`` matrix
    ``W0`` (the Schur complement of the effective stiffness, factorised once), or for sparse
    models in the full sparse space (:mod:`unilateral.march.full_space`): models with more contacts
    than the size policy's ``full_space_min_m``, and in compiled code also those of more than
    ``compiled_max_n`` DOFs with fewer contacts (constraints of the trivial law, a diagonal ``H``;
    :class:`~unilateral.march.policy.SizePolicy`). The march is the first of :data:`MARCHES` that
    applies: each says when it does.

    Options
    -------
    engine : ``"auto"`` (default: compiled where it applies: ``lcp="bpp"``, a rule of
        :mod:`unilateral.rules`, and either the condensed LCP with at most
        ``compiled_max_n`` DOFs (a dense LU of ``D_eff``) or a
        sparse model with contacts only, stepped in the full space with an envelope Cholesky
        factorisation of ``D_eff`` refactorised from the rows of the contacts that change; other
        models are stepped with sparse factorisations in Python), ``"compiled"`` (the same
        conditions, the condensed LCP with any number of DOFs; an error if none holds) or
        ``"python"``. Both engines perform the same operations and agree to round-off. Pass
        them as ``method=Direct(engine=...)``.
    """

    name = "direct"
    options = ("engine",)
    cq_rules_only = False

    def refusal(self, model) -> str | None:
        """None, or why not: friction on rigid contacts (:mod:`.rigid`)."""
        return rigid_refusal(model, self.name)

    def solve(self, model, load, initial, disc, run):
        march = self.start(model, load, initial, disc, run)
        return march.solution(march.extend(disc.N))

    def start(self, model, load, initial, disc, run):
        """The direct march of ``model`` begun at step 0 (a run that advances on request).

        The march is the first of :data:`MARCHES` that applies (``stats["march"]``; the reasons of
        the others in ``stats["march_alternatives"]``). The marches in Python step one step at a
        time, the compiled ones (condensed and full space) in chunks (``stats["stepping"]``:
        ``"step"``, ``"chunk"``); the bilateral sweep in Python marches in one call at the first
        request (``"whole"``).
        """
        engine = V.choice(f"{self.option_name}['engine']", self.config.get("engine", "auto"), ENGINES)
        run.stats["n"] = model.n
        problem = MarchProblem(model, disc, run, engine)
        candidates, reasons = pick_march(problem, f"{self.option_name}['engine']")
        base = BaseState.prepare(model, load, initial, disc, run, tables=candidates[0].engine == "compiled")
        if base.init.message:
            return SolvedRun.of(failed_at_start(model, base.init, run), disc.N)
        run.timer.lap("initial")
        march = None
        for spec in candidates:
            march = spec.begin(base, disc, run)
            if march is not None:
                break
            reasons[spec.name] = "its arrays could not be built for this rule or matrix layout"
        if march is None:
            raise ValueError(f"{self.option_name}['engine']={engine!r}: no direct march could begin "
                             f"({_listed(reasons)})")
        run.timer.lap("factorize")
        run.stats.update(march=spec.name, march_alternatives=reasons, engine=spec.engine,
                         lcp_space=spec.space, engine_reason=problem.engine_reason)
        if problem.cache is not None:
            run.stats["numba_cache"] = problem.cache
        stepping = ("chunk" if isinstance(march, ChunkedMarch) else "whole" if isinstance(march, WholeMarch)
                    else "step")
        return MarchRun(model, run, disc, base.init, march, stepping)


class MarchProblem:
    """What the choice of a direct march looks at: the model, the grid, the run and the engine asked
    for, with the facts the marches' conditions share.

    ``wanted``: the compiled loops are wanted (engine ``"compiled"``, or ``"auto"`` and the policy's
    :meth:`~unilateral.march.policy.SizePolicy.compiled_pays`, then with ``engine_choice="cost"``
    :meth:`~unilateral.march.policy.SizePolicy.engine_cost`), ``engine_reason`` why, ``cache`` the
    state of numba's cache where it was read (:func:`unilateral.march.loops.cache_state`) or None.
    """

    def __init__(self, model, disc, run, engine):
        self.model, self.disc, self.run, self.engine = model, disc, run, engine
        self.policy = current_policy()
        self.bpp = isinstance(run.solver, BlockPrincipalPivoting)
        self.ours = type(disc.rule).__module__ == "unilateral.rules"
        self.full_space = self.bpp and full_space_applies(model)
        self.wanted, self.engine_reason, self.cache = self._wanted()

    def _wanted(self):
        p, N = self.policy, self.disc.N
        if self.engine != "auto":
            return self.engine == "compiled", f"engine={self.engine!r} was asked for", None
        if not p.compiled_pays(N):
            return False, (f"a run of {N} steps is shorter than the policy's compile_min_steps = "
                           f"{p.compile_min_steps}: the Python loops cost less than loading compiled code"), None
        if p.engine_choice == "steps":
            return True, f"the policy's engine_choice='steps': {N} >= compile_min_steps = {p.compile_min_steps}", None
        if not (self.bpp and self.ours) or self.model.law.faced:
            return True, "no cost to weigh: no compiled march applies, or the Python one compiles its step solver", None
        model = self.model
        full = model.sparse and model.law.trivial and (self.full_space or model.n > p.compiled_max_n)
        if not full and model.n > p.compiled_max_n:
            return True, f"no compiled march applies (n = {model.n} > compiled_max_n)", None

        def cache():
            from ..march import loops     # lazily: numba

            return loops.cache_state(loops.FULL_SPACE if full else loops.CONDENSED)
        return p.engine_cost(N, model.n, model.m, cache, cheap="numba" in sys.modules)


def _needs_compiled(p: MarchProblem) -> str | None:
    if p.engine == "python":
        return "engine='python' was asked for"
    if not (p.bpp and p.ours):
        return (f"compiled marches need lcp='bpp' and a rule of unilateral.rules (got lcp={p.run.solver.name!r}, "
                f"rule={p.disc.rule!r})")
    if not p.wanted:
        return p.engine_reason
    return None


def _compiled_full_space(p: MarchProblem) -> str | None:
    if not (p.model.sparse and p.model.law.trivial):
        return "needs a sparse model with contacts only (constraints of the trivial law)"
    if not (p.full_space or p.model.n > p.policy.compiled_max_n):
        return (f"the condensed LCP is used: at most {p.policy.full_space_min_m} constraints and "
                f"n = {p.model.n} <= compiled_max_n = {p.policy.compiled_max_n}")
    return _needs_compiled(p)


def _compiled_condensed(p: MarchProblem) -> str | None:
    if p.full_space:
        return f"more than {p.policy.full_space_min_m} contacts of a sparse model: the full space is used"
    if p.engine != "compiled" and p.model.n > p.policy.compiled_max_n:
        return (f"n = {p.model.n} > compiled_max_n = {p.policy.compiled_max_n}: a dense LU of D_eff would "
                "cost more than the sparse factorisation")
    return _needs_compiled(p)


def _python_full_space(p: MarchProblem) -> str | None:
    if p.engine == "compiled":
        return "engine='compiled' was asked for"
    return None if p.full_space else (f"needs lcp='bpp' and a sparse model with more than "
                                      f"{p.policy.full_space_min_m} contacts")


def _python_condensed(p: MarchProblem) -> str | None:
    if p.engine == "compiled":
        return "engine='compiled' was asked for"
    return "more than the policy's full_space_min_m contacts: the full space is used" if p.full_space else None


def _begin_compiled_full_space(base, disc, run):
    from ..march.full_space import full_space_march     # lazily: numba

    return full_space_march(base.stepper(disc, condensed=False), disc.N, base.init.v, base.init.psi, dt=disc.dt,
                            bilateral=run.bilateral, callback=run.callback, max_iter=run.solver.max_iter or 50)


def _begin_compiled_condensed(base, disc, run):
    return CompiledDirectMarch.of(base.stepper(disc, condensed=True), disc.N, base.init.v, base.init.psi,
                                  dt=disc.dt, bilateral=run.bilateral, tol=run.solver.tol,
                                  max_iter=run.solver.max_iter or 10 * base.model.m + 10, callback=run.callback)


def _begin_python_full_space(base, disc, run):
    return ActiveSetMarch(base.stepper(disc, condensed=False), disc.N, base.init.v, base.init.psi, dt=disc.dt,
                          bilateral=run.bilateral, callback=run.callback)


def _begin_python_condensed(base, disc, run):
    """The condensed LCP a step at a time; the bilateral sweep in one call."""
    stepper, args = base.stepper(disc, condensed=True), (disc.N, base.init.v, base.init.psi)
    if run.bilateral:
        return WholeMarch(lambda: march_direct(stepper, *args, solver=run.solver, dt=disc.dt, bilateral=True,
                                               callback=run.callback), disc.N)
    return DirectMarch(stepper, *args, run.solver, dt=disc.dt, callback=run.callback)


@dataclass(frozen=True)
class MarchSpec:
    """A direct march: its name, engine and LCP space, when it applies and how it begins.

    ``applies(problem) -> None | str`` gives None or the reason it does not apply;
    ``begin(base, disc, run)`` returns the march begun at step 0, or None if its arrays cannot be
    built (then the next march that applies is begun).
    """

    name: str
    engine: str
    space: str
    applies: Callable
    begin: Callable


#: The direct marches, most preferred first: the first that applies steps the model.
MARCHES = (
    MarchSpec("compiled full space", "compiled", "full", _compiled_full_space, _begin_compiled_full_space),
    MarchSpec("compiled condensed", "compiled", "condensed", _compiled_condensed, _begin_compiled_condensed),
    MarchSpec("python full space", "python", "full", _python_full_space, _begin_python_full_space),
    MarchSpec("python condensed", "python", "condensed", _python_condensed, _begin_python_condensed),
)


def pick_march(problem: MarchProblem, option: str):
    """The marches of :data:`MARCHES` that apply to ``problem`` (most preferred first) and the
    reasons of those that do not, by name. A ValueError names ``option`` if none applies."""
    reasons = {spec.name: spec.applies(problem) for spec in MARCHES}
    candidates = [spec for spec in MARCHES if reasons[spec.name] is None]
    if not candidates:
        raise ValueError(f"{option}={problem.engine!r}: no direct march applies to this problem ({_listed(reasons)})")
    return candidates, {name: why for name, why in reasons.items() if why is not None}


def _listed(reasons: dict) -> str:
    """``"name: why; name: why"`` of the marches that do not apply."""
    return "; ".join(f"{name}: {why}" for name, why in reasons.items())
