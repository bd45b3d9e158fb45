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
  (exponentially convergent, ``~ k D + 24`` points per period). The sums over the angles are
  compiled (:func:`_angular_loop`); the ``exp(+-i k_x d)`` of offsets on a progression (a regular
  grid of patches) are powers of one exponential per angle (:func:`_axis_plan`).

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


def _axis_plan(keys, kabs):
    """How :func:`_axis_factors` evaluates the distinct axis factors ``(d, a1, a2)`` (U, 3), ``d >= 0``.

    The offsets are written ``d = d0 + m delta + r`` (``d0`` the smallest). Where ``|r| kabs <= 1e-6``
    (``kabs`` the largest ``|k|``; exact multiples have ``r = 0``), ``exp(+-i k_x d)`` is the ``m``-th
    power of ``exp(+-i k_x delta)`` times ``exp(+-i k_x d0)`` and, for ``r != 0``, ``exp(+-i k_x r)`` to
    second order (error below ``1e-19``); the other offsets are evaluated directly. ``delta`` is the
    smallest or the most frequent gap between distinct offsets (gaps rounded to 1e-12), whichever
    costs fewer direct evaluations and steps (a progression of more than ``4 U + 16`` steps is not
    used). The sinc products are evaluated once per distinct ``(a1, a2)``.

    Returns
    -------
    tuple
        ``(d0, delta, d, m, r, order, ngrid, group, half)``: ``d``, ``r`` (U,) float; ``m`` (U,) int;
        ``order`` (U,) int, the ``ngrid`` keys on the progression by increasing ``m``, then the
        others; ``group`` (U,) int, the row of the key's sides in ``half`` (G, 2) (half sides).
    """
    d = np.ascontiguousarray(keys[:, 0], dtype=float)
    sizes, group = np.unique(keys[:, 1:], axis=0, return_inverse=True)
    distinct = np.unique(d)
    d0 = float(distinct[0])
    best = (30 * np.count_nonzero(d != d0), 1.0, np.zeros(d.size, dtype=np.int64), d - d0, d == d0)
    if distinct.size > 1:
        gaps, counts = np.unique(np.round(np.diff(distinct), 12), return_counts=True)
        for delta in sorted({float(gaps[0]), float(gaps[np.argmax(counts)])}):
            if delta <= 0.0:
                continue
            m = np.rint((d - d0) / delta).astype(np.int64)
            r = d - (d0 + m * delta)
            on = np.abs(r) * kabs <= 1e-6
            if m[on].max() > 4 * d.size + 16:
                continue
            cost = 30 * np.count_nonzero(~on) + int(m[on].max())
            if cost < best[0]:
                best = (cost, delta, m, r, on)
    _, delta, m, r, on = best
    m[~on] = -1
    r[~on] = 0.0
    grid = np.flatnonzero(on)
    order = np.concatenate([grid[np.argsort(m[grid], kind="stable")], np.flatnonzero(~on)])
    return (d0, delta, d, m, r, order.astype(np.int64), int(grid.size), group.ravel().astype(np.int64),
            np.ascontiguousarray(0.5 * sizes))


# --- compiled angular sums -----------------------------------------------------------------------
# Plain functions here, compiled by :func:`_compiled` on first use (numba is imported then, as the
# rest of the package does), with numba's disk cache. One wavenumber at a time, in blocks of
# ``_BLOCK`` angles, :func:`_axis_factors` evaluates the x and y factors of the distinct keys and
# :func:`_angular_loop` accumulates their weighted products over the angles for every
# (x key, y key) combination, then picks the pairs: the sums of the batched products of
# ``X(k cos theta)`` and ``Y(k sin theta)`` over the same nodes as before, without the
# (wavenumbers x angles x keys) temporaries.

#: Angles per block of the compiled loop.
_BLOCK = 128
#: Powers of ``exp(+-i k_x delta)`` are re-evaluated directly every ``_ANCHOR`` steps (round-off of
#: the repeated products stays below ``_ANCHOR`` ulps of ``exp(|Im k_x| d) <= e^3``).
_ANCHOR = 128
#: Sinc ``sin(z)/z`` by its Taylor series (to ``z^14``, error < 1e-19) for ``|z|^2 < _SMALL``, else
#: from ``exp(+-i z)``.
_SMALL = 0.25


def _phase(kxr, kxi, v):
    """``exp(i k_x v)`` and ``exp(-i k_x v)`` as ``(re, im, re, im)`` for ``k_x = kxr + i kxi``."""
    if v == 0.0:
        return 1.0, 0.0, 1.0, 0.0
    e = np.exp(-kxi * v)
    c = np.cos(kxr * v)
    s = np.sin(kxr * v)
    return e * c, e * s, c / e, -s / e


