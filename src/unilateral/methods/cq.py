"""``method="cq"``: the paper's CLCP with convolution-quadrature weights of ``Lambda(s)``."""

from __future__ import annotations


import numpy as np

from .. import _validate as V
from ..initial import InitialState, static_lcp
from ..kernels import MatrixKernel, cq_weights
from .base import Method
from .clcp_march import FFT_HISTORY_MIN_STEPS, march_weights
from .common import clcp_on_matrix_model, failed_at_start, finish
from .rigid import refusal as rigid_refusal


class CQ(Method):
    """The convolutional LCP of Liolios (1990), eq. (27), with convolution-quadrature weights.

    The weights of ``Lambda(s)`` (a :class:`~unilateral.kernels.MatrixKernel` of a
    :class:`~unilateral.model.Model`, or the kernel of a :class:`~unilateral.kernels.KernelModel`)
    are computed by FFT on a circle (:func:`~unilateral.kernels.cq_weights`); the history is summed
    directly or FFT-blocked; one LCP per step.

    A :class:`~unilateral.soil.FoundationModel` (a structure on a soil given by ``Phi(s)``) is
    solved in its dual form, in the contact forces, with the weights of
    ``Lambda_D(s) = T^T D(s)^-1 T + Phi(s)`` (:func:`unilateral.methods.foundation_solve.solve_foundation`).

    Options
    -------
    L, rho : FFT size and circle radius of the weights (see :func:`~unilateral.kernels.cq_weights`)
    history : ``"naive"`` (O(N^2 m^2)) or ``"fft"`` (O(m^2 N log^2 N), the default above 256 steps)
    engine : ``"auto"`` (compiled where it applies: naive history and ``lcp="bpp"``),
        ``"compiled"`` or ``"python"``
    """

    name = "cq"
    solves = frozenset({"matrices", "foundation", "laplace kernel"})
    options = ("L", "rho", "history", "engine")

    def refusal(self, model) -> str | None:
        """None, or why not: rigid contacts on a structure not stable without them (:mod:`.rigid`)."""
        return rigid_refusal(model, self.name)

    def memory_estimate(self, model, disc) -> dict:
        out = super().memory_estimate(model, disc)
        N, m = disc.N, model.m
        out[f"the CQ weights (3 copies of (N+1) m^2, m = {m})"] = 24.0 * (N + 1) * m ** 2
        soil = getattr(model, "soil", None)
        if soil is None:        # the FFT that computes them: L = 8 (N+1) complex values per entry, twice
            out["the FFT of the weights (2 x 8 (N+1) m^2 complex)"] = 256.0 * (N + 1) * m ** 2
            coupled = m
        else:                   # only the soil's: SOIL_FFT_POINTS (J+1) per entry (its diagonal if uncoupled)
            from ..soil.flexibility import SOIL_FFT_POINTS

            memory = getattr(soil, "memory", None)
            J = N if memory is None else min(N, int(np.ceil(memory / disc.dt)) + 64)
            entries = soil.m if soil.is_diagonal else soil.m ** 2
            out[f"the FFT of the soil's weights (2 x {SOIL_FFT_POINTS} (J+1) entries complex, J = {J})"] = (
                32.0 * SOIL_FFT_POINTS * (J + 1) * entries)
            coupled = m - len(model.slips)      # the slips take no part in the history
        if self.config.get("history", "fft" if N > FFT_HISTORY_MIN_STEPS else "naive") == "fft":
            out[f"the weight spectra of the FFT-blocked history (2 N s^2 complex, s = {coupled})"] = (
                32.0 * N * coupled ** 2)
        return out

    def _options(self):
        """The options of the weights (``L``, ``rho``) and of the march (``history``, ``engine``)."""
        return ({k: self.config[k] for k in ("L", "rho") if k in self.config},
                {k: self.config[k] for k in ("history", "engine") if k in self.config})

    def solve(self, model, load, initial, disc, run):
        """Solve by the route of ``model``'s kind (matrices, a foundation, a Laplace-domain kernel)."""
        route = self.by_kind(model, disc, {"matrices": self._solve_matrices, "laplace kernel": self._solve_kernel,
                                           "foundation": self._solve_foundation_model})
        return route(model, load, initial, disc, run)

    def _solve_matrices(self, model, load, initial, disc, run):
        weight_options, march = self._options()
        run.stats["n"] = model.n

        def clcp(psiL, v_b):
            W = cq_weights(MatrixKernel(model), disc.N, disc.dt, disc.rule, **weight_options)
            run.timer.lap("weights")
            v, psi, log = march_weights(W, psiL, v_b, disc, run, law=model.law, **march)
            run.stats["history_round_off"] = history_round_off(W, v, psi, model.law.rate)
            return v, psi, log

        return with_history_warning(clcp_on_matrix_model(model, load, initial, disc, run, clcp))

    def _solve_kernel(self, model, load, initial, disc, run):
        if load is not None:
            raise ValueError("load is not used by a KernelModel: its psiL carries the loading; pass load=None")
        return self._solve_kernel_model(model, initial, disc, run, *self._options())

    def _solve_foundation_model(self, model, load, initial, disc, run):
        return self._solve_foundation(model, load, initial, disc, run, *self._options())

    def _solve_foundation(self, model, load, initial, disc, run, weight_options, march):
        from ..history import HISTORIES, coupled_unknowns, history_on_coupled_unknowns
        from .foundation_solve import solve_foundation

        def operators():
            W = model.weights(disc.N, disc.dt, disc.rule, **weight_options)
            name = march.get("history") or ("fft" if disc.N > FFT_HISTORY_MIN_STEPS else "naive")
            name = V.choice("cq_options['history']", name, HISTORIES)
            coupled = coupled_unknowns(W)          # one scan of the weights for both histories
            clcp = lambda psi_affine, z_b: march_weights(W, psi_affine, z_b, disc, run, law=model.law,
                                                         coupled=coupled, **march)
            return (0.5 * (W[0] + W[0].T), lambda: history_on_coupled_unknowns(HISTORIES[name], W, coupled),
                    clcp)

        return solve_foundation(model, load, initial, disc, run, operators=operators)

    def _solve_kernel_model(self, model, initial, disc, run, weight_options, march):
        N = disc.N
        psiL = model.psiL_samples(N, disc.dt)
        run.timer.lap("setup")
        W = cq_weights(model.kernel, N, disc.dt, disc.rule, **weight_options)
        W = np.real_if_close(W) if np.iscomplexobj(W) else W
        run.timer.lap("weights")
        if isinstance(initial, str) and V.choice("initial", initial, ("static", "rest")) == "static":
            Lambda0 = model.Lambda_real(0.0)
            v_b, iters, message = static_lcp(model.law.matrix(Lambda0), model.law.rows(psiL[0]), run.solver)
            run.stats["static_lcp_iterations"] = iters
            if message:
                return failed_at_start(model, InitialState(v=v_b, psi=psiL[0], message=message), run)
            # psi_n = psiL_n - Lambda(0) v_b for a v held at its static value since -infinity.
            psi_affine = psiL - Lambda0 @ v_b
        else:
            if isinstance(initial, dict):
                unknown = set(initial) - {"v0"}
                if unknown:
                    raise ValueError(f"initial for a KernelModel takes only 'v0'; got keys {sorted(unknown)}")
                v_b = V.as_vector("initial['v0']", initial.get("v0", 0.0), model.m)
                if np.any(v_b < 0):
                    raise ValueError(f"initial['v0'] must be >= 0, got {v_b}")
            elif isinstance(initial, str):
                v_b = np.zeros(model.m)
            else:
                raise TypeError(f"initial must be 'static', 'rest' or dict(v0=...), got {V.describe(initial)}")
            # v jumps to v_b at t = 0: its convolution is the CQ step response sum_{j<=n} W_j v_b.
            psi_affine = psiL - np.cumsum(W, axis=0) @ v_b
        v, psi, log = march_weights(W, psi_affine, v_b, disc, run, law=model.law, **march)
        run.timer.lap("steps")
        run.stats["history_round_off"] = history_round_off(W, v, psi, model.law.rate)
        K = v.shape[0] - 1
        return with_history_warning(finish(model, run, log, t=disc.t[: K + 1], v=v, psi=psi,
                                           psiL=model.law.rows(psiL[: K + 1])))


