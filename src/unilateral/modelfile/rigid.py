"""``[[contacts]]`` and ``[[rigid_blocks]]`` of a model file: rigid contacts (no compliance) and
rigid rocking blocks (:mod:`unilateral.structure.rigid`, ``docs/rocking.md``); in a 3-D frame rigid
boxes on four corners (``width``, ``width_y``: :mod:`unilateral.structure.rigid3d`).

The tables are made by :func:`rigid_tables` from the value types of
:mod:`unilateral.modelfile.schema` (which calls it), those of a 3-D frame by :func:`rigid_tables_3d`
(called by :mod:`unilateral.modelfile.schema3d`; this module imports no other module of the package
at its top), and built by :func:`add_rigid`. Run them with ``method = "moreau-jean"`` (Newton's
impact law) and ``rule = "trapezoidal"`` or ``"bdf1"``.
"""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field


def rigid_tables(Table, NodeRef, Direction, Name, Positive, NonNegative, *, NodeId=None):
    """The pydantic tables ``(Contact, RigidBlock)`` of ``[[contacts]]`` and ``[[rigid_blocks]]``,
    built on the schema's base ``Table`` and value types (``NodeId``: a node id that is not checked
    as a node reference, for a block's ``on``: a node or a block's name)."""
    NodeId = NodeRef if NodeId is None else NodeId

    class Contact(Table):
        """[[contacts]]: a rigid unilateral contact of a node with the fixed ground, or with another
        node (``on``; no compliance)."""

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
        on: NodeRef | None = Field(None, description=(
            "The node the contact bears on (the relative motion along the normal; internal, not a ground "
            "reaction); none: the fixed ground."))

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
        on: NodeId | None = Field(None, description=(
            "What the block stands on: none, the ground; a node of [[nodes]], a floor (the base centre at that "
            "node: node height/2 above it); the name of another [[rigid_blocks]] entry, its top face (a stack)."))

    return Contact, RigidBlock


_FACETS_3D = ("The facets of the friction polygon in the tangent plane (with mu; an even integer >= 4, default 8): "
              "it circumscribes Coulomb's circle |T| <= mu N, exact along its facet normals (x and y for a multiple "
              "of 4), sec(pi/facets) too strong along its vertices.")


def rigid_tables_3d(Table, Contact, NodeRef, Name, Direction3, Positive, NonNegative, *, NodeId=None):
    """The pydantic tables ``(Contact3D, RigidBox)`` of ``[[contacts]]`` and ``[[rigid_blocks]]`` of a
    3-D frame (``[frame] dimensions = 3``: :meth:`Frame3D.contact`, :meth:`Frame3D.rigid_box
    <unilateral.structure.Frame3D.rigid_box>`), built on the schema's ``Table``, the 2-D ``Contact`` and
    the value types (``Direction3`` of :mod:`unilateral.modelfile.schema3d`; ``NodeId`` as in
    :func:`rigid_tables`, for a box's ``on``)."""
    NodeId = NodeRef if NodeId is None else NodeId

    class Contact3D(Contact):
        """[[contacts]] of a 3-D frame: a rigid unilateral contact of a node with the fixed ground, or
        with another node (``on``)."""

        EXAMPLE: ClassVar[str] = '[[contacts]] name = "stop", node = 1, direction = "uz", gap = 0.01'
        direction: Direction3 = Field("uz", description="The normal, from the ground to the node: the "
                                      "direction in which the node separates.")
        mu: NonNegative | None = Field(None, description=(
            "Coulomb friction in the tangent plane (a polygonal cone of facets facets); method = \"moreau-jean\" only."))
        facets: int | None = Field(None, description=_FACETS_3D)
        on: NodeRef | None = Field(None, description=(
            "The node the contact bears on (the relative motion along the normal and, with mu, in the tangent "
            "plane; internal, not a ground reaction); none: the fixed ground."))

    class RigidBox(Table):
        """[[rigid_blocks]] of a 3-D frame: a rigid box rocking on its four base corners (Housner in
        both planes); its corners are the contacts "<name>.sw", ".se", ".ne", ".nw"."""

        EXAMPLE: ClassVar[str] = ('[[rigid_blocks]] name = "B", node = "c", width = 0.4, width_y = 0.6, '
                                  'height = 1.2, mass = 1.0')
        name: Name
        node: NodeRef = Field(description=(
            "The centre of mass (a node of [[nodes]], free: no support)."))
        width: Positive = Field(description="Plan dimension 2 bx along x [length].")
        width_y: Positive = Field(description="Plan dimension 2 by along y [length].")
        height: Positive = Field(description="Height 2h [length].")
        mass: Positive = Field(description="Mass [mass].")
        Jx: NonNegative | None = Field(None, description=(
            "Rotary inertia about x through the centre [mass length^2]; none: the solid box's m (by^2 + h^2) / 3."))
        Jy: NonNegative | None = Field(None, description=(
            "Rotary inertia about y through the centre [mass length^2]; none: the solid box's m (bx^2 + h^2) / 3."))
        Jz: NonNegative | None = Field(None, description=(
            "Rotary inertia about z through the centre [mass length^2]; none: the solid box's m (bx^2 + by^2) / 3."))
        restitution: float = Field(0.0, ge=0.0, le=1.0, description=(
            "Newton's e of the corners (0: Housner's impact, the angular momentum about the new edge kept)."))
        mu: NonNegative | None = Field(None, description=(
            "None: the base does not slide or twist (held); a number: Coulomb friction at the corners, the base "
            "free (it slides in plan and twists; method = \"moreau-jean\" only)."))
        facets: int | None = Field(None, description=_FACETS_3D)
        on: NodeId | None = Field(None, description=(
            "What the box stands on: none, the ground; a node of [[nodes]], a floor (the base centre at that "
            "node: node height/2 above it); the name of another [[rigid_blocks]] entry, its top face (a stack, "
            "the plan within the lower box's)."))

    return Contact3D, RigidBox


