"""Numbering of the free DOFs of a 3-D frame: supports, rotations, rigid links and diaphragms.

Every node has six nodal DOFs ``(ux, uy, uz, rx, ry, rz)``; the structure's unknowns ``u`` (n,)
are the free ones, and ``u_full = T u`` gives all nodal DOFs (``6 n_nodes``). A node tied to a
master node ``m`` by a rigid link follows the master's rigid-body motion, ``d = x_s - x_m``:

    u_s = u_m + theta_m x d,   theta_s = theta_m

(``u = (ux, uy, uz)``, ``theta = (rx, ry, rz)``), i.e. ``ux_s = ux_m + dz ry_m - dy rz_m``,
``uy_s = uy_m + dx rz_m - dz rx_m``, ``uz_s = uz_m + dy rx_m - dx ry_m``. A slave of a rigid
diaphragm (nodes at the master's z) follows it in the plane only: ``ux_s = ux_m - dy rz_m``,
``uy_s = uy_m + dx rz_m``, ``rz_s = rz_m``; it keeps its own ``uz``, ``rx``, ``ry``.

A rotation of a node is free only if something uses it (a beam end, a spring along it, a rotary
inertia, a slave's rotation, or a slave offset across it), as in :class:`.dofs.DofMap`.
Rotations of the other nodes are reported as 0.
"""

from __future__ import annotations

from collections.abc import Hashable

import numpy as np
import scipy.sparse as sp

from .dofs import DofMap, _root
from .elements3d import DOF_NAMES, ROTATIONS, TRANSLATIONS

#: The DOFs of a slave of a rigid diaphragm that follow its master.
IN_PLANE = ("ux", "uy", "rz")


def rigid_rows(offset) -> dict:
    """``dof -> ((master dof, coefficient), ...)`` of the rigid-body motion of a slave at ``offset``
    (3,) from its master."""
    dx, dy, dz = (float(x) for x in offset)
    return {"ux": (("ux", 1.0), ("ry", dz), ("rz", -dy)), "uy": (("uy", 1.0), ("rz", dx), ("rx", -dz)),
            "uz": (("uz", 1.0), ("rx", dy), ("ry", -dx)),
            "rx": (("rx", 1.0),), "ry": (("ry", 1.0),), "rz": (("rz", 1.0),)}


class DofMap3D(DofMap):
    """Free DOFs of a 3-D frame and the master-slave transformation ``u_full = T u``.

    Parameters
    ----------
    coords : dict node -> (3,) coordinates, in definition order
    restrained : set of (node, dof) supported DOFs
    rotated : set of (node, rotation) pairs (``"rx"``, ``"ry"``, ``"rz"``) that something uses
    ties : dict slave node -> (master node, tied DOFs): all six DOFs for a rigid link,
        :data:`IN_PLANE` for a rigid diaphragm (chains allowed, no cycles)
    equal : dict ``(node, dof) -> other node`` or None: the nodal DOF ``dof`` of ``node`` equals the
        same DOF of ``other`` (``Frame3D.equal_dof``); no cycles

    Attributes
    ----------
    nodes : list of node ids, in definition order
    free : list of (node, dof) pairs; ``u[k]`` is the DOF ``free[k]``
    masters : dict slave of a rigid link -> root master (the end of the chain of rigid links)
    ties : the ``ties`` given (rigid links and diaphragms)
    equal : the ``equal`` ties given
    T : (6 n_nodes, n) csr matrix; row ``6 p + d`` is DOF ``DOF_NAMES[d]`` of ``nodes[p]``

    :meth:`full_index`, :meth:`nodal` (``(..., n_nodes, 6)``) and :meth:`gather` are those of
    :class:`~unilateral.structure.DofMap` on the six :attr:`dof_names`.
    """

    dof_names = DOF_NAMES

    def __init__(self, coords: dict, restrained: set, rotated: set, ties: dict, equal=None):
        self.nodes = list(coords)
        self.equal = dict(equal or {})
        self._position = {node: p for p, node in enumerate(self.nodes)}
        self.ties = dict(ties)
        links = {s: m for s, (m, tied) in ties.items() if len(tied) == len(DOF_NAMES)}
        self.masters = {s: _root(s, links) for s in links}
        self._rows = {s: rigid_rows(np.asarray(coords[s], float) - np.asarray(coords[m], float))
                      for s, (m, _) in ties.items()}
        used = set(rotated)
        grown = True
        while grown:                                    # a used slave DOF uses its master's rotations
            grown = False
            for s, (m, tied) in ties.items():
                for dof in tied:
                    if dof in TRANSLATIONS or (s, dof) in used:
                        new = {(m, r) for r, c in self._rows[s][dof] if r in ROTATIONS and c != 0.0} - used
                        used |= new
                        grown = grown or bool(new)
            for (s, dof), m in self.equal.items():       # a used tied rotation uses the master's
                if (s, dof) in used and (m, dof) not in used:
                    used.add((m, dof))
                    grown = True
        self._restrained = set(restrained)
        self.free = [(node, dof) for node in self.nodes for dof in DOF_NAMES
                     if not self._tied(node, dof) and (node, dof) not in self.equal
                     and (node, dof) not in self._restrained
                     and (dof in TRANSLATIONS or (node, dof) in used)]
        self._index = {key: k for k, key in enumerate(self.free)}
        memo: dict = {}
        rows, cols, vals = [], [], []
        for p, node in enumerate(self.nodes):
            for d, dof in enumerate(DOF_NAMES):
                for key, value in self._expression(node, dof, memo).items():
                    if value != 0.0:
                        rows.append(len(DOF_NAMES) * p + d)
                        cols.append(self._index[key])
                        vals.append(value)
        self.T = sp.csr_matrix((vals, (rows, cols)), shape=(len(DOF_NAMES) * len(self.nodes), len(self.free)))

    def _tied(self, node, dof) -> bool:
        return node in self.ties and dof in self.ties[node][1]

    def _expression(self, node, dof, memo) -> dict:
        """``{free (node, dof): coefficient}`` of nodal DOF ``dof`` of ``node``."""
        key = (node, dof)
        if key in memo and memo[key] is None:
            raise ValueError(f"the ties form a cycle through {node}.{dof} (equal_dof, rigid links and diaphragms)")
        if key not in memo:
            memo[key] = None                            # in progress: met again, a cycle
            if key in self.equal:
                memo[key] = dict(self._expression(self.equal[key], dof, memo))
            elif self._tied(node, dof):
                master = self.ties[node][0]
                out: dict = {}
                for mdof, c in self._rows[node][dof]:
                    if c != 0.0:
                        for free, value in self._expression(master, mdof, memo).items():
                            out[free] = out.get(free, 0.0) + c * value
                memo[key] = out
            else:
                memo[key] = {key: 1.0} if key in self._index else {}
        return memo[key]

    def index(self, node: Hashable, dof: str) -> int:
        """Position of the free DOF ``(node, dof)`` in ``u``; ``ValueError`` if it is not free."""
        self.full_index(node, dof)
        if (node, dof) in self.equal:
            raise ValueError(f"{node}.{dof} is not a free DOF: it is tied to the {dof} of node "
                             f"{self.equal[(node, dof)]!r}; use nodal() for the displacements of every node")
        if self._tied(node, dof) and node not in self.masters:
            raise ValueError(f"{node}.{dof} is not a free DOF: node {node!r} is in a rigid diaphragm of node "
                             f"{self.ties[node][0]!r} (its {dof} follows the master); use nodal() for the "
                             "displacements of every node")
        return super().index(node, dof)
