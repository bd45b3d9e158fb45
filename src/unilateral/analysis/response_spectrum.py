"""Response spectra of ground-motion records and the first period of a structure.

:func:`response_spectrum` computes the pseudo-acceleration spectrum ``Sa(T, zeta) = w^2 max|u|``
of a linear oscillator ``u'' + 2 zeta w u' + w^2 u = -a_g(t)`` starting at rest. The record is
taken as piecewise linear between its samples (as :class:`~unilateral.loads.GroundMotion` and the
solver interpolate it), and the oscillator is stepped by the recurrence of Nigam & Jennings (1969)
that is *exact* for such an excitation: over a step ``dt``,

    [u, v]_{k+1} = A [u, v]_k + B0 a_k + B1 (a_{k+1} - a_k) / dt,

with ``A, B0, B1`` taken from the matrix exponential of the oscillator augmented by the linear
excitation (no formula transcribed by hand, no time-step restriction).

:func:`first_period` is the first natural period of a :class:`unilateral.Model` with every
constraint bilateral (``K`` holds the unilateral springs as if bonded): the generalised
eigenproblem ``K x = w^2 M x``, solved as ``M x = mu K x`` (``K`` is positive definite, ``M`` may be
singular: massless DOFs give ``mu = 0``).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp


def oscillator_recurrence(period: float, zeta: float, dt: float) -> np.ndarray:
    """The exact step of the oscillator under a piecewise-linear ground acceleration.

    Returns
    -------
    (2, 4) ndarray
        Rows ``u, v`` at ``t + dt`` as combinations of ``[u, v, a_k, (a_{k+1} - a_k)/dt]`` at ``t``.
    """
    w = 2 * math.pi / period
    F = np.array([[0.0, 1.0, 0.0, 0.0],
                  [-w * w, -2 * zeta * w, -1.0, 0.0],
                  [0.0, 0.0, 0.0, 1.0],
                  [0.0, 0.0, 0.0, 0.0]])
    return sla.expm(F * dt)[:2]


def response_spectrum(record, periods, zeta: float = 0.05) -> np.ndarray:
    """Pseudo-spectral accelerations ``Sa(T) = (2 pi / T)^2 max |u|`` of ``record``.

    Parameters
    ----------
    record : GroundMotion
        Accelerations in m/s^2 (read with :func:`unilateral.loads.read_record`).
    periods : float or array_like
        Periods ``T > 0``, s.
    zeta : float
        Damping ratio (default 5 %).

    Returns
    -------
    float or ndarray
        ``Sa`` in m/s^2, the shape of ``periods``; the peak is taken over the record's duration.
    """
    scalar = np.ndim(periods) == 0
    T = np.atleast_1d(np.asarray(periods, dtype=float))
    if not np.all(np.isfinite(T) & (T > 0)):
        raise ValueError(f"periods must be finite and > 0, got {periods!r}")
    if not 0 <= zeta < 1:
        raise ValueError(f"zeta must be in [0, 1), got {zeta!r}")
    a = np.asarray(record.acceleration, dtype=float)
    dt = float(record.dt)
    samples = a[:-1].tolist()
    slopes = (np.diff(a) / dt).tolist()
    peak = np.array([_peak_displacement(oscillator_recurrence(p, zeta, dt), samples, slopes) for p in T])
    Sa = (2 * np.pi / T) ** 2 * peak
    return float(Sa[0]) if scalar else Sa.reshape(np.shape(periods))


def _peak_displacement(step: np.ndarray, samples: list, slopes: list) -> float:
    """``max |u|`` over the samples, stepping the recurrence ``step`` (2, 4) in plain floats."""
    (a11, a12, b1, c1), (a21, a22, b2, c2) = step.tolist()
    u = v = peak = 0.0
    for ak, sk in zip(samples, slopes):
        u, v = a11 * u + a12 * v + b1 * ak + c1 * sk, a21 * u + a22 * v + b2 * ak + c2 * sk
        if abs(u) > peak:
            peak = abs(u)
    return peak


def natural_periods(model, count: int = 1) -> np.ndarray:
    """The ``count`` longest natural periods of ``model`` with every constraint bilateral.

    Parameters
    ----------
    model : unilateral.Model
        ``M`` (may be singular) and ``K`` (positive definite), dense or sparse.
    count : int
        How many periods.

    Returns
    -------
    (count,) ndarray
        Periods in the model's time unit, longest first.
    """
    K, M = model.K, model.M
    n = K.shape[0]
    count = min(int(count), n)
    if n > 1500 and sp.issparse(K):
        from scipy.sparse.linalg import eigsh

        mu = eigsh(sp.csc_matrix(M), k=count, M=sp.csc_matrix(K), which="LA", return_eigenvectors=False)
    else:
        Kd = K.toarray() if sp.issparse(K) else np.asarray(K, dtype=float)
        Md = M.toarray() if sp.issparse(M) else np.asarray(M, dtype=float)
        mu = sla.eigh(Md, Kd, eigvals_only=True, subset_by_index=[n - count, n - 1])
    mu = np.sort(np.asarray(mu))[::-1]
    if not np.all(mu > 0):
        raise ValueError("the model has fewer modes with mass than asked for (M is zero on them)")
    return 2 * np.pi * np.sqrt(mu)


def first_period(model) -> float:
    """First natural period ``T1`` of ``model`` with every constraint bilateral (model time unit)."""
    return float(natural_periods(model, 1)[0])
