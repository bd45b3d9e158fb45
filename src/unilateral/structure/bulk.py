"""Many nodes, beams, masses and soil contacts of a 2-D frame at once, from arrays.

:meth:`Frame2D.nodes <unilateral.structure.Frame2D.nodes>`, :meth:`~unilateral.structure.Frame2D.beams`,
:meth:`~unilateral.structure.Frame2D.masses` and :meth:`~unilateral.structure.Frame2D.soils` are the
loops of :meth:`~unilateral.structure.Frame2D.node`, :meth:`~unilateral.structure.Frame2D.beam`, ...
over the rows of arrays (a mesh, a pile, a beam on many springs): the same elements and matrices to
the last bit, without a Python call and a check per element (a beam of 10^4 elements is built in
milliseconds). Each call checks all its rows before it adds any: a call that fails leaves the frame
as it was, and its message names the argument, the row and the value.
"""

from __future__ import annotations

import numbers

import numpy as np

from . import elements as el
from .dofs import node_list


def ids(where, arg, values) -> list:
    """``values`` (a sequence or 1-D array of ints or strs) as a list of Python ints and strs."""
    array = np.asarray(values)
    if array.ndim != 1:
        raise ValueError(f"{where}: {arg} must be a 1-D sequence of ids, got shape {array.shape}")
    if array.dtype.kind in "iu":
        return array.tolist()
    out = list(values)
    for k, value in enumerate(out):
        if isinstance(value, numbers.Integral) and not isinstance(value, bool):
            out[k] = int(value)
        elif isinstance(value, str):
            out[k] = str(value)                         # (a numpy string: the plain str)
        else:
            raise TypeError(f"{where}: {arg}[{k}] = {value!r} must be an int or a str")
    return out


def reals(where, arg, values, size, bound=None) -> np.ndarray:
    """``values`` (a number, or one per row) as a float array ``(size,)``: finite and ``> 0``
    (``bound=">0"``) or ``>= 0`` (``">=0"``); the message names the first bad row."""
    x = np.asarray(values)
    if x.dtype.kind not in "iuf":
        raise TypeError(f"{where}: {arg} must be a real number or {size} of them, got {values!r}")
    x = x.astype(float, copy=False)
    if x.ndim > 1 or (x.ndim == 1 and x.size != size):
        raise ValueError(f"{where}: {arg} must be a number or {size} numbers (one per row), got shape {x.shape}")
    x = np.broadcast_to(x, (size,))
    ok = np.isfinite(x)
    if bound == ">0":
        ok &= x > 0
    elif bound == ">=0":
        ok &= x >= 0
    if not ok.all():
        k = int(np.argmin(ok))
        need = "finite" if not np.isfinite(x[k]) else "> 0" if bound == ">0" else ">= 0"
        raise ValueError(f"{where}: {arg}[{k}] = {float(x[k])!r} must be {need}")
    return x


def check_defined(where, arg, nodes, coords) -> None:
    """Raise naming the first of ``nodes`` that is not a node of ``coords``."""
    for k, node in enumerate(nodes):
        if node not in coords:
            raise ValueError(f"{where}: {arg}[{k}] = {node!r} is not defined (nodes: {node_list(list(coords))})")


def check_names(where, names, used, size) -> list:
    """``names`` as a list of ``size`` non-empty strs, distinct and not in ``used``."""
    names = list(names)
    if len(names) != size:
        raise ValueError(f"{where}: {len(names)} names for {size} rows; give one name per row")
    for k, name in enumerate(names):
        if not isinstance(name, str) or not name:
            raise TypeError(f"{where}: names[{k}] must be a non-empty str, got {name!r}")
        names[k] = str(name)                            # (a numpy string: the plain str)
    if len(set(names)) != size or not used.isdisjoint(names):
        seen = set()
        for k, name in enumerate(names):
            if name in used or name in seen:
                raise ValueError(f"{where}: names[{k}] = {name!r} is already used by another element")
            seen.add(name)
    return names


def add_nodes(frame, node_ids, x, y) -> None:
    """:meth:`Frame2D.nodes <unilateral.structure.Frame2D.nodes>`."""
    where = "nodes"
    node_ids = ids(where, "ids", node_ids)
    size = len(node_ids)
    xy = np.empty((size, 2))
    xy[:, 0], xy[:, 1] = reals(where, "x", x, size), reals(where, "y", y, size)
    coords = frame._coords
    if len(set(node_ids)) != size or not coords.keys().isdisjoint(node_ids):
        seen = set()
        for k, node in enumerate(node_ids):
            if node in coords or node in seen:
                raise ValueError(f"{where}: ids[{k}] = {node!r}: node {node!r} is already defined")
            seen.add(node)
    coords.update(zip(node_ids, xy))


