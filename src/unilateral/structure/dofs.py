"""Numbering of the free DOFs: supports, rotational DOFs and rigid (master-slave) links.

Every node has three nodal DOFs ``(ux, uy, rz)``; the structure's unknowns ``u`` (n,) are the
free ones. ``u_full = T u`` gives all nodal DOFs (``3 n_nodes``): supported DOFs are zero, and a
node rigidly linked to a master follows the master's rigid-body motion

    ux_s = ux_m - (y_s - y_m) rz_m,   uy_s = uy_m + (x_s - x_m) rz_m,   rz_s = rz_m

A *tie* (``ties``) makes one nodal DOF of a node equal to the same DOF of another node (OpenSees'
``equalDOF``), the rest of its DOFs its own: a rigid block standing on a floor or on another block
has its base's ``ux`` tied to the point it stands on (no slip; :mod:`.stacks`).

A node gets a free ``rz`` only if something rotates it (a beam end, an ``"rz"`` spring, a
rotational mass, or a rigid link whose slave is offset or rotated), so that trusses and springs
do not leave rotations without stiffness. Rotations of the other nodes are reported as 0.
"""

from __future__ import annotations

from collections.abc import Hashable

import numpy as np
import scipy.sparse as sp

from .elements import DOF_NAMES


class DofMap:
    """Free DOFs of a frame and the master-slave transformation ``u_full = T u``.

    Parameters
    ----------
    coords : dict node -> (2,) coordinates, in definition order
    restrained : set of (node, dof) supported DOFs
    rotated : set of nodes whose rotation something uses
    links : dict slave node -> master node (chains allowed, no cycles)
    ties : dict ``(node, dof) -> other node``: the nodal DOF ``dof`` of ``node`` (free otherwise)
        equals the same DOF of ``other`` (a slave or free node), or None (no ties); no cycles

    Attributes
    ----------
    nodes : list of node ids, in definition order
    free : list of (node, dof) pairs; ``u[k]`` is the DOF ``free[k]``
    masters : dict slave -> root master (the end of the chain of links)
    T : (3 n_nodes, n) csr matrix; row ``3 p + d`` is DOF ``dof_names[d]`` of ``nodes[p]``
    """

    #: The nodal DOFs of every node, in the order of the rows of ``T`` (:class:`.dofs3d.DofMap3D`:
    #: the six of a 3-D frame).
    dof_names: tuple[str, ...] = DOF_NAMES

    def __init__(self, coords: dict, restrained: set, rotated: set, links: dict, ties=None):
        self.nodes = list(coords)
        self._position = {node: p for p, node in enumerate(self.nodes)}
        self.masters = {s: _root(s, links) for s in links}
        offset = {s: np.asarray(coords[s]) - np.asarray(coords[m]) for s, m in self.masters.items()}
        rotating = set(rotated) - set(self.masters)
        rotating |= {m for s, m in self.masters.items() if s in rotated or offset[s].any()}
        width, names = len(self.dof_names), self.dof_names
        keep = np.ones((len(self.nodes), width), dtype=bool)       # free: not slave, not supported, used
        if self.masters:
            keep[[self._position[s] for s in self.masters]] = False
        if "rz" in names:
            keep[:, names.index("rz")] &= np.array([node in rotating for node in self.nodes], dtype=bool)
        for node, dof in restrained:
            if dof in names and self._known(node):
                keep[self._position[node], names.index(dof)] = False
        rows = np.flatnonzero(keep)                                 # the rows of T with a 1
        nodes = self.nodes
        self.free = list(zip(map(nodes.__getitem__, (rows // width).tolist()),
                             map(names.__getitem__, (rows % width).tolist())))
        self._index = dict(zip(self.free, range(len(self.free))))
        self._restrained = set(restrained)
        tied_rows, tied_cols, tied_vals = [], [], []
        for node, m in self.masters.items():         # a slave follows its master's rigid-body motion
            p = width * self._position[node]
            dx, dy = offset[node]
            for row, dof, value in ((p, "ux", 1.0), (p, "rz", -dy), (p + 1, "uy", 1.0), (p + 1, "rz", dx),
                                    (p + 2, "rz", 1.0)):
                col = self._index.get((m, dof))
                if col is not None and value != 0.0:
                    tied_rows.append(row)
                    tied_cols.append(col)
                    tied_vals.append(value)
        n = len(self.free)
        self._free_rows = rows                       # T's row of each free DOF (its only entry: 1)
        rows = np.concatenate([rows, np.array(tied_rows, dtype=rows.dtype)])
        cols = np.concatenate([np.arange(n), np.array(tied_cols, dtype=int)])
        vals = np.concatenate([np.ones(n), np.array(tied_vals, dtype=float)])
        self.T = csr_of_entries(vals, rows, cols, (width * len(self.nodes), n))
        self.ties = dict(ties or {})
        if self.ties:
            self._tie()

    def _tie(self) -> None:
        """Eliminate the tied DOFs: the column of each tied ``(node, dof)`` is replaced by the row of
        ``T`` of the DOF it equals, ``T <- T + T[:, j] (T[other] - e_j)``, and dropped (the order does
        not matter; a tie that comes back to itself is a cycle)."""
        T = self.T.tocsc()
        for (node, dof), other in self.ties.items():
            j = self._index.get((node, dof))
            if j is None:
                raise ValueError(f"tie of {node}.{dof} to node {other!r}: {node}.{dof} is not a free DOF "
                                 "(supported, a slave's or already tied)")
            row = T[self.full_index(other, dof)]
            if row[0, j] != 0.0:
                raise ValueError(f"tie of {node}.{dof} to node {other!r}: the ties form a cycle through {node}.{dof}")
            unit = sp.csr_matrix(([1.0], ([0], [j])), shape=row.shape)
            T = (T + T[:, j] @ (row - unit)).tocsc()
        keep = [k for k, key in enumerate(self.free) if key not in self.ties]
        T = T[:, keep].tocsr()
        T.eliminate_zeros()
        self.T = T
        self._free_rows = self._free_rows[keep]
        self.free = [self.free[k] for k in keep]
        self._index = dict(zip(self.free, range(len(self.free))))

    def _known(self, node) -> bool:
        """Whether ``node`` is a node of the map (False for an unhashable ``node``)."""
        try:
            return node in self._position
        except TypeError:
            return False

    @property
    def n(self) -> int:
        """Number of free DOFs."""
        return len(self.free)

    @property
    def names(self) -> list[str]:
        """DOF names ``"node.dof"``, e.g. ``"3.uy"``."""
        prefix = {node: f"{node}." for node in self.nodes}
        return [prefix[node] + dof for node, dof in self.free]

    def full_index(self, node: Hashable, dof: str) -> int:
        """Row of nodal DOF ``dof`` of ``node`` in ``u_full``."""
        names = self.dof_names
        if dof not in names:
            raise ValueError(f"dof={dof!r} is not valid; use {', '.join(map(repr, names[:-1]))} or {names[-1]!r}")
        if node not in self._position:
            raise ValueError(f"node {node!r} is not defined (nodes: {node_list(self.nodes)})")
        return len(names) * self._position[node] + names.index(dof)

    def index(self, node: Hashable, dof: str) -> int:
        """Position of the free DOF ``(node, dof)`` in ``u``; ``ValueError`` if it is not free."""
        self.full_index(node, dof)
        if (node, dof) in self._index:
            return self._index[(node, dof)]
        if (node, dof) in getattr(self, "ties", {}):
            reason = f"it is tied to the {dof} of node {self.ties[(node, dof)]!r}"
        elif node in self.masters:
            reason = f"node {node!r} is rigidly linked to node {self.masters[node]!r} (a slave node)"
        elif (node, dof) in self._restrained:
            reason = f"{dof} of node {node!r} is supported"
        else:
            reason = f"node {node!r} has no {dof} DOF: no element rotates it"
        raise ValueError(f"{node}.{dof} is not a free DOF: {reason}; "
                         "use nodal() for the displacements of every node")

    def nodal(self, u) -> np.ndarray:
        """Displacements of every node (supported and slave nodes included).

        Parameters
        ----------
        u : (..., n) free DOFs

        Returns
        -------
        (..., n_nodes, len(dof_names)) array of the :attr:`dof_names` per node (``(ux, uy, rz)`` in
        2-D, ``(ux, uy, uz, rx, ry, rz)`` in 3-D), in the order of ``nodes``
        """
        u = np.asarray(u, dtype=float)
        if u.shape[-1:] != (self.n,):
            raise ValueError(f"u must have shape (..., {self.n}), got {u.shape}")
        flat = u.reshape(-1, self.n)
        full = (self.T @ flat.T).T
        return full.reshape(u.shape[:-1] + (len(self.nodes), len(self.dof_names)))

    def gather(self, f_full) -> np.ndarray:
        """Free-DOF load ``T^T f_full`` (n,) of nodal loads ``f_full`` (``len(dof_names) n_nodes``,)."""
        return np.asarray(self.T.T @ f_full).ravel()


def csr_of_entries(vals, rows, cols, shape) -> sp.csr_matrix:
    """``sp.csr_matrix((vals, (rows, cols)), shape=shape)``, made without the COO route when no
    ``(row, col)`` repeats: the same canonical arrays (rows in order, sorted columns, explicit zeros
    kept), without the overhead of scipy's conversions (tens of microseconds on a small matrix)."""
    rows, cols = np.asarray(rows), np.asarray(cols)
    vals = np.asarray(vals)
    if (rows.ndim != 1 or rows.shape != cols.shape or rows.shape != vals.shape or vals.dtype != np.float64
            or rows.dtype.kind not in "iu" or cols.dtype.kind not in "iu" or len(shape) != 2):
        return sp.csr_matrix((vals, (rows, cols)), shape=shape)
    if rows.size and (min(rows.min(), cols.min()) < 0 or rows.max() >= shape[0] or cols.max() >= shape[1]):
        return sp.csr_matrix((vals, (rows, cols)), shape=shape)    # (its message)
    order = np.lexsort((cols, rows))
    r, c = rows[order], cols[order]
    if r.size > 1 and np.any((r[1:] == r[:-1]) & (c[1:] == c[:-1])):
        return sp.csr_matrix((vals, (rows, cols)), shape=shape)    # repeated entries: summed there
    indptr = np.zeros(shape[0] + 1, dtype=np.intp)
    np.cumsum(np.bincount(r, minlength=shape[0]), out=indptr[1:])
    return sp.csr_matrix((vals[order], c, indptr), shape=shape)


def node_list(nodes, limit=10) -> str:
    """``"1, 2, 3"`` (truncated with ``...`` beyond ``limit`` nodes) for error messages."""
    shown = ", ".join(repr(node) if isinstance(node, str) else str(node) for node in list(nodes)[:limit])
    return shown + (", ..." if len(nodes) > limit else "") if nodes else "none"


def _root(node, links):
    """End of the chain of rigid links starting at ``node`` (chains are checked acyclic)."""
    while node in links:
        node = links[node]
    return node
