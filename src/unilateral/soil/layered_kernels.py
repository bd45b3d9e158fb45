"""The compiled kernels of :class:`~unilateral.soil.layered.Layered`: its surface kernels
``zz``, ``rr``, ``c`` (P-SV) and ``tt`` (SH) evaluated by one loop over ``(s, k)`` with scalars only.

Plain functions here, compiled by :func:`compiled` on first use (numba is imported then, as the
rest of the package does), with numba's disk cache. They evaluate, one ``(s, k)`` at a time and
with scalars, the formulas of the numpy reference path (:meth:`Layered._down_basis`,
:meth:`Layered._layer_stiffness`, :meth:`Layered._halfspace_stiffness`, :meth:`Layered._sh_layer`,
:meth:`Layered._surface_stiffness`, :meth:`Layered._kernels_reference`; the layer's 4 x 4 solve
replaced by two 2 x 2 ones, see :func:`_layer_point`), so that no (ns, nk, 4, 4) temporary is
ever formed.
"""

from __future__ import annotations

import numpy as np


def _basis_point(k, S, G, eta, v):
    """Down-going basis of :meth:`Layered._down_basis` at one ``(k, S)``.

    Parameters
    ----------
    k, S, G : complex
        Wavenumber, ``S = rho s^2/G(s)`` and ``G(s)`` of the material.
    eta : float
        ``G/(lambda + 2G)``.
    v : (3, 4) complex ndarray
        Output: rows ``vP``, ``w``, ``vS`` (entries ``U, W, X, Z``).

    Returns
    -------
    al, be : complex
        ``alpha = sqrt(k^2 + eta S)``, ``beta = sqrt(k^2 + S)``.
    """
    kk = k * k
    al = np.sqrt(kk + eta * S)
    be = np.sqrt(kk + S)
    c = 1.0 - eta
    ab = al + be
    ka = al + k
    kb = k + be
    q = 2.0 * kk + S
    n = 1.0 / kb                      # reciprocals: complex divisions dominate the cost
    na = 1.0 / ka
    rc = 1.0 / c
    v[0, 0] = k
    v[0, 1] = al
    v[0, 2] = -2.0 * G * k * al
    v[0, 3] = -G * q
    v[1, 0] = ab * n * rc
    v[1, 1] = -eta * ab * na * rc
    v[1, 2] = -G * ab * (1.0 + eta * eta * S * (na * na) * rc)
    v[1, 3] = G * S * ab * (n * n) * rc
    v[2, 0] = be * n
    v[2, 1] = k * n
    v[2, 2] = -G * q * n
    v[2, 3] = -2.0 * G * k * be * n
    return al, be


def _right_divide(t, d):
    """``T D^-1`` of 2 x 2 matrices (tuples of their entries row by row) by the closed-form inverse
    of ``D``."""
    t00, t01, t10, t11 = t
    d00, d01, d10, d11 = d
    r = 1.0 / (d00 * d11 - d01 * d10)
    return ((t00 * d11 - t01 * d10) * r, (t01 * d00 - t00 * d01) * r,
            (t10 * d11 - t11 * d10) * r, (t11 * d00 - t10 * d01) * r)


def _halfspace_point(k, S, G, eta, v):
    """Surface stiffness ``(K00, K01, K10, K11)`` of a half-space at one ``(k, S)``.

    The 2 x 2 of :meth:`Layered._halfspace_stiffness`, ``K = T D^-1`` with ``D``, ``T`` the
    displacement and (negated) traction rows of the down-going basis.
    """
    _basis_point(k, S, G, eta, v)
    return _right_divide((-v[1, 2], -v[2, 2], -v[1, 3], -v[2, 3]), (v[1, 0], v[2, 0], v[1, 1], v[2, 1]))


