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
import numbers
import operator
from abc import ABC, abstractmethod
from dataclasses import dataclass, replace
from itertools import accumulate, chain, compress

import numpy as np
import scipy.sparse as sp

from ..loads.units import STANDARD_GRAVITY
from ..constraints import Contact, Friction, Yield
from ..model import ConstantStrain, Model, NaturalForm
from . import bulk, elements as el, rigid, support_motion
from .dofs import DofMap, csr_of_entries, node_list
from .modes import check_frequency_range, modal_damping_matrix

_isfinite = math.isfinite
_INF = math.inf


class _Frame(ABC):
    """What :class:`Frame2D` and :class:`~unilateral.structure.Frame3D` share: the node, name and tie
    checks, Rayleigh and modal damping, the directional elements and the assembly of the natural
    form, the mass and the damping matrices.

    A subclass sets the nodal DOFs :attr:`_dof_names` and the components :attr:`_axes` of a vector
    (see :func:`~unilateral.structure.elements.direction_terms`), and gives the master of a slave
    node with :meth:`_master`.
    """

    #: The nodal DOFs of every node.
    _dof_names = el.DOF_NAMES
    #: The components of a vector direction in messages (:func:`~unilateral.structure.elements.vector`).
    _axes = ("dx", "dy")

    def __init__(self):
        self._coords: dict = {}
        self._restrained: set = set()
        self._elements: list[el.Element] = []
        self._dashpots: list[el.Element] = []
        self._names: set = set()
        self._mass: dict = {}
        self._rayleigh: tuple[float, float] | None = None
        self._modal: tuple | None = None
        self._beams: dict = {}              # name -> the beam as defined (before any hinge)
        self._hinges: dict = {}             # (beam, end) -> hinge name: one hinge per beam end

    # ------------------------------------------------------------------ damping
    def rayleigh(self, a0=0.0, a1=0.0) -> None:
        """Rayleigh damping ``C += a0 M + a1 K`` (either coefficient may be left at 0).

        ``K`` here is the stiffness of the bilateral elements only: a unilateral element (soil,
        gap, cable, and in 2-D a yield link or a slider) gets no stiffness-proportional damping,
        which would act across an open contact or a slip. Give a contact its own dashpot (``c``)
        instead. A 2-D beam with a :meth:`Frame2D.hinge` keeps it, acting on its total end rotation
        (plastic part included).
        """
        if self._rayleigh is not None:
            a0, a1 = self._rayleigh
            raise ValueError(f"Rayleigh damping is already set (a0={a0!r}, a1={a1!r})")
        self._rayleigh = (_real("rayleigh", "a0", a0, ">=0"), _real("rayleigh", "a1", a1, ">=0"))

    def rayleigh_from_ratios(self, zeta, f1, f2) -> None:
        """Rayleigh damping with the damping ratio ``zeta`` at the frequencies ``f1``, ``f2`` (Hz).

        ``a0 = 2 zeta w1 w2 / (w1 + w2)``, ``a1 = 2 zeta / (w1 + w2)``, ``w = 2 pi f``; see
        :meth:`rayleigh` for the stiffness used.
        """
        where = "rayleigh_from_ratios"
        zeta = _real(where, "zeta", zeta, ">=0")
        w1 = 2 * np.pi * _real(where, "f1", f1, ">0")
        w2 = 2 * np.pi * _real(where, "f2", f2, ">0")
        self.rayleigh(2 * zeta * w1 * w2 / (w1 + w2), 2 * zeta / (w1 + w2))

    def modal_damping(self, zeta, modes=None) -> None:
        """Modal damping: the ratio ``zeta`` in each mode of the structure with its constraints held.

        ``C += M Phi diag(2 zeta_i w_i) Phi^T M`` with ``w_i``, ``Phi`` (mass-normalised, ``Phi^T M
        Phi = I``) the modes of ``K = G E G^T`` (every element bilateral: contacts closed and bonded,
        no slip, no yield) and ``M``. DOFs without mass are condensed statically
        (``K* = K_mm - K_m0 K_00^-1 K_0m``): the modes are those of ``(K*, M_mm)`` and the damping
        acts on the DOFs with mass only, so the condensed system has exactly the ratio ``zeta_i`` in
        mode ``i``. Modes beyond those damped get none.

        Parameters
        ----------
        zeta : float (one ratio for the damped modes) or sequence (one per mode, lowest first), >= 0
        modes : int or None
            The number of lowest modes damped; None: all modes (a sequence ``zeta``: ``len(zeta)``).

        Adds to :meth:`rayleigh` damping and the dashpots if both are given.
        """
        where = "modal_damping"
        if self._modal is not None:
            raise ValueError(f"{where}: modal damping is already set (zeta={self._modal[0]!r})")
        if np.ndim(zeta) == 0:
            zeta = _real(where, "zeta", zeta, ">=0")
        else:
            zeta = tuple(_real(where, f"zeta[{k}]", z, ">=0") for k, z in enumerate(zeta))
            if not zeta:
                raise ValueError(f"{where}: zeta is an empty sequence")
        if modes is not None:
            if isinstance(modes, bool) or not isinstance(modes, numbers.Integral) or modes < 1:
                raise ValueError(f"{where}: modes={modes!r} must be an integer >= 1 (the number of modes) or None")
            modes = int(modes)
            if not isinstance(zeta, float) and len(zeta) != modes:
                raise ValueError(f"{where}: {len(zeta)} ratios for modes={modes}; give one per mode")
        self._modal = (zeta, modes)

    # ------------------------------------------------------------------ shared parts of the builders
    def _define_node(self, node_id, xyz) -> None:
        """Define node ``node_id`` at the coordinates ``xyz`` (``(x, y)`` or ``(x, y, z)``)."""
        if type(node_id) is int or type(node_id) is str:
            pass
        elif isinstance(node_id, numbers.Integral) and not isinstance(node_id, bool):
            node_id = int(node_id)
        elif not isinstance(node_id, str):
            raise TypeError(f"node id must be an int or a str, got {node_id!r}")
        if node_id in self._coords:
            at = ", ".join(f"{x:g}" for x in self._coords[node_id])
            raise ValueError(f"node {node_id!r} is already defined (at ({at}))")
        where = f"node {node_id!r}"
        if len(xyz) == 2:
            self._coords[node_id] = np.array([_real(where, "x", xyz[0]), _real(where, "y", xyz[1])])
        else:
            self._coords[node_id] = np.array([_real(where, axis, value) for axis, value in zip("xyz", xyz)])

    def _support_flags(self, node, values) -> tuple[str, dict]:
        """``(where, {dof: flag})`` of a support of ``node`` with the flags ``values`` of the
        :attr:`_dof_names`, checked: booleans, at least one True."""
        where = f"support at node {node!r}"
        self._node(where, "node", node)
        flags = dict(zip(self._dof_names, values))
        for dof, flag in flags.items():
            if not isinstance(flag, (bool, np.bool_)):
                raise TypeError(f"{where}: {dof}={flag!r} must be True or False")
        if not any(flags.values()):
            names = self._dof_names
            raise ValueError(f"{where}: {', '.join(names[:-1])} and {names[-1]} are all False; the support "
                             "restrains nothing")
        return where, flags

    @abstractmethod
    def _master(self, node):
        """The master of ``node`` if it is a slave (of a rigid link or a diaphragm), else None."""

    def _check_tie(self, where, master, slave, dofs) -> None:
        """The checks of tying ``dofs`` of ``slave`` to ``master`` (a rigid link or a diaphragm):
        defined nodes, not the same node, ``slave`` not yet a slave nor supported on ``dofs``, no
        loop of ties."""
        self._node(where, "master", master)
        self._node(where, "slave", slave)
        if master == slave:
            raise ValueError(f"{where}: master and slave are the same node {slave!r}")
        if self._master(slave) is not None:
            raise ValueError(f"{where}: node {slave!r} is already a slave of node {self._master(slave)!r}")
        supported = [dof for dof in dofs if (slave, dof) in self._restrained]
        if supported:
            raise ValueError(f"{where}: slave node {slave!r} is supported ({', '.join(supported)}); "
                             "support the master node instead")
        root = master
        while self._master(root) is not None:
            root = self._master(root)
            if root == slave:
                raise ValueError(f"{where}: the link would close a loop of rigid links through node {slave!r}")

    def _assemble(self, dofs, exempt=frozenset()) -> dict:
        """The natural form of the elements on the free DOFs ``dofs``, the mass and the damping
        matrices: the fields of a :class:`Structure` but the foundation and P-Delta.

        Raises ``ValueError`` if no DOF is free, or naming the free DOFs no element stiffens but
        those ``exempt`` (see :func:`_check_stiffness`).
        """
        if dofs.n == 0:
            raise ValueError("every DOF is supported or linked: the frame has no free DOF")
        elements = el.check_clearances(self._elements, self._coords)
        G = _compatibility(elements, dofs)
        stiffness = [e.E for e in elements]
        E = _block_diagonal(stiffness)
        kelvin = any(e.E_v is not None for e in elements)
        E_v = _block_diagonal([np.zeros_like(e.E) if e.E_v is None else e.E_v for e in elements]) if kelvin else None
        theta = np.concatenate([e.theta for e in elements]) if elements else np.zeros(0)
        starts = accumulate([block.shape[0] for block in stiffness], initial=0)
        columns = [(start, u) for start, e in zip(starts, elements) for u in e.unknowns]
        rows = np.array([start + u.row for start, u in columns], dtype=int)     # each unknown's primary strain
        m = len(columns)
        # one entry (row, b) per unknown, and the extra entries of an unknown on several strains
        # (a facet of a polygonal friction cone: both tangential strains)
        entries = np.array([(start + row, col, b) for col, (start, u) in enumerate(columns) for row, b in u.entries],
                           dtype=float).reshape(-1, 3)
        B = csr_of_entries(entries[:, 2], entries[:, 0].astype(int), entries[:, 1].astype(int), (G.shape[1], m))
        r = np.array([u.r for _, u in columns])
        A = _interaction([e for e in elements if e.unknowns], m)
        nodal_mass = _nodal_mass(self._mass, dofs)
        M = _lumped_mass(dofs, nodal_mass)
        K = (G @ E @ G.T).tocsr()
        _check_stiffness(K, dofs, exempt=exempt)
        check_frequency_range(K, M, dofs.names)
        C = self._damping(dofs, M, K)
        natural = NaturalForm(G=G, E=E, B=B, A=A, r=r, theta=ConstantStrain(theta), E_v=E_v)
        return dict(
            natural=natural, M=M, C=C, dofs=dofs,
            element_names=tuple(e.name for e in elements),
            strain_names=_strain_names(elements),
            constraint_names=tuple(u.name for _, u in columns),
            constraint_strains=rows, nodal_mass=nodal_mass,
            elements=tuple(elements), dashpots=tuple(self._dashpots),
            coords=dict(zip(self._coords, np.array(list(self._coords.values())))),      # (copies)
            rayleigh=self._rayleigh,
        )

    # ------------------------------------------------------------------ plasticity and friction
    def _hinge_site(self, name, beam, end) -> str:
        """The label of the hinge ``name`` at the end ``end`` of the beam ``beam``, checked: a beam of
        the frame, ``"i"`` or ``"j"``, one hinge per beam end."""
        where = self._label("hinge", name)
        if not isinstance(beam, str) or beam not in self._beams:
            beams = ", ".join(repr(b) for b in list(self._beams)[:10]) or "none"
            raise ValueError(f"{where}: beam={beam!r} is not a beam of the frame (beams: {beams})")
        if end not in ("i", "j"):
            raise ValueError(f"{where}: end={end!r} is not valid; use 'i' or 'j'")
        if (beam, end) in self._hinges:
            raise ValueError(f"{where}: end {end!r} of beam {beam!r} already has the hinge "
                             f"{self._hinges[(beam, end)]!r}; one hinge per beam end")
        return where

    def _put_hinge(self, name, beam, end, hinged) -> None:
        """Replace the beam ``beam`` by ``hinged(beam element)``, its element with the hinge."""
        p = next(p for p, e in enumerate(self._elements) if e.name == beam)
        self._elements[p] = hinged(self._elements[p])
        self._hinges[(beam, end)] = name
        self._names.add(name)

    def yield_link(self, name, node_i, node_j=None, *, k, Fy=None, Fy_t=None, Fy_c=None, direction="ux",
                   hardening=0.0) -> None:
        """Zero-length elastic-plastic spring from ``node_i`` to the ground (``node_j=None``) or to
        ``node_j``, along ``direction`` (as :meth:`spring`).

        Force ``sigma = k (e - v+ + v-)`` (tension positive) with ``-Fy_c <= sigma - Hk (v+ - v-) <= Fy_t``:
        the plastic multipliers ``"name.plastic+"`` (tension) and ``"name.plastic-"`` (compression)
        grow only while their face yields; the plastic deformation is ``v+ - v-``. Linear kinematic
        hardening ``Hk = hardening k`` gives the post-yield stiffness ``k h / (1 + h)``.

        Parameters
        ----------
        k : elastic stiffness, force/length (force length/rad along a rotation), > 0
        Fy : yield force both ways, force (force length along a rotation), > 0; or
        Fy_t, Fy_c : yield forces in tension and compression, > 0 (e.g. a buckling-restrained
            brace, ``Fy_c > Fy_t``)
        hardening : ``h = Hk / k >= 0`` (0: perfectly plastic)
        """
        where, ends, terms = self._ends("yield_link", name, node_i, node_j, direction, ("node_i", "node_j"))
        k = _real(where, "k", k, ">0")
        r = _yield_forces(where, Fy, Fy_t, Fy_c)
        A = el.kinematic_hardening(_hardening(where, hardening) * k)
        self._add(el.directional(name, "yield", *ends, terms, k, unknowns=el.pair(name, 0, "yield", r=r, k=k), A=A,
                                 dof_names=self._dof_names))

    def slider(self, name, node, *, mu, N, k, direction="ux") -> None:
        """Flat sliding bearing under ``node``: a stick spring ``k`` in series with Coulomb
        friction under the constant normal force ``N``.

        A :meth:`yield_link` to the ground with ``Fy = mu N`` both ways, whose slips
        ``"name.slip+"``, ``"name.slip-"`` form a friction family with a constant normal force
        (:class:`~unilateral.constraints.Friction` with ``normal=None``; its law is that of a yield
        pair, and results report it as friction). ``N`` does not follow the vertical response;
        support or connect the node vertically by other elements.

        Parameters
        ----------
        mu : friction coefficient, >= 0
        N : normal (compressive) force, force, > 0
        k : stick stiffness, force/length, > 0
        direction : ``"ux"`` (default), another translation or a vector: the sliding direction
        """
        where, ends, terms = self._ends("slider", name, node, None, direction, ("node", None))
        if any(dof.startswith("r") for dof in dict(terms)):
            raise ValueError(f"{where}: direction={direction!r} is not a sliding direction; use a translation "
                             "('ux', 'uy', ...) or a vector")
        k, mu = _real(where, "k", k, ">0"), _real(where, "mu", mu, ">=0")
        force = mu * _real(where, "N", N, ">0")
        self._add(el.directional(name, "slider", *ends, terms, k,
                                 unknowns=el.pair(name, 0, "friction", r=(force, force), mu=mu, k=k),
                                 dof_names=self._dof_names))

    # ------------------------------------------------------------------ helpers
    def _damping(self, dofs, M, K=None):
        """Attached dashpots plus Rayleigh damping plus modal damping, or None.

        The stiffness-proportional part uses the bilateral elements only: a unilateral element
        must not transmit damping forces across an open contact.
        """
        C = None
        if self._dashpots:
            Gd = _compatibility(self._dashpots, dofs)
            C = (Gd @ _block_diagonal([d.E for d in self._dashpots]) @ Gd.T).tocsr()
        if self._rayleigh is not None:
            a0, a1 = self._rayleigh
            R = a0 * M
            bilateral = [e for e in self._elements if not e.unilateral] if a1 else []
            if a1 and bilateral:
                Gb = _compatibility(bilateral, dofs)
                R = R + a1 * (Gb @ _block_diagonal([e.E for e in bilateral]) @ Gb.T)
            C = R.tocsr() if C is None else (C + R).tocsr()
        if self._modal is not None:
            D = sp.csr_matrix(modal_damping_matrix(K, M, *self._modal))
            C = D if C is None else (C + D).tocsr()
        return C

    def _label(self, kind, name) -> str:
        if not isinstance(name, str) or not name:
            raise TypeError(f"{kind} name must be a non-empty str, got {name!r}")
        if name in self._names:
            raise ValueError(f"{kind} {name!r}: the name is already used by another element")
        return f"{kind} {name!r}"

    def _add(self, element: el.Element) -> None:
        self._elements.append(element)
        self._names.add(element.name)

    def _known(self, node) -> bool:
        """Whether ``node`` is a defined node (False for an unhashable ``node``)."""
        try:
            return node in self._coords
        except TypeError:
            return False

    def _node(self, where, arg, node) -> None:
        if not self._known(node):
            nodes = node_list(list(self._coords))
            raise ValueError(f"{where}: {arg}={node!r} is not defined (nodes: {nodes})")

    def _two_nodes(self, where, i, j, labels=("i", "j")) -> None:
        self._node(where, labels[0], i)
        self._node(where, labels[1], j)
        if i == j:
            raise ValueError(f"{where}: {labels[0]} and {labels[1]} are the same node {i!r}")

    def _directional(self, kind, name, i, j, k, direction) -> el.Element:
        where, ends, terms = self._ends(kind, name, i, j, direction)
        coefficient = "c" if kind == "dashpot" else "k"
        return el.directional(name, kind, *ends, terms, _real(where, coefficient, k, ">0"), dof_names=self._dof_names)

    def _ends(self, kind, name, i, j, direction, labels=("i", "j")):
        """``(where, ends, terms)`` of a directional element from node ``i`` to the ground or ``j``
        (``labels``: the names of the arguments ``i`` and ``j``, for messages)."""
        where = self._label(kind, name)
        self._node(where, labels[0], i)
        if j is not None:
            self._two_nodes(where, i, j, labels)
        return where, ((None, i) if j is None else (i, j)), el.direction_terms(where, direction, self._dof_names,
                                                                               self._axes)


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
        the nodes, not in ``sigma``), and the energy terms do not count it. A gravity at or above
        the buckling load makes ``K`` indefinite: ``to_model`` then refuses the model.
        ``enabled=False`` switches it off.
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

    def bar(self, name, i, j, E, A, *, axial_strain=0.0) -> None:
        """Axial bar from node ``i`` to node ``j`` (strain: elongation, stiffness ``EA/L``)."""
        where = self._label("bar", name)
        self._two_nodes(where, i, j)
        self._add(el.bar(name, i, self._coords[i], j, self._coords[j], E=_real(where, "E", E, ">0"),
                         A=_real(where, "A", A, ">0"), axial_strain=_real(where, "axial_strain", axial_strain)))

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
             ct=0.0) -> None:
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

        With ``mu``, a tangential strain ``t . u_node`` (``t`` the direction turned 90 degrees
        clockwise: ``"ux"`` for ``"uy"``) carries the force ``T = kt (e_t - s+ + s-) + ct (...)'``
        with ``|T| <= mu N``, ``N = capacity - sigma`` the compression of the contact (``N = 0``:
        no tangential force once the node has lifted off); the slips ``s+-`` are the unknowns
        ``"name.slip+"``, ``"name.slip-"``.
        """
        where = self._label("soil", name)
        self._node(where, "node", node)
        self._add(self._contact("soil", where, name, None, node, k=k, c=c, direction=direction, gap=gap,
                                capacity=capacity, friction=_friction(where, mu, kt, ct)))

    def soils(self, names, nodes, k, *, c=0.0, gap=0.0, capacity=0.0, direction="uy") -> None:
        """Many tensionless soil elements at once: :meth:`soil` ``(names[k], nodes[k], k[k], c=c[k],
        gap=gap[k], capacity=capacity[k], direction=direction)`` for every row (the numbers: (n,) or
        one for all; one ``direction``; without friction: contacts with friction by :meth:`soil`).
        All rows are checked before any element is added."""
        bulk.add_soils(self, names, nodes, k, c=c, gap=gap, capacity=capacity, direction=direction)

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

    def hinge(self, name, beam, end, *, My, k=None, hardening=0.0) -> None:
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

        Parameters
        ----------
        My : yield moment, force length, > 0
        k : rotational stiffness of the spring, force length/rad, > 0, or None (rigid-plastic)
        hardening : ``h >= 0``
        """
        where = self._hinge_site(name, beam, end)
        My = _strength(where, "My", My)
        k = None if k is None else _real(where, "k", k, ">0")
        reference = k if k is not None else self._beams[beam].E[1, 1]          # k or 4EI/L
        modulus = _hardening(where, hardening) * reference
        self._put_hinge(name, beam, end, lambda beam_element: el.hinge(beam_element, name, end, My=My, k=k,
                                                                      modulus=modulus))

    # ------------------------------------------------------------------ foundation on a soil medium
    def foundation(self, name, node, *, width=None, length, soil, patches=None, nodes=None,
                   horizontal="support", gap=0.0, mass=0.0, J=0.0, mu=None) -> None:
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
        """
        from .foundation import _check_overlap, build_foundation, horizontal_cone

        where = f"foundation {name!r}"
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
        dofs = DofMap(self._coords, self._restrained, rotated, self._links)
        on_soil = rigid.exempt_dofs(self, dofs)         # held by rigid contacts (rigid.py), and:
        for footing in self._foundations:               # the soil stiffens these (FoundationModel checks)
            for terms in footing.moved_rows(self._coords) + (footing.shear_rows() if footing.sliding else []):
                on_soil |= {(node, dof) for node, dof, _ in terms}
        fields = self._assemble(dofs, exempt=on_soil)
        footings = None
        if self._foundations:
            from .foundation import Footings

            footings = Footings(self._foundations, first=len(fields["constraint_names"]))
        structure = support_motion.attach(self, Structure(**fields, foundation=footings))
        if self._p_delta is None:
            return rigid.attach(self, structure)
        if self._foundations:
            raise ValueError("p_delta: not available with a foundation on a soil medium")
        g, (dx, dy) = self._p_delta
        load = structure.gravity(g, (dx, dy)) if (dx or dy) else np.zeros(structure.n)
        axial = structure.static_axial_forces(load)
        return replace(structure, geometric=structure.geometric_stiffness(axial), axial_forces=axial)

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
        one :class:`~unilateral.constraints.Yield` and one :class:`~unilateral.constraints.Friction`
        (each only if it has unknowns)."""
        pairs = self.constraints
        index = {u.name: k for k, (_, u) in enumerate(pairs)}
        of = {kind: [k for k, (_, u) in enumerate(pairs) if u.kind == kind] for kind in el.UNKNOWN_KINDS}
        families = [Contact(of["contact"])] if of["contact"] else []
        if of["yield"]:
            families.append(Yield(of["yield"], polygons=_yield_polygons(pairs, of["yield"])))
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

            return to_foundation_model(self)
        nat = self.natural
        model = Model.from_natural(
            nat.G, nat.E, nat.B, M=self.M, A=_nonzero_interaction(nat.A, np.shape(nat.B)[1]), r=nat.r,
            theta=nat.theta.value if isinstance(nat.theta, ConstantStrain) else nat.theta, theta_rate=nat.theta_rate,
            C=self.C, E_v=nat.E_v, dof_names=self.dofs.names,
            constraint_names=list(self.constraint_names), families=self.families(),
            on_soil=self.foundation is not None,
        )
        if self.foundation is not None:
            from .foundation import to_foundation_model

            return to_foundation_model(self, model)
        if self.geometric is not None:
            from ..model import check_definite

            K = (model.K + self.geometric).tocsr()
            try:
                check_definite("K", K, strict=True)
            except ValueError as exc:
                raise ValueError(f"p_delta: K - K_G is not positive definite: the gravity load reaches the "
                                 f"buckling load of the structure held bilateral ({exc})") from None
            model.K = K
            model.natural = replace(model.natural, K_geometric=self.geometric)
        return model

    def static_axial_forces(self, load) -> dict:
        """Axial forces (tension positive) of the beams and bars under the static load ``load``
        (n,), every element bilateral (contacts closed and bonded, no yield), imposed strains
        included: ``{name: N}``."""
        from scipy.sparse.linalg import spsolve

        nat = self.natural
        theta = nat.theta(0.0)
        GE = nat.G @ nat.E
        K = (GE @ nat.G.T).tocsc()
        f = np.asarray(load, dtype=float) + np.asarray(GE @ theta).ravel()
        u = np.atleast_1d(spsolve(K, f))
        sigma = nat.E @ (np.asarray(nat.G.T @ u).ravel() - theta)
        out, start = {}, 0
        for e in self.elements:
            if e.kind in ("beam", "bar"):
                out[e.name] = float(sigma[start])
            start += e.E.shape[0]
        return out

    def geometric_stiffness(self, axial) -> sp.csr_matrix:
        """Geometric stiffness ``K_G`` (n, n) of the axial forces ``axial`` ``{beam or bar name: N}``
        (tension positive; a compression lowers the stiffness).

        Beams: the consistent matrix of the cubic deflection, ``N/(30 L) [[36, 3L, -36, 3L],
        [3L, 4L^2, -3L, -L^2], [-36, -3L, 36, -3L], [3L, -L^2, -3L, 4L^2]]`` on the transverse
        displacements and the rotations ``(v_i, rz_i, v_j, rz_j)``; bars: the string stiffness
        ``N/L [[1, -1], [-1, 1]]`` on ``(v_i, v_j)`` (``v = -s ux + c uy``, ``(c, s)`` the chord).
        """
        full = self.dofs.T.shape[0]
        rows, cols, vals = [], [], []
        for e in self.elements:
            if e.name not in axial or e.kind not in ("beam", "bar"):
                continue
            N = float(axial[e.name])
            i, j = e.dofs[0][0], e.dofs[-1][0]
            L, (c, s) = el.chord(e.name, i, self.coords[i], j, self.coords[j])
            index = {d: k for k, d in enumerate(e.dofs)}
            if e.kind == "beam":
                T = np.zeros((4, len(e.dofs)))
                T[0, [index[(i, "ux")], index[(i, "uy")]]] = (-s, c)
                T[1, index[(i, "rz")]] = 1.0
                T[2, [index[(j, "ux")], index[(j, "uy")]]] = (-s, c)
                T[3, index[(j, "rz")]] = 1.0
                k = N / (30 * L) * np.array([[36, 3 * L, -36, 3 * L], [3 * L, 4 * L * L, -3 * L, -L * L],
                                             [-36, -3 * L, 36, -3 * L], [3 * L, -L * L, -3 * L, 4 * L * L]])
            else:
                T = np.zeros((2, len(e.dofs)))
                T[0, [index[(i, "ux")], index[(i, "uy")]]] = (-s, c)
                T[1, [index[(j, "ux")], index[(j, "uy")]]] = (-s, c)
                k = N / L * np.array([[1.0, -1.0], [-1.0, 1.0]])
            ke = T.T @ k @ T
            at = np.array([self.dofs.full_index(node, dof) for node, dof in e.dofs])
            rows.append(np.repeat(at, len(at)))
            cols.append(np.tile(at, len(at)))
            vals.append(ke.ravel())
        KG = _coo(rows, cols, vals, (full, full))
        return (self.dofs.T.T @ KG @ self.dofs.T).tocsr()

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


