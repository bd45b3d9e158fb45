"""Lamb's problem, horizontal step point load: closed-form surface displacements (Chao; Kausel).

Chao, C. C. (1960), "Dynamical response of an elastic half-space to tangential surface loadings",
J. Appl. Mech. 27, 559-567, solved the problem for Poisson's ratio 1/4; Kausel, E. (2013), "Lamb's
problem at its simplest", Proc. R. Soc. A 469, 20120462, gave explicit formulas for any ``nu``, in
terms of the three roots ``x_1, x_2, x_3`` of the Rayleigh cubic
``16(1-eta) x^3 - 8(3-2 eta) x^2 + 8 x - 1 = 0`` (``x = (c_s/c)^2``, ``eta = (c_s/c_p)^2``,
``x_3 = (c_s/c_R)^2 > 1``; ``x_1 <= x_2 < eta`` real for ``nu < 0.2631``, complex conjugates above),
the same roots as :mod:`.pekeris`. The formulas below were taken from the author's companion program
``Lamb_3D.m`` (E. Kausel, version 3.3, 6 Sept. 2012, "Generalization of all of the above to arbitrary
Poisson's ratio: Kausel, Lamb's problem at its simplest"), whose vertical-load formula is the one of
:func:`.pekeris.lamb_step_vertical`; the paper's own text could not be read here. They are checked in
``tests/test_soil_chao.py`` against Cerruti's static limits, their own arrival-time behaviour and the
package's wavenumber-integral half-space (:class:`.halfspace.HalfSpace`) by convolution quadrature.

Setting: a horizontal force ``P H(t)`` along ``+x`` at the origin of the surface of a half-space with
shear modulus ``G``; receiver on the surface at distance ``r`` and azimuth ``theta`` from ``+x``;
``tau = c_s t / r``; arrivals ``tau_P = sqrt(eta)``, ``tau_S = 1``, ``tau_R = sqrt(x_3)``. With
``f = P/(2 pi G r)``, ``g = (1 - nu) f`` and

    C_i = (1 - x_i) sqrt(|eta - x_i|) / prod_{j != i} (x_i - x_j),

the displacements are ``u_r = U_r(tau) cos(theta)`` (radial), ``u_theta = -U_t(tau) sin(theta)``
(tangential), i.e. ``U_r`` is ``u_x`` on the line of the force and ``U_t`` is ``u_x`` on the line
across it, with

* ``U_r = U_t = 0`` for ``tau < tau_P``;
* ``tau_P < tau < 1``:
  ``U_r = g/2 tau^2 [C_1/sqrt(tau^2 - x_1) + C_2/sqrt(tau^2 - x_2) + C_3/sqrt(x_3 - tau^2)]``,
  ``U_t = g/2 [1 - C_1 sqrt(tau^2 - x_1) - C_2 sqrt(tau^2 - x_2) + C_3 sqrt(x_3 - tau^2)]``;
* ``1 < tau < tau_R``: ``U_r = f + g C_3 tau^2/sqrt(x_3 - tau^2)`` (the Rayleigh singularity;
  ``C_3 < 0``), ``U_t = g [1 + C_3 sqrt(x_3 - tau^2)]`` (no Rayleigh singularity: no SH surface
  wave; ``U_t`` jumps at the S arrival instead);
* ``tau > tau_R``: ``U_r = f``, ``U_t = g``: Cerruti's static ``u_x`` on the two lines,
  ``P/(2 pi G r)`` and ``P (1-nu)/(2 pi G r)``.

For complex ``x_1 = conj(x_2)`` the pair of terms is ``2 Re(C_1 ...)``.

Vertical displacement under the horizontal load (``z`` positive down, the package's convention):
``u_z = W(tau) cos(theta)``, down ahead of the force; by reciprocity ``W`` is minus the radial
displacement under a downward vertical step load (Kausel's ``U_zx = -U_rz`` with ``z`` up). With
``b = 1 - eta``, ``n_i = b/(eta - x_i)``, ``D_i = (1 - 2 x_i)(1 - x_i)/prod_{j != i}(x_i - x_j)``,
``Pi(n, m) = int_0^{pi/2} d phi / ((1 + n sin^2 phi) sqrt(1 - m sin^2 phi))`` (note the sign of ``n``;
``K(m) = Pi(0, m)``) and ``h = P/(8 pi^2 G r b^{3/2})``:

* ``W = 0`` for ``tau < tau_P``;
* ``tau_P < tau < 1``, ``m = (tau^2 - eta)/b``: ``W = h tau [2 K(m) - sum_i D_i Pi(n_i m, m)]``;
* ``tau > 1``, ``m = b/(tau^2 - eta)``: ``W = h tau sqrt(m) [2 K(m) - sum_i D_i Pi(n_i, m)]``
  (continuous at ``tau = 1``, smooth through ``tau_R``),
* plus, for ``tau > tau_R``, the Rayleigh pole term ``P C_R tau / (4 pi G r sqrt(tau^2 - x_3))``,
  ``C_R = (2 x_3 - 1)^3 / (1 - 4 x_3 + 8 b x_3^3)`` (the singularity is on the late side here).

Caution, found while checking: ``Lamb_3D.m`` gives for ``tau > tau_R`` the pole term *alone*. That
tends to ``C_R P/(4 pi G r)``, which is Cerruti's ``(1 - 2 nu) P/(4 pi G r)`` only for ``nu = 1/4``
(``C_R/(1 - 2 nu) = 0.90, 1.19, 2.79`` at ``nu = 0.1, 1/3, 0.45``). Keeping the elliptic term of
``1 < tau < tau_R`` beyond ``tau_R`` as well (it is analytic there) restores Cerruti's limit for every
``nu`` (to 1e-9 at ``tau = 1e6``) and agrees with the wavenumber integral after the Rayleigh arrival
(at ``nu = 1/3`` to 8e-4 of ``P/(2 pi G r)``, against 3e-2 for the pole term alone; see the tests).
This module uses that form; it is this module's reading, not a formula seen in print.

The elliptic integrals are evaluated by Carlson's symmetric forms (``scipy.special.elliprf``,
``elliprj``): ``Pi(n, m) = R_F(0, 1-m, 1) - n/3 R_J(0, 1-m, 1, 1+n)``, also for complex ``n``.

For ``nu = 1/4`` (``eta = 1/3``, ``x = 1/4, (3 -+ sqrt3)/4``) the constants are surds,
``C_1 = 2 sqrt3``, ``C_2 = -sqrt(10 + 6 sqrt3)/3``, ``C_3 = -sqrt(6 sqrt3 - 10)/3`` (reduced here from the
general form, not transcribed from Chao's paper, which could not be consulted):
:func:`chao_quarter` evaluates them as a check of the root bookkeeping.

Degenerate cases: ``nu = 0`` (``x_2 = eta``) and the double root at ``nu ~ 0.2631`` are not treated.
"""

