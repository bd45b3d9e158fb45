"""Rigid blocks standing on a frame's floor or on other rigid blocks (stacks), for
:meth:`Frame2D.rigid_block(..., on=) <unilateral.structure.Frame2D.rigid_block>`.

A rigid contact between two bodies (``Frame2D.contact(name, node, on=other)``) has the column of
the *relative* motion along its normal ``d``,

    N = T^T (e_d(node) - e_d(on)),    opening = N^T u + gap,

and the same in the tangent for friction: its force ``v >= 0`` pushes ``node`` along ``+d`` and
``on`` along ``-d`` (it is internal: momentum is exchanged between the two, an impact's impulse
included, and the ground's reactions do not count it).

**A block on a floor** (``on`` a node ``f`` of the frame): the block's base centre is at ``f``;
its corners bear on two points ``"<name>.on.left"``, ``"<name>.on.right"`` of the floor, rigidly
linked to ``f`` (a rotation of the floor's node raises one and lowers the other: the floor is
taken as straight over the block's width, the tangent of the beam's deflected line at ``f``), and
the base's ``ux`` is tied to ``f``'s (no slip, :class:`~unilateral.structure.dofs.DofMap`'s
``ties``; with ``mu`` the corners' friction instead). Bearing points at the corners are what is
physically right for a floor that is not a node at each corner: a rigid block touches the floor
at its corners whatever the floor's mesh.

**A block on a block** (``on`` the name of a rigid block ``L``): the base line lies on ``L``'s top
face (``h`` above ``L``'s centre by ``L``'s half-height) within its width; the corners bear on
points of that face, rigidly linked to ``L``'s base (the master of ``L``), the base's ``ux`` tied to
the point of the face under its centre ``"<name>.on"``.

**The weight's second-order term on a moving base.** The potential of a block's weight is ``W``
times the height of its centre, ``W (uy_b + h cos theta)`` with ``uy_b``, ``theta`` the absolute
displacement and rotation of its base: ``-W h`` on its own ``rz`` whatever it stands on
(:class:`~unilateral.structure.rigid.RigidBlock`). A bearing point at the height ``dy`` above the
master ``m`` it is linked to drops by ``dy phi_m^2 / 2`` when ``m`` turns by ``phi_m`` (the rigid
rotation, exact: ``dx sin phi - dy (1 - cos phi)``), a curvature of the contact's opening that the
linear column omits; with the static force the point carries, the weight ``W_c`` of the block and
of all that stands on it, that is the geometric stiffness ``-W_c dy`` on ``m``'s rotation. For a
block on a block ``dy = 2 h_L``: a stack held together then has the second-order stiffness of the
monolith, ``-sum W_i y_i`` (``y_i`` the height of each centre above the ground's corners), as
``docs/rocking.md`` derives it for one block. On a floor ``dy = 0`` (the bearing points at the
node's level). Like P-Delta, this takes the carried force at its static value.

**In 3-D** (:meth:`Frame3D.rigid_box(..., on=) <unilateral.structure.Frame3D.rigid_box>`) the same
with four corners (bearing points ``"<name>.on.sw"``, ...), the plan of an upper box within the
lower's top face along x and y, the base's ``ux``, ``uy``, ``rz`` tied to ``"<name>.on"`` (a partial
rigid link of the 3-D frame; none with ``mu``), and the carried term ``-W_c dz`` on the seat's
``rx`` and on its ``ry`` (the drop ``dz (rx^2 + ry^2) / 2``; the products with the seat's twist
``rz`` are left out).
"""

from __future__ import annotations

import math