# ---------------------------------------------------------------------- assembly
def _compatibility(elements, dofs: DofMap) -> sp.csr_matrix:
    """``G = T^T L^T`` (n, ne) with ``e = L u_full`` the elements' strains of the nodal DOFs.

    The entries of ``L^T`` are gathered per group of elements of one shape of ``a`` (a beam's
    (3, 6), a soil spring's (1, 1), ...): one array operation per group, not per element.
    """
    full = dofs.T.shape[0]
    if not elements:
        return (dofs.T.T @ sp.csr_matrix((full, 0))).tocsr()
    at = _full_rows(elements, dofs)
    if len(elements) <= SMALL_ASSEMBLY:
        L = _rows_of_blocks([e.a for e in elements], at.tolist(), full)
    else:
        L = _rows_of_groups(elements, at, full)
    if not L.has_canonical_format:
        L.sum_duplicates()
    return (dofs.T.T @ L.T).tocsr()     # (L^T in CSC: L's own arrays, as T^T's CSC product takes them)


#: Up to this many elements (or blocks) the builder's sparse matrices are gathered by a loop in
#: Python, which costs less than the array operations by groups on so few.
SMALL_ASSEMBLY = 64


def _rows_of_blocks(blocks, columns, width) -> sp.csr_matrix:
    """The CSR matrix (sum of the blocks' rows, width) whose rows are those of the 2-D ``blocks``
    one after the other, block ``p`` on the columns ``columns[c_p:c_p + d_p]`` (``c_p`` the sum of
    the widths ``d`` of the blocks before), explicit zeros kept."""
    indptr, indices, data = [0], [], []
    start = 0
    for block in blocks:
        values = block.tolist()
        d = block.shape[1]
        where = columns[start:start + d]
        for row in values:
            indices += where
            data += row
            indptr.append(len(indices))
        start += d
    return sp.csr_matrix((np.array(data, dtype=float), np.array(indices, dtype=np.intp),
                          np.array(indptr, dtype=np.intp)), shape=(len(indptr) - 1, width))


