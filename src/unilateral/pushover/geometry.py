"""P-Delta of a pushover: the geometric stiffness of the gravity's axial forces, consistent or string.

The gravity load ``q_g`` of the pushover is solved on the structure held bilateral (contacts closed,
no yield; :meth:`Structure.static_axial_forces`), and the axial forces ``N`` (tension positive) of
its beams and bars give a constant geometric stiffness ``K_G`` added to ``K``:

* ``"consistent"``: the matrix of the cubic deflection of each beam between its nodes,
  ``N/(30 L) [[36, 3L, -36, 3L], [3L, 4L^2, -3L, -L^2], ...]`` on ``(v_i, rz_i, v_j, rz_j)`` (in 3-D:
  in both bending planes; :meth:`Structure.geometric_stiffness`, the form of ``Frame2D.p_delta`` and
  ``Frame3D.p_delta``). It acts on the nodes'
  rotations, not on a hinge's plastic rotation inside the element: a column that sways as a rigid
  bar about a plastic hinge at its base is seen as the nodal cubic ``(0, 0, d, d/h)`` and stiffened
  by ``34/30`` of the string value ``N/h``, and its rotational terms bend the column at the joints;
* ``"string"``: the chord rotation only, ``N/L [[1, -1], [-1, 1]]`` on the transverse
  displacements ``(v_i, v_j)`` (in 3-D: both transverse directions) of every beam and bar (the
  "P-Delta" transformation of frame programs, a leaning column;
  :func:`unilateral.structure.geometric.string`): a sway mechanism then softens by ``sum N / h`` exactly.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..structure.geometric import string
from .control import static_model_of

#: The forms of the geometric stiffness a pushover may add.
P_DELTA_FORMS = ("consistent", "string")


def with_p_delta(structure, form, q_gravity):
    """``structure`` with the geometric stiffness ``form`` of the axial forces of ``q_gravity``.

    Parameters
    ----------
    structure : Structure (a plane or a space frame)
    form : ``False`` (none: any P-Delta of the structure removed), ``"consistent"`` or ``"string"``
    q_gravity : (n,) the gravity load of the pushover (force)

    Returns
    -------
    Structure, whose ``geometric`` and ``axial_forces`` are those of ``form`` (``to_model`` adds
    ``geometric`` to ``K`` and refuses an indefinite ``K``)

    Raises
    ------
    ValueError
        An unknown form, or a form without gravity (no axial forces).
    """
    if form is False:
        return replace(structure, geometric=None, axial_forces=None)
    if form not in P_DELTA_FORMS:
        raise ValueError(f"p_delta={form!r} is not valid; use None (the structure as built), False (none), "
                         "'consistent' or 'string'")
    if not np.any(q_gravity):
        raise ValueError(f"p_delta={form!r} needs the gravity's axial forces: give gravity (g or a load vector)")
    K = None
    if structure.foundation is not None:            # footings: the static state on the soil's static springs
        K = static_model_of(replace(structure, geometric=None, axial_forces=None)).K
    axial = structure.static_axial_forces(q_gravity, K)
    K_G = structure.geometric_stiffness(axial) if form == "consistent" else string(structure, axial)
    return replace(structure, geometric=K_G, axial_forces=axial)
