"""``method="modal"``: the CLCP with the history evaluated recursively from poles and residues."""

from __future__ import annotations


import numpy as np

from .. import _validate as V
from ..model import remembered
from ..kernels import PoleResidueKernel
from ..march.clcp import march_cq, march_cq_compiled
from .base import Method
from .clcp_march import ENGINES, compiled_applies, use_compiled
from .common import clcp_on_matrix_model
from .rigid import refusal as rigid_refusal


class Modal(Method):
    """The CLCP of :class:`~unilateral.methods.cq.CQ` with the exact recursive history.

    ``Lambda(s)`` of a matrix model is put in pole-residue form
    (:class:`~unilateral.kernels.PoleResidueKernel`): the paper's "recursive evaluation of
    convolution integrals", one scalar recursion per pole, O(r m) per step. With every pole it
    equals ``method="cq"`` to round-off.

    A :class:`~unilateral.soil.FoundationModel` with a rational soil (Kelvin elements, cones,
    Veletsos-Verbic, AAA fits of flexibilities) is solved in its dual form with the poles of
    ``T^T D(s)^-1 T`` and of ``Phi(s)`` (:meth:`~unilateral.soil.FoundationModel.modal_form`); a
    structure resting only on Kelvin soil elements (``K`` singular) through the equivalent paper
    model with Kelvin elements (:meth:`~unilateral.soil.FoundationModel.kelvin_model`), whose
    solution has the same meaning.

    Options
    -------
    modes : None (every pole, exact, dense models) or an int (that many lowest modes plus the
        static correction, for large models with classical damping)
    engine : ``"auto"``, ``"compiled"`` or ``"python"``
    """

    name = "modal"
    solves = frozenset({"matrices", "foundation"})
    options = ("modes", "engine")

    def refusal(self, model) -> str | None:
        """None if the pole-residue form of ``model``'s kernel exists, else why not (it is computed
        here, and kept on the model for the solve: :func:`~unilateral.model.remembered`); rigid
        contacts on a structure not stable without them are refused (:mod:`.rigid`)."""
        why_not = rigid_refusal(model, self.name)
        if why_not is not None:
            return why_not
        try:
            if model.kind == "foundation":
                remembered(model, ("modal form",), model.modal_form)
            else:
                self._kernel(model)
        except ValueError as exc:
            if "modes must be" in str(exc):     # a bad option, not a property of the model
                raise
            if model.kind == "foundation" and model.soil.kelvin is not None:
                return None                     # the equivalent Kelvin model (the paper's primal form)
            return str(exc)
        return None

    def _kernel(self, model):
        modes = self.config.get("modes")
        return remembered(model, ("poles", repr(modes)), lambda: PoleResidueKernel.from_model(model, modes=modes))

    def solve(self, model, load, initial, disc, run):
        """Solve by the route of ``model``'s kind (matrices or a foundation)."""
        route = self.by_kind(model, disc, {"matrices": self._solve_matrices, "foundation": self._solve_foundation_model})
        return route(model, load, initial, disc, run)

    def _engine(self):
        return V.choice("modal_options['engine']", self.config.get("engine", "auto"), ENGINES)

    def _solve_foundation_model(self, model, load, initial, disc, run):
        return self._solve_foundation(model, load, initial, disc, run, self._engine())

    def _solve_matrices(self, model, load, initial, disc, run):
        engine = self._engine()
        run.stats["n"] = model.n
        why_not = self.refusal(model)
        if why_not is not None:
            raise ValueError(f"method='modal': {why_not}")
        kernel = self._kernel(model)
        run.stats["modal"] = {key: value for key, value in kernel.info.items()
                              if isinstance(value, (int, float, str))}
        W0 = kernel.W0(disc.dt, disc.rule)
        run.timer.lap("poles")

        def clcp(psi_affine, v_b):
            history = kernel.history(disc.N, disc.dt, disc.rule)
            run.stats["history"] = history.name
            solver = run.solver
            if use_compiled(engine, compiled_applies(run), run, option="modal_options", needs="lcp='bpp'",
                            steps=disc.N):
                run.stats["engine"] = "compiled"
                return march_cq_compiled("recursive", (W0, *history.arrays(), psi_affine), v_b, dt=disc.dt,
                                         tol=solver.tol, max_iter=solver.max_iter or 10 * model.m + 10,
                                         callback=run.callback, law=model.law)
            run.stats["engine"] = "python"
            return march_cq(W0, history, psi_affine, v_b, solver, dt=disc.dt, bilateral=run.bilateral,
                            callback=run.callback, law=model.law)

        return clcp_on_matrix_model(model, load, initial, disc, run, clcp)

    def _solve_foundation(self, model, load, initial, disc, run, engine):
        from .foundation_solve import foundation_base_state, primal_columns, solve_foundation

        if self.config.get("modes") is not None:
            raise ValueError("modal_options['modes'] does not apply to a FoundationModel (every pole is used)")
        try:
            kernel = remembered(model, ("modal form",), model.modal_form)
        except ValueError as exc:
            if model.soil.kelvin is not None:
                run.stats["foundation_route"] = f"the equivalent Kelvin model (the paper's primal form): {exc}"
                if not (isinstance(initial, str) and initial == "static"):
                    # the foundation's own initial values (soil unloaded), as the Kelvin model's
                    given = foundation_base_state(model, None, initial, run.solver)
                    initial = {"u0": given.u, "udot0": given.udot, "v0": given.v}
                sol = self.solve(model.kelvin_model(), load, initial, disc, run)
                sol.stats["formulation"] = "primal CLCP in the openings (the paper's Kelvin soil elements)"
                if model.sliding:           # the columns of the dual form: contacts, shears, slips
                    sol.v, sol.psi = primal_columns(model, sol.v, sol.psi)
                    sol.psiL = primal_columns(model, np.zeros_like(sol.psiL), sol.psiL)[1]
                    sol.constraint_names = list(model.constraint_names)
                return sol
            raise ValueError(f"method='modal': {exc}") from None
        run.stats["modal"] = {key: value for key, value in kernel.info.items()
                              if isinstance(value, (int, float, str))}
        run.timer.lap("poles")

        def operators():
            W0 = kernel.W0(disc.dt, disc.rule)
            new_history = lambda: kernel.history(disc.N, disc.dt, disc.rule)

            def clcp(psi_affine, c_b):
                history = new_history()
                run.stats["history"] = history.name
                solver = run.solver
                if use_compiled(engine, compiled_applies(run), run, option="modal_options", needs="lcp='bpp'",
                                steps=disc.N):
                    run.stats["engine"] = "compiled"
                    return march_cq_compiled("recursive", (W0, *history.arrays(), psi_affine), c_b,
                                             dt=disc.dt, tol=solver.tol,
                                             max_iter=solver.max_iter or 10 * model.m + 10, callback=run.callback)
                run.stats["engine"] = "python"
                return march_cq(W0, history, psi_affine, c_b, solver, dt=disc.dt, callback=run.callback)

            return W0, new_history, clcp

        return solve_foundation(model, load, initial, disc, run, operators=operators)
