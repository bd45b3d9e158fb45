"""Rigid unilateral contacts and rigid rocking blocks for :class:`~unilateral.structure.Frame2D`.

**Rigid contact** (``Frame2D.contact``, :meth:`RigidContacts.contact`): a node against the fixed ground with
no compliance (or against another node, ``on``: the column of the relative motion; :mod:`.stacks`).
The paper's contact is a spring ``k`` in series with the unilateral deformation ``v`` (the opening);
with ``k -> infinity`` its ``H = k`` has no finite value, so a rigid contact is written in the *dual*
(force) form instead, a column of ``F`` with ``H = 0``:

    M u'' + C u' + K u = q + N v,        psi = N^T u - g,   g = -gap,
    v >= 0 (the compressive contact force),  psi >= 0 (the opening),  psi^T v = 0

``N`` (n,) is the unit normal ``d`` (pointing from the ground to the node) carried to the free
DOFs through the rigid links, ``u_full = T u``: ``N = T^T e_d``. The family
:class:`~unilateral.constraints.RigidContact` gives these rows the row map ``P = -1``, so that
each step's LCP is ``w = psi_n = psi_free + N^T D_eff^-1 N (1 - alpha) v_n >= 0``: its matrix
``P W0 = (1 - alpha) N^T D_eff^-1 N`` is positive definite when the DOFs the contacts move carry
mass (``D_eff = c0 M + (1 - alpha)(c1 C + K)``). ``K`` is the stiffness of the structure *without*
its rigid contacts: singular for a free body, indefinite with the rocking's negative geometric
stiffness; :class:`~unilateral.Model` is given it as is (its check of ``K`` is for the paper's
primal contacts, whose bilateral structure is held).

What the methods do with them:

* ``direct``: the condensed LCP above, every rule (the compiled march of the general law).
  An impact is *position-level*: the opening at the end of the step is held at zero, the
  velocity follows from the rule. BDF1 gives a perfectly plastic impact (Moreau's sweeping
  process in the limit ``dt -> 0``), the trapezoidal rule a velocity reversal (an elastic bounce,
  then chatter), BDF2 a few steps of chatter and a partial loss (``docs/rocking.md``).
* ``cq`` and ``modal``: ``Lambda(s) = -N^T D(s)^-1 N``; they apply where ``K`` is positive
  definite (a mass on a spring against a rigid stop: they agree with ``direct`` to round-off),
  and are refused otherwise: the poles of ``D(s)^-1`` at ``s = 0`` (a free body) or ``s > 0``
  (rocking) make the convolution weights grow without bound (:func:`method_refusal`).
* ``event``: refused: it integrates the smooth motion between contact changes and has no impact
  law (a rigid contact closing with a velocity needs a jump of the velocity).

Friction (``mu``) on a rigid contact: Coulomb's law on the tangential impulses at the velocity level,
taken by ``method="moreau-jean"`` only (the other methods refuse it; the tangent columns ride on the
family :class:`~unilateral.constraints.RigidContact`, not among the model's unknowns).

**Rigid block** (``Frame2D.rigid_block``, :meth:`RigidContacts.rigid_block`): a rectangle of width ``2 b`` and
height ``2 h`` with its centre of mass at a node, standing on its two base corners; see
:class:`RigidBlock` and ``docs/rocking.md`` for the linearised equations of rocking it reproduces
(Housner 1963). ``on=`` stands it on a frame's floor or on another block (a stack: :mod:`.stacks`).

In 3-D (``Frame3D.contact``, ``Frame3D.rigid_box``: a box on four corners) the builders are those of
:mod:`unilateral.structure.rigid3d`; the assembly and the model here are shared.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import numbers
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..loads.units import STANDARD_GRAVITY
from . import elements as el
from . import stacks


@dataclass(frozen=True)
class RigidContact:
    """One rigid contact as given: ``name``, ``node``, the normal's ``terms`` ``((dof, d), ...)``
    (unit, from the ground to the node), the initial ``gap`` (opening at ``u = 0``, length) and
    Newton's coefficient of ``restitution`` (used by ``method="moreau-jean"``), Coulomb's ``mu`` and
    ``on``: the node it bears on (None: the ground; the column is then the relative motion)."""

    name: str
    node: object
    terms: tuple
    gap: float
    restitution: float = 0.0
    mu: float = 0.0
    on: object = None

    @property
    def tangent_terms(self) -> tuple:
        """The tangent ``(dof, t)`` terms: the normal turned by -90 degrees (``uy`` -> ``ux``)."""
        d = dict(self.terms)
        return tuple((dof, c) for dof, c in (("ux", d.get("uy", 0.0)), ("uy", -d.get("ux", 0.0))) if c)

    @property
    def tangent_axes(self) -> tuple:
        """The tangent axes of the friction, each ``((dof, t), ...)``: ``(tangent_terms,)`` (a 3-D
        contact has two, :class:`~unilateral.structure.rigid3d.RigidContact3D`)."""
        return (self.tangent_terms,)


@dataclass(frozen=True)
class RigidBlock:
    """A rigid rectangular block rocking on its two base corners.

    Attributes
    ----------
    name : str
    node : the centre-of-mass node (a slave of ``base``), carrying ``mass`` and ``J``
    base : the base-centre node (the master: ``uy``, ``rz`` free, ``ux`` supported: no slip)
    corners : (left, right) corner nodes (slaves of ``base``), each in rigid contact with the
        ground (the contacts have the corners' names)
    b, h : half-width and half-height, length (the centre is ``h`` above the contact plane)
    mass : mass, force time^2/length;  J : rotary inertia about the centre, force length time^2
    g : gravity of the second-order term, length/time^2 (0: none)
    on : what it stands on: None (the ground), a node of the frame (a floor) or the name of a rigid
        block (a stack; :mod:`.stacks`)
    seat : the node its corners' bearing points are rigidly linked to (the floor node, the lower
        block's base), or None on the ground
    """

    name: str
    node: object
    base: object
    corners: tuple
    b: float
    h: float
    mass: float
    J: float
    g: float
    on: object = None
    seat: object = None

    @property
    def W(self) -> float:
        """Weight ``m g``, force."""
        return self.mass * self.g

    def geometric_terms(self) -> tuple:
        """The second-order term of the weight on the base: ``(("rz", -W h),)``."""
        return (("rz", -self.W * self.h),)

    @property
    def I0(self) -> float:
        """Rotary inertia about a base corner, ``J + m (b^2 + h^2)``, force length time^2."""
        return self.J + self.mass * (self.b ** 2 + self.h ** 2)

    @property
    def p(self) -> float:
        """Frequency parameter of the linearised rocking, ``p = sqrt(W h / I0)``, rad/time."""
        return math.sqrt(self.W * self.h / self.I0)

    @property
    def alpha(self) -> float:
        """Slenderness angle ``atan(b / h)``, rad."""
        return math.atan2(self.b, self.h)

    @property
    def restitution(self) -> float:
        """Housner's ratio of the angular velocities after/before an impact, ``1 - 2 m b^2 / I0``
        (angular momentum about the new corner conserved; ``1 - 3/2 sin^2 alpha`` for a uniform
        rectangle)."""
        return 1.0 - 2.0 * self.mass * self.b ** 2 / self.I0

    @property
    def uplift_acceleration(self) -> float:
        """Horizontal ground acceleration at which a corner lifts, ``g b / h``, length/time^2."""
        return self.g * self.b / self.h

    def first_impact_time(self, theta0) -> float:
        """Time from the release at rest from the tilt ``theta0`` (rad, ``0 < theta0 < b/h``) to
        the first impact, ``acosh((b/h) / (b/h - theta0)) / p``, of the linearised equation
        ``I0 theta'' = W (h theta - b)`` (``theta`` the tilt about the pivot corner)."""
        a = self.b / self.h
        if not 0.0 < theta0 < a:
            raise ValueError(f"theta0={theta0!r} must lie in (0, b/h = {a:.6g}): beyond b/h the block overturns")
        return math.acosh(a / (a - theta0)) / self.p

    def impact_times(self, theta0, count) -> np.ndarray:
        """Times (count,) of the first ``count`` impacts of the linearised free rocking released at
        rest from ``theta0`` with Housner's impact law (the angular velocity times ``r`` at each).

        The impact velocity ``omega_1 = p sqrt(2 a theta0 - theta0^2)`` (``a = b/h``: energy), and a
        phase that leaves ``theta = 0`` with ``omega`` returns to it after
        ``(2 / p) atanh(omega / (p a))``; ``omega_{k+1} = r omega_k``.
        """
        a, p, r = self.b / self.h, self.p, self.restitution
        t = [self.first_impact_time(theta0)]
        omega = p * math.sqrt(2 * a * theta0 - theta0 ** 2)
        for _ in range(count - 1):
            omega *= r
            t.append(t[-1] + 2.0 / p * math.atanh(omega / (p * a)))
        return np.array(t[:count])

    def tilt(self, t, theta0) -> np.ndarray:
        """Closed-form tilt ``b/h + (theta0 - b/h) cosh(p t)`` (rad) of the linearised free rocking
        released at rest from ``theta0``, until the first impact; ``t`` (N,) times."""
        a = self.b / self.h
        return a + (theta0 - a) * np.cosh(self.p * np.asarray(t, dtype=float))


@dataclass(frozen=True)
class RigidPart:
    """The rigid contacts and blocks of a built frame (``structure.rigid`` of its ``RigidStructure``).

    Attributes
    ----------
    contacts : tuple of RigidContact, in the order of their unknowns (after the frame's own)
    N : (n, mr) csr, the columns of ``F`` of the contacts (``N = T^T e_d``; ``T^T (e_d(node) - e_d(on))``
        for a contact between two nodes)
    gap : (mr,) initial openings, length
    geometric : (n, n) csr, the blocks' second-order gravity terms (``-W h`` on each block's
        ``rz``, on each 3-D box's ``rx`` and ``ry``), added to ``K``
    blocks : dict name -> RigidBlock (or :class:`~unilateral.structure.rigid3d.RigidBox` in 3-D)
    tangent : (n, mr) csr, the tangent columns of the contacts with friction (zero columns without);
        in 3-D a pair of them, the axes ``t1``, ``t2``
    """

    contacts: tuple
    N: sp.csr_matrix
    gap: np.ndarray
    geometric: sp.csr_matrix
    blocks: dict
    tangent: sp.csr_matrix = None

    @property
    def names(self) -> tuple:
        return tuple(c.name for c in self.contacts)

    def to_model(self, structure):
        """The :class:`~unilateral.Model` of ``structure`` with its rigid contacts (see the module)."""
        return _model(structure, self)


# ---------------------------------------------------------------------- the builders
def _parts(frame) -> dict:
    """The rigid contacts and blocks defined on ``frame`` so far (kept on the frame)."""
    parts = frame.__dict__.get("_rigid")
    if parts is None:
        parts = frame.__dict__["_rigid"] = {"contacts": [], "blocks": {}}
    return parts


class RigidContacts:
    """The rigid contacts and blocks of :class:`~unilateral.structure.Frame2D` (a base of it)."""

    def contact(self, name, node, *, on=None, direction="uy", gap=0.0, mu=None, restitution=0.0) -> None:
        """Rigid unilateral contact of ``node`` with the fixed ground, or with the node ``on`` (no
        compliance, ``H = 0``).

        Parameters
        ----------
        name : str, the contact's name (its unknown and row, after the frame's own unknowns)
        node : the node (a slave of a rigid link too)
        on : the node the contact bears on, or None (default: the fixed ground). The column is the
            relative motion, ``N = T^T (e_d(node) - e_d(on))``; the force pushes ``node`` along ``d``
            and ``on`` back (internal: the ground's reactions do not count it; :mod:`.stacks`)
        direction : ``"ux"``, ``"uy"`` or a vector ``(dx, dy)``: the normal, from the ground (from
            ``on``) to the node (the direction in which the node separates); default ``"uy"``
        gap : initial opening at ``u = 0``, length, >= 0
        mu : Coulomb's coefficient of friction (>= 0) along the tangent (the normal turned by -90
            degrees), or None (no friction; the tangential motion then free or held by supports);
            friction is taken by ``method="moreau-jean"`` only
        restitution : Newton's coefficient ``e`` in [0, 1] of the velocity-level impact law of
            ``method="moreau-jean"`` (0: perfectly plastic; the position-level ``direct`` ignores it)

        The contact's unknown ``v`` is the compressive force (force) and ``-psi`` of a solution the
        opening (``Solution.psi`` holds ``P psi = -opening``).
        """
        where = self._label("contact", name)
        self._node(where, "node", node)
        if on is not None:
            self._node(where, "on", on)
            if on == node:
                raise ValueError(f"{where}: on={on!r} is the node itself; give the node it bears on, or None "
                                 "(the ground)")
        mu = 0.0 if mu is None else _number(where, "mu", mu, ">=0")
        terms = el.direction_terms(where, direction)
        if any(dof == "rz" for dof, _ in terms):
            raise ValueError(f"{where}: direction={direction!r} is not a normal; use 'ux', 'uy' or a vector (dx, dy)")
        e = _number(where, "restitution", restitution, ">=0")
        if e > 1.0:
            raise ValueError(f"{where}: restitution={restitution!r} must lie in [0, 1] (Newton's coefficient: "
                             "0 perfectly plastic, 1 elastic)")
        _parts(self)["contacts"].append(RigidContact(name, node, terms, _number(where, "gap", gap, ">=0"), e, mu,
                                                     on))
        self._names.add(name)

    def rigid_block(self, name, node, *, width, height, mass, J=None, base=None, g=STANDARD_GRAVITY,
                    restitution=0.0, mu=None, on=None) -> RigidBlock:
        """A rigid rectangular block rocking on its base corners, its centre of mass at ``node``.

        Adds the base-centre node ``base`` (default ``"<name>.base"``) at ``height / 2`` below
        ``node`` as the master of the block (its ``ux`` supported: the base cannot slide; ``uy`` and
        ``rz`` free), links ``node`` and the corners ``"<name>.left"``, ``"<name>.right"`` (at
        ``-+ width / 2`` on the base line) rigidly to it, puts ``mass`` and ``J`` on ``node``, a
        rigid contact with the ground (vertical, named after the corner) at each corner, and the
        second-order term of the weight (see :class:`RigidBlock`, ``docs/rocking.md``).

        Parameters
        ----------
        name : str;  node : the centre-of-mass node, defined, free (not supported, not a slave)
        width, height : ``2 b`` and ``2 h``, length, > 0
        mass : force time^2/length, > 0
        J : rotary inertia about the centre, force length time^2; None: the uniform rectangle's
            ``m (b^2 + h^2) / 3``
        base : id of the base-centre node to create, or None
        g : gravity of the weight's geometric stiffness ``-W h`` on the base's ``rz``
            (length/time^2, >= 0; the load of the weight itself is ``Structure.gravity(g)``); 0: none
        restitution : Newton's ``e`` of the corners' contacts, [0, 1] (default 0: Housner's impact,
            the angular momentum about the new corner conserved)
        mu : None (default): the base cannot slide (its ``ux`` supported); a number >= 0: the base is
            free and each corner has Coulomb friction ``mu`` (``method="moreau-jean"`` only): the block
            slides, rocks or both (a block with ``mu < b/h`` under a base acceleration above ``mu g``
            slides before it can rock)
        on : None (default): the block stands on the ground; a node ``f`` of the frame: on its floor
            at ``f`` (the base centre at ``f``: give ``node`` ``height / 2`` above it; the corners bear
            on points rigidly linked to ``f``, the base's ``ux`` tied to ``f``'s); the name of a rigid
            block ``L``: on ``L``'s top face (a stack; the base within ``L``'s width, the corners on
            points rigidly linked to ``L``'s base). The corners' contacts are then between the two
            bodies, the weight's second-order term that of a block on a moving base (:mod:`.stacks`)

        Returns
        -------
        RigidBlock
        """
        where = self._label("rigid_block", name)
        self._node(where, "node", node)
        if mu is not None:
            mu = _number(where, "mu", mu, ">=0")
        b = _number(where, "width", width, ">0") / 2
        h = _number(where, "height", height, ">0") / 2
        m = _number(where, "mass", mass, ">0")
        J = m * (b * b + h * h) / 3.0 if J is None else _number(where, "J", J, ">=0")
        g = _number(where, "g", g, ">=0")
        below = None if on is None else stacks.support(self, where, name, node, on, b=b, h=h)
        stacks.check_centre(self, where, name, node)
        base = f"{name}.base" if base is None else base
        corners = (f"{name}.left", f"{name}.right")
        x, y = (float(c) for c in self._coords[node])
        self.node(base, x, y - h)
        self.node(corners[0], x - b, y - h)
        self.node(corners[1], x + b, y - h)
        if mu is None and below is None:
            self.support(base, ux=True, uy=False, rz=False)
        for slave in (node, *corners):
            self.rigid_link(base, slave)
        seat, bearings = (None, (None, None)) if below is None else stacks.seat(
            self, name, base, corners, *below, tie=mu is None)
        self.mass(node, m, J=J)
        self._names.add(name)
        for corner, bearing in zip(corners, bearings):
            self.contact(corner, corner, on=bearing, direction="uy", restitution=restitution, mu=mu)
        block = RigidBlock(name, node, base, corners, b, h, m, J, g, on, seat)
        _parts(self)["blocks"][name] = block
        return block


# ---------------------------------------------------------------------- assembly
def exempt_dofs(frame, dofs) -> set:
    """The free DOFs ``(node, dof)`` the rigid contacts move: no element need stiffen them (their
    mass and the contacts hold them). Raises where rigid contacts are not available (with a
    foundation on a soil medium, with P-Delta)."""
    contacts = _parts(frame)["contacts"] if "_rigid" in frame.__dict__ else []
    if not contacts:
        return set()
    if frame._foundations:
        raise ValueError("contact/rigid_block: rigid contacts together with a foundation on a soil medium are not "
                         "available")
    if frame._p_delta is not None:
        raise ValueError("contact/rigid_block: p_delta with rigid contacts is not available (the static axial "
                         "forces need the structure held; a rigid block has its own second-order term, g)")
    out = set()
    for contact in contacts:
        out |= {dofs.free[i] for i in _column(contact, dofs).indices}
        for axis in contact.tangent_axes if contact.mu else ():
            out |= {dofs.free[i] for i in _column(contact, dofs, axis).indices}
    return out


def attach(frame, structure):
    """``structure`` with the :class:`RigidPart` of ``frame`` (a ``RigidStructure``: a subclass with
    the field ``rigid`` whose ``to_model`` appends the rigid contacts), or ``structure`` itself
    without rigid contacts."""
    parts = frame.__dict__.get("_rigid")
    if not parts or not parts["contacts"]:
        return structure
    dofs = structure.dofs
    contacts = tuple(parts["contacts"])
    N = sp.hstack([_column(c, dofs).T for c in contacts], format="csr")
    for j, c in enumerate(contacts):
        _check_column(c, N[:, j], dofs)
    terms = [(dofs.index(block.base, dof), value) for block in parts["blocks"].values() if block.g
             for dof, value in block.geometric_terms()]       # a block's rz; a box's rx, ry (rigid3d.py)
    terms += stacks.carried_terms(frame, parts["blocks"], dofs)  # the weights a block or floor carries
    rows, vals = [r for r, _ in terms], [v for _, v in terms]
    geometric = sp.csr_matrix((vals, (rows, rows)), shape=(dofs.n, dofs.n))
    axes = max(len(c.tangent_axes) for c in contacts)            # 1 (2-D) or 2 (3-D: t1, t2)
    Tt = tuple(sp.hstack([_column(c, dofs, c.tangent_axes[a]).T if c.mu else sp.csr_matrix((dofs.n, 1))
                          for c in contacts], format="csr") for a in range(axes))
    part = RigidPart(contacts, N, np.array([c.gap for c in contacts]), geometric, dict(parts["blocks"]),
                     Tt[0] if axes == 1 else Tt)
    values = {f.name: getattr(structure, f.name) for f in dataclasses.fields(structure)}
    return _with_rigid(type(structure))(**values, rigid=part)


@functools.lru_cache(maxsize=None)
def _with_rigid(base):
    """The subclass of the structure class ``base`` with the field ``rigid`` (a :class:`RigidPart`)."""
    def to_model(self):
        """The :class:`~unilateral.Model` with the rigid contacts after the frame's own unknowns
        (:mod:`unilateral.structure.rigid`)."""
        return _model(self, self.rigid)

    doc = (f"A built frame with rigid contacts: :class:`{base.__name__}` and ``rigid``, the "
           ":class:`~unilateral.structure.rigid.RigidPart` (contacts, blocks), whose unknowns follow the "
           "frame's own in the model (not among ``constraint_names``).")
    name = f"Rigid{base.__name__}"
    cls = dataclasses.make_dataclass(name, [("rigid", object, None)], bases=(base,), frozen=True, eq=False,
                                     namespace={"to_model": to_model, "__doc__": doc, "__module__": __name__})
    globals()[name] = cls                       # found by its name: a built structure pickles
    return cls


def _check_column(contact, column, dofs) -> None:
    """Raise if the contact's column ``column`` (n, 1) is zero, or if it bears on a node ``on`` held
    along the normal (a support: that is the ground, whose reactions would miss the force)."""
    held = [dof for dof, _ in contact.terms if (contact.on, dof) in dofs._restrained]
    if contact.on is not None and held:
        raise ValueError(f"contact {contact.name!r}: node on={contact.on!r} is supported ({', '.join(held)}): it is "
                         "the ground; give on=None")
    root = lambda node: dofs.masters.get(node, node)
    if contact.on is not None and root(contact.node) == root(contact.on):
        raise ValueError(f"contact {contact.name!r}: nodes {contact.node!r} and on={contact.on!r} are rigidly linked "
                         f"together (one body, master {root(contact.on)!r}): they cannot move apart")
    if column.nnz == 0:
        if contact.on is not None:
            raise ValueError(f"contact {contact.name!r}: nodes {contact.node!r} and on={contact.on!r} cannot move "
                             "apart along the normal (rigidly linked together, or supported)")
        raise ValueError(f"contact {contact.name!r}: node {contact.node!r} cannot move along the normal (supported); "
                         "the contact would act on nothing")


def ties(frame) -> dict:
    """The ties of :class:`~unilateral.structure.dofs.DofMap` the rigid blocks need (the bases of
    blocks standing on a floor or on a block: their ``ux`` tied to the point under them)."""
    return dict(stacks.ties(frame))


def _column(contact, dofs, terms=None) -> sp.csr_matrix:
    """``(T^T (e_d(node) - e_d(on)))^T`` (1, n) of a contact: its normal (or the direction
    ``terms``) on the free DOFs, relative to the node ``on`` if it bears on one."""
    row = sp.csr_matrix((1, dofs.n))
    for dof, d in contact.terms if terms is None else terms:
        row = row + d * dofs.T[dofs.full_index(contact.node, dof)]
        if contact.on is not None:
            row = row - d * dofs.T[dofs.full_index(contact.on, dof)]
    row = sp.csr_matrix(row)
    row.eliminate_zeros()
    return row


def _model(structure, part):
    """The Model of the frame's own elements with the rigid contacts appended (see the module)."""
    return contact_model(structure, part, M=structure.M, C=structure.C, dof_names=structure.dofs.names)


def contact_model(structure, part, *, M, C, dof_names, T=None):
    """The Model of ``structure``'s elements (its natural form) with the rigid contacts of ``part``
    appended: the columns ``N`` with ``H = 0``, ``g = -gap``, the family
    :class:`~unilateral.constraints.RigidContact`; ``K = G E G^T`` plus the blocks' second-order terms
    (singular or indefinite, see the module).

    Parameters
    ----------
    structure : the built frame (its ``natural`` form, ``families()``, ``constraint_names``)
    part : RigidPart
    M, C : (n, n) mass and damping on the model's DOFs (C None: none)
    dof_names : the n names of the model's DOFs
    T : (n_structure, n) csr or None, a reduction ``u_structure = T u`` of the structure's DOFs (the
        ties of ``unilateral.opensees``); None: the structure's own DOFs
    """
    from ..constraints import RigidContact as RigidFamily
    from ..model import Model

    def reduced(X):
        return sp.csr_matrix(X if T is None else T.T @ X)

    nat = structure.natural
    m, mr = structure.m, len(part.contacts)
    G, E, B = reduced(nat.G), sp.csr_matrix(nat.E), sp.csr_matrix(nat.B)
    n = G.shape[0]
    GE = G @ E
    K = (GE @ G.T + (part.geometric if T is None else T.T @ part.geometric @ T)).tocsr()
    theta = nat.theta(0.0)
    F = sp.hstack([GE @ B, reduced(part.N)], format="csr").toarray()
    H = np.zeros((m + mr, m + mr))
    H[:m, :m] = nat.A + (B.T @ E @ B).toarray()
    g = np.concatenate([np.asarray(B.T @ (E @ theta)).ravel() + nat.r, -part.gap])
    F_v = H_v = None
    if nat.E_v is not None:
        GEv = G @ sp.csr_matrix(nat.E_v)
        C = GEv @ G.T if C is None else C + GEv @ G.T
        F_v = np.hstack([(GEv @ B).toarray(), np.zeros((n, mr))])
        H_v = np.zeros((m + mr, m + mr))
        H_v[:m, :m] = (B.T @ sp.csr_matrix(nat.E_v) @ B).toarray()
    mu = [c.mu for c in part.contacts]
    plane = isinstance(part.tangent, tuple)                  # 3-D: the axes t1, t2 and a polygonal cone
    tangent = (np.stack([reduced(t).toarray() for t in part.tangent], axis=2) if plane
               else reduced(part.tangent).toarray()) if any(mu) else None
    families = list(structure.families()) + [RigidFamily(
        np.arange(m, m + mr), name="rigid contact", restitution=[c.restitution for c in part.contacts], mu=mu,
        tangent=tangent, facets=[c.facets for c in part.contacts] if plane and any(mu) else None)]
    # K may be singular or indefinite (see the module): the Model is built on a placeholder and then
    # given K, as Structure.to_model does with P-Delta's geometric stiffness
    model = Model(M=M, K=sp.identity(n, format="csr"), F=F, H=H, C=C, g=g, F_v=F_v, H_v=H_v,
                  q_imposed=np.asarray(GE @ theta).ravel(), dof_names=list(dof_names),
                  constraint_names=list(structure.constraint_names) + list(part.names), families=families)
    model.K = K
    return model


# ---------------------------------------------------------------------- loads and results
def ground_motion(structure, a_g, direction="ux") -> tuple:
    """The term ``(-T^T M_full r_full, a_g)`` of a ground acceleration ``a_g(t)`` along ``direction``.

    ``r_full`` is 1 on the ``direction`` of every node, supported or slave (``Structure.gravity``
    with a unit acceleration along it): a block's centre, a slave of its base whose ``ux`` is
    supported, gets its inertia force ``-m a_g`` at the height ``h``, i.e. the moment ``m h a_g``
    on the base's ``rz``. (``Structure.ground_motion`` is 1 on the free DOFs only, which is 0 for
    a block.) For a :class:`~unilateral.loads.LoadHistory`: ``LoadHistory(st.gravity(), [term])``.
    """
    if direction not in ("ux", "uy"):
        raise ValueError(f"direction={direction!r} is not valid for a ground motion; valid: 'ux', 'uy'")
    if not callable(a_g):
        raise TypeError(f"a_g must be a time function a_g(t), got {a_g!r}")
    unit = (1.0, 0.0) if direction == "ux" else (0.0, 1.0)
    return -structure.gravity(1.0, unit), a_g


def initial_forces(model, u0, q0, udot0=None, *, tol=1e-12) -> np.ndarray:
    """Contact forces ``v0`` (m,) consistent with the initial state ``(u0, udot0)`` under the load
    ``q0`` (n,), for ``initial={"u0": u0, "udot0": udot0, "v0": v0}``.

    The rigid contacts that touch (opening and its rate within ``tol`` of the model's scale) carry
    the forces of the acceleration-level LCP ``w = N_A^T u0'' >= 0, v_A >= 0, w^T v_A = 0`` with
    ``M u0'' = q0 - K u0 - C udot0 + F v``; the other unknowns those of
    :func:`~unilateral.initial.given_state` (``u`` held). Without it the rigid contacts start at
    ``v0 = 0`` and the first step's acceleration is that of a free fall, an ``O(dt)`` error of the
    trapezoidal rule and BDF2 (the forces are taken at ``t = 0`` by their history terms).

    Parameters
    ----------
    model : Model with rigid contacts (:class:`~unilateral.constraints.RigidContact` family); ``M``
        invertible (every free DOF with mass)
    u0, q0 : (n,) displacements (length) and load (force);  udot0 : (n,) or None (at rest)
    tol : relative tolerance of a touching contact

    Returns
    -------
    v0 : (m,)
    """
    from ..constraints import RigidContact as RigidFamily
    from ..initial import given_state, static_lcp
    from ..lcp import get_lcp_solver
    from ..linalg import dense

    u0 = np.asarray(u0, dtype=float)
    udot0 = np.zeros_like(u0) if udot0 is None else np.asarray(udot0, dtype=float)
    v0 = given_state(model, {"u0": u0, "udot0": udot0}).v.copy()
    rigid_idx = np.concatenate([f.indices for f in model.families if isinstance(f, RigidFamily)] or [[]])
    rigid_idx = rigid_idx.astype(int)
    F, M = dense(model.F), dense(model.M)
    N = F[:, rigid_idx]
    opening = N.T @ u0 - model.g(0.0)[rigid_idx]
    rate = N.T @ udot0
    scale = 1.0 + float(np.max(np.abs(u0), initial=0.0))
    touching = rigid_idx[(np.abs(opening) <= tol * scale) & (np.abs(rate) <= tol * (1.0 + np.abs(udot0).max()))]
    v0[rigid_idx] = 0.0
    if touching.size == 0:
        return v0
    f = np.asarray(q0, dtype=float) - model.K @ u0 + F @ v0 - model.damping() @ udot0
    NA = F[:, touching]
    X = _accelerations(M, dense(model.K), np.column_stack([np.asarray(f).ravel(), NA]))
    v, _, message = static_lcp(NA.T @ X[:, 1:], -(NA.T @ X[:, 0]), get_lcp_solver("bpp"))
    if message:
        raise ValueError("initial_forces: no contact forces hold the initial state: " + message)
    v0[touching] = v
    return v0


def _accelerations(M, K, R) -> np.ndarray:
    """``u''`` (n, k) of the forces ``R`` (n, k): ``M^-1 R`` on the DOFs with mass, the DOFs without
    (a massless rotation of a beam's end) following by the static condensation
    ``u0'' = -K00^-1 K0m um''`` (a force on a massless DOF is refused)."""
    mass = np.diag(M) > 0
    if mass.all():
        return np.linalg.solve(M, R)
    if np.abs(R[~mass, 1:]).max(initial=0.0) > 0:
        raise ValueError("initial_forces: a rigid contact acts on a DOF without mass; give the contact node mass")
    out = np.zeros_like(R)
    out[mass] = np.linalg.solve(M[np.ix_(mass, mass)], R[mass])
    out[~mass] = -np.linalg.solve(K[np.ix_(~mass, ~mass)], K[np.ix_(~mass, mass)] @ out[mass])
    return out


def _block_2d(structure, name) -> RigidBlock:
    """The 2-D block ``name``; ``TypeError`` for a 3-D box (its results: :mod:`.rigid3d`)."""
    block = structure.rigid.blocks[name]
    if not isinstance(block, RigidBlock):
        raise TypeError(f"{name!r} is a 3-D rigid box: use unilateral.structure.rigid3d.box_tilts, box_energy "
                        "or unilateral.analysis.rigid.block_results")
    return block


def block_rotation(structure, sol, name) -> np.ndarray:
    """History (N+1,) of the rotation ``rz`` (rad, counter-clockwise) of the block ``name``."""
    block = _block_2d(structure, name)
    return structure.node_displacement(sol, block.base, "rz")


def block_energy(structure, sol, name) -> np.ndarray:
    """Mechanical energy (N+1,) of the block ``name`` in the linearised model, force length:
    ``m uy'^2 / 2 + (J + m h^2) theta'^2 / 2 - W h theta^2 / 2 + W uy`` (``uy``, ``theta`` of the
    base node; constant while the block pivots on a corner or flies, lost at the impacts)."""
    block = _block_2d(structure, name)
    T = structure.dofs.T
    rows = [T[structure.dofs.full_index(block.base, dof)] for dof in ("uy", "rz")]
    (uy, th), (vy, om) = ([np.asarray(r @ x.T).ravel() for r in rows] for x in (sol.u, sol.udot))
    m, h, W = block.mass, block.h, block.W
    return 0.5 * m * vy ** 2 + 0.5 * (block.J + m * h * h) * om ** 2 - 0.5 * W * h * th ** 2 + W * uy


def impacts(structure, sol, name) -> list[dict]:
    """The impacts of the block ``name``: the sign changes of its rotation.

    Each impact is a dict with ``step`` (the first step past the crossing), ``time`` (the crossing:
    from the closed-form pivoting motion of the step before, :meth:`RigidBlock.tilt`'s equation,
    if one corner carried the block then, else by linear interpolation; s), and ``ratio``, the
    measured ratio of the angular velocities after/before, ``sqrt(E_after / E_before)`` with
    :func:`block_energy` at the extremes of the tilt before and after the impact (the energy of a
    pivoting phase is ``I0 omega^2 / 2`` at ``theta = 0``); ``nan`` if no extreme follows.
    Housner's value is :attr:`RigidBlock.restitution`.
    """
    block = _block_2d(structure, name)
    theta = block_rotation(structure, sol, name)
    omega = np.asarray(structure.dofs.T[structure.dofs.full_index(block.base, "rz")] @ sol.udot.T).ravel()
    energy = block_energy(structure, sol, name)
    s = np.sign(theta)
    steps = np.flatnonzero((s[1:] * s[:-1] < 0) | ((s[1:] == 0) & (s[:-1] != 0))) + 1
    extremes = np.flatnonzero(np.sign(omega[1:]) * np.sign(omega[:-1]) < 0) + 1     # omega changes sign
    contacts = [sol.constraint_names.index(c) for c in block.corners] if sol.constraint_names else []
    out = []
    for k in steps:
        before = extremes[extremes < k]
        after = extremes[extremes > k]
        e0 = energy[before[-1]] if before.size else energy[0]
        ratio = math.sqrt(energy[after[0]] / e0) if after.size and e0 > 0 and energy[after[0]] >= 0 else math.nan
        dt = sol.t[k] - sol.t[k - 1]
        pivoting = contacts and np.count_nonzero(sol.v[k - 1, contacts] > 0) == 1
        tau = (_pivot_crossing(block, abs(theta[k - 1]), -abs(omega[k - 1]), 2 * dt) if pivoting
               else theta[k - 1] / (theta[k - 1] - theta[k]) * dt)
        out.append({"step": int(k), "time": float(sol.t[k - 1] + tau), "ratio": ratio})
    return out


def _pivot_crossing(block, phi, phidot, span) -> float:
    """Time ``tau`` in ``(0, span]`` at which the pivoting tilt ``phi + ...`` reaches 0: the root of
    ``a + (phi - a) cosh(p tau) + phidot / p sinh(p tau)``, ``a = b / h`` (bisection to round-off)."""
    a, p = block.b / block.h, block.p
    f = lambda tau: a + (phi - a) * math.cosh(p * tau) + phidot / p * math.sinh(p * tau)
    lo, hi = 0.0, span
    if f(hi) > 0:
        return span
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (mid, hi) if f(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


def _number(where, arg, value, bound) -> float:
    """``float(value)``, finite, ``> 0`` (``">0"``) or ``>= 0`` (``">=0"``)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{where}: {arg} must be a real number, got {value!r}")
    x = float(value)
    if not math.isfinite(x) or (bound == ">0" and x <= 0) or (bound == ">=0" and x < 0):
        raise ValueError(f"{where}: {arg}={value!r} must be finite and {bound[:-1]} 0")
    return x
