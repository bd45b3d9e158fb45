"""Rigid unilateral contacts and rigid rocking boxes for :class:`~unilateral.structure.Frame3D`.

The 3-D counterpart of :mod:`unilateral.structure.rigid` (whose assembly, model and impact law the
3-D frame shares: the contacts are columns ``N = T^T e_d`` of ``F`` with ``H = 0``, the family
:class:`~unilateral.constraints.RigidContact`, solved by ``method="moreau-jean"``).

**Rigid contact** (``Frame3D.contact``, :meth:`RigidBoxes.contact`): a node against the fixed
ground (or against another node, ``on``: the columns of the relative motion) along a normal ``d`` (``"ux"``, ``"uy"``, ``"uz"`` or a vector), with Newton's coefficient
of restitution and, with ``mu``, Coulomb friction in its tangent plane (axes ``t1``, ``t2``,
:func:`~unilateral.structure.elements3d.tangents`): a polygonal cone of ``facets`` facets
circumscribing Coulomb's circle ``|T| <= mu N`` (default 8; facet ``k`` of the normal ``(cos th_k,
sin th_k)`` on ``(t1, t2)``, ``th_k = 2 pi k / facets``, the convention of ``Frame3D.soil`` and the
footings in plan), solved by ``method="moreau-jean"`` (:mod:`unilateral.march.impact`).

**Rigid box** (``Frame3D.rigid_box``, :class:`RigidBox`): a rectangular box of plan ``2 bx x 2 by``
and height ``2 h`` with its centre of mass at a node, standing on its four base corners. Its base
centre (the master) moves by ``uz``, ``rx``, ``ry`` (``ux``, ``uy``, ``rz`` held: no slip, no
twist; with ``mu`` free too: the corners' friction holds them, the box slides in plan and twists). With the corners in the plane of the base, a corner ``(x, y)`` (from the base centre)
rises by ``uz + rx y - ry x``; the centre's height drops by ``h (rx^2 + ry^2) / 2`` at second
order, so the weight ``W = m g`` adds ``-W h`` on the base's ``rx`` and ``ry`` to ``K``. Rocking
about an edge parallel to y (tilt ``ry``, the x-z plane) is then Housner's block of half-width
``bx``, ``I0 = Jy + m (bx^2 + h^2)``; about an edge parallel to x (tilt ``rx``), of half-width
``by``, ``I0 = Jx + m (by^2 + h^2)`` (:meth:`RigidBox.plane`). A box with ``Jx = Jy`` (a square
plan, solid) rocking about a corner with its tilt axis perpendicular to the diagonal stays in that
plane: Housner's block of half-width ``d = sqrt(bx^2 + by^2)`` (:meth:`RigidBox.diagonal`).
``on=`` stands a box on a frame's floor or on another box (a stack: :mod:`.stacks`). See
``docs/rocking.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..loads.units import STANDARD_GRAVITY
from . import elements as el
from . import elements3d as el3
from . import stacks
from .rigid import RigidBlock, RigidContact, _number, _parts

#: The corners of a box: name suffix -> (sign of x, sign of y) from the base centre.
CORNERS = {"sw": (-1.0, -1.0), "se": (1.0, -1.0), "ne": (1.0, 1.0), "nw": (-1.0, 1.0)}
#: The facets of a rigid contact's friction polygon unless given (as a footing's in plan).
DEFAULT_FACETS = 8


@dataclass(frozen=True)
class RigidContact3D(RigidContact):
    """A rigid contact of a 3-D frame (:class:`~unilateral.structure.rigid.RigidContact`) with the
    axes ``(t1 terms, t2 terms)`` of its tangent plane and the ``facets`` of its friction polygon."""

    axes: tuple = ()
    facets: int = DEFAULT_FACETS

    @property
    def tangent_axes(self) -> tuple:
        """``(t1, t2)``, each ``((dof, t), ...)`` on ``ux``, ``uy``, ``uz``."""
        return self.axes


@dataclass(frozen=True)
class RigidBox:
    """A rigid rectangular box rocking on its four base corners (:mod:`unilateral.structure.rigid3d`).

    Attributes
    ----------
    name : str
    node : the centre-of-mass node (a slave of ``base``), carrying ``mass``, ``Jx``, ``Jy``, ``Jz``
    base : the base-centre node (the master: ``uz``, ``rx``, ``ry`` free; ``ux``, ``uy``, ``rz`` held)
    corners : the four corner nodes ``"<name>.sw"``, ``".se"``, ``".ne"``, ``".nw"`` (x to the east,
        y to the north), each in rigid contact with the ground (the contacts have their names)
    bx, by, h : half-widths along x and y and half-height, length
    mass : mass;  Jx, Jy, Jz : rotary inertias about the centre, mass length^2
    g : gravity of the second-order term, length/time^2 (0: none)
    on : what it stands on: None (the ground), a node of the frame (a floor) or the name of a rigid
        box (a stack; :mod:`.stacks`)
    seat : the node its corners' bearing points are rigidly linked to (the floor node, the lower
        box's base), or None on the ground
    """

    name: str
    node: object
    base: object
    corners: tuple
    bx: float
    by: float
    h: float
    mass: float
    Jx: float
    Jy: float
    Jz: float
    g: float
    on: object = None
    seat: object = None

    @property
    def W(self) -> float:
        """Weight ``m g``, force."""
        return self.mass * self.g

    def geometric_terms(self) -> tuple:
        """The second-order term of the weight on the base: ``((dof, -W h), ...)`` on ``rx`` and ``ry``."""
        return (("rx", -self.W * self.h), ("ry", -self.W * self.h))

    def plane(self, axis) -> RigidBlock:
        """The 2-D block of the rocking about an edge: ``axis="y"`` (an edge parallel to y, the tilt
        ``ry``, rocking in the x-z plane: half-width ``bx``, ``J = Jy``) or ``"x"`` (tilt ``rx``,
        the y-z plane: ``by``, ``Jx``). Its ``p``, ``restitution``, ``impact_times``, ... are
        Housner's closed forms of that rocking."""
        if axis not in ("x", "y"):
            raise ValueError(f"axis={axis!r} is not valid; use 'x' or 'y' (the direction of the edge)")
        b, J = (self.bx, self.Jy) if axis == "y" else (self.by, self.Jx)
        return RigidBlock(self.name, self.node, self.base, self.corners, b, self.h, self.mass, J, self.g, self.on,
                          self.seat)

    def diagonal(self) -> RigidBlock:
        """The 2-D block of the rocking about a corner with the tilt axis perpendicular to the
        diagonal: half-width ``d = sqrt(bx^2 + by^2)``, ``J = Jx``; the motion stays in that plane,
        and the flat landing is Housner's impact onto the opposite corner, where ``Jx = Jy`` (a
        square solid box; otherwise the motion couples the two tilts). ``ValueError`` otherwise."""
        if not math.isclose(self.Jx, self.Jy, rel_tol=1e-12, abs_tol=0.0):
            raise ValueError(f"rigid box {self.name!r}: Jx={self.Jx:g} != Jy={self.Jy:g}: the diagonal rocking "
                             "is not planar (give a square plan or Jx = Jy)")
        return RigidBlock(self.name, self.node, self.base, self.corners, math.hypot(self.bx, self.by), self.h,
                          self.mass, self.Jx, self.g)

    @property
    def uplift_acceleration(self) -> tuple:
        """Horizontal ground accelerations ``(g bx / h, g by / h)`` along x and y at which a corner
        lifts, length/time^2."""
        return (self.g * self.bx / self.h, self.g * self.by / self.h)


