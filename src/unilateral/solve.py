"""One entry point for dynamic analyses: :func:`solve`."""

from __future__ import annotations

import functools
import time

import numpy as np

from . import _validate as V
from .active_set import march_direct_active_set
from .clcp import march_cq, march_cq_compiled, march_direct, sweep_direct
from .cq import cq_weights
from .history import NaiveHistory
from .history_fft import FFTBlockedHistory
from .initial import InitialState, given_state, static_lcp, static_state
from .kernel_model import KernelModel
from .kernels import MatrixKernel
from .lcp import BlockPrincipalPivoting, get_lcp_solver
from .linalg import transpose_times
from .modal import PoleResidueKernel
from .model import Model
from .result import Solution
from .rules import CQ_RULES, get_rule
from .stepping import DENSE_STEPPING_MAX_N, StructureStepper
from .time_kernel import TimeKernelModel, solve_time_kernel

METHODS = ("auto", "cq", "modal", "direct")
HISTORIES = {"naive": NaiveHistory, "fft": FFTBlockedHistory}
ENGINES = ("auto", "compiled", "python")
#: method="direct" solves the LCP in the full sparse space (active-set pivoting with cached
#: factorisations) for sparse models with more constraints than this, when lcp="bpp".
FULL_SPACE_MIN_M = 64
#: Above this many steps the CQ history is summed by the FFT-blocked algorithm by default.
FFT_HISTORY_MIN_STEPS = 256


