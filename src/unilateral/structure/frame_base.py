"""The base of the 2-D and 3-D frame builders, :class:`_Frame`: the node, name and tie checks,
Rayleigh and modal damping, the directional elements, yield links and sliders, and the assembly
of the natural form, the mass and the damping matrices of a build.
"""

from __future__ import annotations

import numbers
from abc import ABC, abstractmethod
from dataclasses import replace
from itertools import accumulate

import numpy as np
import scipy.sparse as sp

from ..model import ConstantStrain, NaturalForm
from . import elements as el, hinge_laws
from .assembly import (_block_diagonal, _check_stiffness, _compatibility, _interaction, _lumped_mass, _nodal_mass,
                       _strain_names)
from .checks import _hardening, _real, _yield_forces
from .dofs import csr_of_entries, node_list
from .modes import check_frequency_range, modal_damping_matrix


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
        self._equal: dict = {}              # (slave, dof) -> master: the equal_dof ties

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
        masters = {(m, dof) for (_, dof), m in self._equal.items()}
        held = [dof for dof, flag in flags.items() if flag and (node, dof) in masters]
        if held:
            raise ValueError(f"{where}: {', '.join(held)} of node {node!r} are masters of equal_dof ties; a tie "
                             "to a supported DOF is a support: support the tied nodes' DOFs instead of the ties")
        tied = [dof for dof, flag in flags.items() if flag and (node, dof) in self._equal]
        if tied:
            raise ValueError(f"{where}: {', '.join(tied)} of node {node!r} are tied by equal_dof to node "
                             f"{self._equal[(node, tied[0])]!r}; support the master's instead")
        return where, flags

    def equal_dof(self, master, slave, *dofs) -> None:
        """Tie the nodal DOFs ``dofs`` of node ``slave`` to the same DOFs of node ``master``
        (OpenSees' ``equalDOF``): ``u_slave[dof] = u_master[dof]``; the slave keeps its other DOFs.

        The tied DOFs are eliminated (the slave's DOF reads the master's in the results). Chains
        are allowed (a master may itself be tied); a tied DOF cannot be supported (support the
        master's), nor be a DOF a rigid link or diaphragm already ties.

        Parameters
        ----------
        master, slave : node ids
        *dofs : str, each one of the nodal DOFs (``"ux"``, ``"uy"``, ``"rz"`` in 2-D)
        """
        where = f"equal_dof({master!r}, {slave!r}{''.join(f', {d!r}' for d in dofs)})"
        self._node(where, "master", master)
        self._node(where, "slave", slave)
        names = self._dof_names
        if not dofs:
            raise ValueError(f"{where}: no DOF given; give one or more of {', '.join(map(repr, names))}")
        for k, dof in enumerate(dofs):
            if not isinstance(dof, str) or dof not in names:
                raise ValueError(f"{where}: dofs[{k}]={dof!r} is not a DOF of a {len(names) // 3 + 1}-D frame; "
                                 f"use {', '.join(map(repr, names))}")
            if dofs.index(dof) != k:
                raise ValueError(f"{where}: {dof!r} is given twice")
        if master == slave:
            raise ValueError(f"{where}: master and slave are the same node {slave!r}")
        for dof in dofs:
            if (slave, dof) in self._restrained:
                raise ValueError(f"{where}: {dof} of slave node {slave!r} is supported; support the master's instead")
            if (master, dof) in self._restrained:
                raise ValueError(f"{where}: {dof} of master node {master!r} is supported; a tie to a supported DOF "
                                 f"is a support: support {dof} of node {slave!r} instead of tying it")
            if self._follows(slave, dof):
                raise ValueError(f"{where}: {dof} of node {slave!r} already follows node {self._master(slave)!r} "
                                 "(a rigid link or diaphragm)")
            if (slave, dof) in self._equal:
                raise ValueError(f"{where}: {dof} of node {slave!r} is already tied to node "
                                 f"{self._equal[(slave, dof)]!r}; a DOF follows one master")
            root = master
            while (root, dof) in self._equal:
                root = self._equal[(root, dof)]
                if root == slave:
                    raise ValueError(f"{where}: the tie would close a loop of ties of {dof} through node {slave!r}")
        self._equal.update({(slave, dof): master for dof in dofs})

    def _follows(self, node, dof) -> bool:
        """Whether DOF ``dof`` of ``node`` follows a master (a rigid link; 3-D: or a diaphragm)."""
        return self._master(node) is not None

    def _with_equal(self, ties: dict, equal=None) -> dict:
        """The ties ``{(node, dof): other}`` of the DOF map: ``ties`` (rigid blocks') and ``equal`` (default:
        every :meth:`equal_dof` tie)."""
        equal = self._equal if equal is None else equal
        both = set(ties) & set(equal)
        if both:
            node, dof = sorted(both, key=repr)[0]
            raise ValueError(f"equal_dof: {dof} of node {node!r} is tied to node {self._equal[(node, dof)]!r} and "
                             f"to node {ties[(node, dof)]!r} (a rigid block standing on it); tie it once")
        return {**ties, **equal}

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
        tied = [dof for dof in dofs if (slave, dof) in self._equal]
        if tied:
            raise ValueError(f"{where}: {', '.join(tied)} of node {slave!r} are tied by equal_dof to node "
                             f"{self._equal[(slave, tied[0])]!r}; a DOF follows one master")
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

    def yield_link(self, name, node_i, node_j=None, *, k=None, Fy=None, Fy_t=None, Fy_c=None, direction="ux",
                   hardening=0.0, backbone=None) -> None:
        """Zero-length elastic-plastic spring from ``node_i`` to the ground (``node_j=None``) or to
        ``node_j``, along ``direction`` (as :meth:`spring`).

        Force ``sigma = k (e - v+ + v-)`` (tension positive) with ``-Fy_c <= sigma - Hk (v+ - v-) <= Fy_t``:
        the plastic multipliers ``"name.plastic+"`` (tension) and ``"name.plastic-"`` (compression)
        grow only while their face yields; the plastic deformation is ``v+ - v-``. Linear kinematic
        hardening ``Hk = hardening k`` gives the post-yield stiffness ``k h / (1 + h)``.

        ``backbone`` (instead of ``k`` and the yield forces): the force-deformation law is the convex
        multi-linear backbone through the points ``(e, F)``, as :meth:`Frame2D.hinge
        <unilateral.structure.Frame2D.hinge>`'s moment-rotation one (slopes decreasing, > 0; beyond
        the last point ``hardening`` times the initial slope; points with ``e < 0`` a compression
        branch of the same slopes, else symmetric): elastic-perfectly-plastic springs in parallel,
        one pair ``"name.plastic<s>+-"`` per segment (the first ``"name.plastic+-"``), unloading with
        the initial stiffness and reloading by Masing's rule (OpenSees: a ``Parallel`` of
        ``ElasticPP`` materials).

        Parameters
        ----------
        k : elastic stiffness, force/length (force length/rad along a rotation), > 0
        Fy : yield force both ways, force (force length along a rotation), > 0; or
        Fy_t, Fy_c : yield forces in tension and compression, > 0 (e.g. a buckling-restrained
            brace, ``Fy_c > Fy_t``)
        hardening : ``h = Hk / k >= 0`` (0: perfectly plastic)
        backbone : sequence of ``(e, F)`` pairs [length, force; along a rotation rad, force length], or None
        """
        where, ends, terms = self._ends("yield_link", name, node_i, node_j, direction, ("node_i", "node_j"))
        if backbone is not None:
            given = [arg for arg, value in (("k", k), ("Fy", Fy), ("Fy_t", Fy_t), ("Fy_c", Fy_c)) if value is not None]
            if given:
                raise ValueError(f"{where}: {given[0]} cannot go with a backbone, which gives the link's stiffness "
                                 "and strengths (its first point: k = F1/e1, Fy = F1)")
            K, ks, plus, minus = hinge_laws.backbone_springs(where, backbone, _hardening(where, hardening))
            unknowns, A = el.backbone_pairs(name, 0, None, K=K, k=ks, theta_plus=plus, theta_minus=minus)
            self._add(el.directional(name, "yield", *ends, terms, K, unknowns=unknowns, A=A, dof_names=self._dof_names))
            return
        if k is None:
            raise ValueError(f"{where}: k is missing; give the elastic stiffness k (> 0) and the yield force(s), "
                             "or a backbone")
        k = _real(where, "k", k, ">0")
        r = _yield_forces(where, Fy, Fy_t, Fy_c)
        A = el.kinematic_hardening(_hardening(where, hardening) * k)
        self._add(el.directional(name, "yield", *ends, terms, k, unknowns=el.pair(name, 0, "yield", r=r, k=k), A=A,
                                 dof_names=self._dof_names))

    def _axial_yield(self, where, element, Fy, Fy_t, Fy_c, hardening):
        """``element`` (a bar: one axial strain, stiffness ``EA/L``) with the axial yield pair
        ``"name.plastic+-"`` of ``Fy`` or ``(Fy_t, Fy_c)`` and kinematic hardening ``hardening EA/L``,
        or as it is when no yield force is given."""
        if Fy is None and Fy_t is None and Fy_c is None:
            if hardening:
                raise ValueError(f"{where}: hardening={hardening!r} needs a yield force Fy (or Fy_t and Fy_c)")
            return element
        k = float(element.E[0, 0])
        r = _yield_forces(where, Fy, Fy_t, Fy_c)
        return replace(element, unknowns=el.pair(element.name, 0, "yield", r=r, k=k),
                          A=el.kinematic_hardening(_hardening(where, hardening) * k))

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
