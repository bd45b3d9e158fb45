"""A linear structure resting on a soil given in the Laplace domain, through unilateral contacts.

    M u'' + C u' + K u = q + T c                       (n DOFs, m contact points)
    v = T^T u + (Phi * c) + gap  >= 0,   c >= 0,   v^T c = 0

``T`` (n, m) maps the displacements to the *upward* displacement of the foundation at each contact
point, ``c`` are the compressive contact forces (they push the foundation up and the soil down),
``Phi(s)`` (m, m) is the soil's dynamic flexibility (downward surface displacement per unit downward
force, any of :mod:`unilateral.soil`), ``v`` the openings (uplift) and ``gap`` the opening at
``u = 0, c = 0`` (negative: an initial penetration). The solvers march the *dual* CLCP in the contact
forces, whose kernel is ``Lambda_D(s) = T^T D(s)^-1 T + Phi(s)``, ``D(s) = K + s C + s^2 M``
(``docs/theory.md``, section 12).

:class:`~unilateral.soil.flexibility.SoilFlexibility` is the soil; :class:`FoundationModel` is the problem;
:class:`FoundationKernel` is ``Lambda_D(s)``.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.linalg import block_diag

from .. import _validate as V
from ..kernels.base import Kernel
from ..linalg import Factorization, dense
from ..model import Model, checked_names
from .flexibility import SoilFlexibility, _facet_names, facet_normals

__all__ = ["FoundationKernel", "FoundationModel"]

#: Structures with at most this many DOFs are evaluated by batched dense solves.
_DENSE_BATCH_MAX_N = 64
#: Structures with at most this many DOFs are checked for massless zero-stiffness modes.
_CHECK_MAX_N = 2000


# ====================================================================== the model
class FoundationModel:
    """A linear structure on a soil given in the Laplace domain, through unilateral contacts.

    ::

        M u'' + C u' + K u = q + T c
        v = T^T u + (Phi * c) + gap,     v >= 0,  c >= 0,  v^T c = 0

    Solved by :func:`unilateral.solve` with ``method="cq"`` (any soil), ``"modal"`` (a rational
    soil, see :meth:`modal_form`) or ``"auto"``. The result's ``v`` are the openings (uplift,
    >= 0) and ``psi = -c`` (<= 0, compression), the meaning of the paper's Kelvin soil elements;
    ``psiL`` is ``-c`` with every contact held at its initial opening (the bilateral case).

    Parameters
    ----------
    M, K : (n, n) array_like or sparse
        Mass and stiffness of the structure *without* the soil; symmetric positive semidefinite.
        ``K`` may be singular (a footing resting only on the soil): every zero-stiffness mode
        must then carry mass or damping.
    T : (n, m) array_like or sparse
        Upward displacement of the foundation at each contact, ``z_f = T^T u`` (a contact force
        ``c_j`` acts on the structure as the load ``T[:, j] c_j``).
    soil : SoilFlexibility
        ``Phi(s)`` (m, m), downward soil displacement per unit compressive contact force.
    C : (n, n), optional
        Damping of the structure (symmetric PSD; default zero).
    gap : (m,) array_like or float, optional
        Opening at ``u = 0`` with the soil unloaded (default 0; negative: a penetration).
    dof_names : sequence of n str, optional
    contact_names : sequence of m str, optional
    Tx : (n, m) array_like or sparse, optional
        Horizontal displacement of the foundation at each contact patch, ``x_f = Tx^T u``: the
        footings slide (``soil`` then has ``2 m`` rows, x then z).
    mu : float or (m,) array_like, optional
        Coulomb friction coefficient of each patch on the soil (with ``Tx``; >= 0).
    Ty : (n, m) array_like or sparse, optional
        With ``Tx``: the footing's displacement along y at each patch, ``y_f = Ty^T u``: the
        footings slide in plan (``soil`` then has ``3 m`` rows, x, y then z).
    facets : int, optional
        With ``Ty``: the facets of each patch's polygonal friction cone (even, >= 4; default 8).
    K_geometric : (n, n) array_like or sparse, optional
        P-Delta: the geometric stiffness included in ``K``. ``K - K_geometric`` must be positive
        semidefinite, ``K`` itself need not be: a footing resting only on the soil rocks unstably under
        its weight without it (the frame's own ``D(s)`` has a real pole); its stability on the soil is
        that of ``K + T Phi(0)^-1 T^T`` (checked by :meth:`unilateral.structure.Structure.to_model`).

    Attributes
    ----------
    n, m : int
    M, K, C, T : the matrices (dense or CSR), ``C`` None if undamped
    soil : SoilFlexibility
    gap : (m,)
    dof_names, constraint_names : list of str (``contact_names``)

    A structure with unilateral elements of its own (gaps, cables, yielding links, hinges, sliders:
    a :class:`~unilateral.model.Model` with its constraint families) rests on the soil with
    :meth:`on`: the model's ``m_p`` constraints come first, the ``m_s`` soil contacts (a
    :class:`~unilateral.constraints.SoilContact` family) after them, and one CLCP couples them
    (``docs/theory.md``, section 12).

    **Footings that slide** (``Tx`` and ``mu`` given): the soil is the horizontal and vertical
    flexibility of the patches, ``Phi(s)`` (2 m_s, 2 m_s) ordered as
    :meth:`HalfSpace.surface_flexibility <unilateral.soil.HalfSpace.surface_flexibility>` with
    ``components="xz"`` (the x components of the patches, then z; z down, forces on the soil). Each
    patch then has, after the ``m_s`` contacts, a horizontal force ``f_j`` on the soil
    (:class:`~unilateral.constraints.SoilShear`: either sign; the soil's force on the footing is
    ``-f_j``) and a slip pair (:class:`~unilateral.constraints.SoilFriction`): the footing moves
    with the soil surface horizontally but for the slip, and slips only where ``|f_j| = mu_j c_j``.
    An open patch carries no shear (``|f| <= mu c = 0``), so a footing can rock, lift and slide at
    once. Unknowns: the model's, ``c`` (m_s), ``f`` (m_s), ``s+, s-`` (pairs, 2 m_s): ``m = m_p +
    4 m_s``. The solution's columns: contacts ``v`` opening, ``psi = -c``; shears ``v`` the patch's
    net slip ``s+ - s-`` (length), ``psi`` the soil's horizontal force on the footing ``-f``;
    slips ``v`` the cumulative slips ``s+-``, ``psi`` the friction functions ``+-f - mu c <= 0``.

    **Footings that slide in plan** (``Ty`` too, and ``facets``): ``Phi(s)`` (3 m_s, 3 m_s) has
    the x, y, then z rows (``components="xyz"``); each patch has two horizontal forces ``(fx, fy)``
    (the shears: the x block, then the y block) and a polygonal Coulomb cone of ``facets`` facets of
    unit normals ``d_k`` (:func:`facet_normals`, in opposite pairs): facet ``k`` keeps
    ``d_k . f <= mu c`` and slips by ``lambda_k d_k``. The plane case is the special case of one
    direction and the two facets ``+x, -x``. Unknowns: the model's, ``c``, ``fx``, ``fy``, then
    ``facets`` slip multipliers per patch: ``m = m_p + (3 + facets) m_s``. The solution's columns:
    shears ``v`` the net slip ``sum_k lambda_k d_k`` (x block, y block), ``psi = -f``; facets ``v``
    the multipliers, ``psi`` the facet functions ``d_k . f - mu c <= 0``.

    Notes
    -----
    Units: any consistent set (e.g. kN, m, s: then ``Phi`` is in m/kN).
    Initial states (``initial=`` of :func:`unilateral.solve`): ``"static"`` - the static
    unilateral equilibrium with the soil's static flexibility ``Phi(0)`` (the structure with
    ``K + T Phi(0)^-1 T^T`` must be stable); ``"rest"`` - ``u = 0``, soil unloaded (needs
    ``gap >= 0``); ``{"u0": ..., "udot0": ...}`` - given values, soil unloaded (``T^T u0 + gap >= 0``).
    """

    kind = "foundation"     #: the kind of problem, as the methods know it (``Method.solves``)
    def __init__(self, M, K, T, soil, *, C=None, gap=None, dof_names=None, contact_names=None, Tx=None, mu=None,
                 Ty=None, facets=None, K_geometric=None):
        self.K = V.as_matrix("K", K, (None, None))
        n = self.K.shape[0]
        if self.K.shape != (n, n) or n == 0:
            raise ValueError(f"K must be square (n, n) with n >= 1, got shape {self.K.shape}")
        self.M = V.as_matrix("M", M, (n, n))
        self.C = None if C is None else V.as_matrix("C", C, (n, n))
        self.T = V.as_matrix("T", T, (n, None))
        m = self.T.shape[1]
        if m == 0:
            raise ValueError("T must have at least one column (one contact point)")
        geometric = None if K_geometric is None else V.as_matrix("K_geometric", K_geometric, (n, n))
        for name in ("M", "K", "C"):
            if getattr(self, name) is not None:
                V.check_symmetric(name, getattr(self, name))
                elastic = self.K - geometric if name == "K" and geometric is not None else getattr(self, name)
                _check_psd(name if elastic is getattr(self, name) else "K - K_geometric", elastic)
        if not isinstance(soil, SoilFlexibility):
            raise TypeError("soil must be a SoilFlexibility (SoilFlexibility.halfspace, .cones, .impedances, "
                            f".kelvin, .rational or .callable), got {V.describe(soil)}")
        self.Tx = None if Tx is None else V.as_matrix("Tx", Tx, (n, m))
        if (Tx is None) != (mu is None):
            raise ValueError("Tx and mu go together (footings that slide on the soil): give both or neither")
        if Tx is None and (Ty is not None or facets is not None):
            raise ValueError("Ty and facets are for footings that slide in plan: give Tx and mu too")
        self.Ty = None if Ty is None else V.as_matrix("Ty", Ty, (n, m))
        #: The unit normals (facets, directions) of each patch's friction facets (None: no sliding).
        self.directions = None if Tx is None else facet_normals(1 if Ty is None else 2, facets)
        rows = (1 + self.horizontal) * m
        if soil.m != rows:
            raise ValueError(f"soil has m = {soil.m} rows but T has {m} columns (one per contact): give a soil of "
                             f"{rows} rows" + ("", " (x then z components of each patch, components='xz')",
                                               " (x, y then z components of each patch, components='xyz')"
                                               )[self.horizontal])
        self.mu = None if mu is None else V.as_vector("mu", mu, m)
        if self.mu is not None and (np.any(~np.isfinite(self.mu)) or np.any(self.mu < 0)):
            raise ValueError(f"mu must be finite and >= 0 (friction coefficients), got {self.mu.tolist()}")
        self.soil = soil
        self.gap = V.as_vector("gap", 0.0 if gap is None else gap, m)
        self.dof_names = checked_names("dof_names", dof_names, n, "u")
        names = checked_names("contact_names", contact_names, m, "c")
        if self.horizontal == 1:
            names = names + [f"{x}.shear" for x in names] + [f"{x}.slip{sign}" for x in names for sign in "+-"]
        elif self.horizontal == 2:
            faces = _facet_names(self.directions.shape[0])
            names = (names + [f"{x}.shear_x" for x in names] + [f"{x}.shear_y" for x in names]
                     + [f"{x}.{face}" for x in names for face in faces])
        self.constraint_names = names
        #: The structure's own unilateral constraints (a Model), or None (:meth:`on`).
        self.structure = None
        self._check_rigid_modes()

    @classmethod
    def on(cls, structure: Model, T, soil, *, gap=None, contact_names=None, Tx=None, mu=None, Ty=None,
           facets=None) -> FoundationModel:
        """A :class:`~unilateral.model.Model` with constraints of its own, resting on the soil.

        The model's ``M, K, C`` are the structure without the soil; its constraints (any
        families: contact, yield, friction) keep their indices ``0 .. m_p - 1``; the soil
        contacts follow, ``m_p .. m_p + m_s - 1``, with the meaning of the plain form (``v`` the
        opening, ``psi = -c``). The solution's constraints are the model's and then the contacts.

        Parameters
        ----------
        structure : Model
            With constant ``g`` and imposed-strain load ``q_imposed``.
        T, soil, gap, contact_names, Tx, mu, Ty, facets : as for the constructor (``m_s`` contacts).
        """
        if not isinstance(structure, Model):
            raise TypeError(f"structure must be a unilateral.Model, got {V.describe(structure)}")
        if not (structure.g_is_constant and structure.q_imposed_is_constant):
            raise ValueError("a structure on a soil needs constant g and q_imposed (loads that vary in time "
                             "go in load=)")
        ms = V.as_matrix("T", T, (structure.n, None)).shape[1]
        if contact_names is None:
            contact_names = [f"soil{j}" for j in range(ms)]
        natural = getattr(structure, "natural", None)
        out = cls(structure.M, structure.K, T, soil, C=structure.C, gap=gap, dof_names=structure.dof_names,
                  contact_names=contact_names, Tx=Tx, mu=mu, Ty=Ty, facets=facets,
                  K_geometric=None if natural is None else natural.K_geometric)
        twice = set(structure.constraint_names) & set(out.constraint_names)
        if twice:
            raise ValueError(f"contact_names: {sorted(twice)[:3]} are also names of the structure's constraints; "
                             "names must be unique")
        if structure.m:
            out.structure = structure
            out.constraint_names = list(structure.constraint_names) + out.constraint_names
        return out

    # ------------------------------------------------------------------ sizes and flags
    @property
    def n(self) -> int:
        """Number of structural DOFs."""
        return self.K.shape[0]

    @property
    def mp(self) -> int:
        """Number of the structure's own constraints (:meth:`on`; 0 for a plain foundation model)."""
        return 0 if self.structure is None else self.structure.m

    @property
    def ms(self) -> int:
        """Number of soil contacts (columns of ``T``)."""
        return self.T.shape[1]

    @property
    def m(self) -> int:
        """Number of constraints: the structure's and the soil contacts (with their shears and slips)."""
        return self.mp + (1 + self.horizontal + self.facets) * self.ms

    @property
    def sliding(self) -> bool:
        """The footings slide: horizontal soil forces limited by friction (``Tx``, ``mu``)."""
        return self.Tx is not None

    @property
    def horizontal(self) -> int:
        """Horizontal directions of the soil forces: 0 (none), 1 (x: ``Tx``), 2 (in plan: ``Tx``, ``Ty``)."""
        return 0 if self.Tx is None else (1 if self.Ty is None else 2)

    @property
    def facets(self) -> int:
        """Friction facets (slip multipliers) per patch: 0, 2 (``+x, -x``) or the cone's in plan."""
        return 0 if self.directions is None else self.directions.shape[0]

    def horizontal_maps(self) -> list:
        """``[Tx]`` or ``[Tx, Ty]``: the footing's horizontal displacement at the patches per direction."""
        return [T for T in (self.Tx, self.Ty) if T is not None]

    @property
    def mixed(self) -> bool:
        """The structure has constraints of its own, or the footings slide: the CLCP mixes the primal
        and the dual form (:meth:`weights`)."""
        return self.structure is not None or self.sliding

    @property
    def contact_names(self) -> list:
        """The names of the soil contacts."""
        return self.constraint_names[self.mp:self.mp + self.ms]

    @property
    def contacts(self) -> np.ndarray:
        """Indices (m_s,) of the soil contacts' unknowns ``c`` among the model's."""
        return self.mp + np.arange(self.ms)

    @property
    def shears(self) -> np.ndarray:
        """Indices (horizontal m_s,) of the patches' horizontal forces ``f`` (empty unless :attr:`sliding`):
        the x block, then the y block (in plan)."""
        return self.mp + self.ms + np.arange(self.horizontal * self.ms)

    @property
    def slips(self) -> np.ndarray:
        """Indices (facets m_s,) of the slip multipliers patch by patch, in opposite pairs ``(s+, s-)``
        (empty unless :attr:`sliding`)."""
        return self.mp + (1 + self.horizontal) * self.ms + np.arange(self.facets * self.ms)

    @property
    def soil_rows(self) -> np.ndarray:
        """The unknowns (soil.m,) that the rows of ``Phi`` act on: ``c``; sliding: ``f`` (x, y) then ``c``."""
        return np.concatenate([self.shears, self.contacts])

    @property
    def law(self):
        """The step law: the structure's families and the soil contacts (dual rows).

        A plain foundation model: contacts only (its kernel ``Lambda_D`` is positive definite).
        Footings that slide add the shears (free) and the slip pairs (friction on the contacts' forces).
        """
        from ..constraints import SoilContact, SoilFriction, SoilShear, contact_law, step_law

        if not self.mixed:
            return contact_law(self.ms)
        families = [] if self.structure is None else list(self.structure.families)
        families.append(SoilContact(self.contacts, name="soil"))
        if self.sliding:
            families += [SoilShear(self.shears, name="soil shear"),
                         SoilFriction(self.slips, normal=np.repeat(self.contacts, self.facets),
                                      mu=np.repeat(self.mu, self.facets),
                                      name="soil friction")]
        return step_law(families, self.m)

    @property
    def sparse(self) -> bool:
        return sp.issparse(self.K)

    #: Imposed strains of the structure's elements are constant (the gap is in the contact law).
    q_imposed_is_constant = True

    def q_imposed(self, t) -> np.ndarray:
        """The structure's imposed-strain load (constant; zero for a plain foundation model)."""
        return np.zeros(self.n) if self.structure is None else self.structure.q_imposed(0.0)

    def damping(self):
        """C, or a zero matrix of the right kind if the structure is undamped."""
        if self.C is not None:
            return self.C
        return sp.csr_matrix((self.n, self.n)) if self.sparse else np.zeros((self.n, self.n))

    def D(self, s):
        """``D(s) = K + s C + s^2 M`` of the structure alone, for a scalar ``s``."""
        out = self.K + (s * s) * self.M
        return out if self.C is None else out + s * self.C

    def __repr__(self) -> str:
        return f"FoundationModel(n={self.n}, m={self.m}, soil={self.soil!r})"

    # ------------------------------------------------------------------ kernels
    def kernel(self) -> FoundationKernel:
        """``Lambda_D(s) = T^T D(s)^-1 T + Phi(s)``: the kernel of the dual CLCP (plain models)."""
        self._plain("kernel")
        return FoundationKernel(self)

    def _plain(self, what):
        if self.mixed:
            raise ValueError(f"{what}: not available for a structure with constraints of its own on the soil "
                             "(FoundationModel.on) or footings that slide (Tx, mu); use method='cq'")

    def structure_flexibility(self, s) -> np.ndarray:
        """``T^T D(s)^-1 T`` for ``s`` (L,) (``s != 0`` if ``K`` is singular): (L, m, m)."""
        s = np.atleast_1d(np.asarray(s))
        dtype = float if np.isrealobj(s) else complex
        out = np.empty((s.size, self.ms, self.ms), dtype=dtype)
        if self.n <= _DENSE_BATCH_MAX_N:
            K, M, T = dense(self.K), dense(self.M), dense(self.T)
            Cd = None if self.C is None else dense(self.C)
            for lo in range(0, s.size, 2048):
                sl = s[lo:lo + 2048]
                D = K[None] + (sl * sl)[:, None, None] * M[None]
                if Cd is not None:
                    D = D + sl[:, None, None] * Cd[None]
                out[lo:lo + 2048] = np.swapaxes(T, 0, 1)[None] @ np.linalg.solve(D, np.broadcast_to(T, D.shape[:1] + T.shape))
            return out
        Td = dense(self.T)
        for k, sk in enumerate(s):
            lu = Factorization(self.D(sk), what=f"D(s) = K + s C + s^2 M of the structure at s = {sk}")
            out[k] = Td.T @ lu.solve(Td.astype(dtype))
        return out

    def weights(self, N: int, dt: float, rule, **cq_options) -> np.ndarray:
        """Convolution-quadrature weights ``W_0 .. W_N`` of the model's kernel: (N+1, m, m).

        Plain model: the weights of ``Lambda_D(s) = T^T D(s)^-1 T + Phi(s)`` (positive definite).
        The structure's part is computed exactly as the impulse responses of the rule applied to the
        structure (all columns of :meth:`impulse_basis` stepped together by compiled code,
        :func:`~unilateral.soil.structure_weights.structure_weights`): these *are* its CQ weights
        (zero initial data), without the round-off that the FFT on a circle suffers where
        ``D(s)`` is ill-conditioned at small ``|s|`` (a footing resting only on the soil has a
        pole of ``D(s)^-1`` at ``s = 0``; axially rigid members add stiffness 1e7 times larger).
        The soil's part is :meth:`SoilFlexibility.cq_weights` (truncated where the soil's impulse
        response has died out; ``cq_options``: ``L``, ``rho`` force the full FFT).

        Mixed model (:meth:`on`): the weights of the symmetric kernel
        ``Lambda(s) = H_a - F_a^T D(s)^-1 F_a - diag(0, Phi(s))`` with ``F_a = [F, T]``,
        ``H_a = diag(H, 0)``: rows of the structure's constraints ``psi``, rows of the soil contacts
        ``+opening`` (the :class:`~unilateral.constraints.SoilContact` row map makes them the LCP's
        ``w``; ``docs/theory.md``, section 12). Footings that slide: ``F_a = [F, T, -Tx, 0]``, the
        x-z soil block on the rows of ``f`` and ``c``, and the constant coupling of each shear to its
        slips (``Lambda_{f s+-} = Lambda_{s+- f} = -+1``: the shear row holds the slip, the slip rows
        the force ``+-f``). In plan: ``F_a = [F, T, -Tx, -Ty, 0]``, the x-y-z block, and
        ``Lambda_{f_i lambda_k} = Lambda_{lambda_k f_i} = -d_{k,i}`` for each facet ``k`` of normal
        ``d_k`` (the slip ``sum_k lambda_k d_k``, the facet rows ``d_k . f``).
        """
        from ..rules import get_rule

        rule = get_rule(rule, cq=True)
        N, m = int(N), self.m
        free = self.stepping_model()
        basis = self.impulse_basis()
        if free.viscous:
            W = self._swept_weights(free, rule, dt, N, basis)
        else:
            from .structure_weights import structure_weights

            W = structure_weights(self.M, self.K, self.C, free.F, rule, dt, N, basis=basis)
            W[0] -= free.H @ basis
        if basis.shape[1] < m:
            W = W @ basis.T
        soil = self.soil.cq_weights(N, dt, rule, **cq_options)
        if not self.mixed:
            return W + soil
        np.negative(W, out=W)
        rows = self.soil_rows
        W[:, rows[:, None], rows[None, :]] -= soil
        if self.sliding:            # the shear row holds the slip: psi_f = slip - (x_f - x_soil)
            ms, nf = self.ms, self.facets
            for i in range(self.horizontal):
                f = self.shears[i * ms:(i + 1) * ms]
                for k in range(nf):             # slip lambda_k d_k; the facet's row d_k . f
                    if self.directions[k, i]:
                        s = self.slips[k::nf]
                        W[0, f, s] = W[0, s, f] = -self.directions[k, i]
        return W

    def _swept_weights(self, free, rule, dt, N, basis) -> np.ndarray:
        """The structure's weights by one linear sweep per impulse (Kelvin elements of the structure)."""
        from ..march.direct import sweep_direct
        from ..march.stepper import StructureStepper

        m, n = self.m, self.n
        zeros_n, zeros_m = np.zeros((N + 2, n)), np.zeros((N + 2, m))
        W = np.empty((N + 1, m, basis.shape[1]))
        for j in range(basis.shape[1]):
            stepper = StructureStepper(free, rule, dt, zeros_n, zeros_m, None, condensed=False)
            impulse = np.zeros((N + 2, m))
            impulse[1] = basis[:, j]
            _, _, _, response, _ = sweep_direct(stepper, N + 1, np.zeros(m), np.zeros(m), impulse)
            W[:, :, j] = response[1:]
        return W

    def impulse_basis(self) -> np.ndarray:
        """(m, r) orthonormal impulses whose responses give the structure's weights of every contact.

        The structure's part ``T^T D(s)^-1 T`` vanishes on the null space of ``T``: with ``V`` the
        right singular vectors of ``T`` of its ``r`` nonzero singular values, the response to
        ``e_j`` is that to ``V V^T e_j``. A rigid footing (``r = 2``: ``uy``, ``rz``) on hundreds
        of patches then takes two sweeps instead of one per patch. The identity (one sweep per
        contact) when ``r`` is not below ``m / 4``, where the saving would not pay. A mixed model:
        the unknowns whose columns load the structure or carry ``H`` (slips do neither).
        """
        if self.mixed:
            free = self.stepping_model()
            used = np.asarray(abs(free.F).sum(axis=0)).ravel() + np.abs(free.H).sum(axis=0) > 0
            return np.eye(self.m)[:, used]
        T = dense(self.T)
        _, sv, vt = np.linalg.svd(T, full_matrices=False)
        r = int(np.sum(sv > sv.max(initial=0.0) * max(T.shape) * np.finfo(float).eps))
        return vt[:r].T if 4 * r < self.m else np.eye(self.m)

    # ------------------------------------------------------------------ equivalent matrix models
    def static_model(self) -> Model:
        """The static problem as a paper :class:`~unilateral.model.Model` (openings ``v``).

        With ``S0 = Phi(0)^-1`` the soil is a set of springs in series with the contacts:
        ``K + T S0 T^T``, ``F = T S0``, ``H = S0``, ``g = -S0 gap``, imposed load ``-T S0 gap``;
        its static state is the static state of this model (``psi = -c``). A mixed model's own
        constraints come first, as they are. Footings that slide: the springs act on
        ``B = [-Tx, T]`` and the unknowns ``E [o; s+; s-] = [-(s+ - s-); o]`` (openings, then slip
        pairs with :class:`~unilateral.constraints.Friction` on the openings' reactions):
        ``K + B S0 B^T``, ``F = B S0 E``, ``H = E^T S0 E``; the slip rows' ``psi`` are ``+-f``.
        In plan ``B = [-Tx, -Ty, T]`` and the facets' columns of ``E`` are ``-d_k`` on the x and y
        springs (their ``psi`` are ``d_k . f``).
        """
        S0 = np.linalg.inv(self.soil.static())
        S0 = 0.5 * (S0 + S0.T)
        return self._spring_model(S0, None)

    def kelvin_model(self) -> Model:
        """The paper's Model with Kelvin soil elements, when ``Phi = diag(1/(k + s c))``.

        ``K + T k T^T``, ``C + T c T^T``, ``F = T k``, ``F_v = T c``, ``H = k``, ``H_v = c``,
        ``g = -k gap``: the same problem in the openings (the paper's primal form).
        """
        if self.soil.kelvin is None:
            raise ValueError(f"kelvin_model needs a soil of Kelvin elements (SoilFlexibility.kelvin), "
                             f"not {self.soil.description}")
        k, c = self.soil.kelvin
        return self._spring_model(np.diag(k), np.diag(c) if np.any(c) else None)

    def _spring_model(self, S, Cs) -> Model:
        """The structure with springs ``S`` (and dashpots ``Cs``) in series with the soil contacts."""
        from ..constraints import Contact, Friction, default_families

        ms = self.ms
        big = self.n > _CHECK_MAX_N
        T = dense(self.T) if not big else sp.csr_matrix(self.T)
        gap = self.gap
        k, nf = self.horizontal, self.facets
        if self.sliding:
            maps = [-(dense(X) if not big else sp.csr_matrix(X)) for X in self.horizontal_maps()]
            T = np.hstack(maps + [T]) if not big else sp.hstack(maps + [T]).tocsr()
            E = np.zeros(((k + 1) * ms, (nf + 1) * ms))
            E[k * ms + np.arange(ms), np.arange(ms)] = 1.0
            for i in range(k):
                for f in range(nf):
                    if self.directions[f, i]:
                        E[i * ms + np.arange(ms), ms + nf * np.arange(ms) + f] = -self.directions[f, i]
            gap = np.concatenate([np.zeros(k * ms), gap])
        else:
            E = np.eye(ms)
        TS = T @ S
        add = lambda A, B: (A + B) if not sp.issparse(A) else (A + sp.csr_matrix(B))
        K = add(self.K, TS @ T.T)
        C, F_v, H_v = self.C, None, None
        if Cs is not None:
            C = add(self.damping(), T @ Cs @ T.T)
            F_v, H_v = T @ Cs @ E, E.T @ Cs @ E
        q_imp = self.q_imposed(0.0) - np.asarray(TS @ gap).ravel()
        F, H, g = TS @ E, E.T @ S @ E, -(E.T @ S @ gap)
        mp = self.mp
        soil_families = [Contact(np.arange(mp, mp + ms), name="soil")]
        if self.sliding:
            soil_families.append(Friction(mp + ms + np.arange(nf * ms), normal=np.repeat(mp + np.arange(ms), nf),
                                          mu=np.repeat(self.mu, nf), name="soil friction"))
        names = self.constraint_names[:mp + ms] + self.constraint_names[mp + (1 + k) * ms:]
        families = soil_families if mp or self.sliding else default_families(ms)
        base = self.structure
        if base is not None:
            k = E.shape[1]
            stack = (lambda A, B: sp.hstack([sp.csr_matrix(A), sp.csr_matrix(B)]).tocsr()) \
                if (sp.issparse(base.F) or sp.issparse(F)) else (lambda A, B: np.hstack([A, B]))
            F = stack(base.F, F)
            H = block_diag(dense(base.H), H)
            g = np.concatenate([base.g(0.0), g])
            if base.viscous or Cs is not None:
                F_v = stack(np.zeros((self.n, mp)) if base.F_v is None else dense(base.F_v),
                            np.zeros((self.n, k)) if Cs is None else F_v)
                H_v = block_diag(np.zeros((mp, mp)) if base.H_v is None else dense(base.H_v),
                                 np.zeros((k, k)) if Cs is None else H_v)
            families = list(base.families) + soil_families
        try:
            return Model(self.M, K, F, H, C=C, g=g, F_v=F_v, H_v=H_v,
                         q_imposed=q_imp if np.any(q_imp) else None,
                         dof_names=self.dof_names, constraint_names=names, families=families)
        except ValueError as exc:
            raise ValueError(f"the structure on the soil's static springs is not stable ({exc}): "
                             "K + T Phi(0)^-1 T^T must be positive definite; support the structure or "
                             "connect every free DOF to the foundation") from None

    def modal_form(self, *, tol: float = 1e-8):
        """``Lambda_D(s)`` as a :class:`~unilateral.kernels.PoleResidueKernel` (rational soils).

        The structure's poles and residues of ``T^T D(s)^-1 T`` (every pole, dense state-space form)
        plus the soil's :class:`SoilPoles`. Needs a rational soil and a structure whose ``K`` is
        positive definite (``D(s)^-1`` without a pole at ``s = 0``).

        Raises
        ------
        ValueError
            Saying which condition fails.
        """
        from ..kernels.pole_residue import PoleResidueKernel
        from ..kernels.poles_dense import check_points, dense_poles

        self._plain("the pole-residue form")
        if not self.soil.is_rational:
            raise ValueError(f"the soil ({self.soil.description}) has no pole-residue form; "
                             "use method='cq'")
        try:
            bare = Model(self.M, self.K, self.T, np.zeros((self.m, self.m)), C=self.C)
        except ValueError as exc:
            raise ValueError("the structure without the soil has a zero-stiffness mode (K is singular: "
                             f"{exc}), so T^T D(s)^-1 T has a pole at s = 0 that the recursive history "
                             "does not take; use method='cq'") from None
        parts = dense_poles(bare)                  # Lambda of the bare model = -T^T D^-1 T
        sp_ = self.soil.poles
        poles = np.concatenate([parts["poles"], sp_.poles])
        B = np.vstack([-parts["B"], sp_.B])
        Cf = np.vstack([parts["Cf"], sp_.Cf])
        Lambda0 = -parts["Lambda0"] + sp_.static()
        info = dict(parts["info"], soil_poles=int(np.where(sp_.poles.imag > 0, 2, 1).sum()))
        kernel = PoleResidueKernel(poles, B, Cf, Lambda0=0.5 * (Lambda0 + Lambda0.T), info=info)
        err = kernel.relative_error(self.kernel(), check_points(kernel.poles))
        kernel.info["reconstruction_error"] = err
        if not err <= tol:
            raise ValueError(f"the pole-residue form reproduces Lambda_D(s) only to {err:.2e} relative "
                             f"(tol = {tol:.0e}); use method='cq'")
        return kernel

    def stepping_model(self):
        """The structure alone, for :class:`~unilateral.march.stepper.StructureStepper`.

        ``F = T``, ``H = 0``: a sweep with prescribed "increments" ``dc`` loads the structure with
        ``T dc`` and returns ``offset + T^T du`` (the structural part of the opening).
        """
        return _FreeStructure(self)

    # ------------------------------------------------------------------ checks
    def _check_rigid_modes(self):
        if self.n > _CHECK_MAX_N:
            return
        K = dense(self.K)
        w, X = np.linalg.eigh(K)
        scale = max(abs(w).max(initial=0.0), 1e-300)
        Z = X[:, np.abs(w) <= 1e-10 * scale]       # not the negative modes of P-Delta (K - K_G is checked)
        if Z.shape[1] == 0:
            return
        inertia = Z.T @ (dense(self.M) + (0 if self.C is None else dense(self.C))) @ Z
        size = np.abs(dense(self.M)).max(initial=0.0) + (0 if self.C is None else np.abs(dense(self.C)).max())
        e, Y = np.linalg.eigh(0.5 * (inertia + inertia.T))
        if e[0] <= 1e-10 * max(size, 1e-300):
            mode = Z @ Y[:, 0]
            moved = [self.dof_names[i] for i in np.flatnonzero(np.abs(mode) > 1e-6 * np.abs(mode).max())]
            raise ValueError("the structure without the soil has a zero-stiffness mode without mass or "
                             f"damping (moving DOFs {', '.join(moved[:10])}): it cannot be stepped; give "
                             "those DOFs mass, stiffness or supports")