def _layer_point(k, S, G, eta, h, v):
    """Exact P-SV layer stiffness of :meth:`Layered._layer_stiffness` at one ``(k, S)``.

    The 4 x 4 ``K = T D^-1`` of the reference has, with ``J = diag(1, -1)`` (the mirror image about
    the mid-plane), the blocks ``D = [[P, J Q], [Q, J P]]`` and ``T = [[-P', J Q'], [Q', -J P']]``
    (``P``, ``P'``: displacement and traction rows of the down-going solutions at their origin;
    ``Q``, ``Q'``: at the other face). Combining the down- and up-going columns into their sum and
    difference (symmetric and antisymmetric motions) splits it into two 2 x 2 problems:

        K = 1/2 [[K+ + K-, (K+ - K-) J], [J (K+ - K-), J (K+ + K-) J]],
        K+- = (-P' +- J Q') (P +- J Q)^-1,

    the same matrix, without a 4 x 4 elimination. Returns the entries of ``K+`` then ``K-``, row by
    row; ``v`` (3, 4) is a work array.
    """
    al, be = _basis_point(k, S, G, eta, v)
    x = 0.5 * (al - be) * h
    Eh = np.exp(-be * h)
    x2 = x.real * x.real + x.imag * x.imag           # |x|^2 (no hypot)
    if x2 > 0.25:
        Dh = (np.exp(-al * h) - Eh) / (al - be)
    else:
        if x2 < 1e-8:
            shc = 1.0 + x * x / 6.0
        else:
            shc = np.sinh(x) / x
        Dh = -h * np.exp(-0.5 * (al + be) * h) * shc
    # down-going solutions at z = h: Q = vP D(h) + w E(h), S = vS E(h); rows U, W, X, Z
    q0 = v[0, 0] * Dh + v[1, 0] * Eh
    q1 = v[0, 1] * Dh + v[1, 1] * Eh
    q2 = v[0, 2] * Dh + v[1, 2] * Eh
    q3 = v[0, 3] * Dh + v[1, 3] * Eh
    s0 = v[2, 0] * Eh
    s1 = v[2, 1] * Eh
    s2 = v[2, 2] * Eh
    s3 = v[2, 3] * Eh
    w0, w1, w2, w3 = v[1, 0], v[1, 1], v[1, 2], v[1, 3]
    u0, u1, u2, u3 = v[2, 0], v[2, 1], v[2, 2], v[2, 3]
    kp = _right_divide((q2 - w2, s2 - u2, -w3 - q3, -u3 - s3), (w0 + q0, u0 + s0, w1 - q1, u1 - s1))
    km = _right_divide((-w2 - q2, -u2 - s2, q3 - w3, s3 - u3), (w0 - q0, u0 - s0, w1 + q1, u1 + s1))
    return kp + km


def _sh_point(k, S, G, h):
    """``(diagonal, off-diagonal)`` of the SH layer stiffness of :meth:`Layered._sh_layer`."""
    be = np.sqrt(k * k + S)
    E = np.exp(-be * h)
    x = -2.0 * be * h
    if x.real * x.real + x.imag * x.imag < 1e-16:
        ratio = 1.0 / (2.0 * h) + 0j
    else:
        ratio = be / (-np.expm1(x))
    c = G * ratio
    return c * (1.0 + E * E), -2.0 * c * E