class RigidBoxes:
    """The rigid contacts and boxes of :class:`~unilateral.structure.Frame3D` (a base of it)."""

    def contact(self, name, node, *, direction="uz", gap=0.0, mu=None, restitution=0.0, facets=None,
                tangent=None, on=None) -> None:
        """Rigid unilateral contact of ``node`` with the fixed ground, or with the node ``on`` (no
        compliance, ``H = 0``), as :meth:`Frame2D.contact <unilateral.structure.Frame2D.contact>`.

        Parameters
        ----------
        name : str, the contact's name (its unknown and row, after the frame's own unknowns)
        node : the node (a slave of a rigid link too)
        direction : ``"ux"``, ``"uy"``, ``"uz"`` or a vector ``(dx, dy, dz)``: the normal, from the
            ground to the node (the direction in which the node separates); default ``"uz"``
        gap : initial opening at ``u = 0``, length, >= 0
        mu : Coulomb's coefficient of friction (>= 0) in the tangent plane, or None (no friction: the
            tangential motion free or held by supports); ``method="moreau-jean"`` only
        restitution : Newton's coefficient ``e`` in [0, 1] of ``method="moreau-jean"``
        facets : int, even, >= 4 (default 8; with ``mu`` only): the facets of the friction polygon
        tangent : (3,) vector, optional: the first tangent axis ``t1`` (projected on the tangent
            plane; default global X, or Y for a normal along X), ``t2 = d x t1`` (with ``mu`` only)
        on : the node the contact bears on, or None (default: the fixed ground). The columns (the
            normal's, and the tangents' with ``mu``) are those of the relative motion,
            ``N = T^T (e_d(node) - e_d(on))``; the force pushes ``node`` along ``d`` and ``on``
            back (internal: the ground's reactions do not count it; :mod:`.stacks`)

        The contact's unknown ``v`` is the compressive force (force), ``-psi`` the opening (length).

        Notes
        -----
        The friction cone is the polygon of ``N = facets`` facets circumscribing Coulomb's circle
        ``|T| <= mu v``: facet ``k`` keeps ``d_k . T <= mu v``, ``d_k = (cos th_k, sin th_k)`` on
        ``(t1, t2)``, ``th_k = 2 pi k / N`` (``tangent`` turns it). The step's LCP takes it by its
        vertices (:mod:`unilateral.march.impact`). Sliding along a facet normal (``t1``, and ``t2``
        for ``N`` a multiple of 4) is Coulomb's; along a vertex the polygon is ``sec(pi/N)`` too
        strong (8.2 % for 8, 2.0 % for 16), and in between the slip leaves the direction of the
        driving force by up to ``pi/N`` (``docs/rocking.md``, "Friction in 3-D").
        """
        where = self._label("contact", name)
        self._node(where, "node", node)
        if on is not None:
            self._node(where, "on", on)
            if on == node:
                raise ValueError(f"{where}: on={on!r} is the node itself; give the node it bears on, or None "
                                 "(the ground)")
        terms = el.direction_terms(where, direction, el3.DOF_NAMES, el3.AXES)
        if any(dof in el3.ROTATIONS for dof, _ in terms):
            raise ValueError(f"{where}: direction={direction!r} is not a normal; use 'ux', 'uy', 'uz' or a vector "
                             "(dx, dy, dz)")
        mu, facets = _friction(where, mu, facets, tangent)
        axes = tuple(tuple((dof, float(x)) for dof, x in zip(el3.TRANSLATIONS, t) if x != 0.0)
                     for t in el3.tangents(where, terms, tangent)) if mu else ()
        e = _restitution(where, restitution)
        _parts(self)["contacts"].append(RigidContact3D(name, node, terms, _number(where, "gap", gap, ">=0"), e,
                                                       mu or 0.0, on, axes=axes, facets=facets))
        self._names.add(name)

    def rigid_box(self, name, node, *, width_x, width_y, height, mass, Jx=None, Jy=None, Jz=None, base=None,
                  g=STANDARD_GRAVITY, restitution=0.0, mu=None, facets=None, on=None) -> RigidBox:
        """A rigid rectangular box rocking on its four base corners, its centre of mass at ``node``.

        Adds the base-centre node ``base`` (default ``"<name>.base"``) at ``height / 2`` below
        ``node`` as the master of the box (its ``ux``, ``uy``, ``rz`` supported: the base cannot
        slide or twist; ``uz``, ``rx``, ``ry`` free; with ``mu`` all six free), links ``node`` and the corners ``"<name>.sw"``,
        ``".se"``, ``".ne"``, ``".nw"`` (at ``(-+ width_x / 2, -+ width_y / 2)`` on the base plane)
        rigidly to it, puts ``mass`` and the inertias on ``node``, a vertical rigid contact with the
        ground (named after the corner) at each corner, and the second-order term of the weight,
        ``-W h`` on the base's ``rx`` and ``ry`` (:class:`RigidBox`, ``docs/rocking.md``).

        Parameters
        ----------
        name : str;  node : the centre-of-mass node, defined, free (not supported, not a slave)
        width_x, width_y, height : ``2 bx``, ``2 by`` and ``2 h``, length, > 0
        mass : mass, > 0
        Jx, Jy, Jz : rotary inertias about the centre, mass length^2, >= 0; None: the solid box's
            ``m (by^2 + h^2) / 3``, ``m (bx^2 + h^2) / 3``, ``m (bx^2 + by^2) / 3``
        base : id of the base-centre node to create, or None
        g : gravity of the weight's second-order term (length/time^2, >= 0; the load of the weight
            itself is ``Structure3D.gravity(g)``); 0: none
        restitution : Newton's ``e`` of the corners' contacts, [0, 1] (default 0: Housner's impact)
        mu : None (default): the base cannot slide or twist (its ``ux``, ``uy``, ``rz`` supported); a
            number >= 0: the base is free and each corner has Coulomb friction ``mu`` in the plan
            (``method="moreau-jean"`` only): the box slides in both plan directions, twists about the
            vertical, rocks, or all of these (a box with ``mu`` below ``bx / h`` and ``by / h`` under a base
            acceleration above ``mu g`` slides before it can rock)
        facets : the facets of the corners' friction polygons (with ``mu``; an even int >= 4, default
            8), on the axes x, y (:meth:`contact`)
        on : None (default): the box stands on the ground; a node ``f`` of the frame: on its floor at
            ``f`` (the base centre at ``f``: give ``node`` ``height / 2`` above it; the corners bear on
            points ``"<name>.on.sw"``, ... rigidly linked to ``f``, the base's ``ux``, ``uy``, ``rz``
            tied to ``f``'s rigid motion without ``mu``); the name of a rigid box ``L``: on ``L``'s top
            face (a stack; the plan within ``L``'s, the corners on points rigidly linked to ``L``'s
            base). The corners' contacts are then between the two bodies, the weight's second-order
            terms those of a box on a moving base, ``-W_c dz`` on the seat's ``rx`` and ``ry``
            (:mod:`.stacks`)

        Returns
        -------
        RigidBox
        """
        where = self._label("rigid_box", name)
        self._node(where, "node", node)
        mu, facets = _friction(where, mu, facets, None)
        bx = _number(where, "width_x", width_x, ">0") / 2
        by = _number(where, "width_y", width_y, ">0") / 2
        h = _number(where, "height", height, ">0") / 2
        m = _number(where, "mass", mass, ">0")
        solid = {"Jx": by * by + h * h, "Jy": bx * bx + h * h, "Jz": bx * bx + by * by}
        given = {"Jx": Jx, "Jy": Jy, "Jz": Jz}
        J = {k: m * solid[k] / 3.0 if given[k] is None else _number(where, k, given[k], ">=0") for k in solid}
        g = _number(where, "g", g, ">=0")
        e = _restitution(where, restitution)
        below = None if on is None else stacks.support(self, where, name, node, on, b=(bx, by), h=h)
        stacks.check_centre(self, where, name, node)
        base = f"{name}.base" if base is None else base
        corners = tuple(f"{name}.{c}" for c in CORNERS)
        x, y, z = (float(c) for c in self._coords[node])
        self.node(base, x, y, z - h)
        for corner, (sx, sy) in zip(corners, CORNERS.values()):
            self.node(corner, x + sx * bx, y + sy * by, z - h)
        if mu is None and below is None:
            self.support(base, ux=True, uy=True, uz=False, rx=False, ry=False, rz=True)
        for slave in (node, *corners):
            self.rigid_link(base, slave)
        seat, bearings = (None, (None,) * 4) if below is None else stacks.seat(
            self, name, base, corners, *below, tie=mu is None)
        self.mass(node, m, Jx=J["Jx"], Jy=J["Jy"], Jz=J["Jz"])
        self._names.add(name)
        for corner, bearing in zip(corners, bearings):
            self.contact(corner, corner, direction="uz", restitution=e, mu=mu, on=bearing,
                         facets=facets if mu is not None else None)
        box = RigidBox(name, node, base, corners, bx, by, h, m, J["Jx"], J["Jy"], J["Jz"], g, on, seat)
        _parts(self)["blocks"][name] = box
        return box


