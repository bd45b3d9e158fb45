"""``method="direct"``: the full model stepped with the rule, one LCP per step."""

from __future__ import annotations

from .. import _validate as V
from ..lcp import BlockPrincipalPivoting
from ..march.active_set import FULL_SPACE_MIN_M, ActiveSetMarch, full_space_applies
from ..march.jit import compiled_pays
from ..march.direct import ChunkedMarch, CompiledDirectMarch, DirectMarch, march_direct
from ..march.stepper import COMPILED_MAX_N
from ..model import Model
from .base import Method
from .clcp_march import ENGINES
from .common import BaseState, failed_at_start
from .stepping import MarchRun, SolvedRun, WholeMarch


class Direct(Method):
    """Direct time stepping of the full model with one LCP per step.

    Every rule (BDF1, BDF2, trapezoidal, Newmark, HHT). With a rule that has a
    convolution-quadrature form, one step is one step of the CLCP with the same rule: the exact
    reference of ``cq`` and ``modal``. The LCP is solved on the condensed ``m x m`` matrix
    ``W0`` (the Schur complement of the effective stiffness, factorised once), or for sparse
    models in the full sparse space (:mod:`unilateral.march.full_space`): models with more than
    :data:`~unilateral.march.active_set.FULL_SPACE_MIN_M` contacts, and in compiled code also
    those of more than :data:`~unilateral.march.stepper.COMPILED_MAX_N` DOFs with fewer contacts
    (constraints of the trivial law, a diagonal ``H``).

    Options
    -------
    engine : ``"auto"`` (default: compiled where it applies: ``lcp="bpp"``, a rule of
        :mod:`unilateral.rules`, and either the condensed LCP with at most
        :data:`~unilateral.march.stepper.COMPILED_MAX_N` DOFs (a dense LU of ``D_eff``) or a
        sparse model with contacts only, stepped in the full space with an envelope Cholesky
        factorisation of ``D_eff`` refactorised from the rows of the contacts that change; other
        models are stepped with sparse factorisations in Python), ``"compiled"`` (the same
        conditions, the condensed LCP with any number of DOFs; an error if none holds) or
        ``"python"``. Both engines perform the same operations and agree to round-off. Pass
        them as ``method=Direct(engine=...)``.
    """

    name = "direct"
    models = (Model,)
    options = ("engine",)
    cq_rules_only = False

    def solve(self, model, load, initial, disc, run):
        march = self.start(model, load, initial, disc, run)
        return march.solution(march.extend(disc.N))

    def start(self, model, load, initial, disc, run):
        """The direct march of ``model`` begun at step 0 (a run that advances on request).

        The marches in Python step one step at a time, the compiled ones (condensed and full
        space) in chunks (``stats["stepping"]``: ``"step"``, ``"chunk"``); the bilateral sweep in
        Python marches in one call at the first request (``"whole"``).
        """
        engine = V.choice(f"{self.option_name}['engine']", self.config.get("engine", "auto"), ENGINES)
        run.stats["n"] = model.n
        bpp = isinstance(run.solver, BlockPrincipalPivoting)
        ours = type(disc.rule).__module__ == "unilateral.rules"
        full_space = full_space_applies(model) and bpp
        # sparse models stepped in compiled code in the full space (envelope factorisation)
        sparse_ok = model.sparse and model.law.trivial and bpp and ours and (full_space or model.n > COMPILED_MAX_N)
        condensed_ok = not full_space and bpp and ours
        if engine == "compiled" and not (sparse_ok or condensed_ok):
            raise ValueError(f"{self.option_name}['engine']='compiled' needs lcp='bpp', a rule of "
                             "unilateral.rules and the condensed LCP (a sparse model with at most "
                             f"{FULL_SPACE_MIN_M} constraints or a dense model) or a sparse model with "
                             f"contacts only; got lcp={run.solver.name!r}, rule={disc.rule!r}, n={model.n}, "
                             f"m={model.m}")
        wanted = engine == "compiled" or (engine == "auto" and compiled_pays(disc.N))
        compiled_sparse = sparse_ok and wanted
        compiled = condensed_ok and wanted and (engine == "compiled" or model.n <= COMPILED_MAX_N)
        base = BaseState.prepare(model, load, initial, disc, run, tables=compiled or compiled_sparse)
        if base.init.message:
            return SolvedRun.of(failed_at_start(model, base.init, run), disc.N)
        run.timer.lap("initial")
        args = (disc.N, base.init.v, base.init.psi)
        options = dict(dt=disc.dt, bilateral=run.bilateral, callback=run.callback)
        march = None
        if compiled_sparse:
            from ..march.full_space import full_space_march     # lazily: numba

            march = full_space_march(base.stepper(disc, condensed=False), *args, **options,
                                     max_iter=run.solver.max_iter or 50)
            full_space = full_space or march is not None
        stepper = None if march is not None else base.stepper(disc, condensed=not full_space)
        run.timer.lap("factorize")
        if march is None and compiled and not full_space:
            march = CompiledDirectMarch.of(stepper, *args, dt=disc.dt, bilateral=run.bilateral,
                                           max_iter=run.solver.max_iter or 10 * model.m + 10,
                                           tol=run.solver.tol, callback=run.callback)
        run.stats["lcp_space"] = "full" if full_space else "condensed"
        run.stats["engine"] = "compiled" if march is not None else "python"
        if march is None:
            march = _python_march(stepper, args, options, run.solver, full_space)
        stepping = ("chunk" if isinstance(march, ChunkedMarch) else "whole" if isinstance(march, WholeMarch)
                    else "step")
        return MarchRun(model, run, disc, base.init, march, stepping)


def _python_march(stepper, args, options, solver, full_space):
    """The march in Python: the condensed LCP a step at a time, the full space or the bilateral
    sweep in one call."""
    if full_space:
        return ActiveSetMarch(stepper, *args, **options)
    if options["bilateral"]:
        return WholeMarch(lambda: march_direct(stepper, *args, solver=solver, **options), args[0])
    return DirectMarch(stepper, *args, solver, dt=options["dt"], callback=options["callback"])