def support(frame, where, name, node, on, *, b, h):
    """``("node", f)`` or ``("block", L)``: what the block ``name`` (centre ``node``, half-width
    ``b``, half-height ``h``) stands on, checked, its placement too, before anything is added;
    ``on`` the name of a rigid block or a node of ``frame``. A 3-D box gives ``b = (bx, by)`` (its
    plan half-widths; the vertical is z)."""
    blocks = frame.__dict__.get("_rigid", {}).get("blocks", {})
    if isinstance(on, str) and on == name:
        raise ValueError(f"{where}: on={on!r} is the block itself; give the node or the rigid block it stands on")
    is_block = isinstance(on, str) and on in blocks
    if is_block and frame._known(on):
        raise ValueError(f"{where}: on={on!r} is both a node and a rigid block; rename one of them")
    if not is_block and not frame._known(on):
        names = ", ".join(map(repr, blocks)) or "none"
        raise ValueError(f"{where}: on={on!r} is neither a defined node nor a rigid block (blocks: {names})")
    if not is_block:
        owner = _owner(frame, on)
        if on == node:
            raise ValueError(f"{where}: on={on!r} is the block's own centre node")
        if owner is not None:
            raise ValueError(f"{where}: on={on!r} is a node of rigid block {owner!r}; to stand on that block give "
                             f"on={owner!r}")
    below, chain = ("block", on) if is_block else ("node", on), [name]
    while below[0] == "block":                  # down the stack to the floor or the ground
        chain.append(below[1])
        lower = blocks[below[1]]
        on_block = lower.on in blocks and lower.seat == blocks[lower.on].base
        below = ("block" if on_block else "node", lower.on)
    if below[1] is not None and below[1] == node:
        raise ValueError(f"{where}: on={on!r} closes a cycle of stacks: {' on '.join(map(repr, chain))} on node "
                         f"{node!r}, the centre of {name!r}")
    at = [float(c) for c in frame._coords[node]]
    at[-1] -= h                                 # the base centre (the vertical: y in 2-D, z in 3-D)
    if is_block:
        _on_top(where, blocks[on], frame._coords[blocks[on].base], at, b)
        return ("block", on)
    floor = [float(c) for c in frame._coords[on]]
    if not all(_near(a, f, max(_widths(b))) for a, f in zip(at, floor)):
        raise ValueError(f"{where}: the block's base centre ({_xyz(at)}) must be at node on={on!r} "
                         f"({_xyz(floor)}): put the centre node height/2 above it")
    held = [dof for dof in ("ux", "uy", "uz")[:len(at)] if (on, dof) in frame._restrained]
    if held:
        raise ValueError(f"{where}: node on={on!r} is supported ({', '.join(held)}): it is the ground; give "
                         "on=None")
    return ("node", on)


def check_centre(frame, where, name, node) -> None:
    """Raise if ``node``, to be the centre of the block ``name``, is the floor node of a block."""
    blocks = _parts_blocks(frame)
    carried = [b.name for b in blocks.values() if getattr(b, "seat", None) == node]
    if carried:
        raise ValueError(f"{where}: node={node!r} is the floor node of rigid block {carried[0]!r}: a block's centre "
                         f"cannot carry another block; stand that block on this one (on={name!r})")


def _on_top(where, lower, at_lower, at, b) -> None:
    """Raise unless the base centre ``at`` (its last coordinate the base level) and the base's
    half-widths ``b`` (a float in 2-D, ``(bx, by)`` in 3-D) lie on the top face of the block
    ``lower`` (its base centre at ``at_lower``): no overhang."""
    low = [float(c) for c in at_lower]
    top = low[-1] + 2 * lower.h
    if not _near(at[-1], top, max(_widths(b))):
        axis = "yz"[len(at) - 2]
        raise ValueError(f"{where}: the block's base at {axis} = {at[-1]:g} must lie on the top face of rigid "
                         f"block {lower.name!r}, {axis} = {top:g}")
    half = _widths(lower.b if hasattr(lower, "b") else (lower.bx, lower.by))
    for axis, x, xl, bi, bl in zip("xy", at[:-1], low[:-1], _widths(b), half):
        if abs(x - xl) + bi > bl * (1 + 1e-12) + 1e-12 * max(1.0, abs(xl)):
            raise ValueError(f"{where}: the block's base {axis} in [{x - bi:g}, {x + bi:g}] must lie within the top "
                             f"face of rigid block {lower.name!r}, [{xl - bl:g}, {xl + bl:g}] (no overhang)")


