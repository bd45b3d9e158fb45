"""Choosing how a CLCP with stored weights is marched: the history and the engine."""

from __future__ import annotations

from .. import _validate as V
from ..history import HISTORIES, history_on_coupled_unknowns
from ..lcp import BlockPrincipalPivoting
from ..march.clcp import march_cq, march_cq_compiled
from ..march.policy import current_policy

ENGINES = ("auto", "compiled", "python")
#: Above this many steps the history of stored weights is summed by the FFT-blocked algorithm.
FFT_HISTORY_MIN_STEPS = 256


def compiled_applies(run) -> bool:
    """The compiled marches use block principal pivoting and step every constraint."""
    return isinstance(run.solver, BlockPrincipalPivoting) and not run.bilateral


def use_compiled(engine, compiled_ok, run, *, option, needs, steps) -> bool:
    """Whether to run compiled: ``engine`` asked for it (and it applies), or ``auto``, it applies and
    a run of ``steps`` steps is long enough (:meth:`unilateral.march.policy.SizePolicy.compiled_pays`)."""
    if engine == "compiled" and not compiled_ok:
        raise ValueError(f"{option}['engine']='compiled' needs {needs}")
    return engine == "compiled" or (engine == "auto" and compiled_ok and current_policy().compiled_pays(steps))


def march_weights(W, psi_affine, v_b, disc, run, *, history=None, engine="auto", option="cq_options",
                  law=None, coupled=None):
    """March the CLCP with stored weights ``W (N+1, m, m)``; return ``(v, psi, log)``.

    ``history``: ``"naive"`` or ``"fft"`` (default: FFT-blocked above
    :data:`FFT_HISTORY_MIN_STEPS` steps); ``engine``: ``"auto"``, ``"compiled"`` (naive history
    and block principal pivoting only) or ``"python"``; ``law``: the model's
    :class:`~unilateral.constraints.StepLaw` (default: contact only); ``coupled``: the unknowns
    ``W_1 .. W_N`` couple, if known (:func:`~unilateral.history.coupled_unknowns`).
    """
    W0 = 0.5 * (W[0] + W[0].T)
    N = W.shape[0] - 1
    history = V.choice(f"{option}['history']", history or ("fft" if N > FFT_HISTORY_MIN_STEPS else "naive"),
                       HISTORIES)
    engine = V.choice(f"{option}['engine']", engine, ENGINES)
    run.stats["history"] = history
    solver = run.solver
    compiled_ok = history == "naive" and compiled_applies(run) and (law is None or law.compiled_ok)
    if use_compiled(engine, compiled_ok, run, option=option,
                    needs="history='naive' and lcp='bpp' (and no footings that slide)", steps=N):
        run.stats["engine"] = "compiled"
        W = W.copy()
        W[0] = W0
        return march_cq_compiled("naive", (W, psi_affine), v_b, dt=disc.dt, tol=solver.tol,
                                 max_iter=solver.max_iter or 10 * W.shape[1] + 10, callback=run.callback,
                                 law=law)
    run.stats["engine"] = "python"
    sums = history_on_coupled_unknowns(HISTORIES[history], W, coupled)
    return march_cq(W0, sums, psi_affine, v_b, solver, dt=disc.dt, bilateral=run.bilateral, callback=run.callback,
                    law=law)
