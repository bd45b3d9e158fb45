"""``method="modal"``: the CLCP with the history evaluated recursively from poles and residues."""

from __future__ import annotations

from .. import _validate as V
from ..kernels import PoleResidueKernel
from ..march.clcp import march_cq, march_cq_compiled
from ..model import Model
from .base import Method
from .clcp_march import ENGINES, compiled_applies, use_compiled
from .common import clcp_on_matrix_model


class PolesRefused(ValueError):
    """The pole-residue form of a model's kernel was refused (``method="auto"`` then steps directly)."""


class Modal(Method):
    """The CLCP of :class:`~unilateral.methods.cq.CQ` with the exact recursive history.

    ``Lambda(s)`` of a matrix model is put in pole-residue form
    (:class:`~unilateral.kernels.PoleResidueKernel`): the paper's "recursive evaluation of
    convolution integrals", one scalar recursion per pole, O(r m) per step. With every pole it
    equals ``method="cq"`` to round-off.

    Options
    -------
    modes : None (every pole, exact, dense models) or an int (that many lowest modes plus the
        static correction, for large models with classical damping)
    engine : ``"auto"``, ``"compiled"`` or ``"python"``
    """

    name = "modal"
    models = (Model,)
    options = ("modes", "engine")

    def solve(self, model, load, initial, disc, run):
        engine = V.choice("modal_options['engine']", self.config.get("engine", "auto"), ENGINES)
        run.stats["n"] = model.n
        try:
            kernel = PoleResidueKernel.from_model(model, modes=self.config.get("modes"))
        except ValueError as exc:
            if "modes must be" in str(exc):
                raise
            raise PolesRefused(str(exc)) from None
        run.stats["modal"] = {key: value for key, value in kernel.info.items()
                              if isinstance(value, (int, float, str))}
        W0 = kernel.W0(disc.dt, disc.rule)
        run.timer.lap("poles")

        def clcp(psi_affine, v_b):
            history = kernel.history(disc.N, disc.dt, disc.rule)
            run.stats["history"] = history.name
            solver = run.solver
            if use_compiled(engine, compiled_applies(run), run, option="modal_options", needs="lcp='bpp'"):
                run.stats["engine"] = "compiled"
                return march_cq_compiled("recursive", (W0, *history.arrays(), psi_affine), v_b, dt=disc.dt,
                                         tol=solver.tol, max_iter=solver.max_iter or 10 * model.m + 10,
                                         callback=run.callback)
            run.stats["engine"] = "python"
            return march_cq(W0, history, psi_affine, v_b, solver, dt=disc.dt, bilateral=run.bilateral,
                            callback=run.callback)

        return clcp_on_matrix_model(model, load, initial, disc, run, clcp)