class _FreeStructure:
    """The structure without the soil, in the interface StructureStepper reads.

    Columns ``F_a = [F, T]`` (the structure's own constraints, then the soil contacts) and
    ``H_a = diag(H, 0)``: a sweep with prescribed increments ``dz`` loads the structure with
    ``F_a dz`` and returns ``offset + F_a^T du - H_a dz`` (the structural part of the rows: the
    constraint functions and the openings).
    """

    def __init__(self, model: FoundationModel):
        self.M, self.K, self.C = model.M, model.K, model.C
        self.n, self.m = model.n, model.m
        self._model = model
        base = model.structure
        T = model.T
        if model.sliding:           # columns of c, f (-Tx: f acts on the soil) and the slips (none)
            maps = model.horizontal_maps()
            parts = [T] + [-X for X in maps] + [sp.csr_matrix((model.n, model.facets * model.ms))]
            T = sp.hstack(parts).tocsr() if sp.issparse(T) or any(sp.issparse(X) for X in maps) \
                else np.hstack([dense(p) for p in parts])
        ms = T.shape[1]
        self.F, self.H, self.F_v, self.H_v = T, np.zeros((ms, ms)), None, None
        if base is not None:
            mp = base.m
            sparse = sp.issparse(base.F) or sp.issparse(T)
            stack = (lambda A, B: sp.hstack([sp.csr_matrix(A), sp.csr_matrix(B)]).tocsr()) if sparse \
                else (lambda A, B: np.hstack([dense(A), dense(B)]))
            self.F = stack(base.F, T)
            self.H = block_diag(dense(base.H), np.zeros((ms, ms)))
            if base.viscous:
                self.F_v = stack(np.zeros((self.n, mp)) if base.F_v is None else base.F_v, np.zeros((self.n, ms)))
                self.H_v = block_diag(np.zeros((mp, mp)) if base.H_v is None else dense(base.H_v),
                                      np.zeros((ms, ms)))
        self.viscous = self.F_v is not None

    def damping(self):
        return self._model.damping()

    def H_of(self, s):
        return self.H if self.H_v is None else self.H + s * self.H_v