from __future__ import annotations

import numpy as np
from scipy.special import elliprf, elliprj

from .lamb import eta_of

__all__ = ["lamb_step_horizontal", "lamb_step_coupled", "chao_quarter", "cerruti_surface"]


def _roots(nu):
    if not 0.0 < nu < 0.5:
        raise ValueError(f"nu must satisfy 0 < nu < 1/2, got {nu!r}")
    eta = eta_of(nu)
    x = np.roots([16.0 * (1.0 - eta), -8.0 * (3.0 - 2.0 * eta), 8.0, -1.0]).astype(complex)
    x = x[np.argsort(x.real)]
    if abs(x[0].imag) < 1e-12:
        x = x.real.astype(complex)
        if abs(x[1] - x[0]) < 1e-6:
            raise ValueError(f"nu = {nu!r} is (too close to) the double root of the Rayleigh cubic")
    return eta, x


def _pairsum(values, complex_pair):
    """``v_1 + v_2`` of the two 'false' roots: ``2 Re v_1`` when they are complex conjugates."""
    return 2.0 * np.real(values[0]) if complex_pair else np.real(values[0] + values[1])


def _prod_others(x, i):
    others = [x[j] for j in range(3) if j != i]
    return (x[i] - others[0]) * (x[i] - others[1])


