"""Natural strains and stiffnesses of 2-D frame elements.

Every element has ``k`` natural strains, each a linear combination of the nodal DOFs
``(ux, uy, rz)`` of its end nodes, ``e = a u_elem``, and natural stresses (Liolios 1990, eqs. 1-4)

    sigma = E (e - B v - theta) + E_v (e' - B v')

``ux``, ``uy`` are displacements along global x and y, ``rz`` the counter-clockwise rotation.
Strain conventions (checked in ``tests/test_structure.py``):

- beam ``i -> j`` (length L, unit chord ``(c, s)``): ``[elongation, rz_i - beta, rz_j - beta]``,
  ``beta = (-s (ux_j - ux_i) + c (uy_j - uy_i)) / L`` the chord rotation (counter-clockwise);
  ``E = [[EA/L, 0, 0], [0, 4EI/L, 2EI/L], [0, 2EI/L, 4EI/L]]``; stresses: axial force (tension
  positive) and the end moments acting on the element (counter-clockwise positive).
- bar and cable: ``[elongation]``, ``E = [[EA/L]]``, axial force tension positive.
- spring, dashpot, soil, gap, yield link and slider ("directional" elements between an end ``i``
  and an end ``j``, either of which may be the ground): ``[d . (u_j - u_i)]`` for a unit direction
  ``d`` (or the relative rotation for ``"rz"``): the extension of the element, positive when ``j``
  moves away from ``i`` along ``d``; force tension positive. A contact with friction adds the
  tangential strain ``t . (u_j - u_i)``, ``t`` the direction ``d`` turned 90 degrees clockwise
  (``t = x`` for ``d = y``), and the tangential force ``T`` along ``t``.

**Constraint unknowns.** An element carries any number of :class:`Unknown` s, each a column of
``B``: a strain row of the element, its ``B`` entry ``b`` (+1 or -1; a facet of a polygonal
friction cone in 3-D: the facet's direction cosines, one entry on each tangential strain, the
second in :attr:`Unknown.extra`), its resistance ``r`` and its
family (``"contact"``, ``"yield"`` or ``"friction"``, :mod:`unilateral.constraints`); the element's
``A`` couples its unknowns (kinematic hardening). With ``psi = B^T sigma - A v - r``:

- a contact (soil, gap: ``b = +1``, ``v`` = separation; cable: ``b = -1``, ``v`` = slack
  shortening) carries compression (a cable: tension) and at most the force ``r``;
- a yield pair (``"name.plastic+"``, ``b = +1``, ``r = F_t``; ``"name.plastic-"``, ``b = -1``,
  ``r = F_c``) on one strain keeps its force in ``-F_c <= sigma <= F_t``; ``v`` are the cumulative
  plastic multipliers, the plastic strain is ``v+ - v-``; a soil contact with a bearing capacity
  ``Q`` has its compression face alone (``"name.plastic-"``, ``r = Q``, :func:`bearing_unknown`),
  whose multiplier is the plastic settlement;
- a slip pair (``"name.slip+"``, ``"name.slip-"``) on a tangential strain keeps
  ``|T| <= mu N``, ``N`` the compression of its contact ``"name"`` (or a constant ``N`` in ``r``);
- a facet of a polygonal friction cone (3-D, :func:`.elements3d.frictional`) keeps
  ``d_k . T <= mu N`` for its unit direction ``d_k`` in the tangent plane: its column has the
  entries ``d_k`` on the two tangential strains (``row``, ``b`` and one ``extra`` entry).
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass, replace

import numpy as np

_hypot = np.hypot                           # not math.hypot: the same rounding as before

DOF_NAMES = ("ux", "uy", "rz")
#: Elements between two ends along a direction (either end may be the ground).
DIRECTIONAL_KINDS = ("spring", "dashpot", "soil", "gap", "yield", "slider")
#: The families of constraint unknowns (:mod:`unilateral.constraints`).
UNKNOWN_KINDS = ("contact", "yield", "friction")


@dataclass(frozen=True)
class Unknown:
    """One constraint unknown of an element: a column of ``B`` and its law.

    Attributes
    ----------
    name : str
        The constraint's name (``"soil3"``, ``"soil3.slip+"``, ``"brace.plastic-"``).
    row : int
        The element's strain (row of ``Element.a``) the unknown enters, with ``B`` entry ``b``:
        its primary strain (:attr:`Structure.constraint_strains
        <unilateral.structure.Structure.constraint_strains>`, the force reported for the unknown).
    b : float
        +1 or -1; a facet of a polygon (a friction cone, :func:`.elements3d.frictional`, or a 3-D
        hinge's interaction polygon, :func:`.elements3d.hinge`): the component of its unit normal
        on ``row`` (the larger in magnitude of its two).
    r : float
        Resistance, >= 0 [force, or force length for a rotation]: a contact's capacity, a yield
        force or moment, a slider's ``mu N``.
    kind : str
        ``"contact"``, ``"yield"`` or ``"friction"``: the family of the unknown.
    normal : str or None
        Friction: the name of the contact whose compression ``N`` bounds the slip (``|T| <= mu N``);
        None: the normal force is constant, in ``r``.
    mu : float
        Friction coefficient, >= 0.
    node : node id or None
        Where the unknown acts, for reports (None: the element's nodes).
    k : float or None
        Elastic stiffness in series with the multiplier [force/length, or force length/rad for a
        rotation]: a yield link's or a hinge spring's ``k``, a slider's or a friction contact's
        stick stiffness. The yield deformation of a face is ``r / k``. None: rigid-plastic (a
        hinge without ``k``), or a contact.
    extra : tuple of (int, float) pairs
        Further ``(row, b)`` entries of the unknown's column of ``B`` on other strains of the
        element (default none: one entry, ``(row, b)``): a facet of a polygonal friction cone
        enters both tangential strains, ``(t1 row, cos th_k)`` and ``(t2 row, sin th_k)``.
    """

    name: str
    row: int
    b: float
    r: float = 0.0
    kind: str = "contact"
    normal: str | None = None
    mu: float = 0.0
    node: Hashable | None = None
    k: float | None = None
    extra: tuple = ()

    @property
    def entries(self) -> tuple[tuple[int, float], ...]:
        """Every ``(row, b)`` entry of the unknown's column of ``B``: ``(row, b)`` first, then
        :attr:`extra`."""
        return ((self.row, self.b), *self.extra)


@dataclass(frozen=True)
class Element:
    """One element in natural form.

    Attributes
    ----------
    name : str
    kind : str
        ``"beam"``, ``"bar"``, ``"cable"``, ``"spring"``, ``"dashpot"``, ``"soil"``, ``"gap"``,
        ``"yield"`` (yield link) or ``"slider"``.
    dofs : tuple of (node, dof) pairs, length d
        The nodal DOFs the strains depend on (``dof`` in ``"ux"``, ``"uy"``, ``"rz"``).
    a : (k, d) ndarray
        Natural strains ``e = a u_elem`` of the DOFs ``dofs``.
    E : (k, k) ndarray
        Stiffness (for a dashpot: its viscosity, assembled into the damping matrix C).
    theta : (k,) ndarray
        Imposed strains (thermal strain, initial gap, slack).
    E_v : (k, k) ndarray or None
        Viscosity of a Kelvin element (dashpot in parallel with the spring, in series with the
        contact), or None.
    unknowns : tuple of Unknown
        The constraint unknowns the element carries (none for a bilateral element).
    A : (u, u) ndarray or None
        Interaction of the element's ``u`` unknowns (kinematic hardening); None: zero.
    """

    name: str
    kind: str
    dofs: tuple
    a: np.ndarray
    E: np.ndarray
    theta: np.ndarray
    E_v: np.ndarray | None = None
    unknowns: tuple = ()
    A: np.ndarray | None = None

    @property
    def unilateral(self) -> bool:
        """Every strain of the element passes through an unknown (soil, gap, cable, yield link,
        slider): its force is the constraint's, so it takes no stiffness-proportional damping.
        A beam with a plastic hinge is not unilateral."""
        return bool(self.unknowns) and ({row for u in self.unknowns for row, _ in u.entries}
                                    == set(range(self.E.shape[0])))

    @property
    def interaction(self) -> np.ndarray:
        """``A`` (u, u) of the element's unknowns (zero without hardening)."""
        u = len(self.unknowns)
        return np.zeros((u, u)) if self.A is None else self.A

    @property
    def strain_labels(self) -> tuple[str, ...]:
        """Names of the natural strains, e.g. ``("col.axial", "col.rot_i", "col.rot_j")``."""
        if self.kind == "beam":
            name = self.name
            return (f"{name}.axial", f"{name}.rot_i", f"{name}.rot_j")
        return (self.name, f"{self.name}.tangential")[: self.E.shape[0]]


def contact_unknown(name, r=0.0) -> Unknown:
    """``Unknown(name, 0, 1.0, r)``: the contact of a directional element's strain, made without the
    frozen dataclass's ``__setattr__`` per field (the same fields, defaults and object)."""
    unknown = object.__new__(Unknown)
    unknown.__dict__.update(name=name, row=0, b=1.0, r=r, kind="contact", normal=None, mu=0.0, node=None, k=None,
                            extra=())
    return unknown


def bearing_unknown(name, Q, k) -> Unknown:
    """The plastic settlement ``"name.plastic-"`` of a soil contact with the bearing capacity ``Q``
    [force]: a one-sided yield face on the contact's strain (row 0, ``b = -1``, ``r = Q``, the
    spring ``k`` [force/length] in series), ``psi = -sigma - Q <= 0``; its multiplier ``w`` [length]
    only grows (:class:`~unilateral.constraints.Bearing`) and enters the strain as ``+w``: the force
    ``sigma = k (e - v + w - theta)``."""
    return Unknown(f"{name}.plastic-", 0, -1.0, Q, "yield", None, 0.0, None, k)


def with_bearing(element, name, Q) -> Element:
    """The soil contact ``element`` with the bearing capacity ``Q`` [force] on its strain (row 0):
    the settlement :func:`bearing_unknown` after its unknowns, uncoupled (``A`` padded with zeros)."""
    n = len(element.unknowns)
    A = None
    if element.A is not None:
        A = np.zeros((n + 1, n + 1))
        A[:n, :n] = element.A
    return replace(element, unknowns=element.unknowns + (bearing_unknown(name, Q, float(element.E[0, 0])),), A=A)


def _element(name, kind, dofs, a, E, theta, *, E_v=None, unknowns=(), A=None) -> Element:
    """``Element(name, kind, dofs, a, E, theta, E_v, unknowns, A)``, made without the frozen
    dataclass's ``__setattr__`` per field (the builder makes thousands): the same fields, defaults
    and object."""
    element = object.__new__(Element)
    element.__dict__.update(name=name, kind=kind, dofs=dofs, a=a, E=E, theta=theta, E_v=E_v, unknowns=unknowns, A=A)
    return element


def chord(where: str, i: Hashable, xi: np.ndarray, j: Hashable, xj: np.ndarray):
    """Length and unit vector of the chord from node ``i`` at ``xi`` to node ``j`` at ``xj``.

    Raises ``ValueError`` for a zero-length chord.
    """
    L, c, s = _chord(where, i, xi, j, xj)
    return L, np.array([c, s])


def _chord(where, i, xi, j, xj) -> tuple[float, float, float]:
    """``(L, c, s)`` of :func:`chord` as floats (the same numbers, without the arrays). ``where`` may
    be a pair ``(kind, name)``, made the text ``"kind 'name'"`` only for a message."""
    dx, dy = float(xj[0]) - float(xi[0]), float(xj[1]) - float(xi[1])
    L = abs(dx) if dy == 0.0 else abs(dy) if dx == 0.0 else float(_hypot(dx, dy))   # hypot(x, 0) = |x| exactly
    if L == 0.0:
        if type(where) is tuple:
            where = f"{where[0]} {where[1]!r}"
        raise ValueError(
            f"{where}: nodes i={i!r} and j={j!r} are both at ({xi[0]:g}, {xi[1]:g}): "
            "zero-length element"
        )
    return L, dx / L, dy / L


def beam(name, i, xi, j, xj, *, E, A, I, axial_strain=0.0, curvature=0.0) -> Element:
    """Euler-Bernoulli beam-column ``i -> j``.

    Parameters
    ----------
    xi, xj : (2,) node coordinates
    E, A, I : Young's modulus, cross-section area and second moment of area (> 0)
    axial_strain : imposed (e.g. thermal) axial strain; imposed elongation ``axial_strain * L``
    curvature : imposed curvature ``w''`` (positive: concave towards the left of ``i -> j``);
        imposed end rotations relative to the chord ``(-curvature L/2, +curvature L/2)``
    """
    L, c, s = _chord(("beam", name), i, xi, j, xj)
    dofs = ((i, "ux"), (i, "uy"), (i, "rz"), (j, "ux"), (j, "uy"), (j, "rz"))
    numbers = np.array(beam_numbers(L, c, s, E, A, I, axial_strain=axial_strain, curvature=curvature))
    a, stiffness, theta = numbers[:18], numbers[18:27], numbers[27:]
    a.shape, stiffness.shape = (3, 6), (3, 3)                      # (views of numbers, as reshape's)
    return _element(name, "beam", dofs, a, stiffness, theta)


def beam_numbers(L, c, s, E, A, I, *, axial_strain, curvature) -> tuple:
    """The 30 numbers of a beam of length ``L`` and unit chord ``(c, s)``: ``a`` (3, 6), the
    stiffness (3, 3) and ``theta`` (3,), row after row; of floats (one beam, :func:`beam`) or of
    arrays (one entry per beam, :func:`unilateral.structure.bulk.add_beams`), the same arithmetic."""
    bs, bc = s / L, c / L                   # beta = [bs, -bc, 0, -bs, bc, 0] . u_elem
    EA, EI = E * A, E * I
    k4, k2 = 4 * EI / L, 2 * EI / L
    return (-c, -s, 0.0, c, s, 0.0,                                          # a (3, 6)
            0.0 - bs, 0.0 + bc, 1.0, 0.0 + bs, 0.0 - bc, 0.0,
            0.0 - bs, 0.0 + bc, 0.0, 0.0 + bs, 0.0 - bc, 1.0,
            EA / L, 0.0, 0.0, 0.0, k4, k2, 0.0, k2, k4,                      # stiffness (3, 3)
            axial_strain * L, -curvature * L / 2, curvature * L / 2)         # theta (3,)


def bar(name, i, xi, j, xj, *, E, A, axial_strain=0.0) -> Element:
    """Axial bar ``i -> j``: strain = elongation, stiffness ``EA/L``; ``axial_strain`` imposed."""
    L, dofs, a = _axial("bar", name, i, xi, j, xj)
    return Element(name, "bar", dofs, a, np.array([[E * A / L]]), np.array([axial_strain * L]))


def cable(name, i, xi, j, xj, *, E, A, slack=0.0, capacity=0.0) -> Element:
    """Tension-only cable ``i -> j``: a bar with one contact ``b = -1`` (``v`` = slack shortening),
    ``theta = slack`` and ``r = capacity`` (the compression it carries before going slack)."""
    L, dofs, a = _axial("cable", name, i, xi, j, xj)
    return Element(name, "cable", dofs, a, np.array([[E * A / L]]), np.array([slack]),
                   unknowns=(Unknown(name, 0, -1.0, capacity),))


def _axial(kind, name, i, xi, j, xj):
    """Length, DOFs and elongation row ``(1, 4)`` of an axial member ``i -> j``."""
    L, c, s = _chord(f"{kind} {name!r}", i, xi, j, xj)
    dofs = ((i, "ux"), (i, "uy"), (j, "ux"), (j, "uy"))
    return L, dofs, np.array([[-c, -s, c, s]])


def directional(name, kind, i, j, terms, k, *, c=0.0, theta=0.0, unknowns=(), A=None,
                dof_names=DOF_NAMES) -> Element:
    """Element of the relative motion ``d . (u_j - u_i)`` of two ends (``None`` = ground).

    Parameters
    ----------
    terms : tuple of (dof, coefficient) pairs
        The direction ``d`` (see :func:`direction_terms`).
    k : stiffness (for a dashpot: its viscosity)
    c : viscosity of a Kelvin dashpot in parallel with ``k`` (0: none)
    theta : imposed strain
    unknowns, A : the constraint unknowns on the strain (row 0) and their interaction (see :class:`Element`)
    dof_names : the nodal DOFs, in order (default the 2-D ones; a 3-D element: those of
        :mod:`.elements3d`)
    """
    dofs, a = _relative(i, j, (terms,), dof_names)
    E_v = np.array([[c]]) if c > 0 else None
    return _element(name, kind, dofs, a, np.array([[k]]), np.array([theta]), E_v=E_v, unknowns=tuple(unknowns), A=A)


#: The smallest stick stiffness ``kt`` of a friction contact relative to its normal stiffness ``k``:
#: below it the friction rows of the step LCP (scale ``kt``) are lost to round-off beside the normal
#: row (scale ``k``) and the contact sticks or slips at random (``kt = 1e-8 k`` gave a wrong response).
STICK_STIFFNESS_MIN_RATIO = 1e-10


def check_stick_stiffness(name, kind, k, kt) -> None:
    """Refuse a stick stiffness ``kt`` too small beside the normal stiffness ``k`` to be carried.

    Raises
    ------
    ValueError
        Naming the contact, ``kt``, ``k`` and the smallest ``kt`` that is valid.
    """
    if kt < STICK_STIFFNESS_MIN_RATIO * k:
        raise ValueError(
            f"{kind} {name!r}: kt = {kt!r} is below {STICK_STIFFNESS_MIN_RATIO:g} times the normal stiffness "
            f"k = {k!r}; double precision cannot carry the friction beside the contact. Give kt >= "
            f"{STICK_STIFFNESS_MIN_RATIO * k:.6g}, or leave mu out for a frictionless contact")


#: The largest clearance of a contact (soil, gap) relative to the size of its frame (the span of
#: the node coordinates). A clearance is the paper's imposed strain ``theta = -gap``: an open contact
#: carries ``v = e + gap``, and the structure sees ``F (v - gap)``, so its response moves by about
#: ``eps gap k / K`` (eps = 2.2e-16) whether or not the gap ever closes (measured on the pounding
#: example: 5e-12 m at gap 1e3 m, 5e-9 m at 1e6 m, 1.5 m at 1e15 m, against 0.025 m of response).
CLEARANCE_MAX_RATIO = 10.0
#: The size given to a frame whose nodes are all at the origin (no length of its own), length: its
#: clearances are refused above 1e5 length units (a round-off of 2.2e-11 units times k/K).
POINT_FRAME_SIZE = 1e4


def clearance_bound(coords) -> tuple[float, str]:
    """``(bound, size)``: the largest clearance a frame with the nodes ``coords`` carries
    (:data:`CLEARANCE_MAX_RATIO` times the span of the node coordinates; for nodes that all coincide,
    their largest coordinate, or at the origin :data:`POINT_FRAME_SIZE`), and the size it is of, in words."""
    points = np.array(list(coords.values()), dtype=float).reshape(len(coords), -1) if coords else np.zeros((1, 2))
    span = float(np.max(points.max(axis=0) - points.min(axis=0)))
    largest = float(np.abs(points).max())
    size, basis = ((span, "the span of its nodes") if span > 0 else
                   (largest, "its nodes' largest coordinate") if largest > 0 else
                   (POINT_FRAME_SIZE, "a frame whose nodes are all at the origin"))
    return CLEARANCE_MAX_RATIO * size, f"{size:.6g}, {basis}"


def check_clearances(elements, coords):
    """``elements``, checked: refuse a contact clearance that double precision cannot carry beside
    the frame's size.

    Parameters
    ----------
    elements : the frame's elements (those with an imposed strain on a contact's strain are checked)
    coords : dict node -> coordinates (2,) or (3,), length

    Raises
    ------
    ValueError
        Naming the element, its ``gap``, the frame's size and the largest ``gap`` that is valid
        (:func:`clearance_bound`).
    """
    bound, size = clearance_bound(coords)
    for e in elements:
        if e.kind not in ("soil", "gap", "cable"):
            continue
        what, gap = ("slack", float(e.theta[0])) if e.kind == "cable" else ("gap", -float(e.theta[0]))
        if abs(gap) > bound:
            raise ValueError(
                f"{e.kind} {e.name!r}: {what} = {gap!r} exceeds {CLEARANCE_MAX_RATIO:g} times the size of the frame "
                f"({size}): a clearance is an imposed strain that an open contact "
                f"cancels (v = e + gap), and double precision carries the response only to about 2.2e-16 * gap; "
                f"give |{what}| <= {bound:.6g}, or leave the element out if it never closes")
    return elements


#: The largest friction coefficient of a contact element (soil, gap). A friction row of the step
#: LCP is ``psi_slip + mu psi_normal``: it adds ``mu`` times the contact's row, so the round-off of the
#: contact row (its scale ``k`` times the opening) reaches the tangential force ``mu`` times over.
#: An open gap must carry no tangential force; measured on the pounding example (kt = 1e5 kN/m,
#: direct): 1e-11 kN at mu = 1, 1.5e-10 at mu = 10, 1.5e-9 at 100, 2.7e-5 kN (cq) at 1e4 and a
#: positive slip function, and on a frame of two columns the step LCP fails at mu = 100.
FRICTION_MU_MAX = 10.0


def check_friction_coefficient(name, kind, mu) -> None:
    """Refuse a friction coefficient ``mu`` above :data:`FRICTION_MU_MAX` on a contact element.

    Raises
    ------
    ValueError
        Naming the contact, ``mu`` and the largest ``mu`` that is valid.
    """
    if mu > FRICTION_MU_MAX:
        raise ValueError(
            f"{kind} {name!r}: mu = {mu!r} is above {FRICTION_MU_MAX:g}: the friction rows of the step LCP add mu "
            "times the contact row, whose round-off then gives an open contact a tangential force and the "
            "step LCP an ill-conditioned matrix (docs/theory.md, section 13); friction coefficients of "
            f"real interfaces are below about 2. Give mu <= {FRICTION_MU_MAX:g}")


def frictional(name, kind, i, j, terms, *, k, kt, mu, c=0.0, ct=0.0, theta=0.0, capacity=0.0) -> Element:
    """A contact along ``d`` (``terms``) with Coulomb friction along ``t``, ``d`` turned clockwise.

    Strains ``[d . (u_j - u_i), t . (u_j - u_i)]``, stiffness ``diag(k, kt)`` [force/length],
    Kelvin viscosity ``diag(c, ct)`` [force time/length]; unknowns: the contact ``name`` (row 0,
    ``b = +1``, capacity ``r``) and the slips ``name.slip+``, ``name.slip-`` (row 1, friction
    coefficient ``mu`` on the compression of ``name``).
    """
    check_stick_stiffness(name, kind, k, kt)
    check_friction_coefficient(name, kind, mu)
    dofs, a = _relative(i, j, (terms, tangent_terms(f"{kind} {name!r}", terms)))
    E_v = np.diag([c, ct]) if c > 0 or ct > 0 else None
    unknowns = (Unknown(name, 0, 1.0, capacity), *pair(name, 1, "friction", normal=name, mu=mu, k=kt))
    return Element(name, kind, dofs, a, np.diag([k, kt]), np.array([theta, 0.0]), E_v=E_v, unknowns=unknowns)


def pair(name, row, kind, *, r=(0.0, 0.0), normal=None, mu=0.0, node=None, k=None) -> tuple[Unknown, Unknown]:
    """The two unknowns (``b = +1``, ``b = -1``) of a two-sided yield surface or a slip on strain ``row``.

    Named ``name.plastic+``/``name.plastic-`` (``kind="yield"``) or ``name.slip+``/``name.slip-``
    (``kind="friction"``); ``r`` = (positive, negative) resistance, e.g. ``(F_t, F_c)``; ``k`` the
    elastic stiffness in series (see :class:`Unknown`).
    """
    suffix = "plastic" if kind == "yield" else "slip"
    return tuple(Unknown(f"{name}.{suffix}{sign}", row, b, resistance, kind, normal, mu, node, k)
                 for sign, b, resistance in (("+", 1.0, r[0]), ("-", -1.0, r[1])))


def kinematic_hardening(modulus) -> np.ndarray:
    """``A`` (2, 2) of a yield pair with linear kinematic hardening ``modulus`` (force per unit of
    the pair's strain: force/length, or force length/rad for a rotation):
    ``psi+- = +-(sigma - modulus (v+ - v-)) - r+-``."""
    return modulus * np.array([[1.0, -1.0], [-1.0, 1.0]])


def hinge(beam_element, name, end, *, My, k=None, modulus=0.0) -> Element:
    """``beam_element`` with a plastic hinge at ``end`` (``"i"`` or ``"j"``).

    The plastic rotation ``v+ - v-`` enters the end rotation (``rot_i`` or ``rot_j``) as an
    imposed strain; the yield pair ``name.plastic+-`` keeps the end moment in ``-My <= M <= My``
    [force length]. With ``k`` [force length/rad] an elastic rotational spring lies in series:
    its flexibility ``1/k`` is added to the beam's on that rotation (the spring's massless inner
    node condensed out), so the beam's stiffness becomes ``(E^-1 + e e^T / k)^-1``.
    ``modulus`` [force length/rad] is the kinematic hardening of the pair.
    """
    row = END_ROWS[end]
    E = beam_element.E if k is None else in_series(beam_element.E, (row,), k)
    unknowns = pair(name, row, "yield", r=(My, My), node=end_node(beam_element, end), k=k)
    return _with_unknowns(beam_element, E, unknowns, kinematic_hardening(modulus))


#: The strain row of the end rotation of a 2-D beam at each end (:func:`beam`).
END_ROWS = {"i": 1, "j": 2}


def end_node(beam_element, end):
    """The node at the end ``end`` of a 2-D beam."""
    return beam_element.dofs[0 if end == "i" else 3][0]


def in_series(E, rows, k) -> np.ndarray:
    """The stiffness ``(E^-1 + sum_row e_row e_row^T / k)^-1`` (symmetrised) of an element ``E`` with an
    elastic spring ``k`` in series on each strain of ``rows``: the springs' massless inner nodes
    condensed out."""
    flexibility = np.linalg.inv(E)
    for row in rows:
        flexibility[row, row] += 1.0 / k
    E = np.linalg.inv(flexibility)
    return 0.5 * (E + E.T)


def _with_unknowns(beam_element, E, unknowns, A) -> Element:
    """``beam_element`` with the stiffness ``E`` and the further ``unknowns``, coupled by ``A``."""
    n, u = len(beam_element.unknowns), len(unknowns)
    full = np.zeros((n + u, n + u))
    full[:n, :n] = beam_element.interaction
    full[n:, n:] = A
    return replace(beam_element, E=E, unknowns=beam_element.unknowns + tuple(unknowns), A=full)


def backbone_hinge(beam_element, name, end, *, K, k, theta_plus, theta_minus) -> Element:
    """``beam_element`` with a hinge at ``end`` whose moment-rotation law is a convex multi-linear
    backbone: elastic-perfectly-plastic springs in parallel (:func:`.hinge_laws.backbone_springs`).

    Parameters
    ----------
    K : the hinge's initial stiffness [force length/rad]: the sum of the springs' and of an elastic
        spring ``K - sum(k)`` (the slope beyond the backbone's last point)
    k : (n,) the springs' stiffnesses, > 0
    theta_plus, theta_minus : (n,) their yield rotations in the two senses, > 0

    The parallel springs, of rotation ``theta`` (the hinge's) and plastic rotations ``p_s``, carry
    ``M = K theta - sum_s k_s p_s = K (theta - sum_s q_s)``: one spring ``K`` in series with the beam
    (as :func:`hinge` with ``k = K``) whose plastic rotation is ``sum_s q_s``, ``q_s = k_s p_s / K``.
    Spring ``s`` yields when ``|k_s (theta - p_s)| = k_s theta_s``; divided by ``k_s / K`` its yield
    function is ``+-(M - alpha_s) - K theta_s`` with the back moment ``alpha_s = (K^2/k_s) q_s - K
    sum_t q_t``. Its pair ``name.plastic+-`` (the first spring), ``name.plastic<s>+-`` (``s`` = 2,
    3, ...) has ``b = +-1`` on the end rotation, ``r = K theta_s``, multipliers ``q_s+-`` (rad), and
    ``A = K (diag(K/k) - 1 1^T)`` on the pairs' net multipliers: positive semidefinite (Cauchy-Schwarz,
    ``sum k_s <= K``), singular only without the elastic spring, along ``q ~ k`` (every spring flows).
    """
    row = END_ROWS[end]
    unknowns, A = backbone_pairs(name, row, end_node(beam_element, end), K=K, k=k, theta_plus=theta_plus,
                                 theta_minus=theta_minus)
    return _with_unknowns(beam_element, in_series(beam_element.E, (row,), K), unknowns, A)


def backbone_pairs(name, row, node, *, K, k, theta_plus, theta_minus) -> tuple[list, np.ndarray]:
    """The yield pairs (2 n unknowns) on strain ``row`` of a spring ``K`` whose law is the convex
    multi-linear backbone of the parallel springs ``k`` (n,) yielding at the deformations
    ``theta_plus``, ``theta_minus`` (n,) (:func:`backbone_hinge`, where the algebra is), and their
    interaction ``A`` (2 n, 2 n): ``name.plastic+-``, ``name.plastic2+-``, ... with ``r = K theta_s``."""
    unknowns = []
    for s, (r_plus, r_minus) in enumerate(zip(K * np.asarray(theta_plus), K * np.asarray(theta_minus))):
        tag = "" if s == 0 else str(s + 1)
        unknowns += [Unknown(f"{name}.plastic{tag}+", row, 1.0, float(r_plus), "yield", None, 0.0, node, K),
                     Unknown(f"{name}.plastic{tag}-", row, -1.0, float(r_minus), "yield", None, 0.0, node, K)]
    net = K * (np.diag(K / np.asarray(k, dtype=float)) - 1.0)
    return unknowns, np.kron(net, kinematic_hardening(1.0))


def polygon_hinge(beam_element, name, node, rows, polygon, moduli) -> Element:
    """``beam_element`` with a rigid-plastic hinge bounding the stresses of two of its strains,
    ``s = (sigma[rows[0]], sigma[rows[1]])``, by a convex polygon (the axial force and an end moment
    of a 2-D beam; the two end moments of a 3-D beam).

    Parameters
    ----------
    node : the node at the hinge, for reports
    rows : the two strain rows
    polygon : (n (N, 2), r (N,))
        The unit outward normals on ``s`` and the resistances of the ``N`` facets (even; facet
        ``k + N/2`` never active with facet ``k``: opposite, or not adjacent)
    moduli : (2,) kinematic hardening moduli on the two strains

    Facet ``k`` is an unknown ``name.facet<k>`` of the ``"yield"`` family whose column of ``B`` is
    ``n_k`` on ``rows`` (the primary entry on the larger in magnitude, the first row on a tie, the
    other in ``extra`` unless it is 0): ``psi_k = n_k . (s - alpha) - r_k``, the plastic strains
    ``sum_k lambda_k n_k`` (associated flow) imposed on the two strains, the back stress ``alpha =
    diag(moduli)`` times them (``A_kj = n_k^T diag(moduli) n_j``). The unknowns come in the pairs
    ``(k, k + N/2)``, in that order (those of :class:`~unilateral.constraints.Yield`).
    """
    normals, resistances = polygon
    half = len(normals) // 2
    order = [f for p in range(half) for f in (p, p + half)]
    unknowns = []
    for f in order:
        (n0, n1) = normals[f]
        (row, b), (other, b2) = (((rows[0], n0), (rows[1], n1)) if abs(n0) >= abs(n1)
                                 else ((rows[1], n1), (rows[0], n0)))
        unknowns.append(Unknown(f"{name}.facet{f}", row, float(b), float(resistances[f]), "yield", None, 0.0, node,
                                None, ((other, float(b2)),) if b2 != 0.0 else ()))
    ordered = np.asarray(normals)[order]
    return _with_unknowns(beam_element, beam_element.E, unknowns,
                          ordered @ np.diag(np.asarray(moduli, dtype=float)) @ ordered.T)


def _relative(i, j, directions, dof_names=DOF_NAMES):
    """DOFs and strain rows ``(len(directions), d)`` of the motions ``dir . (u_j - u_i)``
    (``directions``: the ``(dof, coefficient)`` pairs of each direction; ``None`` = ground; the
    DOFs in the order of ``dof_names``, the 2-D or the 3-D ones)."""
    if len(directions) == 1 and len(directions[0]) == 1 and directions[0][0][0] in dof_names:
        (dof, x), = directions[0]            # one DOF (a spring or a contact along "uy"): the same rows
        if i is None and j is not None:
            return ((j, dof),), np.array([[1.0 * x]])
        if i is not None and j is not None:
            return ((i, dof), (j, dof)), np.array([[-1.0 * x, 1.0 * x]])
    ends = [(node, sign) for node, sign in ((i, -1.0), (j, 1.0)) if node is not None]
    names = [dof for dof in dof_names if any(dof == d for terms in directions for d, _ in terms)]
    dofs = tuple((node, dof) for node, _ in ends for dof in names)
    a = np.array([[sign * dict(terms).get(dof, 0.0) for _, sign in ends for dof in names] for terms in directions])
    return dofs, a


def tangent_terms(where: str, terms) -> tuple[tuple[str, float], ...]:
    """``(dof, coefficient)`` pairs of ``t``, the direction ``terms`` turned 90 degrees clockwise.

    ``t = (d_y, -d_x)``: ``"ux"`` for ``d = "uy"``, ``-uy`` for ``d = "ux"``; ``(t, d)`` is oriented
    as ``(x, y)``. Raises ``ValueError`` for a rotation (``"rz"``), which has no tangent.
    """
    d = dict(terms)
    if "rz" in d:
        raise ValueError(f"{where}: friction (mu) needs a translational direction ('ux', 'uy' or a vector), "
                         "not 'rz'")
    dx, dy = d.get("ux", 0.0), d.get("uy", 0.0)
    return tuple((dof, x) for dof, x in (("ux", dy), ("uy", -dx)) if x != 0.0)


def direction_terms(where: str, direction, dof_names=DOF_NAMES, axes=("dx", "dy")) -> tuple[tuple[str, float], ...]:
    """``(dof, coefficient)`` pairs of the motion along ``direction``.

    Parameters
    ----------
    direction : one of ``dof_names`` or a vector of the translations of ``dof_names``
        (``"ux"``, ``"uy"``, ...): in 2-D ``"ux"``, ``"uy"``, ``"rz"`` or ``(dx, dy)``. A vector is
        normalised to unit length.
    dof_names : the nodal DOFs (default the 2-D ones, :data:`DOF_NAMES`; in 3-D those of
        :mod:`.elements3d`)
    axes : the names of a vector's components in the message of a bad vector (see :func:`vector`)
    """
    if type(direction) is str and direction in dof_names:
        return ((direction, 1.0),)
    translations = tuple(dof for dof in dof_names if dof.startswith("u"))
    choices = f"{', '.join(map(repr, dof_names))} or a vector ({', '.join('d' + dof[1:] for dof in translations)})"
    if isinstance(direction, str):
        if direction not in dof_names:
            raise ValueError(f"{where}: direction={direction!r} is not valid; use {choices}")
        return ((direction, 1.0),)
    try:
        d = vector(where, "direction", direction, axes)
    except TypeError:
        raise TypeError(f"{where}: direction must be {choices}, got {direction!r}") from None
    d = unit(d)
    return tuple((dof, float(x)) for dof, x in zip(translations, d) if x != 0.0)


def length(d) -> float:
    """The Euclidean length of a finite vector without overflow or underflow (like :func:`math.hypot`).

    The components are scaled by the largest ``|d_i|`` before they are squared: ``[1e200, 1e200, 0]``
    has the length ``1.414e200`` (not ``inf``), ``[1e-200, 0]`` the length ``1e-200`` (not 0).

    Parameters
    ----------
    d : (k,) array_like of finite floats

    Returns
    -------
    float
    """
    d = np.asarray(d, dtype=float)
    big = float(np.max(np.abs(d), initial=0.0))
    if big == 0.0 or not np.isfinite(big):
        return big
    return big * float(np.sqrt(np.sum((d / big) ** 2)))


def unit(d) -> np.ndarray:
    """``d / |d|`` for a finite nonzero vector, scaled by its largest component first (no overflow).

    Every direction of the structure code (element directions, ``vecxz``, tangents, gravity,
    ground motions) is normalised here.

    Parameters
    ----------
    d : (k,) array_like, finite and nonzero (as :func:`vector` checks)

    Returns
    -------
    (k,) ndarray of unit length

    Raises
    ------
    ValueError
        If ``d`` is zero or not finite.
    """
    d = np.asarray(d, dtype=float)
    big = float(np.max(np.abs(d), initial=0.0))
    if big == 0.0 or not np.isfinite(big):
        raise ValueError(f"direction {tuple(map(float, d))} must be a finite nonzero vector")
    d = d / big
    return d / float(np.sqrt(np.sum(d * d)))


def vector(where: str, arg: str, value, axes=("dx", "dy")) -> np.ndarray:
    """``value`` as a finite nonzero vector of ``len(axes)`` components (named ``axes`` in the
    messages); ``TypeError`` if it is not a vector, ``ValueError`` naming ``arg`` if it is not finite
    and nonzero or not of that size."""
    shape = f"({', '.join(axes)})"
    try:
        d = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{where}: {arg} must be a vector {shape}, got {value!r}") from None
    if d.shape != (len(axes),) or not np.all(np.isfinite(d)) or not d.any():
        raise ValueError(f"{where}: {arg}={value!r} must be a finite nonzero vector {shape}")
    return d
