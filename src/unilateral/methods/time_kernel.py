"""``method="time-kernel"``: the CLCP of a time-domain kernel by product integration (the paper's alternative)."""

from __future__ import annotations

import numpy as np

from .. import _validate as V
from ..discretization import Discretization
from ..initial import InitialState, static_lcp
from ..kernels import time_kernel_weights
from ..kernels.time_domain import QUADRATURES, RATE_RULES
from ..run_context import RunContext
from .base import Method
from .clcp_march import march_weights
from .common import failed_at_start, finish


class TimeKernelMethod(Method):
    """Product integration of ``Lambda(t) = Lambda_inf delta + Lambda_rate delta' + Lambda_r(t)``.

    The weights come from :func:`~unilateral.kernels.time_kernel_weights`; the CLCP is marched
    in Python with a naive or FFT-blocked history. The rule of the discretisation is not used.

    Options
    -------
    quadrature : ``"trapezoidal"`` (default) or ``"rectangle"``
    rate : ``"bdf2"`` (default) or ``"bdf1"``, for the ``delta'`` part
    history : ``"naive"`` or ``"fft"`` (default above 256 steps)
    """

    name = "time-kernel"
    solves = frozenset({"time kernel"})
    options = ("quadrature", "rate", "history")
    cq_rules_only = False

    def solve(self, model, load, initial, disc, run):
        if load is not None:
            raise ValueError("load is not used by a kernel model: its psiL carries the loading; pass load=None")
        initial = V.choice("initial", initial, ("static", "rest"))
        quadrature = V.choice("quadrature", self.config.get("quadrature", "trapezoidal"), QUADRATURES)
        rate = V.choice("rate", self.config.get("rate", "bdf2"), RATE_RULES)
        run.stats.update(quadrature=quadrature, rate=rate)
        run.stats.pop("rule", None)
        N, dt = disc.N, disc.dt
        psiL = model.psiL_samples(N, dt)
        run.timer.lap("setup")
        W = time_kernel_weights(model.kernel, N, dt, quadrature=quadrature, rate=rate)
        run.timer.lap("weights")
        if initial == "static":
            Lambda0 = model.kernel.Lambda0
            if Lambda0 is None:
                raise ValueError(
                    "initial='static' needs the static kernel Lambda(0): pass Lambda0 to TimeKernel "
                    "(TimeKernel.from_laplace sets it), or use initial='rest'"
                )
            v_b, run.stats["static_lcp_iterations"], message = static_lcp(Lambda0, psiL[0], run.solver)
            if message:
                return failed_at_start(model, InitialState(v=v_b, psi=psiL[0], message=message), run)
            psi_affine = psiL - Lambda0 @ v_b      # v held at v_b since -infinity
        else:
            v_b, psi_affine = np.zeros(model.m), psiL
        run.timer.lap("initial")
        v, psi, log = march_weights(W, psi_affine, v_b, disc, run, history=self.config.get("history"),
                                    engine="python", option="time_kernel_options")
        run.timer.lap("steps")
        K = v.shape[0] - 1
        return finish(model, run, log, t=disc.t[: K + 1], v=v, psi=psi, psiL=psiL[: K + 1])


def solve_time_kernel(model, *, dt, t_end, initial="static", lcp="bpp", lcp_options=None,
                      bilateral=False, quadrature="trapezoidal", rate="bdf2", history=None,
                      callback=None):
    """Solve the CLCP of a :class:`~unilateral.kernels.TimeKernelModel` step by step.

    ``unilateral.solve(model, ...)`` does the same with the default options.

    Parameters
    ----------
    model : TimeKernelModel
    dt, t_end : float
        Time step and end time; ``N = round(t_end / dt)`` steps.
    initial : {"static", "rest"}
        ``"static"``: start from the static unilateral state under ``psiL(0)``, the LCP with
        the static kernel ``kernel.Lambda0`` (``Lambda(s=0)``; set by
        :meth:`~unilateral.kernels.TimeKernel.from_laplace`, otherwise to be given to the
        :class:`~unilateral.kernels.TimeKernel`), held since ``t = -inf``. ``"rest"``: ``v(0) = 0``.
    lcp : str or LCPSolver ; lcp_options : dict, optional
        As for :func:`unilateral.solve`.
    bilateral : bool
        Hold every constraint at its initial state.
    quadrature, rate : str
        See :func:`~unilateral.kernels.time_kernel_weights`.
    history : {"naive", "fft"}, optional
        Summation of the history term; default ``"fft"`` above 256 steps.
    callback : callable ``callback(k, N)``, optional

    Returns
    -------
    Solution
        ``u`` and ``udot`` are None; ``stats`` has ``method = "time-kernel"``, the LCP statistics
        and ``time`` per phase (``setup``, ``weights``, ``initial``, ``steps``).
    """
    if getattr(model, "kind", None) != "time kernel":
        raise TypeError(f"model must be a KernelModel of a TimeKernel (TimeKernelModel), got {V.describe(model)}")
    disc = Discretization.from_user(dt, t_end)
    run = RunContext.from_user(lcp, lcp_options, bilateral, callback)
    method = TimeKernelMethod(quadrature=quadrature, rate=rate, history=history)
    run.stats.update(method=method.name, lcp_solver=run.solver.name, steps=disc.N, dt=disc.dt, m=model.m)
    return method.solve(model, None, initial, disc, run)
