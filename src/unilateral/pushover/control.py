"""The control DOF of a pushover and the structure it is given for.

The control displacement is ``u_c = e . u`` with ``e`` (n,) a row of ``u_full = T u`` (a free DOF,
or a slave node's DOF that follows its master). On a bare :class:`~unilateral.Model`, ``node`` and
``dof`` together name a DOF (``"3.ux"`` of ``model.dof_names``), or else ``node`` is the index of a
DOF or its full name.
"""

from __future__ import annotations

import numbers

import numpy as np

from ..model import Model

#: The DOFs of a node of a plane frame (a 3-D frame: ``ux, uy, uz, rx, ry, rz``).
PLANE_DOFS = ("ux", "uy", "rz")


def as_structure_and_model(target):
    """``(structure or None, model)`` of a ``Frame2D`` or ``Frame3D`` (built here), a ``Structure`` (2-D
    or 3-D) or a ``Model``.

    Raises
    ------
    TypeError
        Anything else.
    ValueError
        A law this pushover does not follow. Footings on a soil medium are carried by the soil's
        static springs (:meth:`~unilateral.soil.FoundationModel.static_model`: the openings of the
        patches are the unknowns).
    """
    structure = target
    if not isinstance(target, Model) and hasattr(target, "build") and not hasattr(target, "to_model"):
        structure = target.build()                      # a Frame2D builder
    if isinstance(structure, Model):
        structure, model = None, structure
    elif hasattr(structure, "to_model") and hasattr(structure, "dofs"):
        model = static_model_of(structure)
    else:
        raise TypeError(f"structure_or_model must be a Frame2D, a Structure or a unilateral.Model, got "
                        f"{type(target).__name__}")
    law = model.law
    if law.Q is not None or law.free.any():
        raise ValueError("structure_or_model: free unknowns or an unknown map (a model whose law has them, such as "
                         "a FoundationModel's dynamic form) are not supported by the pushover; give the structure, "
                         "or the model's static_model()")
    return structure, model


def static_model_of(structure) -> Model:
    """The model of ``structure``'s static problem: its :meth:`to_model`, or with footings on a soil
    medium that model's :meth:`~unilateral.soil.FoundationModel.static_model` (the soil's static
    springs ``Phi(0)^-1``)."""
    model = structure.to_model()
    return model if getattr(structure, "foundation", None) is None else model.static_model()


def control_vector(structure, model, node, dof) -> tuple[np.ndarray, str]:
    """``(e (n,), label)``: the control vector and the name of the control DOF.

    Raises
    ------
    ValueError
        A node that is not in the structure, a DOF that is not valid or not free.
    """
    if structure is None:
        return _model_control(model, node, dof)
    names = tuple(structure.dofs.dof_names)
    if dof not in names:
        raise ValueError(f"dof={dof!r} is not valid; use one of {', '.join(map(repr, names))}")
    nodes = structure.dofs.nodes
    if node not in nodes:
        listed = ", ".join(map(repr, nodes[:12])) + (" ..." if len(nodes) > 12 else "")
        raise ValueError(f"node={node!r} is not a node of the structure (nodes: {listed})")
    row = structure.dofs.T[structure.dofs.full_index(node, dof)]
    e = np.asarray(row.toarray()).ravel()
    if not np.any(e):
        raise ValueError(f"node={node!r}, dof={dof!r}: that DOF cannot move (it is supported, or nothing rotates "
                         "it); choose a free DOF as the control DOF")
    return e, f"{node}.{dof}"


def _model_control(model, node, dof) -> tuple[np.ndarray, str]:
    """The control DOF of a bare model: an index, a name, or ``"node.dof"``."""
    names = list(model.dof_names)
    if f"{node}.{dof}" in names:
        k = names.index(f"{node}.{dof}")
    elif isinstance(node, numbers.Integral) and not isinstance(node, bool):
        if not 0 <= int(node) < model.n:
            raise ValueError(f"node={node!r} is not a DOF of the model: give an index 0..{model.n - 1} or a name "
                             f"of model.dof_names")
        k = int(node)
    elif str(node) in names:
        k = names.index(str(node))
    else:
        listed = ", ".join(map(repr, names[:12])) + (" ..." if len(names) > 12 else "")
        raise ValueError(f"node={node!r}, dof={dof!r} names no DOF of the model (DOFs: {listed}); give an index "
                         f"0..{model.n - 1} or a name of model.dof_names")
    e = np.zeros(model.n)
    e[k] = 1.0
    return e, names[k]