def solve(model, load=None, *, dt, t_end, method="auto", rule="bdf2", initial="static",
          lcp="bpp", lcp_options=None, bilateral=False, cq_options=None, modal_options=None,
          callback=None) -> Solution:
    """Dynamic response of a structure with unilateral constraints.

    Parameters
    ----------
    model : Model, KernelModel or TimeKernelModel
        A :class:`~unilateral.time_kernel.TimeKernelModel` (time-domain kernel, e.g. by
        numerical Laplace inversion) is solved by :func:`~unilateral.time_kernel.solve_time_kernel`.
    load : callable ``q(t) -> (n,)`` or array (N+1, n), optional
        Total applied load (gravity included) at ``t_k = k dt``; ``N = round(t_end / dt)``.
        Not used by a :class:`KernelModel` (its ``psiL`` carries the loading).
    dt : float
        Time step, > 0.
    t_end : float
        End time, >= dt.
    method : {"auto", "cq", "modal", "direct"}
        ``"auto"`` (default): the fastest correct method for the model at hand, reported in
        ``stats["method"]`` with the reason in ``stats["method_reason"]``: ``"cq"`` for a
        :class:`KernelModel` (the only route without matrices); ``"modal"`` for small models
        (n, m <= 64) with a CQ rule and the default LCP solver, everything compiled; ``"direct"``
        otherwise (large sparse models: full-space active-set LCP), and as the fallback if the
        pole decomposition of a model is refused (e.g. a defective pole). ``"cq"``: the convolutional LCP of Liolios (1990), eq. (27), with convolution-quadrature
        weights of ``Lambda(s)`` and one LCP per step. ``"modal"``: the same CLCP with the
        history evaluated recursively from the poles and residues of ``Lambda(s)`` (the paper's
        "recursive evaluation of convolution integrals"), O(r m) per step. ``"direct"``: the full
        model stepped with the same rule and one LCP per step (also Newmark and HHT).
    rule : str or Rule
        ``"bdf1"``, ``"bdf2"`` (default), ``"trapezoidal"``; with ``method="direct"`` also
        ``"newmark"`` and ``"hht"``, or a :class:`~unilateral.rules.Newmark` instance.
    initial : "static", "rest" or dict
        ``"static"``: start at rest from the static unilateral equilibrium under ``q(0)``.
        ``"rest"`` (kernel models): ``v(0) = 0``. A dict with ``u0``, ``udot0``, ``v0``
        (kernel models: ``v0`` only) gives the initial conditions, eqs. (10)-(12).
    lcp : str or LCPSolver
        ``"bpp"`` (block principal pivoting, default), ``"lemke"``, ``"pgs"``, ``"newton"``,
        ``"enumerate"``, or a solver instance.
    lcp_options : dict, optional
        Options for a named solver (e.g. ``{"tol": 1e-12}``).
    bilateral : bool
        Hold every constraint at its initial state (``v = v(0)``, e.g. the static one): the
        paper's "without uplift" case. A gap that is open statically stays open by as much.
    modal_options : dict, optional
        For ``method="modal"``: ``modes`` (None: every pole, exact; an int: that many lowest
        modes plus the static correction, for large models with classical damping) and
        ``engine`` as for ``cq_options``.
    cq_options : dict, optional
        ``L`` and ``rho`` of the FFT that computes the weights (see :func:`cq_weights`);
        ``history``: ``"naive"`` (direct summation, O(N^2 m^2)) or ``"fft"`` (FFT-blocked,
        O(m^2 N log^2 N); the default above 256 steps); ``engine``: ``"auto"`` (default: the
        compiled march where it applies, i.e. naive history and the default ``lcp="bpp"``),
        ``"compiled"`` or ``"python"``.
    callback : callable ``callback(k, N)``, optional
        Called after every step (progress bars).

    Returns
    -------
    Solution
    """
    timer = _Timer()
    dt = V.positive_float("dt", dt)
    t_end = V.positive_float("t_end", t_end)
    if t_end < dt * (1 - 1e-12):
        raise ValueError(f"t_end={t_end!r} must be >= dt={dt!r}")
    N = int(round(t_end / dt))
    method = V.choice("method", method, METHODS)
    if isinstance(model, TimeKernelModel):
        if method != "auto" or load is not None or cq_options or modal_options or rule != "bdf2":
            raise ValueError(
                "a TimeKernelModel is solved by product integration of its time-domain kernel: "
                "pass only dt, t_end, initial, lcp, lcp_options, bilateral (method='auto', load=None)"
            )
        return solve_time_kernel(model, dt=dt, t_end=t_end, initial=initial, lcp=lcp,
                                 lcp_options=lcp_options, bilateral=bilateral, callback=callback)
    if not isinstance(model, (Model, KernelModel)):
        raise TypeError(
            f"model must be a unilateral.Model, KernelModel or TimeKernelModel, got {V.describe(model)}"
        )
    requested = method
    if method == "auto":
        method, reason = _choose_method(model, rule, lcp, cq_options, modal_options)
    if isinstance(model, KernelModel) and method != "cq":
        raise ValueError(f"method={method!r} needs matrices; a KernelModel is solved with method='cq'")
    rule = get_rule(rule, cq=method != "direct")
    solver = get_lcp_solver(lcp, **(lcp_options or {}))
    if cq_options is not None and method != "cq":
        raise ValueError(f"cq_options apply to method='cq' only (method={method!r})")
    if modal_options is not None and method != "modal":
        raise ValueError(f"modal_options apply to method='modal' only (method={method!r})")
    stats = {"method": method, "rule": rule.name, "lcp_solver": solver.name, "steps": N,
             "dt": dt, "m": model.m}
    if requested == "auto":
        stats["method_reason"] = reason
    timer.lap("setup")
    if isinstance(model, KernelModel):
        if load is not None:
            raise ValueError("load is not used by a KernelModel: its psiL carries the loading; pass load=None")
        return _solve_kernel(model, N, dt, rule, initial, solver, bilateral, cq_options or {},
                             callback, stats, timer)
    options = (cq_options if method == "cq" else modal_options) or {}
    return _solve_matrix(model, load, N, dt, method, rule, initial, solver, bilateral,
                         options, callback, stats, timer)


def _choose_method(model, rule, lcp, cq_options, modal_options):
    """The method of ``method="auto"`` and why (measured in the benchmark suite)."""
    if isinstance(model, KernelModel):
        return "cq", "a KernelModel is solved by convolution quadrature of its Lambda(s)"
    if cq_options is not None:
        return "cq", "cq_options were given"
    if modal_options is not None:
        return "modal", "modal_options were given"
    small = model.n <= DENSE_STEPPING_MAX_N and model.m <= FULL_SPACE_MIN_M
    cq_rule = isinstance(rule, str) and rule.lower() in CQ_RULES
    if small and cq_rule and lcp == "bpp" and model.m:
        return "modal", ("small model: the compiled CLCP march with the exact recursive history "
                         "and compiled linear sweeps is the fastest end to end")
    space = "full-space active-set LCP" if model.sparse and model.m > FULL_SPACE_MIN_M else "condensed LCP"
    return "direct", f"direct stepping ({space}) is the fastest end to end for this model"


