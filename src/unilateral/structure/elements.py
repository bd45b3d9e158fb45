"""Natural strains and stiffnesses of 2-D frame elements.

Every element has ``k`` natural strains, each a linear combination of the nodal DOFs
``(ux, uy, rz)`` of its end nodes, ``e = a u_elem``, and natural stresses (Liolios 1990, eqs. 1-4)

    sigma = E (e - b v - theta) + E_v (e' - b v')

``ux``, ``uy`` are displacements along global x and y, ``rz`` the counter-clockwise rotation.
Strain conventions (checked in ``tests/test_structure.py``):

- beam ``i -> j`` (length L, unit chord ``(c, s)``): ``[elongation, rz_i - beta, rz_j - beta]``,
  ``beta = (-s (ux_j - ux_i) + c (uy_j - uy_i)) / L`` the chord rotation (counter-clockwise);
  ``E = [[EA/L, 0, 0], [0, 4EI/L, 2EI/L], [0, 2EI/L, 4EI/L]]``; stresses: axial force (tension
  positive) and the end moments acting on the element (counter-clockwise positive).
- bar and cable: ``[elongation]``, ``E = [[EA/L]]``, axial force tension positive.
- spring, dashpot, soil and gap ("directional" elements between an end ``i`` and an end ``j``,
  either of which may be the ground): ``[d . (u_j - u_i)]`` for a unit direction ``d`` (or the
  relative rotation for ``"rz"``): the extension of the element, positive when ``j`` moves away
  from ``i`` along ``d``; force tension positive.

Unilateral elements have one strain and ``b = +1`` (contacts: soil, gap; ``v`` = separation) or
``b = -1`` (cables; ``v`` = slack shortening). With ``psi = b sigma - r <= 0`` a contact carries
compression and at most the tension ``r``; a cable carries tension and at most the compression ``r``.
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass

import numpy as np

DOF_NAMES = ("ux", "uy", "rz")


@dataclass(frozen=True)
class Element:
    """One element in natural form.

    Attributes
    ----------
    name : str
    kind : str
        ``"beam"``, ``"bar"``, ``"cable"``, ``"spring"``, ``"dashpot"``, ``"soil"`` or ``"gap"``.
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
    b : float
        ``B`` entry of a unilateral element's single strain (+1 contact, -1 cable); 0 if bilateral.
    r : float
        Resistance (capacity) of a unilateral element, >= 0.
    """

    name: str
    kind: str
    dofs: tuple
    a: np.ndarray
    E: np.ndarray
    theta: np.ndarray
    E_v: np.ndarray | None = None
    b: float = 0.0
    r: float = 0.0

    @property
    def unilateral(self) -> bool:
        return self.b != 0.0

    @property
    def strain_labels(self) -> tuple[str, ...]:
        """Names of the natural strains, e.g. ``("col.axial", "col.rot_i", "col.rot_j")``."""
        if self.kind == "beam":
            return tuple(f"{self.name}.{s}" for s in ("axial", "rot_i", "rot_j"))
        return (self.name,)


def chord(where: str, i: Hashable, xi: np.ndarray, j: Hashable, xj: np.ndarray):
    """Length and unit vector of the chord from node ``i`` at ``xi`` to node ``j`` at ``xj``.

    Raises ``ValueError`` for a zero-length chord.
    """
    d = np.asarray(xj, dtype=float) - np.asarray(xi, dtype=float)
    L = float(np.hypot(d[0], d[1]))
    if L == 0.0:
        raise ValueError(
            f"{where}: nodes i={i!r} and j={j!r} are both at ({xi[0]:g}, {xi[1]:g}): "
            "zero-length element"
        )
    return L, d / L


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
    L, (c, s) = chord(f"beam {name!r}", i, xi, j, xj)
    dofs = tuple((node, dof) for node in (i, j) for dof in DOF_NAMES)
    axial = np.array([-c, -s, 0.0, c, s, 0.0])
    beta = np.array([s, -c, 0.0, -s, c, 0.0]) / L
    rot_i, rot_j = np.eye(6)[2], np.eye(6)[5]
    a = np.vstack([axial, rot_i - beta, rot_j - beta])
    EA, EI = E * A, E * I
    stiffness = np.array([[EA / L, 0.0, 0.0], [0.0, 4 * EI / L, 2 * EI / L], [0.0, 2 * EI / L, 4 * EI / L]])
    theta = np.array([axial_strain * L, -curvature * L / 2, curvature * L / 2])
    return Element(name, "beam", dofs, a, stiffness, theta)


def bar(name, i, xi, j, xj, *, E, A, axial_strain=0.0) -> Element:
    """Axial bar ``i -> j``: strain = elongation, stiffness ``EA/L``; ``axial_strain`` imposed."""
    L, dofs, a = _axial("bar", name, i, xi, j, xj)
    return Element(name, "bar", dofs, a, np.array([[E * A / L]]), np.array([axial_strain * L]))


def cable(name, i, xi, j, xj, *, E, A, slack=0.0, capacity=0.0) -> Element:
    """Tension-only cable ``i -> j``: a bar with ``b = -1`` (``v`` = slack shortening),
    ``theta = slack`` and ``r = capacity`` (the compression it carries before going slack)."""
    L, dofs, a = _axial("cable", name, i, xi, j, xj)
    return Element(name, "cable", dofs, a, np.array([[E * A / L]]), np.array([slack]), b=-1.0, r=capacity)


def _axial(kind, name, i, xi, j, xj):
    """Length, DOFs and elongation row ``(1, 4)`` of an axial member ``i -> j``."""
    L, (c, s) = chord(f"{kind} {name!r}", i, xi, j, xj)
    dofs = ((i, "ux"), (i, "uy"), (j, "ux"), (j, "uy"))
    return L, dofs, np.array([[-c, -s, c, s]])


def directional(name, kind, i, j, terms, k, *, c=0.0, theta=0.0, b=0.0, r=0.0) -> Element:
    """Element of the relative motion ``d . (u_j - u_i)`` of two ends (``None`` = ground).

    Parameters
    ----------
    terms : tuple of (dof, coefficient) pairs
        The direction ``d`` (see :func:`direction_terms`).
    k : stiffness (for a dashpot: its viscosity)
    c : viscosity of a Kelvin dashpot in parallel with ``k`` (0: none)
    theta, b, r : imposed strain, ``B`` entry and resistance (see :class:`Element`)
    """
    dofs, coef = [], []
    for node, sign in ((i, -1.0), (j, 1.0)):
        if node is not None:
            for dof, value in terms:
                dofs.append((node, dof))
                coef.append(sign * value)
    E_v = np.array([[c]]) if c > 0 else None
    return Element(name, kind, tuple(dofs), np.array([coef]), np.array([[k]]), np.array([theta]),
                   E_v=E_v, b=b, r=r)


def direction_terms(where: str, direction) -> tuple[tuple[str, float], ...]:
    """``(dof, coefficient)`` pairs of the motion along ``direction``.

    Parameters
    ----------
    direction : "ux", "uy", "rz" or (2,) vector
        A vector is normalised to unit length.
    """
    if isinstance(direction, str):
        if direction not in DOF_NAMES:
            raise ValueError(
                f"{where}: direction={direction!r} is not valid; use 'ux', 'uy', 'rz' or a vector (dx, dy)"
            )
        return ((direction, 1.0),)
    try:
        d = np.array(direction, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(
            f"{where}: direction must be 'ux', 'uy', 'rz' or a vector (dx, dy), got {direction!r}"
        ) from None
    if d.shape != (2,) or not np.all(np.isfinite(d)) or not d.any():
        raise ValueError(
            f"{where}: direction={direction!r} must be a finite nonzero vector (dx, dy)"
        )
    d = d / np.hypot(d[0], d[1])
    return tuple((dof, float(x)) for dof, x in zip(("ux", "uy"), d) if x != 0.0)
