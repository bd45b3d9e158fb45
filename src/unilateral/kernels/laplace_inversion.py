"""Numerical inversion of Laplace transforms by accelerated Fourier series.

Both methods sample ``F(s)`` on a vertical line ``s_k = gamma + i pi k / T`` and sum the Fourier
series (trapezoidal rule for the Bromwich integral, Durbin 1974; Crump 1976)

    f(t) ~ exp(gamma t) / T  Re[ F(gamma)/2 + sum_{k>=1} F(s_k) z^k ],    z = exp(i pi t / T),

which represents ``exp(-gamma t) f(t)`` as a Fourier series of period ``2T``. Its aliasing error
is ``sum_{j>=1} exp(-2 j gamma T) f(t + 2 j T)``: the shift ``gamma = ln(1/tol) / (2T)`` makes
it ``~ tol |f|``, and the factor ``exp(gamma t)`` amplifies the truncation and round-off errors
by at most ``tol^(-t/2T)``. They differ in how the slowly converging tail is summed:

* ``"dehoog"`` -- de Hoog, Knight & Stokes (1982): the tail is summed as the continued fraction
  of its power series in ``z`` (a diagonal Pade approximant), whose coefficients come from the
  quotient-difference algorithm, with the further acceleration of the continued fraction's
  remainder. The continued fraction depends on ``z`` only, so it is built once per window.
* ``"durbin"`` -- the plain trapezoidal series of Durbin (1974), its tail accelerated by Wynn's
  epsilon algorithm on the partial sums at each ``t`` (or not at all, ``acceleration="none"``).

Two refinements make them work for oscillatory, lightly damped responses over many periods
(the kernels and bilateral responses of structures):

* The quotient-difference algorithm is unstable in double precision, and the classical method
  needs Pade approximants that absorb the whole spectrum of the response: measured for
  ``sin(2 pi t)`` at one t with ``T = 2t``, ``M = 40`` gives 1e-7 at t = 5, but at t = 10
  (40 periods within ``2T``) no ``M`` up to 100 gives an error below 0.3. Here the terms up to the
  frequency ``omega_max`` (default: the Nyquist frequency of the time grid, ``pi n / t_max``) are
  summed directly, and only the smooth remainder, beyond every resonance, is accelerated.
  With fewer than 32 times the default is ``32 pi / t_max``.
* A Fourier series of period ``2T`` is least accurate near ``t = 0`` and ``t = 2T``, where the
  periodic extension of ``exp(-gamma t) f(t)`` has its jump (in ``f`` or in a derivative). The
  times are therefore grouped in windows ``(t_w / ratio, t_w]`` with ``t_w`` descending from
  ``max(t)``, each inverted with its own ``T = scale t_w``, so that ``t / T`` stays in
  ``[1 / (scale ratio), 1 / scale]``.

Talbot's and Stehfest's methods are not offered: Stehfest's uses real ``s`` only and its
Gaver functionals need high precision to resolve anything but smooth, non-oscillating
responses; Talbot's contour assumes ``F`` analytic to the left of its path, i.e. its singularities
near the negative real axis, and the poles ``-zeta w +- i w`` of a lightly damped structure lie
next to the imaginary axis. Both fail on oscillatory responses.

Measured accuracy with the defaults (``tol = 1e-12``, ``scale = 2``, ``ratio = 4``; dehoog
``M = 20``, durbin ``p = 10``): maximum absolute error at 2000 equally spaced times in
``(0, t_max]`` (tests/test_time_kernel.py pins these with margin):

========================================================  =========  =========
pair                                                      dehoog     durbin
========================================================  =========  =========
``1/(s+1)``, t_max = 10                                   1e-12      5e-10
``w/(s^2+w^2)``, w = 2 pi, t_max = 10 (10 periods)        2e-12      5e-12
the same, t_max = 50 (1000 times)                         1e-12      7e-11
``1/((s+0.5)^2+w^2)``, t_max = 10                         1e-13      1e-12
``(K + s a K + s^2 M)^-1``, 2 x 2, two modes, t_max = 30  1e-12      4e-12
========================================================  =========  =========

A delayed step ``exp(-s tau)/s`` is discontinuous at ``t = tau``, and a Fourier series has the
Gibbs phenomenon there: at 2000 times up to ``2 tau`` the error is 1e-12 (dehoog) / 1e-11
(durbin) for ``|t - tau| > 0.05 tau``, 3e-10 / 4e-8 for ``|t - tau| > 0.01 tau``, and O(1)
next to the jump (at ``t = tau`` the series gives about the mean, 1/2).
"""