# ---------------------------------------------------------------------- matrix models
def _solve_matrix(model, load, N, dt, method, rule, initial, solver, bilateral, options,
                  callback, stats, timer):
    stats["n"] = model.n
    q = _load_function(model, load, N, dt)
    init = _initial_matrix(model, q, initial, solver)
    t = dt * np.arange(N + 1)
    if init.message:
        return _failed_at_start(model, init, stats, timer)
    stats["static_lcp_iterations"] = init.lcp_iterations
    u_b, v_b = init.u, init.v
    K_ub = model.K @ u_b
    F_vb = model.F @ v_b
    HFu = transpose_times(model.F, u_b) - model.H @ v_b
    if method != "direct" and model.n <= DENSE_STEPPING_MAX_N:
        # small models: the compiled sweeps take every step's load and offset as arrays
        load_inc = _load_table(model, load, q, N, dt) + (F_vb - K_ub)
        g = model.g(0.0) if model.g_is_constant else np.array([model.g(k * dt) for k in range(N + 1)])
        offset = np.tile(HFu, (N + 1, 1)) - g
    else:
        load_inc = lambda k: q(k) + F_vb - K_ub
        offset = lambda k: HFu - model.g(k * dt)
    make_stepper = lambda: StructureStepper(model, rule, dt, load_inc, offset, init.udot, condensed=False)
    timer.lap("initial")

    psiL = None
    if method == "direct":
        full_space = (model.sparse and model.m > FULL_SPACE_MIN_M
                      and isinstance(solver, BlockPrincipalPivoting))
        stats["lcp_space"] = "full" if full_space else "condensed"
        stepper = StructureStepper(model, rule, dt, load_inc, offset, init.udot, condensed=not full_space)
        timer.lap("factorize")
        march = march_direct_active_set if full_space else functools.partial(march_direct, solver=solver)
        du, dud, v, psi, log = march(stepper, N, v_b, init.psi, dt=dt, bilateral=bilateral,
                                     callback=callback)
        timer.lap("steps")
    else:
        _, _, _, psiL, _ = sweep_direct(make_stepper(), N, v_b, init.psi)
        timer.lap("bilateral")
        if method == "cq":
            weight_options, march = _split_cq_options(options)
            W = cq_weights(MatrixKernel(model), N, dt, rule, **weight_options)
            timer.lap("weights")
            v, psi, log = _march_weights(W, psiL, v_b, solver, dt, bilateral, callback, march, stats)
        else:
            marched = _march_modal(model, N, dt, rule, psiL, v_b, solver, bilateral, callback,
                                   options, stats, timer)
            if marched is None:             # method="auto" fell back to direct stepping
                stats["method"] = "direct"
                return _solve_matrix(model, load, N, dt, "direct", rule, initial, solver, bilateral,
                                     {}, callback, stats, timer)
            v, psi, log = marched
        timer.lap("steps")
        K = v.shape[0] - 1
        dv = v - v_b
        du, dud, _, _, _ = sweep_direct(make_stepper(), K, v_b, init.psi, dv)
        timer.lap("recover")
    K = v.shape[0] - 1
    return _finish(model, t[: K + 1], v, psi, None if psiL is None else psiL[: K + 1],
                   u_b + du, dud, log, stats, timer)


def _initial_matrix(model, q, initial, solver) -> InitialState:
    if isinstance(initial, str) and V.choice("initial", initial, ("static", "rest")) == "static":
        return static_state(model, q(0), solver)
    if isinstance(initial, str):                              # "rest"
        return given_state(model, {})
    if isinstance(initial, dict):
        return given_state(model, initial)
    raise TypeError(f"initial must be 'static', 'rest' or a dict of u0, udot0, v0; got {V.describe(initial)}")


