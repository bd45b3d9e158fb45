"""Lamb's problem in the Laplace domain: wavenumber kernel, integration contour, angular factors.

Vertical surface displacement of a homogeneous (visco)elastic half-space (``z`` down, both load and
displacement positive downward) under a vertical surface traction, for ``Re s >= 0``.  With
``sigma_s = s/c_s``, ``sigma_p = s/c_p``, ``alpha = sqrt(k^2 + sigma_p^2)``, ``beta = sqrt(k^2 + sigma_s^2)``
(principal roots) and the Rayleigh function

    R(k) = (2 k^2 + sigma_s^2)^2 - 4 k^2 alpha beta,

the 2-D Fourier transform of the displacement per unit force is ``G_hat(k) = sigma_s^2 alpha / (G R)``
(Lamb 1904; e.g. Kausel, *Fundamental Solutions in Elastodynamics*, 2006, with ``omega = -i s``).
As ``s -> 0`` or ``k -> oo``, ``G_hat -> (1 - nu)/(G k)``, the transform of Boussinesq's solution.

Numerics (all new here, in this module):

* the static part ``(1 - nu)/(G k)`` is subtracted and done in closed form (``statics``); the rest
  ``G_hat - (1-nu)/(G k) = O(sigma^2/k^3)`` is absolutely integrable;
* ``R`` is rationalised for ``|sigma_s|^2 << k^2`` to avoid cancellation,
  ``G G_hat = alpha (a^2 + 4 k^2 alpha beta) / P(k)`` with ``a = 2k^2 + sigma_s^2``,
  ``P = 16 k^6 (1-eta) + 8 k^4 S (3 - 2 eta) + 8 k^2 S^2 + S^3``, ``S = sigma_s^2``, ``eta = (c_s/c_p)^2``;
* contour: for ``s`` in the closed first quadrant all branch points and the Rayleigh poles
  ``k = +-i sigma`` lie in the 2nd and 4th quadrants, so the integrand is analytic in the first quadrant
  and the real ``k`` axis may be replaced by ``k = x (1 + 0.3 i)`` (a wedge; scale-invariant distance
  ``>= 0.29 |k_pole|`` to every singularity, however close ``s`` is to the imaginary axis) followed by
  the horizontal line ``Im k = h = 3/D`` (``D`` the largest pair extent; the angular factors grow only
  like ``exp(h D) = e^3``). ``s`` with ``Im s < 0`` are obtained by conjugation. Gauss-Legendre panels:
  geometric (ratio 2) on the wedge, width ``2h`` on the line;
* angular factor of a receiver/source rectangle pair: ``H(k) = int_0^2pi S_r S_s cos(k_x dx) cos(k_y dy)
  dtheta`` (``S`` = products of sincs), independent of ``s``; periodic trapezoidal rule in ``theta``
  (exponentially convergent, ``~ k D + 24`` points per period).

Horizontal and coupled components (the surface Green's tensor): :func:`tensor_kernels` (P-SV radial,
SH, vertical/radial coupling; derivation in the comment block above it) and
:func:`angular_components` (angular factors weighted by ``cos^2``, ``cos sin``, ``cos``, ``sin`` of the
wavenumber angle, with ``sin(k_x dx)``-type factors for the odd components), on the same contour.
"""

from __future__ import annotations

import numpy as np
from scipy.special import jv

_GL_X, _GL_W = np.polynomial.legendre.leggauss(12)
WEDGE = 0.3


def eta_of(nu: float) -> float:
    """``(c_s/c_p)^2 = (1 - 2 nu) / (2 (1 - nu))``."""
    return (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))


def rayleigh_ratio(nu: float) -> float:
    """``(c_s/c_R)^2``: the root > 1 of ``16(1-eta) x^3 - 8(3-2eta) x^2 + 8x - 1 = 0`` (Rayleigh 1885)."""
    eta = eta_of(nu)
    roots = np.roots([16.0 * (1.0 - eta), -8.0 * (3.0 - 2.0 * eta), 8.0, -1.0])
    real = roots[np.abs(roots.imag) < 1e-12].real
    return float(real[real > 1.0].max())