def _widths(b) -> tuple:
    return (float(b),) if isinstance(b, (int, float)) else tuple(float(x) for x in b)


def _xyz(at) -> str:
    return ", ".join(f"{x:g}" for x in at)


def seat(frame, name, base, corners, kind, on, *, tie) -> tuple:
    """Add the bearing points of the block ``name`` on ``on`` (``kind`` ``"node"`` or ``"block"``,
    checked by :func:`support`): ``"<name>.on"`` under the base centre and ``"<name>.on.<corner>"``
    (``.left``, ``.right``; a box's ``.sw``, ``.se``, ``.ne``, ``.nw``) under the corners, rigidly
    linked to the floor node or to the lower block's base; tie the base to the first (``tie``: no
    slip; its ``ux`` in 2-D, a DofMap tie; a box's ``ux``, ``uy``, ``rz``, a partial rigid link of
    the 3-D frame). Returns ``(master, bearings)``: the node the points are linked to and the
    bearing point of each corner."""
    master = on if kind == "node" else _parts_blocks(frame)[on].base
    points = (f"{name}.on", *(f"{name}.on.{corner[len(name) + 1:]}" for corner in corners))
    for point, at in zip(points, (base, *corners)):
        frame.node(point, *(float(c) for c in frame._coords[at]))
        frame.rigid_link(master, point)
    if tie and len(frame._coords[base]) == 3:
        frame._tie(f"rigid_box({name!r}): the base on {on!r}", points[0], base, ("ux", "uy", "rz"))
    elif tie:
        ties(frame)[(base, "ux")] = points[0]
    return master, points[1:]


def ties(frame) -> dict:
    """The ties ``(node, dof) -> other node`` of ``frame``'s blocks (the bases' ``ux``), kept on it."""
    return frame.__dict__.setdefault("_rigid_ties", {})


def carried_terms(frame, blocks, dofs) -> list:
    """The geometric stiffness of the weights the bearing points carry (see the module): ``[(row,
    -W_c dy)]`` on the rotation of the master of each block's bearing points (``rz`` in 2-D; ``rx``
    and ``ry`` for a 3-D box, ``dy`` then the height ``dz``)."""
    out = []
    for block in blocks.values():
        master = getattr(block, "seat", None)
        if master is None or not block.g:
            continue
        root = dofs.masters.get(master, master)
        dy = float(frame._coords[block.base][-1] - frame._coords[root][-1])
        for dof in ("rx", "ry") if len(frame._coords[root]) == 3 else ("rz",):
            if dy and (root, dof) in dofs.free:
                out.append((dofs.index(root, dof), -carried_weight(blocks, block) * dy))
    return out


def carried_weight(blocks, block) -> float:
    """``W`` of ``block`` and of every block that stands on it (directly or up a stack), force."""
    return sum(b.W for b in stack_of(blocks, block))


def stack_of(blocks, block) -> list:
    """``block`` and every block standing on it, directly or up a stack (2-D blocks or 3-D boxes)."""
    out = [block]
    for b in blocks.values():
        if getattr(b, "seat", None) == block.base and b is not block:
            out += stack_of(blocks, b)
    return out


def _owner(frame, node):
    """The name of the rigid block ``node`` belongs to (its centre, base, corners or bearing
    points' master chain ending at a block's base), or None."""
    blocks = _parts_blocks(frame)
    for block in blocks.values():
        if node in (block.node, block.base, *block.corners):
            return block.name
    root = node
    while frame._master(root) is not None:
        root = frame._master(root)
        for block in blocks.values():
            if root == block.base:
                return block.name
    return None


def _parts_blocks(frame) -> dict:
    return frame.__dict__.get("_rigid", {}).get("blocks", {})


def _near(a, b, scale) -> bool:
    return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9 * max(1.0, abs(scale)))

