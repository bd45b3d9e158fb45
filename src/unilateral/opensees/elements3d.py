"""The 3-D ``elasticBeamColumn`` (``-ndm 3 -ndf 6``) with a ``Linear`` (or ``PDelta``: :mod:`.pdelta`) transformation and its
``vecxz``, as OpenSees's ``ElasticBeam3d`` and ``LinearCrdTransf3d``.

Local axes: ``x'`` from ``i`` to ``j``, ``y' = vecxz x x'`` (normalised), ``z' = x' x y'``; the
Euler-Bernoulli stiffness with ``Iz`` for bending in the ``x'-y'`` plane and ``Iy`` in ``x'-z'``
(the same axes as :meth:`unilateral.structure.Frame3D.beam`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .refusals import refuse

__all__ = ["BeamColumn3D", "parse_beam3d", "beam_axes", "beam_stiffness3d"]


@dataclass
class BeamColumn3D:
    """An ``elasticBeamColumn`` of a 3-D model: nodes, ``A, E, G, J, Iy, Iz``, transformation tag."""

    i: int
    j: int
    A: float
    E: float
    G: float
    J: float
    Iy: float
    Iz: float
    transf: int
    mass: float = 0.0


def parse_beam3d(what, i, j, args, domain) -> BeamColumn3D:
    """``element('elasticBeamColumn', tag, i, j, A, E, G, J, Iy, Iz, transfTag)`` (``args`` after ``j``)."""
    numbers = list(args[:7])
    if len(numbers) < 7 or any(isinstance(a, str) for a in numbers):
        refuse(what, "A, E, G, J, Iy, Iz and transfTag are needed (a section tag is not in the subset)",
               "element('elasticBeamColumn', tag, i, j, A, E, G, J, Iy, Iz, transfTag)")
    A, E, G, J, Iy, Iz = (float(x) for x in numbers[:6])
    transf = int(numbers[6])
    if transf not in domain.transforms:
        refuse(what, f"geomTransf {transf} is not defined", "define the geomTransf first")
    if min(A, E, G, J, Iy, Iz) <= 0:
        refuse(what, f"A={A!r}, E={E!r}, G={G!r}, J={J!r}, Iy={Iy!r}, Iz={Iz!r} must be > 0",
               "positive section properties")
    rest = list(args[7:])
    while rest:
        flag = rest.pop(0)
        if flag == "-mass" and rest and float(rest[0]) == 0.0:
            rest.pop(0)
        elif flag == "-lMass":
            pass
        else:
            refuse(f"{what} {flag!r}", "the option is not in the subset (a beam's own mass: give nodal masses)",
                   "nodal masses with mass(node, ...)")
    beam_axes(what, domain.nodes[i], domain.nodes[j], domain.transforms[transf][1])
    return BeamColumn3D(i, j, A, E, G, J, Iy, Iz, transf)


def beam_axes(what, xi, xj, vecxz):
    """The length and the rows ``x', y', z'`` (3, 3) of the local axes of a member."""
    d = np.asarray(xj, dtype=float) - np.asarray(xi, dtype=float)
    L = float(np.linalg.norm(d))
    if L == 0.0:
        refuse(what, "its nodes coincide", "an elasticBeamColumn between two distinct points (zeroLength for none)")
    x = d / L
    y = np.cross(np.asarray(vecxz, dtype=float), x)
    ny = float(np.linalg.norm(y))
    if ny <= 1e-12 * max(float(np.linalg.norm(vecxz)), 1e-300):
        refuse(what, f"its vecxz {vecxz} is parallel to the member", "a vecxz in the local x-z plane")
    y /= ny
    return L, np.array([x, y, np.cross(x, y)])


def beam_stiffness3d(domain, e, what="elasticBeamColumn") -> tuple[np.ndarray, np.ndarray]:
    """The global stiffness (12, 12) of a 3-D beam on ``(ux, uy, uz, rx, ry, rz)`` of ``i`` then ``j``,
    and the rotation (12, 12) from global to local components."""
    L, R3 = beam_axes(what, domain.nodes[e.i], domain.nodes[e.j], domain.transforms[e.transf][1])
    k = np.zeros((12, 12))
    ea, gj = e.E * e.A / L, e.G * e.J / L
    k[np.ix_([0, 6], [0, 6])] = ea * np.array([[1, -1], [-1, 1]])
    k[np.ix_([3, 9], [3, 9])] = gj * np.array([[1, -1], [-1, 1]])
    for (v, r, sign), I in (((1, 5, 1.0), e.Iz), ((2, 4, -1.0), e.Iy)):
        ei = e.E * I / L
        idx = [v, r, v + 6, r + 6]
        a, b = 12 * ei / L ** 2, 6 * ei / L * sign
        k[np.ix_(idx, idx)] = np.array([[a, b, -a, b], [b, 4 * ei, -b, 2 * ei],
                                        [-a, -b, a, -b], [b, 2 * ei, -b, 4 * ei]])
    R = np.zeros((12, 12))
    for block in range(4):
        R[3 * block:3 * block + 3, 3 * block:3 * block + 3] = R3
    return R.T @ k @ R, R