def _sinc_products(kxr, kxi, b, half, sinc):
    """The sinc products of the groups of :func:`_axis_factors` at ``k_x = kxr + i kxi``, ``j < b``.

    Parameters
    ----------
    kxr, kxi : (>= b,) float, the wavenumbers ``k_x`` (real and imaginary parts)
    b : int
    half : (G, 2) float, the half sides of a group's two rectangles (<= 0: a point)
    sinc : (2, G, >= b) float, output: ``sinc[:, g, j]`` (re, im) the product over the two sides
        of ``sin(k_x h) / (k_x h)``
    """
    for g in range(half.shape[0]):
        for j in range(b):
            sr, si = 1.0, 0.0
            for side in range(2):
                h = half[g, side]
                if h <= 0.0:
                    continue
                if side == 1 and h == half[g, 0]:
                    fr, fi = sr, si
                else:
                    zr = h * kxr[j]
                    zi = h * kxi[j]
                    z2r = zr * zr - zi * zi
                    z2i = 2.0 * zr * zi
                    if z2r * z2r + z2i * z2i < _SMALL * _SMALL:  # 1 - z^2/3! + z^4/5! - ... + z^14/15!
                        fr, fi = 1.0, 0.0
                        for n in range(15, 1, -2):
                            cr = -(fr * z2r - fi * z2i) / (n * (n - 1))
                            fi = -(fr * z2i + fi * z2r) / (n * (n - 1))
                            fr = 1.0 + cr
                    else:                                       # (e^{iz} - e^{-iz})/(2 i z)
                        er, ei, qr, qi = _phase(kxr[j], kxi[j], h)
                        nr = 0.5 * (ei - qi)
                        ni = 0.5 * (qr - er)
                        den = zr * zr + zi * zi
                        fr = (nr * zr + ni * zi) / den
                        fi = (ni * zr - nr * zi) / den
                sr, si = sr * fr - si * fi, sr * fi + si * fr
            sinc[0, g, j] = sr
            sinc[1, g, j] = si


def _axis_factors(k, proj, b, plan, want, arrays):
    """Axis factors of the keys of ``plan`` (:func:`_axis_plan`) at ``k_x = k proj[j]``, ``j < b``.

    ``k = (re, im)``; ``arrays = (wk, sinc, out)``: ``out[0, :, u, j]`` (re, im) = sinc product
    times ``cos(k_x d_u)`` if ``want[0]``; ``out[1]`` the same with ``sin(k_x d_u)`` if
    ``want[1]``. Work space: ``wk`` (10, >= b) and ``sinc`` (2, G, >= b) float.
    """
    kr, ki = k
    wk, sinc, out = arrays
    d0, delta, d, m, r, order, ngrid, group, half = plan
    kxr, kxi, Pr, Pi, Qr, Qi = wk[0], wk[1], wk[2], wk[3], wk[4], wk[5]
    Wr, Wi, Vr, Vi = wk[6], wk[7], wk[8], wk[9]
    for j in range(b):
        kxr[j] = kr * proj[j]
        kxi[j] = ki * proj[j]
    _sinc_products(kxr, kxi, b, half, sinc)
    even, odd = want[0], want[1]
    mcur = 0
    for t in range(order.size):
        u = order[t]
        if t >= ngrid:                                   # off the progression: direct
            for j in range(b):
                Pr[j], Pi[j], Qr[j], Qi[j] = _phase(kxr[j], kxi[j], d[u])
        elif t == 0:
            for j in range(b):
                Pr[j], Pi[j], Qr[j], Qi[j] = _phase(kxr[j], kxi[j], d0)
        while t < ngrid and mcur < m[u]:
            if mcur == 0:
                for j in range(b):
                    Wr[j], Wi[j], Vr[j], Vi[j] = _phase(kxr[j], kxi[j], delta)
            mcur += 1
            if mcur % _ANCHOR == 0:
                dm = d0 + mcur * delta
                for j in range(b):
                    Pr[j], Pi[j], Qr[j], Qi[j] = _phase(kxr[j], kxi[j], dm)
            else:
                for j in range(b):
                    pr = Pr[j] * Wr[j] - Pi[j] * Wi[j]
                    Pi[j] = Pr[j] * Wi[j] + Pi[j] * Wr[j]
                    Pr[j] = pr
                    qr = Qr[j] * Vr[j] - Qi[j] * Vi[j]
                    Qi[j] = Qr[j] * Vi[j] + Qi[j] * Vr[j]
                    Qr[j] = qr
        ru = r[u]
        g = group[u]
        for j in range(b):
            er, ei, fr, fi = Pr[j], Pi[j], Qr[j], Qi[j]
            if ru != 0.0:                       # times exp(+-i z), z = k_x r, to second order
                zr = kxr[j] * ru
                zi = kxi[j] * ru
                hr = 0.5 * (zr * zr - zi * zi)
                hi = zr * zi
                ar, ai = 1.0 - zi - hr, zr - hi
                br, bi = 1.0 + zi - hr, -zr - hi
                er, ei = er * ar - ei * ai, er * ai + ei * ar
                fr, fi = fr * br - fi * bi, fr * bi + fi * br
            sr, si = sinc[0, g, j], sinc[1, g, j]
            if even:                            # cos = (e + f)/2
                cr, ci = 0.5 * (er + fr), 0.5 * (ei + fi)
                out[0, 0, u, j] = cr * sr - ci * si
                out[0, 1, u, j] = cr * si + ci * sr
            if odd:                             # sin = (e - f)/(2 i)
                cr, ci = 0.5 * (ei - fi), 0.5 * (fr - er)
                out[1, 0, u, j] = cr * sr - ci * si
                out[1, 1, u, j] = cr * si + ci * sr