class FoundationKernel(Kernel):
    """``Lambda_D(s) = T^T D(s)^-1 T + Phi(s)`` of a :class:`FoundationModel` (dual kernel).

    ``kernel(s)`` for ``s`` (L,) returns (L, m, m): the opening at the contacts per unit
    compressive contact force (m/N). Real for real ``s``.
    """

    def __init__(self, model: FoundationModel):
        self.model = model
        self.m = model.m

    def evaluate(self, s: np.ndarray) -> np.ndarray:
        s = np.atleast_1d(np.asarray(s))
        out = self.model.structure_flexibility(s) + self.model.soil.evaluate(s)
        return out.real if np.isrealobj(s) else out


def _check_psd(name, A):
    """Symmetric positive semidefinite (dense check up to a size)."""
    d = A.diagonal() if sp.issparse(A) else np.diag(A)
    if np.any(d < 0):
        i = int(np.argmax(d < 0))
        raise ValueError(f"{name} must be positive semidefinite; {name}[{i}, {i}] = {float(d[i])!r}")
    if A.shape[0] <= _CHECK_MAX_N:
        eig = np.linalg.eigvalsh(dense(A))
        limit = 10 * A.shape[0] * np.finfo(float).eps * max(np.abs(eig).max(initial=0.0), 1e-300)
        if eig[0] < -limit:
            raise ValueError(f"{name} must be symmetric positive semidefinite; its smallest eigenvalue is "
                             f"{eig[0]:.3g} (largest {eig[-1]:.3g})")