from __future__ import annotations

import math

import numpy as np

from .. import _validate as V

METHODS = ("dehoog", "durbin")
_COMMON = {"tol": 1e-12, "scale": 2.0, "ratio": 4.0, "omega_max": None}
_DEFAULTS = {"dehoog": dict(_COMMON, M=20), "durbin": dict(_COMMON, p=10, acceleration="epsilon")}
#: Entries whose samples are all below this fraction of the largest are taken as zero (the
#: quotient-difference table of an identically zero series is 0/0).
NEGLIGIBLE = 1e-14
_BLOCK = 128
#: The default ``omega_max`` is the Nyquist frequency of at least this many times in (0, max(t)].
MIN_TIMES = 32


def invert_laplace(F, t, *, method="dehoog", vectorized=True, **options) -> np.ndarray:
    """Values of the real function ``f(t)`` whose Laplace transform is ``F(s)``.

    Parameters
    ----------
    F : callable
        ``F(s)`` for complex ``s`` with ``Re s > 0``, returning an array of any trailing
        shape (e.g. (m, m)); ``f`` must be real, i.e. ``F(conj s) = conj F(s)``.
    t : array_like of positive times, any shape
    method : {"dehoog", "durbin"}
    vectorized : bool
        ``F`` accepts an array of ``s`` of shape (L,) and returns (L, ...) (default); otherwise
        it is called once per ``s``.
    **options
        ``tol`` (aliasing level, in (0, 1), default 1e-12), ``scale`` (``T = scale t_w``,
        >= 1, default 2), ``ratio`` (window width, > 1, default 4), ``omega_max`` (frequency up
        to which the series is summed directly, default ``pi max(t.size, 32) / max(t)``; raise
        it above the highest natural frequency if the times are few); for ``"dehoog"`` ``M`` (order of
        the continued fraction, ``2M + 1`` terms, default 20); for ``"durbin"`` ``p``
        (``2p + 1`` partial sums for the epsilon algorithm, default 10) and ``acceleration``
        (``"epsilon"`` or ``"none"``).

    Returns
    -------
    f : array of shape ``t.shape + trailing shape of F(s)``, float

    Notes
    -----
    Costs per window: ``K + 2M + 1`` (``K + 2p + 1``) evaluations of ``F`` with
    ``K = ceil(omega_max T / pi)``, and ``O(n_w K)`` work per entry for the direct sum at the
    ``n_w`` times of the window.
    """
    times = np.asarray(t, dtype=float)
    if times.size == 0:
        raise ValueError("t must hold at least one time, got an empty array")
    V.check_finite("t", times)
    if np.any(times <= 0):
        raise ValueError(f"t must be > 0 (the series is not defined at t = 0), got min(t) = {times.min()!r}")
    if not callable(F):
        raise TypeError(f"F must be callable F(s), got {V.describe(F)}")
    method = V.choice("method", method, METHODS)
    opts = _options(method, options, times)
    flat = times.ravel()
    order = np.argsort(flat)[::-1]
    out = None
    start = 0
    while start < flat.size:
        t_w = flat[order[start]]
        stop = start + int(np.count_nonzero(flat[order[start:]] > t_w / opts["ratio"]))
        idx = order[start:stop]
        values = _window(F, vectorized, flat[idx], t_w * opts["scale"], method, opts)
        if out is None:
            out = np.empty((flat.size,) + values.shape[1:])
        out[idx] = values
        start = stop
    return out.reshape(times.shape + out.shape[1:])


