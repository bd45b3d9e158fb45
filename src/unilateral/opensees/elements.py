"""The elements of the subset: ``elasticBeamColumn`` (2-D: ``Linear`` or ``PDelta`` transformation;
3-D: ``Linear``), ``zeroLength`` (``-mat ... -dir ...``, default orientation, ``-doRayleigh``) and,
in 2-D, ``truss`` (``A``, a uniaxial material, ``-rho``, ``-doRayleigh``)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .elements3d import parse_beam3d
from .refusals import refuse

__all__ = ["BeamColumn", "ZeroLength", "Truss", "parse_element", "beam_stiffness", "TRUSSES"]

#: The truss element's names (OpenSees takes both spellings).
TRUSSES = ("truss", "Truss")

_ELEMENT_ALTERNATIVE = ("elasticBeamColumn (elastic members) with zeroLength ElasticPP rotational springs at "
                        "their ends for plastic hinges, and zeroLength ENT/ElasticPPGap springs for contacts")
_REFUSED = {
    "forceBeamColumn": "a fibre section's nonlinear stress-strain integration is not a finite set of "
                       "piecewise-linear yield faces",
    "dispBeamColumn": "a fibre section's nonlinear stress-strain integration is not a finite set of "
                      "piecewise-linear yield faces",
    "nonlinearBeamColumn": "a fibre section's nonlinear stress-strain integration is not a finite set of "
                           "piecewise-linear yield faces",
    "beamWithHinges": "its hinge sections are fibre or nonlinear sections",
    "corotTruss": "its corotational kinematics (the geometric stiffness of its axial force, the rotation of its "
                  "chord) is not the linear truss even at small displacements: measured against openseespy on a "
                  "braced frame, the drift differs by 2e-4 of its peak at 0.3 % drift and by 3e-3 at 3 %, with "
                  "tension-only braces by 7e-3 (the slack and taut events shift); its eleForce also omits the "
                  "inertia load that truss's holds",
    "CorotTruss": "its corotational kinematics is not the linear truss even at small displacements (see "
                  "corotTruss)",
    "twoNodeLink": "not in this slice",
    "quad": "continuum elements are not in this slice",
}


@dataclass
class BeamColumn:
    """An ``elasticBeamColumn``: nodes ``i``, ``j``, ``A``, ``E``, ``Iz``, its transformation's tag
    and its mass per length (``-mass``: only 0 is taken)."""

    i: int
    j: int
    A: float
    E: float
    I: float
    transf: int
    mass: float = 0.0


@dataclass
class ZeroLength:
    """A ``zeroLength`` from node ``i`` to ``j``: its materials' tags and directions (1, 2, 3) and
    ``-doRayleigh``."""

    i: int
    j: int
    materials: tuple
    directions: tuple
    rayleigh: bool = False


@dataclass
class Truss:
    """A ``truss`` from node ``i`` to ``j``: area ``A``, its material's tag, its mass per length ``rho``
    (lumped, ``rho L / 2`` on ``ux``, ``uy`` of each end) and ``-doRayleigh``."""

    i: int
    j: int
    A: float
    material: int
    rho: float = 0.0
    rayleigh: bool = False


def parse_element(kind, args, domain):
    """The element of ``element(kind, tag, *args)``.

    Parameters
    ----------
    kind : str, ``"elasticBeamColumn"``, ``"zeroLength"`` or ``"truss"``
    args : tuple, the arguments after the tag
    domain : Domain, for the nodes, transformations and materials named

    Returns
    -------
    BeamColumn, ZeroLength or Truss

    Raises
    ------
    OpenSeesRefused
        For another element or an option outside the subset.
    """
    what = f"element({kind!r})"
    if kind in _REFUSED:
        refuse(what, _REFUSED[kind], "truss (the linear truss)" if kind in ("corotTruss", "CorotTruss")
               else _ELEMENT_ALTERNATIVE)
    if kind == "elasticBeamColumn":
        return _beam(what, args, domain)
    if kind == "zeroLength":
        return _zero_length(what, args, domain)
    if kind in TRUSSES:
        return _truss(what, kind, args, domain)
    refuse(what, "only elasticBeamColumn, zeroLength and truss are in this slice", _ELEMENT_ALTERNATIVE)


def _nodes(what, args, domain):
    if len(args) < 2:
        refuse(what, "the nodes are missing", "element(type, tag, iNode, jNode, ...)")
    i, j = int(args[0]), int(args[1])
    for node in (i, j):
        if node not in domain.nodes:
            refuse(what, f"node {node} is not defined", "define the nodes first")
    return i, j


def _beam(what, args, domain):
    i, j = _nodes(what, args, domain)
    if domain.ndm == 3:
        return parse_beam3d(what, i, j, args[2:], domain)
    numbers = [a for a in args[2:] if not isinstance(a, str)]
    flags = [a for a in args[2:] if isinstance(a, str)]
    if len(numbers) < 4 or (numbers and isinstance(args[2], str)):
        refuse(what, "A, E, Iz and transfTag are needed (a section tag is not in the subset)",
               "element('elasticBeamColumn', tag, i, j, A, E, Iz, transfTag)")
    A, E, I = (float(x) for x in numbers[:3])
    transf = int(numbers[3])
    if transf not in domain.transforms:
        refuse(what, f"geomTransf {transf} is not defined", "define the geomTransf first")
    mass = 0.0
    rest = list(args[2 + 4:])
    while rest:
        flag = rest.pop(0)
        if flag == "-mass" and rest:
            mass = float(rest.pop(0))
            if mass:
                refuse(f"{what} -mass {mass!r}", "OpenSees distributes an elasticBeamColumn's own mass otherwise "
                       "than the lumped m L / 2 per end on ux, uy (they differ by 16 % in a measured case), so "
                       "the model would not be OpenSees's", "the beam's mass as nodal masses with mass(node, ...)")
        elif flag in ("-cMass", "-lMass"):
            if flag == "-cMass":
                refuse(f"{what} -cMass", "a consistent mass matrix couples the nodes; the model has lumped masses",
                       "the default lumped mass ('-mass', m)")
        else:
            refuse(f"{what} {flag!r}", "the option is not in the subset", "'-mass', massPerLength")
    del flags
    if min(A, E, I) <= 0:
        refuse(what, f"A={A!r}, E={E!r}, Iz={I!r} must be > 0", "positive section properties")
    return BeamColumn(i, j, A, E, I, transf, mass)


def _zero_length(what, args, domain):
    i, j = _nodes(what, args, domain)
    rest = list(args[2:])
    mats, dirs, rayleigh = [], [], False
    while rest:
        flag = rest.pop(0)
        if flag == "-mat":
            while rest and not isinstance(rest[0], str):
                mats.append(int(rest.pop(0)))
        elif flag == "-dir":
            while rest and not isinstance(rest[0], str):
                dirs.append(int(rest.pop(0)))
        elif flag == "-doRayleigh" and rest:
            rayleigh = bool(int(rest.pop(0)))
        elif flag == "-orient":
            vals = []
            while rest and not isinstance(rest[0], str):
                vals.append(float(rest.pop(0)))
            if len(vals) not in (3, 6) or not np.allclose(vals, [1, 0, 0, 0, 1, 0][:len(vals)]):
                refuse(f"{what} -orient {vals}", "a rotated zeroLength is not in this slice",
                       "the default orientation (local x = global X) or '-orient', 1, 0, 0, 0, 1, 0")
        else:
            refuse(f"{what} {flag!r}", "the option is not in the subset", "'-mat', tags..., '-dir', dirs...")
    if not mats or len(mats) != len(dirs):
        refuse(what, "one '-dir' per '-mat' is needed", "'-mat', m1, m2, '-dir', d1, d2")
    for m, d in zip(mats, dirs):
        if m not in domain.materials:
            refuse(what, f"uniaxialMaterial {m} is not defined", "define the material first")
        if d not in range(1, domain.ndf + 1):
            refuse(f"{what} -dir {d}", f"a node with {domain.ndf} DOFs has the directions 1..{domain.ndf}",
                   f"-dir 1..{domain.ndf}")
        if rayleigh and domain.materials[m].kind != "Elastic":
            refuse(f"{what} -doRayleigh 1 with {domain.materials[m].kind}", "stiffness-proportional damping of "
                   "a contact or yield spring would act across an open contact or a plastic slip (its tangent "
                   "changes)", "-doRayleigh 0 (the default) for ENT, ElasticPP and ElasticPPGap")
    if len(set(dirs)) != len(dirs):
        refuse(what, "two materials in one direction", "one material per direction")
    return ZeroLength(i, j, tuple(mats), tuple(dirs), rayleigh)


def _truss(what, kind, args, domain):
    i, j = _nodes(what, args, domain)
    if domain.ndm != 2:
        refuse(what, "a truss of a 3-D model is not in this slice", "elasticBeamColumn, or a 2-D model")
    rest = list(args[2:])
    if len(rest) < 2 or any(isinstance(a, str) for a in rest[:2]):
        refuse(what, "A and matTag are needed (a section truss, '-section', is not in the subset)",
               f"element({kind!r}, tag, i, j, A, matTag)")
    A, mat = float(rest.pop(0)), int(rest.pop(0))
    if not A > 0:
        refuse(what, f"A={A!r} must be > 0", "a positive area")
    if mat not in domain.materials:
        refuse(what, f"uniaxialMaterial {mat} is not defined", "define the material first")
    rho, rayleigh = 0.0, False
    while rest:
        flag = rest.pop(0)
        if flag == "-rho" and rest:
            rho = float(rest.pop(0))
        elif flag == "-doRayleigh" and rest:
            rayleigh = bool(int(rest.pop(0)))
        elif flag == "-cMass" and rest:
            if int(rest.pop(0)):
                refuse(f"{what} -cMass 1", "a consistent mass matrix couples the nodes; the model has lumped "
                       "masses", "the default lumped mass ('-rho', rho)")
        else:
            refuse(f"{what} {flag!r}", "the option is not in the subset", "'-rho', rho, '-doRayleigh', 0 or 1")
    if np.allclose(domain.nodes[i], domain.nodes[j]):
        refuse(what, "its nodes coincide: a truss needs a length", "zeroLength for coincident nodes")
    if rho < 0:
        refuse(what, f"-rho {rho!r} < 0", "rho >= 0")
    if rayleigh and domain.materials[mat].kind != "Elastic":
        refuse(f"{what} -doRayleigh 1 with {domain.materials[mat].kind}", "stiffness-proportional damping of a "
               "contact or yield material would act across an open contact or a plastic slip (its tangent "
               "changes)", "-doRayleigh 0 (the default) for ENT, ElasticPP and ElasticPPGap")
    return Truss(i, j, A, mat, rho, rayleigh)


def beam_stiffness(xi, xj, A, E, I) -> np.ndarray:
    """The global stiffness of a 2-D Euler-Bernoulli beam.

    Parameters
    ----------
    xi, xj : (2,) coordinates of its ends
    A, E, I : float, area, modulus, moment of inertia

    Returns
    -------
    (6, 6) ndarray on ``(ux, uy, rz)`` of ``i`` then ``j``
    """
    d = np.asarray(xj, dtype=float) - np.asarray(xi, dtype=float)
    L = float(np.hypot(*d))
    c, s = d / L
    ea, ei = E * A / L, E * I / L
    k = np.array([[ea, 0, 0, -ea, 0, 0],
                  [0, 12 * ei / L**2, 6 * ei / L, 0, -12 * ei / L**2, 6 * ei / L],
                  [0, 6 * ei / L, 4 * ei, 0, -6 * ei / L, 2 * ei],
                  [-ea, 0, 0, ea, 0, 0],
                  [0, -12 * ei / L**2, -6 * ei / L, 0, 12 * ei / L**2, -6 * ei / L],
                  [0, 6 * ei / L, 2 * ei, 0, -6 * ei / L, 4 * ei]])
    R = np.zeros((6, 6))
    R[:3, :3] = R[3:, 3:] = [[c, s, 0], [-s, c, 0], [0, 0, 1]]
    return R.T @ k @ R
