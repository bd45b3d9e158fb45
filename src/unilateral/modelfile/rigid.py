"""``[[contacts]]`` and ``[[rigid_blocks]]`` of a model file: rigid contacts (no compliance) and
rigid rocking blocks (:mod:`unilateral.structure.rigid`, ``docs/rocking.md``).

The tables are made by :func:`rigid_tables` from the value types of
:mod:`unilateral.modelfile.schema` (which calls it; this module imports no other module of the
package), and built by :func:`add_rigid`. Run them with ``method = "moreau-jean"`` (Newton's
impact law) and ``rule = "trapezoidal"`` or ``"bdf1"``.
"""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field


def rigid_tables(Table, NodeRef, Direction, Name, Positive, NonNegative):
    """The pydantic tables ``(Contact, RigidBlock)`` of ``[[contacts]]`` and ``[[rigid_blocks]]``,
    built on the schema's base ``Table`` and value types."""

    class Contact(Table):
        """[[contacts]]: a rigid unilateral contact of a node with the fixed ground (no compliance)."""

        EXAMPLE: ClassVar[str] = '[[contacts]] name = "stop", node = 1, direction = "uy", gap = 0.01'
        name: Name
        node: NodeRef
        direction: Direction = Field("uy", description="The normal, from the ground to the node: the "
                                     "direction in which the node separates.")
        gap: NonNegative = Field(0.0, description="Opening at u = 0 [length].")
        restitution: float = Field(0.0, ge=0.0, le=1.0, description=(
            "Newton's coefficient of restitution e (method = \"moreau-jean\"): 0 perfectly plastic, 1 elastic."))
        mu: NonNegative | None = Field(None, description=(
            "Coulomb friction along the tangent (the normal turned by -90 degrees); method = \"moreau-jean\" only."))

    class RigidBlock(Table):
        """[[rigid_blocks]]: a rigid rectangular block rocking on its two base corners (Housner)."""

        EXAMPLE: ClassVar[str] = '[[rigid_blocks]] name = "B", node = "c", width = 0.4, height = 1.2, mass = 1.0'
        name: Name
        node: NodeRef = Field(description="The centre of mass (a node of [[nodes]], free: no support).")
        width: Positive = Field(description="Width 2b [length].")
        height: Positive = Field(description="Height 2h [length].")
        mass: Positive = Field(description="Mass [mass].")
        J: NonNegative | None = Field(None, description=(
            "Rotary inertia about the centre [mass length^2]; none: the uniform rectangle's m (b^2 + h^2) / 3."))
        restitution: float = Field(0.0, ge=0.0, le=1.0, description=(
            "Newton's e of the corners (0: Housner's impact, the angular momentum about the new corner kept)."))
        mu: NonNegative | None = Field(None, description=(
            "None: the base does not slide (held); a number: Coulomb friction at the corners, the base free "
            "(it slides where mu < b/h and the base acceleration exceeds mu g; method = \"moreau-jean\" only)."))

    return Contact, RigidBlock


def add_rigid(fr, document, to_mass, each, g=None) -> None:
    """Add the ``[[contacts]]`` and ``[[rigid_blocks]]`` of ``document`` to the frame ``fr``.

    ``each(document, section, action)`` calls ``action(table)`` with the table's key path as the
    context of its errors; ``g`` the gravity of ``[loads.gravity]`` in the model's units (the
    blocks' second-order term; None: no gravity, no term). A 3-D frame is refused.
    """
    if not (document.contacts or document.rigid_blocks):
        return
    if not hasattr(fr, "rigid_block"):
        section = "contacts" if document.contacts else "rigid_blocks"
        each(document, section, lambda table: _refuse_3d(section))
    each(document, "contacts", lambda c: fr.contact(c.name, c.node, direction=c.direction, gap=c.gap,
                                                    restitution=c.restitution, mu=c.mu))
    each(document, "rigid_blocks", lambda b: fr.rigid_block(
        b.name, b.node, width=b.width, height=b.height, mass=b.mass * to_mass,
        J=None if b.J is None else b.J * to_mass, restitution=b.restitution, mu=b.mu, g=0.0 if g is None else g))


def _refuse_3d(section):
    raise ValueError(f"[[{section}]] are not available in a 3-D frame (rigid contacts and blocks are 2-D: Frame2D)")


def ground_inertia(structure, direction):
    """The influence ``-T^T M_full r_full`` (n,) of a unit ground acceleration along ``direction`` for a
    frame with rigid contacts (every node's inertia, a block's centre included: a slave of its base,
    whose ``ux`` is held), or None for a frame without them (the caller's ``-M r``)."""
    if getattr(structure, "rigid", None) is None:
        return None
    if direction not in ("ux", "uy"):
        raise ValueError(f"direction={direction!r}: a ground motion of a frame with rigid contacts acts along "
                         "'ux' or 'uy'")
    return -structure.gravity(1.0, (1.0, 0.0) if direction == "ux" else (0.0, 1.0))
