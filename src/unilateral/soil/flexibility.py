"""The soil's dynamic flexibility ``Phi(s)`` under the footings' contact points, and its weights.

:class:`SoilFlexibility` wraps the soil kernels of :mod:`unilateral.soil` (half-space, layered,
cones, impedances, Kelvin springs, rational fits, a user's callable) as the (m, m) flexibility of
the contact points (downward surface displacement per unit downward force), with its static value,
its poles where it is rational (:class:`SoilPoles`) and its convolution-quadrature weights;
:func:`facet_normals` gives the facets of a polygonal friction cone. The problem of a structure on
it is :class:`~unilateral.soil.foundation_model.FoundationModel`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _validate as V

__all__ = ["SoilFlexibility", "SoilPoles", "facet_normals"]

#: Points on the circle per soil weight (:meth:`SoilFlexibility.cq_weights`): each is an evaluation
#: of the soil's kernel, the costly part of a half-space's weights.
SOIL_FFT_POINTS = 6
#: The algebraic tail of a soil's weights (:meth:`SoilFlexibility.cq_weights`) is accepted when
#: its self-check estimates the error of the step responses below this fraction of the largest
#: static flexibility (the estimate is 20 to 40 times the error measured against all weights).
TAIL_TOL = 3e-4
#: ``W_j ~ A j^-TAIL_POWER`` beyond the computed weights: the impulse response of a 3-D elastic
#: half-space (layered or not) decays as ``t^-3`` (``Phi(s) - Phi(0) - s Phi'(0) ~ s^2 log s``).
TAIL_POWER = 3.0


#: The end of a half-space soil's description per ``components``.
_COMPONENT_LABELS = {"z": "", "xz": ", x and z", "xyz": ", x, y and z"}


def facet_normals(horizontal: int, facets=None) -> np.ndarray:
    """The unit normals ``d_k`` (facets, horizontal) of the friction facets of a patch, in pairs.

    One horizontal direction (a plane footing): the pair ``+x, -x`` (``facets`` None or 2). Two (a
    footing in plan): the polygonal Coulomb cone of ``facets`` facets (even, >= 4; default 8), facet
    ``k`` of ``th_k = 2 pi k / facets`` from x (as
    :func:`unilateral.structure.elements3d.facet_directions`), ordered in opposite pairs
    ``(k, k + facets/2)``, ``k = 0 .. facets/2 - 1``: ``facets=4`` gives ``+x, -x, +y, -y``.
    Components within 1e-12 of 0 or +-1 are made exact, and opposite facets exactly opposite.
    """
    if horizontal == 1:
        if facets not in (None, 2):
            raise ValueError(f"facets={facets!r}: a footing that slides along x has the two faces +x, -x; give "
                             "Ty too (footings that slide in plan) for a polygonal friction cone")
        return np.array([[1.0], [-1.0]])
    facets = 8 if facets is None else facets
    if isinstance(facets, bool) or not isinstance(facets, (int, np.integer)) or facets < 4 or facets % 2:
        raise ValueError(f"facets={facets!r} is not valid; give an even int >= 4 (the facets of the polygonal "
                         "friction cone in plan come in opposite pairs)")
    half = int(facets) // 2
    order = np.ravel(np.column_stack([np.arange(half), np.arange(half) + half]))
    th = 2.0 * np.pi * order / int(facets)
    d = np.column_stack([np.cos(th), np.sin(th)])
    for exact in (0.0, 1.0, -1.0):
        d[np.abs(d - exact) < 1e-12] = exact
    d[1::2] = -d[0::2]                  # opposite facets exactly opposite (their columns cancel)
    return d


def _facet_names(facets: int) -> list:
    """The names of a patch's friction facets in the order of :func:`facet_normals` (in plan):
    ``facets=4``: ``slip+``, ``slip-`` (``+-x``), ``slip2+``, ``slip2-`` (``+-y``), as the 3-D friction
    contacts; else ``facet<k>`` (``k`` the facet's number from x)."""
    if facets == 4:
        return ["slip+", "slip-", "slip2+", "slip2-"]
    half = facets // 2
    return [f"facet{k + side * half}" for k in range(half) for side in (0, 1)]


def _real(W) -> np.ndarray:
    """``W`` real if its imaginary part is round-off (the weights of a real kernel)."""
    return np.real_if_close(W) if np.iscomplexobj(W) else W


@dataclass(frozen=True)
class _Weights:
    """Computed soil weights ``W_0 .. W_J`` (J+1, m, m) or diagonals (J+1, m, 1); ``complete``: the
    weights beyond ``J`` are known: ``A j^-TAIL_POWER`` (``tail``, the shape of a weight) or zero
    (``tail`` None)."""

    W: np.ndarray
    complete: bool = False
    tail: np.ndarray | None = None


# ====================================================================== rational soils
@dataclass
class SoilPoles:
    """Pole-residue form ``Phi(s) = P0 + sum_k b_k c_k^T / (s - p_k)`` of a rational soil.

    A pole with ``Im p > 0`` stands for itself and its conjugate (factors ``conj b_k, conj c_k``);
    real poles have real factors (the convention of
    :class:`~unilateral.kernels.PoleResidueKernel`).

    Attributes
    ----------
    poles : (r,) complex, ``Re p < 0``, ``Im p >= 0``, 1/s
    B, Cf : (r, m) complex, residue factors (m/N per second)
    P0 : (m, m) real, ``Phi(inf)``, m/N
    """

    poles: np.ndarray
    B: np.ndarray
    Cf: np.ndarray
    P0: np.ndarray

    def evaluate(self, s) -> np.ndarray:
        """``Phi(s)`` for ``s`` of shape (L,): (L, m, m) complex."""
        s = np.atleast_1d(np.asarray(s, dtype=complex))
        out = np.broadcast_to(self.P0, (s.size,) + self.P0.shape).astype(complex)
        if self.poles.size:
            mult = np.where(self.poles.imag > 0, 2.0, 1.0)
            for p, b, c, k in zip(self.poles, self.B, self.Cf, mult):
                term = np.outer(b, c)[None] / (s - p)[:, None, None]
                if k == 2.0:
                    term = term + np.outer(b.conj(), c.conj())[None] / (s - np.conj(p))[:, None, None]
                out = out + term
        return out

    def static(self) -> np.ndarray:
        """``Phi(0)`` (m, m) real."""
        return self.evaluate(np.zeros(1))[0].real


def _pole_constants(parts, m, starts) -> np.ndarray:
    """``diag(P0_1, P0_2, ...)`` (m, m) of the parts' pole-residue constants."""
    out = np.zeros((m, m))
    for p, a in zip(parts, starts):
        out[a:a + p.m, a:a + p.m] = p.poles.P0
    return out


def _scalar_poles(num, den, where):
    """Poles, residues and constant of ``den(s)/num(s)`` (coefficients lowest power first).

    Returns None if ``num`` has a multiple root (no simple pole-residue form); raises if a root
    lies in ``Re s >= 0`` (the impedance has no static stiffness or is unstable).
    """
    num = np.trim_zeros(np.asarray(num, dtype=float), "b")
    den = np.trim_zeros(np.asarray(den, dtype=float), "b")
    if num.size == 0 or not np.all(np.isfinite(num)):
        raise ValueError(f"{where}: the impedance is zero or not finite")
    if den.size > num.size:
        return None                         # the flexibility grows with s: not a soil
    roots = np.roots(num[::-1]) if num.size > 1 else np.zeros(0, complex)
    if np.any(roots.real >= 0):
        bad = roots[np.argmax(roots.real)]
        raise ValueError(f"{where}: the impedance vanishes at s = {bad:.6g} in Re s >= 0 (no static "
                         "stiffness or an unstable soil); a soil impedance needs E(s) != 0 there")
    scale = max(np.abs(roots).max(initial=0.0), 1e-300)
    if roots.size > 1 and np.min(np.abs(roots[:, None] - roots[None, :])
                                 + np.eye(roots.size) * scale) < 1e-7 * scale:
        return None
    dnum = np.polynomial.polynomial.polyder(num)
    res = np.polynomial.polynomial.polyval(roots, den) / np.polynomial.polynomial.polyval(roots, dnum)
    const = den[-1] / num[-1] if den.size == num.size else 0.0
    return roots.astype(complex), res.astype(complex), float(const)


def _impedance_polynomials(E):
    """``(num, den)`` of a recognised rational impedance ``E(s) = num/den``, or None."""
    from .cones import Cone
    from .impedances import VeletsosVerbic

    if isinstance(E, Cone):
        if E.M_int:
            a = E.z0 / E.c                            # q = a s
            return [E.K, E.K * a, E.dM + E.C * a, E.dM * a], [1.0, a]
        return [E.K, E.C, E.dM], [1.0]
    if isinstance(E, VeletsosVerbic):
        T, b = E.T, E.g2 * E.T
        poly = np.polynomial.polynomial.polymul([1.0, E.c4 * T, E.m3 * T ** 2], [1.0, b])
        poly = poly + np.array([0.0, 0.0, E.g1 * (E.g2 * T) ** 2, 0.0])[: poly.size]
        return E.K0 * poly, [1.0, b]
    if isinstance(E, tuple):
        return [E[0], E[1]], [1.0]
    if isinstance(E, (int, float, np.floating, np.integer)) and not isinstance(E, bool):
        return [float(E)], [1.0]
    return None


def _impedance_callable(E, where):
    """``E(s)`` as a vectorised function returning (L,) complex."""
    if isinstance(E, tuple):
        if len(E) != 2:
            raise ValueError(f"{where}: a Kelvin impedance is a pair (k, c), got {E!r}")
        k = V.positive_float(f"{where} k", E[0])
        c = float(E[1])
        if not (np.isfinite(c) and c >= 0):
            raise ValueError(f"{where}: the dashpot c must be >= 0, got {E[1]!r}")
        return lambda s: k + c * s
    if isinstance(E, (int, float, np.floating, np.integer)) and not isinstance(E, bool):
        k = V.positive_float(where, E)
        return lambda s: np.full(s.shape, k, dtype=complex)
    if callable(E):
        return lambda s: np.asarray(E(s), dtype=complex).reshape(s.shape)
    raise TypeError(f"{where} must be a number k, a pair (k, c), a Cone, a VeletsosVerbic or a "
                    f"callable E(s); got {V.describe(E)}")


# ====================================================================== the soil
class SoilFlexibility:
    """The soil's dynamic flexibility ``Phi(s)`` (m, m) at the contact points.

    ``Phi_ij(s)``: Laplace transform of the downward displacement of the soil surface under contact
    ``i`` per unit downward (compressive) force at contact ``j`` (m/N, or m/kN in kN units).
    Build it with one of the constructors:

    * :meth:`halfspace` - the rigorous (visco)elastic half-space under rectangular patches;
    * :meth:`cones` - cone-type coupled flexibility of patches (delays: not rational);
    * :meth:`impedances` - one impedance ``E_i(s)`` per contact, ``Phi = diag(1/E_i(s))``;
    * :meth:`kelvin` - ``E_i = k_i + s c_i`` (the paper's soil elements);
    * :meth:`rational` - AAA fits (:class:`~unilateral.soil.RationalFit`) of flexibilities;
    * :meth:`callable` - any ``Phi(s)``.

    Parameters
    ----------
    func : callable
        ``func(s)`` for ``s`` (L,) complex, ``Re s > 0``, returns (L, m, m) (or (L,) if m = 1).
    m : int
        Number of contacts.
    static : callable, optional
        ``static() -> (m, m)``: ``Phi(0)``; default ``func(0)``.
    poles : SoilPoles, optional
        The exact pole-residue form of a rational soil (enables ``method="modal"``).
    kelvin : tuple of (m,) arrays, optional
        ``(k, c)`` when ``Phi = diag(1/(k + s c))``.
    diagonal : callable, optional
        ``diagonal(s) -> (L, m)``: the diagonal of ``func(s)`` when it is diagonal (uncoupled
        contacts); the weights are then computed per contact, not for the ``m x m`` matrix.
    description : str

    Attributes
    ----------
    m : int
    is_diagonal : bool
        The contacts are uncoupled (``Phi(s)`` diagonal, given by ``diagonal``).
    is_rational : bool
        The exact pole-residue form is known (``method="modal"`` applies).
    poles : SoilPoles or None
    kelvin : (k, c) or None
    description : str
    """

    def __init__(self, func, m, *, static=None, poles=None, kelvin=None, diagonal=None, description="Phi(s)"):
        if not callable(func):
            raise TypeError(f"func must be callable Phi(s) -> (L, m, m), got {V.describe(func)}")
        m = int(m)
        if m < 1:
            raise ValueError(f"m (the number of contacts) must be >= 1, got {m}")
        self._func, self.m, self._static = func, m, static
        self.poles, self.kelvin, self.description = poles, kelvin, description
        self._diagonal = diagonal
        #: Time (s) after which the soil's impulse response is negligible, or None (unknown): the
        #: truncation hint of :meth:`cq_weights`.
        self.memory = None

    # ------------------------------------------------------------------ evaluation
    def evaluate(self, s) -> np.ndarray:
        """``Phi(s)`` for ``s`` (L,) complex with ``Re s >= 0``: (L, m, m) complex, m/N."""
        s = np.atleast_1d(np.asarray(s, dtype=complex))
        out = np.asarray(self._func(s))
        if self.m == 1 and out.shape == s.shape:
            out = out.reshape(-1, 1, 1)
        if out.shape != (s.size, self.m, self.m):
            raise ValueError(f"the soil flexibility ({self.description}) returned shape {out.shape} for "
                             f"{s.size} values of s; expected ({s.size}, {self.m}, {self.m})")
        if not np.all(np.isfinite(out)):
            k = int(np.argmax(~np.all(np.isfinite(out), axis=(1, 2))))
            raise ValueError(f"the soil flexibility ({self.description}) is not finite at s = {s[k]!r}")
        return out

    __call__ = evaluate

    def static(self) -> np.ndarray:
        """``Phi(0)`` (m, m) real symmetric positive definite: the static flexibility.

        Raises ``ValueError`` if the soil has none (e.g. constant-Q damping creeps: ``G(0) = 0``).
        """
        try:
            value = self._static() if self._static is not None else self.evaluate(np.zeros(1))[0]
        except (ValueError, ZeroDivisionError, FloatingPointError) as exc:
            raise ValueError(f"the soil ({self.description}) has no static flexibility Phi(0): {exc}; "
                             "start from initial='rest' or given values, or use a soil with a finite "
                             "static flexibility") from None
        value = np.asarray(value)
        if value.shape != (self.m, self.m) or not np.all(np.isfinite(value)):
            raise ValueError(f"the soil ({self.description}) has no finite static flexibility Phi(0) "
                             f"(got {V.describe(value)})")
        scale = np.abs(value).max(initial=0.0)
        if np.iscomplexobj(value):
            if np.abs(value.imag).max(initial=0.0) > 1e-10 * scale:
                raise ValueError(f"Phi(0) of the soil ({self.description}) is not real")
            value = value.real
        value = 0.5 * (value + value.T)
        eig = np.linalg.eigvalsh(value)
        if eig[0] <= 1e-12 * max(scale, 1e-300):
            raise ValueError(f"the static flexibility Phi(0) of the soil ({self.description}) must be "
                             f"positive definite; its smallest eigenvalue is {eig[0]:.3g}")
        return value

    def cq_weights(self, N: int, dt: float, rule, **cq_options) -> np.ndarray:
        """Convolution-quadrature weights ``W_0 .. W_N`` (N+1, m, m) real of ``Phi(s)``.

        The impulse response of a soil without creep dies out, so only ``W_0 .. W_J`` are computed,
        by the FFT on a circle with ``L = 6 (J + 1)`` points instead of ``8 (N + 1)`` (the weights
        agree with the full FFT to about 1e-8 of the largest, far below the soil kernel's own 1e-6;
        with ``4 (J + 1)`` their round-off would spoil the checks below). ``J`` starts at
        ``memory / dt`` plus 64 steps (``memory``, s: a hint of the constructor, e.g. three
        Rayleigh-wave travel times across the half-space's patches); the weights beyond ``J`` are

        * zero, if the last eighth of the computed ones is below ``1e-8`` of the largest (their
          round-off floor is about 1e-10 of it): a response that is static once the waves have
          crossed the foundation (Pekeris's vertical point load at ``nu = 1/4``);
        * otherwise ``A j^-3`` (:data:`TAIL_POWER`), the algebraic tail of an elastic half-space or
          layered soil (``Phi(s) - Phi(0) - s Phi'(0) ~ s^2 log s`` at small ``s``), with ``A``
          chosen so that all weights sum to the static flexibility ``Phi(0)`` (their generating
          function at ``zeta = 1``): the step responses tend to the exact static ones. Accepted if
          its self-check passes: the tail fitted at ``J/2`` predicts the computed step responses up
          to ``J`` within :data:`TAIL_TOL` of the largest static flexibility (measured on two
          sliding footings of 10 strips, x and z, against all 4 001 weights: estimates 3.3e-4,
          1.9e-4, 2.9e-5 and errors of the step responses 1.4e-5, 8.6e-6, 1.6e-6 of the static
          flexibility at ``J = 900``, 1000, 1500; the soil kernel itself is accurate to about 1e-6);

        else ``J`` doubles (or becomes ``N`` once ``4 J > N``: all weights cost less than two more
        tries; a creeping soil, e.g. constant-Q damping, or a layer on a rigid base that rings,
        ends there). Weights are kept per ``(dt, rule)`` on this object, so
        that the cases of one analysis (with and without uplift, several loads) evaluate ``Phi(s)``
        once.

        ``cq_options`` (``L``, ``rho``) give the plain :func:`~unilateral.kernels.cq_weights` of all
        ``N + 1`` weights.
        """
        from ..kernels.cq_weights import cq_weights
        from ..rules import get_rule

        rule = get_rule(rule, cq=True)
        N, dt = int(N), float(dt)
        kernel = self.evaluate if self._diagonal is None else self._evaluate_diagonal
        if cq_options:
            return self._expand(_Weights(_real(cq_weights(kernel, N, dt, rule, **cq_options))), N)
        cache = self.__dict__.setdefault("_weights_cache", {})
        key = (dt, rule.name)
        known = cache.get(key)
        if known is None or not (known.complete or known.W.shape[0] >= N + 1):
            memory = getattr(self, "memory", None)
            J = N if memory is None else min(N, int(np.ceil(float(memory) / dt)) + 64)
            while True:
                W = _real(cq_weights(kernel, J, dt, rule, L=SOIL_FFT_POINTS * (J + 1)))
                if J == N:
                    known = _Weights(W)
                    break
                if np.abs(W[J - J // 8:]).max(initial=0.0) <= 1e-8 * np.abs(W).max(initial=0.0):
                    known = _Weights(W, complete=True)
                    break
                tail, estimate = self._algebraic_tail(W)
                if estimate <= TAIL_TOL:
                    known = _Weights(W, complete=True, tail=tail)
                    break
                J = N if 4 * J > N else 2 * J          # near N: all weights, the cheaper
            cache[key] = known
        return self._expand(known, N)

    def _algebraic_tail(self, W) -> tuple[np.ndarray | None, float]:
        """``(A, estimate)``: the tail ``A j^-3`` (a weight's shape) beyond the computed weights ``W``
        (J+1, m, m) or diagonals (J+1, m, 1), and the self-check's error estimate (``inf``: no tail,
        e.g. a soil without a static flexibility); see :meth:`cq_weights`."""
        from scipy.special import zeta        # Hurwitz zeta: sum_{j >= q} j^-p

        try:
            static = self.static()
        except ValueError:
            return None, np.inf
        if W.shape[2] == 1:
            static = np.diag(static)[:, None]
        J, p = W.shape[0] - 1, TAIL_POWER
        half = J // 2
        if half < 16:
            return None, np.inf
        fitted = (static - W[:half + 1].sum(axis=0)) / zeta(p, half + 1)
        j = np.arange(half + 1, J + 1, dtype=float)
        drift = np.cumsum((j ** -p)[:, None, None] * fitted[None] - W[half + 1:], axis=0)
        estimate = float(np.abs(drift).max() / np.abs(static).max())
        return (static - W.sum(axis=0)) / zeta(p, J + 1), estimate

    def _evaluate_diagonal(self, s) -> np.ndarray:
        """The diagonal of ``Phi(s)`` of an uncoupled soil as (L, m, 1) complex (``evaluate``'s checks)."""
        out = np.asarray(self._diagonal(np.atleast_1d(np.asarray(s, dtype=complex))))[:, :, None]
        if not np.all(np.isfinite(out)):
            k = int(np.argmax(~np.all(np.isfinite(out), axis=(1, 2))))
            raise ValueError(f"the soil flexibility ({self.description}) is not finite at s = {s[k]!r}")
        return out

    def _expand(self, known: _Weights, N: int) -> np.ndarray:
        """``W_0 .. W_N`` (N+1, m, m) from computed weights (:class:`_Weights`) and their tail."""
        W = known.W
        out = np.zeros((N + 1, W.shape[1], W.shape[2]))
        k = min(N + 1, W.shape[0])
        out[:k] = W[:k]
        if known.tail is not None and N + 1 > k:
            out[k:] = (np.arange(k, N + 1, dtype=float) ** -TAIL_POWER)[:, None, None] * known.tail[None]
        if W.shape[2] == self.m:
            return out
        full = np.zeros((N + 1, self.m, self.m))
        index = np.arange(self.m)
        full[:, index, index] = out[:, :, 0]
        return full

    @property
    def is_diagonal(self) -> bool:
        """True if the contacts are uncoupled (``Phi(s)`` diagonal): weights per contact."""
        return self._diagonal is not None

    @property
    def is_rational(self) -> bool:
        """True if the exact pole-residue form is known (``method="modal"`` applies)."""
        return self.poles is not None

    def __repr__(self) -> str:
        return f"SoilFlexibility(m={self.m}, {self.description}{', rational' if self.is_rational else ''})"

    # ------------------------------------------------------------------ constructors
    @classmethod
    def halfspace(cls, halfspace, patches, *, kmax_factor=1.0, components="z") -> SoilFlexibility:
        """The rigorous flexibility of rectangular patches on a :class:`~unilateral.soil.HalfSpace`
        or a :class:`~unilateral.soil.Layered` soil.

        ``Phi = halfspace.surface_flexibility(patches, s, components=components)`` (each distinct
        pair geometry computed once). ``"z"``: one contact per patch, in the order of ``patches``;
        the contact force of a patch is its uniform pressure times its area. ``"xz"``: the x rows of
        the patches, then their z rows (footings that slide, :class:`FoundationModel` with ``Tx``);
        ``"xyz"``: the x rows, the y rows, then the z rows (footings that slide in plan, ``Tx`` and
        ``Ty``). Not rational: ``method="cq"``.
        """
        components = V.choice("components", components, ("z", "xz", "xyz"))
        from .halfspace import HalfSpace
        from .layered import Layered
        from .patches import RectangularPatches

        if isinstance(halfspace, Layered):
            return cls._layered(halfspace, patches, kmax_factor, components)
        if not isinstance(halfspace, HalfSpace):
            raise TypeError(f"halfspace must be a unilateral.soil.HalfSpace or Layered, got {V.describe(halfspace)}")
        if not isinstance(patches, RectangularPatches):
            raise TypeError(f"patches must be RectangularPatches (strips, grid, disc), got {V.describe(patches)}")
        if np.any(patches.sizes <= 0):
            raise ValueError("patches must have positive sides (a point contact has an infinite "
                             "self-flexibility on a half-space)")
        func = lambda s: halfspace.surface_flexibility(patches, s, kmax_factor=kmax_factor, components=components)
        soil = cls(func, len(components) * patches.m,
                   description=f"half-space G={halfspace.G:g}, nu={halfspace.nu:g}, rho={halfspace.rho:g}, "
                               f"{patches.m} patches" + _COMPONENT_LABELS[components])
        if halfspace.damping == 0.0 or halfspace.damping_model == "kelvin_voigt":
            # three Rayleigh-wave travel times across the patches (the weights' truncation hint)
            lo = patches.centres - 0.5 * patches.sizes
            hi = patches.centres + 0.5 * patches.sizes
            soil.memory = 3.0 * float(np.hypot(*(hi.max(axis=0) - lo.min(axis=0)))) / halfspace.cr
        return soil

    @classmethod
    def block_diagonal(cls, parts) -> SoilFlexibility:
        """Uncoupled soils side by side: ``Phi = diag(Phi_1, Phi_2, ...)`` (contacts in that order).

        Footings on soils that do not interact through the ground (cones, Winkler-Kelvin beds, or
        flexibilities given per footing). Rational (``method="modal"``), Kelvin and diagonal if
        every part is.
        """
        parts = list(parts)
        if not parts or not all(isinstance(p, SoilFlexibility) for p in parts):
            raise TypeError("parts must be a non-empty list of SoilFlexibility")
        sizes = [p.m for p in parts]
        m = sum(sizes)
        starts = np.cumsum([0] + sizes)

        def func(s):
            out = np.zeros((np.size(s), m, m), dtype=complex)
            for p, a in zip(parts, starts):
                out[:, a:a + p.m, a:a + p.m] = p.evaluate(s)
            return out

        def static():
            out = np.zeros((m, m))
            for p, a in zip(parts, starts):
                out[a:a + p.m, a:a + p.m] = p.static()
            return out

        diagonal = None
        if all(p.is_diagonal for p in parts):
            diagonal = lambda s: np.concatenate([p._diagonal(s) for p in parts], axis=1)
        poles = None
        if all(p.is_rational for p in parts):
            pad = lambda A, a, k: np.pad(A, ((0, 0), (a, m - a - k)))
            poles = SoilPoles(np.concatenate([p.poles.poles for p in parts]),
                              np.vstack([pad(p.poles.B, a, p.m) for p, a in zip(parts, starts)]),
                              np.vstack([pad(p.poles.Cf, a, p.m) for p, a in zip(parts, starts)]),
                              _pole_constants(parts, m, starts))
        kelvin = None
        if all(p.kelvin is not None for p in parts):
            kelvin = (np.concatenate([p.kelvin[0] for p in parts]), np.concatenate([p.kelvin[1] for p in parts]))
        out = cls(func, m, static=static, poles=poles, kelvin=kelvin, diagonal=diagonal,
                  description="; ".join(p.description for p in parts))
        memories = [p.memory for p in parts]
        out.memory = None if any(x is None for x in memories) else max(memories)
        return out

    def permuted(self, order) -> SoilFlexibility:
        """The same soil with its rows and columns in the order ``order`` (m,) (a permutation):
        ``Phi'(s) = Phi(s)[order][:, order]``, with its pole-residue, Kelvin and diagonal forms."""
        order = np.asarray(order)
        if np.sort(order).tolist() != list(range(self.m)):
            raise ValueError(f"order must be a permutation of 0..{self.m - 1}, got {order.tolist()}")
        ix = np.ix_(order, order)
        poles = None if self.poles is None else SoilPoles(self.poles.poles, self.poles.B[:, order],
                                                          self.poles.Cf[:, order], self.poles.P0[ix])
        kelvin = None if self.kelvin is None else (self.kelvin[0][order], self.kelvin[1][order])
        diagonal = None if self._diagonal is None else (lambda s: self._diagonal(s)[:, order])
        out = SoilFlexibility(lambda s: self.evaluate(s)[:, order][:, :, order], self.m,
                              static=lambda: self.static()[ix], poles=poles, kelvin=kelvin, diagonal=diagonal,
                              description=self.description)
        out.memory = self.memory
        return out

    @classmethod
    def _layered(cls, layered, patches, kmax_factor, components) -> SoilFlexibility:
        """:meth:`halfspace` for a :class:`~unilateral.soil.Layered` soil."""
        from .patches import RectangularPatches

        if not isinstance(patches, RectangularPatches) or np.any(patches.sizes <= 0):
            raise ValueError("patches must be RectangularPatches with positive sides")
        func = lambda s: layered.surface_flexibility(patches, s, kmax_factor=kmax_factor, components=components)
        soil = cls(func, len(components) * patches.m, description=f"{layered!r}, {patches.m} patches"
                   + _COMPONENT_LABELS[components])
        materials = layered.materials + ([] if layered.halfspace is None else [layered.halfspace])
        if all(x.damping == 0.0 or x.damping_model == "kelvin_voigt" for x in materials):
            # the truncation hint: three Rayleigh-wave travel times of the slowest material across the
            # patches and ten vertical round trips through the layers (the weights grow past it)
            lo = patches.centres - 0.5 * patches.sizes
            hi = patches.centres + 0.5 * patches.sizes
            slowest = min(x.cr for x in materials)
            depth = sum(2.0 * t / x.cs for t, x in zip(layered.thickness, layered.materials))
            soil.memory = 3.0 * float(np.hypot(*(hi.max(axis=0) - lo.min(axis=0)))) / slowest + 10.0 * depth
        return soil

    @classmethod
    def cones(cls, patches, G, nu, rho, *, wave="rayleigh") -> SoilFlexibility:
        """Cone-type coupled flexibility of patches (:func:`~unilateral.soil.cone_flexibility`).

        Diagonal: Wolf's vertical cone of the equal-area disc; coupling: Boussinesq decay with a
        wave delay. Rational (``method="modal"``) only for one patch (no coupling, no delay).

        The coupling is not passive in general: for 2 to 4 strips of a 10 m square footing under the
        tower of :func:`unilateral.structure.examples.halfspace_tower`, the march with every contact
        held (the bilateral case) grows without bound at every time step tried, and ``Phi(0)`` of 5
        or more such strips is not positive definite. ``Frame2D.foundation`` therefore spreads the
        footing's own vertical cone over the patches instead (:mod:`unilateral.structure.foundation`).
        A soil must not create energy: the Hermitian part of the admittance ``i omega Phi(i omega)``
        is checked on a frequency grid up to 20 shear-wave transits of the smallest patch per
        second, and a coupled model that fails is refused (an unstable march would be a silently
        wrong answer; the rigorous half-space passes the same check to 2e-12).
        """
        from .cones import cone, cone_flexibility

        func = lambda s: cone_flexibility(patches, G, nu, rho, s, wave=wave)
        func(np.ones(1))                                        # validates the arguments
        if patches.m == 1:
            single = cls.impedances([cone("vertical", G, nu, rho, float(np.sqrt(patches.areas[0] / np.pi)))])
            single.description = f"vertical cone, G={G:g}, nu={nu:g}, rho={rho:g}"
            return single
        _check_passive(func, patches, G, rho)
        return cls(func, patches.m, description=f"cones, G={G:g}, nu={nu:g}, rho={rho:g}, {patches.m} patches")

    @classmethod
    def impedances(cls, impedances) -> SoilFlexibility:
        """One impedance per contact, uncoupled: ``Phi(s) = diag(1 / E_i(s))``.

        Parameters
        ----------
        impedances : sequence of m items, each
            a number ``k`` (a spring, N/m), a pair ``(k, c)`` (a Kelvin element ``k + s c``), a
            :class:`~unilateral.soil.Cone`, a :class:`~unilateral.soil.VeletsosVerbic` (all
            rational: ``method="modal"`` applies), or a callable ``E(s)`` for (L,) complex ``s``
            returning (L,) (e.g. a :class:`~unilateral.soil.RationalFit` of an impedance).
        """
        pair = (isinstance(impedances, tuple) and len(impedances) == 2
                and all(isinstance(x, (int, float)) for x in impedances))
        if callable(impedances) or pair or not isinstance(impedances, (list, tuple)):
            raise TypeError("impedances must be a list with one impedance per contact, e.g. [(k, c)] "
                            f"for one contact; got {V.describe(impedances)}")
        items = list(impedances)
        if not items:
            raise ValueError("impedances must hold at least one impedance (one per contact)")
        funcs = [_impedance_callable(E, f"impedances[{i}]") for i, E in enumerate(items)]
        m = len(items)

        def diagonal(s):
            return np.stack([np.broadcast_to(1.0 / f(s), s.shape) for f in funcs], axis=1)

        def func(s):
            out = np.zeros((s.size, m, m), dtype=complex)
            out[:, np.arange(m), np.arange(m)] = diagonal(s)
            return out

        polys = [_impedance_polynomials(E) for E in items]
        poles = None
        if all(p is not None for p in polys):
            parts = [_scalar_poles(num, den, f"impedances[{i}]") for i, (num, den) in enumerate(polys)]
            if all(part is not None for part in parts):
                poles = _diagonal_poles(parts, m)
        kelvin = None
        if all(isinstance(E, tuple) or (isinstance(E, (int, float)) and not isinstance(E, bool))
               for E in items):
            kc = [(float(E[0]), float(E[1])) if isinstance(E, tuple) else (float(E), 0.0) for E in items]
            kelvin = (np.array([x[0] for x in kc]), np.array([x[1] for x in kc]))
        return cls(func, m, poles=poles, kelvin=kelvin, diagonal=diagonal, description=f"{m} impedances")

    @classmethod
    def kelvin(cls, k, c=0.0) -> SoilFlexibility:
        """Kelvin soil elements, ``Phi = diag(1/(k_i + s c_i))``: the paper's soil model.

        Parameters
        ----------
        k : (m,) array_like, > 0, N/m (a scalar with ``c`` of length m is broadcast)
        c : (m,) array_like or float, >= 0, N s/m
        """
        k = np.atleast_1d(np.asarray(k, dtype=float))
        c = np.atleast_1d(np.asarray(c, dtype=float))
        size = max(k.size, c.size)
        k = V.as_vector("k", k if k.size > 1 else k[0], size)
        c = V.as_vector("c", c if c.size > 1 else c[0], size)
        if np.any(k <= 0):
            i = int(np.argmax(k <= 0))
            raise ValueError(f"k must be > 0 (soil springs); k[{i}] = {float(k[i])!r}")
        if np.any(c < 0):
            i = int(np.argmax(c < 0))
            raise ValueError(f"c must be >= 0 (soil dashpots); c[{i}] = {float(c[i])!r}")
        soil = cls.impedances([(float(a), float(b)) for a, b in zip(k, c)])
        soil.description = f"{size} Kelvin elements"
        return soil

    @classmethod
    def rational(cls, fits) -> SoilFlexibility:
        """Rational fits of *flexibilities* (m/N) in pole-residue form (``method="modal"`` applies).

        Parameters
        ----------
        fits : RationalFit, a sequence of m fits (diagonal ``Phi``) or an m x m nested sequence
            (entry by entry; ``None`` for a zero entry). Anything with ``poles``, ``residues``
            (``Re poles < 0``, conjugate-closed), ``constant`` and ``linear = 0``
            (e.g. :func:`~unilateral.soil.fit_rational` with ``linear=False``).
        """
        if hasattr(fits, "poles"):
            grid = [[fits]]
        else:
            rows = list(fits)
            if rows and all(hasattr(f, "poles") or f is None for f in rows):
                grid = [[f if i == j else None for j in range(len(rows))] for i, f in enumerate(rows)]
            else:
                grid = [list(r) for r in rows]
        m = len(grid)
        if m == 0 or any(len(r) != m for r in grid):
            raise ValueError(f"fits must be one fit, m fits or an m x m table of fits; got {len(grid)} rows "
                             f"of lengths {[len(r) for r in grid]}")
        poles, B, Cf = [], [], []
        P0 = np.zeros((m, m))
        for i in range(m):
            for j in range(m):
                f = grid[i][j]
                if f is None:
                    continue
                for name in ("poles", "residues", "constant", "linear"):
                    if not hasattr(f, name):
                        raise TypeError(f"fits[{i}][{j}] has no attribute {name!r}: give a RationalFit")
                if f.linear != 0.0:
                    raise ValueError(f"fits[{i}][{j}] has a linear term {f.linear:.3g} s: a flexibility "
                                     "cannot grow like s; fit it with linear=False (or pass an impedance "
                                     "fit to SoilFlexibility.impedances)")
                p = np.asarray(f.poles, dtype=complex)
                r = np.asarray(f.residues, dtype=complex)
                if np.any(p.real >= 0):
                    raise ValueError(f"fits[{i}][{j}] has a pole in Re s >= 0: {p[np.argmax(p.real)]}")
                P0[i, j] = f.constant
                keep = p.imag >= 0
                for pk, rk in zip(p[keep], r[keep]):
                    b, cf = np.zeros(m, complex), np.zeros(m, complex)
                    b[i], cf[j] = rk, 1.0
                    poles.append(pk if pk.imag > 0 else complex(pk.real, 0.0))
                    B.append(b if pk.imag > 0 else b.real.astype(complex))
                    Cf.append(cf)
        sp_ = SoilPoles(np.array(poles, dtype=complex), np.array(B, dtype=complex).reshape(-1, m),
                        np.array(Cf, dtype=complex).reshape(-1, m), P0)
        return cls(sp_.evaluate, m, static=sp_.static, poles=sp_, description=f"rational fit, m={m}")

    @classmethod
    def callable(cls, func, m, *, static=None) -> SoilFlexibility:
        """Any ``Phi(s)``: ``func(s)`` for (L,) complex ``s`` returns (L, m, m) (or (L,) if m = 1).

        ``static`` (m, m), optional: ``Phi(0)`` if ``func`` cannot be evaluated at ``s = 0``.
        """
        if static is not None:
            value = V.as_matrix("static", static, (int(m), int(m)), allow_sparse=False)
            return cls(func, m, static=lambda: value, description="user's Phi(s)")
        return cls(func, m, description="user's Phi(s)")


def _diagonal_poles(parts, m) -> SoilPoles:
    poles, B, Cf = [], [], []
    P0 = np.zeros((m, m))
    for i, (roots, res, const) in enumerate(parts):
        P0[i, i] = const
        for p, r in zip(roots, res):
            if p.imag < -1e-12 * abs(p):
                continue
            real = abs(p.imag) <= 1e-12 * abs(p)
            b, c = np.zeros(m, complex), np.zeros(m, complex)
            b[i], c[i] = (r.real if real else r), 1.0
            poles.append(complex(p.real, 0.0) if real else p)
            B.append(b)
            Cf.append(c)
    return SoilPoles(np.array(poles, dtype=complex), np.array(B, dtype=complex).reshape(-1, m),
                     np.array(Cf, dtype=complex).reshape(-1, m), P0)


def _check_passive(func, patches, G, rho) -> None:
    """Raise ValueError if the soil would create energy: the Hermitian part of the admittance
    ``i omega Phi(i omega)`` (velocity per force) must be positive semidefinite, checked on a grid of
    frequencies up to ``20 c_s / size`` of the smallest patch, to 1e-6 of its largest eigenvalue."""
    cs = float(np.sqrt(G / rho))
    size = float(np.sqrt(np.min(patches.areas)))
    omega = np.geomspace(1e-3, 20.0, 120) * cs / size
    Y = 1j * omega[:, None, None] * np.asarray(func(1j * omega))
    eig = np.linalg.eigvalsh(0.5 * (Y + np.conj(np.swapaxes(Y, 1, 2))))
    relative = eig.min(axis=1) / np.abs(eig).max(axis=1)
    k = int(np.argmin(relative))
    if relative[k] < -1e-6:
        raise ValueError(
            f"the coupled cone model of these {patches.m} patches is not passive: the Hermitian part of "
            f"i omega Phi(i omega) has a negative eigenvalue ({relative[k]:.3g} of its largest) at omega = "
            f"{omega[k]:.4g} rad/s (the soil would create energy and the march would grow without bound); "
            "use SoilFlexibility.halfspace (rigorous) or SoilFlexibility.impedances with one cone per patch "
            "(uncoupled)")