def _friction(where, mu, facets, tangent) -> tuple:
    """``(mu, facets)`` checked: ``(None, DEFAULT_FACETS)`` without friction (``facets`` and
    ``tangent`` refused then), else ``mu >= 0`` and ``facets`` an even int >= 4."""
    if mu is None:
        for arg, value in (("facets", facets), ("tangent", tangent)):
            if value is not None:
                raise ValueError(f"{where}: {arg}={value!r} is a friction parameter; give the friction "
                                 "coefficient mu too (or remove it)")
        return None, DEFAULT_FACETS
    mu = _number(where, "mu", mu, ">=0")
    facets = DEFAULT_FACETS if facets is None else facets
    if isinstance(facets, (bool, np.bool_)) or not isinstance(facets, (int, np.integer)) or facets < 4 or facets % 2:
        raise ValueError(f"{where}: facets={facets!r} is not valid; give the facets of the friction polygon, an "
                         "even int >= 4 (opposite facets in pairs; fewer than 4 do not bound the tangent plane)")
    return mu, int(facets)


def _restitution(where, restitution) -> float:
    e = _number(where, "restitution", restitution, ">=0")
    if e > 1.0:
        raise ValueError(f"{where}: restitution={restitution!r} must lie in [0, 1] (Newton's coefficient: "
                         "0 perfectly plastic, 1 elastic)")
    return e