def add_beams(frame, names, i, j, *, E, A, I, axial_strain=0.0, curvature=0.0) -> None:
    """:meth:`Frame2D.beams <unilateral.structure.Frame2D.beams>`."""
    where = "beams"
    i, j = ids(where, "i", i), ids(where, "j", j)
    size = len(i)
    if len(j) != size:
        raise ValueError(f"{where}: i has {size} nodes and j {len(j)}; give one of each per beam")
    names = check_names(where, names, frame._names, size)
    coords = frame._coords
    check_defined(where, "i", i, coords)
    check_defined(where, "j", j, coords)
    for k in range(size):
        if i[k] == j[k]:
            raise ValueError(f"{where}: i[{k}] and j[{k}] are the same node {i[k]!r} (beam {names[k]!r})")
    E, A, I = reals(where, "E", E, size, ">0"), reals(where, "A", A, size, ">0"), reals(where, "I", I, size, ">0")
    axial_strain = reals(where, "axial_strain", axial_strain, size)
    curvature = reals(where, "curvature", curvature, size)
    xi = np.array([coords[node] for node in i]).reshape(size, 2)
    xj = np.array([coords[node] for node in j]).reshape(size, 2)
    dx, dy = xj[:, 0] - xi[:, 0], xj[:, 1] - xi[:, 1]
    # hypot(x, 0) = |x| exactly: the lengths of elements.beam
    L = np.where(dy == 0.0, np.abs(dx), np.where(dx == 0.0, np.abs(dy), np.hypot(dx, dy)))
    if not L.all():
        k = int(np.argmin(L != 0.0))
        el._chord(("beam", names[k]), i[k], xi[k], j[k], xj[k])     # its message
    table = np.empty((size, 30))               # the 30 numbers of elements.beam, a row per beam
    numbers = el.beam_numbers(L, dx / L, dy / L, E, A, I, axial_strain=axial_strain, curvature=curvature)
    for column, value in enumerate(numbers):
        table[:, column] = value
    a = table[:, :18].reshape(size, 3, 6)
    stiffness = table[:, 18:27].reshape(size, 3, 3)
    theta = table[:, 27:]
    dofs = {node: ((node, "ux"), (node, "uy"), (node, "rz")) for node in {*i, *j}}
    make, beams, elements = el._element, frame._beams, frame._elements
    for p, name in enumerate(names):
        element = make(name, "beam", dofs[i[p]] + dofs[j[p]], a[p], stiffness[p], theta[p])
        beams[name] = element
        elements.append(element)
    frame._names.update(names)


def add_masses(frame, nodes, m, *, J=0.0) -> None:
    """:meth:`Frame2D.masses <unilateral.structure.Frame2D.masses>`."""
    where = "masses"
    nodes = ids(where, "nodes", nodes)
    size = len(nodes)
    check_defined(where, "nodes", nodes, frame._coords)
    rows = np.empty((size, 3))
    rows[:, 0] = rows[:, 1] = 0.0 + reals(where, "m", m, size, ">=0")
    rows[:, 2] = 0.0 + reals(where, "J", J, size, ">=0")
    mass = frame._mass
    for node, row in zip(nodes, rows):
        before = mass.get(node)
        mass[node] = row if before is None else before + row


def add_soils(frame, names, nodes, k, *, c=0.0, gap=0.0, capacity=0.0, direction="uy", bearing=None) -> None:
    """:meth:`Frame2D.soils <unilateral.structure.Frame2D.soils>`."""
    where = "soils"
    nodes = ids(where, "nodes", nodes)
    size = len(nodes)
    names = check_names(where, names, frame._names, size)
    check_defined(where, "nodes", nodes, frame._coords)
    terms = el.direction_terms(where, direction)
    k, c = reals(where, "k", k, size, ">0"), reals(where, "c", c, size, ">=0")
    theta = -reals(where, "gap", gap, size)
    capacity = reals(where, "capacity", capacity, size, ">=0").tolist()
    bearing = None if bearing is None else reals(where, "bearing", bearing, size, ">0").tolist()
    template, row = el._relative(None, 0, (terms,))             # the DOFs and the row of one element
    moved = [dof for _, dof in template]
    a = np.empty((size, 1, row.shape[1]))
    a[:] = row
    stiffness, theta = k.reshape(size, 1, 1).copy(), theta.reshape(size, 1)
    viscosity = c.reshape(size, 1, 1).copy()
    make, contact, settle, elements = el._element, el.contact_unknown, el.bearing_unknown, frame._elements
    for p, (name, node) in enumerate(zip(names, nodes)):
        unknowns = (contact(name, capacity[p]),)
        if bearing is not None:                                 # the plastic settlement beyond the capacity
            unknowns += (settle(name, bearing[p], float(k[p])),)
        elements.append(make(name, "soil", tuple((node, dof) for dof in moved), a[p], stiffness[p], theta[p],
                             E_v=viscosity[p] if c[p] > 0 else None, unknowns=unknowns, A=None))
    frame._names.update(names)