def _options(method, options, times):
    unknown = set(options) - set(_DEFAULTS[method])
    if unknown:
        raise ValueError(
            f"unknown options {sorted(unknown)} for method={method!r}; valid: {sorted(_DEFAULTS[method])}"
        )
    opts = dict(_DEFAULTS[method], **options)
    tol = float(opts["tol"])
    if not 0.0 < tol < 1.0:
        raise ValueError(f"tol must lie in (0, 1), got {opts['tol']!r}")
    opts["tol"] = tol
    opts["scale"] = V.positive_float("scale", opts["scale"])
    if opts["scale"] < 1.0:
        raise ValueError(f"scale must be >= 1 (T = scale t), got {opts['scale']!r}")
    opts["ratio"] = V.positive_float("ratio", opts["ratio"])
    if opts["ratio"] <= 1.0:
        raise ValueError(f"ratio must be > 1, got {opts['ratio']!r}")
    if opts["omega_max"] is None:
        opts["omega_max"] = math.pi * max(times.size, MIN_TIMES) / times.max()
    opts["omega_max"] = V.positive_float("omega_max", opts["omega_max"])
    key = "M" if method == "dehoog" else "p"
    n = opts[key]
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"{key} must be a positive integer, got {n!r}")
    if method == "durbin":
        opts["acceleration"] = V.choice("acceleration", opts["acceleration"], ("epsilon", "none"))
    return opts


def _samples(F, vectorized, s):
    """``F(s)`` for ``s`` of shape (L,) as a complex array (L, ...), checked."""
    if vectorized:
        a = np.asarray(F(s), dtype=complex)
        if a.ndim == 0 or a.shape[0] != s.shape[0]:
            raise ValueError(
                f"F(s) for s of shape {s.shape} must return shape ({s.shape[0]}, ...), got {a.shape}; "
                "pass vectorized=False if F takes one s at a time"
            )
    else:
        a = np.array([np.asarray(F(sk), dtype=complex) for sk in s])
    V.check_finite("F(s)", a)
    return a


def _window(F, vectorized, t, T, method, opts):
    """Inversion at the times ``t`` (n_w,) of one window with half-period ``T``; (n_w, ...)."""
    K = math.ceil(opts["omega_max"] * T / math.pi)
    tail = 2 * opts["M"] + 1 if method == "dehoog" else 2 * opts["p"] + 1
    gamma = math.log(1.0 / opts["tol"]) / (2.0 * T)
    s = gamma + 1j * math.pi * np.arange(K + tail) / T
    a = _samples(F, vectorized, s)
    shape = a.shape[1:]
    a = a.reshape(a.shape[0], -1)
    a[0] *= 0.5
    size = np.max(np.abs(a), axis=0)
    live = size > NEGLIGIBLE * max(np.max(size), np.finfo(float).tiny)
    series = np.zeros((t.size, a.shape[1]), dtype=complex)
    if np.any(live):
        b = a[:, live]
        head = _head_sum(b[:K], t, T)
        zK = np.exp(1j * math.pi * K * t / T)[:, None]
        if method == "dehoog":
            rest = _continued_fraction(_qd_coefficients(b[K:], opts["M"]), t / T, opts["M"])
        else:
            rest = _durbin_tail(b[K:], t / T, opts["acceleration"])
        series[:, live] = head + zK * rest
    f = np.exp(gamma * t)[:, None] / T * series.real
    return f.reshape((t.size,) + shape)


def _head_sum(a, t, T):
    """``sum_{k<K} a_k exp(i pi k t / T)`` for ``a`` (K, e) at ``t`` (n,); (n, e) complex.

    In blocks of ``_BLOCK`` terms: ``z^(b + j) = z^b z^j`` with both factors from ``exp``, so
    that only ``n (_BLOCK + K / _BLOCK)`` exponentials are needed.
    """
    K = a.shape[0]
    out = np.zeros((t.size, a.shape[1]), dtype=complex)
    width = min(K, _BLOCK)
    if K == 0:
        return out
    phase = math.pi / T * t
    inner = np.exp(1j * np.outer(phase, np.arange(width)))            # (n, width)
    for b in range(0, K, width):
        block = a[b:b + width]
        out += np.exp(1j * b * phase)[:, None] * (inner[:, :block.shape[0]] @ block)
    return out