# ---------------------------------------------------------------------- loads and results
def ground_motion(structure, a_g, direction="ux") -> tuple:
    """The term ``(-T^T M_full r_full, a_g)`` of a ground acceleration ``a_g(t)`` (length/time^2) along
    ``direction`` (``"ux"``, ``"uy"``, ``"uz"`` or a vector ``(dx, dy, dz)``) of a 3-D frame with
    rigid boxes: every node's inertia, a box's centre (a slave of its held base) included, as
    :func:`unilateral.structure.rigid.ground_motion` in 2-D."""
    terms = dict(el.direction_terms("ground motion", direction, el3.DOF_NAMES, el3.AXES))
    if any(dof in el3.ROTATIONS for dof in terms):
        raise ValueError(f"direction={direction!r} is not valid for a ground motion; valid: 'ux', 'uy', 'uz' "
                         "or a vector (dx, dy, dz)")
    if not callable(a_g):
        raise TypeError(f"a_g must be a time function a_g(t), got {a_g!r}")
    return -structure.gravity(1.0, tuple(terms.get(d, 0.0) for d in el3.TRANSLATIONS)), a_g


def box_tilts(structure, sol, name) -> tuple:
    """``(rx, ry, uz)`` (N+1,) each: the base's tilts (rad) and rise (length) of the box ``name``."""
    box = structure.rigid.blocks[name]
    T = structure.dofs.T
    return tuple(np.asarray(T[structure.dofs.full_index(box.base, dof)] @ sol.u.T).ravel()
                 for dof in ("rx", "ry", "uz"))