def add_rigid(fr, document, to_mass, each, g=None) -> None:
    """Add the ``[[contacts]]`` and ``[[rigid_blocks]]`` of ``document`` to the frame ``fr``.

    ``each(document, section, action)`` calls ``action(table)`` with the table's key path as the
    context of its errors; ``g`` the gravity of ``[loads.gravity]`` in the model's units (the
    blocks' second-order term; None: no gravity, no term). A 3-D frame (``fr.rigid_box``) takes
    boxes; its gravity must be vertical (along -z).
    """
    if not (document.contacts or document.rigid_blocks):
        return
    plane = {"facets": lambda t: t.facets} if hasattr(fr, "rigid_box") else {}        # 3-D: the friction polygon
    each(document, "contacts", lambda c: fr.contact(c.name, c.node, direction=c.direction, gap=c.gap,
                                                    restitution=c.restitution, mu=c.mu, on=c.on,
                                                    **{k: f(c) for k, f in plane.items()}))
    g = 0.0 if g is None else g
    if not hasattr(fr, "rigid_box"):
        each(document, "rigid_blocks", lambda b: _stacked_order(document, b) or fr.rigid_block(
            b.name, b.node, width=b.width, height=b.height, mass=b.mass * to_mass,
            J=None if b.J is None else b.J * to_mass, restitution=b.restitution, mu=b.mu, g=g, on=b.on))
        return
    scaled = lambda J: None if J is None else J * to_mass
    each(document, "rigid_blocks", lambda b: _vertical(document) or _stacked_order(document, b) or fr.rigid_box(
        b.name, b.node, width_x=b.width, width_y=b.width_y, height=b.height, mass=b.mass * to_mass, Jx=scaled(b.Jx),
        Jy=scaled(b.Jy), Jz=scaled(b.Jz), restitution=b.restitution, mu=b.mu, facets=b.facets, g=g,
        on=b.on))


def _stacked_order(document, block) -> None:
    """Raise unless the block that ``block`` stands on (``on`` a block's name) comes before it in
    ``[[rigid_blocks]]`` (the lower block is built first), naming a cycle of stacks if there is one."""
    blocks = document.rigid_blocks
    position = {b.name: k for k, b in enumerate(blocks)}
    k = position.get(block.name)
    if block.on not in position or k is None or position[block.on] < k:
        return
    chain, seen, below = [block.name], {block.name}, block.on
    while below in position and below not in seen:
        chain.append(below)
        seen.add(below)
        below = blocks[position[below]].on
    if below in seen:
        raise ValueError(f"on = {block.on!r} closes a cycle of stacks: {' on '.join(map(repr, chain + [below]))}")
    raise ValueError(f"on = {block.on!r} is a block listed after it (rigid_blocks[{position[block.on]}]); list the "
                     "lower block first")


def _vertical(document) -> None:
    """Raise unless the gravity of a 3-D document (if any) acts along -z (a box's second-order term)."""
    gravity = document.loads.gravity
    if gravity is not None and tuple(gravity.direction) != (0.0, 0.0, -1.0):
        raise ValueError(f"a rigid box needs gravity along -z ([loads.gravity] direction = [0, 0, -1]), got "
                         f"{list(gravity.direction)}: its second-order term -W h is that of a vertical weight")


def ground_inertia(structure, direction):
    """The influence ``-T^T M_full r_full`` (n,) of a unit ground acceleration along ``direction`` for a
    frame with rigid contacts (every node's inertia, a block's centre included: a slave of its base,
    whose ``ux`` is held), or None for a frame without them (the caller's ``-M r``)."""
    if getattr(structure, "rigid", None) is None:
        return None
    if len(next(iter(structure.coords.values()))) == 3:          # a 3-D frame: "ux", "uy", "uz" or a vector
        from ..structure.rigid3d import ground_motion

        return ground_motion(structure, lambda t: 0.0, direction)[0]
    if direction not in ("ux", "uy"):
        raise ValueError(f"direction={direction!r}: a ground motion of a frame with rigid contacts acts along "
                         "'ux' or 'uy'")
    return -structure.gravity(1.0, (1.0, 0.0) if direction == "ux" else (0.0, 1.0))