def _rows_of_groups(elements, at, full) -> sp.csr_matrix:
    """``L`` (ne, full) of :func:`_compatibility`, gathered per group of elements of one shape of ``a``."""
    blocks = [e.a for e in elements]
    shapes = np.fromiter(chain.from_iterable(map(_shape_of, blocks)), dtype=np.intp,
                         count=2 * len(blocks)).reshape(-1, 2)
    # L (ne, full) row by row: strain row i of an element of shape (k, d) holds row i of its ``a``
    # on the columns of its DOFs; then L^T = the transpose, summed and sorted as a COO's would be
    sizes = shapes[:, 0] * shapes[:, 1]
    entry_start, dof_start = _exclusive_cumsum(sizes), _exclusive_cumsum(shapes[:, 1])
    nnz = int(sizes.sum())
    indices = np.empty(nnz, dtype=np.intp)
    data = np.empty(nnz)
    per_row = np.empty(int(shapes[:, 0].sum()), dtype=np.intp)
    strain_start = _exclusive_cumsum(shapes[:, 0])
    for (k, d), members in _groups(shapes):
        count = members.size
        where = np.add.outer(entry_start[members], np.arange(k * d))                       # (count, k d)
        index = at[np.add.outer(dof_start[members], np.arange(d))]                         # (count, d)
        indices[where] = np.broadcast_to(index[:, None, :], (count, k, d)).reshape(count, k * d)
        data[where] = _stacked([blocks[p] for p in members.tolist()]).reshape(count, k * d)
        per_row[np.add.outer(strain_start[members], np.arange(k))] = d
    indptr = np.zeros(per_row.size + 1, dtype=np.intp)
    np.cumsum(per_row, out=indptr[1:])
    return sp.csr_matrix((data, indices, indptr), shape=(per_row.size, full))