def kernel(k, S, eta, nu):
    """``G(s) [G_hat(k, s) - (1 - nu)/(G(s) k)]`` for nodes ``k`` (nk,) and ``S = sigma_s^2`` (ns,).

    Returns (ns, nk) complex. Dimension: 1/length (times force/length^2 -> m/N after dividing by G).
    """
    K2 = (k * k)[None, :]
    S = S[:, None]
    al = np.sqrt(K2 + eta * S)
    be = np.sqrt(K2 + S)
    a = 2.0 * K2 + S
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        direct = S * al / (a * a - 4.0 * K2 * al * be)
        P = ((16.0 * (1.0 - eta) * K2 + 8.0 * (3.0 - 2.0 * eta) * S) * K2 + 8.0 * S * S) * K2 + S ** 3
        ration = al * (a * a + 4.0 * K2 * al * be) / P
    small = np.abs(S) < 0.5 * np.abs(K2)
    out = np.where(small, ration, direct)
    return out - (1.0 - nu) / k[None, :]


def tail_coefficients(S, eta):
    """Large-``k`` expansion ``kernel ~ A/k^3 + B/k^5`` (derived symbolically for this module)."""
    A = -S * (3 * eta ** 2 - 4 * eta + 3) / (8 * (1 - eta) ** 2)
    B = S ** 2 * (eta ** 4 + 2 * eta ** 3 - 18 * eta ** 2 + 22 * eta - 11) / (32 * (eta - 1) ** 3)
    return A, B


def contour(sig_lo: float, D: float, kmax: float, width: float = 2.0):
    """Nodes ``k`` (complex) and weights ``w`` (complex, include ``dk/dx``) of the deformed contour.

    ``sig_lo``: smallest ``|k|`` of any singularity (smallest ``|sigma_p|``); ``D``: largest pair extent
    (sets ``h = 3/D``); ``kmax``: truncation abscissa; ``width``: flat panels are ``width * h`` wide.
    Nodes are returned in increasing ``Re k``.
    """
    h = 3.0 / D
    xc = h / WEDGE
    x0 = min(0.25 * sig_lo, xc)
    edges = [0.0, x0]
    while edges[-1] < xc * (1 - 1e-12):
        edges.append(min(2.0 * edges[-1], xc))
    wedge_edges = np.array(edges)
    if kmax > xc:
        n = int(np.ceil((kmax - xc) / (width * h)))
        flat_edges = np.linspace(xc, xc + n * width * h, n + 1)
    else:
        flat_edges = np.array([xc])
    ks, ws = [], []
    for edges, wedge in ((wedge_edges, True), (flat_edges, False)):
        if len(edges) < 2:
            continue
        lo, hi = edges[:-1, None], edges[1:, None]
        x = 0.5 * (lo + hi) + 0.5 * (hi - lo) * _GL_X[None, :]
        wx = 0.5 * (hi - lo) * _GL_W[None, :]
        x, wx = x.ravel(), wx.ravel()
        if wedge:
            ks.append(x * (1.0 + 1j * WEDGE))
            ws.append(wx * (1.0 + 1j * WEDGE))
        else:
            ks.append(x + 1j * h)
            ws.append(wx.astype(complex))
    return np.concatenate(ks), np.concatenate(ws)


def pair_extent(keys) -> np.ndarray:
    """``sqrt((|dx| + (a_r+a_s)/2)^2 + (|dy| + (b_r+b_s)/2)^2)`` for pair keys (P, 6)."""
    dx, dy, ar, br, as_, bs = keys.T
    return np.hypot(dx + 0.5 * (ar + as_), dy + 0.5 * (br + bs))


