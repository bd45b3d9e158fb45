"""The deformations and forces of every ``zeroLength`` and truss material at once, vectorised over
the materials and over a block of states (the steps of one ``analyze``).

The values are those of :func:`.queries.material_forces`, bit for bit: the same floating-point
operations in the same order, applied to arrays. A material's deformation ``e = d . (U_j - U_i)``
is the picked component for a unit direction ``d`` (a ``zeroLength``; exact) and ``np.matmul`` of
the stacked rows otherwise (a truss's chord; the dot product of ``numpy.dot``); its force is
:meth:`~.materials.Material.force` called once per material with arrays, plus its Rayleigh
dashpot ``damp E edot``.
"""

from __future__ import annotations

import numpy as np

from .materials import Material

__all__ = ["SpringTable", "spring_table", "nodal_block", "stress_block"]


def spring_table(b, domain) -> SpringTable:
    """The :class:`SpringTable` of the built model ``b`` (made once per built model)."""
    table = getattr(b, "_spring_table", None)
    if table is None:
        table = SpringTable(b, domain)
        b._spring_table = table
    return table


def nodal_block(b, X) -> np.ndarray:
    """The nodal values (S, 3 nodes) of the reduced states ``X`` (S, n): ``P x`` of each row."""
    return np.asarray(b.P @ np.asarray(X, dtype=float).T).T


def stress_block(b, U, V) -> np.ndarray:
    """The stresses (S, len(rows)) at the strains ``rows`` the springs read, of the reduced ``u``
    (S, n) and ``v`` (S, m): :meth:`~.build.Built.stresses` of each row."""
    rows, S_u, S_v, s0, _ = b.stress
    if not rows.size:
        return np.zeros((len(U), 0))
    return (np.asarray(S_u @ np.asarray(U).T) - np.asarray(S_v @ np.asarray(V).T)).T - s0


class SpringTable:
    """The materials of the springs of one built model, flattened into columns.

    Attributes
    ----------
    columns : dict tag -> slice, the columns of the element's materials (in ``b.springs`` order)
    elements : dict tag -> int, the element's index in the global forces of :meth:`global_forces`
    ndf : int, DOFs per node
    lookup : dict, the responses the queries asked, by ``(tag, name)`` (filled by :mod:`.queries`)
    """

    def __init__(self, b, domain):
        nf = self.ndf = b.ndf
        self.columns, self.elements, self.lookup = {}, {}, {}
        ri, rj, dirs, layer, owner, materials = [], [], [], [], [], []
        for tag, table in b.springs.items():
            e = domain.elements[tag]
            start = len(ri)
            self.elements[tag] = len(self.elements)
            for k, (material, direction, reads, damp) in enumerate(table):
                ri.append(b.row[e.i])
                rj.append(b.row[e.j])
                dirs.append(np.asarray(direction, dtype=float))
                layer.append(k)
                owner.append(self.elements[tag])
                materials.append((material, reads, damp))
            self.columns[tag] = slice(start, len(ri))
        self.n = len(ri)
        self.ri, self.rj = np.array(ri, dtype=np.int64), np.array(rj, dtype=np.int64)
        self.dirs = np.array(dirs).reshape(self.n, nf)
        unit = (np.count_nonzero(self.dirs, axis=1) == 1) & (self.dirs.max(axis=1, initial=0.0) == 1.0)
        self.unit = _index(np.flatnonzero(unit))
        comp = np.argmax(self.dirs[unit], axis=1)
        self.gather_i, self.gather_j = self.ri[unit] + comp, self.rj[unit] + comp
        self.other = np.flatnonzero(~unit)
        self.batches = _batches(materials, b.stress[0])
        layer, owner = np.array(layer, dtype=np.int64), np.array(owner, dtype=np.int64)
        self.layers = [(_index(np.flatnonzero(layer == k)), _index(owner[layer == k])) for k in range(layer.max(initial=-1) + 1)]

    def deformations(self, U) -> np.ndarray:
        """``e = d . (U_j - U_i)`` (S, columns) of the nodal values ``U`` (S, 3 nodes)."""
        out = np.empty((U.shape[0], self.n))
        if self.gather_i.size:                           # unit directions: the component (exact)
            out[:, self.unit] = U[:, self.gather_j] - U[:, self.gather_i]
        if self.other.size:
            span = np.arange(self.ndf)
            diff = U[:, self.rj[self.other, None] + span] - U[:, self.ri[self.other, None] + span]
            out[:, self.other] = np.matmul(diff[:, :, None, :], self.dirs[self.other][None, :, :, None])[:, :, 0, 0]
        return out

    def forces(self, e, edot, sigma) -> np.ndarray:
        """The material forces (S, columns), tension positive, of the deformations ``e``, their rates
        ``edot`` (S, columns) and the stresses ``sigma`` (S, rows) of :func:`stress_block`."""
        out = np.empty_like(e)
        for kind, cols, material, strains, signs, dE, E, eta in self.batches:
            dv = edot[:, cols]
            if kind == "read":                           # Material.force: its one stress
                out[:, cols] = signs[0] * sigma[:, strains[0]] + dE * dv
            elif kind == "elastic":                      # Material.force: E e + eta edot
                out[:, cols] = (E * e[:, cols] + eta * dv) + dE * dv
            else:
                read = [signs[r] * sigma[:, strains[r]] for r in range(strains.shape[0])]
                out[:, cols] = material.force(e[:, cols], dv, read) + dE * dv
        return out

    def global_forces(self, f) -> np.ndarray:
        """The global end forces (S, elements, 2 ndf) of the material forces ``f`` (S, columns):
        ``-f d`` at ``i`` and ``+f d`` at ``j``, summed over each element's materials in order."""
        nf = self.ndf
        out = np.zeros((f.shape[0], len(self.elements), 2 * nf))
        for cols, owners in self.layers:
            push = f[:, cols, None] * self.dirs[cols]
            out[:, owners, :nf] = out[:, owners, :nf] - push
            out[:, owners, nf:] = out[:, owners, nf:] + push
        return out

    def state(self, U, Ud, sigma) -> dict:
        """``{"e", "f", "force"}`` of a block: deformations, forces (S, columns), and the global
        forces (S, elements, 2 ndf) computed lazily on first use of the item ``"force"``."""
        e = self.deformations(U)
        f = self.forces(e, self.deformations(Ud), sigma)
        return _Lazy(e, f, self)