_shape_of = operator.attrgetter("shape")


def _exclusive_cumsum(sizes) -> np.ndarray:
    """``[0, s0, s0 + s1, ...]`` without the total: where each block starts."""
    out = np.zeros(len(sizes), dtype=np.intp)
    np.cumsum(sizes[:-1], out=out[1:])
    return out


def _groups(keys):
    """``(key, members)`` of the rows of ``keys`` (count, w) ints >= 0 that are equal, in the order of
    their first occurrence; ``members`` the indices of the rows (ascending)."""
    if len(keys) <= 64:                 # a few elements: a dict costs less than the array operations
        found: dict = {}
        for p, key in enumerate(map(tuple, keys.tolist())):
            found.setdefault(key, []).append(p)
        return [(key, np.array(members, dtype=np.intp)) for key, members in found.items()]
    width = keys.max(axis=0) + 1
    code = np.ravel_multi_index(tuple(keys.T), tuple(width)) if keys.shape[1] > 1 else keys[:, 0]
    _, first, inverse = np.unique(code, return_index=True, return_inverse=True)
    order = np.argsort(inverse, kind="stable")
    bounds = np.searchsorted(inverse[order], np.arange(first.size + 1))
    groups = [(first[g], order[bounds[g]:bounds[g + 1]]) for g in range(first.size)]
    groups.sort(key=lambda item: item[0])
    return [(tuple(int(x) for x in keys[at]), members) for at, members in groups]


