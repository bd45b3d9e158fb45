"""P-Delta: the geometric stiffness ``K_G`` of the axial forces ``N`` of beams and bars, 2-D and 3-D.

A beam or bar ``i -> j`` of length ``L`` and unit chord ``x'`` carrying the axial force ``N``
(tension positive; a compression lowers the stiffness) adds, in the global nodal DOFs:

* a bar (or, in :func:`string`, any beam or bar): the string stiffness ``N/L [[P, -P], [-P, P]]`` on
  the end translations, ``P = I - x' x'^T`` (the translations across the chord; in 2-D
  ``P = n n^T``, ``n = (-s, c)``);
* a beam, in :func:`consistent`: the consistent matrix of the cubic deflection in each bending
  plane, ``k = N/(30 L) [[36, 3L, -36, 3L], [3L, 4L^2, -3L, -L^2], [-36, -3L, 36, -3L],
  [3L, -L^2, -3L, 4L^2]]`` on the transverse displacement and the slope ``(w_i, w'_i, w_j, w'_j)``.
  A 2-D beam has one plane: ``w = n . u``, ``w' = rz``. A 3-D beam (local axes ``x', y', z'``,
  :func:`~unilateral.structure.elements3d.local_axes`) has two: ``w = y' . u`` with
  ``w' = z' . theta`` (bending about ``z'``) and ``w = z' . u`` with ``w' = -y' . theta`` (about
  ``y'``), ``theta`` the rotation vector. The torsional term ``N I_p/(A L) [[1, -1], [-1, 1]]`` on
  the twist (``I_p`` the polar moment about the shear centre) is left out: ``I_p`` is not among a
  beam's properties, and the term only matters for torsional (flexural-torsional) buckling.

The element matrices are assembled on the full DOFs and reduced by the DOF map's ``T`` (supports,
rigid links and diaphragms): ``K_G = T^T K_G,full T``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from .assembly import _coo

#: The element kinds that carry an axial force into ``K_G``.
AXIAL_KINDS = ("beam", "beam3d", "bar")
#: The nodal DOFs of a 2-D beam's bending plane, per end.
PLANE_DOFS = ("ux", "uy", "rz")
TRANSLATIONS = ("ux", "uy", "uz")


def consistent(structure, axial) -> sp.csr_matrix:
    """The consistent ``K_G`` (n, n) of ``axial`` ``{beam or bar name: N}``: beams' cubic, bars' string."""
    return _assemble(structure, axial, string_only=False)


def string(structure, axial) -> sp.csr_matrix:
    """The string ``K_G`` (n, n) of ``axial`` ``{beam or bar name: N}``: ``N/L`` across every chord
    (the chord rotation only: the "P-Delta" transformation of frame programs, a leaning column)."""
    return _assemble(structure, axial, string_only=True)


def with_gravity(structure, load, K=None):
    """``structure`` with the consistent P-Delta of the static ``load`` (n,) (its gravity): ``axial_forces``
    of :meth:`~unilateral.structure.Structure.static_axial_forces` (solved with ``K`` (n, n) if given:
    a frame on footings, with the soil's static springs) and their ``geometric`` stiffness."""
    axial = structure.static_axial_forces(load, K)
    return replace(structure, geometric=structure.geometric_stiffness(axial), axial_forces=axial)


def bending(N, L) -> np.ndarray:
    """The consistent (4, 4) matrix ``k`` of a bending plane on ``(w_i, w'_i, w_j, w'_j)``."""
    return N / (30.0 * L) * np.array([[36.0, 3 * L, -36.0, 3 * L], [3 * L, 4 * L * L, -3 * L, -L * L],
                                      [-36.0, -3 * L, 36.0, -3 * L], [3 * L, -L * L, -3 * L, 4 * L * L]])


def _plane(t, r) -> np.ndarray:
    """(4, 2 (d + k)) map from an element's ``(u_i, theta_i, u_j, theta_j)`` to ``(w_i, w'_i, w_j, w'_j)``,
    ``w = t . u`` and ``w' = r . theta`` (``t`` (d,), ``r`` (k,))."""
    d, k = len(t), len(r)
    T = np.zeros((4, 2 * (d + k)))
    T[0, :d], T[1, d:d + k], T[2, d + k:2 * d + k], T[3, 2 * d + k:] = t, r, t, r
    return T


def _element(structure, e, N, string_only) -> tuple:
    """``(dofs, ke)``: the (node, dof) names and the geometric matrix of one beam or bar."""
    i, j = e.dofs[0][0], e.dofs[-1][0]
    chord = np.asarray(structure.coords[j], dtype=float) - np.asarray(structure.coords[i], dtype=float)
    L = float(np.linalg.norm(chord))
    x = chord / L
    if string_only or e.kind == "bar":
        P = np.eye(x.size) - np.outer(x, x)
        return ([(node, dof) for node in (i, j) for dof in TRANSLATIONS[:x.size]],
                N / L * np.kron(np.array([[1.0, -1.0], [-1.0, 1.0]]), P))
    k = bending(N, L)
    if e.kind == "beam":
        T = _plane((-x[1], x[0]), (1.0,))
        return [(node, dof) for node in (i, j) for dof in PLANE_DOFS], T.T @ k @ T
    y, z = e.a[4, 3:6], e.a[2, 3:6]                 # the local axes, from the strains roty_i and rotz_i
    about_z, about_y = _plane(y, z), _plane(z, -y)
    return list(e.dofs), about_z.T @ k @ about_z + about_y.T @ k @ about_y


def _assemble(structure, axial, *, string_only) -> sp.csr_matrix:
    """``T^T K_G T`` of the beams and bars named in ``axial``."""
    dofs = structure.dofs
    full = dofs.T.shape[0]
    rows, cols, vals = [], [], []
    for e in structure.elements:
        if e.name not in axial or e.kind not in AXIAL_KINDS:
            continue
        names, ke = _element(structure, e, float(axial[e.name]), string_only)
        at = np.array([dofs.full_index(node, dof) for node, dof in names])
        rows.append(np.repeat(at, len(at)))
        cols.append(np.tile(at, len(at)))
        vals.append(ke.ravel())
    return (dofs.T.T @ _coo(rows, cols, vals, (full, full)) @ dofs.T).tocsr()