#: Above this estimated relative round-off of the constraint functions a ``cq`` run warns
#: (:func:`history_round_off`).
HISTORY_ROUND_OFF_WARNING = 1e-6


def history_round_off(W, v, psi, rate) -> float:
    """An estimate of the relative round-off that the history sum of the rate unknowns (slips,
    plastic multipliers) leaves in the constraint functions.

    The history ``sum_j W_j v_{n-j}`` sums the cumulative multipliers: terms of size
    ``|W_j| |v|`` (a stick spring ``kt`` times the slip), which must cancel down to forces of the
    size of ``psi``. Each term carries a round-off ``eps |W_j| |v|``, so the estimate is
    ``eps sum_{j>=1} max|W_j[:, rate]| max|v_rate| / max|psi|``. With the trapezoidal rule the
    memory of an undamped stick spring does not decay (no numerical damping) and the sum grows
    with the number of steps; BDF2 damps it within a few steps.

    Parameters
    ----------
    W : (N+1, m, m) weights;  v, psi : (K+1, m) the march's unknowns and constraint functions
    rate : (m,) bool, the rate unknowns

    Returns
    -------
    float, 0 without rate unknowns or with no response
    """
    rate = np.asarray(rate, dtype=bool)
    if not rate.any() or W.shape[0] < 2 or v.shape[0] < 2:
        return 0.0
    scale = float(np.abs(psi).max()) if psi.size else 0.0
    reach = float(np.abs(v[:, rate] - v[0, rate]).max())
    if scale == 0.0 or reach == 0.0:
        return 0.0
    terms = float(np.abs(W[1: v.shape[0], :, rate]).max(axis=(1, 2)).sum())
    return float(np.finfo(float).eps * terms * reach / scale)


def with_history_warning(sol):
    """``sol`` with a warning when :func:`history_round_off` (in its stats) exceeds
    :data:`HISTORY_ROUND_OFF_WARNING`."""
    estimate = sol.stats.get("history_round_off", 0.0)
    if sol.success and estimate > HISTORY_ROUND_OFF_WARNING:
        warning = (f"the cq history of the slips and plastic multipliers carries terms |W_j| |v| whose round-off "
                   f"may reach {estimate:.1e} of the largest constraint function (a stiff stick spring with "
                   "the trapezoidal rule, whose memory does not decay); method='modal' or 'direct' solve the "
                   "same discrete problem without the history sum (docs/theory.md, section 13)")
        sol.stats.setdefault("warnings", []).append(warning)
        sol.message = sol.message + ("; WARNING: " if "WARNING" not in sol.message else "; ") + warning
    return sol