def _qd_coefficients(a, M):
    """Continued-fraction coefficients ``d_0 .. d_2M`` of ``sum_k a_k z^k`` (a: (2M+1, e)).

    The quotient-difference algorithm of de Hoog, Knight & Stokes (1982), vectorised over the
    entries.
    """
    e_cols = a.shape[1]
    q = a[1:] / a[:-1]                                 # q_1^(i), i = 0 .. 2M-1
    e = np.zeros((2 * M + 1, e_cols), dtype=complex)   # e_0^(i) = 0
    d = np.empty((2 * M + 1, e_cols), dtype=complex)
    d[0] = a[0]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for r in range(1, M + 1):
            n = 2 * (M - r) + 1
            e = q[1:n + 1] - q[:n] + e[1:n + 1]        # e_r^(i), i = 0 .. 2(M-r)
            d[2 * r - 1] = -q[0]
            d[2 * r] = -e[0]
            if r < M:
                q = q[1:n] * e[1:n] / e[:n - 1]        # q_{r+1}^(i), i = 0 .. 2(M-r)-1
    if not np.all(np.isfinite(d)):
        raise ValueError(
            "the quotient-difference table of de Hoog's method broke down (a zero divisor). "
            "F(s) tending to a nonzero constant (a delta function in f) does this: subtract the "
            "constant. Otherwise try method='durbin', or another M or omega_max"
        )
    return d


def _continued_fraction(d, x, M):
    """The continued fraction ``d_0 / (1 + d_1 z / (1 + ...))`` at ``z = exp(i pi x)``.

    Evaluated by the three-term recurrences of its convergents ``A_n / B_n``, with the
    accelerated remainder of de Hoog et al. (1982) in place of the last term.

    Parameters
    ----------
    d : (2M+1, e) coefficients ; x : (n,) values of ``t / T``

    Returns
    -------
    (n, e) complex
    """
    z = np.exp(1j * math.pi * x)[:, None]
    A_prev, A = np.zeros_like(z * d[0]), np.broadcast_to(d[0], (z.shape[0], d.shape[1])).copy()
    B_prev, B = np.ones_like(A), np.ones_like(A)
    for n in range(1, 2 * M):
        A_prev, A = A, A + d[n] * z * A_prev
        B_prev, B = B, B + d[n] * z * B_prev
    h = 0.5 * (1.0 + (d[2 * M - 1] - d[2 * M]) * z)
    R = -h * (1.0 - np.sqrt(1.0 + d[2 * M] * z / (h * h)))
    return (A + R * A_prev) / (B + R * B_prev)


def _durbin_tail(a, x, acceleration):
    """``sum_j a_j z^j`` (a: (2p+1, e)) at ``z = exp(i pi x)``, epsilon-accelerated; (n, e)."""
    j = np.arange(a.shape[0])
    powers = np.exp(1j * math.pi * np.outer(j, x))      # (2p+1, n)
    partial = np.cumsum(powers[:, :, None] * a[:, None, :], axis=0)
    if acceleration == "none":
        return partial[-1]
    return _wynn_epsilon(partial)


def _wynn_epsilon(S):
    """Limit of the partial sums ``S`` (n, ...) by Wynn's epsilon algorithm.

    The even columns ``eps_2k`` of the table are estimates of the limit. Once they have
    converged, the next columns divide by differences at round-off level and break down, so the
    estimate returned per entry is the latest one of the even column that changed least from
    the previous even column (the usual error estimate), among the finite ones.
    """
    best = S[-1].copy()
    last = S[-1]
    change = np.abs(S[-1] - S[-2]) if S.shape[0] > 1 else np.full(best.shape, np.inf)
    prev = np.zeros((S.shape[0] + 1,) + S.shape[1:], dtype=S.dtype)
    cur = S
    column = 0
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        while cur.shape[0] > 1:
            prev, cur = cur, prev[1:cur.shape[0]] + 1.0 / (cur[1:] - cur[:-1])
            column += 1
            if column % 2:
                continue
            estimate = cur[-1]
            delta = np.abs(estimate - last)
            better = np.isfinite(estimate) & (delta < change)
            best[better] = estimate[better]
            change[better] = delta[better]
            last = np.where(np.isfinite(estimate), estimate, last)
    return best
