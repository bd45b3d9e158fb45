"""``method="direct"``: the full model stepped with the rule, one LCP per step."""

from __future__ import annotations

import functools

from ..lcp import BlockPrincipalPivoting
from ..march.active_set import march_direct_active_set
from ..march.direct import march_direct
from ..model import Model
from .base import Method
from .common import BaseState, failed_at_start, finish

#: Sparse models with more constraints than this solve the LCP in the full sparse space
#: (active-set pivoting with cached factorisations) when ``lcp="bpp"``.
FULL_SPACE_MIN_M = 64


class Direct(Method):
    """Direct time stepping of the full model with one LCP per step.

    Every rule (BDF1, BDF2, trapezoidal, Newmark, HHT). With a rule that has a
    convolution-quadrature form, one step is one step of the CLCP with the same rule: the exact
    reference of ``cq`` and ``modal``. The LCP is solved on the condensed ``m x m`` matrix, or for
    sparse models with many constraints in the full sparse space
    (:mod:`unilateral.march.active_set`).
    """

    name = "direct"
    models = (Model,)
    cq_rules_only = False

    def solve(self, model, load, initial, disc, run):
        run.stats["n"] = model.n
        base = BaseState.prepare(model, load, initial, disc, run, tables=False)
        if base.init.message:
            return failed_at_start(model, base.init, run)
        run.timer.lap("initial")
        full_space = (model.sparse and model.m > FULL_SPACE_MIN_M
                      and isinstance(run.solver, BlockPrincipalPivoting))
        run.stats["lcp_space"] = "full" if full_space else "condensed"
        stepper = base.stepper(disc, condensed=not full_space)
        run.timer.lap("factorize")
        march = (march_direct_active_set if full_space
                 else functools.partial(march_direct, solver=run.solver))
        du, dud, v, psi, log = march(stepper, disc.N, base.init.v, base.init.psi, dt=disc.dt,
                                     bilateral=run.bilateral, callback=run.callback)
        run.timer.lap("steps")
        K = v.shape[0] - 1
        return finish(model, run, log, t=disc.t[: K + 1], v=v, psi=psi, u=base.init.u + du, udot=dud)
