"""P-Delta of a pushover: the geometric stiffness of the gravity's axial forces, consistent or string.

The gravity load ``q_g`` of the pushover is solved on the structure held bilateral (contacts closed,
no yield; :meth:`Structure.static_axial_forces`), and the axial forces ``N`` (tension positive) of
its beams and bars give a constant geometric stiffness ``K_G`` added to ``K``:

* ``"consistent"``: the matrix of the cubic deflection of each beam between its nodes,
  ``N/(30 L) [[36, 3L, -36, 3L], [3L, 4L^2, -3L, -L^2], ...]`` on ``(v_i, rz_i, v_j, rz_j)``
  (:meth:`Structure.geometric_stiffness`, the form of ``Frame2D.p_delta``). It acts on the nodes'
  rotations, not on a hinge's plastic rotation inside the element: a column that sways as a rigid
  bar about a plastic hinge at its base is seen as the nodal cubic ``(0, 0, d, d/h)`` and stiffened
  by ``34/30`` of the string value ``N/h``, and its rotational terms bend the column at the joints;
* ``"string"``: the chord rotation only, ``N/L [[1, -1], [-1, 1]]`` on the transverse
  displacements ``(v_i, v_j)`` of every beam and bar (the "P-Delta" transformation of frame
  programs, a leaning column): a sway mechanism then softens by ``sum N / h`` exactly.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from ..structure.elements import chord

#: The forms of the geometric stiffness a pushover may add.
P_DELTA_FORMS = ("consistent", "string")


def with_p_delta(structure, form, q_gravity):
    """``structure`` with the geometric stiffness ``form`` of the axial forces of ``q_gravity``.

    Parameters
    ----------
    structure : Structure (a plane frame)
    form : ``False`` (none: any P-Delta of the structure removed), ``"consistent"`` or ``"string"``
    q_gravity : (n,) the gravity load of the pushover (force)

    Returns
    -------
    Structure, whose ``geometric`` and ``axial_forces`` are those of ``form`` (``to_model`` adds
    ``geometric`` to ``K`` and refuses an indefinite ``K``)

    Raises
    ------
    ValueError
        An unknown form, a 3-D frame, or a form without gravity (no axial forces).
    """
    if form is False:
        return replace(structure, geometric=None, axial_forces=None)
    if form not in P_DELTA_FORMS:
        raise ValueError(f"p_delta={form!r} is not valid; use None (the structure as built), False (none), "
                         "'consistent' or 'string'")
    if len(structure.dofs.dof_names) != 3:
        raise ValueError(f"p_delta={form!r}: P-Delta is for plane frames (Frame2D) only, not yet for 3-D frames")
    if not np.any(q_gravity):
        raise ValueError(f"p_delta={form!r} needs the gravity's axial forces: give gravity (g or a load vector)")
    axial = structure.static_axial_forces(q_gravity)
    K_G = structure.geometric_stiffness(axial) if form == "consistent" else string_stiffness(structure, axial)
    return replace(structure, geometric=K_G, axial_forces=axial)


def string_stiffness(structure, axial) -> sp.csr_matrix:
    """The string geometric stiffness ``K_G`` (n, n): ``N/L [[1, -1], [-1, 1]]`` on the transverse
    displacements ``v = -s ux + c uy`` of the ends of every beam and bar in ``axial``
    ``{name: N}`` (tension positive; ``(c, s)`` the chord)."""
    full = structure.dofs.T.shape[0]
    rows, cols, vals = [], [], []
    for e in structure.elements:
        if e.name not in axial or e.kind not in ("beam", "bar"):
            continue
        i, j = e.dofs[0][0], e.dofs[-1][0]
        L, (c, s) = chord(e.name, i, structure.coords[i], j, structure.coords[j])
        at = [structure.dofs.full_index(node, dof) for node in (i, j) for dof in ("ux", "uy")]
        T = np.array([[-s, c, 0.0, 0.0], [0.0, 0.0, -s, c]])
        ke = T.T @ (float(axial[e.name]) / L * np.array([[1.0, -1.0], [-1.0, 1.0]])) @ T
        rows.append(np.repeat(at, 4))
        cols.append(np.tile(at, 4))
        vals.append(ke.ravel())
    if rows:
        K = sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(full, full))
    else:
        K = sp.coo_matrix((full, full))
    return (structure.dofs.T.T @ K.tocsr() @ structure.dofs.T).tocsr()
