"""Natural strains and stiffnesses of 3-D frame elements (the 3-D analogue of :mod:`.elements`).

Every node has six nodal DOFs ``(ux, uy, uz, rx, ry, rz)``: displacements along the global axes
x, y, z and rotations about them (right-hand rule: ``rz`` turns x towards y, ``rx`` y towards z,
``ry`` z towards x). The elements are :class:`~unilateral.structure.elements.Element` objects, with
the strain conventions of :mod:`.elements`:

- beam ``i -> j`` (:func:`beam`, kind ``"beam3d"``), length L, local axes ``x'`` (the unit chord
  ``i -> j``), ``y'``, ``z'`` (:func:`local_axes`): six strains ``[elongation, twist, rotz_i,
  rotz_j, roty_i, roty_j]``, with ``twist = x' . (theta_j - theta_i)``, ``rotz_* = z' . theta_* -
  beta_z``, ``beta_z = y' . (u_j - u_i) / L`` the chord rotation about ``z'`` and ``roty_* = y' .
  theta_* - beta_y``, ``beta_y = -z' . (u_j - u_i) / L`` the chord rotation about ``y'``
  (``theta`` the rotation vector ``(rx, ry, rz)``, ``u`` the displacement ``(ux, uy, uz)``);
  ``E = diag(EA/L, GJ/L, EIz/L [[4, 2], [2, 4]], EIy/L [[4, 2], [2, 4]])``. Stresses: the axial
  force (tension positive), the torque at ``j`` about ``x'`` and the end moments acting on the
  element about ``z'`` and ``y'`` (right-hand positive). For a beam in the x-y plane with
  ``vecxz = z`` the strains ``[elongation, rotz_i, rotz_j]`` are those of the 2-D beam. A plastic
  hinge at an end (:func:`hinge`) bounds the end moments ``(M_y', M_z')`` (the stresses ``roty``,
  ``rotz`` of that end) by a convex polygon (:func:`hinge_polygon`), one yield unknown per facet.
- bar and cable: ``[elongation]`` along the chord, ``E = [[EA/L]]``, tension positive.
- directional elements (spring, dashpot, soil, gap) between an end ``i`` and an end ``j``
  (either may be the ground): ``[d . (u_j - u_i)]`` for a direction ``d``
  (:func:`.elements.direction_terms` with the 3-D :data:`DOF_NAMES` and :data:`AXES`): a unit
  vector ``(dx, dy, dz)`` or one of the six DOF names (a rotation for ``"rx"``, ``"ry"``, ``"rz"``):
  the extension, positive when ``j`` moves away from ``i`` along ``d``; they are the 2-D
  :func:`.elements.directional` elements on the 3-D DOFs (``dof_names=DOF_NAMES``). A contact with
  friction (:func:`frictional`) adds the tangential strains ``t1 . (u_j - u_i)`` and
  ``t2 . (u_j - u_i)`` along its tangent axes (:func:`tangents`) and their forces ``T1``, ``T2``,
  bounded by a polygonal friction cone of ``N`` facets (:func:`facet_directions`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .elements import Element, Unknown, _relative, check_friction_coefficient, check_stick_stiffness, length, unit
from .elements import vector as _vector

DOF_NAMES = ("ux", "uy", "uz", "rx", "ry", "rz")
TRANSLATIONS = DOF_NAMES[:3]
ROTATIONS = DOF_NAMES[3:]
#: The components of a vector, in messages (:func:`vector`).
AXES = ("x", "y", "z")
#: Sine of the angle below which ``vecxz`` counts as parallel to a beam's axis.
PARALLEL = 1e-6


@dataclass(frozen=True)
class Beam3D(Element):
    """A 3-D beam in natural form (six strains, see :func:`beam`)."""

    @property
    def strain_labels(self) -> tuple[str, ...]:
        """``("b.axial", "b.twist", "b.rotz_i", "b.rotz_j", "b.roty_i", "b.roty_j")``."""
        return tuple(f"{self.name}.{s}" for s in ("axial", "twist", "rotz_i", "rotz_j", "roty_i", "roty_j"))


def chord(where: str, i, xi, j, xj):
    """Length and unit vector (3,) of the chord from node ``i`` at ``xi`` to node ``j`` at ``xj``.

    Raises ``ValueError`` for a zero-length chord.
    """
    d = np.asarray(xj, dtype=float) - np.asarray(xi, dtype=float)
    L = length(d)
    if L == 0.0:
        x, y, z = xi
        raise ValueError(f"{where}: nodes i={i!r} and j={j!r} are both at ({x:g}, {y:g}, {z:g}): "
                         "zero-length element")
    return L, d / L


def vector(where: str, arg: str, value) -> np.ndarray:
    """``value`` as a finite nonzero (3,) vector; ``TypeError``/``ValueError`` naming ``arg``."""
    return _vector(where, arg, value, AXES)


def local_axes(where: str, i, xi, j, xj, vecxz=None):
    """Length ``L`` and the rotation ``R`` (3, 3) whose rows are the local axes ``x', y', z'``.

    The convention of OpenSees's ``geomTransf``: ``x'`` is the unit chord ``i -> j``, ``vecxz``
    any vector in the local ``x'-z'`` plane, ``y' = vecxz x x' / |vecxz x x'|`` and
    ``z' = x' x y'``. ``vecxz=None``: global Z, or global X for a member parallel to Z (then
    ``y' = -Y``, ``z' = X``). Raises ``ValueError`` if ``vecxz`` is parallel to the member.
    """
    L, x = chord(where, i, xi, j, xj)
    if vecxz is None:
        vecxz = (1.0, 0.0, 0.0) if np.linalg.norm(np.cross((0.0, 0.0, 1.0), x)) < PARALLEL else (0.0, 0.0, 1.0)
    given = vector(where, "vecxz", vecxz)
    v = unit(given)
    y = np.cross(v, x)
    if np.linalg.norm(y) < PARALLEL:
        raise ValueError(f"{where}: vecxz={tuple(map(float, given))} is parallel to the member axis {i!r} -> {j!r} "
                         f"{tuple(np.round(x, 12))}; give a vector of the local x-z plane that is not along "
                         "the member")
    y /= np.linalg.norm(y)
    return L, np.vstack([x, y, np.cross(x, y)])


def beam(name, i, xi, j, xj, *, E, A, Iy, Iz, G, J, vecxz=None, axial_strain=0.0) -> Beam3D:
    """Euler-Bernoulli beam-column ``i -> j`` without shear deformation.

    Parameters
    ----------
    xi, xj : (3,) node coordinates
    E, A : Young's modulus and area;  Iy, Iz : second moments of area about ``y'`` and ``z'``;
    G, J : shear modulus and torsion constant (all > 0)
    vecxz : (3,) vector in the local ``x'-z'`` plane, or None (see :func:`local_axes`)
    axial_strain : imposed (e.g. thermal) axial strain; imposed elongation ``axial_strain * L``
    """
    L, (x, y, z) = local_axes(f"beam {name!r}", i, xi, j, xj, vecxz)
    dofs = tuple((node, dof) for node in (i, j) for dof in DOF_NAMES)
    zero = np.zeros(3)
    beta_z = np.concatenate([-y, zero, y, zero]) / L
    beta_y = np.concatenate([z, zero, -z, zero]) / L
    a = np.vstack([np.concatenate([-x, zero, x, zero]), np.concatenate([zero, -x, zero, x]),
                   np.concatenate([zero, z, zero, zero]) - beta_z, np.concatenate([zero, zero, zero, z]) - beta_z,
                   np.concatenate([zero, y, zero, zero]) - beta_y, np.concatenate([zero, zero, zero, y]) - beta_y])
    bending = np.array([[4.0, 2.0], [2.0, 4.0]]) / L
    stiffness = np.zeros((6, 6))
    stiffness[0, 0], stiffness[1, 1] = E * A / L, G * J / L
    stiffness[2:4, 2:4], stiffness[4:6, 4:6] = E * Iz * bending, E * Iy * bending
    theta = np.array([axial_strain * L, 0.0, 0.0, 0.0, 0.0, 0.0])
    return Beam3D(name, "beam3d", dofs, a, stiffness, theta)


def axial(kind, name, i, xi, j, xj, *, E, A, theta=0.0, unknowns=()) -> Element:
    """Bar (``kind="bar"``) or cable ``i -> j``: strain = elongation along the chord, stiffness
    ``EA/L``, imposed strain ``theta`` (an elongation, length), constraint ``unknowns``."""
    L, d = chord(f"{kind} {name!r}", i, xi, j, xj)
    dofs = tuple((node, dof) for node in (i, j) for dof in TRANSLATIONS)
    return Element(name, kind, dofs, np.concatenate([-d, d])[None, :], np.array([[E * A / L]]),
                   np.array([theta]), unknowns=tuple(unknowns))


def cable(name, i, xi, j, xj, *, E, A, slack=0.0, capacity=0.0) -> Element:
    """Tension-only cable ``i -> j``: a bar with one contact ``b = -1`` (``v`` = slack shortening),
    ``theta = slack`` and ``r = capacity``, as :func:`unilateral.structure.elements.cable`."""
    return axial("cable", name, i, xi, j, xj, E=E, A=A, theta=slack, unknowns=(Unknown(name, 0, -1.0, capacity),))


@dataclass(frozen=True)
class FrictionContact(Element):
    """A contact with Coulomb friction in its tangent plane (three strains, see :func:`frictional`)."""

    @property
    def strain_labels(self) -> tuple[str, ...]:
        """``("s", "s.tangential", "s.tangential2")``: along ``d``, ``t1`` and ``t2``."""
        return (self.name, f"{self.name}.tangential", f"{self.name}.tangential2")


def tangents(where: str, terms, tangent=None) -> tuple[np.ndarray, np.ndarray]:
    """The tangent axes ``t1``, ``t2`` (3,) of a contact along the unit direction ``terms``.

    ``t1``: ``tangent`` (default global X, or global Y for a contact along X) without its component
    along ``d``, normalised; ``t2 = d x t1``, so that ``(t1, t2, d)`` is right-handed (``d = z``:
    ``t1 = x``, ``t2 = y``). Raises ``ValueError`` if ``tangent`` is along ``d``.
    """
    d = np.array([dict(terms).get(dof, 0.0) for dof in TRANSLATIONS])
    if tangent is None:
        tangent = (0.0, 1.0, 0.0) if np.linalg.norm(np.cross((1.0, 0.0, 0.0), d)) < PARALLEL else (1.0, 0.0, 0.0)
    given = vector(where, "tangent", tangent)
    t = unit(given)
    t1 = t - (t @ d) * d
    if np.linalg.norm(t1) < PARALLEL:
        raise ValueError(f"{where}: tangent={tuple(map(float, given))} is along the contact's direction; give a vector "
                         "of its tangent plane")
    t1 /= np.linalg.norm(t1)
    return t1, np.cross(d, t1)


def facet_directions(facets: int) -> np.ndarray:
    """The unit outward normals ``d_k = (cos th_k, sin th_k)`` (facets, 2) of a polygonal friction
    cone with ``facets`` facets, on the tangent axes ``(t1, t2)``: ``th_k = 2 pi k / facets``.

    Facet 0 is normal to ``t1``; for an even ``facets`` facet ``k + facets/2`` is opposite to facet
    ``k``. Components within 1e-12 of 0 or +-1 are made exact (``facets=4``: the axes ``+-t1``,
    ``+-t2`` exactly).
    """
    th = 2.0 * np.pi * np.arange(facets) / facets
    d = np.column_stack([np.cos(th), np.sin(th)])
    d[np.abs(d) < 1e-12] = 0.0
    unit = np.abs(np.abs(d) - 1.0) < 1e-12
    d[unit] = np.sign(d[unit])
    return d


def facet_unknowns(name, facets, *, mu, k, rows=(1, 2)) -> tuple[Unknown, ...]:
    """The slip multipliers of the ``facets`` facets (even, >= 4) of a polygonal friction cone.

    Facet ``k`` (direction ``d_k``, :func:`facet_directions`) is an unknown of the
    ``"friction"`` family on the compression of the contact ``name`` with coefficient ``mu``:
    its column of ``B`` is ``cos th_k`` on the strain ``rows[0]`` (along ``t1``) and ``sin th_k`` on
    ``rows[1]`` (along ``t2``): the primary entry (``row``, ``b``) on the larger of the two in
    magnitude (``t1`` on a tie), the other in ``extra`` (left out when it is 0). Its friction
    function is ``d_k . T - mu N`` (the step law's ``psi + mu psi_normal``).

    The unknowns come in opposite pairs ``(k, k + facets/2)``, ``k = 0 .. facets/2 - 1``, in that
    order: the pairs of :class:`~unilateral.constraints.Friction` (their columns are opposite,
    never both active). Names: ``facets=4``: ``name.slip+``, ``name.slip-`` (``+-t1``),
    ``name.slip2+``, ``name.slip2-`` (``+-t2``), the four-sided pyramid; else ``name.facet<k>``.

    Any three facet columns are linearly dependent (they span the two tangential strains): a
    pivoting basis with three facets of one contact is singular; in a solution at most two
    adjacent facets slip (a vertex). The pivoting solvers keep opposite facets apart (the pairs)
    and at most two facets of a cone of more than four active (the cone's group, by its normal:
    :meth:`Friction.polygons <unilateral.constraints.Friction.polygons>`).
    """
    d = facet_directions(facets)
    half = facets // 2
    names = ({0: "slip+", 2: "slip-", 1: "slip2+", 3: "slip2-"} if facets == 4
             else {f: f"facet{f}" for f in range(facets)})
    out = []
    for f in (f for k in range(half) for f in (k, k + half)):
        (c, s) = d[f]
        (row, b), (other, b2) = ((rows[0], c), (rows[1], s)) if abs(c) >= abs(s) else ((rows[1], s), (rows[0], c))
        out.append(Unknown(f"{name}.{names[f]}", row, float(b), 0.0, "friction", name, mu, None, k,
                           ((other, float(b2)),) if b2 != 0.0 else ()))
    return tuple(out)


def frictional(name, kind, i, j, terms, axes, *, k, kt, mu, c=0.0, ct=0.0, theta=0.0, capacity=0.0, facets=4):
    """A contact along ``d`` (``terms``) with Coulomb friction in its tangent plane, on the axes
    ``axes = (t1, t2)`` (:func:`tangents`): a polygonal friction cone of ``facets`` facets.

    Strains ``[d . (u_j - u_i), t1 . (u_j - u_i), t2 . (u_j - u_i)]``, stiffness ``diag(k, kt, kt)``
    [force/length], Kelvin viscosity ``diag(c, ct, ct)``; unknowns: the contact ``name`` (row 0,
    ``b = +1``, capacity ``r``) and the slip multipliers ``lambda_k >= 0`` of the facets
    (:func:`facet_unknowns`): facet ``k`` keeps ``d_k . T <= mu N`` (``T = (T1, T2)`` the tangential
    force, ``N`` the compression of the contact ``name``) and slips by ``lambda_k d_k``. The polygon
    circumscribes Coulomb's circle ``|T| <= mu N`` (its facets touch it). ``facets=4`` is the
    four-sided pyramid: ``name.slip+``, ``name.slip-`` along ``t1`` (row 1) and ``name.slip2+``,
    ``name.slip2-`` along ``t2`` (row 2), ``|T1| <= mu N``, ``|T2| <= mu N``.
    """
    check_stick_stiffness(name, kind, k, kt)
    check_friction_coefficient(name, kind, mu)
    rows = (terms, *(tuple((dof, float(x)) for dof, x in zip(TRANSLATIONS, t) if x != 0.0) for t in axes))
    dofs, a = _relative(i, j, rows, DOF_NAMES)
    unknowns = (Unknown(name, 0, 1.0, capacity), *facet_unknowns(name, facets, mu=mu, k=kt))
    E_v = np.diag([c, ct, ct]) if c > 0 or ct > 0 else None
    return FrictionContact(name, kind, dofs, a, np.diag([k, kt, kt]), np.array([theta, 0.0, 0.0]), E_v=E_v,
                           unknowns=unknowns)


#: The shapes of the interaction polygon of a plastic hinge of a 3-D beam (:func:`hinge_polygon`).
HINGE_SHAPES = ("ellipse", "diamond", "box")
#: The strain rows ``(roty, rotz)`` of the end rotations of a 3-D beam at each end (:func:`beam`).
END_ROWS = {"i": (4, 2), "j": (5, 3)}


def hinge_polygon(shape, facets, My, Mz) -> tuple[np.ndarray, np.ndarray]:
    """The facets of the yield polygon of a plastic hinge in the plane of the end moments ``(M_y', M_z')``.

    Returns ``n`` (facets, 2), the unit outward normals of the facets on ``(M_y', M_z')``, and ``r``
    (facets,), their distances from the origin [force length]: facet ``k`` is ``n_k . M <= r_k``.
    In the normalised plane ``x = (M_y'/My, M_z'/Mz)`` facet ``k`` is ``g_k . x <= c_k``:

    - ``"ellipse"``: ``g_k = (cos th_k, sin th_k)``, ``th_k = 2 pi k / facets``, ``c_k = 1``
      (:func:`facet_directions`): the polygon circumscribing the unit circle (the ellipse
      ``(M_y'/My)^2 + (M_z'/Mz)^2 <= 1``), each facet tangent to it at ``x = g_k``;
    - ``"box"``: the ellipse's polygon with 4 facets, ``|M_y'| <= My``, ``|M_z'| <= Mz``;
    - ``"diamond"``: ``g_k = (+-1, +-1)`` at ``th_k = pi/4 + pi k/2``, ``c_k = 1``:
      ``|M_y'|/My + |M_z'|/Mz <= 1`` (inscribed in the ellipse: its vertices lie on it).

    For an even ``facets`` facet ``k + facets/2`` is opposite to facet ``k``. In moment space
    ``n_k = (g_k1/My, g_k2/Mz) / s_k`` and ``r_k = c_k / s_k``, ``s_k = |(g_k1/My, g_k2/Mz)|``.
    """
    if shape == "diamond":
        g = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])
    else:
        g = facet_directions(4 if shape == "box" else facets)
    scaled = g / np.array([My, Mz])
    s = np.linalg.norm(scaled, axis=1)
    return scaled / s[:, None], 1.0 / s


def hinge(beam_element, name, end, polygon, *, k=None, moduli=(0.0, 0.0)) -> Beam3D:
    """``beam_element`` (a 3-D beam, :func:`beam`) with a plastic hinge at ``end`` (``"i"`` or ``"j"``).

    Parameters
    ----------
    polygon : (n (N, 2), r (N,))
        The unit outward normals on ``(M_y', M_z')`` and the resistances [force length] of the ``N``
        facets (even; facet ``k + N/2`` opposite to facet ``k``), e.g. :func:`hinge_polygon`.
    k : float or None
        Rotational stiffness [force length/rad] of an elastic spring in series on both end
        rotations: the flexibility ``1/k`` is added on the rows ``roty`` and ``rotz`` of ``end``
        (the spring's massless inner node condensed out); None: rigid-plastic.
    moduli : (H_y, H_z)
        Kinematic hardening moduli [force length/rad] about ``y'`` and ``z'``.

    Facet ``k`` is an unknown ``name.facet<k>`` of the ``"yield"`` family whose column of ``B`` is
    ``n_k`` on the rows ``(roty, rotz)`` of ``end`` (the primary entry on the larger in magnitude,
    ``roty`` on a tie, the other in ``extra`` unless it is 0), resistance ``r_k``: its yield
    function is ``psi_k = n_k . (M - alpha) - r_k``, ``M = (M_y', M_z')`` the end moments, the
    plastic rotation ``theta_p = sum_k lambda_k n_k`` (rad, associated flow) an imposed strain on
    the two rows, and the back moment ``alpha = diag(H_y, H_z) theta_p`` (linear kinematic
    hardening: ``A_kj = n_k^T diag(H_y, H_z) n_j``, symmetric positive semidefinite). The unknowns
    come in opposite pairs ``(k, k + N/2)``, in that order (the pairs of
    :class:`~unilateral.constraints.Yield`, as :func:`facet_unknowns` orders friction facets).
    """
    normals, resistances = polygon
    rows = END_ROWS[end]
    E = beam_element.E
    if k is not None:
        flexibility = np.linalg.inv(E)
        for row in rows:
            flexibility[row, row] += 1.0 / k
        E = np.linalg.inv(flexibility)
        E = 0.5 * (E + E.T)
    node = beam_element.dofs[0 if end == "i" else 6][0]
    half = len(normals) // 2
    order = [f for p in range(half) for f in (p, p + half)]
    unknowns = []
    for f in order:
        (ny, nz) = normals[f]
        (row, b), (other, b2) = (((rows[0], ny), (rows[1], nz)) if abs(ny) >= abs(nz)
                                 else ((rows[1], nz), (rows[0], ny)))
        unknowns.append(Unknown(f"{name}.facet{f}", row, float(b), float(resistances[f]), "yield", None, 0.0, node,
                                k, ((other, float(b2)),) if b2 != 0.0 else ()))
    ordered = normals[order]
    n = len(beam_element.unknowns)
    A = np.zeros((n + len(order), n + len(order)))
    A[:n, :n] = beam_element.interaction
    A[n:, n:] = ordered @ np.diag(np.asarray(moduli, dtype=float)) @ ordered.T
    return replace(beam_element, E=E, unknowns=beam_element.unknowns + tuple(unknowns), A=A)
