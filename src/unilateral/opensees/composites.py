"""Uniaxial materials that are exact compositions of the elementary laws (springs, contacts and
elastic-perfectly plastic links in parallel), as OpenSees defines them.

==================================  ===================================================================
``Steel01 Fy E0 b`` (a1 = a3 = 0)   bilinear kinematic hardening: an ``ElasticPP`` of stiffness
                                    ``(1 - b) E0`` and yield force ``(1 - b) Fy`` in parallel with a
                                    spring ``b E0``
``Hardening E sigmaY 0 H``          linear kinematic hardening: the same with ``b = H / (E + H)``
                                    (tangent ``E H / (E + H)``)
``ElasticBilin EP1 EP2 epsP2 ...``  a spring and contacts that close at ``0``, ``epsP2``, ``epsN2`` where
                                    the stiffness grows away from zero (each branch stiffer than the
                                    one before it)
``Parallel tags ...``               the parts of the materials side by side (forces added)
==================================  ===================================================================

Isotropic hardening (Steel01's ``a1..a4``, Hardening's ``H_iso``), a softening ElasticBilin and
``Series`` change the law's faces along the history or make it non-monotone: refused by name.
"""

from __future__ import annotations

import math

from .materials import Material
from .refusals import refuse

__all__ = ["parse_composite", "COMPOSITES"]

COMPOSITES = ("Steel01", "Hardening", "ElasticBilin", "Parallel")


def _numbers(what, args, names, required):
    values = []
    for k, a in enumerate(args):
        if isinstance(a, str):
            refuse(what, f"the option {a!r} is not in the subset", f"the numeric arguments {', '.join(names)}")
        values.append(float(a))
    if len(values) < required or len(values) > len(names):
        refuse(what, f"{len(values)} numbers given", f"{required} to {len(names)} numbers: {', '.join(names)}")
    return values


def _bilinear(E, Fy_t, Fy_c, b) -> Material:
    """An elastic-perfectly plastic link of ``(1 - b) E`` in parallel with a spring ``b E``."""
    plastic = Material("ElasticPP", (1.0 - b) * E, Fy=((1.0 - b) * Fy_t, (1.0 - b) * Fy_c))
    if b == 0.0:
        return plastic
    return Material("bilinear", E, parts=(plastic, Material("Elastic", b * E)))


def _steel01(what, args) -> Material:
    Fy, E0, b, *iso = _numbers(what, args, ("Fy", "E0", "b", "a1", "a2", "a3", "a4"), 3)
    if not (Fy > 0 and E0 > 0 and 0.0 <= b < 1.0):
        refuse(what, f"Fy={Fy!r}, E0={E0!r}, b={b!r}: needs Fy > 0, E0 > 0, 0 <= b < 1", "e.g. Steel01 tag 250 2e5 0.02")
    a1, _, a3, _ = (iso + [0.0, 1.0, 0.0, 1.0][len(iso):])
    if a1 != 0.0 or a3 != 0.0:
        refuse(f"{what} with isotropic hardening (a1={a1!r}, a3={a3!r})", "isotropic hardening moves the yield "
               "forces along the history: not fixed yield faces", "Steel01 with a1 = a3 = 0 (the default): "
               "bilinear kinematic hardening")
    return _bilinear(E0, Fy, Fy, b)


def _hardening(what, args) -> Material:
    E, sy, H_iso, H_kin, *eta = _numbers(what, args, ("E", "sigmaY", "H_iso", "H_kin", "eta"), 4)
    if H_iso != 0.0:
        refuse(f"{what} with H_iso={H_iso!r}", "isotropic hardening moves the yield forces along the history",
               "Hardening with H_iso = 0 (kinematic hardening), or Steel01")
    if eta and eta[0] != 0.0:
        refuse(f"{what} with eta={eta[0]!r}", "a viscoplastic (rate-dependent) yield is not a fixed yield face",
               "eta = 0")
    if not (E > 0 and sy > 0 and H_kin >= 0):
        refuse(what, f"E={E!r}, sigmaY={sy!r}, H_kin={H_kin!r}: needs E > 0, sigmaY > 0, H_kin >= 0",
               "positive E, sigmaY")
    return _bilinear(E, sy, sy, H_kin / (E + H_kin))