def lamb_step_horizontal(tau, nu=0.25, P=1.0, G=1.0, r=1.0):
    """Surface horizontal displacements under a horizontal step point load ``P H(t)`` (Chao/Kausel).

    Parameters
    ----------
    tau : array_like
        Dimensionless time ``c_s t / r`` (>= 0).
    nu : float
        Poisson's ratio, ``0 < nu < 1/2`` (not the double root ``~0.2631``).
    P, G, r : float
        Load (N), shear modulus (Pa) and distance (m).

    Returns
    -------
    U_r, U_t : ndarray, m (shape of ``tau``)
        ``u_x`` at a receiver on the line of the force (``U_r``; radial ``u_r = U_r cos theta``) and on
        the line across it (``U_t``; tangential ``u_theta = -U_t sin theta``). ``U_r`` is infinite at
        the Rayleigh arrival (nan there); ``U_t`` jumps at the S arrival (its value at ``tau = 1``
        exactly is the late one). Both end at Cerruti's static values.
    """
    tau = np.asarray(tau, dtype=float)
    eta, x = _roots(nu)
    f = P / (2.0 * np.pi * G * r)
    g = (1.0 - nu) * f
    C = np.array([(1.0 - x[i]) * np.sqrt(eta - x[i] if i < 2 else x[i] - eta) / _prod_others(x, i)
                  for i in range(3)])
    C3 = C[2].real
    pair = abs(x[0].imag) > 0
    tp, tr = np.sqrt(eta), np.sqrt(x[2].real)
    Ur = np.full(tau.shape, np.nan)
    Ut = np.full(tau.shape, np.nan)
    before = tau <= tp
    Ur[before] = Ut[before] = 0.0
    m = (tau > tp) & (tau < 1.0)
    t2 = tau[m] ** 2
    sq = [np.sqrt(t2.astype(complex) - x[0]), np.sqrt(t2.astype(complex) - x[1])]
    s3 = np.sqrt(x[2].real - t2)
    Ur[m] = 0.5 * g * t2 * (_pairsum([C[0] / sq[0], C[1] / sq[1]], pair) + C3 / s3)
    Ut[m] = 0.5 * g * (1.0 - _pairsum([C[0] * sq[0], C[1] * sq[1]], pair) + C3 * s3)
    m = (tau >= 1.0) & (tau < tr)
    t2 = tau[m] ** 2
    s3 = np.sqrt(x[2].real - t2)
    Ur[m] = f + g * C3 * t2 / s3
    Ut[m] = g * (1.0 + C3 * s3)
    late = tau > tr
    Ur[late] = f
    Ut[late] = g
    Ut[tau == tr] = g
    return Ur, Ut


def _ellip_pi(n, m):
    """``int_0^{pi/2} dphi / ((1 + n sin^2) sqrt(1 - m sin^2))`` for ``0 <= m < 1``, complex ``n``
    with ``1 + n`` off the closed negative real axis (Carlson)."""
    m = np.asarray(m, dtype=float)
    n = np.asarray(n, dtype=complex)
    y = (1.0 - m).astype(complex)
    return elliprf(0.0, y, 1.0) - n / 3.0 * elliprj(0.0, y, 1.0, 1.0 + n)


