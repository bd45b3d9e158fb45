"""The CLCP with a time-domain kernel ``Lambda(t)`` (the paper's alternative route, section 4).

``psi(t) = psiL(t) - (Lambda * v)(t)`` with

    Lambda(t) = Lambda_inf delta(t) + Lambda_rate delta'(t) + Lambda_r(t),

where ``Lambda_inf + s Lambda_rate`` is the asymptote of ``Lambda(s)`` for large ``|s|`` (the
instantaneous stiffness ``H`` and, with Kelvin dashpots, their viscosity) and ``Lambda_r`` a
regular function, the inverse transform of ``Lambda(s) - Lambda_inf - s Lambda_rate``. Numerical
Laplace inversion cannot represent the two singular parts, so they are split off first.

The convolution is discretised by product integration on the grid ``t_k = k dt``
(:func:`time_kernel_weights`), giving weights ``W_j`` of the same form as the
convolution-quadrature weights of :func:`~unilateral.kernels.cq_weights`, and the CLCP is marched by
:func:`~unilateral.march.clcp.march_cq`, one LCP per step (:func:`solve_time_kernel`).

Compared with convolution quadrature, which needs ``Lambda(s)`` only on a circle and is exact
for the equivalent time stepping, this route needs ``Lambda_r`` sampled accurately at the grid
(numerical inversion, to ~1e-10 relative for structural kernels) and is second order only where
``Lambda_r`` is smooth on the scale ``dt``. It fails where the kernel has dynamics between the
frequencies the grid resolves and ~100 / dt: e.g. the paper's example with Kelvin soil elements
(dashpots in series with the contacts under a massless foundation and an axially rigid column)
has relaxation times from ~1e-3 s down to ~1e-7 s, no asymptote ``Lambda_inf + s Lambda_rate``
holds at ``|s| ~ 10 pi / dt`` for any practical dt, :meth:`TimeKernel.from_laplace` warns
(``asymptote_misfit`` ~ 1e-2) and the march is wrong. Use convolution quadrature there.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .. import _validate as V
from .base import CallableKernel, Kernel
from .laplace_inversion import METHODS as INVERSION_METHODS
from .laplace_inversion import invert_laplace
from ..rules import BDF

#: The asymptote ``Lambda_inf + s Lambda_rate`` is fitted at ``s = i y`` with
#: ``y = ASYMPTOTE_FACTOR (pi / dt) 2^j``, j = 0..3: above every frequency the grid resolves.
ASYMPTOTE_FACTOR = 10.0
#: A fitted ``Lambda_rate`` with ``|Lambda_rate| y`` below this fraction of ``|Lambda(i y)|`` is
#: round-off of a bounded kernel and is dropped.
RATE_NEGLIGIBLE = 1e-10
#: Number of times at which the inversion is repeated with the other method.
CHECK_TIMES = 8
#: Relative discrepancy of the two inversions, or misfit of the asymptote, above which
#: :meth:`TimeKernel.from_laplace` warns.
WARN_LEVEL = 1e-5
QUADRATURES = ("trapezoidal", "rectangle")
RATE_RULES = ("bdf2", "bdf1")


class TimeKernel:
    """``Lambda(t) = Lambda_inf delta(t) + Lambda_rate delta'(t) + Lambda_r(t)``.

    Parameters
    ----------
    Lambda_inf : (m, m) array_like
        Instantaneous part, ``lim Lambda(s)`` (minus ``s Lambda_rate``) for ``|s| -> inf``.
    Lambda_r : callable ``Lambda_r(t) -> (m, m)`` or array (N+1, m, m)
        Regular part, a function of ``t >= 0``, or its samples at ``t_k = k dt``.
    dt : float, optional
        Spacing of the samples (required with an array ``Lambda_r``).
    Lambda_rate : (m, m) array_like, optional
        Coefficient of ``delta'(t)`` (``(Lambda_rate delta' * v)(t) = Lambda_rate v'(t)``): the
        viscosity of dashpots in series with the constraints (Kelvin elements).
    Lambda0 : (m, m) array_like, optional
        The static kernel ``Lambda(s = 0) = Lambda_inf + integral_0^inf Lambda_r(t) dt``, needed
        to start from the static state (``initial="static"`` in :func:`solve_time_kernel`).
    info : dict, optional
        How the kernel was obtained (filled by :meth:`from_laplace`).

    Attributes
    ----------
    m : int
    Lambda_inf, Lambda_rate, Lambda0 : (m, m) float (``Lambda_rate``, ``Lambda0`` may be None)
    info : dict
    """

    def __init__(self, Lambda_inf, Lambda_r, *, dt=None, Lambda_rate=None, Lambda0=None, info=None):
        self.Lambda_inf = _square("Lambda_inf", Lambda_inf, None)
        self.m = m = self.Lambda_inf.shape[0]
        self.Lambda_rate = None if Lambda_rate is None else _square("Lambda_rate", Lambda_rate, m)
        self.Lambda0 = None if Lambda0 is None else _square("Lambda0", Lambda0, m)
        self.info = dict(info or {})
        self.dt = None if dt is None else V.positive_float("dt", dt)
        if callable(Lambda_r):
            self.Lambda_r, self._samples = Lambda_r, None
            return
        try:
            samples = np.array(Lambda_r, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(
                f"Lambda_r must be a callable Lambda_r(t) or an array (N+1, m, m), got {V.describe(Lambda_r)}"
            ) from None
        if m == 1 and samples.ndim == 1:
            samples = samples[:, None, None]
        if samples.ndim != 3 or samples.shape[1:] != (m, m) or samples.shape[0] < 1:
            raise ValueError(f"Lambda_r samples must have shape (N+1, {m}, {m}), got {samples.shape}")
        V.check_finite("Lambda_r", samples)
        if self.dt is None:
            raise ValueError("dt is required with sampled Lambda_r (the samples are at t_k = k dt)")
        self.Lambda_r, self._samples = None, samples

    @classmethod
    def from_laplace(cls, Lambda, m, *, dt, N, method="dehoog", Lambda_inf=None, Lambda_rate=None,
                     vectorized=False, inversion_options=None) -> TimeKernel:
        """Time-domain kernel of ``Lambda(s)`` by numerical Laplace inversion, sampled at ``k dt``.

        1. The asymptote: ``Lambda_inf`` and ``Lambda_rate``, where not given, are fitted by
           least squares at ``s = i y_j``, ``y_j = 10 (pi / dt) 2^j``, j = 0..3:
           ``Re Lambda(i y) = Lambda_inf + c / y^2`` and ``Im Lambda(i y) / y = Lambda_rate +
           c' / y^2``, the expansion ``Lambda(s) = s A1 + A0 + B / s + C / s^2 + ...`` of a
           kernel analytic at infinity; its next terms are ``O((omega / y)^4)`` for the
           frequencies ``omega < pi / dt`` that the grid resolves. Dynamics much faster than
           ``y_0`` (e.g. an axially rigid column in series with a soil dashpot) is thereby
           taken as quasi-static, part of ``Lambda_inf``, instead of leaving an unresolvable
           spike in ``Lambda_r``. A ``Lambda_rate`` at round-off level (bounded kernels) is
           dropped. ``info["asymptote_misfit"]``, the largest residual of the fit relative to
           ``max |Lambda(i y_j)|``, is small only if the expansion holds at these ``y`` (with
           given parts: if they are right); it is not for a kernel growing like ``sqrt(s)``
           (an unbounded medium), or with dynamics on the scale of ``y_0``.
        2. ``Lambda_r(t_k)``, k = 1..N, by inverting ``Lambda(s) - Lambda_inf - s Lambda_rate``
           with ``method`` (one call for all times, every ``Lambda`` evaluation batched). The
           series cannot be evaluated at t = 0 (it converges to the mean of the jump there):
           ``Lambda_r(0)`` is extrapolated by the cubic through k = 1..4 (error
           ``O(dt^4 Lambda_r'''')``, which enters the weights multiplied by ``dt / 2``).
        3. The check: ``Lambda_r`` at ``CHECK_TIMES`` grid times by the other method;
           ``info["check_relative"]`` is the largest discrepancy relative to
           ``max |Lambda_r(t_k)|`` (1e-12 .. 1e-10 measured for the kernels of the tests).
        4. ``Lambda0 = Lambda(0)``, if ``Lambda`` is finite at ``s = 0``.

        Cost: about ``2.7 N`` evaluations of ``Lambda(s)`` for the inversion (the series up to
        the Nyquist frequency ``pi / dt`` in each window) and as many again for the check.

        Warns (RuntimeWarning) if the check or the asymptote misfit exceeds ``WARN_LEVEL``.

        Parameters
        ----------
        Lambda : callable or Kernel
            ``Lambda(s) -> (m, m)`` (see :class:`~unilateral.kernels.CallableKernel`), e.g. a
            :class:`~unilateral.kernels.MatrixKernel`.
        m : int
        dt : float
            Sample spacing; the inversion resolves frequencies up to ``pi / dt``.
        N : int
            Samples ``t_k = k dt`` for k = 0..N.
        method : {"dehoog", "durbin"}
        Lambda_inf, Lambda_rate : (m, m) array_like, optional
            Known asymptote (e.g. ``H`` and ``H_v`` of a matrix model); a given ``Lambda_inf``
            without ``Lambda_rate`` means the kernel is bounded.
        vectorized : bool
            ``Lambda`` accepts an array of s (ignored for a Kernel).
        inversion_options : dict, optional
            Options of :func:`~unilateral.kernels.invert_laplace`.

        Returns
        -------
        TimeKernel
        """
        dt = V.positive_float("dt", dt)
        if isinstance(N, bool) or not isinstance(N, (int, np.integer)) or N < 1:
            raise ValueError(f"N must be a positive integer, got {N!r}")
        method = V.choice("method", method, INVERSION_METHODS)
        kernel = Lambda if isinstance(Lambda, Kernel) else CallableKernel(Lambda, m, vectorized=vectorized)
        if kernel.m != m:
            raise ValueError(f"m={m!r} does not match the kernel's m={kernel.m}")
        options = dict(inversion_options or {})
        options.setdefault("omega_max", math.pi / dt)
        info = {"method": method, "inversion_options": options}
        given = {name: None if value is None else _square(name, value, m)
                 for name, value in (("Lambda_inf", Lambda_inf), ("Lambda_rate", Lambda_rate))}
        A0, A1, misfit = fit_asymptote(kernel, dt, **given)
        info["asymptote"] = "given" if given["Lambda_inf"] is not None else "fitted"
        info["asymptote_misfit"] = misfit

        def remainder(s):
            out = kernel(s) - A0
            return out if A1 is None else out - s[:, None, None] * A1

        samples, check = _inverted_samples(remainder, m, dt, N, method, options)
        info.update(check)
        _warn_inaccurate(info)
        return cls(A0, samples, dt=dt, Lambda_rate=A1, Lambda0=_static(kernel, info), info=info)

    def samples(self, N: int, dt: float) -> np.ndarray:
        """``Lambda_r(t_k)`` at ``t_k = k dt``, k = 0..N, shape (N+1, m, m)."""
        if self._samples is None:
            out = np.empty((N + 1, self.m, self.m))
            for k in range(N + 1):
                value = np.asarray(self.Lambda_r(k * dt), dtype=float)
                if value.size != self.m * self.m:
                    raise ValueError(
                        f"Lambda_r(t) must return shape ({self.m}, {self.m}), got {value.shape} at t={k * dt}"
                    )
                out[k] = value.reshape(self.m, self.m)
            V.check_finite("Lambda_r(t)", out)
            return out
        if not math.isclose(dt, self.dt, rel_tol=1e-9):
            raise ValueError(f"dt={dt!r} differs from the spacing {self.dt!r} of the Lambda_r samples")
        if self._samples.shape[0] < N + 1:
            raise ValueError(f"Lambda_r has {self._samples.shape[0]} samples but {N} steps need {N + 1}")
        return self._samples[: N + 1]

    def __repr__(self) -> str:
        kind = "callable" if self._samples is None else f"{self._samples.shape[0]} samples, dt={self.dt:g}"
        rate = ", Lambda_rate" if self.Lambda_rate is not None else ""
        return f"TimeKernel(m={self.m}, Lambda_r {kind}{rate})"


def fit_asymptote(kernel, dt, *, Lambda_inf=None, Lambda_rate=None):
    """Fit ``Lambda(s) ~ Lambda_inf + s Lambda_rate`` at ``s = i y_j`` (see :meth:`TimeKernel.from_laplace`).

    Parameters
    ----------
    kernel : Kernel
    dt : float
    Lambda_inf, Lambda_rate : (m, m) float, optional
        Known parts, held fixed (``Lambda_rate`` is zero if only ``Lambda_inf`` is given).

    Returns
    -------
    Lambda_inf : (m, m) float
    Lambda_rate : (m, m) float or None
    misfit : float
        Largest residual of the fit relative to ``max |Lambda(i y_j)|``.
    """
    y = ASYMPTOTE_FACTOR * math.pi / dt * 2.0 ** np.arange(4)
    values = kernel(1j * y)                                        # (4, m, m)
    m = values.shape[1]
    if Lambda_inf is not None and Lambda_rate is None:
        Lambda_rate = np.zeros((m, m))
    A0, res0 = _fit_tail(values.real, y, Lambda_inf)
    A1, res1 = _fit_tail(values.imag / y[:, None, None], y, Lambda_rate)
    scale = max(np.max(np.abs(values)), np.finfo(float).tiny)
    misfit = float(max(np.max(np.abs(res0)), np.max(np.abs(res1 * y[:, None, None]))) / scale)
    if not np.any(A1) or np.max(np.abs(A1)) * y[-1] <= RATE_NEGLIGIBLE * np.max(np.abs(values[-1])):
        A1 = None
    return A0, A1, misfit


def _fit_tail(data, y, known):
    """Least-squares ``data (4, m, m) ~ A + c / y^2`` with ``A`` fitted (and symmetrised) or ``known``.

    Returns ``A`` and the residuals (4, m, m).
    """
    flat = data.reshape(data.shape[0], -1)
    if known is not None:
        rest = flat - known.reshape(1, -1)
        c = (y ** -2) @ rest / np.sum(y ** -4)
        return known, (rest - np.outer(y ** -2, c)).reshape(data.shape)
    basis = np.stack([np.ones_like(y), y ** -2], axis=1)
    coef = np.linalg.lstsq(basis, flat, rcond=None)[0]
    A = coef[0].reshape(data.shape[1:])
    return 0.5 * (A + A.T), (flat - basis @ coef).reshape(data.shape)


def time_kernel_weights(kernel, N, dt, *, quadrature="trapezoidal", rate="bdf2") -> np.ndarray:
    """Weights ``W_j`` with ``(Lambda * v)(t_n) ~ sum_{j=0..n} W_j v_{n-j}`` (product integration).

    ``quadrature="trapezoidal"`` (second order for ``Lambda_r`` smooth on the scale ``dt``):
    ``W_0 = Lambda_inf + dt/2 Lambda_r(0)``, ``W_j = dt Lambda_r(t_j)``. The trapezoidal rule for
    ``integral_0^t_n Lambda_r(tau) v(t_n - tau) dtau`` also halves the end term ``j = n``, which
    multiplies ``v_0``; the library marches increments about the initial state, ``dv_0 = 0``
    (:func:`~unilateral.march.clcp.march_cq`), so the end correction vanishes and the weights form a
    convolution. ``quadrature="rectangle"`` drops the ``dt/2 Lambda_r(0)`` term: first order
    (a reference for the convergence tests).

    The rate part ``Lambda_rate v'(t_n)`` is discretised by ``rate``: ``"bdf2"`` (default,
    second order, ``(3 v_n - 4 v_{n-1} + v_{n-2}) / (2 dt)``, the same BDF2 that damps contact
    chatter in convolution quadrature) or ``"bdf1"`` (``(v_n - v_{n-1}) / dt``, first order).

    Parameters
    ----------
    kernel : TimeKernel
    N : int, highest weight index (number of steps)
    dt : float
    quadrature : {"trapezoidal", "rectangle"}
    rate : {"bdf2", "bdf1"}

    Returns
    -------
    W : (N + 1, m, m) float
    """
    if not isinstance(kernel, TimeKernel):
        raise TypeError(f"kernel must be a TimeKernel, got {V.describe(kernel)}")
    if isinstance(N, bool) or not isinstance(N, (int, np.integer)) or N < 0:
        raise ValueError(f"N must be an integer >= 0, got {N!r}")
    dt = V.positive_float("dt", dt)
    quadrature = V.choice("quadrature", quadrature, QUADRATURES)
    rate = V.choice("rate", rate, RATE_RULES)
    W = dt * kernel.samples(N, dt)
    W[0] = kernel.Lambda_inf + (0.5 * W[0] if quadrature == "trapezoidal" else 0.0)
    if kernel.Lambda_rate is not None:
        W += (BDF(int(rate[-1])).delta_coefficients(N) / dt)[:, None, None] * kernel.Lambda_rate[None]
    return W


def _square(name, value, m):
    """``value`` as a float (m, m) matrix (a scalar for m = 1); any m if ``m`` is None."""
    if np.ndim(value) == 0:
        value = [[value]]
    A = V.as_matrix(name, value, (m, m), allow_sparse=False)
    if A.shape[0] != A.shape[1]:
        raise ValueError(f"{name} must be square, got shape {A.shape}")
    return A


def _static(kernel, info):
    """``Lambda(0)`` as a real symmetric matrix, or None (with the reason in ``info``)."""
    try:
        with np.errstate(divide="ignore", invalid="ignore"):
            value = kernel(np.array([0.0]))[0]
    except (ValueError, ZeroDivisionError) as exc:        # LinAlgError is a ValueError
        info["Lambda0"] = f"not available: Lambda(0) failed ({exc})"
        return None
    value = np.real(value)
    info["Lambda0"] = "Lambda(s = 0)"
    return 0.5 * (value + value.T)


def _inverted_samples(remainder, m, dt, N, method, options) -> tuple[np.ndarray, dict]:
    """Steps 2 and 3 of :meth:`TimeKernel.from_laplace`: the samples of the inverse of ``remainder``
    and their check by the other method.

    Parameters
    ----------
    remainder : callable, ``remainder(s) -> (len(s), m, m)``;  m : int;  dt : float;  N : int
    method : the inversion method;  options : dict of :func:`~unilateral.kernels.invert_laplace`
        (with ``omega_max``)

    Returns
    -------
    samples : (N + 1, m, m), ``samples[0]`` extrapolated by the cubic through k = 1..4
    check : dict, ``check_method``, ``check_times`` and ``check_relative`` of ``info``
    """
    samples = np.empty((N + 1, m, m))
    samples[1:] = invert_laplace(remainder, dt * np.arange(1, N + 1), method=method, **options)
    q = min(4, N)
    samples[0] = sum((-1) ** (j + 1) * math.comb(q, j) * samples[j] for j in range(1, q + 1))
    other = INVERSION_METHODS[1 - INVERSION_METHODS.index(method)]
    k = np.unique(np.round(np.linspace(1, N, min(CHECK_TIMES, N))).astype(int))
    check = invert_laplace(remainder, dt * k, method=other, omega_max=options["omega_max"])
    scale = max(np.max(np.abs(samples[1:])), np.finfo(float).tiny)
    return samples, dict(check_method=other, check_times=dt * k,
                         check_relative=float(np.max(np.abs(check - samples[k])) / scale))


def _warn_inaccurate(info) -> None:
    """Warn (RuntimeWarning, at the caller of :meth:`TimeKernel.from_laplace`) if the check or the
    asymptote misfit of its ``info`` exceeds ``WARN_LEVEL``."""
    for key in ("check_relative", "asymptote_misfit"):
        if info[key] > WARN_LEVEL:
            warnings.warn(
                f"TimeKernel.from_laplace: {key} = {info[key]:.3g} > {WARN_LEVEL:g}: the kernel "
                "may vary faster than dt resolves, or its asymptote is not Lambda_inf + s "
                "Lambda_rate; check info, reduce dt or give Lambda_inf/Lambda_rate",
                RuntimeWarning, stacklevel=3)
