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

__all__ = ["boussinesq", "rectangle_corner_displacement", "mean_inverse_distance", "cerruti",
           "cerruti_averages",
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


# --- horizontal (Cerruti) and coupled static surface flexibilities -------------------------------
#
# Cerruti (1882) surface displacements per unit tangential point force P e_x at the origin (z down,
# x, y along the surface; e.g. Johnson, *Contact Mechanics*, 1985, Sec. 3.2; Kausel 2006, Sec. 15):
#
#     u_x = [(1 - nu)/r + nu x^2/r^3] / (2 pi G) = [1/r - nu d^2 r/dx^2] / (2 pi G)
#     u_y = nu x y / (2 pi G r^3)                 = -nu d^2 r/(dx dy) / (2 pi G)
#     u_z = (1 - 2 nu) x / (4 pi G r^2)           = (1 - 2 nu) d(ln r)/dx / (4 pi G)
#
# (u_z > 0, i.e. downward, ahead of the force; by reciprocity a downward force draws the surface
# inward, u_r = -(1 - 2 nu)/(4 pi G r), Boussinesq). Their averages over receiver x source rectangles
# are corner sums (see ``_axis_terms``) of antiderivatives h, F11, M with
#     d^2 h/dy^2 = r,   d^2 F11/(dx dy) = r,   d^3 M/(dx dy^2) = ln r,
# derived for this module (x, y >= 0, then extended by parity):
#     h   = r^3/6 + (x^2/2) (y asinh(y/x) - r)                                   (even, even)
#     F11 = x y r/3 + (y^3/6) asinh(x/y) + (x^3/6) asinh(y/x)                     (odd, odd)
#     M   = (x y^2/2 - x^3/6) ln r + (y^3/6) atan(x/y) + (x^2 y/2) atan(y/x)
#           + x^3/18 - 7 x y^2/6                                                   (odd, even)
# each continuous with the parity extension, so that the identities hold in the distributional sense.

def _h02(x, y):
    x, y = np.abs(x), np.abs(y)
    r = np.hypot(x, y)
    return r ** 3 / 6.0 + 0.5 * x * (y * _xasinh(x, y) - x * r)


def _f11(x, y):
    sx, sy = np.sign(x), np.sign(y)
    x, y = np.abs(x), np.abs(y)
    r = np.hypot(x, y)
    val = x * y * r / 3.0 + (y * y * _xasinh(y, x) + x * x * _xasinh(x, y)) / 6.0
    return sx * sy * val


def _xatan(a, b):
    """a^3 atan(b/a) -> 0 at a = 0 (a, b >= 0)."""
    a, b = np.broadcast_arrays(np.asarray(a, float), np.asarray(b, float))
    out = np.zeros(a.shape)
    nz = a > 0
    out[nz] = a[nz] ** 3 * np.arctan(b[nz] / a[nz])
    return out


def _m12(x, y):
    sx = np.sign(x)
    x, y = np.abs(x), np.abs(y)
    r = np.hypot(x, y)
    with np.errstate(divide="ignore"):
        lnr = np.where(r > 0, np.log(np.where(r > 0, r, 1.0)), 0.0)
    # (x^2 y/2) atan(y/x) = (y/(2x)) x^3 atan(y/x): written as x^2 y atan(y/x) safely
    t2 = np.where(x > 0, 0.5 * x * x * y * np.arctan2(y, np.where(x > 0, x, 1.0)), 0.0)
    val = ((0.5 * x * y * y - x ** 3 / 6.0) * lnr + _xatan(y, x) / 6.0 + t2
           + x ** 3 / 18.0 - 7.0 * x * y * y / 6.0)
    return sx * val


def _corner_sum(fun, dx, dy, recv_size, src_size):
    """Average over receiver x source rectangles of ``d^2/dx^2 d^2/dy^2 fun`` (both sides > 0)."""
    p, tx, nx = _axis_terms(dx, recv_size[0], src_size[0])
    q, ty, ny = _axis_terms(dy, recv_size[1], src_size[1])
    if p != 2 or q != 2:
        raise ValueError("closed-form horizontal statics need patches with positive sides")
    total = 0.0
    for ux, sx in tx:
        for uy, sy in ty:
            total += sx * sy * float(fun(np.float64(ux), np.float64(uy)))
    return total / (nx * ny)


_CERRUTI_KERNELS = (
    lambda X, Y: 1.0 / np.hypot(X, Y),                 # 1/r
    lambda X, Y: Y * Y / np.hypot(X, Y) ** 3,          # d^2 r/dx^2
    lambda X, Y: X * X / np.hypot(X, Y) ** 3,          # d^2 r/dy^2
    lambda X, Y: -X * Y / np.hypot(X, Y) ** 3,         # d^2 r/dxdy
    lambda X, Y: X / (X * X + Y * Y),                  # d ln r/dx
    lambda X, Y: Y / (X * X + Y * Y),                  # d ln r/dy
)


def cerruti_averages(dx, dy, recv_size, src_size):
    """Averages over receiver x source rectangles of the kernels of the static surface Green's tensor.

    Parameters
    ----------
    dx, dy : float, m
        Receiver centre minus source centre (signed).
    recv_size, src_size : (2,) float, m
        Rectangle sides ``(a, b)``; all > 0 for near pairs (closed form), any >= 0 for pairs farther
        apart than 6 times the largest side (4-point Gauss rule per direction, relative error < 1e-9).

    Returns
    -------
    (6,) float ndarray
        Means of ``1/r`` (1/m), ``d^2 r/dx^2 = y^2/r^3``, ``d^2 r/dy^2 = x^2/r^3``,
        ``d^2 r/dxdy = -x y/r^3`` (1/m), ``d ln r/dx = x/r^2``, ``d ln r/dy = y/r^2`` (1/m), with
        ``(x, y)`` the receiver point minus the source point. See the comment block above for the
        Cerruti (1882) kernels and the antiderivatives used.
    """
    ar, br = recv_size
    as_, bs = src_size
    size = max(ar, br, as_, bs)
    if size > 0 and np.hypot(dx, dy) > 6.0 * size:
        def nodes(a):
            return (0.5 * a * _GX, 0.5 * _GW) if a > 0 else (np.zeros(1), np.ones(1))
        xr, wxr = nodes(ar)
        yr, wyr = nodes(br)
        xs, wxs = nodes(as_)
        ys, wys = nodes(bs)
        X = (dx + xr[:, None] - xs[None, :]).ravel()[:, None]
        Y = (dy + yr[:, None] - ys[None, :]).ravel()[None, :]
        W = (wxr[:, None] * wxs[None, :]).ravel()[:, None] * (wyr[:, None] * wys[None, :]).ravel()[None, :]
        return np.array([float(np.sum(W * f(X, Y))) for f in _CERRUTI_KERNELS])
    inv_r = mean_inverse_distance(dx, dy, recv_size, src_size)
    rxx = _corner_sum(_h02, dx, dy, recv_size, src_size)
    ryy = _corner_sum(lambda x, y: _h02(y, x), dx, dy, recv_size, src_size)
    rxy = _corner_sum(_f11, dx, dy, recv_size, src_size)
    lx = _corner_sum(_m12, dx, dy, recv_size, src_size)
    ly = _corner_sum(lambda x, y: _m12(y, x), dx, dy, recv_size, src_size)
    return np.array([inv_r, rxx, ryy, rxy, lx, ly])


def cerruti(x, y, G, nu):
    """Static surface Green's tensor of the half-space (Boussinesq 1885, Cerruti 1882).

    Parameters
    ----------
    x, y : array_like, m
        Receiver minus source position on the surface (not both zero).
    G, nu : float
        Shear modulus and Poisson's ratio.

    Returns
    -------
    (3, 3, ...) ndarray, m/N
        ``T[i, j]`` = surface displacement component ``i`` per unit point force component ``j``
        (order x, y, z; z positive down, into the half-space). In particular
        ``T[x, x] = [(1-nu)/r + nu x^2/r^3]/(2 pi G)``, ``T[x, y] = nu x y/(2 pi G r^3)``,
        ``T[z, x] = +(1 - 2 nu) x/(4 pi G r^2)`` (a horizontal force +x pushes the surface *down* ahead
        of it, ``x > 0``, and up behind it), ``T[x, z] = -T[z, x]`` (a downward force draws the surface
        inward), ``T[z, z] = (1-nu)/(2 pi G r)``. Johnson, *Contact Mechanics* (1985), Sec. 3.2.
    """
    x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
    r = np.hypot(x, y)
    c = 1.0 / (2.0 * np.pi * G)
    T = np.empty((3, 3) + x.shape)
    T[0, 0] = c * ((1 - nu) / r + nu * x * x / r ** 3)
    T[1, 1] = c * ((1 - nu) / r + nu * y * y / r ** 3)
    T[0, 1] = T[1, 0] = c * nu * x * y / r ** 3
    T[2, 0] = (1 - 2 * nu) * x / (4 * np.pi * G * r * r)
    T[2, 1] = (1 - 2 * nu) * y / (4 * np.pi * G * r * r)
    T[0, 2], T[1, 2] = -T[2, 0], -T[2, 1]
    T[2, 2] = c * (1 - nu) / r
    return T