def box_energy(structure, sol, name) -> np.ndarray:
    """Mechanical energy (N+1,) of the box ``name`` in the linearised model, force length:
    ``m |v_c|^2 / 2 + (Jx rx'^2 + Jy ry'^2 + Jz rz'^2) / 2 - W h (rx^2 + ry^2) / 2 + W uz``, with the
    centre's velocity ``v_c = (ux' + h ry', uy' - h rx', uz')`` (``ux``, ``uy``, ``rz`` of the base
    0 where held: a box without friction)."""
    box = structure.rigid.blocks[name]
    T = structure.dofs.T
    rows = [T[structure.dofs.full_index(box.base, dof)] for dof in el3.DOF_NAMES]
    (ux, uy, uz, rx, ry, rz), (vx, vy, vz, wx, wy, wz) = ([np.asarray(r @ x.T).ravel() for r in rows]
                                                          for x in (sol.u, sol.udot))
    m, h, W = box.mass, box.h, box.W
    kinetic = 0.5 * m * ((vx + h * wy) ** 2 + (vy - h * wx) ** 2 + vz ** 2) + 0.5 * (
        box.Jx * wx ** 2 + box.Jy * wy ** 2 + box.Jz * wz ** 2)
    return kinetic - 0.5 * W * h * (rx ** 2 + ry ** 2) + W * uz