def _angular_loop(k, nodes, korder, spec, pairs, plans, out):
    """``out[q, i, p] = (2 pi/n_i) sum_j w_q(theta_j) X_p(k_i cos theta_j) Y_p(k_i sin theta_j)``.

    ``theta_j = (j + 1/2) pi/(2 n_i)``, ``j < n_i = nodes[i]``, the wavenumbers taken in the order
    ``korder`` (by ``n_i``: the angles are evaluated once per ``n``); ``spec[q] = (weight, x odd,
    y odd)`` as in :data:`ANGULAR_SPECS`; ``pairs = (ix, iy)``, ``plans = (xplan, yplan)``: pair
    ``p`` has the x key ``ix[p]`` of ``xplan`` and the y key ``iy[p]`` of ``yplan``.
    """
    ix, iy = pairs
    xplan, yplan = plans
    nq = spec.shape[0]
    Ux, Uy = xplan[2].size, yplan[2].size
    wantx = np.zeros(2, dtype=np.bool_)
    wanty = np.zeros(2, dtype=np.bool_)
    for q in range(nq):
        wantx[spec[q, 1]] = True
        wanty[spec[q, 2]] = True
    B = _BLOCK
    wt, ywr, ywi = np.empty(B), np.empty(B), np.empty(B)
    wk = np.empty((10, B))
    sx = np.empty((2, xplan[8].shape[0], B))
    sy = np.empty((2, yplan[8].shape[0], B))
    FX = np.zeros((2, 2, Ux, B))
    FY = np.zeros((2, 2, Uy, B))
    acc = np.empty((nq, 2, Ux, Uy))
    cos_all = np.empty(nodes.max())
    sin_all = np.empty(nodes.max())
    n_prev = 0
    for i in korder:
        n = nodes[i]
        kr, ki = k[i].real, k[i].imag
        acc[:] = 0.0
        if n != n_prev:
            step = 0.5 * np.pi / n
            for j in range(n):
                th = (j + 0.5) * step
                cos_all[j] = np.cos(th)
                sin_all[j] = np.sin(th)
            n_prev = n
        for j0 in range(0, n, B):
            b = min(B, n - j0)
            cth = cos_all[j0:j0 + b]
            sth = sin_all[j0:j0 + b]
            _axis_factors((kr, ki), cth, b, xplan, wantx, (wk, sx, FX))
            _axis_factors((kr, ki), sth, b, yplan, wanty, (wk, sy, FY))
            for q in range(nq):
                code, xo, yo = spec[q, 0], spec[q, 1], spec[q, 2]
                for j in range(b):
                    c, s = cth[j], sth[j]
                    if code == 0:
                        wt[j] = 1.0
                    elif code == 1:
                        wt[j] = c * c
                    elif code == 2:
                        wt[j] = c * s
                    elif code == 3:
                        wt[j] = c
                    else:
                        wt[j] = s
                for v in range(Uy):
                    yr, yi = FY[yo, 0, v], FY[yo, 1, v]
                    for j in range(b):
                        ywr[j] = wt[j] * yr[j]
                        ywi[j] = wt[j] * yi[j]
                    for u in range(Ux):
                        xr, xi = FX[xo, 0, u], FX[xo, 1, u]
                        sr = 0.0
                        si = 0.0
                        for j in range(b):
                            sr += xr[j] * ywr[j] - xi[j] * ywi[j]
                            si += xr[j] * ywi[j] + xi[j] * ywr[j]
                        acc[q, 0, u, v] += sr
                        acc[q, 1, u, v] += si
        scale = 2.0 * np.pi / n
        for q in range(nq):
            for p in range(ix.size):
                out[q, i, p] = scale * complex(acc[q, 0, ix[p], iy[p]], acc[q, 1, ix[p], iy[p]])


