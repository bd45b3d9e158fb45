"""A 2-D frame builder: nodes, supports, elements and masses -> the natural form and a Model.

Example (the paper's foundation, see :func:`unilateral.structure.examples.liolios1990`)::

    fr = Frame2D()
    fr.node(1, 0.0, 10.0); fr.node(2, 0.0, 0.0); fr.node(3, -5.0, 0.0)
    fr.support(2, ux=True, uy=False)
    fr.rigid_link(2, 3)
    fr.beam("column", 2, 1, E=1.0, A=1e12, I=1e9)
    fr.mass(1, 40.0)
    fr.soil("soil3", 3, 200e3, c=10e3)
    fr.soil("soil2", 2, 200e3, c=10e3)
    st = fr.build()
    model = st.to_model()
    q = lambda t: st.gravity(10.0) + 200.0 * (0 < t <= 0.1) * st.nodal_load(1, ux=1.0)

Strain and sign conventions of the elements are in :mod:`unilateral.structure.elements`.
"""

from __future__ import annotations

import math
from itertools import compress

import numpy as np

from ..loads.units import STANDARD_GRAVITY
from . import bulk, elements as el, hinge_laws, rigid, support_motion
from .assembly import _block_diagonal, _compatibility, _groups, _lumped_mass  # noqa: F401  (tests/test_build_speed.py)
from .assembly import _node_and_dof_columns
from .built import Structure
from .checks import _friction, _hardening, _real, _strength
from .dofs import DofMap
from .frame_base import _Frame
from .geometric import with_gravity

_isfinite = math.isfinite
_INF = math.inf


def _rz_ties(equal: dict, rotated: set) -> tuple[set, dict]:
    """``(rotated, equal)``: the rotated nodes with both ends of each ``rz`` tie of
    :meth:`Frame2D.equal_dof` one end of which something else rotates (the slave's ``rz`` then reads
    the master's), and the ties without the ``rz`` ties between nodes nothing rotates (both read 0)."""
    out, grown = set(rotated), True
    while grown:
        grown = False
        for (slave, dof), master in equal.items():
            if dof == "rz" and (slave in out) != (master in out):
                out |= {slave, master}
                grown = True
    return out, {key: master for key, master in equal.items() if key[1] != "rz" or key[0] in out}


def _no_bearing_capacity(where, q_ult) -> None:
    """Refuse a bearing capacity ``q_ult`` (not None) on a footing on a soil medium."""
    if q_ult is not None:
        raise ValueError(f"{where}: q_ult={q_ult!r}: a bearing capacity is not available on a soil medium (the "
                         "plastic settlement of a patch would add to the soil's surface displacement in the "
                         "Laplace domain); put the footing on soil springs that yield instead: "
                         "Frame2D.spring_footing(..., q_ult=...), or Frame2D.soils(..., bearing=...) under "
                         "nodes rigidly linked to the footing")