def box_results(structure, sol, name, corners) -> dict:
    """The rocking of the rigid box ``name`` (:func:`unilateral.analysis.rigid.block_results` of a
    box): ``rotation`` (N+1,) the tilt ``sqrt(rx^2 + ry^2)`` (rad), ``rotation_x``, ``rotation_y``
    (rad), ``omega`` (N+1,) its rate ``|(rx', ry')|`` (rad/time), ``uplift`` (N+1,) the largest
    opening of the four corners (length), ``corners`` (``corners``: the contact results of the four),
    ``peak_rotation``, ``peak_uplift``, ``overturned`` and ``overturn_time``: the first time the
    centre's plan offset ``(h ry, -h rx)`` leaves the base (``h |ry| > bx`` or ``h |rx| > by``, the
    linearised loss of the restoring moment), and ``impacts`` (time, the corner struck, loss)."""
    box = structure.rigid.blocks[name]
    T = structure.dofs.T
    rows = [T[structure.dofs.full_index(box.base, dof)] for dof in ("rx", "ry")]
    rx, ry = (np.asarray(r @ sol.u.T).ravel() for r in rows)
    wx, wy = (np.asarray(r @ sol.udot.T).ravel() for r in rows)
    uplift = np.max([corners[c]["opening"] for c in box.corners], axis=0)
    tilt = np.hypot(rx, ry)
    past = np.flatnonzero((box.h * np.abs(ry) > box.bx) | (box.h * np.abs(rx) > box.by))
    impacts = []
    for ev in sol.stats.get("impacts", ()):
        struck = [c for c in ev["contacts"] if c in box.corners]
        if struck:
            impacts.append({"time": ev["time"], "corner": struck[0], "loss": ev["loss"]})
    return {"rotation": tilt, "rotation_x": rx, "rotation_y": ry, "omega": np.hypot(wx, wy), "uplift": uplift,
            "corners": corners, "peak_rotation": float(np.max(tilt)), "peak_uplift": float(np.max(uplift)),
            "overturned": bool(past.size), "overturn_time": float(sol.t[past[0]]) if past.size else None,
            "impacts": impacts}
