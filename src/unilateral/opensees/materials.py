"""Uniaxial materials of a ``zeroLength`` element and the elements of :class:`~unilateral.structure.Frame2D`
they become.

===============  ====================================================================
``Elastic``      a spring ``k = E`` (``spring``), with ``eta``: a dashpot in parallel
``ENT``          a compression-only contact spring (``gap`` with gap 0)
``ElasticPP``    an elastic-perfectly plastic link (``yield_link``); ``eps0``: its imposed strain
``ElasticPPGap`` a gap contact (compression gap: ``gap < 0``, ``Fy < 0``; tension gap: both > 0);
                 its yield force must not be reached (checked at every step)
===============  ====================================================================

The deformation of a material is ``e = u_j - u_i`` along its direction, its force ``f`` tension
positive (OpenSees's ``basicDeformation`` and ``basicForce``).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..structure import Frame3D
from ..structure import elements as el
from .refusals import REFUSED_MATERIALS, refuse

__all__ = ["Material", "parse_material", "DIRECTIONS"]

#: The ``-dir`` of a zeroLength element and the DOF it acts on, by the number of DOFs per node.
DIRECTIONS = {3: {1: "ux", 2: "uy", 3: "rz"}, 6: {1: "ux", 2: "uy", 3: "uz", 4: "rx", 5: "ry", 6: "rz"}}


@dataclass
class Material:
    """A uniaxial material.

    Attributes
    ----------
    kind : str
    E : float, the elastic stiffness
    eta : float, the viscosity of an ``Elastic`` (0: none)
    Fy : tuple (tension, compression) yield forces of an ``ElasticPP`` (both > 0), or the signed yield
        force of an ``ElasticPPGap``
    gap : float, the signed gap of an ``ElasticPPGap``
    eps0 : float, the initial strain of an ``ElasticPP``
    parts : tuple of Material, the laws in parallel of a composite (``Steel01``, ``Hardening``,
        ``ElasticBilin``, ``Parallel``); empty for an elementary law
    """

    kind: str
    E: float
    eta: float = 0.0
    Fy: object = None
    gap: float = 0.0
    eps0: float = 0.0
    parts: tuple = ()

    # ------------------------------------------------------------------ into the frame
    def add(self, fr, name, i, j, dof) -> list:
        """Add the element(s) of this material to a frame.

        Parameters
        ----------
        fr : Frame2D
        name : str, the element's name
        i, j : node tags (the zeroLength's or the truss's nodes)
        dof : str, the DOF name of the direction (``ux``, ``uy``, ``rz``, ...), or a truss's chord
            ``(c, s)``

        Returns
        -------
        list of (str, int)
            The elements whose stress is read (none for an ``Elastic``) and the sign (+1 or -1) that
            makes each stress OpenSees's force.
        """
        if self.parts:
            return [read for k, part in enumerate(self.parts) for read in part.add(fr, f"{name}.{k}", i, j, dof)]
        if self.kind == "Elastic":
            fr.spring(name, i, self.E, j=j, direction=dof)
            if self.eta:
                fr.dashpot(f"{name}.eta", i, self.eta, j=j, direction=dof)
            return []
        if self.kind == "ENT":
            fr.gap(name, i, j, self.E, gap=0.0, direction=dof)
            return [(name, 1)]
        if self.kind == "ElasticPPGap":
            if self.Fy < 0:                   # compression gap: contact once e <= gap
                fr.gap(name, i, j, self.E, gap=-self.gap, direction=dof)
                return [(name, 1)]
            fr.gap(name, j, i, self.E, gap=self.gap, direction=dof)    # tension gap: on -e
            return [(name, -1)]
        Fy_t, Fy_c = self.Fy
        if not self.eps0:
            fr.yield_link(name, i, j, k=self.E, Fy_t=Fy_t, Fy_c=Fy_c, direction=dof)
            return [(name, 1)]
        # an imposed strain eps0: the element of yield_link with theta = eps0
        if isinstance(fr, Frame3D):
            refuse("uniaxialMaterial('ElasticPP') with eps0 in a 3-D model", "an imposed strain of a 3-D yield "
                   "link is not in the subset", "eps0 = 0 (the default)")
        where = fr._label("yield_link", name)
        fr._two_nodes(where, i, j)
        terms = el.direction_terms(where, dof)
        fr._add(el.directional(name, "yield", i, j, terms, self.E, theta=self.eps0,
                               unknowns=el.pair(name, 0, "yield", r=(Fy_t, Fy_c), k=self.E)))
        return [(name, 1)]

    def on_truss(self, A, L) -> Material:
        """The material as a force-deformation law of a truss of area ``A`` and length ``L``.

        A truss's force is ``A sigma(e / L)``: stiffnesses and viscosities times ``A / L``, forces
        times ``A``, strains (gaps, ``eps0``) times ``L``; the parts of a composite likewise.
        """
        Fy = self.Fy
        if Fy is not None:
            Fy = tuple(A * f for f in Fy) if isinstance(Fy, tuple) else A * Fy
        return replace(self, E=self.E * A / L, eta=self.eta * A / L, Fy=Fy, gap=self.gap * L, eps0=self.eps0 * L,
                       parts=tuple(part.on_truss(A, L) for part in self.parts))

    def force(self, e, edot, forces) -> float:
        """OpenSees's force of the material.

        Parameters
        ----------
        e, edot : float, the deformation ``u_j - u_i`` and its rate
        forces : list of float, the signed stresses of the elements :meth:`add` returned, in order

        Returns
        -------
        float, tension positive
        """
        if self.parts:
            total, at = 0.0, 0
            for part in self.parts:
                n = part.reads()
                total += part.force(e, edot, forces[at:at + n])
                at += n
            return total
        if self.kind == "Elastic":
            return self.E * e + self.eta * edot
        return forces[0]

    def reads(self) -> int:
        """The number of element stresses :meth:`force` reads."""
        return sum(part.reads() for part in self.parts) if self.parts else int(self.kind != "Elastic")


def _number(what, name, value, bound=None):
    try:
        x = float(value)
    except (TypeError, ValueError):
        refuse(what, f"{name}={value!r} is not a number", f"a number for {name}")
    if bound == ">0" and not x > 0:
        refuse(what, f"{name}={x!r} must be > 0", f"{name} > 0")
    return x


def parse_material(kind, args) -> Material:
    """The material of ``uniaxialMaterial(kind, tag, *args)``.

    Parameters
    ----------
    kind : str, ``"Elastic"``, ``"ENT"``, ``"ElasticPP"`` or ``"ElasticPPGap"``
    args : tuple, the arguments after the tag

    Returns
    -------
    Material

    Raises
    ------
    OpenSeesRefused
        For another material (Steel02, Concrete02, ...) or options outside the subset.
    """
    what = f"uniaxialMaterial({kind!r})"
    if kind in REFUSED_MATERIALS:
        refuse(what, REFUSED_MATERIALS[kind], "ElasticPP (elastic-perfectly plastic), Steel01 or Hardening "
               "(bilinear kinematic hardening), ENT (compression-only contact), ElasticPPGap (gap), ElasticBilin, "
               "Elastic or a Parallel of these, whose laws are piecewise linear with fixed faces")
    if kind not in ("Elastic", "ENT", "ElasticPP", "ElasticPPGap"):
        refuse(what, "only Elastic, ENT, ElasticPP, ElasticPPGap, Steel01, Hardening, ElasticBilin and Parallel "
               "are in the subset (piecewise-linear laws "
               "that are contacts or yield faces)", "ElasticPP for yielding, ENT for a compression-only "
               "contact, ElasticPPGap for a gap, Elastic for a linear spring")
    if any(isinstance(a, str) for a in args if not (kind == "ElasticPPGap" and a in ("damage", "noDamage"))):
        refuse(what, f"the options {[a for a in args if isinstance(a, str)]} are not in the subset",
               "the numeric arguments only")
    if not args:
        refuse(what, "the stiffness E is missing", f"uniaxialMaterial({kind!r}, tag, E, ...)")
    E = _number(what, "E", args[0], ">0")
    if kind == "Elastic":
        eta = _number(what, "eta", args[1]) if len(args) > 1 else 0.0
        if len(args) > 2 and _number(what, "Eneg", args[2]) != E:
            refuse(f"{what} with Eneg != E", "a bilinear elastic law is a spring that changes stiffness, "
                   "not a contact or a yield face", "Elastic with one E, or an Elastic spring in parallel "
                   "with an ENT spring of the stiffness difference")
        if eta < 0:
            refuse(what, f"eta={eta!r} < 0", "eta >= 0")
        return Material("Elastic", E, eta=eta)
    if kind == "ENT":
        if len(args) > 1:
            refuse(what, "the extra arguments of ENT are not in the subset", "uniaxialMaterial('ENT', tag, E)")
        return Material("ENT", E)
    if kind == "ElasticPP":
        if len(args) < 2:
            refuse(what, "the yield strain epsyP is missing", "uniaxialMaterial('ElasticPP', tag, E, epsyP)")
        epsP = _number(what, "epsyP", args[1], ">0")
        epsN = _number(what, "epsyN", args[2]) if len(args) > 2 else -epsP
        if not epsN < 0:
            refuse(what, f"epsyN={epsN!r} must be < 0", "a negative compressive yield strain")
        eps0 = _number(what, "eps0", args[3]) if len(args) > 3 else 0.0
        if len(args) > 4:
            refuse(what, "more than four numbers", "uniaxialMaterial('ElasticPP', tag, E, epsyP, epsyN, eps0)")
        return Material("ElasticPP", E, Fy=(E * epsP, -E * epsN), eps0=eps0)
    return _gap_material(what, E, args)


def _gap_material(what, E, args) -> Material:
    numbers = [a for a in args if not isinstance(a, str)]
    if len(numbers) < 3:
        refuse(what, "E, Fy and gap are needed", "uniaxialMaterial('ElasticPPGap', tag, E, Fy, gap)")
    Fy, gap = _number(what, "Fy", numbers[1]), _number(what, "gap", numbers[2])
    eta = _number(what, "eta", numbers[3]) if len(numbers) > 3 else 0.0
    if eta != 0.0:
        refuse(f"{what} with eta={eta!r}", "a hardening gap is not in this slice", "eta = 0")
    if Fy == 0 or (Fy > 0 and gap < 0) or (Fy < 0 and gap > 0):
        refuse(what, f"Fy={Fy!r} and gap={gap!r} must have one sign (a compression gap: both < 0, a tension "
               "gap: both > 0)", "Fy and gap of one sign")
    return Material("ElasticPPGap", E, Fy=Fy, gap=gap)
