"""Wolf's cone models of a rigid disc on a homogeneous half-space, and cone-type surface coupling.

Wolf, J. P. (1994), *Foundation Vibration Analysis Using Simple Physical Models*, Prentice Hall;
Wolf & Deeks (2004), *Foundation Vibration Analysis: a Strength-of-Materials Approach*, Elsevier;
Meek & Wolf (1992), J. Geotech. Eng. 118(5) (nearly incompressible soil: ``c = 2 c_s`` and trapped mass).

Disc of radius ``r0``, ``A0 = pi r0^2``, ``I0 = pi r0^4/4`` (rocking) or ``pi r0^4/2`` (torsion).

==========  ==========================  ==================================  ======================
DOF         ``z0/r0``                   wave speed ``c``                    trapped mass (nu > 1/3)
==========  ==========================  ==================================  ======================
horizontal  ``(pi/8)(2-nu)``            ``c_s``                             --
vertical    ``(pi/4)(1-nu)(c/c_s)^2``   ``c_p`` (nu<=1/3), ``2 c_s`` (>1/3)  ``2.4(nu-1/3) rho A0 r0``
rocking     ``(9pi/32)(1-nu)(c/c_s)^2`` as vertical                         ``1.2(nu-1/3) rho I0 r0``
torsion     ``9pi/32``                  ``c_s``                             --
==========  ==========================  ==================================  ======================

Translational cone: ``S(s) = K + C s + dM s^2`` with ``K = rho c^2 A0/z0``, ``C = rho c A0``.
Rotational cone: ``S(s) = K + C s q/(1+q) + dM s^2``, ``q = s z0/c``, ``K = 3 rho c^2 I0/z0``,
``C = rho c I0``; at ``s = i omega`` this is Wolf's ``K[1 - b0^2/(3(1+b0^2)) + i b0^3/(3(1+b0^2))]``
(``b0 = omega z0/c``). Network: spring ``K`` in parallel with an internal mass ``M_int = rho I0 z0``
attached to the footing through a dashpot ``C`` (Wolf's "monkey tail"), plus ``dM`` on the footing.
Static stiffnesses are exact (``4Gr0/(1-nu)``, ``8Gr0/(2-nu)``, ``8Gr0^3/(3(1-nu))``, ``16Gr0^3/3``);
dynamic values are within about 20 % of rigorous solutions (Wolf 1994) for ``0 <= a0 <= ~3``.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V
from .lamb import eta_of, rayleigh_ratio
from .patches import RectangularPatches

__all__ = ["Cone", "cone", "cone_flexibility"]


class Cone:
    """A cone model ``S(s)`` (callable) with its discrete network.

    Attributes
    ----------
    dof : str
    K, C : float
        Spring and dashpot (N/m, N s/m or N m/rad, N m s/rad).
    dM : float
        Trapped mass (kg or kg m^2) on the footing (0 unless nu > 1/3 in vertical/rocking).
    M_int : float
        Internal mass of the rotational cones (0 for translational ones).
    z0, c : float
        Apex height (m) and wave speed (m/s).
    """

    def __init__(self, dof, K, C, dM, M_int, z0, c):
        self.dof, self.K, self.C, self.dM, self.M_int, self.z0, self.c = dof, K, C, dM, M_int, z0, c

    @property
    def network(self) -> dict:
        """Spring ``K``; translational: dashpot ``C`` to ground; rotational: internal mass ``M_int``
        linked to the footing by dashpot ``C_int = C``; both: mass ``M = dM`` on the footing."""
        if self.M_int:
            return {"K": self.K, "C": 0.0, "M": self.dM, "M_int": self.M_int, "C_int": self.C}
        return {"K": self.K, "C": self.C, "M": self.dM, "M_int": 0.0, "C_int": 0.0}

    def __call__(self, s) -> np.ndarray:
        """Dynamic stiffness ``S(s)``, (len(s),) complex."""
        s = np.atleast_1d(np.asarray(s, dtype=complex))
        if self.M_int:
            q = s * self.z0 / self.c
            return self.K + self.C * s * q / (1.0 + q) + self.dM * s ** 2
        return self.K + self.C * s + self.dM * s ** 2


def cone(dof, G, nu, rho, r0) -> Cone:
    """Wolf's (1994) cone for a rigid surface disc of radius ``r0`` (see module table).

    Parameters
    ----------
    dof : {"vertical", "horizontal", "rocking", "torsion"}
    G : float, Pa; nu : float in [0, 0.5); rho : float, kg/m^3; r0 : float, m
    """
    dof = V.choice("dof", dof, {"vertical", "horizontal", "rocking", "torsion"})
    G, rho, r0 = V.positive_float("G", G), V.positive_float("rho", rho), V.positive_float("r0", r0)
    nu = float(nu)
    if not 0.0 <= nu < 0.5:
        raise ValueError(f"nu must lie in [0, 0.5), got {nu!r}")
    cs = np.sqrt(G / rho)
    A0 = np.pi * r0 ** 2
    if dof in ("horizontal", "torsion"):
        if dof == "horizontal":
            z0 = np.pi / 8.0 * (2.0 - nu) * r0
            return Cone(dof, rho * cs ** 2 * A0 / z0, rho * cs * A0, 0.0, 0.0, z0, cs)
        I0 = np.pi * r0 ** 4 / 2.0
        z0 = 9.0 * np.pi / 32.0 * r0
        return Cone(dof, 3.0 * rho * cs ** 2 * I0 / z0, rho * cs * I0, 0.0, rho * I0 * z0, z0, cs)
    big = nu > 1.0 / 3.0
    c = 2.0 * cs if big else cs / np.sqrt(eta_of(nu))
    if dof == "vertical":
        z0 = np.pi / 4.0 * (1.0 - nu) * (c / cs) ** 2 * r0
        dM = 2.4 * (nu - 1.0 / 3.0) * rho * A0 * r0 if big else 0.0
        return Cone(dof, rho * c ** 2 * A0 / z0, rho * c * A0, dM, 0.0, z0, c)
    I0 = np.pi * r0 ** 4 / 4.0
    z0 = 9.0 * np.pi / 32.0 * (1.0 - nu) * (c / cs) ** 2 * r0
    dM = 1.2 * (nu - 1.0 / 3.0) * rho * I0 * r0 if big else 0.0
    return Cone(dof, 3.0 * rho * c ** 2 * I0 / z0, rho * c * I0, dM, rho * I0 * z0, z0, c)


def cone_flexibility(patches: RectangularPatches, G, nu, rho, s, wave="rayleigh") -> np.ndarray:
    """Approximate coupled vertical flexibility of surface patches by cones (Wolf & Meek type).

    Diagonal: ``1/S(s)`` of the vertical cone of the equal-area disc ``r0 = sqrt(A/pi)``. Coupling
    between patches ``i != j`` at centre distance ``r``: the static Boussinesq decay with a wave delay,
    ``(1 - nu)/(2 pi G r) exp(-s r/c)``, ``c`` the Rayleigh (default), shear or P-wave speed - the
    amplitude-decay-plus-delay idea of Wolf & Meek's cone interaction, with the amplitude chosen so the
    static limit is exact (Boussinesq) for well-separated patches.

    Not passive in general (measured: the Hermitian part of ``i omega Phi(i omega)`` of two strips
    of a 10 m footing reaches -0.69 of its largest eigenvalue), so it is not a soil to march in time:
    :meth:`unilateral.soil.SoilFlexibility.cones` refuses it for more than one patch.

    Parameters
    ----------
    patches : RectangularPatches (positive sides)
    G, nu, rho : float
    s : complex scalar or (ns,) array, ``Re s >= 0``
    wave : {"rayleigh", "shear", "p"}

    Returns
    -------
    (ns, m, m) complex, m/N; symmetric. Approximate: radiation and coupling only roughly right (no
    near-field, no dispersion of the delay); use :class:`HalfSpace` for the rigorous one.
    """
    wave = V.choice("wave", wave, {"rayleigh", "shear", "p"})
    G, rho = V.positive_float("G", G), V.positive_float("rho", rho)
    s = np.atleast_1d(np.asarray(s, dtype=complex))
    cs = np.sqrt(G / rho)
    c = {"rayleigh": cs / np.sqrt(rayleigh_ratio(nu)), "shear": cs, "p": cs / np.sqrt(eta_of(nu))}[wave]
    d = patches.centres[:, None, :] - patches.centres[None, :, :]
    r = np.hypot(d[..., 0], d[..., 1])
    m = patches.m
    off = ~np.eye(m, dtype=bool)
    F = np.zeros((s.size, m, m), dtype=complex)
    F[:, off] = (1.0 - nu) / (2.0 * np.pi * G * r[off])[None, :] * np.exp(-s[:, None] * r[off][None, :] / c)
    r0 = np.sqrt(patches.areas / np.pi)
    for i in range(m):
        F[:, i, i] = 1.0 / cone("vertical", G, nu, rho, r0[i])(s)
    return F
