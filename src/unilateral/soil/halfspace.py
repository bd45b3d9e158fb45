"""Homogeneous (visco)elastic half-space: surface flexibilities (vertical, horizontal, coupled) in the
Laplace domain."""

from __future__ import annotations

import numpy as np

from .. import _validate as V
from . import lamb
from .patches import RectangularPatches, pair_table
from .statics import cerruti_averages, mean_inverse_distance

__all__ = ["HalfSpace"]

_CHUNK = 4_000_000          # complex entries per (s, k) block
_KERNEL_BLOCK = 65_536      # complex entries per (s, k) block of the patch kernels (cache-sized temporaries)


def laplace_points(s, materials):
    """``(sq, flip, zero)``: the values ``s`` (ns,) checked (finite, ``Re s >= 0``) and folded into
    the upper half-plane (``flip``: the ones conjugated, whose results are conjugated back), and
    which are zero; ``s = 0`` is refused for a constant-Q material of ``materials`` (it creeps)."""
    s = np.atleast_1d(np.asarray(s, dtype=complex))
    if s.ndim != 1:
        raise ValueError(f"s must be a scalar or 1-D array, got shape {s.shape}")
    V.check_finite("s", s.view(float))
    if np.any(s.real < -1e-12 * np.abs(s)):
        bad = s[np.argmin(s.real)]
        raise ValueError(f"s must satisfy Re s >= 0 (the kernel is defined there); got s = {bad!r}")
    flip = s.imag < 0
    sq = np.where(flip, np.conj(s), s)
    zero = sq == 0
    if np.any(zero) and any(m.damping > 0 and m.damping_model == "constant_q" for m in materials):
        raise ValueError("s = 0 is not allowed with damping_model='constant_q' and damping > 0 "
                         "(G(0) = 0: a constant-Q solid creeps); use damping=0 or 'kelvin_voigt'")
    return sq, flip, zero


def component_blocks(vals: dict, patches: RectangularPatches, components: str) -> np.ndarray:
    """The (ns, c m, c m) matrix of the components ``"xz"`` or ``"xyz"`` from their pair values.

    ``vals`` maps ``"xx"``, ``"zz"``, ``"zx"`` (and ``"yy"``, ``"xy"``, ``"zy"``) to (ns, m, m)
    values for ``|dx|, |dy|``; the odd components take the signs of the separations here.
    """
    d = patches.centres[:, None, :] - patches.centres[None, :, :]
    sx, sy = np.sign(d[..., 0]), np.sign(d[..., 1])
    zx = vals["zx"] * sx
    if components == "xz":
        return np.block([[vals["xx"], zx.transpose(0, 2, 1)], [zx, vals["zz"]]])
    xy = vals["xy"] * (sx * sy)
    zy = vals["zy"] * sy
    return np.block([[vals["xx"], xy, zx.transpose(0, 2, 1)],
                     [xy, vals["yy"], zy.transpose(0, 2, 1)],
                     [zx, zy, vals["zz"]]])