def _kernel_loop(k, materials, stack, out):
    """Surface kernels of a stack for all ``(s, k)``, written into preallocated arrays.

    Parameters
    ----------
    k : (nk,) complex
    materials : tuple ``(S, G, eta)``
        ``S = rho s^2/G(s)`` and ``G(s)`` (nmat, ns) complex of the layers from the top, then the
        half-space (if any); ``eta`` (nmat,) float.
    stack : tuple ``(h, halfspace, want_sh)``
        Layer thicknesses (nl,) float; a half-space below the last layer (else a rigid base);
        compute the SH kernel.
    out : tuple ``(zz, rr, cz, tt)`` of (ns, nk) complex
        Outputs: ``F_zz``, ``F_xx`` and ``-(F_xz + F_zx)/2`` of the P-SV surface flexibility and
        (if ``want_sh``) the SH one; ``tt`` is not touched otherwise.
    """
    S, G, eta = materials
    h, halfspace, want_sh = stack
    zz, rr, cz, tt = out
    nl = h.shape[0]
    ns = S.shape[1]
    nk = k.shape[0]
    v = np.empty((3, 4), np.complex128)
    for i in range(ns):
        for j in range(nk):
            kj = k[j]
            b00 = b01 = b10 = b11 = 0j
            if halfspace:
                b00, b01, b10, b11 = _halfspace_point(kj, S[nl, i], G[nl, i], eta[nl], v)
            for L in range(nl - 1, -1, -1):
                p00, p01, p10, p11, m00, m01, m10, m11 = _layer_point(kj, S[L, i], G[L, i], eta[L], h[L], v)
                # blocks of the layer's K (see _layer_point): K11 = (K+ + K-)/2 = A, K22 = J A J,
                # K12 = B J, K21 = J B with B = (K+ - K-)/2
                a00, a01, a10, a11 = 0.5 * (p00 + m00), 0.5 * (p01 + m01), 0.5 * (p10 + m10), 0.5 * (p11 + m11)
                if L == nl - 1 and not halfspace:
                    b00, b01, b10, b11 = a00, a01, a10, a11
                    continue
                d00, d01, d10, d11 = 0.5 * (p00 - m00), 0.5 * (p01 - m01), 0.5 * (p10 - m10), 0.5 * (p11 - m11)
                # Kb <- K11 - K12 (K22 + Kb)^-1 K21
                c00 = a00 + b00
                c01 = b01 - a01
                c10 = b10 - a10
                c11 = a11 + b11
                r = 1.0 / (c00 * c11 - c01 * c10)
                # X = (K22 + Kb)^-1 K21, K21 = [[d00, d01], [-d10, -d11]]
                x00 = (c11 * d00 + c01 * d10) * r
                x01 = (c11 * d01 + c01 * d11) * r
                x10 = (-c00 * d10 - c10 * d00) * r
                x11 = (-c00 * d11 - c10 * d01) * r
                # K12 = [[d00, -d01], [d10, -d11]]
                b00 = a00 - (d00 * x00 - d01 * x10)
                b01 = a01 - (d00 * x01 - d01 * x11)
                b10 = a10 - (d10 * x00 - d11 * x10)
                b11 = a11 - (d10 * x01 - d11 * x11)
            r = 1.0 / (b00 * b11 - b01 * b10)
            zz[i, j] = b00 * r
            rr[i, j] = b11 * r
            cz[i, j] = 0.5 * (b10 + b01) * r
            if want_sh:
                kb = 0j
                if halfspace:
                    kb = G[nl, i] * np.sqrt(kj * kj + S[nl, i])
                for L in range(nl - 1, -1, -1):
                    d, o = _sh_point(kj, S[L, i], G[L, i], h[L])
                    if L == nl - 1 and not halfspace:
                        kb = d
                    else:
                        kb = d - o * o / (d + kb)
                tt[i, j] = 1.0 / kb


_COMPILED = None


def compiled():
    """:func:`_kernel_loop` compiled by numba (imported here, on first use; disk-cached).

    Its helpers are compiled too and replace the plain functions of this module.
    """
    global _COMPILED
    if _COMPILED is None:
        import numba

        jit = numba.njit(cache=True, error_model="numpy")      # x/0 -> inf/nan as numpy, no exception
        module = globals()
        for name in ("_basis_point", "_right_divide", "_halfspace_point", "_layer_point", "_sh_point"):
            if not isinstance(module[name], numba.core.dispatcher.Dispatcher):
                module[name] = jit(module[name])
        _COMPILED = jit(_kernel_loop)
    return _COMPILED