_COMPILED = None


def _compiled():
    """:func:`_angular_loop` compiled by numba (imported here, on first use; disk-cached).

    Its helpers are compiled too and replace the plain functions of this module. The sums may be
    reassociated (vectorised) and multiply-adds fused: results change at round-off only.
    """
    global _COMPILED
    if _COMPILED is None:
        import numba

        jit = numba.njit(cache=True, error_model="numpy", fastmath={"reassoc", "contract"})
        module = globals()
        for name in ("_phase", "_sinc_products", "_axis_factors"):
            if not isinstance(module[name], numba.core.dispatcher.Dispatcher):
                module[name] = jit(module[name])
        _COMPILED = jit(_angular_loop)
    return _COMPILED


def _angular_sums(k, keys, names) -> np.ndarray:
    """Angular factors (len(names), nk, P) of the components ``names`` (:data:`ANGULAR_SPECS`)."""
    k = np.ascontiguousarray(k, dtype=complex)
    P = keys.shape[0]
    out = np.empty((len(names), k.size, P), dtype=complex)
    if k.size == 0 or P == 0:
        return out
    xkeys, ix = np.unique(np.round(keys[:, [0, 2, 4]], 12), axis=0, return_inverse=True)
    ykeys, iy = np.unique(np.round(keys[:, [1, 3, 5]], 12), axis=0, return_inverse=True)
    nodes = np.empty(k.size, dtype=np.int64)
    korder = []
    for idx, n in _angular_groups(k, float(pair_extent(keys).max())):
        nodes[idx] = n
        korder.append(idx)
    kabs = float(np.abs(k).max())
    spec = np.array([ANGULAR_SPECS[nm] for nm in names], dtype=np.int64).reshape(-1, 3)
    _compiled()(k, nodes, np.concatenate(korder).astype(np.int64), spec,
                (ix.ravel().astype(np.int64), iy.ravel().astype(np.int64)),
                (_axis_plan(xkeys, kabs), _axis_plan(ykeys, kabs)), out)
    return out


def angular(k, keys) -> np.ndarray:
    """Angular factors ``H_p(k)`` (nk, P) for pair keys (P, 6) ``|dx|, |dy|, a_r, b_r, a_s, b_s``.

    ``H_p(k) = int_0^2pi X(k cos theta) Y(k sin theta) dtheta``: the integrand factorises into an
    x-factor ``(|dx|, a_r, a_s)`` and a y-factor ``(|dy|, b_r, b_s)`` (sinc products times
    ``cos(k_x dx)``, ``cos(k_y dy)``); each distinct factor is evaluated once per angle (on a grid
    there are ~sqrt(P) of each, see :func:`_axis_plan`) and the pairs are formed by products over
    the angles (:func:`_angular_loop`). The integrand is even in ``theta -> -theta`` and
    ``theta -> pi - theta``: midpoint nodes on the first quadrant, never at ``k_x = 0`` or
    ``k_y = 0``.
    """
    return _angular_sums(k, keys, ["1"])[0]


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


#: angular weights of the tensor components: name -> (weight, x factor odd, y factor odd), the weight
#: 0: 1, 1: cos^2, 2: cos sin, 3: cos, 4: sin of the wavenumber angle
ANGULAR_SPECS = {
    "1": (0, False, False),                # zz (and xx + yy)
    "cc": (1, False, False),               # xx: cos^2 K_rr + sin^2 K_tt
    "cs": (2, True, True),                 # xy
    "c": (3, True, False),                 # zx
    "s": (4, False, True),                 # zy
}


def angular_components(k, keys, names) -> dict:
    """Angular factors of the tensor components for pair keys (P, 6) (``|dx|, |dy|`` >= 0).

    ``H_name(k) = int_0^2pi w(theta) X(k cos theta) Y(k sin theta) dtheta`` with ``X`` the sinc
    product times ``cos(k_x |dx|)`` (even) or ``sin(k_x |dx|)`` (odd) and likewise ``Y``; the weight
    ``w`` and the parities are those of :data:`ANGULAR_SPECS` (each integrand is even under
    ``theta -> -theta`` and ``theta -> pi - theta``, so the first quadrant suffices, as in
    :func:`angular`). Returns ``{name: (nk, P) complex}``.
    """
    H = _angular_sums(k, keys, list(names))
    return {nm: H[i] for i, nm in enumerate(names)}
