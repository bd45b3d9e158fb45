"""A built frame, :class:`Structure`: the natural form, the mass, damping and DOF map, the
constraint families and the model (:meth:`Structure.to_model`), the load vectors (gravity, nodal,
distributed, ground motion) and the deformations and forces of the constraint unknowns.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from ..loads.units import STANDARD_GRAVITY
from ..constraints import Bearing, Contact, Friction, Yield
from ..model import ConstantStrain, Model, NaturalForm
from . import elements as el, support_motion
from .assembly import _nonzero_interaction
from .checks import _real
from .dofs import DofMap
from .geometric import AXIAL_KINDS, consistent


@dataclass(frozen=True, eq=False)
class Structure:
    """A built frame: the natural form (Liolios 1990, eqs. 1-9) and the DOF map.

    Attributes
    ----------
    natural : NaturalForm
        ``G`` (n, ne) csr, ``E`` (ne, ne) csr, ``B`` (ne, m) csr, ``A`` (m, m) dense (kinematic
        hardening of yield pairs, else zero), ``r`` (m,),
        ``theta`` (constant imposed strains, as a function of time), ``E_v`` (ne, ne) csr or None.
    M : (n, n) csr mass matrix (lumped, transformed by the rigid links)
    C : (n, n) csr damping of attached dashpots and Rayleigh damping, or None; the Kelvin
        dashpots of unilateral elements are in ``natural.E_v`` instead
    dofs : DofMap
    element_names : names of the elements of the natural form, in strain order
    strain_names : (ne,) names of the natural strains (``"col.axial"``, ``"col.rot_i"``, ...)
    constraint_names : (m,) names of the constraint unknowns, the order of ``v`` and ``psi``: a
        contact has its element's name, the unknowns of slips and yield pairs
        ``"name.slip+"``, ``"name.slip-"``, ``"name.plastic+"``, ``"name.plastic-"``
    constraint_strains : (m,) int, the strain (row of ``G^T u``) each unknown enters (two unknowns
        of a pair share one); an unknown on several strains (a facet of a polygonal friction cone,
        :meth:`Frame3D.soil <unilateral.structure.Frame3D.soil>`): its primary strain
        (:attr:`Unknown.row <unilateral.structure.elements.Unknown.row>`)
    nodal_mass : (n_nodes, 3) lumped ``(m, m, J)`` per node, in the order of ``dofs.nodes``
    elements : the :class:`~unilateral.structure.elements.Element` objects of the natural form,
        in strain order (empty for a structure built by hand)
    dashpots : the attached dashpots (their viscosity is in ``C``)
    coords : dict node -> (2,) coordinates
    rayleigh : ``(a0, a1)`` of the Rayleigh damping in ``C``, or None
    foundation : :class:`~unilateral.structure.foundation.Footings` or None
        The footings on a soil medium (:meth:`Frame2D.foundation`); their contacts are not among
        ``constraint_names`` (``m`` counts the frame's own unilateral elements); in the model and
        its solutions they follow the frame's own constraints.
    geometric : (n, n) csr or None
        P-Delta (:meth:`Frame2D.p_delta`): the geometric stiffness of the gravity's axial forces,
        added to ``K`` by :meth:`to_model`.
    axial_forces : dict beam or bar name -> its static axial force under gravity (tension
        positive), with P-Delta; else None

    Results of a solution (end forces, reactions, base shear, drifts, accelerations) are in
    :mod:`unilateral.structure.forces`; :meth:`influence` and :meth:`ground_motion` build the load
    of a ground motion.
    """

    natural: NaturalForm
    M: sp.csr_matrix
    C: sp.csr_matrix | None
    dofs: DofMap
    element_names: tuple
    strain_names: tuple
    constraint_names: tuple
    constraint_strains: np.ndarray
    nodal_mass: np.ndarray
    elements: tuple = ()
    dashpots: tuple = ()
    coords: dict | None = None
    rayleigh: tuple | None = None
    foundation: object = None
    geometric: sp.csr_matrix | None = None
    axial_forces: dict | None = None

    @property
    def n(self) -> int:
        """Number of free DOFs."""
        return self.dofs.n

    @property
    def m(self) -> int:
        """Number of constraint unknowns."""
        return len(self.constraint_names)

    @property
    def constraints(self) -> tuple:
        """``(element, unknown)`` of each constraint unknown, in the order of ``v``
        (:class:`~unilateral.structure.elements.Unknown`)."""
        return tuple((e, u) for e in self.elements for u in e.unknowns)

    @property
    def unilateral_strains(self) -> np.ndarray:
        """Strain rows of the unilateral elements (soil, gap, cable, yield link, slider: every strain
        of theirs carries an unknown): no stiffness-proportional damping, ``elastic_unilateral`` energy."""
        rows, start = [], 0
        for e in self.elements:
            k = e.E.shape[0]
            if e.unilateral:
                rows.extend(range(start, start + k))
            start += k
        return np.array(rows, dtype=int)

    def families(self) -> list:
        """The constraint families of the unknowns: one :class:`~unilateral.constraints.Contact`,
        one :class:`~unilateral.constraints.Yield`, one :class:`~unilateral.constraints.Bearing` (the
        settlements of soil springs with a bearing capacity, each the partner of its contact) and one
        :class:`~unilateral.constraints.Friction` (each only if it has unknowns)."""
        pairs = self.constraints
        index = {u.name: k for k, (_, u) in enumerate(pairs)}
        of = {kind: [k for k, (_, u) in enumerate(pairs) if u.kind == kind] for kind in el.UNKNOWN_KINDS}
        families = [Contact(of["contact"])] if of["contact"] else []
        settled = [k for k in of["yield"] if pairs[k][0].kind == "soil"]     # bearing capacities of soil springs
        paired = [k for k in of["yield"] if pairs[k][0].kind != "soil"]
        if paired:
            families.append(Yield(paired, polygons=_yield_polygons(pairs, paired)))
        if settled:
            families.append(Bearing(settled, contacts=[index[pairs[k][0].name] for k in settled]))
        if of["friction"]:
            slips = [pairs[k][1] for k in of["friction"]]
            normal = [-1 if u.normal is None else index[u.normal] for u in slips]
            families.append(Friction(of["friction"], normal=normal, mu=[u.mu for u in slips]))
        return families

    def to_model(self):
        """The problem to solve: a :class:`Model` or, with a foundation, a ``FoundationModel``.

        Without a foundation: the reduced problem (eqs. 13-16) via :meth:`Model.from_natural`; DOF
        names are ``"node.dof"`` (e.g. ``"3.uy"``), constraint names :attr:`constraint_names`, and the
        constraint families those of :meth:`families`.
        With footings (:meth:`Frame2D.foundation`): the
        :class:`~unilateral.soil.FoundationModel` of the frame's ``M, K, C`` without the soil, ``T``
        of the footings, the soil's ``Phi(s)`` and the footings' gaps; the frame's own constraints
        (if any, :meth:`FoundationModel.on <unilateral.soil.FoundationModel.on>`) come first, then
        the contacts. Its solutions have for the contacts ``v`` the openings and ``psi = -c``
        (minus the contact forces).
        """
        if self.foundation is not None and not self.m:
            from .foundation import to_foundation_model

            return _soil_supported_definite(to_foundation_model(self), self.geometric)
        nat = self.natural
        model = Model.from_natural(
            nat.G, nat.E, nat.B, M=self.M, A=_nonzero_interaction(nat.A, np.shape(nat.B)[1]), r=nat.r,
            theta=nat.theta.value if isinstance(nat.theta, ConstantStrain) else nat.theta, theta_rate=nat.theta_rate,
            C=self.C, E_v=nat.E_v, dof_names=self.dofs.names,
            constraint_names=list(self.constraint_names), families=self.families(),
            on_soil=self.foundation is not None,
        )
        if self.geometric is not None:
            model.K = (model.K + self.geometric).tocsr()
            model.natural = replace(model.natural, K_geometric=self.geometric)
            if self.foundation is None:
                _check_below_buckling(model.K)
        if self.foundation is not None:
            from .foundation import to_foundation_model

            return _soil_supported_definite(to_foundation_model(self, model), self.geometric)
        return model

    def static_axial_forces(self, load, K=None) -> dict:
        """Axial forces (tension positive) of the beams and bars under the static load ``load``
        (n,), every element bilateral (contacts closed and bonded, no yield), imposed strains
        included: ``{name: N}``. ``K`` (n, n): the stiffness to solve with, if not ``G E G^T`` (a
        frame on footings: with the soil's static springs)."""
        from scipy.sparse.linalg import spsolve

        nat = self.natural
        theta = nat.theta(0.0)
        GE = nat.G @ nat.E
        K = (GE @ nat.G.T).tocsc() if K is None else sp.csc_matrix(K)
        f = np.asarray(load, dtype=float) + np.asarray(GE @ theta).ravel()
        u = np.atleast_1d(spsolve(K, f))
        sigma = nat.E @ (np.asarray(nat.G.T @ u).ravel() - theta)
        out, start = {}, 0
        for e in self.elements:
            if e.kind in AXIAL_KINDS:
                out[e.name] = float(sigma[start])
            start += e.E.shape[0]
        return out

    def geometric_stiffness(self, axial) -> sp.csr_matrix:
        """Geometric stiffness ``K_G`` (n, n) of the axial forces ``axial`` ``{beam or bar name: N}``
        (tension positive; a compression lowers the stiffness): the consistent matrix of
        :func:`unilateral.structure.geometric.consistent`.

        Beams: ``N/(30 L) [[36, 3L, -36, 3L], [3L, 4L^2, -3L, -L^2], [-36, -3L, 36, -3L], [3L, -L^2,
        -3L, 4L^2]]`` on the transverse displacements and the slopes of each bending plane (2-D:
        ``(v_i, rz_i, v_j, rz_j)``; 3-D: both planes of the local axes); bars: the string stiffness
        ``N/L [[1, -1], [-1, 1]]`` on the displacements across the chord.
        """
        return consistent(self, axial)

    def gravity(self, g=STANDARD_GRAVITY, direction=(0.0, -1.0)) -> np.ndarray:
        """Load (n,) of gravity ``g`` along ``direction`` (normalised) on the lumped masses."""
        g = _real("gravity", "g", g)
        d = dict(el.direction_terms("gravity", direction))
        if "rz" in d:
            raise ValueError("gravity: direction='rz' is not a direction of gravity; use a vector (dx, dy)")
        f = np.zeros_like(self.nodal_mass)
        f[:, 0] = self.nodal_mass[:, 0] * g * d.get("ux", 0.0)
        f[:, 1] = self.nodal_mass[:, 1] * g * d.get("uy", 0.0)
        return self.dofs.gather(f.ravel())

    def nodal_load(self, node, ux=0.0, uy=0.0, rz=0.0) -> np.ndarray:
        """Load (n,) of a force ``(ux, uy)`` and a moment ``rz`` at ``node`` (slave nodes too).

        Raises ``ValueError`` if a nonzero component acts on a DOF that nothing free can move
        (a supported DOF, or a rotation no element resists).
        """
        f = np.zeros(self.dofs.T.shape[0])
        for dof, value in (("ux", ux), ("uy", uy), ("rz", rz)):
            value = _real(f"nodal_load at node {node!r}", dof, value)
            if value:
                row = self.dofs.full_index(node, dof)
                if self.dofs.T[row].nnz == 0:
                    raise ValueError(
                        f"nodal_load at node {node!r}: {dof}={value!r} acts on a DOF that cannot move "
                        "(supported, or a rotation no element resists)"
                    )
                f[row] = value
        return self.dofs.gather(f)

    def distributed_load(self, beam, wx=0.0, wy=0.0) -> np.ndarray:
        """Load (n,) equivalent to a uniform load ``(wx, wy)`` (force per length of the beam, along
        global x and y) on the beam ``beam``: its fixed-end forces reversed.

        Each end gets the force ``(wx, wy) L/2``; the component ``w_t = -s wx + c wy`` across the
        beam (``(c, s)`` its unit chord ``i -> j``) adds the moments ``+w_t L^2/12`` at ``i`` and
        ``-w_t L^2/12`` at ``j`` (counter-clockwise). For Euler-Bernoulli beams these give the
        exact nodal displacements of the uniform load; the element forces between the nodes are
        those of the nodal loads (without the fixed-end part). Moments on a rotation that is
        supported or that no element resists (a bar's end) are dropped. Use it as a term of a
        :class:`~unilateral.loads.LoadHistory` (``LoadHistory(st.distributed_load("girder", wy=-q))``).
        """
        where = f"distributed_load on beam {beam!r}"
        element = next((e for e in self.elements if e.name == beam and e.kind == "beam"), None)
        if element is None:
            beams = [e.name for e in self.elements if e.kind == "beam"]
            raise ValueError(f"{where}: no beam {beam!r} (beams: {', '.join(map(repr, beams[:10])) or 'none'})")
        wx, wy = _real(where, "wx", wx), _real(where, "wy", wy)
        i, j = element.dofs[0][0], element.dofs[3][0]
        L, (c, s) = el.chord(where, i, self.coords[i], j, self.coords[j])
        moment = (-s * wx + c * wy) * L * L / 12.0
        f = np.zeros(self.dofs.T.shape[0])
        for node, sign in ((i, 1.0), (j, -1.0)):
            f[self.dofs.full_index(node, "ux")] += wx * L / 2
            f[self.dofs.full_index(node, "uy")] += wy * L / 2
            f[self.dofs.full_index(node, "rz")] += sign * moment
        return self.dofs.gather(f)

    def influence(self, direction="ux") -> np.ndarray:
        """Influence vector ``r`` (n,) of a rigid ground translation along ``"ux"`` or ``"uy"``.

        ``r`` is 1 on the free translations along ``direction`` and 0 elsewhere (rotations 0):
        with ``u_full = T r`` every node that is not supported moves by one unit along the
        direction (rigidly linked nodes follow their masters). A ground acceleration ``a_g(t)``
        then loads the structure, in displacements relative to the ground, with ``-M r a_g(t)``.
        """
        if direction not in ("ux", "uy"):
            raise ValueError(f"direction={direction!r} is not valid for a ground motion; valid: 'ux', 'uy'")
        return np.array([1.0 if dof == direction else 0.0 for _, dof in self.dofs.free])

    def ground_motion(self, a_g, direction="ux") -> tuple:
        """The term ``(-M r, a_g)`` of a ground acceleration ``a_g(t)`` along ``direction``.

        For :class:`~unilateral.loads.LoadHistory`: ``LoadHistory(st.gravity(), [st.ground_motion(a_g)])``.
        ``a_g`` is a time function (e.g. a :class:`~unilateral.loads.GroundMotion` in the model's
        units); the displacements solved are relative to the ground; the absolute acceleration
        is ``u'' + r a_g`` (:func:`unilateral.structure.forces.absolute_acceleration`).
        """
        if not callable(a_g):
            raise TypeError(f"a_g must be a time function a_g(t), got {a_g!r}")
        return -np.asarray(self.M @ self.influence(direction)).ravel(), a_g

    def element_deformations(self, u, v, t=None) -> tuple[np.ndarray, np.ndarray]:
        """Deformations of the strains of the constraint unknowns (:attr:`constraint_strains`).

        Parameters
        ----------
        u : (..., n) displacements;  v : (..., m) constraint unknowns
        t : (N,) times of ``u`` (N, n); needed with support motions (imposed strains varying in time)

        Returns
        -------
        e : (..., m) total strain: the relative displacement along the element (soil, gap:
            positive = separating; a slip: the tangential motion), the elongation (cable, yield
            link) or the beam's end rotation (hinge)
        eps : (..., m) elastic part ``e - (B v)_row - theta`` (force ``= k eps`` plus the Kelvin part)
        """
        u = np.asarray(u, dtype=float)
        v = np.asarray(v, dtype=float)
        rows = self.constraint_strains
        Gu = self.natural.G[:, rows]
        steps = int(np.prod(u.shape[:-1]))
        e = (Gu.T @ u.reshape(steps, self.n).T).T.reshape(u.shape[:-1] + (self.m,))
        Bv = (self.natural.B[rows] @ v.reshape(steps, self.m).T).T.reshape(e.shape)
        if t is None and not isinstance(self.natural.theta, ConstantStrain):
            raise ValueError("element_deformations: give the times t of u (the imposed strains vary in time)")
        return e, e - Bv - self.natural.imposed_strains(t)[..., rows]

    def element_forces(self, t, u, v, udot=None, vdot=None) -> np.ndarray:
        """Forces (tension positive) of the strains of the constraint unknowns, ``sigma`` of
        :attr:`constraint_strains` (a hinge: the end moment, counter-clockwise on the beam).

        Parameters
        ----------
        t : (N,) times;  u, udot : (N, n);  v, vdot : (N, m)
            ``udot`` and ``vdot`` are needed with Kelvin elements. ``psi = b sigma - A v - r``
            holds for the associated ``psi`` (a :class:`~unilateral.Solution` holds ``P psi``:
            a slip's ``psi + mu psi_normal``), so for a contact the force is also ``b (psi + r)``.

        Returns
        -------
        (N, m)
        """
        sigma = self.natural.stresses(t, np.atleast_2d(u), np.atleast_2d(v),
                                      None if udot is None else np.atleast_2d(udot),
                                      None if vdot is None else np.atleast_2d(vdot))
        return sigma[:, self.constraint_strains]

    def node_displacement(self, sol, node, dof) -> np.ndarray:
        """History (N+1,) of DOF ``dof`` of ``node`` (supported, moving and slave nodes included)."""
        if sol.u is None or sol.u.shape[1] != self.n:
            shape = None if sol.u is None else sol.u.shape
            raise ValueError(f"sol.u must have shape (N+1, {self.n}) for this structure, got {shape}")
        row = self.dofs.T[self.dofs.full_index(node, dof)]
        imposed = support_motion.support_displacement(self, node, dof, sol)
        return np.asarray(row @ sol.u.T).ravel() + (0.0 if imposed is None else imposed)


def _yield_polygons(pairs, indices) -> list:
    """The yield multipliers of ``indices`` that are the facets of one polygon of more than four
    facets: the unknowns ``name.facet<k>`` of one element and one ``name`` (a hinge's interaction
    polygon: a 3-D hinge's on its end moments, a 2-D one's on the axial force and an end moment; two
    such hinges of one 2-D beam share its axial strain, not their polygons). The pairs of a
    multi-linear hinge's segments (:func:`.elements.backbone_hinge`) are no polygon: they lie on
    one strain, and their hardening makes them independent."""
    groups: dict = {}
    for k in indices:
        element, unknown = pairs[k]
        base, _, facet = unknown.name.rpartition(".")
        if facet.startswith("facet") and facet[5:].isdigit():
            groups.setdefault((id(element), base), []).append(k)
    return [sorted(members) for members in groups.values() if len(members) > 4]


def _check_below_buckling(K) -> None:
    """Refuse a P-Delta stiffness ``K - K_G`` (n, n) that is not positive definite: the gravity load
    reaches the buckling load of the structure held bilateral."""
    from ..model import check_definite

    try:
        check_definite("K", K, strict=True)
    except ValueError as exc:
        raise ValueError(f"p_delta: K - K_G is not positive definite: the gravity load reaches the "
                         f"buckling load of the structure held bilateral ({exc})") from None


def _soil_supported_definite(model, geometric):
    """``model`` (a FoundationModel), with P-Delta (``geometric`` not None) checked below buckling on
    the soil's static springs (:meth:`~unilateral.soil.FoundationModel.static_model`)."""
    if geometric is not None:
        try:
            static = model.static_model()
        except ValueError as exc:
            raise ValueError(f"p_delta: K - K_G is not positive definite on the soil's static springs: the gravity "
                             f"load reaches the buckling (overturning) load of the structure on its footings ({exc})") \
                from None
        _check_below_buckling(sp.csr_matrix(static.K))
    return model
