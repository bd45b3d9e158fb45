"""A 3-D frame builder: nodes with six DOFs, supports, rigid links and diaphragms, beams, bars,
springs, dashpots, masses and the unilateral elements (tensionless soil, pounding gaps, slack
cables) -> the natural form and a :class:`~unilateral.Model`.

Example (a portal frame in the x-z plane on tensionless soil)::

    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0); fr.node(2, 5.0, 0.0, 0.0)
    fr.node(3, 0.0, 0.0, 3.0); fr.node(4, 5.0, 0.0, 3.0)
    for base in (1, 2):
        fr.support(base, ux=True, uy=True, uz=False, rx=True, rz=True)
        fr.soil(f"soil{base}", base, 1e5, c=1e3)            # along "uz"
    section = dict(E=3e7, A=0.16, Iy=2e-3, Iz=2e-3, G=1.2e7, J=3e-3)
    fr.beam("c1", 1, 3, **section); fr.beam("c2", 2, 4, **section); fr.beam("g", 3, 4, **section)
    fr.mass(3, 20.0); fr.mass(4, 20.0)
    st = fr.build()
    model = st.to_model()
    q = st.gravity(9.81) + st.nodal_load(3, ux=100.0)

Strain and sign conventions of the elements are in :mod:`unilateral.structure.elements3d`, the
kinematics of rigid links and diaphragms in :mod:`unilateral.structure.dofs3d`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp  # noqa: F401  (the annotations of the fields Structure3D inherits resolve here)

from ..loads.units import STANDARD_GRAVITY
from ..model import NaturalForm  # noqa: F401  (the annotations of the fields Structure3D inherits resolve here)
from . import elements as el, rigid, support_motion
from . import elements3d as el3
from .built import Structure
from .checks import _friction, _hardening, _real, _strength
from .dofs import DofMap  # noqa: F401  (likewise)
from .dofs3d import IN_PLANE, DofMap3D
from .frame_base import _Frame
from .geometric import with_gravity
from .rigid3d import RigidBoxes


class Frame3D(RigidBoxes, support_motion.SupportMotions, _Frame):
    """Builder of a space frame with unilateral elements (foundation uplift, pounding, cables).

    Nodes have the DOFs ``ux``, ``uy``, ``uz`` (along global x, y, z) and ``rx``, ``ry``, ``rz``
    (rotations about them, right-hand rule). A rotation is a DOF only where something uses it
    (a beam end, a spring along it, a rotary inertia, a rigid link or diaphragm whose slave is
    offset), as in :class:`~unilateral.structure.Frame2D`; a translation or a rotation that nothing
    stiffens makes :meth:`build` raise, naming it (support it, or connect an element).

    Define nodes first, then supports, links, elements and masses in any order, then :meth:`build`.
    Every element name must be unique. Each contact (:meth:`soil`, :meth:`cable`, :meth:`gap`) adds
    one unilateral unknown ``v >= 0`` and one reaction ``psi <= 0``, named after the element, with
    the conventions of :class:`~unilateral.structure.Frame2D`.

    Masses: :meth:`mass` (with rotary inertia), and a beam's own mass (``rho`` of :meth:`beam`).
    Damping: :meth:`rayleigh`, :meth:`rayleigh_from_ratios`, :meth:`modal_damping`, :meth:`dashpot`
    and the Kelvin dashpots of contacts. Loads are vectors of the built :class:`Structure3D`.
    Coulomb friction on contacts (``mu`` of :meth:`soil` and :meth:`gap`) is a polygonal friction
    cone of ``facets`` facets in the tangent plane (default 4: a four-sided pyramid), circumscribing
    Coulomb's circle. Rigid footings in plan on a soil medium (:meth:`foundation`: a grid of
    contact patches, rocking about both axes). Yielding links and sliders (:meth:`yield_link`,
    :meth:`slider`) along any direction, as in 2-D. Plastic hinges at beam ends (:meth:`hinge`, after
    the beam) yield under the end moments about both bending axes, within a polygonal interaction
    surface (an ellipse's circumscribed polygon, a diamond or a box). Flexible footings in plan
    (:meth:`foundation` with ``nodes``: a patch under each node of a grid). Second-order effects of
    gravity: :meth:`p_delta`. Rigid contacts (:meth:`contact`) and rigid boxes rocking on their four
    corners (:meth:`rigid_box`), for ``method="moreau-jean"`` (:mod:`unilateral.structure.rigid3d`).
    """

    _dof_names = el3.DOF_NAMES
    _axes = el3.AXES

    def __init__(self):
        super().__init__()
        self._ties: dict = {}
        self._foundations = []
        self._p_delta: tuple | None = None

    # ------------------------------------------------------------------ nodes and supports
    def node(self, node_id, x, y, z) -> None:
        """Define node ``node_id`` (int or str) at ``(x, y, z)``."""
        self._define_node(node_id, (x, y, z))

    def support(self, node, ux=True, uy=True, uz=True, rx=False, ry=False, rz=False) -> None:
        """Restrain DOFs of ``node`` (True = restrained; default: a pin); restrained DOFs are
        removed from ``u``. Repeated calls add up."""
        where, flags = self._support_flags(node, (ux, uy, uz, rx, ry, rz))
        tied = [dof for dof, flag in flags.items() if flag and self._tied(node, dof)]
        if tied:
            master = self._ties[node][0]
            raise ValueError(f"{where}: {', '.join(tied)} of node {node!r} follow node {master!r} (a rigid link or "
                             "diaphragm); support the master node instead")
        self._restrained |= {(node, dof) for dof, flag in flags.items() if flag}

    def rigid_link(self, master, slave) -> None:
        """Attach node ``slave`` rigidly (all six DOFs) to node ``master``: ``u_s = u_m + theta_m x
        (x_s - x_m)``, ``theta_s = theta_m`` (:mod:`unilateral.structure.dofs3d`).

        The slave's DOFs are eliminated; chains are allowed (a master may itself be a slave). A
        slave node cannot be supported; support its master.
        """
        self._tie(f"rigid_link({master!r}, {slave!r})", master, slave, el3.DOF_NAMES)

    def rigid_diaphragm(self, master, slaves) -> None:
        """A rigid floor in the plane ``z = z_master``: the ``ux``, ``uy``, ``rz`` of each slave follow
        the master's in-plane rigid motion, ``ux_s = ux_m - (y_s - y_m) rz_m``,
        ``uy_s = uy_m + (x_s - x_m) rz_m``, ``rz_s = rz_m``; the slaves keep ``uz``, ``rx``, ``ry``.

        Parameters
        ----------
        master : node id
            E.g. a node at the floor's centre of mass (support its ``uz``, ``rx``, ``ry`` if nothing
            else stiffens them).
        slaves : sequence of node ids, at the master's z
        """
        where = f"rigid_diaphragm({master!r}, ...)"
        self._node(where, "master", master)
        if isinstance(slaves, (str, bytes)) or not hasattr(slaves, "__iter__"):
            raise TypeError(f"{where}: slaves must be a sequence of node ids, got {slaves!r}")
        slaves = list(slaves)
        if not slaves:
            raise ValueError(f"{where}: slaves is empty; give the nodes of the floor")
        z = self._coords[master][2]
        for k, slave in enumerate(slaves):
            self._node(where, f"slaves[{k}]", slave)
            if abs(self._coords[slave][2] - z) > 1e-9 * max(1.0, abs(z)):
                raise ValueError(f"{where}: slaves[{k}]={slave!r} is at z={self._coords[slave][2]:g}, not in the "
                                 f"plane z={z:g} of the master")
            if slaves.index(slave) != k:
                raise ValueError(f"{where}: slaves[{k}]={slave!r} is given twice")
        before = dict(self._ties)
        try:
            for slave in slaves:
                self._tie(where, master, slave, IN_PLANE)
        except ValueError:
            self._ties = before                         # all the slaves or none
            raise

    def mass(self, node, m, *, Jx=0.0, Jy=0.0, Jz=0.0) -> None:
        """Lumped mass ``m`` on ``ux``, ``uy`` and ``uz`` of ``node`` and rotary inertias ``Jx``,
        ``Jy``, ``Jz`` (mass length^2) on ``rx``, ``ry``, ``rz``.

        Repeated calls add up. A slave node's mass acts on its master through ``T^T M T``.
        """
        where = f"mass at node {node!r}"
        self._node(where, "node", node)
        m = _real(where, "m", m, ">=0")
        add = np.array([m, m, m] + [_real(where, arg, J, ">=0") for arg, J in (("Jx", Jx), ("Jy", Jy), ("Jz", Jz))])
        self._mass[node] = self._mass.get(node, np.zeros(6)) + add

    def p_delta(self, enabled=True, *, g=STANDARD_GRAVITY, direction=(0.0, 0.0, -1.0)) -> None:
        """P-Delta: the geometric stiffness of the gravity's axial forces, constant in time, in ``K``.

        As :meth:`Frame2D.p_delta <unilateral.structure.Frame2D.p_delta>`: :meth:`build` solves the
        linear static problem of the gravity ``g`` along ``direction`` (a vector (dx, dy, dz),
        normalised; default -z) on the lumped masses with every element bilateral, takes the axial
        force ``N`` (tension positive) of each beam and bar and adds their consistent geometric
        stiffness (:meth:`Structure3D.geometric_stiffness`: the cubic of both bending planes of each
        beam, the string ``N/L`` across a bar; the torsional term ``N I_p/(A L)`` is left out, see
        :mod:`unilateral.structure.geometric`) to the ``K`` of :meth:`Structure3D.to_model`, which
        refuses a gravity at or above the buckling load (``K - K_G`` not positive definite).
        Element forces and the elastic energies stay those of ``G E G^T``; the energy balance counts
        ``u^T K_G u / 2`` as its ``geometric`` term. With footings on a soil medium the static state
        holds them on the soil's static springs (``Phi(0)``), as in 2-D. ``enabled=False`` switches it off.
        """
        if not enabled:
            self._p_delta = None
            return
        self._p_delta = (_real("p_delta", "g", g, ">0"), _gravity_direction("p_delta", direction))

    def foundation(self, name, node=None, *, soil, width=None, length=None, patches=None, nodes=None,
                   horizontal="support", gap=0.0, mass=0.0, Jx=0.0, Jy=0.0, Jz=0.0, mu=None, facets=None) -> None:
        """A rigid rectangular footing on a soil medium, resting on an ``nx x ny`` grid of unilateral
        contact patches, or a flexible one (``nodes``: one patch per node of a grid)
        (:mod:`unilateral.structure.foundation3d`); :meth:`Structure3D.to_model
        <unilateral.structure.Structure.to_model>` then gives a
        :class:`~unilateral.soil.FoundationModel`, as for :meth:`Frame2D.foundation
        <unilateral.structure.Frame2D.foundation>`.

        The footing is centred on ``node`` (its base at the node's z), which carries its ``uz`` and its
        rocking ``rx``, ``ry``; the upward displacement of the patch at ``(x, y)`` is
        ``uz + rx (y - y_node) - ry (x - x_node)``. Footings on a half-space (or a layered soil) share
        it: every patch of every footing is coupled to every other through the ground.

        With ``horizontal="soil"`` the footing also rests on the soil horizontally and slides in plan:
        each patch carries a horizontal force ``(fx, fy)`` through the soil's x-y-z flexibility,
        limited by a polygonal Coulomb cone of ``facets`` facets (``d_k . f <= mu c``); the footing's
        displacement at a patch is ``(ux - (y - y_node) rz, uy + (x - x_node) rz)``, so its sway, rocking
        and twist couple through the ground (:mod:`unilateral.structure.foundation3d`). Every footing of
        the frame then slides, with the same ``facets``.

        Parameters
        ----------
        name : str
            Contacts are named ``"name.1"`` ... (x varying fastest, then y).
        node : node id
        width, length : float, length
            Plan dimensions along x and y.
        soil : SoilFlexibility, SoilSpec or dict
            As for ``Frame2D.foundation`` (``{"model": "halfspace", "Vs": ..., "nu": ..., "rho": ...}``,
            ``"layered"``, ``"cones"``, ``"winkler-kelvin"``).
        patches : (int, int) or int
            ``(nx, ny)`` patches along x and y (one int: both), at most 400 in all; rigid only
            (default ``(3, 3)``).
        horizontal : {"support", "none", "soil"}
            ``"support"`` (default): ``ux``, ``uy`` and ``rz`` of ``node`` supported; ``"none"``: the
            frame holds the footing in plan (springs, other members); ``"soil"``: the footing slides
            on the soil in plan (``mu``, ``facets``; ``ux``, ``uy``, ``rz`` of ``node`` must be free).
        gap : float or (nx ny,) array, length
            Opening of each patch at ``u = 0`` with the soil unloaded.
        mass, Jx, Jy, Jz : float >= 0
            The footing's own mass (on the translations of ``node``) and rotary inertias (``Jz``: its
            twist, e.g. for a footing that slides in plan); a rigid footing's only.
        mu : float > 0
            ``horizontal="soil"``: the friction coefficient of the footing on the soil.
        facets : int, even >= 4
            ``horizontal="soil"``: the facets of each patch's friction cone in plan (default 8: its
            strength is at most ``sec(pi/8) = 1.082`` times Coulomb's; 4, the pyramid ``+-x``, ``+-y``,
            is ``sqrt 2`` times along the diagonals, and its anisotropy twists a footing pushed off
            its axes much more: 0.10 rad against 0.018 with 8 and 0.012 with 16 facets in
            ``tests/test_sliding_footings3d.py``'s tower at 0.5 rad). With 32 facets the pivoting
            solver failed at a step of that run.
        """
        from .foundation3d import Footings3D, build_footing, check_plan_overlap

        where = self._label("foundation", name)
        self._check_footing_nodes(where, node, nodes, patches, (mass, Jx, Jy, Jz))
        fnd = build_footing(name=name, node=node, width=width, length=length, soil=soil,
                            patches=(3, 3) if patches is None else patches, horizontal=horizontal, gap=gap,
                            coords=self._coords, mu=mu, facets=facets, nodes=nodes)
        used = {n: f.name for f in self._foundations for n in f.contact_nodes()}
        used |= {f.node: f.name for f in self._foundations if f.rigid}
        for contact in dict.fromkeys(fnd.contact_nodes()):
            if contact in used:
                raise ValueError(f"{where}: node {contact!r} already rests on footing {used[contact]!r}; give each "
                                 "footing its own nodes")
        self._check_on_soil(where, fnd)
        check_plan_overlap(self._foundations, fnd, where)
        Footings3D(self._foundations + [fnd])               # one soil for all: the same medium, one elevation
        if horizontal == "support":
            self.support(fnd.node, ux=True, uy=True, uz=False, rz=True)
        if mass or Jx or Jy or Jz:
            self.mass(node, mass, Jx=Jx, Jy=Jy, Jz=Jz)
        self._foundations.append(fnd)
        self._names.add(name)

    def _check_footing_nodes(self, where, node, nodes, patches, inertia) -> None:
        """The nodes of a new footing are defined: a rigid one's ``node``, or a flexible one's grid
        ``nodes`` (then no ``patches`` and no own ``inertia`` = (mass, Jx, Jy, Jz))."""
        from .foundation3d import grid_nodes

        if nodes is None:
            if node is None:
                raise ValueError(f"{where}: give node (a rigid footing's node) or nodes (a flexible footing's grid "
                                 "of nodes)")
            self._node(where, "node", node)
        else:
            for i, row in enumerate(grid_nodes(where, nodes)):
                for j, other in enumerate(row):
                    self._node(where, f"nodes[{i}][{j}]", other)
            if node is not None:
                self._node(where, "node", node)
            if patches is not None:
                raise ValueError(f"{where}: patches={patches!r}: a flexible footing has one patch per node of "
                                 "nodes; remove patches")
            if any(inertia):
                mass, Jx, Jy, Jz = inertia
                raise ValueError(f"{where}: mass={mass!r}, Jx={Jx!r}, Jy={Jy!r}, Jz={Jz!r} are for a rigid footing; "
                                 "give a flexible footing's masses to its nodes with Frame3D.mass")

    def _check_on_soil(self, where, fnd) -> None:
        """Raise if a DOF a footing moves on the soil is supported (rigid: or follows another node)."""
        dofs = ("uz", "ux", "uy", "rz") if fnd.sliding else ("uz",)
        for node in dict.fromkeys(fnd.contact_nodes()):
            for dof in dofs if fnd.rigid else [d for d in dofs if d != "rz"]:
                if (node, dof) in self._restrained or (fnd.rigid and self._tied(node, dof)):
                    what = "move on" if dof == "uz" else "slide on"
                    raise ValueError(f"{where}: {dof} of node {node!r} is supported" +
                                     (" (or follows another node)" if fnd.rigid else "") +
                                     f": the footing could not {what} the soil; remove that support")

    # The damping of :class:`_Frame`, listed as this class's own: the API reference documents those only.
    rayleigh = _Frame.rayleigh
    rayleigh_from_ratios = _Frame.rayleigh_from_ratios
    modal_damping = _Frame.modal_damping
    yield_link = _Frame.yield_link
    slider = _Frame.slider

    # ------------------------------------------------------------------ bilateral elements
    def beam(self, name, i, j, *, E, A, Iy, Iz, G, J, vecxz=None, axial_strain=0.0, rho=None) -> None:
        """Euler-Bernoulli beam-column (no shear deformation) from node ``i`` to node ``j``.

        Natural strains (:mod:`unilateral.structure.elements3d`): elongation, twist, and the end
        rotations about the local ``z'`` and ``y'`` relative to the chord; stiffness
        ``diag(EA/L, GJ/L, EIz/L [[4, 2], [2, 4]], EIy/L [[4, 2], [2, 4]])``.

        Parameters
        ----------
        E, A : Young's modulus (force/length^2) and area (length^2), > 0
        Iy, Iz : second moments of area (length^4) about the local ``y'`` and ``z'``, > 0
        G, J : shear modulus (force/length^2) and torsion constant (length^4), > 0
        vecxz : (3,) vector, optional
            A vector in the local ``x'-z'`` plane, as OpenSees's ``geomTransf``: ``x'`` runs from
            ``i`` to ``j``, ``y' = vecxz x x'`` (normalised), ``z' = x' x y'``. Default: global Z,
            or global X for a member along Z. It must not be parallel to the member.
        axial_strain : imposed (e.g. thermal) axial strain, constant in time
        rho : mass per volume (force time^2/length^4), or None: the beam's own mass ``rho A L``,
            lumped half at each end node on ``ux``, ``uy``, ``uz`` (no rotary inertia), as
            :meth:`mass` would add it.
        """
        where = self._label("beam", name)
        self._two_nodes(where, i, j)
        props = {arg: _real(where, arg, value, ">0")
                 for arg, value in (("E", E), ("A", A), ("Iy", Iy), ("Iz", Iz), ("G", G), ("J", J))}
        element = el3.beam(name, i, self._coords[i], j, self._coords[j], vecxz=vecxz,
                           axial_strain=_real(where, "axial_strain", axial_strain), **props)
        if rho is not None:
            L = el3.chord(where, i, self._coords[i], j, self._coords[j])[0]
            half = _real(where, "rho", rho, ">=0") * props["A"] * L / 2
            for node in (i, j):
                self.mass(node, half)
        self._add(element)
        self._beams[name] = element

    def bar(self, name, i, j, E, A, *, axial_strain=0.0, Fy=None, Fy_t=None, Fy_c=None, hardening=0.0) -> None:
        """Axial bar from node ``i`` to node ``j`` (strain: elongation, stiffness ``EA/L``); ``Fy`` (or
        ``Fy_t``, ``Fy_c``), ``hardening``: axial yield, as :meth:`Frame2D.bar
        <unilateral.structure.Frame2D.bar>`."""
        where = self._label("bar", name)
        self._two_nodes(where, i, j)
        bar = el3.axial("bar", name, i, self._coords[i], j, self._coords[j], E=_real(where, "E", E, ">0"),
                        A=_real(where, "A", A, ">0"),
                        theta=_real(where, "axial_strain", axial_strain) * el3.chord(
                            where, i, self._coords[i], j, self._coords[j])[0])
        self._add(self._axial_yield(where, bar, Fy, Fy_t, Fy_c, hardening))

    def spring(self, name, i, k, *, j=None, direction="uz") -> None:
        """Linear spring ``k`` from node ``i`` to the ground (``j=None``) or to node ``j``.

        Strain: extension ``d . u_i`` to the ground, ``d . (u_j - u_i)`` between two nodes, for
        ``direction`` ``"ux"``, ``"uy"``, ``"uz"``, ``"rx"``, ``"ry"``, ``"rz"`` or a vector
        ``(dx, dy, dz)`` (normalised). ``k``: force/length (force length/rad for a rotation).
        """
        self._add(self._directional("spring", name, i, j, k, direction))

    def dashpot(self, name, i, c, *, j=None, direction="uz") -> None:
        """Attached linear dashpot ``c`` (acts in tension too; goes into ``C``), like :meth:`spring`."""
        self._dashpots.append(self._directional("dashpot", name, i, j, c, direction))
        self._names.add(name)

    # ------------------------------------------------------------------ unilateral elements
    def soil(self, name, node, k, *, c=0.0, direction="uz", gap=0.0, capacity=0.0, mu=None, kt=None, ct=0.0,
             tangent=None, facets=4, bearing=None) -> None:
        """Tensionless soil element under ``node``: spring ``k`` and dashpot ``c`` in parallel (a
        Kelvin element) in series with a unilateral contact, as
        :meth:`Frame2D.soil <unilateral.structure.Frame2D.soil>`.

        Strain ``e = d . u_node`` along ``direction`` (default ``"uz"``), which points from the soil
        to the node (the direction in which the node separates); ``e < 0`` compresses the soil.
        ``v >= 0`` is the separation; the force ``sigma = k (e - v + gap) + c (e' - v')`` (tension
        positive) satisfies ``sigma <= capacity``.

        Parameters
        ----------
        k : stiffness, force/length, > 0;  c : viscosity, force time/length, >= 0
        direction : ``"ux"``, ``"uy"``, ``"uz"`` or a vector ``(dx, dy, dz)``
        gap : initial gap between node and soil (imposed strain ``-gap``), length
        capacity : the tension ``r >= 0`` carried before separating, force (default 0)
        bearing : the bearing capacity ``Q > 0`` of the spring, force, or None: the compression never
            exceeds it, beyond it the soil settles plastically (the unknown ``"name.plastic-"``), as
            :meth:`Frame2D.soil <unilateral.structure.Frame2D.soil>`
        mu : Coulomb friction coefficient >= 0, or None (no friction: the node slides freely)
        kt : stick stiffness, force/length, > 0, along each tangent axis; required with ``mu``
        ct : viscosity of a Kelvin dashpot in parallel with ``kt``, force time/length (default 0)
        tangent : (3,) vector, optional: the first tangent axis ``t1`` (projected on the tangent
            plane; default global X, or Y for a contact along X); ``t2 = d x t1``
        facets : int, even, >= 4 (default 4)
            The number ``N`` of facets of the polygonal friction cone (with ``mu`` only).

        Notes
        -----
        With ``mu``, the tangential strains ``t1 . u_node`` and ``t2 . u_node`` carry the forces
        ``T = (T1, T2)`` (stiffness ``kt`` along each axis, viscosity ``ct``) within a polygonal
        friction cone of ``N`` facets: facet ``k`` has the outward unit normal
        ``d_k = (cos th_k, sin th_k)`` on ``(t1, t2)``, ``th_k = 2 pi k / N`` (facet 0 normal to
        ``t1``: ``tangent`` turns the polygon), and keeps ``d_k . T <= mu N``, ``N = capacity -
        sigma`` the compression of the contact; its slip multiplier ``lambda_k >= 0`` (an unknown of
        the ``"friction"`` family, rate law) slips the node by ``lambda_k d_k``. The polygon
        *circumscribes* Coulomb's circle ``|T| <= mu N`` (its facets touch it), so ``N = 4`` is
        today's pyramid and every facet normal is exact:

        - strength: sliding under a tangential force along ``phi`` starts at
          ``mu N / cos(phi - th_k)`` (``th_k`` the nearest facet normal): exact along the ``N``
          facet normals, too strong by at most the factor ``1 / cos(pi/N)`` along the vertices
          (relative error ``sec(pi/N) - 1 ~ (pi/N)^2 / 2``: 41 % for N = 4, 8.2 % for 8, 2.0 % for
          16, 0.48 % for 32); it is never weaker than Coulomb's.
        - slip direction: the slip rate lies in the polygon's normal cone at the friction force
          ``T`` (along ``d_k`` on facet ``k``, between ``d_k`` and ``d_k+1`` at their vertex), so it
          is at most ``pi/N`` away from ``T`` (Coulomb: along ``T``): 45 degrees for N = 4, 22.5
          for 8, 11.25 for 16, 5.6 for 32. In steady sliding under a tangential load ``P`` (with
          inertia and viscous drag) ``T = proj(P)``, the projection of ``P`` on the polygon, and
          the slip runs along ``P - proj(P)`` instead of along ``P``, also within ``pi/N``: exact
          along the facet normals and the vertices; the bound is approached just above the onset
          of sliding near a vertex, and the error shrinks as ``P`` grows past ``mu N``.

        Choose ``tangent`` (with ``N = 4``) along the expected sliding, or raise ``N``. The inscribed
        polygon (facets at ``mu N cos(pi/N)``) would have the same direction error and the strength
        error ``1 - cos(pi/N)`` on the safe side; the circumscribed one keeps ``N = 4`` as it was.
        ``N`` even (the facets come in opposite pairs, as the slip pairs of 2-D friction), at least 4
        (fewer cannot bound the tangent plane). The unknowns: ``N = 4``: ``"name.slip+"``,
        ``"name.slip-"`` (along ``+-t1``: the 2-D names), ``"name.slip2+"``, ``"name.slip2-"``
        (along ``+-t2``); ``N > 4``: ``"name.facet0"`` ... ``"name.facet<N-1>"`` (facet ``k`` along
        ``th_k``), ordered in opposite pairs ``facet0, facet<N/2>, facet1, facet<N/2+1>, ...``
        (:func:`~unilateral.structure.elements3d.facet_unknowns`).

        With ``N > 4`` any three facet columns of ``B`` are linearly dependent (two tangential
        strains), so a basis with three facets is singular: block principal pivoting (``lcp="bpp"``,
        the default) keeps at most two facets of a cone active (its group rule), so that a step that
        violates many facets at once (a sudden push far beyond the strength) is solved too
        (``tests/test_friction_cone.py``: 20 times the strength on 16 facets, equal to Lemke's
        method).
        """
        where, ends, terms = self._ends("soil", name, node, None, direction, ("node", None))
        element = self._contact("soil", where, name, ends, terms, k=k, c=c, gap=gap, capacity=capacity,
                                friction=(_friction(where, mu, kt, ct), tangent, _facets(where, mu, facets)))
        if bearing is not None:
            element = el.with_bearing(element, name, _real(where, "bearing", bearing, ">0"))
        self._add(element)

    def gap(self, name, i, j, k, *, gap=0.0, c=0.0, direction=None, mu=None, kt=None, ct=0.0,
            tangent=None, facets=4) -> None:
        """Pounding (gap) link between nodes ``i`` and ``j``: compression-only contact spring ``k``
        (force/length, with a Kelvin dashpot ``c``, force time/length) that engages when the gap
        closes, as :meth:`Frame2D.gap <unilateral.structure.Frame2D.gap>`.

        Strain ``e = d . (u_j - u_i)``: the opening along ``direction`` (a vector or ``"ux"``,
        ``"uy"``, ``"uz"``; default: the unit vector from ``i`` to ``j``). The link engages when
        ``e <= -gap`` (length); ``v >= 0`` is the gap opening. ``mu``, ``kt``, ``ct``, ``tangent``,
        ``facets``: Coulomb friction across the closed gap, a polygonal friction cone of ``facets``
        facets (even, >= 4, default 4: the four-sided pyramid), with the conventions, the unknowns'
        names and the error bounds of :meth:`soil` (tangential strains ``t1 . (u_j - u_i)``,
        ``t2 . (u_j - u_i)``).
        """
        if direction is None and self._known(i) and self._known(j) and i != j:
            direction = el3.chord(f"gap {name!r}", i, self._coords[i], j, self._coords[j])[1]
        where, ends, terms = self._ends("gap", name, i, j, "ux" if direction is None else direction)
        self._add(self._contact("gap", where, name, ends, terms, k=k, c=c, gap=gap, capacity=0.0,
                                friction=(_friction(where, mu, kt, ct), tangent, _facets(where, mu, facets))))

    def cable(self, name, i, j, E, A, *, slack=0.0, capacity=0.0) -> None:
        """Tension-only cable (bar) from node ``i`` to node ``j`` that goes slack in compression.

        Strain ``e`` = elongation; ``B = -1`` and ``theta = slack``: the axial force is
        ``EA/L (e + v - slack)`` with ``v >= 0`` the slack shortening; taut once ``e >= slack``.
        Negative ``slack``: a pretensioned cable. ``capacity``: the compression carried (default 0).
        """
        where = self._label("cable", name)
        self._two_nodes(where, i, j)
        self._add(el3.cable(name, i, self._coords[i], j, self._coords[j], E=_real(where, "E", E, ">0"),
                            A=_real(where, "A", A, ">0"), slack=_real(where, "slack", slack),
                            capacity=_real(where, "capacity", capacity, ">=0")))

    # ------------------------------------------------------------------ plasticity
    def hinge(self, name, beam, end, *, My, Mz, shape="ellipse", facets=None, k=None, hardening=0.0) -> None:
        """Plastic hinge at the end ``"i"`` or ``"j"`` of the beam ``beam`` (define the beam first),
        yielding under the end moments about both bending axes: a polygonal interaction surface.

        The end moments ``M = (M_y', M_z')`` (the beam's natural stresses ``roty`` and ``rotz`` at that
        end: the moments acting on the beam about its local ``y'`` and ``z'``, right-hand positive,
        force length) stay within a convex polygon of ``N`` facets: facet ``k`` keeps
        ``n_k . (M - alpha) <= r_k`` (``n_k`` its unit outward normal on ``(M_y', M_z')``, ``r_k`` >
        0, force length, :func:`~unilateral.structure.elements3d.hinge_polygon`). Each facet is an
        unknown ``"name.facet<k>"`` of the ``"yield"`` family, a multiplier ``lambda_k >= 0`` (rad)
        that only grows, while its facet yields (``d lambda_k >= 0``, ``psi_k <= 0``, ``psi_k d
        lambda_k = 0``); the plastic rotation ``theta_p = sum_k lambda_k n_k`` (rad, on ``(y', z')``:
        associated flow, normal to the active facet, in the normal cone at a vertex) is an imposed
        strain on the two end rotations. Its column of ``B`` is ``n_k`` on those two strains (the
        primary entry on the larger component, the other an extra entry, as for the facets of a
        friction cone, :func:`~unilateral.structure.elements3d.facet_unknowns`). The unknowns come
        in opposite pairs ``(k, k + N/2)``: ``facet0, facet<N/2>, facet1, ...``, the pairs of the
        :class:`~unilateral.constraints.Yield` family (never both active).

        Shapes, in the normalised plane ``x = (M_y'/My, M_z'/Mz)``:

        - ``"ellipse"`` (default): ``(M_y'/My)^2 + (M_z'/Mz)^2 <= 1`` replaced by the polygon that
          circumscribes it: ``N = facets`` facets tangent to it, with normals at the angles
          ``th_k = 2 pi k / N`` in the normalised plane (facet 0 along ``+M_y'``). The pure-``My``
          points lie on facets exactly, and so do the pure-``Mz`` points when ``N`` is a multiple
          of 4 (else they are vertices). Along a ray from the origin the polygon's strength is
          between 1 and ``sec(pi/N)`` times the ellipse's (exact along the facet normals, the
          bound at the vertices): an overstrength of at most ``sec(pi/N) - 1``: 41 % for N = 4,
          8.2 % for 8, 2.0 % for 16, 0.48 % for 32. The plastic rotation is normal to the facet,
          within ``pi/N`` (in the normalised plane) of the ellipse's normal.
        - ``"diamond"``: ``|M_y'|/My + |M_z'|/Mz <= 1``, exactly 4 facets (inscribed in the ellipse).
        - ``"box"``: ``|M_y'| <= My`` and ``|M_z'| <= Mz`` independently, exactly 4 facets: two
          uncoupled 2-D hinges (:meth:`Frame2D.hinge <unilateral.structure.Frame2D.hinge>`), the
          ellipse's polygon with ``N = 4``.

        ``k=None``: a rigid-plastic hinge in the beam itself. ``k`` given: an elastic-plastic
        rotational spring in series between the beam end and the node on both bending rotations
        (elastic rotations ``M_y'/k``, ``M_z'/k``): the flexibility ``1/k`` is added on both rows,
        the spring's massless inner node condensed into the beam's stiffness (no DOF added), as in
        2-D. Kinematic hardening: the back moment ``alpha = diag(H_y, H_z) theta_p`` translates the
        polygon, ``H_y = h 4EIy/L`` and ``H_z = h 4EIz/L`` without ``k``, ``H_y = H_z = h k`` with
        it; in the facets' terms ``A_kj = n_k^T diag(H_y, H_z) n_j`` (the 2-D pair's
        ``modulus [[1, -1], [-1, 1]]`` on one axis). A history in one plane (only ``M_y'``, say)
        stays on the facets normal to that axis and is the 2-D hinge's.

        Parameters
        ----------
        name : str, unique
        beam : str, the name of a beam of the frame
        end : ``"i"`` or ``"j"``; one hinge per beam end
        My, Mz : plastic moments about the local ``y'`` and ``z'``, force length, > 0
        shape : ``"ellipse"``, ``"diamond"`` or ``"box"``
        facets : int or None
            ``N``: with ``"ellipse"`` an even int >= 4 (default 8); ``"diamond"`` and ``"box"`` have
            exactly 4 (None or 4).
        k : rotational stiffness of the spring, force length/rad, > 0, or None (rigid-plastic)
        hardening : ``h >= 0``

        Notes
        -----
        Any three facet columns of one hinge are linearly dependent (two rotations): a pivoting
        basis with three facets of one hinge is singular; in a solution at most two adjacent facets
        flow (a vertex). Block principal pivoting (``lcp="bpp"``, the default) keeps the facets of a
        polygon of more than four apart that way (its group rule, as for a friction cone,
        :meth:`soil`), so a step that pushes the moment far beyond the polygon at once is solved
        too (1.2 and 3 times the strength with 8 and 16 facets, rigid-plastic and with ``k``: equal
        to ``lcp="lemke"``, ``tests/test_hinge3d.py``).
        """
        where = self._hinge_site(name, beam, end)
        My, Mz = _strength(where, "My", My), _strength(where, "Mz", Mz)
        shape, facets = _hinge_shape(where, shape, facets)
        k = None if k is None else _real(where, "k", k, ">0")
        h = _hardening(where, hardening)
        E = self._beams[beam].E
        moduli = (h * k, h * k) if k is not None else (h * E[4, 4], h * E[2, 2])       # k, or 4EIy/L and 4EIz/L
        polygon = el3.hinge_polygon(shape, facets, My, Mz)
        self._put_hinge(name, beam, end, lambda beam_element: el3.hinge(beam_element, name, end, polygon, k=k,
                                                                       moduli=moduli))

    # ------------------------------------------------------------------ build
    def build(self, *, p_delta=None) -> Structure3D:
        """Number the DOFs and assemble the natural form, the mass and the damping matrices.

        ``p_delta=True`` is :meth:`p_delta` with the standard gravity along -z (``False``: off; None:
        as set by :meth:`p_delta`). Raises ``ValueError`` naming the free DOFs that no element
        stiffens (``K`` would be singular).
        """
        if p_delta is not None:
            self.p_delta(bool(p_delta))
        if not self._coords:
            raise ValueError("the frame has no nodes; add nodes with Frame3D.node()")
        everything = self._elements + self._dashpots
        rotated = {(node, dof) for e in everything for node, dof in e.dofs if dof in el3.ROTATIONS}
        rotated |= {(node, dof) for node, mass in self._mass.items()
                    for dof, J in zip(el3.ROTATIONS, mass[3:]) if J > 0}
        on_soil = set()                                 # the soil stiffens these (FoundationModel checks)
        for footing in self._foundations:
            rows = footing.moved_rows(self._coords)
            if footing.sliding:
                rows = rows + footing.shear_rows() + footing.shear_rows_y()
            on_soil |= {(node, dof) for terms in rows for node, dof, _ in terms}
        rotated |= {(node, dof) for node, dof in on_soil if dof in el3.ROTATIONS}
        dofs = DofMap3D(self._coords, self._restrained, rotated, self._ties, equal=self._equal)
        on_soil |= rigid.exempt_dofs(self, dofs)        # held by rigid contacts (rigid3d.py)
        if any(not footing.rigid for footing in self._foundations):
            # a flexible footing's node may follow a master (rigid links): the soil stiffens the master's DOFs
            from .foundation import _rows_matrix

            rows = [r for f in self._foundations for r in f.moved_rows(self._coords)
                    + (f.shear_rows() + f.shear_rows_y() if f.sliding else [])]
            on_soil |= {dofs.free[i] for i in np.flatnonzero(np.abs(_rows_matrix(dofs, rows, len(rows))).sum(axis=1))}
        fields = self._assemble(dofs, exempt=on_soil)
        if self._foundations:
            from .foundation import check_patch_gaps
            from .foundation3d import Footings3D

            check_patch_gaps(self._foundations, self._coords)
            fields["foundation"] = Footings3D(self._foundations, first=len(fields["constraint_names"]))
        structure = support_motion.attach(self, Structure3D(**fields))
        if self._p_delta is None:
            return rigid.attach(self, structure)
        g, d = self._p_delta
        load = structure.gravity(g, tuple(d.get(dof, 0.0) for dof in el3.TRANSLATIONS))
        # on footings: the static state with the soil's static springs (its static flexibility Phi(0))
        return with_gravity(structure, load, None if not self._foundations else structure.to_model().static_model().K)

    # ------------------------------------------------------------------ helpers
    def _tied(self, node, dof) -> bool:
        return node in self._ties and dof in self._ties[node][1]

    def _master(self, node):
        return self._ties[node][0] if node in self._ties else None

    def _follows(self, node, dof) -> bool:
        return self._tied(node, dof)

    def _tie(self, where, master, slave, dofs) -> None:
        """Tie ``dofs`` of ``slave`` to ``master`` (a rigid link or a diaphragm), with the checks."""
        self._check_tie(where, master, slave, dofs)
        self._ties[slave] = (master, tuple(dofs))

    @staticmethod
    def _contact(kind, where, name, ends, terms, *, k, c, gap, capacity, friction):
        """A contact (soil, gap) along ``terms``: Kelvin element ``k``, ``c`` with one unknown, and
        with ``friction = ((mu, kt, ct), tangent, facets)`` (``(None, tangent, facets)``: none) a
        polygonal friction cone of ``facets`` facets."""
        if any(dof in el3.ROTATIONS for dof, _ in terms):
            raise ValueError(f"{where}: direction={terms[0][0]!r} is not valid for a contact; use 'ux', 'uy', "
                             "'uz' or a vector (dx, dy, dz)")
        contact = dict(k=_real(where, "k", k, ">0"), c=_real(where, "c", c, ">=0"), theta=-_real(where, "gap", gap))
        capacity = _real(where, "capacity", capacity, ">=0")
        coulomb, tangent, facets = friction
        if coulomb is None:
            if tangent is not None:
                raise ValueError(f"{where}: tangent is a friction parameter; give the friction coefficient mu too "
                                 "(or remove it)")
            return el.directional(name, kind, *ends, terms, contact.pop("k"),
                                  unknowns=(el.Unknown(name, 0, 1.0, capacity),), dof_names=el3.DOF_NAMES, **contact)
        mu, kt, ct = coulomb
        return el3.frictional(name, kind, *ends, terms, el3.tangents(where, terms, tangent), kt=kt, ct=ct, mu=mu,
                              capacity=capacity, facets=facets, **contact)


def _gravity_direction(where, direction) -> dict:
    """``{dof: component}`` of the unit vector ``direction`` (dx, dy, dz) of gravity; ``ValueError``
    for a rotation or a vector that is not finite and nonzero."""
    d = dict(el.direction_terms(where, direction, el3.DOF_NAMES, el3.AXES))
    if any(dof in el3.ROTATIONS for dof in d):
        raise ValueError(f"{where}: direction={direction!r} is not a direction of gravity; use a vector "
                         "(dx, dy, dz)")
    return d


def _facets(where, mu, facets) -> int:
    """The number of facets of a friction cone: an even int >= 4; other than 4 only with ``mu``."""
    if isinstance(facets, (bool, np.bool_)) or not isinstance(facets, (int, np.integer)):
        raise TypeError(f"{where}: facets must be an even int >= 4 (the facets of the friction cone), "
                        f"got {facets!r}")
    facets = int(facets)
    if facets < 4 or facets % 2:
        raise ValueError(f"{where}: facets={facets} must be an even int >= 4 (the facets of the friction cone "
                         "come in opposite pairs, and fewer than 4 do not bound the tangent plane)")
    if mu is None and facets != 4:
        raise ValueError(f"{where}: facets is a friction parameter; give the friction coefficient mu too "
                         "(or remove it)")
    return facets


def _hinge_shape(where, shape, facets) -> tuple[str, int]:
    """``(shape, N)`` of a hinge's polygon: ``shape`` one of :data:`~.elements3d.HINGE_SHAPES`; ``N`` an even
    int >= 4 for ``"ellipse"`` (default 8), 4 for ``"diamond"`` and ``"box"``."""
    if not isinstance(shape, str) or shape not in el3.HINGE_SHAPES:
        raise ValueError(f"{where}: shape={shape!r} is not valid; use 'ellipse', 'diamond' or 'box'")
    if facets is None:
        return shape, 8 if shape == "ellipse" else 4
    if isinstance(facets, (bool, np.bool_)) or not isinstance(facets, (int, np.integer)):
        raise TypeError(f"{where}: facets must be an even int >= 4 (the facets of the hinge's polygon), got {facets!r}")
    facets = int(facets)
    if shape != "ellipse" and facets != 4:
        raise ValueError(f"{where}: facets={facets} is not valid for shape={shape!r}, which has exactly 4 facets; "
                         "give facets=4 or leave it out (or use shape='ellipse')")
    if facets < 4 or facets % 2:
        raise ValueError(f"{where}: facets={facets} must be an even int >= 4 (the facets of the hinge's polygon "
                         "come in opposite pairs, and fewer than 4 do not bound the moment plane)")
    return shape, facets


@dataclass(frozen=True, eq=False)
class Structure3D(Structure):
    """A built 3-D frame: the natural form and the DOF map (:class:`DofMap3D`).

    The attributes are those of :class:`~unilateral.structure.Structure`, with ``coords`` node ->
    (3,) coordinates and ``nodal_mass`` (n_nodes, 6) the lumped ``(m, m, m, Jx, Jy, Jz)`` per node.
    :meth:`to_model`, :meth:`families`, :meth:`element_forces`, :meth:`element_deformations`,
    :meth:`node_displacement` and :meth:`ground_motion` work as in 2-D; the loads are 3-D:
    :meth:`gravity`, :meth:`nodal_load`, :meth:`distributed_load`, :meth:`influence`. Beams have
    the kind ``"beam3d"`` (six strains). The ground's forces, base forces, torque and drifts of a
    solution: :mod:`unilateral.structure.forces3d` (those of :mod:`unilateral.structure.forces` are
    for 2-D frames). P-Delta (:meth:`Frame3D.p_delta`): :meth:`geometric_stiffness` is the consistent
    matrix of both bending planes of each beam (:mod:`unilateral.structure.geometric`).
    """

    def to_model(self):
        """As :meth:`Structure.to_model <unilateral.structure.Structure.to_model>`; footings that slide
        in plan (``Frame3D.foundation(horizontal="soil")``) give the
        :class:`~unilateral.soil.FoundationModel` with ``Tx``, ``Ty`` and ``facets``
        (:func:`~unilateral.structure.foundation3d.to_plan_model`)."""
        if self.foundation is not None and self.foundation.sliding:
            from .built import _soil_supported_definite
            from .foundation3d import to_plan_model

            return _soil_supported_definite(to_plan_model(self), self.geometric)
        return super().to_model()

    def gravity(self, g=STANDARD_GRAVITY, direction=(0.0, 0.0, -1.0)) -> np.ndarray:
        """Load (n,) of gravity ``g`` along ``direction`` (a vector, normalised) on the lumped masses."""
        g = _real("gravity", "g", g)
        d = _gravity_direction("gravity", direction)
        f = np.zeros_like(self.nodal_mass)
        for column, dof in enumerate(el3.TRANSLATIONS):
            f[:, column] = self.nodal_mass[:, column] * g * d.get(dof, 0.0)
        return self.dofs.gather(f.ravel())

    def nodal_load(self, node, ux=0.0, uy=0.0, uz=0.0, rx=0.0, ry=0.0, rz=0.0) -> np.ndarray:
        """Load (n,) of a force ``(ux, uy, uz)`` and a moment ``(rx, ry, rz)`` at ``node`` (slave
        nodes too).

        Raises ``ValueError`` if a nonzero component acts on a DOF that nothing free can move
        (a supported DOF, or a rotation no element resists).
        """
        f = np.zeros(self.dofs.T.shape[0])
        for dof, value in zip(el3.DOF_NAMES, (ux, uy, uz, rx, ry, rz)):
            value = _real(f"nodal_load at node {node!r}", dof, value)
            if value:
                row = self.dofs.full_index(node, dof)
                if self.dofs.T[row].nnz == 0:
                    raise ValueError(f"nodal_load at node {node!r}: {dof}={value!r} acts on a DOF that cannot move "
                                     "(supported, or a rotation no element resists)")
                f[row] = value
        return self.dofs.gather(f)

    def influence(self, direction="ux") -> np.ndarray:
        """Influence vector ``r`` (n,) of a rigid ground translation along ``direction``.

        ``direction``: ``"ux"``, ``"uy"``, ``"uz"`` or a vector ``(dx, dy, dz)`` (normalised), e.g.
        ``(cos a, sin a, 0)`` for a record at an angle ``a`` from x in plan; a pair of horizontal
        components at ``a``: ``ground_motion(a1, (cos a, sin a, 0))`` and
        ``ground_motion(a2, (-sin a, cos a, 0))``. ``r`` is the component of the unit translation
        on each free translation (every node that is not supported moves by one unit along the
        direction; linked nodes follow their masters). A ground acceleration ``a_g(t)`` then loads
        the structure, in displacements relative to the ground, with ``-M r a_g(t)``
        (:meth:`ground_motion`).
        """
        if isinstance(direction, str) and direction not in el3.TRANSLATIONS:
            raise ValueError(f"direction={direction!r} is not valid for a ground motion; valid: 'ux', 'uy', 'uz' "
                             "or a vector (dx, dy, dz)")
        d = dict(el.direction_terms("ground motion", direction, el3.DOF_NAMES, el3.AXES))
        if any(dof in el3.ROTATIONS for dof in d):
            raise ValueError(f"direction={direction!r} is not valid for a ground motion; valid: 'ux', 'uy', 'uz' "
                             "or a vector (dx, dy, dz)")
        return np.array([d.get(dof, 0.0) if dof in el3.TRANSLATIONS else 0.0 for _, dof in self.dofs.free])

    def distributed_load(self, beam, wx=0.0, wy=0.0, wz=0.0) -> np.ndarray:
        """Load (n,) equivalent to a uniform load ``w = (wx, wy, wz)`` (force per length of the beam,
        along global x, y, z) on the beam ``beam``: its fixed-end forces reversed.

        Each end gets the force ``w L/2``, and the moments ``+L^2/12 x' x w`` at ``i`` and
        ``-L^2/12 x' x w`` at ``j`` (``x'`` the unit chord ``i -> j``; the 2-D moments ``+-w_t L^2/12``
        of :meth:`Structure.distributed_load <unilateral.structure.Structure.distributed_load>`). For
        Euler-Bernoulli beams these give the exact nodal displacements of the uniform load. Moments
        on a rotation that is supported are dropped.
        """
        where = f"distributed_load on beam {beam!r}"
        element = next((e for e in self.elements if e.name == beam and e.kind == "beam3d"), None)
        if element is None:
            beams = [e.name for e in self.elements if e.kind == "beam3d"]
            raise ValueError(f"{where}: no beam {beam!r} (beams: {', '.join(map(repr, beams[:10])) or 'none'})")
        w = np.array([_real(where, arg, value) for arg, value in (("wx", wx), ("wy", wy), ("wz", wz))])
        i, j = element.dofs[0][0], element.dofs[6][0]
        L, x = el3.chord(where, i, self.coords[i], j, self.coords[j])
        moment = np.cross(x, w) * L * L / 12.0
        f = np.zeros(self.dofs.T.shape[0])
        for node, sign in ((i, 1.0), (j, -1.0)):
            for dof, value in zip(el3.DOF_NAMES, np.concatenate([w * L / 2, sign * moment])):
                f[self.dofs.full_index(node, dof)] += value
        return self.dofs.gather(f)