class HalfSpace:
    """Homogeneous isotropic half-space, elastic or (causally) viscoelastic.

    Parameters
    ----------
    G : float, Pa (or any consistent force/length^2)
        Shear modulus (at ``omega_ref`` for the damped models).
    nu : float
        Poisson's ratio, ``0 <= nu < 0.5``.
    rho : float, kg/m^3 (mass/length^3)
        Mass density.
    damping : float, optional
        Material (hysteretic) damping ratio ``xi >= 0``; 0 (default) is elastic.
    damping_model : {"constant_q", "kelvin_voigt"}
        How ``xi`` enters the correspondence principle ``G -> G(s)`` (``nu`` is kept constant, so both
        wave speeds scale alike):

        * ``"constant_q"`` (default; Kjartansson 1979, J. Geophys. Res. 84, 4737):
          ``G(s) = G (s/omega_ref)^(2 g) / cos(pi g)``, ``g = arctan(2 xi)/pi``. Analytic in
          ``Re s > 0``, real for real ``s`` (a real kernel), and ``G(i omega) = |.| e^{i pi g}`` has the
          loss tangent ``2 xi`` at *every* frequency, exactly ``G (1 + 2 i xi)`` at ``omega_ref``. This is
          the causal counterpart of the hysteretic ``G (1 + 2 i xi sgn omega)`` (which is not analytic).
          Its price: ``G(0) = 0`` (creep), so ``s = 0`` is rejected when ``xi > 0``.
        * ``"kelvin_voigt"``: ``G(s) = G (1 + 2 xi s/omega_ref)``; exact loss ``2 xi`` at ``omega_ref``
          only, damping proportional to frequency and a modulus growing like ``s``.
    omega_ref : float, rad/s
        Reference circular frequency of the damped models (default ``2 pi``, i.e. 1 Hz).

    Notes
    -----
    Range of validity: linear (visco)elasticity, small strains. With ``components="z"`` only vertical
    tractions act (relaxed contact: no shear tractions on the surface); ``"xz"``/``"xyz"`` give the
    surface Green's tensor (horizontal and coupled components) for horizontal loads and bonded
    contact (see :mod:`.rigid`). :meth:`surface_displacement` and :meth:`point_green` are vertical only.
    """

    def __init__(self, G, nu, rho, damping=0.0, damping_model="constant_q", omega_ref=2 * np.pi):
        self.G = V.positive_float("G", G)
        self.rho = V.positive_float("rho", rho)
        try:
            nu = float(nu)
        except (TypeError, ValueError):
            raise TypeError(f"nu must be a number, got {V.describe(nu)}") from None
        if not 0.0 <= nu < 0.5:
            raise ValueError(f"nu must lie in [0, 0.5), got {nu!r}")
        self.nu = nu
        damping = float(damping)
        if not (np.isfinite(damping) and damping >= 0.0):
            raise ValueError(f"damping must be >= 0, got {damping!r}")
        self.damping = damping
        self.damping_model = V.choice("damping_model", damping_model, {"constant_q", "kelvin_voigt"})
        self.omega_ref = V.positive_float("omega_ref", omega_ref)

    # --- material ------------------------------------------------------------------------------
    @property
    def cs(self) -> float:
        """Shear-wave speed ``sqrt(G/rho)`` (m/s) of the reference modulus."""
        return float(np.sqrt(self.G / self.rho))

    @property
    def cp(self) -> float:
        """Compression-wave speed ``c_s sqrt(2(1-nu)/(1-2nu))`` (m/s)."""
        return self.cs / np.sqrt(lamb.eta_of(self.nu))

    @property
    def cr(self) -> float:
        """Rayleigh-wave speed (m/s)."""
        return self.cs / np.sqrt(lamb.rayleigh_ratio(self.nu))

    def modulus(self, s) -> np.ndarray:
        """Correspondence-principle shear modulus ``G(s)`` (complex, shape of ``s``)."""
        s = np.asarray(s, dtype=complex)
        xi = self.damping
        if xi == 0.0:
            return np.full(s.shape, self.G, dtype=complex)
        if self.damping_model == "kelvin_voigt":
            return self.G * (1.0 + 2.0 * xi * s / self.omega_ref)
        g = np.arctan(2.0 * xi) / np.pi
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.G / np.cos(np.pi * g) * (s / self.omega_ref) ** (2.0 * g)

    # --- helpers -------------------------------------------------------------------------------
    def _prepare(self, s):
        sq, flip, zero = laplace_points(s, [self])
        Gs = self.modulus(sq)
        S = np.zeros(sq.shape, dtype=complex)
        S[~zero] = sq[~zero] ** 2 * self.rho / Gs[~zero]
        return sq, flip, Gs, S, zero

    def _finish(self, vals, Gs, flip):
        vals = vals / Gs[:, None]
        vals[flip] = np.conj(vals[flip])
        return vals

    # --- public API ----------------------------------------------------------------------------
    def surface_flexibility(self, patches: RectangularPatches, s, *, components="z",
                            kmax_factor=1.0) -> np.ndarray:
        """Surface flexibility matrix ``Phi(s)`` of rectangular patches (vertical or full tensor).

        ``Phi_ij(s)`` is the displacement component of row ``i`` averaged over its patch per unit total
        force of the component of column ``j`` uniformly distributed on its patch (Laplace
        transforms). Averaging (a Galerkin definition) makes ``Phi`` symmetric (reciprocity).

        Sign convention: ``z`` positive *down* (into the soil), ``x, y`` along the patch coordinates.
        Horizontal-vertical coupling: a horizontal force ``+x`` at the origin moves the surface point
        at ``(x, y)`` vertically by ``+(1 - 2 nu) x/(4 pi G r^2)`` statically, i.e. *down* ahead of the
        force (``x > 0``) and up behind it; reciprocally a downward force draws the surface inward,
        ``u_x = -(1 - 2 nu) x/(4 pi G r^2)`` (Cerruti 1882, Boussinesq 1885; Johnson, *Contact
        Mechanics*, 1985, Sec. 3.2; Kausel, *Fundamental Solutions in Elastodynamics*, 2006). So
        ``Phi_{z_i x_j}`` is odd in ``x_i - x_j`` (statically of its sign), and reciprocity gives
        ``Phi_{x_i z_j} = Phi_{z_j x_i}``.

        Parameters
        ----------
        patches : RectangularPatches
            ``m`` patches with positive sides.
        s : complex scalar or (ns,) array, 1/s
            Laplace variable(s), ``Re s >= 0`` (``s = i omega`` gives the frequency-domain flexibility as
            the limit from ``Re s > 0``; ``s = 0`` the static Boussinesq flexibility, exact, closed form).
        components : {"z", "xz", "xyz"}
            ``"z"`` (default): vertical only, (ns, m, m). ``"xz"``: (ns, 2m, 2m), rows/columns
            ``0..m-1`` the x components of the m patches, ``m..2m-1`` the z components (no y forces;
            the y displacements are not returned). ``"xyz"``: (ns, 3m, 3m), x then y then z blocks.
        kmax_factor : float
            Multiplies the wavenumber truncation (for convergence studies).

        Returns
        -------
        Phi : (ns, m, m), (ns, 2m, 2m) or (ns, 3m, 3m) complex, m/N
            Symmetric; ``Phi(conj s) = conj Phi(s)``.

        Notes
        -----
        The dynamic part is a wavenumber integral along a deformed contour (see :mod:`.lamb`); it is
        computed once per *distinct* pair geometry ``(|dx|, |dy|, sizes)`` - on a regular grid that is
        about ``m`` pairs instead of ``m^2`` - and the ``s``-independent angular factors are shared by
        all ``s``, so the cost is one ``(ns x nk) @ (nk x pairs)`` product. Accuracy ~1e-6 relative (see
        tests). Truncation ``k_max = 6 max|s/c_s| + 30/a_min``
        (``a_min`` the smallest patch side).

        Horizontal and coupled components (``components != "z"``): the static part is Cerruti's
        solution averaged in closed form (:func:`.statics.cerruti_averages`); the dynamic residual uses
        the P-SV radial, SH and coupling kernels of :func:`.lamb.tensor_kernels` with the angular
        factors ``cos^2``, ``cos sin``, ``cos``/``sin`` of :func:`.lamb.angular_components` on the same
        contour (the odd components with ``sin(k_x dx)``-type factors, then signed by
        ``sgn(dx)``, ``sgn(dy)``).
        """
        if not isinstance(patches, RectangularPatches):
            raise TypeError(f"patches must be RectangularPatches, got {V.describe(patches)}")
        if np.any(patches.sizes <= 0):
            raise ValueError("surface_flexibility needs patches with positive sides (the self-flexibility "
                             "of a point or line is infinite); use point_green for points")
        comps = V.choice("components", components, {"z", "xz", "xyz"})
        sq, flip, Gs, S, zero = self._prepare(s)
        keys, index = pair_table(patches, patches, symmetric=True)
        if comps == "z":
            vals = self._pairs(keys, S, zero, kmax_factor)
            vals = self._finish(vals, Gs, flip)
            return vals[:, index]
        vals = self._tensor_pairs(keys, S, zero, kmax_factor, comps)
        vals = {nm: self._finish(v, Gs, flip)[:, index] for nm, v in vals.items()}
        return component_blocks(vals, patches, comps)

    def surface_displacement(self, points, patches: RectangularPatches, s, *, kmax_factor=1.0):
        """Vertical displacement at surface points per unit force uniformly spread on each patch.

        Parameters
        ----------
        points : (n, 2) array_like, m
            Receiver points.
        patches : RectangularPatches
            ``m`` source patches with positive sides.
        s : complex scalar or (ns,) array
            As in :meth:`surface_flexibility`.

        Returns
        -------
        (ns, n, m) complex, m/N
        """
        pts = V.as_matrix("points", points, (None, 2), allow_sparse=False)
        if np.any(patches.sizes <= 0):
            raise ValueError("source patches must have positive sides")
        recv = RectangularPatches(pts, np.zeros_like(pts))
        sq, flip, Gs, S, zero = self._prepare(s)
        keys, index = pair_table(recv, patches, symmetric=False)
        vals = self._pairs(keys, S, zero, kmax_factor)
        return self._finish(vals, Gs, flip)[:, index]

    def point_green(self, r, s, *, kmax_factor=1.0) -> np.ndarray:
        """Surface vertical displacement at distance ``r`` per unit vertical point force (Lamb 1904).

        Parameters
        ----------
        r : float or (nr,) array, m, > 0
        s : complex scalar or (ns,) array, ``Re s >= 0``

        Returns
        -------
        (ns, nr) complex, m/N
            ``-> (1-nu)/(2 pi G r)`` (Boussinesq) at ``s = 0``. The Hankel integral is evaluated on the
            deformed contour after subtracting the static term and the two leading large-``k`` terms
            ``A/(k^2+b^2)^{3/2} + B'/(k^2+b^2)^{5/2}`` (``b = |sigma_s|``), whose transforms are
            ``A e^{-br}/b`` and ``B'(1+br) e^{-br}/(3 b^3)``.
        """
        r = np.atleast_1d(np.asarray(r, dtype=float))
        if r.ndim != 1 or np.any(~(r > 0)):
            raise ValueError("r must be a positive scalar or 1-D array")
        sq, flip, Gs, S, zero = self._prepare(s)
        nu, eta = self.nu, lamb.eta_of(self.nu)
        out = np.zeros((sq.size, r.size), dtype=complex)
        out += (1.0 - nu) / (2.0 * np.pi * r)[None, :]
        dyn = ~zero
        if np.any(dyn):
            Sd = S[dyn]
            sig = np.abs(np.sqrt(Sd))
            kmax_s = kmax_factor * (8.0 * sig + 30.0 / r.min())       # per-s truncation
            k, w = lamb.contour(np.sqrt(eta) * sig.min(), float(r.max()), kmax_s.max(), width=3.0)
            J = lamb.point_hankel(k, r)
            A, B = lamb.tail_coefficients(Sd, eta)
            b = sig
            Bp = B + 1.5 * b ** 2 * A
            res = np.empty((Sd.size, r.size), dtype=complex)
            order = np.argsort(kmax_s)
            i = 0
            while i < Sd.size:
                # a block of s values sharing the node prefix k.real <= kmax of its last member
                step = max(1, _CHUNK // k.size)
                sl = order[i:i + step]
                nk = int(np.searchsorted(k.real, kmax_s[sl].max())) + 1
                step = max(1, min(step * 4, _CHUNK // max(nk, 1)))
                sl = order[i:i + step]
                nk = min(k.size, int(np.searchsorted(k.real, kmax_s[sl].max())) + 12)
                kk, ww = k[:nk], w[:nk]
                K = lamb.kernel(kk, Sd[sl], eta, nu)
                q = (kk[None, :] ** 2 + b[sl, None] ** 2)
                K -= A[sl, None] / q ** 1.5 + Bp[sl, None] / q ** 2.5
                res[sl] = (K * (ww * kk)[None, :]) @ J[:nk] / (4.0 * np.pi ** 2)
                i += sl.size
            br = b[:, None] * r[None, :]
            res += (A[:, None] * np.exp(-br) / b[:, None]
                    + Bp[:, None] * (1.0 + br) * np.exp(-br) / (3.0 * b[:, None] ** 3)) / (2.0 * np.pi)
            out[dyn] += res
        return self._finish(out, Gs, flip)

    # --- engine --------------------------------------------------------------------------------
    def _contour(self, keys, Sd, kmax_factor):
        """The wavenumber contour ``(k, w)`` of pair keys (P, 6) at the nonzero ``S`` values ``Sd``:
        truncated at ``k_max = kmax_factor (6 max|sqrt(S)| + 30/a_min)``."""
        sig = np.abs(np.sqrt(Sd))
        sizes = keys[:, 2:]
        a_min = float(sizes[sizes > 0].min())
        D = float(lamb.pair_extent(keys).max())
        return lamb.contour(np.sqrt(lamb.eta_of(self.nu)) * sig.min(), D,
                            kmax_factor * (6.0 * sig.max() + 30.0 / a_min))

    def _pairs(self, keys, S, zero, kmax_factor):
        """(ns, P) values times G(s): static closed form plus wavenumber integral."""
        nu, eta = self.nu, lamb.eta_of(self.nu)
        static = np.array([mean_inverse_distance(*kk[:2], kk[2:4], kk[4:6]) for kk in keys])
        static *= (1.0 - nu) / (2.0 * np.pi)
        vals = np.repeat(static[None, :].astype(complex), S.size, axis=0)
        dyn = ~zero
        if np.any(dyn):
            Sd = S[dyn]
            k, w = self._contour(keys, Sd, kmax_factor)
            H = lamb.angular(k, keys)
            wk = (w * k)[None, :]
            res = np.empty((Sd.size, keys.shape[0]), dtype=complex)
            step = max(1, _KERNEL_BLOCK // k.size)
            for i in range(0, Sd.size, step):
                sl = slice(i, i + step)
                res[sl] = (lamb.kernel(k, Sd[sl], eta, nu) * wk) @ H / (4.0 * np.pi ** 2)
            vals[dyn] += res
        return vals

    def _tensor_pairs(self, keys, S, zero, kmax_factor, comps):
        """{component: (ns, P)} values times ``G(s)`` at ``(|dx|, |dy|)`` (odd ones unsigned)."""
        nu, eta = self.nu, lamb.eta_of(self.nu)
        A = np.array([cerruti_averages(*kk[:2], kk[2:4], kk[4:6]) for kk in keys])     # (P, 6)
        inv_r, rxx, ryy, rxy, lx, ly = A.T
        c = 1.0 / (2.0 * np.pi)
        static = {"zz": (1.0 - nu) * c * inv_r, "xx": c * (inv_r - nu * rxx),
                  "zx": (1.0 - 2.0 * nu) * 0.5 * c * lx}
        names = ["1", "cc", "c"]
        if comps == "xyz":
            static.update(yy=c * (inv_r - nu * ryy), xy=-nu * c * rxy, zy=(1.0 - 2.0 * nu) * 0.5 * c * ly)
            names += ["cs", "s"]
        vals = {nm: np.repeat(v[None, :].astype(complex), S.size, axis=0) for nm, v in static.items()}
        dyn = ~zero
        if np.any(dyn):
            Sd = S[dyn]
            k, w = self._contour(keys, Sd, kmax_factor)
            H = lamb.angular_components(k, keys, names)
            Hss = H["1"] - H["cc"]
            wk = (w * k)[None, :] / (4.0 * np.pi ** 2)
            res = {nm: np.empty((Sd.size, keys.shape[0]), dtype=complex) for nm in static}
            step = max(1, _KERNEL_BLOCK // k.size)
            for i in range(0, Sd.size, step):
                sl = slice(i, i + step)
                kzz = lamb.kernel(k, Sd[sl], eta, nu) * wk
                krr, ktt, kc = (kk * wk for kk in lamb.tensor_kernels(k, Sd[sl], eta, nu))
                res["zz"][sl] = kzz @ H["1"]
                res["xx"][sl] = krr @ H["cc"] + ktt @ Hss
                res["zx"][sl] = kc @ H["c"]
                if comps == "xyz":
                    res["yy"][sl] = krr @ Hss + ktt @ H["cc"]
                    res["xy"][sl] = -((krr - ktt) @ H["cs"])
                    res["zy"][sl] = kc @ H["s"]
            for nm in static:
                vals[nm][dyn] += res[nm]
        return vals
