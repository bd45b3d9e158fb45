"""Lamb's problem, vertical step point load: closed-form surface vertical displacement.

Pekeris, C. L. (1955), "The seismic surface pulse", Proc. Natl. Acad. Sci. USA 41, 469-480, gave the
closed form for Poisson's ratio 1/4; Mooney (1974, BSSA 64, 473-491) and Kausel (2013, "Lamb's problem
at its simplest", Proc. R. Soc. A 469, 20120462) extended it to any ``nu`` in terms of the three roots
``x_1 < x_2 < x_3`` of the Rayleigh cubic ``16(1-eta) x^3 - 8(3-2 eta) x^2 + 8 x - 1 = 0``
(``x = (c_s/c)^2``, ``eta = (c_s/c_p)^2``; ``x_3 = (c_s/c_R)^2``).

With ``tau = c_s t / r`` and ``f = P (1-nu)/(2 pi G r)`` (Boussinesq), the vertical displacement
(positive in the direction of the load) is

* ``0`` for ``tau < sqrt(eta)`` (before the P wave),
* ``f/2 [1 - sum_{i=1,2} A_i / sqrt(tau^2 - x_i) - A_3 / sqrt(x_3 - tau^2)]`` for ``sqrt(eta) < tau < 1``,
* ``f [1 - A_3 / sqrt(x_3 - tau^2)]`` for ``1 < tau < sqrt(x_3)`` (the Rayleigh singularity at the end),
* ``f`` for ``tau > sqrt(x_3)``,

``A_i = (x_i - 1/2)^2 sqrt(|eta - x_i|) / prod_{j != i} (x_i - x_j)``. For ``nu > 0.2631`` the roots
``x_1, x_2`` are complex conjugates and the sum becomes ``2 Re(A_1/sqrt(tau^2 - x_1))``.

For ``nu = 1/4`` this is Pekeris' formula (``P/(32 pi G r)`` times)
``6 - sqrt3/sqrt(tau^2 - 1/4) - sqrt(3 sqrt3 + 5)/sqrt(3/4 + sqrt3/4 - tau^2)
+ sqrt(3 sqrt3 - 5)/sqrt(tau^2 - 3/4 + sqrt3/4)`` between the P and S arrivals and
``12 - 2 sqrt(3 sqrt3 + 5)/sqrt(3/4 + sqrt3/4 - tau^2)`` between the S and Rayleigh arrivals,
implemented separately in :func:`pekeris_quarter` as a check.
"""

from __future__ import annotations

import numpy as np

from .lamb import eta_of

__all__ = ["lamb_step_vertical", "pekeris_quarter", "arrival_times"]


def _roots(nu):
    eta = eta_of(nu)
    x = np.roots([16.0 * (1.0 - eta), -8.0 * (3.0 - 2.0 * eta), 8.0, -1.0]).astype(complex)
    x = x[np.argsort(x.real)]
    return eta, x


def arrival_times(nu):
    """Dimensionless arrival times ``tau = c_s t / r`` of the P, S and Rayleigh waves, shape (3,)."""
    eta, x = _roots(nu)
    return np.array([np.sqrt(eta), 1.0, np.sqrt(x[2].real)])


def lamb_step_vertical(tau, nu=0.25, P=1.0, G=1.0, r=1.0):
    """Surface vertical displacement under a vertical step point load ``P H(t)`` (Pekeris/Mooney/Kausel).

    Parameters
    ----------
    tau : array_like
        Dimensionless time ``c_s t / r`` (>= 0).
    nu : float
        Poisson's ratio, ``0 < nu < 1/2``.
    P, G, r : float
        Load (N), shear modulus (Pa) and distance (m).

    Returns
    -------
    w : ndarray, m (shape of ``tau``)
        Displacement in the direction of the load; infinite at the Rayleigh arrival (returned as nan
        there), equal to Boussinesq's ``P (1-nu)/(2 pi G r)`` after it.
    """
    tau = np.asarray(tau, dtype=float)
    eta, x = _roots(nu)
    f = P * (1.0 - nu) / (2.0 * np.pi * G * r)
    A = np.empty(3, dtype=complex)
    for i in range(3):
        others = [x[j] for j in range(3) if j != i]
        A[i] = (x[i] - 0.5) ** 2 * np.sqrt(eta - x[i] if i < 2 else x[i] - eta) / (
            (x[i] - others[0]) * (x[i] - others[1]))
    complex_pair = abs(x[0].imag) > 1e-12
    t2 = tau.astype(complex) ** 2
    out = np.full(tau.shape, np.nan)
    tp, ts, tr = np.sqrt(eta), 1.0, np.sqrt(x[2].real)
    before = tau < tp
    out[before] = 0.0
    mid = (tau > tp) & (tau < ts)
    if complex_pair:
        term = 2.0 * np.real(A[0] / np.sqrt(t2[mid] - x[0]))
    else:
        term = np.real(A[0] / np.sqrt(t2[mid] - x[0]) + A[1] / np.sqrt(t2[mid] - x[1]))
    out[mid] = 0.5 * f * (1.0 - term - A[2].real / np.sqrt(x[2].real - tau[mid] ** 2))
    late = (tau >= ts) & (tau < tr)
    out[late] = f * (1.0 - A[2].real / np.sqrt(x[2].real - tau[late] ** 2))
    out[tau > tr] = f
    return out


def pekeris_quarter(tau, P=1.0, G=1.0, r=1.0):
    """Pekeris' (1955) explicit closed form for ``nu = 1/4`` (see module docstring); same output as
    :func:`lamb_step_vertical` with ``nu = 1/4``."""
    tau = np.asarray(tau, dtype=float)
    r3 = np.sqrt(3.0)
    g2 = 0.75 + r3 / 4.0                       # (c_s/c_R)^2
    c = P / (32.0 * np.pi * G * r)
    out = np.full(tau.shape, np.nan)
    out[tau < 1.0 / r3] = 0.0
    m = (tau > 1.0 / r3) & (tau < 1.0)
    t2 = tau[m] ** 2
    out[m] = c * (6.0 - r3 / np.sqrt(t2 - 0.25) - np.sqrt(3 * r3 + 5) / np.sqrt(g2 - t2)
                  + np.sqrt(3 * r3 - 5) / np.sqrt(t2 - 0.75 + r3 / 4.0))
    m = (tau >= 1.0) & (tau < np.sqrt(g2))
    out[m] = c * (12.0 - 2.0 * np.sqrt(3 * r3 + 5) / np.sqrt(g2 - tau[m] ** 2))
    out[tau > np.sqrt(g2)] = 12.0 * c
    return out
