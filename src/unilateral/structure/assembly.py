"""The sparse assembly of the natural form from the elements: the compatibility ``G``, the
block-diagonal ``E``, the interactions ``A``, the lumped mass ``M``, the strain names, and the
check that every free DOF has stiffness.

The matrices are gathered per group of elements of one shape (one array operation per group), or
by a loop in Python for a few elements (:data:`SMALL_ASSEMBLY`).
"""

from __future__ import annotations

import operator
from itertools import chain

import numpy as np
import scipy.sparse as sp

from . import elements as el
from .dofs import DofMap


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

    Without rigid links and ties ``T`` picks the free rows of ``u_full`` (one 1 per column, at most one per
    row): ``M`` is then the diagonal of the masses of the free DOFs, the zero ones not stored (as
    the product stores no zero), made directly; with links, the product."""
    if type(dofs) is DofMap and not dofs.masters and not dofs.ties and nodal_mass.dtype == np.float64:
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