def _stacked(blocks) -> np.ndarray:
    """The entries of the equally shaped 2-D ``blocks``, one after the other, as floats
    (``np.asarray(blocks, dtype=float).ravel()``)."""
    return np.concatenate(blocks).astype(float, copy=False).ravel()


def _full_rows(elements, dofs: DofMap) -> np.ndarray:
    """The rows in ``u_full`` of the DOFs of every element, one after the other
    (:meth:`DofMap.full_index` of each)."""
    width, position = len(dofs.dof_names), dofs._position
    offset = {dof: d for d, dof in enumerate(dofs.dof_names)}
    nodes, names = _node_and_dof_columns(elements)
    try:
        return (width * np.fromiter(map(position.__getitem__, nodes), dtype=np.intp, count=len(nodes))
                + np.fromiter(map(offset.__getitem__, names), dtype=np.intp, count=len(names)))
    except (KeyError, TypeError):
        return np.array([dofs.full_index(node, dof) for e in elements for node, dof in e.dofs], dtype=np.intp)


_FIRST, _SECOND = operator.itemgetter(0), operator.itemgetter(1)


def _node_and_dof_columns(elements) -> tuple[list, list]:
    """The nodes and the DOF names of the ``(node, dof)`` pairs of every element, one after the
    other: two lists (gathered by the interpreter's iterators, not a loop of Python code)."""
    pairs = list(chain.from_iterable([e.dofs for e in elements]))
    return list(map(_FIRST, pairs)), list(map(_SECOND, pairs))


