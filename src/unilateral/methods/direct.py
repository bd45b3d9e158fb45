"""``method="direct"``: the full model stepped with the rule, one LCP per step."""

from __future__ import annotations

import functools

from .. import _validate as V
from ..lcp import BlockPrincipalPivoting
from ..march.active_set import march_direct_active_set
from ..march.jit import compiled_pays
from ..march.direct import march_direct, march_direct_compiled
from ..march.stepper import COMPILED_MAX_N
from ..model import Model
from .base import Method
from .clcp_march import ENGINES
from .common import BaseState, failed_at_start, finish

#: Sparse models with more constraints than this solve the LCP in the full sparse space
#: (active-set pivoting with cached factorisations) when ``lcp="bpp"``.
FULL_SPACE_MIN_M = 64


class Direct(Method):
    """Direct time stepping of the full model with one LCP per step.

    Every rule (BDF1, BDF2, trapezoidal, Newmark, HHT). With a rule that has a
    convolution-quadrature form, one step is one step of the CLCP with the same rule: the exact
    reference of ``cq`` and ``modal``. The LCP is solved on the condensed ``m x m`` matrix
    ``W0`` (the Schur complement of the effective stiffness, factorised once), or for sparse
    models with many constraints in the full sparse space (:mod:`unilateral.march.active_set`).

    Options
    -------
    engine : ``"auto"`` (default: compiled where it applies: the condensed LCP, ``lcp="bpp"``, a
        rule of :mod:`unilateral.rules` and at most :data:`~unilateral.march.stepper.COMPILED_MAX_N`
        DOFs, larger models being stepped with sparse factorisations in Python), ``"compiled"``
        (the same conditions but any number of DOFs; an error if they do not hold) or
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
        full_space = (model.sparse and model.m > FULL_SPACE_MIN_M and model.law.trivial
                      and isinstance(run.solver, BlockPrincipalPivoting))
        compiled_ok = (not full_space and isinstance(run.solver, BlockPrincipalPivoting)
                       and type(disc.rule).__module__ == "unilateral.rules")
        if engine == "compiled" and not compiled_ok:
            raise ValueError(f"{self.option_name}['engine']='compiled' needs lcp='bpp', a rule of "
                             "unilateral.rules and the condensed LCP (a sparse model with at most "
                             f"{FULL_SPACE_MIN_M} constraints or a dense model); got lcp="
                             f"{run.solver.name!r}, rule={disc.rule!r}, n={model.n}, m={model.m}")
        compiled = engine == "compiled" or (engine == "auto" and compiled_ok and model.n <= COMPILED_MAX_N
                                            and compiled_pays(disc.N))
        base = BaseState.prepare(model, load, initial, disc, run, tables=compiled)
        if base.init.message:
            return failed_at_start(model, base.init, run)
        run.timer.lap("initial")
        run.stats["lcp_space"] = "full" if full_space else "condensed"
        stepper = base.stepper(disc, condensed=not full_space)
        run.timer.lap("factorize")
        out = None
        if compiled:
            solver = run.solver
            out = march_direct_compiled(stepper, disc.N, base.init.v, base.init.psi, dt=disc.dt,
                                        max_iter=solver.max_iter or 10 * model.m + 10, tol=solver.tol,
                                        bilateral=run.bilateral, callback=run.callback)
        run.stats["engine"] = "python" if out is None else "compiled"
        if out is None:
            march = (march_direct_active_set if full_space
                     else functools.partial(march_direct, solver=run.solver))
            out = march(stepper, disc.N, base.init.v, base.init.psi, dt=disc.dt,
                        bilateral=run.bilateral, callback=run.callback)
        du, dud, v, psi, log = out
        run.timer.lap("steps")
        K = v.shape[0] - 1
        return finish(model, run, log, t=disc.t[: K + 1], v=v, psi=psi, u=base.init.u + du, udot=dud)