class Frame2D(rigid.RigidContacts, support_motion.SupportMotions, _Frame):
    """Builder of a plane frame with unilateral elements (foundation uplift, pounding, cables).

    Nodes have the DOFs ``ux``, ``uy`` (along global x, y) and ``rz`` (counter-clockwise). Define
    nodes first, then supports, links, elements and masses in any order (a :meth:`hinge` after its
    beam), then :meth:`build`. Every element name must be unique.

    Each contact (:meth:`soil`, :meth:`cable`, :meth:`gap`) adds one unilateral unknown ``v >= 0``
    and one reaction ``psi <= 0``, named after the element; a contact with friction (``mu``) adds
    two slip multipliers ``"name.slip+"``, ``"name.slip-"``. A :meth:`yield_link` or a
    :meth:`hinge` adds two plastic multipliers ``"name.plastic+"``, ``"name.plastic-"`` (yield
    family), a :meth:`slider` two slips ``"name.slip+"``, ``"name.slip-"`` (friction family);
    for these ``psi`` is the yield function, ``<= 0``.

    Masses: :meth:`mass`, and a beam's own mass from its density (``rho`` of :meth:`beam`). Damping:
    :meth:`rayleigh` and/or :meth:`modal_damping`. Second-order effects of gravity: :meth:`p_delta`.
    Loads are vectors of the built :class:`Structure`: :meth:`Structure.gravity`,
    :meth:`Structure.nodal_load`, :meth:`Structure.distributed_load` (a uniform load on a beam).
    """

    def __init__(self):
        super().__init__()
        self._links: dict = {}
        self._p_delta: tuple | None = None
        self._foundations = []

    # ------------------------------------------------------------------ nodes and supports
    def node(self, node_id, x, y) -> None:
        """Define node ``node_id`` (int or str) at ``(x, y)``."""
        coords = self._coords
        if ((type(node_id) is int or type(node_id) is str) and type(x) is float and type(y) is float
                and _isfinite(x) and _isfinite(y) and node_id not in coords):
            coords[node_id] = np.array([x, y])          # what the checks below give these arguments
            return
        self._define_node(node_id, (x, y))

    def nodes(self, ids, x, y) -> None:
        """Many nodes at once: :meth:`node` ``(ids[k], x[k], y[k])`` for every row ``k``.

        ``ids`` (n,) ints or strs; ``x``, ``y`` (n,) or one number for all. All rows are checked
        before any node is added (a call that fails adds none); see :mod:`.bulk`.
        """
        bulk.add_nodes(self, ids, x, y)

    def support(self, node, ux=True, uy=True, rz=False) -> None:
        """Restrain DOFs of ``node`` (True = restrained); restrained DOFs are removed from ``u``."""
        where, flags = self._support_flags(node, (ux, uy, rz))
        if node in self._links:
            raise ValueError(
                f"{where}: node {node!r} is rigidly linked to node {self._links[node]!r}; "
                "support the master node instead"
            )
        self._restrained |= {(node, dof) for dof, flag in flags.items() if flag}

    def rigid_link(self, master, slave) -> None:
        """Attach node ``slave`` rigidly (ux, uy, rz) to node ``master``: ``u_full = T u``.

        The slave's DOFs are eliminated; chains of links are allowed (a master may itself be a
        slave). A slave node cannot be supported; support its master.
        """
        self._check_tie(f"rigid_link({master!r}, {slave!r})", master, slave, el.DOF_NAMES)
        self._links[slave] = master

    def mass(self, node, m, *, J=0.0) -> None:
        """Lumped mass ``m`` on ``ux`` and ``uy`` of ``node`` and rotational inertia ``J`` on ``rz``.

        Repeated calls add up. A slave node's mass acts on its master through ``T^T M T``.
        """
        if not (type(m) is float and type(J) is float and 0.0 <= m < _INF and 0.0 <= J < _INF
                and self._known(node)):           # (else the checks, in their order)
            where = f"mass at node {node!r}"
            self._node(where, "node", node)
            m, J = _real(where, "m", m, ">=0"), _real(where, "J", J, ">=0")
        before = self._mass.get(node)
        # 0.0 + x: the sum of the first call with a zero array, as later calls add to the sum
        self._mass[node] = np.array([0.0 + m, 0.0 + m, 0.0 + J]) if before is None else before + np.array([m, m, J])

    def masses(self, nodes, m, *, J=0.0) -> None:
        """Many lumped masses at once: :meth:`mass` ``(nodes[k], m[k], J=J[k])`` for every row ``k``
        (``m``, ``J``: (n,) or one number for all; a node given twice gets the sum). All rows are
        checked before any mass is added."""
        bulk.add_masses(self, nodes, m, J=J)

    # The damping of :class:`_Frame`, listed as this class's own: the API reference documents those only.
    rayleigh = _Frame.rayleigh
    rayleigh_from_ratios = _Frame.rayleigh_from_ratios
    modal_damping = _Frame.modal_damping

    def p_delta(self, enabled=True, *, g=STANDARD_GRAVITY, direction=(0.0, -1.0)) -> None:
        """P-Delta: the geometric stiffness of the gravity's axial forces, constant in time, in ``K``.

        :meth:`build` solves the linear static problem of the gravity ``g`` along ``direction`` on
        the lumped masses (:meth:`Structure.gravity`) with every element bilateral (contacts
        closed, no yield), takes the axial force ``N`` (tension positive) of each beam and bar, and
        adds their consistent geometric stiffness (:meth:`Structure.geometric_stiffness`; a
        compression ``N < 0`` lowers ``K``) to the ``K`` of :meth:`Structure.to_model`. The element
        forces reported stay those of ``G E G^T`` (the geometric part shows in the equilibrium of
        the nodes, not in ``sigma``); the energy balance counts its energy (``geometric``). With
        footings on a soil medium the static problem holds them on the soil's static springs. A
        gravity at or above the buckling load makes ``K`` indefinite (on a soil: ``K`` with the soil's
        static springs): ``to_model`` then refuses the model. ``enabled=False`` switches it off.
        """
        if not enabled:
            self._p_delta = None
            return
        g = _real("p_delta", "g", g, ">0")
        d = dict(el.direction_terms("p_delta", direction))
        if "rz" in d:
            raise ValueError("p_delta: direction='rz' is not a direction of gravity; use a vector (dx, dy)")
        self._p_delta = (g, (d.get("ux", 0.0), d.get("uy", 0.0)))

    # ------------------------------------------------------------------ bilateral elements
    def beam(self, name, i, j, E, A, I, *, axial_strain=0.0, curvature=0.0, rho=None) -> None:
        """Euler-Bernoulli beam-column from node ``i`` to node ``j``.

        Natural strains: elongation, and the end rotations at ``i`` and ``j`` relative to the
        chord; stiffness ``[[EA/L, 0, 0], [0, 4EI/L, 2EI/L], [0, 2EI/L, 4EI/L]]``.
        ``axial_strain`` and ``curvature`` are imposed (e.g. thermal) strains, constant in time.

        ``rho`` (mass per volume, force time^2/length^4, or None): the beam's own mass
        ``rho A L``, lumped half at each end node on ``ux`` and ``uy`` (no rotational inertia), as
        :meth:`mass` would add it; :meth:`Structure.gravity` then gives its self-weight, ``rho A L g / 2``
        per end, which are the exact fixed-end forces of a uniform weight apart from the end
        moments ``+- w L^2/12`` (use :meth:`Structure.distributed_load` for those).
        """
        where = self._label("beam", name)
        coords = self._coords
        try:
            defined = i in coords and j in coords and i != j
        except TypeError:
            defined = False
        if not defined:
            self._two_nodes(where, i, j)
        # the checks of _real, made inline for floats (else by _real, in the same order)
        if not (type(E) is float and type(A) is float and type(I) is float
                and 0.0 < E < _INF and 0.0 < A < _INF and 0.0 < I < _INF):
            E, A, I = _real(where, "E", E, ">0"), _real(where, "A", A, ">0"), _real(where, "I", I, ">0")
        if not (type(axial_strain) is float and type(curvature) is float
                and _isfinite(axial_strain) and _isfinite(curvature)):
            axial_strain, curvature = _real(where, "axial_strain", axial_strain), _real(where, "curvature", curvature)
        element = el.beam(name, i, coords[i], j, coords[j], E=E, A=A, I=I, axial_strain=axial_strain,
                          curvature=curvature)
        if rho is not None:
            half = _real(where, "rho", rho, ">=0") * A * el.chord(where, i, coords[i], j, coords[j])[0] / 2
            for node in (i, j):
                self.mass(node, half)
        self._beams[name] = element
        self._elements.append(element)
        self._names.add(name)

    def beams(self, names, i, j, E, A, I, *, axial_strain=0.0, curvature=0.0) -> None:
        """Many beam-columns at once: :meth:`beam` ``(names[k], i[k], j[k], E[k], A[k], I[k], ...)``
        for every row ``k``: the same elements, without a Python call per beam.

        ``names``, ``i``, ``j`` (n,); ``E``, ``A``, ``I``, ``axial_strain``, ``curvature`` (n,) or
        one number for all (a beam's own mass: :meth:`masses`). All rows are checked before any
        beam is added (a call that fails adds none); the message names the argument and the row.
        """
        bulk.add_beams(self, names, i, j, E=E, A=A, I=I, axial_strain=axial_strain, curvature=curvature)

    def bar(self, name, i, j, E, A, *, axial_strain=0.0, Fy=None, Fy_t=None, Fy_c=None, hardening=0.0) -> None:
        """Axial bar from node ``i`` to node ``j`` (strain: elongation, stiffness ``EA/L``).

        ``Fy`` (or ``Fy_t`` and ``Fy_c``) [force]: the bar yields axially (a brace, a tie): its axial
        force stays in ``-Fy_c <= N - Hk (v+ - v-) <= Fy_t``, the plastic elongation ``v+ - v-`` of the
        pair ``"name.plastic+-"`` (as :meth:`yield_link` along the chord), kinematic hardening
        ``Hk = hardening EA/L``. Without them the bar is elastic.
        """
        where = self._label("bar", name)
        self._two_nodes(where, i, j)
        bar = el.bar(name, i, self._coords[i], j, self._coords[j], E=_real(where, "E", E, ">0"),
                     A=_real(where, "A", A, ">0"), axial_strain=_real(where, "axial_strain", axial_strain))
        self._add(self._axial_yield(where, bar, Fy, Fy_t, Fy_c, hardening))

    def spring(self, name, i, k, *, j=None, direction="uy") -> None:
        """Linear spring ``k`` from node ``i`` to the ground (``j=None``) or to node ``j``.

        Strain: extension ``d . u_i`` to the ground, ``d . (u_j - u_i)`` between two nodes, for
        ``direction`` ``"ux"``, ``"uy"``, ``"rz"`` or a vector ``(dx, dy)`` (normalised).
        """
        self._add(self._directional("spring", name, i, j, k, direction))

    def dashpot(self, name, i, c, *, j=None, direction="uy") -> None:
        """Attached linear dashpot ``c`` (acts in tension too; goes into ``C``), like :meth:`spring`."""
        element = self._directional("dashpot", name, i, j, c, direction)
        self._dashpots.append(element)
        self._names.add(name)

    # ------------------------------------------------------------------ unilateral elements
    def soil(self, name, node, k, *, c=0.0, direction="uy", gap=0.0, capacity=0.0, mu=None, kt=None,
             ct=0.0, bearing=None) -> None:
        """Tensionless soil element under ``node``: spring ``k`` and dashpot ``c`` in parallel (a
        Kelvin element, ``E_v = c``) in series with a unilateral contact.

        Strain ``e = d . u_node``: the displacement of the node along ``direction`` (default
        ``"uy"``), which points from the soil to the node, i.e. the direction in which the node
        separates. ``e < 0`` compresses the soil. ``v >= 0`` is the separation; the force
        ``sigma = k (e - v + gap) + c (e' - v')`` (tension positive) satisfies ``sigma <= capacity``,
        with ``v > 0`` only where ``sigma = capacity``.

        Parameters
        ----------
        k : stiffness, force/length;  c : viscosity, force time/length
        gap : initial gap between node and soil (imposed strain ``theta = -gap``), length;
            negative: an initial penetration (preload)
        capacity : the tension ``r >= 0`` the element carries before separating, force (default 0)
        mu : Coulomb friction coefficient >= 0, or None (no friction: the node slides freely)
        kt : stick stiffness, force/length, > 0; required with ``mu``
        ct : viscosity of a Kelvin dashpot in parallel with ``kt``, force time/length (default 0)
        bearing : the bearing capacity ``Q > 0`` of the spring, force (not a pressure: a footing of
            area ``A`` on ``n`` springs with the ultimate pressure ``q_ult`` gives each ``q_ult A / n``),
            or None (default: the soil carries any compression)

        With ``bearing``, the compression never exceeds ``Q``: ``-sigma <= Q``; beyond it the soil
        settles plastically by ``w >= 0``, the unknown ``"name.plastic-"`` (a one-sided yield face,
        rate law: ``w' >= 0`` only while ``-sigma = Q``; :class:`~unilateral.constraints.Bearing`),
        and the force is ``sigma = k (e - v + w + gap) + c (e' - v' + w')``. Unloading is elastic
        with the permanent settlement ``w``; the tension side keeps its contact (lift-off at
        ``capacity``). The settlement's work ``Q w`` is the ``plastic_work`` of the energy balance.

        With ``mu``, a tangential strain ``t . u_node`` (``t`` the direction turned 90 degrees
        clockwise: ``"ux"`` for ``"uy"``) carries the force ``T = kt (e_t - s+ + s-) + ct (...)'``
        with ``|T| <= mu N``, ``N = capacity - sigma`` the compression of the contact (``N = 0``:
        no tangential force once the node has lifted off); the slips ``s+-`` are the unknowns
        ``"name.slip+"``, ``"name.slip-"``.
        """
        where = self._label("soil", name)
        self._node(where, "node", node)
        element = self._contact("soil", where, name, None, node, k=k, c=c, direction=direction, gap=gap,
                                capacity=capacity, friction=_friction(where, mu, kt, ct))
        if bearing is not None:
            element = el.with_bearing(element, name, _real(where, "bearing", bearing, ">0"))
        self._add(element)

    def soils(self, names, nodes, k, *, c=0.0, gap=0.0, capacity=0.0, direction="uy", bearing=None) -> None:
        """Many tensionless soil elements at once: :meth:`soil` ``(names[k], nodes[k], k[k], c=c[k],
        gap=gap[k], capacity=capacity[k], direction=direction, bearing=bearing[k])`` for every row
        (the numbers: (n,) or one for all; ``bearing`` [force per spring] None for none; one
        ``direction``; without friction: contacts with friction by :meth:`soil`). All rows are
        checked before any element is added."""
        bulk.add_soils(self, names, nodes, k, c=c, gap=gap, capacity=capacity, direction=direction, bearing=bearing)

    def spring_footing(self, name, node, *, width, k, length=1.0, c=0.0, springs=8, q_ult=None, gap=0.0) -> None:
        """A rigid footing under ``node`` on a bed of tensionless soil springs (Winkler) that may yield.

        The footing (``width`` along the frame's x, centred on ``node``, ``length`` out of plane, area
        ``A = width length``) is cut into ``springs`` equal strips; at each strip's centre a node
        ``"name.<j>"`` (``j = 1 ...`` from left to right) rigidly linked to ``node`` rests on the
        :meth:`soil` ``"name.<j>"`` of stiffness ``k A / springs``, viscosity ``c A / springs`` and
        bearing capacity ``q_ult A / springs`` (:meth:`soils`). ``node`` carries the footing's ``uy``
        and ``rz``; restrain its ``ux`` (:meth:`support`) or connect it horizontally otherwise.

        Under a vertical load ``N`` the footing's moment capacity (the plateau of its static
        moment-rotation curve) is ``M_n = M_ult - q_ult length h^2 f (1 - f) / 2``, ``h = width/springs``,
        ``f`` the fractional part of ``N springs / (q_ult A)``; it tends to ``M_ult = N width / 2
        (1 - N / N_ult)``, ``N_ult = q_ult A``, with the order 2 in ``1/springs``
        (``tests/test_bearing_capacity.py``).

        Parameters
        ----------
        width, length : float, length, > 0
        k : modulus of subgrade reaction (stiffness per unit area), force/length^3, > 0
        c : viscosity per unit area, force time/length^3, >= 0
        springs : int >= 1, the number of springs
        q_ult : the ultimate bearing pressure, force/length^2, > 0, or None (no bearing capacity)
        gap : the springs' initial gap, length (negative: a penetration)
        """
        where = self._label("spring_footing", name)
        self._node(where, "node", node)
        width, length = _real(where, "width", width, ">0"), _real(where, "length", length, ">0")
        if isinstance(springs, bool) or not isinstance(springs, int) or springs < 1:
            raise ValueError(f"{where}: springs={springs!r} must be an int >= 1 (the number of soil springs)")
        share = width * length / springs
        k, c = _real(where, "k", k, ">0") * share, _real(where, "c", c, ">=0") * share
        bearing = None if q_ult is None else _real(where, "q_ult", q_ult, ">0") * share
        gap = _real(where, "gap", gap)
        ids = [f"{name}.{j + 1}" for j in range(springs)]
        x0, y0 = self._coords[node]
        taken = [i for i in ids if i in self._coords or i in self._names]
        if taken:
            raise ValueError(f"{where}: {taken[0]!r} is already a node or an element name; rename the footing")
        self.nodes(ids, x0 - width / 2 + (np.arange(springs) + 0.5) * (width / springs), np.full(springs, y0))
        for i in ids:
            self.rigid_link(node, i)
        self.soils(ids, ids, k, c=c, gap=gap, bearing=bearing)
        self._names.add(name)

    def gap(self, name, i, j, k, *, gap=0.0, c=0.0, direction=None, mu=None, kt=None, ct=0.0) -> None:
        """Pounding (gap) link between nodes ``i`` and ``j``: compression-only contact spring ``k``
        (force/length, with a Kelvin dashpot ``c``, force time/length, in parallel) that engages
        when the gap closes.

        Strain ``e = d . (u_j - u_i)``: the opening of the gap along ``direction``, which points
        from ``i`` to ``j`` (default: the unit vector from node ``i`` to node ``j``). The link
        engages when ``e <= -gap`` (length); ``v >= 0`` is the gap opening, force as :meth:`soil`
        with capacity 0. ``mu``, ``kt``, ``ct``: Coulomb friction across the closed gap, as for
        :meth:`soil` (tangential strain ``t . (u_j - u_i)``).
        """
        where = self._label("gap", name)
        self._two_nodes(where, i, j)
        if direction is None:
            _, direction = el.chord(where, i, self._coords[i], j, self._coords[j])
        self._add(self._contact("gap", where, name, i, j, k=k, c=c, direction=direction, gap=gap, capacity=0.0,
                                friction=_friction(where, mu, kt, ct)))

    def cable(self, name, i, j, E, A, *, slack=0.0, capacity=0.0) -> None:
        """Tension-only cable (bar) from node ``i`` to node ``j`` that goes slack in compression.

        Strain ``e`` = elongation; ``B = -1`` and ``theta = slack``, so the axial force is
        ``EA/L (e + v - slack)`` with ``v >= 0`` the slack shortening: the cable is taut once
        ``e >= slack`` and carries at most the compression ``capacity`` (default 0).
        Negative ``slack``: a pretensioned cable.
        """
        where = self._label("cable", name)
        self._two_nodes(where, i, j)
        self._add(el.cable(name, i, self._coords[i], j, self._coords[j], E=_real(where, "E", E, ">0"),
                           A=_real(where, "A", A, ">0"), slack=_real(where, "slack", slack),
                           capacity=_real(where, "capacity", capacity, ">=0")))

    # ------------------------------------------------------------------ plasticity and friction
    # The plasticity and friction of :class:`_Frame`, listed as this class's own (the API reference).
    yield_link = _Frame.yield_link
    slider = _Frame.slider

    def hinge(self, name, beam, end, *, My=None, k=None, hardening=0.0, backbone=None, interaction=None,
              Ny=None) -> None:
        """Plastic hinge at the end ``"i"`` or ``"j"`` of the beam ``beam`` (define the beam first).

        The end moment ``M`` (the beam's natural stress ``rot_i`` or ``rot_j``: the moment acting
        on the beam at that end, counter-clockwise positive) stays in ``-My <= M - Hk (v+ - v-) <= My``;
        the plastic rotation ``v+ - v-`` (rad) of the multipliers ``"name.plastic+"``,
        ``"name.plastic-"`` is an imposed strain on that end rotation.

        ``k=None``: a rigid-plastic hinge in the beam itself; ``hardening`` is relative to the
        beam's ``4EI/L`` (``Hk = hardening 4EI/L``). ``k`` given: an elastic-plastic rotational
        spring in series between the beam end and the node (elastic rotation ``M/k``, post-yield
        stiffness ``k h / (1 + h)`` with ``Hk = hardening k``); the spring's massless inner node is
        condensed into the beam's stiffness, so no DOF is added. Stiffness-proportional Rayleigh
        damping acts on the beam's total end rotation, plastic part included.

        ``backbone`` (instead of ``My`` and ``k``): the spring's moment-rotation law is the convex
        multi-linear backbone through the points ``(theta, M)`` (slopes decreasing, > 0; beyond the
        last point the slope ``hardening`` times the initial one, 0: flat; points with ``theta < 0``
        a negative branch of the same slopes, else symmetric), exactly: elastic-perfectly-plastic
        springs in parallel, one per segment, unloading elastically with the initial stiffness and
        reloading by Masing's rule (:mod:`.hinge_laws`, :func:`.elements.backbone_hinge`). The
        multipliers ``"name.plastic+-"``, ``"name.plastic2+-"``, ... are those of the segments.

        ``interaction`` (instead of ``k``): a rigid-plastic hinge bounding the axial force ``N``
        (tension positive) and the end moment ``M`` by a convex polygon in ``(N, M)``: its vertices,
        or ``"aisc"`` (AISC 360 eq. H1-1, with ``Ny`` and ``My``); one yield unknown ``"name.facet<k>"``
        per facet, associated flow: the plastic elongation and rotation ``sum_k lambda_k n_k``
        (:func:`.elements.polygon_hinge`). ``hardening`` is relative to ``EA/L`` and ``4EI/L``.

        Parameters
        ----------
        My : yield moment, force length, > 0 (the plastic moment of a shape ``interaction``)
        k : rotational stiffness of the spring, force length/rad, > 0, or None (rigid-plastic)
        hardening : ``h >= 0``
        backbone : sequence of ``(theta, M)`` pairs [rad, force length], or None
        interaction : ``"aisc"`` or a sequence of ``(N, M)`` vertices [force, force length], or None
        Ny : the axial yield force of a shape ``interaction``, force, > 0
        """
        where = self._hinge_site(name, beam, end)
        beam_E = self._beams[beam].E
        if backbone is not None or interaction is not None:
            law = self._hinge_law(where, beam_E, _hardening(where, hardening), My=My, k=k, backbone=backbone, interaction=interaction, Ny=Ny)
            self._put_hinge(name, beam, end, lambda beam_element: law(beam_element, name, end))
            return
        if Ny is not None:
            raise ValueError(f"{where}: Ny={Ny!r} is the axial yield force of an interaction shape; give "
                             "interaction='aisc' too, or leave Ny out")
        if My is None:
            raise ValueError(f"{where}: My is missing; give the yield moment My (force length, > 0), or a backbone")
        My = _strength(where, "My", My)
        k = None if k is None else _real(where, "k", k, ">0")
        modulus = _hardening(where, hardening) * (k if k is not None else beam_E[1, 1])          # k or 4EI/L
        self._put_hinge(name, beam, end, lambda beam_element: el.hinge(beam_element, name, end, My=My, k=k,
                                                                      modulus=modulus))

    @staticmethod
    def _hinge_law(where, beam_E, h, *, My, k, backbone, interaction, Ny):
        """The element law ``(beam element, name, end) -> element`` of a hinge with a ``backbone`` or
        an ``interaction`` polygon, the arguments checked."""
        if backbone is not None:
            given = [arg for arg, value in (("My", My), ("k", k), ("interaction", interaction), ("Ny", Ny))
                     if value is not None]
            if given:
                raise ValueError(f"{where}: {given[0]} cannot go with a backbone, which gives the hinge's "
                                 "stiffness and strengths (its first point: k = M1/theta1, My = M1)")
            K, ks, theta_plus, theta_minus = hinge_laws.backbone_springs(where, backbone, h)
            return lambda e, name, end: el.backbone_hinge(e, name, end, K=K, k=ks, theta_plus=theta_plus,
                                                          theta_minus=theta_minus)
        if k is not None:
            raise ValueError(f"{where}: k={k!r} cannot go with an interaction polygon: the axial force - moment "
                             "hinge is rigid-plastic (its plastic elongation and rotation are imposed on the beam)")
        shape = isinstance(interaction, str)
        if not shape and (My is not None or Ny is not None):
            raise ValueError(f"{where}: My and Ny scale a named interaction shape ('aisc'); the vertices "
                             f"interaction={interaction!r} are in force and force length already: leave them out")
        polygon = hinge_laws.interaction_polygon(
            where, interaction, Ny=None if Ny is None or not shape else _strength(where, "Ny", Ny),
            My=None if My is None or not shape else _strength(where, "My", My))
        moduli = (h * beam_E[0, 0], h * beam_E[1, 1])                  # EA/L, 4EI/L
        return lambda e, name, end: el.polygon_hinge(e, name, el.end_node(e, end), (0, el.END_ROWS[end]),
                                                     polygon, moduli)

    # ------------------------------------------------------------------ foundation on a soil medium
    def foundation(self, name, node, *, width=None, length, soil, patches=None, nodes=None,
                   horizontal="support", gap=0.0, mass=0.0, J=0.0, mu=None, q_ult=None) -> None:
        """A footing resting on a soil medium (half-space, cones or Winkler-Kelvin) through
        unilateral contacts; :meth:`Structure.to_model` then gives a
        :class:`~unilateral.soil.FoundationModel` (``docs/theory.md``, section 12).

        Any number of footings, beside any other element (gaps, pounding links, cables, soil
        springs, yielding links, hinges, sliders). Footings on a half-space share it: every patch
        of every footing is coupled through the ground (give them the same soil); footings on
        cones or Winkler-Kelvin beds are uncoupled. Footings at one elevation must not overlap.

        Rigid footing (``nodes=None``): ``node`` carries the footing's ``uy`` and ``rz``;
        ``patches`` strips (default 3) across ``width`` (the frame's x, centred on ``node``), each
        ``length`` long out of plane. Flexible footing: one patch per node of ``nodes`` (the nodes of
        a footing beam at one elevation), centred on it, twice as wide as the nearer end of its
        tributary strip within ``centre +- width/2`` (default ``width``: the span of the nodes plus
        one mean node spacing: equally spaced nodes then get equal patches covering the footing).

        Parameters
        ----------
        name : str
            Contacts are named ``"name.1"`` ... (rigid, left to right) or ``"name.<node>"``.
        node : node id
            The reference node: the rigid footing's node; where ``horizontal`` acts.
        width, length : float, length
        soil : SoilFlexibility, SoilSpec or dict
            E.g. ``{"model": "halfspace", "Vs": 200.0, "nu": 1/3, "rho": 2.0, "damping": 0.0}``,
            ``{"model": "cones", "G": ..., "nu": ..., "rho": ...}`` or
            ``{"model": "winkler-kelvin", "k": 200e3, "c": 10e3}`` (per patch); see
            :mod:`unilateral.structure.foundation`.
        patches : int, optional
            Number of strips of a rigid footing (default 3).
        nodes : sequence of node ids, optional
            A flexible footing's contact nodes.
        horizontal : {"support", "cone", "none", "soil"}
            The footing's horizontal restraint: ``ux`` of ``node`` supported (default), Wolf's
            horizontal cone as a bilateral spring and dashpot at ``node`` (no sliding), nothing, or
            the soil itself: each patch's horizontal force through the soil's horizontal flexibility,
            limited by Coulomb friction ``mu`` - the footing slides (every footing of the frame then
            takes ``"soil"``; see :mod:`unilateral.structure.foundation`).
        mu : float >= 0, optional
            With ``horizontal="soil"``: the friction coefficient of the footing on the soil.
        gap : float or (m,) array, length
            Opening at ``u = 0`` with the soil unloaded (negative: a penetration).
        mass, J : float >= 0, mass and mass length^2
            The rigid footing's own mass (on ``ux``, ``uy`` of ``node``) and rotary inertia (on
            ``rz``); a flexible footing's masses are those of its nodes (:meth:`mass`).
        q_ult : None
            Refused: a bearing capacity on a soil medium would need a plastic settlement added to the
            soil's surface displacement in the Laplace domain, which is not implemented. A footing
            whose soil yields: :meth:`spring_footing` (``q_ult`` per unit area on soil springs).
        """
        from .foundation import build_foundation, horizontal_cone

        where = f"foundation {name!r}"
        _no_bearing_capacity(where, q_ult)
        if not isinstance(name, str) or not name:
            raise TypeError(f"foundation name must be a non-empty str, got {name!r}")
        if name in self._names:
            raise ValueError(f"{where}: the name is already used by another element")
        self._node(where, "node", node)
        for k, other in enumerate(nodes or ()):
            self._node(where, f"nodes[{k}]", other)
        fnd = build_foundation(name=name, node=node, nodes=nodes, width=width, length=length, soil=soil,
                               patches=3 if patches is None and nodes is None else patches,
                               horizontal=horizontal, gap=gap, coords=self._coords, mu=mu)
        self._check_footing(where, fnd, mass, J)
        if fnd.horizontal == "support":
            self.support(node, ux=True, uy=False)
        elif fnd.horizontal == "cone":
            K, C = horizontal_cone(fnd, where)
            self.spring(f"{name}.horizontal_spring", node, K, direction="ux")
            self.dashpot(f"{name}.horizontal_dashpot", node, C, direction="ux")
        if mass or J:
            self.mass(node, mass, J=J)
        self._foundations.append(fnd)
        self._names.add(name)

    def _check_footing(self, where, fnd, mass, J) -> None:
        """Raise if the new footing ``fnd`` rests on another footing's nodes or overlaps it, has its
        own ``mass`` or ``J`` while flexible, or a DOF it moves on the soil is supported."""
        from .foundation import _check_overlap

        used = {n for f in self._foundations for n in f.contact_nodes()}
        if used & set(fnd.contact_nodes()):
            raise ValueError(f"{where}: node(s) {sorted(used & set(fnd.contact_nodes()), key=repr)} already rest on "
                             "another footing; give each footing its own nodes")
        _check_overlap(self._foundations, fnd, where)
        if (mass or J) and not fnd.rigid:
            raise ValueError(f"{where}: mass={mass!r}, J={J!r} are for a rigid footing; give a flexible footing's "
                             "masses to its nodes with Frame2D.mass")
        for contact in fnd.contact_nodes():
            if contact in self._links:
                continue
            for dof in ("uy", "ux") if fnd.sliding else ("uy",):
                if (contact, dof) in self._restrained:
                    raise ValueError(f"{where}: {dof} of node {contact!r} is supported: the footing could not move "
                                     "on the soil; remove that support")

    # ------------------------------------------------------------------ build
    def build(self, *, p_delta=None) -> Structure:
        """Number the DOFs and assemble the natural form, the mass and the damping matrices.

        ``p_delta=True`` is :meth:`p_delta` with the standard gravity (``False``: off; None: as set
        by :meth:`p_delta`). Raises ``ValueError`` if a free DOF has no stiffness (``K`` would be
        singular).
        """
        if p_delta is not None:
            self.p_delta(bool(p_delta))
        if not self._coords:
            raise ValueError("the frame has no nodes; add nodes with Frame2D.node()")
        everything = self._elements + self._dashpots
        nodes, names = _node_and_dof_columns(everything)
        rotated = set(compress(nodes, map("rz".__eq__, names)))
        rotated |= {node for node, mass in self._mass.items() if mass[2] > 0}
        for footing in self._foundations:
            if footing.rigid and footing.m > 1:
                rotated.add(footing.node)               # the footing rocks on its patches
        rotated, equal = _rz_ties(self._equal, rotated)
        dofs = DofMap(self._coords, self._restrained, rotated, self._links, ties=self._with_equal(rigid.ties(self), equal))
        on_soil = rigid.exempt_dofs(self, dofs)         # held by rigid contacts (rigid.py), and:
        for footing in self._foundations:               # the soil stiffens these (FoundationModel checks)
            for terms in footing.moved_rows(self._coords) + (footing.shear_rows() if footing.sliding else []):
                on_soil |= {(node, dof) for node, dof, _ in terms}
        fields = self._assemble(dofs, exempt=on_soil)
        footings = None
        if self._foundations:
            from .foundation import Footings, check_patch_gaps

            check_patch_gaps(self._foundations, self._coords)
            footings = Footings(self._foundations, first=len(fields["constraint_names"]))
        structure = support_motion.attach(self, Structure(**fields, foundation=footings))
        if self._p_delta is None:
            return rigid.attach(self, structure)
        g, (dx, dy) = self._p_delta
        load = structure.gravity(g, (dx, dy)) if (dx or dy) else np.zeros(structure.n)
        # on footings: the static state with the soil's static springs (its static flexibility Phi(0))
        return with_gravity(structure, load, None if not self._foundations else structure.to_model().static_model().K)

    # ------------------------------------------------------------------ helpers
    def _master(self, node):
        return self._links.get(node)

    def _contact(self, kind, where, name, i, j, *, k, c, direction, gap, capacity, friction) -> el.Element:
        terms = el.direction_terms(where, direction)
        contact = dict(k=_real(where, "k", k, ">0"), c=_real(where, "c", c, ">=0"), theta=-_real(where, "gap", gap))
        capacity = _real(where, "capacity", capacity, ">=0")
        if friction is None:
            return el.directional(name, kind, i, j, terms, unknowns=(el.contact_unknown(name, capacity),), **contact)
        mu, kt, ct = friction
        return el.frictional(name, kind, i, j, terms, kt=kt, ct=ct, mu=mu, capacity=capacity, **contact)