def _strain_names(elements) -> tuple:
    """The names of the elements' strains, one after the other (their ``strain_labels``)."""
    names = []
    for e in elements:
        name = e.name
        if e.kind == "beam" and type(e) is el.Element and type(name) is str:
            names += (name + ".axial", name + ".rot_i", name + ".rot_j")
        else:
            names += e.strain_labels
    return tuple(names)


def _lumped_mass(dofs, nodal_mass) -> sp.csr_matrix:
    """``M = (T^T diag(m) T).tocsr()`` of the lumped masses ``nodal_mass`` (n_nodes, 3).

    Without rigid links ``T`` picks the free rows of ``u_full`` (one 1 per column, at most one per
    row): ``M`` is then the diagonal of the masses of the free DOFs, the zero ones not stored (as
    the product stores no zero), made directly; with links, the product."""
    if type(dofs) is DofMap and not dofs.masters and nodal_mass.dtype == np.float64:
        n = dofs.n
        d = nodal_mass.ravel()[dofs._free_rows]
        if np.all(d >= 0):
            stored = d != 0
            indptr = np.zeros(n + 1, dtype=np.intp)
            np.cumsum(stored, out=indptr[1:])
            return sp.csr_matrix((d[stored], np.flatnonzero(stored), indptr), shape=(n, n))
    d = nodal_mass.ravel()
    if nodal_mass.dtype == np.float64 and np.all(d >= 0):
        # T^T @ sp.diags(d) converts the diagonal to CSC (dropping its zeros): made so here
        stored = d != 0
        indptr = np.zeros(d.size + 1, dtype=np.intp)
        np.cumsum(stored, out=indptr[1:])
        D = sp.csc_matrix((d[stored], np.flatnonzero(stored), indptr), shape=(d.size, d.size))
        return (dofs.T.T @ D @ dofs.T).tocsr()
    return (dofs.T.T @ sp.diags(nodal_mass.ravel()) @ dofs.T).tocsr()