def _factor(kc, d, a1, a2):
    """``sinc(kc a1/2) sinc(kc a2/2) cos(kc d)`` for complex ``kc`` (sinc(0) = 1; sizes may be 0)."""
    out = np.cos(kc * d)
    for a in (a1, a2):
        if a > 0:
            z = 0.5 * a * kc
            out = out * (np.sin(z) / z)
    return out


def _factors(kc, keys):
    """``_factor`` of every key (U, 3) ``(d, a1, a2)``, stacked on a last axis: (..., U).

    The sinc products depend on the sizes only: each distinct ``(a1, a2)`` is evaluated once and
    only ``cos(kc d)`` per key (strips of one width share one pair of sincs).
    """
    sizes, group = np.unique(keys[:, 1:], axis=0, return_inverse=True)
    sincs = [_factor(kc, 0.0, a1, a2) for a1, a2 in sizes]
    return np.stack([np.cos(kc * d) * sincs[g] for (d, _, _), g in zip(keys, group.ravel())], axis=-1)


def _angular_groups(k, Rmax):
    """Groups of wavenumbers with the number of angular nodes each needs: ``(indices, n)``.

    ``n ~ 1.1 |k| R / 4 + 6`` nodes per quarter period (``R`` the largest pair extent) resolve the
    angular factors to round-off; wavenumbers sorted by ``|k|`` are grouped while their need is
    within 25 % of the group's first, which then takes the largest need of the group.
    """
    def n_needed(kabs):
        return int(np.ceil((1.1 * kabs * Rmax + 24.0) / 4.0))

    order = np.argsort(np.abs(k))
    kabs_sorted = np.abs(k[order])
    start = 0
    while start < k.size:
        limit = 1.25 * n_needed(kabs_sorted[start]) + 2
        stop = start + 1
        while stop < k.size and n_needed(kabs_sorted[stop]) <= limit:
            stop += 1
        yield order[start:stop], n_needed(kabs_sorted[stop - 1])
        start = stop


