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


#: Most wavenumber nodes of the contour of one Laplace value (:meth:`.Layered.contour`). The contour
#: runs to ``k_max = 1.5 max|s/c_s| + 12 / h_1`` in panels of width ``2 Y = 2 min(3 / D, 0.25 / h_max)``,
#: so its nodes grow as ``1 / h_1``: measured on six strips (D = 3.5 m) under a 5 m layer, 1.8e3 nodes
#: with a top layer of 1 m, 1.5e4 of 10 cm, 1.4e5 of 1 cm (73 s for 64 values on a loaded machine),
#: 1.4e6 of 1 mm (over 540 s in the issue's case) and 1.4e9 of 1 um (22 GiB for the nodes alone).
MAX_CONTOUR_NODES = 200_000
#: Rough seconds per node and Laplace value of the integration (8e-6 measured for 21 pairs of patches on a
#: loaded machine: 78 s for 1.4e5 nodes and 64 values).
SECONDS_PER_NODE = 8e-6


def check_contour_nodes(thickness, nodes: int, values: int, D: float) -> None:
    """Refuse, before the contour is allocated, a layered soil whose wavenumber integration would take
    more than :data:`MAX_CONTOUR_NODES` nodes per Laplace value: a ValueError naming the top layer's
    thickness (what sets them), the count, the estimated cost and the thickness that fits.

    Parameters
    ----------
    thickness : (n,) layer thicknesses [L];  nodes : nodes of the contour per value;  values : the
    Laplace values asked for;  D : the largest pair extent [L] (the panel width is ``6 / D`` at most)
    """
    if nodes <= MAX_CONTOUR_NODES:
        return
    h1 = float(thickness[0])
    fits = h1 * nodes / MAX_CONTOUR_NODES
    raise ValueError(
        f"layers[0]['thickness'] = {h1!r}: a top layer this thin needs {nodes:.3g} wavenumber nodes per Laplace "
        f"value (the contour runs to 12 / thickness = {12.0 / h1:.3g} [1/L] in panels of width 2 min(3 / D, "
        f"0.25 / h_max), D = {D:.3g} [L] the footprint), {nodes * values:.3g} for the {values} values asked "
        f"(roughly {nodes * values * SECONDS_PER_NODE:.3g} s for 21 pairs of patches): more than the "
        f"{MAX_CONTOUR_NODES:,} nodes allowed; make the top layer at least {fits:.3g} thick, or merge it with "
        "the layer below (a layer much thinner than the footing changes its flexibility little)")
