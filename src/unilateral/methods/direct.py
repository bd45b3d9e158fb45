"""``method="direct"``: the full model stepped with the rule, one LCP per step."""

from __future__ import annotations

import functools

from .. import _validate as V
from ..lcp import BlockPrincipalPivoting
from ..march.active_set import FULL_SPACE_MIN_M, full_space_applies, march_direct_active_set
from ..march.jit import compiled_pays
from ..march.direct import march_direct, march_direct_compiled
from ..march.stepper import COMPILED_MAX_N
from ..model import Model
from .base import Method
from .clcp_march import ENGINES
from .common import BaseState, failed_at_start, finish


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
        engine = V.choice(f"{self.option_name}['engine']", self.config.get("engine", "auto"), ENGINES)
        run.stats["n"] = model.n
        bpp = isinstance(run.solver, BlockPrincipalPivoting)
        ours = type(disc.rule).__module__ == "unilateral.rules"
        full_space = full_space_applies(model) and bpp
        # sparse models stepped in compiled code in the full space (envelope factorisation)
        sparse_ok = model.sparse and model.law.trivial and bpp and ours and (full_space or model.n > COMPILED_MAX_N)
        condensed_ok = not full_space and bpp and ours
        compiled_ok = sparse_ok or condensed_ok
        if engine == "compiled" and not compiled_ok:
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
            return failed_at_start(model, base.init, run)
        run.timer.lap("initial")
        march_args = (disc.N, base.init.v, base.init.psi)
        options = dict(dt=disc.dt, bilateral=run.bilateral, callback=run.callback)
        out = None
        if compiled_sparse:
            from ..march.full_space import march_full_space     # lazily: numba

            stepper = base.stepper(disc, condensed=False)
            run.timer.lap("factorize")
            out = march_full_space(stepper, *march_args, **options, max_iter=run.solver.max_iter or 50)
            full_space = full_space or out is not None
        if out is None:
            stepper = base.stepper(disc, condensed=not full_space)
            run.timer.lap("factorize")
        if out is None and compiled and not full_space:
            solver = run.solver
            out = march_direct_compiled(stepper, *march_args, max_iter=solver.max_iter or 10 * model.m + 10,
                                        tol=solver.tol, **options)
        run.stats["lcp_space"] = "full" if full_space else "condensed"
        run.stats["engine"] = "compiled" if out is not None else "python"
        if out is None:
            march = (march_direct_active_set if full_space
                     else functools.partial(march_direct, solver=run.solver))
            out = march(stepper, *march_args, **options)
        du, dud, v, psi, log = out
        run.timer.lap("steps")
        K = v.shape[0] - 1
        return finish(model, run, log, t=disc.t[: K + 1], v=v, psi=psi, u=base.init.u + du, udot=dud)