def _load_function(model, load, N, dt):
    """Return ``q(k) -> (n,)``: applied load plus the load of imposed strains at ``t_k``."""
    n = model.n
    imposed = model.q_imposed
    if load is None:
        return lambda k: imposed(k * dt)
    if callable(load):
        def q(k):
            value = np.asarray(load(k * dt), dtype=float)
            if value.shape != (n,):
                raise ValueError(f"load(t) must return shape ({n},), got shape {value.shape} at t={k * dt}")
            if not np.all(np.isfinite(value)):
                raise ValueError(f"load(t) returned a non-finite value at t={k * dt} (step {k})")
            return value + imposed(k * dt)
        return q
    arr = V.as_matrix("load", load, (None, n), allow_sparse=False)
    if arr.shape[0] < N + 1:
        raise ValueError(
            f"load has {arr.shape[0]} rows but t_end/dt = {N} steps need {N + 1} (rows at t = k dt)"
        )
    return lambda k: arr[k] + imposed(k * dt)


def _load_table(model, load, q, N, dt):
    """``q(k)`` of every step, (N+1, n): sampled at once for an array load or one with ``sample(t)``."""
    n = model.n
    vectorised = model.q_imposed_is_constant and (
        isinstance(load, np.ndarray) or (callable(getattr(load, "sample", None)) and callable(load)))
    if not vectorised:
        return np.array([q(k) for k in range(N + 1)], dtype=float).reshape(N + 1, n)
    if isinstance(load, np.ndarray):
        Q = np.array(load[: N + 1], dtype=float)
    else:
        Q = np.asarray(load.sample(dt * np.arange(N + 1)), dtype=float)
        if Q.shape != (N + 1, n):
            raise ValueError(f"load.sample(t) must return shape ({N + 1}, {n}) for {N + 1} times, "
                             f"got shape {Q.shape}")
        bad = np.flatnonzero(~np.all(np.isfinite(Q), axis=1))
        if bad.size:
            raise ValueError(f"load(t) returned a non-finite value at t={bad[0] * dt} (step {bad[0]})")
    return Q + model.q_imposed(0.0)


# ---------------------------------------------------------------------- kernel models
def _solve_kernel(model, N, dt, rule, initial, solver, bilateral, cq_options, callback, stats, timer):
    psiL = model.psiL_samples(N, dt)
    timer.lap("setup")
    weight_options, march = _split_cq_options(cq_options)
    W = cq_weights(model.kernel, N, dt, rule, **weight_options)
    W = np.real_if_close(W) if np.iscomplexobj(W) else W
    timer.lap("weights")
    if isinstance(initial, str) and V.choice("initial", initial, ("static", "rest")) == "static":
        Lambda0 = model.Lambda_real(0.0)
        v_b, iters, message = static_lcp(Lambda0, psiL[0], solver)
        stats["static_lcp_iterations"] = iters
        if message:
            return _failed_at_start(model, InitialState(v=v_b, psi=psiL[0], message=message), stats, timer)
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
    v, psi, log = _march_weights(W, psi_affine, v_b, solver, dt, bilateral, callback, march, stats)
    timer.lap("steps")
    K = v.shape[0] - 1
    return _finish(model, dt * np.arange(K + 1), v, psi, psiL[: K + 1], None, None, log, stats, timer)


# ---------------------------------------------------------------------- shared pieces
def _split_cq_options(cq_options):
    """Split ``cq_options`` into the weight options (``L``, ``rho``) and the march options."""
    options = dict(cq_options)
    march = {"history": options.pop("history", None), "engine": options.pop("engine", "auto")}
    unknown = set(options) - {"L", "rho"}
    if unknown:
        raise ValueError(
            f"cq_options has unknown keys {sorted(unknown)}; valid keys: 'L', 'rho', 'history', 'engine'"
        )
    V.choice("cq_options['engine']", march["engine"], ENGINES)
    return options, march


