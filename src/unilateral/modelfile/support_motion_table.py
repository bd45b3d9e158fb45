"""``[[loads.support_motion]]`` of a model file: a displacement history imposed on a supported DOF
(multiple-support excitation, :meth:`unilateral.structure.Frame2D.support_motion`).

The table is made by :func:`support_motion_table` from the value types of
:mod:`unilateral.modelfile.schema` (which calls it; this module imports no other module of the
package) and built by :func:`unilateral.modelfile.build` (``_support_motions``).
"""

from __future__ import annotations

from typing import ClassVar, Literal

from pydantic import Field


def support_motion_table(Table, NodeRef, TimeFunction):
    """The pydantic table ``SupportMotion`` of ``[[loads.support_motion]]``, built on the schema's
    base ``Table``, node reference and time-function tables."""

    class SupportMotion(Table):
        """[[loads.support_motion]]: the displacement history of a supported DOF (the response is the
        total motion; stiffness-proportional Rayleigh damping is refused with it)."""

        EXAMPLE: ClassVar[str] = ('[[loads.support_motion]] node = 1, dof = "ux", scale = 0.01, '
                                  'displacement = { type = "table", file = "base.csv" }')
        node: NodeRef = Field(description="A node of [[nodes]] with dof supported in [[supports]].")
        dof: Literal["ux", "uy", "uz", "rx", "ry", "rz"] = Field(description=(
            "The supported DOF that moves (ux, uy, rz in 2-D; ux .. rz in 3-D)."))
        displacement: TimeFunction = Field(description=(
            "The displacement history [length] (rotation [rad] for r*), times the scale: a time function, e.g. "
            '{ type = "table", file = "base.csv" } (times [time], displacements) or a pulse.'))
        scale: float = Field(1.0, description="Factor on the displacement history.")

    return SupportMotion