def _nodal_mass(masses, dofs) -> np.ndarray:
    """``(n_nodes, len(dofs.dof_names))`` lumped masses of the nodes of ``dofs`` (zero without one)."""
    width = len(dofs.dof_names)
    zero = np.zeros(width)
    per_node = [masses.get(node, zero) for node in dofs.nodes]
    if per_node and {(type(x), x.shape, x.dtype) for x in masses.values()} <= {(np.ndarray, (width,), zero.dtype)}:
        return np.concatenate(per_node).reshape(len(per_node), width)    # (the same rows as np.array's)
    return np.array(per_node)


def _block_diagonal(blocks) -> sp.csr_matrix:
    """Sparse block-diagonal matrix of small dense blocks (grouped by size: one array operation per
    size, not per block)."""
    if not blocks:
        return _coo([], [], [], (0, 0))
    if len(blocks) <= SMALL_ASSEMBLY and all(block.ndim == 2 for block in blocks):
        columns = list(range(sum(len(block) for block in blocks)))
        E = _rows_of_blocks(blocks, columns, len(columns))
        if E.shape[0] == len(columns):
            return E
    sizes = np.fromiter(map(len, blocks), dtype=np.intp, count=len(blocks))
    starts, entry_start = _exclusive_cumsum(sizes), _exclusive_cumsum(sizes * sizes)
    total, nnz = int(sizes.sum()), int((sizes * sizes).sum())
    # row by row (CSR): row i of a block of size k starting at s holds its row i on columns s .. s + k - 1
    indices = np.empty(nnz, dtype=np.intp)
    data = np.empty(nnz)
    per_row = np.empty(total, dtype=np.intp)
    for (k,), members in _groups(sizes[:, None]):
        count = members.size
        where = np.add.outer(entry_start[members], np.arange(k * k))                       # (count, k k)
        idx = np.add.outer(starts[members], np.arange(k))                                  # (count, k)
        indices[where] = np.broadcast_to(idx[:, None, :], (count, k, k)).reshape(count, k * k)
        data[where] = _stacked([blocks[p] for p in members.tolist()]).reshape(count, k * k)
        per_row[idx] = k
    indptr = np.zeros(total + 1, dtype=np.intp)
    np.cumsum(per_row, out=indptr[1:])
    return sp.csr_matrix((data, indices, indptr), shape=(total, total))


def _interaction(elements, m) -> np.ndarray:
    """``A`` (m, m): the elements' interactions of their unknowns on the diagonal (zero without
    hardening)."""
    A = np.zeros((m, m))
    start = 0
    for e in elements:
        u = len(e.unknowns)
        if u and e.A is not None:
            A[start:start + u, start:start + u] = e.A
        start += u
    return A


def _nonzero_interaction(A, m):
    """``A``, or None if it is a zero float array of shape ``(m, m)`` (which
    :meth:`Model.from_natural` then makes itself, without copying or checking a zero matrix)."""
    if type(A) is np.ndarray and A.dtype == np.float64 and A.shape == (m, m) and not A.any():
        return None
    return A