def lamb_step_coupled(tau, nu=0.25, P=1.0, G=1.0, r=1.0):
    """Surface vertical displacement under a horizontal step point load ``P H(t)`` (Kausel 2013).

    Parameters as :func:`lamb_step_horizontal`.

    Returns
    -------
    W : ndarray, m (shape of ``tau``)
        Downward displacement at a receiver on the line of the force, ahead of it (``u_z = W cos
        theta``); by reciprocity also minus the radial displacement under a downward vertical step
        load. Continuous at the S arrival (nan at ``tau = 1`` exactly), infinite just after the
        Rayleigh arrival (nan at ``tau_R``); tends to Cerruti's ``(1 - 2 nu) P/(4 pi G r)`` as
        ``tau -> oo`` (see the caution in the module docstring about the late-time form).
    """
    tau = np.asarray(tau, dtype=float)
    eta, x = _roots(nu)
    b = 1.0 - eta
    pair = abs(x[0].imag) > 0
    n = b / (eta - x)
    D = np.array([(1.0 - 2.0 * x[i]) * (1.0 - x[i]) / _prod_others(x, i) for i in range(3)])
    D[2] = D[2].real
    h = P / (8.0 * np.pi ** 2 * G * r * b ** 1.5)
    tp, tr = np.sqrt(eta), np.sqrt(x[2].real)
    W = np.full(tau.shape, np.nan)
    W[tau <= tp] = 0.0
    sel = (tau > tp) & (tau < 1.0)
    mm = (tau[sel] ** 2 - eta) / b
    terms = [D[i] * _ellip_pi(n[i] * mm, mm) for i in range(3)]
    W[sel] = h * tau[sel] * (2.0 * _ellip_pi(0.0, mm).real - _pairsum(terms[:2], pair) - terms[2].real)
    sel = tau > 1.0
    mm = b / (tau[sel] ** 2 - eta)
    terms = [D[i] * _ellip_pi(n[i] * np.ones_like(mm), mm) for i in range(3)]
    W[sel] = h * tau[sel] * np.sqrt(mm) * (2.0 * _ellip_pi(0.0, mm).real - _pairsum(terms[:2], pair)
                                           - terms[2].real)
    x3 = x[2].real
    CR = (2.0 * x3 - 1.0) ** 3 / (1.0 - 4.0 * x3 + 8.0 * b * x3 ** 3)
    sel = tau > tr
    W[sel] += P * CR * tau[sel] / (4.0 * np.pi * G * r * np.sqrt(tau[sel] ** 2 - x3))
    W[tau == tr] = np.nan
    return W


def chao_quarter(tau, P=1.0, G=1.0, r=1.0):
    """``U_r, U_t`` of :func:`lamb_step_horizontal` for ``nu = 1/4`` with the constants in surds (see the
    module docstring); a check of the general formula's root bookkeeping, not an independent source."""
    tau = np.asarray(tau, dtype=float)
    r3 = np.sqrt(3.0)
    x1, x2, x3 = 0.25, (3.0 - r3) / 4.0, (3.0 + r3) / 4.0
    c1, c2, c3 = 2.0 * r3, -np.sqrt(10.0 + 6.0 * r3) / 3.0, -np.sqrt(6.0 * r3 - 10.0) / 3.0
    f = P / (2.0 * np.pi * G * r)
    g = 0.75 * f
    Ur = np.full(tau.shape, np.nan)
    Ut = np.full(tau.shape, np.nan)
    Ur[tau <= 1.0 / r3] = Ut[tau <= 1.0 / r3] = 0.0
    m = (tau > 1.0 / r3) & (tau < 1.0)
    t2 = tau[m] ** 2
    a, b, c = np.sqrt(t2 - x1), np.sqrt(t2 - x2), np.sqrt(x3 - t2)
    Ur[m] = 0.5 * g * t2 * (c1 / a + c2 / b + c3 / c)
    Ut[m] = 0.5 * g * (1.0 - c1 * a - c2 * b + c3 * c)
    m = (tau >= 1.0) & (tau < np.sqrt(x3))
    t2 = tau[m] ** 2
    Ur[m] = f + g * c3 * t2 / np.sqrt(x3 - t2)
    Ut[m] = g * (1.0 + c3 * np.sqrt(x3 - t2))
    m = tau >= np.sqrt(x3)
    Ur[m & (tau > np.sqrt(x3))] = f
    Ut[m] = g
    return Ur, Ut


def cerruti_surface(x, y, nu, P=1.0, G=1.0):
    """Cerruti's (1882) static surface displacements ``(u_x, u_y, u_z)`` (``z`` down) at ``(x, y)`` per
    horizontal point force ``P`` along ``+x`` at the origin:
    ``u_x = P[(1-nu)/r + nu x^2/r^3]/(2 pi G)``, ``u_y = P nu x y/(2 pi G r^3)``,
    ``u_z = P (1-2nu) x/(4 pi G r^2)`` (down ahead of the force; as in :mod:`.statics`)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    r = np.hypot(x, y)
    c = P / (2.0 * np.pi * G)
    return (c * ((1.0 - nu) / r + nu * x * x / r ** 3), c * nu * x * y / r ** 3,
            0.5 * c * (1.0 - 2.0 * nu) * x / r ** 2)