def angular(k, keys, chunk_entries: int = 2_000_000) -> np.ndarray:
    """Angular factors ``H_p(k)`` (nk, P) for pair keys (P, 6) ``|dx|, |dy|, a_r, b_r, a_s, b_s``.

    The integrand factorises into an x-factor ``(|dx|, a_r, a_s)`` and a y-factor ``(|dy|, b_r, b_s)``;
    each distinct factor is evaluated once (on a grid there are ~sqrt(P) of each) and the pairs are
    formed by a batched product over the angles. Nodes never sit at ``k_x = 0`` or ``k_y = 0``
    (midpoint angles), so the sincs are evaluated directly.
    """
    k = np.asarray(k)
    P = keys.shape[0]
    xkeys, ix = np.unique(np.round(keys[:, [0, 2, 4]], 12), axis=0, return_inverse=True)
    ykeys, iy = np.unique(np.round(keys[:, [1, 3, 5]], 12), axis=0, return_inverse=True)
    ix, iy = ix.ravel(), iy.ravel()
    Rmax = float(pair_extent(keys).max())

    out = np.empty((k.size, P), dtype=complex)
    for idx, n in _angular_groups(k, Rmax):
        step = max(1, chunk_entries // (n * (len(xkeys) + len(ykeys) + P)))
        theta = (np.arange(n) + 0.5) * (0.5 * np.pi / n)
        c, s = np.cos(theta), np.sin(theta)
        for j in range(0, idx.size, step):
            sel = idx[j:j + step]
            kk = k[sel][:, None]
            kx, ky = kk * c[None, :], kk * s[None, :]
            Sx = _factors(kx, xkeys)                                        # (q, n, Ux)
            Sy = _factors(ky, ykeys)                                        # (q, n, Uy)
            M = np.matmul(Sx.transpose(0, 2, 1), Sy)                       # (q, Ux, Uy)
            out[sel] = (2.0 * np.pi / n) * M[:, ix, iy]
    return out


def point_hankel(k, r):
    """``2 pi J0(k r)`` (nk, nr): the angular factor of a point/point pair."""
    return 2.0 * np.pi * jv(0, k[:, None] * r[None, :])


# --- horizontal and coupled components (surface Green's tensor) ----------------------------------
#
# Same half-space, same transform (inverse ``(1/4 pi^2) int G_hat e^{+i k.x} d^2k``). A surface traction
# with components ``t_r`` (along the wavenumber vector), ``t_t`` (across it) and ``t_z`` (down) gives,
# derived here from the potentials ``phi = A e^{-alpha z}``, ``psi = B e^{-beta z}`` and the traction
# conditions ``sigma_zz = -t_z``, ``sigma_xz = -t_r`` at ``z = 0`` (cf. Kausel 2006, surface Green's
# functions of a half-space; Lamb 1904),
#
#     G u_r = [S beta t_r - i k C t_z] / R,   G u_z = [i k C t_r + S alpha t_z] / R,   G u_t = t_t / beta,
#
# with ``C = 2 k^2 + S - 2 alpha beta``. Statics (``S -> 0``): ``S beta/R -> (1-nu)/k``,
# ``1/beta -> 1/k`` and ``i k C/R -> -i (1 - 2 nu)/(2 k)``, the transforms of Cerruti's solution.
# With ``k = k (cos theta, sin theta)``: ``G_xx = cos^2 K_rr + sin^2 K_tt``, ``G_xy = cos sin (K_rr - K_tt)``,
# ``G_zx = cos(theta) i k C/R = -G_xz``. The odd parts of ``e^{i k.x}`` pair with the odd angular
# weights: ``Phi_zx = (1/4pi^2) int k dk K_c int cos(theta) S_r S_s sin(k_x dx) cos(k_y dy) dtheta`` with
# ``K_c = i (i k C/R) = k (2 alpha beta - a)/R`` (real for real ``k, s``; static ``(1 - 2 nu)/(2 k)``), and
# ``Phi_xy = -(1/4pi^2) int k dk (K_rr - K_tt) int cos sin S_r S_s sin(k_x dx) sin(k_y dy) dtheta``.

def tensor_kernels(k, S, eta, nu):
    """Dynamic residuals (``s``-dependent part) of the horizontal/coupled kernels, times ``G(s)``.

    Parameters
    ----------
    k : (nk,) complex
        Contour nodes.
    S : (ns,) complex
        ``sigma_s^2 = s^2 rho/G(s)``.
    eta, nu : float

    Returns
    -------
    K_rr, K_tt, K_c : (ns, nk) complex, 1/m
        ``S beta/R - (1-nu)/k`` (P-SV radial), ``1/beta - 1/k`` (SH) and
        ``k (2 alpha beta - a)/R - (1-2 nu)/(2k)`` (vertical/radial coupling). Each is rationalised
        for ``|S| < |k|^2/2`` (``R (a^2 + 4 k^2 alpha beta) = S P``, ``2 alpha beta - a =
        S (4 eta k^2 + (4 eta - 1) S)/(2 alpha beta + a)``) to avoid cancellation, as in :func:`kernel`.
    """
    K2 = (k * k)[None, :]
    kk = k[None, :]
    S = S[:, None]
    al = np.sqrt(K2 + eta * S)
    be = np.sqrt(K2 + S)
    a = 2.0 * K2 + S
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        R = a * a - 4.0 * K2 * al * be
        P = ((16.0 * (1.0 - eta) * K2 + 8.0 * (3.0 - 2.0 * eta) * S) * K2 + 8.0 * S * S) * K2 + S ** 3
        Q = (a * a + 4.0 * K2 * al * be) / P                   # = S / R
        small = np.abs(S) < 0.5 * np.abs(K2)
        krr = np.where(small, be * Q, S * be / R)
        kc = np.where(small, kk * (4.0 * eta * K2 + (4.0 * eta - 1.0) * S) * Q / (2.0 * al * be + a),
                      kk * (2.0 * al * be - a) / R)
    ktt = -S / (kk * be * (kk + be))
    return krr - (1.0 - nu) / kk, ktt, kc - (0.5 - nu) / kk


def _factors_odd(kc, keys, odd):
    """As :func:`_factors` with ``sin(kc d)`` instead of ``cos(kc d)`` when ``odd``."""
    if not odd:
        return _factors(kc, keys)
    sizes, group = np.unique(keys[:, 1:], axis=0, return_inverse=True)
    sincs = [_factor(kc, 0.0, a1, a2) for a1, a2 in sizes]
    return np.stack([np.sin(kc * d) * sincs[g] for (d, _, _), g in zip(keys, group.ravel())], axis=-1)


#: angular weights of the tensor components: name -> (weight(cos, sin), x factor odd, y factor odd)
ANGULAR_SPECS = {
    "1": (None, False, False),                       # zz (and xx + yy)
    "cc": (lambda c, s: c * c, False, False),        # xx: cos^2 K_rr + sin^2 K_tt
    "cs": (lambda c, s: c * s, True, True),          # xy
    "c": (lambda c, s: c, True, False),              # zx
    "s": (lambda c, s: s, False, True),              # zy
}


def angular_components(k, keys, names, chunk_entries: int = 2_000_000) -> dict:
    """Angular factors of the tensor components for pair keys (P, 6) (``|dx|, |dy|`` >= 0).

    ``H_name(k) = int_0^2pi w(theta) X(k cos theta) Y(k sin theta) dtheta`` with ``X`` the sinc
    product times ``cos(k_x |dx|)`` (even) or ``sin(k_x |dx|)`` (odd) and likewise ``Y``; the weight
    ``w`` and the parities are those of :data:`ANGULAR_SPECS` (each integrand is even under
    ``theta -> -theta`` and ``theta -> pi - theta``, so the first quadrant suffices, as in
    :func:`angular`). Returns ``{name: (nk, P) complex}``.
    """
    k = np.asarray(k)
    P = keys.shape[0]
    xkeys, ix = np.unique(np.round(keys[:, [0, 2, 4]], 12), axis=0, return_inverse=True)
    ykeys, iy = np.unique(np.round(keys[:, [1, 3, 5]], 12), axis=0, return_inverse=True)
    ix, iy = ix.ravel(), iy.ravel()
    Rmax = float(pair_extent(keys).max())
    specs = [(nm,) + ANGULAR_SPECS[nm] for nm in names]
    need_x = {odd for _, _, odd, _ in specs}
    need_y = {odd for _, _, _, odd in specs}

    out = {nm: np.empty((k.size, P), dtype=complex) for nm in names}
    for idx, n in _angular_groups(k, Rmax):
        step = max(1, chunk_entries // (n * (2 * len(xkeys) + 2 * len(ykeys) + len(names) * P)))
        theta = (np.arange(n) + 0.5) * (0.5 * np.pi / n)
        c, s = np.cos(theta), np.sin(theta)
        for j in range(0, idx.size, step):
            sel = idx[j:j + step]
            kk = k[sel][:, None]
            kx, ky = kk * c[None, :], kk * s[None, :]
            SX = {odd: _factors_odd(kx, xkeys, odd) for odd in need_x}        # (q, n, Ux)
            SY = {odd: _factors_odd(ky, ykeys, odd) for odd in need_y}        # (q, n, Uy)
            for oy in need_y:                                   # one product per y parity
                group = [sp for sp in specs if sp[3] == oy]
                Sx = np.concatenate([SX[ox] if wfun is None else SX[ox] * wfun(c, s)[None, :, None]
                                     for _, wfun, ox, _ in group], axis=2)   # (q, n, g Ux)
                M = np.matmul(Sx.transpose(0, 2, 1), SY[oy])                 # (q, g Ux, Uy)
                for i, (nm, *_rest) in enumerate(group):
                    out[nm][sel] = (2.0 * np.pi / n) * M[:, i * len(xkeys) + ix, iy]
    return out