def _index(k):
    """The indices ``k`` as a slice if they are a contiguous range (a view, no copy), else as they are."""
    if k.size and np.array_equal(k, np.arange(k[0], k[0] + k.size)):
        return slice(int(k[0]), int(k[0]) + k.size)
    return k


def _batches(materials, stress_rows) -> list:
    """The columns of ``materials`` (``(material, reads, damp)`` per column) in batches computed
    together: ``(kind, columns, material, strains (reads, c), signs (reads, c), damp E (c,), E (c,),
    eta (c,))``. ``"read"``: the elementary laws whose force is their one stress, ``"elastic"``: the
    ``Elastic`` springs (``E e + eta edot``), ``"law"``: one per composite law (its ``force``)."""
    groups = {}
    for c, (material, reads, damp) in enumerate(materials):
        if type(material).force is not Material.force or material.parts:
            key = ("law", repr(material))
        else:
            key = ("elastic" if material.kind == "Elastic" else "read", len(reads))
        group = groups.setdefault(key, (material, [], [], [], [], [], []))
        for store, value in zip(group[1:], (c, [strain for strain, _ in reads], [float(sign) for _, sign in reads],
                                            damp * material.E, material.E, material.eta)):
            store.append(value)
    out = []
    for (kind, _), (material, cols, strains, signs, dE, E, eta) in groups.items():
        reads = len(strains[0])
        out.append((kind, _index(np.array(cols, dtype=np.int64)), material,
                    np.searchsorted(stress_rows, np.array(strains, dtype=np.int64).reshape(len(cols), reads).T),
                    np.array(signs, dtype=float).reshape(len(cols), reads).T, np.array(dE), np.array(E),
                    np.array(eta)))
    return out


class _Lazy(dict):
    """``{"e", "f"}`` and ``"force"`` made on first access."""

    def __init__(self, e, f, table):
        super().__init__(e=e, f=f)
        self.table = table

    def __missing__(self, key):
        if key != "force":
            raise KeyError(key)
        self["force"] = value = self.table.global_forces(self["f"])
        return value