def _coo(rows, cols, vals, shape) -> sp.csr_matrix:
    if not vals:
        return sp.csr_matrix(shape)
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=shape)


def _check_stiffness(K, dofs: DofMap, exempt=frozenset()) -> None:
    """Raise ``ValueError`` naming the free DOFs no element stiffens.

    A mechanism whose diagonal is positive (e.g. a frame that sways with pinned joints, or a
    foundation on one soil element that rocks) is named where ``K`` must be factorised, by
    :func:`unilateral.linalg.mechanism_dofs` (the static state): its mass may still make the
    dynamic problem well posed.
    """
    d = K.diagonal()
    bad = np.array([i for i in np.flatnonzero(d <= 0) if dofs.free[i] not in exempt], dtype=int)
    if bad.size:
        names = ", ".join(dofs.names[i] for i in bad[:10]) + (", ..." if bad.size > 10 else "")
        raise ValueError(
            f"no element gives stiffness to DOF(s) {names}: the structure is a mechanism; "
            "support these DOFs or connect elements to them"
        )


def _real(where, arg, value, bound=None) -> float:
    """``float(value)``, finite, and ``> 0`` (bound ``">0"``) or ``>= 0`` (``">=0"``)."""
    kind = type(value)
    if kind is float or kind is int:            # the common case, checked without the ABCs
        x = float(value)
        if _isfinite(x) and (bound is None or (x > 0 if bound == ">0" else x >= 0 if bound == ">=0" else True)):
            return x
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{where}: {arg} must be a real number, got {value!r}")
    x = float(value)
    if not np.isfinite(x):
        raise ValueError(f"{where}: {arg}={value!r} must be finite")
    if bound == ">0" and x <= 0:
        raise ValueError(f"{where}: {arg}={value!r} must be > 0")
    if bound == ">=0" and x < 0:
        raise ValueError(f"{where}: {arg}={value!r} must be >= 0")
    return x


def _friction(where, mu, kt, ct):
    """``(mu, kt, ct)`` of a contact with Coulomb friction, or None without ``mu``."""
    if mu is None and kt is None and (ct is None or (type(ct) is float and ct == 0.0)):
        return None
    if mu is None:
        extra = [arg for arg, value in (("kt", kt), ("ct", ct)) if value is not None and value != 0.0]
        if extra:
            raise ValueError(f"{where}: {extra[0]} is a friction parameter; give the friction coefficient mu "
                             "too (or remove it)")
        return None
    mu = _real(where, "mu", mu, ">=0")
    if kt is None:
        raise ValueError(f"{where}: friction (mu={mu!r}) needs the stick stiffness kt (force/length, > 0)")
    return mu, _real(where, "kt", kt, ">0"), _real(where, "ct", ct, ">=0")


def _yield_forces(where, Fy, Fy_t, Fy_c) -> tuple[float, float]:
    """``(Fy_t, Fy_c)`` from ``Fy`` (both ways) or from both ``Fy_t`` and ``Fy_c``."""
    if Fy is not None:
        if Fy_t is not None or Fy_c is not None:
            raise ValueError(f"{where}: give either Fy (both ways) or Fy_t and Fy_c, not both")
        Fy = _strength(where, "Fy", Fy)
        return Fy, Fy
    if Fy_t is None or Fy_c is None:
        missing = "Fy" if Fy_t is None and Fy_c is None else ("Fy_t" if Fy_t is None else "Fy_c")
        raise ValueError(f"{where}: {missing} is missing; give the yield force Fy (both ways) or both Fy_t "
                         "(tension) and Fy_c (compression), > 0")
    return _strength(where, "Fy_t", Fy_t), _strength(where, "Fy_c", Fy_c)


#: The smallest yield force or moment: below it the summary's force ratios (force / Fy) and
#: ductilities (deformation / (Fy / k)) overflow or lose every digit.
MIN_STRENGTH = 1e-150


def _strength(where, arg, value) -> float:
    """A strength (``Fy``, ``My``, ...): finite, > 0 and >= :data:`MIN_STRENGTH`."""
    value = _real(where, arg, value, ">0")
    if value < MIN_STRENGTH:
        raise ValueError(f"{where}: {arg}={value!r} is below {MIN_STRENGTH:g}: the force ratios and ductilities "
                         f"(force / {arg}) cannot be represented in double precision; give {arg} >= "
                         f"{MIN_STRENGTH:g} (in the model's units), or leave the element out for no strength")
    return value


def _hardening(where, value) -> float:
    """The kinematic hardening ratio ``h >= 0``.

    Softening (``-1 < h < 0``) would make the model's ``A`` indefinite, which
    :meth:`Model.from_natural` refuses.
    """
    h = _real(where, "hardening", value)
    if h < 0:
        raise ValueError(f"{where}: hardening={value!r} must be >= 0 (the ratio of the kinematic hardening "
                         "modulus to the elastic stiffness; softening is not supported)")
    return h


def _yield_polygons(pairs, indices) -> list:
    """The yield multipliers of ``indices`` that are the facets of one polygon of more than four
    facets: those of one element whose columns of ``B`` share strains (a 3-D hinge at one beam end)."""
    groups: dict = {}
    for k in indices:
        element, unknown = pairs[k]
        rows = {row for row, _ in unknown.entries}
        joined = [key for key in groups if key[0] == id(element) and key[1] & rows]
        members = [k]
        for key in joined:
            members += groups.pop(key)
            rows |= key[1]
        groups[(id(element), frozenset(rows))] = members
    return [sorted(members) for members in groups.values() if len(members) > 4]

