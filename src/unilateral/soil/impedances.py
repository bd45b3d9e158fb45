"""Veletsos & Verbic (1973) impedances of a rigid massless disc on a (visco)elastic half-space.

Veletsos, A. S. and Verbic, B. (1973), "Vibration of viscoelastic foundations", Earthquake Eng.
Struct. Dyn. 2, 87-102. Approximations fitted to the rigorous relaxed-contact solutions of
Veletsos & Wei (1971) and Luco & Westmann (1971); coefficients as reproduced in Shye & Robinson (1980,
UIUC SRS 484, Table 4.1). In the frequency domain (``a0 = omega R / c_s``, ``K* = K0 (k + i a0 c)``)

* horizontal ``k = 1``, ``c = alpha1``;
* rocking ``k = 1 - b1 (b2 a0)^2/(1+(b2 a0)^2) - b3 a0^2``, ``c = b1 b2 (b2 a0)^2/(1+(b2 a0)^2)``;
* vertical ``k = 1 - g1 (g2 a0)^2/(1+(g2 a0)^2) - g3 a0^2``, ``c = g4 + g1 g2 (g2 a0)^2/(1+(g2 a0)^2)``.

These are the values at ``s = i omega`` of the *rational* Laplace-domain functions (``p = s R / c_s``)

    K(s)/K0 = 1 + c4 p + m3 p^2 + g1 (g2 p)^2 / (1 + g2 p),

(``c4 = g4``, ``m3 = g3``; rocking: ``b``'s, ``c4 = 0``; horizontal: ``1 + alpha1 p``), which are analytic
and stable in ``Re s > 0``: the mechanical analogue is a spring ``K0``, a dashpot ``K0 g4 R/c_s``, a mass
``K0 g3 (R/c_s)^2`` on the footing and an internal mass ``K0 g1 (g2 R/c_s)^2`` attached through a dashpot
``K0 g1 g2 R/c_s``. Static stiffnesses (relaxed contact): ``4GR/(1-nu)``, ``8GR/(2-nu)``,
``8GR^3/(3(1-nu))``.

Range of validity: tabulated for ``nu = 0, 1/3, 0.45, 0.5`` (linear interpolation in between, flagged
approximate; vertical ``nu = 0.45`` interpolated between 1/3 and 1/2); accuracy about 5-10 % for
``a0 <= 1.5``, degrading beyond ``a0 ~ 2``. Material damping: pass ``s`` through the correspondence
principle yourself (Veletsos & Verbic's viscoelastic form replaces ``G`` by ``G(s)``).
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V

__all__ = ["VV_TABLE", "veletsos_verbic", "VeletsosVerbic"]

_NU = np.array([0.0, 1.0 / 3.0, 0.45, 0.5])
VV_TABLE = {
    "alpha1": np.array([0.775, 0.65, 0.60, 0.60]),
    "beta1": np.array([0.8, 0.8, 0.8, 0.8]),
    "beta2": np.array([0.525, 0.5, 0.45, 0.4]),
    "beta3": np.array([0.0, 0.0, 0.023, 0.027]),
    "gamma1": np.array([0.25, 0.35, np.nan, 0.0]),
    "gamma2": np.array([1.0, 0.8, np.nan, 0.0]),
    "gamma3": np.array([0.0, 0.0, np.nan, 0.17]),
    "gamma4": np.array([0.85, 0.75, np.nan, 0.85]),
}


def _coef(name, nu):
    y = VV_TABLE[name]
    ok = np.isfinite(y)
    return float(np.interp(nu, _NU[ok], y[ok]))


class VeletsosVerbic:
    """Rational Laplace-domain impedance of one DOF of a rigid disc (see module docstring).

    Attributes
    ----------
    K0 : float
        Static stiffness (N/m or N m/rad).
    T : float
        ``R / c_s`` (s).
    c4, m3, g1, g2 : float
        Dimensionless coefficients of ``K/K0 = 1 + c4 p + m3 p^2 + g1 (g2 p)^2/(1 + g2 p)``.
    network : dict
        ``K`` (spring), ``C`` (dashpot to ground), ``M`` (mass on the footing), ``M_int`` (internal
        mass) and ``C_int`` (dashpot linking it to the footing) of the equivalent network.
    """

    def __init__(self, K0, T, c4, m3, g1, g2):
        self.K0, self.T = float(K0), float(T)
        self.c4, self.m3, self.g1, self.g2 = float(c4), float(m3), float(g1), float(g2)
        self.network = {
            "K": self.K0, "C": self.K0 * self.c4 * self.T, "M": self.K0 * self.m3 * self.T ** 2,
            "M_int": self.K0 * self.g1 * (self.g2 * self.T) ** 2, "C_int": self.K0 * self.g1 * self.g2 * self.T,
        }

    def __call__(self, s) -> np.ndarray:
        """Impedance ``K(s)``, shape (len(s),), complex (N/m or N m/rad)."""
        s = np.atleast_1d(np.asarray(s, dtype=complex))
        p = s * self.T
        return self.K0 * (1.0 + self.c4 * p + self.m3 * p ** 2 + self.g1 * (self.g2 * p) ** 2 / (1.0 + self.g2 * p))

    def coefficients(self, a0):
        """Frequency-domain ``(k, c)`` at ``a0 = omega R/c_s`` (``K(i omega) = K0 (k + i a0 c)``)."""
        a0 = np.asarray(a0, dtype=float)
        z = self(1j * a0 / self.T) / self.K0
        return z.real, np.where(a0 > 0, z.imag / np.where(a0 > 0, a0, 1.0), self.c4 + self.g1 * self.g2 * 0)


def veletsos_verbic(dof, G, nu, rho, R) -> VeletsosVerbic:
    """Veletsos & Verbic (1973) impedance of a rigid massless disc of radius ``R``.

    Parameters
    ----------
    dof : {"vertical", "horizontal", "rocking"}
    G : float, Pa; nu : float in [0, 0.5]; rho : float, kg/m^3; R : float, m

    Returns
    -------
    VeletsosVerbic
        Callable ``K(s)`` returning (len(s),) complex; N/m (translations) or N m/rad (rocking).
    """
    dof = V.choice("dof", dof, {"vertical", "horizontal", "rocking"})
    G = V.positive_float("G", G)
    rho = V.positive_float("rho", rho)
    R = V.positive_float("R", R)
    nu = float(nu)
    if not 0.0 <= nu <= 0.5:
        raise ValueError(f"nu must lie in [0, 0.5], got {nu!r}")
    T = R / np.sqrt(G / rho)
    if dof == "vertical":
        K0 = 4.0 * G * R / (1.0 - nu)
        g1, g2, g3, g4 = (_coef(n, nu) for n in ("gamma1", "gamma2", "gamma3", "gamma4"))
        return VeletsosVerbic(K0, T, g4, g3, g1, g2)
    if dof == "rocking":
        K0 = 8.0 * G * R ** 3 / (3.0 * (1.0 - nu))
        b1, b2, b3 = (_coef(n, nu) for n in ("beta1", "beta2", "beta3"))
        return VeletsosVerbic(K0, T, 0.0, b3, b1, b2)
    K0 = 8.0 * G * R / (2.0 - nu)
    return VeletsosVerbic(K0, T, _coef("alpha1", nu), 0.0, 0.0, 0.0)
