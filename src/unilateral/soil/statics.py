"""Closed-form static (Boussinesq) surface flexibilities of an elastic half-space.

The vertical surface displacement of a homogeneous, isotropic, elastic half-space (shear modulus
``G``, Poisson's ratio ``nu``) under a vertical surface point load ``P`` is Boussinesq's (1885)

    w(r) = P (1 - nu) / (2 pi G r).

Averages of ``1/r`` over rectangles are obtained exactly from antiderivatives ``f_pq`` with
``d^p/dx^p d^q/dy^q f_pq = 1/r`` (``p, q`` in 0..2): a uniform load on a rectangle and a displacement
averaged over a rectangle (or taken at a point) reduce to signed sums of ``f_pq`` at corner offsets.
For ``p = q = 1`` this is the classical corner formula of Love (1929) / Steinbrenner (1934):
the corner displacement of a uniformly loaded ``B x L`` rectangle (pressure ``q``) is

    w = q (1 - nu) / (2 pi G) [B asinh(L/B) + L asinh(B/L)].

Valid for the linear elastic half-space (small strains), any ``0 <= nu < 1/2`` (and the limit 1/2).
"""

from __future__ import annotations

import numpy as np

__all__ = ["boussinesq", "rectangle_corner_displacement", "mean_inverse_distance",
           "static_flexibility"]


def boussinesq(r, G, nu):
    """Boussinesq surface vertical displacement per unit vertical point force.

    Parameters
    ----------
    r : array_like, m
        Distance(s) from the load, > 0.
    G : float, Pa (any consistent force/length^2)
        Shear modulus.
    nu : float
        Poisson's ratio, 0 <= nu <= 1/2.

    Returns
    -------
    w : ndarray, same shape as ``r``, m/N
        ``(1 - nu) / (2 pi G r)`` (Boussinesq 1885; e.g. Johnson, *Contact Mechanics*, 1985, eq. 3.22).
    """
    r = np.asarray(r, dtype=float)
    return (1.0 - nu) / (2.0 * np.pi * G * r)


def rectangle_corner_displacement(B, L, q, G, nu):
    """Corner displacement of a uniformly loaded flexible rectangle (Love 1929, Steinbrenner 1934).

    Parameters
    ----------
    B, L : float, m
        Sides of the rectangle.
    q : float, Pa
        Uniform pressure (total force ``q B L``).
    G, nu : float
        Shear modulus and Poisson's ratio of the half-space.

    Returns
    -------
    w : float, m
        ``q (1 - nu)/(2 pi G) [B asinh(L/B) + L asinh(B/L)]``, i.e. the classical
        ``q B (1 - nu^2)/E * I_s`` with Steinbrenner's influence factor
        ``I_s = (1/pi)[ln((1 + sqrt(1 + m^2))/m) m + ln(m + sqrt(1 + m^2))]``, ``m = L/B``.
    """
    return q * (1.0 - nu) / (2.0 * np.pi * G) * (B * np.arcsinh(L / B) + L * np.arcsinh(B / L))


# --- antiderivatives f_pq of 1/r (p-fold in x, q-fold in y), written for x, y >= 0 -------------

def _xasinh(a, b):
    """a * asinh(b / a) with the limit 0 at a = 0 (a, b >= 0)."""
    out = np.zeros(np.broadcast(a, b).shape)
    a, b = np.broadcast_arrays(a, b)
    nz = a > 0
    out[nz] = a[nz] * np.arcsinh(b[nz] / a[nz])
    return out


def _f(p, q, x, y):
    """Antiderivative of 1/r, even/odd extended: sgn(x)^p sgn(y)^q f_pq(|x|, |y|)."""
    if p < q:
        return _f(q, p, y, x)
    sx = np.sign(x) if p % 2 else 1.0
    sy = np.sign(y) if q % 2 else 1.0
    x = np.abs(x)
    y = np.abs(y)
    r = np.hypot(x, y)
    if (p, q) == (0, 0):
        val = 1.0 / r
    elif (p, q) == (1, 0):
        val = np.arcsinh(x / y)
    elif (p, q) == (1, 1):
        val = _xasinh(x, y) + _xasinh(y, x)
    elif (p, q) == (2, 0):
        val = x * np.arcsinh(x / y) - r
    elif (p, q) == (2, 1):
        val = 0.5 * x * _xasinh(x, y) + x * _xasinh(y, x) - 0.5 * y * r
    elif (p, q) == (2, 2):
        val = (0.5 * x * y * _xasinh(x, y) + 0.5 * x * y * _xasinh(y, x)
               - r ** 3 / 6.0)
    else:  # pragma: no cover
        raise ValueError((p, q))
    return sx * sy * val


