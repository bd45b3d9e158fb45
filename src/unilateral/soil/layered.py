"""Horizontally layered (visco)elastic soil: surface flexibilities of patches in the Laplace domain.

A stack of horizontal layers (thickness ``h_j``, shear modulus ``G_j``, Poisson's ratio ``nu_j``,
density ``rho_j``, material damping ``xi_j``) rests on a homogeneous half-space or on a rigid base.
:meth:`Layered.surface_flexibility` returns the same quantity as
:meth:`.HalfSpace.surface_flexibility`: the displacement averaged over receiver patch ``i`` per unit
total force uniformly spread on source patch ``j`` (``z`` positive down), vertical (``"z"``) or with
the horizontal components (``"xz"``, ``"xyz"``), for Laplace ``s`` with ``Re s >= 0``.

Method: exact stiffness matrices on a deformed wavenumber contour
------------------------------------------------------------------
The surface kernel ``G_hat(k, s)`` (2-D Fourier transform of the vertical surface displacement per
unit vertical force; it depends on ``|k|`` only) is the ``zz`` entry of the inverse of the surface
stiffness of the stack, obtained by condensing, from the base upwards, the *exact* 4 x 4 P-SV
stiffness matrix of every layer (Kausel & Roesset 1981, Bull. Seism. Soc. Am. 71, 1743) and the
exact 2 x 2 stiffness of the half-space (or a fixed bottom for a rigid base). The other entries of
that inverse are the radial and the vertical/radial coupling kernels; the transverse (SH, Love)
kernel comes from the exact 2 x 2 SH layer stiffnesses, condensed the same way. They are combined
with the angular factors ``cos^2``, ``cos sin``, ``cos``, ``sin`` of
:func:`.lamb.angular_components` exactly as :class:`.HalfSpace` combines Lamb's kernels. The patch
flexibilities are then

    Phi_ij(s) = Phi^(1)_ij(s) + 1/(4 pi^2) int_C [G_hat(k, s) - G_hat^(1)(k, s)] H_ij(k) k dk,

where ``^(1)`` is the homogeneous half-space made of the *top layer's* material (computed by
:class:`.HalfSpace`, statics in closed form) and ``H_ij`` are the ``s``-independent angular factors
of rectangle pairs (:func:`.lamb.angular`). The bracket decays like ``exp(-2 k h_1)``: the
wavenumber truncation is set by the top layer's thickness, not by the patch size, and the singular
near field of small patches is entirely in the closed-form half-space part.

Layer stiffness. In every layer the P-SV solutions are written with *normalised* exponentials
(``exp(-alpha z)``, ``exp(-alpha (h - z))`` ...; all ``|.| <= 1``, so thick layers and large ``k``
neither overflow nor lose digits) and, instead of the P wave itself, with the divided difference
``(P - S)/(alpha - beta)``, whose coefficients were reduced by hand to forms such as
``(alpha + beta)/((k + beta)(1 - eta))`` that stay finite as ``s -> 0``. The basis therefore goes over
continuously into the static (Jordan) basis ``{e^{-kz}, k z e^{-kz}}``: ``s = 0`` is computed by the
same code, with no cancellation, and a layer on a rigid base has its static flexibility.

Why this and not the thin-layer method (TLM, Kausel 1981; Kausel & Peek 1982):

* accuracy for complex ``s``: the stiffness matrices are exact for any complex ``s`` and ``k``, so
  the only errors are quadrature errors (measured ~1e-9 relative; the kernels of a homogeneous stack
  reproduce Lamb's to 1e-13); the TLM has an ``O((k h)^2)``
  discretisation error in every sublayer, which for the near field of a patch of side ``a`` needs
  sublayers ``<< a`` throughout the depth reached by the load;
* half-space termination: exact here (the half-space stiffness has the same branch points as Lamb's
  problem, handled by the same contour as :mod:`.lamb`); the TLM needs a paraxial boundary or PMLs,
  whose stretching depends on the frequency and which fail as ``s -> 0`` (statics and creep);
* ``s -> 0``: continuous here (see above); the TLM with a PML is not;
* cost: per ``s``, ``n_k ~ 10^3`` nodes times ``n_layers`` layer matrices (two closed-form 2 x 2
  solves each, see below), plus one ``(n_s x n_k) @ (n_k x P)`` product with the ``P`` distinct pair
  geometries (about ``m`` on a grid) whose angular factors are shared by all ``s``. The TLM's
  closed-form modal sums are cheaper for *point* loads, but for rectangle pairs they would still
  need a wavenumber integral (no closed form of a rectangle's modal sum).

The price of the exact method is the contour. For a homogeneous half-space all singularities of the
integrand lie in the 2nd and 4th quadrants (see :mod:`.lamb`), but a layer also has *evanescent*
modes: complex poles in all four quadrants (for a stratum on a rigid base, ``nu = 0.3``, we located
one at ``k h = 1.45 + 2.57 i`` statically and one at ``k h = 1.96 + 0.55 i`` for ``omega h/c_s = 7.6``:
they come closer to the real axis as the frequency grows). The contour here is therefore the wedge
``k = x (1 + 0.3 i)`` capped at a height ``Y = min(3/D, y_c / h_max)`` (``D`` the largest pair extent,
``h_max`` the thickest layer, ``y_c = 0.25`` by default): high enough to pass well above the real
propagating-mode poles of ``s = i omega`` (surface waves, which move into the 4th quadrant for
``Re s > 0``), low enough to stay below the evanescent poles. The tests check that halving ``Y``
changes nothing. Backward (negative group velocity) modes, which move into the 1st quadrant, can
exist in narrow frequency bands of some profiles; at such ``s = i omega`` the result is the limit from
``Re s > 0`` only if ``Y`` lies below them - a known limitation (give such a profile a little
material damping, or ``s`` a small positive real part). The tests and docs/theory.md give the
measured margins (halving ``Y`` changes < 1.2e-7 up to ``omega h/c_s = 20``; doubling it crosses
the pole above, an 8 % change).

Implementation and speed. The kernels are evaluated by one compiled loop over ``(s, k)``
(:func:`.layered_kernels._kernel_loop`, numba, compiled on first use and cached on disk) with
scalars only: the layer's 4 x 4 ``K = T D^-1`` is split, by the layer's mirror symmetry, into its
symmetric and antisymmetric 2 x 2 parts (:func:`.layered_kernels._layer_point`), and every inverse
is a closed-form 2 x 2 one; the groups of ``s`` sharing one truncation are evaluated in blocks of at most ``_BLOCK`` ``(s, k)``
entries, so no large temporary is formed. The original batched numpy formulation (``np.stack`` of
(ns, nk, 4, 4) arrays and LAPACK solves) is kept as the reference (:meth:`Layered._kernels_reference`):
the two agree to <= 6e-13 relative, entry by entry, for ``k h >= 0.015``
(``tests/test_soil_layered.py``); for ``k h << 1`` the condensation of the stiffness formulation
loses about ``log10(1/(k h))`` digits whatever the algebra, and both paths err by ~1e-11 against
Lamb's kernels at ``k h = 5e-4``. Measured on the example ``unilateral example footings``
(``cq_weights(600, 0.01, "bdf2")`` of its layered soil, 4808 values of ``s``, 11 patches; 2 shared
cores, load average 1.0-2.2, medians of 3 in three alternating sessions): the layered part
(:meth:`Layered._difference`) went from 12.9-14.2 s to 1.15-1.22 s (11-12x), the whole
``cq_weights`` from 14.0-16.4 s to 2.6-3.3 s (about 5x; the remaining time is mostly the
closed-form half-space part, :class:`.HalfSpace`); the compiled loop costs about 0.4 us per
``(s, k)`` for one layer on a half-space, mostly complex ``sqrt`` and ``exp``. First use compiles
it (2.7 s once; later processes load it from the cache in 0.3 s).

Damping: each layer is a :class:`.HalfSpace` material, so ``damping`` (``xi``), ``damping_model``
(``"constant_q"`` or ``"kelvin_voigt"``) and ``omega_ref`` have exactly the meaning of
:meth:`.HalfSpace.modulus`; ``nu`` is kept constant. Identical materials give identical results.

References
----------
Kausel, E. & Roesset, J. M. (1981). Stiffness matrices for layered soils. BSSA 71(6), 1743-1761.
Kausel, E. (2006). *Fundamental Solutions in Elastodynamics*. Cambridge University Press.
Kausel, E. & Peek, R. (1982). Dynamic loads in the interior of a layered stratum: an explicit
solution. BSSA 72(5), 1459-1481.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V
from . import lamb, layered_kernels
from .halfspace import HalfSpace, component_blocks, laplace_points
from .patches import RectangularPatches, pair_table
from .layer_ranges import check_contour_nodes, check_modulus, check_thickness

__all__ = ["Layered"]

_LAYER_KEYS = {"thickness", "G", "Vs", "nu", "rho", "damping"}
_NU_MAX = 0.499         # above: the P-SV basis degenerates as eta = G/(lambda + 2G) -> 0 (see _layer_material)
_CHUNK = 2_000_000      # complex (s, k) entries per group of s sharing one truncation (sets the results)
_BLOCK = 65_536         # complex (s, k) entries per evaluation block of a group (speed only)
_SIG_FACTOR = 1.5       # k_max = _SIG_FACTOR max|s/c_s| + 12/h_1 (beyond the slowest wave: exp decay)


def _layer_material(j, d, damping_model, omega_ref):
    """Validate one layer dict; return (thickness, HalfSpace material)."""
    where = f"layers[{j}]"
    if not isinstance(d, dict):
        raise TypeError(f"{where} must be a dict with keys thickness, G (or Vs), nu, rho[, damping], "
                        f"got {V.describe(d)}")
    unknown = set(d) - _LAYER_KEYS
    if unknown:
        raise ValueError(f"{where} has unknown key(s) {sorted(unknown)}; allowed: {sorted(_LAYER_KEYS)}")
    for key in ("thickness", "nu", "rho"):
        if key not in d:
            raise ValueError(f"{where} is missing the key {key!r}")
    if ("G" in d) == ("Vs" in d):
        raise ValueError(f"{where} needs exactly one of the keys 'G' and 'Vs'")
    h = check_thickness(f"{where}['thickness']", _positive(f"{where}['thickness']", d["thickness"]))
    rho = _positive(f"{where}['rho']", d["rho"])
    G = check_modulus(where, _positive(f"{where}['G']", d["G"]) if "G" in d else None,
                      _positive(f"{where}['Vs']", d["Vs"]) if "Vs" in d else None, rho)
    nu = _number(f"{where}['nu']", d["nu"])
    if not 0.0 <= nu < 0.5:
        raise ValueError(f"{where}['nu'] must lie in [0, 0.5), got {nu!r}")
    if nu > _NU_MAX:
        # measured error of the kernels against Lamb's: 1e-11 at nu = 0.49, 1e-10 at 0.499, 8e-7 at
        # 0.4999 (it grows like 1/eta^2): the P-SV matrices become singular as lambda + 2G -> oo
        raise ValueError(f"{where}['nu'] = {nu!r} > {_NU_MAX}: nearly incompressible layers make the "
                         f"P-SV stiffness matrices singular (lambda + 2G -> oo); use nu <= {_NU_MAX}")
    xi = _number(f"{where}['damping']", d.get("damping", 0.0))
    if not (np.isfinite(xi) and xi >= 0.0):
        raise ValueError(f"{where}['damping'] must be >= 0, got {xi!r}")
    return h, HalfSpace(G, nu, rho, damping=xi, damping_model=damping_model, omega_ref=omega_ref)


def _number(name, value):
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number, got {V.describe(value)}") from None
    if not np.isfinite(out):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return out


def _positive(name, value):
    out = _number(name, value)
    if not out > 0.0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return out


def _shc(x):
    """``sinh(x)/x`` (complex ``x``), 1 at 0."""
    small = np.abs(x) < 1e-4
    xs = np.where(small, 1.0, x)
    return np.where(small, 1.0 + x * x / 6.0, np.sinh(xs) / xs)


class Layered:
    """Horizontally layered soil on a homogeneous half-space or on a rigid base.

    Parameters
    ----------
    layers : sequence of dict
        From the surface down. Keys: ``thickness`` (m, > 0), ``G`` (Pa, > 0) *or* ``Vs`` (m/s, > 0,
        then ``G = rho Vs^2``), ``nu`` (``0 <= nu <= 0.499``), ``rho`` (kg/m^3, > 0), optional ``damping``
        (material damping ratio ``xi >= 0``, default 0). Unknown keys are refused.
    halfspace : HalfSpace or None
        The underlying half-space; ``None`` is a rigid base (fixed bottom).
    damping_model, omega_ref : optional
        As in :class:`.HalfSpace`; by default those of ``halfspace`` (or ``"constant_q"`` and
        ``2 pi`` rad/s for a rigid base). Giving values different from the half-space's is refused:
        one correspondence principle for the whole profile.

    Attributes
    ----------
    thickness : (n,) float ndarray, m
    materials : list of HalfSpace
        One per layer (carries ``G, nu, rho, damping`` and :meth:`.HalfSpace.modulus`).
    halfspace : HalfSpace or None

    Notes
    -----
    See the module docstring for the method, its accuracy and its limitation (backward modes).
    """

    def __init__(self, layers, halfspace=None, *, damping_model=None, omega_ref=None):
        if halfspace is not None and not isinstance(halfspace, HalfSpace):
            raise TypeError(f"halfspace must be a HalfSpace or None (rigid base), got {V.describe(halfspace)}")
        if halfspace is not None:
            for name, given, own in (("damping_model", damping_model, halfspace.damping_model),
                                     ("omega_ref", omega_ref, halfspace.omega_ref)):
                if given is not None and given != own:
                    raise ValueError(f"{name}={given!r} differs from the half-space's {own!r}")
            damping_model, omega_ref = halfspace.damping_model, halfspace.omega_ref
        damping_model = "constant_q" if damping_model is None else damping_model
        omega_ref = 2 * np.pi if omega_ref is None else omega_ref
        if isinstance(layers, dict) or not hasattr(layers, "__len__"):
            raise TypeError(f"layers must be a list of dicts, got {V.describe(layers)}")
        if len(layers) == 0:
            raise ValueError("layers must hold at least one layer (use HalfSpace for a homogeneous soil)")
        parsed = [_layer_material(j, d, damping_model, omega_ref) for j, d in enumerate(layers)]
        self.thickness = np.array([h for h, _ in parsed])
        self.materials = [m for _, m in parsed]
        self.halfspace = halfspace
        self.damping_model = self.materials[0].damping_model
        self.omega_ref = self.materials[0].omega_ref

    def __repr__(self):
        base = "rigid base" if self.halfspace is None else f"half-space cs={self.halfspace.cs:.4g}"
        return f"Layered({len(self.thickness)} layers, depth {self.thickness.sum():.4g}, {base})"

    # --- helpers -------------------------------------------------------------------------------
    def _all_materials(self):
        return self.materials + ([] if self.halfspace is None else [self.halfspace])

    def _prepare(self, s):
        return laplace_points(s, self._all_materials())

    @staticmethod
    def _material_arrays(mat, sq, zero):
        """``G(s)`` (ns,), ``S = rho s^2/G(s)`` (ns,), ``eta`` for one material."""
        Gs = mat.modulus(sq)
        S = np.zeros(sq.shape, dtype=complex)
        S[~zero] = sq[~zero] ** 2 * mat.rho / Gs[~zero]
        return Gs, S, lamb.eta_of(mat.nu)

    # --- P-SV stiffness: the numpy (batched) formulation, reference of the compiled loop ---------
    @staticmethod
    def _down_basis(k, S, G, eta):
        """Traction-displacement vectors of the two down-going solutions at their origin.

        Returns ``vP, w, vS`` (..., 4) with rows ``(U, W, X, Z)``: the down-going solution of the
        divided-difference type is ``vP D(z) + w e^{-beta z}`` and the S type ``vS e^{-beta z}``.
        Plane strain with ``u_x = U(z) sin kx``, ``u_z = W(z) cos kx``, ``sigma_xz = X sin kx``,
        ``sigma_zz = Z cos kx``.
        """
        al = np.sqrt(k * k + eta * S)
        be = np.sqrt(k * k + S)
        c = 1.0 - eta
        ab = al + be
        vP = np.stack([k * np.ones_like(al), al, -2.0 * G * k * al, -G * (2.0 * k * k + S)], axis=-1)
        w = np.stack([ab / ((k + be) * c),
                      -eta * ab / ((al + k) * c),
                      -G * ab * (1.0 + eta * eta * S / ((al + k) ** 2 * c)),
                      G * S * ab / ((be + k) ** 2 * c)], axis=-1)
        n = 1.0 / (k + be)
        vS = np.stack([be * n, k * n, -G * (2.0 * k * k + S) * n, -2.0 * G * k * be * n], axis=-1)
        return al, be, vP, w, vS

    @classmethod
    def _halfspace_stiffness(cls, k, S, G, eta):
        """(..., 2, 2) stiffness of a half-space surface: forces ``(F_x, F_z)`` for ``(U, W)``."""
        *_, w, vS = cls._down_basis(k, S, G, eta)
        M = np.stack([w, vS], axis=-1)                       # (..., 4, 2), columns Q, S at z = 0
        Dm, Tm = M[..., :2, :], -M[..., 2:, :]
        return np.linalg.solve(np.swapaxes(Dm, -1, -2), np.swapaxes(Tm, -1, -2)).swapaxes(-1, -2)

    @classmethod
    def _layer_stiffness(cls, k, S, G, eta, h):
        """(..., 4, 4) exact P-SV stiffness of a layer, dofs ``(U_top, W_top, U_bot, W_bot)``."""
        al, be, vP, w, vS = cls._down_basis(k, S, G, eta)
        x = 0.5 * (al - be) * h
        big = np.abs(x) > 0.5
        with np.errstate(over="ignore", invalid="ignore"):
            Dh_big = (np.exp(-al * h) - np.exp(-be * h)) / np.where(big, al - be, 1.0)
        Dh = np.where(big, Dh_big, -h * np.exp(-0.5 * (al + be) * h) * _shc(np.where(big, 0.0, x)))
        Eh = np.exp(-be * h)[..., None]
        Dh = Dh[..., None]
        mirror = np.array([1.0, -1.0, -1.0, 1.0])
        Qd0, Sd0 = w, vS                                     # down-going at z = 0
        Qdh, Sdh = vP * Dh + w * Eh, vS * Eh                 # down-going at z = h
        Qu0, Su0 = mirror * Qdh, mirror * Sdh                # up-going at z = 0 (mirror image)
        Quh, Suh = mirror * Qd0, mirror * Sd0                # up-going at z = h
        top = np.stack([Qd0, Sd0, Qu0, Su0], axis=-1)        # (..., 4, 4) rows U W X Z
        bot = np.stack([Qdh, Sdh, Quh, Suh], axis=-1)
        Dm = np.concatenate([top[..., :2, :], bot[..., :2, :]], axis=-2)
        Tm = np.concatenate([-top[..., 2:, :], bot[..., 2:, :]], axis=-2)
        return np.linalg.solve(np.swapaxes(Dm, -1, -2), np.swapaxes(Tm, -1, -2)).swapaxes(-1, -2)

    def _surface_stiffness(self, k, mats):
        """(ns, nk, 2, 2) surface stiffness of the stack, condensed from the base up.

        ``mats``: list of ``(Gs, S, eta)`` per layer (then the half-space), arrays (ns,).
        """
        kk = k[None, :]
        Kb = None
        if self.halfspace is not None:
            Gs, S, eta = mats[-1]
            Kb = self._halfspace_stiffness(kk, S[:, None], Gs[:, None], eta)
        for j in range(len(self.thickness) - 1, -1, -1):
            Gs, S, eta = mats[j]
            K = self._layer_stiffness(kk, S[:, None], Gs[:, None], eta, self.thickness[j])
            K11, K12, K21, K22 = K[..., :2, :2], K[..., :2, 2:], K[..., 2:, :2], K[..., 2:, 2:]
            if Kb is None:
                Kb = K11
            else:
                Kb = K11 - K12 @ np.linalg.solve(K22 + Kb, K21)
        return Kb

    @staticmethod
    def _sh_layer(k, S, G, h):
        """(..., 2, 2) exact SH (Love) stiffness of a layer, dofs ``(V_top, V_bot)``.

        ``G beta/(1 - E^2) [[1 + E^2, -2E], [-2E, 1 + E^2]]``, ``E = exp(-beta h)`` (= ``G beta [coth,
        -csch; -csch, coth](beta h)``, written with ``|E| <= 1``; ``-> G/h [[1, -1], [-1, 1]]`` as
        ``beta h -> 0``).
        """
        be = np.sqrt(k * k + S)
        E = np.exp(-be * h)
        x = -2.0 * be * h
        small = np.abs(x) < 1e-8
        xs = np.where(small, 1.0, x)
        # G beta / (1 - E^2) = -2 G h / (x (exp(x) - 1)/x ... ) written with expm1 and its limit
        ratio = np.where(small, 1.0 / (2.0 * h), be / np.where(small, 1.0, -np.expm1(xs)))
        c = G * ratio
        return c * (1.0 + E * E), -2.0 * c * E

    def _surface_flexibility_kernels(self, k, sq, want_sh):
        """``(F, g_tt)``: the (ns, nk, 2, 2) P-SV surface flexibility (``(U, W)`` per ``(F_x, F_z)``)
        and, if ``want_sh``, the (ns, nk) SH surface flexibility (else None).

        The original numpy formulation (batched 4 x 4 LAPACK solves; large temporaries), kept as the
        reference of :func:`.layered_kernels._kernel_loop` (:meth:`_kernels_reference`, used by the
        tests only).
        """
        zero = sq == 0
        mats = [self._material_arrays(m, sq, zero) for m in self._all_materials()]
        Kb = self._surface_stiffness(k, mats)
        det = Kb[..., 0, 0] * Kb[..., 1, 1] - Kb[..., 0, 1] * Kb[..., 1, 0]
        F = np.stack([np.stack([Kb[..., 1, 1], -Kb[..., 0, 1]], -1),
                      np.stack([-Kb[..., 1, 0], Kb[..., 0, 0]], -1)], -2) / det[..., None, None]
        if not want_sh:
            return F, None
        kk = k[None, :]
        kb = None
        if self.halfspace is not None:
            Gs, S, _ = mats[-1]
            kb = Gs[:, None] * np.sqrt(kk * kk + S[:, None])
        for j in range(len(self.thickness) - 1, -1, -1):
            Gs, S, _ = mats[j]
            d, o = self._sh_layer(kk, S[:, None], Gs[:, None], self.thickness[j])
            kb = d if kb is None else d - o * o / (d + kb)
        return F, 1.0 / kb

    def kernel(self, k, s):
        """Vertical surface kernel ``G_hat(k, s)``: 2-D Fourier transform of ``u_z`` per unit force.

        Parameters
        ----------
        k : (nk,) complex array, 1/m
            Wavenumbers (``|k|`` of the 2-D wave vector; complex on a contour).
        s : complex scalar or (ns,) array, ``Re s >= 0``, ``Im s >= 0`` (no conjugation here)

        Returns
        -------
        (ns, nk) complex, m^3/N
            ``-> (1 - nu)/(G k)`` for a half-space at ``s = 0``.
        """
        return self.kernels(k, s, sh=False)["zz"]

    def kernels(self, k, s, *, sh=True):
        """Surface Green's tensor kernels in the wavenumber domain (conventions of :mod:`.lamb`).

        Parameters
        ----------
        k : (nk,) complex array, 1/m
        s : complex scalar or (ns,) array, ``Re s >= 0``, ``Im s >= 0``
        sh : bool
            Also compute the SH kernel ``tt``.

        Returns
        -------
        dict of (ns, nk) complex, m^3/N
            ``zz`` (vertical), ``rr`` (radial, P-SV), ``tt`` (transverse, SH) and ``c`` (the
            vertical/radial coupling ``K_c`` of :func:`.lamb.tensor_kernels`, static half-space value
            ``(1 - 2 nu)/(2 G k)``), *not* reduced by their static parts. For a homogeneous half-space
            ``G zz = kernel + (1-nu)/k``, ``G rr = K_rr + (1-nu)/k``, ``G tt = K_tt + 1/k``,
            ``G c = K_c + (1-2nu)/(2k)`` of :mod:`.lamb`.
        """
        k = np.atleast_1d(np.asarray(k, dtype=complex))
        sq = np.atleast_1d(np.asarray(s, dtype=complex))
        return self._kernels_compiled(k, sq, sh)

    def _kernels_compiled(self, k, sq, sh):
        """:meth:`kernels` (``k`` (nk,), ``sq`` (ns,) complex) by the compiled loop
        :func:`.layered_kernels._kernel_loop`."""
        zero = sq == 0
        mats = [self._material_arrays(m, sq, zero) for m in self._all_materials()]
        S = np.array([m[1] for m in mats], dtype=complex).reshape(len(mats), sq.size)
        G = np.array([m[0] for m in mats], dtype=complex).reshape(len(mats), sq.size)
        eta = np.array([m[2] for m in mats], dtype=float)
        shape = (sq.size, k.size)
        zz, rr, c = np.empty(shape, complex), np.empty(shape, complex), np.empty(shape, complex)
        tt = np.empty(shape if sh else (0, 0), complex)
        try:
            layered_kernels.compiled()(np.ascontiguousarray(k), (S, G, eta),
                        (np.ascontiguousarray(self.thickness, dtype=float), self.halfspace is not None, bool(sh)),
                        (zz, rr, c, tt))
        except ZeroDivisionError:
            # numba raises on a complex x/0 (e.g. G(0) = 0 of constant-Q damping at s = 0, refused
            # by surface_flexibility): the numpy formulation decides (LinAlgError or inf/nan), as before
            return self._kernels_reference(k, sq, sh=sh)
        out = {"zz": zz, "rr": rr, "c": c}
        if sh:
            out["tt"] = tt
        return out

    def _kernels_reference(self, k, s, *, sh=True):
        """:meth:`kernels` by the original numpy formulation (batched arrays; kept as the reference of
        the compiled loop for the tests)."""
        k = np.atleast_1d(np.asarray(k, dtype=complex))
        sq = np.atleast_1d(np.asarray(s, dtype=complex))
        F, gtt = self._surface_flexibility_kernels(k, sq, sh)
        out = {"zz": F[..., 1, 1], "rr": F[..., 0, 0], "c": -0.5 * (F[..., 1, 0] + F[..., 0, 1])}
        if sh:
            out["tt"] = gtt
        return out

    # --- public API ----------------------------------------------------------------------------
    def surface_flexibility(self, patches: RectangularPatches, s, *, components="z", kmax_factor=1.0,
                            height_factor=1.0) -> np.ndarray:
        """Surface flexibility matrix ``Phi(s)`` of rectangular patches on the layered soil.

        Same definition, sign conventions and layout as :meth:`.HalfSpace.surface_flexibility`:
        ``Phi_ij(s)`` is the displacement component of row ``i`` averaged over its patch per unit total
        force of the component of column ``j`` uniformly distributed on its patch (``z`` down;
        Laplace transforms; symmetric).

        Parameters
        ----------
        patches : RectangularPatches
            ``m`` patches with positive sides.
        s : complex scalar or (ns,) array, 1/s
            Laplace variable(s), ``Re s >= 0``; ``s = i omega`` is the frequency-domain flexibility
            (limit from ``Re s > 0``); ``s = 0`` the static flexibility (also on a rigid base).
        components : {"z", "xz", "xyz"}
            ``"z"``: vertical, (ns, m, m). ``"xz"``: (ns, 2m, 2m), x block then z block. ``"xyz"``:
            (ns, 3m, 3m), x, y, z blocks. The horizontal parts need the tensor version of
            :class:`.HalfSpace` (its ``components`` argument).
        kmax_factor : float
            Multiplies the wavenumber truncation (convergence studies).
        height_factor : float
            Multiplies the height ``Y`` of the contour (convergence studies; see module docstring).

        Returns
        -------
        Phi : (ns, m, m), (ns, 2m, 2m) or (ns, 3m, 3m) complex, m/N
            ``Phi(conj s) = conj Phi(s)``; real for real ``s``.

        Notes
        -----
        Truncation ``k_max = 1.5 max_j |s/c_s,j| + 12/h_1`` per ``s`` (``h_1`` the top layer's
        thickness): the integrand is the difference with the top material's half-space, whose poles
        (surface waves) lie below the slowest wavenumber ``max_j |s/c_s,j|`` and which decays like
        ``exp(-2 k h_1)`` beyond it. Horizontal components: P-SV radial and coupling kernels from the same
        condensed stiffness, SH (Love) kernel from the exact 2 x 2 SH layer stiffness, angular factors
        of :func:`.lamb.angular_components`.
        """
        comps = V.choice("components", components, {"z", "xz", "xyz"})
        if not isinstance(patches, RectangularPatches):
            raise TypeError(f"patches must be RectangularPatches, got {V.describe(patches)}")
        if np.any(patches.sizes <= 0):
            raise ValueError("surface_flexibility needs patches with positive sides (the self-flexibility "
                             "of a point or line is infinite)")
        kmax_factor = V.positive_float("kmax_factor", kmax_factor)
        height_factor = V.positive_float("height_factor", height_factor)
        sq, flip, zero = self._prepare(s)
        top = self.materials[0]
        # the top material's half-space (closed-form statics; handles the near field exactly)
        base = (top.surface_flexibility(patches, sq) if comps == "z"
                else top.surface_flexibility(patches, sq, components=comps))
        keys, index = pair_table(patches, patches, symmetric=True)
        vals = self._difference(keys, sq, zero, kmax_factor, height_factor, comps)
        vals = {nm: v[:, index] for nm, v in vals.items()}
        diff = vals["zz"] if comps == "z" else component_blocks(vals, patches, comps)
        diff[flip] = np.conj(diff[flip])
        base[flip] = np.conj(base[flip])
        out = base + diff
        real = sq.imag == 0
        out[real] = out[real].real       # exact property; drops quadrature noise (~1e-9) of the contour
        return out

    # --- engine --------------------------------------------------------------------------------
    def contour(self, sq, D, kmax_factor=1.0, height_factor=1.0):
        """Nodes and weights ``(k, w)`` of the wavenumber contour for Laplace values ``sq`` (ns,).

        Wedge ``k = x (1 + 0.3 i)`` from 0 in 12-point Gauss-Legendre panels, geometric (ratio 2) down
        to ``x = 0.25 min(|sigma_p|_min, 1/h_tot)``, then the line ``Im k = Y = min(3/D, 0.25/h_max)``
        (times ``height_factor``) in panels of width ``2 Y`` up to ``k_max``.

        Parameters
        ----------
        sq : (ns,) complex, 1/s
            Laplace values (``Im >= 0``).
        D : float, m
            Largest pair extent (:func:`.lamb.pair_extent`).
        kmax_factor, height_factor : float
            As in :meth:`surface_flexibility` (more than ``layer_ranges.MAX_CONTOUR_NODES`` nodes, a top
            layer far thinner than the footprint, are refused before they are allocated).

        Returns
        -------
        k, w : (nk,) complex, 1/m: nodes in increasing ``Re k`` and weights (including ``dk/dx``)
        """
        zero = sq == 0
        sig = np.zeros(sq.size)
        for mat in self._all_materials():
            Gs = mat.modulus(sq[~zero])
            sig[~zero] = np.maximum(sig[~zero], np.abs(sq[~zero] * np.sqrt(mat.rho / Gs)))
        sig_lo = np.inf
        for mat in self._all_materials():
            if np.any(~zero):
                Gs = mat.modulus(sq[~zero])
                sig_lo = min(sig_lo, float(np.min(np.abs(sq[~zero] * np.sqrt(mat.rho / Gs)))
                                           * np.sqrt(lamb.eta_of(mat.nu))))
        htot = float(self.thickness.sum())
        sig_lo = min(sig_lo, 1.0 / htot)
        Y = height_factor * min(3.0 / D, 0.25 / float(self.thickness.max()))
        xc = Y / lamb.WEDGE
        edges = [0.0, min(0.25 * sig_lo, xc)]
        while edges[-1] < xc * (1 - 1e-12):
            edges.append(min(2.0 * edges[-1], xc))
        kmax = kmax_factor * (_SIG_FACTOR * sig.max() + 12.0 / self.thickness[0])
        n = max(1, int(np.ceil((kmax - xc) / (2.0 * Y))))
        check_contour_nodes(self.thickness, 12 * (n + len(edges) - 1), sq.size, D)     # before it is allocated
        flat = np.linspace(xc, xc + n * 2.0 * Y, n + 1)
        ks, ws = [], []
        for e, wedge in ((np.array(edges), True), (flat, False)):
            lo, hi = e[:-1, None], e[1:, None]
            x = (0.5 * (lo + hi) + 0.5 * (hi - lo) * lamb._GL_X[None, :]).ravel()
            wx = (0.5 * (hi - lo) * lamb._GL_W[None, :]).ravel()
            if wedge:
                ks.append(x * (1.0 + 1j * lamb.WEDGE))
                ws.append(wx * (1.0 + 1j * lamb.WEDGE))
            else:
                ks.append(x + 1j * Y)
                ws.append(wx.astype(complex))
        return np.concatenate(ks), np.concatenate(ws)

    def _difference(self, keys, sq, zero, kmax_factor, height_factor, comps="z"):
        """{component: (ns, P)}: ``1/(4 pi^2) int [G_hat - G_hat^(1)] H k dk`` over the contour.

        Components as in :meth:`.HalfSpace.surface_flexibility` (odd ones ``zx``, ``zy``, ``xy`` at
        ``|dx|, |dy|``, unsigned). Each ``s`` uses the prefix of the contour up to its own ``k_max``;
        an ``s`` for which the top layer is opaque, ``exp(-2 h_1 Re sigma_p1) < 1e-20`` (``sigma_p1``
        bounds ``Re alpha_1`` from below on the real ``k`` axis), has a zero difference: the waves
        reflected below the top layer are below round-off.
        """
        out_names = {"z": ["zz"], "xz": ["zz", "xx", "zx"], "xyz": ["zz", "xx", "zx", "yy", "xy", "zy"]}[comps]
        out = {nm: np.zeros((sq.size, keys.shape[0]), dtype=complex) for nm in out_names}
        top = self.materials[0]
        G1, S1, eta1 = self._material_arrays(top, sq, zero)
        nu1, h1 = top.nu, float(self.thickness[0])
        sig_p1 = np.sqrt(eta1 * S1)
        sig_p1 = np.where(sig_p1.real < 0, -sig_p1, sig_p1)
        active = np.flatnonzero(2.0 * h1 * sig_p1.real < 46.0)            # exp(-46) = 1e-20
        if active.size == 0:
            return out
        sig = np.zeros(sq.size)
        for mat in self._all_materials():
            _, S, _ = self._material_arrays(mat, sq, zero)
            sig = np.maximum(sig, np.abs(np.sqrt(S)))
        kmax_s = kmax_factor * (_SIG_FACTOR * sig + 12.0 / h1)
        D = float(lamb.pair_extent(keys).max())
        k, w = self.contour(sq[active], D, kmax_factor, height_factor)
        names = ["1"] if comps == "z" else (["1", "cc", "c"] if comps == "xz" else ["1", "cc", "c", "cs", "s"])
        H = {"1": lamb.angular(k, keys)} if comps == "z" else lamb.angular_components(k, keys, names)
        if comps != "z":
            H["ss"] = H["1"] - H["cc"]
        wk_all = (w * k)[None, :] / (4.0 * np.pi ** 2)
        order = active[np.argsort(kmax_s[active])]
        i = 0
        while i < order.size:
            nk = min(k.size, int(np.searchsorted(k.real, kmax_s[order[i]])) + 12)
            step = max(1, _CHUNK // (4 * nk))
            sl = order[i:i + step]
            nk = min(k.size, int(np.searchsorted(k.real, kmax_s[sl].max())) + 12)
            i += sl.size
            kn, wk, kk = k[:nk], wk_all[:, :nk], k[None, :nk]
            Hn = {nm: v[:nk] for nm, v in H.items()}
            # the group ``sl`` fixes the truncation (nk) of its s; it is evaluated in blocks of rows
            # small enough for the temporaries to stay in cache (rows are independent)
            rows = max(1, _BLOCK // nk)
            for b in range(0, sl.size, rows):
                sb = sl[b:b + rows]
                g = self.kernels(kn, sq[sb], sh=comps != "z")
                Gi = G1[sb, None]
                dzz = (g["zz"] - (lamb.kernel(kn, S1[sb], eta1, nu1) + (1.0 - nu1) / kk) / Gi) * wk
                out["zz"][sb] = dzz @ Hn["1"]
                if comps == "z":
                    continue
                krr, ktt, kc = lamb.tensor_kernels(kn, S1[sb], eta1, nu1)
                drr = (g["rr"] - (krr + (1.0 - nu1) / kk) / Gi) * wk
                dtt = (g["tt"] - (ktt + 1.0 / kk) / Gi) * wk
                dc = (g["c"] - (kc + (0.5 - nu1) / kk) / Gi) * wk
                out["xx"][sb] = drr @ Hn["cc"] + dtt @ Hn["ss"]
                out["zx"][sb] = dc @ Hn["c"]
                if comps == "xyz":
                    out["yy"][sb] = drr @ Hn["ss"] + dtt @ Hn["cc"]
                    out["xy"][sb] = -((drr - dtt) @ Hn["cs"])
                    out["zy"][sb] = dc @ Hn["s"]
        return out
