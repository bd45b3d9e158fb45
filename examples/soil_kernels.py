"""Soil as an unbounded medium: the half-space flexibility of surface patches, and a disc impedance.

What it shows
-------------
:mod:`unilateral.soil` gives the Laplace-domain kernels of a homogeneous elastic half-space
(shear modulus 50 MPa, Poisson's ratio 1/3, density 1800 kg/m^3; SI units):

1. ``HalfSpace.surface_flexibility(patches, s)``: the matrix ``Phi(s)`` of mean vertical
   displacement of each patch per unit force on each patch (m/N), by Lamb's problem, for two
   2 m x 2 m patches side by side and a third one 20 m away, at ``s = 0`` (static, Boussinesq in
   closed form) and on the imaginary axis ``s = i omega`` (steady state, complex: the imaginary part
   is the energy radiated into the soil). Far apart, two patches interact like two point loads:
   ``Phi_13(0)`` is compared with Boussinesq's ``(1 - nu)/(2 pi G r)``.
2. The impedance of a rigid disc of radius 2 m two ways: rigorously, from the flexibility of the
   patches covering it (``K(s) = 1^T Phi(s)^-1 1``, equal displacement of every patch), and by the
   rational approximation of Veletsos & Verbic (1973), ``veletsos_verbic("vertical", ...)``, at
   dimensionless frequencies ``a0 = omega R / c_s`` from 0 to 1.5. Both are normalised by the exact
   static stiffness ``4 G R / (1 - nu)``.

What it prints
--------------
``Phi(0)`` and ``Phi(i omega)`` of the three patches (in m/GN), the far-field check, and a table
``a0, K/K0 rigorous, K/K0 Veletsos-Verbic`` (they agree to the 5-10 % that Veletsos & Verbic
state). The lines ``far field ...``, ``static disc ...`` and ``largest difference ...`` are
checked by ``tests/test_examples.py``.

Run: ``python examples/soil_kernels.py`` (about a second).
"""

import numpy as np

from unilateral.soil import HalfSpace, RectangularPatches, boussinesq, disc, veletsos_verbic

G, nu, rho = 50e6, 1.0 / 3.0, 1800.0
soil = HalfSpace(G, nu, rho)
print(f"half-space: G = {G:.3g} Pa, nu = {nu:.3f}, rho = {rho:g} kg/m^3, c_s = {soil.cs:.1f} m/s")

# 1. three square patches of 2 m: two side by side, one 20 m away
patches = RectangularPatches(np.array([[0.0, 0.0], [2.0, 0.0], [20.0, 0.0]]), (2.0, 2.0))
omega = 2 * np.pi * 5.0                                    # 5 Hz
Phi0, Phiw = soil.surface_flexibility(patches, np.array([0.0, 1j * omega]))
np.set_printoptions(precision=3, linewidth=110)
print("Phi(0) [m/GN] =\n", 1e9 * Phi0.real)
print(f"Phi(i omega), omega = {omega:.1f} rad/s [m/GN] =\n", 1e9 * Phiw)
point = boussinesq(20.0, G, nu)
print(f"far field: Phi_13(0) = {Phi0[0, 2].real:.6e} m/N, Boussinesq at 20 m {point:.6e} m/N, "
      f"relative difference {abs(Phi0[0, 2].real / point - 1):.1e}")

# 2. a rigid disc: patches under it, against Veletsos & Verbic
R = 2.0
cells = disc(R, 10)
R_eq = np.sqrt(cells.areas.sum() / np.pi)                  # radius of the same area as the cells
K0 = 4 * G * R_eq / (1 - nu)                               # exact static stiffness of a rigid disc
a0 = np.array([0.0, 0.25, 0.5, 0.75, 1.0, 1.5])
s = 1j * a0 * soil.cs / R_eq
one = np.ones(len(cells.areas))
rigorous = np.array([one @ np.linalg.solve(P, one) for P in soil.surface_flexibility(cells, s)]) / K0
vv = veletsos_verbic("vertical", G, nu, rho, R_eq)
approx = vv(s) / K0
print(f"rigid disc from {len(one)} patches (equal-area radius {R_eq:.3f} m), K0 = 4GR/(1-nu) = {K0:.4e} N/m")
print(f"{'a0':>5} {'rigorous K/K0':>22} {'Veletsos-Verbic K/K0':>22}")
for a, k1, k2 in zip(a0, rigorous, approx):
    print(f"{a:5.2f} {k1.real:10.4f} {k1.imag:+9.4f}i  {k2.real:10.4f} {k2.imag:+9.4f}i")
print(f"static disc: rigorous K(0)/K0 = {rigorous[0].real:.4f}")
low = a0 <= 1.0
print(f"largest difference for a0 <= 1: {np.abs(rigorous[low] - approx[low]).max():.3f} K0")