def _march_modal(model, N, dt, rule, psi_affine, v_b, solver, bilateral, callback, options, stats,
                 timer):
    options = dict(options)
    modes = options.pop("modes", None)
    engine = V.choice("modal_options['engine']", options.pop("engine", "auto"), ENGINES)
    if options:
        raise ValueError(f"modal_options has unknown keys {sorted(options)}; valid keys: 'modes', 'engine'")
    try:
        kernel = PoleResidueKernel.from_model(model, modes=modes)
    except ValueError as exc:
        if stats.get("method_reason") is None:
            raise
        stats["method_reason"] += f"; modal refused ({exc}), direct used instead"
        return None
    stats["modal"] = {key: value for key, value in kernel.info.items()
                      if isinstance(value, (int, float, str))}
    W0 = kernel.W0(dt, rule)
    history = kernel.history(N, dt, rule)
    timer.lap("poles")
    compiled_ok = isinstance(solver, BlockPrincipalPivoting) and not bilateral
    if engine == "compiled" and not compiled_ok:
        raise ValueError("modal_options['engine']='compiled' needs lcp='bpp'")
    stats["history"] = history.name
    if engine == "compiled" or (engine == "auto" and compiled_ok and callback is None):
        stats["engine"] = "compiled"
        return march_cq_compiled("recursive", (W0, *history.arrays(), psi_affine), v_b, dt=dt,
                                 tol=solver.tol, max_iter=solver.max_iter or 10 * model.m + 10)
    stats["engine"] = "python"
    return march_cq(W0, history, psi_affine, v_b, solver, dt=dt, bilateral=bilateral, callback=callback)


def _march_weights(W, psi_affine, v_b, solver, dt, bilateral, callback, march, stats):
    W = W.copy()
    W[0] = 0.5 * (W[0] + W[0].T)
    N = W.shape[0] - 1
    history = march["history"] or ("fft" if N > FFT_HISTORY_MIN_STEPS else "naive")
    history = V.choice("cq_options['history']", history, HISTORIES)
    engine = march["engine"].lower()
    compiled_ok = history == "naive" and isinstance(solver, BlockPrincipalPivoting) and not bilateral
    if engine == "compiled" and not compiled_ok:
        raise ValueError("cq_options['engine']='compiled' needs history='naive' and lcp='bpp'")
    stats["history"] = history
    if engine == "compiled" or (engine == "auto" and compiled_ok and callback is None):
        stats["engine"] = "compiled"
        return march_cq_compiled("naive", (W, psi_affine), v_b, dt=dt, tol=solver.tol,
                                 max_iter=solver.max_iter or 10 * W.shape[1] + 10)
    stats["engine"] = "python"
    return march_cq(W[0], HISTORIES[history](W), psi_affine, v_b, solver, dt=dt, bilateral=bilateral,
                    callback=callback)


def _finish(model, t, v, psi, psiL, u, udot, log, stats, timer):
    N = stats["steps"]
    stats.update(log.stats())
    if hasattr(log, "factorizations"):
        stats["factorizations"] = log.factorizations
    stats["steps_done"] = len(t) - 1
    stats["time"] = timer.laps()
    if log.failure:
        success = False
        message = f"stopped after {len(t) - 1} of {N} steps: {log.failure}"
    else:
        success = True
        message = f"{N} steps, {stats['contact_changes']} contact changes"
    return Solution(t=t, v=v, psi=psi, psiL=psiL, u=u, udot=udot, success=success,
                    message=message, stats=stats, dof_names=list(getattr(model, "dof_names", [])),
                    constraint_names=list(model.constraint_names))


def _failed_at_start(model, init, stats, timer):
    stats["time"] = timer.laps()
    stats["steps_done"] = 0
    n_u = None if init.u is None else init.u[None]
    return Solution(t=np.zeros(1), v=init.v[None], psi=init.psi[None], psiL=init.psi[None],
                    u=n_u, udot=None if init.udot is None else init.udot[None], success=False,
                    message=init.message, stats=stats, dof_names=list(getattr(model, "dof_names", [])),
                    constraint_names=list(model.constraint_names))


class _Timer:
    """Wall time per phase."""

    def __init__(self):
        self._start = self._last = time.perf_counter()
        self._laps = {}

    def lap(self, name):
        now = time.perf_counter()
        self._laps[name] = self._laps.get(name, 0.0) + now - self._last
        self._last = now

    def laps(self):
        out = dict(self._laps)
        out["total"] = time.perf_counter() - self._start
        return out
