"""The ranges of a layered soil's layer properties (:mod:`unilateral.soil.layered`) and of a site
profile's (:mod:`unilateral.loads.site_response`): far beyond any soil, and inside what their
integrations compute without overflow (``thickness = 1e-308`` made the wavenumber truncation
``12 / h`` infinite, ``1e308`` the contour depth and the FFT length; ``Vs = 1e308`` the modulus
``rho Vs^2``)."""

from __future__ import annotations

import math

#: Thinnest and thickest layer [L] (a micrometre and ten thousand kilometres in metres).
THICKNESS_RANGE = (1e-6, 1e7)
#: Fastest shear wave [L/T] (ten thousand km/s in metres per second; rock: about 3 km/s).
MAX_SPEED = 1e7


def check_thickness(name: str, h: float) -> float:
    """``h`` if within :data:`THICKNESS_RANGE`; otherwise a ValueError naming ``name`` and the range."""
    low, high = THICKNESS_RANGE
    if not low <= h <= high:
        raise ValueError(f"{name} = {h!r} is out of range: valid {low:g} <= thickness <= {high:g} [L] "
                         "(a layer of a micrometre to ten thousand kilometres, in metres)")
    return h


def check_modulus(where: str, G: float | None, vs: float | None, rho: float) -> float:
    """The shear modulus of a layer given by ``G`` or by ``vs`` (and ``rho``), its wave speed checked
    against :data:`MAX_SPEED`; a ValueError naming the key, the value and the valid range."""
    speed = vs if vs is not None else math.sqrt(G / rho)
    if not speed <= MAX_SPEED:
        given = (f"{where}['Vs'] = {vs!r}" if vs is not None
                 else f"{where}['G'] = {G!r} with rho = {rho!r} (Vs = sqrt(G / rho) = {speed:.3g})")
        raise ValueError(f"{given} is out of range: valid shear-wave speeds are at most {MAX_SPEED:g} [L/T]")
    modulus = G if G is not None else rho * vs * vs
    if not 0.0 < modulus < math.inf:
        raise ValueError(f"{where}: the shear modulus rho Vs^2 = {modulus!r} (rho = {rho!r}, Vs = {vs!r}) is not a "
                         "finite number > 0; give values of a consistent unit set")
    return modulus