def _contact(k, at, tension) -> Material:
    """A contact of stiffness ``k`` that closes at the deformation ``at`` (beyond it, on its side)."""
    if tension:
        return Material("ElasticPPGap", k, Fy=math.inf, gap=at)
    return Material("ElasticPPGap", k, Fy=-math.inf, gap=at) if at else Material("ENT", k)


def _elastic_bilin(what, args) -> Material:
    EP1, EP2, epsP2, *neg = _numbers(what, args, ("EP1", "EP2", "epsP2", "EN1", "EN2", "epsN2"), 3)
    EN1 = neg[0] if len(neg) > 0 else EP1
    EN2 = neg[1] if len(neg) > 1 else EP2
    epsN2 = neg[2] if len(neg) > 2 else -epsP2
    if not (epsP2 > 0 and epsN2 < 0 and min(EP1, EN1) > 0):
        refuse(what, f"epsP2={epsP2!r}, epsN2={epsN2!r}, EP1={EP1!r}, EN1={EN1!r}", "epsP2 > 0 > epsN2, EP1, EN1 > 0")
    if EP2 < EP1 or EN2 < EN1:
        refuse(f"{what} softening (EP2={EP2!r} < EP1={EP1!r} or EN2={EN2!r} < EN1={EN1!r})", "a nonlinear elastic law "
               "whose stiffness drops unloads along its loading path: neither a contact nor a yield face",
               "EP2 >= EP1 and EN2 >= EN1 (a law that stiffens away from zero), or ElasticPP for a yield")
    parts = [Material("Elastic", min(EP1, EN1))]
    if EP1 != EN1:
        parts.append(_contact(abs(EP1 - EN1), 0.0, tension=EP1 > EN1))
    if EP2 > EP1:
        parts.append(_contact(EP2 - EP1, epsP2, tension=True))
    if EN2 > EN1:
        parts.append(_contact(EN2 - EN1, epsN2, tension=False))
    return Material("ElasticBilin", EP1, parts=tuple(parts))


def _parallel(what, args, materials) -> Material:
    tags, factors = list(args), None
    if "-factors" in tags:
        at = tags.index("-factors")
        tags, factors = tags[:at], [float(f) for f in tags[at + 1:]]
    if not tags or any(isinstance(t, str) for t in tags):
        refuse(what, "the material tags are missing", "uniaxialMaterial('Parallel', tag, *tags)")
    if factors is not None and any(f != 1.0 for f in factors):
        refuse(f"{what} -factors", "scaled materials are not in the subset", "define the scaled materials directly")
    parts = []
    for t in tags:
        if int(t) not in materials:
            refuse(what, f"uniaxialMaterial {t} is not defined", "define the materials first")
        m = materials[int(t)]
        if m.kind == "ElasticPPGap" and math.isfinite(m.Fy):
            refuse(f"{what} with the ElasticPPGap {t}", "the check that a gap stays below its yield force "
                   "needs its own element", "the gap in a zeroLength element of its own")
        parts.extend(m.parts or (m,))
    return Material("Parallel", sum(p.E for p in parts), parts=tuple(parts))


def parse_composite(kind, args, materials) -> Material:
    """The material ``uniaxialMaterial(kind, tag, *args)`` of :data:`COMPOSITES`.

    Parameters
    ----------
    kind : str, one of :data:`COMPOSITES`
    args : tuple, the arguments after the tag
    materials : dict, the materials defined (for ``Parallel``)

    Returns
    -------
    Material, with its ``parts`` in parallel
    """
    what = f"uniaxialMaterial({kind!r})"
    if kind == "Steel01":
        return _steel01(what, args)
    if kind == "Hardening":
        return _hardening(what, args)
    if kind == "ElasticBilin":
        return _elastic_bilin(what, args)
    return _parallel(what, args, materials)