def _axis_terms(d, a_recv, a_src):
    """Offsets, signs and order for one axis (see module docstring)."""
    if a_recv > 0 and a_src > 0:
        h1, h2 = 0.5 * (a_recv + a_src), 0.5 * (a_recv - a_src)
        return 2, [(d + h1, 1.0), (d - h1, 1.0), (d + h2, -1.0), (d - h2, -1.0)], a_recv * a_src
    a = a_recv + a_src
    if a > 0:
        return 1, [(d + 0.5 * a, 1.0), (d - 0.5 * a, -1.0)], a
    return 0, [(d, 1.0)], 1.0


_GX, _GW = np.polynomial.legendre.leggauss(4)


def mean_inverse_distance(dx, dy, recv_size, src_size):
    """Mean of ``1/|x - x'|`` with ``x`` over the receiver and ``x'`` over the source rectangle.

    Parameters
    ----------
    dx, dy : float, m
        Receiver centre minus source centre.
    recv_size, src_size : (2,) float, m
        Sides ``(a, b)`` along x and y; a zero side means a point (or line) in that direction.

    Returns
    -------
    float, 1/m
        Exact (closed form) for near pairs; for pairs farther apart than 6 times the largest side a
        4 x 4 x 4 x 4 Gauss rule is used (relative error < 1e-9) to avoid cancellation in the corner sums.
    """
    ar, br = recv_size
    as_, bs = src_size
    size = max(ar, br, as_, bs)
    dist = np.hypot(dx, dy)
    if size > 0 and dist > 6.0 * size:
        def nodes(a):
            return (0.5 * a * _GX, 0.5 * _GW) if a > 0 else (np.zeros(1), np.ones(1))
        xr, wxr = nodes(ar)
        yr, wyr = nodes(br)
        xs, wxs = nodes(as_)
        ys, wys = nodes(bs)
        X = dx + xr[:, None] - xs[None, :]
        Y = dy + yr[:, None] - ys[None, :]
        WX = wxr[:, None] * wxs[None, :]
        WY = wyr[:, None] * wys[None, :]
        R = np.hypot(X.ravel()[:, None], Y.ravel()[None, :])
        return float(np.sum(WX.ravel()[:, None] * WY.ravel()[None, :] / R))
    p, tx, nx = _axis_terms(dx, ar, as_)
    q, ty, ny = _axis_terms(dy, br, bs)
    total = 0.0
    for ux, sx in tx:
        for uy, sy in ty:
            total += sx * sy * float(_f(p, q, np.float64(ux), np.float64(uy)))
    return total / (nx * ny)


def static_flexibility(dx, dy, recv_sizes, src_sizes, G, nu):
    """Static vertical flexibility for many receiver/source pairs.

    Parameters
    ----------
    dx, dy : (n,) float, m
        Centre offsets (receiver minus source).
    recv_sizes, src_sizes : (n, 2) float, m
        Rectangle sides (zero = point).
    G, nu : float or complex
        Shear modulus (may be a complex correspondence-principle modulus) and Poisson's ratio.

    Returns
    -------
    (n,) float or complex, m/N
        ``(1 - nu)/(2 pi G) * mean(1/r)``: displacement averaged over the receiver per unit total
        vertical force uniformly distributed on the source.
    """
    out = np.array([mean_inverse_distance(x, y, rs, ss)
                    for x, y, rs, ss in zip(dx, dy, recv_sizes, src_sizes)])
    return (1.0 - nu) / (2.0 * np.pi * G) * out
